// The Control tab: the bicycle under full-state feedback u = r − K x on (φ, δ, φ̇, δ̇)
// (/api/linear/closed_loop). The inputs fed back (steer torque, lean torque); K typed in a
// small grid, one row per input, or designed by LQR (Q's diagonal, R, at one design speed or
// at every speed of the sweep). The closed loop's eigenvalues against speed are drawn by the
// Eigenvalues tab's plot, the ranges where the loop is stable shaded and called "stable", the
// bicycle alone faint behind them; the certified stable speeds said in one sentence.

import { api } from "./api.js";
import { parseNumber } from "./editor.js";
import { html, num } from "./format.js";
import { EigenPlot } from "./plot.js";
import { stabilizesText } from "./critical.js";

const $ = (id) => document.getElementById(id);
const INPUTS = [
  { name: "steer_torque", symbol: "T_δ", text: "steer torque T_δ" },
  { name: "lean_torque", symbol: "T_φ", text: "lean torque T_φ" },
];
const STATES = [
  { symbol: "φ", text: "lean" },
  { symbol: "δ", text: "steer" },
  { symbol: "φ̇", text: "lean rate" },
  { symbol: "δ̇", text: "steer rate" },
];
/** Steer into the fall against a steer spring: T_δ = 100 φ − 10 δ + 20 φ̇. */
const DEFAULT_K = { steer_torque: ["-100", "10", "-20", "0"], lean_torque: ["0", "0", "0", "0"] };

export class ControlPanel {
  /** `bike()`: the bicycle edited; `speeds()`: the sweep's {start, stop, step} (null entries
   * when a field is not a number); `openLoop()`: /api/eigen's answer for the bicycle alone;
   * `label()`: its name; `ylim()`: the plots' |λ| limit; `onChange()`: the link must be rewritten. */
  constructor({ bike, speeds, openLoop, label, ylim, onChange }) {
    this.ylim = ylim;
    this.bike = bike;
    this.speeds = speeds;
    this.openLoop = openLoop;
    this.label = label;
    this.onChange = onChange;
    this.sequence = 0;
    this.answer = null;
    this.fresh = false;
    this.k = structuredClone(DEFAULT_K);
    this.r = { steer_torque: "1", lean_torque: "1" };
    this.plot = new EigenPlot($("ctl-plot"), { label: "Closed-loop eigenvalues against forward speed", testid: "ctl-chart", stableLabel: "stable", faint: true });
    this.drawFields();
    $("ctl-form").addEventListener("submit", (e) => {
      e.preventDefault();
      this.edited();
    });
    $("ctl-form").addEventListener("change", (e) => {
      if (e.target.closest(".plot")) return;
      this.keep();
      if (e.target.name === "ctl-input" || e.target.name === "ctl-mode") this.drawFields();
      this.edited();
    });
  }

  edited() {
    this.compute();
    this.onChange();
  }

  /** The inputs ticked, in the library's order. */
  inputsChosen() {
    return INPUTS.filter((i) => $(`ctl-in-${i.name}`).checked);
  }

  mode() {
    return $("ctl-mode-lqr").checked ? "lqr" : "gains";
  }

  /** What the fields hold, kept per input so that a row survives unticking its input. */
  keep() {
    for (const i of INPUTS) {
      STATES.forEach((_, j) => {
        const field = $(`ctl-k-${i.name}-${j}`);
        if (field) this.k[i.name][j] = field.value;
      });
      const r = $(`ctl-r-${i.name}`);
      if (r) this.r[i.name] = r.value;
    }
  }

