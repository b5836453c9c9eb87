// JBike6's stylized side view, drawn from the geometry /api/bike/validate returns: wheels,
// steer axis and trail, fork, a stylized frame, and each body's centre of mass (the quartered
// disc, area proportional to mass) with its inertia ellipse, each of the two shown on request.

import { svg, fixed, FONT } from "./format.js";

const INK = "#1f2937";
const MUTED = "#6b7280";
const AXIS = "#2563eb";
const BODY_COLOURS = {
  rider: "#f59e0b",
  frame: "#64748b",
  rack: "#a855f7",
  fork: "#0ea5e9",
  basket: "#14b8a6",
  "rear frame B": "#f59e0b",
  "front frame H": "#0ea5e9",
};

/** The quartered disc that marks a centre of mass. */
function comSymbol(x, y, r, colour) {
  const g = svg("g");
  g.append(svg("circle", { cx: x, cy: y, r, fill: "#ffffff", stroke: colour, "stroke-width": 1.5 }));
  const q = (a0) => {
    const a1 = a0 + Math.PI / 2;
    return `M${x},${y} L${x + r * Math.cos(a0)},${y - r * Math.sin(a0)} A${r},${r} 0 0 0 ${x + r * Math.cos(a1)},${y - r * Math.sin(a1)} Z`;
  };
  g.append(svg("path", { d: `${q(0)} ${q(Math.PI)}`, fill: colour }));
  return g;
}

/**
 * Draws `view` (and, faint, `ghost`: a second design's view) into `container`, fitted to its
 * size; `centres` and `ellipses` say whether the bodies' centres of mass (with their labels) and
 * inertia ellipses are drawn. Returns the <svg> element.
 */
