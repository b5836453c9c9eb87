// The simulation panel: speed and initial perturbation in, /api/simulate, then an animated 3-D
// view with play / pause / scrub / playback rate beside lean and steer against time and the
// ground track, all following one current frame. Earlier runs stay overlaid (faint) until
// cleared; a hands-free run is drawn with the linear model's prediction from the same initial
// state (/api/linear/response); the time series export as CSV.

import { api } from "./api.js";
import { during } from "./work.js";
import { parseNumber } from "./editor.js";
import { fixed, html, num, slug, download } from "./format.js";
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
/**
 * The leaning rider (Moore 2012's rider-lean model): the request's `rider` fields and the
 * link's keys. The torque's duration may be empty (the whole run).
 */
const RIDER = [
  ["sim-rider-k", "hinge_stiffness", "rk"],
  ["sim-rider-c", "hinge_damping", "rc"],
  ["sim-rider-torque", "torque", "rt"],
  ["sim-rider-for", "torque_duration", "rd"],
  ["sim-rider-lean", "lean_deg", "rl"],
];
/** Runs kept: the current one and up to this many earlier ones, overlaid. */
const KEEP = 4;

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

/** A short name of a run's inputs, for the legend and the CSV. */
function runLabel(r) {
  const parts = [`v ${num(r.speed)}`];
  if (r.lean_deg) parts.push(`φ₀ ${num(r.lean_deg)}°`);
  if (r.steer_deg) parts.push(`δ₀ ${num(r.steer_deg)}°`);
  if (r.lean_rate) parts.push(`φ̇₀ ${num(r.lean_rate)}`);
  if (r.steer_rate) parts.push(`δ̇₀ ${num(r.steer_rate)}`);
  if (r.steer_torque && r.steer_torque !== 0) parts.push(`T_δ ${r.steer_torque}`);
  if (r.lean_torque && r.lean_torque !== 0) parts.push(`T_φ ${r.lean_torque}`);
  if (r.from_turn) parts.push("held turn");
  if (r.rider) {
    const h = r.rider;
    parts.push(`leaning rider k ${num(h.hinge_stiffness)}, c ${num(h.hinge_damping)}`);
    if (h.torque) parts.push(`T_r ${num(h.torque)}${h.torque_duration !== undefined ? ` for ${num(h.torque_duration)} s` : ""}`);
    if (h.lean_deg) parts.push(`φ_r₀ ${num(h.lean_deg)}°`);
  }
  return parts.join(", ");
}

