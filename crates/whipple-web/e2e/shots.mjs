// Screenshots of the page's states: node shots.mjs URL OUT_DIR
import { launch } from "./browser.mjs";
import { mkdirSync } from "node:fs";
import { join } from "node:path";

const [url, out = "/tmp/whipple-shots"] = process.argv.slice(2);
mkdirSync(out, { recursive: true });
const { context, close } = await launch();
try {
  const page = context.pages()[0] ?? (await context.newPage());
  page.on("console", (m) => console.log(`[page ${m.type()}] ${m.text()}`));
  page.on("pageerror", (e) => console.log(`[page error] ${e.message}`));
  await page.goto(url);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20_000 });
  await page.waitForTimeout(300);
  await page.screenshot({ path: join(out, "1-crown.png") });
  // Hover on the plot.
  const box = await page.getByTestId("plot-overlay").boundingBox();
  await page.mouse.move(box.x + box.width * 0.62, box.y + box.height * 0.5);
  await page.waitForTimeout(150);
  await page.screenshot({ path: join(out, "2-hover.png") });
  // Compare with the benchmark bicycle.
  await page.getByTestId("compare-select").selectOption("preset:benchmark");
  await page.waitForTimeout(800);
  await page.mouse.move(10, 10);
  await page.screenshot({ path: join(out, "3-compare.png") });
  // Invalid mass.
  await page.getByTestId("param-mrider").fill("-5");
  await page.waitForTimeout(800);
  await page.screenshot({ path: join(out, "4-invalid.png") });
  await page.getByTestId("param-mrider").fill("80");
  // Benchmark tab.
  await page.getByTestId("compare-select").selectOption("");
  await page.click("#tab-benchmark");
  await page.waitForTimeout(600);
  await page.screenshot({ path: join(out, "5-benchmark-tab.png") });
  // The two-mass skate.
  await page.getByTestId("bike-select").selectOption("preset:two-mass-skate");
  await page.waitForTimeout(800);
  await page.screenshot({ path: join(out, "6-skate.png") });
  await page.setViewportSize({ width: 1024, height: 800 });
  await page.getByTestId("bike-select").selectOption("preset:benchmark");
  await page.waitForTimeout(800);
  await page.screenshot({ path: join(out, "7-narrow.png"), fullPage: true });
  // A speed grid that is too fine, and a file that does not parse.
  await page.fill("#v-step", "0.00000001");
  await page.press("#v-step", "Enter");
  await page.waitForTimeout(800);
  await page.screenshot({ path: join(out, "8-too-many-speeds.png") });
  await page.fill("#v-step", "0.01");
  await page.press("#v-step", "Enter");
  const bad = join(out, "broken.toml");
  (await import("node:fs")).writeFileSync(bad, "name = \"broken\"\n[benchmark]\nw = = 1\n");
  await page.setInputFiles("#file-input", bad);
  await page.waitForTimeout(800);
  await page.screenshot({ path: join(out, "9-bad-file.png") });
  // Two small ones for the README.
  await page.setViewportSize({ width: 1280, height: 760 });
  await page.getByTestId("bike-select").selectOption("preset:schwinn-crown");
  await page.getByTestId("compare-select").selectOption("preset:benchmark");
  await page.waitForTimeout(1000);
  const plot = await page.getByTestId("plot-overlay").boundingBox();
  await page.mouse.move(plot.x + plot.width * 0.45, plot.y + plot.height * 0.5);
  await page.waitForTimeout(200);
  await page.screenshot({ path: join(out, "docs-whipple-serve.png") });
  await page.mouse.move(1, 1);
  await page.getByTestId("compare-select").selectOption("");
  await page.getByTestId("param-mrider").fill("-5");
  await page.waitForTimeout(800);
  await page.screenshot({ path: join(out, "docs-invalid-entry.png") });
  // The simulation panel, at both common laptop widths.
  await page.mouse.move(1, 1);
  await page.getByTestId("param-mrider").fill("80");
  await page.getByTestId("bike-select").selectOption("preset:benchmark");
  await page.waitForTimeout(800);
  await page.getByTestId("tab-sim").click();
  const run = async (speed, seconds) => {
    await page.fill("#sim-speed", String(speed));
    await page.click("[data-testid=sim-run]");
    await page.waitForFunction(() => !document.querySelector("[data-testid=sim-outcome]").classList.contains("running"));
    await page.waitForTimeout(seconds * 1000);
    await page.getByTestId("sim-play").click(); // pause mid-animation
  };
  for (const [width, height] of [[1440, 900], [1280, 800]]) {
    await page.setViewportSize({ width, height });
    await run(4.6, 2.5);
    await page.screenshot({ path: join(out, `10-sim-weave-${width}.png`) });
  }
  await page.setViewportSize({ width: 1280, height: 760 });
  await run(4.6, 3.2);
  await page.screenshot({ path: join(out, "docs-simulation-weave.png") });
  await run(3, 0.2);
  await page.$eval("#sim-scrub", (e) => {
    e.value = e.max;
    e.dispatchEvent(new Event("input", { bubbles: true }));
  });
  await page.waitForTimeout(300);
  await page.screenshot({ path: join(out, "docs-simulation-fall.png") });
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.waitForTimeout(300);
  await page.screenshot({ path: join(out, "11-sim-fall-1440.png") });
  await page.setViewportSize({ width: 1024, height: 800 });
  await page.waitForTimeout(300);
  await page.screenshot({ path: join(out, "12-sim-narrow.png"), fullPage: true });
} finally {
  await close();
}
