// The Measure tab: the bench, in order (Moore 2012 ch. 2), as a form under BicycleParameters'
// keys of `<Name>Measured.txt`. Each section says what to measure, draws the set-up and holds
// its fields (value ± σ, in the file's units); every number derived is the server's
// (POST /api/measure, the library's pipeline), shown beside the section that feeds it as the
// fields are typed. A `*Measured.txt` opens into the form and the form saves as one; "Load into
// editor" hands the bicycle (values with σ) to the parameter editor.

import { api } from "./api.js";
import { begin, during } from "./work.js";
import { parseNumber } from "./editor.js";
import { html, num, download, inputText, minus } from "./format.js";

const $ = (id) => document.getElementById(id);
const DEBOUNCE_MS = 300;
/** Hangings of a frame the form offers at most (the library reads up to 16). */
const MAX_HANGINGS = 16;

const field = (key, label, unit, hint) => ({ key, label, unit, hint });

/** The bench's sections, in the order the measurements are made. `steps`: which of the
 * library's step functions (and which keys taken as measured) each section shows. */
const SECTIONS = [
  {
    id: "wheels",
    title: "1 · Wheels",
    text: "Roll each wheel in a straight line over the floor for a whole number of turns (a chalk mark on the tyre) and measure the distance; weigh it.",
    drawing: "wheel",
    fields: [
      field("dR", "dR", "m", "distance the rear wheel rolled"),
      field("nR", "nR", "turns", "whole turns of the rear wheel over dR"),
      field("dF", "dF", "m", "distance the front wheel rolled"),
      field("nF", "nF", "turns", "whole turns of the front wheel over dF"),
      field("mR", "mR", "kg", "rear wheel mass"),
      field("mF", "mF", "kg", "front wheel mass"),
    ],
    steps: (s) => s.function === "wheel_radius" || ["mR", "mF"].includes(s.key) && !s.function,
  },
  {
    id: "geometry",
    title: "2 · Geometry",
    text: "On level ground, with the bicycle upright and the steer straight: the wheelbase between the wheels' contact points, the head tube's angle with the ground, and the fork offset (the front hub's distance from the steer axis).",
    drawing: "geometry",
    fields: [
      field("w", "w", "m", "wheelbase"),
      field("gamma", "gamma", "°", "head tube angle with the ground"),
      field("f", "f", "m", "fork offset"),
    ],
    steps: (s) => ["steer_axis_tilt", "trail"].includes(s.function) || (s.key === "w" && !s.function),
  },
  {
    id: "rod",
    title: "3 · Calibration rod",
    text: "Hang a steel rod of known mass, length and diameter by its middle from the torsion pendulum's wire and time its twisting oscillation: this gives the wire's torsion constant k.",
    drawing: "rod",
    fields: [
      field("mP", "mP", "kg", "the rod's mass"),
      field("lP", "lP", "m", "the rod's length"),
      field("dP", "dP", "m", "the rod's diameter"),
      field("TtP1", "TtP1", "s", "the rod's torsional period"),
    ],
    steps: (s) => ["rod_transverse_inertia", "torsion_constant"].includes(s.function),
  },
  {
    id: "frames",
    title: "4 · Frames hung from the wire",
    text: "Hang each frame from the wire at three or more angles. In each: the angle α of the steer axis with the horizontal, the distance a from the wheel's axle to the wire's plumb line (positive with the axle on its left, right side view) and the period of the twisting oscillation. The plumb lines cross at the mass centre.",
    drawing: "hanging",
    fields: [field("mB", "mB", "kg", "rear frame mass"), field("mH", "mH", "kg", "front frame (fork and handlebar) mass")],
    hangings: true,
    steps: (s) => ["hanging_line", "intersection", "mass_centre", "line_residual"].includes(s.function) || (["mB", "mB_frame", "mH"].includes(s.key) && !s.function),
  },
  {
    id: "compound",
    title: "5 · Compound pendulums",
    text: "Swing each wheel from a knife edge inside its rim, and each frame about its wheel's axle, and time a small oscillation; lR and lF are the distances from the knife edge to the axle.",
    drawing: "compound",
    fields: [
      field("g", "g", "m/s²", "gravity where the pendulums swung"),
      field("lR", "lR", "m", "rear wheel: knife edge to axle"),
      field("TcR1", "TcR1", "s", "rear wheel's compound period"),
      field("lF", "lF", "m", "front wheel: knife edge to axle"),
      field("TcF1", "TcF1", "s", "front wheel's compound period"),
      field("TcB1", "TcB1", "s", "rear frame's compound period, about the rear axle"),
      field("TcH1", "TcH1", "s", "front frame's compound period, about the front axle"),
    ],
    steps: (s) => ["compound_pendulum_inertia", "pendulum_length"].includes(s.function) || (s.key === "g" && !s.function),
  },
  {
    id: "torsional",
    title: "6 · Torsional pendulums",
    text: "Hang each wheel from the wire by its rim, its plane vertical, and time its twisting about a diameter. (The frames' torsional periods TtB, TtH are timed in their hangings, section 4.)",
    drawing: "torsional",
    fields: [
      field("TtR1", "TtR1", "s", "rear wheel's torsional period about a diameter"),
      field("TtF1", "TtF1", "s", "front wheel's torsional period about a diameter"),
    ],
    steps: (s) => ["torsional_pendulum_inertia", "planar_inertia", "principal_planar"].includes(s.function),
  },
  {
    id: "rider",
    title: "7 · The rider (optional)",
    text: "Seat a rider measured for Yeadon's body model — the 95 lengths of a <Rider>YeadonMeas.txt, in the posture of a <Rider><Bike>YeadonCFG.txt — on this bicycle: the hips, knees, shoulders and elbows are solved so that the feet reach the bottom bracket and the hands the grips, placed by the frame's measurements below, and the rider joins the rear frame.",
    drawing: "rider",
    fields: [
      field("lcs", "lcs", "m", "chain stay length, rear hub to bottom bracket"),
      field("hbb", "hbb", "m", "bottom bracket height above the ground"),
      field("lst", "lst", "m", "seat tube length, from the bottom bracket"),
      field("lsp", "lsp", "m", "seat post length, out of the seat tube"),
      field("lamst", "lamst", "rad", "seat tube angle with the ground, rising backwards"),
      field("whb", "whb", "m", "handlebar width, between the grips"),
      field("LhbF", "LhbF", "m", "distance from the front hub to a grip"),
      field("LhbR", "LhbR", "m", "distance from the rear hub to a grip"),
    ],
    rider: true,
    steps: (s) => ["bottom_bracket", "seat", "handlebar_grips", "seated_configuration", "rider_in_benchmark_frame", "combine_with_rear_frame"].includes(s.function),
  },
];
/** The rider's seat and handlebar keys: fields of section 7, not kept keys. */
const RIDER_KEYS = SECTIONS.find((s) => s.rider).fields.map((f) => f.key);

