// Work under way, for whoever must wait until the page has settled (the e2e tests): a count
// written to <body data-pending="N"> of the requests in flight, the recompute scheduled and the
// handlers running. A piece of work is released one task after it ends, so that what its
// awaiting code starts at once (the next request, a redraw) is counted before it: "0" means the
// page has settled and nothing it was asked to do is still coming.

let pending = 0;

function set(delta) {
  pending += delta;
  document.body.dataset.pending = String(pending);
}

/** Counts one piece of work started now; `end()` releases it. */
export function begin() {
  set(1);
  let ended = false;
  return function end() {
    if (ended) return;
    ended = true;
    setTimeout(() => set(-1), 0);
  };
}

/** Runs `body` (async) counted as work under way, and returns what it returns. */
export async function during(body) {
  const end = begin();
  try {
    return await body();
  } finally {
    end();
  }
}
