// The critical-speeds table: v_d, v_w, v_c and the self-stable ranges, one column per design
// (the edited one first, then those it is compared with).

import { html, fixed, num } from "./format.js";
import { COMPARE_COLOURS } from "./plot.js";

/**
 * What the sweep says about a mode where the critical speed is absent from the range: the sign
 * of its real part over the whole range ("unstable at every speed" reads differently from
 * "none", which would suggest it never goes wrong).
 */
function throughout(eigen, mode) {
  const cols = eigen?.eigenvalues.filter((c) => c.mode === mode) ?? [];
  if (!cols.length) return null;
  const res = cols.flatMap((c) => c.re);
  if (res.every((x) => x > 0)) return "unstable";
  if (res.every((x) => x < 0)) return "stable";
  return null;
}

/** The intervals the certificate could not decide, in words ("" when there are none). */
function undecided(c) {
  const u = c?.unresolved ?? [];
  if (!u.length) return "";
  return u.map(([a, b]) => (b === null || b >= 1e300 ? `above ${fixed(a, 3)}` : `${fixed(a, 3)} – ${fixed(b, 3)}`)).join(", ");
}

/** " ± σ" where the bicycle's parameters carry standard deviations ("" otherwise). */
function pm(sigma) {
  return Number.isFinite(sigma) && sigma > 0 ? ` ± ${num(sigma, 2)}` : "";
}

/** km/h in a m/s: the page's one conversion back (editor.js reads "20 km/h" as 20 / 3.6 m/s). */
const KMH_PER_MPS = 3.6;

/** " (15.45 km/h)" after a speed in m/s where the speeds were typed in km/h ("" otherwise). */
function alsoKmh(kmh, v, sigma) {
  return kmh && Number.isFinite(v) ? ` (${fixed(v * KMH_PER_MPS, 2)}${pm(sigma * KMH_PER_MPS)} km/h)` : "";
}

function speed(v, eigen, mode, range, c, sigma, kmh = false) {
  if (v !== null && v !== undefined) return `${fixed(v, 4)}${pm(sigma)}${alsoKmh(kmh, v, sigma)}`;
  // Where the certificate could not decide, "none" would contradict it.
  const open = undecided(c);
  if (open) return `undecided in ${open}`;
  const where = range ? ` ${fixed(range[0], 1)}–${fixed(range[1], 1)}` : "";
  const state = mode && throughout(eigen, mode);
  if (state === "unstable") return `none: unstable at every speed${where}`;
  if (state === "stable") return `none: stable at every speed${where}`;
  return `none in${where}`;
}

/** The library's words for a speed round-off could not certify: its enclosure, marked. */
function notCertified(reason) {
  const at = /\[([^,\]]+),\s*([^\]]+)\]/.exec(reason);
  const [a, b] = at ? [Number(at[1]), Number(at[2])] : [];
  return Number.isFinite(a) && Number.isFinite(b) ? `not certified: in [${num(a, 8)}, ${num(b, 8)}]` : "not certified (round-off)";
}

function ranges(c, kmh = false) {
  if (!c) return "–";
  const open = undecided(c);
  if (c.stable_speed_ranges.length === 0) return open ? `undecided in ${open}; nowhere else` : "nowhere";
  const list = (scale, digits, withSigma) =>
    c.stable_speed_ranges
      .map(([a, b], k) => {
        const [sa, sb] = withSigma ? c.stable_speed_ranges_sigma?.[k] ?? [] : [];
        return `${fixed(a * scale, digits)}${pm(sa)} – ${fixed(b * scale, digits)}${pm(sb)}${b >= c.range[1] ? "+" : ""}`;
      })
      .join(", ");
  return list(1, 3, true) + (kmh ? ` (${list(KMH_PER_MPS, 2, false)} km/h)` : "");
}

const weaveText = (c, e, kmh = false) => speed(c?.weave_speed, e, "weave", c?.range, c, c?.weave_speed_sigma, kmh);
const capsizeText = (c, e, kmh = false) => speed(c?.capsize_speed, e, "capsize", c?.range, c, c?.capsize_speed_sigma, kmh);

/** What the table shows of one design ({eigen}) for v_w, v_c and the self-stable ranges. */
export function criticalSummary(eigen) {
  const c = eigen?.critical ?? null;
  return { weave: weaveText(c, eigen), capsize: capsizeText(c, eigen), stable: ranges(c) };
}

/**
 * Fills `container` with the table for `designs` ([{label, eigen}], the first edited). `kmh`:
 * the speeds were typed in km/h, so each speed is also given in km/h after its m/s.
 */
