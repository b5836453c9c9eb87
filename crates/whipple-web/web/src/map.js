// The Design map tab (and, with the y axis left empty, the one-parameter study: v_w and v_c
// against one parameter, the self-stable band shaded, from POST /api/study): one quantity (the width of the self-stable range, v_w, v_c, the weave
// frequency or the largest real part at a speed) over two parameters of the current bicycle
// (POST /api/map, what `whipple map` writes: critical speeds certified for every design, invalid
// designs marked with their reason, never computed). Axes are typed as on the command line,
// NAME=START:STOP:COUNT; the base design is marked, and the cell under the cursor is read out.

import { api } from "./api.js";
import { parseNumber } from "./editor.js";
import { html, num, ramp, ticks, tickLabel, FONT } from "./format.js";

/** Where v sits on a diverging scale over `range`: 0.5 at zero, 0 at the lowest value (when
 *  negative), 1 at the highest (when positive). */
function divergingPlace(v, [lo, hi]) {
  if (v < 0) return lo < 0 ? 0.5 - 0.5 * Math.min(1, v / lo) : 0.5;
  return hi > 0 ? 0.5 + 0.5 * Math.min(1, v / hi) : 0.5;
}

/** A diverging colour for f in [0, 1]: blue below the middle, white at it, red above. */
function divergingRamp(f) {
  const t = Math.max(0, Math.min(1, f));
  const [from, to, u] = t < 0.5 ? [[37, 99, 235], [255, 255, 255], t / 0.5] : [[255, 255, 255], [220, 38, 38], (t - 0.5) / 0.5];
  const c = from.map((x, k) => Math.round(x + (to[k] - x) * u));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}

const $ = (id) => document.getElementById(id);

/** The quantities a map can show: the response's arrays, how they read, their unit. */
export const MAP_QUANTITIES = {
  stable_width: { words: "width of the self-stable range", unit: "m/s" },
  v_w: { words: "weave speed v_w", unit: "m/s" },
  v_c: { words: "capsize speed v_c", unit: "m/s" },
  weave_frequency: { words: "weave frequency at v_w", unit: "rad/s" },
  max_real: { words: "largest real part at the speed", unit: "1/s" },
  band_margin: { words: "self-stable over the band: the smaller margin", unit: "m/s" },
};

/** The band typed as A:B (m/s): [a, b], null when the field is empty, or an error's words. */
export function parseBand(text) {
  const t = text.trim();
  if (t === "") return null;
  // km/h after the band applies to both ends, as the CLI's `--band 16:23km/h`.
  const kmh = /km\/h$/.test(t);
  const parts = t.split(":").map((p) => (kmh ? p.trim().replace(/km\/h$/, "") : p));
  // Each end in m/s, or in km/h where it says so; both in km/h when the band ends in it.
  const [a, b] = parts.map((p) => parseNumber(p, kmh ? null : "speed")).map((x) => (x === null ? NaN : kmh ? x / 3.6 : x));
  if (parts.length !== 2 || parts.some((p) => p.trim() === "") || !Number.isFinite(a) || !Number.isFinite(b)) {
    return { error: `the band is A:B in m/s or km/h (for example 4:8, or 16:23 km/h), not “${t}”` };
  }
  if (!(a < b)) return { error: `the band's A must be less than its B, got ${t}` };
  return [a, b];
}

/** Colours of the cells that have no number on the scale. */
const INVALID = "#e5e7eb";
const UNBOUNDED = "#fca5a5";
const NONE = "#ffffff";
const UNDECIDED = "#fde68a";
/** Pixels around the cells for the axes: left, bottom, top, right. */
const MARGIN = { left: 52, bottom: 36, top: 8, right: 10 };