  /** The K grid or the LQR weights, for the inputs ticked. */
  drawFields() {
    const inputs = this.inputsChosen();
    const lqr = this.mode() === "lqr";
    $("ctl-gains").hidden = lqr;
    $("ctl-lqr").hidden = !lqr;
    const head = html("tr", {}, html("th", { scope: "col", class: "ctl-corner", text: "K" }), ...STATES.map((s) => html("th", { scope: "col", title: s.text, text: s.symbol })));
    const rows = inputs.map((i) => html("tr", {}, html("th", { scope: "row", title: i.text, text: i.symbol }), ...STATES.map((s, j) => html("td", {}, html("input", {
      id: `ctl-k-${i.name}-${j}`, type: "text", inputmode: "decimal", spellcheck: "false", value: this.k[i.name][j],
      "aria-label": `gain of ${i.text} on ${s.text} ${s.symbol}`, "data-testid": `ctl-k-${i.name}-${j}`,
    })))));
    $("ctl-gains").replaceChildren(html("table", { class: "ctl-grid" }, html("thead", {}, head), html("tbody", {}, ...rows)),
      html("p", { class: "note", text: "u = r − K x: each input is minus its row of gains times (φ, δ, φ̇, δ̇), in N m per rad and per rad/s." }));
    $("ctl-r").replaceChildren(...inputs.map((i) => html("label", { title: `R's diagonal entry for ${i.text}` }, `R ${i.symbol} `, html("input", {
      id: `ctl-r-${i.name}`, type: "text", inputmode: "decimal", spellcheck: "false", value: this.r[i.name], "data-testid": `ctl-r-${i.name}`,
    }))));
  }

  /** The state the link carries. */
  inputs() {
    this.keep();
    const chosen = this.inputsChosen().map((i) => i.name);
    return {
      m: this.mode(),
      in: chosen.join(","),
      k: chosen.map((n) => this.k[n].map((x) => x.trim()).join(",")).join("/"),
      q: [0, 1, 2, 3].map((j) => $(`ctl-q-${j}`).value.trim()).join(","),
      r: chosen.map((n) => this.r[n].trim()).join(","),
      v: $("ctl-speed").value.trim(),
      s: $("ctl-scheduled").checked ? "1" : "0",
    };
  }

  /** Restores what `inputs()` gave; what is missing keeps its default. */
  setInputs(s) {
    if (s.in !== undefined) {
      const names = s.in.split(",").filter((n) => INPUTS.some((i) => i.name === n));
      if (names.length) for (const i of INPUTS) $(`ctl-in-${i.name}`).checked = names.includes(i.name);
    }
    const chosen = this.inputsChosen().map((i) => i.name);
    if (s.k !== undefined) {
      s.k.split("/").forEach((row, k) => {
        const values = row.split(",");
        if (chosen[k] && values.length === 4) this.k[chosen[k]] = values;
      });
    }
    if (s.r !== undefined) s.r.split(",").forEach((x, k) => chosen[k] && (this.r[chosen[k]] = x));
    if (s.q !== undefined) s.q.split(",").slice(0, 4).forEach((x, j) => ($(`ctl-q-${j}`).value = x));
    if (s.v !== undefined) $("ctl-speed").value = s.v;
    if (s.s !== undefined) $("ctl-scheduled").checked = s.s === "1";
    $(s.m === "lqr" ? "ctl-mode-lqr" : "ctl-mode-gains").checked = true;
    this.drawFields();
  }

  /** The bicycle changed: the answer shown is of another one until computed again. */
  invalidate() {
    this.fresh = false;
  }

  say(text) {
    $("ctl-message").textContent = text ?? "";
    $("ctl-message").hidden = !text;
  }

  /** Marks the fields of `ids` invalid (and only them). */
  mark(ids) {
    for (const e of document.querySelectorAll("#panel-control input[type=text]")) {
      const bad = ids.includes(e.id);
      e.classList.toggle("invalid", bad);
      e.setAttribute("aria-invalid", String(bad));
    }
  }

