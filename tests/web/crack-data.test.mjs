// The root crack as the result view shows it (web/js/crack-data.js), and
// the job form's crack section as data (web/js/submit-fields.js).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import {
  crackAnalysis, crackLengths, crackNumbers, crackVerdict, cyclesText, finalLength, kChart, mmText, niceTicks,
  pathFigure, pathPoints, stopText, verdictSentence,
} from "../../web/js/crack-data.js";
import { CRACK_GROUP, FIELDS, fieldPointerFor, fieldSchema, hintText, jobFromValues } from "../../web/js/submit-fields.js";

const schema = JSON.parse(readFileSync(new URL("../../schemas/job.schema.json", import.meta.url), "utf8"));
const close = (a, b, tol = 1e-12) => assert.ok(Math.abs(a - b) <= tol, `${a} is not ${b}`);

// The tip after each of 4 increments of 0.2 mm from a 1.0 mm crack on the
// paper's pinion (root near y = -19.5 mm), turning a little down.
function path(turnsDeg) {
  const p = [[-2.15e-3, -20.1e-3]];
  let a = 0;
  for (const t of turnsDeg) {
    a += (t * Math.PI) / 180;
    const [x, y] = p[p.length - 1];
    p.push([x + 0.2e-3 * Math.cos(a), y + 0.2e-3 * Math.sin(a)]);
  }
  return p;
}
const CRACK = {
  path_m: path([-12, -4, -2, 1]),
  increments: 4,
  increment_m: 0.2e-3,
  initial_length_m: 1.0e-3,
  spacing_m: 0.1e-3,
  start_fillet_position: 0.4725,
  K_I_Pa_sqrt_m: [3.1e6, 3.6e6, 4.2e6, 4.9e6, 5.8e6],
  K_II_Pa_sqrt_m: [0.35e6, 0.12e6, 0.05e6, -0.03e6, 0.02e6],
  K_eq_Pa_sqrt_m: [3.16e6, 3.61e6, 4.2e6, 4.9e6, 5.8e6],
  kink_deg: [-12.0, -4.0, -2.0, 1.0, -0.4],
  outcome: "tooth",
  reached_boundary: false,
  stop: "4 increments, as asked",
  paris: { C: 1e-11, m: 3, R: 0, cycles: 1234567, rule: "trapezoidal" },
};

test("the crack is read from analysis.crack, and only there", () => {
  assert.equal(crackAnalysis({ analysis: { crack: CRACK } }), CRACK);
  assert.equal(crackAnalysis({ analysis: {} }), null);
  assert.equal(crackAnalysis({}), null);
  assert.equal(crackAnalysis(null), null);
  assert.equal(crackAnalysis({ analysis: { crack: [1, 2] } }), null);
});

test("lengths: the initial one at the drawn tip, then each segment added", () => {
  const l = crackLengths(CRACK);
  assert.equal(l.length, 5);
  close(l[0], 1.0e-3);
  for (let k = 1; k < 5; k++) close(l[k] - l[k - 1], 0.2e-3, 1e-15);
  close(finalLength(CRACK), 1.8e-3, 1e-15);
  // Along the path, not the chord from the first tip to the last.
  const p = CRACK.path_m;
  assert.ok(finalLength(CRACK) - 1e-3 > Math.hypot(p[4][0] - p[0][0], p[4][1] - p[0][1]));
});

test("K of stage k goes with the length before increment k", () => {
  const c = kChart(CRACK);
  assert.equal(c.length_m.length, 5);
  assert.deepEqual(c.series.map((s) => s.label), ["K_I", "K_II", "K_eq (max. tangential stress)"]);
  close(c.length_m[0], 1.0e-3);
  close(c.series[0].values[0], 3.1, 1e-12); // MPa m^0.5
  close(c.series[0].values[4], 5.8, 1e-12);
  close(c.length_m[4], 1.8e-3, 1e-15);
  close(c.series[1].values[3], -0.03, 1e-12);
  // A run cut short (K for fewer stages than tips, or the reverse): pairs
  // beyond the shorter list are dropped, never shifted.
  const short = kChart({ ...CRACK, K_I_Pa_sqrt_m: [3.1e6, 3.6e6], K_II_Pa_sqrt_m: undefined, K_eq_Pa_sqrt_m: [] });
  assert.equal(short.length_m.length, 2);
  assert.equal(short.series.length, 1);
  close(short.length_m[1], 1.2e-3, 1e-15);
  const fewTips = kChart({ ...CRACK, path_m: CRACK.path_m.slice(0, 3) });
  assert.equal(fewTips.length_m.length, 3);
  close(fewTips.series[0].values[2], 4.2, 1e-12);
});