/** The value of `quantity` at cell `k` of `answer`, or why there is none. */
export function cell(answer, quantity, k) {
  if (answer.status[k] !== "ok") {
    const reason = answer.reasons.find((r) => r[0] === k)?.[1];
    return { kind: answer.status[k], reason: reason ?? answer.status[k] };
  }
  // A design with no self-stable speed has no width: "none", as the legend says.
  if (quantity === "stable_width" && !answer.stable[k]) return { kind: "none" };
  if (quantity === "stable_width" && answer.stable_unbounded[k]) return { kind: "unbounded" };
  if (quantity === "band_margin") {
    const over = answer.stable_over?.[k];
    if (over === false) return { kind: "none" };
    if (over !== true) return { kind: "undecided" };
  }
  const value = answer[quantity]?.[k];
  return Number.isFinite(value) ? { kind: "value", value } : { kind: "none" };
}

export class MapPanel {
  /**
   * `bike()` gives the current bicycle, `label()` its name; `onChange()` when the inputs change;
   * `onLoad(bike, where)` takes the design of a clicked cell into the editor.
   */
  constructor({ bike, label, onChange, onLoad }) {
    this.bike = bike;
    this.label = label;
    this.onChange = onChange ?? (() => {});
    this.onLoad = onLoad ?? (() => {});
    this.answer = null;
    // A map under way can be stopped (the server stops its work once the request is dropped;
    // the static site ends the worker that runs it).
    $("map-cancel").addEventListener("click", () => this.controller?.abort());
    $("map-form").addEventListener("submit", (e) => {
      e.preventDefault();
      this.compute();
      this.onChange();
    });
    $("map-quantity").addEventListener("change", () => {
      // A band asked for now, or one the answer lacks: the map is computed again.
      const wantsBand = $("map-quantity").value === "band_margin";
      if (this.answer && wantsBand && !this.answer.band) this.compute();
      else this.draw();
      this.onChange();
    });
    const canvas = $("map-canvas");
    canvas.addEventListener("mousemove", (e) => this.hover(e));
    // A mouse leaving clears the read-out; after a tap (its emulated mouse leaves as the finger
    // goes to the "Load this design" button) the read-out and its button stay.
    canvas.addEventListener("mouseleave", () => {
      if (this.lastPointer !== "touch") $("map-readout").textContent = "";
    });
    // A mouse click loads the design at once; a tap (a phone) reads the cell out and offers
    // to load it: a tap is how a phone reads a cell, and it should not replace the bicycle.
    // The cell under the finger as it lifts: by the click that follows, the read-out written
    // meanwhile may have moved the page.
    canvas.addEventListener("pointerup", (e) => {
      this.lastPointer = e.pointerType;
      this.tapped = e.pointerType === "touch" ? this.cellAt(e) : null;
    });
    canvas.addEventListener("click", (e) => (this.lastPointer === "touch" ? this.offer(e) : this.load(e)));
  }

  /** The inputs, for the link: {x, y, quantity, speed, band}. */
  inputs() {
    const inputs = { x: $("map-x").value, y: $("map-y").value, quantity: $("map-quantity").value, speed: $("map-speed").value };
    if ($("map-band").value.trim()) inputs.band = $("map-band").value.trim();
    return inputs;
  }

  setInputs(s) {
    if (s.x) $("map-x").value = s.x;
    if (s.y) $("map-y").value = s.y;
    if (s.quantity && s.quantity in MAP_QUANTITIES) $("map-quantity").value = s.quantity;
    if (s.speed !== undefined) $("map-speed").value = s.speed;
    if (s.band !== undefined) $("map-band").value = s.band;
  }

  /** Forgets the map (the bicycle changed): the tab computes it again when it opens. */
  invalidate() {
    this.controller?.abort();
    this.sequence = (this.sequence ?? 0) + 1;
    this.answer = null;
    this.pending = false;
    this.key = null;
  }

