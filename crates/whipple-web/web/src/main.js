// The page: a bike picker, the parameter editor, the side view, the critical speeds, and below
// them the eigenvalues against speed, the root locus, the modes and the simulation, kept in
// step with the API. Rule: nothing on the page shows numbers that do not match the form — a
// result that no longer matches is veiled and says why — and the whole state lives in the URL
// (see url.js), so that a link reproduces what its sender saw and back/forward work.

import "./style.css";
import { api } from "./api.js";
import { inBrowser } from "./backend.js";
import { begin, during } from "./work.js";
import { listDesigns, saveDesign, deleteDesign, findDesign } from "./store.js";
import { Editor, parseNumber } from "./editor.js";
import { getPath, setPath, applyParameterTable, JBIKE6_SOURCES, JBIKE6_GROUPS, BENCHMARK_GROUPS } from "./fields.js";
import { drawSideView } from "./sideview.js";
import { EigenPlot, LocusPlot, COMPARE_COLOURS } from "./plot.js";
import { drawCritical, criticalSummary } from "./critical.js";
import { SimPanel } from "./sim.js";
import { ModesPanel } from "./modes.js";
import { ResponsePanel } from "./response.js";
import { ControlPanel } from "./control.js";
import { RiddenPanel } from "./ridden.js";
import { SensitivityPanel } from "./sensitivity.js";
import { MapPanel } from "./map.js";
import { MeasurePanel } from "./measure.js";
import { readUrl, writeUrl, diffEdits } from "./url.js";
import { html, slug, download, svgText, svgPng, num } from "./format.js";

const $ = (id) => document.getElementById(id);
const clone = (x) => JSON.parse(JSON.stringify(x));
const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);
const DEFAULT_PRESET = "schwinn-crown";
const MAX_COMPARED = 5;
const VIEWS = ["eigen", "locus", "modes", "resp", "control", "ridden", "sens", "map", "sim", "measure"];

const state = {
  presets: [],
  key: "",
  designId: null,
  base: null, // the bicycle as picked (preset or saved design): edits are relative to it
  baseKey: "", // the picker's key of `base` (a conversion changes `key`, not the base)
  bike: null,
  units: null, // the units the design's file typed keys in ({c: "mm"}): Save TOML writes them so
  form: "jbike6",
  validated: null,
  eigen: null,
  valid: true,
  lastError: null,
  speedsError: null, // why the eigenvalues shown are not those of the speeds asked for
  compare: [], // [{key, bike, eigen, validated, label}]
  view: "eigen",
  restoring: false,
};

const editor = new Editor(
  $("editor-body"),
  (path, value, part = "value") => {
    const table = state.bike.jbike6 ? (state.form === "jbike6" ? state.bike.jbike6 : null) : state.bike.benchmark;
    if (!table) return;
    // A measured value keeps its σ when the value is edited, and its value when σ is.
    const current = getPath(table, path);
    if (current !== null && typeof current === "object") current[part] = value;
    else if (part === "value") setPath(table, path, value);
    updateModified();
    schedule();
    remember(false);
  },
  () => schedule(),
  // A value typed with a unit ("62 mm", "18 deg") is written in it by Save TOML (`c_mm`), one
  // typed with the SI unit ("0.062 m") without a suffix.
  (key, unit) => {
    const units = { ...(state.units ?? {}) };
    if (unit) units[key] = unit;
    else delete units[key];
    state.units = Object.keys(units).length ? units : null;
  },
);
const plot = new EigenPlot($("eigen-plot"));
const locus = new LocusPlot($("locus-plot"));
const sim = new SimPanel({ bike: () => clone(state.bike), label: () => currentLabel(), onRun: () => remember(true) });
const modes = new ModesPanel({
  bike: () => clone(state.bike),
  label: () => currentLabel(),
  onChange: () => remember(true),
  onPlay3d: (initial) => {
    sim.setInputs({ speed: num(initial.speed, 6), lean_deg: num(initial.lean_deg, 4), steer_deg: num(initial.steer_deg, 4), lean_rate: num(initial.lean_rate, 4), steer_rate: num(initial.steer_rate, 4), duration: num(initial.duration, 3), steer_torque: "0", lean_torque: "0" });
    showView("sim");
    sim.run();
  },
});
const response = new ResponsePanel({ bike: () => clone(state.bike), label: () => currentLabel(), onChange: () => remember(true) });
const control = new ControlPanel({ bike: () => clone(state.bike), speeds: () => speedGrid(), openLoop: () => state.eigen, label: () => currentLabel(), ylim: () => yLimit(), onChange: () => remember(true) });
const ridden = new RiddenPanel({ bike: () => clone(state.bike), label: () => currentLabel(), onChange: () => remember(true) });
const sensitivity = new SensitivityPanel({ bike: () => clone(state.bike), label: () => currentLabel(), onChange: () => remember(true) });
const designMap = new MapPanel({
  bike: () => clone(state.bike),
  label: () => currentLabel(),
  onChange: () => remember(true),
  // A clicked cell becomes the edited bicycle (unsaved edits of the one shown, kept in the link).
  onLoad: (bike, where) => {
    bike.name = state.bike.name;
    state.bike = bike;
    renderEditor();
    updateModified();
    schedule();
    remember(true);
    say(`Loaded the design at ${where} into the editor (not saved).`, "info");
  },
});
// The Measure tab's bicycle goes to the editor as a design of the link (not saved), and the
// eigenvalues show it.
const measure = new MeasurePanel({
  onChange: () => remember(false),
  onLoad: (bike) => during(async () => {
    await select("link:", { def: bike });
    showView("eigen", { push: false });
    remember(true);
    say(`Loaded “${bike.name}”, computed from its bench measurements, into the editor (not saved: Save to my designs keeps it).`, "info");
  }),
});
let sideSvg = null;

