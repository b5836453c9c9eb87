// The parameter forms' layout: every number of the JBike6 and benchmark layouts in the order and
// groups the page shows them, with the name the library uses in its messages and files (`lib`)
// and a short label. What each number means and its unit come from the library's parameter
// table (GET /api/parameters, [applyParameterTable]), their one home. Angles are stored in
// radians (the files' unit) and typed in degrees (`angle: true`); `plausible` is the range in
// degrees where a value is expected, so that one typed in radians can be recognised.

const I3 = ["I11", "I22", "Izz"];

function wheel(key, lib, title) {
  return {
    title,
    rows: [
      { path: [key, "D"], lib: `D${lib}`, label: "D" },
      { path: [key, "m"], lib: `m${lib}`, label: "m" },
      { triple: [0, 1, 2].map((k) => ({ path: [key, "I", k], lib: `I${lib}(${k + 1})`, label: I3[k] })), label: "I" },
      { path: [key, "alpha"], lib: `alphaI${lib}`, label: "α", angle: true },
    ],
  };
}

function rearBody(key, title) {
  return {
    title,
    rows: [
      { path: [key, "m"], lib: `m${key}`, label: "m" },
      { path: [key, "xcm"], lib: `xcm${key}`, label: "x" },
      { path: [key, "ycm"], lib: `ycm${key}`, label: "y" },
      { triple: [0, 1, 2].map((k) => ({ path: [key, "I", k], lib: `I${key}(${k + 1})`, label: I3[k] })), label: "I" },
      { path: [key, "alpha"], lib: `alphaI${key}`, label: "α", angle: true },
    ],
  };
}

function frontBody(key, title) {
  return {
    title,
    rows: [
      { path: [key, "m"], lib: `m${key}`, label: "m" },
      { path: [key, "ucm"], lib: `ucm${key}`, label: "u" },
      { path: [key, "vcm"], lib: `vcm${key}`, label: "v" },
      { triple: [0, 1, 2].map((k) => ({ path: [key, "I", k], lib: `I${key}(${k + 1})`, label: I3[k] })), label: "I" },
      { path: [key, "alpha"], lib: `alphaI${key}`, label: "α", angle: true },
    ],
  };
}

/** JBike6's form (Schwab & Papadopoulos 2003): x forward from the rear contact, y up. */
export const JBIKE6_GROUPS = [
  {
    title: "Geometry",
    rows: [
      { path: ["wheelbase"], lib: "wheelbase", label: "wheelbase" },
      { path: ["head_angle"], lib: "head_angle", label: "head angle", angle: true, plausible: [45, 90] },
      { path: ["trail"], lib: "trail", label: "trail" },
      { path: ["gravity"], lib: "gravity", label: "gravity" },
    ],
  },
  wheel("rear_wheel", "rearwheel", "Rear wheel"),
  wheel("front_wheel", "frontwheel", "Front wheel"),
  rearBody("rider", "Rider"),
  rearBody("frame", "Frame"),
  rearBody("rack", "Rear rack"),
  frontBody("fork", "Fork and handlebar"),
  frontBody("basket", "Front basket"),
];

function b(key, label, extra = {}) {
  return { path: [key], lib: key, label, ...extra };
}

/** Meijaard et al. 2007, Table 1: x forward, y right, z down from the rear contact. */
export const BENCHMARK_GROUPS = [
  {
    title: "Geometry",
    rows: [
      b("w", "w"),
      b("c", "c"),
      b("lam", "λ", { angle: true, plausible: [0, 45] }),
      b("g", "g"),
    ],
  },
  {
    title: "Rear wheel R",
    rows: [b("rR", "r_R"), b("mR", "m_R"), b("IRxx", "I_Rxx"), b("IRyy", "I_Ryy")],
  },
  {
    title: "Rear body and frame B",
    rows: [
      b("xB", "x_B"),
      b("zB", "z_B"),
      b("mB", "m_B"),
      b("IBxx", "I_Bxx"),
      b("IByy", "I_Byy"),
      b("IBzz", "I_Bzz"),
      b("IBxz", "I_Bxz"),
    ],
  },
  {
    title: "Front frame H",
    rows: [
      b("xH", "x_H"),
      b("zH", "z_H"),
      b("mH", "m_H"),
      b("IHxx", "I_Hxx"),
      b("IHyy", "I_Hyy"),
      b("IHzz", "I_Hzz"),
      b("IHxz", "I_Hxz"),
    ],
  },
  {
    title: "Front wheel F",
    rows: [b("rF", "r_F"), b("mF", "m_F"), b("IFxx", "I_Fxx"), b("IFyy", "I_Fyy")],
  },
];

/** A unit as the page prints it: `kg m^2` → `kg m²`. */
function prettyUnit(unit) {
  return unit.replace(/\^2/g, "²").replace(/\^3/g, "³");
}

/** A description's first clause without its asides: what a hint or a message calls it. */
function shortDescription(text) {
  return text.replace(/\s*\([^)]*\)/g, "").split(";")[0].trim();
}

/**
 * Fills every row's `unit` and `hint` (and each cell's `description`) from the library's
 * parameter table, the body of GET /api/parameters ({benchmark: [...], jbike6: [...],
 * jbike6_sources: {key: [...]}}, each entry {key, unit, description, ...}), and
 * [JBIKE6_SOURCES]. Returns the `lib` names the table does not know (none, unless the page and
 * the server disagree).
 */
export function applyParameterTable(table) {
  Object.assign(JBIKE6_SOURCES, table.jbike6_sources ?? {});
  const byKey = new Map([...(table.benchmark ?? []), ...(table.jbike6 ?? [])].map((p) => [p.key, p]));
  const unknown = [];
  for (const group of [...JBIKE6_GROUPS, ...BENCHMARK_GROUPS]) {
    for (const row of group.rows) {
      const cells = row.triple ?? [row];
      const infos = cells.map((c) => byKey.get(c.lib));
      cells.forEach((c, k) => {
        if (infos[k]) c.description = infos[k].description;
        else unknown.push(c.lib);
      });
      const first = infos.find(Boolean);
      if (!first) continue;
      row.unit = row.angle ? "°" : prettyUnit(first.unit);
      row.hint = row.triple
        ? infos.filter(Boolean).map((i) => shortDescription(i.description)).join("; ")
        : shortDescription(first.description);
    }
  }
  return unknown;
}

export function getPath(obj, path) {
  return path.reduce((o, k) => (o == null ? undefined : o[k]), obj);
}

export function setPath(obj, path, value) {
  let o = obj;
  for (const k of path.slice(0, -1)) o = o[k];
  o[path[path.length - 1]] = value;
}

/**
 * Where a rule of the benchmark form, checked after JBike6's bodies are combined, comes from in
 * the JBike6 form: the fields to flag for a benchmark name in an error. Filled by
 * [applyParameterTable] from the library's table (`jbike6_sources` of GET /api/parameters).
 */
export const JBIKE6_SOURCES = {};