  async compute() {
    const request = { bike: this.bike(), x: $("map-x").value.trim() };
    const y = $("map-y").value.trim();
    if (y) request.y = y;
    const speed = parseNumber($("map-speed").value, "speed");
    if ($("map-speed").value.trim() !== "" && speed !== null) request.speed = speed;
    const band = parseBand($("map-band").value);
    const bandMissing = !band && $("map-quantity").value === "band_margin" && request.y;
    if (band?.error || bandMissing) {
      // Refused here, before any work: the field says why, and no old map stays as if it answered.
      this.sequence = (this.sequence ?? 0) + 1;
      this.answer = null;
      this.key = null;
      this.pending = false;
      $("map-band").classList.add("invalid");
      $("map-meta").textContent = "";
      $("map-message").textContent = band?.error ?? "“self-stable over the band” needs a band A:B, for example 4:8";
      $("map-message").hidden = false;
      const canvas = $("map-canvas");
      canvas.getContext("2d").clearRect(0, 0, canvas.width, canvas.height);
      $("map-legend").replaceChildren();
      return;
    }
    if (band) request.band = band;
    // The same question asked again (a redraw of the page) is not computed twice.
    const key = JSON.stringify(request);
    if (key === this.key && (this.answer || this.pending)) return;
    const mine = (this.sequence = (this.sequence ?? 0) + 1);
    this.key = key;
    this.pending = true;
    // A map asked for supersedes the one under way: that one stops.
    this.controller?.abort();
    const controller = (this.controller = new AbortController());
    $("map-meta").textContent = "computing…";
    $("map-cancel").hidden = false;
    for (const id of ["map-x", "map-y", "map-speed", "map-band"]) $(id).classList.remove("invalid");
    const started = performance.now();
    // How far it is: the designs done as the back end tells them, and the time taken.
    const shown = (done, total) => {
      if (mine !== this.sequence) return;
      const seconds = num((performance.now() - started) / 1000, 1);
      $("map-meta").textContent = total ? `computing… ${done.toLocaleString("en")} of ${total.toLocaleString("en")} designs, ${seconds} s` : `computing… ${seconds} s`;
    };
    const ticking = setInterval(() => this.progress || shown(), 500);
    const onProgress = (done, total) => {
      this.progress = [done, total];
      shown(done, total);
    };
    this.progress = null;
    try {
      const options = { signal: controller.signal, onProgress };
      const answer = await (request.y ? api.map(request, options) : api.study(request, options));
      if (mine !== this.sequence) return;
      this.pending = false;
      $("map-message").hidden = true;
      this.answer = answer;
      // The axes as asked (the fields may be edited later): a clicked cell is on this grid.
      this.asked = { x: request.x, y: request.y };
      this.seconds = (performance.now() - started) / 1000;
      this.draw();
    } catch (e) {
      if (mine !== this.sequence) return;
      this.pending = false;
      this.key = null;
      this.answer = null;
      if (e.kind === "cancelled") {
        // Stopped by the Cancel button: no map, and the header says so.
        $("map-meta").textContent = `cancelled after ${num((performance.now() - started) / 1000, 1)} s; Compute asks again`;
        $("map-message").hidden = true;
        const canvas = $("map-canvas");
        canvas.getContext("2d").clearRect(0, 0, canvas.width, canvas.height);
        $("map-legend").replaceChildren();
        $("map-axes").textContent = "";
        return;
      }
      $("map-meta").textContent = "";
      const field = { x: "map-x", y: "map-y", speed: "map-speed", band: "map-band", range: "map-band" }[e.field];
      if (field) $(field).classList.add("invalid");
      $("map-message").textContent = e.message;
      $("map-message").hidden = false;
      const canvas = $("map-canvas");
      canvas.getContext("2d").clearRect(0, 0, canvas.width, canvas.height);
      $("map-legend").replaceChildren();
    } finally {
      clearInterval(ticking);
      if (mine === this.sequence) $("map-cancel").hidden = true;
    }
  }

