// The parameter forms: every number of the JBike6 and benchmark layouts, with the name the
// library uses in its messages (`lib`), a label, a unit and a one-line meaning. Angles are
// stored in radians (the files' unit) and typed in degrees (`angle: true`); `plausible` is the
// range in degrees where a value is expected, so that one typed in radians can be recognised.

const I3 = ["I11", "I22", "Izz"];

function wheel(key, lib, title) {
  return {
    title,
    rows: [
      { path: [key, "D"], lib: `D${lib}`, label: "D", unit: "m", hint: "diameter" },
      { path: [key, "m"], lib: `m${lib}`, label: "m", unit: "kg", hint: "mass" },
      { triple: [0, 1, 2].map((k) => ({ path: [key, "I", k], lib: `I${lib}(${k + 1})`, label: I3[k] })), label: "I", unit: "kg m²", hint: "principal moments: two diametral, then spin" },
      { path: [key, "alpha"], lib: `alphaI${lib}`, label: "α", unit: "°", hint: "angle of axis 1 from x", angle: true },
    ],
  };
}

function rearBody(key, title) {
  return {
    title,
    rows: [
      { path: [key, "m"], lib: `m${key}`, label: "m", unit: "kg", hint: "mass" },
      { path: [key, "xcm"], lib: `xcm${key}`, label: "x", unit: "m", hint: "centre of mass, forward of the rear contact" },
      { path: [key, "ycm"], lib: `ycm${key}`, label: "y", unit: "m", hint: "centre of mass, above the ground" },
      { triple: [0, 1, 2].map((k) => ({ path: [key, "I", k], lib: `I${key}(${k + 1})`, label: I3[k] })), label: "I", unit: "kg m²", hint: "principal moments about the centre of mass" },
      { path: [key, "alpha"], lib: `alphaI${key}`, label: "α", unit: "°", hint: "angle of axis 1 from x, counter-clockwise", angle: true },
    ],
  };
}

function frontBody(key, title) {
  return {
    title,
    rows: [
      { path: [key, "m"], lib: `m${key}`, label: "m", unit: "kg", hint: "mass" },
      { path: [key, "ucm"], lib: `ucm${key}`, label: "u", unit: "m", hint: "centre of mass, perpendicular to the steer axis (forward)" },
      { path: [key, "vcm"], lib: `vcm${key}`, label: "v", unit: "m", hint: "centre of mass, up the steer axis from the ground" },
      { triple: [0, 1, 2].map((k) => ({ path: [key, "I", k], lib: `I${key}(${k + 1})`, label: I3[k] })), label: "I", unit: "kg m²", hint: "principal moments about the centre of mass" },
      { path: [key, "alpha"], lib: `alphaI${key}`, label: "α", unit: "°", hint: "angle of axis 1 from x, counter-clockwise", angle: true },
    ],
  };
}

/** JBike6's form (Schwab & Papadopoulos 2003): x forward from the rear contact, y up. */
export const JBIKE6_GROUPS = [
  {
    title: "Geometry",
    rows: [
      { path: ["wheelbase"], lib: "wheelbase", label: "wheelbase", unit: "m", hint: "horizontal distance between the wheel contacts" },
      { path: ["head_angle"], lib: "head_angle", label: "head angle", unit: "°", hint: "steer axis angle from the horizontal", angle: true, plausible: [45, 90] },
      { path: ["trail"], lib: "trail", label: "trail", unit: "m", hint: "front contact behind the steer axis' ground point" },
      { path: ["gravity"], lib: "gravity", label: "gravity", unit: "m/s²", hint: "gravitational acceleration" },
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

function b(key, label, unit, hint, extra = {}) {
  return { path: [key], lib: key, label, unit, hint, ...extra };
}

/** Meijaard et al. 2007, Table 1: x forward, y right, z down from the rear contact. */
export const BENCHMARK_GROUPS = [
  {
    title: "Geometry",
    rows: [
      b("w", "w", "m", "wheelbase"),
      b("c", "c", "m", "trail"),
      b("lam", "λ", "°", "steer axis tilt from the vertical", { angle: true, plausible: [0, 45] }),
      b("g", "g", "m/s²", "gravitational acceleration"),
    ],
  },
  {
    title: "Rear wheel R",
    rows: [b("rR", "r_R", "m", "radius"), b("mR", "m_R", "kg", "mass"), b("IRxx", "I_Rxx", "kg m²", "diametral moment"), b("IRyy", "I_Ryy", "kg m²", "spin moment")],
  },
  {
    title: "Rear body and frame B",
    rows: [
      b("xB", "x_B", "m", "centre of mass, forward"),
      b("zB", "z_B", "m", "centre of mass, down (negative: above the ground)"),
      b("mB", "m_B", "kg", "mass"),
      b("IBxx", "I_Bxx", "kg m²", "moment about x"),
      b("IByy", "I_Byy", "kg m²", "moment about y (pitch)"),
      b("IBzz", "I_Bzz", "kg m²", "moment about z (yaw)"),
      b("IBxz", "I_Bxz", "kg m²", "product of inertia"),
    ],
  },
  {
    title: "Front frame H",
    rows: [
      b("xH", "x_H", "m", "centre of mass, forward"),
      b("zH", "z_H", "m", "centre of mass, down (negative: above the ground)"),
      b("mH", "m_H", "kg", "mass"),
      b("IHxx", "I_Hxx", "kg m²", "moment about x"),
      b("IHyy", "I_Hyy", "kg m²", "moment about y"),
      b("IHzz", "I_Hzz", "kg m²", "moment about z"),
      b("IHxz", "I_Hxz", "kg m²", "product of inertia"),
    ],
  },
  {
    title: "Front wheel F",
    rows: [b("rF", "r_F", "m", "radius"), b("mF", "m_F", "kg", "mass"), b("IFxx", "I_Fxx", "kg m²", "diametral moment"), b("IFyy", "I_Fyy", "kg m²", "spin moment")],
  },
];

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
 * the JBike6 form: the fields to flag for a benchmark name in an error.
 */
export const JBIKE6_SOURCES = {
  w: ["wheelbase"], c: ["trail"], lam: ["head_angle"], g: ["gravity"],
  rR: ["Drearwheel"], mR: ["mrearwheel"], IRxx: ["Irearwheel(1)", "Irearwheel(2)"], IRyy: ["Irearwheel(3)", "Drearwheel"],
  rF: ["Dfrontwheel"], mF: ["mfrontwheel"], IFxx: ["Ifrontwheel(1)", "Ifrontwheel(2)"], IFyy: ["Ifrontwheel(3)", "Dfrontwheel"],
  ...Object.fromEntries(["xB", "zB", "mB", "IBxx", "IByy", "IBzz", "IBxz"].map((k) => [k, ["mrider", "mframe", "mrack"]])),
  ...Object.fromEntries(["xH", "zH", "mH", "IHxx", "IHyy", "IHzz", "IHxz"].map((k) => [k, ["mfork", "mbasket"]])),
};

/** Display names of the presets (the API lists their file names and summaries). */
export const PRESET_TITLES = {
  benchmark: "Benchmark bicycle (Meijaard et al. 2007)",
  "schwinn-crown": "Schwinn Crown (JBike6 default)",
  "two-mass-skate": "Two-mass skate (Kooijman et al. 2011)",
  "browser-jason": "Batavus Browser with rider Jason (Moore 2012)",
};
