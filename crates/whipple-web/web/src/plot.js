// Eigenvalues against forward speed: real parts solid, imaginary parts dashed (positive ones, as
// in Meijaard et al. 2007, Fig. 3), coloured by mode; the self-stable range shaded; critical
// speeds marked; the compared designs each in one colour; values read out under the pointer.
// And the root locus: the same eigenvalues in the complex plane, coloured by speed.

import { svg, html, fixed, num, ramp } from "./format.js";
import { Chart, nearest, visibleRange, legend } from "./chart.js";

export const MODE_COLOURS = { weave: "#2563eb", capsize: "#dc2626", castering: "#7c3aed", unclassified: "#6b7280" };
/** Colours of the compared designs, in order. */
export const COMPARE_COLOURS = ["#475569", "#c2410c", "#047857", "#a21caf", "#0e7490", "#854d0e"];
const STABLE = "#dcfce7";
const INK = "#1f2937";

const modeColour = (mode) => MODE_COLOURS[mode] ?? MODE_COLOURS.unclassified;

/** The rows of a design's eigenvalues at index `i`, a conjugate pair read out once. */
function readDesign(rows, dots, design, i, colourOf, X, Y, imaginary = true) {
  rows.push(html("div", { class: "tt-name", text: design.label }));
  const cols = design.eigen.eigenvalues;
  const seen = new Set();
  const x = X ? X(design.eigen.speeds[i]) : 0;
  cols.forEach((c, k) => {
    const re = c.re[i], im = c.im[i];
    const colour = colourOf(c.mode);
    if (X) dots.push({ x, y: Y(re), colour });
    if (X && imaginary && im > 0) dots.push({ x, y: Y(im), colour, hollow: true });
    if (seen.has(k)) return;
    const partner = cols.findIndex((o, j) => j !== k && !seen.has(j) && im !== 0 && Math.abs(o.re[i] - re) <= 1e-9 * (1 + Math.abs(re)) && Math.abs(o.im[i] + im) <= 1e-9 * (1 + Math.abs(im)));
    if (partner >= 0) seen.add(partner);
    seen.add(k);
    const value = im !== 0 ? `${num(re)} ± ${num(Math.abs(im))}i` : num(re);
    rows.push(html("div", { class: "tt-row" }, html("span", { class: "tt-dot", style: `background:${colour}` }), html("span", { class: "tt-mode", text: c.mode }), html("span", { class: "tt-val", text: value })));
  });
}

/** The same speed on another design's grid, or -1 when it has none within half a step. */
function sameSpeed(design, v) {
  const s = design.eigen.speeds;
  const j = nearest(s, v);
  const half = 0.5 * Math.abs((s[1] ?? s[0]) - s[0]);
  return Math.abs(s[j] - v) <= 1e-9 + half ? j : -1;
}

export class EigenPlot extends Chart {
  /**
   * `stableLabel`: what the shaded ranges are called ("self-stable" for the bicycle alone,
   * "stable" for a closed loop); `faint`: the other designs drawn faintly, for comparison only
   * (their critical speeds not marked); `others`: their name in the legend when faint.
   */
  constructor(container, { label = "Eigenvalues against forward speed", testid = "plot", stableLabel = "self-stable", faint = false } = {}) {
    super(container, { label, xLabel: "forward speed v [m/s]", yLabel: "eigenvalue λ [1/s]", testid });
    this.designs = null;
    this.stableLabel = stableLabel;
    this.faint = faint;
  }

  ready() {
    return Boolean(this.designs?.length);
  }

  /**
   * `designs`: [{label, eigen}] with /api/eigen's answers, the first the design edited.
   * `ylim`: the full view's vertical axis runs from −ylim to ylim. `stale`: a reason the curves
   * do not match the form, drawn over them (null when they do).
   */
  update(designs, { ylim = 10, stale = null, keepView = true } = {}) {
    const speeds = designs[0].eigen.speeds;
    const key = `${speeds[0]}:${speeds[speeds.length - 1]}:${ylim}`;
    if (!keepView || key !== this.viewKey) this.view = null;
    this.viewKey = key;
    this.designs = designs;
    this.ylim = ylim;
    this.stale = stale;
    this.draw();
  }

  extent() {
    const s = this.designs[0].eigen.speeds;
    const x0 = s[0];
    const x1 = s[s.length - 1] > x0 ? s[s.length - 1] : x0 + 1;
    return { x0, x1, y0: -this.ylim, y1: this.ylim };
  }

  fitY(x0, x1) {
    let lo = Infinity, hi = -Infinity;
    for (const d of this.designs) {
      const [i0, i1] = visibleRange(d.eigen.speeds, x0, x1);
      for (const c of d.eigen.eigenvalues) {
        for (let i = i0; i <= i1; i += 1) {
          lo = Math.min(lo, c.re[i]);
          hi = Math.max(hi, c.re[i], c.im[i] > 0 ? c.im[i] : -Infinity);
        }
      }
    }
    return Number.isFinite(lo) && Number.isFinite(hi) ? { y0: lo, y1: hi } : null;
  }

