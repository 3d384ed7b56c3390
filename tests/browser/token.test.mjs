// The dashboard of a server started with --token-file, in headless Chromium:
// the page and its scripts load without the token, it asks for the token
// once (a wrong one is refused in the dialog), then everything works with
// it: the job list, the live event stream, a job's rendered image and its
// downloads (which a browser fetches by itself, with the login cookie). A
// reload does not ask again. Any console error fails the test.
//
//   node tests/browser/token.test.mjs --gearsph build/gearsph --screenshots build/browser-screenshots
import { mkdirSync, mkdtempSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { SHOTS, check, failures, openBrowser, startServer, tearDown, finish, checkNoConsoleErrors } from "./harness.mjs";

const TOKEN = "token for the dashboard test";

const scratch = mkdtempSync(join(tmpdir(), "gearsph-browser-token-"));
mkdirSync(SHOTS, { recursive: true });
const tokenFile = join(scratch, "token");
writeFileSync(tokenFile, `${TOKEN}\n`);
const server = await startServer(join(scratch, "data"), ["--threads-per-job", "1", "--token-file", tokenFile]);
console.log(`server: ${server.url}`);
const api = (path, init = {}) => fetch(server.url + path,
  { ...init, headers: { Authorization: `Bearer ${TOKEN}`, ...(init.headers || {}) } });

const { context, page, consoleErrors } = await openBrowser(join(scratch, "profile"), { timeout: 120_000 });
const refused = [];
page.on("response", (r) => {
  if (r.status() === 401) refused.push(r.url());
});

let exitCode = 1;
try {
  // A finished job to look at, submitted with the token.
  const submitted = await api("/jobs", {
    method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ name: "plate-behind-token", scene: { type: "plate", length_m: 0.1, thickness_m: 0.01 },
      discretization: { spacing_m: 0.002 }, time: { end_s: 0.005 }, output: { frames: 3 } }),
  });
  check(submitted.status === 201, `a job submitted with the token (${submitted.status})`);
  const id = (await submitted.json()).jobID;

  // 1. The page loads without the token and asks for it.
  await page.goto(server.url + "/");
  const dialog = page.locator("#token-dialog");
  await dialog.waitFor({ state: "visible" });
  check(await page.locator(".brand").isVisible(), "the page and its styles load without the token");
  await page.screenshot({ path: join(SHOTS, "token-01-asked.png") });

  // 2. A wrong token is refused in the dialog; the right one is taken.
  await page.fill("#token-input", "guess");
  await page.click("#token-submit");
  await page.locator("#token-error").waitFor({ state: "visible" });
  check((await page.locator("#token-error").textContent()).includes("not this server's token"),
    "a wrong token is refused in the dialog");
  await page.fill("#token-input", TOKEN);
  await page.click("#token-submit");
  await dialog.waitFor({ state: "detached" });
  await page.waitForFunction(() => /gearsph .* worker/.test(document.getElementById("server-state").textContent));
  check(true, "the server's identity shows once the token is given");
  await page.waitForFunction(() => document.querySelector("#runtime-estimate dd")?.textContent.startsWith("≈"));
  check(true, "the New job page gets its schema and preview");

  // 3. The live list: the event stream carries the job to successful.
  await page.click('a[data-view="jobs"]');
  await page.locator(`tr[data-job="${id}"] .status.successful`).waitFor();
  const later = await api("/jobs", {
    method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ name: "plate-live", scene: { type: "plate", length_m: 0.1, thickness_m: 0.01 },
      discretization: { spacing_m: 0.002 }, time: { end_s: 0.005 } }),
  });
  const idLive = (await later.json()).jobID;
  await page.locator(`tr[data-job="${idLive}"] .status.successful`).waitFor();
  check(true, "a job submitted elsewhere appears and finishes in the list: the event stream is signed in");

  // 4. The result: the image and the downloads come with the cookie.
  await page.click(`tr[data-job="${id}"] a.job-link`);
  await page.waitForFunction(() => {
    const img = document.getElementById("field-image");
    return img && img.complete && img.naturalWidth > 0;
  });
  check(true, "the rendered image loads");
  const href = await page.locator('#downloads a[download="history.csv"]').getAttribute("href");
  const download = await page.evaluate(async (u) => (await fetch(u, { credentials: "same-origin" })).status, href);
  check(download === 200, `a download link works without a header (${download})`);
  await page.screenshot({ path: join(SHOTS, "token-02-result.png") });

  // 5. A reload does not ask again.
  refused.length = 0;
  await page.reload();
  await page.waitForFunction(() => /gearsph .* worker/.test(document.getElementById("server-state").textContent));
  check(await page.locator("#token-dialog").count() === 0, "a reload does not ask for the token again");
  check(refused.length === 0, `nothing is refused after the reload${refused.length ? ": " + refused.join(", ") : ""}`);

  // The one refusal the test asked for: the wrong token's 401 from /login.
  const unexpected = consoleErrors.filter((e) => !(e.includes("401") && e.includes("/login")));
  consoleErrors.length = 0;
  consoleErrors.push(...unexpected);
  checkNoConsoleErrors(consoleErrors);
  exitCode = failures.length ? 1 : 0;
} catch (e) {
  console.error(`FAIL: ${e.stack || e}`);
  await page.screenshot({ path: join(SHOTS, "token-failure.png") }).catch(() => {});
  if (consoleErrors.length) console.error("console errors:\n  " + consoleErrors.join("\n  "));
} finally {
  await tearDown({ context, server, scratch });
}
finish(exitCode);
