// The page: a bike picker, the parameter editor, the side view, the critical speeds and the
// eigenvalues against speed, kept in step with the API.

import "./style.css";
import { api } from "./api.js";
import { listDesigns, saveDesign, deleteDesign, findDesign } from "./store.js";
import { Editor, parseNumber } from "./editor.js";
import { setPath } from "./fields.js";
import { drawSideView } from "./sideview.js";
import { EigenPlot } from "./plot.js";
import { drawCritical } from "./critical.js";
import { SimPanel } from "./sim.js";
import { html, slug, download, svgText, svgPng } from "./format.js";

const $ = (id) => document.getElementById(id);
const clone = (x) => JSON.parse(JSON.stringify(x));
const DEFAULT_PRESET = "schwinn-crown";

const state = {
  presets: [],
  key: "",
  designId: null,
  bike: null,
  form: "jbike6",
  modified: false,
  validated: null,
  eigen: null,
  valid: true,
  compare: { key: "", bike: null, eigen: null, validated: null, label: "" },
};

const editor = new Editor($("editor-body"), (path, value) => {
  const table = state.bike.jbike6 ? (state.form === "jbike6" ? state.bike.jbike6 : null) : state.bike.benchmark;
  if (!table) return;
  setPath(table, path, value);
  setModified(true);
  schedule();
});
const plot = new EigenPlot($("eigen-plot"));
const sim = new SimPanel({ bike: () => clone(state.bike) });
let sideSvg = null;

// ---- messages ---------------------------------------------------------------------------

/** Shows a message; `source` says who may clear it ("bike" for validation, else any caller). */
function say(text, kind = "info", source = "general") {
  const box = $("message");
  box.className = `message ${kind}`;
  box.dataset.source = source;
  box.replaceChildren(html("span", { text }));
  box.hidden = !text;
}

/** Hides the message if it came from `source` (every message when no source is given). */
function quiet(source) {
  const box = $("message");
  if (!source || box.dataset.source === source) box.hidden = true;
}

// ---- picker -------------------------------------------------------------------------------

function optionLabel(p) {
  return p.name === DEFAULT_PRESET ? `${p.name} (JBike6 default)` : p.name;
}

function fillPickers() {
  const designs = listDesigns();
  for (const select of [$("bike-select"), $("compare-select")]) {
    const keep = select.value;
    select.replaceChildren();
    if (select.id === "compare-select") select.append(html("option", { value: "", text: "— nothing —" }));
    const presets = html("optgroup", { label: "Presets" });
    for (const p of state.presets) presets.append(html("option", { value: `preset:${p.name}`, text: optionLabel(p), title: p.summary }));
    select.append(presets);
    const mine = html("optgroup", { label: designs.length ? "My designs" : "My designs (none saved yet)" });
    for (const d of designs) mine.append(html("option", { value: `design:${d.id}`, text: d.name }));
    select.append(mine);
    select.value = keep;
  }
  $("bike-select").value = state.key;
  $("compare-select").value = state.compare.key;
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
  return bike?.name ?? key.slice(7);
}

async function select(key) {
  try {
    const bike = await bikeFor(key);
    state.key = key;
    state.designId = key.startsWith("design:") ? key.slice(7) : null;
    state.bike = bike;
    state.form = bike.jbike6 ? "jbike6" : "benchmark";
    state.validated = null;
    setModified(false);
    $("design-name").value = bike.name ?? "";
    $("delete-design").hidden = !state.designId;
    fillPickers();
    quiet();
    renderEditor();
    await recompute();
  } catch (e) {
    say(e.message, "error");
  }
}

function setModified(on) {
  state.modified = on;
  $("modified").hidden = !on;
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
}

function convertToBenchmark() {
  if (!state.validated) {
    say("Mend the invalid parameters first: the conversion needs a valid bicycle.", "error");
    return;
  }
  state.bike = { ...(state.bike.name ? { name: `${state.bike.name} (benchmark form)` } : {}), ...(state.bike.source ? { source: state.bike.source } : {}), benchmark: clone(state.validated.benchmark) };
  state.designId = null;
  $("design-name").value = state.bike.name ?? "";
  state.form = "benchmark";
  setModified(true);
  renderEditor();
  say("Now in the benchmark form: save it to keep it.");
  schedule();
}

for (const tab of document.querySelectorAll(".tab[data-form]")) {
  tab.addEventListener("click", () => {
    if (tab.disabled) return;
    state.form = tab.dataset.form;
    renderEditor();
    if (state.lastError) editor.flag(state.lastError);
  });
}

