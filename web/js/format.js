// Numbers and times for people: engineering prefixes, fixed significant
// figures, durations. Pure functions (no DOM): unit-tested in Node.

const PREFIXES = [
  [1e9, "G"], [1e6, "M"], [1e3, "k"], [1, ""], [1e-3, "m"], [1e-6, "µ"], [1e-9, "n"],
];

export function eng(value, unit = "", digits = 3) {
  if (value === null || value === undefined || Number.isNaN(value)) return "—";
  if (!Number.isFinite(value)) return String(value);
  if (value === 0) return `0 ${unit}`.trim();
  const a = Math.abs(value);
  const [scale, prefix] = PREFIXES.find(([s]) => a >= s * 0.9995) || PREFIXES[PREFIXES.length - 1];
  return `${parseFloat((value / scale).toPrecision(digits))} ${prefix}${unit}`.trim();
}

export function sig(value, digits = 3) {
  if (value === null || value === undefined || Number.isNaN(value)) return "—";
  const a = Math.abs(value);
  if (a !== 0 && (a < 1e-3 || a >= 1e6)) return value.toExponential(digits - 1);
  return Number(value.toPrecision(digits)).toLocaleString("en-US", { maximumFractionDigits: 12 });
}

export function int(value) {
  if (value === null || value === undefined) return "—";
  return Math.round(value).toLocaleString("en-US");
}

export function duration(seconds) {
  if (seconds === null || seconds === undefined || !Number.isFinite(seconds)) return "—";
  if (seconds < 1) return `${(seconds * 1000).toFixed(0)} ms`;
  if (seconds < 60) return `${seconds.toFixed(seconds < 10 ? 1 : 0)} s`;
  const m = Math.floor(seconds / 60), s = Math.round(seconds % 60);
  if (m < 60) return `${m} min ${String(s).padStart(2, "0")} s`;
  const h = Math.floor(m / 60);
  if (h < 48) return `${h} h ${String(m % 60).padStart(2, "0")} min`;
  return `${(h / 24).toFixed(1)} days`;
}

export function bytes(n) {
  if (n === null || n === undefined) return "—";
  const units = ["B", "KB", "MB", "GB", "TB"];
  let i = 0;
  while (n >= 1000 && i < units.length - 1) { n /= 1000; i++; }
  return `${n.toFixed(n < 10 && i > 0 ? 1 : 0)} ${units[i]}`;
}

export function when(iso) {
  if (!iso) return "—";
  const d = new Date(iso);
  const today = new Date();
  const time = d.toLocaleTimeString("en-GB", { hour: "2-digit", minute: "2-digit", second: "2-digit" });
  if (d.toDateString() === today.toDateString()) return time;
  return `${d.toISOString().slice(0, 10)} ${time}`;
}

export function escapeId(s) {
  return s.replace(/[^A-Za-z0-9_-]/g, "_");
}

// Time left of a running job; none until its first steps give a speed.
export function eta(job) {
  if (job.status === "accepted") return "queued";
  if (job.status !== "running") return "—";
  if (job.setup && !(job.step > 0)) {
    return `setting up: ${job.setup.stage} ${Math.round(100 * (job.setup.fraction ?? 0))} %`;
  }
  if (!(job.step > 0) || job.eta_s === null || job.eta_s === undefined) return "estimating…";
  return duration(job.eta_s);
}

// The server as the header names it (GET /health): its version and how it
// runs jobs, a core budget the jobs share or a fixed workers x threads; and
// a dependency that is down (a 503 /health), by name.
export function serverIdentity(hl) {
  const plural = (n, word) => `${n} ${word}${n === 1 ? "" : "s"}`;
  const runs = hl.core_budget > 0
    ? `${plural(hl.core_budget, "core")} shared by the jobs`
    : `${plural(hl.workers, "worker")} × ${plural(hl.threads_per_job, "thread")}`;
  const names = { store: "job store", results: "results directory" };
  const down = Object.entries(hl.dependencies || {})
    .filter(([, d]) => d && d.status === "down")
    .map(([name]) => `${names[name] || name} unreachable`);
  return [`gearsph ${hl.version}`, runs, ...down].join(" · ");
}

// Whether /health named a dependency that is down.
export function serverDegraded(hl) {
  return Object.values(hl.dependencies || {}).some((d) => d && d.status === "down");
}
