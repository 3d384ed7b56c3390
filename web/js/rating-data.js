// The answer of POST /rating (docs/rating.md) as the rating view shows it:
// each gear's safeties against the required ones (levelled and ranked as
// the verdict panel's, verdict-data.js), the stresses, every factor in its
// group and the lives at the required safeties. Pure (no DOM).
import { ranked } from "./verdict-data.js";

// "pinion" and "wheel", or "pinion" and "rack".
export function gearNames(r) {
  return ["pinion", r?.geometry?.type === "rack" ? "rack" : "wheel"];
}

const MPa = (pa) => (Number.isFinite(pa) ? pa / 1e6 : NaN);
const mpaText = (pa) => (Number.isFinite(pa) ? `${(pa / 1e6).toFixed(1)} MPa` : "–");

// Each gear's pitting and root bending safety, then the static ones (at the
// largest load) and the yield; the smallest margin first.
export function safetyRows(r) {
  const [p, b, st] = [r.pitting, r.bending, r.static || {}];
  const rows = [];
  gearNames(r).forEach((gear, k) => {
    rows.push(
      { mode: `Pitting, ${gear}`, kind: "S_H", gear: k, S: p.S_H[k], required: p.required_S_H,
        note: `σ_H ${mpaText(p.sigma_H_Pa[k])} against σ_HP ${mpaText(p.sigma_HP_Pa[k])}` },
      { mode: `Root bending, ${gear}`, kind: "S_F", gear: k, S: b.S_F[k], required: b.required_S_F,
        note: `σ_F ${mpaText(b.sigma_F_Pa[k])} against σ_FP ${mpaText(b.sigma_FP_Pa[k])}` },
      { mode: `Static pitting, ${gear}`, kind: "S_H_static", gear: k, S: st.S_H?.[k], required: p.required_S_H,
        note: `at the largest load, σ_H ${mpaText(st.sigma_H_Pa?.[k])}, Z_NT ${fixed(st.Z_NT?.[k], 2)}` },
      { mode: `Static root bending, ${gear}`, kind: "S_F_static", gear: k, S: st.S_F?.[k], required: b.required_S_F,
        note: `at the largest load, σ_F ${mpaText(st.sigma_F_Pa?.[k])}, Y_NT ${fixed(st.Y_NT?.[k], 2)}` },
      { mode: `Yield at the root, ${gear}`, kind: "S_yield", gear: k, S: st.S_yield?.[k], required: 1,
        note: "yield strength over the static root stress" });
  });
  return ranked(rows);
}

// [label, unit, [pinion, wheel]] in MPa; a pair value is given to both.
export function stressRows(r) {
  const p = r.pitting, b = r.bending;
  const both = (v) => [v, v];
  return [
    ["σ_H0 nominal contact stress", "MPa", both(MPa(p.sigma_H0_Pa))],
    ["σ_H contact stress", "MPa", p.sigma_H_Pa.map(MPa)],
    ["σ_Hlim endurance limit", "MPa", p.sigma_Hlim_Pa.map(MPa)],
    ["σ_HG pitting stress limit", "MPa", p.sigma_HG_Pa.map(MPa)],
    ["σ_HP permissible contact stress", "MPa", p.sigma_HP_Pa.map(MPa)],
    ["σ_F0 nominal root stress", "MPa", b.sigma_F0_Pa.map(MPa)],
    ["σ_F root stress", "MPa", b.sigma_F_Pa.map(MPa)],
    ["σ_Flim endurance limit", "MPa", b.sigma_Flim_Pa.map(MPa)],
    ["σ_FG tooth root stress limit", "MPa", b.sigma_FG_Pa.map(MPa)],
    ["σ_FP permissible root stress", "MPa", b.sigma_FP_Pa.map(MPa)],
  ];
}