// ---- messages ---------------------------------------------------------------------------

/**
 * Shows a message; `source` says who may clear it ("bike" for validation, "local" for text in
 * a number field, else any caller); `actions`: [{text, run}] buttons after the text.
 */
function say(text, kind = "info", source = "general", actions = []) {
  const box = $("message");
  box.className = `message ${kind}`;
  box.dataset.source = source;
  box.replaceChildren(html("span", { text }));
  for (const a of actions) {
    const b = html("button", { type: "button", class: "btn tiny", text: a.text, "data-testid": a.testid ?? null });
    b.addEventListener("click", a.run);
    box.append(" ", b);
  }
  box.hidden = !text;
}

/** Hides the message if it came from `source` (every message when no source is given). */
function quiet(source) {
  const box = $("message");
  if (!source || box.dataset.source === source) box.hidden = true;
}

// ---- picker -------------------------------------------------------------------------------

/** A preset's display title, as the library names it (GET /api/presets). */
function presetTitle(name) {
  return state.presets.find((p) => p.name === name)?.title ?? name;
}

function fillPickers() {
  const designs = listDesigns();
  for (const select of [$("bike-select"), $("compare-select")]) {
    select.replaceChildren();
    if (select.id === "compare-select") select.append(html("option", { value: "", text: state.compare.length ? "— add a design, or clear all —" : "— add a design —" }));
    // The literature's bicycles, then the measured ones (BicycleParameters' data set, with σ).
    const presets = html("optgroup", { label: "Presets" });
    const measured = html("optgroup", { label: "Measured bicycles (Moore 2012, with σ)" });
    for (const p of state.presets) (p.measured ? measured : presets).append(html("option", { value: `preset:${p.name}`, text: presetTitle(p.name), title: `${p.summary} (${p.source})` }));
    select.append(presets);
    if (measured.children.length) select.append(measured);
    const mine = html("optgroup", { label: designs.length ? "My designs" : "My designs (none saved yet)" });
    for (const d of designs) mine.append(html("option", { value: `design:${d.id}`, text: d.name }));
    select.append(mine);
  }
  // A design that came with a link (not in this browser's designs): listed as such, so that
  // the picker names what is shown instead of standing empty.
  const picker = $("bike-select");
  if (state.key && state.bike && ![...picker.options].some((o) => o.value === state.key)) {
    const linked = html("optgroup", { label: "From the link" });
    linked.append(html("option", { value: state.key, text: `${state.bike.name || "a design"} (not saved here)`, "data-testid": "linked-option" }));
    picker.append(linked);
  }
  picker.value = state.key;
  $("compare-select").value = "";
  drawCompareList();
}

async function bikeFor(key) {
  const [kind, name] = [key.slice(0, key.indexOf(":")), key.slice(key.indexOf(":") + 1)];
  if (kind === "preset") return api.preset(name);
  const design = findDesign(name);
  if (!design) throw new Error("that design is no longer saved in this browser");
  return clone(design.bike);
}

function labelFor(key, bike) {
  if (key.startsWith("design:")) return findDesign(key.slice(7))?.name ?? bike?.name ?? "design";
  if (key.startsWith("preset:")) return presetTitle(key.slice(7));
  return bike?.name ?? "bicycle";
}

function currentLabel() {
  if (state.key.startsWith("preset:") && state.bike?.name === state.base?.name) return presetTitle(state.key.slice(7));
  return state.bike?.name ?? labelFor(state.key, state.bike);
}

/** Picks a bicycle. Unsaved edits of the one left are kept for an undo. */
async function select(key, { edits = null, def = null, keepMessage = false } = {}) {
  const leaving = state.bike && isModified() ? { key: state.key, baseKey: state.baseKey, designId: state.designId, base: clone(state.base), bike: clone(state.bike), units: state.units, form: state.form, label: currentLabel() } : null;
  try {
    const base = def ?? (await bikeFor(key));
    state.key = key;
    state.baseKey = key;
    state.designId = key.startsWith("design:") ? key.slice(7) : null;
    state.base = clone(base);
    state.bike = clone(base);
    state.units = state.designId ? (findDesign(state.designId)?.units ?? null) : null;
    if (edits) applyEdits(state.bike, edits);
    state.form = state.bike.jbike6 ? "jbike6" : "benchmark";
    state.validated = null;
    state.lastError = null;
    $("design-name").value = state.bike.name ?? "";
    $("delete-design").hidden = !state.designId;
    fillPickers();
    updateModified();
    if (!keepMessage) quiet();
    renderEditor();
    if (leaving && !state.restoring) {
      say(`Your edits to “${leaving.label}” are not saved; they are kept here until you leave the page.`, "info", "undo", [
        { text: `Back to the edited “${leaving.label}”`, testid: "undo-switch", run: () => restore(leaving) },
      ]);
    }
    await recompute();
  } catch (e) {
    say(e.message, "error");
  }
}

/** Goes back to a bicycle as it was (an undo of a switch). */
async function restore(saved) {
  state.key = saved.key;
  state.baseKey = saved.baseKey;
  state.designId = saved.designId;
  state.base = saved.base;
  state.bike = saved.bike;
  state.units = saved.units ?? null;
  state.form = saved.form;
  state.validated = null;
  $("design-name").value = state.bike.name ?? "";
  $("delete-design").hidden = !state.designId;
  fillPickers();
  updateModified();
  quiet();
  renderEditor();
  remember(true);
  await recompute();
}

