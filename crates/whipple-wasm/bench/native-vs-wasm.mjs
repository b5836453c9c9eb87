// Asks the WebAssembly module (wasm-bindgen's `--target nodejs` output) and the native
// handlers (the `answer` example) the requests e2e/page.mjs compares, and says for each
// whether the two JSON texts are the same bytes; where they are not, how many numbers part
// and by how many units in the last place.
//   node native-vs-wasm.mjs PKG_DIR NATIVE_ANSWER_BINARY
import { createRequire } from "node:module";
import { spawnSync } from "node:child_process";
import path from "node:path";

const [pkgDir, native] = process.argv.slice(2);
const wasm = createRequire(import.meta.url)(path.resolve(pkgDir, "whipple_wasm.js"));

function viaWasm(method, url, body) {
  const reply = wasm.call(method, url, new TextEncoder().encode(body ?? ""), () => {});
  return { status: reply.status, text: new TextDecoder().decode(reply.body) };
}

function viaNative(method, url, body) {
  const run = spawnSync(native, [method, url], { input: body ?? "", maxBuffer: 1 << 30 });
  if (run.status !== 0) throw new Error(`${native} ${method} ${url}: ${run.stderr}`);
  const out = run.stdout.toString("utf8");
  const nl = out.indexOf("\n");
  return { status: Number(out.slice(0, nl)), text: out.slice(nl + 1) };
}

function ulps(a, b) {
  if (a === b) return 0n;
  const view = new DataView(new ArrayBuffer(16));
  view.setFloat64(0, a);
  view.setFloat64(8, b);
  const ordered = (i) => {
    const bits = view.getBigInt64(i);
    return bits < 0n ? -(bits & 0x7fffffffffffffffn) : bits;
  };
  const d = ordered(0) - ordered(8);
  return d < 0n ? -d : d;
}

function tally(a, b, where, t) {
  if (typeof a === "number" && typeof b === "number") {
    t.numbers += 1;
    const u = ulps(a, b);
    if (u > 0n) {
      t.differing += 1;
      if (!t.first) t.first = `${where}: ${a} / ${b}`;
      if (u > t.worst) t.worst = u;
    }
  } else if (Array.isArray(a) && Array.isArray(b)) {
    if (a.length !== b.length) t.shape = t.shape ?? where;
    a.forEach((x, i) => i < b.length && tally(x, b[i], `${where}[${i}]`, t));
  } else if (a && b && typeof a === "object" && typeof b === "object") {
    for (const k of Object.keys(a)) if (k in b) tally(a[k], b[k], `${where}.${k}`, t);
  }
  return t;
}

const bike = JSON.parse(viaWasm("GET", "/api/presets/benchmark").text);
const browser = JSON.parse(viaWasm("GET", "/api/presets/browser").text);
const asks = [
  ["POST", "/api/eigen", { bike, speeds: { start: 0, stop: 10, step: 0.01 } }],
  ["POST", "/api/eigen", { bike: browser, speeds: { start: 0, stop: 10, step: 0.05 } }],
  ["POST", "/api/sensitivity", { bike: browser }],
  ["POST", "/api/map", { bike, x: "trail=-0.05:0.2:41", y: "head_angle_deg=60:85:41", speed: 5 }],
  ["POST", "/api/simulate", { bike, speed: 4.6, lean_deg: 5, duration: 3 }],
  ["POST", "/api/turn", { bike, speed: 5, lean_deg: 11.5 }],
  ["POST", "/api/linear/frequency", { bike, speeds: [3, 5], input: "steer_torque", output: "lean", frequencies: { start: 0.1, stop: 100, count: 50 } }],
  ["POST", "/api/ridden", { bike, speed: 5, lane: "single", speeds: { start: 3, stop: 6, step: 1 } }],
];
let parted = 0;
for (const [method, url, request] of asks) {
  const body = JSON.stringify(request);
  const here = viaWasm(method, url, body);
  const there = viaNative(method, url, body);
  if (here.status === there.status && here.text === there.text) {
    console.log(`bits  ${method} ${url}: ${here.status}, ${here.text.length} bytes, identical`);
    continue;
  }
  parted += 1;
  let t = { numbers: 0, differing: 0, worst: 0n, first: "", shape: null };
  try {
    t = tally(JSON.parse(here.text), JSON.parse(there.text), "", t);
  } catch (e) {
    t.first = e.message;
  }
  console.log(`PARTS ${method} ${url}: ${here.status} / ${there.status}, ${t.differing} of ${t.numbers} numbers differ, at most ${t.worst} ulps${t.shape ? `, shapes part at ${t.shape}` : ""}; first ${t.first}`);
}
console.log(parted === 0 ? "every answer is the same bytes" : `${parted} answers part`);
process.exit(parted === 0 ? 0 : 1);
