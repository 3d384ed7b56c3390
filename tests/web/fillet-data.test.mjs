import { test } from "node:test";
import assert from "node:assert/strict";
import {
  FIELD_PAIRS, feComparison, feImageRange, filletChart, filletCheck, filletTable, finestMesh, joinOnX, sphFieldImage,
} from "../../web/js/fillet-data.js";

// A static check as summary.json gives it (values of the paper's pinion,
// 1 kN at the pitch point), its curves cut to three samples.
const check = {
  fillet_curves: {
    tension: { arc_m: [0, 0.001, 0.002], radius_m: [0.019, 0.0192, 0.0198], sigma1_Pa: [13e6, 31e6, 41.2e6] },
    compression: { arc_m: [0, 0.001, 0.002], radius_m: [0.019, 0.0192, 0.0198], sigma3_Pa: [-13e6, -33e6, -43.3e6] },
  },
  fillet_tension_peak_Pa: 41195943.7,
  fillet_tension_peak_radius_m: 0.0197818,
  fillet_compression_peak_Pa: -43321684.9,
  fillet_stress_at_iso30_Pa: 41075276.9,
  fillet_tension_peak_error_vs_iso: 0.010674,
  fillet_iso30_error_vs_iso: 0.007714,
  iso_sigma_F0_Pa: 40760854.8,
  load_radius_m: 0.024,
  contact_point: "pitch",
};
const comparison = {
  status: "compared",
  fillet_tension_peak_Pa: { sph: 41195943.7, fe: 41709882.7, error: -0.012322 },
  fillet_compression_peak_Pa: { sph: -43321684.9, fe: -44710844.0, error: 0.031070 },
  fillet_stress_at_iso30_Pa: { sph: 41075276.9, fe: 41677424.9, error: -0.014448 },
  fillet_tension_peak_radius_m: { sph: 0.0197818, fe: 0.0197272, error: 0.002768 },
  fe_fillet_size_m: 0.0001,
};
const mesh = (size) => ({ fillet_size_m: size, arc_m: [0, 0.0005, 0.002], iso30_arc_m: 0.0019065,
  tension_sigma1_Pa: [11e6, 21e6, 41.7e6], compression_sigma3_Pa: [-11e6, -22e6, -44.7e6] });

test("only a static check with fillet curves has the panel", () => {
  assert.equal(filletCheck({ analysis: { static_check: check } }), check);
  assert.equal(filletCheck({ analysis: { static_check: { root_stress_Pa: 1 } } }), null);
  assert.equal(filletCheck({ analysis: {} }), null);
  assert.equal(filletCheck({}), null);
  assert.equal(filletCheck(undefined), null);
});

test("FE values only from a check that compared", () => {
  assert.equal(feComparison({ fe_comparison: comparison }), comparison);
  assert.ok(feComparison({ fe_comparison: { ...comparison, status: "sph_values_missing" } }));
  for (const status of ["unavailable", "failed", "not_run"]) {
    assert.equal(feComparison({ fe_comparison: { status, message: "ccx not found" } }), null, status);
  }
  assert.equal(feComparison({}), null);
});

test("the finest FE mesh is the reference", () => {
  assert.equal(finestMesh({ meshes: [mesh(0.0002), mesh(0.0001)] }).fillet_size_m, 0.0001);
  assert.equal(finestMesh({ meshes: [mesh(0.0001), mesh(0.0002)] }).fillet_size_m, 0.0001);
  assert.equal(finestMesh({ meshes: [] }), null);
  assert.equal(finestMesh(null), null);
});

test("curves with their own samples on one arc-length axis", () => {
  const { x, ys } = joinOnX([[[0, 2], [10, 30]], [[0, 1, 2], [-1, -2, -3]]]);
  assert.deepEqual(x, [0, 1, 2]);
  assert.deepEqual(ys[0], [10, undefined, 30]);
  assert.deepEqual(ys[1], [-1, -2, -3]);
});

test("SPH curves alone, with ISO's sigma_F0 as a level", () => {
  const c = filletChart(check);
  assert.deepEqual(c.arc_m, [0, 0.001, 0.002]);
  assert.deepEqual(c.series.map((s) => s.label), ["SPH σ1, tension fillet", "SPH σ3, compression fillet", "ISO 6336-3 σF0"]);
  assert.deepEqual(c.series[1].values, [-13e6, -33e6, -43.3e6]);
  assert.ok(c.series[2].values.every((v) => v === check.iso_sigma_F0_Pa));
  assert.deepEqual(c.marks, []);
});