function isModified() {
  return Boolean(state.base && state.bike && !same(state.base, state.bike));
}

function updateModified() {
  const modified = isModified();
  $("modified").hidden = !modified;
  const reset = $("reset-bike");
  reset.hidden = !modified;
  const kind = state.baseKey.startsWith("preset:") ? "preset" : state.baseKey.startsWith("design:") ? "design" : "link";
  reset.title = {
    preset: "Back to the preset's values (and σ of a measured bicycle), undoing every edit",
    design: "Back to the design as last saved in My designs (a file: as it was opened), undoing every edit",
    link: "Back to the design as the link gave it, undoing every edit",
  }[kind];
  reset.setAttribute("aria-label", { preset: "Reset to the preset", design: "Reset to the design as saved", link: "Reset to the design of the link" }[kind]);
}

/** Undoes every edit: the bicycle as picked (a preset, a saved design, a file as opened). */
function resetToBase() {
  if (!state.base) return;
  state.bike = clone(state.base);
  if (state.key !== state.baseKey) {
    // A conversion to the benchmark form is undone too.
    state.key = state.baseKey;
    state.designId = state.key.startsWith("design:") ? state.key.slice(7) : null;
    $("delete-design").hidden = !state.designId;
    fillPickers();
  }
  state.form = state.bike.jbike6 ? "jbike6" : "benchmark";
  $("design-name").value = state.bike.name ?? "";
  updateModified();
  renderEditor();
  schedule();
  remember(true);
}
$("reset-bike").addEventListener("click", resetToBase);

// About: a panel over the page, closed by Escape or a click elsewhere.
document.addEventListener("click", (e) => {
  if ($("about").open && !$("about").contains(e.target)) $("about").open = false;
});
document.addEventListener("keydown", (e) => {
  if (e.key !== "Escape" || !$("about").open) return;
  $("about").open = false;
  $("about").querySelector("summary").focus();
});

/** Applies {path: value} edits (paths as url.js writes them) to a bicycle. */
function applyEdits(bike, edits) {
  for (const [path, value] of Object.entries(edits)) {
    if (path === "name") {
      bike.name = value;
      continue;
    }
    const parts = path.split(".").map((p) => (/^\d+$/.test(p) ? Number(p) : p));
    const table = bike.jbike6 ?? bike.benchmark;
    try {
      setPath(table, parts, value);
    } catch {
      // A path that this bicycle does not have: ignored (the URL came from another layout).
    }
  }
}

// ---- editor -------------------------------------------------------------------------------

function renderEditor() {
  const isJbike6 = Boolean(state.bike.jbike6);
  $("tab-jbike6").disabled = !isJbike6;
  $("tab-jbike6").title = isJbike6 ? "JBike6's seven-body description" : "this design is described in the benchmark form";
  for (const tab of document.querySelectorAll(".tab[data-form]")) tab.setAttribute("aria-selected", String(tab.dataset.form === state.form));
  if (state.form === "jbike6") {
    editor.render("jbike6", state.bike.jbike6);
  } else if (!isJbike6) {
    editor.render("benchmark", state.bike.benchmark);
  } else {
    const note = html("div", { class: "note-box" },
      html("span", { text: "Converted from the JBike6 form (read-only): bodies combined by the parallel-axis theorem." }),
      html("button", { class: "btn small", id: "to-benchmark", text: "Edit in benchmark form" }));
    note.querySelector("button").addEventListener("click", convertToBenchmark);
    editor.render("benchmark", state.validated?.benchmark ?? {}, { readOnly: true, note });
  }
  showWarnings();
}

/** The last validation's warnings beside their fields (a new rendering of the form keeps them). */
function showWarnings() {
  editor.warn(state.validated?.warnings?.filter((w) => w.severity === "warning"), { sources: state.form === "jbike6" ? JBIKE6_SOURCES : null });
}

function convertToBenchmark() {
  if (!state.validated) {
    say("Mend the invalid parameters first: the conversion needs a valid bicycle.", "error");
    return;
  }
  state.bike = { ...(state.bike.name ? { name: `${state.bike.name} (benchmark form)` } : {}), ...(state.bike.source ? { source: state.bike.source } : {}), benchmark: clone(state.validated.benchmark) };
  // The JBike6 form's keys are gone: its file's units do not carry over to the combined bodies.
  state.units = null;
  state.designId = null;
  state.key = "converted:";
  $("design-name").value = state.bike.name ?? "";
  state.form = "benchmark";
  updateModified();
  renderEditor();
  say("Now in the benchmark form: save it to keep it.");
  remember(true);
  schedule();
}

for (const tab of document.querySelectorAll(".tab[data-form]")) {
  tab.addEventListener("click", () => {
    if (tab.disabled) return;
    state.form = tab.dataset.form;
    renderEditor();
    if (state.lastError) flagError(state.lastError);
  });
}

$("design-name").addEventListener("input", () => {
  const name = $("design-name").value.trim();
  if (name) state.bike.name = name;
  else delete state.bike.name;
  updateModified();
  remember(false);
});

// ---- computing ----------------------------------------------------------------------------

function speedGrid() {
  const read = (id) => parseNumber($(id).value, "speed");
  return { start: read("v-start"), stop: read("v-stop"), step: read("v-step") };
}

/** Whether the speed range was typed in km/h: the critical speeds are then given in km/h too. */
function speedsTypedInKmh() {
  return ["v-start", "v-stop", "v-step"].some((id) => /km\/h$/.test($(id).value.trim()));
}

/** The unit beside the speed fields, as typed: m/s; km/h when every field but a zero is typed
 * in km/h; both when they are mixed (each field is read in its own unit). */
