// The rating calculator's form: the pair and its load as fields, the two
// gears side by side, and the server's refusals shown at the fields their
// JSON pointers name (and listed above the form with the pointer).
import { getPointer, unitOf } from "./schema.js";
import { FIELDS, GEARS, GEAR_FIELDS, PAIR_GROUPS, documentFromValues, fieldId, fieldPointerFor, hintText } from "./rating-fields.js";
import { formText } from "./submit-fields.js";
import { h, put } from "./ui.js";

export function ratingForm({ onEdit }) {
  const problems = h("div", { class: "problems", id: "rating-problems", hidden: true, tabindex: "-1" });
  const form = h("form", { novalidate: true, id: "rating-form", "aria-describedby": "rating-problems" });
  const inputs = new Map(); // pointer -> {input, cell, error, spec}

  function control(spec, label) {
    const id = fieldId(spec.pointer);
    const input = spec.type === "enum"
      ? h("select", { id, name: spec.pointer },
        [...(spec.optional || spec.def === undefined ? [h("option", { value: "" }, "—")] : []),
          ...spec.options.map((v) => h("option", { value: v }, v))])
      : h("input", { id, name: spec.pointer, type: spec.type === "text" ? "text" : "number", step: spec.step || "any",
        inputmode: spec.type === "text" ? null : "decimal", autocomplete: "off",
        placeholder: spec.placeholder || (spec.def !== undefined ? String(spec.def) : "") });
    if (label) input.setAttribute("aria-label", label);
    input.setAttribute("aria-describedby", `${id}-error`);
    const error = h("div", { class: "error", id: `${id}-error`, hidden: true });
    input.addEventListener("input", () => { clearFieldError(spec.pointer); onEdit?.(); });
    return { id, input, error };
  }

  function fieldRow(spec) {
    const { id, input, error } = control(spec);
    const cell = h("div", { class: "field", dataset: { pointer: spec.pointer } },
      h("label", { for: id }, spec.label), input, h("span", { class: "unit" }, unitOf(spec.pointer)),
      h("div", { class: "hint" }, hintText(spec)), error);
    inputs.set(spec.pointer, { input, cell, error, spec });
    return cell;
  }

  // The two gears: one row per quantity, the pinion's and the wheel's side by side.
  function gearGrid() {
    const byGear = GEARS.map((_, g) => FIELDS.filter((f) => f.gear === g));
    const rows = GEAR_FIELDS.map((f, i) => {
      const cells = byGear.map((fields, g) => {
        const spec = fields[i];
        const { input, error } = control(spec, `${GEARS[g]}: ${f.label}`);
        const cell = h("div", { class: "gear-cell", dataset: { pointer: spec.pointer } },
          input, h("span", { class: "unit" }, unitOf(spec.pointer)), error);
        inputs.set(spec.pointer, { input, cell, error, spec: { ...spec, label: `${GEARS[g]} ${f.label.toLowerCase()}` } });
        return cell;
      });
      return [h("div", { class: "gear-label", title: hintText(f) }, f.label,
        f.def !== undefined ? h("span", { class: "hint" }, ` (${f.def})`) : null), ...cells];
    });
    return h("div", { class: "gear-grid", role: "group", "aria-label": "Pinion and wheel" },
      h("div", {}), ...GEARS.map((g) => h("div", { class: "gear-head" }, g)), rows.flat());
  }

  for (const [title, fields] of PAIR_GROUPS) {
    form.append(h("fieldset", {}, h("legend", {}, title), h("div", { class: "fields" }, fields.map(fieldRow))));
  }
  form.append(h("fieldset", {}, h("legend", {}, "Gears and materials"), gearGrid()));

  function fill(doc) {
    // A choice with a default shows it; an empty number field leaves its default to the server.
    for (const [pointer, { input, spec }] of inputs) {
      input.value = formText(getPointer(doc, pointer) ?? (spec.type === "enum" ? spec.def : undefined));
    }
  }

  function read() {
    return documentFromValues([...inputs.values()].map(({ input, spec }) => [spec, input.value]));
  }

  function clearFieldError(pointer) {
    const f = inputs.get(pointer);
    if (!f) return;
    f.cell.classList.remove("invalid");
    f.input.removeAttribute("aria-invalid");
    f.error.hidden = true;
    f.error.textContent = "";
  }

  function clearErrors() {
    problems.hidden = true;
    problems.replaceChildren();
    for (const p of inputs.keys()) clearFieldError(p);
  }

  function fieldFor(pointer) {
    const p = fieldPointerFor(pointer || "", [...inputs.keys()]);
    return p === null ? null : inputs.get(p);
  }

  // Each problem at its field (where the form has one) and in the list
  // above the form with its JSON pointer.
  function showProblems(errors, title) {
    for (const e of errors) {
      const f = fieldFor(e.pointer);
      if (!f) continue;
      f.cell.classList.add("invalid");
      f.input.setAttribute("aria-invalid", "true");
      f.error.hidden = false;
      f.error.textContent = f.error.textContent ? `${f.error.textContent} ${e.detail}` : e.detail;
    }
    const list = h("ul", {}, errors.map((e) => {
      const f = fieldFor(e.pointer);
      const where = e.pointer ? h("code", {}, e.pointer) : null;
      const link = f ? h("a", { href: "#" + f.input.id, onclick: (ev) => { ev.preventDefault(); f.input.focus(); } }, f.spec.label) : null;
      return h("li", { dataset: { pointer: e.pointer || "" } }, link, link && where ? " " : "", where, link || where ? ": " : "", e.detail);
    }));
    put(problems, h("strong", {}, title || `${errors.length} problem${errors.length === 1 ? "" : "s"} with this pair`), list);
    problems.hidden = errors.length === 0;
    const first = form.querySelector(".invalid input, .invalid select");
    (first || problems).focus();
  }

  return { form, problems, fill, read, clearErrors, showProblems };
}
