// End-to-end test of the page in headless Chromium: node test.mjs URL
// Run by crates/whipple-web/tests/e2e.rs against a server on an ephemeral loopback port.
import { launch } from "./browser.mjs";
import { CAPSIZE_SPEED, WEAVE_SPEED, asShown } from "./reference.mjs";
import { readFileSync, writeFileSync, mkdtempSync, rmSync } from "node:fs";
import { join } from "node:path";
import { tmpdir } from "node:os";

const url = process.argv[2];
if (!url || !/^http:\/\/(127\.0\.0\.1|localhost|\[::1\])[:/]/.test(url)) {
  console.error("usage: node test.mjs http://127.0.0.1:PORT/ (loopback only)");
  process.exit(2);
}
const LIMIT_MS = Number(process.env.E2E_TIMEOUT_MS ?? 90_000);
const watchdog = setTimeout(() => {
  console.error(`e2e: FAILED: gave up after ${LIMIT_MS / 1000} s`);
  process.exit(1);
}, LIMIT_MS);

let checks = 0;
function check(condition, what) {
  if (!condition) throw new Error(`check failed: ${what}`);
  checks += 1;
  console.log(`  ok ${checks}: ${what}`);
}

const { context, close } = await launch();
const page = context.pages()[0] ?? (await context.newPage());
page.setDefaultTimeout(30_000); // generous: CI's machine is shared and SwiftShader is slow
const errors = [];
page.on("pageerror", (e) => errors.push(e.message));
// Every request must stay on the server under test.
const origin = new URL(url).origin;
await page.route("**/*", (route) => {
  const u = route.request().url();
  if (u.startsWith(origin) || u.startsWith("data:") || u.startsWith("blob:")) return route.continue();
  errors.push(`request off loopback: ${u}`);
  return route.abort();
});

const text = async (id) => (await page.getByTestId(id).textContent()).trim();
const number = (s) => Number(s.replace("−", "-").replace(/[^0-9.eE+-].*$/, ""));
const plotPaths = () => page.$$eval("[data-testid=eigen-plot] svg path", (ps) => ps.map((p) => p.getAttribute("d")).join("|"));
/** The page's next animation frame: what it draws by then is drawn. */
const nextFrame = () => page.evaluate(() => new Promise((done) => requestAnimationFrame(() => done())));
/** Until the page has settled: nothing in flight or scheduled (web/src/work.js), and drawn. */
async function settled() {
  await page.waitForSelector("body[data-pending='0']", { state: "attached" });
  await nextFrame();
}
/** Reads the element's text at each of the page's frames until `predicate` holds (15 s at most). */
async function waitForText(id, predicate) {
  const until = Date.now() + 15_000;
  let last = null;
  while (Date.now() < until) {
    last = await page.getByTestId(id).textContent({ timeout: 1_000 }).catch(() => null);
    if (last !== null && predicate(last.trim())) return last.trim();
    await nextFrame();
  }
  throw new Error(`timed out waiting on ${id}: last text "${last}"`);
}

