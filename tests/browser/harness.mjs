// What the browser tests share: their options, their pass/fail record, a
// `gearsph serve` on a free loopback port, and headless Chromium on one page
// that records console errors.
import { spawn } from "node:child_process";
import { rmSync } from "node:fs";
import { resolve } from "node:path";
import { chromium } from "playwright-core";

export function option(name, fallback) {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : fallback;
}
export const GEARSPH = resolve(option("gearsph", "build/gearsph"));
export const SHOTS = resolve(option("screenshots", "build/browser-screenshots"));
export const CHROMIUM = option("chromium", "/usr/bin/chromium");

export const failures = [];
export function check(condition, message) {
  if (!condition) {
    failures.push(message);
    console.error(`FAIL: ${message}`);
  } else {
    console.log(`ok: ${message}`);
  }
}

// Resolves once the server prints its address: { child, url, log() }.
export function startServer(dataDir, extraArgs = [], env = {}) {
  return new Promise((resolvePromise, reject) => {
    const child = spawn(GEARSPH, ["serve", "--port", "0", "--data", dataDir, ...extraArgs],
      { stdio: ["ignore", "pipe", "pipe"], env: { ...process.env, ...env } });
    let out = "", err = "";
    const timer = setTimeout(() => reject(new Error(`the server did not start:\n${out}${err}`)), 60_000);
    child.stdout.on("data", (d) => {
      out += d;
      const m = out.match(/listening on (http:\/\/[\d.]+:\d+)/);
      if (m) {
        clearTimeout(timer);
        resolvePromise({ child, url: m[1], log: () => out + err });
      }
    });
    child.stderr.on("data", (d) => (err += d));
    child.on("exit", (code) => {
      clearTimeout(timer);
      reject(new Error(`gearsph serve exited with ${code}:\n${out}${err}`));
    });
  });
}

// Chromium with its profile in `profileDir`, one page of 1280 x 800 whose
// console errors and page errors land in `consoleErrors`, but for those
// `expected(msg)` accepts.
export async function openBrowser(profileDir, { timeout = 120_000, expected = () => false } = {}) {
  const context = await chromium.launchPersistentContext(profileDir, {
    executablePath: CHROMIUM,
    headless: true,
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync"],
    viewport: { width: 1280, height: 800 },
  });
  const page = context.pages()[0] || (await context.newPage());
  page.setDefaultTimeout(timeout);
  const consoleErrors = [];
  page.on("console", (msg) => {
    if (msg.type() !== "error" || expected(msg)) return;
    consoleErrors.push(`${msg.text()} (${msg.location().url || "?"})`);
  });
  page.on("pageerror", (e) => consoleErrors.push(`page error: ${e.message}`));
  return { context, page, consoleErrors };
}

// The end every test shares: no console errors, then the browser closed,
// the server stopped and the scratch directory removed however the test
// went; finish() exits 1 if a check failed or the test threw.
export function checkNoConsoleErrors(consoleErrors) {
  check(consoleErrors.length === 0, `no console errors${consoleErrors.length ? ":\n  " + consoleErrors.join("\n  ") : ""}`);
}
export async function tearDown({ context, server, scratch }) {
  await context.close();
  server.child.kill("SIGTERM");
  await new Promise((r) => server.child.once("exit", r));
  rmSync(scratch, { recursive: true, force: true });
}
export function finish(exitCode) {
  if (failures.length) console.error(`${failures.length} check(s) failed`);
  process.exit(exitCode);
}