const HANGING_COLUMNS = [
  { prefix: "alpha", unit: "°", hint: "steer axis angle with the horizontal" },
  { prefix: "a", unit: "m", hint: "axle to the wire's plumb line" },
  { prefix: "Tt", unit: "s", hint: "torsional period in this hanging" },
];
const FRAMES = [
  { part: "B", name: "rear frame" },
  { part: "H", name: "front frame" },
];

/** The order a saved file lists its keys in. */
function keyOrder(counts) {
  const keys = SECTIONS.flatMap((s) => s.fields.map((f) => f.key));
  for (const { part } of FRAMES) for (let i = 1; i <= counts[part]; i++) for (const c of HANGING_COLUMNS) keys.push(`${c.prefix}${part}${i}`);
  return keys;
}

/** A value to the decimals of its three-digit σ, as `whipple measure` prints it. */
export function withSigma(value, sigma) {
  if (sigma === null || sigma === undefined) return `${num(value, 6)}`;
  if (!(sigma > 0)) return num(value, 6);
  const digits = Math.max(0, 2 - Math.floor(Math.log10(Math.abs(sigma))));
  return `${minus(value.toFixed(digits))} ± ${sigma.toFixed(digits)}`;
}

const unitText = (u) => u.replace("^2", "²");

// ---- drawings: the set-ups, labelled with the keys -------------------------------------------

const INK = "#111827";
const ACCENT = "#2563eb";
const MUTED = "#6b7280";

function wheelSvg(cx, cy, r, mark = null) {
  let spokes = "";
  for (let k = 0; k < 6; k++) {
    const a = (k * Math.PI) / 3 + 0.3;
    spokes += `<line x1="${cx}" y1="${cy}" x2="${(cx + r * Math.cos(a)).toFixed(1)}" y2="${(cy + r * Math.sin(a)).toFixed(1)}" stroke="${MUTED}" stroke-width="0.8"/>`;
  }
  const dot = mark ? `<circle cx="${mark[0]}" cy="${mark[1]}" r="3" fill="${ACCENT}"/>` : "";
  return `<circle cx="${cx}" cy="${cy}" r="${r}" fill="none" stroke="${INK}" stroke-width="3"/>${spokes}<circle cx="${cx}" cy="${cy}" r="2.5" fill="${INK}"/>${dot}`;
}

const ARROWS = `<defs><marker id="ms-arrow" viewBox="0 0 8 8" refX="7" refY="4" markerWidth="7" markerHeight="7" orient="auto-start-reverse"><path d="M0 0 8 4 0 8z" fill="${ACCENT}"/></marker></defs>`;
const label = (x, y, text, anchor = "middle", colour = ACCENT) => `<text x="${x}" y="${y}" text-anchor="${anchor}" font-size="11" font-family="ui-monospace, monospace" fill="${colour}">${text}</text>`;
const dim = (x1, y1, x2, y2) => `<line x1="${x1}" y1="${y1}" x2="${x2}" y2="${y2}" stroke="${ACCENT}" stroke-width="1.2" marker-start="url(#ms-arrow)" marker-end="url(#ms-arrow)"/>`;

