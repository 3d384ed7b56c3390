import { test } from "node:test";
import assert from "node:assert/strict";
import { level, safeties, verdictRows } from "../../web/js/verdict-data.js";

// The 5 kN static check of the paper's pinion in 250 HB nodular iron
// (docs/rating.md), as analysis.rating reports it.
const rated = { analysis: { rating: {
  load_point: "hpstc", required_S_F: 1.4, required_S_H: 1.0,
  simulated: { S_F: 1.411, S_H_hertz: 0.684, S_yield: 1.634 },
  method_B: { S_F: 1.393, S_F_at_load_point: 1.393, S_H: 0.430 },
} } };

test("the governing mode comes first, each with its level", () => {
  const rows = verdictRows(rated);
  assert.deepEqual(rows.map((r) => r.mode), ["Pitting, pinion", "Root bending, pinion", "Yield at the fillet (static load)"]);
  assert.deepEqual(rows.map((r) => r.level), ["red", "amber", "green"]);
  assert.ok(Math.abs(rows[1].margin - 1.411 / 1.4) < 1e-12);
});

test("the resolved pressure is preferred where the check resolved the contact", () => {
  const resolved = structuredClone(rated);
  resolved.analysis.rating.simulated.S_H_resolved = 1.2;
  assert.equal(verdictRows(resolved).find((r) => r.mode.startsWith("Pitting")).S, 1.2);
});

test("an unrated run has no verdict; levels at their bounds", () => {
  assert.deepEqual(verdictRows({ analysis: {} }), []);
  assert.equal(level(0.999), "red");
  assert.equal(level(1.0), "amber");
  assert.equal(level(1.1), "green");
  assert.equal(level(NaN), "red");
});

test("the compare view's safeties: the simulated S_F and S_H, null when unrated", () => {
  assert.deepEqual(safeties(rated), { S_F: 1.411, S_H: 0.684 });
  assert.equal(safeties({ analysis: {} }), null);
});

test("a static check with the FE check names the FE safety beside the simulated one", () => {
  const withFe = structuredClone(rated);
  withFe.analysis.rating.fe_check = { S_F: 1.433, S_H_hertz: 0.684 };
  const bending = verdictRows(withFe).find((r) => r.mode.startsWith("Root"));
  assert.equal(bending.S, 1.411);
  assert.match(bending.note, /FE check 1\.433/);
});

test("a dynamic run: method B with the measured K_v, or ISO's with the reason", () => {
  const dynamic = { analysis: { rating: {
    required_S_F: 1.4, required_S_H: 1.0,
    K_v: { iso6336_1_method_B: 1.02, measured: 1.3 },
    method_B: { S_F: 2.0, S_H: 1.2 },
    with_measured_K_v: { S_F: 1.57, S_H: 1.06 },
  } } };
  const rows = verdictRows(dynamic);
  assert.deepEqual(rows.map((r) => r.S), [1.06, 1.57]);
  assert.match(rows[0].note, /measured K_v 1\.300/);
  assert.deepEqual(safeties(dynamic), { S_F: 1.57, S_H: 1.06 });
  const unsteady = structuredClone(dynamic);
  delete unsteady.analysis.rating.with_measured_K_v;
  unsteady.analysis.rating.K_v = { iso6336_1_method_B: 1.02, measured: null, reason: "no steady mesh" };
  const u = verdictRows(unsteady);
  assert.deepEqual(u.map((r) => r.S), [1.2, 2.0]);
  assert.match(u[0].note, /not measured: no steady mesh/);
  assert.deepEqual(safeties(unsteady), { S_F: 2.0, S_H: 1.2 });
});