// The factors by group: [key, symbol, unit, what]. A key the answer has
// and no group names goes to "Other", so every factor is shown.
export const FACTOR_GROUPS = [
  ["Load factors (ISO 6336-1)", [
    ["K_A", "K_A", "", "application factor"],
    ["K_v", "K_v", "", "dynamic factor, method B"],
    ["K_v_range", "", "", "K_v's speed range"],
    ["resonance_ratio_N", "N", "", "resonance ratio n_1 / n_E1"],
    ["n_E1_rpm", "n_E1", "rpm", "resonance speed of the pinion"],
    ["K_Hbeta", "K_Hβ", "", "face load factor, contact"],
    ["K_Hbeta_from", "", "", "K_Hβ from"],
    ["K_Fbeta", "K_Fβ", "", "face load factor, root"],
    ["N_F", "N_F", "", "exponent of K_Fβ"],
    ["K_Halpha", "K_Hα", "", "transverse load factor, contact"],
    ["K_Falpha", "K_Fα", "", "transverse load factor, root"],
    ["c_th_N_mm_um", "c'_th", "N/(mm·µm)", "theoretical single-pair stiffness"],
    ["c_prime_N_mm_um", "c'", "N/(mm·µm)", "single-pair stiffness"],
    ["c_gamma_alpha_N_mm_um", "c_γα", "N/(mm·µm)", "mesh stiffness, for K_v and K_Hα"],
    ["c_gamma_beta_N_mm_um", "c_γβ", "N/(mm·µm)", "mesh stiffness, for K_Hβ"],
    ["y_alpha_um", "y_α", "µm", "running-in allowance, pitch"],
    ["F_betax_um", "F_βx", "µm", "initial equivalent misalignment"],
    ["F_betay_um", "F_βy", "µm", "effective misalignment after running-in"],
  ]],
  ["Pitting factors (ISO 6336-2)", [
    ["Z_H", "Z_H", "", "zone factor"],
    ["Z_E_sqrt_MPa", "Z_E", "√MPa", "elasticity factor"],
    ["Z_eps", "Z_ε", "", "contact ratio factor"],
    ["Z_beta", "Z_β", "", "helix angle factor"],
    ["Z_B", "Z_B", "", "single pair tooth contact factor, pinion"],
    ["Z_D", "Z_D", "", "single pair tooth contact factor, wheel"],
    ["Z_L", "Z_L", "", "lubricant factor"],
    ["Z_v", "Z_v", "", "velocity factor"],
    ["Z_R", "Z_R", "", "roughness factor"],
    ["Z_W", "Z_W", "", "work hardening factor"],
    ["Z_X", "Z_X", "", "size factor"],
    ["Z_NT", "Z_NT", "", "life factor at the required life"],
  ]],
  ["Bending factors (ISO 6336-3)", [
    ["Y_F", "Y_F", "", "form factor"],
    ["Y_S", "Y_S", "", "stress correction factor"],
    ["Y_beta", "Y_β", "", "helix angle factor"],
    ["Y_B", "Y_B", "", "rim thickness factor"],
    ["Y_DT", "Y_DT", "", "deep tooth factor"],
    ["Y_ST", "Y_ST", "", "stress correction factor of the test gear"],
    ["Y_NT", "Y_NT", "", "life factor at the required life"],
    ["Y_deltarelT", "Y_δrelT", "", "relative notch sensitivity factor"],
    ["Y_RrelT", "Y_RrelT", "", "relative surface factor"],
    ["Y_X", "Y_X", "", "size factor"],
    ["s_Fn_mm", "s_Fn", "mm", "root chord at the 30° tangents"],
    ["rho_F_mm", "ρ_F", "mm", "root fillet radius there"],
    ["h_Fe_mm", "h_Fe", "mm", "bending moment arm"],
  ]],
];

// [{title, rows: [{symbol, unit, what, values}]}]; values is one value of
// the pair or [pinion, wheel].
export function factorGroups(r) {
  const f = r.factors || {};
  const named = new Set(FACTOR_GROUPS.flatMap(([, rows]) => rows.map(([key]) => key)));
  const groups = FACTOR_GROUPS.map(([title, rows]) => ({
    title,
    rows: rows.filter(([key]) => key in f).map(([key, symbol, unit, what]) => ({ key, symbol, unit, what, values: f[key] })),
  }));
  const other = Object.keys(f).filter((k) => !named.has(k))
    .map((key) => ({ key, symbol: key, unit: "", what: "", values: f[key] }));
  if (other.length) groups.push({ title: "Other", rows: other });
  return groups;
}

// The life: the load cycles of the required life, and the cycles and hours
// at which each safety falls to the required one (null: past 1e10 cycles,
// or never on the optimum line).
export function lifeRows(r) {
  const L = r.life || {}, H = L.pitting || {}, F = L.bending || {};
  return [
    { label: "Load cycles N_L at the required life", unit: "", values: r.load?.cycles, kind: "cycles" },
    { label: "Required life", unit: "h", values: r.load?.life_h, kind: "hours" },
    { label: `Life at S_H = ${H.required_S}`, unit: "h", values: H.hours, kind: "hours" },
    { label: `Load cycles at S_H = ${H.required_S}`, unit: "", values: H.cycles, kind: "cycles" },
    { label: `Life at S_F = ${F.required_S}`, unit: "h", values: F.hours, kind: "hours" },
    { label: `Load cycles at S_F = ${F.required_S}`, unit: "", values: F.cycles, kind: "cycles" },
  ];
}

// A factor with four significant figures (1.003, 0.9101, 189.8); text as text.
export function factorText(v) {
  if (v === null || v === undefined) return "–";
  if (typeof v !== "number") return String(v);
  if (!Number.isFinite(v)) return String(v);
  const a = Math.abs(v);
  if (a !== 0 && (a < 1e-3 || a >= 1e5)) return v.toExponential(3).replace("e+", "e");
  return String(Number(v.toPrecision(4)));
}

// Lives: cycles as 1.080e9, hours rounded; null: past the life lines' end.
export function lifeText(v, kind) {
  if (v === null) return "past 1e10 cycles";
  if (!Number.isFinite(v)) return "–";
  if (kind === "cycles") return v.toExponential(3).replace("e+", "e");
  return v >= 1e7 ? v.toExponential(2).replace("e+", "e") : Math.round(v).toLocaleString("en-US");
}

export function fixed(v, digits = 3) {
  return Number.isFinite(v) ? v.toFixed(digits) : "–";
}