const DRAWINGS = {
  wheel: {
    alt: "A wheel rolled along the ground: a chalk mark at the bottom, the wheel rolled nR whole turns to the mark at the bottom again, the distance between them dR.",
    body: () => `<line x1="10" y1="110" x2="250" y2="110" stroke="${INK}" stroke-width="1.5"/>${wheelSvg(50, 76, 34, [50, 110])}${wheelSvg(210, 76, 34, [210, 110])}
      <path d="M 84 60 Q 130 18 176 60" fill="none" stroke="${MUTED}" stroke-width="1.2" stroke-dasharray="4 3" marker-end="url(#ms-arrow)"/>
      ${label(130, 30, "nR turns")}${dim(50, 124, 210, 124)}${label(130, 138, "dR")}`,
    view: "0 0 260 144",
  },
  geometry: {
    alt: "A bicycle's side view: the wheelbase w between the contact points, the head tube angle gamma between the steer axis and the ground, and the fork offset f from the front hub perpendicular to the steer axis.",
    body: () => {
      // To scale but for the fork offset, doubled: r = 40, w = 3.3 r, the steer axis tilted
      // back by lambda = 90° − gamma, the front hub ahead of it by f, the trail c that follows.
      const [r, lambda, f] = [40, (25 * Math.PI) / 180, 12];
      const hub = [180, 72];
      const c = (r * Math.sin(lambda) - f) / Math.cos(lambda);
      const p = [hub[0] + c, 112];
      const d = [-Math.sin(lambda), -Math.cos(lambda)];
      const on = (y) => [p[0] + ((p[1] - y) / Math.cos(lambda)) * d[0], y];
      const t = (hub[0] - p[0]) * d[0] + (hub[1] - p[1]) * d[1];
      const foot = [p[0] + t * d[0], p[1] + t * d[1]];
      const [h1, h2] = [on(20), on(40)];
      const f2 = (q) => q.map((x) => x.toFixed(1)).join(" ");
      const top = on(4);
      return `<line x1="4" y1="112" x2="276" y2="112" stroke="${INK}" stroke-width="1.5"/>
        ${wheelSvg(48, 72, r)}${wheelSvg(hub[0], hub[1], r)}
        <path d="M 48 72 L 100 84 L 88 24 Z M 88 24 L ${f2(h1)} M 100 84 L ${f2(h2)} M ${f2(h1)} L ${f2(h2)} L ${f2(hub)} M ${f2(h1)} L ${(h1[0] - 4).toFixed(1)} 8 L ${(h1[0] - 20).toFixed(1)} 8 M 80 24 L 96 24" fill="none" stroke="${INK}" stroke-width="2.2" stroke-linejoin="round"/>
        <line x1="${top[0].toFixed(1)}" y1="${top[1]}" x2="${(p[0] - 6 * d[0]).toFixed(1)}" y2="${(p[1] - 6 * d[1]).toFixed(1)}" stroke="${MUTED}" stroke-width="1" stroke-dasharray="5 3"/>
        <line x1="${hub[0]}" y1="${hub[1]}" x2="${foot[0].toFixed(1)}" y2="${foot[1].toFixed(1)}" stroke="${ACCENT}" stroke-width="2.5"/>${label(hub[0] + 7, hub[1] - 9, "f", "start")}
        <path d="M ${(p[0] - 30).toFixed(1)} ${p[1]} A 30 30 0 0 1 ${f2([p[0] + 30 * d[0], p[1] + 30 * d[1]])}" fill="none" stroke="${ACCENT}" stroke-width="1.2"/>
        ${label(p[0] + 12, p[1] + 14, "gamma", "start")}
        ${dim(48, 126, hub[0], 126)}${label(114, 140, "w")}`;
    },
    view: "0 0 280 144",
  },
    rod: {
    alt: "A torsion pendulum: a wire from a fixed support holding a rod of mass mP, length lP and diameter dP at its middle, twisting back and forth with period TtP1.",
    body: () => `<rect x="80" y="6" width="100" height="8" fill="${MUTED}"/><line x1="130" y1="14" x2="130" y2="76" stroke="${INK}" stroke-width="1.5"/>
      <rect x="40" y="76" width="180" height="10" rx="5" fill="#cbd5e1" stroke="${INK}" stroke-width="1.5"/>
      <path d="M 100 100 A 34 10 0 0 0 160 100" fill="none" stroke="${ACCENT}" stroke-width="1.2" marker-start="url(#ms-arrow)" marker-end="url(#ms-arrow)"/>
      ${label(130, 124, "TtP1")}${dim(40, 64, 220, 64)}${label(196, 58, "lP")}${label(226, 86, "dP", "start")}${label(56, 104, "mP")}${label(140, 40, "wire, k", "start", MUTED)}`,
    view: "0 0 260 136",
  },
  hanging: {
    alt: "A rear frame hung from the torsion pendulum's wire: the steer axis at angle alphaB1 with the horizontal, the wire's plumb line running down through the mass centre, the rear axle at distance aB1 from it; the frame twists about the wire with period TtB1.",
    body: () => {
      // The rear frame (axle, seat tube, head tube) turned by -35° about its clamp on the wire.
      const a = (-35 * Math.PI) / 180;
      const [cx, cy] = [140, 44];
      const at = (x, y) => [cx + (x - cx) * Math.cos(a) - (y - cy) * Math.sin(a), cy + (x - cx) * Math.sin(a) + (y - cy) * Math.cos(a)];
      const f2 = (q) => q.map((x) => x.toFixed(1)).join(" ");
      const axle = at(70, 100);
      const bb = at(122, 106);
      const seat = at(110, 50);
      const [head1, head2] = [at(178, 52), at(170, 84)];
      // The steer axis extended below the head tube, and its angle with the horizontal.
      const dir = [head2[0] - head1[0], head2[1] - head1[1]];
      const len = Math.hypot(...dir);
      const end = [head2[0] + (dir[0] / len) * 34, head2[1] + (dir[1] / len) * 34];
      const alpha = Math.atan2(dir[1], dir[0]);
      const arc = [head2[0] + 22 * Math.cos(alpha), head2[1] + 22 * Math.sin(alpha)];
      return `<rect x="100" y="2" width="80" height="7" fill="${MUTED}"/>
        <line x1="140" y1="9" x2="140" y2="142" stroke="${MUTED}" stroke-width="1" stroke-dasharray="4 3"/>
        <line x1="140" y1="9" x2="140" y2="52" stroke="${INK}" stroke-width="1.5"/>
        <path d="M ${f2(axle)} L ${f2(bb)} L ${f2(seat)} Z M ${f2(seat)} L ${f2(head1)} M ${f2(bb)} L ${f2(head2)}" fill="none" stroke="${INK}" stroke-width="2.2" stroke-linejoin="round"/>
        <line x1="${head1[0].toFixed(1)}" y1="${head1[1].toFixed(1)}" x2="${head2[0].toFixed(1)}" y2="${head2[1].toFixed(1)}" stroke="${INK}" stroke-width="4"/>
        <line x1="${head2[0].toFixed(1)}" y1="${head2[1].toFixed(1)}" x2="${end[0].toFixed(1)}" y2="${end[1].toFixed(1)}" stroke="${MUTED}" stroke-width="1" stroke-dasharray="4 3"/>
        <line x1="${head2[0].toFixed(1)}" y1="${head2[1].toFixed(1)}" x2="${(head2[0] + 34).toFixed(1)}" y2="${head2[1].toFixed(1)}" stroke="${MUTED}" stroke-width="1"/>
        <path d="M ${(head2[0] + 22).toFixed(1)} ${head2[1].toFixed(1)} A 22 22 0 0 1 ${f2(arc)}" fill="none" stroke="${ACCENT}" stroke-width="1.2"/>
        ${label(head2[0] + 26, head2[1] + 22, "alphaB1", "start")}
        <circle cx="${axle[0].toFixed(1)}" cy="${axle[1].toFixed(1)}" r="4" fill="#fff" stroke="${INK}" stroke-width="1.5"/>
        <circle cx="140" cy="98" r="5" fill="${ACCENT}"/><text x="168" y="124" font-size="10" fill="${MUTED}">mass centre</text><line x1="144" y1="101" x2="166" y2="118" stroke="${MUTED}" stroke-width="0.8"/>
        ${dim(axle[0].toFixed(1), (axle[1] + 14).toFixed(1), 140, (axle[1] + 14).toFixed(1))}${label((axle[0] + 140) / 2, axle[1] + 28, "aB1")}
        ${label(146, 24, "TtB1", "start")}`;
    },
    view: "0 0 260 166",
  },
    compound: {
    alt: "A compound pendulum: a wheel hung from a knife edge inside its rim swings in its own plane with period TcR1; lR is the knife edge's distance to the axle.",
    body: () => `<path d="M 110 14 L 150 14 L 130 30 Z" fill="${MUTED}"/>${wheelSvg(130, 80, 48)}
      ${dim(130, 32, 130, 80)}${label(138, 60, "lR", "start")}
      <path d="M 70 126 Q 130 148 190 126" fill="none" stroke="${ACCENT}" stroke-width="1.2" marker-start="url(#ms-arrow)" marker-end="url(#ms-arrow)"/>${label(200, 128, "TcR1", "start")}
      ${label(30, 28, "knife edge", "start", MUTED)}`,
    view: "0 0 260 150",
  },
  torsional: {
    alt: "A torsional pendulum: a wheel hung from the wire by its rim, its plane vertical, twisting about the vertical diameter with period TtR1.",
    body: () => `<rect x="90" y="4" width="80" height="7" fill="${MUTED}"/><line x1="130" y1="11" x2="130" y2="36" stroke="${INK}" stroke-width="1.5"/>
      <ellipse cx="130" cy="84" rx="16" ry="48" fill="none" stroke="${INK}" stroke-width="3"/><line x1="130" y1="36" x2="130" y2="132" stroke="${MUTED}" stroke-dasharray="4 3"/>
      <path d="M 92 136 A 38 8 0 0 0 168 136" fill="none" stroke="${ACCENT}" stroke-width="1.2" marker-start="url(#ms-arrow)" marker-end="url(#ms-arrow)"/>${label(176, 138, "TtR1", "start")}
      ${label(140, 26, "wire, k", "start", MUTED)}`,
    view: "0 0 260 150",
  },
};

