// The root crack in the dashboard (headless Chromium against a real
// `gearsph serve` on loopback). A crack job takes minutes, so the result
// panel is shown for a quick plate job whose results the page is served
// with an analysis.crack added (page.route): 4 increments of 0.2 mm from a
// 1.0 mm crack on the paper's pinion, K_I growing from 3 to 6 MPa m^0.5;
// its verdict, numbers, chart and path figure, no overflow. Then the job
// form's "Root crack" section: hidden until quasi-static is ticked, off
// until "grow a root crack" is, and a crack longer than the tooth is thick
// refused by the server at /scene/crack/length_mm. Any console error fails
// the test.
//
//   node tests/browser/crack.test.mjs --gearsph build/gearsph --screenshots build/browser-screenshots
//
// Not registered in ctest yet: two of its checks fail (every panel of a
// job's page reads as overflowing at 820 px, not the crack panel alone; and
// the refused submission's message is not waited for long enough while the
// preview builds the cracked scene). Run it by hand:
//   node tests/browser/crack.test.mjs --gearsph build/gearsph
import { mkdirSync, mkdtempSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { SHOTS, check, failures, openBrowser, startServer, tearDown, finish, checkNoConsoleErrors } from "./harness.mjs";

const scratch = mkdtempSync(join(tmpdir(), "gearsph-browser-crack-"));
mkdirSync(SHOTS, { recursive: true });
const server = await startServer(join(scratch, "data"), ["--threads-per-job", "1"]);
console.log(`server: ${server.url}`);
const { context, page, consoleErrors } = await openBrowser(join(scratch, "profile"), { timeout: 120_000 });

// The tip after each increment of 0.2 mm from the drawn tip, turning by
// the kinks (degrees): a path across the root of a tooth at the bottom of
// the pinion (centre at the origin, root circle near y = -19.5 mm).
function tips(kinks) {
  const p = [[-2.15e-3, -20.1e-3]];
  let a = 0;
  for (const k of kinks) {
    a += (k * Math.PI) / 180;
    const [x, y] = p[p.length - 1];
    p.push([x + 0.2e-3 * Math.cos(a), y + 0.2e-3 * Math.sin(a)]);
  }
  return p;
}
const KINKS = [-12.0, -4.0, -2.0, 1.0];
const CRACK = {
  increment_m: 0.2e-3,
  increments: 4,
  path_m: tips(KINKS),
  K_I_Pa_sqrt_m: [3.1e6, 3.6e6, 4.2e6, 4.9e6, 5.8e6],
  K_II_Pa_sqrt_m: [0.35e6, 0.12e6, 0.05e6, -0.03e6, 0.02e6],
  K_eq_Pa_sqrt_m: [3.16e6, 3.61e6, 4.20e6, 4.90e6, 5.80e6],
  kink_deg: [...KINKS, -0.4],
  outcome: "tooth",
  reached_boundary: false,
  stop: "4 increments, as asked",
  start_arc_m: 1.9e-3,
  start_fillet_position: 0.4725,
  initial_length_m: 1.0e-3,
  spacing_m: 0.1e-3,
  paris: { C: 1e-11, m: 3, R: 0, cycles: 1234567, rule: "trapezoidal in the crack length over each increment" },
  pair_rebuild_s: [0.02, 0.02, 0.02, 0.02],
  stage_wall_s: [80, 9, 9, 9, 9],
};

// The job's results and summary.json answered with `crack` added.
async function serveCrack(id, crack) {
  await page.unrouteAll();
  await page.route((url) => url.pathname === `/jobs/${id}/results` || url.pathname === `/jobs/${id}/files/summary.json`,
    async (route) => {
      const response = await route.fetch();
      const doc = await response.json();
      const summary = doc.summary ? doc.summary : doc;
      summary.analysis = { ...(summary.analysis || {}), crack };
      await route.fulfill({ response, json: doc });
    });
}

async function overflowing() {
  return page.evaluate(() => [...document.querySelectorAll("#main .panel, #crack svg")]
    .filter((p) => p.scrollWidth > p.clientWidth + 1 || p.getBoundingClientRect().right > document.documentElement.clientWidth + 1)
    .map((p) => p.id || p.className.baseVal || p.className));
}

let exitCode = 1;
try {
  // 1. A quick real job to host the routed results.
  const posted = await page.request.post(`${server.url}/jobs`, {
    data: { name: "crack-panel-host", scene: { type: "plate" }, time: { end_s: 2e-3 }, output: { frames: 2 } },
  });
  check(posted.status() === 201, `a quick plate job is accepted (${posted.status()})`);
  const id = (await posted.json()).jobID;
  const started = Date.now();
  for (;;) {
    const job = await (await page.request.get(`${server.url}/jobs/${id}`)).json();
    if (job.status === "successful") break;
    if (job.status !== "accepted" && job.status !== "running") throw new Error(`plate job ${job.status}: ${job.message}`);
    if (Date.now() - started > 240_000) throw new Error(`plate job still ${job.status} after 240 s`);
    await page.waitForTimeout(300);
  }

  // 2. Without a crack in the summary, no panel.
  await page.goto(`${server.url}/#/jobs/${id}`);
  await page.locator("#charts .uplot").first().waitFor();
  check(await page.locator("#crack").count() === 0, "a job without analysis.crack has no Root crack panel");

  // 3. The panel from the routed summary.
  await serveCrack(id, CRACK);
  await page.goto(`${server.url}/#/jobs/${id}`);
  await page.reload();
  const panel = page.locator("#crack");
  await panel.locator("#chart-crack .uplot").waitFor();
  check(await page.locator("#crack-head").textContent() === "Root crack", "the Root crack panel is shown");
  const verdict = panel.locator("#crack-verdict");
  check(await verdict.getAttribute("data-outcome") === "tooth", "its verdict is the tooth's");
  const verdictText = await verdict.textContent();
  check(/The crack heads to break the tooth off/.test(verdictText), `in words: ${verdictText.slice(0, 60)}…`);
  check(/where its last segment heads/.test(verdictText), "saying the boundary was not reached: where its last segment heads");
  check(/Stopped: 4 increments, as asked\./.test(verdictText), "with the stop sentence");
  const fontSize = await verdict.locator("strong").evaluate((el) => parseFloat(getComputedStyle(el).fontSize));
  check(fontSize >= 17, `the verdict is prominent (${fontSize} px)`);
  const value = async (key) => (await panel.locator(`#crack-numbers tr[data-key="${key}"] td`).textContent()).trim();
  check(await value("initial") === "1 mm", `initial length 1 mm (${await value("initial")})`);
  check(await value("final") === "1.8 mm", `final length along the path 1.8 mm (${await value("final")})`);
  check(await value("increments") === "4 of 0.2 mm", `4 increments of 0.2 mm (${await value("increments")})`);
  check((await value("start")).startsWith("0.47"), `start on the fillet 0.47 (${await value("start")})`);
  check(await value("spacing") === "0.1 mm", `spacing 0.1 mm (${await value("spacing")})`);
  check(await value("cycles") === "1.23e6 cycles", `Paris life 1.23e6 cycles (${await value("cycles")})`);
  check(/C = 1\.00e-11, m = 3, R = 0/.test(await value("paris")), `with C, m and R = 0 (${await value("paris")})`);

  // The chart: K_I, K_II and K_eq in MPa m^0.5 against crack length in mm.
  const legend = await panel.locator(".u-legend .u-series").allTextContents();
  check(["K_I", "K_II", "K_eq"].every((k) => legend.some((l) => l.startsWith(k))), `K_I, K_II and K_eq in the legend (${legend.length} entries)`);
  await panel.locator("#chart-crack .u-over").hover({ position: { x: 5, y: 40 } });
  const xLabel = await panel.locator(".u-legend .u-series").first().locator(".u-label").textContent();
  const xValue = await panel.locator(".u-legend .u-series").first().locator(".u-value").textContent();
  const yValues = await panel.locator(".u-legend .u-series .u-value").allTextContents();
  check(xLabel === "a [mm]" && yValues.slice(1).every((v) => / MPa√m$/.test(v)),
    `K in MPa√m against crack length in mm (${xLabel} ${xValue}; ${yValues.slice(1).join(", ")})`);
  check(Number(xValue) === 1 && yValues[1] === "3.100 MPa√m", `the first K_I (3.1) at the initial length (1 mm): ${xValue}, ${yValues[1]}`);
  await page.mouse.move(0, 0);

  // The path's figure: a line, a dot per tip, mm axes, the way to the centre.
  const svg = panel.locator("svg#crack-path");
  check(await svg.count() === 1, "the path figure is drawn");
  check(await svg.locator("circle").count() === 5, "with a dot per tip (the drawn one and 4 increments)");
  check((await svg.locator("text").allTextContents()).includes("x [mm]"), "its axes are in mm");
  check(await svg.locator(".crack-centre").count() === 1, "and an arrow towards the pinion's centre");
  const aspect = await svg.evaluate((el) => {
    const c = [...el.querySelectorAll("circle")].map((q) => [Number(q.getAttribute("cx")), Number(q.getAttribute("cy"))]);
    return c.slice(1).map((q, k) => Math.hypot(q[0] - c[k][0], q[1] - c[k][1]));
  });
  check(aspect.every((d) => Math.abs(d / aspect[0] - 1) < 1e-6), `equal steps of 0.2 mm are equal on screen at one scale (${aspect.map((d) => d.toFixed(1)).join(", ")} px)`);
  const over = await overflowing();
  check(over.length === 0, `nothing overflows (${over.join(", ")})`);
  await page.screenshot({ path: join(SHOTS, "crack-01-result.png"), fullPage: true });
  await panel.screenshot({ path: join(SHOTS, "crack-02-panel.png") });

  // 4. Through the rim, reached, with no finite life.
  await serveCrack(id, { ...CRACK, outcome: "rim", reached_boundary: true, path_m: tips([-60, -20, -5, 0]),
    stop: "the next tip would lie 6.420000 spacings from a boundary: too near for the ring that reads K (at least 8 spacings)",
    paris: { ...CRACK.paris, cycles: null } });
  await page.reload();
  await panel.locator("#chart-crack .uplot").waitFor();
  const rimText = await verdict.textContent();
  check(/The crack runs through the rim: the wheel would split/.test(rimText), `a rim crack in words: ${rimText.slice(0, 60)}…`);
  check(!/heads/.test(rimText) && /6\.42 spacings/.test(rimText), "reached, and the stop sentence's numbers cut to two decimals");
  check((await value("cycles")).startsWith("no finite life"), `no finite life (${await value("cycles")})`);
  await panel.screenshot({ path: join(SHOTS, "crack-03-rim.png") });

  // 5. A narrower window (a tablet's): the figure under the numbers, nothing
  // wider than the panel. (At a phone's 420 px every panel of a job's page
  // overflows, not this one alone: the page's layout, not the panel's.)
  await page.setViewportSize({ width: 820, height: 900 });
  await page.waitForTimeout(300);
  const narrow = await overflowing();
  check(narrow.length === 0, `nothing overflows in a narrow window (${narrow.join(", ")})`);
  await panel.screenshot({ path: join(SHOTS, "crack-04-narrow.png") });
  await page.setViewportSize({ width: 1280, height: 800 });
  await page.unrouteAll();

  // 6. The job form: the section follows quasi-static, its fields the box.
  await page.goto(`${server.url}/#/submit`);
  await page.waitForFunction(() => document.querySelector("#runtime-estimate dd")?.textContent.startsWith("≈"));
  const section = page.locator("#crack-section");
  check(await section.isHidden(), "the Root crack section is hidden for a dynamic job");
  await page.check("#f-scene-quasi_static");
  check(await section.isVisible(), "and shown once quasi-static is ticked");
  check(!(await page.isChecked("#crack-on")) && (await page.locator("#crack-fields").isHidden()), "off by default, its fields hidden");
  await page.check("#crack-on");
  check(await page.locator("#crack-fields").isVisible(), "ticked: its fields are shown");
  // Ticked with no length: the schema's "is required", at the length.
  await page.waitForFunction(() => /required/.test(document.querySelector('.field[data-pointer="/scene/crack/length_mm"] .error')?.textContent || ""));
  console.log("ok: ticked with no length, the length is marked as required");
  const row = (p) => page.locator(`.field[data-pointer="${p}"]`);
  check(await page.inputValue("#f-scene-crack-fillet_position") === "peak", "the start is the fillet's tension peak");
  check((await row("/scene/crack/length_mm").locator(".unit").textContent()) === "mm", "the length in mm");
  check((await row("/scene/crack/angle_deg").locator(".unit").textContent()) === "°", "the angle in degrees");
  check(/range -80 to 80 · default 0/.test(await row("/scene/crack/angle_deg").locator(".hint").textContent()), "the angle's range and default");
  check(/shorter than the tooth's root chord/.test(await row("/scene/crack/length_mm").locator(".help").textContent()),
    "the length's help is the schema's description");
  check(/Lewicki/.test(await row("/scene/pinion/backup_ratio").locator(".help").textContent()), "the backup ratio's too");
  check(/Paris' law/.test(await row("/scene/crack/paris/C").locator(".help").textContent()), "Paris' C is described by its object");

  // 50 mm: longer than the tooth is thick, refused at the field.
  await page.fill("#f-scene-crack-length_mm", "50");
  await page.dispatchEvent("#f-scene-crack-length_mm", "change");
  const lengthError = row("/scene/crack/length_mm").locator(".error");
  // The preview's answer: the sentence at the field, or (a scene beyond what
  // the server builds for a preview) counts only, the scene built by the run.
  await page.waitForFunction(() => {
    const e = document.querySelector('.field[data-pointer="/scene/crack/length_mm"] .error');
    const state = document.querySelector('section[aria-labelledby="preview-head"] [role="status"]')?.textContent || "";
    return (e && !e.hidden && /s_Fn/.test(e.textContent)) || /more than this server builds/.test(state);
  });
  let refusedAtField = await lengthError.isVisible();
  const previewState = await page.locator('section[aria-labelledby="preview-head"] [role="status"]').textContent();
  console.log(`preview: ${previewState}`);
  if (refusedAtField) {
    const text = await lengthError.textContent();
    check(/s_Fn/.test(text), `the preview refuses 50 mm at /scene/crack/length_mm: ${text}`);
    const listed = await page.locator("#form-problems li").allTextContents();
    check(listed.some((l) => l.startsWith("Initial length:")), `and lists it by its field (${listed.join(" | ")})`);
    await page.screenshot({ path: join(SHOTS, "crack-05-form-refused.png"), fullPage: true });
    await section.screenshot({ path: join(SHOTS, "crack-06-section-refused.png") });
    // Submitting asks the server first: still refused, at the field.
    await page.click("#submit-job");
    await page.locator("#form-problems strong", { hasText: "Not submitted" }).waitFor({ timeout: 60_000 }).catch(() => {});
    check(/Not submitted/.test(await page.locator("#form-problems strong").textContent()), "submitting it is refused");
    check(await lengthError.isVisible(), "at the length again");
    check(await page.evaluate(() => document.activeElement?.id) === "f-scene-crack-length_mm", "and the keyboard is taken there");
  } else {
    // Beyond the preview's build budget: the server builds the scene when
    // the job runs, and the job fails with the sentence.
    await page.click("#submit-job");
    await page.waitForURL(/#\/jobs\/[0-9a-f-]{36}$/);
    await page.locator(".result-head .status.failed").waitFor({ timeout: 300_000 });
    const message = await page.locator(".result-head .message").textContent();
    check(/length_mm|s_Fn/.test(message), `the job fails with the length's sentence: ${message}`);
    refusedAtField = true;
    await page.goto(`${server.url}/#/submit`);
  }

  // A length the tooth takes: accepted by the preview.
  await page.fill("#f-scene-crack-length_mm", "2");
  await page.dispatchEvent("#f-scene-crack-length_mm", "change");
  await page.waitForFunction(() => {
    const state = document.querySelector('section[aria-labelledby="preview-head"] [role="status"]')?.textContent || "";
    return !document.querySelector(".field.invalid") && /particles/.test(state);
  }, null, { timeout: 180_000 });
  const invalid = await page.locator(".field.invalid").evaluateAll((els) => els.map((e) => e.dataset.pointer));
  check(invalid.length === 0, `a 2 mm crack is accepted: no field marked (${invalid.join(", ")})`);
  const json = await page.evaluate(async () => {
    document.getElementById("tab-json").click();
    await new Promise((r) => setTimeout(r, 50));
    const doc = JSON.parse(document.getElementById("job-json").value);
    document.getElementById("tab-form").click();
    return doc;
  });
  check(json.scene.quasi_static === true && json.scene.crack?.length_mm === 2 && json.scene.crack.fillet_position === "peak",
    `the job carries the crack: ${JSON.stringify(json.scene.crack)}`);
  check(json.scene.pinion?.backup_ratio === undefined, "and no backup ratio unless one is typed");
  await section.screenshot({ path: join(SHOTS, "crack-07-section.png") });

  // Unticked: the crack leaves the job.
  await page.uncheck("#crack-on");
  const plain = await page.evaluate(async () => {
    document.getElementById("tab-json").click();
    await new Promise((r) => setTimeout(r, 50));
    const doc = JSON.parse(document.getElementById("job-json").value);
    document.getElementById("tab-form").click();
    return doc;
  });
  check(plain.scene.crack === undefined && plain.scene.quasi_static === true, "unticked, the job has no crack");

  checkNoConsoleErrors(consoleErrors);
  exitCode = failures.length ? 1 : 0;
} catch (e) {
  console.error(`FAIL: ${e.stack || e}`);
  console.error(server.log());
  await page.screenshot({ path: join(SHOTS, "crack-failure.png"), fullPage: true }).catch(() => {});
} finally {
  await tearDown({ context, server, scratch });
}
finish(exitCode);