  /** The value range of the colour scale: the 1st to the 99th percentile of the finite values. */
  scale(values) {
    const sorted = values.filter(Number.isFinite).sort((a, b) => a - b);
    if (sorted.length === 0) return null;
    const at = (f) => sorted[Math.min(sorted.length - 1, Math.max(0, Math.round(f * (sorted.length - 1))))];
    const lo = at(0.01);
    const hi = at(0.99);
    return hi > lo ? [lo, hi] : [lo, lo + 1];
  }

  draw() {
    const a = this.answer;
    if (!a) return;
    if (!a.y) {
      this.drawStudy();
      return;
    }
    const quantity = $("map-quantity").value;
    const q = MAP_QUANTITIES[quantity];
    const { nx, ny } = a;
    const cells = Array.from({ length: nx * ny }, (_, k) => cell(a, quantity, k));
    const range = this.scale(cells.filter((c) => c.kind === "value").map((c) => c.value));
    // The largest real part: a diverging scale, white at zero, each side to its own extreme
    // (stable blue below, unstable red above), so that a faintly stable design still shows.
    const diverging = quantity === "max_real" && range !== null;
    this.range = range;
    const colourOf = (v) => (diverging ? divergingRamp(divergingPlace(v, range)) : ramp(range ? (v - range[0]) / (range[1] - range[0]) : 0.5));
    $("map-canvas").setAttribute("aria-label", `Design map: ${q.words} over ${a.x.name} and ${a.y.name}`);
    const host = $("map-plot");
    const width = Math.max(260, Math.min(host.clientWidth || 600, 900));
    // As tall as the panel leaves room for, in proportion to the width.
    const room = ($("panel-map").clientHeight || 600) - 190;
    const height = Math.round(Math.max(220, Math.min(width * 0.62, Math.max(room, 220), 560)));
    const { g, area } = frame(width, height);
    this.area = area;
    const w = area.w / nx;
    const h = area.h / ny;
    for (let iy = 0; iy < ny; iy++) {
      for (let ix = 0; ix < nx; ix++) {
        const c = cells[iy * nx + ix];
        g.fillStyle =
          c.kind === "value" ? colourOf(c.value) : c.kind === "unbounded" ? UNBOUNDED : c.kind === "none" ? NONE : c.kind === "undecided" ? UNDECIDED : INVALID;
        // y up: the first row at the bottom.
        g.fillRect(area.x + Math.floor(ix * w), area.y + Math.floor(area.h - (iy + 1) * h), Math.ceil(w), Math.ceil(h));
      }
    }
    // The designs self-stable over the band, outlined: an edge wherever one qualifies and its
    // neighbour (or the map's edge) does not.
    if (quantity === "band_margin" && a.stable_over) {
      const qualifies = (ix, iy) => ix >= 0 && iy >= 0 && ix < nx && iy < ny && a.status[iy * nx + ix] === "ok" && a.stable_over[iy * nx + ix] === true;
      const px = (ix) => area.x + ix * w;
      const py = (iy) => area.y + area.h - iy * h;
      g.strokeStyle = "#111827";
      g.lineWidth = 1.5;
      g.beginPath();
      for (let iy = 0; iy < ny; iy++) {
        for (let ix = 0; ix < nx; ix++) {
          if (!qualifies(ix, iy)) continue;
          if (!qualifies(ix - 1, iy)) (g.moveTo(px(ix), py(iy)), g.lineTo(px(ix), py(iy + 1)));
          if (!qualifies(ix + 1, iy)) (g.moveTo(px(ix + 1), py(iy)), g.lineTo(px(ix + 1), py(iy + 1)));
          if (!qualifies(ix, iy - 1)) (g.moveTo(px(ix), py(iy)), g.lineTo(px(ix + 1), py(iy)));
          if (!qualifies(ix, iy + 1)) (g.moveTo(px(ix), py(iy + 1)), g.lineTo(px(ix + 1), py(iy + 1)));
        }
      }
      g.stroke();
      $("map-canvas").dataset.qualifying = String(a.stable_over.filter((o, k) => o === true && a.status[k] === "ok").length);
    } else {
      delete $("map-canvas").dataset.qualifying;
    }
    // Axes: each cell centred on its grid value.
    const xAt = (v) => area.x + ((v - a.x.start) / (a.x.stop - a.x.start || 1)) * (area.w - w) + w / 2;
    const yAt = (v) => area.y + area.h - (((v - a.y.start) / (a.y.stop - a.y.start || 1)) * (area.h - h) + h / 2);
    const lo = (axis) => Math.min(axis.start, axis.stop);
    const hi = (axis) => Math.max(axis.start, axis.stop);
    axes(g, area, { lo: lo(a.x), hi: hi(a.x), name: a.x.name }, { lo: lo(a.y), hi: hi(a.y), name: a.y.name }, xAt, yAt, height);
    // The base design.
    const [bx, by] = a.base ?? [];
    if (Number.isFinite(bx) && Number.isFinite(by)) {
      g.strokeStyle = "#111827";
      g.lineWidth = 2;
      g.beginPath();
      g.arc(xAt(bx), yAt(by), 6, 0, 2 * Math.PI);
      g.stroke();
    }
    const counts = { ok: 0, invalid: 0, accuracy_lost: 0 };
    for (const s of a.status) counts[s] = (counts[s] ?? 0) + 1;
    $("map-meta").textContent = `${this.label()}: ${q.words} over ${nx} × ${ny} designs (${counts.ok} computed${counts.invalid ? `, ${counts.invalid} invalid` : ""}${counts.accuracy_lost ? `, ${counts.accuracy_lost} with accuracy lost` : ""}) in ${num(this.seconds ?? 0, 2)} s`;
    this.drawLegend(q, range, quantity, diverging);
    $("map-axes").textContent = `x: ${axisText(a.x)} · y: ${axisText(a.y)} · ○ the bicycle itself`;
  }

