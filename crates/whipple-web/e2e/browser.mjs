// Headless Chromium through playwright-core, never downloading a browser of its own.
// playwright-core is found in WHIPPLE_WEB_NODE_MODULES (set by the Rust test from build.rs's
// npm install) or, failing that, in ../web/node_modules.
import { createRequire } from "node:module";
import { existsSync, mkdtempSync, rmSync } from "node:fs";
import { join, resolve } from "node:path";
import { tmpdir } from "node:os";
import { fileURLToPath } from "node:url";

const here = fileURLToPath(new URL(".", import.meta.url));

function loadPlaywright() {
  const places = [process.env.WHIPPLE_WEB_NODE_MODULES, join(here, "..", "web", "node_modules")].filter(Boolean);
  for (const dir of places) {
    if (existsSync(join(dir, "playwright-core"))) return createRequire(join(resolve(dir), "noop.js"))("playwright-core");
  }
  throw new Error(`playwright-core not found in ${places.join(" or ")}; run npm ci in crates/whipple-web/web`);
}

export const CHROMIUM = process.env.CHROMIUM ?? "/usr/bin/chromium";

/** Starts headless Chromium with a fresh profile; returns {browser, close}. `phone`: a touch
 *  screen of 390 × 844 (a phone's), touch events on. */
export async function launch({ phone = false } = {}) {
  const { chromium } = loadPlaywright();
  const profile = mkdtempSync(join(tmpdir(), "whipple-e2e-"));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: phone ? { width: 390, height: 844 } : { width: 1440, height: 900 },
    hasTouch: phone,
    isMobile: phone,
    deviceScaleFactor: 1,
    acceptDownloads: true,
    timeout: 30_000,
    args: [
      "--no-sandbox",
      // WebGL (the simulation's 3-D view) on the CPU: SwiftShader through ANGLE.
      "--enable-unsafe-swiftshader",
      "--use-angle=swiftshader",
      "--disable-quic",
      "--no-first-run",
      "--disable-background-networking",
      "--disable-component-update",
      "--disable-sync",
      "--disable-dev-shm-usage",
      // Compositing and 2-D drawing in software, in the browser's own processes: with them on
      // SwiftShader's emulated GPU as well, the GPU process took more CPU than everything else
      // together (page.mjs: 196 s → 116 s on two cores). WebGL alone stays on SwiftShader.
      "--disable-gpu-compositing",
      "--disable-gpu-rasterization",
      "--disable-accelerated-2d-canvas",
    ],
  });
  return {
    context,
    close: async () => {
      await context.close().catch(() => {});
      rmSync(profile, { recursive: true, force: true });
    },
  };
}
