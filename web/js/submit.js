// New job: the rack-and-pinion form (limits, units and defaults from the
// job schema), a live preview of the geometry from POST /preview, the size
// and run-time estimate, and the server's refusals next to their fields.
// The JSON tab takes any job document. The form is submit-form.js, the
// panels drawn from a preview submit-preview.js; this wires them.
import { ApiError, apiFetch, post, schema } from "./api.js";
import { events } from "./events.js";
import { eng, int } from "./format.js";
import { getPointer } from "./schema.js";
import { PAPER_CASE } from "./submit-fields.js";
import { jobForm } from "./submit-form.js";
import { drawPreview, showEstimate, showModel } from "./submit-preview.js";
import { h, toast } from "./ui.js";

// The form's state survives a change of view (but not a reload).
let saved = null;

// The page's elements: the job panel (tabs, form, JSON), the preview panels.
function layout(root, jobs) {
  const el = {
    jsonArea: h("textarea", { id: "job-json", spellcheck: "false", "aria-label": "Job document (JSON)" }),
    tabForm: h("button", { type: "button", role: "tab", "aria-selected": "true", id: "tab-form" }, "Form"),
    tabJson: h("button", { type: "button", role: "tab", "aria-selected": "false", id: "tab-json" }, "JSON (advanced)"),
    submitButton: h("button", { type: "submit", class: "primary", form: "job-form", id: "submit-job" }, "Submit job"),
    resetButton: h("button", { type: "button", id: "reset-form" }, "Paper's case"),
    formState: h("span", { class: "muted", role: "status", "aria-live": "polite" }),
    canvas: h("canvas", { class: "preview-canvas", id: "preview-canvas", role: "img", "aria-label": "Geometry preview" }),
    legend: h("div", { class: "legend" }),
    previewState: h("span", { class: "muted", role: "status", "aria-live": "polite" }),
    estimate: h("div", { id: "estimate" }),
    model: h("div", { id: "model" }),
  };
  el.jsonPanel = h("div", { class: "json-editor", hidden: true },
    h("p", { class: "muted", style: "margin-top:0" },
      "Any job of the schema (",
      h("a", { href: "/schema", target: "_blank" }, "GET /schema"),
      "): other scene types, method options, output settings. The preview follows as you type."),
    el.jsonArea);
  root.append(
    h("div", { class: "page-head" },
      h("h1", {}, "New rack-and-pinion job"),
      h("p", {}, "Pre-filled with the paper's case: 12-tooth pinion, module 4 mm, turning at 15 rad/s against a free rack.")),
    h("div", { class: "grid-2" },
      h("section", { class: "panel", "aria-labelledby": "job-head" },
        h("header", {},
          h("h2", { id: "job-head" }, "Job"),
          h("div", { class: "segmented", role: "tablist", style: "margin-left:auto" }, el.tabForm, el.tabJson)),
        h("div", { class: "body" }, jobs.problems, jobs.form, el.jsonPanel,
          h("div", { class: "form-actions" }, el.submitButton, el.resetButton, el.formState))),
      h("div", { class: "stack sticky" },
        h("section", { class: "panel", "aria-labelledby": "preview-head" },
          h("header", {}, h("h2", { id: "preview-head" }, "Geometry preview"), el.previewState),
          h("div", { class: "body" }, el.canvas, el.legend)),
        h("section", { class: "panel", "aria-labelledby": "estimate-head" },
          h("header", {}, h("h2", { id: "estimate-head" }, "Size and run time"),
            h("span", { class: "estimate-badge" }, "estimate")),
          h("div", { class: "body" }, el.estimate)),
        h("section", { class: "panel", "aria-labelledby": "model-head" },
          h("header", {}, h("h2", { id: "model-head" }, "What is modelled")),
          h("div", { class: "body" }, el.model)))));
  return el;
}

