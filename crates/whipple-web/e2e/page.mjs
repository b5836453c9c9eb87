// End-to-end checks of the page (the page never shows numbers that do not match the form; plots
// to explore; modes; links; weight; accessibility; layouts) in headless Chromium:
//   node page.mjs URL
// Run by crates/whipple-web/tests/e2e.rs. Each section starts from a fresh load of the page and
// runs even when an earlier one failed (E2E_KEEP_GOING=1 is the default), so a run against an
// older page lists every check that page fails; the exit status is 1 when any failed.
// Prints the navigation-to-plot time and the page's weight as the browser received it.
import { launch } from "./browser.mjs";
import { CAPSIZE_SPEED, WEAVE_AT_5, WEAVE_SPEED, asShown } from "./reference.mjs";
import { readFileSync, readdirSync, writeFileSync, mkdtempSync, rmSync, existsSync } from "node:fs";
import { createRequire } from "node:module";
import { join, resolve } from "node:path";
import { tmpdir } from "node:os";
import { fileURLToPath } from "node:url";

const url = process.argv[2];
if (!url || !/^http:\/\/(127\.0\.0\.1|localhost|\[::1\])[:/]/.test(url)) {
  console.error("usage: node page.mjs http://127.0.0.1:PORT/ (loopback only)");
  process.exit(2);
}
const LIMIT_MS = Number(process.env.E2E_TIMEOUT_MS ?? 290_000);
const watchdog = setTimeout(() => {
  console.error(`e2e page: FAILED: gave up after ${LIMIT_MS / 1000} s`);
  process.exit(1);
}, LIMIT_MS);
const only = process.env.E2E_ONLY ? new RegExp(process.env.E2E_ONLY) : null;
// The static site (E2E_BACKEND=site): the same page answering its API in the browser, served by
// a plain static file server; E2E_SERVER names a `whipple serve` to compare its numbers with.
const site = process.env.E2E_BACKEND === "site";
const server = process.env.E2E_SERVER ?? null;
if (site && !server) {
  console.error("E2E_BACKEND=site needs E2E_SERVER=http://127.0.0.1:PORT/ (a whipple serve to compare with)");
  process.exit(2);
}

let checks = 0;
const failures = [];
/** A check that must hold; `quiet` ones (one of many alike) are counted, not printed. */
function check(condition, what, { quiet = false } = {}) {
  if (!condition) throw new Error(`check failed: ${what}`);
  checks += 1;
  if (!quiet) console.log(`  ok ${checks}: ${what}`);
}

function axeSource() {
  const here = fileURLToPath(new URL(".", import.meta.url));
  const places = [process.env.WHIPPLE_WEB_NODE_MODULES, process.env.AXE_NODE_MODULES, join(here, "..", "web", "node_modules")].filter(Boolean);
  for (const dir of places) {
    const file = join(resolve(dir), "axe-core", "axe.min.js");
    if (existsSync(file)) return readFileSync(file, "utf8");
  }
  throw new Error(`axe-core not found in ${places.join(" or ")}`);
}

const { context, close } = await launch();
const page = context.pages()[0] ?? (await context.newPage());
page.setDefaultTimeout(20_000);
const errors = [];
page.on("pageerror", (e) => errors.push(e.message));
const origin = new URL(url).origin;
const responses = [];
page.on("response", (r) => responses.push(r));
await page.route("**/*", (route) => {
  const u = route.request().url();
  if (u.startsWith(origin) || u.startsWith("data:") || u.startsWith("blob:")) return route.continue();
  errors.push(`request off loopback: ${u}`);
  return route.abort();
});

/** The static site's first view (page, style, script, worker, the first module), brotli-compressed:
 * issue 32's budget. */
const SITE_FIRST_VIEW_BUDGET = 400_000;

const text = async (id) => ((await page.getByTestId(id).first().textContent({ timeout: 3_000 })) ?? "").trim();
const number = (s) => Number(s.replace("−", "-").replace(/[^0-9.eE+-].*$/, ""));
/** The page's next animation frame: what it draws by then is drawn. */
const nextFrame = () => page.evaluate(() => new Promise((done) => requestAnimationFrame(() => done())));
/** Until `predicate` (run here, re-checked at each of the page's frames) is true. */
async function waitFor(what, predicate, ms = 10_000) {
  const until = Date.now() + ms;
  let last;
  while (Date.now() < until) {
    last = await predicate().catch((e) => `(${e.message})`);
    if (last === true) return;
    await nextFrame();
  }
  throw new Error(`timed out waiting for ${what} (last: ${JSON.stringify(last)})`);
}
/** Whether `predicate` becomes true in time; the check after it says what was seen. */
const becomes = (predicate, ms) => waitFor("", predicate, ms).then(() => true, () => false);
/**
 * Until the page has settled: no request in flight, no recompute scheduled, no handler running
 * (the page's <body data-pending>, web/src/work.js), and what that work drew is drawn. What an
 * action would have done, it has done by then: a check that nothing happened can follow.
 */
async function settled(ms = 20_000) {
  const pending = () => page.evaluate(() => document.body.dataset.pending);
  try {
    await page.waitForSelector("body[data-pending='0']", { state: "attached", timeout: ms });
    await nextFrame();
    await page.waitForSelector("body[data-pending='0']", { state: "attached", timeout: ms });
  } catch (e) {
    throw new Error(`the page did not settle: ${await pending()} pieces of work still under way (${e.message.split("\n")[0]})`);
  }
}
const waitForText = async (id, predicate, ms) => {
  let seen = null;
  await waitFor(`${id}`, async () => {
    seen = await page.getByTestId(id).first().textContent({ timeout: 1_000 });
    return seen !== null && predicate(seen.trim()) ? true : seen;
  }, ms);
  return seen.trim();
};
/** A fresh page at `path` (a query string), ready. */
async function open(path = "", viewport = { width: 1440, height: 900 }) {
  await page.setViewportSize(viewport);
  await page.goto(new URL(path, url).href);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20_000 });
  await waitForText("capsize-speed", (t) => /\d/.test(t));
}
/** Waits for a run to end and pauses its animation (SwiftShader's drawing costs a core). */
async function ran(predicate) {
  const outcome = await waitForText("sim-outcome", (t) => !/simulating/.test(t) && predicate(t), 30_000);
  if ((await page.getByTestId("sim-play").getAttribute("aria-pressed")) === "true") await page.getByTestId("sim-play").click();
  return outcome;
}
const pick = (key) => page.getByTestId("bike-select").selectOption(key);
const xTicks = (id) => page.$$eval(`[data-testid=${id}] svg > g[fill] > text`, (ts) => ts.map((t) => t.textContent).join(" "));
const plotBox = async (id) => page.getByTestId(id).boundingBox();
const downloadOf = async (click) => {
  const [d] = await Promise.all([page.waitForEvent("download", { timeout: 5_000 }), click()]);
  return { name: d.suggestedFilename(), text: readFileSync(await d.path(), "utf8") };
};

async function section(name, body) {
  if (only && !only.test(name)) return;
  console.log(`${name}`);
  const started = Date.now();
  try {
    await body();
    console.log(`  (${((Date.now() - started) / 1000).toFixed(1)} s)`);
  } catch (e) {
    failures.push(`${name}: ${e.message.split("\n")[0]}`);
    console.log(`  FAILED: ${e.message.split("\n")[0]}`);
    const shot = join(tmpdir(), `whipple-e2e-page-${failures.length}.png`);
    await page.screenshot({ path: shot }).catch(() => {});
    console.log(`  screenshot: ${shot}`);
  }
}

const timings = {};

await section("weight: the first load is small and compressed; three.js comes with the Simulation tab", async () => {
  responses.length = 0;
  await page.setViewportSize({ width: 1440, height: 900 });
  const started = Date.now();
  await page.goto(url);
  await page.waitForFunction(() => document.querySelector("[data-testid=eigen-plot] svg path[d*=L]"), null, { polling: "raf", timeout: 20_000 });
  const atPlot = await page.evaluate(() => performance.now());
  timings.navigationToPlotMs = Math.round(atPlot);
  timings.wallMs = Date.now() - started;
  await page.waitForLoadState("load");
  await settled();
  let transferred = 0;
  let raw = 0;
  const assets = [];
  for (const r of responses) {
    const u = new URL(r.url());
    if (u.pathname.startsWith("/api/")) continue;
    const h = await r.allHeaders();
    const body = await r.body().catch(() => Buffer.alloc(0));
    const sent = Number(h["content-length"] ?? body.length);
    transferred += sent;
    raw += body.length;
    assets.push({ path: u.pathname, sent, encoding: h["content-encoding"] ?? "identity", cache: h["cache-control"] ?? "", etag: h.etag ?? "" });
  }
  timings.initialTransferred = transferred;
  timings.initialUncompressed = raw;
  console.log(`  navigation to plot: ${timings.navigationToPlotMs} ms (performance.now at the first drawn curve); the page's files: ${transferred} bytes sent, ${raw} bytes unpacked`);
  for (const a of assets) console.log(`    ${a.path} ${a.sent} B ${a.encoding} "${a.cache}" ${a.etag}`);
  check(!assets.some((a) => /three|view3d/.test(a.path)), "three.js is not part of it");
  if (site) {
    // A static host compresses as it likes (this one not at all): the site's own manifest
    // gives every file's size brotli-compressed, as a host that compresses would send it.
    const files = await page.evaluate(async () => (await fetch("manifest.json")).json());
    const first = files.filter((f) => f.first);
    const brotli = first.reduce((s, f) => s + f.brotli, 0);
    const wasm = first.find((f) => f.name.endsWith(".wasm"));
    const whole = files.find((f) => /^assets\/whipple-[0-9A-F]+\.wasm$/.test(f.name));
    check(Boolean(whole) && !whole.first && /whipple-first-/.test(wasm?.name ?? ""), `the first view loads the first module, not the whole one (${whole?.brotli} bytes brotli)`);
    timings.siteFirstViewBrotli = brotli;
    console.log(`  the site's first view, brotli: ${brotli} bytes (the module ${wasm?.brotli} of them); ${first.map((f) => `${f.name} ${f.brotli}`).join(", ")}`);
    check(first.length === assets.length && first.every((f) => assets.some((a) => a.path === `/${f.name}` || (f.name === "index.html" && a.path === "/"))), `the first view loads the files the manifest lists: ${assets.map((a) => a.path).join(", ")}`);
    check(Boolean(wasm) && brotli < SITE_FIRST_VIEW_BUDGET, `the first view is under ${SITE_FIRST_VIEW_BUDGET / 1000} KB brotli, the module included: ${brotli} bytes`);
    const fetched = page.waitForResponse((r) => /view3d-.*\.js$/.test(r.url()));
    await page.getByTestId("tab-sim").click();
    await fetched;
    check(true, "opening the Simulation tab fetches the 3-D code");
    return;
  }
  check(transferred < 100_000, `the initial page is under 100 KB as sent: ${transferred} bytes`);
  const scripts = assets.filter((a) => a.path.endsWith(".js") || a.path.endsWith(".css"));
  check(scripts.length >= 2 && scripts.every((a) => a.encoding === "br" || a.encoding === "gzip"), `scripts and styles are compressed: ${scripts.map((a) => `${a.path} ${a.encoding}`).join(", ")}`);
  check(scripts.every((a) => /max-age=31536000/.test(a.cache) && /immutable/.test(a.cache) && a.etag), "hashed names are cached for a year, with ETags");
  const pageAsset = assets.find((a) => a.path === "/");
  check(pageAsset && /no-cache/.test(pageAsset.cache) && pageAsset.etag, "the page itself is revalidated (no-cache, ETag)");
  // A revalidation of the page costs a 304.
  const again = await page.evaluate(async (etag) => (await fetch("/", { headers: { "if-none-match": etag } })).status, pageAsset.etag);
  check(again === 304, `If-None-Match answers 304 (${again})`);
  responses.length = 0;
  const fetched = page.waitForResponse((r) => /view3d-.*\.js$/.test(r.url()));
  await page.getByTestId("tab-sim").click();
  await fetched;
  check(true, "opening the Simulation tab fetches the 3-D code");
});

