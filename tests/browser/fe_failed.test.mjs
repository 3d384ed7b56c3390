// A job whose FE check failed, in the dashboard (headless Chromium against
// a real `gearsph serve` on loopback): the job stays successful (its SPH
// run is complete) and the list and the job view show the red "FE check
// failed" badge beside its status, with the tool's words in its title
// (docs/api.md, The FE stage). The server's gmsh is a stand-in script that
// fails, as in tests/test_fe_server.cpp; ccx is /bin/true. Any console
// error fails the test.
//
//   node tests/browser/fe_failed.test.mjs --gearsph build/gearsph --screenshots build/browser-screenshots
import { chmodSync, mkdirSync, mkdtempSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { SHOTS, check, failures, openBrowser, startServer, tearDown, finish, checkNoConsoleErrors } from "./harness.mjs";

const scratch = mkdtempSync(join(tmpdir(), "gearsph-browser-fe-"));
mkdirSync(SHOTS, { recursive: true });
const gmsh = join(scratch, "gmsh");
writeFileSync(gmsh, "#!/bin/sh\necho 'meshing failed: the stand-in gmsh of the browser test' >&2\nexit 1\n");
chmodSync(gmsh, 0o755);
const server = await startServer(join(scratch, "data"), ["--threads-per-job", "1"], { GEARSPH_GMSH: gmsh, GEARSPH_CCX: "/bin/true" });
console.log(`server: ${server.url}`);

const { context, page, consoleErrors } = await openBrowser(join(scratch, "profile"), { timeout: 120_000 });

// The badge's colours: the stylesheet's --bad (red text) on --bad-soft.
async function badgeColours(locator) {
  return locator.evaluate((el) => {
    const s = getComputedStyle(el);
    return { color: s.color, background: s.backgroundColor };
  });
}
const RED = "rgb(180, 35, 24)"; // --bad, #b42318 (web/css/app.css)

let exitCode = 1;
try {
  // A static gear check asking for the FE check, through the API; a short
  // relaxation will do (the check runs after it and fails at its first mesh).
  const job = {
    name: "fe-check-fails",
    scene: { type: "rack_pinion", quasi_static: true, fe_check: true,
      pinion: { omega_rad_s: 0 }, rack: { velocity_m_s: 0, load_N: 1000 } },
    time: { end_s: 2e-4 },
  };
  const submitted = await page.request.post(`${server.url}/jobs`, { data: job });
  check(submitted.status() === 201, `the job is accepted (${submitted.status()})`);
  const id = (await submitted.json()).jobID;
  const started = Date.now();
  let final;
  for (;;) {
    final = await (await page.request.get(`${server.url}/jobs/${id}`)).json();
    if (["successful", "failed", "dismissed"].includes(final.status)) break;
    if (Date.now() - started > 300_000) throw new Error(`job ${id} still ${final.status} after 300 s`);
    await page.waitForTimeout(500);
  }
  check(final.status === "successful", `the job itself is successful (${final.status}: ${final.message})`);
  check(final.fe_check?.status === "failed", `its fe_check says failed (${JSON.stringify(final.fe_check)})`);

  // The job list: the red badge beside the status.
  await page.goto(`${server.url}/#/jobs`);
  const row = page.locator(`tr[data-job="${id}"]`);
  const listBadge = row.locator('.fe-check[data-fe-check="failed"]');
  await listBadge.waitFor({ state: "visible" });
  check((await listBadge.textContent()) === "FE check failed", "the list shows \"FE check failed\"");
  check(await row.locator(".status.successful").count() === 1, "beside the job's own successful status");
  const listColours = await badgeColours(listBadge);
  check(listColours.color === RED, `the list's badge is red (${listColours.color} on ${listColours.background})`);
  check(/gmsh/.test(await listBadge.getAttribute("title")), "its title gives the tool's words");
  await page.screenshot({ path: join(SHOTS, "14-fe-check-failed-list.png"), fullPage: true });

  // The job view: the same badge by its status, the message saying so.
  await page.goto(`${server.url}/#/jobs/${id}`);
  await page.locator("#job-title").waitFor();
  const viewBadge = page.locator('#job-title ~ .fe-check[data-fe-check="failed"]').first();
  await viewBadge.waitFor({ state: "visible" });
  check((await viewBadge.textContent()) === "FE check failed", "the job view shows \"FE check failed\"");
  const viewColours = await badgeColours(viewBadge);
  check(viewColours.color === RED, `the job view's badge is red (${viewColours.color})`);
  check(/gmsh/.test(await viewBadge.getAttribute("title")), "its title gives the tool's words");
  await page.screenshot({ path: join(SHOTS, "15-fe-check-failed-job.png"), fullPage: true });

  checkNoConsoleErrors(consoleErrors);
  exitCode = failures.length ? 1 : 0;
} catch (e) {
  console.error(`FAIL: ${e.stack || e}`);
  console.error(server.log());
  await page.screenshot({ path: join(SHOTS, "fe-failed-failure.png"), fullPage: true }).catch(() => {});
} finally {
  await tearDown({ context, server, scratch });
}
finish(exitCode);
