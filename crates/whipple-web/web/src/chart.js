// The interactive frame every plot of the page shares: axes, grid and ticks drawn as SVG (so
// that a figure exports as SVG or PNG), and the ways to explore it:
//   wheel            zoom about the pointer (shift: horizontal only)
//   drag             pan;  shift-drag, or drag with "Box zoom" on: zoom to the box drawn
//   one finger       (touch screens) scrolls the page as anywhere else; a tap reads out there
//   two fingers      pinch to zoom, drag to pan (touch screens)
//   double-click     back to the full view;  "Autoscale": fit the vertical axis to what is seen
//   keyboard         (the plot takes focus) ←/→ step the read-out through the data, shift+←/→
//                    and ↑/↓ pan, + and − zoom, 0 or Home the full view, A autoscale
// The read-out under the pointer (or the keyboard's cursor) is computed again from the new data
// at every redraw, so it never shows values of an earlier drawing.
//
// A plot extends Chart and provides: extent() → the full view {x0, x1, y0, y1};
// fitY(x0, x1) → {y0, y1} of the data seen (for autoscale); render(root, frame) to draw the
// data; readAt(px, py, frame) → {rows, dots, x} or null for the read-out; xs() → the sorted
// x values the keyboard steps through. With `logX`, the plot's x values are log₁₀ of the
// quantity (a Bode plot's frequency): ticks fall on decades (and 2 and 5 between them when
// few decades are seen), labelled with the quantity itself.

import { svg, html, ticks, tickLabel, logTicks, num, FONT } from "./format.js";

const GRID = "#e5e7eb";
const INK = "#1f2937";

let clipCount = 0;

export class Chart {
  constructor(container, { label, xLabel, yLabel, margin, minWidth = 280, minHeight = 180, crosshair = true, fontSize = 11, flipY = false, logX = false, testid = null }) {
    this.logX = logX;
    this.testid = testid ?? container.dataset.testid ?? "plot";
    this.flipY = flipY; // true: y grows downwards (the ground track seen from above)
    this.container = container;
    this.label = label;
    this.xLabel = xLabel;
    this.yLabel = yLabel;
    this.margin = margin ?? { left: 56, right: 16, top: 36, bottom: 42 };
    this.minWidth = minWidth;
    this.minHeight = minHeight;
    this.crosshair = crosshair;
    this.fontSize = fontSize;
    this.view = null; // null: the full view
    this.hover = null; // {px, py} in the svg's pixels, or {key: x} for the keyboard's cursor
    this.boxMode = false;
    this.svgEl = null;
    this.frame = null;
    this.stale = null;
    this.holder = html("div", { class: "plot-holder" });
    this.tooltip = html("div", { class: "tooltip", hidden: true, "data-testid": `${this.testid}-tooltip` });
    this.box = html("div", { class: "zoom-box", hidden: true });
    this.live = html("div", { class: "sr-only", "aria-live": "polite" });
    const button = (text, title, testid) => html("button", { type: "button", class: "btn tiny", title, text, "data-testid": testid, tabindex: "-1" });
    this.boxButton = button("Box", "Box zoom: drag a box to zoom into it (or shift-drag)", "zoom-box");
    this.boxButton.setAttribute("aria-pressed", "false");
    this.autoButton = button("Fit y", "Autoscale: fit the vertical axis to the curves shown (A)", "zoom-auto");
    this.resetButton = button("Reset", "Back to the full view (double-click, 0)", "zoom-reset");
    this.tools = html("div", { class: "plot-tools" }, this.boxButton, this.autoButton, this.resetButton);
    container.replaceChildren(this.holder, this.tooltip, this.box, this.tools, this.live);
    container.tabIndex = 0;
    container.setAttribute("role", "group");
    container.setAttribute("aria-roledescription", "interactive plot");
    container.setAttribute("aria-label", `${label}. Arrow keys read the values out; plus and minus zoom; 0 resets.`);
    this.boxButton.addEventListener("click", () => {
      this.boxMode = !this.boxMode;
      this.boxButton.setAttribute("aria-pressed", String(this.boxMode));
    });
    this.autoButton.addEventListener("click", () => this.autoscale());
    this.resetButton.addEventListener("click", () => this.reset());
    this.listen();
    let pending = 0;
    new ResizeObserver(() => {
      cancelAnimationFrame(pending);
      pending = requestAnimationFrame(() => this.ready() && this.draw());
    }).observe(container);
  }

