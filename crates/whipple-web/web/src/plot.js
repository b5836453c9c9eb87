// Eigenvalues against forward speed, drawn as SVG: real parts solid, imaginary parts dashed
// (positive ones, as in Meijaard et al. 2007, Fig. 3), coloured by mode; the self-stable range
// shaded; critical speeds marked; values read out under the pointer; a second design in grey.

import { svg, html, fixed, sig, ticks, tickLabel, FONT } from "./format.js";

export const MODE_COLOURS = { weave: "#2563eb", capsize: "#dc2626", castering: "#7c3aed", unclassified: "#6b7280" };
const COMPARE = "#64748b";
const STABLE = "#dcfce7";
const INK = "#1f2937";
const GRID = "#e5e7eb";

/** Index of the speed nearest `v` in the sorted `speeds`. */
function nearest(speeds, v) {
  let lo = 0, hi = speeds.length - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (speeds[mid] < v) lo = mid; else hi = mid;
  }
  return Math.abs(speeds[lo] - v) <= Math.abs(speeds[hi] - v) ? lo : hi;
}

export class EigenPlot {
  constructor(container) {
    this.container = container;
    this.data = null;
    this.svgEl = null;
    this.tooltip = html("div", { class: "tooltip", hidden: true, "data-testid": "plot-tooltip" });
    this.holder = html("div", { class: "plot-holder" });
    container.replaceChildren(this.holder, this.tooltip);
    let pending = 0;
    new ResizeObserver(() => {
      cancelAnimationFrame(pending);
      pending = requestAnimationFrame(() => this.data && this.draw());
    }).observe(container);
  }

  /**
   * `primary` and `secondary`: {label, eigen} where `eigen` is /api/eigen's answer (secondary
   * may be null). `ylim`: the vertical axis runs from −ylim to ylim.
   */
  update(primary, secondary, { ylim = 10, stale = false } = {}) {
    this.data = { primary, secondary, ylim, stale };
    this.draw();
  }

