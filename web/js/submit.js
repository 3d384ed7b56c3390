// New job: the rack-and-pinion form (limits, units and defaults from the
// job schema), a live preview of the geometry from POST /preview, the size
// and run-time estimate, and the server's refusals next to their fields.
// The JSON tab takes any job document.
import { ApiError, post, schema } from "./api.js";
import { bytes, duration, eng, h, int, put, sig } from "./format.js";
import { getPointer, limitsText, nodeAt, setPointer, unitOf } from "./schema.js";
import { events } from "./events.js";
import { toast } from "./app.js";

const GROUPS = [
  ["Job", [
    { pointer: "/name", label: "Name", type: "text" },
  ]],
  ["Pinion", [
    { pointer: "/scene/pinion/module_mm", label: "Module" },
    { pointer: "/scene/pinion/teeth", label: "Teeth", step: 1 },
    { pointer: "/scene/pinion/pressure_angle_deg", label: "Pressure angle" },
    { pointer: "/scene/pinion/face_width_mm", label: "Face width" },
    { pointer: "/scene/pinion/profile_shift", label: "Profile shift" },
    { pointer: "/scene/pinion/omega_rad_s", label: "Speed ω" },
    { pointer: "/scene/pinion/modelled_teeth", label: "Modelled teeth", type: "teeth" },
  ]],
  ["Rack", [
    { pointer: "/scene/rack/velocity_m_s", label: "Initial velocity" },
    { pointer: "/scene/rack/load_N", label: "Load" },
    { pointer: "/scene/rack/modelled_teeth", label: "Modelled teeth", type: "teeth" },
  ]],
  ["Material (both bodies)", [
    { pointer: "/scene/material/E_Pa", label: "Young's modulus E" },
    { pointer: "/scene/material/nu", label: "Poisson's ratio ν" },
    { pointer: "/scene/material/rho_kg_m3", label: "Density ρ" },
  ]],
  ["Discretisation and method", [
    { pointer: "/discretization/spacing_mm", label: "Particle spacing" },
    { pointer: "/discretization/kernel", label: "Kernel", type: "enum" },
    { pointer: "/method/formulation", label: "Formulation", type: "enum" },
    { pointer: "/method/contact/model", label: "Contact model", type: "enum" },
  ]],
  ["Time and output", [
    { pointer: "/time/end_s", label: "End time" },
    { pointer: "/time/dt_s", label: "Time step", placeholder: "automatic" },
    { pointer: "/output/frames", label: "Frames", step: 1 },
  ]],
];
const FIELDS = GROUPS.flatMap(([, f]) => f);
const PAPER_CASE = { name: "paper-base-case", scene: { type: "rack_pinion" } };

const COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"];
const DRIVEN = "#9aa1ab";