  /** A one-parameter study: v_w (blue) and v_c (red) against the parameter, the band shaded. */
  drawStudy() {
    const a = this.answer;
    const host = $("map-plot");
    const width = Math.max(260, Math.min(host.clientWidth || 600, 900));
    const room = ($("panel-map").clientHeight || 600) - 190;
    const height = Math.round(Math.max(220, Math.min(width * 0.5, Math.max(room, 220), 460)));
    const canvas = $("map-canvas");
    const { g, area } = frame(width, height);
    this.area = area;
    const n = a.nx;
    const xs = Array.from({ length: n }, (_, i) => (n > 1 ? a.x.start + ((a.x.stop - a.x.start) * i) / (n - 1) : a.x.start));
    const finite = [...a.v_w, ...a.v_c].filter(Number.isFinite);
    const top = finite.length ? Math.max(...finite) * 1.08 : 10;
    const xlo = Math.min(a.x.start, a.x.stop);
    const xhi = Math.max(a.x.start, a.x.stop);
    const xAt = (v) => area.x + ((v - xlo) / (xhi - xlo || 1)) * area.w;
    const yAt = (v) => area.y + area.h - (Math.min(v, top) / top) * area.h;
    // The self-stable band, a polygon per run of consecutive stable designs.
    g.fillStyle = "rgba(16, 185, 129, 0.22)";
    let run = [];
    const flush = () => {
      if (run.length > 1) {
        g.beginPath();
        run.forEach(([x, lo2], k) => (k ? g.lineTo(xAt(x), yAt(lo2)) : g.moveTo(xAt(x), yAt(lo2))));
        [...run].reverse().forEach(([x, , hi2]) => g.lineTo(xAt(x), yAt(hi2)));
        g.closePath();
        g.fill();
      }
      run = [];
    };
    for (let i = 0; i < n; i++) {
      if (a.status[i] === "ok" && a.stable[i] && Number.isFinite(a.stable_from[i])) run.push([xs[i], a.stable_from[i], a.stable_unbounded[i] ? top : a.stable_to[i] ?? top]);
      else flush();
    }
    flush();
    const line = (values, colour) => {
      g.strokeStyle = colour;
      g.lineWidth = 2;
      g.beginPath();
      let down = false;
      values.forEach((v, i) => {
        if (!Number.isFinite(v)) {
          down = false;
          return;
        }
        if (down) g.lineTo(xAt(xs[i]), yAt(v));
        else g.moveTo(xAt(xs[i]), yAt(v));
        down = true;
      });
      g.stroke();
    };
    line(a.v_w, "#2563eb");
    line(a.v_c, "#dc2626");
    axes(g, area, { lo: xlo, hi: xhi, name: a.x.name }, { lo: 0, hi: top, name: "speed v [m/s]" }, xAt, yAt, height);
    const [bx] = a.base ?? [];
    if (Number.isFinite(bx)) {
      g.strokeStyle = "#111827";
      g.setLineDash([4, 3]);
      g.beginPath();
      g.moveTo(xAt(bx), area.y);
      g.lineTo(xAt(bx), area.y + area.h);
      g.stroke();
      g.setLineDash([]);
    }
    canvas.setAttribute("aria-label", `v_w and v_c against ${a.x.name}`);
    const ok = a.status.filter((st) => st === "ok").length;
    $("map-meta").textContent = `${this.label()}: v_w and v_c against ${a.x.name}, ${n} designs (${ok} computed) in ${num(this.seconds ?? 0, 2)} s`;
    $("map-axes").textContent = `x: ${axisText(a.x)} · dashed: the bicycle itself`;
    const legend = $("map-legend");
    const swatch = (colour, text) => html("span", { class: "map-swatch" }, html("span", { class: "dot", style: `background:${colour}` }), html("span", { text }));
    legend.replaceChildren(swatch("#2563eb", "weave speed v_w"), swatch("#dc2626", "capsize speed v_c"), swatch("rgba(16, 185, 129, 0.35)", "self-stable"));
  }

