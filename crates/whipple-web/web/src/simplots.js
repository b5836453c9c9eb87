// The simulation's SVG plots: lean and steer against time with a cursor at the current frame,
// and the ground track (contact points seen from above) with the current position marked.

import { svg, ticks, tickLabel, FONT } from "./format.js";

const INK = "#1f2937";
const GRID = "#e5e7eb";
export const SIM_COLOURS = { lean: "#2563eb", steer: "#d97706", rear: "#374151", front: "#dc2626" };
const DEG = 180 / Math.PI;

function frameBox(container, minW, minH) {
  return {
    width: Math.max(minW, Math.round(container.clientWidth)),
    height: Math.max(minH, Math.round(container.clientHeight)),
  };
}

function polyline(xs, ys, X, Y) {
  let d = "";
  for (let i = 0; i < xs.length; i += 1) d += `${i ? "L" : "M"}${X(xs[i]).toFixed(1)} ${Y(ys[i]).toFixed(1)}`;
  return d;
}

function axesText(root, x, y, text, attrs = {}) {
  root.append(svg("text", { x, y, fill: "#4b5563", ...attrs }, text));
}

/** Lean and steer [deg] against t [s]; `cursor(i)` moves the current-frame line. */
export class TimePlot {
  constructor(container) {
    this.container = container;
    this.frames = null;
    this.index = 0;
    new ResizeObserver(() => this.frames && this.draw()).observe(container);
  }

  update(result) {
    this.result = result;
    this.frames = result.frames;
    this.draw();
  }

  draw() {
    const { width, height } = frameBox(this.container, 240, 120);
    const m = { left: 44, right: 12, top: 22, bottom: 30 };
    const pw = width - m.left - m.right;
    const ph = height - m.top - m.bottom;
    const t = this.frames.map((f) => f.t);
    const lean = this.frames.map((f) => f.lean * DEG);
    const steer = this.frames.map((f) => f.steer * DEG);
    const tmax = Math.max(this.result.duration, t[t.length - 1] || 0, 1e-3);
    let ymax = Math.max(1, ...lean.map(Math.abs), ...steer.map(Math.abs));
    ymax = Math.min(ymax * 1.08, 180);
    const X = (x) => m.left + (x / tmax) * pw;
    const Y = (y) => m.top + ((ymax - Math.max(-ymax, Math.min(ymax, y))) / (2 * ymax)) * ph;
    const root = svg("svg", { width, height, viewBox: `0 0 ${width} ${height}`, "font-family": FONT, "font-size": 10.5, role: "img", "aria-label": "Lean and steer against time" });
    root.append(svg("rect", { x: 0, y: 0, width, height, fill: "#ffffff" }));
    const tt = ticks(0, tmax, Math.max(3, Math.round(pw / 70)));
    const yt = ticks(-ymax, ymax, Math.max(4, Math.round(ph / 30)));
    const grid = svg("g", { stroke: GRID });
    for (const v of tt) grid.append(svg("line", { x1: X(v), y1: m.top, x2: X(v), y2: m.top + ph }));
    for (const v of yt) grid.append(svg("line", { x1: m.left, y1: Y(v), x2: m.left + pw, y2: Y(v) }));
    root.append(grid);
    root.append(svg("line", { x1: m.left, y1: Y(0), x2: m.left + pw, y2: Y(0), stroke: "#9ca3af" }));
    for (const v of tt) axesText(root, X(v), m.top + ph + 13, tickLabel(v, tt), { "text-anchor": "middle" });
    for (const v of yt) axesText(root, m.left - 5, Y(v) + 3.5, tickLabel(v, yt), { "text-anchor": "end" });
    axesText(root, m.left + pw, height - 4, "t [s]", { "text-anchor": "end", fill: INK });
    axesText(root, 11, m.top + ph / 2, "angle [°]", { "text-anchor": "middle", fill: INK, transform: `rotate(-90 11 ${m.top + ph / 2})` });
    root.append(svg("rect", { x: m.left, y: m.top, width: pw, height: ph, fill: "none", stroke: "#9ca3af" }));
    const curves = svg("g", { fill: "none", "stroke-width": 1.8, "stroke-linejoin": "round" });
    curves.append(svg("path", { d: polyline(t, lean, X, Y), stroke: SIM_COLOURS.lean, "data-testid": "sim-lean-curve" }));
    curves.append(svg("path", { d: polyline(t, steer, X, Y), stroke: SIM_COLOURS.steer }));
    root.append(curves);
    // Legend.
    const legend = svg("g", { "font-size": 11, fill: INK });
    [["lean φ", SIM_COLOURS.lean], ["steer δ", SIM_COLOURS.steer]].forEach(([label, colour], k) => {
      const x = m.left + k * 86;
      legend.append(svg("line", { x1: x, y1: 11, x2: x + 18, y2: 11, stroke: colour, "stroke-width": 2.5 }));
      legend.append(svg("text", { x: x + 23, y: 15 }, label));
    });
    root.append(legend);
    // The current frame.
    this.cursorLine = svg("line", { y1: m.top, y2: m.top + ph, stroke: INK, "stroke-width": 1, "stroke-dasharray": "3 2", "data-testid": "sim-cursor" });
    this.leanDot = svg("circle", { r: 3.5, fill: SIM_COLOURS.lean });
    this.steerDot = svg("circle", { r: 3.5, fill: SIM_COLOURS.steer });
    root.append(this.cursorLine, this.leanDot, this.steerDot);
    this.X = X;
    this.Y = Y;
    this.container.replaceChildren(root);
    this.cursor(this.index);
  }

