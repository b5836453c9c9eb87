// Number formatting and small DOM helpers shared by the views.

export const SVG_NS = "http://www.w3.org/2000/svg";

/** An SVG element with attributes; children appended in order. */
export function svg(tag, attrs = {}, ...children) {
  const el = document.createElementNS(SVG_NS, tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v !== undefined && v !== null) el.setAttribute(k, String(v));
  }
  for (const c of children) el.append(c);
  return el;
}

/** An HTML element with attributes (`text` sets textContent, `class` the class). */
export function html(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === undefined || v === null || v === false) continue;
    if (k === "text") el.textContent = v;
    else el.setAttribute(k, v === true ? "" : String(v));
  }
  for (const c of children) el.append(c);
  return el;
}

/** Fixed decimals with a true minus sign. */
export function fixed(x, digits) {
  if (x === null || x === undefined || !Number.isFinite(x)) return "–";
  const s = x.toFixed(digits);
  return s.startsWith("-") ? `−${s.slice(1)}` : s;
}

/** Four significant digits, for hover read-outs. */
export function sig(x) {
  if (!Number.isFinite(x)) return "–";
  const a = Math.abs(x);
  const s = a !== 0 && (a < 1e-3 || a >= 1e5) ? x.toExponential(3) : x.toFixed(Math.max(0, 3 - Math.floor(Math.log10(a || 1))));
  return s.startsWith("-") ? `−${s.slice(1)}` : s;
}

/** "Nice" tick values covering [lo, hi] with about `count` ticks. */
export function ticks(lo, hi, count) {
  const span = hi - lo;
  if (!(span > 0)) return [lo];
  const raw = span / Math.max(1, count);
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw) ?? 10 * mag;
  const out = [];
  for (let t = Math.ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step) {
    out.push(Math.abs(t) < step * 1e-9 ? 0 : t);
  }
  return out;
}

/**
 * Ticks of a logarithmic axis drawn in log₁₀ units over [lo, hi]: the decades, every k-th
 * when there are more than `count`, and 2 and 5 of each decade when fewer than three are seen.
 */
export function logTicks(lo, hi, count) {
  if (!(hi > lo)) return [lo];
  const first = Math.ceil(lo - 1e-9), last = Math.floor(hi + 1e-9);
  const decades = last - first + 1;
  const out = [];
  if (decades >= 3) {
    const every = Math.max(1, Math.ceil(decades / Math.max(1, count)));
    for (let k = first; k <= last; k += every) out.push(k);
    return out;
  }
  for (let k = Math.floor(lo); k <= Math.ceil(hi); k++) {
    for (const m of [1, 2, 5]) {
      const t = k + Math.log10(m);
      if (t >= lo - 1e-9 && t <= hi + 1e-9) out.push(t);
    }
  }
  return out.length ? out : ticks(lo, hi, count);
}

/** A tick label with just the decimals the step needs. */
export function tickLabel(t, all) {
  const step = all.length > 1 ? Math.abs(all[1] - all[0]) : 1;
  const digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9) + (step / 10 ** Math.floor(Math.log10(step)) === 2.5 ? 1 : 0));
  return fixed(t, digits);
}

/** A file name from a design name. */
export function slug(name) {
  return (name || "bicycle").toLowerCase().replace(/[^a-z0-9]+/g, "-").replace(/^-|-$/g, "") || "bicycle";
}

/** Offers `data` (string or Blob) as a download called `name`. */
export function download(name, data, type) {
  const blob = data instanceof Blob ? data : new Blob([data], { type });
  const url = URL.createObjectURL(blob);
  const a = html("a", { href: url, download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** A standalone SVG file's text from an <svg> element (hover layers removed). */
export function svgText(svgEl) {
  const clone = svgEl.cloneNode(true);
  clone.querySelectorAll("[data-export=skip]").forEach((n) => n.remove());
  clone.setAttribute("xmlns", SVG_NS);
  return `<?xml version="1.0" encoding="UTF-8"?>\n${new XMLSerializer().serializeToString(clone)}\n`;
}

/** A PNG (Blob) of an <svg> element at `scale` times its size, on white. */
export async function svgPng(svgEl, scale = 2) {
  const width = Number(svgEl.getAttribute("width"));
  const height = Number(svgEl.getAttribute("height"));
  const url = URL.createObjectURL(new Blob([svgText(svgEl)], { type: "image/svg+xml" }));
  try {
    const img = new Image();
    await new Promise((resolve, reject) => {
      img.onload = resolve;
      img.onerror = () => reject(new Error("the drawing could not be rendered"));
      img.src = url;
    });
    const canvas = html("canvas", { width: Math.round(width * scale), height: Math.round(height * scale) });
    const ctx = canvas.getContext("2d");
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
    return await new Promise((resolve) => canvas.toBlob(resolve, "image/png"));
  } finally {
    URL.revokeObjectURL(url);
  }
}

export const FONT = "system-ui, -apple-system, 'Segoe UI', Roboto, 'Helvetica Neue', Arial, sans-serif";

/** A true minus sign. */
export function minus(s) {
  return s.startsWith("-") ? `−${s.slice(1)}` : s;
}

/**
 * A number as a person reads it: `digits` significant digits, trailing zeros dropped
 * (25.759999999999998 → "25.76"), exponent form only for very large or small magnitudes.
 */
export function num(x, digits = 4) {
  if (x === null || x === undefined || !Number.isFinite(x)) return "–";
  if (x === 0) return "0";
  const a = Math.abs(x);
  if (a < 1e-4 || a >= 1e7) return minus(x.toExponential(digits - 1).replace(/\.?0+e/, "e"));
  let s = x.toPrecision(digits);
  if (s.includes("e")) s = Number(s).toString();
  if (s.includes(".")) s = s.replace(/0+$/, "").replace(/\.$/, "");
  return minus(s);
}

/** A value for an input box: 12 significant digits, so that round-off never shows. */
export function inputText(x) {
  if (!Number.isFinite(x)) return "";
  const s = Number(x.toPrecision(12)).toString();
  return s;
}

/** A time span in words: "1.4 s", "0.25 s", "12 s", "2 min". */
export function seconds(t) {
  if (!Number.isFinite(t)) return "–";
  if (t >= 120) return `${num(t / 60, 2)} min`;
  return `${num(t, t < 10 ? 2 : 3)} s`;
}

/** A colour along a perceptually even ramp (viridis-like), for `f` in [0, 1]. */
export function ramp(f) {
  const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  const t = Math.max(0, Math.min(1, f)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(t));
  const u = t - i;
  const c = stops[i].map((a, k) => Math.round(a + (stops[i + 1][k] - a) * u));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}
