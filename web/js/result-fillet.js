// The result view's "Fillet stress (tooth 0)" panel, for a static gear
// check: sigma_1 along the tension fillet and sigma_3 along the compression
// fillet against arc length, with the FE check's curves when it ran; the
// peaks against FE (or ISO 6336-3's sigma_F0); and the SPH and FE fields
// of tooth 0 side by side, one quantity on one colour scale.
import { get } from "./api.js";
import { lineChart } from "./charts.js";
import { eng } from "./format.js";
import {
  FIELD_PAIRS, feComparison, feImageRange, filletChart, filletCheck, filletTable, finestMesh, sphFieldImage,
} from "./fillet-data.js";
import { meshingZone } from "./results-data.js";
import { h } from "./ui.js";

// scene.contact_point, as the schema names it.
const CONTACT = {
  pitch: "contact at the pitch point",
  hpstc: "contact at the highest point of single tooth contact",
  lpstc: "contact at the lowest point of single tooth contact",
  tip: "contact at the tip",
};

function percent(e) {
  if (e === null) return "—";
  const v = 100 * e;
  return `${v > 0 ? "+" : v < 0 ? "−" : ""}${Math.abs(v).toFixed(1)} %`;
}

// A minus sign, not a hyphen, in the table's numbers.
function value(v, unit) {
  return (unit === "m" ? eng(v, "m", 4) : eng(v, unit)).replace(/^-/, "−");
}

function peaksTable(check, comparison) {
  const { reference, rows } = filletTable(check, comparison);
  const refHead = reference === "FE" ? "FE" : "ISO 6336-3 σF0";
  return h("div", { class: "table-wrap" },
    h("table", { class: "fillet-table", id: "fillet-table", "aria-labelledby": "fillet-table-head",
      "aria-describedby": "fillet-table-note" },
      h("thead", {}, h("tr", {},
        h("th", { scope: "col" }, "Tooth 0"),
        h("th", { scope: "col", class: "num" }, "SPH"),
        h("th", { scope: "col", class: "num" }, refHead),
        h("th", { scope: "col", class: "num" }, reference === "FE" ? "error" : "difference"))),
      h("tbody", {}, rows.map((r) => h("tr", { dataset: { key: r.key } },
        h("th", { scope: "row" }, r.label),
        h("td", { class: "num" }, value(r.sph, r.unit)),
        h("td", { class: "num" }, r.ref === null ? "—" : value(r.ref, r.unit)),
        h("td", { class: "num" }, percent(r.error)))))));
}

// What the table's last column means, and what else the reader should know.
function tableNote(check, summary, comparison) {
  const iso = Number.isFinite(check.iso_sigma_F0_Pa) ? eng(check.iso_sigma_F0_Pa, "Pa") : null;
  // How the SPH values were read (docs/gears.md, "Where the stress is read").
  const reading = check.fillet_reading === "stretch"
    ? "SPH read from the fillet's stretch (σ = E/(1 − ν²) ε along the free edge). "
    : check.fillet_reading === "stress_fit" ? "SPH read from a fit of the particles' stress. " : "";
  if (comparison) {
    const d = comparison.coarse_fine_difference?.fillet_tension_peak_Pa?.relative_difference;
    return reading + [
      "error = (SPH − FE) / |FE|, FE (gmsh + CalculiX) on its finest fillet mesh",
      comparison.fe_fillet_size_m > 0 ? ` (${Number((comparison.fe_fillet_size_m * 1e3).toPrecision(3))} mm elements)` : "",
      Number.isFinite(d) ? `, whose tension peak is within ${Math.abs(100 * d).toFixed(2)} % of the coarser mesh's` : "",
      iso ? `. ISO 6336-3 σF0 = ${iso}.` : ".",
      comparison.status === "sph_values_missing" && comparison.message ? ` ${comparison.message}` : "",
    ].join("");
  }
  const fe = summary.fe_comparison;
  return reading + "difference = (SPH − σF0) / σF0, σF0 by ISO 6336-3 method B for the load radius, at the 30° tangent point." +
    (fe?.status ? ` FE check: ${fe.status}${fe.message ? `, ${fe.message}` : ""}.` : "");
}