function showSpeedUnit() {
  const typed = ["v-start", "v-stop", "v-step"].map((id) => $(id).value.trim()).filter((t) => t !== "" && parseNumber(t, "speed") !== 0);
  const kmh = typed.filter((t) => /km\/h$/.test(t)).length;
  $("v-unit").textContent = kmh === 0 ? "m/s" : kmh === typed.length ? "km/h" : "m/s or km/h, as typed";
}

function yLimit() {
  const y = parseNumber($("y-limit").value);
  return y && y > 0 ? y : 10;
}

let timer = 0;
/** Releases the scheduled recompute from the work under way (work.js) once it has started. */
let scheduled = null;
function schedule() {
  clearTimeout(timer);
  scheduled ??= begin();
  timer = setTimeout(runScheduled, 120);
}

function runScheduled() {
  timer = 0;
  const end = scheduled;
  scheduled = null;
  recompute();
  end?.();
}

/** Runs a scheduled recompute now, so that its message comes before, not after, the next. */
function flushScheduled() {
  if (!timer) return;
  clearTimeout(timer);
  runScheduled();
}

/** Why the results shown do not match the form, or null when they do. */
function staleReason({ speeds = true } = {}) {
  const local = editor.localErrors();
  if (local.length) return `not recomputed: ${local.map((l) => l.what).join(", ")} ${local.length > 1 ? "are" : "is"} not a number`;
  if (!state.valid) return "not recomputed: the parameters are invalid";
  if (speeds && state.speedsError) return `not recomputed: ${state.speedsError}`;
  return null;
}

/** The library's error in the form's words (a benchmark rule met in the JBike6 form). */
function flagError(error) {
  const jbike6 = Boolean(state.bike.jbike6) && state.form === "jbike6";
  const isOwn = JBIKE6_GROUPS.some((g) => g.rows.some((r) => (r.triple ?? [r]).some((c) => error.field && c.lib.startsWith(error.field))));
  if (jbike6 && error.field && !isOwn && JBIKE6_SOURCES[error.field]) {
    const names = JBIKE6_SOURCES[error.field];
    const rule = `${error.rule ?? error.message} (the benchmark form's ${error.field}, from these JBike6 entries)`;
    editor.flag({ ...error, field: names.join(",") }, { rule });
    return { translated: true, names };
  }
  return { translated: false, count: editor.flag(error) };
}

function describeField(lib) {
  for (const g of [...JBIKE6_GROUPS, ...BENCHMARK_GROUPS]) {
    for (const r of g.rows) for (const c of r.triple ?? [r]) if (c.lib === lib) return `${g.title.toLowerCase()} ${r.label}${r.triple ? ` ${c.label}` : ""}`;
  }
  return lib;
}

let sequence = 0;
async function recompute() {
  const mine = ++sequence;
  const local = editor.localErrors();
  if (local.length) {
    // Nothing is asked of the server: the results stay as they were, veiled, and say why.
    const what = local.map((l) => `${l.what} (${l.text.trim() === "" ? "empty" : `“${l.text}”`})`).join(", ");
    say(`Not recomputed: ${what} ${local.length > 1 ? "are" : "is"} not a number. The results shown are for the last numbers typed.`, "error", "local");
    drawAll();
    return;
  }
  if ($("message").dataset.source === "local") quiet("local");
  const grid = speedGrid();
  for (const id of ["v-start", "v-stop", "v-step"]) $(id).classList.remove("invalid");
  if (Object.values(grid).some((x) => x === null)) {
    for (const id of ["v-start", "v-stop", "v-step"]) if (parseNumber($(id).value, "speed") === null) $(id).classList.add("invalid");
    $("eigen-message").textContent = "The speeds must be numbers.";
    $("eigen-message").hidden = false;
    // The results of the last speeds stay, veiled: they are not those the fields ask for.
    state.speedsError = "the speeds are not numbers";
    drawAll();
    return;
  }
  const bike = clone(state.bike);
  const [validated, eigen] = await Promise.allSettled([api.validate(bike), api.eigen(bike, grid)]);
  if (mine !== sequence) return;
  if (validated.status === "rejected") {
    const error = validated.reason;
    state.valid = false;
    state.lastError = error;
    editor.warn([]);
    const flagged = flagError(error);
    if (flagged.translated) {
      const names = flagged.names.map(describeField).join(", ");
      say(`The bicycle is not valid: ${error.rule ?? error.message}. Checked on the benchmark form after combining the bodies (${error.field}); it comes from: ${names}.`, "error", "bike");
    } else {
      say(error.message, "error", "bike");
    }
    $("message").dataset.field = error.field ?? "";
    drawAll();
    return;
  }
  state.valid = true;
  state.lastError = null;
  editor.clearServerFlags();
  state.validated = validated.value;
  if (state.form === "benchmark" && state.bike.jbike6) renderEditor();
  // Warnings (a measured tensor breaking the triangle inequality, …) beside their fields.
  showWarnings();
  if (eigen.status === "rejected") {
    const error = eigen.reason;
    if (error.field === "speeds" || error.field === "range") for (const id of ["v-start", "v-stop", "v-step"]) $(id).classList.add("invalid");
    $("eigen-message").textContent = error.message;
    $("eigen-message").hidden = false;
    quiet("bike");
    // The eigenvalues and critical speeds shown are of the last request that succeeded: veiled.
    state.speedsError = error.field === "speeds" || error.field === "range" ? "the speeds are invalid" : "the eigenvalues could not be computed";
    drawSide();
    drawAll();
    return;
  }
  state.speedsError = null;
  $("eigen-message").hidden = true;
  quiet("bike");
  state.eigen = eigen.value;
  sim.suggestSpeed(state.eigen.critical, currentLabel());
  modes.suggest(state.eigen.critical);
  drawAll();
  if (state.view === "modes") modes.compute();
  // The response of another bicycle is never shown: computed now, or when its tab opens.
  if (state.view === "resp") response.compute();
  else response.invalidate();
  if (state.view === "control") control.compute();
  else control.invalidate();
  if (state.view === "ridden") ridden.compute();
  else ridden.invalidate();
  if (state.view === "sens") sensitivity.compute();
  // A map of another bicycle is never shown: computed now, or again when its tab opens.
  if (state.view === "map") designMap.compute();
  else designMap.invalidate();
  if (!window.whippleFirstPlot) {
    window.whippleFirstPlot = performance.now();
    performance.mark("whipple:first-plot");
  }
}