DRAWINGS.rider = {
  alt: "A rider seated on the bicycle: the bottom bracket at height hbb, lcs from the rear hub; the seat tube of length lst at angle lamst with the ground and the seat post lsp above it; the grips LhbF from the front hub and LhbR from the rear hub; the feet on the bottom bracket, the hands on the grips.",
  body: () => {
    const [rear, front, bb] = [[48, 92], [212, 92], [112, 100]];
    const ang = (72 * Math.PI) / 180;
    const top = [bb[0] - 70 * Math.cos(ang), bb[1] - 70 * Math.sin(ang)];
    const seat = [bb[0] - 92 * Math.cos(ang), bb[1] - 92 * Math.sin(ang)];
    const grip = [178, 34];
    const f2 = (q) => q.map((x) => x.toFixed(1)).join(" ");
    const shoulder = [seat[0] + 36, seat[1] - 46];
    const knee = [seat[0] + 40, seat[1] + 14];
    return `<line x1="4" y1="132" x2="276" y2="132" stroke="${INK}" stroke-width="1.5"/>
      ${wheelSvg(rear[0], rear[1], 40)}${wheelSvg(front[0], front[1], 40)}
      <path d="M ${f2(rear)} L ${f2(bb)} L ${f2(top)} Z M ${f2(top)} L 186 40 L ${f2(front)} M ${f2(bb)} L 188 46 M 186 40 L ${f2(grip)}" fill="none" stroke="${INK}" stroke-width="2.2" stroke-linejoin="round"/>
      <line x1="${top[0].toFixed(1)}" y1="${top[1].toFixed(1)}" x2="${seat[0].toFixed(1)}" y2="${seat[1].toFixed(1)}" stroke="${ACCENT}" stroke-width="3"/>
      <path d="M ${f2(seat)} L ${f2(shoulder)} L ${f2([grip[0] - 16, grip[1] - 8])} L ${f2(grip)} M ${f2(seat)} L ${f2(knee)} L ${f2(bb)}" fill="none" stroke="${MUTED}" stroke-width="3" stroke-linecap="round" stroke-linejoin="round"/>
      <circle cx="${(shoulder[0] + 6).toFixed(1)}" cy="${(shoulder[1] - 14).toFixed(1)}" r="9" fill="none" stroke="${MUTED}" stroke-width="3"/>
      <line x1="${grip[0]}" y1="${grip[1]}" x2="${front[0]}" y2="${front[1]}" stroke="${ACCENT}" stroke-width="1" stroke-dasharray="4 3"/>
      <line x1="${grip[0]}" y1="${grip[1]}" x2="${rear[0]}" y2="${rear[1]}" stroke="${ACCENT}" stroke-width="1" stroke-dasharray="4 3"/>
      ${label(206, 60, "LhbF", "start")}${label(96, 58, "LhbR", "end")}
      ${label(84, 108, "lcs", "end")}${dim(bb[0], 132, bb[0], bb[1])}${label(bb[0] + 6, 124, "hbb", "start")}
      ${label(top[0] + 14, top[1] + 40, "lst", "start")}${label(seat[0] - 6, seat[1] + 16, "lsp", "end")}
      <path d="M ${bb[0] - 24} ${bb[1]} A 24 24 0 0 1 ${f2([bb[0] - 24 * Math.cos(ang), bb[1] - 24 * Math.sin(ang)])}" fill="none" stroke="${ACCENT}" stroke-width="1.2"/>${label(bb[0] - 30, bb[1] - 6, "lamst", "end")}
      ${label(grip[0] + 8, grip[1] - 6, "grips (whb)", "start", MUTED)}`;
  },
  view: "0 -66 280 206",
};

