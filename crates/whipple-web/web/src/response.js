// The Response tab: the bicycle as a linear system, one input and one output at a time
// (/api/linear/frequency, the library's exact transfer functions). A speed slider and a few
// speeds compared ("3, 5, 7" m/s): Bode magnitude [dB] and phase [deg] against frequency on
// logarithmic axes, one curve per speed, the slider's drawn heavy; the poles and zeros at the
// slider's speed, a right-half-plane zero flagged, and the speeds where a zero crosses s = 0
// (steer torque → lean: the counter-steering zero). `kind` is the sub-view: the Bode plot, or
// a time response (/api/linear/time, exact): the step response and the motion from an initial
// lean drawn as lean and steer against time, and the path in the plane of a pulse of torque
// (the rear and front contacts seen from above); each optionally beside the same manoeuvre on
// the non-linear model, dashed, with the largest difference.

import { api } from "./api.js";
import { parseNumber } from "./editor.js";
import { html, svg, num } from "./format.js";
import { Chart, nearest, legend } from "./chart.js";
import { COMPARE_COLOURS } from "./plot.js";

const $ = (id) => document.getElementById(id);
/** The frequency grid [rad/s]: 0.1 to 100 rad/s (0.016 to 16 Hz), logarithmic. */
const GRID = { start: 0.1, stop: 100, count: 300 };
/** The most speeds compared besides the slider's (the server takes 16 in all). */
const MAX_COMPARED = 8;
const HEAVY = "#111827";
export const KINDS = ["bode", "step", "initial", "path"];
/** The time views: the time response asked for, its span [s] and samples. */
const TIME_VIEWS = {
  step: { kind: "step", duration: 10, samples: 401 },
  initial: { kind: "initial", duration: 6, samples: 241 },
  path: { kind: "pulse", duration: 6, samples: 241 },
};
const LINEAR_COLOURS = { lean: "#1d4ed8", steer: "#b45309", rear: "#1d4ed8", front: "#b45309" };

/** "3, 5, 7" → [3, 5, 7]; null when a part is not a number (empty parts skipped). */
export function parseSpeeds(text) {
  const parts = String(text ?? "").split(/[,\s;]+/).filter(Boolean);
  const out = [];
  for (const p of parts) {
    const v = parseNumber(p, "speed");
    if (v === null) return null;
    out.push(v);
  }
  return out;
}

/** A complex number as read: "−0.775 ± 4.465i" for a pair, "2.31" for a real value. */
function complexText(re, im) {
  return im !== 0 ? `${num(re)} ± ${num(Math.abs(im))}i` : num(re);
}

/** Conjugate pairs listed once (the one with the positive imaginary part). */
function once(values) {
  return values.filter(({ re, im }) => !(im < 0 && values.some((o) => o.re === re && o.im === -im)));
}

/** One of the two Bode plots: `quantity` "magnitude_db" or "phase_deg" against log₁₀ ω. */
class BodePlot extends Chart {
  constructor(container, { quantity, label, yLabel, legendOn }) {
    super(container, { label, xLabel: "frequency ω [rad/s]", yLabel, logX: true, minHeight: 140, margin: { left: 56, right: 14, top: legendOn ? 36 : 30, bottom: 38 }, testid: container.dataset.testid });
    this.quantity = quantity;
    this.legendOn = legendOn;
    this.answer = null;
  }

  ready() {
    return Boolean(this.answer?.responses?.length);
  }

  /** `answer`: /api/linear/frequency's; `heavy`: the slider's speed; `stale`: why it no longer matches. */
  update(answer, { heavy, stale = null, keepView = false }) {
    if (!keepView) this.view = null;
    this.answer = answer;
    this.heavy = heavy;
    this.stale = stale;
    this.logOmega = answer.frequencies.map(Math.log10);
    // Each phase curve is unwrapped along its own grid from its principal value; shifted by
    // whole turns so that it starts within 180° of the curve before it, the curves compare.
    this.shift = [];
    let previous = null;
    for (const r of answer.responses) {
      const first = r.phase_deg[0];
      const turns = previous === null || !Number.isFinite(first) ? 0 : Math.round((previous - first) / 360);
      this.shift.push(360 * turns);
      if (Number.isFinite(first)) previous = first + 360 * turns;
    }
    this.draw();
  }