$("design-name").addEventListener("input", () => {
  const name = $("design-name").value.trim();
  if (name) state.bike.name = name;
  else delete state.bike.name;
  setModified(true);
});

// ---- computing ----------------------------------------------------------------------------

function speedGrid() {
  const read = (id) => parseNumber($(id).value);
  return { start: read("v-start"), stop: read("v-stop"), step: read("v-step") };
}

function yLimit() {
  const y = parseNumber($("y-limit").value);
  return y && y > 0 ? y : 10;
}

let timer = 0;
function schedule() {
  clearTimeout(timer);
  timer = setTimeout(recompute, 120);
}

let sequence = 0;
async function recompute() {
  const mine = ++sequence;
  if (editor.hasLocalErrors()) {
    say("Some entries are not numbers.", "error", "bike");
    showStale();
    return;
  }
  const grid = speedGrid();
  for (const id of ["v-start", "v-stop", "v-step"]) $(id).classList.remove("invalid");
  if (Object.values(grid).some((x) => x === null)) {
    for (const id of ["v-start", "v-stop", "v-step"]) if (parseNumber($(id).value) === null) $(id).classList.add("invalid");
    $("eigen-message").textContent = "The speeds must be numbers.";
    $("eigen-message").hidden = false;
    return;
  }
  const bike = clone(state.bike);
  const [validated, eigen] = await Promise.allSettled([api.validate(bike), api.eigen(bike, grid)]);
  if (mine !== sequence) return;
  if (validated.status === "rejected") {
    const error = validated.reason;
    state.valid = false;
    state.lastError = error;
    const flagged = editor.flag(error);
    say(error.message, "error", "bike");
    $("message").dataset.field = error.field ?? "";
    if (!flagged && state.bike.jbike6 && state.form === "jbike6") {
      $("message").append(html("span", { class: "hint", text: " (a rule of the benchmark form, checked after combining the bodies)" }));
    }
    showStale();
    return;
  }
  state.valid = true;
  state.lastError = null;
  editor.clearServerFlags();
  state.validated = validated.value;
  if (state.form === "benchmark" && state.bike.jbike6) renderEditor();
  if (eigen.status === "rejected") {
    const error = eigen.reason;
    if (error.field === "speeds" || error.field === "range") for (const id of ["v-start", "v-stop", "v-step"]) $(id).classList.add("invalid");
    $("eigen-message").textContent = error.message;
    $("eigen-message").hidden = false;
    quiet("bike");
    drawSide();
    return;
  }
  $("eigen-message").hidden = true;
  quiet("bike");
  state.eigen = eigen.value;
  sim.suggestSpeed(state.eigen.critical);
  drawAll();
}

async function recomputeCompare() {
  const c = state.compare;
  if (!c.key) {
    c.eigen = null;
    c.validated = null;
    drawAll();
    return;
  }
  const grid = speedGrid();
  try {
    c.bike = c.bike ?? (await bikeFor(c.key));
    c.label = labelFor(c.key, c.bike);
    const [validated, eigen] = await Promise.all([api.validate(c.bike), api.eigen(c.bike, grid)]);
    c.validated = validated;
    c.eigen = eigen;
  } catch (e) {
    c.eigen = null;
    c.validated = null;
    say(`The design compared with cannot be computed: ${e.message}`, "error");
  }
  drawAll();
}

function currentLabel() {
  return state.bike?.name ?? labelFor(state.key, state.bike);
}

function drawSide() {
  if (!state.validated) return;
  sideSvg = drawSideView($("side-view"), state.validated.side_view, state.compare.validated?.side_view ?? null, { stale: !state.valid });
  const v = state.validated;
  $("side-meta").textContent = `${v.form === "jbike6" ? "JBike6 form" : "benchmark form"} · ${v.derived.total_mass.toFixed(1)} kg · head angle ${v.derived.head_angle_deg.toFixed(2)}°`;
}

function drawAll() {
  drawSide();
  if (!state.eigen) return;
  const primary = { label: currentLabel(), eigen: state.eigen };
  const secondary = state.compare.eigen ? { label: state.compare.label, eigen: state.compare.eigen } : null;
  plot.update(primary, secondary, { ylim: yLimit(), stale: !state.valid });
  drawCritical($("critical"), { label: primary.label, critical: state.eigen.critical }, secondary && { label: secondary.label, critical: secondary.eigen.critical }, { stale: !state.valid });
}

function showStale(text) {
  if (text) say(text, "error");
  drawAll();
}

// ---- bottom panel: eigenvalues or simulation ------------------------------------------------

