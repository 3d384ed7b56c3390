// The rack-and-pinion form as data: its fields (JSON pointer, label, kind),
// the paper's case it starts from, the text of each field's hint, and the
// conversions between what a person types and the job document. Pure (no
// DOM): unit-tested in Node.
import { limitsText, nodeAt, setPointer } from "./schema.js";

export const GROUPS = [
  ["Job", [
    { pointer: "/name", label: "Name", type: "text" },
  ]],
  ["Pinion", [
    { pointer: "/scene/pinion/module_mm", label: "Module" },
    { pointer: "/scene/pinion/teeth", label: "Teeth", step: 1 },
    { pointer: "/scene/pinion/pressure_angle_deg", label: "Pressure angle" },
    { pointer: "/scene/pinion/face_width_mm", label: "Face width" },
    { pointer: "/scene/pinion/profile_shift", label: "Profile shift" },
    { pointer: "/scene/pinion/omega_rad_s", label: "Speed ω" },
    { pointer: "/scene/pinion/modelled_teeth", label: "Modelled teeth", type: "teeth" },
  ]],
  ["Rack", [
    { pointer: "/scene/rack/velocity_m_s", label: "Initial velocity" },
    { pointer: "/scene/rack/load_N", label: "Load" },
    { pointer: "/scene/rack/modelled_teeth", label: "Modelled teeth", type: "teeth" },
  ]],
  ["Material (both bodies)", [
    { pointer: "/scene/material/E_Pa", label: "Young's modulus E" },
    { pointer: "/scene/material/nu", label: "Poisson's ratio ν" },
    { pointer: "/scene/material/rho_kg_m3", label: "Density ρ" },
  ]],
  // A static check whose materials carry strength is rated (docs/rating.md).
  ["Strength (ISO 6336-5, for the rating)", [
    { pointer: "/scene/material/iso6336_5/class", label: "Class", type: "enum", optional: true },
    { pointer: "/scene/material/iso6336_5/quality", label: "Quality", type: "enum", optional: true },
    { pointer: "/scene/material/iso6336_5/steel", label: "Steel (V, V(cast))", type: "enum", optional: true },
    { pointer: "/scene/material/iso6336_5/hardness_HB", label: "Hardness HB", placeholder: "St, GTS, GJS, GJL", optional: true },
    { pointer: "/scene/material/iso6336_5/hardness_HV", label: "Hardness HV", placeholder: "V, Eh, IF, NT, NV", optional: true },
    { pointer: "/scene/material/sigma_Hlim_Pa", label: "σ_Hlim", placeholder: "from the class", optional: true },
    { pointer: "/scene/material/sigma_Flim_Pa", label: "σ_Flim", placeholder: "from the class", optional: true },
    { pointer: "/scene/material/yield_Pa", label: "Yield strength", optional: true },
  ]],
  ["Discretisation and method", [
    { pointer: "/discretization/spacing_mm", label: "Particle spacing" },
    { pointer: "/discretization/kernel", label: "Kernel", type: "enum" },
    { pointer: "/method/formulation", label: "Formulation", type: "enum" },
    { pointer: "/method/contact/model", label: "Contact model", type: "enum" },
    // Off: nothing sent (the schema's default, a dynamic run).
    { pointer: "/scene/quasi_static", label: "Quasi-static (static check)", type: "bool" },
  ]],
  ["Time and output", [
    { pointer: "/time/end_s", label: "End time" },
    { pointer: "/time/dt_s", label: "Time step", placeholder: "automatic" },
    { pointer: "/output/frames", label: "Frames", step: 1 },
  ]],
];
// The root crack (docs/cracks.md, "The gear"): a section of its own, shown
// for a quasi-static job and sent only while its box is ticked, so that a
// hidden or unticked section leaves the job as it was. Each field shows the
// schema's description in full: the limits depend on the spacing and the
// tooth, which a range cannot say.
export const CRACK_SECTION = "crack";
export const CRACK_GROUP = ["Root crack", [
  { pointer: "/scene/crack/fillet_position", label: "Start on the tension fillet", type: "position", initial: "peak", section: CRACK_SECTION, describe: true },
  { pointer: "/scene/crack/length_mm", label: "Initial length", placeholder: "required", section: CRACK_SECTION, describe: true },
  { pointer: "/scene/crack/angle_deg", label: "Angle to the fillet's normal", section: CRACK_SECTION, describe: true },
  { pointer: "/scene/crack/increment_mm", label: "Increment", placeholder: "4 spacings", section: CRACK_SECTION, describe: true },
  { pointer: "/scene/crack/max_increments", label: "Increments at most", step: 1, section: CRACK_SECTION, describe: true },
  { pointer: "/scene/crack/paris/C", label: "Paris C", unit: "m/cycle", placeholder: "no life", optional: true, section: CRACK_SECTION, describe: true },
  { pointer: "/scene/crack/paris/m", label: "Paris exponent m", optional: true, section: CRACK_SECTION, describe: true },
  { pointer: "/scene/pinion/backup_ratio", label: "Backup ratio m_B", placeholder: "rim_depth_mm", optional: true, section: CRACK_SECTION, describe: true },
]];
export const FIELDS = [...GROUPS, CRACK_GROUP].flatMap(([, f]) => f);
export const PAPER_CASE = { name: "paper-base-case", scene: { type: "rack_pinion" } };