  /** True once there is data to draw (plots override). */
  ready() {
    return false;
  }

  /** The view drawn: the user's, or the full one. */
  currentView() {
    return this.view ?? this.extent();
  }

  /** Sets the view; drawn at the next frame (`now`: at once). */
  setView(view, now = false) {
    const v = { ...view };
    if (!(v.x1 > v.x0) || !(v.y1 > v.y0) || ![v.x0, v.x1, v.y0, v.y1].every(Number.isFinite)) return;
    this.view = v;
    if (now) this.draw();
    else this.scheduleDraw();
  }

  reset() {
    this.view = null;
    this.draw();
  }

  autoscale() {
    const v = this.currentView();
    const fit = this.fitY(v.x0, v.x1);
    if (fit && fit.y1 > fit.y0) {
      const pad = 0.05 * (fit.y1 - fit.y0);
      this.setView({ ...v, y0: fit.y0 - pad, y1: fit.y1 + pad }, true);
    }
  }

  scheduleDraw() {
    if (this.drawPending) return;
    this.drawPending = requestAnimationFrame(() => {
      this.drawPending = 0;
      this.draw();
    });
  }

  /** Pointer position in the svg's pixels. */
  local(e) {
    const r = this.container.getBoundingClientRect();
    return { px: e.clientX - r.left, py: e.clientY - r.top };
  }

  inPlot({ px, py }) {
    const f = this.frame;
    return f && px >= f.left && px <= f.left + f.pw && py >= f.top && py <= f.top + f.ph;
  }

  /** Data coordinates of a pixel. */
  toData({ px, py }) {
    const f = this.frame;
    const u = (py - f.top) / f.ph;
    return { x: f.x0 + ((px - f.left) / f.pw) * (f.x1 - f.x0), y: this.flipY ? f.y0 + u * (f.y1 - f.y0) : f.y1 - u * (f.y1 - f.y0) };
  }

  zoomAbout({ px, py }, fx, fy) {
    const f = this.frame;
    if (!f) return;
    const { x, y } = this.toData({ px, py });
    this.setView({ x0: x - (x - f.x0) * fx, x1: x + (f.x1 - x) * fx, y0: y - (y - f.y0) * fy, y1: y + (f.y1 - y) * fy });
  }

  pan(dpx, dpy) {
    const f = this.frame;
    if (!f) return;
    const dx = (dpx / f.pw) * (f.x1 - f.x0);
    const dy = ((this.flipY ? -dpy : dpy) / f.ph) * (f.y1 - f.y0);
    this.setView({ x0: f.x0 - dx, x1: f.x1 - dx, y0: f.y0 + dy, y1: f.y1 + dy });
  }

