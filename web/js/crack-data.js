// A root crack grown in a static gear check (summary analysis.crack,
// docs/cracks.md "The gear") as the result view shows it: the verdict in
// words, the numbers, K against crack length and the path's figure. Pure
// (no DOM, no chart library): unit-tested in Node.
import { sig } from "./format.js";

// analysis.crack of a summary, else null.
export function crackAnalysis(summary) {
  const c = summary?.analysis?.crack;
  return c && typeof c === "object" && !Array.isArray(c) ? c : null;
}

const finite = (v) => (Number.isFinite(v) ? v : null);

// path_m as [[x, y], ...] of finite numbers (a malformed point ends it: the
// points after it would be joined across the gap).
export function pathPoints(crack) {
  const out = [];
  for (const p of Array.isArray(crack?.path_m) ? crack.path_m : []) {
    if (!Array.isArray(p) || !Number.isFinite(p[0]) || !Number.isFinite(p[1])) break;
    out.push([p[0], p[1]]);
  }
  return out;
}

// The crack's length [m] with its tip at each point of path_m. path_m[0] is
// the drawn tip (the solver's paths start at the tip it cut, not at the
// mouth: scene/crack_stages.cpp pushes tips[0] first), so its length is the
// initial one and every later point adds the segment that reached it.
// [] without a finite initial length.
export function crackLengths(crack) {
  const initial = finite(crack?.initial_length_m);
  if (initial === null) return [];
  const p = pathPoints(crack);
  const out = p.length ? [initial] : [];
  for (let k = 1; k < p.length; k++) out.push(out[k - 1] + Math.hypot(p[k][0] - p[k - 1][0], p[k][1] - p[k - 1][1]));
  return out;
}

// The length at the end, along the path; null when unknown.
export function finalLength(crack) {
  const l = crackLengths(crack);
  return l.length ? l[l.length - 1] : finite(crack?.initial_length_m);
}

const MPA = 1e-6;

// K against crack length: {length_m, series: [{label, values [MPa m^0.5],
// colour, dash}]}. Stage k reads K with the tip at path_m[k] (grow_crack_stage
// reads K, then pushes the next tip), so K[k] goes with crackLengths[k]: the
// length before increment k. A run stopped at a boundary or by
// max_increments has one stage more than increments, its last K read at the
// final tip; pairs beyond the shorter list are dropped.
export function kChart(crack) {
  const lengths = crackLengths(crack);
  const lists = [
    ["K_I", crack?.K_I_Pa_sqrt_m, "#d62728", undefined],
    ["K_II", crack?.K_II_Pa_sqrt_m, "#1f77b4", undefined],
    ["K_eq (max. tangential stress)", crack?.K_eq_Pa_sqrt_m, "#111827", [6, 4]],
  ].filter(([, v]) => Array.isArray(v) && v.length);
  const n = Math.min(lengths.length, ...lists.map(([, v]) => v.length));
  if (!lists.length || !(n > 0)) return null;
  return {
    length_m: lengths.slice(0, n),
    series: lists.map(([label, v, colour, dash]) => ({
      label, colour, dash, values: v.slice(0, n).map((x) => (Number.isFinite(x) ? x * MPA : null)),
    })),
  };
}

// The outcome in words (outcome "tooth" | "rim" | "arrested" | null). A run
// that used its max_increments before reaching a boundary has the outcome
// of where its last segment heads, reached_boundary false: said as such.
//   {outcome, level ("bad" | "ok" | "none"), headline (the words after "The
//   crack"), note}
export function crackVerdict(crack) {
  const outcome = crack?.outcome ?? null;
  const reached = crack?.reached_boundary === true;
  const ahead = "where its last segment heads: growth stopped before the path reached a boundary";
  if (outcome === "tooth") {
    return { outcome, level: "bad", headline: reached ? "breaks the tooth off" : "heads to break the tooth off",
      note: reached ? "the path runs out at the toothed surface beside tooth 0: the tooth comes away" : ahead };
  }
  if (outcome === "rim") {
    return { outcome, level: "bad", headline: reached ? "runs through the rim: the wheel would split" : "heads through the rim: the wheel would split",
      note: reached ? "the path runs to the bore or the modelled sector's cut sides" : ahead };
  }
  if (outcome === "arrested") {
    return { outcome, level: "ok", headline: "arrested", note: "K_I fell to 0: the crack closes under this load" };
  }
  return { outcome: null, level: "none", headline: "no outcome", note: "the run ended before the growth gave one" };
}

// The verdict as the panel's first line.
export function verdictSentence(v) {
  if (v.outcome === "arrested") return "The crack is arrested";
  return v.outcome ? `The crack ${v.headline}` : "No outcome";
}

