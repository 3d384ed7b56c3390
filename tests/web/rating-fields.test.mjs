// The rating form as data: its fields, choices and defaults are the rating
// schema's, its example is the shipped one, and what a person types becomes
// the rating document.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { CLASSES, FIELDS, TR_6336_30_EXAMPLE_1, documentFromValues, fieldPointerFor, hintText, parseValue }
  from "../../web/js/rating-fields.js";

const read = (path) => JSON.parse(readFileSync(new URL(`../../${path}`, import.meta.url), "utf8"));
const schema = read("schemas/rating.schema.json");
const spec = (pointer) => FIELDS.find((f) => f.pointer === pointer);

// The rating schema's node of a pointer (through $ref and array items).
function nodeAt(pointer) {
  let node = schema;
  for (const key of pointer.split("/").slice(1)) {
    node = /^\d+$/.test(key) ? node.items : node.properties?.[key];
    while (node?.$ref) node = node.$ref.replace(/^#\//, "").split("/").reduce((n, p) => n[p], schema);
    if (!node) return null;
  }
  return node;
}

test("the example is the shipped schemas/examples file", () => {
  assert.deepEqual(TR_6336_30_EXAMPLE_1, read("schemas/examples/rating-iso-tr-6336-30-1.json"));
});

test("every field is in the schema, with its choices and default", () => {
  for (const f of FIELDS) {
    const node = nodeAt(f.pointer);
    assert.ok(node, f.pointer);
    if (f.type === "enum") assert.deepEqual(f.options, node.enum, f.pointer);
    if (f.def !== undefined) assert.equal(f.def, node.default, f.pointer);
  }
  assert.deepEqual(CLASSES, nodeAt("/gears/0/material/iso6336_5/class").enum);
  assert.ok(FIELDS.filter((f) => f.gear === 1).length === FIELDS.filter((f) => f.gear === 0).length);
});

test("the example's every value has a field, so loading it loses nothing", () => {
  const leaves = (v, p) => (v && typeof v === "object" ? Object.entries(v).flatMap(([k, x]) => leaves(x, `${p}/${k}`)) : [p]);
  const pointers = FIELDS.map((f) => f.pointer);
  for (const p of leaves(TR_6336_30_EXAMPLE_1, "")) assert.ok(pointers.includes(p), p);
});

test("typed text becomes the rating document; empty fields are left out", () => {
  const doc = documentFromValues([
    [spec("/pair/normal_module_mm"), "8"],
    [spec("/pair/helix_angle_deg"), ""],
    [spec("/gears/1/teeth"), " 103 "],
    [spec("/gears/0/material/iso6336_5/class"), "Eh"],
    [spec("/gears/0/material/E_Pa"), "2.06e11"],
    [spec("/load/speed_rpm"), "fast"],
  ]);
  assert.deepEqual(doc, {
    pair: { normal_module_mm: 8 },
    gears: [{ material: { E_Pa: 2.06e11, iso6336_5: { class: "Eh" } } }, { teeth: 103, material: {} }],
    load: { speed_rpm: "fast" }, // refused by the server, at its field
  });
  assert.ok(Array.isArray(doc.gears));
  assert.equal(parseValue("17", spec("/gears/0/teeth")), 17);
  assert.equal(parseValue("NV(nitr)", spec("/gears/1/material/iso6336_5/class")), "NV(nitr)");
});

test("a problem's pointer finds its field, or the first field inside it", () => {
  const pointers = FIELDS.map((f) => f.pointer);
  assert.equal(fieldPointerFor("/gears/0/teeth", pointers), "/gears/0/teeth");
  assert.equal(fieldPointerFor("/gears/1/material/iso6336_5", pointers), "/gears/1/material/iso6336_5/class");
  assert.equal(fieldPointerFor("/gears/1/rim_thickness_mm", pointers), null);
  assert.equal(fieldPointerFor("", pointers), null);
});

test("hints name the default or what an empty field leaves to the server", () => {
  assert.equal(hintText(spec("/pair/pressure_angle_deg")), "default 20");
  assert.equal(hintText(spec("/pair/center_distance_mm")), "empty: from the shifts");
});
