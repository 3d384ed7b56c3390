// The page's shared UI helpers: building elements, the toast, and the
// dialog that asks for the access token of a server started with
// --token-file. Every view imports these; this module imports no view.

// A tiny element builder: h("div", {class: "x"}, child, "text").
export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (v === null || v === undefined || v === false) continue;
    if (k === "class") el.className = v;
    else if (k.startsWith("on") && typeof v === "function") el.addEventListener(k.slice(2), v);
    else if (k === "dataset") Object.assign(el.dataset, v);
    else if (v === true) el.setAttribute(k, "");
    else el.setAttribute(k, v);
  }
  for (const c of children.flat()) {
    if (c === null || c === undefined || c === false) continue;
    el.append(c instanceof Node ? c : document.createTextNode(String(c)));
  }
  return el;
}

// el.replaceChildren() that, like h(), leaves out null, undefined and false
// (which replaceChildren would show as text).
export function put(el, ...children) {
  el.replaceChildren(...children.flat().filter((c) => c !== null && c !== undefined && c !== false));
  return el;
}

let toastTimer = null;
export function toast(message, ms = 5000) {
  const t = document.getElementById("toast");
  t.textContent = message;
  t.hidden = false;
  clearTimeout(toastTimer);
  toastTimer = setTimeout(() => (t.hidden = true), ms);
}

// Asks for the access token in a modal dialog; resolves with it, or with
// null if the person closes the dialog. `message` says why it asks again.
export function askForToken(message = "") {
  return new Promise((resolve) => {
    const input = h("input", { type: "password", id: "token-input", name: "token", required: true,
      autocomplete: "current-password", spellcheck: "false", "aria-describedby": "token-help token-error" });
    const error = h("p", { class: "error", id: "token-error", role: "alert", hidden: !message }, message);
    const form = h("form", { method: "dialog" },
      h("h2", { id: "token-title" }, "Access token"),
      h("p", { id: "token-help" }, "This server was started with --token-file. Enter the token from that file; the browser keeps it for the next visits."),
      h("label", { for: "token-input" }, "Token"), input, error,
      h("div", { class: "form-actions" },
        h("button", { type: "submit", class: "primary", id: "token-submit" }, "Sign in")));
    const dialog = h("dialog", { id: "token-dialog", "aria-labelledby": "token-title" }, form);
    let answer = null;
    form.addEventListener("submit", () => {
      answer = input.value.trim() || null;
    });
    dialog.addEventListener("close", () => {
      dialog.remove();
      resolve(answer);
    });
    document.body.append(dialog);
    dialog.showModal();
    input.focus();
  });
}
