// Screenshots of the page's states at a phone's, a laptop's and a desktop's width:
//   node shots.mjs URL OUT_DIR [WIDTHS]     (WIDTHS default 390,1280,1920)
// Writes OUT_DIR/WIDTH-STATE.png, then OUT_DIR/done.
// With SHOTS_GUIDE=1 it takes only the user guide's screenshots, under the names the guide
// shows (docs/screenshots/*.png; the e2e test `guide_screenshots_in_headless_chromium` runs it
// so, and docs/hooks/screenshots.py puts them in the built guide).
import { launch } from "./browser.mjs";
import { mkdirSync, writeFileSync } from "node:fs";
import { join } from "node:path";

const [url, out = "/tmp/whipple-shots", list = "390,1280,1920"] = process.argv.slice(2);
mkdirSync(out, { recursive: true });
const widths = list.split(",").map(Number);
/** The guide's screenshots: (width, state) → the name the guide shows. */
const GUIDE = new Map([
  ["390-1-crown", "whipple-serve-390.png"],
  ["1280-4-compare-three", "whipple-serve.png"],
  ["1280-6-not-a-number", "whipple-serve-invalid-entry.png"],
  ["1280-8-root-locus", "whipple-serve-root-locus.png"],
  ["1280-9-modes", "whipple-serve-modes.png"],
  ["1280-10-sim-weave", "whipple-serve-simulation.png"],
  ["1280-11-sim-fall", "whipple-serve-fall.png"],
  ["1280-13-sensitivity", "whipple-serve-sensitivity.png"],
  ["1280-14-design-map", "whipple-serve-design-map.png"],
  ["1280-15-sim-held-turn", "whipple-serve-turn.png"],
]);
const guide = process.env.SHOTS_GUIDE === "1";
const { context, close } = await launch();
const page = context.pages()[0] ?? (await context.newPage());
page.on("pageerror", (e) => console.log(`[page error] ${e.message}`));
/** The page's next animation frame: what it draws by then is drawn. */
const nextFrame = () => page.evaluate(() => new Promise((done) => requestAnimationFrame(() => done())));
/** Until the page has settled: nothing in flight or scheduled (web/src/work.js), and drawn. */
const settled = async () => {
  await page.waitForSelector("body[data-pending='0']", { state: "attached", timeout: 30_000 });
  await nextFrame();
};
/** Until the element's text matches `pattern`. */
const shows = (id, pattern) => page.waitForFunction(([id, source]) => new RegExp(source).test(document.querySelector(`[data-testid="${id}"]`)?.textContent ?? ""), [id, pattern.source], { timeout: 30_000 });
const ticks = (id) => page.$$eval(`[data-testid=${id}] svg > g[fill] > text`, (ts) => ts.map((t) => t.textContent).join(" "));
const ready = async (query) => {
  await page.goto(new URL(query, url).href);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20_000 });
  await page.waitForFunction(() => /\d/.test(document.querySelector("[data-testid=capsize-speed]")?.textContent ?? ""));
  await settled();
};
const run = async (speed, seconds, duration = 10) => {
  await page.fill("#sim-speed", String(speed));
  await page.fill("#sim-duration", String(duration));
  await page.click("[data-testid=sim-run]");
  await page.waitForFunction(() => !document.querySelector("[data-testid=sim-outcome]").classList.contains("running"), null, { timeout: 30_000 });
  // The animation played to `seconds` of simulated time (or to its end, when the run is shorter).
  await page.waitForFunction((s) => {
    const t = Number(document.getElementById("sim-t").textContent.replace("−", "-"));
    const end = Number(document.getElementById("sim-scrub").max);
    return t >= Math.min(s, end);
  }, seconds, { timeout: 60_000 });
  if ((await page.getByTestId("sim-play").getAttribute("aria-pressed")) === "true") await page.getByTestId("sim-play").click();
};
try {
  for (const width of widths) {
    const height = width <= 400 ? 844 : width <= 1300 ? 800 : 1080;
    await page.setViewportSize({ width, height });
    /** Whether this run takes any of `names` at this width (every state without SHOTS_GUIDE). */
    const want = (...names) => !guide || names.some((name) => GUIDE.has(`${width}-${name}`));
    const shot = async (name) => {
      if (!want(name)) return;
      const file = guide ? GUIDE.get(`${width}-${name}`) : `${width}-${name}.png`;
      await page.screenshot({ path: join(out, file), fullPage: width <= 400 && !name.includes("hover") && !name.includes("zoom") });
      console.log(file);
    };
    if (want("1-crown", "2-hover", "3-zoomed")) {
      await ready("?bike=preset:schwinn-crown");
      await shot("1-crown");
      await page.getByTestId("eigen-plot").scrollIntoViewIfNeeded();
      const box = await page.getByTestId("eigen-plot").boundingBox();
      await page.mouse.move(box.x + box.width * 0.55, box.y + box.height * 0.5);
      await page.getByTestId("plot-tooltip").waitFor({ state: "visible" });
      await shot("2-hover");
      const full = await ticks("eigen-plot");
      await page.mouse.wheel(0, -500);
      await page.waitForFunction((before) => [...document.querySelectorAll("[data-testid=eigen-plot] svg > g[fill] > text")].map((t) => t.textContent).join(" ") !== before, full);
      await nextFrame();
      await shot("3-zoomed");
      await page.mouse.move(1, 1);
    }
    if (want("4-compare-three")) {
      await ready("?bike=preset:schwinn-crown&cmp=preset:benchmark,preset:browser-jason");
      await shows("compare2-capsize-speed", /\d/);
      await settled();
      await shot("4-compare-three");
    }
    if (want("5-invalid", "6-not-a-number", "7-did-you-mean")) {
      await ready("?bike=preset:schwinn-crown");
      await page.getByTestId("param-mrider").fill("-5");
      await shows("error-mrider", /./);
      await settled();
      await shot("5-invalid");
      await page.getByTestId("param-mrider").fill("abc");
      await shows("error-mrider", /not a number/);
      await settled();
      await shot("6-not-a-number");
      await page.getByTestId("param-mrider").fill("80");
      await page.getByTestId("param-head_angle").fill("1.2388");
      await shows("hint-head_angle", /./);
      await settled();
      await shot("7-did-you-mean");
    }
    if (want("8-root-locus")) {
      await ready("?bike=preset:benchmark&tab=locus");
      await shot("8-root-locus");
    }
    if (want("9-modes")) {
      await ready("?bike=preset:benchmark&tab=modes&mv=5");
      await shows("mode-meta", /at 5 m\/s/);
      await settled();
      await shot("9-modes");
    }
    if (want("10-sim-weave", "11-sim-fall")) {
      await ready("?bike=preset:benchmark&tab=sim");
      await run(4.6, 2.5);
      await run(5.5, 2.5);
      await shot("10-sim-weave");
      await run(3, 0.3);
      await page.$eval("#sim-scrub", (e) => {
        e.value = e.max;
        e.dispatchEvent(new Event("input", { bubbles: true }));
      });
      await settled();
      await shot("11-sim-fall");
    }
    if (want("12-negative-trail")) {
      await ready("?bike=preset:schwinn-crown");
      await page.getByTestId("param-trail").fill("-0.05");
      await shows("capsize-speed", /unstable at every speed/);
      await settled();
      await shot("12-negative-trail");
    }
    if (want("13-sensitivity")) {
      await ready("?bike=preset:browser-jason&tab=sens");
      await page.getByTestId("sens-tornado").waitFor({ timeout: 15_000 });
      await shot("13-sensitivity");
    }
    if (want("14-design-map")) {
      await ready("?bike=preset:schwinn-crown&tab=map");
      await page.waitForFunction(() => /designs \(/.test(document.querySelector("[data-testid=map-meta]")?.textContent ?? ""), null, { timeout: 20_000 });
      // In view, so that the pointer is over the map and its read-out is drawn (on a phone the map
      // lies below the fold).
      await page.getByTestId("map-canvas").scrollIntoViewIfNeeded();
      const mbox = await page.getByTestId("map-canvas").boundingBox();
      await page.mouse.move(mbox.x + mbox.width * 0.6, mbox.y + mbox.height * 0.45);
      await shows("map-readout", /./);
      await shot("14-design-map");
      await page.mouse.move(1, 1);
    }
    if (want("15-sim-held-turn")) {
      await ready("?bike=preset:benchmark&tab=sim&sim=speed:5;lean_deg:11.5;lean_rate:0.05;turn:held");
      await run(5, 4, 6);
      await shot("15-sim-held-turn");
    }
  }
  writeFileSync(join(out, "done"), "");
} finally {
  await close();
}