function showView(view) {
  $("panel-eigen").hidden = view !== "eigen";
  $("panel-sim").hidden = view !== "sim";
  document.querySelector(".layout").classList.toggle("sim-active", view === "sim");
  for (const tab of document.querySelectorAll(".tab[data-view]")) tab.setAttribute("aria-selected", String(tab.dataset.view === view));
  if (view === "eigen") drawAll();
}
for (const tab of document.querySelectorAll(".tab[data-view]")) tab.addEventListener("click", () => showView(tab.dataset.view));

// ---- controls -----------------------------------------------------------------------------

$("bike-select").addEventListener("change", (e) => select(e.target.value));
$("compare-select").addEventListener("change", (e) => {
  state.compare = { key: e.target.value, bike: null, eigen: null, validated: null, label: "" };
  recomputeCompare();
});
for (const id of ["v-start", "v-stop", "v-step"]) {
  $(id).addEventListener("change", () => {
    schedule();
    recomputeCompare();
  });
}
$("y-limit").addEventListener("change", drawAll);

$("save-design").addEventListener("click", () => {
  const name = state.bike.name || "My design";
  state.bike.name = name;
  $("design-name").value = name;
  const design = saveDesign({ id: state.designId ?? undefined, name, bike: clone(state.bike) });
  state.designId = design.id;
  state.key = `design:${design.id}`;
  setModified(false);
  $("delete-design").hidden = false;
  fillPickers();
  say(`Saved “${name}” to My designs (kept in this browser).`);
});

$("delete-design").addEventListener("click", () => {
  if (!state.designId) return;
  const name = findDesign(state.designId)?.name ?? "design";
  deleteDesign(state.designId);
  if (state.compare.key === state.key) state.compare = { key: "", bike: null, eigen: null, validated: null, label: "" };
  say(`Deleted “${name}” from My designs.`);
  select(`preset:${DEFAULT_PRESET}`);
});

$("save-toml").addEventListener("click", async () => {
  try {
    const { toml } = await api.toml(state.bike);
    download(`${slug(state.bike.name)}.toml`, toml, "application/toml");
  } catch (e) {
    say(e.message, "error");
  }
});

$("open-file").addEventListener("click", () => $("file-input").click());
$("file-input").addEventListener("change", async (e) => {
  const file = e.target.files?.[0];
  e.target.value = "";
  if (!file) return;
  const ext = file.name.split(".").pop().toLowerCase();
  const format = ext === "json" ? "json" : ext === "m" ? "m" : "toml";
  try {
    const { bike } = await api.parse(await file.text(), format);
    bike.name = bike.name ?? file.name.replace(/\.[^.]*$/, "");
    const design = saveDesign({ name: bike.name, bike });
    await select(`design:${design.id}`);
    if ($("message").hidden) say(`Loaded ${file.name} into My designs.`);
  } catch (err) {
    say(`${file.name}: ${err.message}`, "error");
  }
});

const exportName = (what) => `${slug(currentLabel())}-${what}`;
$("eigen-csv").addEventListener("click", () => {
  if (!state.eigen) return;
  const cols = state.eigen.eigenvalues;
  const lines = ["v,re1,im1,re2,im2,re3,im3,re4,im4"];
  state.eigen.speeds.forEach((v, i) => lines.push([v, ...cols.flatMap((c) => [c.re[i], c.im[i]])].join(",")));
  download(`${exportName("eigenvalues")}.csv`, `${lines.join("\n")}\n`, "text/csv");
});
$("eigen-svg").addEventListener("click", () => plot.svgEl && download(`${exportName("eigenvalues")}.svg`, svgText(plot.svgEl), "image/svg+xml"));
$("eigen-png").addEventListener("click", async () => plot.svgEl && download(`${exportName("eigenvalues")}.png`, await svgPng(plot.svgEl)));
$("side-svg").addEventListener("click", () => sideSvg && download(`${exportName("side-view")}.svg`, svgText(sideSvg), "image/svg+xml"));
$("side-png").addEventListener("click", async () => sideSvg && download(`${exportName("side-view")}.png`, await svgPng(sideSvg)));

let resizeTimer = 0;
new ResizeObserver(() => {
  clearTimeout(resizeTimer);
  resizeTimer = setTimeout(drawSide, 60);
}).observe($("side-view"));

// ---- start --------------------------------------------------------------------------------

(async () => {
  try {
    state.presets = await api.presets();
  } catch (e) {
    say(e.message, "error");
    return;
  }
  state.key = `preset:${DEFAULT_PRESET}`;
  fillPickers();
  await select(state.key);
  document.body.dataset.ready = "true";
})();
