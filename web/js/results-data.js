// Pure helpers over a job's results and documents (no DOM, no chart
// library): history.csv, the frame times of results.xmf, the meshing zone,
// the charts a history has, the conditions that tell compared jobs apart.
// Unit-tested in Node.

// history.csv -> {columns: [names], data: {name: Float64Array}}.
export function parseCsv(text) {
  const lines = text.split("\n").filter((l) => l.length);
  const columns = lines[0].split(",").map((s) => s.trim());
  const data = {};
  const n = lines.length - 1;
  for (const c of columns) data[c] = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    const cells = lines[i + 1].split(",");
    for (let k = 0; k < columns.length; k++) data[columns[k]][i] = cells[k] === "" ? NaN : Number(cells[k]);
  }
  return { columns, data, rows: n };
}

// Frame times from results.xmf (XDMF temporal collection).
export function frameTimes(xmf) {
  return [...xmf.matchAll(/<Time Value="([^"]+)"/g)].map((m) => Number(m[1]));
}

// The meshing zone of a rack-and-pinion run: around the pitch point
// (0, -r_p), the pinion being centred at the origin; null for other scenes.
export function meshingZone(summary) {
  const p = summary?.model?.pinion;
  if (!p?.pitch_radius_m || !p?.teeth) return null;
  const rp = p.pitch_radius_m;
  const m = (2 * rp) / p.teeth;
  return [-2.6 * m, -rp - 1.55 * m, 2.6 * m, -rp + 1.55 * m];
}

// History charts that exist in this run: [{id, title, quantity, unit, series}].
export function historyCharts(hist) {
  const cols = hist.columns;
  const d = hist.data;
  const pick = (re) => cols.filter((c) => re.test(c));
  const nice = (c) => c.replace(/^probe_/, "").replace(/_(m_s|N|Pa|m)$/, "").replace(/_/g, " ");
  const charts = [];
  const vel = [...pick(/^probe_.*_v[xy]_m_s$/), ...pick(/^rack_vx_m_s$/)];
  if (vel.length) {
    charts.push({ id: "chart-velocity", title: "Probe velocities", quantity: "velocity", unit: "m/s", prefix: false,
      series: vel.map((c) => ({ label: c === "rack_vx_m_s" ? "rack mean vx" : nice(c), values: d[c],
        dash: /_vy_/.test(c) ? [4, 3] : undefined })) });
  }
  const force = [...pick(/^contact_force_N$/), ...pick(/^tooth_force_.*_N$/)];
  if (force.length) {
    charts.push({ id: "chart-force", title: "Contact force", quantity: "force", unit: "N",
      series: force.map((c) => ({ label: c === "contact_force_N" ? "total contact force" : nice(c), values: d[c] })) });
  }
  const stress = [...pick(/^max_von_mises_Pa$/), ...pick(/^root_stress_.*_Pa$/)];
  if (stress.length) {
    charts.push({ id: "chart-stress", title: "Maximum stress", quantity: "stress", unit: "Pa",
      series: stress.map((c) => ({ label: c === "max_von_mises_Pa" ? "max von Mises" : nice(c), values: d[c] })) });
  }
  if (!charts.length) {
    const other = cols.filter((c) => c !== "time_s").slice(0, 4);
    charts.push({ id: "chart-history", title: "History", quantity: "value", unit: "", prefix: false,
      series: other.map((c) => ({ label: c, values: d[c] })) });
  }
  return charts;
}

// Parameters that say what a run's condition was, when they differ.
const KEY_PARAMETERS = ["/scene/pinion/omega_rad_s", "/scene/rack/load_N", "/discretization/spacing_m",
  "/discretization/spacing_mm", "/discretization/kernel", "/method/contact/model", "/method/formulation"];

function flatten(doc, prefix = "", out = {}) {
  for (const [k, v] of Object.entries(doc || {})) {
    const p = `${prefix}/${k}`;
    if (v && typeof v === "object" && !Array.isArray(v)) flatten(v, p, out);
    else out[p] = JSON.stringify(v);
  }
  return out;
}

function shortName(pointer) {
  return pointer.split("/").slice(-2).join(".").replace(/^(scene|method|time|output|discretization)\./, "");
}

export function conditions(jobDocs) {
  const flat = jobDocs.map((d) => flatten(d));
  const keys = new Set(flat.flatMap((f) => Object.keys(f)));
  let differing = [...keys].filter((k) => k !== "/name" && k !== "/threads" && new Set(flat.map((f) => f[k])).size > 1);
  if (!differing.length) differing = KEY_PARAMETERS.filter((k) => keys.has(k)).slice(0, 3);
  return flat.map((f) => differing.filter((k) => f[k] !== undefined).map((k) => `${shortName(k)} = ${f[k]}`).join(", "));
}