export class SimPanel {
  /** `bike()` gives the current bicycle (files' JSON layout); `onRun()` is told of each run. */
  constructor({ bike, label, onRun }) {
    this.bike = bike;
    this.label = label;
    this.onRun = onRun ?? (() => {});
    this.result = null;
    this.runs = [];
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
      // The hint no longer says the speed was set for the user.
      this.hint();
      this.noteSpeed();
    });
    $("sim-play").addEventListener("click", () => (this.playing ? this.pause() : this.play()));
    $("sim-scrub").addEventListener("input", () => this.seek(Number($("sim-scrub").value)));
    $("sim-rate").addEventListener("change", () => {
      this.last = performance.now();
    });
    $("sim-csv").addEventListener("click", () => this.exportCsv());
    $("sim-clear").addEventListener("click", () => {
      this.runs = this.runs.slice(0, 1);
      this.drawPlots();
    });
    $("sim-linear").addEventListener("change", () => this.drawPlots());
    $("sim-from-turn").addEventListener("change", () => this.noteTurn());
    $("sim-rider").addEventListener("change", () => this.noteRider());
    this.noteRider();
    this.setEnabled(false);
  }

  /**
   * The 3-D view, created on first use: three.js is fetched only then (it is most of the
   * page's weight). WebGL may be missing: then the plots still work.
   */
  async ensureView() {
    if (this.view || this.viewError) return this.view;
    try {
      // Counted as work under way (work.js) until the view is made.
      const { SimView } = await during(() => import("./view3d.js"));
      this.view = this.view ?? new SimView($("sim-view"));
    } catch (e) {
      this.viewError = e;
      $("sim-view").replaceChildren(html("div", { class: "sim-no-view", text: `The 3-D view needs WebGL, which this browser does not offer (${e.message}). The plots below still follow the simulation.` }));
    }
    return this.view;
  }

  /**
   * Says where the current bicycle is self-stable, and suggests the middle of that range as
   * the speed unless the user typed one.
   */
  suggestSpeed(critical, label) {
    const range = critical?.stable_speed_ranges?.[0];
    if (!this.speedEdited) {
      const v = range ? 0.5 * (range[0] + range[1]) : 5;
      $("sim-speed").value = String(Math.round(v * 100) / 100);
    }
    this.suggested = { critical, label };
    this.hint();
    this.noteSpeed();
  }

  /** Where the bicycle is self-stable, and whether v was set to the middle of it for the user. */
  hint() {
    if (!this.suggested) return;
    const { critical, label } = this.suggested;
    const range = critical?.stable_speed_ranges?.[0];
    const name = label ? `${label}: ` : "";
    const where = range
      ? `self-stable ${fixed(range[0], 2)}–${fixed(range[1], 2)} m/s${this.speedEdited ? "" : " (v set to its middle)"}`
      : `no self-stable speed in ${fixed(critical?.range?.[0] ?? 0, 1)}–${fixed(critical?.range?.[1] ?? 10, 1)} m/s`;
    $("sim-speed-hint").textContent = `${name}${where}`;
  }

  /** A word under a negative speed: the bicycle then rides backwards. */
  noteSpeed() {
    const v = parseNumber($("sim-speed").value, "speed");
    const note = $("sim-speed-note");
    note.textContent = v !== null && v < 0 ? `v = ${num(v)} m/s: riding backwards` : "";
    note.hidden = !note.textContent;
  }

  setEnabled(on) {
    for (const id of ["sim-play", "sim-scrub", "sim-rate", "sim-csv"]) $(id).disabled = !on;
  }

  say(text, kind = "error") {
    $("sim-message").className = `message ${kind}`;
    $("sim-message").textContent = text;
    $("sim-message").hidden = !text;
  }

  /** The inputs as typed (for the URL). */
  inputs() {
    const out = {};
    for (const [id, key] of [...INPUTS, ...TORQUES]) out[key] = $(id).value;
    if ($("sim-from-turn").checked) out.turn = "held";
    if ($("sim-rider").checked) {
      out.rider = "lean";
      for (const [id, , key] of RIDER) out[key] = $(id).value;
    }
    return out;
  }

  /**
   * With the leaning rider the rider's fields are used and the held turn (the rigid rider's)
   * is not (the server's rule); the steer and lean torques act as without it.
   */
  noteRider() {
    const on = $("sim-rider").checked;
    for (const [id] of RIDER) $(id).disabled = !on;
    $("sim-from-turn").disabled = on;
    if (on) $("sim-from-turn").checked = false;
    this.noteTurn();
  }

  /** On a held turn the turn sets the steer and its torque: those inputs are not used. */
  noteTurn() {
    const on = $("sim-from-turn").checked;
    for (const id of ["sim-steer", "sim-steer-torque"]) $(id).disabled = on;
    if (!on) $("sim-turn").hidden = true;
  }

  /** The held turn a run starts on: its numbers and its stability, in words. */
  showTurn(answer) {
    const box = $("sim-turn");
    const t = answer.turn;
    const s = answer.stability;
    const radius = Number.isFinite(t.rear_radius) ? `${num(Math.abs(t.rear_radius), 4)} m` : "straight";
    const friction = t.contact.map((c) => num(c.friction_ratio, 3)).join(" / ");
    const eig = s ? s.eigenvalues.map((z) => (Math.abs(z.im) > 1e-9 ? `${num(z.re, 4)} ± ${num(Math.abs(z.im), 4)}i` : num(z.re, 4))) : [];
    const unique = eig.filter((e, k) => eig.indexOf(e) === k);
    const verdict = s ? (s.stable ? html("span", { class: "good", "data-testid": "sim-turn-verdict", text: "stable" }) : html("span", { class: "bad", "data-testid": "sim-turn-verdict", text: `unstable (largest Re λ ${num(s.max_real, 4)} 1/s)` })) : html("span", { class: "bad", "data-testid": "sim-turn-verdict", text: `stability not decided: ${answer.stability_error}` });
    box.replaceChildren(
      document.createTextNode("held turn: steer δ "),
      html("b", { "data-testid": "sim-turn-steer", text: `${fixed(answer.steer_deg, 4)}°` }),
      document.createTextNode(", torque T_δ "),
      html("b", { "data-testid": "sim-turn-torque", text: `${num(t.steer_torque, 6)} N m` }),
      document.createTextNode(`, rear radius ${radius}, lateral acceleration ${num(t.lateral_acceleration, 3)} m/s², friction ratio rear / front ${friction}; λ = ${unique.join(", ")} 1/s: `),
      verdict,
    );
    box.hidden = false;
  }

  /** Fills the inputs (from the URL); a speed given counts as typed. */
  setInputs(values) {
    for (const [id, key] of [...INPUTS, ...TORQUES]) {
      if (values[key] !== undefined) $(id).value = values[key];
    }
    if (values.speed !== undefined) this.speedEdited = true;
    $("sim-from-turn").checked = values.turn === "held";
    $("sim-rider").checked = values.rider === "lean";
    for (const [id, , key] of RIDER) if (values[key] !== undefined) $(id).value = values[key];
    this.noteTurn();
    this.noteRider();
    this.noteSpeed();
  }

  /** The request for the inputs, or null (the field flagged) when one is not a number. */
  request() {
    const request = { bike: this.bike() };
    for (const [id] of [...INPUTS, ...TORQUES, ...RIDER]) $(id).classList.remove("invalid");
    for (const [id, key] of INPUTS) {
      const x = parseNumber($(id).value, key === "speed" ? "speed" : null);
      if (x === null) {
        $(id).classList.add("invalid");
        this.refused(`${$(id).dataset.label} must be a number.`);
        return null;
      }
      request[key] = x;
    }
    for (const [id, key] of TORQUES) {
      const text = $(id).value.trim();
      const x = parseNumber(text);
      if (text === "") request[key] = 0;
      else request[key] = x === null ? text : x;
    }
    if ($("sim-rider").checked) {
      request.rider = {};
      for (const [id, key] of RIDER) {
        const text = $(id).value.trim();
        if (key === "torque_duration" && text === "") continue;
        const x = parseNumber(text);
        if (x === null) {
          $(id).classList.add("invalid");
          this.refused(`${$(id).dataset.label} must be a number.`);
          return null;
        }
        request.rider[key] = x;
      }
    } else if ($("sim-from-turn").checked) {
      // The turn's steer and its holding torque (the server's), not the inputs'.
      request.from_turn = true;
      request.steer_deg = 0;
      delete request.steer_torque;
    }
    return request;
  }

  /** A run refused: the message, and the pill says what the plots still show. */
  refused(message) {
    this.say(message);
    const pill = $("sim-outcome");
    pill.className = "sim-outcome bad";
    pill.dataset.kind = "refused";
    pill.textContent = this.result ? `refused, not run: still showing the previous run (${runLabel(this.runs[0].request)})` : "refused, not run";
  }

  async run() {
    const request = this.request();
    if (!request) return;
    this.pause();
    this.say(request.speed < 0 ? `v = ${num(request.speed)} m/s: the bicycle rides backwards (the linear model has no self-stable speed below zero).` : "", "warning");
    $("sim-run").disabled = true;
    $("sim-outcome").className = "sim-outcome running";
    $("sim-outcome").textContent = "simulating…";
    try {
      if (request.from_turn) {
        $("sim-turn").hidden = true;
        this.showTurn(await api.turn({ bike: request.bike, speed: request.speed, lean_deg: request.lean_deg }));
      }
      const result = await api.simulate(request);
      const run = { request, result, label: runLabel(request), linear: null };
      // The linear model beside is the rigid rider's: not drawn with the leaning one.
      const handsFree = request.steer_torque === 0 && request.lean_torque === 0 && !request.rider;
      if (handsFree) {
        const end = result.frames[result.frames.length - 1].t;
        const { bike, speed, lean_deg, steer_deg, lean_rate, steer_rate } = request;
        run.linear = await api.linearResponse({ bike, speed, lean_deg, steer_deg, lean_rate, steer_rate, duration: Math.max(end, 1e-3), dt: 1 / result.frame_rate }).catch(() => null);
      }
      this.runs = [run, ...this.runs].slice(0, KEEP);
      this.load(result);
      $("sim-linear-note").textContent = handsFree ? "" : request.rider ? "linear model: rigid rider only" : "linear model: hands-free runs only";
      this.onRun(request);
      await this.ensureView();
      this.view?.load(result);
      this.seek(0);
      this.play();
    } catch (e) {
      const input = [...INPUTS, ...TORQUES].find(([, key]) => key === e.field) ?? RIDER.find(([, key]) => `rider.${key}` === e.field);
      if (input) $(input[0]).classList.add("invalid");
      this.refused(e.message);
    } finally {
      $("sim-run").disabled = false;
    }
  }

  drawPlots() {
    if (!this.runs.length) return;
    const showLinear = $("sim-linear").checked;
    this.timePlot.update(this.runs.map((r, k) => ({ ...r, linear: k === 0 && showLinear ? r.linear : null })));
    $("sim-clear").disabled = this.runs.length < 2;
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
    $("sim-meta").textContent = `${result.name ?? "bicycle"} · ${runLabel(this.runs[0].request)} · ${result.steps.toLocaleString("en")} steps`;
    this.drawPlots();
    this.trackPlot.update(result);
    this.setEnabled(true);
  }

  /** The current run's time series (and the linear prediction) as CSV, named after the bike. */
  exportCsv() {
    const run = this.runs[0];
    if (!run) return;
    const r = run.request;
    const lines = [
      `# whipple simulation of ${run.result.name ?? this.label()}: ${run.label}; ${run.result.outcome.message}`,
      "# angles in degrees, rates in rad/s, positions in m; linear_*: the linear model from the same initial state (hands free)",
    ];
    const linear = run.linear;
    const leaning = run.result.frames[0]?.rider_lean !== undefined;
    lines.push(["t", "lean_deg", "steer_deg", "lean_rate", "steer_rate", "yaw_deg", "speed", "rear_x", "rear_y", "front_x", "front_y", ...(leaning ? ["rider_lean_deg"] : []), ...(linear ? ["linear_lean_deg", "linear_steer_deg"] : [])].join(","));
    run.result.frames.forEach((f, i) => {
      const row = [f.t, f.lean * DEG, f.steer * DEG, f.lean_rate, f.steer_rate, f.yaw * DEG, f.speed, ...f.rear_contact, ...f.front_contact];
      if (leaning) row.push(f.rider_lean * DEG);
      if (linear) row.push(linear.lean[i] * DEG, linear.steer[i] * DEG);
      lines.push(row.map((x) => (x === undefined ? "" : String(x))).join(","));
    });
    download(`${slug(run.result.name ?? this.label())}-simulation-v${num(r.speed)}.csv`, `${lines.join("\n")}\n`, "text/csv");
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
    $("sim-rider-readout-row").hidden = f.rider_lean === undefined;
    if (f.rider_lean !== undefined) $("sim-rider-readout").textContent = fixed(f.rider_lean * DEG, 1);
    this.view?.show(i);
    this.timePlot.cursor(i);
    this.trackPlot.cursor(i);
  }
}