try {
  await page.goto(url);
  await page.waitForSelector("body[data-ready=true]");
  check((await page.title()).includes("whipple"), "the page loads");

  // Pick another bicycle, then JBike6's default, the Schwinn Crown.
  await page.getByTestId("bike-select").selectOption("preset:benchmark");
  await waitForText("capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  check(true, `the benchmark bicycle's capsize speed is ${asShown(CAPSIZE_SPEED)} m/s (Meijaard et al. 2007)`);
  await page.getByTestId("bike-select").selectOption("preset:schwinn-crown");
  await waitForText("capsize-speed", (t) => t.startsWith("7.98"));
  const capsize = number(await text("capsize-speed"));
  check(Math.abs(capsize - 7.9807) < 5e-5, `the Schwinn Crown's capsize speed is ${capsize} m/s (JBike6: 7.9807)`);
  const weave = number(await text("weave-speed"));
  check(weave > 5 && weave < 5.5, `its weave speed is ${weave} m/s`);
  check((await page.locator("[data-testid=stable-range]").count()) === 1, "one self-stable range is shaded");
  check((await page.locator("[data-testid=side-view] svg circle").count()) > 4, "the side view is drawn");

  // Hovering reads values out. The plot redraws itself when its container is resized (on a
  // cold start the layout may still settle after the speeds are shown), replacing the overlay:
  // hover through the locator, which waits for a stable, attached element and retries if it
  // is replaced, rather than through a bounding box taken once (null when detached).
  const overlay = page.getByTestId("plot-overlay");
  // On a cold start the first hover has been seen to miss (Playwright finds the plot's frame at
  // the point while the layout settles): a few attempts, each with the overlay's size now, in
  // CSS pixels.
  let shown = false;
  for (let attempt = 0; attempt < 5 && !shown; attempt++) {
    try {
      const size = await overlay.evaluate((e) => { const r = e.getBoundingClientRect(); return { w: r.width, h: r.height }; });
      await overlay.hover({ position: { x: size.w * 0.6, y: size.h / 2 }, timeout: 5_000 });
      await page.getByTestId("plot-tooltip").waitFor({ state: "visible", timeout: 3_000 });
      shown = true;
    } catch {
      // Off the plot, the read-out hides: the next attempt starts from there.
      await page.mouse.move(0, 0);
      await page.getByTestId("plot-tooltip").waitFor({ state: "hidden", timeout: 5_000 }).catch(() => {});
      await settled();
    }
  }
  check(shown, "the plot's read-out appears on hover");
  check((await text("plot-tooltip")).includes("weave"), "hovering the plot shows the eigenvalues");
  await page.mouse.move(1, 1);

  // A shorter trail: the plot and the critical speeds change.
  const before = await plotPaths();
  const sideBefore = await page.$eval("[data-testid=side-view]", (e) => e.innerHTML);
  await page.getByTestId("param-trail").fill("0.05");
  await waitForText("capsize-speed", (t) => !t.startsWith("7.9807"));
  await waitForText("capsize-speed", (t) => Number.isFinite(number(t)));
  const capsize2 = number(await text("capsize-speed"));
  // whipple speeds on the Crown with trail = 0.05: v_c 6.15224 m/s, v_w 4.52487 m/s.
  check(Math.abs(capsize2 - 6.15224) < 5e-4, `with a 50 mm trail the capsize speed reads ${await text("capsize-speed")} (6.1522 m/s)`);
  const weave2 = number(await text("weave-speed"));
  check(Math.abs(weave2 - 4.52487) < 5e-4, `and the weave speed ${await text("weave-speed")} (4.5249 m/s)`);
  check((await plotPaths()) !== before, "the eigenvalue plot is redrawn");
  check((await page.$eval("[data-testid=side-view]", (e) => e.innerHTML)) !== sideBefore, "the side view is redrawn");

  // An invalid mass: the library's message, in place.
  await page.getByTestId("param-mrider").fill("-5");
  await waitForText("error-mrider", (t) => t.length > 0);
  check((await text("error-mrider")) === "must not be negative", `the rider's mass is flagged: "${await text("error-mrider")}"`);
  const message = await text("message");
  check(message.includes("invalid parameter `mrider` = -5: must not be negative"), `the library's message is shown: "${message}"`);
  check(await page.getByTestId("param-mrider").evaluate((e) => e.classList.contains("invalid")), "the field is marked invalid");
  await page.getByTestId("param-mrider").fill("abc");
  await waitForText("error-mrider", (t) => t === "not a number");
  check(true, "text that is not a number is flagged before asking the server");
  await page.getByTestId("param-mrider").fill("80");
  await page.getByTestId("param-trail").fill("0.090968");
  await waitForText("capsize-speed", (t) => t.startsWith("7.9807"));
  check((await text("error-mrider")) === "", "mending the entries clears the flag and restores the speeds");

  // Comparison of two designs on one plot.
  await page.getByTestId("compare-select").selectOption("preset:benchmark");
  await waitForText("compare-capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  check(true, `comparing with the benchmark bicycle lists its capsize speed ${asShown(CAPSIZE_SPEED)} beside the Crown's`);

  // CSV export.
  const [csv] = await Promise.all([page.waitForEvent("download"), page.click("#eigen-csv")]);
  const csvText = readFileSync(await csv.path(), "utf8").split("\n");
  // A first line naming the designs, the CLI's columns with the mode names, then the
  // compared design's columns.
  // Comment lines first: the designs, then each one's critical speeds.
  const head = csvText.find((l) => !l.startsWith("#")) ?? "";
  check(csvText[0].startsWith("# ") && head.startsWith("v,re1_weave,im1_weave,re2_weave,im2_weave,re3_capsize,im3_capsize,re4_castering,im4_castering,"), `the CSV export names the designs and the modes: ${head.slice(0, 60)}…`);
  check(csvText.some((l) => /^# .*: .*v_w = [\d.]+ m\/s/.test(l)), `and each design's critical speeds: ${csvText[1]}`);
  check(csvText.filter((l) => l && !l.startsWith("#")).length === 1002, "and one row per speed (1001)");
  const [png] = await Promise.all([page.waitForEvent("download"), page.click("#eigen-png")]);
  check(readFileSync(await png.path()).subarray(1, 4).toString() === "PNG", "the plot exports as PNG");
  const [svgFile] = await Promise.all([page.waitForEvent("download"), page.click("#eigen-svg")]);
  check(readFileSync(await svgFile.path(), "utf8").includes("<svg"), "the plot exports as SVG");

  // Save as TOML, load it back as one of my designs.
  await page.getByTestId("compare-select").selectOption("");
  await page.getByTestId("param-trail").fill("0.07");
  await waitForText("capsize-speed", (t) => !t.startsWith("7.9807"));
  const edited = await text("capsize-speed");
  const [toml] = await Promise.all([page.waitForEvent("download"), page.click("#save-toml")]);
  const tomlText = readFileSync(await toml.path(), "utf8");
  check(tomlText.includes("[jbike6]") && tomlText.includes("trail = 0.07"), "Save TOML writes the CLI's format with the edited trail");
  const dir = mkdtempSync(join(tmpdir(), "whipple-e2e-file-"));
  const file = join(dir, "short-trail.toml");
  writeFileSync(file, tomlText.replace(/^name = .*$/m, 'name = "short trail"'));
  await page.getByTestId("bike-select").selectOption("preset:benchmark");
  await waitForText("capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  await page.setInputFiles("#file-input", file);
  await waitForText("capsize-speed", (t) => t === edited);
  rmSync(dir, { recursive: true, force: true });
  check((await page.getByTestId("bike-select").inputValue()).startsWith("design:"), "the loaded file becomes one of my designs");
  check(await page.evaluate(() => JSON.parse(localStorage.getItem("whipple.designs.v1")).some((d) => d.name === "short trail")), "kept in localStorage");

  // Rename and save to my designs, then delete it.
  await page.fill("#design-name", "short trail, renamed");
  await page.click("#save-design");
  await page.waitForFunction(() => [...document.querySelectorAll("#bike-select option")].some((o) => o.textContent === "short trail, renamed"));
  check(true, "Save to my designs lists the renamed design in the picker");
  await page.click("#delete-design");
  await waitForText("capsize-speed", (t) => t.startsWith("7.9807"));
  check(!(await page.evaluate(() => [...document.querySelectorAll("#bike-select option")].some((o) => o.textContent === "short trail, renamed"))), "Delete removes it and goes back to the Schwinn Crown");
  const [side] = await Promise.all([page.waitForEvent("download"), page.click("#side-svg")]);
  check(readFileSync(await side.path(), "utf8").includes("total 91.1 kg"), "the side view exports as SVG");
  // The simulation panel: the benchmark bicycle at 4.6 m/s (self-stable: the weave decays).
  await page.getByTestId("bike-select").selectOption("preset:benchmark");
  await waitForText("capsize-speed", (t) => t.startsWith(asShown(CAPSIZE_SPEED)));
  await page.getByTestId("tab-sim").click();
  check((await page.locator("#panel-sim").isVisible()) && !(await page.locator("#panel-eigen").isVisible()), "the Simulation tab takes the eigenvalue plot's place");
  const suggested = Number(await page.inputValue("#sim-speed"));
  check(Math.abs(suggested - (WEAVE_SPEED + CAPSIZE_SPEED) / 2) < 0.01, `the suggested speed ${suggested} m/s is the middle of the self-stable range`);
  await page.fill("#sim-duration", "31");
  await page.click("[data-testid=sim-run]");
  await waitForText("sim-message", (t) => t.includes("limit of 30 s"));
  check(await page.locator("#sim-duration").evaluate((e) => e.classList.contains("invalid")), `a 31 s run is refused at the field: "${await text("sim-message")}"`);
  await page.fill("#sim-speed", "4.6");
  await page.fill("#sim-duration", "10");
  const started = Date.now();
  await page.click("[data-testid=sim-run]");
  await waitForText("sim-outcome", (t) => t.startsWith("completed"));
  check(await page.getByTestId("sim-message").isHidden(), `the run completes: "${await text("sim-outcome")}" (${Date.now() - started} ms with the request)`);
  const simTime = async () => number(await text("sim-t"));
  /** The displayed time and the scrub bar's position, read together. */
  const reading = () => page.evaluate(() => ({
    t: Number(document.getElementById("sim-t").textContent.replace("−", "-")),
    scrub: Number(document.getElementById("sim-scrub").value),
  }));
  // SwiftShader draws slowly (and compiles its shaders on the first frame): poll.
  const advanced = async (r0) => {
    const until = Date.now() + 15_000;
    while (Date.now() < until) {
      await nextFrame();
      const r = await reading();
      if (r.t > r0.t && r.scrub > r0.scrub) return r;
    }
    return r0;
  };
  const r1 = await reading();
  const r2 = await advanced(r1);
  check(r2.t > r1.t && r2.scrub > r1.scrub, `the animation advances while playing: t ${r1.t} -> ${r2.t} s, scrub ${r1.scrub.toFixed(2)} -> ${r2.scrub.toFixed(2)}`);
  const r3 = await advanced(r2);
  check(r3.t > r2.t, `and keeps advancing: ${r3.t} s`);
  await page.getByTestId("sim-play").click();
  const p1 = await simTime();
  // Twenty of the page's frames: each would have advanced a playing animation.
  for (let frame = 0; frame < 20; frame++) await nextFrame();
  check((await simTime()) === p1, `pause stops it at t = ${p1} s`);
  const pixels = () => page.$eval("[data-testid=sim-canvas]", (c) => {
    const gl = c.getContext("webgl2") ?? c.getContext("webgl");
    if (!gl) return null;
    const data = new Uint8Array(c.width * c.height * 4);
    gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, data);
    const colours = new Set();
    let hash = 0;
    let notSky = 0;
    for (let i = 0; i < data.length; i += 4) {
      const [r, g, b] = [data[i], data[i + 1], data[i + 2]];
      if (Math.abs(r - 234) + Math.abs(g - 241) + Math.abs(b - 248) > 24) notSky += 1;
      colours.add((r >> 4) * 256 + (g >> 4) * 16 + (b >> 4));
      hash = (hash * 31 + r + 7 * g + 13 * b) % 1_000_000_007;
    }
    return { notSky: notSky / (data.length / 4), colours: colours.size, hash };
  });
  const shot1 = await pixels();
  check(shot1 && shot1.notSky > 0.2 && shot1.colours > 20, `the 3-D view is drawn (WebGL): ${shot1 && (100 * shot1.notSky).toFixed(0)}% of the canvas off the sky colour, ${shot1?.colours} colours`);
  const leanCursor = () => page.$eval("[data-testid=sim-cursor]", (e) => Number(e.getAttribute("x1")));
  const marker = () => page.$eval("[data-testid=sim-track-marker]", (e) => Number(e.getAttribute("cx")));
  const [c1, m1] = [await leanCursor(), await marker()];
  await page.$eval("#sim-scrub", (e) => {
    e.value = "7.5";
    e.dispatchEvent(new Event("input", { bubbles: true }));
  });
  await waitForText("sim-t", (t) => t === "7.50");
  check((await leanCursor()) > c1 && (await marker()) > m1, "scrubbing to 7.5 s moves the time plots' cursor and the ground-track marker");
  const shot2 = await pixels();
  check(shot2 && shot2.hash !== shot1.hash, "and redraws the 3-D view");
  await page.selectOption("[data-testid=sim-rate]", "2");
  // Measure from early in the run: from 7.5 s at 2x the 10 s run ends within the 1.5 s the
  // measurement takes (and a slow first frame made it read 0).
  await page.$eval("#sim-scrub", (e) => {
    e.value = "1";
    e.dispatchEvent(new Event("input", { bubbles: true }));
  });
  await waitForText("sim-t", (t) => t === "1.00");
  // At 2x, simulated time runs twice as fast as the page's clock (measured in the page).
  // SwiftShader under load may take a second per frame, and the page advances at most 1 s of
  // wall time per frame (so as not to jump): time the displayed clock at the moments it
  // changes (read at every frame) over at least 1.5 s, and note the slowest frame.
  const { rate, slowest } = await page.evaluate(async () => {
    const t = () => Number(document.getElementById("sim-t").textContent.replace("−", "-"));
    const frame = () => new Promise((r) => requestAnimationFrame(() => r()));
    let slowest = 0;
    let seen = performance.now();
    const change = async (from, until) => {
      while (performance.now() < until) {
        await frame();
        if (t() !== from) {
          slowest = Math.max(slowest, performance.now() - seen);
          seen = performance.now();
          return [t(), seen];
        }
      }
      return [from, performance.now()];
    };
    document.getElementById("sim-play").click();
    const [t0, w0] = await change(t(), performance.now() + 10_000);
    let [t1, w1] = [t0, w0];
    while (w1 - w0 < 1500) [t1, w1] = await change(t1, performance.now() + 10_000);
    document.getElementById("sim-play").click();
    return { rate: (t1 - t0) / ((w1 - w0) / 1000), slowest };
  });
  check(slowest > 900 ? rate > 0.5 : rate > 1.5 && rate < 2.5, `at 2x the simulated time runs ${rate.toFixed(2)} times as fast as the clock (slowest frame ${slowest.toFixed(0)} ms${slowest > 900 ? ": the page caps a frame's step at 1 s, so only the advance is checked" : ""})`);

  // A fall at 3 m/s, below the weave speed.
  await page.fill("#sim-speed", "3");
  await page.click("[data-testid=sim-run]");
  await waitForText("sim-outcome", (t) => !t.startsWith("completed") && !t.startsWith("simulating"));
  const fell = await text("sim-outcome");
  const kind = await page.getByTestId("sim-outcome").getAttribute("data-kind");
  // The rear wheel would lift off at t = 1.6036 s (41° of lean), before the lean reaches 60°.
  check(kind === "wheel_lifted" && fell.includes("rear wheel") && fell.includes("t = 1.60 s"), `at 3 m/s the rear wheel lifts off at 1.60 s: "${fell}" (${kind})`);
  // A rider's steer torque as an expression: one with an unknown name is refused at the field;
  // steering into the lean holds the bicycle up at the same 3 m/s.
  await page.fill("#sim-steer-torque", "2*foo");
  await page.click("[data-testid=sim-run]");
  await waitForText("sim-message", (t) => t.includes("unknown name `foo`"));
  check(await page.locator("#sim-steer-torque").evaluate((e) => e.classList.contains("invalid")), `an unknown name in the steer torque is refused at the field: "${await text("sim-message")}"`);
  await page.fill("#sim-steer-torque", "10*lean + 20*lean_rate");
  await page.click("[data-testid=sim-run]");
  await waitForText("sim-outcome", (t) => t.startsWith("completed"));
  check(!(await page.locator("#sim-steer-torque").evaluate((e) => e.classList.contains("invalid"))), `steering into the lean holds it up at 3 m/s: "${await text("sim-outcome")}"`);
  await page.getByTestId("tab-eigen").click();
  check(await page.locator("#panel-eigen").isVisible(), "the eigenvalue tab comes back");
  // A design whose self-stable range is about 1e-12 m/s wide (the benchmark with its trail
  // where v_w meets v_c): the certificate cannot decide there, and no cell may contradict it
  // ("nowhere" or "none" beside an undecided interval).
  await page.goto(`${url}?bike=preset:benchmark&e=c:-0.008009376368681962`);
  await page.waitForSelector("body[data-ready=true]");
  const undecided = await waitForText("stable-ranges", (t) => t.startsWith("undecided in"));
  check(undecided.includes("2.696") && undecided.endsWith("nowhere else"), `an undecided design: self-stable "${undecided}"`);
  const weaveUndecided = await text("weave-speed");
  check(weaveUndecided.startsWith("undecided in 2.696"), `and its weave speed "${weaveUndecided}", not "none"`);
  check(errors.length === 0, `no page errors (${errors.join("; ") || "none"})`);
  console.log(`e2e: ok (${checks} checks)`);
} catch (e) {
  const shot = join(tmpdir(), `whipple-e2e-failure-${Date.now()}.png`);
  await page.screenshot({ path: shot }).catch(() => {});
  console.error(`e2e: FAILED: ${e.message}\n  page errors: ${errors.join("; ") || "none"}\n  screenshot: ${shot}`);
  process.exitCode = 1;
} finally {
  await close();
  clearTimeout(watchdog);
}
