// The stress along tooth 0's fillets as the result view shows it: the SPH
// static check's curves (summary analysis.static_check.fillet_curves), the
// FE check's of its finest mesh (fe_fillet_curves.json) on the same arc
// length axis, and the peaks compared (summary fe_comparison, else ISO
// 6336-3's sigma_F0). Pure (no DOM, no chart library): unit-tested in Node.

// The static check of a run that recovered fillet curves, else null.
export function filletCheck(summary) {
  const check = summary?.analysis?.static_check;
  return check?.fillet_curves?.tension && check.fillet_curves.compression ? check : null;
}

// fe_comparison when it holds FE values (the check ran and compared), else null.
export function feComparison(summary) {
  const c = summary?.fe_comparison;
  return c && (c.status === "compared" || c.status === "sph_values_missing") ? c : null;
}

// The finest mesh of fe_fillet_curves.json: the FE check's reference.
export function finestMesh(feCurves) {
  const meshes = (feCurves?.meshes || []).filter((m) => m.arc_m?.length && m.fillet_size_m > 0);
  if (!meshes.length) return null;
  return meshes.reduce((a, b) => (b.fillet_size_m < a.fillet_size_m ? b : a));
}

// Curves sampled at different arc lengths on one sorted axis:
// [[x, y], ...] -> {x, ys: [y at x, undefined where a curve has no sample]}.
export function joinOnX(tables) {
  const x = [...new Set(tables.flatMap(([xs]) => Array.from(xs)))].sort((a, b) => a - b);
  const at = new Map(x.map((v, i) => [v, i]));
  const ys = tables.map(([xs, values]) => {
    const y = new Array(x.length).fill(undefined);
    for (let i = 0; i < xs.length; i++) y[at.get(xs[i])] = values[i] ?? null;
    return y;
  });
  return { x, ys };
}

const TENSION = "#d62728";
const COMPRESSION = "#1f77b4";
const TENSION_FE = "#7f1d1d";
const COMPRESSION_FE = "#1e3a8a";
const REFERENCE = "#6b7280";

// The chart: {arc_m, series: [{label, values (Pa), colour, dash}], marks:
// [{value (m), label}]}. FE curves (finest mesh) are dashed and their
// legend says FE; ISO's sigma_F0 is a dotted level; ISO's 30-degree
// tangent point is marked where the FE curves give its arc length.
export function filletChart(check, feMesh = null) {
  const { tension, compression } = check.fillet_curves;
  const curves = [
    { label: "SPH σ1, tension fillet", colour: TENSION, xy: [tension.arc_m, tension.sigma1_Pa] },
    { label: "SPH σ3, compression fillet", colour: COMPRESSION, xy: [compression.arc_m, compression.sigma3_Pa] },
  ];
  if (feMesh) {
    const size = `${Number((feMesh.fillet_size_m * 1e3).toPrecision(3))} mm mesh`;
    curves.push(
      { label: `FE σ1, tension (${size})`, colour: TENSION_FE, dash: [6, 4], xy: [feMesh.arc_m, feMesh.tension_sigma1_Pa] },
      { label: `FE σ3, compression (${size})`, colour: COMPRESSION_FE, dash: [6, 4], xy: [feMesh.arc_m, feMesh.compression_sigma3_Pa] });
  }
  const { x, ys } = joinOnX(curves.map((c) => c.xy));
  const series = curves.map((c, k) => ({ label: c.label, colour: c.colour, dash: c.dash, values: ys[k] }));
  if (Number.isFinite(check.iso_sigma_F0_Pa)) {
    series.push({ label: "ISO 6336-3 σF0", colour: REFERENCE, dash: [2, 4], values: x.map(() => check.iso_sigma_F0_Pa) });
  }
  const marks = Number.isFinite(feMesh?.iso30_arc_m) ? [{ value: feMesh.iso30_arc_m, label: "ISO 30°" }] : [];
  return { arc_m: x, series, marks };
}

