// The Sensitivity tab: how much each parameter of the bicycle's own form moves the weave speed
// v_w, the capsize speed v_c and the width of the self-stable range (POST /api/sensitivity,
// what `whipple sensitivity` prints: exact derivatives from dual numbers, no finite
// differences), as a tornado of elasticities (d ln v / d ln p: the per cent change of the speed
// for one per cent of the parameter) and a table; with the critical speeds' standard deviations
// when the bicycle's file gives its parameters' uncertainties.

import { api } from "./api.js";
import { html, svg, num, slug, download, FONT } from "./format.js";
import { MODE_COLOURS } from "./plot.js";

const $ = (id) => document.getElementById(id);

/** The quantities a tornado can show: the response's field names and how they read. */
export const QUANTITIES = {
  weave: { derivative: "weave_speed", elasticity: "weave_speed_elasticity", symbol: "v_w", words: "weave speed", colour: MODE_COLOURS.weave },
  capsize: { derivative: "capsize_speed", elasticity: "capsize_speed_elasticity", symbol: "v_c", words: "capsize speed", colour: MODE_COLOURS.capsize },
  width: { derivative: "stable_width", elasticity: "stable_width_elasticity", symbol: "v_c − v_w", words: "width of the self-stable range", colour: "#059669" },
};

/** How many parameters the tornado shows (the table lists them all). */
const SHOWN = 12;

/** The parameters sorted by the size of their elasticity for `quantity` (undefined ones last). */
export function ranked(parameters, quantity) {
  const key = QUANTITIES[quantity].elasticity;
  const size = (p) => (Number.isFinite(p[key]) ? Math.abs(p[key]) : -1);
  return [...parameters].sort((a, b) => size(b) - size(a));
}

export class SensitivityPanel {
  /** `bike()` gives the current bicycle, `label()` its name. */
  constructor({ bike, label, onChange }) {
    this.bike = bike;
    this.label = label;
    this.onChange = onChange ?? (() => {});
    this.answer = null;
    this.quantity = "weave";
    $("sens-quantity").addEventListener("change", (e) => {
      this.quantity = e.target.value in QUANTITIES ? e.target.value : "weave";
      this.render();
      this.onChange();
    });
    $("sens-csv").addEventListener("click", () => this.downloadCsv());
  }

  /** The quantity the tornado shows (from a link). */
  setQuantity(quantity) {
    this.quantity = quantity in QUANTITIES ? quantity : "weave";
    $("sens-quantity").value = this.quantity;
  }

  /** Asks the server for the current bicycle's sensitivities and shows them. */
  async compute() {
    const mine = (this.sequence = (this.sequence ?? 0) + 1);
    $("sens-meta").textContent = "computing…";
    try {
      const answer = await api.sensitivity(this.bike());
      if (mine !== this.sequence) return;
      $("sens-message").hidden = true;
      this.answer = answer;
      this.render();
    } catch (e) {
      if (mine !== this.sequence) return;
      this.answer = null;
      $("sens-meta").textContent = "";
      $("sens-message").textContent = e.message;
      $("sens-message").hidden = false;
      $("sens-plot").replaceChildren();
      $("sens-table").replaceChildren();
    }
  }

  render() {
    const a = this.answer;
    if (!a) return;
    const q = QUANTITIES[this.quantity];
    const c = a.critical ?? {};
    const speed = (v, sigma) => (Number.isFinite(v) ? `${num(v, 4)}${Number.isFinite(sigma) && sigma > 0 ? ` ± ${num(sigma, 2)}` : ""} m/s` : "none");
    $("sens-meta").textContent = `${this.label()} (${a.form === "jbike6" ? "JBike6" : "benchmark"} form): v_w ${speed(c.weave_speed, a.weave_speed_sigma)}, v_c ${speed(c.capsize_speed, a.capsize_speed_sigma)}`;
    $("sens-quantity").value = this.quantity;
    const rows = ranked(a.parameters, this.quantity);
    this.drawTornado(rows.slice(0, SHOWN).filter((p) => Number.isFinite(p[q.elasticity])), q);
    this.drawTable(rows);
    const warnings = (a.warnings ?? []).map((w) => w.message).filter(Boolean);
    $("sens-warnings").textContent = warnings.join(" ");
    $("sens-warnings").hidden = warnings.length === 0;
  }

