// Compare: several finished jobs side by side, as in the paper's table
// (condition, max stress, velocity-stability time), and their histories
// overlaid on one time axis.
import { get, text } from "./api.js";
import { PALETTE, joinSeries, lineChart } from "./charts.js";
import { events } from "./events.js";
import { duration, eng, int } from "./format.js";
import { conditions, parseCsv } from "./results-data.js";
import { h } from "./ui.js";
import { safeties } from "./verdict-data.js";

// [history column, title, quantity, SI unit, choose a prefix]
const QUANTITIES = [
  ["rack_vx_m_s", "Rack velocity", "velocity", "m/s", false],
  ["probe_pinion_tooth_vx_m_s", "Pinion tooth velocity (x)", "velocity", "m/s", false],
  ["contact_force_N", "Contact force", "force", "N", true],
  ["max_von_mises_Pa", "Max von Mises stress", "stress", "Pa", true],
  ["transmission_error_m", "Transmission error", "error", "m", true],
];
export function compareView(root, params) {
  let disposed = false;
  let chart = null;
  const selected = new Set((params.get("ids") || "").split(",").filter(Boolean));
  const cache = new Map(); // id -> {summary, job, history}

  const pick = h("div", { class: "pick", id: "compare-pick" });
  const table = h("div", { class: "table-wrap", id: "compare-table" });
  const quantity = h("select", { id: "compare-quantity", "aria-label": "quantity to overlay" },
    QUANTITIES.map(([c, label]) => h("option", { value: c }, label)));
  const chartEl = h("div", { class: "chart", id: "compare-chart" });
  const state = h("span", { class: "muted", role: "status", "aria-live": "polite" });
  const csvLink = h("a", { class: "button small", id: "compare-csv", download: "comparison.csv", hidden: true }, "CSV");
  let csvUrl = null;

  root.append(
    h("div", { class: "page-head" }, h("h1", {}, "Compare jobs"),
      h("p", {}, "Pick finished jobs; the table lists what differs between them and their results.")),
    h("div", { class: "grid-2 compare-grid" },
      h("section", { class: "panel", "aria-labelledby": "pick-head" },
        h("header", {}, h("h2", { id: "pick-head" }, "Successful jobs")),
        h("div", { class: "body" }, pick)),
      h("div", { class: "stack" },
        h("section", { class: "panel", "aria-labelledby": "table-head" },
          h("header", {}, h("h2", { id: "table-head" }, "Results side by side"), state,
            h("span", { class: "spacer" }), csvLink),
          h("div", { class: "body" }, table)),
        h("section", { class: "panel", "aria-labelledby": "overlay-head" },
          h("header", {}, h("h2", { id: "overlay-head" }, "Histories overlaid"), quantity),
          h("div", { class: "body" }, chartEl)))));

  function renderPick() {
    const jobs = events.list().filter((j) => j.status === "successful");
    if (!jobs.length) {
      pick.replaceChildren(h("p", { class: "muted" }, events.loaded ? "No successful jobs yet." : "loading…"));
      return;
    }
    pick.replaceChildren(...jobs.map((j) => {
      const box = h("input", { type: "checkbox", value: j.jobID, checked: selected.has(j.jobID) });
      box.addEventListener("change", () => {
        if (box.checked) selected.add(j.jobID); else selected.delete(j.jobID);
        history.replaceState(null, "", `#/compare?ids=${[...selected].join(",")}`);
        load();
      });
      return h("label", {}, box, h("span", {}, j.name), h("span", { class: "muted mono", style: "font-size:11px" }, j.jobID.slice(0, 8)));
    }));
  }

  async function fetchJob(id) {
    if (!cache.has(id)) {
      cache.set(id, Promise.all([
        get(`/jobs/${id}/results`),
        get(`/jobs/${id}/files/job.json`),
        text(`/jobs/${id}/files/history.csv`).then(parseCsv),
      ]).then(([results, job, history]) => ({ id, summary: results.summary || {}, job, history })));
    }
    return cache.get(id);
  }

  async function load() {
    const ids = [...selected];
    if (!ids.length) {
      csvLink.hidden = true;
      table.replaceChildren(h("p", { class: "muted" }, "Select two or more jobs."));
      chart?.destroy();
      chart = null;
      chartEl.replaceChildren();
      return;
    }
    state.textContent = "loading…";
    let runs;
    try {
      runs = await Promise.all(ids.map(fetchJob));
    } catch (e) {
      state.textContent = `could not load: ${e.message}`;
      return;
    }
    if (disposed) return;
    state.textContent = `${runs.length} job${runs.length === 1 ? "" : "s"}`;
    const cond = conditions(runs.map((r) => r.job));
    // Rated static checks: their safeties side by side (docs/rating.md).
    const rated = runs.some((r) => safeties(r.summary));
    const safety = (r, key) => {
      const v = safeties(r.summary)?.[key];
      return Number.isFinite(v) ? v.toFixed(2) : "—";
    };
    const vst = (s) => s.velocity_stability_time_s === undefined ? "—"
      : s.velocity_stability_time_s < 0 ? "not settled" : eng(s.velocity_stability_time_s, "s");
    table.replaceChildren(h("table", {},
      h("thead", {}, h("tr", {},
        h("th", { scope: "col" }, "Job"), h("th", { scope: "col" }, "Condition"),
        h("th", { scope: "col", class: "num" }, "Max von Mises"),
        h("th", { scope: "col", class: "num" }, "Velocity-stability time"),
        h("th", { scope: "col", class: "num" }, "Max contact force"),
        rated ? h("th", { scope: "col", class: "num" }, "S_F") : null,
        rated ? h("th", { scope: "col", class: "num" }, "S_H") : null,
        h("th", { scope: "col", class: "num hide-narrow" }, "Particles"),
        h("th", { scope: "col", class: "num hide-narrow" }, "Wall time"))),
      h("tbody", {}, runs.map((r, k) => h("tr", {},
        h("td", {}, h("span", { class: "swatch", style: `background:${PALETTE[k % PALETTE.length]}` }),
          h("a", { href: `#/jobs/${r.id}` }, r.summary.name || r.job.name || r.id.slice(0, 8))),
        h("td", { class: "mono" }, cond[k] ? cond[k].split(", ").flatMap((part, i) =>
          [i ? ", " : "", h("span", { class: "nowrap" }, part)]) : "—"),
        h("td", { class: "num" }, eng(r.summary.max_von_mises_Pa, "Pa")),
        h("td", { class: "num" }, vst(r.summary)),
        h("td", { class: "num" }, r.summary.max_contact_force_N === undefined ? "—" : eng(r.summary.max_contact_force_N, "N")),
        rated ? h("td", { class: "num" }, safety(r, "S_F")) : null,
        rated ? h("td", { class: "num" }, safety(r, "S_H")) : null,
        h("td", { class: "num hide-narrow" }, int(r.summary.particles)),
        h("td", { class: "num hide-narrow" }, duration(r.summary.wall_s)))))));
    drawChart(runs);
    // The same table, in SI units, for a spreadsheet.
    const quote = (v) => (/[",\n]/.test(String(v)) ? `"${String(v).replace(/"/g, '""')}"` : String(v));
    const rows = [["job", "jobID", "condition", "max_von_mises_Pa", "velocity_stability_time_s", "max_contact_force_N", "particles", "wall_s", "S_F", "S_H"],
      ...runs.map((r, k) => [r.summary.name || r.job.name || "", r.id, cond[k] || "", r.summary.max_von_mises_Pa ?? "",
        r.summary.velocity_stability_time_s ?? "", r.summary.max_contact_force_N ?? "", r.summary.particles ?? "", r.summary.wall_s ?? "",
        safeties(r.summary)?.S_F ?? "", safeties(r.summary)?.S_H ?? ""])];
    if (csvUrl) URL.revokeObjectURL(csvUrl);
    csvUrl = URL.createObjectURL(new Blob([rows.map((r) => r.map(quote).join(",")).join("\n") + "\n"], { type: "text/csv" }));
    csvLink.href = csvUrl;
    csvLink.hidden = false;
  }

  function drawChart(runs) {
    chart?.destroy();
    chart = null;
    const [col, label, name, unit, prefix] = QUANTITIES.find(([c]) => c === quantity.value);
    const usable = runs.map((r, k) => ({ r, k })).filter(({ r }) => r.history.data[col]);
    if (!usable.length) {
      chartEl.replaceChildren(h("p", { class: "muted" }, `None of these jobs recorded ${label.toLowerCase()}.`));
      return;
    }
    const joined = joinSeries(usable.map(({ r }) => [r.history.data.time_s, r.history.data[col]]));
    chart = lineChart(chartEl, {
      title: label, time_s: joined[0], quantity: name, unit, prefix,
      series: usable.map(({ r, k }, i) => ({ label: r.summary.name || r.id.slice(0, 8), values: joined[i + 1], colour: PALETTE[k % PALETTE.length] })),
    });
  }

  quantity.addEventListener("change", () => load());
  const unsubscribe = events.subscribe((id, kind) => {
    if (kind === "reload" || kind === "status") renderPick();
  });
  renderPick();
  load();
  return {
    dispose() {
      disposed = true;
      unsubscribe();
      chart?.destroy();
      if (csvUrl) URL.revokeObjectURL(csvUrl);
    },
  };
}
