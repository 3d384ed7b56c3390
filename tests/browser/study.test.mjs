// The Study page in the dashboard (headless Chromium against a real
// `gearsph serve --no-local-workers`, so that the sweep's jobs stay queued):
// a speed sweep posted from Node (and a bad one refused at its ratio), its
// page with both jobs queued, refreshed to the report once both are
// dismissed: the K_v chart with the lumped model's fine curve and the
// resonance marks, the "no job ran" sentence, the report to download; a
// job's page links back to its study; an axes study shows its table and
// CSV; an unknown study says so. Any console error but the unknown
// study's own 404 fails the test.
//
//   node tests/browser/study.test.mjs --gearsph build/gearsph --screenshots build/browser-screenshots
import { mkdirSync, mkdtempSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { SHOTS, check, failures, openBrowser, startServer, tearDown, finish, checkNoConsoleErrors } from "./harness.mjs";

// A coarse rack and pinion, quick to plan.
const JOB = {
  name: "pair",
  scene: { type: "rack_pinion", pinion: { omega_rad_s: -15.0 }, rack: { velocity_m_s: -0.36, load_N: 5000.0 } },
  discretization: { particles: "lattice", spacing_mm: 2.0 },
};

const scratch = mkdtempSync(join(tmpdir(), "gearsph-browser-study-"));
mkdirSync(SHOTS, { recursive: true });
const server = await startServer(join(scratch, "data"), ["--no-local-workers", "--threads-per-job", "1"]);
console.log(`server: ${server.url}`);

async function api(method, path, body) {
  const res = await fetch(server.url + path, {
    method,
    headers: { Accept: "application/json", ...(body ? { "Content-Type": "application/json" } : {}) },
    body: body ? JSON.stringify(body) : undefined,
  });
  const type = res.headers.get("Content-Type") || "";
  return { status: res.status, body: type.includes("json") ? await res.json() : await res.text() };
}

const { context, page, consoleErrors } = await openBrowser(join(scratch, "profile"), {
  timeout: 60_000,
  // The unknown study this test opens: the browser logs its 404.
  expected: (msg) => /\/studies\/no-such-study/.test(msg.location().url || "") && /status of 404/.test(msg.text()),
});

// Panels wider than the page shows: their ids.
const overflowing = () => page.evaluate(() => [...document.querySelectorAll("#main .panel")]
  .filter((p) => p.scrollWidth > p.clientWidth + 1).map((p) => p.id || p.className));

let exitCode = 1;
try {
  // 1. A bad sweep is refused at its ratio; the good one is made.
  const bad = await api("POST", "/studies", { name: "bad", speed_sweep: { job: JOB, ratios: [0.5, -1], steady_periods: 2 } });
  check(bad.status === 400 || bad.status === 422, `a negative ratio is refused (${bad.status})`);
  const pointers = (bad.body.errors || []).map((e) => e.pointer);
  check(pointers.includes("/speed_sweep/ratios/1"), `at /speed_sweep/ratios/1 (${pointers.join(", ")})`);
  const made = await api("POST", "/studies", { name: "paper-pair", speed_sweep: { job: JOB, ratios: [0.5, 1.5], steady_periods: 2 } });
  check(made.status === 201, `the sweep is made (${made.status})`);
  const study = made.body;
  check(study.kind === "speed_sweep" && study.jobs?.length === 2, `a speed sweep of two jobs (${study.kind}, ${study.jobs?.length})`);

  // 2. Its page: both jobs queued, the charts still to come.
  await page.goto(`${server.url}/#/studies/${study.studyID}`);
  await page.locator("#study-jobs tbody tr").first().waitFor();
  check((await page.locator("#study-title").textContent()) === "paper-pair", "the page names the study");
  check((await page.title()) === "Study · GearSPH", `the title (${await page.title()})`);
  check((await page.locator('a[data-view="compare"]').getAttribute("aria-current")) === "page", "under the Compare tab");
  const queued = await page.locator("#study-jobs tbody .status").allTextContents();
  check(queued.length === 2 && queued.every((t) => t === "queued"), `both jobs queued (${queued.join(", ")})`);
  const freqs = await page.locator("#study-jobs tbody tr td:nth-child(3)").allTextContents();
  check(freqs.length === 2 && Number(freqs[0]) < Number(freqs[1]), `mesh frequencies ascending (${freqs.join(", ")} Hz)`);
  check(await page.locator("#study-pending").isVisible(), "the charts are announced for when the speeds have finished");
  check((await page.locator("#study-overview").textContent()).includes("speed sweep"), "the kind is shown");
  await page.screenshot({ path: join(SHOTS, "18-study-queued.png"), fullPage: true });

  // 3. Both dismissed: the page refreshes (every 2 s) to the lumped model's report.
  for (const j of study.jobs) {
    const d = await api("DELETE", `/jobs/${j.jobID}`);
    check(d.status === 200 || d.status === 202 || d.status === 204, `job ${j.jobID.slice(0, 8)} dismissed (${d.status})`);
  }
  await page.locator("#study-kv-chart canvas").waitFor({ timeout: 20_000 });
  const doc = (await api("GET", `/studies/${study.studyID}`)).body;
  const report = doc.speed_sweep || {};
  check(Array.isArray(report.K_v_sdof_fine) && report.K_v_sph?.every((v) => v === null),
    "the report has the lumped model's curve and no SPH value");
  const legend = await page.locator("#study-kv-chart .u-legend").textContent();
  check(legend.includes("lumped, fine sweep"), "the K_v chart has the lumped model's fine curve");
  check(legend.includes("speeds up") && legend.includes("speeds down"), "and the lumped model at the speeds going up and down");
  // The axes' titles are drawn on the canvas; the legend names the abscissa.
  check(/f_z \[k?Hz\]/.test(legend), "the abscissa is the mesh frequency in Hz (or kHz)");
  const label = await page.locator("#study-kv-chart").getAttribute("aria-label");
  const f = report.mesh_frequency_Hz_fine;
  const inSweep = (v) => typeof v === "number" && v >= f[0] && v <= f[f.length - 1];
  const lines = await page.locator("#study-lines").textContent();
  if (inSweep(report.resonance_Hz_iso)) {
    check(label.includes("ISO 6336-1 resonance"), `the ISO 6336-1 resonance is marked (${label})`);
  } else if (typeof report.resonance_Hz_iso === "number") {
    check(!label.includes("ISO 6336-1 resonance") && /Not marked.*ISO 6336-1/.test(lines),
      `the ISO 6336-1 resonance (${report.resonance_Hz_iso} Hz) lies beyond the sweep: named in the text, not marked`);
  } else {
    console.log(`note: resonance_Hz_iso is ${report.resonance_Hz_iso}: no ISO mark expected`);
  }
  if (inSweep(report.resonance_Hz_sdof)) check(label.includes("lumped resonance"), "the lumped model's resonance is marked");
  check(!label.includes("SPH resonance"), "no SPH resonance without an SPH run");
  // The cursor over the DTE chart: the legend gives its values in µm.
  const over = page.locator("#study-dte-chart .u-over");
  const box = await over.boundingBox();
  await page.mouse.move(box.x + box.width * 0.02, box.y + box.height / 2);
  const dteLegend = await page.locator("#study-dte-chart .u-legend").textContent();
  check(/\d µm/.test(dteLegend), `the transmission error is in micrometres (${dteLegend.replace(/\s+/g, " ").trim()})`);
  await page.mouse.move(0, 0);
  const note = await page.locator("#study-sph-note").textContent();
  check(/no job ran/i.test(note), `the page says no job ran (${note})`);
  check(/Natural frequency/.test(lines) && /Damping ratio/.test(lines) && /Resonance/.test(lines),
    "natural frequency, damping ratio and resonances as text");
  const dismissed = await page.locator("#study-jobs tbody .status").allTextContents();
  check(dismissed.every((t) => t === "dismissed"), `the jobs shown dismissed (${dismissed.join(", ")})`);
  const download = page.locator("#study-report-json");
  check(/\.json$/.test(await download.getAttribute("download")), "the report is offered as a JSON file");
  const fetched = await page.evaluate(async () => (await fetch(document.getElementById("study-report-json").href)).json());
  check(JSON.stringify(fetched) === JSON.stringify(report), "the download is the server's report");
  const wide = await overflowing();
  check(wide.length === 0, `no panel overflows (${wide.join(", ")})`);
  await page.screenshot({ path: join(SHOTS, "19-study-report.png"), fullPage: true });

  // 4. A job's page links to its study, and back.
  await page.locator("#study-jobs a.job-link").first().click();
  await page.locator("#job-study").waitFor();
  check((await page.locator("#job-study").getAttribute("href")) === `#/studies/${study.studyID}`, "the job's page links to its study");
  await page.click("#job-study");
  await page.locator("#study-kv-chart canvas").waitFor();
  check(page.url().endsWith(`#/studies/${study.studyID}`), "and the link leads back to the study");
  await page.goto(`${server.url}/#/jobs`);
  await page.locator("#jobs-table a.study-link").first().waitFor();
  check(await page.locator("#jobs-table a.study-link").count() >= 2, "the job list links the study's jobs to it");

  // 5. An axes study: its table and the CSV link.
  const grid = await api("POST", "/studies", { name: "load", base: JOB,
    axes: [{ pointer: "/scene/rack/load_N", values: [4000, 6000] }] });
  check(grid.status === 201, `an axes study is made (${grid.status})`);
  for (const j of grid.body.jobs || []) await api("DELETE", `/jobs/${j.jobID}`);
  await page.goto(`${server.url}/#/studies/${grid.body.studyID}`);
  await page.locator("#study-table").waitFor({ timeout: 20_000 });
  check((await page.locator("#study-jobs thead").textContent()).includes("/scene/rack/load_N"), "its jobs' table names the axis");
  check(await page.locator("#study-table tbody tr").count() === 2, "its results table has a row per job");
  const csvHref = await page.locator("#study-csv").getAttribute("href");
  check(csvHref === `/studies/${grid.body.studyID}?format=csv`, `the CSV link (${csvHref})`);
  const csv = await page.evaluate(async (u) => (await fetch(u)).text(), csvHref);
  check(csv.split("\n")[0].includes("jobID"), "the CSV has its header");
  check((await overflowing()).length === 0, "no panel overflows on the axes study");
  await page.screenshot({ path: join(SHOTS, "20-study-axes.png"), fullPage: true });

  // 6. A study that does not exist.
  await page.goto(`${server.url}/#/studies/no-such-study`);
  await page.locator("#study-missing").waitFor();
  check((await page.locator("#study-title").textContent()) === "No such study", "an unknown study is named so");
  await page.screenshot({ path: join(SHOTS, "21-study-missing.png"), fullPage: true });

  checkNoConsoleErrors(consoleErrors);
  exitCode = failures.length ? 1 : 0;
} catch (e) {
  console.error(`FAIL: ${e.stack || e}`);
  console.error(server.log());
  await page.screenshot({ path: join(SHOTS, "study-failure.png"), fullPage: true }).catch(() => {});
} finally {
  await tearDown({ context, server, scratch });
}
finish(exitCode);
