// The parameter editor: one form per layout, numbers with units, angles in degrees, the
// library's messages shown in place next to the field they name.

import { JBIKE6_GROUPS, BENCHMARK_GROUPS, getPath } from "./fields.js";
import { html, inputText, num } from "./format.js";

const DEG = 180 / Math.PI;

/**
 * The units a field of each kind also takes, typed after the number (as the CLI and the files
 * take them: `trail_mm`, `lam_deg`, `--range 15:25km/h`): [symbol, the value in the field's
 * unit, the unit a file writes the key in ("" for the field's own, SI, which files need no
 * suffix for)]. A length field is in m, an angle field in degrees, a speed field in m/s; the
 * conversions are the library's (x / 1000 m, x / 3.6 m/s), so that "62 mm" here is the 0.062 m
 * a file's `c_mm = 62` reads as, to the bit.
 */
const TYPED_UNITS = {
  length: [["mm", (x) => x / 1000, "mm"], ["m", (x) => x, ""]],
  angle: [["°", (x) => x, "deg"], ["deg", (x) => x, "deg"], ["rad", (x) => x * DEG, ""]],
  speed: [["km/h", (x) => x / 3.6, null], ["m/s", (x) => x, null]],
};

/** The units `kind` takes, for messages: "m or mm". */
export function unitsOf(kind) {
  return (TYPED_UNITS[kind] ?? []).map(([u]) => u).join(" or ");
}

/**
 * Parses what was typed into a field of `kind` ("length", "angle", "speed" or null for a bare
 * number): {value, unit} in the field's unit, `unit` the unit a file would write the key in
 * when one was typed ("mm", "deg", "" for SI), undefined when none was; null when the text is
 * not a finite number, or names a unit the field does not take. A decimal comma is a point.
 */
export function parseQuantity(text, kind = null) {
  let t = String(text ?? "").trim().replace(/^−/, "-").replace(",", ".");
  let convert = (x) => x;
  let unit;
  for (const [symbol, to, written] of TYPED_UNITS[kind] ?? []) {
    if (t.endsWith(symbol)) {
      t = t.slice(0, -symbol.length).trim();
      convert = to;
      unit = written ?? undefined;
      break;
    }
  }
  if (t === "" || !/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(t)) return null;
  const x = convert(Number(t));
  return Number.isFinite(x) ? { value: x, unit } : null;
}

/** Parses what was typed; null when it is not a finite number. `kind` as [parseQuantity]'s:
 *  a speed field takes "20 km/h", a length field "62 mm". */
export function parseNumber(text, kind = null) {
  return parseQuantity(text, kind)?.value ?? null;
}

/** The number of a field: itself, or the value of a measured {value, sigma}. */
export function valueOf(raw) {
  return raw !== null && typeof raw === "object" ? raw.value : raw;
}

/** What is wrong with text that is not a number (of `kind`, which takes these units). */
function notANumber(text, kind = null) {
  if (text.trim() === "") return "empty: type a number";
  return kind ? `not a number of ${unitsOf(kind)}` : "not a number";
}

/** The kind of quantity a parameter's field holds, for the units it also takes. */
function kindOf(spec) {
  if (spec.angle) return "angle";
  return spec.unit === "m" ? "length" : null;
}

export class Editor {
  /** `onInput(path, value, part)` is called for every valid number typed (angles in radians;
   * `part` "value", or "sigma" for the σ of a measured value);
   * `onLocal()` whenever a field starts or stops holding text that is not a number;
   * `onUnit(key, unit)` when a value is typed with a unit ("mm", "deg"; "" for SI), so that a
   * saved file writes the key in it (`c_mm`). */
  constructor(container, onInput, onLocal = () => {}, onUnit = () => {}) {
    this.container = container;
    this.onInput = onInput;
    this.onLocal = onLocal;
    this.onUnit = onUnit;
    this.inputs = [];
  }

  /** Draws the form for `form` ("jbike6" or "benchmark") from `values` (that layout's table). */
  render(form, values, { readOnly = false, note = null } = {}) {
    // Drawing anew clears the fields holding text: that is news only where some did (told to
    // every render, it made each one ask for a recompute: two of each request on a switch, and
    // an endless round on the benchmark form of a JBike6 bicycle, which redraws after each).
    const hadLocal = this.inputs.some((i) => i.classList.contains("local"));
    this.container.replaceChildren();
    this.inputs = [];
    if (note) this.container.append(note);
    const groups = form === "jbike6" ? JBIKE6_GROUPS : BENCHMARK_GROUPS;
    for (const group of groups) {
      const details = html("details", { class: "group", open: true });
      details.append(html("summary", { text: group.title }));
      const grid = html("div", { class: "rows" });
      for (const row of group.rows) grid.append(this.row(row, values, readOnly, group.title));
      details.append(grid);
      this.container.append(details);
    }
    if (hadLocal) this.onLocal();
  }