async function recomputeCompare() {
  const grid = speedGrid();
  if (Object.values(grid).some((x) => x === null)) return;
  await Promise.all(state.compare.map(async (c) => {
    try {
      c.bike = c.bike ?? (await bikeFor(c.key));
      c.label = labelFor(c.key, c.bike);
      const [validated, eigen] = await Promise.all([api.validate(c.bike), api.eigen(c.bike, grid)]);
      c.validated = validated;
      c.eigen = eigen;
      c.error = null;
    } catch (e) {
      c.eigen = null;
      c.validated = null;
      c.error = e.message;
    }
  }));
  drawCompareList();
  drawAll();
}

function drawCompareList() {
  const list = $("compare-list");
  list.replaceChildren();
  state.compare.forEach((c, k) => {
    const remove = html("button", { type: "button", class: "chip-x", "aria-label": `Stop comparing with ${c.label || labelFor(c.key)}`, text: "×" });
    remove.addEventListener("click", () => {
      state.compare.splice(k, 1);
      drawCompareList();
      fillPickers();
      drawAll();
      remember(true);
    });
    list.append(html("li", { class: "chip", title: c.error ?? "" },
      html("span", { class: "tt-dot", style: `background:${COMPARE_COLOURS[k % COMPARE_COLOURS.length]}` }),
      html("span", { text: `${c.label || labelFor(c.key)}${c.error ? " (cannot be computed)" : ""}` }), remove));
  });
  list.hidden = !state.compare.length;
}

function drawSide() {
  if (!state.validated) return;
  const ghost = state.compare.find((c) => c.validated)?.validated.side_view ?? null;
  sideSvg = drawSideView($("side-view"), state.validated.side_view, ghost, {
    stale: Boolean(staleReason()),
    reason: staleReason(),
    centres: $("side-centres").checked,
    ellipses: $("side-ellipses").checked,
  });
  const v = state.validated;
  $("side-meta").textContent = `${v.form === "jbike6" ? "JBike6 form" : "benchmark form"} · ${num(v.derived.total_mass, 4)} kg · head angle ${num(v.derived.head_angle_deg, 4)}°`;
  $("side-meta").title = $("side-meta").textContent;
}

function designsShown() {
  // An edited design is named so: beside the design it was edited from, two columns and two
  // curves would otherwise carry one name.
  const primary = { label: isModified() ? `${currentLabel()} (edited)` : currentLabel(), eigen: state.eigen };
  return [primary, ...state.compare.filter((c) => c.eigen).map((c) => ({ label: c.label, eigen: c.eigen }))];
}

function drawAll() {
  drawSide();
  // The modes shown are those of the last valid bicycle: veiled while the form is not.
  modes.veil(staleReason({ speeds: false }));
  if (state.view === "resp" && staleReason({ speeds: false })) response.veil(staleReason({ speeds: false }));
  if (state.view === "control" && staleReason()) control.veil(staleReason());
  if (state.view === "ridden" && staleReason({ speeds: false })) ridden.veil(staleReason({ speeds: false }));
  if (!state.eigen) return;
  const designs = designsShown();
  const stale = staleReason();
  if (state.view === "eigen") plot.update(designs, { ylim: yLimit(), stale });
  if (state.view === "locus") locus.update(designs, { ylim: yLimit(), stale });
  drawCritical($("critical"), designs, { stale: Boolean(stale), reason: stale, kmh: speedsTypedInKmh() });
  drawSummaryBar(designs[0], stale);
}

// ---- the summary bar: the critical speeds in sight while typing on a narrow screen ---------

