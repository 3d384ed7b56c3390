// The rack-and-pinion form built from the job schema, and the problems the
// server finds, shown at the fields they concern (and listed above the
// form, each linked to its field).
import { getPointer, unitOf } from "./schema.js";
import {
  CRACK_GROUP, CRACK_SECTION, GROUPS, fieldId, fieldPointerFor, fieldSchema, formText, hintText, jobFromValues,
} from "./submit-fields.js";
import { h, put } from "./ui.js";

// The root crack's section: shown for a quasi-static job (a crack needs
// the static state), its fields only once "grow a root crack" is ticked;
// sections() says whether its fields go into the job.
function crackSection(inputs, fieldRow, onEdit) {
  const box = h("input", { type: "checkbox", id: "crack-on", "aria-controls": "crack-fields" });
  let section = null;
  let grid = null;
  const quasiStatic = () => inputs.get("/scene/quasi_static")?.input.checked === true;
  function show() {
    if (!section) return;
    section.hidden = !quasiStatic();
    grid.hidden = !box.checked;
  }
  return {
    build(schema) {
      const [title, fields] = CRACK_GROUP;
      grid = h("div", { class: "fields", id: "crack-fields" });
      for (const f of fields) grid.append(fieldRow(schema, f));
      box.addEventListener("change", () => { show(); onEdit(0); });
      inputs.get("/scene/quasi_static")?.input.addEventListener("change", show);
      section = h("fieldset", { id: "crack-section" }, h("legend", {}, title),
        h("label", { class: "crack-toggle", for: "crack-on" }, box,
          "grow a root crack from tooth 0's tension fillet (docs/cracks.md)"),
        grid);
      show();
      return section;
    },
    fill(job) {
      box.checked = getPointer(job, "/scene/crack") !== undefined;
      show();
    },
    sections: () => ({ [CRACK_SECTION]: quasiStatic() && box.checked }),
  };
}

