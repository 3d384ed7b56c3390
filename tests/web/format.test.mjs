import { test } from "node:test";
import assert from "node:assert/strict";
import { bytes, duration, eng, eta, int, serverDegraded, serverIdentity, sig } from "../../web/js/format.js";

test("eng picks the prefix that keeps three figures readable", () => {
  assert.equal(eng(2.75e8, "Pa"), "275 MPa");
  assert.equal(eng(0.004, "m"), "4 mm");
  assert.equal(eng(4e-8, "s"), "40 ns");
  assert.equal(eng(-15, "rad/s"), "-15 rad/s");
  assert.equal(eng(0, "N"), "0 N");
  assert.equal(eng(999.96, "Pa"), "1 kPa");
  assert.equal(eng(null, "m"), "—");
  assert.equal(eng(NaN), "—");
});

test("sig and int", () => {
  assert.equal(sig(1234567), "1.23e+6");
  assert.equal(sig(0.0001234), "1.23e-4");
  assert.equal(sig(3.14159, 3), "3.14");
  assert.equal(int(1234567.4), "1,234,567");
  assert.equal(int(undefined), "—");
});

test("durations from milliseconds to days", () => {
  assert.equal(duration(0.25), "250 ms");
  assert.equal(duration(2.34), "2.3 s");
  assert.equal(duration(42), "42 s");
  assert.equal(duration(125), "2 min 05 s");
  assert.equal(duration(7260), "2 h 01 min");
  assert.equal(duration(3 * 86400), "3.0 days");
  assert.equal(duration(Infinity), "—");
});

test("bytes in decimal units", () => {
  assert.equal(bytes(512), "512 B");
  assert.equal(bytes(6.3e6), "6.3 MB");
  assert.equal(bytes(59e9), "59 GB");
});

test("eta of a job by its status", () => {
  assert.equal(eta({ status: "accepted" }), "queued");
  assert.equal(eta({ status: "successful" }), "—");
  assert.equal(eta({ status: "running", step: 0, eta_s: 5 }), "estimating…");
  assert.equal(eta({ status: "running", step: 10, eta_s: null }), "estimating…");
  assert.equal(eta({ status: "running", step: 10, eta_s: 90 }), "1 min 30 s");
  // A set-up past a second says what it does; the run's first steps replace it.
  const setup = { stage: "relaxing particles", fraction: 0.4, elapsed_s: 1.3 };
  assert.equal(eta({ status: "running", step: 0, setup }), "setting up: relaxing particles 40 %");
  assert.equal(eta({ status: "running", step: 10, eta_s: 90, setup: null }), "1 min 30 s");
});

test("the server's identity: a shared core budget or a fixed split", () => {
  assert.equal(serverIdentity({ version: "0.1.0", workers: 2, threads_per_job: 2, core_budget: 2 }),
    "gearsph 0.1.0 · 2 cores shared by the jobs");
  assert.equal(serverIdentity({ version: "0.1.0", workers: 2, threads_per_job: 1, core_budget: 0 }),
    "gearsph 0.1.0 · 2 workers × 1 thread");
  assert.equal(serverIdentity({ version: "0.1.0", workers: 1, threads_per_job: 4 }),
    "gearsph 0.1.0 · 1 worker × 4 threads");
});

test("a dependency that is down is named in the identity", () => {
  const hl = {
    version: "0.1.0", workers: 2, threads_per_job: 1, core_budget: 2, status: "degraded",
    dependencies: { store: { status: "down", detail: "connection refused" }, results: { status: "up" } },
  };
  assert.equal(serverIdentity(hl), "gearsph 0.1.0 · 2 cores shared by the jobs · job store unreachable");
  assert.equal(serverDegraded(hl), true);
  assert.equal(serverDegraded({ dependencies: { store: { status: "up" } } }), false);
  assert.equal(serverDegraded({}), false);
});