  drawLegend(q, range, quantity, diverging) {
    const legend = $("map-legend");
    legend.replaceChildren();
    if (range) {
      // On the diverging scale the bar is linear in the value, its white stop at zero.
      const stops = diverging
        ? [0, 0.25, 0.5, 0.75, 1].map((f) => {
            const v = range[0] + f * (range[1] - range[0]);
            return `${divergingRamp(divergingPlace(v, range))} ${f * 100}%`;
          })
        : [0, 0.25, 0.5, 0.75, 1].map(ramp);
      if (diverging && range[0] < 0 && range[1] > 0) stops.push(`${divergingRamp(0.5)} ${(-range[0] / (range[1] - range[0])) * 100}%`);
      if (diverging) stops.sort((a, b) => parseFloat(a.split(") ")[1]) - parseFloat(b.split(") ")[1]));
      const bar = html("span", { class: "map-ramp", style: `background: linear-gradient(to right, ${stops.join(", ")})` });
      legend.append(html("span", { text: `${num(range[0], 3)} ` }), bar, html("span", { text: ` ${num(range[1], 3)} ${q.unit}` }));
      if (diverging) legend.append(html("span", { text: " (white: 0; stable below, unstable above)" }));
    }
    const swatch = (colour, text) => html("span", { class: "map-swatch" }, html("span", { class: "dot", style: `background:${colour}` }), html("span", { text }));
    if (quantity === "band_margin" && this.answer?.band) {
      const [lo, hi] = this.answer.band;
      legend.append(
        html("span", { class: "map-swatch" }, html("span", { class: "dot outline" }), html("span", { text: `self-stable at every speed ${num(lo, 4)}–${num(hi, 4)} m/s` })),
        swatch(NONE, "none (not self-stable over the band)"),
        swatch(UNDECIDED, "undecided (round-off)"),
        swatch(INVALID, "invalid design"),
      );
      return;
    }
    legend.append(swatch(NONE, "none (not self-stable)"), swatch(UNBOUNDED, "unbounded"), swatch(INVALID, "invalid design"));
  }