  /** The request from the form; null (the message said, the fields marked) when it is not valid. */
  request() {
    const inputs = this.inputsChosen();
    const refuse = (text, ids) => {
      this.mark(ids);
      this.say(text);
      this.veil("not recomputed: see the message above");
      return null;
    };
    if (!inputs.length) return refuse("Choose at least one input to feed back.", []);
    const grid = this.speeds();
    if (Object.values(grid).some((x) => x === null)) return refuse("The speeds (v from, to, step, above) must be numbers.", []);
    const read = (id, what) => {
      const v = parseNumber($(id).value);
      return v === null ? { bad: { id, what } } : { v };
    };
    const body = { bike: this.bike(), inputs: inputs.map((i) => i.name), speeds: grid };
    const bad = [];
    if (this.mode() === "gains") {
      body.gains = inputs.map((i) => STATES.map((s, j) => {
        const r = read(`ctl-k-${i.name}-${j}`, `K's gain of ${i.symbol} on ${s.symbol}`);
        if (r.bad) bad.push(r.bad);
        return r.v;
      }));
    } else {
      const q = [0, 1, 2, 3].map((j) => {
        const r = read(`ctl-q-${j}`, `Q's weight on ${STATES[j].symbol}`);
        if (r.bad) bad.push(r.bad);
        return r.v;
      });
      const rr = inputs.map((i) => {
        const r = read(`ctl-r-${i.name}`, `R's weight on ${i.symbol}`);
        if (r.bad) bad.push(r.bad);
        return r.v;
      });
      const scheduled = $("ctl-scheduled").checked;
      $("ctl-speed").disabled = scheduled;
      let speed = null;
      if (!scheduled) {
        const r = read("ctl-speed", "the design speed");
        if (r.bad) bad.push(r.bad);
        speed = r.v;
      }
      body.lqr = scheduled ? { q, r: rr, scheduled: true } : { q, r: rr, speed };
    }
    if (bad.length) return refuse(`${bad[0].what[0].toUpperCase()}${bad[0].what.slice(1)} must be a finite number${bad.length > 1 ? ` (and ${bad.length - 1} more field${bad.length > 2 ? "s" : ""})` : ""}.`, bad.map((b) => b.id));
    return body;
  }

  async compute() {
    const body = this.request();
    if (!body) return;
    this.mark([]);
    const mine = ++this.sequence;
    try {
      const answer = await api.closedLoop(body);
      if (mine !== this.sequence) return;
      this.say(null);
      this.answer = answer;
      this.fresh = true;
      this.render();
    } catch (e) {
      if (mine !== this.sequence) return;
      const inputs = this.inputsChosen();
      const fields = {
        gains: inputs.flatMap((i) => STATES.map((_, j) => `ctl-k-${i.name}-${j}`)),
        "lqr.q": [0, 1, 2, 3].map((j) => `ctl-q-${j}`),
        "lqr.r": inputs.map((i) => `ctl-r-${i.name}`),
        "lqr.speed": ["ctl-speed"],
      }[e.field] ?? [];
      this.mark(fields);
      this.say(e.message);
      this.veil("not recomputed: see the message above");
    }
  }

  render() {
    const a = this.answer;
    const open = this.openLoop();
    const designs = [{ label: "closed loop", eigen: a }];
    // The bicycle alone, faint, where it was swept over the same speeds.
    if (open && open.speeds.length === a.speeds.length && open.speeds[0] === a.speeds[0]) designs.push({ label: "open loop (the bicycle alone)", eigen: open });
    this.plot.update(designs, { ylim: this.ylim() ?? 10, stale: null });
    const sentence = stabilizesText(a);
    $("ctl-sentence").textContent = sentence;
    $("ctl-sentence").dataset.stable = String(Boolean(a.critical?.stable_speed_ranges.length));
    const g = a.gains;
    const rows = (k) => k.map((row) => `[${row.map((x) => num(x)).join(", ")}]`).join(" ");
    $("ctl-used").textContent = g.kind === "constant"
      ? `K = ${rows(g.k)}`
      : g.kind === "lqr"
        ? `LQR at ${num(g.speed)} m/s: K = ${rows(g.k)}; Riccati residual ${g.residual.toExponential(1)}`
        : `LQR at each of ${g.schedule.length} speeds, linear between them; largest Riccati residual ${g.largest_residual.toExponential(1)}`;
    $("ctl-meta").textContent = `${this.label()} under feedback on ${a.inputs.map((n) => INPUTS.find((i) => i.name === n)?.symbol ?? n).join(", ")}`;
    this.veil(null);
  }

  /** Draws the curves shown again, for another |λ| limit. */
  redraw() {
    if (this.plot.ready()) this.plot.update(this.plot.designs, { ylim: this.ylim() ?? 10, stale: this.plot.stale });
  }

  /** Veils what is shown (`reason`), or unveils it (null). */
  veil(reason) {
    $("ctl-side").classList.toggle("stale", Boolean(reason));
    $("ctl-side").dataset.stale = reason ?? "";
    if (!this.plot.ready()) return;
    this.plot.stale = reason;
    this.plot.draw();
  }
}
