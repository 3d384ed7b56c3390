// The New job page's right-hand panels, drawn from a POST /preview answer:
// the geometry (particles, outlines, pitch circle, tooth numbers, scale),
// the size and run-time estimate, and what the scene modelled.
import { bytes, duration, eng, int, sig } from "./format.js";
import { h, put } from "./ui.js";

const COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"];
const DRIVEN = "#9aa1ab";

function shade(hex) {
  const n = parseInt(hex.slice(1), 16);
  const f = (c) => Math.round(c * 0.55).toString(16).padStart(2, "0");
  return `#${f(n >> 16)}${f((n >> 8) & 255)}${f(n & 255)}`;
}

// Modelled pinion teeth by number, on the tooth (t0 meshes at the start;
// the charts' "tooth force t1" etc. use the same numbers). Tooth k's axis is
// at -90 degrees + k pitches (counter-clockwise) about the pinion centre,
// turned by the rotation that closes the play.
function drawToothNumbers(g, doc, X, Y) {
  const pin = doc.model?.pinion;
  if (doc.scene !== "rack_pinion" || !Array.isArray(pin?.modelled_teeth) || !pin.teeth || !pin.root_radius_m || !pin.tip_radius_m) return;
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

// The geometry of `doc` on the canvas; `stale`: the job has changed into one
// that cannot be previewed, and this is the last one that could.
export function drawPreview(canvas, legend, doc, stale) {
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
  drawToothNumbers(g, doc, X, Y);
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
  const pin = doc.model?.pinion;
  put(legend,
    ...doc.bodies.map((b, k) => h("span", {}, h("i", { style: `background:${COLOURS[k % COLOURS.length]}` }),
      `${b.name}: ${int(b.free)} free`)),
    h("span", {}, h("i", { style: `background:${DRIVEN}` }), "driven / guided"),
    rp ? h("span", {}, "dashed: pitch circle and pitch line") : null,
    pin?.modelled_teeth ? h("span", {}, "t0, t1…: modelled pinion teeth") : null,
    doc.points ? null : h("span", {}, doc.points_omitted));
}

// Particles, steps, dt, frames, disk, work and the run time (labelled an estimate).
export function showEstimate(el, doc) {
  const rt = doc.run_time;
  const item = (label, value, small) => h("div", {}, h("dt", {}, label), h("dd", {}, value, small ? h("small", {}, " ", small) : null));
  const split = rt.output_s > 0 ? `computing ${duration(rt.compute_s)}, writing output ${duration(rt.output_s)}` : null;
  put(el,
    h("dl", { class: "kv" },
      item("Particles", int(doc.particles), doc.built === false
        ? "estimated from coarser copies of the job"
        : doc.bodies.map((b) => `${b.name} ${int(b.particles)}`).join(", ")),
      item("Time steps", int(doc.steps)),
      doc.built === false ? null : item("Time step dt", eng(doc.dt_s, "s"), `limit ${eng(doc.dt_limit_s, "s")}`),
      item("Simulated time", eng(doc.end_s, "s")),
      item("Frames", int(doc.frames)),
      item("Results on disk", bytes(doc.disk_bytes)),
      item("Work", sig(doc.particle_steps), "particle-steps"),
      h("div", { id: "runtime-estimate" }, h("dt", {}, "Run time (estimate)"), h("dd", {}, "≈ " + duration(rt.wall_s), split ? h("small", {}, " ", split) : null))),
    h("p", { class: "note" }, rt.note));
}

// The modelled teeth, radii and contact ratio (or whatever the scene reports).
export function showModel(el, doc) {
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
  put(el,
    h("table", { class: "summary-table" }, h("tbody", {}, rows.map(([k, v]) => h("tr", {}, h("td", {}, k), h("td", { class: "num" }, v))))),
    m.modelled_teeth_reason ? h("p", { class: "note" }, m.modelled_teeth_reason) : null);
}
