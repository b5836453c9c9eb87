// Times the static site's computations in headless Chromium: node browser.mjs SITE_URL
// (run by crates/whipple-wasm/bench/browser-vs-native, which serves the site and times the
// native command beside it). Prints one JSON line per case: {case, ms: [runs...]}.
import { createRequire } from "node:module";
import { join, resolve } from "node:path";

const url = process.argv[2];
const modules = process.env.WHIPPLE_WEB_NODE_MODULES;
if (!url || !modules) {
  console.error("usage: WHIPPLE_WEB_NODE_MODULES=DIR node browser.mjs SITE_URL");
  process.exit(2);
}
const { chromium } = createRequire(join(resolve(modules), "x.js"))("playwright-core");
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  args: ["--headless", "--no-sandbox", "--disable-background-networking", "--no-first-run"],
});
const page = await browser.newPage();
await page.goto(url);
await page.waitForSelector("body[data-ready=true]", { timeout: 60_000 });
// The 1000 x 1000 map is four requests of 1000 x 250 (a request holds at most 250,000
// designs), asked one after another of the one worker: the grid of `whipple map`'s
// head_angle_deg=60:85:1000, a quarter of its rows each.
const quarter = (j) => {
  const at = (k) => 60 + (25 * k) / 999;
  return { x: "trail=-0.05:0.2:1000", y: `head_angle_deg=${at(250 * j)}:${at(250 * j + 249)}:250`, speed: 5 };
};
const cases = [
  ["eigen sweep, 50,001 speeds", "/api/eigen", [{ speeds: { start: 0, stop: 10, step: 0.0002 } }]],
  ["design map, 500 x 500", "/api/map", [{ x: "trail=-0.05:0.2:500", y: "head_angle_deg=60:85:500", speed: 5 }]],
  ["design map, 1000 x 1000 (four requests)", "/api/map", [0, 1, 2, 3].map(quarter)],
];
const runs = Number(process.env.RUNS ?? 3);
for (const [name, path, parts] of cases) {
  const ms = await page.evaluate(async ({ path, parts, runs }) => {
    const bike = await (await fetch("/api/presets/benchmark")).json();
    const bodies = parts.map((extra) => JSON.stringify({ bike, ...extra }));
    const times = [];
    // One run first, untimed: the module compiled and the worker warm, as a user's second click.
    const first = await fetch(path, { method: "POST", body: bodies[0] });
    if (first.status !== 200) throw new Error(`${path}: ${first.status} ${await first.text()}`);
    for (let i = 0; i < runs; i += 1) {
      const t = performance.now();
      for (const body of bodies) {
        const r = await fetch(path, { method: "POST", body });
        if (r.status !== 200) throw new Error(`${path}: ${r.status} ${await r.text()}`);
        await r.text();
      }
      times.push(performance.now() - t);
    }
    return times;
  }, { path, parts, runs });
  console.log(JSON.stringify({ case: name, ms: ms.map((x) => Math.round(x)) }));
}
await browser.close();
