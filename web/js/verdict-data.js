// The verdict of a rated static check (summary.analysis.rating,
// docs/rating.md) as rows: each failure mode's safety against its required
// value, the governing (smallest margin) first, and a level: red below the
// required safety, amber within 10 % above it, green beyond. Pure (no DOM).

// Margins between 1 and this are amber: little reserve for what the rating
// does not see (load spectrum, material scatter).
export const AMBER_MARGIN = 1.1;

export function level(margin) {
  if (!(margin >= 1)) return "red";
  return margin < AMBER_MARGIN ? "amber" : "green";
}

// [] when the run was not rated. A static check: the simulation's safeties
// (and the FE check's beside them, when it ran); a dynamic run: method B's,
// with the K_v the run measured where it reached a steady mesh.
export function verdictRows(summary) {
  const r = summary?.analysis?.rating;
  if (!r) return [];
  return ranked(r.simulated ? staticRows(r) : r.K_v ? dynamicRows(r) : []);
}

// Rows {S, required, ...} with their margin and level, the smallest margin
// (the governing mode) first; rows without both numbers are left out. The
// rating view ranks its rows with this too.
export function ranked(rows) {
  return rows
    .filter((row) => Number.isFinite(row.S) && Number.isFinite(row.required))
    .map((row) => ({ ...row, margin: row.S / row.required, level: level(row.S / row.required) }))
    .sort((x, y) => x.margin - y.margin);
}

function staticRows(r) {
  const sim = r.simulated, b = r.method_B || {}, fe = r.fe_check;
  const S_H = sim.S_H_resolved ?? sim.S_H_hertz;
  const feF = Number.isFinite(fe?.S_F) ? `; FE check ${fixed(fe.S_F)}` : "";
  const feH = Number.isFinite(fe?.S_H_hertz) ? `; FE load's Hertz ${fixed(fe.S_H_hertz)}` : "";
  const rows = [
    { mode: "Root bending, pinion", S: sim.S_F, required: r.required_S_F,
      note: `from the fillet's tension peak; ISO 6336 method B ${fixed(b.S_F_at_load_point)} at this load point, ${fixed(b.S_F)} at its own${feF}` },
    { mode: "Pitting, pinion", S: S_H, required: r.required_S_H,
      note: `${sim.S_H_resolved !== undefined ? "from the resolved contact pressure" : "Hertz on the simulated tooth force"}; method B ${fixed(b.S_H)}${feH}` },
  ];
  if (sim.S_yield !== undefined) {
    rows.push({ mode: "Yield at the fillet (static load)", S: sim.S_yield, required: 1, note: "yield strength over the fillet peak" });
  }
  return rows;
}

function dynamicRows(r) {
  const kv = r.K_v, b = r.method_B || {}, m = r.with_measured_K_v;
  const src = m || b;
  const how = m
    ? `method B with the measured K_v ${fixed(kv.measured)} (ISO's ${fixed(kv.iso6336_1_method_B)}); with ISO's K_v`
    : `method B, K_v ${fixed(kv.iso6336_1_method_B)} (not measured: ${kv.reason})`;
  return [
    { mode: "Root bending, pinion", S: src.S_F, required: r.required_S_F, note: m ? `${how} ${fixed(b.S_F)}` : how },
    { mode: "Pitting, pinion", S: src.S_H, required: r.required_S_H, note: m ? `${how} ${fixed(b.S_H)}` : how },
  ];
}

function fixed(v) {
  return Number.isFinite(v) ? v.toFixed(3) : "–";
}

// The safeties of a rated run, for the compare view; null if none: the
// simulated ones of a static check, a dynamic run's method B with its
// measured K_v (or ISO's where it measured none).
export function safeties(summary) {
  const r = summary?.analysis?.rating;
  const sim = r?.simulated;
  if (sim) return { S_F: sim.S_F, S_H: sim.S_H_resolved ?? sim.S_H_hertz };
  const d = r?.with_measured_K_v || (r?.K_v ? r.method_B : null);
  return d ? { S_F: d.S_F, S_H: d.S_H } : null;
}
