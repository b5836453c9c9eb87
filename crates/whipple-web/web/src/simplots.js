// The simulation's plots: lean and steer against time (several runs overlaid, the linear model's
// prediction from the same initial state dashed, a cursor at the current frame), and the
// ground track (contact points seen from above) with the current position marked.

import { svg, html, num } from "./format.js";
import { Chart, nearest, legend } from "./chart.js";

const INK = "#1f2937";
export const SIM_COLOURS = { lean: "#2563eb", steer: "#d97706", rider: "#7c3aed", rear: "#374151", front: "#dc2626" };
/** Earlier runs kept for comparison, faint, one colour pair each. */
const OVERLAY = [["#93c5fd", "#fcd34d"], ["#a5b4fc", "#fdba74"], ["#99f6e4", "#fca5a5"], ["#c4b5fd", "#fde68a"]];
const DEG = 180 / Math.PI;

function path(xs, ys, X, Y, every = 1) {
  let d = "";
  for (let i = 0; i < xs.length; i += every) d += `${d ? "L" : "M"}${X(xs[i]).toFixed(1)} ${Y(ys[i]).toFixed(1)}`;
  if (xs.length && (xs.length - 1) % every) d += `L${X(xs[xs.length - 1]).toFixed(1)} ${Y(ys[ys.length - 1]).toFixed(1)}`;
  return d;
}

/** Lean and steer [deg] against t [s]; `cursor(i)` moves the current-frame line. */
export class TimePlot extends Chart {
  constructor(container) {
    super(container, { label: "Lean and steer against time", xLabel: "t [s]", yLabel: "angle [°]", margin: { left: 46, right: 12, top: 36, bottom: 36 }, minWidth: 240, minHeight: 140, fontSize: 10.5 });
    this.runs = null;
    this.index = 0;
  }

  ready() {
    return Boolean(this.runs?.length);
  }

  /** `runs`: [{label, result, linear}] newest first; the first is the one animated. */
  update(runs) {
    this.runs = runs;
    this.view = null;
    this.draw();
  }

  /** The time axis ends where the runs shown end (a fall ends the run early). */
  extent() {
    const end = Math.max(...this.runs.map((r) => r.result.frames[r.result.frames.length - 1].t), 1e-3);
    let y = 1;
    for (const r of this.runs) for (const f of r.result.frames) y = Math.max(y, Math.abs(f.lean * DEG), Math.abs(f.steer * DEG), Math.abs((f.rider_lean ?? 0) * DEG));
    y = Math.min(y * 1.08, 180);
    return { x0: 0, x1: end, y0: -y, y1: y };
  }

  fitY(x0, x1) {
    let lo = Infinity, hi = -Infinity;
    for (const r of this.runs) {
      for (const f of r.result.frames) {
        if (f.t < x0 || f.t > x1) continue;
        const r = (f.rider_lean ?? 0) * DEG;
        lo = Math.min(lo, f.lean * DEG, f.steer * DEG, r);
        hi = Math.max(hi, f.lean * DEG, f.steer * DEG, r);
      }
    }
    return hi > lo ? { y0: lo, y1: hi } : null;
  }

  xs() {
    return this.runs[0].result.frames.map((f) => f.t);
  }

