// The Study page's data from GET /studies/{id}: the jobs' rows, the speed
// sweep's curves joined on one frequency axis, the resonance marks (close
// ones share a label), the lines of text and the "no SPH" sentence.
import { test } from "node:test";
import assert from "node:assert/strict";
import {
  cellText, dteChart, isActive, jobRows, joinOnX, kvChart, parameterColumns, reportFileName, reportLines,
  resonanceMarks, sphNote, sweepRange, sweepRows,
} from "../../web/js/study-data.js";

// The shape of a finished sweep's report (docs/dynamics.md), round numbers.
const fine = Array.from({ length: 11 }, (_, k) => 400 + 80 * k); // 400 ... 1200 Hz
const report = {
  mesh_frequency_Hz: [400, 1200],
  ratio_to_natural_frequency: [0.5, 1.5],
  K_v_sph: [1.05, 1.2],
  K_v_sdof: [1.04, 1.18],
  K_v_sdof_down: [1.04, 1.25],
  dte_pp_m_sph: [2e-6, 5e-6],
  dte_pp_m_sdof: [1.5e-6, null],
  contact_loss_fraction_sph: [0, 0.1],
  contact_loss_fraction_sdof: [0, 0.05],
  steady_sph: [true, true],
  wall_s_sph: [12, 30],
  mesh_frequency_Hz_fine: fine,
  K_v_sdof_fine: fine.map((f) => 1 + 0.5 / (1 + ((f - 800) / 60) ** 2)),
  resonance_Hz_sph: 830,
  resonance_Hz_sdof: 800,
  resonance_Hz_iso: 810,
  natural_frequency_Hz_sdof: 800,
  stiffness_from: "iso",
  damping_ratio: { value: 0.05, from: "assumed (no SPH run's ringing was measured)" },
  iso_stiffness_sdof: { K_v_fine: fine.map(() => 1.1), resonance_Hz: 810, natural_frequency_Hz: 805 },
};
const study = {
  studyID: "s1", name: "paper pair", kind: "speed_sweep", status: "successful", progress: 100,
  counts: { accepted: 0, running: 0, successful: 2, failed: 0, dismissed: 0 },
  jobs: [
    { jobID: "b2", status: "successful", progress: 100, message: "", parameters: { ratio: 1.5, mesh_frequency_Hz: 1200 } },
    { jobID: "a1", status: "successful", progress: 100, message: "", parameters: { ratio: 0.5, mesh_frequency_Hz: 400 } },
  ],
};

test("a study is active while a job is queued or running", () => {
  assert.equal(isActive(study), false);
  const queued = structuredClone(study);
  queued.jobs[0].status = "accepted";
  assert.equal(isActive(queued), true);
  queued.jobs[0].status = "running";
  assert.equal(isActive(queued), true);
  assert.equal(isActive({}), false);
});

test("the jobs' rows link to their pages; a sweep's go up in frequency", () => {
  const rows = jobRows(study);
  assert.deepEqual(rows.map((r) => r.href), ["#/jobs/b2", "#/jobs/a1"]);
  assert.deepEqual(sweepRows(study).map((r) => r.parameters.mesh_frequency_Hz), [400, 1200]);
  assert.deepEqual(sweepRows(study).map((r) => r.index), [2, 1]); // the server's numbering stays
  const axes = { jobs: [{ jobID: "x", parameters: { "/discretization/spacing_mm": 2 } },
    { jobID: "y", parameters: { "/discretization/spacing_mm": 1, "/method/formulation": "total_lagrangian" } }] };
  assert.deepEqual(parameterColumns(axes), ["/discretization/spacing_mm", "/method/formulation"]);
});

test("curves sampled at different speeds share one axis", () => {
  const { x, ys } = joinOnX([[[1, 2, 3], [10, 20, 30]], [[1, 2.5, 3 + 1e-13], [5, null, 7]]]);
  assert.deepEqual(x, [1, 2, 2.5, 3]); // 3 and 3 + 1e-13 are one speed
  assert.deepEqual(ys[0], [10, 20, undefined, 30]); // undefined: bridged
  assert.deepEqual(ys[1], [5, undefined, null, 7]); // null: a gap
});

test("the K_v chart: SPH and the lumped model's speeds as points, its fine curve as a line", () => {
  const c = kvChart(report);
  assert.equal(c.x.length, fine.length); // the sweep's speeds are the fine curve's ends
  assert.deepEqual(c.series.map((s) => s.label), ["SPH", "lumped, fine sweep", "lumped, speeds up", "lumped, speeds down"]);
  const [sph, line, up, down] = c.series;
  assert.equal(sph.line, false);
  assert.ok(sph.points.filled);
  assert.equal(line.line, true);
  assert.equal(up.points.filled, false);
  assert.equal(down.values[down.values.length - 1], 1.25);
  assert.equal(sph.values[0], 1.05);
  assert.equal(sph.values[1], undefined); // 480 Hz: no SPH run there
  assert.ok(line.values.every((v) => Number.isFinite(v)));
  for (const s of c.series) assert.equal(s.values.length, c.x.length);
});