export function drawCritical(container, designs, { stale = false, reason = null, kmh = false } = {}) {
  const rows = [
    ["weave", "v_w", (c, e) => weaveText(c, e, kmh), "weave-speed", "the weave becomes stable above this speed", "#2563eb"],
    ["capsize", "v_c", (c, e) => capsizeText(c, e, kmh), "capsize-speed", "the capsize mode becomes unstable above this speed", "#dc2626"],
    // Where round-off cannot certify v_d the library says where it lies: never "none".
    ["double root", "v_d", (c) => (c?.double_root_unavailable ? notCertified(c.double_root_unavailable) : speed(c?.double_root_speed, null, null, c?.range, c, c?.double_root_speed_sigma, kmh)), "double-root-speed", "two real eigenvalues meet and become the weave pair", "#9ca3af"],
    ["ω at v_w", "rad/s", (c) => (c?.weave_frequency == null ? "–" : fixed(c.weave_frequency, 3)), "weave-frequency", "the weave's angular frequency |Im λ| at v_w", null],
    ["self-stable", "", (c) => ranges(c, kmh), "stable-ranges", "all eigenvalues have negative real parts", "#86efac"],
  ];
  const table = html("table", { class: `critical-table${stale ? " stale" : ""}`, "data-columns": String(designs.length) });
  const head = html("tr", {}, html("th", { class: "unit", scope: "col", text: "m/s" }));
  designs.forEach((d, k) => head.append(html("th", { scope: "col", class: k ? "secondary" : "primary", style: k ? `color:${COMPARE_COLOURS[(k - 1) % COMPARE_COLOURS.length]}` : null, text: d.label, title: d.label })));
  table.append(html("thead", {}, head));
  const body = html("tbody");
  for (const [name, symbol, value, id, hint, colour] of rows) {
    const tr = html("tr", { title: hint, class: id === "stable-ranges" ? "stable" : "" });
    const dot = html("span", { class: "dot", style: `background:${colour ?? "transparent"}` });
    tr.append(html("th", { scope: "row", class: "what" }, dot, html("span", { text: name }), symbol ? html("span", { class: "symbol", text: ` ${symbol}` }) : ""));
    designs.forEach((d, k) => {
      const c = d.eigen?.critical ?? null;
      const why = id === "double-root-speed" ? c?.double_root_unavailable ?? null : null;
      tr.append(html("td", { class: `value${k ? " secondary" : ""}${why ? " uncertified" : ""}`, title: why, "data-testid": k === 0 ? id : k === 1 ? `compare-${id}` : `compare${k}-${id}`, text: value(c, d.eigen) }));
    });
    body.append(tr);
  }
  table.append(body);
  const range = designs[0].eigen?.critical?.range;
  const meta = document.getElementById("critical-meta");
  // The header says what the fields say: veiled results are named as the last ones computed.
  const typed = range && kmh ? ` (${num(range[0] * KMH_PER_MPS)} – ${num(range[1] * KMH_PER_MPS)} km/h)` : "";
  if (meta) meta.textContent = range ? `linear model, ${num(range[0])} – ${num(range[1])} m/s${typed}${stale ? ` (${reason ?? "not recomputed"}; last computed)` : ""}` : "";
  const open = designs[0].eigen?.critical?.stable_speed_ranges.some(([, b]) => b >= range[1]);
  const note = html("p", { class: "note", text: range ? (open ? "“+”: still stable at the end of the plotted speeds." : "") : "Give a speed range to find the critical speeds." });
  container.replaceChildren(html("div", { class: "table-scroll" }, table), note);
}

/**
 * The closed loop's certified stable ranges as a sentence, for the Control tab: "This
 * controller stabilizes the bicycle from 0.8067 m/s (to the end of the plotted speeds, 10 m/s)."
 * `eigen`: /api/linear/closed_loop's answer. The speeds to four decimals, as the table's.
 */
export function stabilizesText(eigen) {
  if (!eigen) return "";
  if (eigen.critical_unavailable) return `The stable speeds could not be certified: ${eigen.critical_unavailable}`;
  const c = eigen.critical;
  if (!c) return "Give a range of speeds to find where this controller stabilizes the bicycle.";
  const [lo, hi] = c.range;
  const open = undecided(c);
  const tail = open ? ` Undecided (round-off) in ${open}.` : "";
  const r = c.stable_speed_ranges;
  if (!r.length) return `This controller does not stabilize the bicycle at any speed from ${num(lo)} to ${num(hi)} m/s.${tail}`;
  if (r.length === 1 && r[0][0] <= lo && r[0][1] >= hi) return `This controller stabilizes the bicycle at every speed plotted, from ${num(lo)} to ${num(hi)} m/s.${tail}`;
  if (r.length === 1 && r[0][1] >= hi) return `This controller stabilizes the bicycle from ${fixed(r[0][0], 4)} m/s (to the end of the plotted speeds, ${num(hi)} m/s).${tail}`;
  const list = r.map(([a, b]) => `${fixed(a, 4)} – ${fixed(b, 4)}${b >= hi ? "+" : ""}`).join(", ");
  return `This controller stabilizes the bicycle from ${list} m/s${r.some(([, b]) => b >= hi) ? " (“+”: to the end of the plotted speeds)" : ""}.${tail}`;
}