function drawing(name) {
  const d = DRAWINGS[name];
  const figure = html("figure", { class: "ms-figure" });
  // Static drawings, no user text: written as markup.
  figure.innerHTML = `<svg viewBox="${d.view}" role="img" aria-label="${d.alt}" data-testid="ms-drawing-${name}">${ARROWS}${d.body()}</svg>`;
  return figure;
}

// ---- the panel --------------------------------------------------------------------------------

export class MeasurePanel {
  /** `onLoad(bike)`: the bicycle computed goes to the editor; `onChange()`: the link must be
   * rewritten. */
  constructor({ onLoad, onChange }) {
    this.onLoad = onLoad;
    this.onChange = onChange;
    this.samples = [];
    this.sample = ""; // the sample the form started from ("" for a file or nothing)
    this.base = {}; // that sample's measurements {key: [value, sigma]} as text
    this.counts = { B: 3, H: 3 };
    this.other = []; // keys read and kept (not the form's), written back on save
    this.rider = null; // {name, fileName, text}: the rider's YeadonMeas.txt
    this.configuration = null; // {fileName, text}: the rider's YeadonCFG.txt on this bicycle
    this.riderFromSample = false; // the rider came with the sample (the link carries it)
    this.answer = null;
    this.sequence = 0;
    this.timer = 0;
    this.waiting = null; // the pending count of a scheduled computation
    this.build();
    $("ms-sample").addEventListener("change", (e) => during(async () => {
      await this.loadSample(e.target.value);
      this.onChange();
    }));
    $("ms-open").addEventListener("click", () => $("ms-file").click());
    $("ms-file").addEventListener("change", (e) => during(() => this.openFile(e)));
    $("ms-save").addEventListener("click", () => this.save());
    $("ms-load").addEventListener("click", () => this.load());
    $("ms-name").addEventListener("input", () => this.schedule());
  }

  /** The samples (GET /api/measure/samples), once. */
  async ensureSamples() {
    if (this.samples.length) return;
    this.samples = await api.measureSamples();
    const select = $("ms-sample");
    select.replaceChildren(html("option", { value: "", text: "— an empty form —" }), ...this.samples.map((s) => html("option", { value: s.name, text: s.title, title: s.source })));
    select.value = this.sample;
  }

  /** Draws the sections and their fields (empty). */
  build() {
    const body = $("ms-sections");
    body.replaceChildren();
    for (const s of SECTIONS) {
      const section = html("section", { class: "ms-step", "aria-labelledby": `ms-h-${s.id}`, "data-testid": `ms-section-${s.id}` });
      section.append(html("h3", { id: `ms-h-${s.id}`, text: s.title }), html("p", { class: "ms-text", text: s.text }), drawing(s.drawing));
      const fields = html("div", { class: "ms-fields" });
      for (const f of s.fields) fields.append(this.fieldRow(f.key, `${f.label}`, f.unit, f.hint));
      section.append(fields);
      if (s.hangings) section.append(html("div", { id: "ms-hangings", class: "ms-hangings" }));
      if (s.rider) section.append(this.riderControls());
      section.append(html("div", { id: `ms-derived-${s.id}`, class: "ms-derived", role: "region", tabindex: "0", "aria-label": `Numbers derived in ${s.title}`, "data-testid": `ms-derived-${s.id}` }));
      body.append(section);
    }
    this.drawHangings({});
    this.showRider();
  }

