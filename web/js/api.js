// Talking to gearsph serve: JSON requests, RFC 9457 problem documents, and
// the access token of a server started with --token-file. The page asks for
// the token once (the prompt is plugged in by the page, so this module needs
// no DOM), keeps it in the browser's storage, sends it on every fetch and
// logs in with it, which sets the cookie a browser sends by itself with
// images, downloads and event streams.

export class ApiError extends Error {
  constructor(status, problem) {
    super(problem?.detail || problem?.title || `HTTP ${status}`);
    this.status = status;
    this.problem = problem || {};
  }
  // [{pointer, detail}] of an invalid-job problem (may be empty).
  get errors() {
    return Array.isArray(this.problem.errors) ? this.problem.errors : [];
  }
}

const TOKEN_KEY = "gearsph-token";

// The browser's storage, or a stand-in where there is none (Node's tests).
function storage() {
  try {
    return globalThis.localStorage ?? null;
  } catch {
    return null; // storage disabled
  }
}
export function storedToken() {
  return storage()?.getItem(TOKEN_KEY) || "";
}
function storeToken(token) {
  if (token) storage()?.setItem(TOKEN_KEY, token);
  else storage()?.removeItem(TOKEN_KEY);
}

// async (message) => token, or null if the person declines.
let askForToken = null;
export function onTokenNeeded(prompt) {
  askForToken = prompt;
}

// The headers of a request, with the token when there is one.
export function withToken(headers = {}) {
  const token = storedToken();
  return token ? { ...headers, Authorization: `Bearer ${token}` } : headers;
}

// POST /login: checks the token and sets the cookie; keeps the token.
export async function login(token) {
  const res = await fetch("/login", {
    method: "POST",
    headers: { "Content-Type": "application/json", Accept: "application/json" },
    body: JSON.stringify({ token }),
  });
  if (!res.ok) {
    const data = await parse(res);
    throw new ApiError(res.status, typeof data === "object" ? data : { detail: data });
  }
  storeToken(token);
}

// One prompt for every request that needs it at the same moment.
let signingIn = null;
function signIn() {
  signingIn ??= (async () => {
    let message = "";
    for (;;) {
      const token = askForToken ? await askForToken(message) : null;
      if (token === null || token === undefined) {
        throw new ApiError(401, { detail: "this server needs an access token" });
      }
      try {
        await login(token);
        return;
      } catch (e) {
        message = e.status === 401 ? "That is not this server's token." : e.message;
      }
    }
  })().finally(() => (signingIn = null));
  return signingIn;
}

// At start-up: whether this server wants a token and the browser carries
// it; a kept token renews the cookie without asking; else the prompt.
export async function ensureSignedIn() {
  const res = await fetch("/login", { headers: { Accept: "application/json" } });
  if (!res.ok) return; // an older server: no login call
  const state = await res.json();
  if (!state.token_required || state.signed_in) return;
  const kept = storedToken();
  if (kept) {
    try {
      await login(kept);
      return;
    } catch {
      storeToken(""); // the server's token changed
    }
  }
  await signIn();
}

// fetch() with the token; a 401 asks for it (once) and tries again.
export async function apiFetch(path, init = {}) {
  const attempt = () => fetch(path, { ...init, headers: withToken(init.headers) });
  const res = await attempt();
  if (res.status !== 401 || !askForToken) return res;
  storeToken("");
  await signIn();
  return attempt();
}

async function parse(res) {
  const type = res.headers.get("Content-Type") || "";
  if (type.includes("json")) return res.json();
  return res.text();
}

export async function request(method, path, body) {
  const init = { method, headers: { Accept: "application/json" } };
  if (body !== undefined) {
    init.headers["Content-Type"] = "application/json";
    init.body = typeof body === "string" ? body : JSON.stringify(body);
  }
  const res = await apiFetch(path, init);
  const data = await parse(res);
  if (!res.ok) throw new ApiError(res.status, typeof data === "object" ? data : { detail: data });
  return data;
}

export const get = (path) => request("GET", path);
export const post = (path, body) => request("POST", path, body);
export const del = (path) => request("DELETE", path);

let schemaPromise;
export function schema() {
  schemaPromise ??= get("/schema");
  return schemaPromise;
}

export async function text(path) {
  const res = await apiFetch(path);
  if (!res.ok) throw new ApiError(res.status, { detail: `${path}: HTTP ${res.status}` });
  return res.text();
}
