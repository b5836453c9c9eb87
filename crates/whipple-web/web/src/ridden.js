// The Ridden tab: the bicycle ridden by Hess's human controller (/api/ridden), the rider's
// gains set at every speed by Hess 2012's crossover rules (HumanControl), the rider's task the
// lateral (path-following) loop. Two plots: HumanControl's lane change (lane_change.m) in the
// plane, the road and the front contact of the linear and of the non-linear bicycle; and the
// certified peak of Hess's handling quality metric against speed, the speeds where the roll or
// lateral loop is unstable (or no gain meets a rule) shaded, the HQM = 5 level drawn (Hess
// reads peaks below 5 as good handling, above 8 as poor). A one-line summary: the gains, each
// model's largest deviation from the road, the peak HQM at the lane change's speed.

import { api } from "./api.js";
import { parseNumber } from "./editor.js";
import { html, svg, num, slug, download } from "./format.js";
import { nearest } from "./chart.js";
import { CurvePlot } from "./response.js";

const $ = (id) => document.getElementById(id);
/** The server's bounds (src/ridden.rs). */
const MIN_SPEED = 1;
const MAX_SPEED = 20;
const MAX_HQM_SPEEDS = 500;
/** Hess's boundary of good handling. */
const GOOD_HQM = 5;
const COLOURS = { road: "#9ca3af", linear: "#1d4ed8", nonlinear: "#dc2626", hqm: "#111827", unstable: "#fde68a", refused: "#e5e7eb", good: "#15803d" };
/** The gains' subscripts, by the library's names (HumanGains::NAMES). */
const SUBSCRIPTS = { kDelta: "δ", kPhiDot: "φ̇", kPhi: "φ", kPsi: "ψ", kY: "y" };
/** The default view's highest peak HQM: above it (near the speed where a loop turns unstable
 * the peak grows without bound) the curve leaves the view, said on the plot; "Fit y" shows it. */
const VIEW_TOP = 20;
const DEFAULTS = { v: "5", lane: "double", from: "1", to: "10", step: "0.25" };
const UNSTABLE_TEXT = "roll or lateral loop unstable";
const REFUSED_TEXT = "no gain by Hess's rules";

/** The largest |front_y − road| of a run [m]. */
export function largestDeviation(run) {
  let worst = 0;
  run.front_y.forEach((y, i) => {
    const d = Math.abs(y - run.road[i]);
    if (d > worst) worst = d;
  });
  return worst;
}

/** Why a speed of the sweep has no peak: "unstable" (a loop unstable) or "refused" (no gain). */
function gapKind(row) {
  return row.peak !== null ? null : row.stable || !/unstable/.test(row.reason ?? "unstable") ? "refused" : "unstable";
}

/** The lane change in the plane. Where the linear closed loop diverges (its front contact
 * metres, or 10²¹ m, off the road) the default view keeps the road in sight, and says that a
 * curve leaves it. */
class LanePlot extends CurvePlot {
  constructor(container) {
    super(container, { label: "The lane change in the plane: the road and the front contact of each model", xLabel: "x along the road [m]", yLabel: "y lateral, right positive [m]", unit: "m", minHeight: 200 });
  }

  /** The road's range [m]. */
  road() {
    const road = this.series[0].y;
    return { lo: Math.min(...road), hi: Math.max(...road) };
  }

  extent() {
    const e = super.extent();
    const { lo, hi } = this.road();
    const room = 2 * Math.max(hi - lo, 1);
    return { ...e, y0: Math.max(e.y0, lo - room), y1: Math.min(e.y1, hi + room) };
  }

  /** The curves, then (on top of them) whether one leaves the default view. */
  render(root, f) {
    super.render(root, f);
    const outside = this.series.filter((s) => s.y.some((y) => Number.isFinite(y) && (y > f.y1 || y < f.y0)));
    if (!outside.length || this.view) return;
    root.append(svg("text", { x: f.left + f.pw - 6, y: f.top + 14, "text-anchor": "end", fill: "#92400e", "font-size": 10.5, stroke: "#ffffff", "stroke-width": 3, "paint-order": "stroke", "data-testid": "rd-lane-outside" }, `${outside.map((s) => s.name).join(" and ")} leave${outside.length > 1 ? "" : "s"} the view`));
  }
}

/** The peak HQM against speed: gaps where there is none, those speeds shaded by why, and the
 * HQM = 5 level as a reference line. */