  render(root, f) {
    const { X, Y } = f;
    const curves = svg("g", { "clip-path": f.clip, fill: "none", "stroke-linejoin": "round" });
    this.runs.slice(1).forEach((r, k) => {
      const [lc, sc] = OVERLAY[k % OVERLAY.length];
      const t = r.result.frames.map((fr) => fr.t);
      curves.append(svg("path", { d: path(t, r.result.frames.map((fr) => fr.lean * DEG), X, Y), stroke: lc, "stroke-width": 1.4, "data-testid": "sim-overlay-curve" }));
      curves.append(svg("path", { d: path(t, r.result.frames.map((fr) => fr.steer * DEG), X, Y), stroke: sc, "stroke-width": 1.4 }));
    });
    const run = this.runs[0];
    if (run.linear) {
      const l = run.linear;
      curves.append(svg("path", { d: path(l.t, l.lean.map((x) => x * DEG), X, Y), stroke: SIM_COLOURS.lean, "stroke-width": 1.2, "stroke-dasharray": "5 3", "data-testid": "sim-linear-curve" }));
      curves.append(svg("path", { d: path(l.t, l.steer.map((x) => x * DEG), X, Y), stroke: SIM_COLOURS.steer, "stroke-width": 1.2, "stroke-dasharray": "5 3" }));
    }
    const t = run.result.frames.map((fr) => fr.t);
    curves.append(svg("path", { d: path(t, run.result.frames.map((fr) => fr.lean * DEG), X, Y), stroke: SIM_COLOURS.lean, "stroke-width": 1.8, "data-testid": "sim-lean-curve" }));
    curves.append(svg("path", { d: path(t, run.result.frames.map((fr) => fr.steer * DEG), X, Y), stroke: SIM_COLOURS.steer, "stroke-width": 1.8 }));
    const leaning = run.result.frames[0].rider_lean !== undefined;
    if (leaning) curves.append(svg("path", { d: path(t, run.result.frames.map((fr) => fr.rider_lean * DEG), X, Y), stroke: SIM_COLOURS.rider, "stroke-width": 1.8, "data-testid": "sim-rider-curve" }));
    root.append(curves);
    const seg = (colour, dash, w = 2.5) => (x, y) => svg("line", { x1: x, y1: y, x2: x + 18, y2: y, stroke: colour, "stroke-width": w, "stroke-dasharray": dash });
    const items = [{ draw: seg(SIM_COLOURS.lean), text: "lean φ" }, { draw: seg(SIM_COLOURS.steer), text: "steer δ" }];
    if (leaning) items.push({ draw: seg(SIM_COLOURS.rider), text: "upper body's lean on the hinge φ_r" });
    if (run.linear) items.push({ draw: seg(INK, "5 3", 1.2), text: "linear model" });
    this.runs.slice(1).forEach((r, k) => items.push({ draw: seg(OVERLAY[k % OVERLAY.length][0]), text: r.label }));
    f.legendBottom = legend(root, items, f.left, f.legendWidth, 10.5);
    this.cursorLine = svg("line", { y1: f.top, y2: f.top + f.ph, stroke: INK, "stroke-width": 1, "stroke-dasharray": "3 2", "data-testid": "sim-cursor" });
    this.leanDot = svg("circle", { r: 3.5, fill: SIM_COLOURS.lean });
    this.steerDot = svg("circle", { r: 3.5, fill: SIM_COLOURS.steer });
    const g = svg("g", { "clip-path": f.clip }, this.cursorLine, this.leanDot, this.steerDot);
    root.append(g);
    this.cursor(this.index);
  }

  readAt(h, f) {
    const run = this.runs[0];
    const times = run.result.frames.map((fr) => fr.t);
    const t = h.key ?? this.toData(h).x;
    const i = nearest(times, t);
    if (h.key === undefined) this.hover.index = i;
    const fr = run.result.frames[i];
    const rows = [html("div", { class: "tt-v", text: `t = ${num(fr.t)} s` })];
    const row = (name, colour, value) => rows.push(html("div", { class: "tt-row" }, html("span", { class: "tt-dot", style: `background:${colour}` }), html("span", { class: "tt-mode", text: name }), html("span", { class: "tt-val", text: value })));
    row("lean φ", SIM_COLOURS.lean, `${num(fr.lean * DEG)}°`);
    row("steer δ", SIM_COLOURS.steer, `${num(fr.steer * DEG)}°`);
    if (fr.rider_lean !== undefined) row("upper body φ_r", SIM_COLOURS.rider, `${num(fr.rider_lean * DEG)}°`);
    const dots = [{ x: f.X(fr.t), y: f.Y(fr.lean * DEG), colour: SIM_COLOURS.lean }, { x: f.X(fr.t), y: f.Y(fr.steer * DEG), colour: SIM_COLOURS.steer }];
    if (run.linear) {
      const j = nearest(run.linear.t, fr.t);
      row("linear φ", SIM_COLOURS.lean, `${num(run.linear.lean[j] * DEG)}°`);
      row("linear δ", SIM_COLOURS.steer, `${num(run.linear.steer[j] * DEG)}°`);
    }
    this.runs.slice(1).forEach((r, k) => {
      const ts = r.result.frames.map((x) => x.t);
      const j = nearest(ts, fr.t);
      if (Math.abs(ts[j] - fr.t) > 0.05) return;
      rows.push(html("div", { class: "tt-name", text: r.label }));
      row("lean φ", OVERLAY[k % OVERLAY.length][0], `${num(r.result.frames[j].lean * DEG)}°`);
      row("steer δ", OVERLAY[k % OVERLAY.length][1], `${num(r.result.frames[j].steer * DEG)}°`);
    });
    return { rows, dots, x: f.X(fr.t) };
  }

