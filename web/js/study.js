// One study (POST /studies): its jobs with their status, refreshed every
// 2 s while any is queued or running; once all have finished, a speed
// sweep's K_v and transmission-error curves against mesh frequency beside
// the lumped model's, or an axes study's table and its CSV.
import { ApiError, get } from "./api.js";
import { lineChart } from "./charts.js";
import { when } from "./format.js";
import { progressBar, statusBadge } from "./job-parts.js";
import {
  cellText, dteChart, isActive, jobRows, kvChart, parameterColumns, reportFileName, reportLines,
  resonanceMarks, sphNote, sweepRows,
} from "./study-data.js";
import { h, put } from "./ui.js";

const POLL_MS = 2000;
const RETRY_MS = 5000; // after a failed refresh (server restarting)

const KIND = { speed_sweep: "speed sweep", axes: "parameter axes" };

function panel(id, title, aside, ...body) {
  return h("section", { class: "panel", id, "aria-labelledby": `${id}-head` },
    h("header", {}, h("h2", { id: `${id}-head` }, title), ...(Array.isArray(aside) ? aside : [aside])),
    h("div", { class: "body" }, ...body));
}

const fixed = (v, d) => (Number.isFinite(v) ? v.toFixed(d) : "—");

// lineChart draws every series as a line; a curve known only at the
// sweep's speeds is drawn as its points instead, and a dimensionless value
// shows no unit. These are uPlot's series options, set right after the
// chart is made: uPlot draws first in a microtask, so it draws them (a
// redraw() before that first draw would lose the scales).
function styleSeries(chart, series, format) {
  chart.plot.series.forEach((s, i) => {
    const spec = series[i - 1];
    if (!spec) return;
    if (format) s.value = (u, v) => (v === null || v === undefined ? "—" : format(v));
    if (spec.line === false) s.paths = () => null;
    if (spec.points) {
      s.points.show = () => true;
      s.points.size = spec.points.size;
      s.points.width = 1.5;
      s.points.fill = () => (spec.points.filled ? spec.colour : "#ffffff");
    }
  });
}

function overview(study) {
  const item = (label, value) => h("div", {}, h("dt", {}, label), h("dd", {}, value));
  const c = study.counts || {};
  const counts = [["accepted", "queued"], ["running", "running"], ["successful", "successful"],
    ["failed", "failed"], ["dismissed", "dismissed"]]
    .filter(([k]) => c[k] > 0).map(([k, word]) => `${c[k]} ${word}`).join(" · ") || "none";
  return h("dl", { class: "kv", id: "study-overview" },
    item("Kind", KIND[study.kind] || study.kind || "—"),
    item("Status", statusBadge(study.status)),
    item("Progress", progressBar({ progress: study.progress, name: study.name })),
    item("Jobs", h("span", { id: "study-counts" }, counts)),
    item("Created", when(study.created)));
}

// The jobs; a finished sweep adds each speed's K_v (SPH and lumped).
function jobsTable(study, report) {
  const sweep = study.kind === "speed_sweep";
  const rows = sweep ? sweepRows(study) : jobRows(study);
  const pointers = sweep ? [] : parameterColumns(study);
  const kvAt = (f, key) => {
    const k = (report?.mesh_frequency_Hz || []).findIndex((x) => Math.abs(x - f) <= 1e-9 * Math.abs(f));
    return k < 0 ? undefined : report[key]?.[k];
  };
  const withKv = sweep && report && !report.error;
  const th = (text, cls) => h("th", { scope: "col", class: cls }, text);
  return h("div", { class: "table-wrap" }, h("table", { id: "study-jobs" },
    h("thead", {}, h("tr", {}, th("#", "num"),
      sweep ? [th("f / f_n", "num"), th("Mesh frequency [Hz]", "num")] : pointers.map((p) => h("th", { scope: "col", class: "mono pointer" }, p)),
      th("Status"), th("Progress"),
      withKv ? [th("K_v SPH", "num"), th("K_v lumped", "num")] : null,
      th("Job"))),
    h("tbody", {}, rows.map((r) => h("tr", { class: `status-${r.status}`, dataset: { job: r.jobID } },
      h("td", { class: "num" }, String(r.index)),
      sweep
        ? [h("td", { class: "num" }, fixed(r.parameters.ratio, 3)), h("td", { class: "num" }, fixed(r.parameters.mesh_frequency_Hz, 1))]
        : pointers.map((p) => h("td", { class: "mono" }, cellText(r.parameters[p]))),
      h("td", { title: r.message }, statusBadge(r.status),
        r.status === "failed" && r.message ? h("div", { class: "small-note failure" }, r.message) : null),
      h("td", {}, progressBar({ progress: r.progress, name: `job ${r.index}` })),
      withKv ? [h("td", { class: "num" }, fixed(kvAt(r.parameters.mesh_frequency_Hz, "K_v_sph"), 3)),
        h("td", { class: "num" }, fixed(kvAt(r.parameters.mesh_frequency_Hz, "K_v_sdof"), 3))] : null,
      h("td", {}, h("a", { href: r.href, class: "job-link" }, r.jobID.slice(0, 8))))))));
}

