// The rendered field of a finished job: a frame slider, play, the field
// and the meshing zone; each frame rendered by the server on request.
import { eng } from "./format.js";
import { meshingZone } from "./results-data.js";
import { h } from "./ui.js";

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

export function fieldViewer(id, summary, times, pngDownload) {
  let playing = null;
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
  const section = h("section", { class: "panel", "aria-labelledby": "field-head" },
    h("header", {}, h("h2", { id: "field-head" }, "Field"), select, zoomButton, h("span", { style: "flex:1" }), pngLink),
    h("div", { class: "body viewer" },
      frames ? h("div", { class: "frame" }, fullSize, loading) : h("div", { class: "empty" }, "This job wrote no frames (output.frames = 0)."),
      h("div", { class: "controls" }, play, slider, time)));
  return {
    section,
    dispose() {
      clearTimeout(playing);
      playing = null;
    },
  };
}