  listen() {
    const el = this.container;
    const pointers = new Map();
    let drag = null;
    el.addEventListener("pointerdown", (e) => {
      if (e.target.closest(".plot-tools") || !this.frame) return;
      const p = this.local(e);
      if (!this.inPlot(p)) return;
      pointers.set(e.pointerId, p);
      // One finger is the page's (it scrolls: touch-action pan-y) or a tap for a read-out; a
      // swipe that began on a plot used to pan the plot and trap the page.
      if (e.pointerType === "touch" && pointers.size === 1) {
        drag = { kind: "tap", start: p, last: p, moved: false };
        return;
      }
      el.setPointerCapture?.(e.pointerId);
      if (pointers.size === 2) {
        const [a, b] = [...pointers.values()];
        drag = { kind: "pinch", a, b, dist: Math.hypot(a.px - b.px, a.py - b.py), view: { ...this.frame } };
      } else {
        drag = { kind: e.shiftKey || this.boxMode ? "box" : "pan", start: p, last: p, moved: false };
      }
      e.preventDefault();
    });
    el.addEventListener("pointermove", (e) => {
      const p = this.local(e);
      if (pointers.has(e.pointerId)) pointers.set(e.pointerId, p);
      if (drag?.kind === "tap") {
        if (Math.abs(p.px - drag.start.px) + Math.abs(p.py - drag.start.py) > 8) drag.moved = true;
        drag.last = p;
      } else if (drag?.kind === "pan") {
        if (Math.abs(p.px - drag.start.px) + Math.abs(p.py - drag.start.py) > 3) drag.moved = true;
        if (drag.moved) this.pan(p.px - drag.last.px, p.py - drag.last.py);
        drag.last = p;
      } else if (drag?.kind === "box") {
        const f = this.frame;
        const x0 = Math.max(f.left, Math.min(drag.start.px, p.px)), x1 = Math.min(f.left + f.pw, Math.max(drag.start.px, p.px));
        const y0 = Math.max(f.top, Math.min(drag.start.py, p.py)), y1 = Math.min(f.top + f.ph, Math.max(drag.start.py, p.py));
        Object.assign(this.box.style, { left: `${x0}px`, top: `${y0}px`, width: `${x1 - x0}px`, height: `${y1 - y0}px` });
        this.box.hidden = false;
        drag.last = p;
      } else if (drag?.kind === "pinch" && pointers.size === 2) {
        const [a, b] = [...pointers.values()];
        const dist = Math.hypot(a.px - b.px, a.py - b.py);
        const mid = { px: (a.px + b.px) / 2, py: (a.py + b.py) / 2 };
        const f = 1 / Math.max(0.05, dist / Math.max(1, drag.dist));
        const v = drag.view;
        const u = (mid.py - v.top) / v.ph;
        const c = { x: v.x0 + ((mid.px - v.left) / v.pw) * (v.x1 - v.x0), y: this.flipY ? v.y0 + u * (v.y1 - v.y0) : v.y1 - u * (v.y1 - v.y0) };
        this.setView({ x0: c.x - (c.x - v.x0) * f, x1: c.x + (v.x1 - c.x) * f, y0: c.y - (c.y - v.y0) * f, y1: c.y + (v.y1 - c.y) * f });
      } else {
        this.hover = this.inPlot(p) ? p : null;
        this.read();
      }
    });
    const end = (e) => {
      pointers.delete(e.pointerId);
      if (drag?.kind === "tap" && !drag.moved && e.type === "pointerup") {
        this.hover = drag.start;
        this.read();
      }
      if (drag?.kind === "box") {
        this.box.hidden = true;
        const a = this.toData(drag.start), b = this.toData(drag.last);
        const wide = Math.abs(drag.last.px - drag.start.px) > 4, tall = Math.abs(drag.last.py - drag.start.py) > 4;
        const f = this.frame;
        if (wide || tall) {
          this.setView({
            x0: wide ? Math.min(a.x, b.x) : f.x0, x1: wide ? Math.max(a.x, b.x) : f.x1,
            y0: tall ? Math.min(a.y, b.y) : f.y0, y1: tall ? Math.max(a.y, b.y) : f.y1,
          }, true);
        }
      }
      drag = pointers.size ? drag : null;
    };
    el.addEventListener("pointerup", end);
    el.addEventListener("pointercancel", end);
    el.addEventListener("pointerleave", (e) => {
      if (drag || e.pointerType !== "mouse") return;
      this.hover = null;
      this.read();
    });
    el.addEventListener("wheel", (e) => {
      const p = this.local(e);
      if (!this.inPlot(p)) return;
      e.preventDefault();
      const f = Math.exp(Math.max(-0.5, Math.min(0.5, e.deltaY * (e.deltaMode === 1 ? 0.05 : 0.0015))));
      this.zoomAbout(p, f, e.shiftKey ? 1 : f);
    }, { passive: false });
    el.addEventListener("dblclick", (e) => {
      if (e.target.closest(".plot-tools")) return;
      this.reset();
    });
    el.addEventListener("keydown", (e) => this.key(e));
    el.addEventListener("blur", () => {
      if (this.hover?.key !== undefined) {
        this.hover = null;
        this.read();
      }
    });
  }

  key(e) {
    if (!this.frame) return;
    const f = this.frame;
    const centre = { px: f.left + f.pw / 2, py: f.top + f.ph / 2 };
    const xs = this.xs();
    let handled = true;
    if ((e.key === "ArrowLeft" || e.key === "ArrowRight") && !e.shiftKey && xs.length) {
      const dir = e.key === "ArrowRight" ? 1 : -1;
      let i = this.hover?.index;
      if (i === undefined) {
        // Start at the middle of the view.
        const mid = (f.x0 + f.x1) / 2;
        i = xs.findIndex((x) => x >= mid);
        if (i < 0) i = xs.length - 1;
      } else {
        const step = Math.max(1, Math.round(xs.length / 200));
        i = Math.max(0, Math.min(xs.length - 1, i + dir * step));
      }
      const x = xs[i];
      if (x < f.x0 || x > f.x1) this.setView({ ...f, x0: x - (f.x1 - f.x0) / 2, x1: x + (f.x1 - f.x0) / 2 });
      this.hover = { index: i, key: x };
      this.read();
    } else if (e.key === "ArrowLeft" || e.key === "ArrowRight") this.pan(e.key === "ArrowRight" ? -f.pw / 10 : f.pw / 10, 0);
    else if (e.key === "ArrowUp" || e.key === "ArrowDown") this.pan(0, e.key === "ArrowUp" ? f.ph / 10 : -f.ph / 10);
    else if (e.key === "+" || e.key === "=") this.zoomAbout(centre, 0.8, 0.8);
    else if (e.key === "-" || e.key === "_") this.zoomAbout(centre, 1.25, 1.25);
    else if (e.key === "0" || e.key === "Home") this.reset();
    else if (e.key === "a" || e.key === "A") this.autoscale();
    else if (e.key === "Escape") {
      this.hover = null;
      this.read();
    } else handled = false;
    if (handled) e.preventDefault();
  }