// The SPH field of the last frame and the FE field of tooth 0, side by
// side: the same quantity (σ1, or von Mises by the select) in the same
// window on the FE figure's colour scale; null when the FE check wrote no
// field image.
function fields(id, summary, check, comparison, names) {
  const pairs = FIELD_PAIRS.filter((p) => names.has(p.fe));
  if (!pairs.length) return null;
  const feRange = feImageRange(comparison);
  const zone = meshingZone(summary);
  const feImg = h("img", { id: "fe-field-image" });
  const feLink = h("a", { target: "_blank", title: "open at full size" }, feImg);
  const sphImg = h("img", { id: "sph-fillet-image" });
  const sphLink = h("a", { target: "_blank", title: "open at full size" }, sphImg);
  const sphCaption = h("figcaption", {});
  const note = h("p", { class: "note", id: "fillet-fields-note" });
  const show = (pair) => {
    const sph = sphFieldImage(id, check, pair, feRange, zone);
    const where = sph.tooth0 ? "tooth 0" : zone ? "meshing zone" : "whole model";
    feImg.src = feLink.href = `/jobs/${id}/files/${pair.fe}`;
    feImg.alt = `FE ${pair.label} in tooth 0, computed by CalculiX under the SPH run's tooth-0 load`;
    sphImg.src = sphLink.href = sph.src;
    sphImg.alt = `SPH ${pair.label} in ${where} at the last frame`;
    sphCaption.textContent = `SPH, ${where}, last frame`;
    const scale = sph.range ? `${eng(sph.range[0], "Pa").replace(/^-/, "−")} to ${eng(sph.range[1], "Pa")}` : null;
    note.textContent = scale && sph.tooth0
      ? `Both figures: ${pair.symbol} of tooth 0 in the same window on one colour scale, ${scale} (the FE figure's, from 1.25 times the larger FE fillet peak); the load's contact zone is off scale, in the end colour. SPH's field is drawn as contours inside the outlines, smoothed for the drawing (docs/results.md).`
      : scale
        ? `Both figures: ${pair.symbol} on one colour scale, ${scale}; this run's summary does not say where tooth 0 is (tooth0_box_m), so the SPH figure shows the ${where}.`
        : "The colour scales differ: the FE summary does not give its figure's range.";
  };
  const choose = h("select", { id: "fe-field-select", "aria-label": "field of both figures" },
    pairs.map((p) => h("option", { value: p.fe }, p.label)));
  choose.addEventListener("change", () => show(pairs.find((p) => p.fe === choose.value)));
  show(pairs[0]);
  return h("div", { class: "fillet-fields-wrap" },
    h("div", { class: "fillet-fields-head" },
      h("h3", { id: "fillet-fields-head" }, "Fields: SPH and FE"),
      pairs.length > 1 ? h("label", {}, "field ", choose) : h("span", { class: "muted" }, pairs[0].label)),
    h("div", { class: "fillet-fields", role: "group", "aria-labelledby": "fillet-fields-head" },
      h("figure", {}, sphLink, sphCaption),
      h("figure", {}, feLink, h("figcaption", {}, "FE (CalculiX), tooth 0"))),
    note);
}

// The panel, or null for a run without fillet curves. draw() is called
// once the section is in the page (the chart takes its width).
export function filletPanel(id, summary, files) {
  const check = filletCheck(summary);
  if (!check) return null;
  const comparison = feComparison(summary);
  const names = new Set((files || []).map((f) => f.name));
  const downloads = ["fillet_curves.png", "fe_fillet_curves.csv"].filter((n) => names.has(n));
  const chartEl = h("div", { class: "chart", id: "chart-fillet" });
  const load = Number.isFinite(check.load_radius_m) ? `load at r = ${eng(check.load_radius_m, "m", 4)}` : "";
  const where = CONTACT[check.contact_point] ? `, ${CONTACT[check.contact_point]}` : "";
  const figure = comparison ? fields(id, summary, check, comparison, names) : null;
  const section = h("section", { class: "panel", id: "fillet", "aria-labelledby": "fillet-head" },
    h("header", {},
      h("h2", { id: "fillet-head" }, "Fillet stress (tooth 0)"),
      h("span", { class: "muted" }, load + where),
      h("span", { class: "spacer" }),
      downloads.map((n) => h("a", { class: "button small", href: `/jobs/${id}/files/${n}`, download: n }, n))),
    h("div", { class: "body fillet" },
      h("div", { class: "fillet-grid" },
        chartEl,
        h("div", {},
          h("h3", { id: "fillet-table-head" }, comparison ? "Peaks: SPH against FE" : "Peaks: SPH against ISO 6336-3"),
          peaksTable(check, comparison),
          h("p", { class: "note", id: "fillet-table-note" }, tableNote(check, summary, comparison)))),
      figure));
  let chart = null;
  let disposed = false;
  return {
    section,
    async draw() {
      let mesh = null;
      if (comparison && names.has("fe_fillet_curves.json")) {
        mesh = finestMesh(await get(`/jobs/${id}/files/fe_fillet_curves.json`).catch(() => null));
      }
      if (disposed) return;
      const c = filletChart(check, mesh);
      try {
        chart = lineChart(chartEl, {
          title: "Along the fillets from the space centre",
          x: { values: c.arc_m, quantity: "arc length", symbol: "s", unit: "m" },
          quantity: "stress", unit: "Pa", series: c.series, marks: c.marks, height: 300,
        });
      } catch (e) {
        chartEl.replaceChildren(h("p", { class: "problems" }, `Could not draw the fillet curves: ${e.message}`));
      }
    },
    destroy() {
      disposed = true;
      chart?.destroy();
    },
  };
}