  xs() {
    return this.designs[0].eigen.speeds;
  }

  render(root, f) {
    const { X, Y, left, top, pw, ph } = f;
    const [primary, ...others] = this.designs;
    const crit = primary.eigen.critical;
    const shade = svg("g", { "clip-path": f.clip });
    for (const [a, b] of crit?.stable_speed_ranges ?? []) {
      const xa = Math.max(left, X(a)), xb = Math.min(left + pw, X(b));
      if (xb <= xa) continue;
      shade.append(svg("rect", { x: xa, y: top, width: xb - xa, height: ph, fill: STABLE, "data-testid": "stable-range" }));
      if (xb - xa > 60) shade.append(svg("text", { x: (xa + xb) / 2, y: top + ph - 8, "text-anchor": "middle", fill: "#15803d", "font-size": 11, "font-weight": 600 }, this.stableLabel));
    }
    root.insertBefore(shade, root.children[2]);

    const curves = svg("g", { "clip-path": f.clip, fill: "none", "stroke-linejoin": "round" });
    const trace = (design, colourOf, width, testid) => {
      const { speeds, eigenvalues } = design.eigen;
      const [i0, i1] = visibleRange(speeds, f.x0, f.x1);
      const every = Math.max(1, Math.floor((i1 - i0) / (4 * pw)));
      const indices = [];
      for (let i = i0; i <= i1; i += every) indices.push(i);
      if (indices[indices.length - 1] !== i1) indices.push(i1);
      for (const col of eigenvalues) {
        const colour = colourOf(col.mode);
        let re = "", im = "", open = false;
        for (const i of indices) {
          const x = X(speeds[i]).toFixed(2);
          re += `${re ? "L" : "M"}${x},${Y(col.re[i]).toFixed(2)}`;
          if (col.im[i] > 0) {
            im += `${open ? "L" : "M"}${x},${Y(col.im[i]).toFixed(2)}`;
            open = true;
          } else open = false;
        }
        curves.append(svg("path", { d: re, stroke: colour, "stroke-width": width, "data-testid": testid }));
        if (im) curves.append(svg("path", { d: im, stroke: colour, "stroke-width": width * 0.85, "stroke-dasharray": "6 4" }));
      }
    };
    others.forEach((d, k) => trace(d, this.faint ? modeColour : () => COMPARE_COLOURS[k % COMPARE_COLOURS.length], this.faint ? 1.1 : 1.4, this.faint ? "faint-curve" : "compare-curve"));
    // Faint designs behind, for comparison: light and thin, under the curves that matter.
    if (this.faint) for (const p of curves.children) p.setAttribute("stroke-opacity", "0.3");
    trace(primary, modeColour, 2, "eigen-curve");
    root.append(curves);

    const marks = svg("g", { "font-size": 11 });
    const placed = [];
    const mark = (v, label, colour, row, dash, sigma = null) => {
      if (v === null || v === undefined || v < f.x0 || v > f.x1) return;
      // A measured bicycle's speed with its σ, and the band ±σ shaded about the line.
      const spread = Number.isFinite(sigma) && sigma > 0;
      if (spread) {
        const [a, b] = [X(Math.max(f.x0, v - sigma)), X(Math.min(f.x1, v + sigma))];
        marks.append(svg("rect", { x: a, y: top, width: Math.max(0, b - a), height: ph, fill: colour, "fill-opacity": 0.1, "data-testid": "sigma-band" }));
      }
      marks.append(svg("line", { x1: X(v), y1: top, x2: X(v), y2: top + ph, stroke: colour, "stroke-width": 1.2, "stroke-dasharray": dash }));
      const text = `${label} ${fixed(v, 3)}${spread ? ` ± ${num(sigma, 2)}` : ""}`;
      const w = text.length * 6.2 + 8;
      const tx = X(v) + w + 4 > left + pw ? X(v) - w - 3 : X(v) + 3;
      // Labels that would overlap go one row further in.
      const step = row >= 0 ? 1 : -1;
      while (placed.some((p) => p.row === row && tx < p.x1 + 2 && tx + w > p.x0 - 2)) row += step;
      placed.push({ row, x0: tx, x1: tx + w });
      const ty = row >= 0 ? top + 14 + 17 * row : top + ph - 22 + 17 * (row + 1);
      marks.append(svg("rect", { x: tx, y: ty - 11, width: w, height: 15, rx: 3, fill: "#ffffff", "fill-opacity": 0.9, stroke: colour, "stroke-width": 0.8 }));
      marks.append(svg("text", { x: tx + 4, y: ty, fill: colour }, text));
    };
    others.forEach((d, k) => {
      const c = d.eigen.critical;
      if (!c || this.faint) return;
      const colour = COMPARE_COLOURS[k % COMPARE_COLOURS.length];
      mark(c.weave_speed, "v_w", colour, -1 - k, "4 3", c.weave_speed_sigma);
      mark(c.capsize_speed, "v_c", colour, -1 - k, "4 3", c.capsize_speed_sigma);
    });
    if (crit) {
      mark(crit.double_root_speed, "v_d", "#4b5563", 0, "2 3", crit.double_root_speed_sigma);
      mark(crit.weave_speed, "v_w", MODE_COLOURS.weave, 0, "6 3", crit.weave_speed_sigma);
      mark(crit.capsize_speed, "v_c", MODE_COLOURS.capsize, 0, "6 3", crit.capsize_speed_sigma);
    }
    root.append(marks);

    const seg = (colour, dash, w = 2) => (x, y) => svg("line", { x1: x, y1: y, x2: x + 18, y2: y, stroke: colour, "stroke-width": w, "stroke-dasharray": dash });
    const items = [{ draw: seg(INK), text: "Re λ" }, { draw: seg(INK, "6 4"), text: "Im λ" }];
    for (const mode of [...new Set(primary.eigen.eigenvalues.map((c) => c.mode))]) items.push({ draw: seg(modeColour(mode), null, 3), text: mode });
    items.push({ draw: (x, y) => svg("rect", { x, y: y - 6, width: 18, height: 12, fill: STABLE, stroke: "#86efac" }), text: this.stableLabel });
    others.forEach((d, k) => items.push({ draw: this.faint ? (x, y) => svg("line", { x1: x, y1: y, x2: x + 18, y2: y, stroke: INK, "stroke-width": 1.4, "stroke-opacity": 0.3 }) : seg(COMPARE_COLOURS[k % COMPARE_COLOURS.length], null, 1.6), text: d.label }));
    f.legendBottom = legend(root, items, left, f.legendWidth);
  }