  cursor(i) {
    this.index = i;
    const fr = this.runs?.[0]?.result.frames[i];
    if (!fr || !this.cursorLine || !this.frame) return;
    const x = this.frame.X(fr.t).toFixed(1);
    this.cursorLine.setAttribute("x1", x);
    this.cursorLine.setAttribute("x2", x);
    this.leanDot.setAttribute("cx", x);
    this.leanDot.setAttribute("cy", this.frame.Y(fr.lean * DEG).toFixed(1));
    this.steerDot.setAttribute("cx", x);
    this.steerDot.setAttribute("cy", this.frame.Y(fr.steer * DEG).toFixed(1));
  }
}

/** The contact points' paths seen from above (x forward to the right, y right downwards). */
export class TrackPlot extends Chart {
  constructor(container) {
    super(container, { label: "Ground track seen from above", xLabel: "x [m] (forward)", yLabel: "y [m] (right)", margin: { left: 46, right: 12, top: 36, bottom: 36 }, minWidth: 240, minHeight: 120, fontSize: 10.5, crosshair: false, flipY: true });
    this.frames = null;
    this.index = 0;
  }

  ready() {
    return Boolean(this.frames?.length);
  }

  update(result) {
    this.frames = result.frames;
    this.view = null;
    this.draw();
  }

  /** Equal scales, the track centred; a nearly straight track has its sideways excursions
   * stretched (up to 20x), which the plot says. */
  extent() {
    const m = this.margin;
    const pw = Math.max(20, Math.max(this.minWidth, this.container.clientWidth) - m.left - m.right);
    const ph = Math.max(20, Math.max(this.minHeight, this.container.clientHeight) - m.top - m.bottom);
    const xs = this.frames.flatMap((f) => [f.rear_contact[0], f.front_contact[0]]);
    const ys = this.frames.flatMap((f) => [f.rear_contact[1], f.front_contact[1]]);
    const [x0, x1] = [Math.min(...xs), Math.max(...xs)];
    const [y0, y1] = [Math.min(...ys), Math.max(...ys)];
    const scale = Math.min(pw / Math.max(x1 - x0, 0.5), ph / Math.max(y1 - y0, 0.5)) * 0.94;
    let yScale = scale;
    if ((y1 - y0) * scale < 0.4 * ph) yScale = Math.min(20 * scale, (0.7 * ph) / Math.max(y1 - y0, 1e-3));
    const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    return { x0: cx - pw / 2 / scale, x1: cx + pw / 2 / scale, y0: cy - ph / 2 / yScale, y1: cy + ph / 2 / yScale };
  }

  fitY(x0, x1) {
    const ys = this.frames.filter((f) => f.rear_contact[0] >= x0 && f.rear_contact[0] <= x1).flatMap((f) => [f.rear_contact[1], f.front_contact[1]]);
    return ys.length ? { y0: Math.min(...ys), y1: Math.max(...ys) } : null;
  }

  xs() {
    return this.frames.map((f) => f.rear_contact[0]);
  }

