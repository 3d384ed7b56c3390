// The rating calculator's form as data (POST /rating, schemas/rating.schema.json):
// its fields (JSON pointer, label, kind), ISO/TR 6336-30's Example 1 it can
// start from, and the conversions between what a person types and the
// rating document. Pure (no DOM): unit-tested in Node against the schema
// and the shipped example, so neither can drift from these.
import { setPointer } from "./schema.js";
import { formText } from "./submit-fields.js";

// The pair, the load and the required safeties, one field each.
export const PAIR_GROUPS = [
  ["Pair", [
    { pointer: "/name", label: "Name", type: "text" },
    { pointer: "/pair/type", label: "Pair", type: "enum", options: ["external", "rack"], def: "external" },
    { pointer: "/pair/normal_module_mm", label: "Normal module m_n" },
    { pointer: "/pair/pressure_angle_deg", label: "Pressure angle α_n", def: 20 },
    { pointer: "/pair/helix_angle_deg", label: "Helix angle β", def: 0 },
    { pointer: "/pair/face_width_mm", label: "Face width b" },
    { pointer: "/pair/center_distance_mm", label: "Centre distance a_w", placeholder: "from the shifts" },
    { pointer: "/pair/accuracy_grade", label: "ISO 1328-1 grade", def: 6, step: 1 },
    { pointer: "/pair/tip_relief_um", label: "Tip relief C_a", placeholder: "C_ay" },
    { pointer: "/pair/basic_rack/addendum_coef", label: "Tool h_aP*", def: 1 },
    { pointer: "/pair/basic_rack/dedendum_coef", label: "Tool h_fP*", def: 1.25 },
    { pointer: "/pair/basic_rack/root_radius_coef", label: "Tool ρ_fP*", def: 0.38 },
    { pointer: "/pair/F_betax_um", label: "Misalignment F_βx", placeholder: "stiff shaft, grade" },
    { pointer: "/pair/K_Hbeta", label: "K_Hβ (if known)", placeholder: "from F_βx" },
  ]],
  ["Load and requirements", [
    { pointer: "/load/torque_N_m", label: "Pinion torque T_1" },
    { pointer: "/load/speed_rpm", label: "Pinion speed n_1" },
    { pointer: "/load/life_h", label: "Required life", def: 20000 },
    { pointer: "/load/application_factor", label: "Application factor K_A", def: 1 },
    { pointer: "/load/static_torque_N_m", label: "Static (misuse) torque", placeholder: "K_A T_1" },
    { pointer: "/lubricant/nu40_mm2_s", label: "Oil viscosity ν_40", def: 220 },
    { pointer: "/required_safety/S_H", label: "Required S_H", def: 1 },
    { pointer: "/required_safety/S_F", label: "Required S_F", def: 1.4 },
    { pointer: "/life_factors/long_life", label: "Past the knee", type: "enum", options: ["reduced", "optimum"], def: "reduced" },
  ]],
];

export const CLASSES = ["St", "St(cast)", "GTS", "GJS", "GJL", "V", "V(cast)", "Eh", "IF", "NT", "NV(nitr)", "NV(nitrocar)"];

// One gear's fields, below /gears/0 (the pinion) or /gears/1 (the wheel).
export const GEAR_FIELDS = [
  { key: "/teeth", label: "Teeth z", step: 1 },
  { key: "/profile_shift", label: "Profile shift x", def: 0 },
  { key: "/flank_Rz_um", label: "Flank roughness R_z", def: 6 },
  { key: "/root_Rz_um", label: "Root roughness R_z", def: 10 },
  { key: "/material/E_Pa", label: "Young's modulus E" },
  { key: "/material/nu", label: "Poisson's ratio ν" },
  { key: "/material/rho_kg_m3", label: "Density ρ" },
  { key: "/material/iso6336_5/class", label: "ISO 6336-5 class", type: "enum", options: CLASSES, optional: true },
  { key: "/material/iso6336_5/quality", label: "Quality", type: "enum", options: ["ML", "MQ", "ME"], optional: true },
  { key: "/material/iso6336_5/steel", label: "Steel (V, V(cast))", type: "enum", options: ["carbon", "alloy"], optional: true },
  { key: "/material/iso6336_5/hardness_HB", label: "Hardness HB", placeholder: "St, GTS, GJS, GJL" },
  { key: "/material/iso6336_5/hardness_HV", label: "Hardness HV", placeholder: "V, Eh, IF, NT, NV" },
  { key: "/material/sigma_Hlim_Pa", label: "σ_Hlim", placeholder: "from the class" },
  { key: "/material/sigma_Flim_Pa", label: "σ_Flim", placeholder: "from the class" },
];
export const GEARS = ["Pinion", "Wheel"];

