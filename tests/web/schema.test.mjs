// The form's view of the job schema, on the real schema.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { getPointer, limitsText, nodeAt, setPointer, unitOf } from "../../web/js/schema.js";

const schema = JSON.parse(readFileSync(new URL("../../schemas/job.schema.json", import.meta.url), "utf8"));

test("nodeAt follows a pointer into the rack-and-pinion scene", () => {
  const teeth = nodeAt(schema, "/scene/pinion/teeth");
  assert.equal(teeth.type, "integer");
  assert.equal(teeth.minimum, 6);
  assert.equal(teeth.maximum, 300);
  assert.equal(nodeAt(schema, "/scene/material/E_Pa").type, "number");
  assert.ok(nodeAt(schema, "/discretization/kernel").enum.length > 1);
  assert.equal(nodeAt(schema, "/scene/no/such/field"), null);
});

test("limits as the form shows them", () => {
  assert.equal(limitsText({ minimum: 6, maximum: 300 }), "6 to 300");
  assert.equal(limitsText({ exclusiveMinimum: 0, maximum: 100 }), "> 0, ≤ 100");
  assert.equal(limitsText({ exclusiveMinimum: 0 }), "> 0");
  assert.equal(limitsText({ minimum: 0, maximum: 1e12 }), "0 to 1e12");
  assert.equal(limitsText({ enum: ["a", "b"] }), "");
  assert.equal(limitsText(nodeAt(schema, "/scene/pinion/teeth")), "6 to 300");
});

test("units from the field names", () => {
  assert.equal(unitOf("/scene/pinion/module_mm"), "mm");
  assert.equal(unitOf("/scene/pinion/omega_rad_s"), "rad/s");
  assert.equal(unitOf("/scene/rack/velocity_m_s"), "m/s");
  assert.equal(unitOf("/scene/material/rho_kg_m3"), "kg/m³");
  assert.equal(unitOf("/scene/material/E_Pa"), "Pa");
  assert.equal(unitOf("/time/end_s"), "s");
  assert.equal(unitOf("/scene/material/nu"), "");
});

test("pointers read and write nested documents", () => {
  const doc = {};
  setPointer(doc, "/scene/pinion/teeth", 14);
  setPointer(doc, "/name", "x");
  assert.deepEqual(doc, { scene: { pinion: { teeth: 14 } }, name: "x" });
  assert.equal(getPointer(doc, "/scene/pinion/teeth"), 14);
  assert.equal(getPointer(doc, "/scene/rack/load_N"), undefined);
  assert.equal(getPointer(doc, "/name/x"), undefined);
});
