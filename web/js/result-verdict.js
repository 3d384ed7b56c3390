// The result view's "Verdict" panel: each failure mode's ISO 6336 safety
// against its required value, green, amber or red, the governing mode first.
// Its table is the rating view's too (rating-result.js).
import { h } from "./ui.js";
import { verdictRows } from "./verdict-data.js";

// Ranked rows (verdict-data.js) as table rows: mode, S, required, level,
// note; `digits` decimals of S.
export function verdictTable(rows, digits = 2) {
  return h("table", { class: "summary-table" }, h("tbody", {},
    rows.map((row) => h("tr", { class: `verdict ${row.level}`, dataset: row.kind ? { kind: row.kind, gear: row.gear } : {} },
      h("td", {}, row.mode),
      h("td", { class: "num" }, h("strong", { class: "safety" }, row.S.toFixed(digits))),
      h("td", { class: "num" }, `≥ ${row.required}`),
      h("td", {}, h("span", { class: `verdict-badge ${row.level}` }, row.level)),
      h("td", { class: "muted" }, row.note)))));
}

// null when the run was not rated.
export function verdictPanel(summary) {
  const rows = verdictRows(summary);
  if (!rows.length) return null;
  const r = summary.analysis.rating;
  return h("section", { class: "panel", id: "verdict", "aria-labelledby": "verdict-head" },
    h("header", {}, h("h2", { id: "verdict-head" }, "Verdict"),
      h("span", { class: "muted" }, `governing: ${rows[0].mode.toLowerCase()}; ${r.load_point ? `contact at ${r.load_point}` : "a dynamic run"}`)),
    h("div", { class: "body" }, verdictTable(rows)));
}
