import { test } from "node:test";
import assert from "node:assert/strict";
import { conditions, frameTimes, historyCharts, meshingZone, parseCsv } from "../../web/js/results-data.js";

test("history.csv as columns of numbers; empty cells are NaN", () => {
  const h = parseCsv("time_s,contact_force_N,rack_vx_m_s\n0,0,-0.353\n1e-5,12.5,\n");
  assert.deepEqual(h.columns, ["time_s", "contact_force_N", "rack_vx_m_s"]);
  assert.equal(h.rows, 2);
  assert.equal(h.data.contact_force_N[1], 12.5);
  assert.ok(Number.isNaN(h.data.rack_vx_m_s[1]));
});

test("frame times from results.xmf", () => {
  const xmf = '<Grid><Time Value="0"/></Grid><Grid><Time Value="2.5e-05"/></Grid>';
  assert.deepEqual(frameTimes(xmf), [0, 2.5e-5]);
  assert.deepEqual(frameTimes(""), []);
});

test("the meshing zone is around the pitch point", () => {
  const zone = meshingZone({ model: { pinion: { pitch_radius_m: 0.024, teeth: 12 } } });
  const m = 0.004;
  assert.equal(zone.length, 4);
  assert.ok(Math.abs(zone[0] + 2.6 * m) < 1e-12);
  assert.ok(zone[1] < -0.024 && zone[3] > -0.024);
  assert.equal(meshingZone({ model: {} }), null);
});

test("the charts a history has", () => {
  const gear = parseCsv("time_s,probe_pinion_tooth_vx_m_s,rack_vx_m_s,contact_force_N,tooth_force_t1_N,max_von_mises_Pa\n0,0,0,0,0,0\n");
  assert.deepEqual(historyCharts(gear).map((c) => c.id), ["chart-velocity", "chart-force", "chart-stress"]);
  const plate = parseCsv("time_s,kinetic_J,tip_y_m\n0,0,0\n");
  const [only] = historyCharts(plate);
  assert.equal(only.id, "chart-history");
  assert.deepEqual(only.series.map((s) => s.label), ["kinetic_J", "tip_y_m"]);
});

test("conditions name what differs between jobs", () => {
  const a = { name: "a", scene: { type: "rack_pinion", rack: { load_N: 0 } } };
  const b = { name: "b", scene: { type: "rack_pinion", rack: { load_N: 500 } } };
  assert.deepEqual(conditions([a, b]), ["rack.load_N = 0", "rack.load_N = 500"]);
});