  /** The rider's two files: open each, or remove the rider; what is loaded, said. */
  riderControls() {
    const open = (id, text, title) => {
      const input = html("input", { id: `${id}-file`, type: "file", accept: ".txt,text/plain", hidden: true });
      const button = html("button", { id, class: "btn small", type: "button", "data-testid": id, text, title });
      button.addEventListener("click", () => input.click());
      input.addEventListener("change", (e) => during(() => this.openRider(e, id === "ms-rider-open")));
      return [button, input];
    };
    const remove = html("button", { id: "ms-rider-remove", class: "btn small", type: "button", "data-testid": "ms-rider-remove", text: "No rider" });
    remove.addEventListener("click", () => {
      this.rider = null;
      this.configuration = null;
      this.riderFromSample = false;
      this.showRider();
      this.schedule();
    });
    return html("div", { class: "ms-rider" },
      html("div", { class: "ms-buttons" },
        ...open("ms-rider-open", "Open YeadonMeas.txt…", "The rider's 95 measurements of Yeadon's body model, a <Rider>YeadonMeas.txt"),
        ...open("ms-configuration-open", "Open YeadonCFG.txt…", "The rider's posture on this bicycle, a <Rider><Bike>YeadonCFG.txt"),
        remove),
      html("p", { id: "ms-rider-status", class: "ms-text", "aria-live": "polite", "data-testid": "ms-rider-status" }));
  }

  async openRider(e, measurements) {
    const file = e.target.files?.[0];
    e.target.value = "";
    if (!file) return;
    const text = await file.text();
    if (measurements) this.rider = { name: file.name.replace(/YeadonMeas\.txt$/, "").replace(/\.[^.]*$/, ""), fileName: file.name, text };
    else this.configuration = { fileName: file.name, text };
    this.riderFromSample = false;
    this.showRider();
    this.schedule();
  }

  /** Says which rider files are loaded, and what a seated rider weighs. */
  showRider() {
    const status = $("ms-rider-status");
    if (!status) return;
    const r = this.answer?.rider;
    if (this.rider && this.configuration) {
      status.textContent = `${this.rider.name || "The rider"} (${this.rider.fileName}) seated as ${this.configuration.fileName}${r ? `: ${num(r.mass, 4)} kg, joint angles solved in ${r.iterations} Newton steps` : ""}.`;
    } else if (this.rider || this.configuration) {
      status.textContent = this.rider ? `${this.rider.fileName} loaded: open the rider's configuration on this bicycle too.` : `${this.configuration.fileName} loaded: open the rider's measurements too.`;
    } else {
      status.textContent = "No rider: the rear frame alone.";
    }
    $("ms-rider-remove").disabled = !(this.rider || this.configuration);
  }

  /** The rider's part of a request, when both files are there. */
  riderBody() {
    if (!(this.rider && this.configuration)) return {};
    return { rider: this.rider.text, configuration: this.configuration.text, ...(this.rider.name ? { rider_name: this.rider.name } : {}) };
  }

  fieldRow(key, text, unit, hint) {
    const value = html("input", { id: `ms-${key}`, type: "text", inputmode: "decimal", spellcheck: "false", autocomplete: "off", "data-key": key, "data-part": "value", "data-testid": `ms-${key}`, "aria-label": `${key}: ${hint} [${unit}]`, title: hint });
    const sigma = html("input", { id: `ms-${key}-sigma`, class: "sigma", type: "text", inputmode: "decimal", spellcheck: "false", autocomplete: "off", "data-key": key, "data-part": "sigma", "data-testid": `ms-${key}-sigma`, "aria-label": `σ of ${key}: its standard deviation [${unit}]`, title: `σ: the standard deviation of ${key}` });
    for (const input of [value, sigma]) input.addEventListener("input", () => this.schedule());
    return html("div", { class: "ms-row", title: hint }, html("label", { class: "ms-key", for: `ms-${key}`, text }), value, html("span", { class: "pm", text: "±" }), sigma, html("span", { class: "unit", text: unit }));
  }

  /** The hanging tables of both frames, keeping what their fields hold. */
  drawHangings(values) {
    const holder = $("ms-hangings");
    const kept = { ...this.read().texts, ...values };
    holder.replaceChildren();
    for (const { part, name } of FRAMES) {
      const table = html("table", { class: "ms-hang" });
      table.append(html("caption", { text: `${name} (${part})` }));
      table.append(html("thead", {}, html("tr", {}, html("th", { scope: "col", text: "#" }), ...HANGING_COLUMNS.map((c) => html("th", { scope: "col", title: c.hint, text: `${c.prefix}${part}i [${c.unit}]` })))));
      const rows = html("tbody");
      for (let i = 1; i <= this.counts[part]; i++) {
        rows.append(html("tr", {}, html("th", { scope: "row", text: String(i) }), ...HANGING_COLUMNS.map((c) => {
          const key = `${c.prefix}${part}${i}`;
          const cell = html("td", {}, ...this.fieldRow(key, "", c.unit, `${name}, hanging ${i}: ${c.hint}`).querySelectorAll("input, .pm"));
          return cell;
        })));
      }
      table.append(rows);
      const add = html("button", { type: "button", class: "btn small", text: `+ hanging of the ${name}`, "data-testid": `ms-add-${part}`, disabled: this.counts[part] >= MAX_HANGINGS });
      add.addEventListener("click", () => {
        this.counts[part] += 1;
        this.drawHangings({});
        this.schedule();
      });
      holder.append(html("div", { class: "ms-hang-wrap", tabindex: "0", role: "region", "aria-label": `Hangings of the ${name}` }, table), add);
    }
    this.fill(kept);
  }