// The speed sweep's report: two charts, the lines of text, the download.
function sweepReport(study, report, charts, download) {
  if (report.error) {
    return panel("study-report", "Speed sweep", null, h("div", { class: "problems" }, report.error));
  }
  const marks = resonanceMarks(report);
  const kvEl = h("div", { class: "chart", id: "study-kv-chart" });
  const dteEl = h("div", { class: "chart", id: "study-dte-chart" });
  const note = sphNote(study, report);
  const lines = reportLines(report);
  const section = panel("study-report", "Speed sweep", [h("span", { class: "muted" }, `${(report.mesh_frequency_Hz || []).length} speeds`),
    h("span", { class: "spacer" }), download],
  note ? h("p", { class: "empty-note", id: "study-sph-note" }, note) : null,
  h("div", { class: "charts" }, kvEl, dteEl),
  h("p", { class: "note" }, "Points are the sweep's speeds: SPH filled blue; the lumped model going up (hollow) and coming down (dots), ",
    "which part where the response jumps. The red line is the lumped model on a fine sweep. Dashed verticals: the resonances."),
  h("dl", { class: "report-lines", id: "study-lines" },
    lines.flatMap(([label, text]) => [h("dt", {}, label), h("dd", {}, text)])));
  // Drawn once the panel is in the page (the charts take its width).
  section.draw = () => {
    const x = { quantity: "mesh frequency", symbol: "f_z", unit: "Hz" };
    const kv = kvChart(report);
    const kvPlot = lineChart(kvEl, { title: "Dynamic factor K_v against mesh frequency", x: { ...x, values: kv.x },
      quantity: "dynamic factor K_v", unit: "–", prefix: false, series: kv.series, marks });
    styleSeries(kvPlot, kv.series, (v) => v.toPrecision(4));
    // The marks are drawn on the canvas: a screen reader hears them here.
    const named = marks.map((m) => `${m.name} resonance at ${Number(m.value.toPrecision(4))} Hz`);
    if (named.length) kvEl.setAttribute("aria-label", `${kvEl.getAttribute("aria-label")}; ${named.join("; ")}`);
    const dte = dteChart(report);
    const dtePlot = lineChart(dteEl, { title: "Dynamic transmission error, peak to peak", x: { ...x, values: dte.x },
      quantity: "DTE peak to peak", unit: "µm", prefix: false, series: dte.series, marks });
    styleSeries(dtePlot, dte.series);
    charts.push(kvPlot, dtePlot);
  };
  return section;
}

// An axes study's table, every column the server gives, and its CSV.
function axesReport(study, id) {
  const columns = study.columns || [];
  const csv = h("a", { class: "button small", id: "study-csv", href: `/studies/${encodeURIComponent(id)}?format=csv`,
    download: `${reportFileName(study).replace(/-speed-sweep\.json$/, "")}.csv` }, "CSV");
  return panel("study-report", "Results", [h("span", { class: "muted" }, `${(study.table || []).length} rows`),
    h("span", { class: "spacer" }), csv],
  h("div", { class: "table-wrap" }, h("table", { id: "study-table", class: "study-table" },
    h("thead", {}, h("tr", {}, columns.map((c) => h("th", { scope: "col",
      class: typeof study.table?.[0]?.[c] === "number" && c !== "job" ? "mono num" : "mono" }, c)))),
    h("tbody", {}, (study.table || []).map((row) => h("tr", {},
      columns.map((c) => c === "jobID" && row[c]
        ? h("td", { class: "mono" }, h("a", { href: `#/jobs/${encodeURIComponent(row[c])}` }, String(row[c]).slice(0, 8)))
        : h("td", { class: typeof row[c] === "number" && c !== "job" ? "num" : "" }, cellText(row[c])))))))));
}

