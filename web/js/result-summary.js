// A finished job's summary numbers, its verdict and its downloads.
import { bytes, duration, eng, int, sig } from "./format.js";
import { verdictPanel } from "./result-verdict.js";
import { h } from "./ui.js";

// Who chose the thread count; for a trial, what it measured a step.
function threadsNote(s) {
  const t = s.thread_trial;
  if (t) return "the fastest of a trial: " + t.threads.map((n, k) => `${n} → ${sig(t.us_per_step[k], 3)} µs`).join(", ") + " a step";
  return { caller: "as the server or command line set", job: "as the job set", size: "by the scene's size" }[s.threads_by] || "";
}

export function summaryPanel(s, files, pngDownload) {
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