export function fieldId(pointer) {
  return "f" + pointer.replace(/\//g, "-");
}

// Numbers of a million and more are shown as 1.73e11, not 173000000000.
export function formText(v) {
  if (v === undefined || v === null) return "";
  if (typeof v === "number" && Math.abs(v) >= 1e6) return v.toExponential().replace("e+", "e");
  return String(v);
}

// The schema's node of a field, the default it shows (its own, or the one
// its enclosing object gives it: the material's, say) and its description.
export function fieldSchema(schema, pointer) {
  const node = nodeAt(schema, pointer);
  const parent = nodeAt(schema, pointer.replace(/\/[^/]*$/, ""));
  const key = pointer.split("/").pop();
  const def = node?.default !== undefined ? node.default
    : parent?.default && typeof parent.default === "object" ? parent.default[key] : undefined;
  // A member the schema does not describe (Paris' C) is described by its object.
  return { node, def, description: node?.description || parent?.description || "" };
}

// "range 6 to 300 · default 12" under a field.
export function hintText(node, def, spec) {
  // A field of one of several forms (a number or "peak"): each form's limits.
  const limits = limitsText(node) || (node?.anyOf || [])
    .map((n) => (n.const !== undefined ? JSON.stringify(n.const) : limitsText(n))).filter(Boolean).join(" or ");
  const showDefault = def !== undefined && typeof def !== "object" && spec.type !== "text" && spec.type !== "bool";
  const text = [limits && `range ${limits}`, showDefault && `default ${formText(def)}`].filter(Boolean).join(" · ");
  return text || (node?.description || "").slice(0, 80);
}

// What a person typed, as the job holds it: numbers as numbers (else the
// text, which the server then refuses at the field), "auto" or a count for
// the modelled teeth, text as text.
export function parseValue(raw, spec) {
  if (spec.type === "teeth") return /^-?\d+$/.test(raw) ? Number(raw) : raw;
  if (spec.type === "bool") return raw === "true";
  if (spec.type === "text" || spec.type === "enum") return raw;
  return Number.isFinite(Number(raw)) ? Number(raw) : raw;
}

// The job of the form: [[spec, raw text]]; empty fields are left to the
// scene, and so are the fields of a section not in `sections` ({crack: true}).
// A checkbox reads "true" when ticked, "" when not.
export function jobFromValues(entries, sections = {}) {
  const job = { scene: { type: "rack_pinion" } };
  for (const [spec, text] of entries) {
    if (spec.section && !sections[spec.section]) continue;
    const raw = text.trim();
    if (raw !== "") setPointer(job, spec.pointer, parseValue(raw, spec));
  }
  return job;
}

// The form field a problem's pointer concerns: itself, the field standing
// for it, or the first field inside it; null if none.
export function fieldPointerFor(pointer, pointers) {
  if (pointers.includes(pointer)) return pointer;
  if (pointer === "/discretization" || pointer.startsWith("/discretization/spacing")) {
    return pointers.includes("/discretization/spacing_mm") ? "/discretization/spacing_mm" : null;
  }
  if (pointer === "/time/cfl") return pointers.includes("/time/dt_s") ? "/time/dt_s" : null;
  if (pointer === "") return null;
  return pointers.find((p) => p.startsWith(pointer + "/")) ?? null;
}
