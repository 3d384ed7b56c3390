// Requests with the access token: asked for once, kept, sent, and the
// login call that sets the cookie. fetch and the browser's storage are
// stood in for.
import { test, beforeEach } from "node:test";
import assert from "node:assert/strict";

const TOKEN = "s3cret";
let calls;
function server({ tokenRequired = true } = {}) {
  calls = [];
  globalThis.fetch = async (path, init = {}) => {
    const headers = init.headers || {};
    calls.push({ path, method: init.method || "GET", headers, body: init.body });
    const json = (status, body) => new Response(status === 204 ? null : JSON.stringify(body), {
      status, headers: { "Content-Type": "application/json" } });
    if (path === "/login" && (init.method || "GET") === "GET") {
      return json(200, { token_required: tokenRequired, signed_in: !tokenRequired });
    }
    if (path === "/login") {
      return JSON.parse(init.body).token === TOKEN ? json(204) : json(401, { title: "Unauthorized", detail: "no" });
    }
    const ok = !tokenRequired || headers.Authorization === `Bearer ${TOKEN}`;
    return ok ? json(200, { path }) : json(401, { detail: "token needed" });
  };
}
function storage() {
  const m = new Map();
  return { getItem: (k) => m.get(k) ?? null, setItem: (k, v) => m.set(k, String(v)), removeItem: (k) => m.delete(k) };
}

const api = await import("../../web/js/api.js");

beforeEach(() => {
  globalThis.localStorage = storage();
  api.onTokenNeeded(null);
});

test("without a token configured nothing is asked", async () => {
  server({ tokenRequired: false });
  let asked = 0;
  api.onTokenNeeded(async () => { asked++; return TOKEN; });
  await api.ensureSignedIn();
  assert.deepEqual(await api.get("/jobs"), { path: "/jobs" });
  assert.equal(asked, 0);
});

test("a 401 asks once for every waiting request, logs in, keeps the token and retries", async () => {
  server();
  let asked = 0;
  api.onTokenNeeded(async () => { asked++; return TOKEN; });
  const answers = await Promise.all([api.get("/jobs"), api.get("/health"), api.text("/schema")]);
  assert.equal(asked, 1);
  assert.deepEqual(answers[0], { path: "/jobs" });
  assert.equal(api.storedToken(), TOKEN);
  assert.equal(calls.filter((c) => c.path === "/login").length, 1);
  // Then sent with every request, without asking again.
  await api.get("/jobs?limit=1");
  assert.equal(calls.at(-1).headers.Authorization, `Bearer ${TOKEN}`);
  assert.equal(asked, 1);
});

test("a wrong token is asked for again, with the reason", async () => {
  server();
  const messages = [];
  const typed = ["guess", TOKEN];
  api.onTokenNeeded(async (message) => { messages.push(message); return typed.shift(); });
  await api.get("/jobs");
  assert.deepEqual(messages, ["", "That is not this server's token."]);
});

test("declining gives the request's 401", async () => {
  server();
  api.onTokenNeeded(async () => null);
  await assert.rejects(api.get("/jobs"), (e) => e instanceof api.ApiError && e.status === 401);
});

test("at start-up a kept token renews the cookie without asking", async () => {
  server();
  localStorage.setItem("gearsph-token", TOKEN);
  let asked = 0;
  api.onTokenNeeded(async () => { asked++; return TOKEN; });
  await api.ensureSignedIn();
  assert.equal(asked, 0);
  assert.equal(calls.filter((c) => c.path === "/login" && c.method === "POST").length, 1);
});

test("at start-up a kept token the server no longer takes is forgotten and asked for", async () => {
  server();
  localStorage.setItem("gearsph-token", "old");
  let asked = 0;
  api.onTokenNeeded(async () => { asked++; return TOKEN; });
  await api.ensureSignedIn();
  assert.equal(asked, 1);
  assert.equal(api.storedToken(), TOKEN);
});

test("problems keep their pointers", async () => {
  globalThis.fetch = async () => new Response(JSON.stringify({ title: "Invalid job", detail: "1 problem",
    errors: [{ pointer: "/time/end_s", detail: "must be greater than 0" }] }),
  { status: 400, headers: { "Content-Type": "application/problem+json" } });
  await assert.rejects(api.post("/jobs", {}), (e) => e.status === 400 && e.errors[0].pointer === "/time/end_s");
});