// Every field with its full pointer; a gear field's `gear` is 0 or 1.
export const FIELDS = [
  ...PAIR_GROUPS.flatMap(([, f]) => f),
  ...GEARS.flatMap((_, gear) => GEAR_FIELDS.map((f) => ({ ...f, gear, pointer: `/gears/${gear}${f.key}` }))),
];

// ISO/TR 6336-30:2017, Example 1: schemas/examples/rating-iso-tr-6336-30-1.json
// (tests/web/rating-fields.test.mjs checks that the two are the same).
const EH_MQ = { E_Pa: 2.06e11, nu: 0.3, rho_kg_m3: 7830, iso6336_5: { class: "Eh", quality: "MQ", hardness_HV: 680 } };
export const TR_6336_30_EXAMPLE_1 = {
  name: "ISO/TR 6336-30:2017, Example 1",
  pair: {
    type: "external", normal_module_mm: 8, pressure_angle_deg: 20, helix_angle_deg: 15.8,
    face_width_mm: 100, center_distance_mm: 500,
    basic_rack: { addendum_coef: 1.0, dedendum_coef: 1.4, root_radius_coef: 0.39 },
    accuracy_grade: 5, tip_relief_um: 70,
  },
  gears: [
    { teeth: 17, profile_shift: 0.145, flank_Rz_um: 6, material: EH_MQ },
    { teeth: 103, profile_shift: 0.0, flank_Rz_um: 6, material: EH_MQ },
  ],
  load: { torque_N_m: 9000, speed_rpm: 360, life_h: 50000, application_factor: 1.0 },
  lubricant: { nu40_mm2_s: 320 },
  required_safety: { S_H: 1.0, S_F: 1.4 },
};

export function fieldId(pointer) {
  return "r" + pointer.replace(/[^A-Za-z0-9_]/g, "-");
}

// What a person typed: numbers as numbers (else the text, which the server
// then refuses at its field), a choice as its text.
export function parseValue(raw, spec) {
  if (spec.type === "text" || spec.type === "enum") return raw;
  return Number.isFinite(Number(raw)) ? Number(raw) : raw;
}

// The rating document of [[spec, raw text]]; empty fields are left to the
// server's defaults. Both gears are always sent (the schema wants two).
export function documentFromValues(entries) {
  const doc = { pair: {}, gears: [{ material: {} }, { material: {} }], load: {} };
  for (const [spec, text] of entries) {
    const raw = String(text).trim();
    if (raw !== "") setPointer(doc, spec.pointer, parseValue(raw, spec));
  }
  return doc;
}

// The form field a problem's pointer concerns: itself, or the first field
// inside it (/gears/0/material/iso6336_5 -> its class); null if none.
export function fieldPointerFor(pointer, pointers) {
  if (!pointer) return null;
  if (pointers.includes(pointer)) return pointer;
  return pointers.find((p) => p.startsWith(pointer + "/")) ?? null;
}

// "default 20" under a field, or what an empty field leaves to the server.
export function hintText(spec) {
  if (spec.def !== undefined) return `default ${formText(spec.def)}`;
  return spec.placeholder ? `empty: ${spec.placeholder}` : "";
}