// The preview follows every change: one request at a time, the latest wins.
function livePreview(page) {
  const { el, jobs, currentJob, showProblems } = page;
  let sequence = 0;
  let timer = null;
  let controller = null;
  let last = null;
  let stale = false;

  function draw(doc, isStale) {
    stale = isStale;
    // The numbers beside the picture are as out of date as the picture.
    el.estimate.classList.toggle("stale", isStale);
    el.model.classList.toggle("stale", isStale);
    drawPreview(el.canvas, el.legend, doc, isStale);
  }

  async function run() {
    const mine = ++sequence;
    controller?.abort();
    controller = new AbortController();
    el.previewState.textContent = "updating…";
    let job;
    try {
      job = currentJob();
    } catch (e) {
      jobs.clearErrors();
      showProblems([{ pointer: "", detail: e.message }], "The JSON does not parse");
      el.previewState.textContent = "not updated";
      return;
    }
    saved = page.mode() === "form" ? job : saved;
    try {
      const res = await apiFetch("/preview", {
        method: "POST", body: JSON.stringify(job), signal: controller.signal,
        headers: { "Content-Type": "application/json", Accept: "application/json" },
      });
      const doc = await res.json();
      if (mine !== sequence || page.disposed()) return;
      jobs.clearErrors();
      if (res.ok && doc.built === false) {
        // Beyond what the server builds for a preview: counts and run time, no geometry.
        if (!doc.accepted) showProblems(doc.errors, "This server would refuse this job");
        el.previewState.textContent = doc.points_omitted;
        draw(last, true);
        showEstimate(el.estimate, doc);
        return;
      }
      if (!res.ok || !doc.outlines) {
        // Not a job (malformed), invalid, or too large to build: the reasons.
        showProblems(doc.errors?.length ? doc.errors : [{ pointer: "", detail: doc.detail || doc.title }],
          doc.valid === false ? undefined : "This server would refuse this job");
        el.previewState.textContent = "fix the marked fields to update the preview";
        draw(last, true);
        return;
      }
      last = doc;
      const chosen = { "/time/end_s": doc.end_s, "/time/dt_s": doc.dt_s, "/discretization/spacing_mm": doc.spacing_m * 1e3 };
      jobs.showChosen((pointer) => (pointer in chosen ? chosen[pointer] : getPointer(doc.job, pointer)));
      if (!doc.accepted) showProblems(doc.errors, "This server would refuse this job");
      el.previewState.textContent = doc.finest_spacing_m < 0.999 * doc.spacing_m
        ? `${int(doc.particles)} particles, spacing ${eng(doc.finest_spacing_m, "m")} to ${eng(doc.spacing_m, "m")}`
        : `${int(doc.particles)} particles, dx = ${eng(doc.spacing_m, "m")}`;
      draw(doc, false);
      showEstimate(el.estimate, doc);
      showModel(el.model, doc);
    } catch (e) {
      if (e.name === "AbortError" || page.disposed()) return;
      el.previewState.textContent = `preview failed: ${e.message}`;
    }
  }

  return {
    schedule(delay = 350) {
      clearTimeout(timer);
      timer = setTimeout(run, delay);
    },
    redraw: () => draw(last, stale),
    stop() {
      clearTimeout(timer);
      controller?.abort();
    },
  };
}

