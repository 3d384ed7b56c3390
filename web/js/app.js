// The dashboard: a hash router over six views and one shared event stream.
// Only this module starts anything; the others can be imported on their own.
import { ensureSignedIn, get, onTokenNeeded } from "./api.js";
import { compareView } from "./compare.js";
import { events } from "./events.js";
import { serverDegraded, serverIdentity } from "./format.js";
import { jobsView } from "./jobs.js";
import { ratingView } from "./rating.js";
import { resultView } from "./result.js";
import { studyView } from "./study.js";
import { submitView } from "./submit.js";
import { askForToken, h } from "./ui.js";

const main = document.getElementById("main");
let current = null; // {dispose()}

function route() {
  const hash = location.hash.replace(/^#/, "") || "/submit";
  const [path, query = ""] = hash.split("?");
  const params = new URLSearchParams(query);
  const parts = path.split("/").filter(Boolean);
  let view = "submit";
  let render;
  let title = null; // the view's own, if not its tab's
  if (parts[0] === "jobs" && parts[1]) {
    view = "jobs";
    render = () => resultView(main, decodeURIComponent(parts[1]), params);
  } else if (parts[0] === "jobs") {
    view = "jobs";
    render = () => jobsView(main, params);
  } else if (parts[0] === "compare") {
    view = "compare";
    render = () => compareView(main, params);
  } else if (parts[0] === "studies" && parts[1]) {
    // A study sets its jobs side by side: it sits under Compare in the tab bar.
    view = "compare";
    title = "Study";
    render = () => studyView(main, decodeURIComponent(parts[1]));
  } else if (parts[0] === "rating") {
    view = "rating";
    render = () => ratingView(main);
  } else {
    render = () => submitView(main, params);
  }
  for (const a of document.querySelectorAll(".tabs a")) {
    if (a.dataset.view === view) a.setAttribute("aria-current", "page");
    else a.removeAttribute("aria-current");
  }
  current?.dispose?.();
  main.replaceChildren();
  current = render();
  title ??= { submit: "New job", jobs: "Jobs", compare: "Compare", rating: "Rating" }[view];
  document.title = `${title} · GearSPH`;
}

// The server's identity, whether a dependency of it is down (/health
// answers 503 with the same document), and whether the live stream is
// connected. Asked again every 10 s.
let identity = null; // null until /health answers, "" if it failed
let degraded = false;
async function health() {
  try {
    const hl = await get("/health");
    identity = serverIdentity(hl);
    degraded = serverDegraded(hl);
  } catch (e) {
    const hl = e && e.problem;
    identity = hl && hl.version ? serverIdentity(hl) : "";
    degraded = Boolean(identity);
  }
  showConnection();
}

function showConnection() {
  const el = document.getElementById("server-state");
  if (identity === null && events.connected !== false) return; // still "connecting…"
  const down = events.connected === false || !identity || degraded;
  el.classList.toggle("down", down);
  el.title = down ? "" : "live updates connected";
  el.replaceChildren(h("span", { class: "dot" }),
    events.connected === false ? "server unreachable: reconnecting…" : identity || "server unreachable");
}

function runningCount() {
  const badge = document.getElementById("running-count");
  const update = (id, kind) => {
    if (kind === "connection") showConnection();
    const n = events.activeCount();
    badge.hidden = n === 0;
    badge.textContent = String(n);
    badge.title = `${n} job${n === 1 ? "" : "s"} queued or running`;
  };
  events.subscribe(update);
  update();
}

// A server started with --token-file: the token is asked for once.
onTokenNeeded(askForToken);

async function start() {
  try {
    await ensureSignedIn();
  } catch {
    // unreachable, or no token given: the views say what fails
  }
  window.addEventListener("hashchange", route);
  route();
  health();
  setInterval(health, 10_000);
  events.start();
  runningCount();
}

start();