  values(r) {
    if (this.quantity !== "phase_deg") return r[this.quantity];
    const k = this.answer.responses.indexOf(r);
    return r.phase_deg.map((p) => p + (this.shift[k] ?? 0));
  }

  extent() {
    const x = this.logOmega;
    const fit = this.fitY(x[0], x[x.length - 1]) ?? { y0: -1, y1: 1 };
    const pad = Math.max(1, 0.06 * (fit.y1 - fit.y0));
    return { x0: x[0], x1: x[x.length - 1], y0: fit.y0 - pad, y1: fit.y1 + pad };
  }

  fitY(x0, x1) {
    let lo = Infinity, hi = -Infinity;
    for (const r of this.answer.responses) {
      this.values(r).forEach((y, i) => {
        const x = this.logOmega[i];
        if (y === null || !Number.isFinite(y) || x < x0 || x > x1) return;
        lo = Math.min(lo, y);
        hi = Math.max(hi, y);
      });
    }
    return hi >= lo ? { y0: lo, y1: hi > lo ? hi : lo + 1 } : null;
  }

  xs() {
    return this.logOmega;
  }

  /** The slider's curve in ink; the compared speeds in the compared designs' colours, in order
   * of speed (the first, slate, left out: it is too near the ink). */
  colour(k) {
    const rs = this.answer.responses;
    if (rs[k].speed === this.heavy) return HEAVY;
    const j = rs.slice(0, k).filter((r) => r.speed !== this.heavy).length;
    return COMPARE_COLOURS[1 + (j % (COMPARE_COLOURS.length - 1))];
  }

  render(root, f) {
    const { X, Y } = f;
    const curves = svg("g", { "clip-path": f.clip, fill: "none", "stroke-linejoin": "round" });
    // The slider's curve last, on top of the others.
    const order = this.answer.responses.map((_, k) => k).sort((a, b) => (this.answer.responses[a].speed === this.heavy) - (this.answer.responses[b].speed === this.heavy));
    for (const k of order) {
      const r = this.answer.responses[k];
      let d = "";
      let pen = false;
      this.values(r).forEach((y, i) => {
        if (y === null || !Number.isFinite(y)) {
          pen = false;
          return;
        }
        d += `${pen ? "L" : "M"}${X(this.logOmega[i]).toFixed(1)} ${Y(y).toFixed(1)}`;
        pen = true;
      });
      const heavy = r.speed === this.heavy;
      curves.append(svg("path", { d, stroke: this.colour(k), "stroke-width": heavy ? 2.4 : 1.4, "data-testid": "resp-curve", "data-speed": r.speed, "data-heavy": String(heavy) }));
    }
    root.append(curves);
    if (this.legendOn) {
      const items = this.answer.responses.map((r, k) => ({
        draw: (x, y) => svg("line", { x1: x, y1: y, x2: x + 18, y2: y, stroke: this.colour(k), "stroke-width": r.speed === this.heavy ? 2.6 : 1.6 }),
        text: `${num(r.speed)} m/s${r.speed === this.heavy ? " (slider)" : ""}`,
      }));
      f.legendBottom = legend(root, items, f.left, f.legendWidth, 11);
    }
  }

  readAt(h, f) {
    const i = h.key !== undefined ? nearest(this.logOmega, h.key) : nearest(this.logOmega, this.toData(h).x);
    if (h.key === undefined) this.hover.index = i;
    const omega = this.answer.frequencies[i];
    const rows = [html("div", { class: "tt-v", text: `ω = ${num(omega)} rad/s (${num(omega / (2 * Math.PI))} Hz)` })];
    const dots = [];
    const unit = this.quantity === "magnitude_db" ? " dB" : "°";
    this.answer.responses.forEach((r, k) => {
      const y = this.values(r)[i];
      rows.push(html("div", { class: "tt-row" }, html("span", { class: "tt-dot", style: `background:${this.colour(k)}` }), html("span", { class: "tt-mode", text: `${num(r.speed)} m/s` }), html("span", { class: "tt-val", text: y === null ? "–" : `${num(y)}${unit}` })));
      if (y !== null && Number.isFinite(y)) dots.push({ x: f.X(this.logOmega[i]), y: f.Y(y), colour: this.colour(k) });
    });
    return { rows, dots, x: f.X(this.logOmega[i]) };
  }
}