// Submits: the server checks the job first (POST /preview answers with the
// problems at their fields); only a job it would take is submitted.
async function submitJob(page) {
  const { el, jobs, currentJob, showProblems } = page;
  jobs.clearErrors();
  let job;
  try {
    job = currentJob();
  } catch (err) {
    showProblems([{ pointer: "", detail: err.message }], "The JSON does not parse");
    return;
  }
  el.submitButton.disabled = true;
  el.formState.textContent = "checking…";
  try {
    const check = await post("/preview", job);
    if (!check.accepted) {
      el.formState.textContent = "";
      showProblems(check.errors, check.valid === false ? "Not submitted: invalid job" : "Not submitted: this server would refuse this job");
      jobs.focusProblems(page.mode() === "form");
      return;
    }
    el.formState.textContent = "submitting…";
    const doc = await post("/jobs", job);
    events.remember(doc);
    el.formState.textContent = "";
    toast(`Job “${doc.name || job.name || "job"}” submitted: ${int(doc.particles)} particles, ${int(doc.steps)} steps.`);
    location.hash = `#/jobs/${doc.jobID}`;
  } catch (err) {
    el.formState.textContent = "";
    if (err instanceof ApiError) {
      const errors = err.errors.length ? err.errors : [{ pointer: "", detail: err.message }];
      showProblems(errors, err.problem.title ? `Not submitted: ${err.problem.title.toLowerCase()}` : undefined);
      jobs.focusProblems(page.mode() === "form");
    } else {
      showProblems([{ pointer: "", detail: err.message }], "Not submitted");
    }
  } finally {
    el.submitButton.disabled = false;
  }
}

export function submitView(root) {
  let mode = "form";
  let disposed = false;
  const jobs = jobForm({ onEdit: (delay) => preview.schedule(delay) });
  const el = layout(root, jobs);

  schema().then((s) => {
    if (disposed) return;
    jobs.build(s);
    jobs.fill(saved || PAPER_CASE);
    preview.schedule(0);
  }).catch((e) => jobs.showProblems([{ pointer: "", detail: `cannot read the job schema: ${e.message}` }]));

  // The job the page would submit; throws on JSON that does not parse.
  function currentJob() {
    if (mode === "form") return jobs.read();
    try {
      return JSON.parse(el.jsonArea.value);
    } catch (e) {
      throw new ApiError(400, { title: "Malformed JSON", detail: `the JSON does not parse: ${e.message}`, errors: [] });
    }
  }

  function showProblems(errors, title) {
    jobs.showProblems(errors, title, mode === "form");
  }

  const page = { el, jobs, currentJob, showProblems, mode: () => mode, disposed: () => disposed };
  const preview = livePreview(page);

  // --- tabs ---
  function setMode(next) {
    if (next === mode) return;
    if (next === "json") el.jsonArea.value = JSON.stringify(jobs.read(), null, 2);
    mode = next;
    jobs.form.hidden = mode !== "form";
    el.jsonPanel.hidden = mode !== "json";
    el.tabForm.setAttribute("aria-selected", String(mode === "form"));
    el.tabJson.setAttribute("aria-selected", String(mode === "json"));
    jobs.clearErrors();
    preview.schedule(0);
  }
  el.tabForm.addEventListener("click", () => setMode("form"));
  el.tabJson.addEventListener("click", () => setMode("json"));
  // Arrow keys move between the two tabs, as in any tab list.
  for (const tab of [el.tabForm, el.tabJson]) {
    tab.addEventListener("keydown", (e) => {
      if (e.key !== "ArrowLeft" && e.key !== "ArrowRight") return;
      e.preventDefault();
      const next = mode === "form" ? "json" : "form";
      setMode(next);
      (next === "form" ? el.tabForm : el.tabJson).focus();
    });
  }
  el.jsonArea.addEventListener("input", () => preview.schedule(600));
  el.resetButton.addEventListener("click", () => {
    saved = null;
    if (mode === "json") el.jsonArea.value = JSON.stringify(PAPER_CASE, null, 2);
    else jobs.fill(PAPER_CASE);
    jobs.clearErrors();
    preview.schedule(0);
  });

  jobs.form.addEventListener("submit", (e) => e.preventDefault());
  el.submitButton.addEventListener("click", (e) => {
    e.preventDefault();
    submitJob(page);
  });

  window.addEventListener("resize", preview.redraw);
  return {
    dispose() {
      disposed = true;
      preview.stop();
      window.removeEventListener("resize", preview.redraw);
    },
  };
}