  /** Horizontal bars of the elasticities, largest first, centred on zero. */
  drawTornado(rows, q) {
    const host = $("sens-plot");
    host.replaceChildren();
    if (rows.length === 0) {
      host.append(html("p", { class: "note", text: `The ${q.words} is not defined for this bicycle, so it has no sensitivities.` }));
      return;
    }
    const width = Math.max(320, host.clientWidth || 640);
    const bar = 22;
    const top = 28;
    const left = Math.min(150, width * 0.3);
    const right = 16;
    const height = top + rows.length * bar + 28;
    const largest = Math.max(...rows.map((p) => Math.abs(p[q.elasticity])), 1e-12);
    const half = (width - left - right) / 2;
    const x0 = left + half;
    // Room beside the longest bar for its value.
    const x = (e) => x0 + (e / largest) * half * 0.75;
    const el = svg("svg", { width, height, viewBox: `0 0 ${width} ${height}`, role: "img", "aria-label": `Elasticities of the ${q.words}`, "data-testid": "sens-tornado", "font-family": FONT, "font-size": 12 });
    el.append(svg("text", { x: 4, y: 16, fill: "#374151", "font-weight": 600 }, document.createTextNode(`elasticity of the ${q.words}, d ln ${q.symbol} / d ln p`)));
    el.append(svg("line", { x1: x0, x2: x0, y1: top - 4, y2: height - 24, stroke: "#9ca3af" }));
    rows.forEach((p, k) => {
      const e = p[q.elasticity];
      const y = top + k * bar;
      const [a, b] = [x(0), x(e)].sort((m, n) => m - n);
      el.append(svg("text", { x: left - 8, y: y + bar * 0.68, "text-anchor": "end", fill: "#111827" }, document.createTextNode(p.symbol || p.key)));
      const rect = svg("rect", { x: a, y: y + 3, width: Math.max(1, b - a), height: bar - 6, fill: q.colour, opacity: 0.85, "data-key": p.key });
      rect.append(svg("title", {}, document.createTextNode(`${p.key} = ${num(p.value, 6)} ${p.unit}: ${p.description}; elasticity ${num(e, 4)}, d${q.symbol}/d${p.key} = ${num(p[q.derivative], 4)}`)));
      el.append(rect);
      const outside = e >= 0 ? b + 4 : a - 4;
      el.append(svg("text", { x: outside, y: y + bar * 0.68, "text-anchor": e >= 0 ? "start" : "end", fill: "#374151", "font-size": 11 }, document.createTextNode(num(e, 3))));
    });
    el.append(svg("text", { x: x0, y: height - 8, "text-anchor": "middle", fill: "#6b7280", "font-size": 11 }, document.createTextNode("0")));
    host.append(el);
  }

  /** Every parameter: value, unit, the derivatives and elasticities of all three quantities. */
  drawTable(rows) {
    const head = html("tr", {}, ...["parameter", "value", "unit", "∂v_w/∂p", "∂v_c/∂p", "e(v_w)", "e(v_c)", "e(width)"].map((t) => html("th", { text: t })));
    const body = rows.map((p) =>
      html("tr", { "data-key": p.key, title: p.description },
        html("td", { class: "what", text: `${p.symbol || p.key}` }, html("span", { class: "symbol", text: p.symbol && p.symbol !== p.key ? ` ${p.key}` : "" })),
        html("td", { class: "value", text: num(p.value, 6) }),
        html("td", { class: "unit", text: p.unit.replace(/\^2/g, "²") }),
        ...["weave_speed", "capsize_speed", "weave_speed_elasticity", "capsize_speed_elasticity", "stable_width_elasticity"].map((k) =>
          html("td", { class: "value", text: Number.isFinite(p[k]) ? num(p[k], 4) : "–" })),
      ));
    $("sens-table").replaceChildren(html("table", { class: "critical-table sens-table", "data-testid": "sens-table" }, html("thead", {}, head), html("tbody", {}, ...body)));
  }

  downloadCsv() {
    const a = this.answer;
    if (!a) return;
    const cols = ["key", "unit", "value", "weave_speed", "capsize_speed", "stable_width", "weave_speed_elasticity", "capsize_speed_elasticity", "stable_width_elasticity"];
    const lines = [`# whipple sensitivities of ${this.label()}: d/dp and d ln/d ln p of v_w, v_c and the stable width`, cols.join(",")];
    for (const p of a.parameters) lines.push(cols.map((k) => (k === "key" || k === "unit" ? p[k] : Number.isFinite(p[k]) ? String(p[k]) : "")).join(","));
    download(`${slug(this.label())}-sensitivities.csv`, `${lines.join("\n")}\n`, "text/csv");
  }
}
