// Bundles the page: node build.mjs [WEB_DIR] [OUT_DIR]
// WEB_DIR holds index.html and src/ (default: this script's directory); OUT_DIR receives
// index.html, app.js and app.css (default: WEB_DIR/dist). Run by crates/whipple-web/build.rs.
import { build } from "esbuild";
import { copyFileSync, mkdirSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const web = resolve(process.argv[2] ?? dirname(fileURLToPath(import.meta.url)));
const out = resolve(process.argv[3] ?? join(web, "dist"));
mkdirSync(out, { recursive: true });

await build({
  entryPoints: { app: join(web, "src", "main.js") },
  outdir: out,
  bundle: true,
  minify: true,
  format: "esm",
  target: ["es2020"],
  legalComments: "none",
  // The page's imports (three) resolve from the node_modules beside this script (build.rs
  // installs them in OUT_DIR/npm), not from the source tree, which has none in a fresh clone.
  nodePaths: [join(dirname(fileURLToPath(import.meta.url)), "node_modules")],
  logLevel: "warning",
});
copyFileSync(join(web, "index.html"), join(out, "index.html"));