/** Curves y(x) (x increasing), each {x, y, colour, dashed, name, testid}: the time plots, the
 * path in the plane, and (extended in ridden.js) the lane change and the peak HQM against
 * speed. A y that is null or not finite leaves a gap; each series is read out at its own x
 * nearest the cursor's. A subclass may draw under the curves (`underlay(root, frame)`) and add
 * legend entries (`legendItems()`). */
export class CurvePlot extends Chart {
  constructor(container, { label, xLabel, yLabel, unit, flipY = false, minHeight = 140 }) {
    super(container, { label, xLabel, yLabel, flipY, minHeight, margin: { left: 56, right: 14, top: 36, bottom: 38 }, testid: container.dataset.testid });
    this.unit = unit;
    this.series = null;
  }

  ready() {
    return Boolean(this.series?.length);
  }

  update(series) {
    this.view = null;
    this.series = series;
    this.draw();
  }

  extent() {
    const xs = this.series[0].x;
    const fit = this.fitY(xs[0], xs[xs.length - 1]) ?? { y0: -1, y1: 1 };
    const pad = Math.max(1e-6, 0.06 * (fit.y1 - fit.y0));
    return { x0: xs[0], x1: xs[xs.length - 1], y0: fit.y0 - pad, y1: fit.y1 + pad };
  }

  fitY(x0, x1) {
    let lo = Infinity, hi = -Infinity;
    for (const s of this.series) {
      s.y.forEach((y, i) => {
        if (!Number.isFinite(y) || s.x[i] < x0 || s.x[i] > x1) return;
        lo = Math.min(lo, y);
        hi = Math.max(hi, y);
      });
    }
    if (!(hi >= lo)) return null;
    return hi > lo ? { y0: lo, y1: hi } : { y0: lo - 1, y1: lo + 1 };
  }

  xs() {
    return this.series[0].x;
  }

  render(root, f) {
    const { X, Y } = f;
    this.underlay?.(root, f);
    const curves = svg("g", { "clip-path": f.clip, fill: "none", "stroke-linejoin": "round" });
    for (const s of this.series) {
      let d = "";
      let pen = false;
      s.y.forEach((y, i) => {
        if (y === null || !Number.isFinite(y)) {
          pen = false;
          return;
        }
        d += `${pen ? "L" : "M"}${X(s.x[i]).toFixed(1)} ${Y(y).toFixed(1)}`;
        pen = true;
      });
      curves.append(svg("path", { d, stroke: s.colour, "stroke-width": s.width ?? (s.dashed ? 1.8 : 2), "stroke-dasharray": s.dashed ? "6 4" : "none", "data-testid": s.testid, "data-name": s.name }));
    }
    root.append(curves);
    const items = this.series.map((s) => ({
      draw: (x, y) => svg("line", { x1: x, y1: y, x2: x + 18, y2: y, stroke: s.colour, "stroke-width": s.width ?? 2, "stroke-dasharray": s.dashed ? "5 3" : "none" }),
      text: s.name,
    }));
    items.push(...(this.legendItems?.() ?? []));
    f.legendBottom = legend(root, items, f.left, f.legendWidth, 11);
  }

  readAt(h, f) {
    const xs = this.series[0].x;
    const i = h.key !== undefined ? nearest(xs, h.key) : nearest(xs, this.toData(h).x);
    if (h.key === undefined) this.hover.index = i;
    const rows = [html("div", { class: "tt-v", text: `${this.xLabel.split(" [")[0]} = ${num(xs[i])}` })];
    const dots = [];
    for (const s of this.series) {
      const j = s.x === xs ? i : nearest(s.x, xs[i]);
      const y = s.y[j];
      rows.push(html("div", { class: "tt-row" }, html("span", { class: "tt-dot", style: `background:${s.colour}` }), html("span", { class: "tt-mode", text: s.name }), html("span", { class: "tt-val", text: Number.isFinite(y) ? `${num(y)} ${this.unit}` : "–" })));
      if (Number.isFinite(y)) dots.push({ x: f.X(s.x[j]), y: f.Y(y), colour: s.colour });
    }
    return { rows, dots, x: f.X(xs[i]) };
  }
}

