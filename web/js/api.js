// Talking to gearsph serve: JSON requests, RFC 9457 problem documents.

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
  const res = await fetch(path, init);
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
  const res = await fetch(path);
  if (!res.ok) throw new ApiError(res.status, { detail: `${path}: HTTP ${res.status}` });
  return res.text();
}