const QUANTITIES = [
  ["fillet_tension_peak_Pa", "Tension peak σ1", "Pa", "fillet_tension_peak_error_vs_iso"],
  ["fillet_compression_peak_Pa", "Compression peak σ3", "Pa", null],
  ["fillet_stress_at_iso30_Pa", "σ1 at ISO's 30° point", "Pa", "fillet_iso30_error_vs_iso"],
  ["fillet_tension_peak_radius_m", "Tension peak radius", "m", null],
];

// The table: with the FE check, SPH, FE and (SPH - FE) / |FE| for each
// quantity; without, SPH and ISO 6336-3's sigma_F0 (defined at the
// 30-degree point, also the reference for the tension peak).
//   {reference: "FE" | "ISO", rows: [{key, label, unit, sph, ref, error}]}
export function filletTable(check, comparison = null) {
  const num = (v) => (Number.isFinite(v) ? v : null);
  if (comparison) {
    return {
      reference: "FE",
      rows: QUANTITIES.map(([key, label, unit]) => {
        const c = comparison[key] || {};
        return { key, label, unit, sph: num(c.sph !== undefined ? c.sph : check[key]), ref: num(c.fe), error: num(c.error) };
      }),
    };
  }
  const iso = num(check.iso_sigma_F0_Pa);
  return {
    reference: "ISO",
    rows: QUANTITIES.map(([key, label, unit, isoError]) => {
      const sph = num(check[key]);
      const ref = isoError && iso !== null ? iso : null;
      const error = ref === null ? null : num(check[isoError]) ?? (sph === null ? null : (sph - ref) / Math.abs(ref));
      return { key, label, unit, sph, ref, error };
    }),
  };
}

// The FE check's colour scale of its tooth-0 stress figures [Pa]:
// fe_comparison.image_range_Pa, or for a run that predates it the same rule
// (fe/gear_fe_model.cpp, root_image_range_Pa) on the FE fillet peaks,
// ±1.25 times the larger. null when neither is there.
export function feImageRange(comparison) {
  const r = comparison?.image_range_Pa;
  if (Array.isArray(r) && r.length === 2 && r.every(Number.isFinite) && r[0] < r[1]) return r;
  const peaks = [comparison?.fillet_tension_peak_Pa?.fe, comparison?.fillet_compression_peak_Pa?.fe];
  if (!peaks.every(Number.isFinite)) return null;
  const cap = 1.25 * Math.max(...peaks.map(Math.abs));
  return cap > 0 ? [-cap, cap] : null;
}

// The fields the panel shows side by side, SPH and FE, the same quantity on
// the same colour scale: the FE figure's file and the SPH image's field and
// range (FE von Mises is drawn from 0 to the σ1 figure's upper end).
export const FIELD_PAIRS = [
  { fe: "fe_max_principal_tooth0.png", sph: "max_principal", label: "largest principal stress σ1", symbol: "σ1",
    range: (r) => r },
  { fe: "fe_von_mises_tooth0.png", sph: "von_mises", label: "von Mises stress", symbol: "von Mises",
    range: (r) => [0, r[1]] },
];

// The URL of the SPH image for a pair: the last frame zoomed to tooth 0
// (static_check.tooth0_box_m; a run without it: the meshing zone, `zone`),
// on the FE figure's colour scale when it is known.
//   {src, tooth0 (zoomed to tooth 0), range (Pa or null)}
export function sphFieldImage(id, check, pair, feRange, zone = null) {
  const box = Array.isArray(check?.tooth0_box_m) && check.tooth0_box_m.length === 4 &&
    check.tooth0_box_m.every(Number.isFinite) ? check.tooth0_box_m : null;
  const window = box || zone;
  const range = feRange ? pair.range(feRange) : null;
  const query = [
    window ? `zoom=${window.map((v) => Number(v.toPrecision(6))).join(",")}` : null,
    range ? `range=${range.map(String).join(",")}` : null, // exactly the FE figure's
  ].filter(Boolean);
  return { src: `/jobs/${id}/images/${pair.sph}.png${query.length ? `?${query.join("&")}` : ""}`, tooth0: !!box, range };
}