  /** Every field's text: {key: [value, sigma]}. */
  read() {
    const texts = {};
    for (const input of document.querySelectorAll("#ms-sections input[data-key]")) {
      const k = input.dataset.key;
      texts[k] = texts[k] ?? ["", ""];
      texts[k][input.dataset.part === "sigma" ? 1 : 0] = input.value;
    }
    return { texts };
  }

  /** Writes {key: [value, sigma]} into the fields there are. */
  fill(texts) {
    for (const [key, [value, sigma]] of Object.entries(texts)) {
      const v = $(`ms-${key}`);
      const s = $(`ms-${key}-sigma`);
      if (v) v.value = value;
      if (s) s.value = sigma;
    }
  }

  /** Fills the form from a list of {key, value, sigma} (the server's reading of a file). */
  fillFrom(measurements) {
    const texts = {};
    for (const m of measurements) texts[m.key] = [inputText(m.value), m.sigma > 0 ? inputText(m.sigma) : ""];
    for (const { part } of FRAMES) {
      let n = 0;
      while (texts[`alpha${part}${n + 1}`] || texts[`a${part}${n + 1}`] || texts[`Tt${part}${n + 1}`]) n += 1;
      this.counts[part] = Math.max(2, Math.min(MAX_HANGINGS, n));
    }
    for (const input of document.querySelectorAll("#ms-sections input[data-key]")) input.value = "";
    this.drawHangings(texts);
    return texts;
  }

  async loadSample(name) {
    await this.ensureSamples();
    const sample = this.samples.find((s) => s.name === name);
    this.sample = sample ? sample.name : "";
    $("ms-sample").value = this.sample;
    this.riderFromSample = Boolean(sample?.rider && sample?.configuration);
    this.rider = this.riderFromSample ? { name: sample.rider_name ?? "", fileName: sample.rider_file_name ?? "", text: sample.rider } : null;
    this.configuration = this.riderFromSample ? { fileName: sample.configuration_file_name ?? "", text: sample.configuration } : null;
    this.showRider();
    if (!sample) {
      this.base = {};
      this.other = [];
      $("ms-name").value = "";
      this.fillFrom([]);
      this.answer = null;
      this.show();
      return;
    }
    $("ms-name").value = sample.file_name.replace(/Measured\.txt$/, "");
    await this.readText(sample.text, sample.file_name);
    this.base = this.read().texts;
  }

  /** A file's text read by the server into the form (and computed). */
  async readText(text, fileName) {
    const mine = ++this.sequence;
    try {
      const answer = await api.measure({ text, file_name: fileName, ...this.riderBody() });
      if (mine !== this.sequence) return;
      this.other = answer.other.filter((o) => !RIDER_KEYS.includes(o.key));
      this.fillFrom([...answer.measurements, ...answer.other.filter((o) => RIDER_KEYS.includes(o.key))]);
      this.answer = answer;
      this.say(null);
      this.mark([]);
      this.show();
    } catch (e) {
      if (mine !== this.sequence) return;
      this.say(`${fileName}: ${e.message}`);
    }
  }

  async openFile(e) {
    const file = e.target.files?.[0];
    e.target.value = "";
    if (!file) return;
    this.sample = "";
    $("ms-sample").value = "";
    this.base = {};
    $("ms-name").value = file.name.replace(/\.[^.]*$/, "").replace(/Measured$/, "");
    await this.readText(await file.text(), file.name);
    this.onChange();
  }

  /** The request from the fields: null (the fields marked, the message said) when a field
   * holds text that is not a number. */
  request() {
    const { texts } = this.read();
    const measurements = {};
    const bad = [];
    for (const [key, [value, sigma]] of Object.entries(texts)) {
      if (value.trim() === "" && sigma.trim() === "") continue;
      const v = parseNumber(value);
      const s = sigma.trim() === "" ? 0 : parseNumber(sigma);
      if (v === null) bad.push(`ms-${key}`);
      if (s === null) bad.push(`ms-${key}-sigma`);
      if (v !== null && s !== null) measurements[key] = { value: v, sigma: s };
    }
    for (const o of this.other) measurements[o.key] = measurements[o.key] ?? { value: o.value, sigma: o.sigma };
    if (bad.length) {
      this.mark(bad);
      this.say(`${bad[0].slice(3).replace(/-sigma$/, " (σ)")} is not a number${bad.length > 1 ? ` (and ${bad.length - 1} more field${bad.length > 2 ? "s" : ""})` : ""}.`);
      this.veil(true);
      return null;
    }
    const name = $("ms-name").value.trim();
    return { measurements, ...(name ? { name } : {}), ...this.riderBody() };
  }

  /** A computation after the typing pauses; counted as work under way until it is done. */
  schedule() {
    clearTimeout(this.timer);
    this.waiting = this.waiting ?? begin();
    this.veil(true);
    this.timer = setTimeout(async () => {
      const end = this.waiting;
      this.waiting = null;
      try {
        await this.compute();
        this.onChange();
      } finally {
        end?.();
      }
    }, DEBOUNCE_MS);
  }