  draw() {
    const { primary, secondary, ylim, stale } = this.data;
    const width = Math.max(360, Math.round(this.container.clientWidth));
    const height = Math.max(240, Math.round(this.container.clientHeight));
    const m = { left: 56, right: 18, top: 40, bottom: 44 };
    const pw = width - m.left - m.right;
    const ph = height - m.top - m.bottom;
    const speeds = primary.eigen.speeds;
    const vmin = speeds[0];
    const vmax = speeds[speeds.length - 1] > vmin ? speeds[speeds.length - 1] : vmin + 1;
    const X = (v) => m.left + ((v - vmin) / (vmax - vmin)) * pw;
    const Y = (y) => m.top + ((ylim - Math.max(-10 * ylim, Math.min(10 * ylim, y))) / (2 * ylim)) * ph;

    const root = svg("svg", { width, height, viewBox: `0 0 ${width} ${height}`, "font-family": FONT, "font-size": 11, role: "img", "aria-label": "Eigenvalues against forward speed" });
    root.append(svg("rect", { x: 0, y: 0, width, height, fill: "#ffffff" }));
    const clipId = `clip-${Math.random().toString(36).slice(2, 8)}`;
    root.append(svg("defs", {}, svg("clipPath", { id: clipId }, svg("rect", { x: m.left, y: m.top, width: pw, height: ph }))));

    // Self-stable speed ranges of the primary design.
    const crit = primary.eigen.critical;
    const shade = svg("g", { "clip-path": `url(#${clipId})` });
    for (const [a, b] of crit?.stable_speed_ranges ?? []) {
      shade.append(svg("rect", { x: X(a), y: m.top, width: Math.max(0, X(b) - X(a)), height: ph, fill: STABLE, "data-testid": "stable-range" }));
      shade.append(svg("text", { x: (X(a) + X(b)) / 2, y: m.top + ph - 8, "text-anchor": "middle", fill: "#15803d", "font-size": 11, "font-weight": 600 }, "self-stable"));
    }
    root.append(shade);

    // Grid and axes.
    const vt = ticks(vmin, vmax, Math.max(4, Math.round(pw / 80)));
    const yt = ticks(-ylim, ylim, Math.max(4, Math.round(ph / 50)));
    const grid = svg("g", { stroke: GRID, "stroke-width": 1 });
    for (const t of vt) grid.append(svg("line", { x1: X(t), y1: m.top, x2: X(t), y2: m.top + ph }));
    for (const t of yt) grid.append(svg("line", { x1: m.left, y1: Y(t), x2: m.left + pw, y2: Y(t) }));
    root.append(grid);
    root.append(svg("line", { x1: m.left, y1: Y(0), x2: m.left + pw, y2: Y(0), stroke: "#9ca3af", "stroke-width": 1 }));
    const axes = svg("g", { fill: "#4b5563" });
    for (const t of vt) axes.append(svg("text", { x: X(t), y: m.top + ph + 16, "text-anchor": "middle" }, tickLabel(t, vt)));
    for (const t of yt) axes.append(svg("text", { x: m.left - 7, y: Y(t) + 4, "text-anchor": "end" }, tickLabel(t, yt)));
    axes.append(svg("text", { x: m.left + pw / 2, y: height - 8, "text-anchor": "middle", fill: INK, "font-size": 12 }, "forward speed v [m/s]"));
    axes.append(svg("text", { x: 14, y: m.top + ph / 2, "text-anchor": "middle", fill: INK, "font-size": 12, transform: `rotate(-90 14 ${m.top + ph / 2})` }, "eigenvalue λ [1/s]"));
    root.append(axes);
    root.append(svg("rect", { x: m.left, y: m.top, width: pw, height: ph, fill: "none", stroke: "#9ca3af", "stroke-width": 1 }));

    // Curves: decimated to about four points per pixel.
    const curves = svg("g", { "clip-path": `url(#${clipId})`, fill: "none", "stroke-linejoin": "round" });
    const trace = (eigen, colourOf, widthRe, faint) => {
      const n = eigen.speeds.length;
      const every = Math.max(1, Math.floor(n / (4 * pw)));
      eigen.eigenvalues.forEach((col) => {
        const colour = colourOf(col.mode);
        let re = "";
        let im = "";
        let imOpen = false;
        const indices = [];
        for (let i = 0; i < n; i += every) indices.push(i);
        if (indices[indices.length - 1] !== n - 1) indices.push(n - 1);
        for (const i of indices) {
          const x = X(eigen.speeds[i]).toFixed(2);
          re += `${re ? "L" : "M"}${x},${Y(col.re[i]).toFixed(2)}`;
          if (col.im[i] > 0) {
            im += `${imOpen ? "L" : "M"}${x},${Y(col.im[i]).toFixed(2)}`;
            imOpen = true;
          } else {
            imOpen = false;
          }
        }
        curves.append(svg("path", { d: re, stroke: colour, "stroke-width": widthRe, "stroke-opacity": faint ? 0.8 : 1 }));
        if (im) curves.append(svg("path", { d: im, stroke: colour, "stroke-width": widthRe * 0.85, "stroke-dasharray": "6 4", "stroke-opacity": faint ? 0.8 : 1 }));
      });
    };
    if (secondary) trace(secondary.eigen, () => COMPARE, 1.4, true);
    trace(primary.eigen, (mode) => MODE_COLOURS[mode] ?? MODE_COLOURS.unclassified, 2, false);
    root.append(curves);

    // Critical speeds: primary labelled at the top, comparison at the bottom.
    const marks = svg("g", { "font-size": 11 });
    const mark = (v, label, colour, top, dash) => {
      if (v === null || v === undefined || v < vmin || v > vmax) return;
      marks.append(svg("line", { x1: X(v), y1: m.top, x2: X(v), y2: m.top + ph, stroke: colour, "stroke-width": 1.2, "stroke-dasharray": dash }));
      const ty = top ? m.top + 14 : m.top + ph - 22;
      const text = `${label} ${fixed(v, 3)}`;
      const w = text.length * 6.2 + 8;
      const left = X(v) + w + 4 > m.left + pw;
      const tx = left ? X(v) - w - 3 : X(v) + 3;
      marks.append(svg("rect", { x: tx, y: ty - 11, width: w, height: 15, rx: 3, fill: "#ffffff", "fill-opacity": 0.9, stroke: colour, "stroke-width": 0.8 }));
      marks.append(svg("text", { x: tx + 4, y: ty, fill: colour }, text));
    };
    if (secondary?.eigen.critical) {
      const c = secondary.eigen.critical;
      mark(c.weave_speed, "v_w", COMPARE, false, "4 3");
      mark(c.capsize_speed, "v_c", COMPARE, false, "4 3");
    }
    if (crit) {
      mark(crit.double_root_speed, "v_d", "#6b7280", true, "2 3");
      mark(crit.weave_speed, "v_w", MODE_COLOURS.weave, true, "6 3");
      mark(crit.capsize_speed, "v_c", MODE_COLOURS.capsize, true, "6 3");
    }
    root.append(marks);

    // Legend above the plot.
    const legend = svg("g", { "font-size": 11, fill: INK });
    let lx = m.left;
    const ly = 18;
    const item = (draw, text) => {
      legend.append(draw(lx, ly));
      legend.append(svg("text", { x: lx + 24, y: ly + 4 }, text));
      lx += 30 + text.length * 6.1;
    };
    const seg = (colour, dash, w = 2) => (x, y) => svg("line", { x1: x, y1: y, x2: x + 18, y2: y, stroke: colour, "stroke-width": w, "stroke-dasharray": dash });
    item(seg(INK), "Re λ");
    item(seg(INK, "6 4"), "Im λ");
    const modes = [...new Set(primary.eigen.eigenvalues.map((c) => c.mode))];
    for (const mode of modes) item(seg(MODE_COLOURS[mode] ?? MODE_COLOURS.unclassified, null, 3), mode);
    item((x, y) => svg("rect", { x, y: y - 6, width: 18, height: 12, fill: STABLE, stroke: "#86efac" }), "self-stable");
    if (secondary) item(seg(COMPARE, null, 1.6), `compared: ${secondary.label}`);
    root.append(legend);

    if (stale) {
      root.append(svg("rect", { x: m.left, y: m.top, width: pw, height: ph, fill: "#ffffff", "fill-opacity": 0.6 }));
      root.append(svg("text", { x: m.left + pw / 2, y: m.top + 30, "text-anchor": "middle", "font-size": 12, fill: "#b91c1c" }, "not recomputed: the parameters are invalid"));
    }

    // Hover read-out (not exported).
    const hover = svg("g", { "data-export": "skip", "pointer-events": "none", visibility: "hidden" });
    const cross = svg("line", { y1: m.top, y2: m.top + ph, stroke: INK, "stroke-width": 0.8, "stroke-dasharray": "3 3" });
    hover.append(cross);
    const dots = svg("g", { "clip-path": `url(#${clipId})` });
    hover.append(dots);
    root.append(hover);
    const overlay = svg("rect", { x: m.left, y: m.top, width: pw, height: ph, fill: "transparent", "data-export": "skip", "data-testid": "plot-overlay" });
    root.append(overlay);
    const read = (clientX) => {
      const box = root.getBoundingClientRect();
      const px = ((clientX - box.left) / box.width) * width;
      const v = vmin + ((px - m.left) / pw) * (vmax - vmin);
      const i = nearest(speeds, v);
      const x = X(speeds[i]);
      cross.setAttribute("x1", x);
      cross.setAttribute("x2", x);
      dots.replaceChildren();
      const rows = [html("div", { class: "tt-v", text: `v = ${sig(speeds[i])} m/s` })];
      const readDesign = (d, colourOf, idx) => {
        rows.push(html("div", { class: "tt-name", text: d.label }));
        const cols = d.eigen.eigenvalues;
        const seen = new Set();
        cols.forEach((c, k) => {
          const re = c.re[idx], im = c.im[idx];
          const colour = colourOf(c.mode);
          dots.append(svg("circle", { cx: x, cy: Y(re), r: 3, fill: colour }));
          if (im > 0) dots.append(svg("circle", { cx: x, cy: Y(im), r: 3, fill: "#ffffff", stroke: colour, "stroke-width": 1.5 }));
          if (seen.has(k)) return;
          // A conjugate pair is read out once.
          const partner = cols.findIndex((o, j) => j !== k && !seen.has(j) && im !== 0 && Math.abs(o.re[idx] - re) <= 1e-9 * (1 + Math.abs(re)) && Math.abs(o.im[idx] + im) <= 1e-9 * (1 + Math.abs(im)));
          if (partner >= 0) seen.add(partner);
          seen.add(k);
          const value = im !== 0 ? `${sig(re)} ± ${sig(Math.abs(im))}i` : sig(re);
          const row = html("div", { class: "tt-row" }, html("span", { class: "tt-dot", style: `background:${colour}` }), html("span", { class: "tt-mode", text: c.mode }), html("span", { class: "tt-val", text: value }));
          rows.push(row);
        });
      };
      readDesign(primary, (mode) => MODE_COLOURS[mode] ?? MODE_COLOURS.unclassified, i);
      if (secondary) {
        const s = secondary.eigen.speeds;
        const j = nearest(s, speeds[i]);
        if (Math.abs(s[j] - speeds[i]) <= 1e-9 + 0.5 * Math.abs((s[1] ?? s[0]) - s[0])) readDesign(secondary, () => COMPARE, j);
      }
      this.tooltip.replaceChildren(...rows);
      this.tooltip.hidden = false;
      hover.setAttribute("visibility", "visible");
      const cw = this.container.clientWidth;
      const tx = (x / width) * box.width;
      this.tooltip.style.left = `${tx + 14 + 220 > cw ? tx - 14 - this.tooltip.offsetWidth : tx + 14}px`;
      this.tooltip.style.top = `${m.top + 26}px`;
    };
    overlay.addEventListener("pointermove", (e) => read(e.clientX));
    overlay.addEventListener("pointerleave", () => {
      hover.setAttribute("visibility", "hidden");
      this.tooltip.hidden = true;
    });

    this.holder.replaceChildren(root);
    this.svgEl = root;
  }
}