test("the verdict in words for each outcome", () => {
  const v = (outcome, reached) => crackVerdict({ outcome, reached_boundary: reached });
  assert.equal(v("tooth", true).headline, "breaks the tooth off");
  assert.equal(v("rim", true).headline, "runs through the rim: the wheel would split");
  assert.equal(v("arrested", false).headline, "arrested");
  assert.equal(v("arrested", false).level, "ok");
  assert.equal(v("tooth", true).level, "bad");
  // Not reached: where the last segment heads, and said so.
  assert.equal(v("tooth", false).headline, "heads to break the tooth off");
  assert.match(v("tooth", false).note, /where its last segment heads/);
  assert.equal(v("rim", false).headline, "heads through the rim: the wheel would split");
  assert.doesNotMatch(v("rim", true).note, /heads/);
  assert.equal(v(null, false).headline, "no outcome");
  assert.equal(crackVerdict(undefined).level, "none");
  assert.equal(verdictSentence(v("arrested", false)), "The crack is arrested");
  assert.equal(verdictSentence(v("tooth", true)), "The crack breaks the tooth off");
  assert.equal(verdictSentence(v(null, false)), "No outcome");
});

test("Paris cycles: an exponent from ten thousand, and no finite life said so", () => {
  assert.equal(cyclesText(1234567), "1.23e6");
  assert.equal(cyclesText(98765), "9.88e4");
  assert.equal(cyclesText(850.4), "850");
  assert.match(cyclesText(null), /^no finite life/);
  assert.match(cyclesText(undefined), /^no finite life/);
  assert.equal(cyclesText(Number.NaN), "—");
});

test("the numbers, each with its unit", () => {
  const rows = Object.fromEntries(crackNumbers(CRACK).map((r) => [r.key, r.value]));
  assert.equal(rows.initial, "1 mm");
  assert.equal(rows.final, "1.8 mm");
  assert.equal(rows.increments, "4 of 0.2 mm");
  assert.match(rows.start, /^0\.47 /);
  assert.equal(rows.spacing, "0.1 mm");
  assert.equal(rows.cycles, "1.23e6 cycles");
  assert.match(rows.paris, /C = 1\.00e-11, m = 3, R = 0/);
  const noLife = Object.fromEntries(crackNumbers({ ...CRACK, paris: { C: 1e-11, m: 3, R: 0, cycles: null } })
    .map((r) => [r.key, r.value]));
  assert.match(noLife.cycles, /^no finite life/);
  // Without paris no life rows; without anything, dashes, never NaN.
  assert.ok(!crackNumbers({ ...CRACK, paris: undefined }).some((r) => r.key === "cycles"));
  const empty = crackNumbers({});
  assert.ok(empty.every((r) => r.value === "—"), JSON.stringify(empty));
  assert.equal(mmText(undefined), "—");
});

test("missing or malformed fields: empty, not wrong", () => {
  assert.deepEqual(crackLengths({ path_m: CRACK.path_m }), []); // no initial length
  assert.deepEqual(crackLengths({ initial_length_m: 1e-3 }), []);
  assert.equal(finalLength({ initial_length_m: 1e-3 }), 1e-3);
  assert.equal(finalLength({}), null);
  assert.equal(kChart({}), null);
  assert.equal(kChart({ ...CRACK, K_I_Pa_sqrt_m: [], K_II_Pa_sqrt_m: [], K_eq_Pa_sqrt_m: [] }), null);
  assert.equal(pathPoints({ path_m: [[0, 1], [2, null], [3, 4]] }).length, 1);
  assert.equal(pathFigure({ path_m: [[0, 1]] }), null);
  assert.equal(stopText(undefined), "");
  assert.equal(stopText("the next tip would lie 7.534000 spacings from a boundary"), "the next tip would lie 7.53 spacings from a boundary");
  assert.equal(stopText("K_I -123456.000000 Pa m^0.5 fell below the threshold"), "K_I -123456 Pa m^0.5 fell below the threshold");
});