export class ResponsePanel {
  /** `bike()` gives the current bicycle, `label()` its name; `onChange()` records the state. */
  constructor({ bike, label, onChange }) {
    this.bike = bike;
    this.label = label;
    this.onChange = onChange ?? (() => {});
    this.answer = null;
    this.fresh = false; // the answer is of the bicycle shown now
    this.sequence = 0;
    this.magnitude = new BodePlot($("resp-magnitude"), { quantity: "magnitude_db", label: "Bode magnitude against frequency", yLabel: "magnitude [dB]", legendOn: true });
    this.phase = new BodePlot($("resp-phase"), { quantity: "phase_deg", label: "Bode phase against frequency", yLabel: "phase [°]", legendOn: false });
    this.lean = new CurvePlot($("resp-lean"), { label: "Lean against time", xLabel: "time t [s]", yLabel: "lean φ [°]", unit: "°" });
    this.steer = new CurvePlot($("resp-steer"), { label: "Steer against time", xLabel: "time t [s]", yLabel: "steer δ [°]", unit: "°" });
    this.path = new CurvePlot($("resp-path"), { label: "The wheels' contact paths in the ground plane, seen from above", xLabel: "x along the run [m]", yLabel: "y, to the right: down [m]", unit: "m", flipY: true });
    this.timeAnswer = null;
    const changed = () => {
      this.compute();
      this.onChange();
    };
    for (const id of ["resp-input", "resp-output", "resp-kind", "resp-nonlinear", "resp-amplitude", "resp-pulse", "resp-lean0"]) $(id).addEventListener("change", changed);
    $("resp-kind").addEventListener("change", () => this.showKind());
    $("resp-speed").addEventListener("input", () => {
      this.showSpeed();
      this.compute();
    });
    $("resp-speed").addEventListener("change", () => this.onChange());
    $("resp-form").addEventListener("submit", (e) => {
      e.preventDefault();
      changed();
    });
    $("resp-compare").addEventListener("change", changed);
    this.showSpeed();
    this.showKind();
  }

  /** The sub-view shown: "bode" or a time view. */
  view() {
    return $("resp-kind").value;
  }

  /** Shows the fields and plots of the sub-view chosen, hides the others. */
  showKind() {
    const kind = this.view();
    const time = kind !== "bode";
    const show = (selector, on) => document.querySelectorAll(selector).forEach((e) => (e.hidden = !on));
    show(".resp-bode-only", !time);
    show(".resp-any-time", time);
    show(".resp-time-only", kind === "step" || kind === "path");
    show(".resp-path-only", kind === "path");
    show(".resp-initial-only", kind === "initial");
    $("resp-magnitude").hidden = time;
    $("resp-phase").hidden = time;
    $("resp-lean").hidden = kind !== "step" && kind !== "initial";
    $("resp-steer").hidden = kind !== "step" && kind !== "initial";
    $("resp-path").hidden = kind !== "path";
    document.querySelector(".resp-plots").classList.toggle("single", kind === "path");
    $("resp-roots").setAttribute("aria-label", time ? "The response's summary" : "Poles and zeros at the slider's speed");
  }

  /** The slider's speed [m/s]. */
  speed() {
    return Number($("resp-speed").value);
  }

  showSpeed() {
    $("resp-speed-value").textContent = `${num(this.speed())} m/s`;
  }

  /** The state the link carries. */
  inputs() {
    return { kind: $("resp-kind").value, in: $("resp-input").value, out: $("resp-output").value, v: $("resp-speed").value, cmp: $("resp-compare").value.trim(), amp: $("resp-amplitude").value.trim(), dur: $("resp-pulse").value.trim(), lean: $("resp-lean0").value.trim(), nl: $("resp-nonlinear").checked ? "1" : "0" };
  }