  cursor(i) {
    this.index = i;
    const f = this.frames?.[i];
    if (!f || !this.cursorLine) return;
    const x = this.X(f.t).toFixed(1);
    this.cursorLine.setAttribute("x1", x);
    this.cursorLine.setAttribute("x2", x);
    this.leanDot.setAttribute("cx", x);
    this.leanDot.setAttribute("cy", this.Y(f.lean * DEG).toFixed(1));
    this.steerDot.setAttribute("cx", x);
    this.steerDot.setAttribute("cy", this.Y(f.steer * DEG).toFixed(1));
  }
}

/** The contact points' paths seen from above (x forward to the right, y right downwards). */
export class TrackPlot {
  constructor(container) {
    this.container = container;
    this.frames = null;
    this.index = 0;
    new ResizeObserver(() => this.frames && this.draw()).observe(container);
  }

  update(result) {
    this.frames = result.frames;
    this.draw();
  }

  draw() {
    const { width, height } = frameBox(this.container, 240, 100);
    const m = { left: 44, right: 12, top: 22, bottom: 30 };
    const pw = width - m.left - m.right;
    const ph = height - m.top - m.bottom;
    const xs = this.frames.flatMap((f) => [f.rear_contact[0], f.front_contact[0]]);
    const ys = this.frames.flatMap((f) => [f.rear_contact[1], f.front_contact[1]]);
    let [x0, x1] = [Math.min(...xs), Math.max(...xs)];
    let [y0, y1] = [Math.min(...ys), Math.max(...ys)];
    // Equal scales on both axes, the track centred; a nearly straight track has its sideways
    // excursions stretched (up to 20x), which the plot says.
    const scale = Math.min(pw / Math.max(x1 - x0, 0.5), ph / Math.max(y1 - y0, 0.5)) * 0.94;
    let yScale = scale;
    if ((y1 - y0) * scale < 0.4 * ph) yScale = Math.min(20 * scale, (0.7 * ph) / Math.max(y1 - y0, 1e-3));
    const stretch = yScale / scale;
    const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    x0 = cx - pw / 2 / scale; x1 = cx + pw / 2 / scale;
    y0 = cy - ph / 2 / yScale; y1 = cy + ph / 2 / yScale;
    const X = (x) => m.left + (x - x0) * scale;
    const Y = (y) => m.top + (y - y0) * yScale;
    const root = svg("svg", { width, height, viewBox: `0 0 ${width} ${height}`, "font-family": FONT, "font-size": 10.5, role: "img", "aria-label": "Ground track" });
    root.append(svg("rect", { x: 0, y: 0, width, height, fill: "#ffffff" }));
    const clipId = `clip-track-${Math.random().toString(36).slice(2, 8)}`;
    root.append(svg("defs", {}, svg("clipPath", { id: clipId }, svg("rect", { x: m.left, y: m.top, width: pw, height: ph }))));
    const xt = ticks(x0, x1, Math.max(3, Math.round(pw / 70)));
    const yt = ticks(y0, y1, Math.max(3, Math.round(ph / 30)));
    const grid = svg("g", { stroke: GRID });
    for (const v of xt) grid.append(svg("line", { x1: X(v), y1: m.top, x2: X(v), y2: m.top + ph }));
    for (const v of yt) grid.append(svg("line", { x1: m.left, y1: Y(v), x2: m.left + pw, y2: Y(v) }));
    root.append(grid);
    for (const v of xt) axesText(root, X(v), m.top + ph + 13, tickLabel(v, xt), { "text-anchor": "middle" });
    for (const v of yt) axesText(root, m.left - 5, Y(v) + 3.5, tickLabel(v, yt), { "text-anchor": "end" });
    axesText(root, m.left + pw, height - 4, "x [m] (forward)", { "text-anchor": "end", fill: INK });
    if (stretch > 1.05) axesText(root, m.left + pw - 4, m.top + 13, `sideways ×${stretch.toFixed(stretch < 10 ? 1 : 0)}`, { "text-anchor": "end", fill: "#b45309", "data-testid": "sim-track-stretch" });
    axesText(root, 11, m.top + ph / 2, "y [m]", { "text-anchor": "middle", fill: INK, transform: `rotate(-90 11 ${m.top + ph / 2})` });
    root.append(svg("rect", { x: m.left, y: m.top, width: pw, height: ph, fill: "none", stroke: "#9ca3af" }));
    const paths = svg("g", { fill: "none", "stroke-width": 1.6, "clip-path": `url(#${clipId})` });
    const rx = this.frames.map((f) => f.rear_contact[0]), ry = this.frames.map((f) => f.rear_contact[1]);
    const fx = this.frames.map((f) => f.front_contact[0]), fy = this.frames.map((f) => f.front_contact[1]);
    paths.append(svg("path", { d: polyline(rx, ry, X, Y), stroke: SIM_COLOURS.rear }));
    paths.append(svg("path", { d: polyline(fx, fy, X, Y), stroke: SIM_COLOURS.front, "stroke-dasharray": "5 3" }));
    root.append(paths);
    const legend = svg("g", { "font-size": 11, fill: INK });
    [["rear contact", SIM_COLOURS.rear, null], ["front contact", SIM_COLOURS.front, "5 3"]].forEach(([label, colour, dash], k) => {
      const x = m.left + k * 112;
      legend.append(svg("line", { x1: x, y1: 11, x2: x + 18, y2: 11, stroke: colour, "stroke-width": 2, "stroke-dasharray": dash }));
      legend.append(svg("text", { x: x + 23, y: 15 }, label));
    });
    root.append(legend);
    this.bikeLine = svg("line", { stroke: INK, "stroke-width": 2.5, "stroke-linecap": "round" });
    this.rearDot = svg("circle", { r: 4, fill: SIM_COLOURS.rear, "data-testid": "sim-track-marker" });
    this.frontDot = svg("circle", { r: 4, fill: SIM_COLOURS.front });
    root.append(this.bikeLine, this.rearDot, this.frontDot);
    this.X = X;
    this.Y = Y;
    this.container.replaceChildren(root);
    this.cursor(this.index);
  }

  cursor(i) {
    this.index = i;
    const f = this.frames?.[i];
    if (!f || !this.rearDot) return;
    const [ax, ay, bx, by] = [this.X(f.rear_contact[0]), this.Y(f.rear_contact[1]), this.X(f.front_contact[0]), this.Y(f.front_contact[1])].map((v) => v.toFixed(1));
    this.rearDot.setAttribute("cx", ax);
    this.rearDot.setAttribute("cy", ay);
    this.frontDot.setAttribute("cx", bx);
    this.frontDot.setAttribute("cy", by);
    for (const [k, v] of [["x1", ax], ["y1", ay], ["x2", bx], ["y2", by]]) this.bikeLine.setAttribute(k, v);
  }
}