  row(spec, values, readOnly, group) {
    const cells = spec.triple ?? [spec];
    const row = html("div", { class: `row${spec.triple ? " triple" : ""}`, title: spec.hint });
    row.append(html("label", { class: "sym", text: spec.label, for: `in-${cells[0].lib}` }));
    const boxes = html("div", { class: "inputs" });
    const error = html("div", { class: "row-error", "data-testid": `error-${cells[0].lib}`, role: "status" });
    const hint = html("div", { class: "row-hint", "data-testid": `hint-${cells[0].lib}` });
    const warning = html("div", { class: "row-warning", "data-testid": `warning-${cells[0].lib}`, role: "status" });
    for (const cell of cells) {
      // A measured value is {value, sigma} (BicycleParameters' `value+/-sigma`): the value in
      // its field, σ in one beside it, both kept through edits.
      const raw = getPath(values, cell.path);
      const measured = raw !== null && typeof raw === "object";
      const value = measured ? raw.value : raw;
      const input = html("input", {
        id: `in-${cell.lib}`,
        type: "text",
        inputmode: "decimal",
        spellcheck: "false",
        autocomplete: "off",
        "data-lib": cell.lib,
        "data-testid": `param-${cell.lib}`,
        "aria-label": `${group}: ${spec.hint}${spec.triple ? ` ${cell.label}` : ""} [${spec.unit}]`,
        placeholder: spec.triple ? cell.label : "",
        readonly: readOnly,
      });
      // Degrees converted from radians to 8 digits: 70.977782, not 70.9777819047 (the radians
      // stay as stored until the field is edited).
      // A read-only (converted) value is shown to 6 digits; the file keeps them all.
      const shown = spec.angle ? Number((value * DEG).toPrecision(8)) : value;
      input.value = readOnly && Number.isFinite(shown) ? String(Number(shown.toPrecision(6))) : inputText(shown);
      // The library's whole description as the tooltip (the row's hint is its first clause).
      const description = cell.description ?? spec.hint;
      input.title = spec.triple ? `${cell.label}: ${description}` : description;
      input.dataset.what = `${group} ${spec.label}${spec.triple ? ` ${cell.label}` : ""}`;
      input.dataset.last = input.value;
      if (!readOnly) this.listen(input, spec, cell, "value", value, hint);
      this.inputs.push(input);
      if (!measured) {
        boxes.append(input);
        continue;
      }
      const sigmaShown = spec.angle ? Number((raw.sigma * DEG).toPrecision(8)) : raw.sigma;
      const sigma = html("input", {
        id: `sigma-${cell.lib}`,
        class: "sigma",
        type: "text",
        inputmode: "decimal",
        spellcheck: "false",
        autocomplete: "off",
        "data-lib": `${cell.lib}.sigma`,
        "data-testid": `sigma-${cell.lib}`,
        "aria-label": `standard deviation σ of ${group}: ${spec.hint}${spec.triple ? ` ${cell.label}` : ""} [${spec.unit}]`,
        title: `σ: the standard deviation of the measured value [${spec.unit}]`,
        readonly: readOnly,
      });
      sigma.value = inputText(sigmaShown);
      sigma.dataset.what = `σ of ${group} ${spec.label}${spec.triple ? ` ${cell.label}` : ""}`;
      if (!readOnly) this.listen(sigma, spec, cell, "sigma", raw.sigma, null);
      this.inputs.push(sigma);
      boxes.append(html("span", { class: "measured" }, input, html("span", { class: "pm", text: "±" }), sigma));
    }
    row.append(boxes);
    row.append(html("span", { class: "unit", text: spec.unit }));
    if (spec.angle) {
      const radians = valueOf(getPath(values, spec.path));
      row.append(html("span", { class: "deg", text: Number.isFinite(radians) ? `${num(radians, 5)} rad` : "" }));
    }
    row.append(error, hint, warning);
    return row;
  }

  /**
   * Sends what is typed into `input` (the `part`, "value" or "sigma", of the field at
   * `cell.path`): a number, or the field marked as holding text. Typing back the text shown
   * sends the value exactly as it was (not its rounded display), so that nothing reads as
   * modified.
   */
  listen(input, spec, cell, part, exact, hint) {
    const shown = input.value.trim();
    const kind = kindOf(spec);
    input.addEventListener("input", () => {
      const q = parseQuantity(input.value, kind);
      const wasLocal = input.classList.contains("local");
      if (q === null) {
        this.markLocal(input, notANumber(input.value, kind));
        if (!wasLocal) this.onLocal();
        return;
      }
      const x = q.value;
      this.unmarkLocal(input);
      if (part === "value" && q.unit !== undefined) this.onUnit(cell.lib, q.unit);
      // Degrees typed with their unit (or radians with theirs) are no slip to point out.
      if (spec.angle && hint && q.unit === undefined) this.suggestDegrees(spec, input, x, hint);
      else if (spec.angle && hint) this.suggestDegrees({ ...spec, plausible: undefined }, input, x, hint);
      const typed = spec.angle ? x / DEG : x;
      this.onInput(cell.path, input.value.trim() === shown && Number.isFinite(exact) ? exact : typed, part);
      if (wasLocal) this.onLocal();
    });
  }

