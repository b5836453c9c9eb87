// The parameter editor: one form per layout, numbers with units, the library's messages shown
// in place next to the field they name.

import { JBIKE6_GROUPS, BENCHMARK_GROUPS, getPath } from "./fields.js";
import { html, fixed } from "./format.js";

/** Text for a number in an input: the shortest form that reads back the same. */
function show(x) {
  return Number.isFinite(x) ? String(x) : "";
}

/** Parses what was typed; null when it is not a finite number. */
export function parseNumber(text) {
  const t = text.trim().replace(/^−/, "-").replace(",", ".");
  if (t === "" || !/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(t)) return null;
  const x = Number(t);
  return Number.isFinite(x) ? x : null;
}

export class Editor {
  /** `onInput(path, value)` is called for every valid number typed. */
  constructor(container, onInput) {
    this.container = container;
    this.onInput = onInput;
    this.inputs = [];
  }

  /** Draws the form for `form` ("jbike6" or "benchmark") from `values` (that layout's table). */
  render(form, values, { readOnly = false, note = null } = {}) {
    this.container.replaceChildren();
    this.inputs = [];
    if (note) this.container.append(note);
    const groups = form === "jbike6" ? JBIKE6_GROUPS : BENCHMARK_GROUPS;
    for (const group of groups) {
      const details = html("details", { class: "group", open: true });
      details.append(html("summary", { text: group.title }));
      const grid = html("div", { class: "rows" });
      for (const row of group.rows) grid.append(this.row(row, values, readOnly));
      details.append(grid);
      this.container.append(details);
    }
  }

  row(spec, values, readOnly) {
    const cells = spec.triple ?? [spec];
    const row = html("div", { class: `row${spec.triple ? " triple" : ""}`, title: spec.hint });
    row.append(html("label", { class: "sym", text: spec.label, for: `in-${cells[0].lib}` }));
    const boxes = html("div", { class: "inputs" });
    for (const cell of cells) {
      const value = getPath(values, cell.path);
      const input = html("input", {
        id: `in-${cell.lib}`,
        type: "text",
        inputmode: "decimal",
        spellcheck: "false",
        autocomplete: "off",
        "data-lib": cell.lib,
        "data-testid": `param-${cell.lib}`,
        "aria-label": `${spec.hint} ${cell.label}`,
        placeholder: spec.triple ? cell.label : "",
        readonly: readOnly,
      });
      input.value = show(value);
      input.title = spec.triple ? `${cell.label}: ${spec.hint}` : spec.hint;
      if (!readOnly) {
        input.addEventListener("input", () => {
          const x = parseNumber(input.value);
          if (x === null) {
            this.markLocal(input, "not a number");
          } else {
            this.unmarkLocal(input);
            if (spec.angle) row.querySelector(".deg").textContent = degrees(x);
            this.onInput(cell.path, x);
          }
        });
      }
      this.inputs.push(input);
      boxes.append(input);
    }
    row.append(boxes);
    const unit = html("span", { class: "unit", text: spec.unit });
    row.append(unit);
    if (spec.angle) {
      row.append(html("span", { class: "deg", text: degrees(getPath(values, spec.path)) }));
    }
    row.append(html("div", { class: "row-error", "data-testid": `error-${cells[0].lib}` }));
    return row;
  }

  markLocal(input, message) {
    input.classList.add("invalid", "local");
    const err = input.closest(".row").querySelector(".row-error");
    err.textContent = message;
  }

  unmarkLocal(input) {
    input.classList.remove("local");
    if (!input.classList.contains("server")) input.classList.remove("invalid");
    const row = input.closest(".row");
    if (!row.querySelector("input.invalid")) row.querySelector(".row-error").textContent = "";
  }

  /** True when some input holds text that is not a number. */
  hasLocalErrors() {
    return this.inputs.some((i) => i.classList.contains("local"));
  }

  /** Marks the fields an API error names (`field`, comma separated) with its rule; returns how many. */
  flag(error) {
    this.clearServerFlags();
    if (!error?.field) return 0;
    const names = error.field.split(",").map((s) => s.trim().split(" ")[0]).filter(Boolean);
    let count = 0;
    for (const input of this.inputs) {
      const lib = input.dataset.lib;
      if (names.some((n) => lib === n || (lib.startsWith(n) && /^[(xyz]/.test(lib.slice(n.length))))) {
        input.classList.add("invalid", "server");
        const err = input.closest(".row").querySelector(".row-error");
        err.textContent = error.rule ?? error.message;
        count += 1;
      }
    }
    const first = this.inputs.find((i) => i.classList.contains("server"));
    first?.closest("details")?.setAttribute("open", "");
    return count;
  }

  clearServerFlags() {
    for (const input of this.inputs) {
      if (!input.classList.contains("server")) continue;
      input.classList.remove("server");
      if (!input.classList.contains("local")) {
        input.classList.remove("invalid");
        input.closest(".row").querySelector(".row-error").textContent = "";
      }
    }
  }
}

function degrees(rad) {
  return Number.isFinite(rad) ? `${fixed((rad * 180) / Math.PI, 2)}°` : "";
}
