// A study's document (GET /studies/{id}) shaped for its page: the jobs'
// rows, the speed sweep's curves on one frequency axis, the resonance marks
// and the sentences under them. Pure functions (no DOM): unit-tested in Node.

// The curves' colours (charts.js's palette, named): SPH blue, the lumped
// model red, its speeds up and down purple and orange, ISO's stiffness grey.
const PALETTE_NAMES = { sph: "#1f77b4", lumped: "#d62728", up: "#9467bd", down: "#ff7f0e", iso: "#7f7f7f" };

export const ACTIVE = new Set(["accepted", "running"]);

// Whether any job of the study is still queued or running (the page polls).
export function isActive(study) {
  return (study.jobs || []).some((j) => ACTIVE.has(j.status));
}

// The axes' pointers of the jobs' parameters, in first-seen order.
export function parameterColumns(study) {
  const seen = [];
  for (const j of study.jobs || []) {
    for (const k of Object.keys(j.parameters || {})) if (!seen.includes(k)) seen.push(k);
  }
  return seen;
}

// One row per job: its link in the dashboard and what it varies.
export function jobRows(study) {
  return (study.jobs || []).map((j, k) => ({
    index: k + 1,
    jobID: j.jobID,
    href: `#/jobs/${encodeURIComponent(j.jobID)}`,
    status: j.status,
    progress: j.progress ?? 0,
    message: j.message || "",
    parameters: j.parameters || {},
  }));
}

// The speed sweep's jobs in ascending mesh frequency, as the report lists them.
export function sweepRows(study) {
  const f = (r) => (Number.isFinite(r.parameters.mesh_frequency_Hz) ? r.parameters.mesh_frequency_Hz : Infinity);
  return jobRows(study).sort((a, b) => f(a) - f(b));
}

const finite = (v) => typeof v === "number" && Number.isFinite(v);
const same = (a, b) => Math.abs(a - b) <= 1e-9 * Math.max(Math.abs(a), Math.abs(b));

// Curves sampled at different abscissae on one axis: [[x, y], ...] ->
// {x, ys}: the union of the (ascending) x, each y undefined where its curve
// has no sample (the chart bridges it) and null where its value is null (a
// gap). Abscissae equal to 1e-9 are one (the fine curve ends on the sweep's
// first and last speeds, up to rounding).
export function joinOnX(tables) {
  const xs = [];
  for (const [x] of tables) for (const v of x) if (finite(v)) xs.push(v);
  xs.sort((a, b) => a - b);
  const x = [];
  for (const v of xs) if (!x.length || !same(x[x.length - 1], v)) x.push(v);
  const ys = tables.map(([tx, ty]) => {
    const out = new Array(x.length).fill(undefined);
    tx.forEach((v, k) => {
      if (finite(v)) out[indexOf(x, v)] = finite(ty[k]) ? ty[k] : null;
    });
    return out;
  });
  return { x, ys };
}