// On a phone or a tablet the editor is below the plots, far from the table: while it is on the
// screen (and the table is not), a bar pinned to the top of the screen repeats the table's
// v_w, v_c and self-stable range, in the table's own words. At the top, the on-screen keyboard
// (at the bottom) never hides it; a field focused under it is scrolled clear of it.
const narrow = matchMedia("(max-width: 860px)");
const inView = { editor: false, table: false };
function updateSummaryBar() {
  const bar = $("summary-bar");
  const show = narrow.matches && inView.editor && !inView.table && Boolean(state.eigen);
  if (bar.hidden === !show) return;
  bar.hidden = !show;
  if (show) clearOfSummaryBar(document.activeElement);
}
function drawSummaryBar(design, stale) {
  const s = criticalSummary(design.eigen);
  $("summary-weave").textContent = s.weave;
  $("summary-capsize").textContent = s.capsize;
  $("summary-stable").textContent = s.stable;
  $("summary-bar").classList.toggle("stale", Boolean(stale));
  $("summary-bar").title = stale ?? "";
  // Veiled as the table is: the last numbers computed, and the reason a tap away.
  $("summary-note").hidden = !stale;
  updateSummaryBar();
}
/** Scrolls the page so that the bar does not cover `input` (a field of the editor). */
function clearOfSummaryBar(input) {
  const bar = $("summary-bar");
  if (bar.hidden || !input || !input.closest?.(".editor")) return;
  requestAnimationFrame(() => {
    const under = bar.getBoundingClientRect().bottom + 8 - input.getBoundingClientRect().top;
    if (under > 0) window.scrollBy(0, -under);
  });
}
const watch = new IntersectionObserver((entries) => {
  for (const e of entries) inView[e.target === $("critical") ? "table" : "editor"] = e.isIntersecting;
  updateSummaryBar();
});
watch.observe(document.querySelector(".editor"));
watch.observe($("critical"));
narrow.addEventListener("change", updateSummaryBar);
document.addEventListener("focusin", (e) => clearOfSummaryBar(e.target));
// Where the on-screen keyboard pans the visual viewport, the bar follows its top.
window.visualViewport?.addEventListener("resize", placeSummaryBar);
window.visualViewport?.addEventListener("scroll", placeSummaryBar);
function placeSummaryBar() {
  $("summary-bar").style.top = `${Math.max(0, window.visualViewport.offsetTop)}px`;
}

// ---- bottom panel: eigenvalues, root locus, modes, simulation -------------------------------

function showView(view, { push = true } = {}) {
  if (!VIEWS.includes(view)) view = "eigen";
  state.view = view;
  for (const v of VIEWS) $(`panel-${v}`).hidden = v !== view;
  $("speed-controls").hidden = !(view === "eigen" || view === "locus" || view === "control");
  // The Control tab takes the sweep's speeds; its plot is not the one the exports write.
  document.querySelector("#speed-controls .btn-group").style.display = view === "control" ? "none" : "";
  document.querySelector(".layout").classList.toggle("ctl-active", view === "control");
  document.querySelector(".layout").classList.toggle("sim-active", view === "sim");
  document.querySelector(".layout").classList.toggle("resp-active", view === "resp");
  document.querySelector(".layout").classList.toggle("rd-active", view === "ridden");
  document.querySelector(".layout").classList.toggle("ms-active", view === "measure");
  for (const tab of document.querySelectorAll(".tab[data-view]")) {
    const on = tab.dataset.view === view;
    tab.setAttribute("aria-selected", String(on));
    tab.tabIndex = on ? 0 : -1;
  }
  if (view === "eigen" || view === "locus") drawAll();
  if (view === "modes") modes.compute();
  else modes.stop();
  // Before the first bicycle is loaded there is nothing to compute: recompute() does it then.
  if (view === "resp" && state.bike && !response.fresh) response.compute();
  if (view === "control" && state.bike && state.eigen && !control.fresh) control.compute();
  if (view === "ridden" && state.bike && state.eigen && !ridden.fresh) ridden.compute();
  if (view === "sens" && state.bike) sensitivity.compute();
  if (view === "map" && state.bike && !designMap.answer) designMap.compute();
  // three.js is fetched when the Simulation tab first opens, not with the page.
  if (view === "sim") sim.ensureView();
  // The sample list is fetched when the Measure tab first opens.
  if (view === "measure") during(() => measure.ensureSamples()).catch((e) => measure.say(e.message));
  if (push) remember(true);
}
const viewTabs = [...document.querySelectorAll(".tab[data-view]")];
for (const tab of viewTabs) {
  tab.addEventListener("click", () => showView(tab.dataset.view));
  // Arrow keys move between the tabs (the ARIA tabs pattern).
  tab.addEventListener("keydown", (e) => {
    const k = viewTabs.indexOf(tab);
    const next = e.key === "ArrowRight" ? k + 1 : e.key === "ArrowLeft" ? k - 1 : null;
    if (next === null) return;
    const t = viewTabs[(next + viewTabs.length) % viewTabs.length];
    t.focus();
    showView(t.dataset.view);
  });
}

// ---- the URL ------------------------------------------------------------------------------

/** The state as the URL carries it. */
function snapshot() {
  const s = {
    bike: state.key,
    edits: null,
    def: null,
    compare: state.compare.map((c) => c.key),
    speeds: [$("v-start").value, $("v-stop").value, $("v-step").value].join(":"),
    ylim: $("y-limit").value,
    view: state.view,
    mode: $("mode-speed").value,
    resp: response.inputs(),
    control: control.inputs(),
    ridden: ridden.inputs(),
    measure: state.view === "measure" || measure.sample || measure.answer ? measure.inputs() : null,
    sim: sim.inputs(),
    sens: sensitivity.quantity,
    map: designMap.inputs(),
    side: Object.fromEntries([["centres", "side-centres"], ["ellipses", "side-ellipses"]].filter(([, id]) => !$(id).checked).map(([k]) => [k, "off"])),
  };
  if (state.key.startsWith("preset:")) {
    const edits = diffEdits(state.base, state.bike);
    if (Object.keys(edits).length) s.edits = edits;
  } else {
    // A design of this browser, a file or a conversion: the receiver has none of them.
    s.def = state.bike;
  }
  return s;
}

/** Records the state in the URL: a new history entry (`push`) or the current one replaced. */
function remember(push) {
  if (state.restoring || !state.bike) return;
  writeUrl(snapshot(), push);
}

