// The critical-speeds table: v_d, v_w, v_c and the self-stable ranges, for the design and the
// one it is compared with.

import { html, fixed } from "./format.js";

function speed(v) {
  return v === null || v === undefined ? "none" : fixed(v, 4);
}

function ranges(c) {
  if (!c) return "–";
  if (c.stable_speed_ranges.length === 0) return "nowhere";
  return c.stable_speed_ranges
    .map(([a, b]) => `${fixed(a, 3)} – ${fixed(b, 3)}${b >= c.range[1] ? "+" : ""}`)
    .join(", ");
}

/** Fills `container` with the table for `primary` and optional `secondary` ({label, critical}). */
export function drawCritical(container, primary, secondary, { stale = false } = {}) {
  const rows = [
    ["weave", "v_w", (c) => speed(c?.weave_speed), "weave-speed", "the weave becomes stable above this speed", "#2563eb"],
    ["capsize", "v_c", (c) => speed(c?.capsize_speed), "capsize-speed", "the capsize mode becomes unstable above this speed", "#dc2626"],
    ["double root", "v_d", (c) => speed(c?.double_root_speed), "double-root-speed", "two real eigenvalues meet and become the weave pair", "#9ca3af"],
    ["ω at v_w", "rad/s", (c) => (c?.weave_frequency == null ? "–" : fixed(c.weave_frequency, 3)), "weave-frequency", "the weave's angular frequency |Im λ| at v_w", null],
    ["self-stable", "", (c) => ranges(c), "stable-ranges", "all eigenvalues have negative real parts", "#86efac"],
  ];
  const table = html("table", { class: `critical-table${stale ? " stale" : ""}` });
  const head = html("tr", {}, html("th", { class: "unit", text: "m/s" }), html("th", { class: "primary", text: primary.label }));
  if (secondary) head.append(html("th", { class: "secondary", text: secondary.label }));
  table.append(html("thead", {}, head));
  const body = html("tbody");
  for (const [name, symbol, value, id, hint, colour] of rows) {
    const tr = html("tr", { title: hint, class: id === "stable-ranges" ? "stable" : "" });
    const dot = html("span", { class: "dot", style: `background:${colour ?? "transparent"}` });
    tr.append(html("td", { class: "what" }, dot, html("span", { text: name }), symbol ? html("span", { class: "symbol", text: ` ${symbol}` }) : ""));
    tr.append(html("td", { class: "value", "data-testid": id, text: value(primary.critical) }));
    if (secondary) tr.append(html("td", { class: "value secondary", "data-testid": `compare-${id}`, text: value(secondary.critical) }));
    body.append(tr);
  }
  table.append(body);
  const range = primary.critical?.range;
  const meta = document.getElementById("critical-meta");
  if (meta) meta.textContent = range ? `linear model, ${fixed(range[0], 1)} – ${fixed(range[1], 1)} m/s` : "";
  const open = primary.critical?.stable_speed_ranges.some(([, b]) => b >= range[1]);
  const note = html("p", { class: "note", text: range ? (open ? "“+”: still stable at the end of the plotted speeds." : "") : "Give a speed range to find the critical speeds." });
  container.replaceChildren(table, note);
}
