// The user's own designs, kept in this browser's localStorage.

const KEY = "whipple.designs.v1";

/** Every saved design: [{id, name, bike, saved}] (newest first). */
export function listDesigns() {
  try {
    const value = JSON.parse(localStorage.getItem(KEY) ?? "[]");
    return Array.isArray(value) ? value.filter((d) => d && d.id && d.bike) : [];
  } catch {
    return [];
  }
}

function writeAll(designs) {
  localStorage.setItem(KEY, JSON.stringify(designs));
}

/** Saves (or replaces, by id) a design and returns it; `units` (optional) are the units its file
 * typed keys in ({c: "mm"}), which Save TOML writes them in again. */
export function saveDesign({ id, name, bike, units }) {
  const designs = listDesigns();
  const design = { id: id ?? `d${Date.now().toString(36)}${Math.random().toString(36).slice(2, 6)}`, name, bike, ...(units && Object.keys(units).length ? { units } : {}), saved: new Date().toISOString() };
  const rest = designs.filter((d) => d.id !== design.id);
  writeAll([design, ...rest]);
  return design;
}

export function deleteDesign(id) {
  writeAll(listDesigns().filter((d) => d.id !== id));
}

export function findDesign(id) {
  return listDesigns().find((d) => d.id === id) ?? null;
}