class HqmPlot extends CurvePlot {
  constructor(container) {
    super(container, { label: "Peak handling quality metric against forward speed", xLabel: "forward speed v [m/s]", yLabel: "peak |HQM(jω)|", unit: "", minHeight: 200 });
    this.rows = null;
    this.laneSpeed = null;
  }

  /** `rows`: /api/ridden's hqm; `laneSpeed`: the lane change's speed, marked. */
  show(rows, laneSpeed) {
    this.rows = rows;
    this.laneSpeed = laneSpeed;
    const x = rows.map((r) => r.speed);
    this.update([{ x, y: rows.map((r) => r.peak), colour: COLOURS.hqm, dashed: false, name: "peak of |HQM|", testid: "rd-hqm-curve", width: 2.2 }]);
  }

  extent() {
    const xs = this.rows.map((r) => r.speed);
    const step = xs.length > 1 ? xs[1] - xs[0] : 1;
    const peaks = this.rows.map((r) => r.peak).filter((p) => p !== null && Number.isFinite(p));
    const top = Math.max(GOOD_HQM * 1.3, Math.min(VIEW_TOP, 1.08 * Math.max(0, ...peaks)));
    return { x0: xs[0] - step / 2, x1: xs[xs.length - 1] + step / 2, y0: 0, y1: top };
  }

  /** Runs of consecutive speeds with no peak, each {kind, from, to} in speed (half a step wide
   * beyond the end speeds, so that a single speed shows). */
  gaps() {
    const xs = this.rows.map((r) => r.speed);
    const half = xs.length > 1 ? (xs[1] - xs[0]) / 2 : 0.5;
    const out = [];
    this.rows.forEach((r, i) => {
      const kind = gapKind(r);
      if (!kind) return;
      const last = out[out.length - 1];
      if (last && last.kind === kind && last.end === i - 1) {
        last.end = i;
        last.to = r.speed + half;
      } else out.push({ kind, start: i, end: i, from: r.speed - half, to: r.speed + half });
    });
    return out;
  }

  underlay(root, f) {
    const { X, Y } = f;
    const g = svg("g", { "clip-path": f.clip });
    for (const gap of this.gaps()) {
      const x0 = X(gap.from), x1 = X(gap.to);
      g.append(svg("rect", { x: x0, y: f.top, width: Math.max(1, x1 - x0), height: f.ph, fill: COLOURS[gap.kind], "fill-opacity": 0.7, "data-testid": `rd-hqm-${gap.kind}`, "data-from": gap.from, "data-to": gap.to }));
    }
    // The unstable or refused speeds themselves: a cross at the foot of the plot.
    this.rows.forEach((r) => {
      if (r.peak !== null) return;
      const x = X(r.speed), y = f.top + f.ph - 6;
      g.append(svg("path", { d: `M${(x - 3).toFixed(1)} ${(y - 3).toFixed(1)}L${(x + 3).toFixed(1)} ${(y + 3).toFixed(1)}M${(x - 3).toFixed(1)} ${(y + 3).toFixed(1)}L${(x + 3).toFixed(1)} ${(y - 3).toFixed(1)}`, stroke: "#92400e", "stroke-width": 1.2, fill: "none", "data-testid": "rd-hqm-gap-marker" }));
    });
    // HQM = 5: Hess's boundary of good handling.
    const y5 = Y(GOOD_HQM);
    g.append(svg("line", { x1: f.left, x2: f.left + f.pw, y1: y5, y2: y5, stroke: COLOURS.good, "stroke-width": 1.4, "stroke-dasharray": "7 4", "data-testid": "rd-hqm-level" }));
    const halo = { stroke: "#ffffff", "stroke-width": 3, "paint-order": "stroke" };
    g.append(svg("text", { x: f.left + f.pw - 6, y: y5 - 5, "text-anchor": "end", fill: COLOURS.good, "font-size": 11, ...halo, "data-testid": "rd-hqm-level-label" }, "HQM = 5: below, good handling (Hess)"));
    // Peaks above the view.
    const highest = Math.max(-Infinity, ...this.rows.map((r) => r.peak).filter((p) => p !== null && Number.isFinite(p)));
    if (highest > f.y1) g.append(svg("text", { x: f.left + f.pw - 6, y: f.top + 26, "text-anchor": "end", fill: "#92400e", "font-size": 10.5, ...halo, "data-testid": "rd-hqm-above" }, `↑ peaks up to ${num(highest, 3)} above the view (Fit y)`));
    // The lane change's speed.
    if (this.laneSpeed !== null && this.laneSpeed >= f.x0 && this.laneSpeed <= f.x1) {
      const x = X(this.laneSpeed);
      g.append(svg("line", { x1: x, x2: x, y1: f.top, y2: f.top + f.ph, stroke: COLOURS.linear, "stroke-width": 1, "stroke-dasharray": "2 3" }));
      g.append(svg("text", { x: x + 4, y: f.top + 12, fill: COLOURS.linear, "font-size": 10.5, ...halo }, "lane change"));
    }
    root.append(g);
  }