  /** Restores what `inputs()` gave; unknown choices keep the defaults. */
  setInputs(s) {
    const choose = (id, value) => {
      if (value !== undefined && [...$(id).options].some((o) => o.value === value)) $(id).value = value;
    };
    choose("resp-kind", s.kind);
    choose("resp-input", s.in);
    choose("resp-output", s.out);
    if (s.v !== undefined && Number.isFinite(Number(s.v))) $("resp-speed").value = s.v;
    if (s.cmp !== undefined) $("resp-compare").value = s.cmp;
    if (s.amp !== undefined) $("resp-amplitude").value = s.amp;
    if (s.dur !== undefined) $("resp-pulse").value = s.dur;
    if (s.lean !== undefined) $("resp-lean0").value = s.lean;
    if (s.nl !== undefined) $("resp-nonlinear").checked = s.nl === "1";
    this.showSpeed();
    this.showKind();
  }

  /** The bicycle changed: the answer shown is of another one until computed again. */
  invalidate() {
    this.fresh = false;
  }

  say(text) {
    $("resp-message").textContent = text ?? "";
    $("resp-message").hidden = !text;
  }

  async compute() {
    if (this.view() !== "bode") return this.computeTime();
    const compared = parseSpeeds($("resp-compare").value);
    $("resp-compare").classList.toggle("invalid", compared === null || compared.length > MAX_COMPARED);
    if (compared === null || compared.length > MAX_COMPARED) {
      this.say(compared === null ? "The speeds compared must be numbers separated by commas (e.g. 3, 5, 7)." : `Compare at most ${MAX_COMPARED} speeds.`);
      this.veil("not recomputed: the speeds compared are invalid");
      return;
    }
    const v = this.speed();
    const speeds = [...new Set([...compared, v])].sort((a, b) => a - b);
    const mine = ++this.sequence;
    try {
      const answer = await api.frequency({ bike: this.bike(), speeds, input: $("resp-input").value, output: $("resp-output").value, frequencies: GRID });
      if (mine !== this.sequence) return;
      this.say(null);
      const sameView = this.answer && this.answer.input.name === answer.input.name && this.answer.output.name === answer.output.name;
      this.answer = answer;
      this.fresh = true;
      this.render(v, { keepView: sameView });
    } catch (e) {
      if (mine !== this.sequence) return;
      const field = e.field === "speeds" ? "resp-compare" : null;
      if (field) $(field).classList.add("invalid");
      this.say(e.message);
      this.veil("not recomputed: see the message above");
    }
  }

  /** The time view's numbers read from the form; null (with the message said and the field
   * marked) when one is not a number or out of range. */
  timeRequest() {
    const view = TIME_VIEWS[this.view()];
    const fields = [
      { id: "resp-amplitude", on: view.kind !== "initial", lo: -100, hi: 100, what: "The amplitude must be a number of newton-metres between −100 and 100." },
      { id: "resp-pulse", on: view.kind === "pulse", lo: 1e-3, hi: view.duration, what: `The pulse's duration must be a number of seconds from 0.001 to ${view.duration}.` },
      { id: "resp-lean0", on: view.kind === "initial", lo: -45, hi: 45, what: "The initial lean must be a number of degrees between −45 and 45." },
    ];
    const values = {};
    let bad = null;
    for (const f of fields) {
      const v = parseNumber($(f.id).value);
      const wrong = f.on && (v === null || !(v >= f.lo && v <= f.hi));
      $(f.id).classList.toggle("invalid", wrong);
      $(f.id).setAttribute("aria-invalid", String(wrong));
      if (wrong && !bad) bad = f.what;
      values[f.id] = v;
    }
    if (bad) {
      this.say(bad);
      this.veil("not recomputed: see the message above");
      return null;
    }
    return {
      bike: this.bike(),
      speed: this.speed(),
      kind: view.kind,
      input: $("resp-input").value,
      amplitude: view.kind === "initial" ? 0 : values["resp-amplitude"],
      pulse_duration: view.kind === "pulse" ? values["resp-pulse"] : 0.5,
      lean_deg: view.kind === "initial" ? values["resp-lean0"] : 0,
      duration: view.duration,
      samples: view.samples,
      nonlinear: $("resp-nonlinear").checked,
    };
  }

