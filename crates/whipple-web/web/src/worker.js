// A Web Worker of the static site: answers the page's API requests with whipple's WebAssembly
// modules (see backend.js), one at a time, in the order asked. The site has two builds of the
// module (crates/whipple-wasm): the first, small, answers the endpoints of the page's first
// view and says which those are (`answers`); the whole one answers every endpoint and is
// loaded only when a request needs it, so that a first visit does not wait for it.
/* global WHIPPLE_WASM, WHIPPLE_WASM_FIRST */
import initFirst, { answers, call as callFirst } from "whipple-wasm-first";
import initWhole, { call as callWhole } from "whipple-wasm";

let first = null;
let whole = null;
const firstReady = () => (first ??= initFirst({ module_or_path: new URL(WHIPPLE_WASM_FIRST, import.meta.url) }));
const wholeReady = () => (whole ??= initWhole({ module_or_path: new URL(WHIPPLE_WASM, import.meta.url) }));

/** The module's `call` that answers `path`: the first module's when it holds it. */
async function caller(path) {
  await firstReady();
  if (answers(path)) return callFirst;
  await wholeReady();
  return callWhole;
}

self.onmessage = async ({ data: { id, method, path, body } }) => {
  let status;
  let bytes;
  try {
    const call = await caller(path);
    // Long work (a map's designs) says how far it is; the page shows it.
    const progress = (done, total) => self.postMessage({ id, progress: [done, total] });
    const reply = call(method, path, body, progress);
    status = reply.status;
    bytes = reply.body;
    reply.free();
  } catch (e) {
    // A module could not load, or trapped: say so as the API says everything.
    status = 500;
    bytes = new TextEncoder().encode(JSON.stringify({
      error: { kind: "internal", message: `the computation failed in the browser: ${e?.message ?? e}`, field: null, rule: null },
    }));
    // A trapped module cannot be trusted again: this worker ends; the page starts another.
    self.postMessage({ id, status, body: bytes, broken: true }, [bytes.buffer]);
    self.close();
    return;
  }
  self.postMessage({ id, status, body: bytes }, [bytes.buffer]);
};
