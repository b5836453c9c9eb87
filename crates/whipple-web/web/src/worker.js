// A Web Worker of the static site: loads whipple's WebAssembly module once and answers the
// page's API requests with it (see backend.js), one at a time, in the order asked.
/* global WHIPPLE_WASM */
import init, { call } from "whipple-wasm";

const ready = init({ module_or_path: new URL(WHIPPLE_WASM, import.meta.url) });

self.onmessage = async ({ data: { id, method, path, body } }) => {
  let status;
  let bytes;
  try {
    await ready;
    const reply = call(method, path, body);
    status = reply.status;
    bytes = reply.body;
    reply.free();
  } catch (e) {
    // The module could not load, or trapped: say so as the API says everything.
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