  legendItems() {
    const kinds = new Set(this.gaps().map((g) => g.kind));
    const swatch = (fill) => (x, y) => svg("rect", { x, y: y - 5, width: 18, height: 10, fill, "fill-opacity": 0.7, stroke: "#92400e", "stroke-width": 0.6 });
    const items = [];
    if (kinds.has("unstable")) items.push({ draw: swatch(COLOURS.unstable), text: UNSTABLE_TEXT });
    if (kinds.has("refused")) items.push({ draw: swatch(COLOURS.refused), text: REFUSED_TEXT });
    return items;
  }

  readAt(h, f) {
    const xs = this.rows.map((r) => r.speed);
    const i = h.key !== undefined ? nearest(xs, h.key) : nearest(xs, this.toData(h).x);
    if (h.key === undefined) this.hover.index = i;
    const r = this.rows[i];
    const rows = [html("div", { class: "tt-v", text: `v = ${num(r.speed)} m/s` })];
    const dots = [];
    if (r.peak !== null) {
      const words = r.peak < GOOD_HQM ? "good handling" : r.peak > 8 ? "poor handling" : "between good and poor";
      rows.push(html("div", { class: "tt-row" }, html("span", { class: "tt-dot", style: `background:${COLOURS.hqm}` }), html("span", { class: "tt-mode", text: "peak HQM" }), html("span", { class: "tt-val", text: num(r.peak) })));
      rows.push(html("div", { class: "tt-name", text: `at ω = ${num(r.frequency)} rad/s; ${words}` }));
      dots.push({ x: f.X(r.speed), y: f.Y(r.peak), colour: COLOURS.hqm });
    } else {
      rows.push(html("div", { class: "tt-name", text: `no peak: ${r.reason ?? (r.stable ? REFUSED_TEXT : UNSTABLE_TEXT)}` }));
    }
    return { rows, dots, x: f.X(r.speed) };
  }
}

export class RiddenPanel {
  /** `bike()`: the bicycle edited; `label()`: its name; `onChange()`: the link must be rewritten. */
  constructor({ bike, label, onChange }) {
    this.bike = bike;
    this.label = label;
    this.onChange = onChange ?? (() => {});
    this.sequence = 0;
    this.answer = null;
    this.fresh = false; // the answer is of the bicycle and the form shown now
    this.lanePlot = new LanePlot($("rd-lane-plot"));
    this.hqmPlot = new HqmPlot($("rd-hqm-plot"));
    $("rd-form").addEventListener("submit", (e) => {
      e.preventDefault();
      this.edited();
    });
    $("rd-lane").addEventListener("change", () => this.edited());
    $("rd-csv-lane").addEventListener("click", () => this.downloadLane());
    $("rd-csv-hqm").addEventListener("click", () => this.downloadHqm());
  }

  edited() {
    this.compute();
    this.onChange();
  }

  /** The state the link carries. */
  inputs() {
    return { v: $("rd-speed").value.trim(), lane: $("rd-lane").value, from: $("rd-from").value.trim(), to: $("rd-to").value.trim(), step: $("rd-step").value.trim() };
  }

  /** Restores what `inputs()` gave; what is missing keeps its default. */
  setInputs(s) {
    const fields = { v: "rd-speed", from: "rd-from", to: "rd-to", step: "rd-step" };
    for (const [k, id] of Object.entries(fields)) $(id).value = s[k] ?? DEFAULTS[k];
    $("rd-lane").value = s.lane === "single" ? "single" : "double";
  }

  /** The bicycle changed: the answer shown is of another one until computed again. */
  invalidate() {
    this.fresh = false;
  }

  say(text) {
    $("rd-message").textContent = text ?? "";
    $("rd-message").hidden = !text;
  }

  /** Marks the fields of `ids` invalid (and only them). */
  mark(ids) {
    for (const e of document.querySelectorAll("#rd-form input[type=text]")) {
      const bad = ids.includes(e.id);
      e.classList.toggle("invalid", bad);
      e.setAttribute("aria-invalid", String(bad));
    }
  }

