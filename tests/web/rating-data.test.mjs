// The rating view's rows from an answer of POST /rating: safeties ranked
// and levelled as the verdict panel's, every factor in a group, the lives.
import { test } from "node:test";
import assert from "node:assert/strict";
import { FACTOR_GROUPS, factorGroups, factorText, gearNames, lifeRows, lifeText, safetyRows, stressRows }
  from "../../web/js/rating-data.js";

// The shape of an answer (docs/rating.md), with round numbers.
const answer = {
  name: "pair",
  geometry: { type: "external" },
  load: { F_t_N: 127352, v_m_s: 2.664, cycles: [1.08e9, 1.783e8], life_h: 50000 },
  pitting: { sigma_H0_Pa: 1.2e9, sigma_H_Pa: [1.3e9, 1.3e9], sigma_Hlim_Pa: [1.5e9, 1.5e9],
    sigma_HG_Pa: [1.34e9, 1.41e9], sigma_HP_Pa: [1.34e9, 1.41e9], S_H: [1.03, 1.12], required_S_H: 1.0 },
  bending: { sigma_F0_Pa: [3e8, 2.8e8], sigma_F_Pa: [3.4e8, 3.2e8], sigma_Flim_Pa: [4.25e8, 4.25e8],
    sigma_FG_Pa: [8.5e8, 8.8e8], sigma_FP_Pa: [6.1e8, 6.3e8], S_F: [2.5, 2.75], required_S_F: 1.4 },
  static: { S_H: [1.5, 1.5], S_F: [3.0, 3.2], sigma_H_Pa: [1.3e9, 1.3e9], sigma_F_Pa: [3.4e8, 3.2e8],
    Z_NT: [1.6, 1.6], Y_NT: [2.5, 2.5], S_yield: [null, null] },
  factors: { K_A: 1, K_v: 1.003, K_Hbeta: 1.16, K_Hbeta_from: "F_betax", Z_NT: [0.91, 0.962], Y_F: [1.4, 1.2], Z_new: 0.5 },
  life: { pitting: { cycles: [2e9, null], hours: [92592.6, null], required_S: 1 },
    bending: { cycles: [null, null], hours: [null, null], required_S: 1.4 } },
};

test("the safeties, governing first, with the verdict panel's levels", () => {
  const rows = safetyRows(answer);
  assert.deepEqual(rows.map((r) => r.mode).slice(0, 2), ["Pitting, pinion", "Pitting, wheel"]);
  assert.deepEqual(rows.map((r) => r.level).slice(0, 2), ["amber", "green"]);
  assert.equal(rows.length, 8); // no yield strength given: no yield rows
  assert.ok(rows.every((r, i) => i === 0 || r.margin >= rows[i - 1].margin));
  const bending = rows.find((r) => r.kind === "S_F" && r.gear === 1);
  assert.equal(bending.S, 2.75);
  assert.equal(bending.required, 1.4);
  assert.match(bending.note, /σ_F 320\.0 MPa against σ_FP 630\.0 MPa/);
  const failing = structuredClone(answer);
  failing.pitting.S_H[0] = 0.9;
  assert.equal(safetyRows(failing)[0].level, "red");
});

test("a rack is named so", () => {
  assert.deepEqual(gearNames({ geometry: { type: "rack" } }), ["pinion", "rack"]);
  assert.deepEqual(gearNames(answer), ["pinion", "wheel"]);
});

test("stresses in MPa per gear; sigma_H0 is the pair's", () => {
  const rows = stressRows(answer);
  assert.deepEqual(rows.find(([l]) => l.startsWith("σ_H0"))[2], [1200, 1200]);
  assert.deepEqual(rows.find(([l]) => l.startsWith("σ_FP"))[2], [610, 630]);
  assert.ok(rows.every(([, unit]) => unit === "MPa"));
});

test("every factor is in a group; one no group names goes to Other", () => {
  const groups = factorGroups(answer);
  const keys = groups.flatMap((g) => g.rows.map((r) => r.key));
  assert.deepEqual(keys.sort(), Object.keys(answer.factors).sort());
  assert.equal(groups.at(-1).title, "Other");
  assert.deepEqual(groups.at(-1).rows.map((r) => r.key), ["Z_new"]);
  assert.deepEqual(groups.find((g) => g.title.startsWith("Pitting")).rows[0].values, [0.91, 0.962]);
  assert.equal(FACTOR_GROUPS.length, 3);
});

test("lives: hours and cycles per gear, past the lines' end said so", () => {
  const rows = lifeRows(answer);
  assert.equal(rows.length, 6);
  assert.equal(rows[2].label, "Life at S_H = 1");
  assert.equal(lifeText(rows[2].values[0], rows[2].kind), "92,593");
  assert.equal(lifeText(rows[2].values[1], rows[2].kind), "past 1e10 cycles");
  assert.equal(lifeText(1.08e9, "cycles"), "1.080e9");
});

test("factors with four significant figures; text as text", () => {
  assert.equal(factorText(1.00298), "1.003");
  assert.equal(factorText(189.8117), "189.8");
  assert.equal(factorText(0.91012), "0.9101");
  assert.equal(factorText("F_betax"), "F_betax");
  assert.equal(factorText(null), "–");
});