function fieldId(pointer) {
  return "f" + pointer.replace(/\//g, "-");
}

// The form's state survives a change of view (but not a reload).
let saved = null;

export function submitView(root) {
  let mode = "form";
  let sequence = 0;
  let timer = null;
  let controller = null;
  let lastPreview = null;
  let disposed = false;

  const problems = h("div", { class: "problems", id: "form-problems", hidden: true, tabindex: "-1" });
  const form = h("form", { novalidate: true, "aria-describedby": "form-problems", id: "job-form" });
  const jsonArea = h("textarea", { id: "job-json", spellcheck: "false", "aria-label": "Job document (JSON)" });
  const jsonPanel = h("div", { class: "json-editor", hidden: true },
    h("p", { class: "muted", style: "margin-top:0" },
      "Any job of the schema (",
      h("a", { href: "/schema", target: "_blank" }, "GET /schema"),
      "): other scene types, method options, output settings. The preview follows as you type."),
    jsonArea);
  const tabForm = h("button", { type: "button", role: "tab", "aria-selected": "true", id: "tab-form" }, "Form");
  const tabJson = h("button", { type: "button", role: "tab", "aria-selected": "false", id: "tab-json" }, "JSON (advanced)");
  const submitButton = h("button", { type: "submit", class: "primary", form: "job-form", id: "submit-job" }, "Submit job");
  const resetButton = h("button", { type: "button", id: "reset-form" }, "Paper's case");
  const formState = h("span", { class: "muted", role: "status", "aria-live": "polite" });

  const canvas = h("canvas", { class: "preview-canvas", id: "preview-canvas", role: "img", "aria-label": "Geometry preview" });
  const legend = h("div", { class: "legend" });
  const previewState = h("span", { class: "muted", role: "status", "aria-live": "polite" });
  const estimate = h("div", { id: "estimate" });
  const model = h("div", { id: "model" });

  root.append(
    h("div", { class: "page-head" },
      h("h1", {}, "New rack-and-pinion job"),
      h("p", {}, "Pre-filled with the paper's case: 12-tooth pinion, module 4 mm, turning at 15 rad/s against a free rack.")),
    h("div", { class: "grid-2" },
      h("section", { class: "panel", "aria-labelledby": "job-head" },
        h("header", {},
          h("h2", { id: "job-head" }, "Job"),
          h("div", { class: "segmented", role: "tablist", style: "margin-left:auto" }, tabForm, tabJson)),
        h("div", { class: "body" }, problems, form, jsonPanel,
          h("div", { class: "form-actions" }, submitButton, resetButton, formState))),
      h("div", { class: "stack sticky" },
        h("section", { class: "panel", "aria-labelledby": "preview-head" },
          h("header", {}, h("h2", { id: "preview-head" }, "Geometry preview"), previewState),
          h("div", { class: "body" }, canvas, legend)),
        h("section", { class: "panel", "aria-labelledby": "estimate-head" },
          h("header", {}, h("h2", { id: "estimate-head" }, "Size and run time"),
            h("span", { class: "estimate-badge" }, "estimate")),
          h("div", { class: "body" }, estimate)),
        h("section", { class: "panel", "aria-labelledby": "model-head" },
          h("header", {}, h("h2", { id: "model-head" }, "What is modelled")),
          h("div", { class: "body" }, model)))));

  // --- the form, from the schema ---
  const inputs = new Map();
  schema().then((s) => {
    if (disposed) return;
    for (const [title, fields] of GROUPS) {
      const grid = h("div", { class: "fields" });
      for (const f of fields) grid.append(fieldRow(s, f));
      form.append(h("fieldset", {}, h("legend", {}, title), grid));
    }
    fill(saved || PAPER_CASE);
    schedulePreview(0);
  }).catch((e) => showProblems([{ pointer: "", detail: `cannot read the job schema: ${e.message}` }]));

  function fieldRow(s, f) {
    const node = nodeAt(s, f.pointer);
    // A default given for the enclosing object (e.g. the material's).
    const parent = nodeAt(s, f.pointer.replace(/\/[^/]*$/, ""));
    const key = f.pointer.split("/").pop();
    const def = node?.default !== undefined ? node.default
      : parent?.default && typeof parent.default === "object" ? parent.default[key] : undefined;
    const id = fieldId(f.pointer);
    const unit = unitOf(f.pointer);
    let input;
    if (f.type === "enum" && node?.enum) {
      input = h("select", { id, name: f.pointer }, node.enum.map((v) => h("option", { value: v }, v)));
    } else if (f.type === "text" || f.type === "teeth") {
      input = h("input", { id, name: f.pointer, type: "text", autocomplete: "off",
        placeholder: f.type === "teeth" ? "auto, all or a number" : "" });
    } else {
      input = h("input", { id, name: f.pointer, type: "number", step: f.step || "any",
        inputmode: "decimal", placeholder: f.placeholder || "" });
    }
    const description = node?.description || "";
    const limits = limitsText(node);
    const hintText = [limits && `range ${limits}`, def !== undefined && typeof def !== "object" && f.type !== "text" && `default ${typeof def === "number" && Math.abs(def) >= 1e6 ? def.toExponential().replace("e+", "e") : def}`]
      .filter(Boolean).join(" · ");
    const hint = h("div", { class: "hint", id: id + "-hint", title: description }, hintText || description.slice(0, 80));
    input.setAttribute("aria-describedby", `${id}-hint ${id}-error`);
    input.title = description;
    const error = h("div", { class: "error", id: id + "-error", hidden: true });
    const row = h("div", { class: "field", dataset: { pointer: f.pointer } },
      h("label", { for: id }, f.label), input, h("span", { class: "unit" }, unit), hint, error);
    inputs.set(f.pointer, { input, row, error, node, spec: f, def });
    input.addEventListener("input", () => { clearFieldError(f.pointer); schedulePreview(); });
    input.addEventListener("change", () => schedulePreview(0));
    return row;
  }

  function fill(job) {
    for (const [pointer, { input, def }] of inputs) {
      let v = getPointer(job, pointer);
      if (v === undefined && def !== undefined && typeof def !== "object") v = def;
      input.value = v === undefined || v === null ? "" : typeof v === "number" && Math.abs(v) >= 1e6 ? v.toExponential().replace("e+", "e") : String(v);
    }
  }

  function readForm() {
    const job = { scene: { type: "rack_pinion" } };
    for (const [pointer, { input, spec }] of inputs) {
      const raw = input.value.trim();
      if (raw === "") continue;
      let v = raw;
      if (spec.type === "teeth") v = /^-?\d+$/.test(raw) ? Number(raw) : raw;
      else if (spec.type !== "text" && spec.type !== "enum") v = Number.isFinite(Number(raw)) ? Number(raw) : raw;
      setPointer(job, pointer, v);
    }
    return job;
  }

  // The job the page would submit; throws on JSON that does not parse.
  function currentJob() {
    if (mode === "form") return readForm();
    try {
      return JSON.parse(jsonArea.value);
    } catch (e) {
      throw new ApiError(400, { title: "Malformed JSON", detail: `the JSON does not parse: ${e.message}`, errors: [] });
    }
  }

  // --- errors at their fields ---
  function clearErrors() {
    problems.hidden = true;
    problems.replaceChildren();
    for (const p of inputs.keys()) clearFieldError(p);
  }
  function clearFieldError(pointer) {
    const f = inputs.get(pointer);
    if (!f) return;
    f.row.classList.remove("invalid");
    f.input.removeAttribute("aria-invalid");
    f.error.hidden = true;
    f.error.textContent = "";
  }
  // The form field a pointer concerns: itself, or the nearest one inside it.
  function fieldFor(pointer) {
    if (inputs.has(pointer)) return inputs.get(pointer);
    if (pointer === "/discretization" || pointer.startsWith("/discretization/spacing")) return inputs.get("/discretization/spacing_mm");
    if (pointer === "/time/cfl") return inputs.get("/time/dt_s");
    for (const [p, f] of inputs) if (p.startsWith(pointer + "/") && pointer !== "") return f;
    return null;
  }
  function showProblems(errors, title) {
    const unplaced = [];
    for (const e of errors) {
      const f = mode === "form" ? fieldFor(e.pointer || "") : null;
      if (f) {
        f.row.classList.add("invalid");
        f.input.setAttribute("aria-invalid", "true");
        f.error.hidden = false;
        f.error.textContent = f.error.textContent ? `${f.error.textContent} ${e.detail}` : e.detail;
      } else {
        unplaced.push(e);
      }
    }
    const list = h("ul", {}, errors.map((e) => {
      const f = mode === "form" ? fieldFor(e.pointer || "") : null;
      const where = e.pointer ? h("code", {}, e.pointer) : null;
      return h("li", {}, f ? h("a", { href: "#" + f.input.id, onclick: (ev) => { ev.preventDefault(); f.input.focus(); } }, f.spec.label) : where,
        f || where ? ": " : "", e.detail);
    }));
    put(problems, h("strong", {}, title || `${errors.length} problem${errors.length === 1 ? "" : "s"} with this job`), list);
    problems.hidden = errors.length === 0;
    return unplaced;
  }

  // --- live preview ---
  function schedulePreview(delay = 350) {
    clearTimeout(timer);
    timer = setTimeout(runPreview, delay);
  }

  async function runPreview() {
    const mine = ++sequence;
    controller?.abort();
    controller = new AbortController();
    previewState.textContent = "updating…";
    let job;
    try {
      job = currentJob();
    } catch (e) {
      clearErrors();
      showProblems([{ pointer: "", detail: e.message }], "The JSON does not parse");
      previewState.textContent = "not updated";
      return;
    }
    saved = mode === "form" ? job : saved;
    try {
      const res = await fetch("/preview", {
        method: "POST", body: JSON.stringify(job), signal: controller.signal,
        headers: { "Content-Type": "application/json", Accept: "application/json" },
      });
      const doc = await res.json();
      if (mine !== sequence || disposed) return;
      clearErrors();
      if (!res.ok || !doc.outlines) {
        // Not a job (malformed), invalid, or too large to build: the reasons.
        showProblems(doc.errors?.length ? doc.errors : [{ pointer: "", detail: doc.detail || doc.title }],
          doc.valid === false ? undefined : "This server would refuse this job");
        previewState.textContent = "fix the marked fields to update the preview";
        drawPreview(lastPreview, true);
        return;
      }
      lastPreview = doc;
      showDefaults(doc);
      if (!doc.accepted) showProblems(doc.errors, "This server would refuse this job");
      previewState.textContent = `${int(doc.particles)} particles, dx = ${eng(doc.spacing_m, "m")}`;
      drawPreview(doc, false);
      showEstimate(doc);
      showModel(doc);
    } catch (e) {
      if (e.name === "AbortError" || disposed) return;
      previewState.textContent = `preview failed: ${e.message}`;
    }
  }

  // Empty fields show what the scene chose for them.
  function showDefaults(doc) {
    const chosen = {
      "/time/end_s": doc.end_s,
      "/time/dt_s": doc.dt_s,
      "/discretization/spacing_mm": doc.spacing_m * 1e3,
    };
    for (const [pointer, { input, spec }] of inputs) {
      const v = pointer in chosen ? chosen[pointer] : getPointer(doc.job, pointer);
      if (v !== undefined && typeof v !== "object") input.placeholder = `${spec.placeholder || "scene default"}: ${v}`;
    }
  }

  let previewStale = false;
  function drawPreview(doc, stale) {
    previewStale = stale;
    // The numbers beside the picture are as out of date as the picture.
    estimate.classList.toggle("stale", stale);
    model.classList.toggle("stale", stale);
    const dpr = window.devicePixelRatio || 1;
    const w = canvas.clientWidth || 600, hgt = canvas.clientHeight || 375;
    canvas.width = Math.round(w * dpr);
    canvas.height = Math.round(hgt * dpr);
    const g = canvas.getContext("2d");
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, w, hgt);
    if (!doc) return;
    const [x0, y0, x1, y1] = doc.bounds_m;
    const pad = 18;
    const scale = Math.min((w - 2 * pad) / (x1 - x0), (hgt - 2 * pad - 16) / (y1 - y0));
    const ox = (w - (x1 - x0) * scale) / 2, oy = (hgt - 16 - (y1 - y0) * scale) / 2;
    const X = (x) => ox + (x - x0) * scale;
    const Y = (y) => hgt - 16 - oy - (y - y0) * scale;
    g.globalAlpha = stale ? 0.35 : 1;

    // Pitch circle and pitch line (pinion centred at the origin).
    const rp = doc.model?.pinion?.pitch_radius_m;
    if (doc.scene === "rack_pinion" && rp) {
      g.save();
      g.setLineDash([5, 4]);
      g.strokeStyle = "#b8bec7";
      g.lineWidth = 1;
      g.beginPath();
      g.arc(X(0), Y(0), rp * scale, 0, 2 * Math.PI);
      g.moveTo(X(x0), Y(-rp));
      g.lineTo(X(x1), Y(-rp));
      g.stroke();
      g.restore();
    }
    // Particles: free ones in their body's colour, driven ones grey.
    const names = doc.bodies.map((b) => b.name);
    if (doc.points) {
      const { x, y, body, driven } = doc.points;
      const r = Math.max(0.8, Math.min(4, 0.42 * doc.spacing_m * scale));
      for (let i = 0; i < x.length; i++) {
        g.fillStyle = driven[i] ? DRIVEN : COLOURS[body[i] % COLOURS.length];
        g.beginPath();
        g.arc(X(x[i]), Y(y[i]), r, 0, 2 * Math.PI);
        g.fill();
      }
    }
    // Outlines on top.
    g.lineWidth = 1.3;
    for (const o of doc.outlines) {
      const b = names.indexOf(o.body);
      g.strokeStyle = b >= 0 ? shade(COLOURS[b % COLOURS.length]) : "#333";
      g.beginPath();
      o.points.forEach(([px, py], k) => (k ? g.lineTo(X(px), Y(py)) : g.moveTo(X(px), Y(py))));
      if (o.closed) g.closePath();
      g.stroke();
    }
    // Modelled pinion teeth by number, on the tooth (t0 meshes at the
    // start; the charts' "tooth force t1" etc. use the same numbers). Tooth
    // k's axis is at -90 degrees + k pitches (counter-clockwise) about the
    // pinion centre, turned by the rotation that closes the play.
    const pin = doc.model?.pinion;
    if (doc.scene === "rack_pinion" && Array.isArray(pin?.modelled_teeth) && pin.teeth && pin.root_radius_m && pin.tip_radius_m) {
      const phase = doc.model.initial_rotation_to_close_play_rad || 0;
      const rMid = (pin.root_radius_m + pin.tip_radius_m) / 2;
      g.save();
      g.font = "600 11px system-ui, sans-serif";
      g.textAlign = "center";
      g.textBaseline = "middle";
      g.lineWidth = 3;
      g.strokeStyle = "rgba(255, 255, 255, 0.9)";
      g.fillStyle = "#0b2540";
      for (const k of pin.modelled_teeth) {
        const a = -Math.PI / 2 + phase + (k * 2 * Math.PI) / pin.teeth;
        const x = X(rMid * Math.cos(a)), y = Y(rMid * Math.sin(a));
        g.strokeText(`t${k}`, x, y);
        g.fillText(`t${k}`, x, y);
      }
      g.restore();
    }
    if (stale) {
      // The geometry of the last valid job: say so on the picture itself.
      g.globalAlpha = 1;
      g.fillStyle = "rgba(251, 252, 253, 0.6)";
      g.fillRect(0, 0, w, hgt);
      g.font = "600 14px system-ui, sans-serif";
      g.fillStyle = "#b42318";
      g.textAlign = "center";
      g.fillText("out of date until the problems with this job are fixed", w / 2, 22);
      g.textAlign = "left";
    }
    // Scale bar.
    const target = (w * 0.18) / scale;
    const bar = [1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2, 0.1, 0.2, 0.5, 1].find((v) => v >= target) || 1;
    g.globalAlpha = 1;
    g.fillStyle = "#333";
    g.fillRect(12, hgt - 12, bar * scale, 3);
    g.font = "12px system-ui, sans-serif";
    g.fillText(eng(bar, "m"), 16 + bar * scale, hgt - 7);
    put(legend,
      ...doc.bodies.map((b, k) => h("span", {}, h("i", { style: `background:${COLOURS[k % COLOURS.length]}` }),
        `${b.name}: ${int(b.free)} free`)),
      h("span", {}, h("i", { style: `background:${DRIVEN}` }), "driven / guided"),
      rp ? h("span", {}, "dashed: pitch circle and pitch line") : null,
      pin?.modelled_teeth ? h("span", {}, "t0, t1…: modelled pinion teeth") : null,
      doc.points ? null : h("span", {}, doc.points_omitted));
  }

  function shade(hex) {
    const n = parseInt(hex.slice(1), 16);
    const f = (c) => Math.round(c * 0.55).toString(16).padStart(2, "0");
    return `#${f(n >> 16)}${f((n >> 8) & 255)}${f(n & 255)}`;
  }

  function showEstimate(doc) {
    const rt = doc.run_time;
    const item = (label, value, small) => h("div", {}, h("dt", {}, label), h("dd", {}, value, small ? h("small", {}, " ", small) : null));
    put(estimate,
      h("dl", { class: "kv" },
        item("Particles", int(doc.particles), doc.bodies.map((b) => `${b.name} ${int(b.particles)}`).join(", ")),
        item("Time steps", int(doc.steps)),
        item("Time step dt", eng(doc.dt_s, "s"), `limit ${eng(doc.dt_limit_s, "s")}`),
        item("Simulated time", eng(doc.end_s, "s")),
        item("Frames", int(doc.frames)),
        item("Results on disk", bytes(doc.disk_bytes)),
        item("Work", sig(doc.particle_steps), "particle-steps"),
        h("div", { id: "runtime-estimate" }, h("dt", {}, "Run time (estimate)"), h("dd", {}, "≈ " + duration(rt.wall_s)))),
      h("p", { class: "note" }, rt.note));
  }

  function showModel(doc) {
    const m = doc.model || {};
    const rows = [];
    if (m.pinion) {
      rows.push(["Pinion teeth modelled", (m.pinion.modelled_teeth || []).join(", ") + ` of ${m.pinion.teeth}`]);
      rows.push(["Pitch / base / tip radius", [m.pinion.pitch_radius_m, m.pinion.base_radius_m, m.pinion.tip_radius_m].map((v) => eng(v, "m")).join(" / ")]);
      if (m.pinion.undercut !== undefined) rows.push(["Undercut", m.pinion.undercut ? "yes" : "no"]);
    }
    if (m.rack) rows.push(["Rack teeth modelled", String(m.rack.modelled_teeth)]);
    if (m.contact_ratio) rows.push(["Contact ratio", sig(m.contact_ratio, 4)]);
    if (!rows.length) {
      for (const [k, v] of Object.entries(m)) if (typeof v !== "object") rows.push([k.replace(/_/g, " "), String(v)]);
    }
    put(model,
      h("table", { class: "summary-table" }, h("tbody", {}, rows.map(([k, v]) => h("tr", {}, h("td", {}, k), h("td", { class: "num" }, v))))),
      m.modelled_teeth_reason ? h("p", { class: "note" }, m.modelled_teeth_reason) : null);
  }

  // --- tabs, submit, reset ---
  function setMode(next) {
    if (next === mode) return;
    if (next === "json") {
      jsonArea.value = JSON.stringify(readForm(), null, 2);
    }
    mode = next;
    form.hidden = mode !== "form";
    jsonPanel.hidden = mode !== "json";
    tabForm.setAttribute("aria-selected", String(mode === "form"));
    tabJson.setAttribute("aria-selected", String(mode === "json"));
    clearErrors();
    schedulePreview(0);
  }
  tabForm.addEventListener("click", () => setMode("form"));
  tabJson.addEventListener("click", () => setMode("json"));
  // Arrow keys move between the two tabs, as in any tab list.
  for (const tab of [tabForm, tabJson]) {
    tab.addEventListener("keydown", (e) => {
      if (e.key !== "ArrowLeft" && e.key !== "ArrowRight") return;
      e.preventDefault();
      const next = mode === "form" ? "json" : "form";
      setMode(next);
      (next === "form" ? tabForm : tabJson).focus();
    });
  }
  jsonArea.addEventListener("input", () => schedulePreview(600));
  resetButton.addEventListener("click", () => {
    saved = null;
    if (mode === "json") jsonArea.value = JSON.stringify(PAPER_CASE, null, 2);
    else fill(PAPER_CASE);
    clearErrors();
    schedulePreview(0);
  });

  form.addEventListener("submit", (e) => e.preventDefault());
  submitButton.addEventListener("click", async (e) => {
    e.preventDefault();
    clearErrors();
    let job;
    try {
      job = currentJob();
    } catch (err) {
      showProblems([{ pointer: "", detail: err.message }], "The JSON does not parse");
      return;
    }
    submitButton.disabled = true;
    formState.textContent = "checking…";
    try {
      // The server checks the job first (POST /preview answers with the
      // problems at their fields); only a job it would take is submitted.
      const check = await post("/preview", job);
      if (!check.accepted) {
        formState.textContent = "";
        showProblems(check.errors, check.valid === false ? "Not submitted: invalid job" : "Not submitted: this server would refuse this job");
        const first = form.querySelector(".field.invalid input, .field.invalid select");
        (mode === "form" && first ? first : problems).focus();
        return;
      }
      formState.textContent = "submitting…";
      const doc = await post("/jobs", job);
      events.remember(doc);
      formState.textContent = "";
      toast(`Job “${doc.name || job.name || "job"}” submitted: ${int(doc.particles)} particles, ${int(doc.steps)} steps.`);
      location.hash = `#/jobs/${doc.jobID}`;
    } catch (err) {
      formState.textContent = "";
      if (err instanceof ApiError) {
        const errors = err.errors.length ? err.errors : [{ pointer: "", detail: err.message }];
        showProblems(errors, err.problem.title ? `Not submitted: ${err.problem.title.toLowerCase()}` : undefined);
        const first = form.querySelector(".field.invalid input, .field.invalid select");
        (mode === "form" && first ? first : problems).focus();
      } else {
        showProblems([{ pointer: "", detail: err.message }], "Not submitted");
      }
    } finally {
      submitButton.disabled = false;
    }
  });

  const onResize = () => drawPreview(lastPreview, previewStale);
  window.addEventListener("resize", onResize);
  return {
    dispose() {
      disposed = true;
      clearTimeout(timer);
      controller?.abort();
      window.removeEventListener("resize", onResize);
    },
  };
}