/** Restores everything the URL says. */
async function applyUrl() {
  const s = readUrl();
  state.restoring = true;
  try {
    if (s.speeds) {
      const [a, b, c] = s.speeds.split(":");
      if (c !== undefined) {
        $("v-start").value = a;
        $("v-stop").value = b;
        $("v-step").value = c;
        showSpeedUnit();
      }
    }
    if (s.ylim) $("y-limit").value = s.ylim;
    if (s.mode) {
      $("mode-speed").value = s.mode;
      modes.speedEdited = true;
    }
    if (s.resp) response.setInputs(s.resp);
    if (s.control) control.setInputs(s.control);
    if (s.ridden) ridden.setInputs(s.ridden);
    if (s.measure) await measure.setInputs(s.measure);
    if (s.sim) sim.setInputs(s.sim);
    if (s.sens) sensitivity.setQuantity(s.sens);
    if (s.map) designMap.setInputs(s.map);
    $("side-centres").checked = s.side?.centres !== "off";
    $("side-ellipses").checked = s.side?.ellipses !== "off";
    state.compare = (s.compare ?? []).filter((k) => k.startsWith("preset:") || findDesign(k.slice(7))).slice(0, MAX_COMPARED).map((key) => ({ key, bike: null, eigen: null, validated: null, label: "" }));
    showView(s.view ?? "eigen", { push: false });
    let key = s.bike || `preset:${DEFAULT_PRESET}`;
    let def = s.def ?? null;
    if (def && key.startsWith("design:") && !findDesign(key.slice(7))) key = "link:";
    if (!def && key.startsWith("design:") && !findDesign(key.slice(7))) key = `preset:${DEFAULT_PRESET}`;
    if (!def && !key.startsWith("preset:") && !key.startsWith("design:")) key = `preset:${DEFAULT_PRESET}`;
    if (def && key.startsWith("design:")) {
      // The design as the link has it (it may hold edits not saved).
      await select(key, { def: findDesign(key.slice(7)).bike, keepMessage: true });
      state.bike = def;
      renderEditor();
      updateModified();
      await recompute();
    } else if (def) {
      await select(key, { def, keepMessage: true });
    } else {
      await select(key, { edits: s.edits, keepMessage: true });
    }
    await recomputeCompare();
  } finally {
    state.restoring = false;
  }
}

window.addEventListener("popstate", () => during(applyUrl));

// ---- controls -----------------------------------------------------------------------------

$("bike-select").addEventListener("change", (e) => during(async () => {
  await select(e.target.value);
  remember(true);
}));
$("compare-select").addEventListener("change", (e) => {
  const key = e.target.value;
  if (!key) state.compare = [];
  else if (!state.compare.some((c) => c.key === key)) {
    if (state.compare.length >= MAX_COMPARED) state.compare.shift();
    state.compare.push({ key, bike: null, eigen: null, validated: null, label: "" });
  }
  fillPickers();
  remember(true);
  recomputeCompare();
});
for (const id of ["v-start", "v-stop", "v-step"]) {
  $(id).addEventListener("input", showSpeedUnit);
  $(id).addEventListener("change", () => {
    schedule();
    recomputeCompare();
    remember(true);
  });
}
for (const id of ["side-centres", "side-ellipses"]) {
  $(id).addEventListener("change", () => {
    drawSide();
    remember(true);
  });
}
$("y-limit").addEventListener("change", () => {
  drawAll();
  if (state.view === "control") control.redraw();
  remember(true);
});

/** Saving refuses a form with text in a number field (it would save the last number). */
function refuseSave(what) {
  const local = editor.localErrors();
  if (!local.length) return false;
  // A recompute still pending from the last keystroke would say "Not recomputed" after this
  // refusal and hide it: it runs first (with text in a field it asks nothing of the server).
  flushScheduled();
  say(`Not saved: ${local.map((l) => l.what).join(", ")} ${local.length > 1 ? "are" : "is"} not a number. Mend ${local.length > 1 ? "them" : "it"} before saving ${what}.`, "error", "local");
  return true;
}

$("save-design").addEventListener("click", () => {
  if (refuseSave("to My designs")) return;
  const name = state.bike.name || "My design";
  state.bike.name = name;
  $("design-name").value = name;
  const design = saveDesign({ id: state.designId ?? undefined, name, bike: clone(state.bike), units: state.units });
  state.designId = design.id;
  state.key = `design:${design.id}`;
  state.baseKey = state.key;
  state.base = clone(state.bike);
  updateModified();
  $("delete-design").hidden = false;
  fillPickers();
  say(`Saved “${name}” to My designs (kept in this browser).`);
  remember(true);
});

$("delete-design").addEventListener("click", async () => {
  if (!state.designId) return;
  const design = findDesign(state.designId);
  if (!design) return;
  deleteDesign(state.designId);
  state.compare = state.compare.filter((c) => c.key !== state.key);
  state.base = null; // nothing left to keep edits for
  await select(`preset:${DEFAULT_PRESET}`);
  say(`Deleted “${design.name}” from My designs.`, "info", "undo", [{
    text: "Undo",
    testid: "undo-delete",
    run: async () => {
      saveDesign(design);
      await select(`design:${design.id}`);
      say(`“${design.name}” is back in My designs.`);
      remember(true);
    },
  }]);
  remember(true);
});

$("save-toml").addEventListener("click", async () => {
  if (refuseSave("as TOML")) return;
  try {
    const { toml } = await api.toml(state.bike, state.units);
    download(`${slug(state.bike.name ?? currentLabel())}.toml`, toml, "application/toml");
  } catch (e) {
    say(e.message, "error");
  }
});

$("copy-link").addEventListener("click", async () => {
  // As Save: a link would hold the last number, not the text in the field.
  if (refuseSave("as a link")) return;
  remember(false);
  try {
    await navigator.clipboard.writeText(location.href);
    say("The link to this view is copied.");
  } catch {
    say(`The link to this view: ${location.href}`);
  }
});

