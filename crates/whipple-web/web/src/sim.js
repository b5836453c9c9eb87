// The simulation panel: speed and initial perturbation in, /api/simulate, then an animated 3-D
// view with play / pause / scrub / playback rate beside lean and steer against time and the
// ground track, all following one current frame.

import { api } from "./api.js";
import { parseNumber } from "./editor.js";
import { fixed, html } from "./format.js";
import { TimePlot, TrackPlot } from "./simplots.js";

const $ = (id) => document.getElementById(id);
const DEG = 180 / Math.PI;
const INPUTS = [
  ["sim-speed", "speed"],
  ["sim-lean", "lean_deg"],
  ["sim-steer", "steer_deg"],
  ["sim-lean-rate", "lean_rate"],
  ["sim-steer-rate", "steer_rate"],
  ["sim-duration", "duration"],
];
/** Rider torques: a number, or an expression the server parses (the CLI's language). */
const TORQUES = [
  ["sim-steer-torque", "steer_torque"],
  ["sim-lean-torque", "lean_torque"],
];

/** Index of the last frame at or before time `t` (frames sorted by time). */
function frameAt(frames, t) {
  let lo = 0, hi = frames.length - 1;
  if (t >= frames[hi].t) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (frames[mid].t <= t) lo = mid; else hi = mid;
  }
  return lo;
}

export class SimPanel {
  /** `bike()` gives the current bicycle (files' JSON layout). */
  constructor({ bike }) {
    this.bike = bike;
    this.result = null;
    this.time = 0;
    this.index = 0;
    this.playing = false;
    this.view = null;
    this.viewError = null;
    this.speedEdited = false;
    this.timePlot = new TimePlot($("sim-time-plot"));
    this.trackPlot = new TrackPlot($("sim-track"));
    $("sim-form").addEventListener("submit", (e) => {
      e.preventDefault();
      this.run();
    });
    $("sim-speed").addEventListener("input", () => {
      this.speedEdited = true;
    });
    $("sim-play").addEventListener("click", () => (this.playing ? this.pause() : this.play()));
    $("sim-scrub").addEventListener("input", () => this.seek(Number($("sim-scrub").value)));
    $("sim-rate").addEventListener("change", () => {
      this.last = performance.now();
    });
    this.setEnabled(false);
  }

  /**
   * The 3-D view, created on first use: three.js is fetched only then (it is most of the
   * page's weight). WebGL may be missing: then the plots still work.
   */
  async ensureView() {
    if (this.view || this.viewError) return this.view;
    try {
      const { SimView } = await import("./view3d.js");
      this.view = this.view ?? new SimView($("sim-view"));
    } catch (e) {
      this.viewError = e;
      $("sim-view").replaceChildren(html("div", { class: "sim-no-view", text: `The 3-D view needs WebGL, which this browser does not offer (${e.message}). The plots below still follow the simulation.` }));
    }
    return this.view;
  }

  /** Suggests a speed inside the first self-stable range (its middle), else 5 m/s. */
  suggestSpeed(critical) {
    if (this.speedEdited) return;
    const range = critical?.stable_speed_ranges?.[0];
    const v = range ? 0.5 * (range[0] + range[1]) : 5;
    $("sim-speed").value = String(Math.round(v * 100) / 100);
    $("sim-speed-hint").textContent = range ? `middle of the self-stable range ${fixed(range[0], 2)}–${fixed(range[1], 2)} m/s` : "no self-stable range found";
  }

  setEnabled(on) {
    for (const id of ["sim-play", "sim-scrub", "sim-rate"]) $(id).disabled = !on;
  }

  say(text) {
    $("sim-message").textContent = text;
    $("sim-message").hidden = !text;
  }

  async run() {
    const request = { bike: this.bike() };
    for (const [id] of [...INPUTS, ...TORQUES]) $(id).classList.remove("invalid");
    for (const [id, key] of INPUTS) {
      const x = parseNumber($(id).value);
      if (x === null) {
        $(id).classList.add("invalid");
        this.say(`${$(id).dataset.label} must be a number.`);
        return;
      }
      request[key] = x;
    }
    for (const [id, key] of TORQUES) {
      const text = $(id).value.trim();
      const x = parseNumber(text);
      if (text === "") request[key] = 0;
      else request[key] = x === null ? text : x;
    }
    this.pause();
    this.say("");
    $("sim-run").disabled = true;
    $("sim-outcome").className = "sim-outcome running";
    $("sim-outcome").textContent = "simulating…";
    try {
      const result = await api.simulate(request);
      this.load(result);
      await this.ensureView();
      this.view?.load(result);
      this.seek(0);
      this.play();
    } catch (e) {
      const input = [...INPUTS, ...TORQUES].find(([, key]) => key === e.field);
      if (input) $(input[0]).classList.add("invalid");
      this.say(e.message);
      $("sim-outcome").className = "sim-outcome";
      $("sim-outcome").textContent = this.result ? "" : "not run yet";
    } finally {
      $("sim-run").disabled = false;
    }
  }

  load(result) {
    this.result = result;
    const frames = result.frames;
    const end = frames[frames.length - 1].t;
    const scrub = $("sim-scrub");
    scrub.max = String(end);
    scrub.step = String(1 / result.frame_rate);
    const o = result.outcome;
    $("sim-outcome").className = `sim-outcome ${o.kind === "completed" ? "good" : "bad"}`;
    $("sim-outcome").textContent = o.message;
    $("sim-outcome").dataset.kind = o.kind;
    $("sim-meta").textContent = `${result.name ?? "bicycle"} · ${result.steps.toLocaleString("en")} steps · ${frames.length} frames`;
    this.timePlot.update(result);
    this.trackPlot.update(result);
    this.setEnabled(true);
  }

  play() {
    if (!this.result) return;
    const end = this.result.frames[this.result.frames.length - 1].t;
    if (this.time >= end) this.seek(0);
    this.playing = true;
    $("sim-play").textContent = "❚❚ Pause";
    $("sim-play").setAttribute("aria-pressed", "true");
    this.last = performance.now();
    const tick = (now) => {
      if (!this.playing) return;
      const rate = Number($("sim-rate").value) || 1;
      const t = this.time + (Math.min(now - this.last, 1000) / 1000) * rate;
      this.last = now;
      this.seek(Math.min(t, end));
      if (t >= end) {
        this.pause();
        return;
      }
      this.raf = requestAnimationFrame(tick);
    };
    this.raf = requestAnimationFrame(tick);
  }

  pause() {
    this.playing = false;
    cancelAnimationFrame(this.raf);
    $("sim-play").textContent = "▶ Play";
    $("sim-play").setAttribute("aria-pressed", "false");
  }

  /** Shows simulated time `t` everywhere: 3-D view, cursors, scrub bar and read-out. */
  seek(t) {
    if (!this.result) return;
    const frames = this.result.frames;
    this.time = Math.max(0, t);
    const i = frameAt(frames, this.time);
    const f = frames[i];
    this.index = i;
    $("sim-scrub").value = String(this.time);
    $("sim-t").textContent = fixed(this.time, 2);
    $("sim-lean-readout").textContent = fixed(f.lean * DEG, 1);
    $("sim-steer-readout").textContent = fixed(f.steer * DEG, 1);
    $("sim-v-readout").textContent = fixed(f.speed, 2);
    this.view?.show(i);
    this.timePlot.cursor(i);
    this.trackPlot.cursor(i);
  }
}