  async computeTime() {
    const request = this.timeRequest();
    if (!request) return;
    const mine = ++this.sequence;
    const view = this.view();
    try {
      const answer = await api.time(request);
      if (mine !== this.sequence) return;
      this.say(null);
      this.timeAnswer = answer;
      this.fresh = true;
      this.renderTime(view, answer);
    } catch (e) {
      if (mine !== this.sequence) return;
      const field = { amplitude: "resp-amplitude", pulse_duration: "resp-pulse", lean_deg: "resp-lean0" }[e.field];
      if (field) $(field).classList.add("invalid");
      this.say(e.message);
      this.veil("not recomputed: see the message above");
    }
  }

  renderTime(view, a) {
    const nl = a.nonlinear;
    const t = a.times;
    const box = $("resp-roots");
    box.replaceChildren();
    const input = a.kind === "initial" ? "no input" : `${a.input.symbol} ${a.kind} of ${num(a.amplitude)} ${a.input.unit}`;
    box.append(html("h3", { text: `At ${num(a.speed)} m/s: ${input}` }));
    const last = t.length - 1;
    if (view === "path") {
      const w = this.bike()?.benchmark?.w ?? 0;
      const l = a.linear;
      const series = [
        { x: l.rear_x, y: l.rear_y, colour: LINEAR_COLOURS.rear, dashed: false, name: "rear contact (linear)", testid: "resp-path-curve" },
        { x: l.rear_x.map((x) => x + w), y: l.front_y, colour: LINEAR_COLOURS.front, dashed: false, name: "front contact (linear)", testid: "resp-path-curve" },
      ];
      if (nl) {
        series.push({ x: nl.motion.rear_x, y: nl.motion.rear_y, colour: LINEAR_COLOURS.rear, dashed: true, name: "rear (non-linear)", testid: "resp-path-curve-nonlinear" });
        series.push({ x: nl.motion.rear_x.map((x) => x + w), y: nl.motion.front_y, colour: LINEAR_COLOURS.front, dashed: true, name: "front (non-linear)", testid: "resp-path-curve-nonlinear" });
      }
      this.path.update(series);
      // How much more y is stretched than x on the screen.
      const f = this.path.frame;
      const e = this.path.extent();
      const stretch = f ? (f.ph / (e.y1 - e.y0)) / (f.pw / (e.x1 - e.x0)) : 1;
      const note = stretch > 1.5 ? ` — y exaggerated ×${num(stretch, 2)}` : "";
      $("resp-meta").textContent = `${this.label()}: the contacts' paths seen from above (front x: rear x + wheelbase)${note}`;
      $("resp-meta").dataset.exaggeration = String(stretch);
      box.append(html("p", { class: "mono", "data-testid": "resp-final", text: `at ${num(t[last])} s: y_P = ${num(l.rear_y[last])} m, ψ = ${num(l.yaw_deg[last])}°` }));
    } else {
      const curves = (key, colour) => {
        const series = [{ x: t, y: a.linear[key], colour, dashed: false, name: "linear", testid: "resp-time-curve" }];
        if (nl) series.push({ x: t, y: nl.motion[key], colour: "#111827", dashed: true, name: "non-linear", testid: "resp-time-curve-nonlinear" });
        return series;
      };
      this.lean.update(curves("lean_deg", LINEAR_COLOURS.lean));
      this.steer.update(curves("steer_deg", LINEAR_COLOURS.steer));
      $("resp-meta").textContent = `${this.label()}: lean and steer against time (linear model${nl ? ", non-linear dashed" : ""})`;
      box.append(html("p", { class: "mono", "data-testid": "resp-final", "data-lean": String(a.linear.lean_deg[last]), text: `at ${num(t[last])} s: φ = ${num(a.linear.lean_deg[last])}°, δ = ${num(a.linear.steer_deg[last])}°` }));
    }
    if (nl) {
      const d = nl.largest_difference;
      box.append(html("p", { class: "mono", "data-testid": "resp-difference", text: `largest difference, non-linear − linear: φ ${num(d.lean_deg)}°, δ ${num(d.steer_deg)}°, ψ ${num(d.yaw_deg)}°, y ${num(d.rear_y)} m` }));
    }
    box.append(html("p", { class: "note", text: nl
      ? "Linear: exact (matrix exponentials). Non-linear: the same manoeuvre integrated on the full model (dashed)."
      : "The linearized model's exact response (matrix exponentials), not a numerical integration." }));
    this.veil(null);
  }

