// Rating: a bare gear pair rated by ISO 6336 method B (POST /rating,
// docs/rating.md), no job. The form is rating-form.js, the answer
// rating-result.js; this wires them to the server.
import { ApiError, post } from "./api.js";
import { TR_6336_30_EXAMPLE_1 } from "./rating-fields.js";
import { ratingForm } from "./rating-form.js";
import { ratingResult } from "./rating-result.js";
import { h, put } from "./ui.js";

// The form and the last answer survive a change of view (not a reload).
let saved = null;
let answer = null;

const placeholder = () => h("section", { class: "panel" }, h("div", { class: "body muted", id: "rating-empty" },
  "Fill in a pair, or load ISO/TR 6336-30's Example 1, and press Rate: each gear's S_H and S_F against the required safeties, ",
  "the stresses, every factor and the life at the required safeties."));

export function ratingView(root) {
  let disposed = false;
  const form = ratingForm({ onEdit: () => (saved = form.read()) });
  const rateButton = h("button", { type: "submit", class: "primary", form: "rating-form", id: "rate" }, "Rate");
  const exampleButton = h("button", { type: "button", id: "rating-example" }, "ISO/TR 6336-30 Example 1");
  const state = h("span", { class: "muted", role: "status", "aria-live": "polite", id: "rating-state" });
  const result = h("div", { id: "rating-answer" });

  root.append(
    h("div", { class: "page-head" }, h("h1", {}, "Gear rating"),
      h("p", {}, "ISO 6336-1, -2, -3 method B with ISO 6336-5 limits, for a cylindrical pair or a pinion with its rack; answered at once, nothing stored.")),
    h("div", { class: "grid-2 rating-grid" },
      h("section", { class: "panel", "aria-labelledby": "rating-pair-head" },
        h("header", {}, h("h2", { id: "rating-pair-head" }, "Pair"), h("span", { class: "muted" }, "empty fields take the defaults shown")),
        h("div", { class: "body" }, form.problems, form.form,
          h("div", { class: "form-actions" }, rateButton, exampleButton, state))),
      result));

  form.fill(saved || TR_6336_30_EXAMPLE_1);
  put(result, answer ? ratingResult(answer) : placeholder());

  async function rate() {
    form.clearErrors();
    const doc = form.read();
    saved = doc;
    rateButton.disabled = true;
    state.textContent = "rating…";
    try {
      const r = await post("/rating", doc);
      if (disposed) return;
      answer = r;
      state.textContent = `rated: ${r.name}`;
      put(result, ratingResult(r));
    } catch (e) {
      if (disposed) return;
      state.textContent = "not rated";
      answer = null;
      put(result, placeholder());
      const errors = e instanceof ApiError && e.errors.length ? e.errors : [{ pointer: "", detail: e.message }];
      form.showProblems(errors, e instanceof ApiError && e.problem.title ? `Not rated: ${e.problem.title.toLowerCase()}` : "Not rated");
    } finally {
      rateButton.disabled = false;
    }
  }

  form.form.addEventListener("submit", (e) => {
    e.preventDefault();
    rate();
  });
  exampleButton.addEventListener("click", () => {
    form.clearErrors();
    form.fill(TR_6336_30_EXAMPLE_1);
    saved = null;
    state.textContent = "ISO/TR 6336-30:2017, Example 1 loaded";
  });
  return { dispose() { disposed = true; } };
}
