// The static site's back end: the API answered in the browser by whipple's WebAssembly module
// (crates/whipple-wasm), the same handlers `whipple serve` runs, in Web Workers so that the page
// never waits on them. Two workers, as the server has two budgets: one for the work the page
// asks for as one types (validate, critical speeds, modes, short sweeps) and one for heavy work
// (maps, studies, simulations, sensitivities, responses), so that a map never holds up typing.
// The site's build names the worker's file (WHIPPLE_WORKER); the server's page never loads it.

/* global WHIPPLE_WORKER */
const WORKER = typeof WHIPPLE_WORKER === "string" ? WHIPPLE_WORKER : null;

/** Whether this page answers its API in the browser (the static site). */
export const inBrowser = WORKER !== null && document.documentElement.dataset.backend === "wasm";

// Heavy endpoints, as the server's budgets sort them (crates/whipple-web/src/api.rs routes()):
// only a choice of worker, never of answer.
const HEAVY = new Set([
  "/api/map", "/api/study", "/api/simulate", "/api/sensitivity", "/api/linear/response",
  "/api/linear/time", "/api/ridden",
]);

class Lane {
  constructor(name) {
    this.name = name;
    this.worker = null;
    this.next = 1;
    // id → {request, resolve, onProgress}: the requests posted to the worker and not answered.
    this.waiting = new Map();
  }

  start() {
    const worker = new Worker(new URL(WORKER, import.meta.url), { type: "module", name: `whipple ${this.name}` });
    worker.onmessage = ({ data }) => {
      const done = this.waiting.get(data.id);
      if (data.progress) {
        done?.onProgress?.(...data.progress);
        return;
      }
      if (done) {
        this.waiting.delete(data.id);
        done.resolve(data);
      }
      // The module trapped: that worker has ended; what it still held is answered, and the
      // next request starts a fresh one.
      if (data.broken) this.fail("the computation stopped in the browser; try again");
    };
    // A trap in the module (out of memory, a bug) ends the worker's state: every request it
    // held is answered with an error and the next one starts a fresh worker.
    worker.onerror = (event) => {
      event.preventDefault?.();
      this.fail(`the computation stopped in the browser (${event.message || "the WebAssembly module failed"})`);
    };
    this.worker = worker;
  }

  fail(message) {
    this.worker?.terminate();
    this.worker = null;
    const body = new TextEncoder().encode(JSON.stringify({ error: { kind: "internal", message, field: null, rule: null } }));
    for (const [, done] of this.waiting) done.resolve({ status: 500, body });
    this.waiting.clear();
  }

  /** Stops request `id`: its worker ends at once (a module cannot be interrupted otherwise), the
   * request is answered as cancelled, and the others it held are asked again of a fresh one. */
  cancel(id) {
    const done = this.waiting.get(id);
    if (!done) return;
    this.waiting.delete(id);
    this.worker?.terminate();
    this.worker = null;
    const body = new TextEncoder().encode(JSON.stringify({ error: { kind: "cancelled", message: "cancelled", field: null, rule: null } }));
    done.resolve({ status: 499, body });
    if (this.waiting.size === 0) return;
    this.start();
    for (const [other, { request }] of this.waiting) this.worker.postMessage({ id: other, ...request, body: request.body.slice() });
  }

  call(method, path, body, { signal, onProgress } = {}) {
    if (!this.worker) this.start();
    const id = this.next++;
    return new Promise((resolve) => {
      // A copy stays here, should the request have to be asked again (cancel).
      const request = { method, path, body };
      this.waiting.set(id, { request, resolve, onProgress });
      signal?.addEventListener("abort", () => this.cancel(id), { once: true });
      this.worker.postMessage({ id, method, path, body: body.slice() });
    });
  }
}

const lanes = { interactive: new Lane("interactive"), heavy: new Lane("heavy") };

/** The last requests answered here, "METHOD /path" (at most 200), for whoever checks what the
 * page asks (the e2e tests read it as they read a server's requests). */
const asked = [];
globalThis.whippleAsked = asked;

/** One request answered in the browser: {status, text}, as a server's answer would be.
 * `options`: {signal} (an AbortSignal: a request aborted is answered 499, kind "cancelled"),
 * {onProgress(done, total)} (long work's progress, a map's designs). */
export async function answer(method, path, bodyText, options = {}) {
  asked.push(`${method} ${path}`);
  if (asked.length > 200) asked.splice(0, asked.length - 200);
  const lane = HEAVY.has(path) ? lanes.heavy : lanes.interactive;
  const body = bodyText === undefined ? new Uint8Array(0) : new TextEncoder().encode(bodyText);
  if (options.signal?.aborted) return { status: 499, text: JSON.stringify({ error: { kind: "cancelled", message: "cancelled", field: null, rule: null } }) };
  const reply = await lane.call(method, path, body, options);
  return { status: reply.status, text: new TextDecoder().decode(reply.body) };
}

// In the static site, the page's own address answers the API as `whipple serve` would, for any
// code in the page that asks it directly (a console, a notebook in the page, the e2e tests):
// fetch("/api/eigen", {method: "POST", body}) is answered by the module, not the network.
if (inBrowser) {
  const network = globalThis.fetch.bind(globalThis);
  globalThis.fetch = async (input, init = {}) => {
    const request = input instanceof Request ? input : null;
    const url = new URL(request ? request.url : String(input), location.href);
    if (url.origin !== location.origin || !/^\/api\//.test(url.pathname)) return network(input, init);
    const method = (init.method ?? request?.method ?? "GET").toUpperCase();
    let body = init.body ?? (request && method !== "GET" ? await request.text() : undefined);
    if (body !== undefined && typeof body !== "string") body = await new Response(body).text();
    const signal = init.signal ?? request?.signal;
    const { status, text } = await answer(method, url.pathname, body, { signal });
    // Aborted, it rejects as a fetch does.
    if (signal?.aborted) throw new DOMException("The operation was aborted.", "AbortError");
    return new Response(text, { status, headers: { "content-type": "application/json" } });
  };
}
