// One job: live progress while it runs; once it has finished, the rendered
// field with a frame slider, play and zoom, the fillet stress of a static
// gear check, the time-history charts, the summary numbers and the files.
import { ApiError, get, text } from "./api.js";
import { lineChart } from "./charts.js";
import { events } from "./events.js";
import { duration, eng, eta, int } from "./format.js";
import { cancelJob, feCheckBadge, progressBar, stageName, statusBadge } from "./job-parts.js";
import { crackPanel } from "./result-crack.js";
import { filletPanel } from "./result-fillet.js";
import { summaryPanel } from "./result-summary.js";
import { fieldViewer } from "./result-viewer.js";
import { frameTimes, historyCharts, parseCsv } from "./results-data.js";
import { h, put } from "./ui.js";

export function resultView(root, id) {
  let disposed = false;
  let charts = [];
  let viewer = null;
  let loaded = false;

  const head = h("div", { class: "result-head" });
  const live = h("section", { class: "panel", id: "live" });
  const content = h("div", { class: "stack", id: "result-content" });
  root.append(h("p", { style: "margin:0 0 8px" }, h("a", { href: "#/jobs" }, "← All jobs")), head, live, content);

  let headKey = "";
  function showHead(job) {
    const active = job.status === "accepted" || job.status === "running";
    // Progress events come four times a second: redraw only on a change.
    const key = `${job.name}|${job.status}|${job.message}|${job.fe_check?.status}|${job.studyID}`;
    if (key === headKey) return;
    headKey = key;
    put(head,
      h("h1", { id: "job-title" }, job.name || "job"),
      statusBadge(job.status),
      feCheckBadge(job),
      h("span", { class: "message" }, job.message || ""),
      job.studyID ? h("a", { href: `#/studies/${encodeURIComponent(job.studyID)}`, id: "job-study", title: "the study this job belongs to" }, "study") : null,
      h("span", { style: "flex:1" }),
      active ? h("button", { type: "button", class: "danger", onclick: () => cancelJob(job) }, "Cancel job") : null);
  }

  function showLive(job) {
    const active = job.status === "accepted" || job.status === "running";
    live.hidden = !active && loaded;
    if (!active && loaded) return;
    const item = (label, value) => h("div", {}, h("dt", {}, label), h("dd", {}, value));
    put(live,
      h("header", {}, h("h2", {}, active ? "Progress" : "Run"), h("span", { class: "muted" }, "live")),
      h("div", { class: "body" }, progressBar(job),
        h("dl", { class: "kv", style: "margin-top:12px" },
          item("Step", `${int(job.step)} / ${int(job.steps)}`),
          item("Simulated", `${eng(job.simulated_s, "s")} of ${eng(job.end_s, "s")}`),
          job.stage ? item("Stage", stageName(job)) : null,
          item("Wall time", job.fe_check && job.stage_wall_s
            ? `${duration(job.wall_s)} (SPH ${duration(job.stage_wall_s.sph)}, FE ${duration(job.stage_wall_s.fe_check ?? 0)})`
            : duration(job.wall_s)),
          item("ETA", eta(job)),
          item("Particles", int(job.particles)))));
  }

  async function refresh(job) {
    if (disposed || !job) return;
    showHead(job);
    showLive(job);
    if ((job.status === "accepted" || job.status === "running") && !content.firstChild) {
      content.append(h("div", { class: "empty", id: "pending-note" },
        "The rendered field, the charts, the summary and the downloads appear here when the run has finished."));
    }
    if (job.status === "successful" && !loaded) {
      loaded = true;
      live.hidden = true;
      await loadResults(job).catch((e) => put(content,
        h("div", { class: "problems" }, `Could not load the results: ${e.message}`)));
    } else if (job.status === "dismissed" && !loaded) {
      loaded = true;
      live.hidden = true;
      content.replaceChildren(h("div", { class: "empty" },
        job.step < job.steps ? `This job was cancelled at step ${int(job.step)} of ${int(job.steps)}; it has no results. `
          : "This job was dismissed; its results were deleted. ",
        h("a", { href: "#/submit" }, "Submit a new job"), "."));
    } else if (job.status === "failed" && !loaded) {
      loaded = true;
      try {
        await get(`/jobs/${id}/results`);
      } catch (e) {
        content.replaceChildren(h("div", { class: "problems" }, h("strong", {}, "The run failed. "), e.message));
      }
    }
  }

  get(`/jobs/${id}`).then((job) => {
    events.remember(job);
    refresh(job);
  }).catch((e) => {
    head.replaceChildren(h("h1", {}, "No such job"));
    live.replaceChildren(h("div", { class: "body" }, e instanceof ApiError ? e.message : String(e)));
  });
  const unsubscribe = events.subscribe((jobId) => {
    if (jobId === id || jobId === null) refresh(events.jobs.get(id));
  });

  async function loadResults(job) {
    const [results, xmf, csv] = await Promise.all([
      get(`/jobs/${id}/results`),
      text(`/jobs/${id}/files/results.xmf`).catch(() => ""),
      text(`/jobs/${id}/files/history.csv`),
    ]);
    if (disposed) return;
    const summary = results.summary || {};
    const times = frameTimes(xmf);
    // The image on show, also offered with the other downloads.
    const pngDownload = h("a", { class: "button small", id: "png-download", hidden: times.length === 0 },
      "image.png", h("span", { class: "muted" }, "this frame"));
    const fillet = filletPanel(id, summary, results.files);
    if (fillet) charts.push(fillet);
    const crack = crackPanel(summary);
    if (crack) charts.push(crack);
    viewer = fieldViewer(id, summary, times, pngDownload);
    put(content,
      h("div", { class: "split" }, viewer.section, summaryPanel(summary, results.files, pngDownload)),
      fillet?.section,
      crack?.section,
      h("section", { class: "panel", "aria-labelledby": "charts-head" },
        h("header", {}, h("h2", { id: "charts-head" }, "Time histories"),
          h("span", { class: "muted" }, "drag to zoom in time, double-click to reset")),
        h("div", { class: "body charts", id: "charts" })));
    const hist = parseCsv(csv);
    const holder = document.getElementById("charts");
    for (const c of historyCharts(hist)) {
      const el = h("div", { class: "chart", id: c.id });
      holder.append(el);
      charts.push(lineChart(el, { ...c, time_s: hist.data.time_s }));
    }
    crack?.draw();
    await fillet?.draw();
  }

  return {
    dispose() {
      disposed = true;
      viewer?.dispose();
      unsubscribe();
      for (const c of charts) c.destroy();
      charts = [];
    },
  };
}