  /** Draws everything for the current view and size. */
  draw() {
    if (this.drawPending) {
      cancelAnimationFrame(this.drawPending);
      this.drawPending = 0;
    }
    if (!this.ready()) return;
    const width = Math.max(this.minWidth, Math.round(this.container.clientWidth));
    const height = Math.max(this.minHeight, Math.round(this.container.clientHeight));
    // The legend (drawn by the plot) may wrap on a narrow screen: the plot then starts lower.
    const m = { ...this.margin, top: this.margin.top + (this.legendExtra ?? 0) };
    const pw = Math.max(20, width - m.left - m.right);
    const ph = Math.max(20, height - m.top - m.bottom);
    const v = this.currentView();
    const X = (x) => m.left + ((x - v.x0) / (v.x1 - v.x0)) * pw;
    // Clamped far outside the plot, so that huge values still draw as lines leaving it.
    const clampY = (y) => Math.max(v.y0 - 50 * (v.y1 - v.y0), Math.min(v.y1 + 50 * (v.y1 - v.y0), y));
    const Y = this.flipY
      ? (y) => m.top + ((clampY(y) - v.y0) / (v.y1 - v.y0)) * ph
      : (y) => m.top + ((v.y1 - clampY(y)) / (v.y1 - v.y0)) * ph;
    const frame = { ...v, left: m.left, top: m.top, pw, ph, width, height, X, Y };
    this.frame = frame;
    const root = svg("svg", { width, height, viewBox: `0 0 ${width} ${height}`, "font-family": FONT, "font-size": this.fontSize, role: "img", "aria-label": this.label });
    root.append(svg("rect", { x: 0, y: 0, width, height, fill: "#ffffff" }));
    const clip = `clip-${(clipCount += 1)}`;
    root.append(svg("defs", {}, svg("clipPath", { id: clip }, svg("rect", { x: m.left, y: m.top, width: pw, height: ph }))));
    frame.clip = `url(#${clip})`;
    const xt = this.logX ? logTicks(v.x0, v.x1, Math.max(3, Math.round(pw / 60))) : ticks(v.x0, v.x1, Math.max(3, Math.round(pw / 80)));
    const yt = ticks(v.y0, v.y1, Math.max(3, Math.round(ph / 32)));
    frame.xt = xt;
    frame.yt = yt;
    const grid = svg("g", { stroke: GRID, "stroke-width": 1 });
    for (const t of xt) grid.append(svg("line", { x1: X(t), y1: m.top, x2: X(t), y2: m.top + ph }));
    for (const t of yt) grid.append(svg("line", { x1: m.left, y1: Y(t), x2: m.left + pw, y2: Y(t) }));
    root.append(grid);
    if (v.y0 < 0 && v.y1 > 0) root.append(svg("line", { x1: m.left, y1: Y(0), x2: m.left + pw, y2: Y(0), stroke: "#9ca3af", "stroke-width": 1 }));
    const axes = svg("g", { fill: "#4b5563" });
    for (const t of xt) axes.append(svg("text", { x: X(t), y: m.top + ph + 15, "text-anchor": "middle" }, this.logX ? num(10 ** t, 3) : tickLabel(t, xt)));
    for (const t of yt) axes.append(svg("text", { x: m.left - 6, y: Y(t) + 4, "text-anchor": "end" }, tickLabel(t, yt)));
    axes.append(svg("text", { x: m.left + pw / 2, y: height - 6, "text-anchor": "middle", fill: INK, "font-size": this.fontSize + 1 }, this.xLabel));
    axes.append(svg("text", { x: 13, y: m.top + ph / 2, "text-anchor": "middle", fill: INK, "font-size": this.fontSize + 1, transform: `rotate(-90 13 ${m.top + ph / 2})` }, this.yLabel));
    root.append(axes);
    frame.legendWidth = Math.max(120, pw - 130); // room for the zoom buttons at the right
    this.render(root, frame);
    if (frame.legendBottom !== undefined) {
      const extra = Math.max(0, frame.legendBottom + 14 - this.margin.top);
      if (extra !== (this.legendExtra ?? 0) && !this.relaying) {
        this.legendExtra = extra;
        this.relaying = true;
        try {
          this.draw();
        } finally {
          this.relaying = false;
        }
        return;
      }
    }
    root.append(svg("rect", { x: m.left, y: m.top, width: pw, height: ph, fill: "none", stroke: "#9ca3af", "stroke-width": 1 }));
    if (this.stale) {
      root.append(svg("rect", { x: m.left, y: m.top, width: pw, height: ph, fill: "#ffffff", "fill-opacity": 0.62, "data-testid": "stale-veil" }));
      root.append(svg("text", { x: m.left + pw / 2, y: m.top + 30, "text-anchor": "middle", "font-size": 12, fill: "#b91c1c" }, this.stale));
    }
    root.append(svg("rect", { x: m.left, y: m.top, width: pw, height: ph, fill: "transparent", "data-export": "skip", "data-testid": `${this.testid}-overlay` }));
    this.hoverLayer = svg("g", { "data-export": "skip", "pointer-events": "none" });
    root.append(this.hoverLayer);
    this.holder.replaceChildren(root);
    this.svgEl = root;
    this.read();
  }

