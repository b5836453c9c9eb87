// The Modes tab: the linear model's eigenmodes at one speed (/api/modes, what `whipple modes`
// prints), each in words ("weave: oscillates every 1.4 s, decays by half in 0.9 s") with its
// lean and steer amplitudes and phase; the mode chosen is animated beside the side view (the
// bicycle seen from behind, for the lean, and from above, for the steer: x(t) = Re(v e^{λt})),
// and "Play in 3-D" starts the non-linear simulation from that mode's shape.

import { api } from "./api.js";
import { parseNumber } from "./editor.js";
import { html, svg, num, seconds, FONT } from "./format.js";
import { MODE_COLOURS } from "./plot.js";

const $ = (id) => document.getElementById(id);
const DEG = 180 / Math.PI;
/** The largest angle drawn in the animation [deg]; the amplitudes are scaled to it. */
const SHOWN = 14;

const cx = (re, im) => ({ re, im });
const mul = (a, b) => cx(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
const abs = (a) => Math.hypot(a.re, a.im);
const expc = (a) => cx(Math.exp(a.re) * Math.cos(a.im), Math.exp(a.re) * Math.sin(a.im));

/** The modes as people read them: a conjugate pair once. */
export function describe(modes) {
  const out = [];
  for (const m of modes) {
    const [re, im] = m.eigenvalue;
    if (im < 0 && modes.some((o) => o !== m && o.eigenvalue[1] === -im && o.eigenvalue[0] === re)) continue;
    out.push({ ...m, words: words(m) });
  }
  return out;
}

/** "weave: oscillates every 1.4 s, decays by half in 0.9 s". */
export function words(m) {
  const [re, im] = m.eigenvalue;
  const parts = [];
  if (im !== 0) parts.push(`oscillates every ${seconds((2 * Math.PI) / Math.abs(im))}`);
  else parts.push("does not oscillate");
  const scale = Math.abs(re) + Math.abs(im);
  if (Math.abs(re) <= 1e-9 * Math.max(1, scale)) parts.push("neither grows nor decays");
  else if (re < 0) parts.push(`decays by half in ${seconds(Math.LN2 / -re)}`);
  else parts.push(`grows to double in ${seconds(Math.LN2 / re)} (unstable)`);
  return `${m.mode}: ${parts.join(", ")}`;
}

/** Steer against lean: amplitude ratio and phase ("steer leads lean by 40°"). */
export function shapeWords(m) {
  const [l, s] = m.eigenvector;
  const lean = cx(l[0], l[1]), steer = cx(s[0], s[1]);
  if (abs(lean) < 1e-12 * abs(steer)) return "steer only (no lean)";
  if (abs(steer) < 1e-12 * abs(lean)) return "lean only (no steer)";
  const ratio = abs(steer) / abs(lean);
  let phase = (Math.atan2(steer.im, steer.re) - Math.atan2(lean.im, lean.re)) * DEG;
  phase = ((phase + 540) % 360) - 180;
  if (m.eigenvalue[1] === 0) return `steer/lean = ${num(Math.abs(phase) < 90 ? ratio : -ratio, 3)} (${Math.abs(phase) < 90 ? "steers into the lean" : "steers against the lean"})`;
  const lead = Math.abs(phase) < 0.5 ? "in phase with lean" : `${phase > 0 ? "leads" : "lags"} lean by ${num(Math.abs(phase), 3)}°`;
  return `steer/lean amplitude ${num(ratio, 3)}, steer ${lead}`;
}

/** The time shown in one loop of the animation [s]. */
function loopTime(m) {
  const [re, im] = m.eigenvalue;
  if (im !== 0) return Math.min(8, Math.max(1.5, (2 * 2 * Math.PI) / Math.abs(im)));
  return Math.min(6, Math.max(1, Math.log(8) / Math.max(1e-6, Math.abs(re))));
}

/** Lean and steer [rad] of the mode at time t, scaled so that the larger starts at SHOWN°. */
function motion(m, t) {
  const [l, s] = m.eigenvector;
  const lean = cx(l[0], l[1]), steer = cx(s[0], s[1]);
  const k = (SHOWN / DEG) / Math.max(abs(lean), abs(steer));
  const e = expc(cx(m.eigenvalue[0] * t, m.eigenvalue[1] * t));
  return { lean: k * mul(lean, e).re, steer: k * mul(steer, e).re };
}

export class ModesPanel {
  /** `bike()` gives the current bicycle; `onPlay3d(initial)` runs it in the Simulation tab. */
  constructor({ bike, label, onPlay3d, onChange }) {
    this.bike = bike;
    this.label = label;
    this.onPlay3d = onPlay3d;
    this.onChange = onChange ?? (() => {});
    this.modes = null;
    this.chosen = null;
    this.raf = 0;
    this.speedEdited = false;
    $("mode-form").addEventListener("submit", (e) => {
      e.preventDefault();
      this.speedEdited = true;
      this.compute();
      this.onChange();
    });
  }

  speed() {
    return parseNumber($("mode-speed").value, "speed");
  }

  /** A speed to look at: the middle of the self-stable range unless one was typed. */
  suggest(critical) {
    if (this.speedEdited) return;
    const range = critical?.stable_speed_ranges?.[0];
    $("mode-speed").value = String(range ? Math.round(50 * (range[0] + range[1])) / 100 : 5);
  }

  async compute() {
    const v = this.speed();
    $("mode-speed").classList.toggle("invalid", v === null);
    if (v === null) {
      $("mode-message").textContent = "The speed must be a number.";
      $("mode-message").hidden = false;
      return;
    }
    const mine = (this.sequence = (this.sequence ?? 0) + 1);
    try {
      const answer = await api.modes(this.bike(), v);
      if (mine !== this.sequence) return;
      $("mode-message").hidden = true;
      this.modes = describe(answer.modes);
      this.render(v);
      const keep = this.modes.findIndex((m) => m.mode === (this.chosen?.mode ?? "weave"));
      this.choose(this.modes[keep >= 0 ? keep : 0]);
    } catch (e) {
      $("mode-message").textContent = e.message;
      $("mode-message").hidden = false;
    }
  }

  /**
   * Veils the modes shown when they are not those of the form (`reason`: why, or null when
   * they are): an invalid bicycle, or text in a field, keeps the last modes on screen as such.
   */
  veil(reason) {
    const list = $("mode-list");
    list.classList.toggle("stale", Boolean(reason));
    list.dataset.stale = reason ?? "";
    const meta = $("mode-meta");
    const base = meta.dataset.base ?? meta.textContent;
    meta.dataset.base = base;
    meta.textContent = reason && base ? `${base} (${reason}; last computed)` : base;
  }

  /** Lists the modes computed at speed `v` (the request's, not the field's, which may be edited since). */
  render(v) {
    const list = $("mode-list");
    list.replaceChildren();
    for (const m of this.modes) {
      const [re, im] = m.eigenvalue;
      const lambda = im !== 0 ? `λ = ${num(re)} ± ${num(Math.abs(im))}i 1/s` : `λ = ${num(re)} 1/s`;
      const item = html("li", { class: "mode-item", "data-mode": m.mode });
      const choose = html("button", { type: "button", class: "mode-choose", "aria-pressed": "false", "data-testid": `mode-${m.mode}` },
        html("span", { class: "tt-dot", style: `background:${MODE_COLOURS[m.mode] ?? MODE_COLOURS.unclassified}` }),
        html("span", { class: "mode-words", "data-testid": `mode-words-${m.mode}`, text: m.words }));
      choose.addEventListener("click", () => this.choose(m));
      const play = html("button", { type: "button", class: "btn small", text: "Play in 3-D", title: "Simulate the non-linear bicycle from this mode's shape", "data-testid": `mode-3d-${m.mode}` });
      play.addEventListener("click", () => this.play3d(m, v));
      item.append(choose, html("div", { class: "mode-detail" }, html("span", { class: "mono", text: lambda }), html("span", { text: ` · ${shapeWords(m)}` })), play);
      list.append(item);
    }
    $("mode-meta").textContent = `${this.label()} at ${num(v)} m/s (linear model)`;
    $("mode-meta").dataset.base = $("mode-meta").textContent;
    this.veil(null);
  }

  choose(m) {
    this.chosen = m;
    for (const b of document.querySelectorAll(".mode-choose")) b.setAttribute("aria-pressed", String(b.closest("li").dataset.mode === m?.mode));
    this.animate();
  }

  /** Initial numbers for the simulation that start the bicycle in mode `m`. */
  initial(m, v) {
    const x = motion(m, 0);
    const [, , lr, sr] = m.eigenvector;
    const [l, s] = m.eigenvector;
    const k = (SHOWN / DEG / 3) / Math.max(Math.hypot(...l), Math.hypot(...s));
    // Rates of Re(k v e^{λt}) at t = 0 are Re(k λ v) = k Re(v_rate).
    return {
      speed: v,
      lean_deg: (x.lean * DEG) / 3,
      steer_deg: (x.steer * DEG) / 3,
      lean_rate: k * lr[0],
      steer_rate: k * sr[0],
      duration: Math.min(10, Math.max(3, 2 * loopTime(m))),
    };
  }

  play3d(m, v) {
    this.onPlay3d(this.initial(m, v), m);
  }

  stop() {
    cancelAnimationFrame(this.raf);
    this.raf = 0;
    $("mode-anim").hidden = true;
  }

  /** The chosen mode, looping, in the inset over the side view. */
  animate() {
    cancelAnimationFrame(this.raf);
    const m = this.chosen;
    const box = $("mode-anim");
    if (!m) {
      box.hidden = true;
      return;
    }
    box.hidden = false;
    const W = 300, H = 150;
    const root = svg("svg", { width: W, height: H, viewBox: `0 0 ${W} ${H}`, "font-family": FONT, "font-size": 10.5, role: "img", "aria-label": `${m.words}: the bicycle seen from behind and from above` });
    root.append(svg("rect", { x: 0, y: 0, width: W, height: H, fill: "#ffffff", "fill-opacity": 0.94, rx: 8, stroke: "#d1d5db" }));
    root.append(svg("text", { x: 10, y: 16, fill: "#111827", "font-weight": 600 }, `${m.mode} at ${num(this.speed())} m/s`));
    root.append(svg("text", { x: 10, y: H - 8, fill: "#4b5563" }, "from behind (lean)"));
    root.append(svg("text", { x: 160, y: H - 8, fill: "#4b5563" }, "from above (steer)"));
    // From behind: ground, and the bicycle as a leaning post with the rider's mass on top.
    root.append(svg("line", { x1: 20, y1: 118, x2: 130, y2: 118, stroke: "#9ca3af" }));
    const post = svg("g", {});
    post.append(svg("line", { x1: 75, y1: 118, x2: 75, y2: 40, stroke: "#1f2937", "stroke-width": 5, "stroke-linecap": "round" }));
    post.append(svg("circle", { cx: 75, cy: 40, r: 9, fill: "#f59e0b", stroke: "#b45309" }));
    root.append(post);
    // From above: the rear frame along x, the front wheel turned by the steer angle.
    root.append(svg("line", { x1: 170, y1: 75, x2: 240, y2: 75, stroke: "#64748b", "stroke-width": 5, "stroke-linecap": "round" }));
    root.append(svg("line", { x1: 160, y1: 75, x2: 185, y2: 75, stroke: "#1f2937", "stroke-width": 4, "stroke-linecap": "round" }));
    const front = svg("g", {});
    front.append(svg("line", { x1: 228, y1: 75, x2: 272, y2: 75, stroke: "#1f2937", "stroke-width": 4, "stroke-linecap": "round" }));
    front.append(svg("line", { x1: 250, y1: 55, x2: 250, y2: 95, stroke: "#0ea5e9", "stroke-width": 3, "stroke-linecap": "round" }));
    root.append(front);
    const readout = svg("text", { x: W - 10, y: 16, "text-anchor": "end", fill: "#374151", "data-testid": "mode-anim-readout" }, "");
    root.append(readout);
    box.replaceChildren(root);
    const period = loopTime(m);
    const start = performance.now();
    const tick = (now) => {
      const t = (((now - start) / 1000) % period);
      const x = motion(m, t);
      post.setAttribute("transform", `rotate(${(x.lean * DEG).toFixed(2)} 75 118)`);
      front.setAttribute("transform", `rotate(${(x.steer * DEG).toFixed(2)} 250 75)`);
      readout.textContent = `t ${t.toFixed(1)} s · φ ${num(x.lean * DEG, 2)}° · δ ${num(x.steer * DEG, 2)}°`;
      box.dataset.t = t.toFixed(3);
      this.raf = requestAnimationFrame(tick);
    };
    this.raf = requestAnimationFrame(tick);
  }
}