  async compute() {
    const body = this.request();
    if (!body) return;
    const mine = ++this.sequence;
    try {
      const answer = await api.measure(body);
      if (mine !== this.sequence) return;
      this.answer = answer;
      this.say(null);
      this.mark([]);
      this.show();
    } catch (e) {
      if (mine !== this.sequence) return;
      // The field the library names: a key, or two ("alphaB1 and alphaB2").
      const keys = (e.field ?? "").split(" and ").filter(Boolean);
      this.mark(keys.flatMap((k) => [`ms-${k}`, ...(/standard deviation/.test(e.message) ? [`ms-${k}-sigma`] : [])]));
      this.say(e.message);
      this.veil(true);
    }
  }

  say(text) {
    $("ms-message").textContent = text ?? "";
    $("ms-message").hidden = !text;
  }

  mark(ids) {
    for (const input of document.querySelectorAll("#ms-sections input[data-key]")) {
      const bad = ids.includes(input.id);
      input.classList.toggle("invalid", bad);
      input.setAttribute("aria-invalid", String(bad));
    }
  }

  /** Veils the derived numbers (they are of other measurements) or unveils them. */
  veil(stale) {
    document.querySelector(".ms-view").classList.toggle("ms-stale", stale);
    $("ms-load").disabled = stale || !this.answer;
  }

  /** The derived numbers, each beside its section. */
  show() {
    const a = this.answer;
    for (const s of SECTIONS) {
      const holder = $(`ms-derived-${s.id}`);
      if (!a) {
        holder.replaceChildren();
        continue;
      }
      const rows = a.steps.filter(s.steps).map((st) => html("tr", { class: st.benchmark ? "bench" : "", title: `${st.description}${st.inputs.length ? ` — from ${st.inputs.join(", ")}` : ""}` },
        html("th", { scope: "row", text: st.key }),
        html("td", { class: "mono", "data-testid": `ms-step-${st.key}`, text: withSigma(st.value, st.sigma) }),
        html("td", { class: "unit", text: unitText(st.unit) }),
        html("td", { class: "ms-what", text: st.description })));
      holder.replaceChildren(html("table", { class: "ms-steps" }, html("tbody", {}, ...rows)));
    }
    const warnings = a?.warnings ?? [];
    $("ms-warnings").replaceChildren(...warnings.map((w) => html("li", { text: w.message })));
    $("ms-warnings").hidden = !warnings.length;
    $("ms-meta").textContent = a ? `${a.name ?? "this bicycle"}: ${a.parameters.length} parameters with σ, ${a.steps.length} steps` : "";
    this.showRider();
    this.veil(false);
  }

  save() {
    const { texts } = this.read();
    const lines = [];
    for (const key of keyOrder(this.counts)) {
      const [value, sigma] = texts[key] ?? ["", ""];
      if (value.trim() === "") continue;
      lines.push(sigma.trim() === "" ? `${key} = ${value.trim()}` : `${key} = ${value.trim()}+/-${sigma.trim()}`);
    }
    for (const o of this.other) lines.push(o.sigma > 0 ? `${o.key} = ${inputText(o.value)}+/-${inputText(o.sigma)}` : `${o.key} = ${inputText(o.value)}`);
    const name = $("ms-name").value.trim() || "bicycle";
    download(`${name.replace(/[^A-Za-z0-9_-]+/g, "")}Measured.txt`, `${lines.join("\n")}\n`, "text/plain");
  }

  load() {
    if (!this.answer) return;
    const bike = JSON.parse(JSON.stringify(this.answer.bike));
    bike.name = bike.name ?? ($("ms-name").value.trim() || "measured bicycle");
    this.onLoad(bike);
  }

  /** The state the link carries: the sample, and the fields that differ from it. */
  inputs() {
    const out = { s: this.sample };
    // The sample's rider, taken off (files opened here are not carried: too long for a link).
    if (!this.riderFromSample && this.samples.find((x) => x.name === this.sample)?.rider) out.r = "none";
    const { texts } = this.read();
    for (const [key, [value, sigma]] of Object.entries(texts)) {
      const base = this.base[key] ?? ["", ""];
      if (value !== base[0] || sigma !== base[1]) out[`k.${key}`] = `${value}/${sigma}`;
    }
    return out;
  }

  /** Restores what `inputs()` gave. */
  async setInputs(s) {
    try {
      await this.loadSample(s.s ?? "");
    } catch (e) {
      this.say(e.message);
      return;
    }
    if (s.r === "none") {
      this.rider = null;
      this.configuration = null;
      this.riderFromSample = false;
      this.showRider();
    }
    const edits = {};
    for (const [k, v] of Object.entries(s)) {
      if (!k.startsWith("k.")) continue;
      const key = k.slice(2);
      if (!/^[A-Za-z][A-Za-z0-9]{0,31}$/.test(key)) continue;
      const [value, sigma = ""] = v.split("/");
      edits[key] = [value, sigma];
      const hanging = key.match(/^(?:alpha|a|Tt)([BH])(\d+)$/);
      if (hanging) this.counts[hanging[1]] = Math.min(MAX_HANGINGS, Math.max(this.counts[hanging[1]], Number(hanging[2])));
    }
    if (Object.keys(edits).length || s.r === "none") {
      this.drawHangings(edits);
      await this.compute();
    }
  }
}
