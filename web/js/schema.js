// The job schema (GET /schema) as the form needs it: the definition behind
// a JSON pointer, its limits, default, unit and description.

function deref(schema, node) {
  let n = node;
  for (let guard = 0; n && n.$ref && guard < 10; guard++) {
    const path = n.$ref.replace(/^#\//, "").split("/");
    let target = schema;
    for (const p of path) target = target?.[p];
    // Keep the referring node's own keywords (default, description).
    const { $ref, ...own } = n;
    n = { ...target, ...own };
  }
  return n;
}

// The schema node of a pointer inside a job of scene type `sceneType`.
export function nodeAt(schema, pointer, sceneType = "rack_pinion") {
  const parts = pointer.split("/").slice(1);
  let node = schema;
  for (let i = 0; i < parts.length && node; i++) {
    const key = parts[i];
    if (node === schema && key === "scene") {
      node = deref(schema, schema.definitions[sceneType]);
      continue;
    }
    node = deref(schema, node.properties?.[key]);
  }
  return node || null;
}

// "6 – 300", "> 0, ≤ 100", "one of …".
const num = (v) => (Math.abs(v) >= 1e5 ? v.toExponential().replace("e+", "e") : String(v));

export function limitsText(node) {
  if (!node || node.enum) return "";
  const lo = node.exclusiveMinimum !== undefined ? `> ${num(node.exclusiveMinimum)}`
    : node.minimum !== undefined ? `≥ ${num(node.minimum)}` : null;
  const hi = node.exclusiveMaximum !== undefined ? `< ${num(node.exclusiveMaximum)}`
    : node.maximum !== undefined ? `≤ ${num(node.maximum)}` : null;
  // Both bounds included reads best as "6 to 300".
  if (lo?.startsWith("≥") && hi?.startsWith("≤")) return `${lo.slice(2)} to ${hi.slice(2)}`;
  return [lo, hi].filter(Boolean).join(", ");
}

// The unit a field name carries (module_mm -> mm, E_Pa -> Pa).
export function unitOf(pointer) {
  const key = pointer.split("/").pop();
  const units = [
    ["_rad_s", "rad/s"], ["_m_s", "m/s"], ["_kg_m3", "kg/m³"], ["_mm2_s", "mm²/s"], ["_deg", "°"],
    ["_mm", "mm"], ["_um", "µm"], ["_N_m", "N·m"], ["_rpm", "rpm"], ["_Pa", "Pa"], ["_N", "N"],
    ["_s", "s"], ["_h", "h"], ["_m", "m"],
  ];
  for (const [suffix, unit] of units) if (key.endsWith(suffix)) return unit;
  return "";
}

export function getPointer(doc, pointer) {
  let v = doc;
  for (const p of pointer.split("/").slice(1)) {
    if (v === null || typeof v !== "object") return undefined;
    v = v[p];
  }
  return v;
}

// Makes the objects on the way, an array where the next key is an index
// (/gears/0/teeth).
export function setPointer(doc, pointer, value) {
  const parts = pointer.split("/").slice(1);
  let v = doc;
  parts.slice(0, -1).forEach((p, i) => {
    if (typeof v[p] !== "object" || v[p] === null) v[p] = /^\d+$/.test(parts[i + 1]) ? [] : {};
    v = v[p];
  });
  v[parts[parts.length - 1]] = value;
}
