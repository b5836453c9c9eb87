// Builds the static site: node site.mjs PKG_DIR OUT_DIR
// PKG_DIR holds wasm-bindgen's output for crates/whipple-wasm's two builds (whipple_wasm.js and
// whipple_wasm_bg.wasm): first/ (the first view's endpoints) and whole/ (every endpoint, the
// feature all-routes); OUT_DIR receives a folder any static host serves:
//   index.html                     the page, answering its API in the browser (data-backend="wasm")
//   assets/app-HASH.js, .css       the page's code and style sheet (as `whipple serve`'s)
//   assets/worker-HASH.js          the Web Worker that runs the modules
//   assets/whipple-first-HASH.wasm the first view's endpoints compiled to WebAssembly
//   assets/whipple-HASH.wasm       whipple's whole API, loaded when a request needs it
//   assets/view3d-HASH.js, ...     code loaded later (three.js with the Simulation tab)
//   sw.js                          the service worker that keeps every file for offline use
//   manifest.json                  [{name, bytes, gzip, brotli, first}] of every file, for the size
//                                  budget (`first`: the first view loads it)
// Run by crates/whipple-wasm/build-site, which builds the module first.
import { build } from "esbuild";
import { createHash } from "node:crypto";
import { mkdirSync, readFileSync, readdirSync, rmSync, writeFileSync } from "node:fs";
import { dirname, join, relative, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { brotliCompressSync, constants, gzipSync } from "node:zlib";

const here = dirname(fileURLToPath(import.meta.url));
const web = here;
const pkg = resolve(process.argv[2] ?? "");
const out = resolve(process.argv[3] ?? join(web, "site"));
if (!process.argv[2]) throw new Error("usage: node site.mjs PKG_DIR OUT_DIR");
rmSync(out, { recursive: true, force: true });
const assets = join(out, "assets");
mkdirSync(assets, { recursive: true });

const hash = (bytes) => createHash("sha256").update(bytes).digest("hex").slice(0, 8).toUpperCase();

// The modules, under names that change with their content (cached for good).
const module = (build, stem) => {
  const wasm = readFileSync(join(pkg, build, "whipple_wasm_bg.wasm"));
  const name = `${stem}-${hash(wasm)}.wasm`;
  writeFileSync(join(assets, name), wasm);
  return name;
};
const wasmName = module("whole", "whipple");
const firstName = module("first", "whipple-first");

const common = {
  bundle: true,
  minify: true,
  format: "esm",
  target: ["es2020"],
  legalComments: "none",
  metafile: true,
  nodePaths: [join(here, "node_modules")],
  logLevel: "warning",
};

// The worker, with wasm-bindgen's glue.
const worker = await build({
  ...common,
  entryPoints: { worker: join(web, "src", "worker.js") },
  outdir: assets,
  entryNames: "[name]-[hash]",
  alias: { "whipple-wasm": join(pkg, "whole", "whipple_wasm.js"), "whipple-wasm-first": join(pkg, "first", "whipple_wasm.js") },
  define: { WHIPPLE_WASM: JSON.stringify(`./${wasmName}`), WHIPPLE_WASM_FIRST: JSON.stringify(`./${firstName}`) },
});
const workerName = Object.keys(worker.metafile.outputs).map((p) => resolve(p)).find((p) => p.endsWith(".js"));
if (!workerName) throw new Error("esbuild wrote no worker");

// The page: the same sources as the server's, told where its worker is.
const page = await build({
  ...common,
  entryPoints: { app: join(web, "src", "main.js") },
  outdir: assets,
  splitting: true,
  entryNames: "[name]-[hash]",
  chunkNames: "[name]-[hash]",
  define: { WHIPPLE_WORKER: JSON.stringify(`./${relative(assets, workerName)}`) },
});
const entry = Object.entries(page.metafile.outputs).find(([, o]) => o.entryPoint);
if (!entry?.[1].cssBundle) throw new Error("esbuild wrote no entry point or style sheet");
const script = relative(assets, resolve(entry[0]));
const style = relative(assets, resolve(entry[1].cssBundle));

let html = readFileSync(join(web, "index.html"), "utf8");
for (const [from, to] of [["/assets/app.js", `assets/${script}`], ["/assets/app.css", `assets/${style}`]]) {
  if (!html.includes(from)) throw new Error(`index.html does not name ${from}`);
  html = html.replaceAll(from, to);
}
if (!html.startsWith('<!doctype html>\n<html lang="en">')) throw new Error("index.html's <html> tag moved");
html = html.replace('<html lang="en">', '<html lang="en" data-backend="wasm">');
writeFileSync(join(out, "index.html"), html);

// Every file, for the service worker's cache and the size budget.
const files = [];
const walk = (dir) => {
  for (const name of readdirSync(dir, { withFileTypes: true })) {
    const path = join(dir, name.name);
    if (name.isDirectory()) walk(path);
    else if (!name.name.endsWith(".map")) files.push(relative(out, path));
  }
};
walk(out);
files.sort();
const version = hash(Buffer.from(files.map((f) => `${f}:${hash(readFileSync(join(out, f)))}`).join("\n")));
writeFileSync(join(out, "sw.js"), `// The static site's service worker (written by web/site.mjs): keeps every file of this
// version for offline use, answers from the cache first, and drops older versions' caches.
const CACHE = "whipple-${version}";
const FILES = ${JSON.stringify(["./", ...files.map((f) => `./${f}`)])};
self.addEventListener("install", (event) => {
  event.waitUntil(caches.open(CACHE).then((cache) => cache.addAll(FILES)).then(() => self.skipWaiting()));
});
self.addEventListener("activate", (event) => {
  event.waitUntil(caches.keys()
    .then((keys) => Promise.all(keys.filter((k) => k.startsWith("whipple-") && k !== CACHE).map((k) => caches.delete(k))))
    .then(() => self.clients.claim()));
});
self.addEventListener("fetch", (event) => {
  if (event.request.method !== "GET") return;
  event.respondWith(caches.open(CACHE).then((cache) =>
    cache.match(event.request, { ignoreSearch: true }).then((hit) => hit ?? fetch(event.request))));
});
`);
files.push("sw.js");

// What the first view loads: the page, its code and style, the worker and the first module
// (not the whole module, three.js or the service worker, which fetches the rest afterwards).
const firstView = (name) => name === "index.html" || /^assets\/(app|worker|whipple-first)-/.test(name);
const manifest = files.map((name) => {
  const bytes = readFileSync(join(out, name));
  const gzip = gzipSync(bytes, { level: 9 }).length;
  const brotli = brotliCompressSync(bytes, {
    params: { [constants.BROTLI_PARAM_QUALITY]: 11, [constants.BROTLI_PARAM_SIZE_HINT]: bytes.length },
  }).length;
  return { name, bytes: bytes.length, gzip, brotli, first: firstView(name) };
});
writeFileSync(join(out, "manifest.json"), `${JSON.stringify(manifest, null, 1)}\n`);
const total = (key, pick = () => true) => manifest.filter(pick).reduce((s, f) => s + f[key], 0);
const first = (f) => f.first;
console.log(`site: ${files.length} files in ${out}; first view ${(total("brotli", first) / 1024).toFixed(0)} KB brotli, ${(total("gzip", first) / 1024).toFixed(0)} KB gzip (all: ${(total("bytes") / 1024).toFixed(0)} KB)`);
