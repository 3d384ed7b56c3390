// One job: live progress while it runs; once it has finished, the rendered
// field with a frame slider, play and zoom, the fillet stress of a static
// gear check, the time-history charts, the summary numbers and the files.
import { ApiError, get, text } from "./api.js";
import { lineChart } from "./charts.js";
import { events } from "./events.js";
import { bytes, duration, eng, eta, int, sig } from "./format.js";
import { cancelJob, feCheckBadge, progressBar, stageName, statusBadge } from "./job-parts.js";
import { filletPanel } from "./result-fillet.js";
import { verdictPanel } from "./result-verdict.js";
import { frameTimes, historyCharts, meshingZone, parseCsv } from "./results-data.js";
import { h, put } from "./ui.js";

const FIELDS = [
  ["von_mises", "von Mises stress"],
  ["max_principal", "largest principal σ1"],
  ["pressure", "pressure"],
  ["stress_xx", "stress σxx"],
  ["stress_yy", "stress σyy"],
  ["stress_xy", "stress σxy"],
  ["velocity", "speed |v|"],
  ["displacement", "displacement |u|"],
  ["density", "density"],
  ["body", "bodies"],
];

export function resultView(root, id) {
  let disposed = false;
  let charts = [];
  let playing = null;
  let loaded = false;

  const head = h("div", { class: "result-head" });
  const live = h("section", { class: "panel", id: "live" });
  const content = h("div", { class: "stack", id: "result-content" });
  root.append(h("p", { style: "margin:0 0 8px" }, h("a", { href: "#/jobs" }, "← All jobs")), head, live, content);

  let headKey = "";
  function showHead(job) {
    const active = job.status === "accepted" || job.status === "running";
    // Progress events come four times a second: redraw only on a change.
    const key = `${job.name}|${job.status}|${job.message}|${job.fe_check?.status}`;
    if (key === headKey) return;
    headKey = key;
    put(head,
      h("h1", { id: "job-title" }, job.name || "job"),
      statusBadge(job.status),
      feCheckBadge(job),
      h("span", { class: "message" }, job.message || ""),
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
    put(content,
      h("div", { class: "split" }, viewer(summary, times, pngDownload), summaryPanel(summary, results.files, pngDownload)),
      fillet?.section,
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
    await fillet?.draw();
  }

  function viewer(summary, times, pngDownload) {
    const frames = times.length;
    const zone = meshingZone(summary);
    let frame = Math.max(0, frames - 1);
    let field = "von_mises";
    let zoom = false;
    const img = h("img", { id: "field-image", alt: "rendered field" });
    // The image at full size (1280 x 800) in a tab of its own.
    const fullSize = h("a", { href: "#", target: "_blank", title: "open at full size" }, img);
    const loading = h("span", { class: "loading", hidden: true }, "rendering…");
    const slider = h("input", { type: "range", id: "frame-slider", min: "0", max: String(Math.max(0, frames - 1)),
      value: String(frame), step: "1", "aria-label": "frame", disabled: frames < 2 });
    const time = h("span", { class: "time num", "aria-live": "off" });
    const select = h("select", { id: "field-select", "aria-label": "field" },
      FIELDS.map(([v, label]) => h("option", { value: v }, label)));
    const play = h("button", { type: "button", id: "play", "aria-pressed": "false", disabled: frames < 2 }, "▶ Play");
    const zoomButton = h("button", { type: "button", id: "zoom", "aria-pressed": "false", disabled: !zone,
      title: zone ? "show the meshing zone around the pitch point" : "only for rack-and-pinion runs" }, "Meshing zone");
    const pngLink = h("a", { class: "button small", id: "png-link", download: "" }, "PNG");

    function url() {
      let u = `/jobs/${id}/images/${field}.png?frame=${frame}`;
      if (zoom && zone) u += `&zoom=${zone.map((v) => v.toPrecision(6)).join(",")}`;
      return u;
    }
    function show() {
      const u = url();
      loading.hidden = false;
      img.src = u;
      const file = `${summary.name || "job"}-${field}-frame${frame}${zoom ? "-zoom" : ""}.png`;
      fullSize.href = u;
      for (const a of [pngLink, pngDownload]) {
        a.href = u;
        a.setAttribute("download", file);
      }
      pngDownload.firstChild.textContent = file;
      slider.value = String(frame);
      time.textContent = frames ? `frame ${frame} / ${frames - 1} · t = ${eng(times[frame], "s", 4)}` : "no frames";
      img.alt = `${FIELDS.find(([v]) => v === field)[1]} at t = ${eng(times[frame], "s", 4)}${zoom ? ", meshing zone" : ""}`;
    }
    img.addEventListener("load", () => {
      loading.hidden = true;
      if (playing) playing = setTimeout(step, 250);
    });
    img.addEventListener("error", () => {
      loading.hidden = false;
      loading.textContent = "image not available";
      stop();
    });
    function step() {
      if (!playing) return;
      if (frame >= frames - 1) return stop();
      frame += 1;
      show();
    }
    function stop() {
      clearTimeout(playing);
      playing = null;
      play.setAttribute("aria-pressed", "false");
      play.textContent = "▶ Play";
    }
    play.addEventListener("click", () => {
      if (playing) return stop();
      if (frame >= frames - 1) frame = 0;
      playing = true;
      play.setAttribute("aria-pressed", "true");
      play.textContent = "❚❚ Pause";
      show();
    });
    slider.addEventListener("input", () => { stop(); frame = Number(slider.value); show(); });
    select.addEventListener("change", () => { field = select.value; show(); });
    zoomButton.addEventListener("click", () => {
      zoom = !zoom;
      zoomButton.setAttribute("aria-pressed", String(zoom));
      show();
    });
    if (frames) show();
    return h("section", { class: "panel", "aria-labelledby": "field-head" },
      h("header", {}, h("h2", { id: "field-head" }, "Field"), select, zoomButton, h("span", { style: "flex:1" }), pngLink),
      h("div", { class: "body viewer" },
        frames ? h("div", { class: "frame" }, fullSize, loading) : h("div", { class: "empty" }, "This job wrote no frames (output.frames = 0)."),
        h("div", { class: "controls" }, play, slider, time)));
  }

  // Who chose the thread count; for a trial, what it measured a step.
  function threadsNote(s) {
    const t = s.thread_trial;
    if (t) return "the fastest of a trial: " + t.threads.map((n, k) => `${n} → ${sig(t.us_per_step[k], 3)} µs`).join(", ") + " a step";
    return { caller: "as the server or command line set", job: "as the job set", size: "by the scene's size" }[s.threads_by] || "";
  }

  function summaryPanel(s, files, pngDownload) {
    const a = s.analysis || {};
    const vs = a.velocity_stability || {};
    const rows = [
      ["Max von Mises stress", eng(s.max_von_mises_Pa, "Pa"), s.max_von_mises_body ? `${s.max_von_mises_body}, t = ${eng(s.max_von_mises_time_s, "s")}` : ""],
      ["Max root stress", s.max_root_stress_Pa !== undefined ? eng(s.max_root_stress_Pa, "Pa") : null,
        a.root_stress_references?.lewis_Pa ? `Lewis ${eng(a.root_stress_references.lewis_Pa, "Pa")}` : ""],
      ["Max contact force", s.max_contact_force_N !== undefined ? eng(s.max_contact_force_N, "N") : null,
        s.max_contact_force_time_s !== undefined ? `t = ${eng(s.max_contact_force_time_s, "s")}` : ""],
      ["Max contact pressure", s.max_contact_pressure_Pa ? eng(s.max_contact_pressure_Pa, "Pa") : null,
        s.max_contact_pressure_Pa ? `Hertz on tooth ${s.max_contact_pressure_tooth}'s force, t = ${eng(s.max_contact_pressure_time_s, "s")}` : ""],
      ["Mesh stiffness", a.mesh_stiffness_N_per_mm_um !== undefined ? `${sig(a.mesh_stiffness_N_per_mm_um, 3)} N/(mm·µm)` : null,
        a.iso_mesh_stiffness_N_per_mm_um !== undefined
          ? `ISO 6336-1: c′ ${sig(a.iso_mesh_stiffness_N_per_mm_um, 3)}` +
            (a.iso_theoretical_mesh_stiffness_N_per_mm_um !== undefined ? `, c′th ${sig(a.iso_theoretical_mesh_stiffness_N_per_mm_um, 3)} (the elastic pair)` : "")
          : ""],
      ["Velocity-stability time", s.velocity_stability_time_s === undefined ? null
        : s.velocity_stability_time_s < 0 ? "not settled" : eng(s.velocity_stability_time_s, "s"),
      vs.definition ? "rack velocity within ±5 %" : ""],
      ["Teeth in contact (mean)", a.contact_ratio ? sig(a.contact_ratio.measured_mean_teeth_in_contact, 3) : null,
        a.contact_ratio ? `contact ratio ${sig(a.contact_ratio.theory, 3)} in theory` : ""],
      ["Energy drift", s.energy ? `${sig(100 * s.energy.drift_relative, 3)} %` : null, "of the energy scale"],
      ["Particles", int(s.particles), s.particles_by_body ? Object.entries(s.particles_by_body).map(([k, v]) => `${k} ${int(v)}`).join(", ") : ""],
      ["Steps × dt", `${int(s.steps)} × ${eng(s.dt_s, "s")}`, `to t = ${eng(s.simulated_s, "s")}`],
      ["Wall time", duration(s.wall_s), s.particle_steps_per_s ? `${sig(s.particle_steps_per_s)} particle-steps/s` : ""],
      ["Threads", s.threads === undefined ? null : int(s.threads), threadsNote(s)],
    ].filter(([, v]) => v !== null && v !== undefined);
    const order = ["results.h5", "results.xmf", "history.csv", "summary.json", "job.json"];
    const shown = (files || []).filter((f) => !f.name.startsWith("image-"))
      .sort((x, y) => (order.indexOf(x.name) + 99) % 99 - (order.indexOf(y.name) + 99) % 99);
    return h("div", { class: "stack" },
      verdictPanel(s),
      h("section", { class: "panel", "aria-labelledby": "summary-head" },
        h("header", {}, h("h2", { id: "summary-head" }, "Summary")),
        h("div", { class: "body" }, h("table", { class: "summary-table", id: "summary-table" }, h("tbody", {},
          rows.map(([k, v, note]) => h("tr", {}, h("td", {}, k), h("td", { class: "num" }, h("strong", {}, v)), h("td", { class: "muted" }, note))))))),
      h("section", { class: "panel", "aria-labelledby": "files-head" },
        h("header", {}, h("h2", { id: "files-head" }, "Downloads")),
        h("div", { class: "body files", id: "downloads" }, shown.map((f) =>
          h("a", { class: "button small", href: f.href, download: f.name, title: f.type }, f.name, h("span", { class: "muted" }, bytes(f.bytes)))),
        pngDownload)));
  }

  return {
    dispose() {
      disposed = true;
      clearTimeout(playing);
      playing = null;
      unsubscribe();
      for (const c of charts) c.destroy();
      charts = [];
    },
  };
}