export function studyView(root, id) {
  let disposed = false;
  let timer = null;
  let charts = [];
  let reportUrl = null;
  let shownKey = "";

  const head = h("div", { class: "result-head", id: "study-head" }, h("h1", {}, "Study"));
  const state = h("span", { class: "muted", role: "status", "aria-live": "polite", id: "study-state" }, "loading…");
  const summary = h("div", { class: "body" });
  const jobs = h("div", { class: "body" });
  const report = h("div", { id: "study-report-holder" });
  root.append(h("p", { style: "margin:0 0 8px" }, h("a", { href: "#/jobs" }, "← All jobs")), head,
    h("div", { class: "stack study-stack" },
      h("section", { class: "panel", id: "study-summary" }, h("header", {}, h("h2", {}, "Overview"), state), summary),
      h("section", { class: "panel", id: "study-jobs-panel", "aria-labelledby": "study-jobs-head" },
        h("header", {}, h("h2", { id: "study-jobs-head" }, "Jobs")), jobs),
      report));

  function clearReport() {
    for (const c of charts) c.destroy();
    charts = [];
    if (reportUrl) URL.revokeObjectURL(reportUrl);
    reportUrl = null;
  }

  function showReport(study) {
    clearReport();
    if (isActive(study)) {
      put(report, h("div", { class: "empty", id: "study-pending" },
        study.kind === "speed_sweep" ? "The curves against mesh frequency appear here once every speed has finished."
          : "The table appears here once every job has finished."));
      return;
    }
    if (study.kind === "speed_sweep" && study.speed_sweep) {
      reportUrl = URL.createObjectURL(new Blob([JSON.stringify(study.speed_sweep, null, 2) + "\n"], { type: "application/json" }));
      const download = h("a", { class: "button small", id: "study-report-json", href: reportUrl, download: reportFileName(study) }, "Report JSON");
      const section = sweepReport(study, study.speed_sweep, charts, download);
      put(report, section);
      section.draw?.();
    } else {
      put(report, axesReport(study, id));
    }
  }

  function show(study) {
    put(head, h("h1", { id: "study-title" }, study.name || "study"), statusBadge(study.status),
      h("span", { class: "muted mono" }, study.studyID));
    put(summary, overview(study));
    put(jobs, jobsTable(study, isActive(study) ? null : study.speed_sweep));
    // The report is redrawn only when what it shows can have changed.
    const key = `${study.status}|${JSON.stringify(study.counts)}|${isActive(study)}`;
    if (key !== shownKey) {
      shownKey = key;
      showReport(study);
    }
    state.textContent = isActive(study) ? "refreshing every 2 s" : "finished";
  }

  async function load() {
    timer = null;
    try {
      const study = await get(`/studies/${encodeURIComponent(id)}`);
      if (disposed) return;
      show(study);
      if (isActive(study)) timer = setTimeout(load, POLL_MS);
    } catch (e) {
      if (disposed) return;
      if (e instanceof ApiError && e.status === 404) {
        put(head, h("h1", { id: "study-title" }, "No such study"));
        state.textContent = "";
        put(summary, h("p", { id: "study-missing" }, `There is no study ${id} on this server: it may have been deleted, `,
          "or the link is from another server. ", h("a", { href: "#/jobs" }, "All jobs"), "."));
        jobs.closest("section").hidden = true;
        return;
      }
      state.textContent = `could not refresh: ${e.message}; trying again`;
      timer = setTimeout(load, RETRY_MS);
    }
  }

  load();
  return {
    dispose() {
      disposed = true;
      clearTimeout(timer);
      clearReport();
    },
  };
}
