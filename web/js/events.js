// One Server-Sent Events stream (/events) for the whole page: the job list,
// the result view and the running-jobs badge subscribe to it. No polling:
// the list is fetched once, and again only after a `reset` event.
import { ensureSignedIn, get } from "./api.js";

// Before a refused stream is opened again (the browser's own retry: 3 s).
const REOPEN_MS = 3000;

class JobEvents {
  constructor() {
    this.jobs = new Map(); // jobID -> latest status document
    this.listeners = new Set();
    this.source = null;
    this.loaded = false;
    this.connected = null; // null until the stream first opens or fails
    this.reopening = false;
  }

  start() {
    if (this.source) return;
    this.reload();
    this.open();
  }

  open() {
    this.source = new EventSource("/events");
    const onEvent = (e) => {
      let doc;
      try { doc = JSON.parse(e.data); } catch { return; }
      if (!doc.jobID) return;
      const old = this.jobs.get(doc.jobID) || {};
      // Progress events carry only the moving numbers; keep the rest.
      this.jobs.set(doc.jobID, { ...old, ...doc });
      this.emit(doc.jobID, e.type);
    };
    this.source.addEventListener("status", onEvent);
    this.source.addEventListener("progress", onEvent);
    this.source.addEventListener("reset", () => this.reload());
    // The browser reconnects by itself; what happened meanwhile is fetched
    // once the stream is back.
    this.source.addEventListener("open", () => {
      if (this.connected === false) this.reload();
      this.connected = true;
      this.emit(null, "connection");
    });
    this.source.addEventListener("error", () => {
      this.connected = false;
      this.emit(null, "connection");
      // A refused stream (401: the server restarted with another token)
      // is closed for good: sign in again, then open it anew.
      if (this.source.readyState === EventSource.CLOSED) this.reopen();
    });
  }

  async reopen() {
    if (this.reopening) return;
    this.reopening = true;
    this.source.close();
    await new Promise((resolve) => setTimeout(resolve, REOPEN_MS));
    try {
      await ensureSignedIn();
    } catch {
      // unreachable or declined: the stream's own errors say so
    }
    this.reopening = false;
    this.open();
  }

  async reload() {
    try {
      const page = await get("/jobs?limit=200");
      this.jobs.clear();
      for (const j of page.jobs) this.jobs.set(j.jobID, j);
      this.loaded = true;
      this.emit(null, "reload");
    } catch (e) {
      this.emit(null, "error", e);
    }
  }

  list() {
    return [...this.jobs.values()].sort((a, b) => (a.created < b.created ? 1 : -1));
  }

  activeCount() {
    let n = 0;
    for (const j of this.jobs.values()) if (j.status === "accepted" || j.status === "running") n++;
    return n;
  }

  subscribe(fn) {
    this.listeners.add(fn);
    return () => this.listeners.delete(fn);
  }

  emit(id, kind, error) {
    for (const fn of this.listeners) fn(id, kind, error);
  }

  remember(doc) {
    if (doc?.jobID) {
      this.jobs.set(doc.jobID, { ...(this.jobs.get(doc.jobID) || {}), ...doc });
      this.emit(doc.jobID, "status");
    }
  }
}

export const events = new JobEvents();