test("the path's figure: one scale for x and y, y up, the centre's way", () => {
  const f = pathFigure(CRACK, { width: 360, height: 260 });
  assert.equal(f.points.length, 5);
  const p = CRACK.path_m;
  // Equal aspect: pixel distances over mm distances are one number.
  const d = (a, b) => Math.hypot(a.x - b.x, a.y - b.y);
  for (let k = 1; k < 5; k++) close(d(f.points[k], f.points[k - 1]) / 0.2, f.scale, 1e-9);
  // The path turns down (y decreasing): the screen's y grows.
  assert.ok(p[4][1] < p[0][1] && f.points[4].y > f.points[0].y);
  assert.ok(f.points.every((q) => q.x >= f.plot.left && q.x <= f.plot.right && q.y >= f.plot.top && q.y <= f.plot.bottom));
  // The pinion's centre (the origin) lies up from a tooth at the bottom.
  assert.ok(f.centre.y < 0 && Math.abs(Math.hypot(f.centre.x, f.centre.y) - 1) < 1e-12);
  assert.ok(f.xTicks.length >= 2 && f.yTicks.length >= 2);
  assert.deepEqual(niceTicks(0, 1, 5), [0, 0.2, 0.4, 0.6, 0.8, 1]);
  assert.deepEqual(niceTicks(-20.3, -19.9, 4), [-20.3, -20.2, -20.1, -20, -19.9]);
});

// --- The job form's crack section.
const crackSpec = (pointer) => CRACK_GROUP[1].find((f) => f.pointer === pointer);

test("every crack field is in the schema, with its range and description", () => {
  for (const f of CRACK_GROUP[1]) {
    const { node, description } = fieldSchema(schema, f.pointer);
    assert.ok(node, f.pointer);
    assert.ok(f.describe && description.length > 10, `${f.pointer} shows a description`);
    assert.ok(FIELDS.includes(f), `${f.pointer} is a field of the form`);
  }
  const pos = crackSpec("/scene/crack/fillet_position");
  const { node, def } = fieldSchema(schema, pos.pointer);
  assert.equal(hintText(node, def, pos), 'range 0 to 1 or "peak"');
  const len = crackSpec("/scene/crack/length_mm");
  assert.equal(hintText(fieldSchema(schema, len.pointer).node, undefined, len), "range > 0, ≤ 1000");
  const ratio = crackSpec("/scene/pinion/backup_ratio");
  assert.equal(hintText(fieldSchema(schema, ratio.pointer).node, undefined, ratio), "range > 0, ≤ 50");
});

test("the crack goes into the job only while its section is on", () => {
  const entries = [
    [FIELDS.find((f) => f.pointer === "/scene/quasi_static"), "true"],
    [crackSpec("/scene/crack/fillet_position"), "peak"],
    [crackSpec("/scene/crack/length_mm"), "1.4"],
    [crackSpec("/scene/crack/angle_deg"), "0"],
    [crackSpec("/scene/crack/increment_mm"), ""],
    [crackSpec("/scene/crack/max_increments"), "40"],
    [crackSpec("/scene/crack/paris/C"), "1e-11"],
    [crackSpec("/scene/crack/paris/m"), "3"],
    [crackSpec("/scene/pinion/backup_ratio"), "1"],
  ];
  const off = jobFromValues(entries);
  assert.deepEqual(off.scene, { type: "rack_pinion", quasi_static: true });
  const on = jobFromValues(entries, { crack: true });
  assert.deepEqual(on.scene.crack, { fillet_position: "peak", length_mm: 1.4, angle_deg: 0, max_increments: 40, paris: { C: 1e-11, m: 3 } });
  assert.equal(on.scene.pinion.backup_ratio, 1);
  assert.equal(jobFromValues([[crackSpec("/scene/crack/fillet_position"), "0.45"]], { crack: true }).scene.crack.fillet_position, 0.45);
  // An unticked quasi-static box sends nothing (the schema's default, false).
  assert.equal(jobFromValues([[FIELDS.find((f) => f.pointer === "/scene/quasi_static"), ""]]).scene.quasi_static, undefined);
});

test("the server's pointers land on the crack's fields", () => {
  const pointers = FIELDS.map((f) => f.pointer);
  for (const p of ["/scene/crack/length_mm", "/scene/crack/increment_mm", "/scene/crack/fillet_position", "/scene/pinion/backup_ratio"]) {
    assert.equal(fieldPointerFor(p, pointers), p);
  }
  // A crack refused as a whole (a dynamic job), or a Paris law without m.
  assert.equal(fieldPointerFor("/scene/crack", pointers), "/scene/crack/fillet_position");
  assert.equal(fieldPointerFor("/scene/crack/paris", pointers), "/scene/crack/paris/C");
});
