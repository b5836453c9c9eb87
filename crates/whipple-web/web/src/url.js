// The page's state in its URL (query string), so that a link reproduces what its sender saw
// and the browser's back and forward buttons step through what was done:
//   bike=preset:benchmark            the bicycle picked (or design:ID, a design of this browser)
//   e=rider.m:90;trail:0.05          edits to a preset (paths into its table, SI and radians)
//   def=BASE64URL                    a whole bicycle (a design, a file, a conversion), as JSON
//   cmp=preset:benchmark,…           the designs compared
//   v=0:10:0.01  y=10                speeds and the vertical axis' limit
//   tab=eigen|locus|modes|resp|control|ridden|sens|map|sim|measure  the bottom panel
//   mv=5                             the speed of the Modes tab
//   rs=kind:bode;in:steer_torque;out:lean;v:5;cmp:3, 5, 7   the Response tab's choices
//   ctl=m:gains;in:steer_torque;k:-100,10,-20,0;q:1,1,1,1;r:1;v:5;s:0   the Control tab's
//                                    choices (K's rows separated by /; s:1 LQR at every speed)
//   rd=v:5;lane:double;from:1;to:10;step:0.25   the Ridden tab's choices, as typed
//   ms=s:browser;k.dR:27.9/0.01    the Measure tab: the sample it started from and the fields
//                                    that differ from it (value/σ as typed)
//   sim=speed:4.6;lean_rate:0.5;…    the simulation's inputs, as typed
//                                    (turn:held: started on the held steady turn)
//   sq=weave                         the quantity of the Sensitivity tab
//   map=x:trail=0:0.2:61;y:…;…       the Design map's axes, quantity and speed, as typed
//   sv=centres:off;ellipses:off      what the side view leaves out (absent: everything drawn)

function encodeJson(value) {
  const bytes = new TextEncoder().encode(JSON.stringify(value));
  let text = "";
  for (const b of bytes) text += String.fromCharCode(b);
  return btoa(text).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

function decodeJson(text) {
  try {
    const b64 = text.replace(/-/g, "+").replace(/_/g, "/");
    const raw = atob(b64 + "=".repeat((4 - (b64.length % 4)) % 4));
    return JSON.parse(new TextDecoder().decode(Uint8Array.from(raw, (c) => c.charCodeAt(0))));
  } catch {
    return null;
  }
}

function pairs(text) {
  const out = {};
  for (const item of (text ?? "").split(";")) {
    const at = item.indexOf(":");
    if (at > 0) out[item.slice(0, at)] = item.slice(at + 1);
  }
  return out;
}

const joinPairs = (obj) => Object.entries(obj).map(([k, v]) => `${k}:${v}`).join(";");

/** The numbers of `bike` that differ from `base` (the same layout), as {path: value}. */
export function diffEdits(base, bike) {
  const out = {};
  if (!base || !bike) return out;
  if ((bike.name ?? "") !== (base.name ?? "")) out.name = bike.name ?? "";
  const walk = (a, b, path) => {
    if (typeof b === "number") {
      if (a !== b) out[path.join(".")] = b;
    } else if (b && typeof b === "object") {
      for (const k of Object.keys(b)) walk(a?.[k], b[k], [...path, k]);
    }
  };
  walk(base.jbike6 ?? base.benchmark, bike.jbike6 ?? bike.benchmark, []);
  return out;
}

/** The state the URL holds (fields absent when it says nothing of them). */
export function readUrl() {
  const q = new URLSearchParams(location.search);
  const edits = {};
  for (const [k, v] of Object.entries(pairs(q.get("e")))) edits[k] = k === "name" ? v : Number(v);
  return {
    bike: q.get("bike"),
    edits: Object.keys(edits).length ? edits : null,
    def: q.get("def") ? decodeJson(q.get("def")) : null,
    compare: q.get("cmp") ? q.get("cmp").split(",").filter(Boolean) : [],
    speeds: q.get("v"),
    ylim: q.get("y"),
    view: q.get("tab"),
    mode: q.get("mv"),
    resp: q.get("rs") ? pairs(q.get("rs")) : null,
    control: q.get("ctl") ? pairs(q.get("ctl")) : null,
    ridden: q.get("rd") ? pairs(q.get("rd")) : null,
    measure: q.get("ms") ? pairs(q.get("ms")) : null,
    sim: q.get("sim") ? pairs(q.get("sim")) : null,
    sens: q.get("sq"),
    map: q.get("map") ? pairs(q.get("map")) : null,
    side: q.get("sv") ? pairs(q.get("sv")) : null,
  };
}

/** Writes `s` into the URL: a new history entry when `push`, else the current one replaced. */
export function writeUrl(s, push) {
  const q = new URLSearchParams();
  if (s.bike) q.set("bike", s.bike);
  if (s.edits) q.set("e", joinPairs(s.edits));
  if (s.def) q.set("def", encodeJson(s.def));
  if (s.compare?.length) q.set("cmp", s.compare.join(","));
  if (s.speeds) q.set("v", s.speeds);
  if (s.ylim) q.set("y", s.ylim);
  if (s.view) q.set("tab", s.view);
  if (s.mode) q.set("mv", s.mode);
  if (s.resp) q.set("rs", joinPairs(s.resp));
  if (s.control) q.set("ctl", joinPairs(s.control));
  if (s.ridden) q.set("rd", joinPairs(s.ridden));
  if (s.measure) q.set("ms", joinPairs(s.measure));
  if (s.sim) q.set("sim", joinPairs(s.sim));
  if (s.sens) q.set("sq", s.sens);
  if (s.map) q.set("map", joinPairs(s.map));
  if (s.side && Object.keys(s.side).length) q.set("sv", joinPairs(s.side));
  const url = `${location.pathname}?${q.toString()}`;
  if (url === `${location.pathname}${location.search}`) return;
  if (push) history.pushState(null, "", url);
  else history.replaceState(null, "", url);
}
