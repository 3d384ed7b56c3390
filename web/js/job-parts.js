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