test("no SPH value: no SPH series; a measured stiffness adds ISO's curve", () => {
  const none = { ...report, K_v_sph: [null, null], dte_pp_m_sph: [null, null], stiffness_from: "measured" };
  const c = kvChart(none);
  assert.ok(!c.series.some((s) => s.label === "SPH"));
  assert.ok(c.series.some((s) => s.label === "lumped, ISO 6336-1 stiffness" && s.dash));
  assert.deepEqual(dteChart(none).series.map((s) => s.label), ["lumped"]);
});

test("the transmission error in micrometres", () => {
  const c = dteChart(report);
  assert.deepEqual(c.x, [400, 1200]);
  const [sph, lumped] = c.series;
  assert.ok(Math.abs(sph.values[1] - 5) < 1e-9);
  assert.ok(Math.abs(lumped.values[0] - 1.5) < 1e-9);
  assert.equal(lumped.values[1], null);
  assert.equal(lumped.line, false); // two speeds: points only
  const dense = { ...report, mesh_frequency_Hz: fine, dte_pp_m_sdof: fine.map(() => 1e-6) };
  assert.equal(dteChart(dense).series.at(-1).line, true);
});

test("resonance marks: only numbers, close ones share a label", () => {
  const marks = resonanceMarks(report);
  assert.deepEqual(marks.map((m) => m.value), [800, 810, 830]);
  // 800 to 830 Hz is 3.75 % of the 800 Hz span: one label at the first.
  assert.deepEqual(marks.map((m) => m.label), ["lumped / ISO 6336-1 / SPH resonance", "", ""]);
  const apart = resonanceMarks({ ...report, resonance_Hz_sph: 1000, resonance_Hz_iso: null });
  assert.deepEqual(apart, [{ value: 800, name: "lumped", label: "lumped resonance" },
    { value: 1000, name: "SPH", label: "SPH resonance" }]);
  assert.deepEqual(resonanceMarks({ mesh_frequency_Hz: [1, 2] }), []);
  // A resonance beyond the sweep's speeds is not marked; the text names it.
  const beyond = { ...report, resonance_Hz_iso: 6700 };
  assert.deepEqual(resonanceMarks(beyond).map((m) => m.name), ["lumped", "SPH"]);
  assert.equal(Object.fromEntries(reportLines(beyond))["Not marked"],
    "ISO 6336-1 6700 Hz: outside the sweep's 400 Hz to 1200 Hz");
  assert.equal(Object.fromEntries(reportLines(report))["Not marked"], undefined);
});

test("the lines of text: natural frequency, stiffness, damping, resonances and their ratios", () => {
  const lines = Object.fromEntries(reportLines(report));
  assert.equal(lines["Natural frequency"], "800 Hz (lumped model)");
  assert.match(lines["Mesh stiffness"], /^ISO 6336-1/);
  assert.equal(lines["Damping ratio"], "ζ = 0.050, assumed (no SPH run's ringing was measured)");
  assert.equal(lines.Resonance, "ISO 6336-1 810 Hz · lumped 800 Hz · SPH 830 Hz");
  assert.equal(lines.Ratios, "SPH/lumped 1.038 · SPH/ISO 1.025 · lumped/ISO 0.988");
  const bare = Object.fromEntries(reportLines({ ...report, resonance_Hz_sph: null, resonance_Hz_iso: null }));
  assert.equal(bare.Resonance, "ISO 6336-1 — · lumped 800 Hz · SPH —");
  assert.equal(bare.Ratios, undefined);
  const measured = Object.fromEntries(reportLines({ ...report, stiffness_from: "measured" }));
  assert.equal(measured["On ISO stiffness"], "natural frequency 805 Hz, resonance 810 Hz");
});

test("a sentence when no SPH speed gave a value", () => {
  assert.equal(sphNote(study, report), null);
  const none = { ...report, K_v_sph: [null, null] };
  const dismissed = { ...study, counts: { accepted: 0, running: 0, successful: 0, failed: 0, dismissed: 2 } };
  assert.match(sphNote(dismissed, none), /^No job ran/);
  assert.match(sphNote(study, none), /^No SPH speed reached a steady mesh/);
});

test("the sweep's range spans its speeds and the fine curve", () => {
  assert.deepEqual(sweepRange(report), [400, 1200]);
  assert.equal(sweepRange({}), null);
});

test("file names and table cells", () => {
  assert.equal(reportFileName(study), "paper_pair-speed-sweep.json");
  assert.equal(reportFileName({ studyID: "abc" }), "abc-speed-sweep.json");
  assert.equal(cellText(null), "—");
  assert.equal(cellText(2), "2");
  assert.equal(cellText(0.123456), "0.1235");
  assert.equal(cellText(true), "yes");
  assert.equal(cellText("successful"), "successful");
});