await section("the hover read-out follows a redraw (bicycle switched with the keyboard)", async () => {
  await open("?bike=preset:schwinn-crown");
  const box = await plotBox("eigen-plot");
  await page.mouse.move(box.x + box.width * 0.6, box.y + box.height * 0.5);
  await page.getByTestId("plot-tooltip").waitFor({ state: "visible" });
  const before = await text("plot-tooltip");
  await page.getByTestId("bike-select").focus();
  await page.keyboard.press("ArrowUp"); // the benchmark bicycle is the first preset
  await waitForText("capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  await settled();
  const visible = await page.getByTestId("plot-tooltip").isVisible();
  const after = visible ? await text("plot-tooltip") : "";
  check(!visible || (after !== before && /benchmark/i.test(after) && !/schwinn/i.test(after)), `after the switch the read-out shows the new bicycle's values: "${after.slice(0, 60)}…" (was "${before.slice(0, 60)}…")`);
  // And after the speed range changes.
  await page.fill("#v-stop", "8");
  await page.press("#v-stop", "Enter");
  await settled();
  const v = (await text("plot-tooltip").catch(() => "")).match(/v = ([\d.]+)/);
  check(!v || Number(v[1]) <= 8, `after a new speed range the read-out's speed lies in it (${v?.[1]})`);
});

await section("text in a number field is reflected everywhere, and nothing else is applied", async () => {
  await open("?bike=preset:schwinn-crown");
  await page.getByTestId("param-mrider").fill("abc");
  await waitForText("error-mrider", (t) => t === "not a number");
  // The message comes with the recompute the keystroke scheduled: waited for, not slept on.
  await waitForText("message", (t) => /not a number/.test(t) && /rider/i.test(t)).catch(() => null);
  const message = await page.getByTestId("message").isVisible() ? await text("message") : "";
  check(/not a number/.test(message) && /rider/i.test(message), `the top message names the field: "${message}"`);
  check(await page.locator("[data-testid=eigen-plot] [data-testid=stale-veil]").count() === 1, "the plot is veiled: it is the last numbers' result");
  await page.getByTestId("param-mrider").fill("-5");
  await waitForText("message", (t) => t.includes("-5"));
  await page.getByTestId("param-mrider").fill("abc");
  await waitForText("message", (t) => !t.includes("-5") && /not a number/.test(t)).catch(() => null);
  const m2 = await text("message");
  check(!m2.includes("-5") && /not a number/.test(m2), `-5 then abc: the message follows the field: "${m2}"`);
  const capsize = await text("capsize-speed");
  await page.getByTestId("param-trail").fill("0.05");
  await settled();
  check((await text("capsize-speed")) === capsize && /not a number/.test(await text("message")), "an edit of another field meanwhile is not computed and the page keeps saying why");
  check(await page.locator("[data-testid=eigen-plot] [data-testid=stale-veil]").count() === 1, "and the plot stays veiled");
  await page.getByTestId("param-mrider").fill("");
  await waitForText("error-mrider", (t) => /empty/.test(t));
  check(true, "an empty field says it is empty");
  await page.getByTestId("param-mrider").fill("80");
  await waitForText("capsize-speed", (t) => t !== capsize && /\d/.test(t));
  check(await page.locator("[data-testid=eigen-plot] [data-testid=stale-veil]").count() === 0 && !(await page.getByTestId("message").isVisible()), `mended, both edits are applied at once: v_c ${await text("capsize-speed")}`);
});

await section("saving with text in a field is refused", async () => {
  await open("?bike=preset:schwinn-crown");
  await page.evaluate(() => localStorage.clear());
  await page.getByTestId("param-mrider").fill("abc");
  let downloaded = false;
  const listener = () => { downloaded = true; };
  page.on("download", listener);
  await page.click("#save-toml");
  await settled();
  page.off("download", listener);
  check(!downloaded && /not saved/i.test(await text("message")), `Save TOML refuses: "${await text("message")}"`);
  await page.click("#save-design");
  await settled();
  check(await page.evaluate(() => (JSON.parse(localStorage.getItem("whipple.designs.v1") ?? "[]")).length === 0) && /not saved/i.test(await text("message")), "Save to my designs refuses too");
  await page.click("#copy-link");
  await settled();
  check(/not saved.*as a link/i.test(await text("message")), `Copy link refuses too (the link would hold the last number): "${await text("message")}"`);
  // Typed and clicked in one task, so the recompute the keystroke scheduled is still pending
  // at the click: the refusal must not be replaced by it afterwards.
  await page.evaluate(() => {
    const input = document.querySelector("[data-testid=param-mrider]");
    for (const typed of ["80", "xyz"]) {
      input.value = typed;
      input.dispatchEvent(new Event("input", { bubbles: true }));
    }
    document.getElementById("save-toml").click();
  });
  await settled();
  check(/not saved/i.test(await text("message")), `a Save clicked before the keystroke's recompute ran keeps its refusal: "${await text("message")}"`);
});

await section("edits survive a switch (undo) and a reload; a deletion can be undone", async () => {
  await open("?bike=preset:schwinn-crown");
  await page.evaluate(() => localStorage.clear());
  await page.getByTestId("param-trail").fill("0.05");
  await waitForText("capsize-speed", (t) => !t.startsWith("7.9807"));
  const edited = await text("capsize-speed");
  await page.reload();
  await page.waitForSelector("body[data-ready=true]");
  await waitForText("capsize-speed", (t) => t === edited);
  check((await page.inputValue("[data-testid=param-trail]")) === "0.05", "a reload keeps the unsaved edit");
  await pick("preset:benchmark");
  await waitForText("capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  check(await page.getByTestId("undo-switch").isVisible(), `switching says the edits are kept: "${await text("message")}"`);
  await page.getByTestId("undo-switch").click();
  await waitForText("capsize-speed", (t) => t === edited);
  check((await page.inputValue("[data-testid=param-trail]")) === "0.05", "and the undo brings them back");
  await page.fill("#design-name", "to delete");
  await page.click("#save-design");
  await page.click("#delete-design");
  await waitForText("capsize-speed", (t) => t.startsWith("7.9807"));
  await settled();
  check(await page.getByTestId("undo-delete").isVisible(), `the deletion's message stays, with an undo: "${await text("message")}"`);
  await page.getByTestId("undo-delete").click();
  await waitForText("capsize-speed", (t) => t === edited);
  check(await page.evaluate(() => JSON.parse(localStorage.getItem("whipple.designs.v1")).some((d) => d.name === "to delete")), "undo restores the design");
});

await section("opening the same file twice makes one design", async () => {
  await open("?bike=preset:benchmark");
  await page.evaluate(() => localStorage.clear());
  const dir = mkdtempSync(join(tmpdir(), "whipple-e2e-page-"));
  const file = join(dir, "twice.toml");
  const toml = await page.evaluate(async () => {
    const bike = await (await fetch("/api/presets/benchmark")).json();
    bike.name = "opened twice";
    return (await (await fetch("/api/bike/toml", { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify({ bike }) })).json()).toml;
  });
  writeFileSync(file, toml);
  await page.setInputFiles("#file-input", file);
  await page.waitForFunction(() => document.querySelector("#bike-select").value.startsWith("design:"));
  await page.setInputFiles("#file-input", file);
  await settled();
  const names = await page.evaluate(() => JSON.parse(localStorage.getItem("whipple.designs.v1")).map((d) => d.name));
  check(names.filter((n) => n === "opened twice").length === 1, `one design after two opens: ${JSON.stringify(names)}`);
  // A file whose format cannot be told is named in the message, with the way to name one.
  const odd = join(dir, "notes.txt");
  writeFileSync(odd, "just some words\nand more\n");
  await page.setInputFiles("#file-input", odd);
  const said = await waitForText("message", (t) => /cannot tell/.test(t));
  check(/cannot tell the format of notes\.txt/.test(said) && /`format`/.test(said), `an unknown file is named: "${said.slice(0, 140)}…"`);
  rmSync(dir, { recursive: true, force: true });
});

await section("a refused simulation says what the plots still show", async () => {
  await open("?bike=preset:benchmark&tab=sim");
  await page.getByTestId("tab-sim").click();
  await page.fill("#sim-speed", "4.6");
  await page.fill("#sim-duration", "2");
  await page.click("[data-testid=sim-run]");
  await ran((t) => t.startsWith("completed"));
  await page.fill("#sim-steer-torque", "2*foo");
  await page.click("[data-testid=sim-run]");
  await waitForText("sim-message", (t) => t.includes("foo"));
  const pill = await text("sim-outcome");
  check(/refused/.test(pill) && /previous run/.test(pill), `the outcome says the run was refused and the plots are the previous run's: "${pill}"`);
});

await section("the simulation starts on a held steady turn, with its torque and stability", async () => {
  await open("?bike=preset:benchmark&tab=sim");
  await page.getByTestId("tab-sim").click();
  await page.getByTestId("sim-from-turn").check();
  check(await page.locator("#sim-steer").isDisabled() && await page.locator("#sim-steer-torque").isDisabled(), "on a turn, the steer and its torque are the turn's: their inputs are off");
  await page.fill("#sim-speed", "5");
  await page.fill("#sim-lean", "11.5");
  await page.fill("#sim-lean-rate", "0.05");
  await page.fill("#sim-duration", "3");
  await page.click("[data-testid=sim-run]");
  const outcome = await ran((t) => t.length > 0 && !/not run/.test(t));
  const api = await page.evaluate(async () => {
    const bike = await (await fetch("/api/presets/benchmark")).json();
    return (await fetch("/api/turn", { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify({ bike, speed: 5, lean_deg: 11.5 }) })).json();
  });
  const steer = await text("sim-turn-steer");
  const torque = await text("sim-turn-torque");
  check(/^completed/.test(outcome), `the run on the 5 m/s, 11.5° turn completes: "${outcome}"`);
  check(Math.abs(parseFloat(steer.replace("−", "-")) - api.steer_deg) < 5e-5, `the turn's steer is the API's: ${steer} (API ${api.steer_deg})`);
  check(Math.abs(parseFloat(torque.replace("−", "-")) - api.turn.steer_torque) < 5e-5, `the holding torque is the API's: ${torque} (API ${api.turn.steer_torque})`);
  check((await text("sim-turn-verdict")) === "stable" && api.stability.stable, "it is said to be stable, as the API says");
  check(/held turn/.test((await page.textContent("#sim-meta")) ?? ""), "the run is labelled as started on the held turn");
  check(new URL(page.url()).searchParams.get("sim")?.includes("turn:held"), `the link keeps it: ${new URL(page.url()).searchParams.get("sim")}`);
  await page.fill("#sim-speed", "3");
  await page.fill("#sim-lean", "5");
  await page.click("[data-testid=sim-run]");
  await ran((t) => t.length > 0 && !/not run|simulating/.test(t));
  const verdict = await waitForText("sim-turn-verdict", (t) => t !== "stable");
  check(/^unstable/.test(verdict), `at 3 m/s the held turn is unstable: "${verdict}"`);
  await page.fill("#sim-lean", "89");
  await page.click("[data-testid=sim-run]");
  const message = await waitForText("sim-message", (t) => t.length > 0);
  check(/turn/i.test(message) && await page.locator("#sim-lean.invalid").count() === 1, `an impossible turn is refused beside the lean: "${message}"`);
  await page.getByTestId("sim-from-turn").uncheck();
  check(!(await page.locator("#sim-steer").isDisabled()) && !(await page.getByTestId("sim-turn").isVisible()), "unticked, the steer input is back and the turn's numbers are gone");
});

await section("the speed hint follows the bicycle", async () => {
  await open("?bike=preset:schwinn-crown");
  await page.getByTestId("tab-sim").click();
  check(/v set to its middle/.test(await text("sim-speed-hint")), `before typing, the hint says v was set: "${await text("sim-speed-hint")}"`);
  await page.fill("#sim-speed", "6");
  check(!/v set to its middle/.test(await text("sim-speed-hint")), `once a speed is typed, it no longer does: "${await text("sim-speed-hint")}"`);
  await pick("preset:benchmark");
  await waitForText("capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  const hint = await waitForText("sim-speed-hint", (t) => t.length > 0);
  check(hint.includes(WEAVE_SPEED.toFixed(2)) && hint.includes(CAPSIZE_SPEED.toFixed(2)), `after switching, the hint gives the benchmark's range: "${hint}"`);
  check((await page.inputValue("#sim-speed")) === "6", "and the speed typed stays");
});

await section("with negative trail the table says the capsize mode is unstable at every speed", async () => {
  await open("?bike=preset:schwinn-crown");
  await page.getByTestId("param-trail").fill("-0.05");
  const vc = await waitForText("capsize-speed", (t) => !t.startsWith("7.98"));
  check(/unstable at every speed/.test(vc), `v_c reads "${vc}"`);
});

await section("a benchmark rule met in the JBike6 form flags the JBike6 fields", async () => {
  await open("?bike=preset:schwinn-crown");
  await page.getByTestId("param-Dfrontwheel").fill("0");
  await waitForText("error-Dfrontwheel", (t) => t.length > 0);
  const flagged = await page.getByTestId("param-Dfrontwheel").evaluate((e) => e.classList.contains("invalid"));
  const message = await text("message");
  check(flagged, `the front wheel's D is flagged: "${await text("error-Dfrontwheel")}"`);
  check(!message.startsWith("invalid parameter `IFyy`") && /front wheel|Dfrontwheel/i.test(message), `the message speaks of the JBike6 entries: "${message}"`);
});

await section("a negative simulation speed is answered", async () => {
  await open("?bike=preset:benchmark");
  await page.getByTestId("tab-sim").click();
  await page.fill("#sim-speed", "-2");
  await settled();
  const note = (await page.getByTestId("sim-speed-note").isVisible()) ? await text("sim-speed-note") : "";
  check(/backwards/.test(note), `a negative speed is named: "${note}"`);
});

await section("no sideways scroll at 768 and 390 px; 1920 px uses the width", async () => {
  for (const [width, height] of [[768, 1024], [390, 844]]) {
    await open("?bike=preset:benchmark", { width, height });
    for (const tab of ["eigen", "control", "measure", "sim"]) {
      await page.getByTestId(`tab-${tab}`).click();
      await settled();
      const { scroll, inner, wide } = await page.evaluate(() => ({
        scroll: document.documentElement.scrollWidth,
        inner: window.innerWidth,
        wide: [...document.querySelectorAll("body *")].filter((e) => e.getBoundingClientRect().right > window.innerWidth + 1 && e.getClientRects().length && getComputedStyle(e).visibility !== "hidden").map((e) => e.id || e.className || e.tagName).slice(0, 5),
      }));
      check(scroll <= inner, `${width} px, ${tab} tab: the page is ${scroll} px wide (${wide.join(", ") || "nothing sticks out"})`);
    }
    const plot = await plotBox("sim-time-plot");
    check(plot && plot.width > 200 && plot.x >= 0 && plot.x + plot.width <= width + 1, `${width} px: the time plot fits (${Math.round(plot?.width ?? 0)} px wide)`);
  }
  await open("?bike=preset:benchmark", { width: 1920, height: 1080 });
  const plot = await plotBox("eigen-plot");
  const editorBox = await page.locator(".editor").boundingBox();
  check(plot.width > 1000 && editorBox.x < plot.x, `1920 px: the editor beside a ${Math.round(plot.width)} px plot`);
});

await section("explore: zoom, pan, box zoom, reset, autoscale and keyboard on the plots", async () => {
  await open("?bike=preset:benchmark");
  const box = await plotBox("eigen-plot");
  const full = await xTicks("eigen-plot");
  await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
  await page.mouse.wheel(0, -400);
  await becomes(async () => (await xTicks("eigen-plot")) !== full);
  const zoomed = await xTicks("eigen-plot");
  check(zoomed !== full, `the wheel zooms: ticks "${full.slice(0, 40)}" → "${zoomed.slice(0, 40)}"`);
  await page.getByTestId("plot-tooltip").waitFor({ state: "visible" });
  check(/v = /.test(await text("plot-tooltip")), "the read-out works in the zoomed view");
  await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.3, box.y + box.height * 0.5, { steps: 5 });
  await page.mouse.up();
  await becomes(async () => (await xTicks("eigen-plot")) !== zoomed);
  const panned = await xTicks("eigen-plot");
  check(panned !== zoomed, "dragging pans");
  await page.mouse.dblclick(box.x + box.width * 0.5, box.y + box.height * 0.5);
  await becomes(async () => (await xTicks("eigen-plot")) === full);
  check((await xTicks("eigen-plot")) === full, "a double-click resets the view");
  await page.keyboard.down("Shift");
  await page.mouse.move(box.x + box.width * 0.4, box.y + box.height * 0.3);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.6, box.y + box.height * 0.6, { steps: 5 });
  await page.mouse.up();
  await page.keyboard.up("Shift");
  await becomes(async () => (await xTicks("eigen-plot")) !== full);
  check((await xTicks("eigen-plot")) !== full, "shift-drag zooms to the box");
  await page.getByTestId("zoom-auto").first().click();
  await settled();
  await page.getByTestId("zoom-reset").first().click();
  await becomes(async () => (await xTicks("eigen-plot")) === full);
  check((await xTicks("eigen-plot")) === full, "Autoscale and Reset buttons work");
  await page.mouse.move(1, 1);
  await page.getByTestId("eigen-plot").focus();
  await page.keyboard.press("ArrowRight");
  await page.keyboard.press("ArrowRight");
  const keyed = await text("plot-tooltip");
  const live = await page.$eval("[data-testid=eigen-plot] [aria-live]", (e) => e.textContent);
  check(/v = /.test(keyed) && /weave/.test(live), `the keyboard reads values out (announced): "${keyed.slice(0, 50)}…"`);
  // The root locus, coloured by speed, with its read-out.
  await page.getByTestId("tab-locus").click();
  await page.waitForSelector("[data-testid=locus-curve]", { state: "attached" });
  check((await page.locator("[data-testid=locus-curve]").count()) > 20, "the root locus is drawn in colour bands of speed");
  await page.getByTestId("locus-plot").focus();
  await page.keyboard.press("ArrowRight");
  check(/v = /.test(await text("locus-plot-tooltip")), "and reads out the speed and eigenvalues");
  // The simulation's time plot zooms too.
  await page.getByTestId("tab-sim").click();
  await page.fill("#sim-speed", "4.6");
  await page.fill("#sim-duration", "3");
  await page.click("[data-testid=sim-run]");
  await ran((t) => t.startsWith("completed"));
  const tb = await plotBox("sim-time-plot");
  const t0 = await xTicks("sim-time-plot");
  await page.mouse.move(tb.x + tb.width * 0.5, tb.y + tb.height * 0.6);
  await page.mouse.wheel(0, -400);
  await becomes(async () => (await xTicks("sim-time-plot")) !== t0);
  check((await xTicks("sim-time-plot")) !== t0, "the time plot zooms");
  const gb = await plotBox("sim-track");
  const g0 = await xTicks("sim-track");
  await page.mouse.move(gb.x + gb.width * 0.5, gb.y + gb.height * 0.6);
  await page.mouse.wheel(0, -400);
  await becomes(async () => (await xTicks("sim-track")) !== g0);
  check((await xTicks("sim-track")) !== g0, "the ground track zooms");
});

await section("compare: three designs at once", async () => {
  await open("?bike=preset:schwinn-crown");
  await page.getByTestId("compare-select").selectOption("preset:benchmark");
  await waitForText("compare-capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  await page.getByTestId("compare-select").selectOption("preset:browser-jason");
  await waitForText("compare2-capsize-speed", (t) => /\d/.test(t));
  check((await page.locator("[data-testid=eigen-plot] [data-testid=compare-curve]").count()) === 8, "two compared designs draw four eigenvalue tracks each");
  const csv = await downloadOf(() => page.click("#eigen-csv"));
  check(/schwinn-crown/.test(csv.name) && /compared: .*Benchmark.*Browser/.test(csv.text.split("\n")[0]), `the CSV is named after the bike (${csv.name}) and names the compared designs`);
  const header = csv.text.split("\n").find((l) => !l.startsWith("#")) ?? "";
  check(/re1_weave/.test(header) && /castering/.test(header), `its header has the mode names: ${header.slice(0, 70)}…`);
  // An edited design beside its original: two names, not one.
  await open("?bike=preset:benchmark");
  await page.getByTestId("compare-select").selectOption("preset:benchmark");
  await waitForText("compare-capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  await page.getByTestId("param-c").fill("0.1");
  await waitForText("capsize-speed", (t) => !t.startsWith(asShown(CAPSIZE_SPEED)));
  const heads = await page.$$eval("#critical thead th", (ths) => ths.slice(1).map((t) => t.textContent));
  check(heads.length === 2 && heads[0] !== heads[1] && /\(edited\)$/.test(heads[0]), `the edited copy is named apart from its original: ${heads.join(" | ")}`);
});

await section("a link reproduces the state; back and forward work", async () => {
  await open("?bike=preset:schwinn-crown");
  await pick("preset:benchmark");
  await waitForText("capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  await page.getByTestId("param-c").fill("0.07");
  await waitForText("capsize-speed", (t) => !t.startsWith(asShown(CAPSIZE_SPEED)));
  const vc = await text("capsize-speed");
  await page.getByTestId("compare-select").selectOption("preset:two-mass-skate");
  await waitForText("compare-capsize-speed", (t) => /\d|none/.test(t));
  await page.fill("#v-stop", "8");
  await page.press("#v-stop", "Enter");
  await page.getByTestId("tab-locus").click();
  await settled();
  const link = page.url();
  const other = await context.newPage();
  await other.goto(link);
  await other.waitForSelector("body[data-ready=true]");
  await other.waitForFunction((v) => document.querySelector("[data-testid=capsize-speed]")?.textContent.trim() === v, vc, { timeout: 10_000 });
  const seen = await other.evaluate(() => ({
    bike: document.querySelector("#bike-select").value,
    c: document.querySelector("[data-testid=param-c]").value,
    stop: document.querySelector("#v-stop").value,
    tab: document.querySelector(".tab[data-view][aria-selected=true]").dataset.view,
    compare: document.querySelector("[data-testid=compare-capsize-speed]")?.textContent ?? null,
  }));
  await other.close();
  check(seen.bike === "preset:benchmark" && seen.c === "0.07" && seen.stop === "8" && seen.tab === "locus" && seen.compare !== null, `the link opens the same state elsewhere: ${JSON.stringify(seen)}`);
  const tabShown = () => page.$eval(".tab[data-view][aria-selected=true]", (e) => e.dataset.view);
  await page.goBack();
  await becomes(async () => (await tabShown()) === "eigen");
  await settled();
  check((await tabShown()) === "eigen", "back returns to the previous tab");
  await page.goBack();
  await becomes(async () => (await page.inputValue("#v-stop")) === "10");
  await settled();
  check((await page.inputValue("#v-stop")) === "10", "back again, the previous speed range");
  await page.goForward();
  await page.goForward();
  await becomes(async () => (await tabShown()) === "locus" && (await page.inputValue("#v-stop")) === "8");
  await settled();
  check((await page.$eval(".tab[data-view][aria-selected=true]", (e) => e.dataset.view)) === "locus" && (await page.inputValue("#v-stop")) === "8", "forward redoes both");
});

await section("modes: in words, animated, and played in 3-D", async () => {
  await open("?bike=preset:benchmark");
  await page.getByTestId("tab-modes").click();
  await page.fill("[data-testid=mode-speed]", "5");
  await page.click("[data-testid=mode-run]");
  await waitForText("mode-meta", (t) => t.includes("at 5 m/s"));
  const weave = await waitForText("mode-words-weave", (t) => t.length > 0);
  // Meijaard et al. 2007, Table 2: the weave's eigenvalues at 5 m/s.
  const period = (2 * Math.PI) / WEAVE_AT_5.im, half = Math.LN2 / -WEAVE_AT_5.re;
  // Shown to two digits: "oscillates every 1.4 s, decays by half in 0.89 s".
  check(weave === `weave: oscillates every ${Number(period.toPrecision(2))} s, decays by half in ${Number(half.toPrecision(2))} s`, `"${weave}" (Meijaard 2007: period ${period.toFixed(3)} s, half-life ${half.toFixed(3)} s)`);
  check(/capsize: does not oscillate, decays by half in/.test(await text("mode-words-capsize")), `"${await text("mode-words-capsize")}"`);
  // An invalid bicycle leaves the last modes on screen veiled, and the header says so.
  await page.getByTestId("param-mB").fill("-1");
  await waitFor("the modes veiled", async () => (await page.getByTestId("mode-list").getAttribute("class")).includes("stale"));
  check(/not recomputed: the parameters are invalid; last computed/.test(await text("mode-meta")), `an invalid bicycle veils the modes: "${await text("mode-meta")}"`);
  await page.getByTestId("param-mB").fill("85");
  await waitFor("the veil lifted", async () => !(await page.getByTestId("mode-list").getAttribute("class")).includes("stale"));
  check(!/not recomputed/.test(await text("mode-meta")), `mended, the modes are current again: "${await text("mode-meta")}"`);
  await page.getByTestId("mode-weave").click();
  await page.getByTestId("mode-anim").waitFor({ state: "visible" });
  // The read-out is written on the first animation frame, which a loaded machine may delay.
  const r = await waitForText("mode-anim-readout", (t) => /φ/.test(t));
  const t1 = await page.getByTestId("mode-anim").getAttribute("data-t");
  await becomes(async () => (await page.getByTestId("mode-anim").getAttribute("data-t")) !== t1);
  const t2 = await page.getByTestId("mode-anim").getAttribute("data-t");
  check(t1 !== t2 && /φ/.test(r), `the weave is animated beside the side view: ${r}`);
  await page.getByTestId("mode-3d-weave").click();
  await ran((t) => t.startsWith("completed"));
  check(await page.locator("#panel-sim").isVisible() && (await page.inputValue("#sim-speed")) === "5", "Play in 3-D runs the simulation from the weave's shape");
  await page.waitForSelector("[data-testid=sim-canvas]", { timeout: 15_000 });
  check(true, "in the 3-D view");
});

await section("simulation: overlay, linear prediction, CSV, time axis ending where the run ended", async () => {
  await open("?bike=preset:benchmark");
  await page.getByTestId("tab-sim").click();
  await page.fill("#sim-speed", "4.6");
  await page.fill("#sim-duration", "4");
  await page.click("[data-testid=sim-run]");
  await ran((t) => t.startsWith("completed"));
  check((await page.locator("[data-testid=sim-linear-curve]").count()) === 1, "the linear model's prediction is drawn");
  const csv = await downloadOf(() => page.click("[data-testid=sim-csv]"));
  const head = csv.text.split("\n");
  check(/benchmark/.test(csv.name) && head[0].includes("benchmark") && head[2].startsWith("t,lean_deg,steer_deg") && head[2].includes("linear_lean_deg"), `CSV ${csv.name}: ${head[2]}`);
  check(head.filter((l) => /^\d/.test(l)).length === 241, "one row per frame (4 s at 60 frames/s, both ends)");
  await page.fill("#sim-speed", "3");
  await page.fill("#sim-duration", "10");
  await page.click("[data-testid=sim-run]");
  const fell = await ran((t) => /t = \d/.test(t));
  check((await page.locator("[data-testid=sim-overlay-curve]").count()) === 1, "the earlier run stays overlaid");
  const end = Number(fell.match(/t = ([\d.]+)/)[1]);
  const ticks = (await xTicks("sim-time-plot")).split(" ").map(Number).filter(Number.isFinite);
  const last = Math.max(...ticks.filter((t) => t <= 12));
  check(last <= Math.max(end, 4) + 1, `the time axis ends near the longest run shown (ticks to ${last} s; this run ended at ${end} s, the earlier at 4 s)`);
});

await section("simulation: the rider's upper body leans on a hinge, drawn, read out, in the link; refused where it does not fit", async () => {
  await open("?bike=preset:schwinn-crown");
  await page.getByTestId("tab-sim").click();
  check(await page.getByTestId("sim-rider-k").isDisabled(), "the hinge's fields wait for the rider box");
  await page.getByTestId("sim-rider").check();
  check(!(await page.getByTestId("sim-steer-torque").isDisabled()) && await page.getByTestId("sim-from-turn").isDisabled(), "with the leaning rider the torques still act and the held turn is not used");
  await page.fill("#sim-speed", "5");
  await page.fill("#sim-lean-rate", "0");
  await page.fill("#sim-duration", "2");
  await page.click("[data-testid=sim-run]");
  const outcome = await ran((t) => t.startsWith("completed"));
  check(/2 s without falling/.test(outcome), `the run completes: "${outcome}"`);
  check((await page.locator("[data-testid=sim-rider-curve]").count()) === 1, "the upper body's lean on the hinge is drawn against time");
  check((await page.locator("[data-testid=sim-linear-curve]").count()) === 0 && /rigid rider only/.test(await page.locator("#sim-linear-note").textContent()), "no rigid-rider linear model beside it, and that is said");
  const meta = await page.locator("#sim-meta").textContent();
  check(/leaning rider k 800, c 50/.test(meta) && /T_r 20 for 0.5 s/.test(meta), `the run is named by its rider: "${meta}"`);
  await page.getByTestId("sim-scrub").fill("0.4");
  const lean = number(await text("sim-rider-readout"));
  check(lean > 0.5, `the read-out shows the upper body leaning right under the torque at 0.4 s: ${lean}°`);
  // The answer's fifth pose drawn: the frames carry the upper body (checked through the API).
  const bike = await page.evaluate(async () => (await (await fetch("/api/presets/schwinn-crown")).json()));
  const answer = await page.evaluate(async (b) => (await fetch("/api/simulate", { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify({ bike: b.bike ?? b, speed: 5, duration: 0.1, rider: { hinge_stiffness: 800, hinge_damping: 50 } }) })).json(), bike);
  check(answer.frames?.[0]?.bodies?.length === 5 && answer.geometry?.upper_body?.mass === 48.816, "the server's frames carry the upper body's pose");
  const csv = await downloadOf(() => page.click("[data-testid=sim-csv]"));
  check(csv.text.split("\n")[2].includes("rider_lean_deg"), "the CSV has the upper body's lean");
  // The link carries the rider; a reload restores it.
  const link = page.url();
  check(/rider%3Alean/.test(link) && /rk%3A800/.test(link), "the link carries the leaning rider");
  await open(new URL(link).search);
  await page.getByTestId("tab-sim").click();
  check(await page.getByTestId("sim-rider").isChecked() && (await page.getByTestId("sim-rider-k").inputValue()) === "800" && await page.getByTestId("sim-from-turn").isDisabled(), "a reload restores the rider and keeps the held turn off");
  // Bad input: text in a hinge field; a bicycle whose rider cannot hold Jason's upper body.
  await page.fill("#sim-rider-c", "soft");
  await page.click("[data-testid=sim-run]");
  await waitForText("sim-message", (t) => /hinge damping must be a number/.test(t));
  check(await page.getByTestId("sim-rider-c").evaluate((e) => e.classList.contains("invalid")), "the damping field is marked");
  await open("?bike=preset:benchmark");
  await page.getByTestId("tab-sim").click();
  await page.getByTestId("sim-rider").check();
  await page.fill("#sim-duration", "1");
  await page.click("[data-testid=sim-run]");
  const refusal = await waitForText("sim-message", (t) => /does not fit/.test(t));
  check(/Jason's upper body/.test(refusal) && /refused/.test(await text("sim-outcome")), `the benchmark bicycle's rider cannot hold it, said: "${refusal.slice(0, 120)}…"`);
});

await section("degrees, precision, display names", async () => {
  await open("?bike=preset:schwinn-crown");
  const options = await page.$$eval("#bike-select option", (os) => os.map((o) => o.textContent));
  check(options.includes("Schwinn Crown (JBike6 default)") && options.some((o) => /Meijaard/.test(o)), `presets under display names: ${options.slice(0, 4).join(" | ")}`);
  const head = await page.inputValue("[data-testid=param-head_angle]");
  check(Math.abs(Number(head) - 70.977782) < 1e-5 && head.length <= 10, `the head angle is typed in degrees: ${head}`);
  // Units and meanings come from the library's parameter table (GET /api/parameters).
  const table = await page.evaluate(async () => (await fetch("/api/parameters")).json());
  const massInfo = table.jbike6.find((p) => p.key === "mrider");
  const massTitle = await page.getByTestId("param-mrider").getAttribute("title");
  check(massInfo && massTitle === massInfo.description, `the rider's mass is described as the library describes it: "${massTitle}"`);
  const unit = await page.getByTestId("param-Irider(1)").evaluate((i) => i.closest(".row").querySelector(".unit").textContent);
  check(unit === "kg m²", `the inertia's unit from the table, printed: "${unit}"`);
  await page.getByTestId("param-head_angle").fill("1.23879599");
  const hint = await waitForText("hint-head_angle", (t) => t.length > 0);
  check(/did you mean 70\.98°\?/.test(hint), `a value in radians: "${hint}"`);
  await page.getByTestId("accept-head_angle").click();
  await waitForText("capsize-speed", (t) => t.startsWith("7.98"));
  check((await page.inputValue("[data-testid=param-head_angle]")) === "70.98", "accepted, the capsize speed is the Crown's again");
  const long = await page.evaluate(() => {
    const texts = [...document.querySelectorAll("input")].map((i) => i.value).concat(document.body.innerText.split(/\s+/));
    return texts.filter((t) => /\d\.\d{9,}/.test(t));
  });
  check(long.length === 0, `no number shown with round-off digits (${long.slice(0, 3).join(", ")})`);
  // The form is drawn on the click (no request): the next frame shows it. Not `settled()`: the
  // requests for the 1.24° head angle typed above may still be computing on the server,
  // superseded.
  await page.click("#tab-benchmark");
  await nextFrame();
  const shown = await page.$$eval("#editor-body input", (is) => is.map((i) => i.value).filter((v) => v.replace(/[-.]/g, "").length > 13));
  check(shown.length === 0, `the converted benchmark form shows sensible digits (${shown.slice(0, 3).join(", ")})`);
});

await section("a measured bicycle's warning beside its field (BicycleParameters' Browser)", async () => {
  await open("?bike=preset:benchmark");
  // BicycleParameters' measured Browser: its frame's principal moments break the triangle
  // inequality by 2.3 %, which a measurement may do: accepted with a warning on I_Byy.
  const data = fileURLToPath(new URL("../../whipple/tests/data/bicycleparameters/BrowserBenchmark.txt", import.meta.url));
  await page.setInputFiles("#file-input", data);
  const warning = await waitForText("warning-IByy", (t) => t.length > 0, 15_000);
  check(/triangle inequality/.test(warning) && /2\.332 %/.test(warning), `the warning stands beside I_Byy: "${warning.slice(0, 120)}…"`);
  const others = await page.$$eval(".row-warning", (ws) => ws.filter((w) => w.textContent).length);
  check(others === 1, `and nowhere else (${others} field)`);
  check(/\d/.test(await text("capsize-speed")), `the bicycle is computed all the same: v_c ${await text("capsize-speed")}`);
});

await section("phones (390 × 844, touch): a swipe on a plot scrolls the page, a tap reads out, a map cell asks before loading", async () => {
  const phone = await launch({ phone: true });
  try {
    const p = phone.context.pages()[0] ?? (await phone.context.newPage());
    await p.goto(new URL("?bike=preset:benchmark", url).href);
    await p.waitForSelector("body[data-ready=true]", { timeout: 20_000 });
    await p.waitForSelector("body[data-pending='0']", { state: "attached", timeout: 30_000 });
    const plot = p.getByTestId("eigen-plot");
    await plot.scrollIntoViewIfNeeded();
    const box = await plot.boundingBox();
    const view = async () => p.$$eval("[data-testid=eigen-plot] svg > g[fill] > text", (ts) => ts.map((t) => t.textContent).join(" "));
    const ticks = await view();
    // A one-finger swipe up that starts on the plot: the page scrolls, the plot does not pan.
    const cdp = await phone.context.newCDPSession(p);
    const before = await p.evaluate(() => window.scrollY);
    const x = box.x + box.width / 2;
    const y = box.y + box.height / 2;
    await cdp.send("Input.dispatchTouchEvent", { type: "touchStart", touchPoints: [{ x, y }] });
    for (let k = 1; k <= 8; k++) await cdp.send("Input.dispatchTouchEvent", { type: "touchMove", touchPoints: [{ x, y: y - 25 * k }] });
    await cdp.send("Input.dispatchTouchEvent", { type: "touchEnd", touchPoints: [] });
    await p.waitForFunction((b) => window.scrollY > b, before, { timeout: 5_000 });
    check((await view()) === ticks, `a swipe on the plot scrolled the page (${before} → ${await p.evaluate(() => window.scrollY)} px) and left the plot's view alone`);
    // A tap on the plot reads out there.
    const box2 = await plot.boundingBox();
    await p.touchscreen.tap(box2.x + box2.width * 0.5, box2.y + box2.height * 0.4);
    await p.waitForFunction(() => {
      const tip = document.querySelector("[data-testid=eigen-plot] [data-testid=plot-tooltip]");
      return tip && !tip.hidden && tip.textContent.length > 0;
    }, null, { timeout: 5_000 });
    check(true, `a tap on the plot shows its read-out: "${await p.locator("[data-testid=eigen-plot] [data-testid=plot-tooltip]").textContent()}"`);
    // The map: a tap reads the cell out and offers to load it; the bicycle stays until asked.
    await p.goto(new URL("?bike=preset:benchmark&tab=map", url).href);
    await p.waitForSelector("body[data-ready=true]", { timeout: 20_000 });
    await p.waitForFunction(() => /designs/.test(document.querySelector("[data-testid=map-meta]")?.textContent ?? ""), null, { timeout: 20_000 });
    const canvas = p.getByTestId("map-canvas");
    // The whole map on the screen: a tap outside the viewport lands elsewhere.
    await canvas.evaluate((c) => c.scrollIntoView({ block: "start" }));
    await p.evaluate(() => new Promise((done) => requestAnimationFrame(() => done())));
    const cb = await canvas.boundingBox();
    const area = JSON.parse(await canvas.getAttribute("data-area"));
    // The canvas may be drawn narrower than its own size on a phone (max-width: 100%).
    const scale = cb.width / parseFloat(await canvas.evaluate((c) => c.style.width));
    await p.touchscreen.tap(cb.x + scale * (area.x + (30.5 / 51) * area.w), cb.y + scale * (area.y + (1 - 20.5 / 51) * area.h));
    await p.getByTestId("map-load").waitFor({ timeout: 5_000 });
    const readout = (await p.getByTestId("map-readout").textContent()) ?? "";
    check(/trail = 0\.1, head_angle_deg = 70/.test(readout) && (await p.inputValue("[data-testid=param-c]")) === "0.08", `a tap reads the cell out and loads nothing yet: "${readout}"`);
    await p.getByTestId("map-load").tap();
    await p.waitForFunction(() => document.querySelector("[data-testid=param-c]").value === "0.1", null, { timeout: 10_000 }).catch(async (e) => {
      throw new Error(`${e.message}; message: ${await p.locator("#message").textContent()}; map message: ${await p.getByTestId("map-message").textContent()}; c = ${await p.inputValue("[data-testid=param-c]")}`);
    });
    check(true, "“Load this design” loads the tapped cell (trail 0.1 m)");
  } finally {
    await phone.close();
  }
});

await section("a link to an opened file, opened in a fresh browser, names the design in the picker", async () => {
  await open("?bike=preset:benchmark");
  const folder = fileURLToPath(new URL("../../whipple/tests/data/bicycleparameters/", import.meta.url));
  await page.setInputFiles("#file-input", join(folder, "FisherBenchmark.txt"));
  await waitFor("Fisher in the editor", async () => (await page.inputValue("#design-name")).startsWith("Fisher"), 15_000);
  await settled();
  const link = page.url();
  const fresh = await launch();
  try {
    const p = fresh.context.pages()[0] ?? (await fresh.context.newPage());
    await p.goto(link);
    await p.waitForSelector("body[data-ready=true]", { timeout: 20_000 });
    await p.waitForSelector("body[data-pending='0']", { state: "attached", timeout: 30_000 });
    const shown = await p.$eval("#bike-select", (s) => s.selectedOptions[0]?.textContent ?? "");
    check(shown === "Fisher (not saved here)", `the picker names the linked design: "${shown}"`);
    const vw = (await p.getByTestId("weave-speed").textContent()) ?? "";
    check(/ ± /.test(vw), `and its σ came with it: v_w ${vw}`);
  } finally {
    await fresh.close();
  }
});

await section("each request once: a first load, a switch, the benchmark form of a JBike6 bicycle", async () => {
  // The server's requests as the browser sends them; the site's as its back end answers them
  // (backend.js's whippleAsked), read since `mark`.
  const seen = [];
  const listen = (r) => r.url().includes("/api/") && seen.push(`${r.method()} ${new URL(r.url()).pathname}`);
  let mark = 0;
  const asked = async () => (site ? (await page.evaluate(() => globalThis.whippleAsked.slice())).slice(mark) : seen.slice());
  const reset = async () => {
    seen.length = 0;
    if (site) mark = await page.evaluate(() => globalThis.whippleAsked.length);
  };
  page.on("request", listen);
  try {
    await open("?bike=preset:benchmark");
    let now = await asked();
    const count = (what) => now.filter((a) => a === what).length;
    check(count("POST /api/bike/validate") === 1 && count("POST /api/eigen") === 1, `the first load asks once each: ${now.join(", ")}`);
    await reset();
    await pick("preset:schwinn-crown");
    await settled();
    now = await asked();
    check(count("POST /api/bike/validate") === 1 && count("POST /api/eigen") === 1, `a switch asks once each: ${now.join(", ")}`);
    await reset();
    await page.click("#tab-benchmark");
    await settled();
    // Settled means nothing in flight or scheduled (work.js): the converted form once asked
    // again after every answer and never settled.
    await nextFrame();
    now = await asked();
    check(now.length === 0 && (await page.getAttribute("body", "data-pending")) === "0", `the benchmark form of the Crown asks nothing, and keeps quiet: ${now.join(", ") || "none"}`);
    check(!site || seen.length === 0, `the site sends no request to the network for its API: ${seen.join(", ") || "none"}`);
  } finally {
    page.off("request", listen);
  }
});

await section("an invalid speed range veils the results and the header says so", async () => {
  await open("?bike=preset:benchmark");
  const veiled = async () => (await page.locator("[data-testid=eigen-plot] [data-testid=stale-veil]").count()) === 1 && (await page.locator("#critical table.stale").count()) === 1;
  for (const [field, typed, what] of [["#v-step", "0", "a step of 0"], ["#v-stop", "-5", "a reversed range"], ["#v-stop", "1e6", "a million speeds"], ["#v-step", "x", "a step that is not a number"]]) {
    await open("?bike=preset:benchmark");
    await page.fill(field, typed);
    await page.press(field, "Enter");
    await waitFor(`${what}: the results veiled`, veiled);
    const meta = await text("critical-meta");
    check(/not recomputed: the speeds are/.test(meta), `${what}: veiled, the header says why: "${meta}"`);
  }
  await page.fill("#v-step", "0.01");
  await page.press("#v-step", "Enter");
  await waitFor("mended: the veil lifted", async () => !(await veiled()));
  check(/^linear model, 0 – 10 m\/s$/.test(await text("critical-meta")), `mended, the header names the speeds again: "${await text("critical-meta")}"`);
});

await section("measured files: every field shows its value and σ, kept through an edit and a save", async () => {
  const folder = fileURLToPath(new URL("../../whipple/tests/data/bicycleparameters/", import.meta.url));
  // Every bicycle BicycleParameters ships (JasonBrowser is a rider alone, not a bicycle).
  const files = readdirSync(folder).filter((f) => f.endsWith("Benchmark.txt") && !f.startsWith("JasonBrowser")).sort();
  const DEG = 180 / Math.PI;
  let fields = 0;
  let sigmas = 0;
  for (const file of files) {
    await open("?bike=preset:benchmark");
    await page.setInputFiles("#file-input", join(folder, file));
    // Named as BicycleParameters names it, without the parameter set's suffix.
    await waitFor(`${file} in the editor`, async () => (await page.inputValue("#design-name")).startsWith(file.replace(/Benchmark\.txt$/, "")), 15_000);
    await settled();
    const shown = await page.$$eval("#editor-body input", (is) => Object.fromEntries(is.map((i) => [i.dataset.testid, i.value])));
    for (const line of readFileSync(join(folder, file), "utf8").split("\n")) {
      const kv = /^\s*(\w+)\s*=\s*(\S+)/.exec(line);
      if (!kv || !(`param-${kv[1]}` in shown)) continue;
      const m = [kv[0], kv[1], ...kv[2].split("+/-")];
      const angle = m[1] === "lam";
      const [value, sigma] = [Number(m[2]), m[3] === undefined ? null : Number(m[3])].map((x) => (x !== null && angle ? x * DEG : x));
      const field = Number(shown[`param-${m[1]}`]);
      // Angles are shown in degrees to 8 digits, other values to 12.
      const digits = angle ? 1e-7 : 1e-11;
      check(Math.abs(field - value) <= digits * Math.max(1, Math.abs(value)), `${file}: ${m[1]} shows ${value} (“${shown[`param-${m[1]}`]}”)`, { quiet: true });
      fields += 1;
      // A σ of 0 (the published benchmark's file) is no measurement spread: no σ field.
      if (sigma !== null && sigma > 0) {
        const s = Number(shown[`sigma-${m[1]}`]);
        check(Math.abs(s - sigma) <= digits * Math.max(1e-3, Math.abs(sigma)), `${file}: σ of ${m[1]} shows ${sigma} (“${shown[`sigma-${m[1]}`]}”)`, { quiet: true });
        sigmas += 1;
      } else {
        check(!(`sigma-${m[1]}` in shown) || Number(shown[`sigma-${m[1]}`]) === 0, `${file}: ${m[1]} has no σ field (none measured)`, { quiet: true });
      }
    }
  }
  check(fields >= 12 * 26 && sigmas >= 10 * 25, `${files.length} files: ${fields} fields showed their value, ${sigmas} their σ`);
  // Fisher: an edit keeps every σ, the table reads v ± σ, and the saved TOML has every σ.
  await open("?bike=preset:benchmark");
  await page.setInputFiles("#file-input", join(folder, "FisherBenchmark.txt"));
  await waitFor("Fisher in the editor", async () => (await page.inputValue("#design-name")).startsWith("Fisher"), 15_000);
  await settled();
  const before = await text("weave-speed");
  check(/^\d+\.\d{4} ± \d/.test(before), `v_w ± σ in the table: "${before}"`);
  check(/ ± /.test(await text("stable-ranges")), `the self-stable range's ends ± σ: "${await text("stable-ranges")}"`);
  const marks = await page.$$eval("[data-testid=eigen-plot] svg text", (ts) => ts.map((t) => t.textContent).filter((t) => /^v_[wc] /.test(t)));
  check(marks.length === 2 && marks.every((t) => / ± /.test(t)) && (await page.locator("[data-testid=eigen-plot] [data-testid=sigma-band]").count()) >= 2, `the plot's markers read v ± σ with the band shaded: ${marks.join(", ")}`);
  const fisherCsv = await downloadOf(() => page.click("#eigen-csv"));
  check(/^# Fisher: .*v_w = [\d.]+ ± [\d.e-]+ m\/s/m.test(fisherCsv.text), `the CSV's header gives v ± σ: ${fisherCsv.text.split("\n")[1]}`);
  await page.getByTestId("param-mB").fill("5");
  await waitForText("weave-speed", (t) => t !== before && / ± /.test(t));
  check((await page.inputValue("[data-testid=sigma-mB]")) === "0.02", "the edited mass keeps its σ (0.02 kg)");
  await page.getByTestId("sigma-mB").fill("0.05");
  await settled();
  const saved = await downloadOf(() => page.click("#save-toml"));
  const measured = saved.text.split("\n").filter((l) => /^\w+ = \{ value = /.test(l));
  check(measured.length === 26 && /^mB = \{ value = 5(\.0)?, sigma = 0\.05 \}/m.test(saved.text), `the saved TOML keeps every σ (${measured.length} of 26), the edited mass with its new σ: ${saved.text.match(/^mB = .*$/m)?.[0]}`);
  // Typing back the value shown clears "modified".
  await page.getByTestId("param-mB").fill("4.5");
  await page.getByTestId("sigma-mB").fill("0.02");
  await settled();
  check(await page.locator("#modified").isHidden(), "retyping the shown values leaves the bicycle unmodified");
});

await section("a file typed in millimetres and degrees reads in SI and is saved in the units it was typed in", async () => {
  await open("?bike=preset:benchmark");
  const si = (await downloadOf(() => page.click("#save-toml"))).text;
  const typed = si
    .replace(/^w = 1\.02 #/m, "w_mm = 1020 #")
    .replace(/^c = 0\.08 #/m, "c_mm = 80 #")
    .replace(/^lam = 0\.3141592653589793 #/m, "lam_deg = 18 #")
    .replace(/^name = .*$/m, 'name = "typed in mm"');
  check(/^c_mm = 80 #/m.test(typed) && /^lam_deg = 18 #/m.test(typed) && /^w_mm = 1020 #/m.test(typed), "a TOML file with w_mm, c_mm and lam_deg");
  await page.setInputFiles("#file-input", { name: "typed.toml", mimeType: "application/toml", buffer: Buffer.from(typed) });
  await waitFor("the typed file in the editor", async () => (await page.inputValue("#design-name")) === "typed in mm", 15_000);
  await settled();
  check((await page.inputValue("[data-testid=param-c]")) === "0.08" && (await page.inputValue("[data-testid=param-w]")) === "1.02", `the fields read SI: c ${await page.inputValue("[data-testid=param-c]")} m, w ${await page.inputValue("[data-testid=param-w]")} m`);
  check(/^4\.2924/.test(await text("weave-speed")), `the benchmark's weave speed: ${await text("weave-speed")}`);
  const back = (await downloadOf(() => page.click("#save-toml"))).text;
  check(/^w_mm = 1020(\.0)? /m.test(back) && /^c_mm = 80(\.0)? /m.test(back) && /^lam_deg = 18(\.0)? /m.test(back) && !/^c = /m.test(back), `Save TOML writes the keys as typed: ${back.match(/^(w_mm|c_mm|lam_deg) = [^ ]*/gm)?.join(", ")}`);
  // An edit is written in the unit the key was typed in; My designs keeps the units over a reload.
  await page.getByTestId("param-c").fill("0.07");
  await settled();
  await page.click("#save-design");
  await page.reload();
  await page.waitForSelector("body[data-ready=true]", { timeout: 20_000 });
  await waitFor("the saved design after a reload", async () => (await page.inputValue("#design-name")) === "typed in mm", 15_000);
  await settled();
  const again = (await downloadOf(() => page.click("#save-toml"))).text;
  check(/^c_mm = 70(\.0)? /m.test(again) && /^lam_deg = 18(\.0)? /m.test(again), `after an edit and a reload: ${again.match(/^(c_mm|lam_deg) = [^ ]*/gm)?.join(", ")}`);
  // A preset has no typed units: its TOML is SI.
  await open("?bike=preset:benchmark");
  check(/^c = 0\.08 /m.test((await downloadOf(() => page.click("#save-toml"))).text), "a preset is saved in SI");
});

await section("units typed in the page's fields: mm and degrees in the editor, km/h in the speeds, saved as typed", async () => {
  await open("?bike=preset:benchmark");
  // 70 mm of trail: `whipple speeds --bike benchmark --set c=0.07` gives v_w 4.173324515661374.
  await page.getByTestId("param-c").fill("70 mm");
  const weave = await waitForText("weave-speed", (t) => /^4\.17/.test(t), 15_000);
  check(/^4\.1733/.test(weave), `"70 mm" of trail is 0.07 m: v_w ${weave} (the CLI: 4.1733)`);
  await page.getByTestId("param-lam").fill("18 deg");
  await settled();
  const typed = (await downloadOf(() => page.click("#save-toml"))).text;
  check(/^c_mm = 70(\.0)? /m.test(typed) && /^lam_deg = 18(\.0)? /m.test(typed) && !/^c = /m.test(typed), `Save TOML writes them as typed: ${typed.match(/^(c_mm|c|lam_deg|lam) = [^ ]*/gm)?.join(", ")}`);
  // The SI unit typed drops the suffix again.
  await page.getByTestId("param-c").fill("0.08 m");
  await settled();
  const si = (await downloadOf(() => page.click("#save-toml"))).text;
  check(/^c = 0\.08 /m.test(si) && !/^c_mm/m.test(si) && /^lam_deg = 18(\.0)? /m.test(si), `"0.08 m" is written as c again: ${si.match(/^(c_mm|c|lam_deg) = [^ ]*/gm)?.join(", ")}`);
  // A unit the field does not take is named, and nothing is sent.
  await page.getByTestId("param-c").fill("70 km/h");
  const wrong = await waitForText("error-c", (t) => t !== "", 5_000);
  check(/not a number of mm or m/.test(wrong), `a speed's unit in a length's field: "${wrong}"`);
  await page.getByTestId("param-c").fill("0.08");
  await settled();
  // Speeds in km/h: 0 to 36 km/h is 0 to 10 m/s.
  await page.fill("#v-stop", "36 km/h");
  await page.fill("#v-step", "0.036 km/h");
  await page.press("#v-step", "Enter");
  const meta = await waitForText("critical-meta", (t) => /^linear model, 0 – 10 m\/s \(0 – 36 km\/h\)$/.test(t), 15_000);
  check(/^4\.2924\d* \(15\.45 km\/h\)$/.test(await text("weave-speed")), `v up to "36 km/h" in steps of "0.036 km/h": "${meta}", v_w ${await text("weave-speed")}`);
  // Typed in km/h, the critical speeds are given in km/h too, after their m/s.
  check(/^4\.292 – 6\.024 \(15\.45 – 21\.69 km\/h\)$/.test(await text("stable-ranges")), `the self-stable range in km/h too: "${await text("stable-ranges")}"`);
  // The unit beside the fields follows them: km/h (the start, 0, is 0 in either), then both.
  check((await text("v-unit")) === "km/h", `the speed fields' unit, typed in km/h: "${await text("v-unit")}"`);
  await page.fill("#v-stop", "10");
  check((await text("v-unit")) === "m/s or km/h, as typed", `one field in m/s, one in km/h: "${await text("v-unit")}"`);
  await page.fill("#v-step", "0.01");
  await page.press("#v-step", "Enter");
  await waitForText("critical-meta", (t) => /^linear model, 0 – 10 m\/s$/.test(t), 15_000);
  check((await text("v-unit")) === "m/s", `typed in m/s again: "${await text("v-unit")}"`);
  check(/^4\.2924\d*$/.test(await text("weave-speed")), `typed in m/s again, m/s alone: v_w ${await text("weave-speed")}`);
  // The design map's speed and band in km/h (both back ends: read from the page, not the wire).
  await open("?bike=preset:benchmark&tab=map");
  await waitForText("map-meta", (t) => /designs \(/.test(t), 20_000);
  await page.selectOption("[data-testid=map-quantity]", "band_margin");
  await page.getByTestId("map-speed").fill("18 km/h");
  await page.getByTestId("map-band").fill("16:23 km/h");
  await page.getByTestId("map-run").click();
  const legend = await waitForText("map-legend", (t) => /self-stable at every speed/.test(t), 20_000);
  const wrongFields = await page.$$eval("#map-speed.invalid, #map-band.invalid", (l) => l.length);
  check(/self-stable at every speed 4\.44\d*–6\.38\d* m\/s/.test(legend) && wrongFields === 0, `"16:23 km/h" is the band 4.444–6.389 m/s, "18 km/h" a speed: "${legend}"`);
});

await section("sensitivity: exact elasticities as a tornado and a table", async () => {
  await open("?bike=preset:benchmark&tab=sens");
  await page.getByTestId("sens-tornado").waitFor({ timeout: 15_000 });
  const bars = await page.$$eval("[data-testid=sens-tornado] rect[data-key]", (rs) => rs.map((r) => r.dataset.key));
  // v_w scales as sqrt(g) (dimensional analysis): its elasticity to g is exactly 1/2, the largest.
  const first = await page.$eval("[data-testid=sens-table] tbody tr", (r) => [r.dataset.key, r.cells[5].textContent]);
  check(bars[0] === "g" && first[0] === "g" && first[1] === "0.5", `the weave speed moves most with g, elasticity 1/2: ${bars.slice(0, 3).join(", ")}; ${first.join(" ")}`);
  const rows = await page.locator("[data-testid=sens-table] tbody tr").count();
  check(rows === 26 && bars.length === 12, `every benchmark parameter in the table (${rows}), the twelve largest as bars (${bars.length})`);
  const trail = await page.$eval("[data-testid=sens-table] tr[data-key=c]", (r) => r.cells[3].textContent);
  check(trail === "11.48", `dv_w/dc = 11.48 as the CLI prints it: ${trail}`);
  await page.selectOption("[data-testid=sens-quantity]", "capsize");
  await waitFor("the capsize tornado", async () => (await page.$eval("[data-testid=sens-tornado]", (e) => e.getAttribute("aria-label"))).includes("capsize"));
  check(page.url().includes("tab=sens"), `the tab is in the link: ${page.url()}`);
  await page.getByTestId("param-c").fill("0.1");
  const edited = await waitForText("sens-meta", (t) => /v_w \d/.test(t) && !t.includes(`v_w ${WEAVE_SPEED.toFixed(3)}`));
  check(/v_w 4\.507/.test(edited), `an edit (trail 0.1 m) is followed (4.507 m/s, as \`whipple speeds\` gives): ${edited}`);
});

await section("design map: a certified map over two parameters, read out under the cursor", async () => {
  await open("?bike=preset:benchmark&tab=map");
  const meta = await waitForText("map-meta", (t) => /designs \(/.test(t), 20_000);
  check(/51 × 51 designs \(2601 computed\)/.test(meta), `the default map: ${meta}`);
  // The base design (trail 0.08 m, head angle 72°) sits on the grid: cell (26, 24).
  const box = await page.getByTestId("map-canvas").boundingBox();
  const area = JSON.parse(await page.getByTestId("map-canvas").getAttribute("data-area"));
  const at = (ix, iy) => [box.x + area.x + ((ix + 0.5) / 51) * area.w, box.y + area.y + (1 - (iy + 0.5) / 51) * area.h];
  await page.mouse.move(...at(26, 24));
  const readout = await waitForText("map-readout", (t) => t.length > 0);
  const width = (CAPSIZE_SPEED - WEAVE_SPEED).toFixed(3);
  check(readout.includes(`trail = 0.08, head_angle_deg = 72: ${width} m/s`), `the benchmark's own cell: its stable width ${width} m/s (${CAPSIZE_SPEED.toFixed(3)} − ${WEAVE_SPEED.toFixed(3)}): "${readout}"`);
  await page.selectOption("[data-testid=map-quantity]", "v_w");
  const [hx, hy] = at(26, 24);
  await page.mouse.move(hx + 1, hy);
  check((await waitForText("map-readout", (t) => t.includes(WEAVE_SPEED.toFixed(2)) || /none/.test(t))).includes(`${WEAVE_SPEED.toFixed(3)} m/s`), `the same cell's weave speed: ${await text("map-readout")}`);
  check(/map=/.test(page.url()) && /tab=map/.test(page.url()), `the map's inputs are in the link: ${page.url()}`);
  // A click loads that cell's design into the editor: trail 0.1 m (ix 30), head angle 70° (iy 20).
  await page.mouse.click(...at(30, 20));
  await waitFor("the clicked design in the editor", async () => (await page.inputValue("[data-testid=param-c]")) === "0.1");
  const lam = await page.inputValue("[data-testid=param-lam]");
  check(Math.abs(Number(lam) - 20) < 1e-9, `the steer axis tilt follows the head angle: λ = ${lam}° (90° − 70°)`);
  await waitForText("map-meta", (t) => /designs \(/.test(t), 20_000);
  await page.mouse.move(...at(30, 20));
  const own = await waitForText("map-readout", (t) => /trail = 0\.1,/.test(t));
  check(/v_w|m\/s/.test(own), `the map follows the loaded design: ${own}`);
  // The loaded design's recompute redraws the map, clearing the fields' flags: it has ended
  // before the malformed axis is asked, and the answer to that has come before it is read.
  await settled();
  await page.getByTestId("map-x").fill("trail=0:0.2");
  await page.getByTestId("map-run").click();
  await settled();
  const message = await waitForText("map-message", (t) => t.length > 0);
  check(/x|trail/.test(message) && (await page.getByTestId("map-x").evaluate((i) => i.classList.contains("invalid"))), `a malformed axis is refused, naming it: "${message}"`);
  // With y empty: the one-parameter study, v_w and v_c against trail.
  await open("?bike=preset:benchmark&tab=map");
  await waitForText("map-meta", (t) => /designs \(/.test(t), 20_000);
  await page.getByTestId("map-x").fill("trail=0:0.2:41");
  await page.getByTestId("map-y").fill("");
  await page.getByTestId("map-run").click();
  const studyMeta = await waitForText("map-meta", (t) => /against trail, 41 designs/.test(t), 20_000);
  check(/41 computed/.test(studyMeta), `the study: ${studyMeta}`);
  const sbox = await page.getByTestId("map-canvas").boundingBox();
  const sarea = JSON.parse(await page.getByTestId("map-canvas").getAttribute("data-area"));
  await page.mouse.move(sbox.x + sarea.x + (16 / 40) * sarea.w, sbox.y + sarea.y + sarea.h / 2);
  const studied = await waitForText("map-readout", (t) => /trail = 0\.08:/.test(t));
  const [vw, vc] = [WEAVE_SPEED.toFixed(3), CAPSIZE_SPEED.toFixed(3)];
  check(studied.includes(`v_w ${vw} m/s, v_c ${vc} m/s; self-stable from ${vw} m/s to ${vc} m/s`), `the benchmark's own trail in the study: "${studied}"`);
});

await section("design map: a map under way says how far it is, and Cancel stops it", async () => {
  await open("?bike=preset:benchmark&tab=map");
  await waitForText("map-meta", (t) => /designs \(/.test(t), 20_000);
  // Every text the header shows, as it changes.
  await page.evaluate(() => {
    const meta = document.querySelector("[data-testid=map-meta]");
    globalThis.metaSeen = [];
    new MutationObserver(() => globalThis.metaSeen.push(meta.textContent)).observe(meta, { childList: true, characterData: true, subtree: true });
  });
  await page.getByTestId("map-x").fill("trail=-0.05:0.2:500");
  await page.getByTestId("map-y").fill("head_angle_deg=60:85:500");
  // Asked and cancelled in one task, so that the answer cannot come first.
  await page.evaluate(() => {
    document.querySelector("[data-testid=map-run]").click();
    document.querySelector("[data-testid=map-cancel]").click();
  });
  const stopped = await waitForText("map-meta", (t) => /^cancelled after/.test(t), 10_000);
  await settled();
  check(await page.getByTestId("map-cancel").isHidden(), `cancelled: "${stopped}", the Cancel button gone`);
  check((await page.getByTestId("map-legend").textContent()) === "" && (await page.getByTestId("map-axes").textContent()) === "" && (await page.getByTestId("map-message").isHidden()), "no map, axes or error stay after a cancel");
  // Asked again, the same map is computed whole (the static site's worker was ended and
  // starts again), the designs counted as they come where the back end tells them.
  await page.getByTestId("map-run").click();
  await waitFor("Cancel shown while the map runs", async () => (await page.getByTestId("map-cancel").isVisible()) || /500 × 500/.test(await text("map-meta")), 10_000);
  const done = await waitForText("map-meta", (t) => /500 × 500 designs/.test(t), 90_000);
  check(/\(\d+ computed/.test(done) && (await page.getByTestId("map-cancel").isHidden()), `then computed whole: ${done}`);
  // fetch("/api/...") aborted rejects as a fetch does, whichever back end answers it.
  const aborted = await page.evaluate(async () => {
    const bike = await (await fetch("/api/presets/benchmark")).json();
    const stop = new AbortController();
    const asked = fetch("/api/map", { method: "POST", body: JSON.stringify({ bike, x: "trail=0:0.2:400", y: "head_angle_deg=60:85:400" }), signal: stop.signal });
    stop.abort();
    try {
      return `answered ${(await asked).status}`;
    } catch (e) {
      return e.name;
    }
  });
  check(aborted === "AbortError", `an aborted fetch of /api/map rejects with an AbortError: ${aborted}`);
  const seen = await page.evaluate(() => globalThis.metaSeen);
  const counted = seen.filter((t) => /^computing… [\d,]+ of 250,000 designs, [\d.]+ s$/.test(t));
  // Both back ends tell the designs done: the static site's worker, the server in the lines
  // of its answer (the first chunk's 32,768 at once, then at most five times a second).
  check(counted.length >= 2 && counted.some((t) => t.startsWith("computing… 32,768 of")), `its progress shown, chunk by chunk: ${counted.join(" | ")}`);
});

await section("design map: self-stable over a band, the qualifying designs outlined", async () => {
  await open("?bike=preset:benchmark&tab=map");
  await waitForText("map-meta", (t) => /designs \(/.test(t), 20_000);
  const box = await page.getByTestId("map-canvas").boundingBox();
  const area = JSON.parse(await page.getByTestId("map-canvas").getAttribute("data-area"));
  const at = (ix, iy) => [box.x + area.x + ((ix + 0.5) / 51) * area.w, box.y + area.y + (1 - (iy + 0.5) / 51) * area.h];
  // Asked without a band, the quantity is refused in the field, with no old map left standing.
  await page.selectOption("[data-testid=map-quantity]", "band_margin");
  const refused = await waitForText("map-message", (t) => /band/.test(t));
  check((await page.getByTestId("map-band").evaluate((i) => i.classList.contains("invalid"))) && (await text("map-meta")) === "", `no band, no map: "${refused}"`);
  // Over 4.5–5.5 m/s: the benchmark's own design (cell 26, 24; its range 4.292… to 6.024… m/s)
  // qualifies with margins 0.2076 below and 0.5243 above.
  await page.getByTestId("map-band").fill("4.5:5.5");
  await page.getByTestId("map-run").click();
  await waitForText("map-meta", (t) => /designs \(/.test(t), 20_000);
  await waitFor("the qualifying designs counted", async () => Number(await page.getByTestId("map-canvas").getAttribute("data-qualifying")) > 0);
  await page.mouse.move(...at(26, 24));
  const below = (4.5 - WEAVE_SPEED).toFixed(4);
  const above = (CAPSIZE_SPEED - 5.5).toFixed(4);
  const inside = await waitForText("map-readout", (t) => /self-stable over/.test(t));
  check(inside.includes(`self-stable over 4.5–5.5 m/s, margins ${below} m/s below and ${above} m/s above`), `the benchmark over 4.5–5.5 m/s: "${inside}"`);
  const legend = await text("map-legend");
  check(/self-stable at every speed 4\.5–5\.5 m\/s/.test(legend) && /undecided/.test(legend), `the legend names the band: "${legend}"`);
  check(/band:4\.5:5\.5/.test(decodeURIComponent(page.url())), `the band is in the link: ${page.url()}`);
  // Over 4–8 m/s no design of this map qualifies (whipple map gives none either).
  await page.getByTestId("map-band").fill("4:8");
  await page.getByTestId("map-run").click();
  await waitFor("the map over 4–8 m/s", async () => (await page.getByTestId("map-canvas").getAttribute("data-qualifying")) === "0");
  await page.mouse.move(...at(26, 25));
  await page.mouse.move(...at(26, 24));
  const outside = await waitForText("map-readout", (t) => /over 4–8/.test(t));
  check(outside.includes("trail = 0.08, head_angle_deg = 72: not self-stable over 4–8 m/s"), `the benchmark over 4–8 m/s: "${outside}"`);
  // A band past the speeds asked for names the band's field.
  await page.getByTestId("map-band").fill("8:4");
  await page.getByTestId("map-run").click();
  const reversed = await waitForText("map-message", (t) => /band/.test(t));
  check(await page.getByTestId("map-band").evaluate((i) => i.classList.contains("invalid")), `a reversed band is refused in its field: "${reversed}"`);
});

await section("side view: centres of mass and inertia ellipses toggled, kept in the link", async () => {
  await open("?bike=preset:schwinn-crown");
  await settled();
  const count = (part) => page.locator(`[data-testid=side-view] [data-part=${part}]`).count();
  const totalLabel = () => page.$$eval("[data-testid=side-view] svg text", (ts) => ts.some((t) => /^total /.test(t.textContent)));
  const [centres, ellipses] = [await count("centre-of-mass"), await count("inertia-ellipse")];
  // The Crown's seven JBike6 bodies and the whole bicycle's centre; the rider, frame, fork, … ellipses.
  check(centres >= 5 && ellipses >= 3 && (await totalLabel()), `both drawn by default: ${centres} centres of mass, ${ellipses} inertia ellipses`);
  await page.getByTestId("side-centres").uncheck();
  await waitFor("the centres of mass hidden", async () => (await count("centre-of-mass")) === 0);
  check((await count("inertia-ellipse")) === ellipses && !(await totalLabel()), "without the centres of mass (and their labels) the ellipses stay");
  await page.getByTestId("side-ellipses").uncheck();
  await waitFor("the ellipses hidden", async () => (await count("inertia-ellipse")) === 0);
  check((await page.locator("[data-testid=side-view] svg circle").count()) > 4, "the bicycle itself is still drawn");
  await settled();
  check(/[?&]sv=centres:off;ellipses:off(&|$)/.test(decodeURIComponent(page.url())), `the link says so: ${decodeURIComponent(new URL(page.url()).search).match(/sv=[^&]*/)?.[0]}`);
  await page.reload();
  await page.waitForSelector("body[data-ready=true]");
  await settled();
  await waitFor("the side view redrawn", async () => (await page.locator("[data-testid=side-view] svg circle").count()) > 4);
  check((await count("centre-of-mass")) === 0 && (await count("inertia-ellipse")) === 0 && !(await page.getByTestId("side-centres").isChecked()) && !(await page.getByTestId("side-ellipses").isChecked()), "a reload keeps both hidden, the boxes unticked");
  await page.getByTestId("side-centres").check();
  await waitFor("the centres of mass back", async () => (await count("centre-of-mass")) === centres);
  check((await count("inertia-ellipse")) === 0, `ticked again: ${centres} centres of mass, still no ellipse`);
});

await section("reset: a preset, a conversion and an opened file go back as picked in one click", async () => {
  // A measured preset: value and σ.
  await open("?bike=preset:browser");
  await settled();
  const reset = page.getByTestId("reset-bike");
  const as = { vw: await text("weave-speed"), c: await page.inputValue("[data-testid=param-c]"), sc: await page.inputValue("[data-testid=sigma-c]") };
  check(await reset.isHidden(), "nothing edited: no reset button");
  const barHeight = () => page.$eval(".topbar", (e) => Math.round(e.getBoundingClientRect().height));
  const unedited = await barHeight();
  await page.getByTestId("param-c").fill("0.09");
  await waitForText("weave-speed", (t) => t !== as.vw && /\d/.test(t));
  await page.getByTestId("sigma-c").fill("0.01");
  await settled();
  check((await page.locator("#modified").isVisible()) && (await reset.isVisible()) && (await reset.getAttribute("aria-label")) === "Reset to the preset", `edited (c 0.09 ± 0.01, v_w ${await text("weave-speed")}): “${await reset.getAttribute("aria-label")}” offered`);
  check((await barHeight()) === unedited, `the top bar keeps its one line with the button (${unedited} px high)`);
  await reset.click();
  await waitForText("weave-speed", (t) => t === as.vw);
  await settled();
  const back = { c: await page.inputValue("[data-testid=param-c]"), sc: await page.inputValue("[data-testid=sigma-c]") };
  check(back.c === as.c && back.sc === as.sc, `one click: c ${back.c} ± ${back.sc} again, v_w ${await text("weave-speed")}`);
  check((await page.locator("#modified").isHidden()) && (await reset.isHidden()) && !/[?&]e=/.test(page.url()), "“modified” cleared, the button gone, the link holds no edit");
  // A JBike6 preset converted to the benchmark form and edited: back to the JBike6 form.
  await open("?bike=preset:schwinn-crown");
  await settled();
  const crown = await text("capsize-speed");
  await page.click("#tab-benchmark");
  await page.click("#to-benchmark");
  await settled();
  await page.getByTestId("param-c").fill("0.05");
  await waitForText("capsize-speed", (t) => t !== crown && /\d/.test(t));
  await reset.click();
  await waitForText("capsize-speed", (t) => t === crown);
  await settled();
  check((await page.$eval("#bike-select", (s) => s.value)) === "preset:schwinn-crown" && (await page.getAttribute("#tab-jbike6", "aria-selected")) === "true" && (await page.locator("#modified").isHidden()), `a conversion undone: the Crown in its JBike6 form, v_c ${crown}`);
  // A file opened: back to the file as opened.
  await open("?bike=preset:benchmark");
  const folder = fileURLToPath(new URL("../../whipple/tests/data/bicycleparameters/", import.meta.url));
  await page.setInputFiles("#file-input", join(folder, "FisherBenchmark.txt"));
  await waitFor("Fisher in the editor", async () => (await page.inputValue("#design-name")).startsWith("Fisher"), 15_000);
  await settled();
  const fisher = { vw: await text("weave-speed"), mB: await page.inputValue("[data-testid=param-mB]") };
  await page.getByTestId("param-mB").fill("7");
  await waitForText("weave-speed", (t) => t !== fisher.vw && /\d/.test(t));
  check((await reset.getAttribute("aria-label")) === "Reset to the design as saved", `an opened file edited: “${await reset.getAttribute("aria-label")}”`);
  await reset.click();
  await waitForText("weave-speed", (t) => t === fisher.vw);
  check((await page.inputValue("[data-testid=param-mB]")) === fisher.mB && (await page.locator("#modified").isHidden()), `back to the file as opened: mB ${fisher.mB}, v_w ${fisher.vw}`);
});

await section("about: collapsed, it opens on what the page shows and lists the references", async () => {
  await open("?bike=preset:benchmark");
  const body = page.getByTestId("about-body");
  check(await body.isHidden(), "collapsed by default");
  await page.click("#about > summary");
  await body.waitFor({ state: "visible" });
  const words = (await body.textContent()).replace(/\s+/g, " ").toLowerCase();
  check(["weave", "capsize", "castering", "self-stable", "σ", "first-order", "not certified"].every((w) => words.includes(w)), "it explains the modes, the self-stable range, σ and “not certified”");
  const refs = await page.$$eval("[data-testid=references] li", (ls) => ls.map((l) => l.textContent.replace(/\s+/g, " ")));
  const cited = [
    /Meijaard, J\. M\. Papadopoulos, A\. Ruina and A\. L\. Schwab \(2007\).*Proc\. R\. Soc\. A 463, 1955–1982.*doi:10\.1098\/rspa\.2007\.1857/,
    /Basu-Mandal, A\. Chatterjee and J\. M\. Papadopoulos \(2007\).*Proc\. R\. Soc\. A 463, 1983–2003/,
    /Moore \(2012\)\. Human Control of a Bicycle\. PhD dissertation, University of California, Davis.*BicycleParameters/,
    /Dressel\. Benchmarking a Fully Non-Linear Bicycle Model with JBike6/,
  ];
  check(refs.length === 4 && cited.every((r) => refs.some((t) => r.test(t))), `four references, cited in full: ${refs.map((r) => r.slice(0, 40)).join(" | ")}`);
  await page.evaluate(axeSource());
  const violations = await page.evaluate(async () => {
    // eslint-disable-next-line no-undef
    const r = await axe.run(document, { runOnly: { type: "tag", values: ["wcag2a", "wcag2aa", "best-practice"] } });
    return r.violations.map((v) => `${v.id} (${v.nodes.length}: ${v.nodes.slice(0, 2).map((n) => n.target.join(" ")).join("; ")})`);
  });
  check(violations.length === 0, `axe-core on the page with the panel open: ${violations.join(", ") || "no violations"}`);
  const box = await body.boundingBox();
  check(box.x >= 0 && box.x + box.width <= 1440 && box.y + box.height <= 900, `the panel stays on the screen (${Math.round(box.width)} × ${Math.round(box.height)} px)`);
  await page.keyboard.press("Escape");
  check(await becomes(() => body.isHidden(), 3_000), "Escape closes it");
  await page.click("#about > summary");
  await body.waitFor({ state: "visible" });
  await page.mouse.click(700, 700);
  check(await becomes(() => body.isHidden(), 3_000), "so does a click elsewhere");
  await page.click("#about > summary");
  await body.waitFor({ state: "visible" });
  await page.click("#about > summary");
  check(await becomes(() => body.isHidden(), 3_000), "and its button closes it");
});

await section("phones (390 × 844, touch): the critical speeds in sight while typing", async () => {
  // Wide: nothing changes.
  await open("?bike=preset:browser");
  await page.getByTestId("param-c").fill("0.09");
  await settled();
  check(await page.getByTestId("summary-bar").isHidden(), "1440 px: no summary bar (the table is beside the editor)");
  const phone = await launch({ phone: true });
  try {
    const p = phone.context.pages()[0] ?? (await phone.context.newPage());
    await p.goto(new URL("?bike=preset:browser", url).href);
    await p.waitForSelector("body[data-ready=true]", { timeout: 20_000 });
    await p.waitForSelector("body[data-pending='0']", { state: "attached", timeout: 30_000 });
    const bar = p.getByTestId("summary-bar");
    check(await bar.isHidden(), "at the top of the page (table in sight): no bar");
    const field = p.getByTestId("param-c");
    await field.scrollIntoViewIfNeeded();
    await field.tap();
    await bar.waitFor({ state: "visible", timeout: 5_000 });
    const before = (await p.getByTestId("summary-weave").textContent()).trim();
    const table = async () => (await p.getByTestId("weave-speed").textContent()).trim();
    check(before === (await table()), `the editor in view: the bar shows v_w as the table does: “${before}”`);
    // The field's place on the screen (the page may grow above it: scroll anchoring keeps it).
    const scrolled = await field.evaluate((i) => i.getBoundingClientRect().top);
    await field.fill("0.09");
    await p.waitForFunction((b) => {
      const t = document.querySelector("[data-testid=summary-weave]").textContent.trim();
      return t !== b && /\d/.test(t) && document.body.dataset.pending === "0";
    }, before, { timeout: 15_000 });
    const after = (await p.getByTestId("summary-weave").textContent()).trim();
    const geometry = () => p.evaluate(() => {
      const b = document.querySelector("[data-testid=summary-bar]").getBoundingClientRect();
      const i = document.activeElement.getBoundingClientRect();
      return { bar: [b.left, b.top, b.right, b.bottom], input: [i.left, i.top, i.right, i.bottom], h: window.innerHeight, w: window.innerWidth, y: window.scrollY, focused: document.activeElement.dataset.testid };
    });
    let g = await geometry();
    const inside = (r) => r[1] >= 0 && r[3] <= g.h && r[0] >= 0 && r[2] <= g.w;
    const apart = (a, b) => a[3] <= b[1] || b[3] <= a[1] || a[2] <= b[0] || b[2] <= a[0];
    check(after === (await table()) && / ± /.test(after), `typed c = 0.09: the bar reads the new v_w “${after}” (the table's words)`);
    check(Math.abs(g.input[1] - scrolled) < 2 && inside(g.bar) && g.focused === "param-c" && inside(g.input) && apart(g.bar, g.input), `without scrolling (the field stayed ${Math.round(scrolled)} px from the top), the bar (${g.bar.map(Math.round)}) and the field typed in (${g.input.map(Math.round)}) both on the screen, apart`);
    // Text that is not a number: the bar, as the table, keeps the last numbers, marked.
    await field.fill("0.0x");
    await p.getByTestId("summary-note").waitFor({ state: "visible", timeout: 5_000 });
    check((await p.getByTestId("summary-weave").textContent()).trim() === after, `“0.0x” typed: the bar keeps “${after}”, marked “${(await p.getByTestId("summary-note").textContent()).trim()}”`);
    await field.fill("0.09");
    await p.getByTestId("summary-note").waitFor({ state: "hidden", timeout: 5_000 });
    // A field focused where the bar is (at the top of the screen) is moved clear of it.
    // (Room below the page, so that the field can be scrolled up there: as a short screen or
    // an on-screen keyboard that shrinks the viewport would allow.)
    const under = await p.evaluate(() => {
      document.body.style.paddingBottom = "1200px";
      const i = document.querySelector("[data-testid=param-w]");
      window.scrollBy(0, i.getBoundingClientRect().top - 10);
      return i.getBoundingClientRect().top;
    });
    await bar.waitFor({ state: "visible" });
    check(under < (await bar.boundingBox()).height, `a field scrolled under the bar (at ${Math.round(under)} px)`);
    await p.evaluate(() => document.querySelector("[data-testid=param-w]").focus({ preventScroll: true }));
    await p.waitForFunction(() => {
      const b = document.querySelector("[data-testid=summary-bar]").getBoundingClientRect();
      return document.activeElement.getBoundingClientRect().top >= b.bottom;
    }, null, { timeout: 5_000 });
    g = await geometry();
    check(g.focused === "param-w" && inside(g.input) && apart(g.bar, g.input), `a field focused under the bar is scrolled clear of it (bar ends at ${Math.round(g.bar[3])} px, the field starts at ${Math.round(g.input[1])} px)`);
  } finally {
    await phone.close();
  }
});

const respCurves = (plot) => page.locator(`[data-testid=${plot}] [data-testid=resp-curve]`).count();
const respPath = () => page.$eval("[data-testid=resp-magnitude] [data-testid=resp-curve][data-heavy=true]", (p) => p.getAttribute("d"));
const rhpZeros = () => page.locator("[data-testid=resp-zero][data-rhp=true]").count();
/** Until the Response tab shows `n` curves in both plots and the page has settled. */
async function respDrawn(n) {
  await waitFor(`${n} Bode curves`, async () => (await respCurves("resp-magnitude")) === n && (await respCurves("resp-phase")) === n, 15_000);
  await settled();
}

await section("response: Bode plots of steer torque → lean, a speed slider, the right-half-plane zero, the link", async () => {
  await open("?bike=preset:benchmark&tab=resp");
  await respDrawn(3);
  check(true, "three speeds compared by default (3, 5, 7 m/s): three curves in magnitude and in phase");
  const heavy = await page.$$eval("[data-testid=resp-magnitude] [data-testid=resp-curve][data-heavy=true]", (ps) => ps.map((p) => p.dataset.speed));
  check(heavy.length === 1 && heavy[0] === "5", `the slider's speed drawn heavy (${heavy.join(", ")} m/s)`);
  const ticks = await xTicks("resp-magnitude");
  check(["0.1", "1", "10", "100"].every((t) => ticks.split(" ").includes(t)), `logarithmic frequency axis, ticks at decades (${ticks})`);
  check((await rhpZeros()) === 0 && /Minimum phase at 5 m\/s/.test(await text("resp-rhp-summary")), "at 5 m/s no zero is in the right half-plane");
  // The crossing of steer torque → lean's zero: √(−g K₀₁₂ / K₂₁₂) of Meijaard et al. 2007 §5's matrices.
  const crossing = Math.sqrt((9.81 * 2.59951685249872) / 76.59734589573222);
  const said = await text("resp-crossing");
  check(said.includes(`${crossing.toFixed(3)} m/s`), `the speed where the zero crosses s = 0 is given: “${said}” (√(−g K₀₁₂ / K₂₁₂) = ${crossing.toFixed(4)} m/s)`);
  await page.getByTestId("resp-speed").fill("0.3");
  await waitForText("resp-speed-value", (t) => t.startsWith("0.3"));
  await respDrawn(4);
  check((await rhpZeros()) === 1, "at 0.3 m/s, below the crossing, one zero is flagged in the right half-plane");
  const zero = number(await page.locator("[data-testid=resp-zero][data-rhp=true]").textContent());
  check(zero > 0, `its real part is positive (${zero} 1/s)`);
  check(/Non-minimum phase at 0\.3 m\/s/.test(await text("resp-rhp-summary")), "and the phase is said to be non-minimum");
  await page.getByTestId("resp-speed").fill("0.8");
  await waitForText("resp-speed-value", (t) => t.startsWith("0.8"));
  await respDrawn(4);
  check((await rhpZeros()) === 0, "at 0.8 m/s, above it, none");
  // Another pair, the slider low, then the link: everything comes back.
  await page.getByTestId("resp-output").selectOption("yaw_rate");
  await page.getByTestId("resp-input").selectOption("lean_torque");
  await page.getByTestId("resp-compare").fill("2, 6");
  await page.getByTestId("resp-compare").press("Enter");
  await page.getByTestId("resp-speed").fill("0.3");
  await waitForText("resp-meta", (t) => /T_φ → ψ̇/.test(t));
  await respDrawn(3);
  const link = page.url();
  check(/[?&]rs=/.test(link) && /tab=resp/.test(link), "the link holds the tab and its choices");
  const pathBefore = await respPath();
  await page.goto("about:blank");
  await open(new URL(link).search);
  await respDrawn(3);
  const restored = await page.evaluate(() => ["resp-input", "resp-output", "resp-speed", "resp-compare"].map((id) => document.getElementById(id).value).join("|"));
  check(restored === "lean_torque|yaw_rate|0.3|2, 6", `the link restores input, output, speed and speeds compared (${restored})`);
  check((await respPath()) === pathBefore, "and draws the same curve");
  check(!(await page.locator("[data-testid=resp-crossing]").count()), "a yaw-rate output has no crossing speed to give");
});

await section("response: recomputed when the bicycle is edited; bad input never breaks the page", async () => {
  await open("?tab=resp");
  await respDrawn(3);
  const before = await respPath();
  const rootsBefore = await text("resp-poles");
  await page.getByTestId("param-trail").fill("0.05");
  await waitFor("the Bode plot redrawn", async () => (await respPath()) !== before, 15_000);
  await settled();
  check((await text("resp-poles")) !== rootsBefore, "a shorter trail redraws the Bode plot and changes the poles listed");
  await page.getByTestId("param-trail").fill("abc");
  await waitFor("the veil", async () => (await page.getByTestId("resp-roots").getAttribute("data-stale")) !== "", 10_000);
  await settled();
  check((await respCurves("resp-magnitude")) === 3 && (await page.locator("[data-testid=resp-magnitude] [data-testid=stale-veil]").count()) === 1, "text in a field veils the curves, which stay");
  await page.getByTestId("param-trail").fill("0.05");
  await waitFor("the veil lifted", async () => (await page.getByTestId("resp-roots").getAttribute("data-stale")) === "", 10_000);
  await settled();
  for (const bad of ["3, x", "1, 2, 3, 4, 5, 6, 7, 8, 9", "1e999"]) {
    await page.getByTestId("resp-compare").fill(bad);
    await page.getByTestId("resp-compare").press("Enter");
    await settled();
    const message = await text("resp-message");
    check(message.length > 0 && (await page.getByTestId("resp-compare").getAttribute("class")).includes("invalid"), `“${bad}” is refused with a message: ${message}`);
    check((await respCurves("resp-magnitude")) > 0, "and the last curves stay, veiled", { quiet: true });
  }
  await page.getByTestId("resp-compare").fill("4");
  await page.getByTestId("resp-compare").press("Enter");
  await respDrawn(2);
  check(!(await page.getByTestId("resp-message").isVisible()), "a good value again: two curves (4 m/s and the slider's), the message gone");
});

await section("response at 1280 × 800 and 390 × 844: nothing overlaps, nothing sticks out", async () => {
  for (const viewport of [{ width: 1280, height: 800 }, { width: 390, height: 844 }]) {
    await open("?bike=preset:benchmark&tab=resp", viewport);
    await respDrawn(3);
    const blocks = ["#resp-form", "#resp-magnitude", "#resp-phase", "#resp-roots"];
    const rects = await page.evaluate((sels) => sels.map((s) => {
      const r = document.querySelector(s).getBoundingClientRect();
      return { s, l: r.left, t: r.top, r: r.right, b: r.bottom };
    }), blocks);
    const out = rects.filter((r) => r.l < 0 || r.r > viewport.width || r.r - r.l < 1 || r.b - r.t < 1).map((r) => r.s);
    check(out.length === 0, `${viewport.width} px: every block within the width (${out.join(", ") || "none outside"})`);
    const overlaps = [];
    for (let i = 0; i < rects.length; i++) {
      for (let j = i + 1; j < rects.length; j++) {
        const [a, b] = [rects[i], rects[j]];
        if (Math.min(a.r, b.r) - Math.max(a.l, b.l) > 1 && Math.min(a.b, b.b) - Math.max(a.t, b.t) > 1) overlaps.push(`${a.s} × ${b.s}`);
      }
    }
    check(overlaps.length === 0, `${viewport.width} px: no two blocks overlap (${overlaps.join(", ") || "none"})`);
    const size = (s) => rects.find((r) => r.s === s);
    const [mag, phase] = [size("#resp-magnitude"), size("#resp-phase")];
    check(mag.b - mag.t >= 130 && phase.b - phase.t >= 130 && mag.r - mag.l >= 300, `${viewport.width} px: room for the plots (${Math.round(mag.r - mag.l)} × ${Math.round(mag.b - mag.t)} and ${Math.round(phase.b - phase.t)} px high)`);
    // The panel holds what it shows: the plots are not cut off by the panel's bottom edge.
    const panel = await page.evaluate(() => document.querySelector("#plots").getBoundingClientRect().bottom);
    check(phase.b <= panel + 1, `${viewport.width} px: the phase plot ends inside its panel (${Math.round(phase.b)} ≤ ${Math.round(panel)})`);
    const { scroll, inner } = await page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, inner: window.innerWidth }));
    check(scroll <= inner, `${viewport.width} px: no sideways scroll (${scroll} px)`);
    if (viewport.width === 1280) {
      // The plots take the whole width below a shorter top row, which still shows the side view and the table whole.
      check(mag.r - mag.l >= 800, `1280 px: the Bode plots take the width (${Math.round(mag.r - mag.l)} px)`);
      const top = await page.evaluate(() => {
        const side = document.querySelector("[data-testid=side-view]");
        const table = document.querySelector("#critical");
        return { drawn: side.querySelector("svg").getBoundingClientRect().height, room: side.clientHeight, table: table.scrollHeight, shown: table.clientHeight };
      });
      check(top.drawn <= top.room + 1 && top.table <= top.shown + 1, `1280 px: the side view drawn within its ${top.room} px, the critical speeds within theirs (${top.table} of ${top.shown} px)`);
    }
  }
});

const ctlCurves = (testid = "eigen-curve") => page.locator(`[data-testid=ctl-plot] [data-testid=${testid}]`).count();
/** Until the Control tab's sentence says something matching `pattern` and the page has settled. */
async function ctlSays(pattern) {
  const test = typeof pattern === "function" ? pattern : (t) => pattern.test(t);
  const said = await waitForText("ctl-sentence", test, 15_000);
  await settled();
  return said;
}

await section("control: K or LQR weights → the closed loop's eigenvalues against speed, stable speeds, the link, bad gains", async () => {
  await open("?bike=preset:benchmark&tab=control");
  // T_δ = 100 φ − 10 δ + 20 φ̇, the default K: the library's example, stable from 0.8067 m/s.
  const said = await ctlSays(/stabilizes/);
  check(said.includes("from 0.8067 m/s"), `K = (−100, 10, −20, 0) stabilizes the benchmark from 0.8067 m/s: “${said}”`);
  check((await ctlCurves()) === 4 && (await ctlCurves("faint-curve")) === 4, "four closed-loop curves, the open loop's four faintly behind");
  const shaded = await page.$$eval("[data-testid=ctl-plot] [data-testid=stable-range]", (rs) => rs.map((r) => r.getAttribute("width")));
  const label = await page.$$eval("[data-testid=ctl-plot] svg text", (ts) => ts.map((t) => t.textContent));
  check(shaded.length === 1 && label.includes("stable") && !label.includes("self-stable"), `the stable range shaded and called “stable” (${shaded.length} range)`);
  // Recomputed when the bicycle is edited.
  await page.getByTestId("param-c").fill("0.05");
  const edited = await ctlSays((t) => !t.includes("0.8067"));
  check(/stabiliz/.test(edited), `a shorter trail recomputes the closed loop: “${edited}”`);
  await page.getByTestId("param-c").fill("0.08");
  await ctlSays(/from 0\.8067 m\/s/);
  // LQR, Q = I, R = 1, at every speed of the sweep from 0.1 m/s (from 0 the library cannot
  // certify the first segment against round-off, and says so): stable over the whole sweep.
  await page.getByTestId("ctl-mode-lqr").check();
  await page.getByTestId("ctl-scheduled").check();
  await page.fill("#v-start", "0.1");
  await page.press("#v-start", "Enter");
  const lqr = await ctlSays(/at every speed plotted/);
  check(/from 0\.1 to 10 m\/s/.test(lqr), `LQR (Q = I, R = 1) scheduled at every speed: “${lqr}”`);
  check(/LQR at each of 991 speeds/.test(await text("ctl-used")), `the gain said: ${await text("ctl-used")}`);
  const res = await page.$$eval("[data-testid=ctl-plot] [data-testid=eigen-curve]", (ps) => ps.length);
  check(res === 4, "and its four curves drawn");
  // The link restores the panel.
  const link = page.url();
  check(/[?&]ctl=/.test(link) && /tab=control/.test(link), "the link holds the tab and its choices");
  await page.goto("about:blank");
  await open(new URL(link).search);
  const again = await ctlSays(/at every speed plotted/);
  const restored = await page.evaluate(() => [document.getElementById("ctl-mode-lqr").checked, document.getElementById("ctl-scheduled").checked, document.getElementById("v-start").value].join("|"));
  check(restored === "true|true|0.1" && again === lqr, `the link restores LQR, the schedule and the speeds (${restored}): “${again}”`);
  // Bad input: refused with a message naming the field, the last curves veiled.
  await page.getByTestId("ctl-mode-gains").check();
  await ctlSays(/from 0\.8067 m\/s/);
  await page.getByTestId("ctl-k-steer_torque-0").fill("abc");
  await page.getByTestId("ctl-k-steer_torque-0").press("Enter");
  await settled();
  const message = await text("ctl-message");
  check(/K's gain of T_δ on φ must be a finite number/.test(message) && (await page.getByTestId("ctl-k-steer_torque-0").getAttribute("aria-invalid")) === "true", `a gain that is not a number is refused: “${message}”`);
  check((await ctlCurves()) === 4 && (await page.locator("[data-testid=ctl-plot] [data-testid=stale-veil]").count()) === 1, "the last curves stay, veiled");
  await page.getByTestId("ctl-k-steer_torque-0").fill("-100");
  await page.getByTestId("ctl-mode-lqr").check();
  await page.getByTestId("ctl-q-0").fill("-1");
  await page.getByTestId("ctl-q-0").press("Enter");
  await settled();
  const refused = await waitForText("ctl-message", (t) => /Q/.test(t));
  check((await page.getByTestId("ctl-q-0").getAttribute("aria-invalid")) === "true", `Q not positive semi-definite is refused by the server, its fields marked: “${refused}”`);
  await page.getByTestId("ctl-q-0").fill("1");
  await page.getByTestId("ctl-q-0").press("Enter");
  await ctlSays(/at every speed plotted/);
  check(!(await page.getByTestId("ctl-message").isVisible()), "a good value again: the message gone");
});

await section("control at 1280 × 800 and 390 × 844: nothing overlaps, nothing sticks out", async () => {
  for (const viewport of [{ width: 1280, height: 800 }, { width: 390, height: 844 }]) {
    await open("?bike=preset:benchmark&tab=control&ctl=m:lqr;in:steer_torque,lean_torque;q:1,1,1,1;r:1,1;v:5;s:0", viewport);
    await ctlSays(/stabilizes/);
    const blocks = [".ctl-controls", "#ctl-plot", ".ctl-side-col"];
    const rects = await page.evaluate((sels) => sels.map((s) => {
      const r = document.querySelector(s).getBoundingClientRect();
      return { s, l: r.left, t: r.top, r: r.right, b: r.bottom };
    }), blocks);
    const out = rects.filter((r) => r.l < 0 || r.r > viewport.width || r.r - r.l < 1 || r.b - r.t < 1).map((r) => r.s);
    check(out.length === 0, `${viewport.width} px: every block within the width (${out.join(", ") || "none outside"})`);
    const overlaps = [];
    for (let i = 0; i < rects.length; i++) {
      for (let j = i + 1; j < rects.length; j++) {
        const [a, b] = [rects[i], rects[j]];
        if (Math.min(a.r, b.r) - Math.max(a.l, b.l) > 1 && Math.min(a.b, b.b) - Math.max(a.t, b.t) > 1) overlaps.push(`${a.s} × ${b.s}`);
      }
    }
    check(overlaps.length === 0, `${viewport.width} px: no two blocks overlap (${overlaps.join(", ") || "none"})`);
    const plot = rects.find((r) => r.s === "#ctl-plot");
    check(plot.b - plot.t >= 230 && plot.r - plot.l >= 300, `${viewport.width} px: room for the plot (${Math.round(plot.r - plot.l)} × ${Math.round(plot.b - plot.t)} px)`);
    const panel = await page.evaluate(() => document.querySelector("#plots").getBoundingClientRect().bottom);
    const last = Math.max(...rects.map((r) => r.b));
    check(last <= panel + 1, `${viewport.width} px: the plot and the gains end inside their panel (${Math.round(last)} ≤ ${Math.round(panel)})`);
    const side = await page.evaluate(() => { const e = document.querySelector(".ctl-side-col"); return { scroll: e.scrollWidth, client: e.clientWidth }; });
    check(side.scroll <= side.client + 1, `${viewport.width} px: the gains and weights fit their column (${side.scroll} of ${side.client} px)`);
    const { scroll, inner } = await page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, inner: window.innerWidth }));
    check(scroll <= inner, `${viewport.width} px: no sideways scroll (${scroll} px)`);
  }
});

/** Until the Ridden tab has drawn an answer (its summary says the gains) and the page has settled. */
async function riddenDrawn(test = () => true) {
  await waitFor("the Ridden tab's answer", async () => {
    const s = await page.getByTestId("rd-summary").textContent({ timeout: 1_000 });
    const veiled = await page.getByTestId("rd-summary").evaluate((e) => e.classList.contains("stale"));
    return (/gains at/.test(s ?? "") && !veiled && test(s)) || s;
  }, 60_000);
  await settled(60_000);
  return text("rd-summary");
}
/** /api/ridden asked directly, with the preset's own bicycle, as the page's default form asks. */
const riddenDirect = (preset, { speed = 5, lane = "double", speeds = { start: 1, stop: 10, step: 0.25 } } = {}) => page.evaluate(async ({ preset, speed, lane, speeds }) => {
  const bike = await (await fetch(`/api/presets/${preset}`)).json();
  const r = await fetch("/api/ridden", { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify({ bike, speed, lane, speeds }) });
  return { status: r.status, body: await r.json() };
}, { preset, speed, lane, speeds });
const largest = (run) => Math.max(...run.front_y.map((y, i) => Math.abs(y - run.road[i])));

await section("ridden: the lane change and the peak HQM against speed, the summary as /api/ridden answers, CSV, the link", async () => {
  await open("?tab=ridden");
  const said = await riddenDrawn();
  const lanes = async (id) => page.locator(`[data-testid=rd-lane-plot] [data-testid=${id}]`).count();
  const nonlinearNote = await page.getByTestId("rd-nonlinear-note").isVisible();
  check((await lanes("rd-road")) === 1 && (await lanes("rd-linear")) === 1 && !(await page.getByTestId("rd-linear-note").isVisible()), "the lane change in the plane: the road and the linear model's front contact drawn, near the road");
  check((await lanes("rd-nonlinear")) === 1 || (nonlinearNote && /Only the linear model is drawn/.test(await text("rd-nonlinear-note"))), `the non-linear model's front contact drawn, or why not said (${nonlinearNote ? await text("rd-nonlinear-note") : "drawn"})`);
  const curve = await page.$eval("[data-testid=rd-hqm-plot] [data-testid=rd-hqm-curve]", (p) => p.getAttribute("d"));
  check(/L/.test(curve), "the peak HQM against speed drawn");
  const level = await page.$$eval("[data-testid=rd-hqm-plot] [data-testid=rd-hqm-level-label]", (ts) => ts.map((t) => t.textContent));
  check(level.length === 1 && /HQM = 5/.test(level[0]) && /good handling/.test(level[0]), `the HQM = 5 level drawn and labelled (“${level[0]}”)`);
  // The summary's numbers are the API's.
  const direct = await riddenDirect("schwinn-crown");
  check(direct.status === 200, `POST /api/ridden answers the Schwinn Crown (${direct.status})`);
  const a = direct.body;
  const gains = await page.$$eval("[data-testid=rd-gain]", (es) => es.map((e) => ({ name: e.dataset.name, value: Number(e.dataset.value), text: e.textContent })));
  check(gains.length === 5 && gains.every((g, k) => g.name === a.gain_names[k] && g.value === a.gains[k]), `the five gains shown are the API's: ${gains.map((g) => `${g.name} ${g.value}`).join(", ")}`);
  const points = Number(await page.getByTestId("rd-summary").getAttribute("data-points"));
  check(points === a.hqm.length && a.hqm.length === 37, `the HQM at the API's ${a.hqm.length} speeds (1 to 10 by 0.25) drawn: ${points}`);
  const dev = await page.getByTestId("rd-deviation").evaluate((e) => ({ linear: Number(e.dataset.linear), nonlinear: e.dataset.nonlinear }));
  check(Math.abs(dev.linear - largest(a.linear)) < 1e-12 && (a.nonlinear ? Math.abs(Number(dev.nonlinear) - largest(a.nonlinear)) < 1e-12 : dev.nonlinear === ""), `the largest deviations from the road are the API's samples': linear ${dev.linear} m, non-linear ${dev.nonlinear || "–"} m`);
  const at5 = a.hqm.find((r) => r.speed === 5);
  const shownPeak = await page.getByTestId("rd-hqm-at").getAttribute("data-peak");
  check(at5 && (at5.peak === null ? shownPeak === "" : Number(shownPeak) === at5.peak), `the peak HQM at 5 m/s is the API's: ${at5?.peak} (“${await text("rd-hqm-at")}”)`);
  const gaps = a.hqm.filter((r) => r.peak === null).length;
  const marked = await page.locator("[data-testid=rd-hqm-plot] [data-testid=rd-hqm-gap-marker]").count();
  check(marked === gaps, `each speed without a peak marked (${marked} of ${gaps}: ${a.hqm.filter((r) => r.peak === null).map((r) => r.speed).join(", ") || "none"})`);
  console.log(`  Schwinn Crown, double lane change at 5 m/s: ${said}`);
  // The hover read-out.
  const box = await plotBox("rd-hqm-plot");
  await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.6);
  const tip = await waitForText("rd-hqm-plot-tooltip", (t) => /v = /.test(t));
  check(/peak HQM|no peak/.test(tip), `the HQM plot reads out under the pointer: “${tip}”`);
  // CSV of both plots.
  const hqmCsv = await downloadOf(() => page.getByTestId("rd-csv-hqm").click());
  const hqmLines = hqmCsv.text.trim().split("\n");
  check(/schwinn.*hqm\.csv$/i.test(hqmCsv.name) && hqmLines[1] === "speed,peak,frequency,stable,reason" && hqmLines.length === 2 + 37, `the HQM as CSV: ${hqmCsv.name}, ${hqmLines.length - 2} speeds`);
  const laneCsv = await downloadOf(() => page.getByTestId("rd-csv-lane").click());
  const laneLines = laneCsv.text.trim().split("\n");
  check(/lane-change-double-v5\.csv$/.test(laneCsv.name) && laneLines[1].startsWith("x_linear,y_linear,road_linear") && laneLines.length === 2 + a.linear.front_x.length, `the lane change as CSV: ${laneCsv.name}, ${laneLines.length - 2} samples`);
  // Another choice, then the link: everything comes back.
  await page.getByTestId("rd-speed").fill("4");
  await page.getByTestId("rd-from").fill("2");
  await page.getByTestId("rd-step").fill("0.5");
  await page.getByTestId("rd-lane").selectOption("single");
  const single = await riddenDrawn((t) => /gains at 4 m\/s/.test(t));
  check(Number(await page.getByTestId("rd-summary").getAttribute("data-points")) === 17 && /single lane change at 4 m\/s/.test(await text("rd-meta")), `the single lane change at 4 m/s, the HQM at 17 speeds: “${single}”`);
  const link = page.url();
  check(/[?&]rd=/.test(link) && /tab=ridden/.test(link), "the link holds the tab and its choices");
  // At 1.5 m/s the non-linear Schwinn Crown falls during the lane change: said in words, the
  // linear model still drawn.
  await page.getByTestId("rd-speed").fill("1.5");
  await page.getByTestId("rd-speed").press("Enter");
  await riddenDrawn((t) => /gains at 1\.5 m\/s/.test(t));
  const fell = await text("rd-nonlinear-note");
  check(/did not complete/.test(fell) && /fell/.test(fell) && /Only the linear model is drawn/.test(fell) && (await lanes("rd-nonlinear")) === 0 && (await lanes("rd-linear")) === 1, `a non-linear run that falls is said beside the plot: “${fell}”`);
  check(/non-linear – \(not completed\)/.test(await text("rd-deviation")), `and the summary says so: “${await text("rd-deviation")}”`);
  // There the rider's loops are unstable (the HQM sweep shades 1 to 2.25 m/s): the exact linear
  // run diverges, which is said, the road kept in view.
  const diverged = await text("rd-linear-note");
  check(/leaves the road/.test(diverged) && /unstable at 1\.5 m\/s/.test(diverged) && (await lanes("rd-lane-outside")) === 1, `the linear run's divergence is said, the road kept in view: “${diverged}”`);
  const shot = join(tmpdir(), "whipple-e2e-ridden-diverged.png");
  await page.locator("#plots").screenshot({ path: shot });
  console.log(`  screenshot: ${shot}`);
  await page.goBack();
  await riddenDrawn((t) => /gains at 4 m\/s/.test(t));
  await page.goto("about:blank");
  await open(new URL(link).search);
  const again = await riddenDrawn();
  const restored = await page.evaluate(() => ["rd-speed", "rd-lane", "rd-from", "rd-to", "rd-step"].map((id) => document.getElementById(id).value).join("|"));
  check(restored === "4|single|2|10|0.5" && again === single, `the link restores the choices (${restored}) and the same summary`);
});

await section("ridden: bad input is named and marked, the last result veiled; recomputed when the bicycle is edited", async () => {
  await open("?bike=preset:benchmark&tab=ridden");
  const first = await riddenDrawn();
  const veils = () => page.locator("[data-testid=rd-lane-plot] [data-testid=stale-veil], [data-testid=rd-hqm-plot] [data-testid=stale-veil]").count();
  const invalid = (id) => page.getByTestId(id).getAttribute("aria-invalid");
  const refused = async (id, value, pattern, what) => {
    await page.getByTestId(id).fill(value);
    await page.getByTestId(id).press("Enter");
    await settled();
    const message = await waitForText("rd-message", (t) => pattern.test(t));
    check((await invalid(id)) === "true" && (await veils()) === 2 && (await page.getByTestId("rd-summary").evaluate((e) => e.classList.contains("stale"))), `${what}: “${message}”, the field marked, both plots and the summary veiled`);
  };
  await refused("rd-speed", "abc", /lane change's speed must be a number/, "letters in the speed");
  await refused("rd-speed", "50", /from 1 to 20 m\/s/, "a speed of 50 m/s");
  await page.getByTestId("rd-speed").fill("5");
  await refused("rd-step", "0.001", /more than 500/, "a step giving 9,001 speeds");
  check((await invalid("rd-speed")) === "false", "the speed, mended, is no longer marked");
  // 20 m/s is within the bounds, but no k_δ meets Hess's rule for the benchmark there: the
  // server's 422 gain_rule_unmet, said as it is.
  await page.getByTestId("rd-step").fill("0.25");
  await refused("rd-speed", "20", /no `kDelta` meets its rule/, "20 m/s, where no gain meets Hess's rule (422 gain_rule_unmet)");
  await page.getByTestId("rd-speed").fill("5");
  await page.getByTestId("rd-speed").press("Enter");
  const mended = await riddenDrawn();
  check(mended === first && !(await page.getByTestId("rd-message").isVisible()) && (await veils()) === 0, "mended: the same answer again, the message gone, nothing veiled");
  // The bicycle edited: the rider's gains are set again for it.
  const before = await page.$$eval("[data-testid=rd-gain]", (es) => es.map((e) => e.dataset.value).join(","));
  await page.getByTestId("param-c").fill("0.05");
  await riddenDrawn((t) => t !== first);
  const after = await page.$$eval("[data-testid=rd-gain]", (es) => es.map((e) => e.dataset.value).join(","));
  check(after !== before, `a shorter trail sets other gains (${after})`);
  // Text in the bicycle's form veils the tab with the form's reason.
  await page.getByTestId("param-c").fill("abc");
  await waitFor("the veil", async () => (await veils()) === 2);
  check(/not recomputed/.test(await page.getByTestId("rd-summary").getAttribute("data-stale")), "text in the bicycle's form veils the Ridden tab");
});

await section("ridden at 1440 × 900, 1280 × 800 and 390 × 844: nothing overlaps, nothing sticks out", async () => {
  for (const viewport of [{ width: 1440, height: 900 }, { width: 1280, height: 800 }, { width: 390, height: 844 }]) {
    await open("?bike=preset:benchmark&tab=ridden", viewport);
    await riddenDrawn();
    const blocks = ["#rd-form", "#rd-summary", "#rd-lane-plot", "#rd-hqm-plot"];
    const rects = await page.evaluate((sels) => sels.map((s) => {
      const r = document.querySelector(s).getBoundingClientRect();
      return { s, l: r.left, t: r.top, r: r.right, b: r.bottom };
    }), blocks);
    const out = rects.filter((r) => r.l < 0 || r.r > viewport.width || r.r - r.l < 1 || r.b - r.t < 1).map((r) => r.s);
    check(out.length === 0, `${viewport.width} px: every block within the width (${out.join(", ") || "none outside"})`);
    const overlaps = [];
    for (let i = 0; i < rects.length; i++) {
      for (let j = i + 1; j < rects.length; j++) {
        const [a, b] = [rects[i], rects[j]];
        if (Math.min(a.r, b.r) - Math.max(a.l, b.l) > 1 && Math.min(a.b, b.b) - Math.max(a.t, b.t) > 1) overlaps.push(`${a.s} × ${b.s}`);
      }
    }
    check(overlaps.length === 0, `${viewport.width} px: no two blocks overlap (${overlaps.join(", ") || "none"})`);
    const size = (s) => rects.find((r) => r.s === s);
    const [lane, hqm] = [size("#rd-lane-plot"), size("#rd-hqm-plot")];
    check(lane.b - lane.t >= 190 && hqm.b - hqm.t >= 190 && lane.r - lane.l >= 300 && hqm.r - hqm.l >= 300, `${viewport.width} px: room for the plots (${Math.round(lane.r - lane.l)} × ${Math.round(lane.b - lane.t)} and ${Math.round(hqm.r - hqm.l)} × ${Math.round(hqm.b - hqm.t)} px)`);
    const panel = await page.evaluate(() => document.querySelector("#plots").getBoundingClientRect().bottom);
    const last = Math.max(...rects.map((r) => r.b));
    check(last <= panel + 1, `${viewport.width} px: the plots end inside their panel (${Math.round(last)} ≤ ${Math.round(panel)})`);
    const form = await page.evaluate(() => { const e = document.querySelector("#rd-form"); return { scroll: e.scrollWidth, client: e.clientWidth }; });
    check(form.scroll <= form.client + 1, `${viewport.width} px: the form's controls fit it (${form.scroll} of ${form.client} px)`);
    const { scroll, inner } = await page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, inner: window.innerWidth }));
    check(scroll <= inner, `${viewport.width} px: no sideways scroll (${scroll} px)`);
    const shot = join(tmpdir(), `whipple-e2e-ridden-${viewport.width}.png`);
    if (viewport.width < 500) await page.locator("#plots").screenshot({ path: shot });
    else await page.screenshot({ path: shot });
    console.log(`  screenshot: ${shot}`);
  }
});

const timeCurves = (plot, testid = "resp-time-curve") => page.locator(`[data-testid=${plot}] [data-testid=${testid}]`).count();
/** The last point of a plot's first linear curve, in the plot's pixels. */
const lastPoint = (plot) => page.$eval(`[data-testid=${plot}] [data-testid=resp-time-curve]`, (p) => p.getAttribute("d").split(/[ML]/).filter(Boolean).at(-1));

await section("response: step response, initial condition, path in the plane, the non-linear model beside", async () => {
  await open("?bike=preset:benchmark&tab=resp");
  await respDrawn(3);
  await page.getByTestId("resp-kind").selectOption("step");
  await waitFor("the step response drawn", async () => (await timeCurves("resp-lean")) === 1 && (await timeCurves("resp-steer")) === 1, 15_000);
  await settled();
  check(!(await page.getByTestId("resp-magnitude").isVisible()) && (await page.getByTestId("resp-amplitude").isVisible()) && !(await page.getByTestId("resp-compare").isVisible()), "the step view shows lean and steer against time and the amplitude field, not the Bode plots");
  // Where the API says the step settles: the same request, asked directly.
  const bike = await page.evaluate(async () => (await fetch("/api/presets/benchmark")).json());
  const api = await page.evaluate(async (bike) => (await fetch("/api/linear/time", { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify({ bike, speed: 5, kind: "step", input: "steer_torque", amplitude: 0.1, duration: 10, samples: 401 }) })).json(), bike);
  const final = Number(await page.getByTestId("resp-final").getAttribute("data-lean"));
  const expected = api.linear.lean_deg.at(-1);
  check(Math.abs(final - expected) < 1e-9 * Math.max(1, Math.abs(expected)), `the step response at 5 m/s ends where the API says (${final.toFixed(4)}° vs ${expected.toFixed(4)}°)`);
  const tail = api.linear.lean_deg.slice(-40);
  check(Math.max(...tail) - Math.min(...tail) < 0.1 * Math.abs(expected), `and has nearly settled there over the last second (${(Math.max(...tail) - Math.min(...tail)).toFixed(4)}° of ${expected.toFixed(3)}°)`);
  const [x, y] = (await lastPoint("resp-lean")).trim().split(" ").map(Number);
  check(Number.isFinite(x) && Number.isFinite(y), `the curve is drawn to its last sample (${x}, ${y} px)`);

  await page.getByTestId("resp-nonlinear").check();
  await waitFor("the non-linear step beside", async () => (await timeCurves("resp-lean", "resp-time-curve-nonlinear")) === 1, 20_000);
  await settled();
  check(/largest difference/.test(await text("resp-difference")), `the largest difference is given: ${await text("resp-difference")}`);

  await page.getByTestId("resp-kind").selectOption("initial");
  await waitFor("the initial-condition response drawn", async () => (await page.getByTestId("resp-lean0").isVisible()) && /no input/.test(await text("resp-roots")) && (await timeCurves("resp-lean")) === 1 && (await timeCurves("resp-steer", "resp-time-curve-nonlinear")) === 1, 20_000);
  await settled();
  check(true, "the initial-condition view draws lean and steer, linear and non-linear");

  await page.getByTestId("resp-kind").selectOption("path");
  await waitFor("two paths and their non-linear twins", async () => (await timeCurves("resp-path", "resp-path-curve")) === 2 && (await timeCurves("resp-path", "resp-path-curve-nonlinear")) === 2, 20_000);
  await settled();
  check(await page.getByTestId("resp-pulse").isVisible(), "the path view draws the rear and front contacts' paths, each beside the non-linear one, with the pulse's duration field");
  const meta = await text("resp-meta");
  const stretch = Number(await page.getByTestId("resp-meta").getAttribute("data-exaggeration"));
  check(stretch <= 1.5 || /y exaggerated ×/.test(meta), `the exaggeration of y is said (×${stretch.toFixed(1)}: “${meta}”)`);

  // Bad numbers: refused with a message, the curves kept under a veil.
  for (const [id, bad] of [["resp-amplitude", "abc"], ["resp-amplitude", "1e9"], ["resp-pulse", "0"], ["resp-pulse", "x"]]) {
    await page.getByTestId(id).fill(bad);
    await page.getByTestId(id).press("Enter");
    await waitFor("the message", async () => (await page.getByTestId("resp-message").isVisible()), 10_000);
    const message = await text("resp-message");
    check((await page.getByTestId(id).getAttribute("class")).includes("invalid") && (await page.locator("[data-testid=resp-path] [data-testid=stale-veil]").count()) === 1, `${id} “${bad}” is refused with a message: ${message}`);
    await page.getByTestId(id).fill(id === "resp-amplitude" ? "0.2" : "0.4");
    await page.getByTestId(id).press("Enter");
    await waitFor("the message gone", async () => !(await page.getByTestId("resp-message").isVisible()), 15_000);
  }
  await settled();
  // The link restores the view.
  const link = page.url();
  const before = await page.$eval("[data-testid=resp-path] [data-testid=resp-path-curve]", (p) => p.getAttribute("d"));
  await page.goto("about:blank");
  await open(new URL(link).search);
  await waitFor("the path restored", async () => (await timeCurves("resp-path", "resp-path-curve-nonlinear")) === 2, 20_000);
  await settled();
  const restored = await page.evaluate(() => ["resp-kind", "resp-amplitude", "resp-pulse"].map((id) => document.getElementById(id).value).join("|") + `|${document.getElementById("resp-nonlinear").checked}`);
  check(restored === "path|0.2|0.4|true", `the link restores the view, amplitude, pulse and the comparison (${restored})`);
  const after = await page.$eval("[data-testid=resp-path] [data-testid=resp-path-curve]", (p) => p.getAttribute("d"));
  check(after === before, "and draws the same path");

  // Recomputed on a bicycle edit; veiled on an invalid one.
  await page.getByTestId("param-c").fill("0.05");
  await waitFor("the path redrawn", async () => (await page.$eval("[data-testid=resp-path] [data-testid=resp-path-curve]", (p) => p.getAttribute("d"))) !== before, 20_000);
  await page.getByTestId("param-c").fill("abc");
  await waitFor("the veil", async () => (await page.locator("[data-testid=resp-path] [data-testid=stale-veil]").count()) === 1, 10_000);
  check(true, "a bicycle edit redraws the path; text in a field veils it");
});

await section("response's time views at 1280 × 800 and 390 × 844: nothing overlaps, nothing sticks out", async () => {
  for (const viewport of [{ width: 1280, height: 800 }, { width: 390, height: 844 }]) {
    for (const kind of ["step", "path"]) {
      await open(`?bike=preset:benchmark&tab=resp&rs=${encodeURIComponent(`kind:${kind};nl:1`)}`, viewport);
      const plot = kind === "path" ? "resp-path" : "resp-lean";
      await waitFor(`the ${kind} view drawn`, async () => (await page.locator(`[data-testid=${plot}] [data-testid$=nonlinear]`).count()) >= 1, 20_000);
      await settled();
      const blocks = ["#resp-form", ...(kind === "path" ? ["#resp-path"] : ["#resp-lean", "#resp-steer"]), "#resp-roots"];
      const rects = await page.evaluate((sels) => sels.map((s) => {
        const r = document.querySelector(s).getBoundingClientRect();
        return { s, l: r.left, t: r.top, r: r.right, b: r.bottom };
      }), blocks);
      const out = rects.filter((r) => r.l < 0 || r.r > viewport.width || r.r - r.l < 1 || r.b - r.t < 1).map((r) => r.s);
      check(out.length === 0, `${viewport.width} px, ${kind}: every block within the width (${out.join(", ") || "none outside"})`);
      const overlaps = [];
      for (let i = 0; i < rects.length; i++) {
        for (let j = i + 1; j < rects.length; j++) {
          const [a, b] = [rects[i], rects[j]];
          if (Math.min(a.r, b.r) - Math.max(a.l, b.l) > 1 && Math.min(a.b, b.b) - Math.max(a.t, b.t) > 1) overlaps.push(`${a.s} × ${b.s}`);
        }
      }
      check(overlaps.length === 0, `${viewport.width} px, ${kind}: no two blocks overlap (${overlaps.join(", ") || "none"})`);
      const first = rects[1];
      check(first.b - first.t >= 130 && first.r - first.l >= 300, `${viewport.width} px, ${kind}: room for the plot (${Math.round(first.r - first.l)} × ${Math.round(first.b - first.t)})`);
      const { scroll, inner } = await page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, inner: window.innerWidth }));
      check(scroll <= inner, `${viewport.width} px, ${kind}: no sideways scroll (${scroll} px)`);
      if (process.env.WHIPPLE_E2E_SHOTS) await page.locator("#panel-resp").screenshot({ path: `${process.env.WHIPPLE_E2E_SHOTS}/resp-${kind}-${viewport.width}.png` });
    }
  }
});

await section("simulation at 1280 × 800: nothing overlaps, nothing sticks out", async () => {
  await open("?bike=preset:benchmark&tab=sim", { width: 1280, height: 800 });
  await page.getByTestId("sim-run").click();
  await ran((t) => /completed|fell/.test(t));
  await settled();
  const blocks = [".editor", ".side", ".stability", "#sim-form", ".sim-turn-row", ".sim-status", "#sim-view", ".sim-transport", ".sim-plot-tools", "#sim-time-plot", "#sim-track"];
  const rects = await page.evaluate((sels) => sels.map((s) => {
    const r = document.querySelector(s).getBoundingClientRect();
    return { s, l: r.left, t: r.top, r: r.right, b: r.bottom };
  }), blocks);
  const out = rects.filter((r) => r.l < 0 || r.r > 1280 || r.r - r.l < 1).map((r) => r.s);
  check(out.length === 0, `every block within the 1280 px (${out.join(", ") || "none outside"})`);
  const overlaps = [];
  for (let i = 0; i < rects.length; i++) {
    for (let j = i + 1; j < rects.length; j++) {
      const [a, b] = [rects[i], rects[j]];
      const w = Math.min(a.r, b.r) - Math.max(a.l, b.l);
      const h = Math.min(a.b, b.b) - Math.max(a.t, b.t);
      if (w > 1 && h > 1) overlaps.push(`${a.s} × ${b.s}`);
    }
  }
  check(overlaps.length === 0, `no two blocks overlap (${overlaps.join(", ") || "none"})`);
  const size = (s) => rects.find((r) => r.s === s);
  const [form, view, time] = [size("#sim-form"), size("#sim-view"), size("#sim-time-plot")];
  check(form.b - form.t < 40, `the controls on one line (${Math.round(form.b - form.t)} px high)`);
  check(view.r - view.l >= 500 && view.b - view.t >= 250 && time.r - time.l >= 500 && time.b - time.t >= 140, `room for the 3-D view (${Math.round(view.r - view.l)} × ${Math.round(view.b - view.t)}) and the plots (${Math.round(time.r - time.l)} × ${Math.round(time.b - time.t)})`);
  const { scroll, inner } = await page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, inner: window.innerWidth }));
  check(scroll <= inner, `no sideways scroll (${scroll} px)`);
  // The top row, shorter beside the simulation, still shows the side view and the table whole.
  const top = await page.evaluate(() => {
    const side = document.querySelector("[data-testid=side-view]");
    const table = document.querySelector("#critical");
    return { drawn: side.querySelector("svg").getBoundingClientRect().height, room: side.clientHeight, table: table.scrollHeight, shown: table.clientHeight };
  });
  check(top.drawn <= top.room + 1 && top.table <= top.shown + 1, `the side view drawn within its ${top.room} px, the critical speeds within theirs (${top.table} of ${top.shown} px)`);
});

// `whipple measure --raw BrowserMeasured.txt` prints these rows (value to the decimals of σ's
// three digits); the page shows the same numbers from /api/measure, which calls the same core.
const MEASURE_BROWSER = { rR: "0.340959 ± 0.000122", IBxx: "0.52963 ± 0.00248" };

/** Until the Measure tab has computed (the derived numbers unveiled) and the page settled. */
async function measured() {
  await settled();
  await waitFor("the derived numbers", async () => !(await page.evaluate(() => document.querySelector(".ms-view").classList.contains("ms-stale"))));
}

await section("measure: the Browser sample's derived numbers as whipple measure prints them, bad input named, load into editor, the eigenvalues of it", async () => {
  await open("?bike=preset:benchmark&tab=measure");
  check((await page.locator("[data-testid^=ms-drawing-]").count()) === 7, "seven drawings of the set-ups (the rider's among them)");
  await page.getByTestId("ms-sample").selectOption("browser");
  await measured();
  check((await page.getByTestId("ms-dR").inputValue()) === "27.85" && (await page.getByTestId("ms-dR-sigma").inputValue()) === "0.01", "the sample fills the form: dR = 27.85 ± 0.01 m");
  check((await page.getByTestId("ms-TtB3").inputValue()) === "1.83976940999", "and the hangings: TtB3 = 1.83976940999 s");
  for (const [key, shown] of Object.entries(MEASURE_BROWSER)) {
    const got = await text(`ms-step-${key}`);
    check(got === shown, `${key} = ${got}, as whipple measure prints it (${shown})`);
  }
  check(/Browser: 26 parameters with σ/.test(await text("ms-meta")), `the summary: ${await text("ms-meta")}`);
  check(/[?&]ms=s(%3A|:)browser/.test(page.url()), "the link holds the sample");
  // Typed: recomputed after the pause; a bad value named by its key, its field marked.
  await page.getByTestId("ms-dR").fill("28.85");
  await measured();
  const radius = await text("ms-step-rR");
  check(radius.startsWith("0.353"), `dR = 28.85 m: rR = ${radius} (28.85 / 26π)`);
  check(/k\.dR(%3A|:)28\.85/.test(page.url()), "the link holds the edit");
  await page.getByTestId("ms-TtB2").fill("-2.3");
  await settled();
  const refused = await waitForText("ms-message", (t) => /TtB2/.test(t));
  check(/a period must be positive/.test(refused) && (await page.getByTestId("ms-TtB2").getAttribute("aria-invalid")) === "true", `a negative period is refused naming TtB2: “${refused}”`);
  check(await page.getByTestId("ms-load").isDisabled(), "and nothing stale can be loaded");
  await page.getByTestId("ms-TtB2").fill("2.37671750273");
  await page.getByTestId("ms-dR").fill("27.85");
  await measured();
  check(!(await page.getByTestId("ms-message").isVisible()) && (await text("ms-step-rR")) === MEASURE_BROWSER.rR, "mended: the message gone, rR back");
  // A file opened fills the form (a list of repeated measurements averaged by the library),
  // and the form saved is a *Measured.txt that the library reads to the same numbers.
  const samples = await page.evaluate(() => fetch("/api/measure/samples").then((r) => r.json()));
  const edited = samples[0].text.replace(/^TcR1 = .*$/m, "TcR1 = 1.36+/-0.001, 1.38+/-0.001");
  await page.setInputFiles("#ms-file", { name: "TestMeasured.txt", mimeType: "text/plain", buffer: Buffer.from(edited) });
  await measured();
  const mean = [await page.getByTestId("ms-TcR1").inputValue(), await page.getByTestId("ms-TcR1-sigma").inputValue()];
  check(mean[0] === "1.37" && mean[1] === "0.000707106781187" && (await page.getByTestId("ms-name").inputValue()) === "Test" && (await page.getByTestId("ms-sample").inputValue()) === "", `TestMeasured.txt opened: “Test”, TcR1 = 1.36, 1.38 read as their mean ${mean[0]} ± ${mean[1]} (√(2·0.001²)/2)`);
  const saved = await downloadOf(() => page.getByTestId("ms-save").click());
  const lines = saved.text.trim().split("\n");
  check(saved.name === "TestMeasured.txt" && lines.length === 50 && lines.includes("TcR1 = 1.37+/-0.000707106781187") && lines.includes("lcs = 0.46"), `saved as ${saved.name}: ${lines.length} lines, the rider's geometry kept`);
  const again = await page.evaluate((text) => fetch("/api/measure", { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify({ text }) }).then((r) => r.json()), saved.text);
  const shownIRyy = await text("ms-step-IRyy");
  const reread = again.steps.find((s) => s.key === "IRyy");
  check(shownIRyy.startsWith(reread.value.toFixed(5)), `the saved file read again gives the IRyy shown (${shownIRyy}; ${reread.value})`);
  // The same bicycle from BicycleParameters' own computation (the preset, its Benchmark.txt):
  // the same critical speeds.
  await open("?bike=preset:browser");
  const weave = await waitForText("weave-speed", (t) => /\d/.test(t));
  const capsize = await text("capsize-speed");
  await open("?bike=preset:benchmark&tab=measure&ms=s:browser");
  await measured();
  await page.getByTestId("ms-load").click();
  await settled();
  check((await page.getByTestId("tab-eigen").getAttribute("aria-selected")) === "true", "loaded: the eigenvalue tab shown");
  check((await page.locator("#design-name").inputValue()) === "Browser" && (await page.getByTestId("bike-select").inputValue()) === "link:", "the editor holds “Browser” (from the link, not saved)");
  check((await page.getByTestId("sigma-IBxx").inputValue()) !== "", `the editor keeps σ: IBxx ± ${await page.getByTestId("sigma-IBxx").inputValue()}`);
  const w2 = await waitForText("weave-speed", (t) => /\d/.test(t));
  check(w2 === weave && (await text("capsize-speed")) === capsize, `its critical speeds are the Browser preset's: v_w ${w2}, v_c ${await text("capsize-speed")}`);
  check((await page.locator("[data-testid=eigen-plot] [data-testid=eigen-curve]").count()) >= 4, "and its eigenvalues drawn");
});

// `whipple measure --raw BrowserMeasured.txt --rider JasonYeadonMeas.txt --configuration
// JasonBrowserYeadonCFG.txt` prints mB = 93.3600 ± 0.0200 and, through `whipple speeds`,
// v_w = 5.1347 ± 0.0353 m/s: the page shows the same from the same core.
await section("measure: Browser with Jason seated as whipple measure --rider seats him; the rider taken off", async () => {
  await open("?bike=preset:benchmark&tab=measure&ms=s:browser-jason");
  await measured();
  const status = await text("ms-rider-status");
  check(/^Jason \(JasonYeadonMeas\.txt\) seated as JasonBrowserYeadonCFG\.txt: 83\.5/.test(status), `the sample's rider seated: “${status}”`);
  check((await page.getByTestId("ms-lsp").inputValue()) === "0.24", "the seat and handlebar measurements are the rider section's fields: lsp = 0.24 m");
  const mB = await page.locator("[data-testid=ms-derived-rider] [data-testid=ms-step-mB]").textContent();
  check(mB === "93.3600 ± 0.0200", `the rear frame with the rider: mB = ${mB}, as whipple measure --rider prints it`);
  check(/^Browser with Jason: 26 parameters with σ/.test(await text("ms-meta")), `the summary: ${await text("ms-meta")}`);
  await page.getByTestId("ms-load").click();
  await settled();
  check((await page.locator("#design-name").inputValue()) === "Browser with Jason", "loaded into the editor as “Browser with Jason”");
  const weave = await waitForText("weave-speed", (t) => /\d/.test(t));
  check(/^5\.13/.test(weave), `its weave speed ${weave} (whipple speeds on the CLI's file: 5.1347 ± 0.0353 m/s)`);
  await open("?bike=preset:benchmark&tab=measure&ms=s:browser-jason");
  await measured();
  await page.getByTestId("ms-rider-remove").click();
  await measured();
  check(/No rider/.test(await text("ms-rider-status")) && /[?&]ms=[^&]*r(%3A|:)none/.test(page.url()), "the rider taken off: said, and the link carries it");
  check((await page.locator("[data-testid=ms-derived-rider] [data-testid=ms-step-mB]").count()) === 0 && /^Browser: 26/.test(await text("ms-meta")), "the rear frame alone again");
});

await section("measure at 1280 × 800 and 390 × 844: nothing sticks out; a screenshot", async () => {
  for (const viewport of [{ width: 1280, height: 800 }, { width: 390, height: 844 }]) {
    await open("?bike=preset:benchmark&tab=measure&ms=s:browser", viewport);
    await measured();
    const rects = await page.evaluate(() => [".ms-controls", ".ms-body", ...[...document.querySelectorAll(".ms-step")].map((_, k) => `.ms-step:nth-child(${k + 1})`)].map((s) => {
      const r = document.querySelector(s).getBoundingClientRect();
      return { s, l: r.left, t: r.top, r: r.right, b: r.bottom };
    }));
    const out = rects.filter((r) => r.l < 0 || r.r > viewport.width || r.r - r.l < 1 || r.b - r.t < 1).map((r) => r.s);
    check(out.length === 0 && rects.length === 9, `${viewport.width} px: the controls and the seven sections within the width (${out.join(", ") || "none outside"})`);
    const steps = rects.filter((r) => r.s.startsWith(".ms-step"));
    const overlaps = [];
    for (let i = 0; i < steps.length; i++) for (let j = i + 1; j < steps.length; j++) {
      const [a, b] = [steps[i], steps[j]];
      if (Math.min(a.r, b.r) - Math.max(a.l, b.l) > 1 && Math.min(a.b, b.b) - Math.max(a.t, b.t) > 1) overlaps.push(`${a.s} × ${b.s}`);
    }
    check(overlaps.length === 0, `${viewport.width} px: no two sections overlap (${overlaps.join(", ") || "none"})`);
    const inner = await page.evaluate(() => [...document.querySelectorAll(".ms-step")].map((e) => e.scrollWidth - e.clientWidth));
    check(inner.every((d) => d <= 1), `${viewport.width} px: each section's content fits it (${inner.join(", ")})`);
    const { scroll, width } = await page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, width: window.innerWidth }));
    check(scroll <= width, `${viewport.width} px: no sideways scroll (${scroll} px)`);
    if (viewport.width === 1280) {
      const body = rects.find((r) => r.s === ".ms-body");
      check(body.b - body.t >= 250, `1280 px: the form has room (${Math.round(body.b - body.t)} px high, scrolling inside)`);
    }
    const shot = join(tmpdir(), `whipple-e2e-measure-${viewport.width}.png`);
    await page.screenshot({ path: shot, fullPage: viewport.width < 500 });
    console.log(`  screenshot: ${shot}`);
  }
});

await section("accessibility: axe-core finds nothing; headings", async () => {
  await open("?bike=preset:schwinn-crown");
  await page.evaluate(axeSource());
  const run = async (what) => {
    const result = await page.evaluate(async () => {
      // eslint-disable-next-line no-undef
      const r = await axe.run(document, { runOnly: { type: "tag", values: ["wcag2a", "wcag2aa", "best-practice"] } });
      return r.violations.map((v) => `${v.id} (${v.nodes.length}: ${v.nodes.slice(0, 2).map((n) => n.target.join(" ")).join("; ")})`);
    });
    check(result.length === 0, `axe-core on the ${what}: ${result.join(", ") || "no violations"}`);
  };
  await run("eigenvalue tab");
  check((await page.locator("h1").count()) === 1 && (await page.locator("h2").count()) >= 4, "one h1 and a heading per panel");
  await page.getByTestId("tab-sim").click();
  await settled();
  await run("simulation tab");
  await page.getByTestId("tab-modes").click();
  await settled();
  await run("modes tab");
  await page.getByTestId("tab-resp").click();
  await page.locator("[data-testid=resp-magnitude] [data-testid=resp-curve]").first().waitFor({ timeout: 15_000 });
  await settled();
  await run("response tab");
  await page.getByTestId("tab-control").click();
  await page.locator("[data-testid=ctl-plot] [data-testid=eigen-curve]").first().waitFor({ timeout: 15_000 });
  await settled();
  await run("control tab");
  await page.getByTestId("tab-ridden").click();
  await page.locator("[data-testid=rd-hqm-plot] [data-testid=rd-hqm-curve]").first().waitFor({ timeout: 60_000 });
  await settled(60_000);
  await run("ridden tab");
  await page.getByTestId("tab-sens").click();
  await page.getByTestId("sens-tornado").waitFor({ timeout: 15_000 });
  await run("sensitivity tab");
  await page.getByTestId("tab-map").click();
  await waitForText("map-meta", (t) => /designs \(/.test(t), 20_000);
  await run("design map tab");
  await page.getByTestId("tab-measure").click();
  await page.getByTestId("ms-sample").selectOption("browser");
  await settled();
  await page.getByTestId("ms-step-IBxx").waitFor({ timeout: 15_000 });
  await run("measure tab");
});

// ---- the static site only ----------------------------------------------------------------

/** A request answered by the site's module in the page and by `whipple serve`: both texts. */
async function bothAnswers(method, path, body) {
  const here = await page.evaluate(async ({ method, path, body }) => {
    const r = await fetch(path, { method, headers: { "content-type": "application/json" }, body: body ?? undefined });
    return { status: r.status, text: await r.text() };
  }, { method, path, body });
  const r = await fetch(new URL(path, server), { method, headers: { "content-type": "application/json" }, body: body ?? undefined });
  return { here, there: { status: r.status, text: await r.text() } };
}

/** Units in the last place between two doubles (0 when equal). */
function ulps(a, b) {
  if (a === b) return 0;
  const view = new DataView(new ArrayBuffer(16));
  view.setFloat64(0, a);
  view.setFloat64(8, b);
  const ordered = (i) => {
    const bits = view.getBigInt64(i);
    return bits < 0n ? -(bits & 0x7fffffffffffffffn) : bits;
  };
  const d = ordered(0) - ordered(8);
  return Number(d < 0n ? -d : d);
}

/** Walks two JSON values together: {numbers, differing, worst} or the path where their shapes part. */
function compareJson(a, b, path = "", tally = { numbers: 0, differing: 0, worst: 0, where: "" }) {
  if (typeof a === "number" && typeof b === "number") {
    tally.numbers += 1;
    if (ulps(a, b) > 0) tally.differing += 1;
    // The difference against the number's size, or against 1 for numbers near zero (a force
    // or an eigenvalue that is zero up to round-off).
    const d = Math.abs(a - b) / Math.max(1, Math.abs(a), Math.abs(b));
    if (d > tally.worst) Object.assign(tally, { worst: d, where: `${path}: ${a} / ${b}` });
    return tally;
  }
  if (Array.isArray(a) && Array.isArray(b) && a.length === b.length) {
    a.forEach((x, i) => compareJson(x, b[i], `${path}[${i}]`, tally));
    return tally;
  }
  if (a && b && typeof a === "object" && typeof b === "object" && !Array.isArray(a) && !Array.isArray(b)) {
    const keys = Object.keys(a);
    if (keys.join() !== Object.keys(b).join()) throw new Error(`the answers' keys part at ${path || "the top"}`);
    for (const k of keys) compareJson(a[k], b[k], `${path}.${k}`, tally);
    return tally;
  }
  if (a !== b) throw new Error(`the answers part at ${path || "the top"}: ${JSON.stringify(a)?.slice(0, 80)} / ${JSON.stringify(b)?.slice(0, 80)}`);
  return tally;
}

if (site) await section("the site's numbers are whipple serve's: bit for bit, or to ten digits where the native linear algebra's FMA parts", async () => {
  await open("?bike=preset:benchmark");
  const bike = await page.evaluate(async () => (await fetch("/api/presets/benchmark")).json());
  const browser = await page.evaluate(async () => (await fetch("/api/presets/browser")).json());
  // "bits": the same bytes. "ulps": the same answer, its numbers within 1e-10 of max(1, |x|).
  // Every elementary function (sin, cos, exp, …) of an answer is whipple::math's (the libm
  // crate) on both back ends, which made maps, simulations and transfer functions bit for
  // bit; a steady turn's eigenvalues and the ridden lane change still part in the last
  // places (faer's dense eigen-solver and matrix products use FMA instructions natively,
  // not in the module: not yet confirmed).
  const asks = [
    ["bits", "GET", "/api/presets/browser", null, "a measured preset"],
    ["bits", "POST", "/api/eigen", { bike, speeds: { start: 0, stop: 10, step: 0.01 } }, "Table 2's eigenvalues and the certified critical speeds"],
    ["bits", "POST", "/api/eigen", { bike: browser, speeds: { start: 0, stop: 10, step: 0.05 } }, "critical speeds with σ"],
    ["bits", "POST", "/api/sensitivity", { bike: browser }, "the exact sensitivities"],
    ["bits", "POST", "/api/map", { bike, x: "trail=-0.05:0.2:41", y: "head_angle_deg=60:85:41", speed: 5 }, "a design map"],
    ["bits", "POST", "/api/simulate", { bike, speed: 4.6, lean_deg: 5, duration: 3 }, "a simulation's every sample and end state"],
    ["ulps", "POST", "/api/turn", { bike, speed: 5, lean_deg: 11.5 }, "a steady turn"],
    ["bits", "POST", "/api/linear/frequency", { bike, speeds: [3, 5], input: "steer_torque", output: "lean", frequencies: { start: 0.1, stop: 100, count: 50 } }, "a transfer function"],
    ["ulps", "POST", "/api/ridden", { bike, speed: 5, lane: "single", speeds: { start: 3, stop: 6, step: 1 } }, "the lane change and HQM"],
    ["bits", "POST", "/api/eigen", { bike: { ...bike, benchmark: { ...bike.benchmark, mB: -1 } }, speeds: { start: 0, stop: 10, step: 0.1 } }, "a bad parameter's message"],
    ["bits", "POST", "/api/eigen", "{", "bad JSON's message"],
    ["bits", "POST", "/api/simulate", { bike, speed: 5, duration: 1e6 }, "a limit's message"],
    ["bits", "GET", "/api/presets/nothing", null, "an unknown preset's message"],
  ];
  const problems = [];
  for (const [how, method, path, request, what] of asks) {
    const body = request === null ? null : typeof request === "string" ? request : JSON.stringify(request);
    const { here, there } = await bothAnswers(method, path, body);
    const same = here.status === there.status && here.text === there.text;
    if (same) {
      check(true, `${what}: ${method} ${path} → ${here.status}, ${here.text.length} bytes, identical to the server's`);
      continue;
    }
    if (how === "bits" || here.status !== there.status) {
      let at = 0;
      while (at < here.text.length && here.text[at] === there.text[at]) at += 1;
      problems.push(`${what}: ${method} ${path} → ${here.status} / ${there.status}, differs from character ${at}: …${here.text.slice(Math.max(0, at - 60), at + 60)}… / …${there.text.slice(Math.max(0, at - 60), at + 60)}…`);
      continue;
    }
    try {
      const t = compareJson(JSON.parse(here.text), JSON.parse(there.text));
      const ok = t.worst <= 1e-10;
      const said = `${what}: ${method} ${path}: ${t.numbers} numbers, ${t.differing} of them not bit for bit (at most ${t.worst.toExponential(1)} of max(1, |x|)${t.where ? `, ${t.where}` : ""})`;
      if (ok) check(true, said);
      else problems.push(said);
    } catch (e) {
      problems.push(`${what}: ${method} ${path}: ${e.message}`);
    }
  }
  check(problems.length === 0, `every answer agrees: ${problems.join("; ") || "all"}`);
});

if (site) await section("the site works offline once loaded: its service worker keeps every file", async () => {
  await open("?bike=preset:benchmark");
  await page.waitForFunction(async () => (await navigator.serviceWorker.ready).active?.state === "activated", null, { timeout: 20_000 });
  // The first visit's files are in the cache once the worker has installed.
  await page.waitForFunction(async () => (await caches.keys()).some((k) => k.startsWith("whipple-")), null, { timeout: 20_000 });
  await page.context().setOffline(true);
  try {
    await page.reload();
    await page.waitForSelector("body[data-ready=true]", { timeout: 20_000 });
    const v = await waitForText("capsize-speed", (t) => /\d/.test(t));
    check(v.includes(asShown(CAPSIZE_SPEED)), `offline, the page computes the capsize speed: ${v}`);
    const fetched = page.waitForResponse((r) => /view3d-.*\.js$/.test(r.url()), { timeout: 20_000 });
    await page.getByTestId("tab-sim").click();
    const three = await fetched;
    check(three.ok() && three.fromServiceWorker(), `offline, the Simulation tab's 3-D code comes from the site's cache (${three.status()})`);
    // An endpoint only the whole module holds: its module too comes from the cache.
    const spec = await page.evaluate(async () => {
      const r = await fetch("/api/openapi.json");
      return { status: r.status, title: (await r.json()).info?.title };
    });
    check(spec.status === 200 && spec.title === "whipple serve", `offline, the whole module answers too: ${JSON.stringify(spec)}`);
  } finally {
    await page.context().setOffline(false);
  }
});

if (errors.length) failures.push(`page errors: ${errors.join("; ")}`);
await close();
clearTimeout(watchdog);
console.log(`e2e page: navigation to plot ${timings.navigationToPlotMs ?? "?"} ms; initial page ${timings.initialTransferred ?? "?"} bytes sent (${timings.initialUncompressed ?? "?"} unpacked)`);
if (failures.length) {
  console.error(`e2e page: FAILED ${failures.length} section(s):\n  ${failures.join("\n  ")}`);
  process.exitCode = 1;
} else {
  console.log(`e2e page: ok (${checks} checks)`);
}