  render(root, f) {
    const { X, Y } = f;
    const stretch = (f.ph / (f.y1 - f.y0)) / (f.pw / (f.x1 - f.x0));
    if (stretch > 1.05) root.append(svg("text", { x: f.left + f.pw - 4, y: f.top + 13, "text-anchor": "end", fill: "#92400e", "data-testid": "sim-track-stretch" }, `sideways ×${num(stretch, 2)}`));
    const paths = svg("g", { fill: "none", "stroke-width": 1.6, "clip-path": f.clip });
    const rx = this.frames.map((fr) => fr.rear_contact[0]), ry = this.frames.map((fr) => fr.rear_contact[1]);
    const fx = this.frames.map((fr) => fr.front_contact[0]), fy = this.frames.map((fr) => fr.front_contact[1]);
    paths.append(svg("path", { d: path(rx, ry, X, Y), stroke: SIM_COLOURS.rear }));
    paths.append(svg("path", { d: path(fx, fy, X, Y), stroke: SIM_COLOURS.front, "stroke-dasharray": "5 3" }));
    root.append(paths);
    const seg = (colour, dash) => (x, y) => svg("line", { x1: x, y1: y, x2: x + 18, y2: y, stroke: colour, "stroke-width": 2, "stroke-dasharray": dash });
    f.legendBottom = legend(root, [{ draw: seg(SIM_COLOURS.rear), text: "rear contact" }, { draw: seg(SIM_COLOURS.front, "5 3"), text: "front contact" }], f.left, f.legendWidth, 10.5);
    this.bikeLine = svg("line", { stroke: INK, "stroke-width": 2.5, "stroke-linecap": "round" });
    this.rearDot = svg("circle", { r: 4, fill: SIM_COLOURS.rear, "data-testid": "sim-track-marker" });
    this.frontDot = svg("circle", { r: 4, fill: SIM_COLOURS.front });
    root.append(svg("g", { "clip-path": f.clip }, this.bikeLine, this.rearDot, this.frontDot));
    this.cursor(this.index);
  }

  readAt(h, f) {
    let i = h.index;
    if (h.key === undefined) {
      let best = Infinity;
      this.frames.forEach((fr, k) => {
        const d = (f.X(fr.rear_contact[0]) - h.px) ** 2 + (f.Y(fr.rear_contact[1]) - h.py) ** 2;
        if (d < best) {
          best = d;
          i = k;
        }
      });
      if (best > 30 ** 2) return null;
      this.hover.index = i;
    }
    const fr = this.frames[i];
    const rows = [
      html("div", { class: "tt-v", text: `t = ${num(fr.t)} s` }),
      html("div", { class: "tt-row" }, html("span", { class: "tt-dot", style: `background:${SIM_COLOURS.rear}` }), html("span", { class: "tt-mode", text: "rear" }), html("span", { class: "tt-val", text: `${num(fr.rear_contact[0])}, ${num(fr.rear_contact[1])} m` })),
      html("div", { class: "tt-row" }, html("span", { class: "tt-dot", style: `background:${SIM_COLOURS.front}` }), html("span", { class: "tt-mode", text: "front" }), html("span", { class: "tt-val", text: `${num(fr.front_contact[0])}, ${num(fr.front_contact[1])} m` })),
    ];
    return { rows, dots: [{ x: f.X(fr.rear_contact[0]), y: f.Y(fr.rear_contact[1]), colour: SIM_COLOURS.rear, r: 5 }], x: f.X(fr.rear_contact[0]) };
  }

  cursor(i) {
    this.index = i;
    const fr = this.frames?.[i];
    if (!fr || !this.rearDot || !this.frame) return;
    const { X, Y } = this.frame;
    const [ax, ay, bx, by] = [X(fr.rear_contact[0]), Y(fr.rear_contact[1]), X(fr.front_contact[0]), Y(fr.front_contact[1])].map((v) => v.toFixed(1));
    this.rearDot.setAttribute("cx", ax);
    this.rearDot.setAttribute("cy", ay);
    this.frontDot.setAttribute("cx", bx);
    this.frontDot.setAttribute("cy", by);
    for (const [k, v] of [["x1", ax], ["y1", ay], ["x2", bx], ["y2", by]]) this.bikeLine.setAttribute(k, v);
  }
}
