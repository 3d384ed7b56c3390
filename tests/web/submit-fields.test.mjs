// The New job form as data: what a person types becomes the job, and the
// server's problems find their fields.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { FIELDS, fieldId, fieldPointerFor, fieldSchema, formText, hintText, jobFromValues, parseValue }
  from "../../web/js/submit-fields.js";

const schema = JSON.parse(readFileSync(new URL("../../schemas/job.schema.json", import.meta.url), "utf8"));
const spec = (pointer) => FIELDS.find((f) => f.pointer === pointer);

test("every field of the form exists in the schema", () => {
  for (const f of FIELDS) assert.ok(fieldSchema(schema, f.pointer).node, f.pointer);
});

test("defaults come from the field or its enclosing object", () => {
  assert.equal(fieldSchema(schema, "/scene/pinion/teeth").def, 12);
  assert.equal(typeof fieldSchema(schema, "/scene/material/E_Pa").def, "number");
  const teeth = spec("/scene/pinion/teeth");
  const { node, def } = fieldSchema(schema, teeth.pointer);
  assert.equal(hintText(node, def, teeth), "range 6 to 300 · default 12");
});

test("typed text becomes the job's values", () => {
  assert.equal(parseValue("12", spec("/scene/pinion/teeth")), 12);
  assert.equal(parseValue("1e-3", spec("/time/end_s")), 0.001);
  assert.equal(parseValue("abc", spec("/time/end_s")), "abc"); // refused by the server, at the field
  assert.equal(parseValue("auto", spec("/scene/pinion/modelled_teeth")), "auto");
  assert.equal(parseValue("3", spec("/scene/pinion/modelled_teeth")), 3);
  assert.equal(parseValue("007", spec("/name")), "007");
  const job = jobFromValues([[spec("/name"), " short "], [spec("/scene/pinion/teeth"), "14"],
    [spec("/time/dt_s"), ""], [spec("/time/end_s"), "0.001"]]);
  assert.deepEqual(job, { scene: { type: "rack_pinion", pinion: { teeth: 14 } }, name: "short", time: { end_s: 0.001 } });
});

test("large numbers are written with an exponent", () => {
  assert.equal(formText(1.73e11), "1.73e11");
  assert.equal(formText(7800), "7800");
  assert.equal(formText(undefined), "");
  assert.equal(formText("auto"), "auto");
});

test("a problem's pointer finds the field that concerns it", () => {
  const pointers = FIELDS.map((f) => f.pointer);
  assert.equal(fieldPointerFor("/scene/pinion/teeth", pointers), "/scene/pinion/teeth");
  assert.equal(fieldPointerFor("/discretization", pointers), "/discretization/spacing_mm");
  assert.equal(fieldPointerFor("/discretization/spacing_m", pointers), "/discretization/spacing_mm");
  assert.equal(fieldPointerFor("/time/cfl", pointers), "/time/dt_s");
  assert.equal(fieldPointerFor("/scene/material", pointers), "/scene/material/E_Pa");
  assert.equal(fieldPointerFor("/output/images", pointers), null);
  assert.equal(fieldPointerFor("", pointers), null);
  assert.equal(fieldId("/scene/pinion/teeth"), "f-scene-pinion-teeth");
});

test("the strength fields add an ISO 6336-5 material only when a class is chosen", () => {
  const cls = spec("/scene/material/iso6336_5/class");
  assert.ok(cls.optional, "the class starts empty");
  assert.deepEqual(fieldSchema(schema, cls.pointer).node.enum.includes("GJS"), true);
  assert.equal(jobFromValues([[cls, ""], [spec("/scene/material/iso6336_5/hardness_HB"), ""]]).scene.material, undefined);
  const job = jobFromValues([[cls, "GJS"], [spec("/scene/material/iso6336_5/hardness_HB"), "250"]]);
  assert.deepEqual(job.scene.material.iso6336_5, { class: "GJS", hardness_HB: 250 });
  // Every class of ISO 6336-5:2016 Table 8 is offered, with the V steels' kind
  // and the Vickers hardness the steels' lines are read in.
  for (const c of ["St", "St(cast)", "GTS", "GJS", "GJL", "V", "V(cast)", "Eh", "IF", "NT", "NV(nitr)", "NV(nitrocar)"]) {
    assert.ok(fieldSchema(schema, cls.pointer).node.enum.includes(c), c);
  }
  const v = jobFromValues([[cls, "V"], [spec("/scene/material/iso6336_5/steel"), "alloy"],
    [spec("/scene/material/iso6336_5/hardness_HV"), "300"]]);
  assert.deepEqual(v.scene.material.iso6336_5, { class: "V", steel: "alloy", hardness_HV: 300 });
});
