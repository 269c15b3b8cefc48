"use strict";
// The pages' words: message templates with named fields, filled as planmethod.words.render
// fills them (render/page_rules.py sends the templates, already in the page's language, and
// the language's decimal sign). Numbers are written by one formatter of the format
// specifications the templates use, as Python's format() writes them: exact decimal digits of
// the double (BigInt), rounded half to even. No sentence is written here: every text a person
// reads comes from a template.
//
// Loaded by the workbook page (inlined), by the studio (a file it serves) and by Node's tests
// (require): it names itself planmethodWords on the page, module.exports under Node.
(function (root) {
  // -- numbers --------------------------------------------------------------------------------
  // the exact decimal digits of a finite double x ≥ 0: [digits, point], x = 0.digits × 10^point
  function exactDecimal(x) {
    if (x === 0) return ["0", 1];
    const view = new DataView(new ArrayBuffer(8));
    view.setFloat64(0, x);
    const high = view.getUint32(0), low = view.getUint32(4);
    const biased = (high >>> 20) & 0x7ff;
    let mantissa = (BigInt(high & 0xfffff) << 32n) | BigInt(low);
    let exponent = -1074;
    if (biased !== 0) {
      mantissa |= 1n << 52n;
      exponent = biased - 1075;
    }
    if (exponent >= 0) {
      const digits = (mantissa << BigInt(exponent)).toString();
      return [digits, digits.length];
    }
    const digits = (mantissa * 5n ** BigInt(-exponent)).toString();
    return [digits, digits.length + exponent];
  }
  // 0.digits × 10^point rounded, half to even, to its first `keep` digits: [digits, point]
  // (`keep` digits, one more where the rounding carried: 0.995 → 1.00)
  function rounded(digits, point, keep) {
    if (keep >= digits.length) return [digits + "0".repeat(keep - digits.length), point];
    if (keep < 0) return ["", point];
    const head = digits.slice(0, keep), rest = digits.slice(keep);
    const above = /[1-9]/.test(rest.slice(1));
    const odd = keep > 0 && Number(head[keep - 1]) % 2 === 1;
    const up = rest[0] > "5" || (rest[0] === "5" && (above || odd));
    if (!up) return [head, point];
    const raised = (BigInt(head || "0") + 1n).toString().padStart(keep, "0");
    return raised.length > keep ? [raised, point + 1] : [raised, point];
  }
  const trimZeros = text => text.indexOf(".") < 0 ? text : text.replace(/\.?0+$/, "");
  // 0.digits × 10^point written with `decimals` digits after the point (digits long enough)
  function positional(digits, point, decimals) {
    let whole, fraction;
    if (point <= 0) {
      whole = "0";
      fraction = "0".repeat(-point) + digits;
    } else {
      whole = (digits + "0".repeat(Math.max(0, point - digits.length))).slice(0, point);
      fraction = digits.slice(point);
    }
    whole = whole.replace(/^0+(?=[0-9])/, "");
    fraction = (fraction + "0".repeat(decimals)).slice(0, decimals);
    return decimals > 0 ? whole + "." + fraction : whole;
  }
  function exponential(digits, point, decimals, trim) {
    let mantissa = digits[0] + (decimals > 0 ? "." + digits.slice(1, decimals + 1) : "");
    if (trim) mantissa = trimZeros(mantissa);
    const exponent = digits === "0".repeat(digits.length) ? 0 : point - 1;
    return mantissa + "e" + (exponent < 0 ? "-" : "+") + String(Math.abs(exponent)).padStart(2, "0");
  }
  // Python's repr of a float (an empty format specification): the shortest digits that read
  // back, positional from 1e-4 up to 1e16
  function shortest(x) {
    if (Number.isInteger(x) && Math.abs(x) < 1e16) return x.toFixed(0) + ".0";
    const [mantissa, power] = x.toExponential().split("e");
    const digits = mantissa.replace(".", ""), exponent = Number(power);
    if (exponent >= -4 && exponent < 16)
      return positional(digits, exponent + 1, Math.max(1, digits.length - exponent - 1));
    return exponential(digits, exponent + 1, digits.length - 1, true);
  }
  // a finite x ≥ 0 by one specification: "" (repr), "d", "f", "e", "g" with a precision
  function unsigned(x, type, precision) {
    if (type === "" && precision === null) return shortest(x);
    const [digits, point] = exactDecimal(x);
    if (type === "f") {
      const [kept, at] = rounded(digits, point, point + precision);
      return positional(kept || "0", kept ? at : 1, precision);
    }
    if (type === "e") {
      const [kept, at] = x === 0 ? ["0".repeat(precision + 1), 1] : rounded(digits, point, precision + 1);
      return exponential(kept, at, precision, false);
    }
    const significant = Math.max(1, precision === null ? 6 : precision);  // "g", and "" with a precision
    if (x === 0) return "0";
    const [kept, at] = rounded(digits, point, significant);
    const exponent = at - 1;
    if (exponent >= -4 && exponent < significant)
      return trimZeros(positional(kept, at, significant - 1 - exponent));
    return exponential(kept, at, significant - 1, true);
  }
  const SPECIFICATION = /^(?:\.([0-9]+))?([defg]?)$/;
  // a number written as Python's format(value, specification) writes it (the specifications
  // the templates use: "", "g", ".6g", ".2f", ".3e", "d")
  function formatNumber(value, specification) {
    const found = SPECIFICATION.exec(specification || "");
    if (!found) throw new Error("format specification not supported: " + specification);
    const precision = found[1] === undefined ? null : Number(found[1]);
    const type = found[2];
    if ((type === "" && precision !== null) || (type === "d" && precision !== null) ||
        (type === "d" && !Number.isInteger(value)))
      throw new Error("format specification not supported for " + value + ": " + specification);
    if (Number.isNaN(value)) return "nan";
    const negative = value < 0 || Object.is(value, -0);
    const size = Math.abs(value);
    if (!Number.isFinite(size)) return (negative ? "-" : "") + "inf";
    const text = (type === "d" || (type === "" && precision === null &&
                                   Number.isInteger(value) && !Object.is(value, -0) &&
                                   Math.abs(value) <= Number.MAX_SAFE_INTEGER))
      ? size.toFixed(0)   // an integer field (a count)
      : unsigned(size, type, type === "f" || type === "e" ?
        (precision === null ? 6 : precision) : precision);
    // a zero is never written with a minus sign (-0.0, or -0.0004 at two decimals), as
    // planmethod.words.render.formatted_number writes it
    return (negative && !/^[0.]+$/.test(text.split(/[eE]/)[0]) ? "-" : "") + text;
  }

  // -- templates ------------------------------------------------------------------------------
  // a field's mark while a message is written as HTML (html(): its markup put in after)
  const MARK = /^\u0000[0-9]+\u0000$/;
  const FIELD = /\{\{|\}\}|\{([A-Za-z_][A-Za-z0-9_]*)(?:!(r))?(?::([^{}]*))?\}/g;
  // a template's named fields filled; a value is text, a number, a message {id, fields} or a
  // list of those (joined with commas), as planmethod.words.render fills them; a text field
  // marked !r is quoted as Python's repr() quotes it (`quote`: page_rules.js)
  function fill(template, fields, renderMessage, decimal, quote) {
    return template.replace(FIELD, (whole, name, conversion, specification) => {
      if (whole === "{{") return "{";
      if (whole === "}}") return "}";
      if (!(name in fields)) throw new Error("no field " + name + " for " + template);
      if (conversion) {
        if (MARK.test(fields[name])) return fields[name];   // set by html() as its markup says
        if (typeof fields[name] !== "string" || !quote || specification)
          throw new Error("cannot quote field " + name + " of " + template);
        return quote(fields[name]);
      }
      return value(fields[name], specification || "", renderMessage, decimal);
    });
  }
  function value(item, specification, renderMessage, decimal) {
    if (Array.isArray(item))
      return item.map(one => value(one, specification, renderMessage, decimal)).join(", ");
    if (typeof item === "number") {
      const text = formatNumber(item, specification);
      return decimal === "." ? text : text.replace(".", decimal);
    }
    if (item !== null && typeof item === "object") return renderMessage(item);
    if (typeof item !== "string") throw new Error("cannot fill in " + item);
    if (specification) throw new Error("format specification on text: " + specification);
    return item;
  }
  const ESCAPES = {"&": "&amp;", "<": "&lt;", ">": "&gt;", "\"": "&quot;", "'": "&#39;"};
  const escapeHtml = text => String(text).replace(/[&<>"']/g, c => ESCAPES[c]);

  // the template of a message: a text, or a sentence whose words follow a number: its forms
  // in the language, which form each count 0…199 takes, and the field that counts (above 199
  // a count takes the form of 100 + its last two digits, as every language's rule does)
  function chosen(template, fields) {
    if (typeof template === "string") return template;
    const count = Math.abs(Math.trunc(fields[template.count]));
    return template.forms[template.plural[count < 200 ? count : 100 + count % 100]];
  }
  // the words of one page: {templates: {id: template}, decimal: the decimal sign, quote:
  // how a field marked !r is quoted (optional)}
  function make(table) {
    const templates = table.templates, decimal = table.decimal || ".";
    // a message's text; a field named in `marks`, at any depth, is written as its mark
    function rendered(message, marks) {
      const template = templates[message.id];
      if (template === undefined) throw new Error("no template " + message.id);
      const fields = message.fields || {};
      const all = Object.assign({}, fields);
      Object.keys(marks).forEach(name => { if (name in all) all[name] = marks[name]; });
      return fill(chosen(template, fields), all, inner => rendered(inner, marks), decimal,
                  table.quote);
    }
    const render = message => rendered(message, {});
    // a text as HTML, escaped, each subscript of its symbols (v_C, n_CB, a_B₃) set as <sub>
    // by the figures' grammar (table.formula: planmethod.render.canvas.formula_grammar; its
    // subscript digits set plain inside the <sub>); without a grammar only escaped. A mark
    // (\u0000…) ends a subscript.
    const grammar = table.formula, subscript = grammar && new RegExp(grammar.pattern, "g");
    const plainDigits = text => text.replace(/[\u2080-\u2089]/g,
                                             digit => String(grammar.digits.indexOf(digit)));
    function formula(text) {
      if (!subscript) return escapeHtml(text);
      let out = "", at = 0;
      for (const match of text.matchAll(subscript)) {
        if (match[1] === undefined || match.index < at) continue;
        const sub = match[1].split("\u0000")[0];
        out += escapeHtml(text.slice(at, match.index)) + "<sub>" + escapeHtml(plainDigits(sub)) +
          "</sub>";
        at = match.index + 1 + sub.length;
      }
      return out + escapeHtml(text.slice(at));
    }
    return {
      // a message: the template `id` with its fields (nested in another's fields, or rendered)
      message: (id, fields) => ({id: id, fields: fields || {}}),
      render: render,
      say: (id, fields) => render({id: id, fields: fields || {}}),
      // the message as HTML: its text escaped (its symbols' subscripts set, `formula`), the
      // fields named in `markup` set as given (in the messages nested in it too)
      html: (id, fields, markup) => {
        const marks = {};
        Object.keys(markup || {}).forEach((name, index) => {
          marks[name] = "\u0000" + index + "\u0000";
        });
        let text = formula(rendered({id: id, fields: fields || {}}, marks));
        Object.keys(marks).forEach(name => { text = text.split(marks[name]).join(markup[name]); });
        return text;
      },
      number: (item, specification) => value(item, specification || "", render, decimal),
      formula: formula,
    };
  }

  const api = {formatNumber: formatNumber, fill: fill, make: make, escapeHtml: escapeHtml};
  if (typeof module === "object" && module.exports) module.exports = api;
  else root.planmethodWords = api;
})(this);