  readAt(h, f) {
    const [primary, ...others] = this.designs;
    const speeds = primary.eigen.speeds;
    const v = h.key ?? this.toData(h).x;
    const i = nearest(speeds, v);
    if (h.key === undefined) this.hover.index = i;
    const rows = [html("div", { class: "tt-v", text: `v = ${num(speeds[i])} m/s` })];
    const dots = [];
    readDesign(rows, dots, primary, i, modeColour, f.X, f.Y);
    others.forEach((d, k) => {
      const j = sameSpeed(d, speeds[i]);
      if (j >= 0) readDesign(rows, dots, d, j, this.faint ? modeColour : () => COMPARE_COLOURS[k % COMPARE_COLOURS.length], f.X, f.Y);
    });
    return { rows, dots, x: f.X(speeds[i]) };
  }
}

/** The root locus: each eigenvalue's path in the complex plane as speed rises, coloured by speed. */
export class LocusPlot extends Chart {
  constructor(container) {
    super(container, { label: "Root locus: eigenvalues in the complex plane, coloured by speed", xLabel: "Re λ [1/s]", yLabel: "Im λ [1/s]", crosshair: false, margin: { left: 56, right: 64, top: 36, bottom: 42 } });
    this.designs = null;
  }

  ready() {
    return Boolean(this.designs?.length);
  }

  update(designs, { ylim = 10, stale = null } = {}) {
    const s = designs[0].eigen.speeds;
    const key = `${s[0]}:${s[s.length - 1]}:${ylim}`;
    if (key !== this.viewKey) this.view = null;
    this.viewKey = key;
    this.designs = designs;
    this.ylim = ylim;
    this.stale = stale;
    this.draw();
  }

  extent() {
    const y = this.ylim;
    return { x0: -1.6 * y, x1: 0.8 * y, y0: -y, y1: y };
  }

  fitY(x0, x1) {
    let lo = Infinity, hi = -Infinity;
    for (const d of this.designs) {
      for (const c of d.eigen.eigenvalues) {
        c.re.forEach((re, i) => {
          if (re >= x0 && re <= x1) {
            lo = Math.min(lo, c.im[i]);
            hi = Math.max(hi, c.im[i]);
          }
        });
      }
    }
    return Number.isFinite(lo) && hi > lo ? { y0: lo, y1: hi } : null;
  }

  xs() {
    return this.designs[0].eigen.speeds;
  }

