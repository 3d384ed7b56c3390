// Line charts with uPlot (served from /vendor/, installed by npm): time
// histories, and the stress along a fillet. Data come in SI; each chart
// picks the prefix that keeps its numbers readable (a 20 µs run is shown
// in µs, 300 MPa as MPa, not 3e8 Pa).
import uPlot from "../vendor/uPlot.esm.js";

export const PALETTE = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22"];

const PREFIXES = [[1e9, "G"], [1e6, "M"], [1e3, "k"], [1, ""], [1e-3, "m"], [1e-6, "µ"], [1e-9, "n"]];

// [scale, prefix] that puts maxAbs in [1, 1000) of the prefixed unit.
export function prefixFor(maxAbs) {
  if (!(maxAbs > 0) || !Number.isFinite(maxAbs)) return [1, ""];
  return PREFIXES.find(([s]) => maxAbs >= s * 0.9995) || PREFIXES[PREFIXES.length - 1];
}

function maxAbs(arrays) {
  let m = 0;
  for (const a of arrays) for (const v of a) if (Number.isFinite(v)) m = Math.max(m, Math.abs(v));
  return m;
}

// Decimals that show a tick increment exactly (0.25 -> 2, 5 -> 0).
function decimalsFor(increment) {
  for (let d = 0; d < 9; d++) {
    const v = increment * 10 ** d;
    if (Math.abs(v - Math.round(v)) < 1e-6 * Math.max(1, Math.abs(v))) return d;
  }
  return 9;
}

function tickLabels(u, splits, axis, space, increment) {
  const d = decimalsFor(increment);
  return splits.map((v) => (v === null ? "" : (Math.abs(v) < increment * 1e-6 ? 0 : v).toFixed(d)));
}

// A dashed vertical line at each mark, labelled at the top of the plot.
function drawMarks(marks, scale) {
  return (u) => {
    const { ctx } = u;
    const { top, height } = u.bbox;
    ctx.save();
    ctx.strokeStyle = "#6b7280";
    ctx.fillStyle = "#5b6573";
    ctx.lineWidth = devicePixelRatio;
    ctx.setLineDash([3 * devicePixelRatio, 3 * devicePixelRatio]);
    ctx.font = `${11 * devicePixelRatio}px system-ui, sans-serif`;
    const right = u.bbox.left + u.bbox.width;
    const gap = 4 * devicePixelRatio;
    for (const m of marks) {
      const x = Math.round(u.valToPos(m.value / scale, "x", true));
      ctx.beginPath();
      ctx.moveTo(x, top);
      ctx.lineTo(x, top + height);
      ctx.stroke();
      // Right of its line, or left of it where it would leave the plot
      // (uPlot leaves its axes' alignment on the context: set it each time).
      const fits = x + gap + ctx.measureText(m.label).width <= right;
      ctx.textAlign = fits ? "left" : "right";
      ctx.fillText(m.label, fits ? x + gap : x - gap, top + 12 * devicePixelRatio);
    }
    ctx.restore();
  };
}

// A chart in `el` that follows the element's width.
//   time_s: sample times [s]; series: [{label, values [SI], colour?, dash?}]
//   quantity/unit: the y axis ("force", "N"); prefix: false keeps the unit as is.
//   x: another abscissa than time, {values [SI], quantity, symbol, unit}
//   ("arc length", "s", "m"); its charts do not follow the time cursor.
//   marks: [{value [SI, x], label}] drawn as vertical lines.
export function lineChart(el, { title, time_s, x, quantity, unit, prefix = true, series, marks = [], height = 260 }) {
  el.replaceChildren();
  const heading = document.createElement("h3");
  heading.textContent = title;
  const holder = document.createElement("div");
  el.append(heading, holder);
  const abscissa = x || { values: time_s, quantity: "time", symbol: "t", unit: "s" };
  const [ts, tp] = prefixFor(maxAbs([abscissa.values]));
  const xUnit = `${tp}${abscissa.unit}`;
  const [ys, yp] = prefix ? prefixFor(maxAbs(series.map((s) => s.values))) : [1, ""];
  const yUnit = `${yp}${unit}`;
  // NaN (a quantity not defined at a sample) is a gap; undefined (a sample
  // another series has, after a join) is bridged.
  const scale = (values, f) => Array.from(values, (v) => (v === undefined ? undefined : Number.isFinite(v) ? v / f : null));
  const width = () => Math.max(260, Math.floor(el.clientWidth || 600));
  const axis = (label, size) => ({ label, labelSize: 20, size, values: tickLabels,
    grid: { stroke: "#eceff3" }, ticks: { stroke: "#d9dde3" } });
  const opts = {
    width: width(),
    height,
    cursor: { drag: { x: true, y: false }, sync: x ? undefined : { key: "gearsph" } },
    scales: { x: { time: false } },
    axes: [axis(`${abscissa.quantity} [${xUnit}]`, 40), axis(`${quantity} [${yUnit}]`, 64)],
    series: [
      { label: `${abscissa.symbol} [${xUnit}]`, value: (u, v) => (v === null || v === undefined ? "—" : v.toPrecision(4)) },
      ...series.map((s, k) => ({
        label: s.label,
        stroke: s.colour || PALETTE[k % PALETTE.length],
        width: 1.5,
        dash: s.dash,
        spanGaps: false,
        value: (u, v) => (v === null || v === undefined ? "—" : `${Number(v).toPrecision(4)} ${yUnit}`),
      })),
    ],
    legend: { live: true },
    hooks: marks.length ? { draw: [drawMarks(marks, ts)] } : {},
  };
  const plot = new uPlot(opts, [scale(abscissa.values, ts), ...series.map((s) => scale(s.values, ys))], holder);
  const ro = new ResizeObserver(() => {
    const w = width();
    if (Math.abs(w - plot.width) > 2) plot.setSize({ width: w, height });
  });
  ro.observe(el);
  el.setAttribute("role", "img");
  el.setAttribute("aria-label", `${title}: ${series.map((s) => s.label).join(", ")} against ${abscissa.quantity}`);
  return { plot, destroy() { ro.disconnect(); plot.destroy(); } };
}

// Several histories on one time axis (their time samples may differ):
// [[t, v], ...] -> [t, v1, v2, ...], undefined where a run has no sample.
export function joinSeries(tables) {
  return uPlot.join(tables.map(([t, v]) => [Array.from(t), Array.from(v)]));
}
