// The dashboard in headless Chromium against a real `gearsph serve` on
// loopback, used as a person would: the paper's case pre-filled with its
// geometry preview, an invalid value refused at its field, two short jobs
// submitted (form and JSON), their progress followed live, a result opened
// (image, frames, zoom, charts), the two compared, a running job cancelled,
// a static gear check with the FE check (the fillet stress panel), the
// keyboard, a narrow window. Any console error or page error fails the
// test. Screenshots go to --screenshots DIR for people to look at.
//
//   node tests/browser/dashboard.test.mjs --gearsph build/gearsph --screenshots build/browser-screenshots
import { mkdirSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { SHOTS, check, failures, openBrowser, startServer, tearDown, finish, checkNoConsoleErrors } from "./harness.mjs";

const STEP_TIMEOUT = 120_000;

const scratch = mkdtempSync(join(tmpdir(), "gearsph-browser-"));
mkdirSync(SHOTS, { recursive: true });
rmSync(join(SHOTS, "failure.png"), { force: true }); // from an earlier run
const server = await startServer(join(scratch, "data"), ["--workers", "2", "--threads-per-job", "1"]);
console.log(`server: ${server.url}`);

const { context, page, consoleErrors } = await openBrowser(join(scratch, "profile"), { timeout: STEP_TIMEOUT });

// The whole page, or (viewport) what the window shows: the job form's
// sticky submit bar is only where a user sees it in the latter; or
// (element) one part of the whole page. The whole page is taken from the
// top: scrolled, the sticky top bar would be drawn across it.
async function shot(name, { viewport = false, element = null } = {}) {
  if (!viewport) await page.evaluate(() => window.scrollTo(0, 0));
  const clip = element ? await element.boundingBox() : undefined;
  await page.screenshot({ path: join(SHOTS, `${name}.png`), fullPage: !viewport, clip });
  console.log(`screenshot: ${join(SHOTS, `${name}.png`)}`);
}

const field = (pointer) => page.locator(`.field[data-pointer="${pointer}"]`);
const input = (pointer) => field(pointer).locator("input, select");

async function waitForPreview() {
  await page.waitForFunction(() => document.querySelector("#runtime-estimate dd")?.textContent.startsWith("≈"));
}

let exitCode = 1;
try {
  // 1. The dashboard at /, with the paper's case and its preview.
  await page.goto(server.url + "/");
  await page.waitForFunction(() => document.querySelector("#f-scene-pinion-teeth")?.value === "12");
  check(await input("/scene/pinion/module_mm").inputValue() === "4", "module pre-filled with the paper's 4 mm");
  check(await input("/scene/pinion/omega_rad_s").inputValue() === "-15", "pinion speed pre-filled with -15 rad/s");
  check((await field("/scene/pinion/teeth").locator(".hint").textContent()).includes("6 to 300"),
    "the teeth field shows the schema's range");
  check((await field("/scene/pinion/module_mm").locator(".unit").textContent()) === "mm", "the module shows its unit");
  await waitForPreview();
  const estimate = await page.locator("#estimate").textContent();
  check(/Particles/.test(estimate) && /Time steps/.test(estimate), "the estimate lists particles and steps");
  check(/estimate/.test(await page.locator("#estimate .note").textContent()), "the run time is labelled as an estimate");
  check(/pinion: [\d,]+ free/.test(await page.locator(".legend").textContent()), "the preview legend counts the pinion's particles");
  const previewPixels = await page.evaluate(() => {
    const c = document.getElementById("preview-canvas");
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let coloured = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i + 3] > 0 && Math.abs(d[i] - d[i + 2]) > 60) coloured++;
    return coloured;
  });
  check(previewPixels > 500, `the preview canvas shows coloured particles (${previewPixels} px)`);
  await shot("01-submit-paper-case", { viewport: true });

  // 2. An invalid value: the server's message at the field, nothing submitted.
  await input("/scene/pinion/teeth").fill("3");
  await page.locator('.field.invalid[data-pointer="/scene/pinion/teeth"] .error').waitFor({ state: "visible" });
  const liveError = await field("/scene/pinion/teeth").locator(".error").textContent();
  check(/6/.test(liveError), `the live check shows the teeth error at the field: "${liveError}"`);
  await page.click("#submit-job");
  await page.locator("#form-problems").waitFor({ state: "visible" });
  check((await page.evaluate(() => location.hash)) === "#/submit" || (await page.evaluate(() => location.hash)) === "",
    "an invalid job is not submitted");
  check(await input("/scene/pinion/teeth").getAttribute("aria-invalid") === "true", "the field is marked invalid");
  check((await page.locator("#form-problems").textContent()).includes("Teeth"), "the problem list links the field");
  await shot("02-invalid-value-at-field", { viewport: true });
  await input("/scene/pinion/teeth").fill("12");
  await page.locator('.field[data-pointer="/scene/pinion/teeth"] .error').waitFor({ state: "hidden" });

  // 3. The paper's case, shortened, from the form.
  await input("/name").fill("paper-short");
  // 1 ms (25,000 steps): a few seconds on an idle machine (2,500 steps
  // finished in under a second, before a progress event), long enough for
  // several progress events (at most four a second) and some contact.
  await input("/time/end_s").fill("0.001");
  await input("/output/frames").fill("8");
  await waitForPreview();
  // Every progress value the job page shows, as it shows it (the page
  // is one document: the recorder outlives the change of view).
  await page.evaluate(() => {
    window.progressSeen = [];
    new MutationObserver(() => {
      const v = document.querySelector("#live .progress")?.getAttribute("aria-valuenow");
      if (v !== null && v !== undefined && window.progressSeen.at(-1) !== Number(v)) window.progressSeen.push(Number(v));
    }).observe(document.getElementById("main"), { childList: true, subtree: true, attributes: true });
  });
  await page.click("#submit-job");
  await page.waitForURL(/#\/jobs\/[0-9a-f-]{36}$/);
  const idA = page.url().split("/").pop();
  check(/^[0-9a-f-]{36}$/.test(idA), `job A submitted (${idA})`);
  await page.waitForFunction(() => window.progressSeen.some((p) => p > 0 && p < 100) ||
    document.querySelector(".result-head .status.successful"));
  const seen = await page.evaluate(() => window.progressSeen);
  check(seen.some((p) => p > 0 && p < 100), `progress seen moving on the job page: ${seen.join(", ")}`);
  await shot("03-job-running");

  // 4. A second job through the JSON tab: a loaded rack.
  await page.click('a[data-view="submit"]');
  await page.click("#tab-json");
  await page.fill("#job-json", JSON.stringify({
    name: "paper-short-loaded",
    scene: { type: "rack_pinion", rack: { load_N: 200 } },
    time: { end_s: 0.0001 },
    output: { frames: 8 },
  }, null, 2));
  await waitForPreview();
  await page.click("#submit-job");
  await page.waitForURL(/#\/jobs\/[0-9a-f-]{36}$/);
  const idB = page.url().split("/").pop();
  check(idB !== idA, `job B submitted from JSON (${idB})`);

  // 5. The job list, live.
  await page.click('a[data-view="jobs"]');
  await page.locator(`tr[data-job="${idA}"]`).waitFor();
  await page.locator(`tr[data-job="${idB}"]`).waitFor();
  await shot("04-jobs-live");
  for (const id of [idA, idB]) {
    const final = page.locator(`tr[data-job="${id}"]`).locator(".status.successful, .status.failed");
    await final.waitFor({ timeout: 300_000 });
    const status = await final.textContent();
    if (status !== "successful") {
      const why = await page.locator(`tr[data-job="${id}"] .failure`).textContent().catch(() => "");
      throw new Error(`job ${id} ${status}: ${why}`);
    }
  }
  console.log("ok: both jobs reached successful in the live list");
  // A static gear check with the FE check, through the API; it runs while
  // the next steps look at A and B. A server without gmsh or CalculiX
  // refuses it (501, fe-unavailable): then only the SPH part is checked.
  const staticJob = (feCheck) => ({
    name: feCheck ? "fillet-fe-check" : "fillet-static",
    scene: { type: "rack_pinion", quasi_static: true, contact_point: "pitch", fe_check: feCheck,
      pinion: { omega_rad_s: 0 }, rack: { velocity_m_s: 0, load_N: 1000 } },
  });
  let feRan = true;
  let staticPost = await page.request.post(`${server.url}/jobs`, { data: staticJob(true) });
  if (staticPost.status() === 501) {
    const why = (await staticPost.json()).detail;
    console.log(`SKIP: the FE part of the fillet panel's checks: ${why}`);
    feRan = false;
    staticPost = await page.request.post(`${server.url}/jobs`, { data: staticJob(false) });
  }
  check(staticPost.status() === 201, `a static gear check submitted (${staticPost.status()})`);
  const idF = (await staticPost.json()).jobID;
  check(await page.locator(`tr[data-job="${idA}"] .progress`).getAttribute("aria-valuenow") === "100",
    "job A's progress bar shows 100 %");
  await shot("05-jobs-finished");

  // 6. The result of A: image, frames, field, zoom, charts, summary, files.
  await page.click(`tr[data-job="${idA}"] a.job-link`);
  // The image on show has loaded, or failed (then say so at once).
  const imageLoaded = async () => {
    await page.waitForFunction(() => {
      const img = document.getElementById("field-image");
      const loading = document.querySelector(".viewer .loading");
      return img && img.complete && (loading.hidden || loading.textContent === "image not available");
    });
    const ok = await page.evaluate(() => document.getElementById("field-image").naturalWidth > 0);
    if (!ok) throw new Error(`image not available: ${await page.locator("#field-image").getAttribute("src")}`);
  };
  await imageLoaded();
  check(await page.evaluate(() => document.getElementById("field-image").naturalWidth) === 1280, "the von Mises image is rendered");
  check(await page.locator(".chart .uplot").count() >= 3, "three history charts are drawn");
  check(await page.locator("#fillet").count() === 0, "a dynamic run has no fillet stress panel");
  const summary = await page.locator("#summary-table").textContent();
  check(/Max von Mises stress/.test(summary) && /Velocity-stability time/.test(summary), "the summary shows max stress and stability time");
  check(/Max contact pressure\s*[\d.]+ MPa/.test(summary), "the summary shows the Hertz contact pressure of a run whose teeth touched");
  for (const name of ["results.h5", "results.xmf", "history.csv", "summary.json"]) {
    check(await page.locator(`#downloads a[download="${name}"]`).count() === 1, `download link for ${name}`);
  }
  check(await page.locator("#png-link").getAttribute("href") !== null, "download link for the PNG");
  const frames = Number(await page.locator("#frame-slider").getAttribute("max"));
  check(frames >= 2, `the frame slider spans ${frames + 1} frames`);
  await shot("06-result-von-mises");
  await page.locator("#frame-slider").focus();
  await page.keyboard.press("Home");
  await imageLoaded();
  check((await page.locator("#field-image").getAttribute("src")).includes("frame=0"), "the slider (keyboard Home) shows frame 0");
  await page.selectOption("#field-select", "velocity");
  await page.click("#zoom");
  await page.locator("#frame-slider").focus();
  await page.keyboard.press("End");
  await imageLoaded();
  const zoomSrc = await page.locator("#field-image").getAttribute("src");
  check(zoomSrc.includes("velocity.png") && zoomSrc.includes("zoom="), `zoomed speed image: ${zoomSrc}`);
  await shot("07-result-zoom-velocity");
  await page.click("#play");
  check((await page.locator("#field-image").getAttribute("src")).includes("frame=0"), "play starts again at frame 0");
  await page.waitForFunction(() => document.getElementById("play").getAttribute("aria-pressed") === "false");
  await imageLoaded();
  check((await page.locator("#field-image").getAttribute("src")).includes(`frame=${frames}&`),
    "play runs through the frames and stops at the last");

  // 7. Compare the two jobs.
  await page.click('a[data-view="jobs"]');
  await page.locator(`tr[data-job="${idA}"] input[type=checkbox]`).check();
  await page.locator(`tr[data-job="${idB}"] input[type=checkbox]`).check();
  await page.click("#compare-selected");
  await page.locator("#compare-table tbody tr").nth(1).waitFor();
  check(await page.locator("#compare-table tbody tr").count() === 2, "the comparison table has both jobs");
  const condition = await page.locator("#compare-table tbody").textContent();
  check(condition.includes("load_N"), "the condition column names what differs (the rack load)");
  await page.locator("#compare-chart .uplot").waitFor();
  check(await page.locator("#compare-chart .u-legend .u-series").count() >= 3, "the histories are overlaid (two series and time)");
  const csv = await page.evaluate(async () => (await fetch(document.getElementById("compare-csv").href)).text());
  const csvLines = csv.trim().split("\n");
  check(csvLines.length === 3 && csvLines[0].includes("max_von_mises_Pa") && csv.includes(idA) && csv.includes(idB),
    "the comparison downloads as CSV (a header and both jobs)");
  await shot("08-compare");

  // 8. Cancel a job that would run for minutes, from the live list.
  const long = await page.request.post(`${server.url}/jobs`, {
    data: { name: "to-cancel", scene: { type: "rack_pinion" }, time: { end_s: 0.01 }, output: { frames: 2 } },
  });
  check(long.status() === 201, `a long job submitted through the API (${long.status()})`);
  const idC = (await long.json()).jobID;
  await page.click('a[data-view="jobs"]');
  const rowC = page.locator(`tr[data-job="${idC}"]`);
  await rowC.locator(".status.running").waitFor();
  page.once("dialog", (d) => d.accept());
  await rowC.locator("button", { hasText: "Cancel" }).click();
  await rowC.locator(".status.dismissed").waitFor();
  console.log("ok: the running job was cancelled from the list and shows as dismissed");
  await shot("09-jobs-cancelled");

  // 9. The static gear check: the fillet stress panel, SPH against FE.
  const staticStarted = Date.now();
  for (;;) {
    const job = await (await page.request.get(`${server.url}/jobs/${idF}`)).json();
    if (job.status === "successful") break;
    if (job.status !== "accepted" && job.status !== "running") throw new Error(`static job ${idF} ${job.status}: ${job.message}`);
    if (Date.now() - staticStarted > 300_000) throw new Error(`static job ${idF} still ${job.status} after 300 s`);
    await page.waitForTimeout(500);
  }
  await page.goto(`${server.url}/#/jobs/${idF}`);
  const panel = page.locator("#fillet");
  await panel.locator("#chart-fillet .uplot").waitFor();
  check(await page.locator("#fillet-head").textContent() === "Fillet stress (tooth 0)", "the fillet stress panel is shown");
  check(await panel.getAttribute("aria-labelledby") === "fillet-head", "the panel is labelled by its heading");
  const legend = await panel.locator(".u-legend .u-series").allTextContents();
  check(legend.some((l) => l.startsWith("SPH σ1")) && legend.some((l) => l.startsWith("SPH σ3")),
    `the chart has the SPH tension and compression curves (${legend.length} legend entries)`);
  // uPlot draws its axes on the canvas: the legend under the cursor tells the units.
  await panel.locator("#chart-fillet .u-over").hover();
  const xLabel = await panel.locator(".u-legend .u-series").first().locator(".u-label").textContent();
  const yValues = await panel.locator(".u-legend .u-series .u-value").allTextContents();
  check(xLabel === "s [mm]" && yValues.some((v) => / MPa$/.test(v)),
    `the curves are stresses in MPa against arc length in mm (${xLabel}; ${yValues.slice(1, 3).join(", ")})`);
  const tableHead = await panel.locator("#fillet-table thead").textContent();
  check(await panel.locator("#fillet-table tbody tr").count() === 4, "the table has the four fillet quantities");
  if (feRan) {
    check(legend.some((l) => l.startsWith("FE σ1")) && legend.some((l) => l.startsWith("FE σ3")),
      "the FE curves are overlaid, named FE in the legend");
    check(/SPH/.test(tableHead) && /FE/.test(tableHead) && /error/.test(tableHead), `the table has SPH, FE and error columns: ${tableHead}`);
    const errors = await panel.locator("#fillet-table tbody td:last-child").allTextContents();
    check(errors.every((e) => /^[+−]?\d+\.\d %$/.test(e)), `every quantity has its error in %: ${errors.join(", ")}`);
    await page.waitForFunction(() => ["fe-field-image", "sph-fillet-image"].every((i) => document.getElementById(i)?.complete));
    const widths = await page.evaluate(() => ["fe-field-image", "sph-fillet-image"].map((i) => document.getElementById(i).naturalWidth));
    check(widths.every((w) => w > 0), `the FE and SPH field images load side by side (${widths.join(", ")} px wide)`);
    check(widths[0] === widths[1], `both figures have one size (${widths.join(", ")} px wide)`);
    // The SPH figure: sigma_1 of tooth 0 (the static check's tooth0_box_m) on
    // the FE figure's colour scale (fe_comparison.image_range_Pa).
    const sphSrc = new URL(await panel.locator("#sph-fillet-image").getAttribute("src"), server.url);
    const staticSummary = await (await page.request.get(`${server.url}/jobs/${idF}/files/summary.json`)).json();
    const box = staticSummary.analysis.static_check.tooth0_box_m;
    const feRange = staticSummary.fe_comparison.image_range_Pa;
    check(sphSrc.pathname.endsWith("/images/max_principal.png"), `the SPH figure is the largest principal stress (${sphSrc.pathname})`);
    check(Array.isArray(box) && sphSrc.searchParams.get("zoom")?.split(",").length === 4,
      `the SPH figure is zoomed to tooth 0 (${sphSrc.searchParams.get("zoom")}; tooth0_box_m ${JSON.stringify(box)})`);
    check(Array.isArray(feRange) && JSON.stringify(sphSrc.searchParams.get("range")?.split(",").map(Number)) === JSON.stringify(feRange),
      `the SPH figure has the FE figure's colour range (${sphSrc.searchParams.get("range")}; image_range_Pa ${JSON.stringify(feRange)})`);
    check(/same window on one colour scale/.test(await panel.locator("#fillet-fields-note").textContent()),
      "the note under the figures says they share window and scale");
    check((await panel.locator("#fe-field-image").getAttribute("src")).endsWith("fe_max_principal_tooth0.png"),
      "the FE field is the largest principal stress of tooth 0");
    check((await panel.locator("#fe-field-image").getAttribute("alt")).startsWith("FE largest principal"), "the FE image has its alt text");
    for (const name of ["fillet_curves.png", "fe_fillet_curves.csv"]) {
      const href = await panel.locator(`header a[download="${name}"]`).getAttribute("href");
      check(href && (await page.request.get(server.url + href)).ok(), `the panel links ${name}`);
    }
  } else {
    check(/ISO 6336-3/.test(tableHead), `without FE the table compares with ISO 6336-3: ${tableHead}`);
  }
  await page.mouse.move(0, 0); // no cursor values in the legend
  await shot("12-result-fillet");
  await shot("12-fillet-panel", { element: panel });
  if (feRan) {
    await page.selectOption("#fe-field-select", "fe_von_mises_tooth0.png");
    await page.waitForFunction(() => {
      const img = document.getElementById("fe-field-image");
      const sph = document.getElementById("sph-fillet-image");
      return img.src.endsWith("fe_von_mises_tooth0.png") && img.complete && img.naturalWidth > 0 &&
        /\/images\/von_mises\.png\?zoom=.*&range=0,/.test(sph.src) && sph.complete && sph.naturalWidth > 0;
    });
    console.log("ok: both fields switch to von Mises");
  }

  // 10. Keyboard: the view tabs are links reached with Tab.
  await page.locator(".brand").focus();
  await page.keyboard.press("Tab");
  await page.keyboard.press("Tab");
  await page.keyboard.press("Enter");
  await page.waitForURL(/#\/jobs$/);
  console.log("ok: Tab and Enter reach the job list");

  // 11. A narrow window.
  await page.setViewportSize({ width: 420, height: 860 });
  await page.goto(`${server.url}/#/submit`);
  await waitForPreview();
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
  check(overflow <= 1, `no horizontal scrolling at 420 px (overflow ${overflow} px)`);
  await shot("10-narrow-submit", { viewport: true });
  await page.goto(`${server.url}/#/jobs/${idA}`);
  await imageLoaded();
  await shot("11-narrow-result");
  await page.goto(`${server.url}/#/jobs/${idF}`);
  await page.locator("#chart-fillet .uplot").waitFor();
  if (feRan) await page.waitForFunction(() => document.getElementById("fe-field-image")?.complete);
  const filletOverflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
  check(filletOverflow <= 1, `no horizontal scrolling of the fillet panel at 420 px (overflow ${filletOverflow} px)`);
  await shot("13-narrow-fillet", { element: page.locator("#fillet") });

  checkNoConsoleErrors(consoleErrors);
  exitCode = failures.length ? 1 : 0;
} catch (e) {
  console.error(`FAIL: ${e.stack || e}`);
  await shot("failure").catch(() => {});
  if (consoleErrors.length) console.error("console errors:\n  " + consoleErrors.join("\n  "));
} finally {
  await tearDown({ context, server, scratch });
}
finish(exitCode);