// Paris cycles for people: 1.23e6 from ten thousand on, else whole cycles.
export function cyclesText(cycles) {
  if (cycles === null || cycles === undefined) return "no finite life (K_eq ≤ 0 on the path: below the threshold of growth)";
  if (!Number.isFinite(cycles)) return "—";
  return cycles >= 1e4 ? cycles.toExponential(2).replace("e+", "e") : String(Math.round(cycles));
}

// The solver's stop sentence, its std::to_string numbers (7.534000) cut to
// two decimals.
export function stopText(stop) {
  if (typeof stop !== "string" || !stop.trim()) return "";
  return stop.trim().replace(/-?\d+\.\d+/g, (t) => String(Number(Number(t).toFixed(2))));
}

// A length in mm, three figures.
export function mmText(m) {
  return Number.isFinite(m) ? `${Number((m * 1e3).toPrecision(3))} mm` : "—";
}

// The panel's numbers: [{key, label, value}], each value a text with its unit.
export function crackNumbers(crack) {
  const rows = [
    ["initial", "Initial length", mmText(crack?.initial_length_m)],
    ["final", "Final length (along the path)", mmText(finalLength(crack))],
    ["increments", "Increments", Number.isFinite(crack?.increments)
      ? `${crack.increments}${Number.isFinite(crack.increment_m) ? ` of ${mmText(crack.increment_m)}` : ""}` : "—"],
    ["start", "Start on the tension fillet", Number.isFinite(crack?.start_fillet_position)
      ? `${crack.start_fillet_position.toFixed(2)} (0 its top, 1 the root circle)` : "—"],
    ["spacing", "Particle spacing along the crack", mmText(crack?.spacing_m)],
  ];
  const p = crack?.paris;
  if (p && typeof p === "object") {
    rows.push(
      ["cycles", "Paris life to the end", p.cycles === null || p.cycles === undefined ? cyclesText(null) : `${cyclesText(p.cycles)} cycles`],
      ["paris", "Paris' law da/dN = C ΔK_eq^m", `C = ${sig(p.C)}, m = ${sig(p.m)}, R = ${sig(p.R ?? 0)} (ΔK in MPa m^0.5, da/dN in m/cycle)`]);
  }
  return rows.map(([key, label, value]) => ({ key, label, value }));
}

// "Nice" tick values (1, 2, 5 times a power of ten) covering [lo, hi].
export function niceTicks(lo, hi, count = 5) {
  if (!(hi > lo)) return [lo];
  const raw = (hi - lo) / count;
  const p = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((f) => f * p).find((s) => s >= raw * (1 - 1e-9));
  const out = [];
  for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step) out.push(Number(v.toPrecision(12)));
  return out;
}

// The path drawn in a width x height box at one scale for x and y (mm, y
// up as in the reference configuration): {points: [{x, y}] px, xTicks,
// yTicks: [{at (px), label (mm)}], centre: {x, y} unit vector from the
// first point towards the pinion's centre (the origin, rack_pinion.cpp),
// plot: {left, top, right, bottom}}; null with fewer than two points.
export function pathFigure(crack, { width = 360, height = 260, margin = { left: 52, right: 16, top: 14, bottom: 40 } } = {}) {
  const pts = pathPoints(crack).map(([x, y]) => [x * 1e3, y * 1e3]);
  if (pts.length < 2) return null;
  const xs = pts.map((p) => p[0]), ys = pts.map((p) => p[1]);
  const plot = { left: margin.left, top: margin.top, right: width - margin.right, bottom: height - margin.bottom };
  const w = plot.right - plot.left, hgt = plot.bottom - plot.top;
  // One scale, the path with a tenth of room about it, centred.
  const span = Math.max(Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys), 1e-6) * 1.2;
  const scale = Math.min(w, hgt) / span;
  const cx = (Math.max(...xs) + Math.min(...xs)) / 2, cy = (Math.max(...ys) + Math.min(...ys)) / 2;
  const px = (x) => plot.left + w / 2 + (x - cx) * scale;
  const py = (y) => plot.top + hgt / 2 - (y - cy) * scale;
  const ticks = (lo, hi, at) => niceTicks(lo, hi, 4).map((v) => ({ at: at(v), label: String(v) }));
  const x0 = cx - w / 2 / scale, x1 = cx + w / 2 / scale, y0 = cy - hgt / 2 / scale, y1 = cy + hgt / 2 / scale;
  const r = Math.hypot(pts[0][0], pts[0][1]);
  return {
    width, height, plot, scale,
    points: pts.map(([x, y]) => ({ x: px(x), y: py(y) })),
    xTicks: ticks(x0, x1, px),
    yTicks: ticks(y0, y1, py),
    centre: r > 0 ? { x: -pts[0][0] / r, y: pts[0][1] / r } : null, // in px directions (y down)
  };
}