  /** The cell under a pointer event: {ix, iy, where} ("trail = 0.1, head_angle_deg = 70"), or null. */
  cellAt(e) {
    const a = this.answer;
    if (!a || !this.area) return null;
    const canvas = $("map-canvas");
    const box = canvas.getBoundingClientRect();
    const area = this.area;
    // Drawn narrower than its own size (a phone: max-width 100%), the canvas is scaled.
    const scale = box.width / (parseFloat(canvas.style.width) || box.width);
    const fx = ((e.clientX - box.left) / scale - area.x) / area.w;
    const fy = 1 - ((e.clientY - box.top) / scale - area.y) / area.h;
    if (fx < 0 || fx > 1 || fy < 0 || fy > 1) return null;
    const at = (axis, i) => (axis.count > 1 ? axis.start + ((axis.stop - axis.start) * i) / (axis.count - 1) : axis.start);
    if (!a.y) {
      // A study: the nearest design along x.
      const ix = Math.min(a.nx - 1, Math.max(0, Math.round(fx * (a.nx - 1))));
      return { ix, iy: 0, where: `${a.x.name} = ${num(at(a.x, ix), 4)}` };
    }
    const ix = Math.min(a.nx - 1, Math.max(0, Math.floor(fx * a.nx)));
    const iy = Math.min(a.ny - 1, Math.max(0, Math.floor(fy * a.ny)));
    return { ix, iy, where: `${a.x.name} = ${num(at(a.x, ix), 4)}, ${a.y.name} = ${num(at(a.y, iy), 4)}` };
  }

  hover(e) {
    this.readCell(this.cellAt(e));
  }

  /** The read-out of cell `c0` (from cellAt), or none. */
  readCell(c0) {
    const a = this.answer;
    if (!c0) {
      $("map-readout").textContent = "";
      return;
    }
    if (!a.y) {
      const k = c0.ix;
      const speeds = (v) => (Number.isFinite(v) ? `${num(v, 4)} m/s` : "none");
      const band = a.status[k] !== "ok" ? `not computed: ${cell(a, "v_w", k).reason}` : a.stable[k] ? `self-stable from ${speeds(a.stable_from[k])} to ${a.stable_unbounded[k] ? "∞" : speeds(a.stable_to[k])}` : "not self-stable";
      $("map-readout").textContent = `${c0.where}: v_w ${speeds(a.v_w[k])}, v_c ${speeds(a.v_c[k])}; ${band} (click to load this design)`;
      return;
    }
    const quantity = $("map-quantity").value;
    const c = cell(a, quantity, c0.iy * a.nx + c0.ix);
    const k = c0.iy * a.nx + c0.ix;
    let value =
      c.kind === "value" ? `${num(c.value, 4)} ${MAP_QUANTITIES[quantity].unit}` : c.kind === "unbounded" ? "unbounded" : c.kind === "none" ? "none" : c.kind === "undecided" ? "undecided (round-off)" : `not computed: ${c.reason}`;
    if (quantity === "band_margin" && a.band && a.status[k] === "ok") {
      const band = `${num(a.band[0], 4)}–${num(a.band[1], 4)} m/s`;
      const above = a.band_margin_above_unbounded[k] ? "∞" : `${num(a.band_margin_above[k], 4)} m/s`;
      value =
        a.stable_over[k] === true
          ? `self-stable over ${band}, margins ${num(a.band_margin_below[k], 4)} m/s below and ${above} above`
          : a.stable_over[k] === false
            ? `not self-stable over ${band}`
            : `undecided over ${band} (round-off leaves speeds of it unclassified)`;
    }
    $("map-readout").textContent = `${c0.where}: ${value} (click to load this design)`;
  }

