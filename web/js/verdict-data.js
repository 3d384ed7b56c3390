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

// [] when the run was not rated.
export function verdictRows(summary) {
  const r = summary?.analysis?.rating;
  if (!r || !r.simulated) return [];
  const sim = r.simulated, b = r.method_B || {};
  const S_H = sim.S_H_resolved ?? sim.S_H_hertz;
  const rows = [
    { mode: "Root bending, pinion", S: sim.S_F, required: r.required_S_F,
      note: `from the fillet's tension peak; ISO 6336 method B ${fixed(b.S_F_at_load_point)} at this load point, ${fixed(b.S_F)} at its own` },
    { mode: "Pitting, pinion", S: S_H, required: r.required_S_H,
      note: `${sim.S_H_resolved !== undefined ? "from the resolved contact pressure" : "Hertz on the simulated tooth force"}; method B ${fixed(b.S_H)}` },
  ];
  if (sim.S_yield !== undefined) {
    rows.push({ mode: "Yield at the fillet (static load)", S: sim.S_yield, required: 1, note: "yield strength over the fillet peak" });
  }
  return rows
    .filter((row) => Number.isFinite(row.S) && Number.isFinite(row.required))
    .map((row) => ({ ...row, margin: row.S / row.required, level: level(row.S / row.required) }))
    .sort((x, y) => x.margin - y.margin);
}

function fixed(v) {
  return Number.isFinite(v) ? v.toFixed(3) : "–";
}

// The simulated safeties of a rated run, for the compare view; null if none.
export function safeties(summary) {
  const sim = summary?.analysis?.rating?.simulated;
  if (!sim) return null;
  return { S_F: sim.S_F, S_H: sim.S_H_resolved ?? sim.S_H_hertz };
}
