// Copies the dashboard's chart library from node_modules (installed by
// `npm ci` from package-lock.json) to web/vendor/, where `gearsph serve`
// serves it: the dashboard needs no internet. Runs as npm's postinstall.
import { copyFileSync, mkdirSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const out = join(root, "web", "vendor");
mkdirSync(out, { recursive: true });
for (const [from, to] of [
  ["node_modules/uplot/dist/uPlot.esm.js", "uPlot.esm.js"],
  ["node_modules/uplot/dist/uPlot.min.css", "uPlot.min.css"],
  ["node_modules/uplot/LICENSE", "uPlot.LICENSE"],
]) {
  copyFileSync(join(root, from), join(out, to));
}
console.log("vendor_web: uPlot copied to web/vendor/");