// onEdit(delay): a field changed; the preview follows after `delay` ms
// (undefined: the usual pause while typing).
export function jobForm({ onEdit }) {
  const problems = h("div", { class: "problems", id: "form-problems", hidden: true, tabindex: "-1" });
  const form = h("form", { novalidate: true, "aria-describedby": "form-problems", id: "job-form" });
  const inputs = new Map(); // pointer -> {input, row, error, spec, def}

  function fieldRow(s, spec) {
    const { node, def } = fieldSchema(s, spec.pointer);
    const id = fieldId(spec.pointer);
    let input;
    if (spec.type === "enum" && node?.enum) {
      // An optional choice starts empty: nothing is sent unless one is picked.
      const none = spec.optional ? [h("option", { value: "" }, "—")] : [];
      input = h("select", { id, name: spec.pointer },
        [...none, ...node.enum.map((v) => h("option", { value: v }, v))]);
    } else if (spec.type === "bool") {
      input = h("input", { id, name: spec.pointer, type: "checkbox" });
    } else if (spec.type === "text" || spec.type === "teeth" || spec.type === "position") {
      input = h("input", { id, name: spec.pointer, type: "text", autocomplete: "off",
        placeholder: spec.type === "teeth" ? "auto, all or a number" : spec.type === "position" ? "0 to 1, or peak" : "" });
    } else {
      input = h("input", { id, name: spec.pointer, type: "number", step: spec.step || "any",
        inputmode: "decimal", placeholder: spec.placeholder || "" });
    }
    const description = node?.description || "";
    const hint = h("div", { class: "hint", id: id + "-hint", title: description }, hintText(node, def, spec));
    input.setAttribute("aria-describedby", `${id}-hint ${id}-error`);
    input.title = description;
    // The crack's fields show their description in full (the limits that
    // depend on the spacing and the tooth are only said there).
    const full = spec.describe ? fieldSchema(s, spec.pointer).description : "";
    const help = full ? h("div", { class: "help", id: id + "-help" }, full) : null;
    if (help) input.setAttribute("aria-describedby", `${id}-hint ${id}-help ${id}-error`);
    const error = h("div", { class: "error", id: id + "-error", hidden: true });
    const unit = h("span", { class: "unit" }, spec.unit ?? unitOf(spec.pointer));
    const row = spec.type === "bool"
      ? h("div", { class: "field", dataset: { pointer: spec.pointer } },
        h("label", { for: id, class: "field-check" }, input, spec.label), hint, error)
      : h("div", { class: "field", dataset: { pointer: spec.pointer } },
        h("label", { for: id }, spec.label), input, unit, hint, help, error);
    inputs.set(spec.pointer, { input, row, error, spec, def });
    input.addEventListener("input", () => { clearFieldError(spec.pointer); onEdit(); });
    input.addEventListener("change", () => onEdit(0));
    return row;
  }

  const crack = crackSection(inputs, fieldRow, onEdit);
  const sections = () => crack.sections();

  // The fields, grouped, from the schema's limits, units and defaults.
  function build(schema) {
    for (const [title, fields] of GROUPS) {
      const grid = h("div", { class: "fields" });
      for (const f of fields) grid.append(fieldRow(schema, f));
      form.append(h("fieldset", {}, h("legend", {}, title), grid));
    }
    form.append(crack.build(schema));
  }

  function fill(job) {
    for (const [pointer, { input, def, spec }] of inputs) {
      let v = getPointer(job, pointer);
      // An optional block's fields (the material's strength) start empty:
      // a default alone must not make the job carry the block.
      if (v === undefined && def !== undefined && typeof def !== "object" && !spec.optional) v = def;
      if (v === undefined && spec.initial !== undefined) v = spec.initial;
      if (spec.type === "bool") input.checked = v === true;
      else input.value = formText(v);
    }
    crack.fill(job);
  }

  function read() {
    return jobFromValues([...inputs.values()].map(({ input, spec }) =>
      [spec, spec.type === "bool" ? (input.checked ? "true" : "") : input.value]), sections());
  }

  // Empty fields show what the scene chose for them.
  function showChosen(chosen) {
    for (const [pointer, { input, spec }] of inputs) {
      const v = chosen(pointer);
      if (v !== undefined && typeof v !== "object") input.placeholder = `${spec.placeholder || "scene default"}: ${v}`;
    }
  }

  function clearFieldError(pointer) {
    const f = inputs.get(pointer);
    if (!f) return;
    f.row.classList.remove("invalid");
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

  // The problems above the form; with atFields, also at the fields they concern.
  function showProblems(errors, title, atFields) {
    for (const e of errors) {
      const f = atFields ? fieldFor(e.pointer) : null;
      if (!f) continue;
      f.row.classList.add("invalid");
      f.input.setAttribute("aria-invalid", "true");
      f.error.hidden = false;
      f.error.textContent = f.error.textContent ? `${f.error.textContent} ${e.detail}` : e.detail;
    }
    const list = h("ul", {}, errors.map((e) => {
      const f = atFields ? fieldFor(e.pointer) : null;
      const where = e.pointer ? h("code", {}, e.pointer) : null;
      return h("li", {}, f ? h("a", { href: "#" + f.input.id, onclick: (ev) => { ev.preventDefault(); f.input.focus(); } }, f.spec.label) : where,
        f || where ? ": " : "", e.detail);
    }));
    put(problems, h("strong", {}, title || `${errors.length} problem${errors.length === 1 ? "" : "s"} with this job`), list);
    problems.hidden = errors.length === 0;
  }

  // Where the keyboard goes after a refusal: the first marked field, or the list.
  function focusProblems(atFields) {
    const first = form.querySelector(".field.invalid input, .field.invalid select");
    (atFields && first ? first : problems).focus();
  }

  return { form, problems, build, fill, read, showChosen, clearErrors, showProblems, focusProblems };
}