  /** The request from the form; null (the message said, the fields marked, the old result
   * veiled) when it is not valid. */
  request() {
    const refuse = (text, ids) => {
      this.mark(ids);
      this.say(text);
      this.veil("not recomputed: see the message above");
      return null;
    };
    const speed = parseNumber($("rd-speed").value, "speed");
    if (speed === null) return refuse(`The lane change's speed must be a number of m/s (got “${$("rd-speed").value.trim()}”).`, ["rd-speed"]);
    if (!(speed >= MIN_SPEED && speed <= MAX_SPEED)) return refuse(`The lane change's speed must lie from ${MIN_SPEED} to ${MAX_SPEED} m/s (got ${num(speed)} m/s).`, ["rd-speed"]);
    const grid = {};
    for (const [k, id, what] of [["start", "rd-from", "from"], ["stop", "rd-to", "to"], ["step", "rd-step", "step"]]) {
      grid[k] = parseNumber($(id).value, "speed");
      if (grid[k] === null) return refuse(`The HQM speeds' “${what}” must be a number of m/s (got “${$(id).value.trim()}”).`, [id]);
    }
    if (!(grid.step > 0)) return refuse("The HQM speeds' step must be positive.", ["rd-step"]);
    if (!(grid.stop >= grid.start)) return refuse("The HQM speeds must run upwards: “to” at least “from”.", ["rd-from", "rd-to"]);
    const count = Math.floor((grid.stop - grid.start) / grid.step + 1e-9) + 1;
    if (count > MAX_HQM_SPEEDS) return refuse(`The HQM speeds from ${num(grid.start)} to ${num(grid.stop)} m/s in steps of ${num(grid.step)} are ${count} speeds, more than ${MAX_HQM_SPEEDS}: use a larger step.`, ["rd-step"]);
    return { bike: this.bike(), speed, lane: $("rd-lane").value, speeds: grid };
  }

  async compute() {
    const body = this.request();
    if (!body) return;
    this.mark([]);
    const mine = ++this.sequence;
    $("rd-meta").textContent = `riding the ${body.lane} lane change at ${num(body.speed)} m/s…`;
    try {
      const answer = await api.ridden(body);
      if (mine !== this.sequence) return;
      this.say(null);
      this.answer = answer;
      this.fresh = true;
      this.render();
    } catch (e) {
      if (mine !== this.sequence) return;
      const fields = { speed: ["rd-speed"], speeds: ["rd-from", "rd-to", "rd-step"], lane: [] }[e.field] ?? [];
      this.mark(fields);
      this.say(e.message);
      $("rd-meta").textContent = "";
      this.veil("not recomputed: see the message above");
    }
  }

  render() {
    const a = this.answer;
    const l = a.linear;
    const series = [
      { x: l.front_x, y: l.road, colour: COLOURS.road, dashed: false, width: 5, name: "road", testid: "rd-road" },
      { x: l.front_x, y: l.front_y, colour: COLOURS.linear, dashed: false, name: "front contact, linear", testid: "rd-linear" },
    ];
    if (a.nonlinear) series.push({ x: a.nonlinear.front_x, y: a.nonlinear.front_y, colour: COLOURS.nonlinear, dashed: true, name: "front contact, non-linear", testid: "rd-nonlinear" });
    this.lanePlot.update(series);
    $("rd-nonlinear-note").hidden = Boolean(a.nonlinear);
    $("rd-nonlinear-note").textContent = a.nonlinear ? "" : `The non-linear bicycle's run: ${a.nonlinear_error ?? "not completed"}. Only the linear model is drawn.`;
    // The linear run is exact: a front contact far off the road is a closed loop that diverges.
    const { lo, hi } = this.lanePlot.road();
    const deviation = largestDeviation(l);
    const diverged = deviation > 5 * Math.max(hi - lo, 1);
    $("rd-linear-note").hidden = !diverged;
    $("rd-linear-note").textContent = diverged ? `The linear bicycle leaves the road (its front contact ${num(deviation, 3)} m off it): with these gains the rider's closed loop is unstable at ${num(a.speed)} m/s.` : "";
    this.hqmPlot.show(a.hqm, a.speed);
    this.renderSummary();
    $("rd-meta").textContent = `${this.label()}: the ${a.lane} lane change at ${num(a.speed)} m/s; the peak HQM at ${a.hqm.length} speeds`;
    this.veil(null);
  }

