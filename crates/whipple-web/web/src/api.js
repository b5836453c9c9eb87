// The page's only contact with the server: the endpoints of /api/openapi.json.
import { during } from "./work.js";
import { answer, inBrowser } from "./backend.js";

/** An error answered by the API: {kind, message, field, rule} plus the HTTP status. */
export class ApiError extends Error {
  constructor(status, body) {
    super(body.message);
    this.status = status;
    this.kind = body.kind;
    this.field = body.field ?? null;
    this.rule = body.rule ?? null;
  }
}

/** One request, counted as work under way until its answer has been handled ([during]).
 * `options`: {signal} to cancel it (an ApiError of kind "cancelled" then), {onProgress(done,
 * total)} told how far long work is (a map's or a study's designs: the static site's worker tells
 * them, a server in the lines of its answer). */
function call(method, path, body, options = {}) {
  return during(() => request(method, path, body, options));
}

const cancelled = () => new ApiError(499, { kind: "cancelled", message: "cancelled" });

async function request(method, path, body, options) {
  if (inBrowser) {
    // The static site: the same request answered by the WebAssembly module (backend.js).
    const { status, text } = await answer(method, path, body === undefined ? undefined : JSON.stringify(body), options);
    let data = null;
    try {
      data = JSON.parse(text);
    } catch {
      data = null;
    }
    if (status !== 200) {
      throw new ApiError(status, data?.error ?? { kind: "http", message: `HTTP ${status}` });
    }
    return data;
  }
  // Long work asked with a progress hook is answered line by line: its progress, then the answer.
  const lines = options.onProgress !== undefined && method === "POST";
  const headers = body === undefined ? {} : { "content-type": "application/json" };
  if (lines) headers.accept = `${NDJSON}, application/json;q=0.5`;
  let response;
  try {
    response = await fetch(path, {
      method,
      headers,
      body: body === undefined ? undefined : JSON.stringify(body),
      // The server stops the work once nobody waits for its answer.
      signal: options.signal,
    });
  } catch (e) {
    if (options.signal?.aborted) throw cancelled();
    throw new ApiError(0, { kind: "network", message: `the server cannot be reached (${e.message}); is \`whipple serve\` still running?` });
  }
  if (lines && response.ok && response.headers.get("content-type")?.startsWith(NDJSON)) {
    return readLines(response, options);
  }
  const data = await response.json().catch(() => null);
  if (options.signal?.aborted) throw cancelled();
  if (!response.ok) {
    throw new ApiError(response.status, data?.error ?? { kind: "http", message: `HTTP ${response.status}` });
  }
  return data;
}

const NDJSON = "application/x-ndjson";

const cutOff = (why) => new ApiError(0, { kind: "network", message: `the server's answer was cut off (${why}); is \`whipple serve\` still running?` });

/** An answer told line by line: `{"progress": [done, total]}` lines told to `onProgress`, then
 * `{"status", "answer"}` or `{"status", "error"}`. A line (the answer's is megabytes) is joined
 * from its pieces once, not searched again as each piece arrives. */
async function readLines(response, options) {
  const reader = response.body.getReader();
  const decoder = new TextDecoder();
  let pieces = [];
  let last = null;
  const take = (line) => {
    const data = JSON.parse(line);
    if (Array.isArray(data.progress)) options.onProgress(...data.progress);
    else last = data;
  };
  try {
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      const parts = decoder.decode(value, { stream: true }).split("\n");
      for (const [k, part] of parts.entries()) {
        if (k === parts.length - 1) {
          if (part) pieces.push(part);
        } else {
          pieces.push(part);
          take(pieces.join(""));
          pieces = [];
        }
      }
    }
  } catch (e) {
    if (options.signal?.aborted) throw cancelled();
    throw cutOff(e.message);
  }
  if (options.signal?.aborted) throw cancelled();
  if (!last || pieces.length > 0) throw cutOff("its last line is missing");
  if (last.status !== 200) throw new ApiError(last.status, last.error ?? { kind: "http", message: `HTTP ${last.status}` });
  return last.answer;
}

