// Pieces of a job shown by more than one view (the list and the result):
// its progress bar, its status badge, and cancelling it.
import { ApiError, del } from "./api.js";
import { events } from "./events.js";
import { h, toast } from "./ui.js";

export function progressBar(job) {
  const pct = Math.max(0, Math.min(100, job.progress ?? 0));
  return h("div", { class: "progress", role: "progressbar", "aria-valuemin": "0", "aria-valuemax": "100",
    "aria-valuenow": String(pct), "aria-label": `progress of ${job.name || "job"}` },
  h("span", { style: `width:${pct}%` }), h("em", {}, `${pct}%`));
}

export function statusBadge(status) {
  return h("span", { class: `status ${status}` }, status === "accepted" ? "queued" : status);
}

// The FE check's state or outcome (job.fe_check, docs/api.md "The FE
// stage"): null for a job without it. A check that did not compare is shown
// as a failure beside the job's own status, which stays that of its SPH run.
const FE_WORDS = {
  pending: "FE check to come", running: "FE check running", compared: "FE check compared",
  sph_values_missing: "FE check compared (SPH values missing)", failed: "FE check failed",
  unavailable: "FE check unavailable", not_run: "FE check not run",
};
export function feCheckBadge(job) {
  const fe = job.fe_check;
  if (!fe || !fe.status) return null;
  const bad = fe.status === "failed" || fe.status === "unavailable" || fe.status === "not_run";
  return h("span", { class: `status ${bad ? "failed" : fe.status === "running" ? "running" : "successful"} fe-check`,
    title: fe.message || "", dataset: { feCheck: fe.status } }, FE_WORDS[fe.status] || `FE check ${fe.status}`);
}

// "SPH" or "FE check" while running.
export function stageName(job) {
  return job.stage === "fe_check" ? "FE check" : job.stage === "sph" ? "SPH run" : "";
}

export async function cancelJob(job) {
  const finished = job.status === "successful" || job.status === "failed";
  const what = finished ? "Dismiss this job and delete its results?" : "Cancel this job?";
  if (!window.confirm(`${what}\n\n${job.name} (${job.jobID})`)) return;
  try {
    events.remember(await del(`/jobs/${job.jobID}`));
  } catch (e) {
    toast(e instanceof ApiError ? e.message : `cancel failed: ${e.message}`);
  }
}
