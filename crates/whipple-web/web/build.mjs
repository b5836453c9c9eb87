// Bundles the page: node build.mjs [WEB_DIR] [OUT_DIR]
// WEB_DIR holds index.html and src/ (default: this script's directory); OUT_DIR receives
// (default: WEB_DIR/dist):
//   index.html                      the page, naming the hashed assets below
//   app-HASH.js, app-HASH.css       the initial script and style sheet
//   view3d-HASH.js, chunk-HASH.js   code loaded later (three.js, only when a 3-D view opens)
//   NAME.gz, NAME.br                every file above, compressed (gzip -9, brotli quality 11)
//   manifest.json                   [{name, type, hash, immutable, bytes, gzip, brotli}]
//   assets.rs                       the same list as Rust (`Asset` values with include_bytes!)
// Run by crates/whipple-web/build.rs; src/assets.rs includes assets.rs and serves the files.
import { build } from "esbuild";
import { createHash } from "node:crypto";
import { mkdirSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { basename, dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { brotliCompressSync, constants, gzipSync } from "node:zlib";

const here = dirname(fileURLToPath(import.meta.url));
const web = resolve(process.argv[2] ?? here);
const out = resolve(process.argv[3] ?? join(web, "dist"));
rmSync(out, { recursive: true, force: true });
mkdirSync(out, { recursive: true });

const result = await build({
  entryPoints: { app: join(web, "src", "main.js") },
  outdir: out,
  bundle: true,
  minify: true,
  // Dynamic import() of view3d.js becomes its own file: three.js loads only when asked for.
  splitting: true,
  format: "esm",
  target: ["es2020"],
  entryNames: "[name]-[hash]",
  chunkNames: "[name]-[hash]",
  legalComments: "none",
  metafile: true,
  // The page's imports (three) resolve from the node_modules beside this script (build.rs
  // installs them in OUT_DIR/npm), not from the source tree, which has none in a fresh clone.
  nodePaths: [join(here, "node_modules")],
  logLevel: "warning",
});

const outputs = Object.keys(result.metafile.outputs).map((p) => resolve(p));
const entry = Object.entries(result.metafile.outputs).find(([, o]) => o.entryPoint);
if (!entry) throw new Error("esbuild wrote no entry point");
const script = basename(entry[0]);
const style = entry[1].cssBundle ? basename(entry[1].cssBundle) : null;
if (!style) throw new Error("esbuild wrote no style sheet");

let page = readFileSync(join(web, "index.html"), "utf8");
for (const [from, to] of [["/assets/app.js", `/assets/${script}`], ["/assets/app.css", `/assets/${style}`]]) {
  if (!page.includes(from)) throw new Error(`index.html does not name ${from}`);
  page = page.replaceAll(from, to);
}
writeFileSync(join(out, "index.html"), page);

const TYPES = { ".js": "text/javascript; charset=utf-8", ".css": "text/css; charset=utf-8", ".html": "text/html; charset=utf-8" };
const manifest = [];
for (const path of [join(out, "index.html"), ...outputs]) {
  const name = basename(path);
  const ext = name.slice(name.lastIndexOf("."));
  const type = TYPES[ext];
  if (!type) continue; // source maps and the like are not served
  const bytes = readFileSync(path);
  const gzip = gzipSync(bytes, { level: 9 });
  const brotli = brotliCompressSync(bytes, {
    params: { [constants.BROTLI_PARAM_QUALITY]: 11, [constants.BROTLI_PARAM_SIZE_HINT]: bytes.length },
  });
  writeFileSync(`${path}.gz`, gzip);
  writeFileSync(`${path}.br`, brotli);
  manifest.push({
    name,
    type,
    // The content's own hash, for the ETag (the file name's hash is esbuild's).
    hash: createHash("sha256").update(bytes).digest("base64url").slice(0, 22),
    // Hashed names never change content: they may be cached for good.
    immutable: name !== "index.html",
    bytes: bytes.length,
    gzip: gzip.length,
    brotli: brotli.length,
  });
}
writeFileSync(join(out, "manifest.json"), `${JSON.stringify(manifest, null, 1)}\n`);

// The Rust table src/assets.rs includes: one `Asset` per file, bodies embedded.
const lit = (s) => JSON.stringify(s);
const rows = manifest.map((a) => {
  const file = join(out, a.name);
  return `    Asset {
        name: ${lit(a.name)},
        content_type: ${lit(a.type)},
        hash: ${lit(a.hash)},
        immutable: ${a.immutable},
        identity: include_bytes!(${lit(file)}),
        gzip: include_bytes!(${lit(`${file}.gz`)}),
        brotli: include_bytes!(${lit(`${file}.br`)}),
    },`;
});
writeFileSync(join(out, "assets.rs"), `// Written by web/build.mjs: the page's files, embedded.\npub(crate) static ASSETS: &[Asset] = &[\n${rows.join("\n")}\n];\n`);