export function drawSideView(container, view, ghost = null, { stale = false, reason = null, centres = true, ellipses = true } = {}) {
  const width = Math.max(320, Math.round(container.clientWidth));
  // As short as the panel is (the Simulation tab's top row at 1280 × 800 is ~200 px): a taller
  // drawing would be cut at its dimensions.
  const height = Math.max(150, Math.round(container.clientHeight));
  const views = ghost ? [view, ghost] : [view];
  // Extent in metres: wheels, bodies (with ellipses), axis.
  let x0 = Infinity, x1 = -Infinity, y1 = 0;
  const grow = (x, y, r = 0) => {
    x0 = Math.min(x0, x - r);
    x1 = Math.max(x1, x + r);
    y1 = Math.max(y1, y + r);
  };
  for (const v of views) {
    for (const w of v.wheels) grow(w.centre[0], w.centre[1], w.radius);
    for (const p of v.steer_axis) grow(p[0], p[1]);
    for (const seg of v.frame) for (const p of seg) grow(p[0], p[1]);
    for (const b of v.bodies) {
      const r = b.ellipse ? Math.max(...b.ellipse.semi_axes) : 0;
      grow(b.centre[0], b.centre[1], Math.min(r, 0.6));
    }
  }
  const margin = { left: 24, right: 24, top: 20, bottom: 58 };
  const scale = Math.min((width - margin.left - margin.right) / (x1 - x0), (height - margin.top - margin.bottom) / y1);
  const ox = margin.left + ((width - margin.left - margin.right) - scale * (x1 - x0)) / 2 - scale * x0;
  const oy = height - margin.bottom;
  const X = (x) => ox + scale * x;
  const Y = (y) => oy - scale * y;
  const line = (p, q, attrs) => svg("line", { x1: X(p[0]), y1: Y(p[1]), x2: X(q[0]), y2: Y(q[1]), "stroke-linecap": "round", ...attrs });

  const root = svg("svg", { width, height, viewBox: `0 0 ${width} ${height}`, "font-family": FONT, role: "img", "aria-label": "Side view of the bicycle" });
  root.append(svg("rect", { x: 0, y: 0, width, height, fill: "#ffffff" }));

  // Ground, hatched.
  const g0 = X(x0) - 20, g1 = X(x1) + 20;
  root.append(svg("line", { x1: g0, y1: oy, x2: g1, y2: oy, stroke: INK, "stroke-width": 1.2 }));
  for (let x = g0; x < g1; x += 10) root.append(svg("line", { x1: x, y1: oy + 1, x2: x - 6, y2: oy + 7, stroke: "#cbd5e1", "stroke-width": 1 }));

  const drawBike = (v, faint) => {
    const g = svg("g", faint ? { opacity: 0.45 } : {});
    const ink = faint ? "#94a3b8" : INK;
    const dash = faint ? "5 4" : null;
    // Bodies first (behind the frame).
    if (!faint && ellipses) {
      for (const b of v.bodies) {
        if (!b.ellipse) continue;
        const colour = BODY_COLOURS[b.name] ?? MUTED;
        const [a, c] = b.ellipse.semi_axes;
        g.append(svg("ellipse", {
          cx: X(b.centre[0]), cy: Y(b.centre[1]), rx: Math.max(a * scale, 0.5), ry: Math.max(c * scale, 0.5),
          transform: `rotate(${(-b.ellipse.angle * 180) / Math.PI} ${X(b.centre[0])} ${Y(b.centre[1])})`,
          fill: colour, "fill-opacity": 0.12, stroke: colour, "stroke-opacity": 0.7, "stroke-width": 1, "data-part": "inertia-ellipse",
        }));
      }
    }
    for (const w of v.wheels) {
      const [cx, cy] = w.centre;
      if (w.radius > 0) {
        g.append(svg("circle", { cx: X(cx), cy: Y(cy), r: w.radius * scale, fill: "none", stroke: ink, "stroke-width": faint ? 1.5 : 3, "stroke-dasharray": dash }));
        if (!faint) g.append(svg("circle", { cx: X(cx), cy: Y(cy), r: w.radius * scale * 0.9, fill: "none", stroke: "#cbd5e1", "stroke-width": 1 }));
      } else {
        // A skate: a short blade on the ground.
        g.append(line([cx - 0.08, 0], [cx + 0.08, 0], { stroke: ink, "stroke-width": 4 }));
      }
      g.append(svg("circle", { cx: X(cx), cy: Y(cy), r: 2.5, fill: ink }));
    }
    for (const [p, q] of v.frame) g.append(line(p, q, { stroke: faint ? ink : "#94a3b8", "stroke-width": faint ? 1.5 : 4, "stroke-dasharray": dash }));
    g.append(line(...v.fork, { stroke: ink, "stroke-width": faint ? 1.5 : 3.5, "stroke-dasharray": dash }));
    g.append(line(...v.head_tube, { stroke: ink, "stroke-width": faint ? 2 : 6, "stroke-dasharray": dash }));
    g.append(line(...v.handlebar, { stroke: ink, "stroke-width": faint ? 1.5 : 3.5 }));
    g.append(line(...v.steer_axis, { stroke: faint ? ink : AXIS, "stroke-width": 1.2, "stroke-dasharray": faint ? "5 4" : "10 4 2 4" }));
    return g;
  };

  if (ghost) root.append(drawBike(ghost, true));
  root.append(drawBike(view, false));

  // Centres of mass, then labels placed where they overlap nothing placed before.
  const labels = svg("g", { "font-size": 11, fill: INK });
  const placed = [];
  const halo = { "paint-order": "stroke", stroke: "#ffffff", "stroke-width": 3, "stroke-linejoin": "round" };
  const place = (x, y, r, text, attrs = {}) => {
    const w = text.length * 6.3;
    const candidates = [];
    for (const dy of [0, 13, -13, 26, -26, 39]) {
      candidates.push({ x: x + r + 4, y: y + 4 + dy, anchor: "start", left: x + r + 4 });
      candidates.push({ x: x - r - 4, y: y + 4 + dy, anchor: "end", left: x - r - 4 - w });
    }
    const free = (c) => placed.every((p) => c.left + w < p.left || p.left + p.w < c.left || c.y - 11 > p.y || p.y - 11 > c.y);
    const c = candidates.find(free) ?? candidates[0];
    placed.push({ left: c.left, w, y: c.y });
    labels.append(svg("text", { x: c.x, y: c.y, "text-anchor": c.anchor, ...halo, ...attrs }, text));
  };
  const [cx, cy] = view.centre_of_mass;
  const symbols = svg("g");
  const mark = (x, y, r, colour) => {
    const g = comSymbol(x, y, r, colour);
    g.setAttribute("data-part", "centre-of-mass");
    symbols.append(g);
  };
  if (centres) {
    for (const b of view.bodies) {
      const colour = b.ellipse ? BODY_COLOURS[b.name] ?? MUTED : INK;
      const r = Math.max(3.5, Math.min(12, 1.3 * Math.sqrt(b.mass)));
      mark(X(b.centre[0]), Y(b.centre[1]), r, colour);
    }
    mark(X(cx), Y(cy), 9, "#dc2626");
    place(X(cx), Y(cy), 9, `total ${fixed(view.total_mass, 1)} kg`, { fill: "#dc2626", "font-weight": 600 });
    for (const b of [...view.bodies].sort((p, q) => q.mass - p.mass)) {
      if (!(b.ellipse || b.mass >= 5)) continue;
      const r = Math.max(3.5, Math.min(12, 1.3 * Math.sqrt(b.mass)));
      place(X(b.centre[0]), Y(b.centre[1]), r, `${b.name} ${fixed(b.mass, 1)} kg`);
    }
  }
  root.append(symbols, labels);

  // Dimensions under the ground: wheelbase and trail.
  const dims = svg("g", { "font-size": 11, fill: MUTED, stroke: MUTED });
  const dim = (xa, xb, y, text) => {
    dims.append(svg("line", { x1: X(xa), y1: y, x2: X(xb), y2: y, "stroke-width": 1 }));
    for (const x of [xa, xb]) dims.append(svg("line", { x1: X(x), y1: y - 4, x2: X(x), y2: y + 4, "stroke-width": 1 }));
    dims.append(svg("text", { x: (X(xa) + X(xb)) / 2, y: y + 15, "text-anchor": "middle", stroke: "none" }, text));
  };
  dim(0, view.wheelbase, oy + 20, `wheelbase ${fixed(view.wheelbase * 1000, 1)} mm`);
  const trailY = oy + 20;
  if (Math.abs(view.trail) > 1e-9) {
    const a = view.wheelbase, c = view.wheelbase + view.trail;
    dims.append(svg("line", { x1: X(a), y1: oy - 3, x2: X(c), y2: oy - 3, stroke: AXIS, "stroke-width": 3 }));
    dims.append(svg("text", { x: X(Math.max(a, c)) + 4, y: trailY + 30, "text-anchor": "end", fill: AXIS, stroke: "none" }, `trail ${fixed(view.trail * 1000, 1)} mm`));
  }
  // Head angle at the axis' ground point.
  const [ga, gt] = view.steer_axis;
  const mid = [ga[0] + (gt[0] - ga[0]) * 0.22, ga[1] + (gt[1] - ga[1]) * 0.22];
  dims.append(svg("text", { x: X(mid[0]) + 8, y: Y(mid[1]), fill: AXIS, stroke: "none" }, `λ ${fixed((view.steer_axis_tilt * 180) / Math.PI, 1)}°`));
  root.append(dims);

  if (stale) {
    root.append(svg("rect", { x: 0, y: 0, width, height, fill: "#ffffff", "fill-opacity": 0.6 }));
    root.append(svg("text", { x: width / 2, y: 24, "text-anchor": "middle", "font-size": 12, fill: "#b91c1c" }, reason ?? "not redrawn: the parameters are invalid"));
  }
  container.replaceChildren(root);
  return root;
}