$("open-file").addEventListener("click", () => $("file-input").click());
$("file-input").addEventListener("change", (e) => during(() => openFile(e)));

/** Reads the file chosen into My designs, or the one it already is there. */
async function openFile(e) {
  const file = e.target.files?.[0];
  e.target.value = "";
  if (!file) return;
  const ext = file.name.split(".").pop().toLowerCase();
  // BicycleParameters' and HumanControl's .txt and YAML files are told apart by the server.
  const format = ext === "json" ? "json" : ext === "m" ? "m" : ext === "toml" ? "toml" : "auto";
  try {
    const { bike, units } = await api.parse(await file.text(), format, file.name);
    bike.name = bike.name ?? file.name.replace(/\.[^.]*$/, "");
    const designs = listDesigns();
    // The same file opened twice is the same design; another bicycle of the same name gets a
    // number.
    const twin = designs.find((d) => d.name === bike.name && same(d.bike, bike));
    if (twin) {
      await select(`design:${twin.id}`);
      say(`${file.name} is already in My designs as “${twin.name}”.`);
      remember(true);
      return;
    }
    let name = bike.name;
    for (let n = 2; designs.some((d) => d.name === name); n += 1) name = `${bike.name} (${n})`;
    bike.name = name;
    const design = saveDesign({ name, bike, units });
    await select(`design:${design.id}`);
    if ($("message").hidden || $("message").dataset.source === "undo") say(`Loaded ${file.name} into My designs${name !== file.name.replace(/\.[^.]*$/, "") ? ` as “${name}”` : ""}.`);
    remember(true);
  } catch (err) {
    say(`${file.name}: ${err.message}`, "error");
  }
}

const exportName = (what) => `${slug(currentLabel())}-${what}`;
$("eigen-csv").addEventListener("click", () => {
  if (!state.eigen) return;
  const designs = designsShown();
  const header = ["v"];
  const columns = [];
  designs.forEach((d, k) => {
    const prefix = k === 0 ? "" : `${slug(d.label)}_`;
    d.eigen.eigenvalues.forEach((c, j) => {
      header.push(`${prefix}re${j + 1}_${c.mode}`, `${prefix}im${j + 1}_${c.mode}`);
      columns.push([d, c]);
    });
  });
  // The critical speeds of each design in the header, ± σ where its parameters carry σ.
  const speedsOf = (d) => {
    const c = d.eigen.critical;
    if (!c) return null;
    const one = (name, v, sigma) => (v === null || v === undefined ? null : `${name} = ${v}${Number.isFinite(sigma) && sigma > 0 ? ` ± ${sigma}` : ""} m/s`);
    const parts = [one("v_d", c.double_root_speed, c.double_root_speed_sigma), one("v_w", c.weave_speed, c.weave_speed_sigma), one("v_c", c.capsize_speed, c.capsize_speed_sigma)].filter(Boolean);
    return parts.length ? `# ${d.label}: ${parts.join(", ")}` : null;
  };
  const lines = [
    `# whipple eigenvalues [1/s] against speed v [m/s] of ${designs[0].label}${designs.length > 1 ? `; compared: ${designs.slice(1).map((d) => d.label).join(", ")}` : ""}`,
    ...designs.map(speedsOf).filter(Boolean),
    header.join(","),
  ];
  state.eigen.speeds.forEach((v, i) => {
    const row = [v];
    for (const [d, c] of columns) {
      // A compared design on another grid contributes where it has the same speed.
      const j = d === designs[0] ? i : d.eigen.speeds.indexOf(v);
      row.push(j >= 0 ? c.re[j] : "", j >= 0 ? c.im[j] : "");
    }
    lines.push(row.join(","));
  });
  download(`${exportName("eigenvalues")}.csv`, `${lines.join("\n")}\n`, "text/csv");
});
const shownPlot = () => (state.view === "locus" ? locus : plot);
$("eigen-svg").addEventListener("click", () => shownPlot().svgEl && download(`${exportName(state.view === "locus" ? "root-locus" : "eigenvalues")}.svg`, svgText(shownPlot().svgEl), "image/svg+xml"));
$("eigen-png").addEventListener("click", async () => shownPlot().svgEl && download(`${exportName(state.view === "locus" ? "root-locus" : "eigenvalues")}.png`, await svgPng(shownPlot().svgEl)));
$("side-svg").addEventListener("click", () => sideSvg && download(`${exportName("side-view")}.svg`, svgText(sideSvg), "image/svg+xml"));
$("side-png").addEventListener("click", async () => sideSvg && download(`${exportName("side-view")}.png`, await svgPng(sideSvg)));

let resizeTimer = 0;
new ResizeObserver(() => {
  clearTimeout(resizeTimer);
  resizeTimer = setTimeout(drawSide, 60);
}).observe($("side-view"));

// ---- start --------------------------------------------------------------------------------

// The static site keeps its files for offline use (its service worker, sw.js beside the page).
if (inBrowser && "serviceWorker" in navigator) {
  navigator.serviceWorker.register("sw.js").catch((e) => console.warn(`offline use is unavailable: ${e.message}`));
}

(async () => {
  try {
    const [presets, table] = await Promise.all([api.presets(), api.parameters()]);
    state.presets = presets;
    const unknown = applyParameterTable(table);
    if (unknown.length) console.warn(`the server's parameter table lacks ${unknown.join(", ")}`);
  } catch (e) {
    say(e.message, "error");
    return;
  }
  state.key = `preset:${DEFAULT_PRESET}`;
  fillPickers();
  await applyUrl();
  writeUrl(snapshot(), false);
  document.body.dataset.ready = "true";
})();
