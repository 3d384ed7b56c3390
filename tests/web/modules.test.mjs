// The dashboard's modules: no import cycle, and every module but the one
// that starts the page (app.js) imports without a browser.
import { test } from "node:test";
import assert from "node:assert/strict";
import { existsSync, readdirSync, readFileSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const JS = resolve(dirname(fileURLToPath(import.meta.url)), "../../web/js");
const modules = readdirSync(JS).filter((f) => f.endsWith(".js")).sort();

function imports(file) {
  const text = readFileSync(join(JS, file), "utf8");
  return [...text.matchAll(/^\s*import\s[^"']*["']\.\/([^"']+)["']/gm)].map((m) => m[1]);
}

test("the modules import each other without a cycle", () => {
  const graph = new Map(modules.map((m) => [m, imports(m)]));
  const state = new Map(); // 1: on the path, 2: done
  const visit = (m, path) => {
    if (state.get(m) === 2) return;
    assert.notEqual(state.get(m), 1, `import cycle: ${[...path, m].join(" -> ")}`);
    state.set(m, 1);
    for (const next of graph.get(m) || []) {
      assert.ok(graph.has(next), `${m} imports ${next}, which does not exist`);
      visit(next, [...path, m]);
    }
    state.set(m, 2);
  };
  for (const m of modules) visit(m, []);
});

test("no module imports app.js, which starts the page", () => {
  for (const m of modules) assert.ok(!imports(m).includes("app.js"), `${m} imports app.js`);
});

test("every module but app.js imports without a DOM", async (t) => {
  const vendored = existsSync(join(JS, "../vendor/uPlot.esm.js"));
  for (const m of modules.filter((f) => f !== "app.js")) {
    const usesVendor = readFileSync(join(JS, m), "utf8").includes("../vendor/");
    const needsVendor = usesVendor || imports(m).some((i) => ["charts.js", "compare.js", "result.js"].includes(i));
    if (needsVendor && !vendored) {
      t.diagnostic(`${m}: skipped, web/vendor/ is filled by npm ci`);
      continue;
    }
    await assert.doesNotReject(import(pathToFileURL(join(JS, m)).href), m);
  }
});