test("the FE curves of the finest mesh are overlaid, dashed, and named FE", () => {
  const c = filletChart(check, mesh(0.0001));
  assert.deepEqual(c.arc_m, [0, 0.0005, 0.001, 0.002]);
  const fe = c.series.filter((s) => s.label.startsWith("FE"));
  assert.equal(fe.length, 2);
  assert.ok(fe.every((s) => s.dash && s.label.includes("0.1 mm")));
  assert.deepEqual(fe[0].values, [11e6, 21e6, undefined, 41.7e6]);
  assert.deepEqual(c.series[0].values, [13e6, undefined, 31e6, 41.2e6]);
  assert.deepEqual(c.marks, [{ value: 0.0019065, label: "ISO 30°" }]);
});

test("the table: SPH, FE and error when the FE check compared", () => {
  const t = filletTable(check, comparison);
  assert.equal(t.reference, "FE");
  assert.deepEqual(t.rows.map((r) => r.key), ["fillet_tension_peak_Pa", "fillet_compression_peak_Pa",
    "fillet_stress_at_iso30_Pa", "fillet_tension_peak_radius_m"]);
  assert.deepEqual(t.rows[1], { key: "fillet_compression_peak_Pa", label: "Compression peak σ3", unit: "Pa",
    sph: -43321684.9, ref: -44710844.0, error: 0.031070 });
  assert.equal(t.rows[3].unit, "m");
  // An SPH value the check did not give stays missing, as in the summary.
  const missing = filletTable(check, { ...comparison, status: "sph_values_missing",
    fillet_compression_peak_Pa: { sph: null, fe: -44710844.0, error: null } });
  assert.equal(missing.rows[1].sph, null);
  assert.equal(missing.rows[1].error, null);
});

test("the table: SPH against ISO 6336-3's sigma_F0 without the FE check", () => {
  const t = filletTable(check);
  assert.equal(t.reference, "ISO");
  const [peak, compression, iso30, radius] = t.rows;
  assert.equal(peak.ref, check.iso_sigma_F0_Pa);
  assert.equal(peak.error, 0.010674);
  assert.equal(iso30.ref, check.iso_sigma_F0_Pa);
  assert.equal(compression.ref, null);
  assert.equal(radius.ref, null);
  assert.equal(radius.sph, 0.0197818);
  // The difference is computed when the summary does not give it.
  const { fillet_tension_peak_error_vs_iso: _, ...older } = check;
  const e = filletTable(older).rows[0].error;
  assert.ok(Math.abs(e - (check.fillet_tension_peak_Pa / check.iso_sigma_F0_Pa - 1)) < 1e-12);
});

test("the SPH field beside the FE one: the same quantity, window and colour scale", () => {
  const box = [-0.0057, -0.0289, 0.0057, -0.0160];
  const withBox = { ...check, tooth0_box_m: box };
  const range = [-55.88e6, 55.88e6];
  // The FE summary's range, as given.
  assert.deepEqual(feImageRange({ ...comparison, image_range_Pa: range }), range);
  // A run that predates it: the same rule on the FE peaks (1.25 times the larger).
  const derived = feImageRange(comparison);
  assert.ok(Math.abs(derived[1] - 1.25 * 44710844.0) < 1e-6 && derived[0] === -derived[1]);
  assert.equal(feImageRange({ status: "compared" }), null);
  assert.equal(feImageRange({ ...comparison, image_range_Pa: [5, 1] })[1], derived[1]);

  const [s1, vm] = FIELD_PAIRS;
  assert.equal(s1.fe, "fe_max_principal_tooth0.png");
  const a = sphFieldImage("j1", withBox, s1, range);
  assert.equal(a.src, `/jobs/j1/images/max_principal.png?zoom=${box.join(",")}&range=-55880000,55880000`);
  assert.ok(a.tooth0);
  // The range read back is exactly the FE figure's.
  const q = new URLSearchParams(a.src.split("?")[1]);
  assert.deepEqual(q.get("range").split(",").map(Number), range);
  // von Mises: from zero to the same upper end, as the FE figure.
  assert.deepEqual(sphFieldImage("j1", withBox, vm, range).range, [0, 55.88e6]);
  assert.match(sphFieldImage("j1", withBox, vm, range).src, /^\/jobs\/j1\/images\/von_mises\.png\?zoom=.*&range=0,55880000$/);
  // Without tooth0_box_m: the meshing zone; without a range: none asked for.
  const zone = [-0.01, -0.03, 0.01, -0.02];
  const b = sphFieldImage("j1", check, s1, null, zone);
  assert.equal(b.src, "/jobs/j1/images/max_principal.png?zoom=-0.01,-0.03,0.01,-0.02");
  assert.equal(b.tooth0, false);
  assert.equal(sphFieldImage("j1", check, s1, null).src, "/jobs/j1/images/max_principal.png");
});