  /** A tap on a cell: its read-out, and a button that loads that design. */
  offer(e) {
    const c0 = this.tapped ?? this.cellAt(e);
    if (!c0 || !this.answer) return;
    this.readCell(c0);
    const readout = $("map-readout");
    readout.textContent = readout.textContent.replace(/ \(click to load this design\)$/, "");
    if (this.answer.status[c0.iy * this.answer.nx + c0.ix] === "invalid") return;
    const button = html("button", { type: "button", class: "btn tiny", text: "Load this design", "data-testid": "map-load" });
    button.addEventListener("click", () => this.load(e, c0));
    readout.append(" ", button);
  }

  /** A click on a cell: that design (the server sets the axes' parameters) into the editor. */
  async load(e, cell = null) {
    const a = this.answer;
    const c0 = cell ?? this.cellAt(e);
    if (!c0 || a.status[c0.iy * a.nx + c0.ix] === "invalid") return;
    try {
      const request = { bike: this.bike(), x: this.asked.x, index: c0.iy * a.nx + c0.ix };
      if (this.asked.y) request.y = this.asked.y;
      const { bike } = await api.mapDesign(request);
      this.onLoad(bike, c0.where);
    } catch (err) {
      $("map-message").textContent = err.message;
      $("map-message").hidden = false;
    }
  }
}

/** The drawing frame shared by the map and the study: the canvas sized, the plot area. */
function frame(width, height) {
  const canvas = $("map-canvas");
  const ratio = window.devicePixelRatio || 1;
  canvas.width = Math.round(width * ratio);
  canvas.height = Math.round(height * ratio);
  canvas.style.width = `${width}px`;
  canvas.style.height = `${height}px`;
  const g = canvas.getContext("2d");
  g.setTransform(ratio, 0, 0, ratio, 0, 0);
  g.clearRect(0, 0, width, height);
  const area = { x: MARGIN.left, y: MARGIN.top, w: width - MARGIN.left - MARGIN.right, h: height - MARGIN.top - MARGIN.bottom };
  canvas.dataset.area = JSON.stringify(area);
  return { g, area };
}

/** Ticks and axis names around `area`; `xAt`, `yAt` map values to pixels. */
function axes(g, area, x, y, xAt, yAt, height) {
  g.strokeStyle = "#9ca3af";
  g.lineWidth = 1;
  g.strokeRect(area.x + 0.5, area.y + 0.5, area.w - 1, area.h - 1);
  g.fillStyle = "#374151";
  g.font = `11px ${FONT}`;
  const xt = ticks(x.lo, x.hi, Math.max(2, Math.floor(area.w / 70)));
  g.textAlign = "center";
  g.textBaseline = "top";
  for (const t of xt) {
    const px = xAt(t);
    g.fillRect(px, area.y + area.h, 1, 4);
    g.fillText(tickLabel(t, xt), px, area.y + area.h + 6);
  }
  const yt = ticks(y.lo, y.hi, Math.max(2, Math.floor(area.h / 45)));
  g.textAlign = "right";
  g.textBaseline = "middle";
  for (const t of yt) {
    const py = yAt(t);
    g.fillRect(area.x - 4, py, 4, 1);
    g.fillText(tickLabel(t, yt), area.x - 6, py);
  }
  g.textAlign = "center";
  g.textBaseline = "bottom";
  g.fillText(x.name, area.x + area.w / 2, height - 1);
  g.save();
  g.translate(11, area.y + area.h / 2);
  g.rotate(-Math.PI / 2);
  g.textBaseline = "middle";
  g.fillText(y.name, 0, 0);
  g.restore();
}

function axisText(axis) {
  return `${axis.name} from ${num(axis.start, 4)} to ${num(axis.stop, 4)} (${axis.count} points)`;
}
