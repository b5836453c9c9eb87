// End-to-end test of the page in headless Chromium: node test.mjs URL
// Run by crates/whipple-web/tests/e2e.rs against a server on an ephemeral loopback port.
import { launch } from "./browser.mjs";
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
page.setDefaultTimeout(15_000);
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
/** Polls the element's text until `predicate` holds (15 s at most). */
async function waitForText(id, predicate) {
  const until = Date.now() + 15_000;
  let last = null;
  while (Date.now() < until) {
    last = await page.getByTestId(id).textContent({ timeout: 1_000 }).catch(() => null);
    if (last !== null && predicate(last.trim())) return last.trim();
    await page.waitForTimeout(100);
  }
  throw new Error(`timed out waiting on ${id}: last text "${last}"`);
}

try {
  await page.goto(url);
  await page.waitForSelector("body[data-ready=true]");
  check((await page.title()).includes("whipple"), "the page loads");

  // Pick another bicycle, then JBike6's default, the Schwinn Crown.
  await page.getByTestId("bike-select").selectOption("preset:benchmark");
  await waitForText("capsize-speed", (t) => t.startsWith("6.0243"));
  check(true, "the benchmark bicycle's capsize speed is 6.0243 m/s (Meijaard et al. 2007)");
  await page.getByTestId("bike-select").selectOption("preset:schwinn-crown");
  await waitForText("capsize-speed", (t) => t.startsWith("7.98"));
  const capsize = number(await text("capsize-speed"));
  check(Math.abs(capsize - 7.9807) < 5e-5, `the Schwinn Crown's capsize speed is ${capsize} m/s (JBike6: 7.9807)`);
  const weave = number(await text("weave-speed"));
  check(weave > 5 && weave < 5.5, `its weave speed is ${weave} m/s`);
  check((await page.locator("[data-testid=stable-range]").count()) === 1, "one self-stable range is shaded");
  check((await page.locator("[data-testid=side-view] svg circle").count()) > 4, "the side view is drawn");

  // Hovering reads values out.
  const box = await page.getByTestId("plot-overlay").boundingBox();
  await page.mouse.move(box.x + box.width * 0.6, box.y + box.height / 2);
  await page.getByTestId("plot-tooltip").waitFor({ state: "visible" });
  check((await text("plot-tooltip")).includes("weave"), "hovering the plot shows the eigenvalues");
  await page.mouse.move(1, 1);

  // A shorter trail: the plot and the critical speeds change.
  const before = await plotPaths();
  const sideBefore = await page.$eval("[data-testid=side-view]", (e) => e.innerHTML);
  await page.getByTestId("param-trail").fill("0.05");
  await waitForText("capsize-speed", (t) => !t.startsWith("7.9807"));
  const capsize2 = number(await text("capsize-speed"));
  check(Number.isFinite(capsize2) ? capsize2 !== capsize : true, `with a 50 mm trail the capsize speed reads ${await text("capsize-speed")}`);
  check(number(await text("weave-speed")) !== weave, `and the weave speed ${await text("weave-speed")}`);
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
  await waitForText("compare-capsize-speed", (t) => t.startsWith("6.0243"));
  check(true, "comparing with the benchmark bicycle lists its capsize speed 6.0243 beside the Crown's");

  // CSV export.
  const [csv] = await Promise.all([page.waitForEvent("download"), page.click("#eigen-csv")]);
  const csvText = readFileSync(await csv.path(), "utf8").split("\n");
  check(csvText[0] === "v,re1,im1,re2,im2,re3,im3,re4,im4", "the CSV export has the header v,re1,im1,...,im4");
  check(csvText.filter(Boolean).length === 1002, "and one row per speed (1001)");
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
  await waitForText("capsize-speed", (t) => t.startsWith("6.0243"));
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