  /**
   * An angle typed in radians where degrees are asked for: offers the degrees, e.g. "did you
   * mean 72°?" for a head angle of 1.2566. The value typed stays as typed until accepted.
   */
  suggestDegrees(spec, input, x, hint) {
    const row = input.closest(".row");
    const rad = row.querySelector(".deg");
    if (rad) rad.textContent = `${num(x / DEG, 5)} rad`;
    hint.replaceChildren();
    const [lo, hi] = spec.plausible ?? [];
    if (lo === undefined || (x >= lo && x <= hi)) return;
    const asDegrees = x * DEG;
    if (!(asDegrees >= lo && asDegrees <= hi)) return;
    const shown = num(asDegrees, 4);
    const accept = html("button", { type: "button", class: "btn tiny", text: `use ${shown}°`, "data-testid": `accept-${input.dataset.lib}` });
    accept.addEventListener("click", () => {
      input.value = shown;
      input.dispatchEvent(new Event("input", { bubbles: true }));
      input.focus();
    });
    hint.append(html("span", { text: `${num(x)}° is unusual for the ${spec.hint}: did you mean ${shown}°? (${num(x)} rad) ` }), accept);
  }

  markLocal(input, message) {
    input.classList.add("invalid", "local");
    input.setAttribute("aria-invalid", "true");
    const err = input.closest(".row").querySelector(".row-error");
    err.textContent = message;
  }

  unmarkLocal(input) {
    input.classList.remove("local");
    if (!input.classList.contains("server")) {
      input.classList.remove("invalid");
      input.removeAttribute("aria-invalid");
    }
    const row = input.closest(".row");
    if (!row.querySelector("input.local")) row.querySelector(".row-error").textContent = row.querySelector("input.server") ? row.querySelector(".row-error").dataset.rule ?? "" : "";
  }

  /** The fields holding text that is not a number: [{lib, what, text}]. */
  localErrors() {
    return this.inputs.filter((i) => i.classList.contains("local")).map((i) => ({ lib: i.dataset.lib, what: i.dataset.what, text: i.value }));
  }

  hasLocalErrors() {
    return this.inputs.some((i) => i.classList.contains("local"));
  }

  /**
   * Marks the fields an API error names (`field`, comma separated; benchmark names translated
   * through `sources` when the form shown is JBike6's) with `rule`; returns how many.
   */
  flag(error, { sources = null, rule = null } = {}) {
    this.clearServerFlags();
    if (!error?.field) return 0;
    let names = error.field.split(",").map((s) => s.trim().split(" ")[0]).filter(Boolean);
    const own = (n) => this.inputs.some((i) => i.dataset.lib === n || (i.dataset.lib.startsWith(n) && /^[(xyz]/.test(i.dataset.lib.slice(n.length))));
    if (sources && !names.some(own)) names = names.flatMap((n) => sources[n] ?? []);
    let count = 0;
    for (const input of this.inputs) {
      const lib = input.dataset.lib;
      if (names.some((n) => lib === n || (lib.startsWith(n) && /^[(xyz]/.test(lib.slice(n.length))))) {
        input.classList.add("invalid", "server");
        input.setAttribute("aria-invalid", "true");
        const err = input.closest(".row").querySelector(".row-error");
        err.dataset.rule = rule ?? error.rule ?? error.message;
        if (!input.classList.contains("local")) err.textContent = err.dataset.rule;
        count += 1;
      }
    }
    const first = this.inputs.find((i) => i.classList.contains("server"));
    first?.closest("details")?.setAttribute("open", "");
    return count;
  }

  /**
   * Shows the library's warnings (notices {severity, field, message}: the bicycle is accepted)
   * beside the fields they name, benchmark names translated through `sources` when the form
   * shown is JBike6's; returns how many fields carry one.
   */
  warn(notices, { sources = null } = {}) {
    for (const w of this.container.querySelectorAll(".row-warning")) w.textContent = "";
    let count = 0;
    for (const notice of notices ?? []) {
      if (!notice?.field) continue;
      let names = [notice.field];
      const matches = (lib, n) => lib === n || (lib.startsWith(n) && /^[(xyz]/.test(lib.slice(n.length)));
      if (sources && !this.inputs.some((i) => matches(i.dataset.lib, notice.field))) names = sources[notice.field] ?? [];
      const rows = new Set(this.inputs.filter((i) => names.some((n) => matches(i.dataset.lib, n))).map((i) => i.closest(".row")));
      for (const row of rows) {
        const box = row.querySelector(".row-warning");
        box.textContent = box.textContent ? `${box.textContent} ${notice.message}` : notice.message;
        count += 1;
      }
    }
    return count;
  }

  clearServerFlags() {
    for (const input of this.inputs) {
      if (!input.classList.contains("server")) continue;
      input.classList.remove("server");
      if (!input.classList.contains("local")) {
        input.classList.remove("invalid");
        input.removeAttribute("aria-invalid");
        input.closest(".row").querySelector(".row-error").textContent = "";
      }
    }
  }
}
