// Jobs: every job with live status and progress from the event stream,
// ETA, cancel, and a selection to compare.
import { duration, eng, eta, int, when } from "./format.js";
import { events } from "./events.js";
import { cancelJob, feCheckBadge, progressBar, stageName, statusBadge } from "./job-parts.js";
import { h } from "./ui.js";

export function jobsView(root) {
  const selected = new Set();
  const filter = h("select", { id: "status-filter", "aria-label": "Show jobs" },
    h("option", { value: "" }, "All jobs"),
    h("option", { value: "active" }, "Queued and running"),
    h("option", { value: "successful" }, "Successful"),
    h("option", { value: "failed" }, "Failed"),
    h("option", { value: "dismissed" }, "Dismissed"));
  const compare = h("button", { type: "button", class: "primary", id: "compare-selected", disabled: true }, "Compare selected");
  const body = h("tbody");
  const table = h("table", { id: "jobs-table" },
    h("thead", {}, h("tr", {},
      h("th", { scope: "col" }, h("span", { class: "hide-narrow" }, "Pick")),
      h("th", { scope: "col" }, "Job"),
      h("th", { scope: "col" }, "Status"),
      h("th", { scope: "col" }, "Progress"),
      h("th", { scope: "col", class: "num hide-narrow" }, "Step"),
      h("th", { scope: "col", class: "num hide-narrow" }, "Simulated"),
      h("th", { scope: "col", class: "num" }, "Wall / ETA"),
      h("th", { scope: "col", class: "hide-narrow" }, "Created"),
      h("th", { scope: "col" }, h("span", { class: "hide-narrow" }, "Actions")))),
    body);
  const empty = h("div", { class: "empty", hidden: true }, "No jobs yet. ", h("a", { href: "#/submit" }, "Submit one"), ".");

  root.append(
    h("div", { class: "page-head" }, h("h1", {}, "Jobs"),
      h("p", {}, "Live: status and progress arrive as server-sent events.")),
    h("section", { class: "panel" },
      h("header", {}, h("div", { class: "toolbar", style: "width:100%" }, filter,
        h("span", { class: "spacer" }), h("span", { class: "muted", id: "selection-note" }, ""), compare)),
      h("div", { class: "table-wrap" }, table, empty)));

  const rows = new Map();

  function row(job) {
    const pick = h("input", { type: "checkbox", "aria-label": `select ${job.name} for comparison`,
      disabled: job.status !== "successful", checked: selected.has(job.jobID) });
    pick.addEventListener("change", () => {
      if (pick.checked) selected.add(job.jobID); else selected.delete(job.jobID);
      updateSelection();
    });
    const active = job.status === "accepted" || job.status === "running";
    const timeCell = job.status === "running"
      ? [duration(job.wall_s), h("div", { class: "muted small-note" }, `ETA ${eta(job)}`)]
      : job.status === "accepted" ? "queued" : duration(job.wall_s);
    const tr = h("tr", { class: `status-${job.status}`, dataset: { job: job.jobID } },
      h("td", {}, pick),
      h("td", {}, h("a", { href: `#/jobs/${job.jobID}`, class: "job-link" }, job.name || job.jobID.slice(0, 8)),
        h("div", { class: "muted mono", style: "font-size:11px" }, job.jobID.slice(0, 8),
          job.studyID ? [" · ", h("a", { href: `#/studies/${encodeURIComponent(job.studyID)}`, class: "study-link" }, "study")] : null)),
      h("td", { title: job.message || "" }, statusBadge(job.status), feCheckBadge(job),
        job.status === "running" && job.stage === "fe_check" ? h("div", { class: "muted small-note" }, stageName(job)) : null,
        job.status === "failed" && job.message ? h("div", { class: "small-note failure" }, job.message) : null),
      h("td", {}, progressBar(job)),
      h("td", { class: "num hide-narrow" }, `${int(job.step)} / ${int(job.steps)}`),
      h("td", { class: "num hide-narrow" }, `${eng(job.simulated_s, "s")} / ${eng(job.end_s, "s")}`),
      h("td", { class: "num" }, timeCell),
      h("td", { class: "hide-narrow num" }, when(job.created)),
      h("td", {}, active
        ? h("button", { type: "button", class: "small danger", onclick: () => cancelJob(job), "aria-label": `cancel ${job.name}` }, "Cancel")
        : job.status === "successful" ? h("a", { class: "button small", href: `#/jobs/${job.jobID}` }, "Results") : null));
    return tr;
  }

  function visible(job) {
    const f = filter.value;
    if (!f) return true;
    if (f === "active") return job.status === "accepted" || job.status === "running";
    return job.status === f;
  }

  function renderAll() {
    rows.clear();
    const list = events.list().filter(visible);
    body.replaceChildren(...list.map((j) => {
      const tr = row(j);
      rows.set(j.jobID, tr);
      return tr;
    }));
    empty.hidden = list.length > 0 || !events.loaded;
    table.hidden = list.length === 0;
  }

  function update(id) {
    if (!id) return renderAll();
    const job = events.jobs.get(id);
    const old = rows.get(id);
    if (!job || !visible(job)) {
      if (old) { old.remove(); rows.delete(id); }
      return;
    }
    if (!old) return renderAll(); // a new job: keep the order
    // Keep keyboard focus on a control that is being replaced.
    const focused = old.contains(document.activeElement) ? document.activeElement.className : null;
    const tr = row(job);
    old.replaceWith(tr);
    rows.set(id, tr);
    if (focused) tr.querySelector(`[class="${focused}"]`)?.focus();
  }

  function updateSelection() {
    compare.disabled = selected.size < 2;
    document.getElementById("selection-note").textContent =
      selected.size ? `${selected.size} selected` : "tick successful jobs to compare them";
  }

  compare.addEventListener("click", () => {
    location.hash = `#/compare?ids=${[...selected].join(",")}`;
  });
  filter.addEventListener("change", renderAll);
  const unsubscribe = events.subscribe(update);
  renderAll();
  updateSelection();
  return { dispose: unsubscribe };
}