  render(root, f) {
    const { X, Y, left, top, pw, ph } = f;
    const [primary, ...others] = this.designs;
    const speeds = primary.eigen.speeds;
    const [v0, v1] = [speeds[0], speeds[speeds.length - 1]];
    this.speedRange = [v0, v1];
    const g = svg("g", { "clip-path": f.clip, fill: "none", "stroke-linecap": "round" });
    // The imaginary axis: where modes change stability.
    if (f.x0 < 0 && f.x1 > 0) g.append(svg("line", { x1: X(0), y1: top, x2: X(0), y2: top + ph, stroke: "#9ca3af" }));
    others.forEach((d, k) => {
      for (const c of d.eigen.eigenvalues) {
        let p = "";
        c.re.forEach((re, i) => { p += `${p ? "L" : "M"}${X(re).toFixed(1)},${Y(c.im[i]).toFixed(1)}`; });
        g.append(svg("path", { d: p, stroke: COMPARE_COLOURS[k % COMPARE_COLOURS.length], "stroke-width": 1.2, "stroke-opacity": 0.8 }));
      }
    });
    // Coloured by speed: one path per colour band, so the drawing stays light.
    const bands = 48;
    const every = Math.max(1, Math.floor(speeds.length / 1500));
    for (const c of primary.eigen.eigenvalues) {
      const paths = Array.from({ length: bands }, () => "");
      for (let i = every; i < speeds.length; i += every) {
        const b = Math.min(bands - 1, Math.floor(((speeds[i] - v0) / Math.max(1e-12, v1 - v0)) * bands));
        paths[b] += `M${X(c.re[i - every]).toFixed(1)},${Y(c.im[i - every]).toFixed(1)}L${X(c.re[i]).toFixed(1)},${Y(c.im[i]).toFixed(1)}`;
      }
      paths.forEach((d, b) => d && g.append(svg("path", { d, stroke: ramp((b + 0.5) / bands), "stroke-width": 2.6, "data-testid": "locus-curve" })));
    }
    root.append(g);
    // Colour bar: speed.
    const bar = svg("g", { "font-size": 10.5, fill: "#4b5563" });
    const bx = left + pw + 14, bw = 12;
    for (let k = 0; k < 32; k += 1) bar.append(svg("rect", { x: bx, y: top + ph - ((k + 1) / 32) * ph, width: bw, height: ph / 32 + 0.5, fill: ramp((k + 0.5) / 32) }));
    bar.append(svg("text", { x: bx + bw / 2, y: top - 6, "text-anchor": "middle" }, "v [m/s]"));
    bar.append(svg("text", { x: bx + bw + 3, y: top + 10 }, num(v1, 3)));
    bar.append(svg("text", { x: bx + bw + 3, y: top + ph }, num(v0, 3)));
    root.append(bar);
    const items = [{ draw: (x, y) => svg("line", { x1: x, y1: y, x2: x + 18, y2: y, stroke: ramp(0.6), "stroke-width": 3 }), text: `${primary.label}: colour is speed` }];
    others.forEach((d, k) => items.push({ draw: (x, y) => svg("line", { x1: x, y1: y, x2: x + 18, y2: y, stroke: COMPARE_COLOURS[k % COMPARE_COLOURS.length], "stroke-width": 1.6 }), text: d.label }));
    f.legendBottom = legend(root, items, left, f.legendWidth);
  }

  readAt(h, f) {
    const [primary, ...others] = this.designs;
    const speeds = primary.eigen.speeds;
    let i = h.index;
    if (h.key === undefined) {
      // The speed whose eigenvalue lies nearest the pointer (in pixels).
      let best = Infinity;
      for (const c of primary.eigen.eigenvalues) {
        c.re.forEach((re, k) => {
          const d = (f.X(re) - h.px) ** 2 + (f.Y(c.im[k]) - h.py) ** 2;
          if (d < best) {
            best = d;
            i = k;
          }
        });
      }
      if (best > 40 ** 2) return null;
      this.hover.index = i;
    }
    const rows = [html("div", { class: "tt-v", text: `v = ${num(speeds[i])} m/s` })];
    const dots = [];
    const colourOf = () => ramp((speeds[i] - speeds[0]) / Math.max(1e-12, speeds[speeds.length - 1] - speeds[0]));
    readDesign(rows, [], primary, i, modeColour, null, null);
    for (const c of primary.eigen.eigenvalues) dots.push({ x: f.X(c.re[i]), y: f.Y(c.im[i]), colour: colourOf(), r: 4.5 });
    others.forEach((d, k) => {
      const j = sameSpeed(d, speeds[i]);
      if (j < 0) return;
      readDesign(rows, [], d, j, () => COMPARE_COLOURS[k % COMPARE_COLOURS.length], null, null);
      for (const c of d.eigen.eigenvalues) dots.push({ x: f.X(c.re[j]), y: f.Y(c.im[j]), colour: COMPARE_COLOURS[k % COMPARE_COLOURS.length], hollow: true });
    });
    return { rows, dots };
  }
}