  /** The read-out at the pointer or the keyboard's cursor, from the data drawn now. */
  read() {
    const layer = this.hoverLayer;
    if (!layer || !this.frame) return;
    layer.replaceChildren();
    const h = this.hover;
    const out = h ? this.readAt(h, this.frame) : null;
    if (!out) {
      this.tooltip.hidden = true;
      return;
    }
    const f = this.frame;
    if (this.crosshair && out.x !== undefined) layer.append(svg("line", { x1: out.x, x2: out.x, y1: f.top, y2: f.top + f.ph, stroke: INK, "stroke-width": 0.8, "stroke-dasharray": "3 3" }));
    const dots = svg("g", { "clip-path": f.clip });
    for (const d of out.dots ?? []) dots.append(svg("circle", { cx: d.x, cy: d.y, r: d.r ?? 3, fill: d.hollow ? "#ffffff" : d.colour, stroke: d.colour, "stroke-width": 1.5 }));
    layer.append(dots);
    this.tooltip.replaceChildren(...out.rows);
    this.tooltip.hidden = false;
    this.live.textContent = this.tooltip.textContent;
    const anchorX = out.x ?? h.px ?? f.left;
    const cw = this.container.clientWidth;
    const w = this.tooltip.offsetWidth;
    this.tooltip.style.left = `${anchorX + 14 + w > cw ? Math.max(0, anchorX - 14 - w) : anchorX + 14}px`;
    this.tooltip.style.top = `${f.top + 8}px`;
  }
}

/** Index of the value nearest `x` in the sorted `values`. */
export function nearest(values, x) {
  let lo = 0, hi = values.length - 1;
  if (hi <= 0) return 0;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (values[mid] < x) lo = mid; else hi = mid;
  }
  return Math.abs(values[lo] - x) <= Math.abs(values[hi] - x) ? lo : hi;
}

/** The index range [i0, i1] of sorted `values` covering [x0, x1], one point beyond each end. */
export function visibleRange(values, x0, x1) {
  const n = values.length;
  let i0 = nearest(values, x0), i1 = nearest(values, x1);
  i0 = Math.max(0, i0 - 1);
  i1 = Math.min(n - 1, i1 + 1);
  return [i0, i1];
}

/** A legend across the top: items of {draw(x, y) → svg, text}; wraps when it must. */
export function legend(root, items, left, width, fontSize = 11) {
  const g = svg("g", { "font-size": fontSize, fill: INK });
  let x = left;
  let y = 16;
  for (const { draw, text } of items) {
    const w = 30 + text.length * fontSize * 0.56;
    if (x > left && x + w > left + width) {
      x = left;
      y += 15;
    }
    g.append(draw(x, y));
    g.append(svg("text", { x: x + 24, y: y + 4 }, text));
    x += w;
  }
  root.append(g);
  return y;
}