// The index in ascending `x` of the abscissa equal to v (v is one of them).
function indexOf(x, v) {
  let lo = 0, hi = x.length - 1;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (x[mid] < v && !same(x[mid], v)) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

const anyNumber = (a) => Array.isArray(a) && a.some(finite);

// The K_v chart: the SPH runs and the lumped model at the sweep's speeds
// (points), the lumped model's fine curve (a line), and, when the lumped
// model used the measured stiffness, the same model on ISO's stiffness.
// series: [{label, values, colour, dash?, points?: {size, filled}, line}]
export function kvChart(report) {
  const f = report.mesh_frequency_Hz || [];
  const fine = report.mesh_frequency_Hz_fine || [];
  const curves = [];
  if (anyNumber(report.K_v_sph)) {
    curves.push({ label: "SPH", x: f, y: report.K_v_sph, colour: PALETTE_NAMES.sph, points: { size: 10, filled: true }, line: false });
  }
  curves.push({ label: "lumped, fine sweep", x: fine, y: report.K_v_sdof_fine || [], colour: PALETTE_NAMES.lumped, line: true });
  curves.push({ label: "lumped, speeds up", x: f, y: report.K_v_sdof || [], colour: PALETTE_NAMES.up, points: { size: 11, filled: false }, line: false });
  curves.push({ label: "lumped, speeds down", x: f, y: report.K_v_sdof_down || [], colour: PALETTE_NAMES.down, points: { size: 5, filled: true }, line: false });
  const iso = report.iso_stiffness_sdof;
  if (report.stiffness_from === "measured" && iso && anyNumber(iso.K_v_fine)) {
    curves.push({ label: "lumped, ISO 6336-1 stiffness", x: fine, y: iso.K_v_fine, colour: PALETTE_NAMES.iso, dash: [6, 4], line: true });
  }
  return chartOf(curves);
}

// The DTE chart in micrometres: the SPH runs (points), the lumped model at
// the same speeds (points, joined by a line once there are enough speeds to
// follow the resonance: a line through two or three would hide it).
export function dteChart(report) {
  const f = report.mesh_frequency_Hz || [];
  const um = (a) => (a || []).map((v) => (finite(v) ? v * 1e6 : null));
  const curves = [];
  if (anyNumber(report.dte_pp_m_sph)) {
    curves.push({ label: "SPH", x: f, y: um(report.dte_pp_m_sph), colour: PALETTE_NAMES.sph, points: { size: 10, filled: true }, line: false });
  }
  curves.push({ label: "lumped", x: f, y: um(report.dte_pp_m_sdof), colour: PALETTE_NAMES.lumped, points: { size: 7, filled: true }, line: f.length >= 5 });
  return chartOf(curves);
}

function chartOf(curves) {
  const { x, ys } = joinOnX(curves.map((c) => [c.x, c.y]));
  return {
    x,
    series: curves.map((c, k) => ({ label: c.label, values: ys[k], colour: c.colour, dash: c.dash, points: c.points, line: c.line })),
  };
}

// The sweep's range of mesh frequency [lo, hi], or null.
export function sweepRange(report) {
  const f = [...(report.mesh_frequency_Hz || []), ...(report.mesh_frequency_Hz_fine || [])].filter(finite);
  return f.length ? [Math.min(...f), Math.max(...f)] : null;
}

const RESONANCES = [["ISO 6336-1", "resonance_Hz_iso"], ["lumped", "resonance_Hz_sdof"], ["SPH", "resonance_Hz_sph"]];

// The resonances (numbers) outside the sweep's range: they cannot be
// marked on its axis, so the text names them. [name, Hz]
export function resonancesOutside(report) {
  const range = sweepRange(report);
  return RESONANCES.map(([name, key]) => [name, report[key]])
    .filter(([, v]) => finite(v) && range && (v < range[0] || v > range[1]));
}

// The resonances as vertical marks {value, name, label}: those that are
// numbers within the sweep's range. Marks closer than `near` of the span
// share one label (drawn at the first), so that their labels do not
// overprint each other.
export function resonanceMarks(report, near = 0.06) {
  const range = sweepRange(report);
  if (!range) return [];
  const found = RESONANCES.map(([name, key]) => [name, report[key]])
    .filter(([, v]) => finite(v) && v >= range[0] && v <= range[1]).sort((a, b) => a[1] - b[1]);
  const span = range[1] - range[0];
  const groups = [];
  for (const [name, value] of found) {
    const last = groups[groups.length - 1];
    if (last && value - last.at <= near * span) last.members.push([name, value]);
    else groups.push({ at: value, members: [[name, value]] });
  }
  return groups.flatMap((g) => g.members.map(([name, value], i) => ({
    value,
    name,
    label: i === 0 ? `${g.members.map(([n]) => n).join(" / ")} resonance` : "",
  })));
}

const hz = (v) => (finite(v) ? `${Number(v.toPrecision(4))} Hz` : "—");
const ratio = (a, b) => (finite(a) && finite(b) && b !== 0 ? (a / b).toFixed(3) : null);

const STIFFNESS = {
  iso: "ISO 6336-1 (c′ and 1.75 c′ over the mesh cycle)",
  measured: "measured (the SPH runs' stiffness over the mesh cycle)",
};

// The lines of text under the charts: [label, text].
export function reportLines(report) {
  const lines = [];
  lines.push(["Natural frequency", `${hz(report.natural_frequency_Hz_sdof)} (lumped model)`]);
  lines.push(["Mesh stiffness", STIFFNESS[report.stiffness_from] || String(report.stiffness_from ?? "—")]);
  const z = report.damping_ratio || {};
  lines.push(["Damping ratio", finite(z.value) ? `ζ = ${z.value.toFixed(3)}, ${z.from || "source not given"}` : "—"]);
  const iso = report.resonance_Hz_iso, sdof = report.resonance_Hz_sdof, sph = report.resonance_Hz_sph;
  lines.push(["Resonance", `ISO 6336-1 ${hz(iso)} · lumped ${hz(sdof)} · SPH ${hz(sph)}`]);
  const ratios = [["SPH/lumped", ratio(sph, sdof)], ["SPH/ISO", ratio(sph, iso)], ["lumped/ISO", ratio(sdof, iso)]]
    .filter(([, r]) => r !== null).map(([n, r]) => `${n} ${r}`);
  if (ratios.length) lines.push(["Ratios", ratios.join(" · ")]);
  const outside = resonancesOutside(report);
  if (outside.length) {
    const [lo, hi] = sweepRange(report);
    lines.push(["Not marked", `${outside.map(([n, v]) => `${n} ${hz(v)}`).join(", ")}: outside the sweep's ${hz(lo)} to ${hz(hi)}`]);
  }
  const isoModel = report.iso_stiffness_sdof;
  if (report.stiffness_from === "measured" && isoModel) {
    lines.push(["On ISO stiffness", `natural frequency ${hz(isoModel.natural_frequency_Hz)}, resonance ${hz(isoModel.resonance_Hz)}`]);
  }
  return lines;
}

// A plain sentence when no SPH speed gave a K_v, else null.
export function sphNote(study, report) {
  if (anyNumber(report.K_v_sph)) return null;
  const counts = study.counts || {};
  const ran = (counts.successful ?? 0) + (counts.failed ?? 0);
  if (ran === 0) return "No job ran: every speed was dismissed or cancelled, so the charts show the lumped model only.";
  return "No SPH speed reached a steady mesh: the charts show the lumped model only.";
}

// What the report's download is called: the study's name, file-safe.
export function reportFileName(study) {
  const base = String(study.name || study.studyID || "study").replace(/[^A-Za-z0-9._-]+/g, "_");
  return `${base}-speed-sweep.json`;
}

// A cell of the axes table: numbers to 4 significant figures, the rest as is.
export function cellText(v) {
  if (v === null || v === undefined || v === "") return "—";
  if (typeof v === "number") return Number.isInteger(v) ? String(v) : String(Number(v.toPrecision(4)));
  if (typeof v === "boolean") return v ? "yes" : "no";
  return String(v);
}
