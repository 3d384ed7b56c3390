// The result view's "Root crack" panel, for a static gear check that grew
// a crack from tooth 0's tension fillet (summary analysis.crack): the
// outcome in words, the numbers (lengths, increments, Paris life), K_I,
// K_II and K_eq against crack length, and a small figure of the path at
// one scale for x and y, so that its direction shows without the image.
import { lineChart } from "./charts.js";
import { crackAnalysis, crackNumbers, crackVerdict, kChart, pathFigure, stopText, verdictSentence } from "./crack-data.js";
import { h } from "./ui.js";

const SVG = "http://www.w3.org/2000/svg";

// h() for SVG elements (createElement would make HTML ones, never drawn).
function s(tag, attrs = {}, ...children) {
  const el = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) if (v !== null && v !== undefined) el.setAttribute(k, String(v));
  for (const c of children.flat(Infinity)) if (c !== null && c !== undefined) el.append(c instanceof Node ? c : document.createTextNode(String(c)));
  return el;
}

const minus = (t) => t.replace(/^-/, "−");

function axes(f) {
  const { plot } = f;
  return [
    s("rect", { x: plot.left, y: plot.top, width: plot.right - plot.left, height: plot.bottom - plot.top, class: "crack-frame" }),
    f.xTicks.filter((t) => t.at >= plot.left - 0.5 && t.at <= plot.right + 0.5).map((t) => [
      s("line", { x1: t.at, x2: t.at, y1: plot.top, y2: plot.bottom, class: "crack-grid" }),
      s("text", { x: t.at, y: plot.bottom + 14, "text-anchor": "middle" }, minus(t.label))]),
    f.yTicks.filter((t) => t.at >= plot.top - 0.5 && t.at <= plot.bottom + 0.5).map((t) => [
      s("line", { x1: plot.left, x2: plot.right, y1: t.at, y2: t.at, class: "crack-grid" }),
      s("text", { x: plot.left - 5, y: t.at + 4, "text-anchor": "end" }, minus(t.label))]),
    s("text", { x: (plot.left + plot.right) / 2, y: f.height - 6, "text-anchor": "middle", class: "crack-axis" }, "x [mm]"),
    s("text", { x: 12, y: (plot.top + plot.bottom) / 2, "text-anchor": "middle", class: "crack-axis",
      transform: `rotate(-90 12 ${(plot.top + plot.bottom) / 2})` }, "y [mm]"),
  ];
}

// The path from the drawn tip to the last, a dot per tip, and an arrow
// from the start towards the pinion's centre: a path along it runs down
// into the rim, one across it through the tooth's root.
function pathSvg(crack) {
  const f = pathFigure(crack);
  if (!f) return h("p", { class: "muted", id: "crack-path-none" }, "No path: the crack did not grow.");
  const [first] = f.points;
  const last = f.points[f.points.length - 1];
  // The arrow: 34 px, shorter where it would leave the plot.
  const room = (p, d, lo, hi) => (d > 1e-9 ? (hi - p) / d : d < -1e-9 ? (lo - p) / d : Infinity);
  const arrow = f.centre ? Math.max(0, Math.min(34,
    room(first.x, f.centre.x, f.plot.left + 4, f.plot.right - 4), room(first.y, f.centre.y, f.plot.top + 14, f.plot.bottom - 14))) : 0;
  const tx = first.x + arrow * (f.centre?.x ?? 0), ty = first.y + arrow * (f.centre?.y ?? 0);
  const svg = s("svg", { id: "crack-path", viewBox: `0 0 ${f.width} ${f.height}`, width: f.width, height: f.height,
    role: "img", "aria-labelledby": "crack-path-title" },
  s("title", { id: "crack-path-title" }, "The crack's path in the reference configuration, x and y in mm at one scale: from the drawn tip, a dot per increment"),
  s("defs", {}, s("marker", { id: "crack-arrow", viewBox: "0 0 10 10", refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: "auto-start-reverse" },
    s("path", { d: "M0 0 L10 5 L0 10 z", class: "crack-arrowhead" }))),
  axes(f),
  f.centre ? [
    s("line", { x1: first.x, y1: first.y, x2: tx, y2: ty, class: "crack-centre", "marker-end": "url(#crack-arrow)" }),
    s("text", { x: tx + (f.centre.x >= 0 ? 4 : -4), y: ty + (f.centre.y >= 0 ? 12 : -4), class: "crack-label",
      "text-anchor": f.centre.x >= 0 ? "start" : "end" }, "to the pinion's centre"),
  ] : null,
  s("polyline", { points: f.points.map((p) => `${p.x.toFixed(1)},${p.y.toFixed(1)}`).join(" "), class: "crack-line" }),
  f.points.map((p, k) => s("circle", { cx: p.x, cy: p.y, r: k === 0 || k === f.points.length - 1 ? 4 : 3,
    class: k === 0 ? "crack-dot start" : "crack-dot" })),
  s("text", { x: last.x, y: last.y - 8, "text-anchor": "middle", class: "crack-label" }, "tip"));
  return h("figure", { class: "crack-figure" }, svg,
    h("figcaption", {}, "Path from the drawn tip (open dot; the initial cut from the mouth lies before it), one dot per increment."));
}

function numbersTable(crack) {
  return h("table", { class: "crack-table", id: "crack-numbers" },
    h("tbody", {}, crackNumbers(crack).map((r) => h("tr", { dataset: { key: r.key } },
      h("th", { scope: "row" }, r.label), h("td", {}, r.value)))));
}

// The panel, or null for a run without a crack. draw() is called once the
// section is in the page (the chart takes its width).
export function crackPanel(summary) {
  const crack = crackAnalysis(summary);
  if (!crack) return null;
  const verdict = crackVerdict(crack);
  const chartEl = h("div", { class: "chart", id: "chart-crack" });
  const section = h("section", { class: "panel", id: "crack", "aria-labelledby": "crack-head" },
    h("header", {}, h("h2", { id: "crack-head" }, "Root crack"),
      h("span", { class: "muted" }, "tooth 0, from its tension fillet, by maximum tangential stress")),
    h("div", { class: "body crack" },
      h("div", { class: `crack-verdict ${verdict.level}`, id: "crack-verdict", dataset: { outcome: verdict.outcome ?? "none" } },
        h("strong", {}, verdictSentence(verdict)),
        h("span", {}, verdict.note),
        stopText(crack.stop) ? h("span", { class: "muted", id: "crack-stop" }, `Stopped: ${stopText(crack.stop)}.`) : null),
      h("div", { class: "crack-grid-2" }, numbersTable(crack), pathSvg(crack)),
      chartEl));
  let chart = null;
  return {
    section,
    draw() {
      const c = kChart(crack);
      if (!c) {
        chartEl.replaceChildren(h("p", { class: "muted" }, "No stress intensity factors in the summary."));
        return;
      }
      try {
        chart = lineChart(chartEl, {
          title: "Stress intensity factors against crack length",
          x: { values: c.length_m, quantity: "crack length", symbol: "a", unit: "m" },
          quantity: "K", unit: "MPa√m", prefix: false, series: c.series, height: 260,
        });
      } catch (e) {
        chartEl.replaceChildren(h("p", { class: "problems" }, `Could not draw the crack's K: ${e.message}`));
      }
    },
    destroy() {
      chart?.destroy();
    },
  };
}