  /** Veils what is shown (`reason`), or unveils it (null). */
  veil(reason) {
    $("resp-roots").classList.toggle("stale", Boolean(reason));
    $("resp-roots").dataset.stale = reason ?? "";
    for (const p of [this.magnitude, this.phase, this.lean, this.steer, this.path]) {
      if (!p.ready()) continue;
      p.stale = reason;
      p.draw();
    }
  }

  render(v, { keepView }) {
    const a = this.answer;
    this.magnitude.update(a, { heavy: v, keepView });
    this.phase.update(a, { heavy: v, keepView });
    $("resp-meta").textContent = `${this.label()}: ${a.input.symbol} → ${a.output.symbol}, |G| in dB of 1 ${a.output.unit} per ${a.input.unit} (linear model)`;
    this.renderRoots(v);
    this.veil(null);
  }

  /** The poles and zeros at the slider's speed, a right-half-plane zero flagged. */
  renderRoots(v) {
    const a = this.answer;
    const r = a.responses.find((x) => x.speed === v) ?? a.responses[0];
    const box = $("resp-roots");
    box.replaceChildren();
    box.append(html("h3", { text: `At ${num(r.speed)} m/s` }));
    if (r.zero_response) {
      box.append(html("p", { class: "note", "data-testid": "resp-zero-response", text: `${a.input.symbol} does not reach ${a.output.symbol} in the linear model: G(s) = 0.` }));
      return;
    }
    const poles = once(r.poles.map(([re, im]) => ({ re, im })));
    const list = (title, items, testid) => {
      const ul = html("ul", { class: "resp-list", "data-testid": testid, "aria-label": title });
      for (const it of items) ul.append(it);
      box.append(html("div", { class: "resp-list-title", text: title }), ul);
    };
    list("poles [1/s]", poles.map((p) => html("li", { class: "mono", "data-testid": "resp-pole", text: `${complexText(p.re, p.im)}${p.re > 0 ? "  (unstable)" : ""}` })), "resp-poles");
    const zeros = once(r.zeros);
    list("zeros [1/s]", zeros.length ? zeros.map((z) => {
      const li = html("li", { class: `mono${z.right_half_plane ? " rhp" : ""}`, "data-testid": "resp-zero", "data-rhp": String(z.right_half_plane) }, complexText(z.re, z.im));
      if (z.right_half_plane) li.append(html("span", { class: "badge bad", text: "right half-plane" }));
      return li;
    }) : [html("li", { class: "note", text: "none" })], "resp-zeros");
    const rhp = r.zeros.some((z) => z.right_half_plane);
    box.append(html("p", { class: `resp-phase-note${rhp ? " warn" : ""}`, "data-testid": "resp-rhp-summary", text: rhp
      ? `Non-minimum phase at ${num(r.speed)} m/s: a zero in the right half-plane.`
      : `Minimum phase at ${num(r.speed)} m/s: no zero in the right half-plane.` }));
    box.append(html("p", { class: "mono resp-gain", text: `gain K = ${num(r.gain)} · G(0) = ${r.static_gain === null ? "– (an integrator)" : num(r.static_gain)}` }));
    if (a.origin_zero_speeds) {
      const s = a.origin_zero_speeds;
      box.append(html("p", { class: "note", "data-testid": "resp-crossing", text: s.length
        ? `A zero crosses s = 0 at ${s.map((c) => `${num(c.value)} m/s`).join(" and ")}: ${a.input.symbol} → ${a.output.symbol} changes there between minimum and non-minimum phase (certified speed${s.length > 1 ? "s" : ""}).`
        : `No zero of ${a.input.symbol} → ${a.output.symbol} crosses s = 0 at any speed.` }));
    }
    box.append(html("p", { class: "note", text: "Exact transfer functions of the linearized model, G(s) = N(s) / det(M s² + v C₁ s + g K₀ + v² K₂), from the polynomial matrix and its adjugate, not a numerical state-space fit; ω from 0.1 to 100 rad/s." }));
  }
}

