// The rating view's answer: the safeties against the required ones (the
// verdict panel's table and colours), the stresses of each gear, every
// factor in its group and the lives at the required safeties.
import { factorGroups, factorText, fixed, gearNames, lifeRows, lifeText, safetyRows, stressRows } from "./rating-data.js";
import { verdictTable } from "./result-verdict.js";
import { h } from "./ui.js";

function panel(id, title, aside, ...body) {
  return h("section", { class: "panel", id, "aria-labelledby": `${id}-head` },
    h("header", {}, h("h2", { id: `${id}-head` }, title), aside ? h("span", { class: "muted" }, aside) : null),
    h("div", { class: "body" }, ...body));
}

// A table with a Pinion and a Wheel column; a value of the pair spans both.
function perGearTable(id, names, rows) {
  const head = h("thead", {}, h("tr", {}, h("th", { scope: "col" }, "Quantity"), h("th", { scope: "col", class: "unit-col" }, "Unit"),
    ...names.map((n) => h("th", { scope: "col", class: "num" }, n)), h("th", { scope: "col" }, "")));
  const body = rows.map((row) => {
    const v = row.values;
    const cells = Array.isArray(v)
      ? v.map((x) => h("td", { class: "num" }, row.text(x)))
      : [h("td", { class: "num pair-value", colspan: 2 }, row.text(v))];
    return h("tr", { dataset: { key: row.key || "" } }, h("th", { scope: "row" }, row.label), h("td", { class: "unit-col muted" }, row.unit),
      ...cells, h("td", { class: "muted" }, row.what || ""));
  });
  return h("div", { class: "table-wrap" }, h("table", { class: "rating-table", id }, head, h("tbody", {}, body)));
}

function verdictSection(r) {
  const rows = safetyRows(r);
  const g = r.governing || {};
  const aside = rows.length
    ? `governing: ${rows[0].mode.toLowerCase()} (S = ${fixed(rows[0].S)} against ${rows[0].required}); ${g.holds ? "the pair holds" : "the pair does not hold"}`
    : "";
  return panel("rating-verdict", "Safety factors", aside, verdictTable(rows, 3));
}

function stressSection(r, names) {
  const rows = stressRows(r).map(([label, unit, values]) => ({ label, unit, values, text: (x) => fixed(x, 1) }));
  return panel("rating-stresses", "Stresses", `F_t ${fixed(r.load?.F_t_N, 0)} N, v ${fixed(r.load?.v_m_s, 3)} m/s`,
    perGearTable("rating-stress-table", names, rows));
}

function factorSection(r, names) {
  const groups = factorGroups(r).map((g) => [
    h("h3", { class: "factor-group" }, g.title),
    perGearTable(`rating-factors-${g.title.split(" ")[0].toLowerCase()}`, names,
      g.rows.map((row) => ({ key: row.key, label: row.symbol || row.what, unit: row.unit, values: row.values,
        what: row.symbol ? row.what : "", text: factorText }))),
  ]);
  const life = lifeRows(r).map((row) => ({ label: row.label, unit: row.unit, values: row.values, text: (x) => lifeText(x, row.kind) }));
  return panel("rating-factors", "Factors and life", r.method || "",
    groups.flat(), h("h3", { class: "factor-group" }, "Life"), perGearTable("rating-life-table", names, life));
}

export function ratingResult(r) {
  const names = gearNames(r).map((n) => n[0].toUpperCase() + n.slice(1));
  return h("div", { class: "stack", id: "rating-result" },
    verdictSection(r), stressSection(r, names), factorSection(r, names));
}
