// The Response tab: the bicycle as a linear system, one input and one output at a time
// (/api/linear/frequency, the library's exact transfer functions). A speed slider and a few
// speeds compared ("3, 5, 7" m/s): Bode magnitude [dB] and phase [deg] against frequency on
// logarithmic axes, one curve per speed, the slider's drawn heavy; the poles and zeros at the
// slider's speed, a right-half-plane zero flagged, and the speeds where a zero crosses s = 0
// (steer torque → lean: the counter-steering zero). `kind` is the sub-view: the Bode plot
// now; step and initial-condition responses and the path in the plane join it as kinds.

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
export const KINDS = ["bode"];

/** "3, 5, 7" → [3, 5, 7]; null when a part is not a number (empty parts skipped). */
export function parseSpeeds(text) {
  const parts = String(text ?? "").split(/[,\s;]+/).filter(Boolean);
  const out = [];
  for (const p of parts) {
    const v = parseNumber(p);
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
    const changed = () => {
      this.compute();
      this.onChange();
    };
    for (const id of ["resp-input", "resp-output", "resp-kind"]) $(id).addEventListener("change", changed);
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
    return { kind: $("resp-kind").value, in: $("resp-input").value, out: $("resp-output").value, v: $("resp-speed").value, cmp: $("resp-compare").value.trim() };
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
    this.showSpeed();
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

  /** Veils what is shown (`reason`), or unveils it (null). */
  veil(reason) {
    $("resp-roots").classList.toggle("stale", Boolean(reason));
    $("resp-roots").dataset.stale = reason ?? "";
    for (const p of [this.magnitude, this.phase]) {
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