  /** One line: the gains, the deviations from the road, the peak HQM at the lane change's speed. */
  renderSummary() {
    const a = this.answer;
    const gains = a.gains.map((g, k) => html("span", { class: "rd-gain", "data-testid": "rd-gain", "data-name": a.gain_names[k], "data-value": String(g), title: `${a.gain_names[k]} (Hess 2012's rules at ${num(a.speed)} m/s)` },
      ...(SUBSCRIPTS[a.gain_names[k]] ? ["k", html("sub", { text: SUBSCRIPTS[a.gain_names[k]] })] : [a.gain_names[k]]), ` = ${num(g)}`));
    const parts = [html("span", { class: "rd-what", text: `gains at ${num(a.speed)} m/s: ` })];
    gains.forEach((g, k) => parts.push(g, k < gains.length - 1 ? ", " : ""));
    const dl = largestDeviation(a.linear);
    const dn = a.nonlinear ? largestDeviation(a.nonlinear) : null;
    parts.push(html("span", { class: "rd-sep", text: " · " }), html("span", { "data-testid": "rd-deviation", "data-linear": String(dl), "data-nonlinear": dn === null ? "" : String(dn) },
      `largest deviation from the road: linear ${num(dl, 3)} m, non-linear ${dn === null ? "– (not completed)" : `${num(dn, 3)} m`}`));
    const row = a.hqm.find((r) => Math.abs(r.speed - a.speed) < 1e-9);
    let hqmText;
    if (!row) hqmText = `peak HQM at ${num(a.speed)} m/s: not in the sweep`;
    else if (row.peak === null) hqmText = `peak HQM at ${num(a.speed)} m/s: none (${row.reason ?? UNSTABLE_TEXT})`;
    else hqmText = `peak HQM at ${num(a.speed)} m/s: ${num(row.peak, 3)}${row.peak < GOOD_HQM ? " (below 5: good handling)" : row.peak > 8 ? " (above 8: poor handling)" : ""}`;
    parts.push(html("span", { class: "rd-sep", text: " · " }), html("span", { "data-testid": "rd-hqm-at", "data-peak": row?.peak === null || !row ? "" : String(row.peak) }, hqmText));
    $("rd-summary").replaceChildren(...parts);
    $("rd-summary").dataset.points = String(a.hqm.length);
  }

  /** Veils what is shown (`reason`), or unveils it (null). */
  veil(reason) {
    $("rd-summary").classList.toggle("stale", Boolean(reason));
    $("rd-summary").dataset.stale = reason ?? "";
    for (const p of [this.lanePlot, this.hqmPlot]) {
      if (!p.ready()) continue;
      p.stale = reason;
      p.draw();
    }
  }

  fileName(what) {
    const a = this.answer;
    return `${slug(a.name ?? this.label())}-${what}`;
  }

  /** The lane change's samples: both models side by side (the non-linear columns empty when it
   * did not complete). */
  downloadLane() {
    const a = this.answer;
    if (!a) return;
    const l = a.linear, n = a.nonlinear;
    const lines = [
      `# whipple: ${a.name ?? this.label()} ridden by Hess's controller (gains by Hess 2012's rules: ${a.gain_names.map((k, i) => `${k} ${a.gains[i]}`).join(", ")}), HumanControl's ${a.lane} lane change at ${a.speed} m/s${n ? "" : `; non-linear: ${a.nonlinear_error ?? "not completed"}`}`,
      "x_linear,y_linear,road_linear,x_nonlinear,y_nonlinear,road_nonlinear",
    ];
    const rows = Math.max(l.front_x.length, n?.front_x.length ?? 0);
    const cell = (v) => (v === undefined || v === null ? "" : String(v));
    for (let i = 0; i < rows; i++) lines.push([l.front_x[i], l.front_y[i], l.road[i], n?.front_x[i], n?.front_y[i], n?.road[i]].map(cell).join(","));
    download(`${this.fileName(`lane-change-${a.lane}-v${num(a.speed)}`)}.csv`, `${lines.join("\n")}\n`, "text/csv");
  }

  /** The peak HQM at each speed, with the reason where there is none. */
  downloadHqm() {
    const a = this.answer;
    if (!a) return;
    const lines = [`# whipple: ${a.name ?? this.label()}, the certified peak of Hess's handling quality metric against speed, gains by Hess 2012's rules at each speed (below 5: good handling)`, "speed,peak,frequency,stable,reason"];
    const quote = (t) => (t ? `"${t.replace(/"/g, '""')}"` : "");
    for (const r of a.hqm) lines.push([r.speed, r.peak ?? "", r.frequency ?? "", r.stable, quote(r.reason)].join(","));
    download(`${this.fileName("hqm")}.csv`, `${lines.join("\n")}\n`, "text/csv");
  }
}
