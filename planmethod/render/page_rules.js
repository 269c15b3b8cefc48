"use strict";
// The rulebook of planmethod grade, applied in a page: every rule comes from Python as data
// (render/page_rules.py: page_rules) — the grammar of a typed number, how a text is quoted
// back, grading's verdict table (planmethod.grading.verdicts: the template of every class of
// an answer and of a drawn point, by "<table>.<class>") — and this script only classifies the
// student's answer and drawn points as grade and grade --drawing do, against the key's
// precomputed values, and fills the class's template with the same fields. It computes no
// mechanics and writes no sentence of its own. tests/js/page_rules.test.js checks it under
// Node against the golden file Python writes (tests/page_golden.py), which says what grade and
// grade --drawing say; tests/test_browser.py checks the page itself in Chromium.
//
// Loaded by the workbook page (inlined, after page_words.js) and by Node's tests (require).
(function (root) {
  const wordsApi = typeof module === "object" && module.exports ?
    require("./page_words.js") : root.planmethodWords;

  // -- reading a typed answer (planmethod.grading.reading.read_number) -------------------------
  function reader(grammar) {
    const spaces = new Set(grammar.spaces);
    const zeros = grammar.zeros.slice().sort((a, b) => a - b);
    const pattern = new RegExp("^(?:" + grammar.pattern + ")$");
    function digit(point) {     // the ASCII digit of a decimal digit of any script, or null
      let low = 0, high = zeros.length - 1;
      while (low <= high) {
        const middle = (low + high) >> 1;
        if (zeros[middle] > point) high = middle - 1;
        else if (point - zeros[middle] >= 10) low = middle + 1;
        else return String(point - zeros[middle]);
      }
      return null;
    }
    const kept = characters => characters.slice(0, grammar.limit).join("");
    // a number, null for no answer, or the text given instead (at most `limit` characters)
    return function read(raw) {
      let characters = Array.from(String(raw));
      let start = 0, end = characters.length;
      while (start < end && spaces.has(characters[start])) start++;
      while (end > start && spaces.has(characters[end - 1])) end--;
      characters = characters.slice(start, end);
      if (!characters.length) return null;
      let cleaned = characters.join("");
      grammar.minus.forEach(sign => { cleaned = cleaned.split(sign).join("-"); });
      grammar.removed.forEach(character => { cleaned = cleaned.split(character).join(""); });
      if (cleaned.split(grammar.comma).length === 2 && cleaned.indexOf(grammar.point) < 0)
        cleaned = cleaned.replace(grammar.comma, grammar.point);
      cleaned = Array.from(cleaned, character => {
        const ascii = digit(character.codePointAt(0));
        return ascii === null ? character : ascii;
      }).join("");
      if (!pattern.test(cleaned)) return kept(characters);
      const value = Number(cleaned.split("_").join(""));
      return Number.isFinite(value) ? value : kept(characters);
    };
  }

  // -- quoting a text back as Python's repr() does (the unprintable code points: data) ---------
  function quoter(unprintable) {
    function printable(point) {
      let low = 0, high = unprintable.length / 2 - 1;
      while (low <= high) {
        const middle = (low + high) >> 1;
        if (unprintable[2 * middle] > point) high = middle - 1;
        else if (unprintable[2 * middle + 1] < point) low = middle + 1;
        else return false;
      }
      return true;
    }
    const hex = (point, width) => point.toString(16).padStart(width, "0");
    return function quoted(text) {
      const quote = text.indexOf("'") >= 0 && text.indexOf("\"") < 0 ? "\"" : "'";
      const named = {"\t": "\\t", "\n": "\\n", "\r": "\\r"};
      return quote + Array.from(text, character => {
        const point = character.codePointAt(0);
        if (character === quote || character === "\\") return "\\" + character;
        if (character in named) return named[character];
        if (point < 0x20 || point === 0x7f) return "\\x" + hex(point, 2);
        if (point < 0x7f || printable(point)) return character;
        if (point <= 0xff) return "\\x" + hex(point, 2);
        return point <= 0xffff ? "\\u" + hex(point, 4) : "\\U" + hex(point, 8);
      }).join("") + quote;
    };
  }

  // -- the verdict on a typed answer (planmethod.grading.answers: grade_question, classify) ----
  // the classes of an answer this script tells apart: every class of grading's table
  // (rules.templates "answers.<class>"), and no other
  const ANSWER_CLASSES = ["no_answer", "not_a_number", "correct", "mistake", "sense_mistake",
    "mistake_and_sense", "negative_magnitude", "sense_reversed", "sense_and_size", "wrong",
    "wrong_of_zero"];

  function make(rules) {
    const quoted = quoter(rules.unprintable);
    const words = wordsApi.make({templates: rules.templates, decimal: rules.decimal,
                                 quote: quoted, formula: rules.formula});
    const read = reader(rules.number);
    const m = words.message;
    const told = Object.keys(rules.templates).filter(id => id.startsWith("answers."))
      .map(id => id.slice("answers.".length));
    const unknown = told.filter(kind => !ANSWER_CLASSES.includes(kind))
      .concat(ANSWER_CLASSES.filter(kind => !told.includes(kind)));
    if (unknown.length) throw new Error("verdict classes not shared with grade: " + unknown);
    const near = (a, b, tolerance) => Math.abs(a - b) <= tolerance;
    const reversed = (answer, right) =>
      right !== 0 && answer !== 0 && (answer > 0) !== (right > 0);

    // a number with its unit, or without one (answers._amount)
    const amountOf = (number, unit) => unit ? m("amounts.amount", {number: number, unit: unit}) :
      m("amounts.bare", {number: number});
    // how far off an answer is: "24.1 % low", "1000 times the right value" (answers._off)
    function off(answer, right) {
      if (right === 0) return m("off.by", {amount: Math.abs(answer - right)});
      const ratio = answer / right;
      if (ratio >= 10 || (ratio > 0 && ratio <= 0.1)) return m("off.times", {ratio: ratio});
      const relative = ratio - 1;
      const way = (relative > 0 ? "off.high" : "off.low") +
        (right < 0 && ratio >= 0 ? "_in_magnitude" : "");
      return m(way, {percent: Math.abs(relative) * 100});
    }
    // which way and about how far, without the right value (answers._way): the share off
    // to one significant digit (answers._rough), as Python's format(x, ".1g") rounds it
    const rough = value => Number(wordsApi.formatNumber(value, ".1g"));
    function way(answer, right, signed) {
      if (signed && reversed(answer, right)) return m("ways.sense");
      const kind = right < 0 && answer <= 0 ? (answer < right ? "larger" : "smaller") :
        (answer > right ? "high" : "low");
      const ratio = right ? answer / right : 0;
      if (ratio <= 0) return m("ways." + kind);
      if (ratio >= 2 || ratio <= 0.1) return m("roughly.times", {ratio: rough(ratio)});
      return m("roughly." + kind, {percent: rough(Math.abs(ratio - 1) * 100)});
    }
    // a known mistake's answer, with the sense reversed too for a signed quantity
    // (answers._named_mistake): [class, fields, the mistake's name] or null
    function namedMistake(given, answer, shown, right) {
      const found = given.mistakes.find(one => near(answer, one.value, one.tolerance));
      if (found) return [found.kind === "sense" ? "sense_mistake" : "mistake", {
        answer: shown, off: off(answer, given.value), mistake: found.feedback,
        gives: found.value, right: right, way: way(answer, given.value, false)}, found.kind];
      if (!given.signed) return null;
      const turned = given.mistakes.find(one => one.kind !== "sense" &&
        near(-answer, one.value, one.tolerance));
      return turned ? ["mistake_and_sense", {answer: shown, mistake: turned.feedback,
                                             right: right}, turned.kind + "+sense"] : null;
    }
    // a wrong answer no known mistake gives (answers._wrong): [class, fields]
    function wrong(given, answer, shown, right) {
      const value = given.value, towards = way(answer, value, given.signed);
      if (given.signed && reversed(answer, value)) {
        const fields = {answer: shown, sense: given.senses[value > 0 ? 0 : 1], right: right,
                        magnitude: Math.abs(answer), way: towards};
        if (near(Math.abs(answer), Math.abs(value), given.tolerance))
          return ["sense_reversed", fields];
        return ["sense_and_size", Object.assign(fields, {
          off: off(Math.abs(answer), Math.abs(value))})];
      }
      const fields = {answer: shown, off: off(answer, value), right: right, way: towards,
                      off_by: amountOf(Math.abs(answer - value), given.unit)};
      if (!value) return ["wrong_of_zero", fields];
      return ["wrong", Object.assign(fields, {share: given.tolerance / Math.abs(value) * 100})];
    }
    // the class of a number given (answers.classify): [class, fields, the mistake's name]
    function classify(given, answer) {
      const shown = m("amounts.given", {symbol: given.symbol,
                                        amount: amountOf(answer, given.unit)});
      const right = m("amounts.right", {amount: amountOf(given.value, given.unit),
                                        tolerance: given.tolerance});
      if (near(answer, given.value, given.tolerance))
        return ["correct", {answer: shown, value: given.value, tolerance: given.tolerance}, null];
      const named = namedMistake(given, answer, shown, right);
      if (named) return named;
      if (!given.signed && answer < 0 && given.note)
        return ["negative_magnitude", {answer: shown, note: given.note, right: right}, null];
      return wrong(given, answer, shown, right).concat([null]);
    }

    // the verdict on `raw` (the text typed) for a key's question; `quantity` holds what a
    // negative magnitude is told (`negative`) and what the signs mean (`senses`)
    function answerVerdict(question, raw, quantity) {
      quantity = quantity || {};
      const given = {
        symbol: question.symbol || question.id, value: question.value,
        tolerance: question.tolerance, unit: question.unit || "", signed: !!question.signed,
        mistakes: question.mistakes || [], note: quantity.negative || null,
        senses: quantity.senses || [m("senses.other_positive"), m("senses.other_negative")],
      };
      const answer = read(raw);
      let kind, fields, mistake = null;
      if (typeof answer === "number") {
        [kind, fields, mistake] = classify(given, answer);
      } else {
        const right = m("amounts.right", {amount: amountOf(given.value, given.unit),
                                          tolerance: given.tolerance});
        [kind, fields] = answer === null ? ["no_answer", {symbol: given.symbol, right: right}] :
          ["not_a_number", {symbol: given.symbol, given: answer, right: right}];
      }
      // the page's HTML of them: the symbols' subscripts set, the text typed quoted as it is
      const markup = typeof answer === "string" ?
        {given: wordsApi.escapeHtml(quoted(answer))} : {};
      return {id: question.id, correct: kind === "correct", mistake: mistake,
              answer: typeof answer === "number" ? answer : null, verdict: kind,
              feedback: words.say("answers." + kind, fields),
              hint: words.say("hints." + kind, fields),
              feedbackHtml: words.html("answers." + kind, fields, markup),
              hintHtml: words.html("hints." + kind, fields, markup)};
    }

    // -- a drawn plan point (planmethod.grading.drawings: grade_drawing's _grade_point) --------
    // the mistakes whose position of the point lies within `radius` of the drawn point
    // (planmethod.grading.plan_points.named_mistakes)
    function namedMistakes(candidates, x, y, radius) {
      const out = [];
      (candidates || []).forEach(([mistake, mx, my]) => {
        if (Math.hypot(x - mx, y - my) <= radius && !out.includes(mistake)) out.push(mistake);
      });
      return out;
    }
    // the mistakes named on every wrong point of a plan, two or more of them
    // (planmethod.grading.plan_points.common_mistakes)
    function commonMistakes(named) {
      if (named.length < 2) return [];
      return named[0].filter(mistake => named.slice(1).every(other => other.includes(mistake)));
    }
    // the mistakes' explanations, one or the other (plan_points._or_when)
    const orWhen = (mistakes, texts) => mistakes.slice(1).reduce(
      (sentence, mistake) => m("parts.or_when", {first: sentence, second: texts[mistake]}),
      texts[mistakes[0]]);

    // one drawn plan: where its points belong and what its sentences tell of them (a frame's
    // drawing data: plan_points.drawing_frame, the mistakes by name), the points drawn
    // {label: [x, y]}, the points' course names {label: b₃}, what each mistake tells
    function sheet(plan, drawn, names, texts) {
      const name = label => names[label] || label;
      // where a point is drawn, else where it belongs (drawings._Sheet.drawn)
      const at = label => drawn[label] || (plan.points[label] || plan.others[label] ||
        [0, 0]).slice(0, 2);
      // how a point is off a line it is the intersection of (drawings._line_part)
      function linePart([through, degrees, line], found, right, radius) {
        const base = at(through), angle = degrees * Math.PI / 180;
        const direction = [Math.cos(angle), Math.sin(angle)];
        const offLine = Math.abs((found[0] - base[0]) * direction[1] -
                                 (found[1] - base[1]) * direction[0]);
        const along = (found[0] - right[0]) * direction[0] + (found[1] - right[1]) * direction[1];
        const fields = {line: line, through: name(through)};
        if (offLine <= radius && Math.abs(along) > radius)
          return m("parts.on_the_line", Object.assign({along: Math.abs(along)}, fields));
        if (offLine > radius) return m("parts.off_the_line", Object.assign({off: offLine}, fields));
        return null;
      }
      // the quantities read off a point that it makes wrong by half a percent or more
      // (drawings._readings): the pole is at the origin
      function readings(label) {
        const out = [], seen = new Set();
        (plan.reads || []).forEach(([quantity, start, end, length]) => {
          if (label !== start && label !== end) return;
          const from = drawn[start] || (start === plan.pole ? [0, 0] : undefined);
          const to = drawn[end];
          if (!from || !to || !length) return;
          const change = Math.hypot(to[0] - from[0], to[1] - from[1]) / length - 1;
          if (Math.abs(change) < 0.005) return;
          const part = m(change > 0 ? "parts.read_high" : "parts.read_low",
                         {quantity: quantity, percent: Math.abs(change) * 100});
          const key = JSON.stringify(part);
          if (!seen.has(key)) { seen.add(key); out.push(part); }
        });
        return out;
      }
      // where a misplaced point is off, and why (drawings._explain)
      function explain(label, found, right, distance, radius) {
        const point = name(label), placed = (plan.placed || {})[label] || [];
        let sentence = m("points.off", {point: point, distance: distance, radius: radius});
        if (placed[0] === "intersect") {
          const parts = ((plan.lines || {})[label] || [])
            .map(line => linePart(line, found, right, radius)).filter(part => part !== null);
          if (parts.length === 1)
            sentence = m("points.off_line", {point: point, distance: distance, line: parts[0]});
          else if (parts.length)
            sentence = m("points.off_lines", {point: point, distance: distance, line: parts[0],
                                              other: parts[1]});
        } else if (placed[0] === "lay_off") {
          const [, start, length, direction] = placed, from = at(start);
          sentence = m("points.laid_off", {
            point: point, distance: distance, radius: radius, start: name(start),
            length: length, direction: direction,
            drawn: Math.hypot(found[0] - from[0], found[1] - from[1])});
        } else if (placed[0] === "similarity") {
          sentence = m("points.similarity", {point: point, distance: distance, radius: radius,
                                             references: placed[1].map(name)});
        }
        const read = readings(label);
        return read.length ? m("parts.readings", {sentence: sentence, readings: read}) : sentence;
      }
      // the verdict on one point: placed, scored (required), graded at all (grade checks a
      // helper point when placed, and leaves out a point at the pole), right (null: a
      // construction point not placed), the mistakes named, its message and sentence
      return function verdict(label) {
        const [x, y, radius] = plan.points[label], found = drawn[label];
        const required = plan.required.includes(label);
        const result = {placed: found !== undefined, required: required, ok: false,
                        graded: required || (plan.helpers || []).includes(label),
                        mistakes: []};
        if (found === undefined) {
          result.ok = required ? false : null;
          result.message = m(required ? "points.missing" : "point_missing_helper",
                             {point: name(label)});
        } else {
          const distance = Math.hypot(found[0] - x, found[1] - y);
          result.distance = distance;
          result.ok = distance <= radius;
          if (result.ok) {
            result.message = m("points.within", {point: name(label), radius: radius,
                                                 distance: distance});
          } else {
            result.message = explain(label, found, [x, y], distance, radius);
            result.mistakes = namedMistakes((plan.mistakes || {})[label], found[0], found[1],
                                            radius);
            if (result.mistakes.length) result.message = m("parts.mistakes", {
              sentence: result.message, lies: m("parts.lies", {where: m("parts.where", {
                mistakes: orWhen(result.mistakes, texts)})})});
          }
        }
        result.sentence = words.render(result.message);
        return result;
      };
    }
    // the plan's summary after a check: how many of its points are right, and the mistakes
    // every wrong point is named with (as grade --drawing notes them: plan_points.plan_sentence)
    function planSummary(plan, right, total, common, texts) {
      const count = m("plan_right_" + plan, {right: right, total: total});
      if (!common.length) return words.render(count);
      return words.say("plan_summary_mistakes", {count: count, mistakes: m(
        "parts.plan", {mistakes: orWhen(common, texts)})});
    }

    return {words: words, read: read, quoted: quoted, answerVerdict: answerVerdict,
            namedMistakes: namedMistakes, commonMistakes: commonMistakes, sheet: sheet,
            planSummary: planSummary};
  }

  const api = {make: make};
  if (typeof module === "object" && module.exports) module.exports = api;
  else root.planmethodRules = api;
})(this);