export const api = {
  presets: () => call("GET", "/api/presets"),
  /** The library's parameter table: {benchmark: [...], jbike6: [...]} with units and meanings. */
  parameters: () => call("GET", "/api/parameters"),
  preset: (name) => call("GET", `/api/presets/${encodeURIComponent(name)}`),
  validate: (bike) => call("POST", "/api/bike/validate", { bike }),
  eigen: (bike, speeds) => call("POST", "/api/eigen", { bike, speeds }),
  /** `units`: the units a file typed its keys in ({c: "mm"}, as `parse` gave them), written back so. */
  toml: (bike, units) => call("POST", "/api/bike/toml", units && Object.keys(units).length ? { bike, units } : { bike }),
  /** A file's text in `format` (or "auto": told from `fileName` and the text). */
  parse: (text, format, fileName) => call("POST", "/api/bike/parse", { text, format, file_name: fileName }),
  /** `request`: {bike, speed, lean_deg, steer_deg, lean_rate, steer_rate, duration, ...}. */
  simulate: (request) => call("POST", "/api/simulate", request),
  /** A design map: `request` {bike, x, y, speed?} with axes NAME=START:STOP:COUNT. */
  map: (request, options) => call("POST", "/api/map", request, options),
  /** A one-parameter study: `request` {bike, x, speed?}, as /api/map without y. */
  study: (request, options) => call("POST", "/api/study", request, options),
  /** One design of a map, `request` {bike, x, y, index}: {bike} in the files' JSON layout. */
  mapDesign: (request) => call("POST", "/api/map/design", request),
  /** Exact sensitivities of v_w, v_c and the stable width to every parameter; σ of the speeds. */
  sensitivity: (bike) => call("POST", "/api/sensitivity", { bike }),
  /** The eigenmodes at one speed: {modes: [{mode, eigenvalue: [re, im], eigenvector}]}. */
  modes: (bike, speed) => call("POST", "/api/modes", { bike, speed }),
  /** A held steady turn of the non-linear bicycle, `request` {bike, speed, lean_deg | steer_deg |
   * radius}: {turn, lean_deg, steer_deg, stability} (SI and radians, degrees beside). */
  turn: (request) => call("POST", "/api/turn", request),
  /** The linear model's free response: `request` as /api/simulate's initial numbers. */
  linearResponse: (request) => call("POST", "/api/linear/response", request),
  /** One input → output pair at a few speeds, `request` {bike, speeds, input, output,
   * frequencies: {start, stop, count}}: per speed the poles, zeros, gains and Bode data. */
  frequency: (request) => call("POST", "/api/linear/frequency", request),
  /** The linear model's exact time response, `request` {bike, speed, kind, input, amplitude,
   * pulse_duration, lean_deg, duration, samples, nonlinear}: lean, steer, yaw, the ground path;
   * with nonlinear, the same manoeuvre on the non-linear model and the difference. */
  time: (request) => call("POST", "/api/linear/time", request),
  /** The bicycle under feedback u = r − K x, `request` {bike, inputs, gains | lqr: {q, r, speed |
   * scheduled}, speeds}: the gain used, the closed loop's eigenvalues in /api/eigen's shape and
   * its certified critical speeds. */
  closedLoop: (request) => call("POST", "/api/linear/closed_loop", request),
  /** The bicycle ridden by Hess's controller, `request` {bike, speed, lane: "single" | "double",
   * speeds: {start, stop, step}}: the gains by Hess 2012's rules at `speed`, HumanControl's lane
   * change on the linear and the non-linear bicycle, and the certified peak HQM at every speed. */
  ridden: (request) => call("POST", "/api/ridden", request),
  /** Bench measurements to a bicycle, `request` {text, file_name} (a *Measured.txt) or
   * {measurements: {key: {value, sigma}}, name}: {name, bike, parameters, steps, measurements,
   * other, correlations, warnings}. */
  measure: (request) => call("POST", "/api/measure", request),
  /** The Measure tab's samples: [{name, title, file_name, source, text}]. */
  measureSamples: () => call("GET", "/api/measure/samples"),
};
