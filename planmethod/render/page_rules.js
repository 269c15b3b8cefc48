"use strict";
// The rulebook of planmethod grade, applied in a page: every rule comes from Python as data
// (render/page_rules.py: page_rules) — the grammar of a typed number, how a text is quoted
// back, the verdict classes of an answer in the order they are tried and the template of each,
// the sentences of a drawn point — and this script only classifies the student's answer with
// them against the key's precomputed values. It computes no mechanics and writes no sentence
// of its own. tests/js/page_rules.test.js checks it under Node against the golden file Python
// writes (tests/page_golden.py); tests/test_browser.py checks the page itself in Chromium.
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

  // -- the verdict on a typed answer (planmethod.grading.answers.grade_question) ---------------
  function make(rules) {
    const words = wordsApi.make({templates: rules.templates, decimal: rules.decimal});
    const read = reader(rules.number);
    const quoted = quoter(rules.unprintable);
    const m = words.message;
    const reversed = (answer, right) =>
      right !== 0 && answer !== 0 && (answer > 0) !== (right > 0);

    // how far off an answer is: "24.1 % low", "1000 times the right value"
    function off(answer, right) {
      if (right === 0) return m("off_zero", {difference: Math.abs(answer - right)});
      const ratio = answer / right;
      if (ratio >= 10 || (ratio > 0 && ratio <= 0.1)) return m("off_times", {ratio: ratio});
      const relative = ratio - 1;
      const way = (relative > 0 ? "off_high" : "off_low") +
        (right < 0 && ratio >= 0 ? "_magnitude" : "");
      return m(way, {percent: Math.abs(relative) * 100});
    }
    // which way, without the right value (a reversed sense is a class of its own)
    function way(answer, right) {
      if (right < 0 && answer <= 0) return m(answer < right ? "way_larger" : "way_smaller");
      return m(answer > right ? "way_high" : "way_low");
    }
    const withUnit = (id, unit, fields) =>
      unit ? m(id, Object.assign({unit: unit}, fields)) : m(id + "_unitless", fields);
    const near = (a, b, tolerance) => Math.abs(a - b) <= tolerance;

    // each verdict class: whether it holds, and its fields (in the order rules.answers lists
    // the classes: the first that holds is the verdict)
    const CLASSES = {
      no_answer: given => given.answer === null ? {} : null,
      not_a_number: given => typeof given.answer === "string" ?
        {text: quoted(given.answer)} : null,
      correct: given => near(given.answer, given.value, given.tolerance) ?
        {value: given.value, tolerance: given.tolerance} : null,
      sense_mistake: given => {
        const found = given.mistakes.find(k => near(given.answer, k.value, k.tolerance));
        return found && found.kind === "sense" ? {mistake: found} : null;
      },
      mistake: given => {
        const found = given.mistakes.find(k => near(given.answer, k.value, k.tolerance));
        return found ? {mistake: found, off: off(given.answer, given.value)} : null;
      },
      mistake_and_sense: given => {
        if (!given.signed) return null;
        const found = given.mistakes.find(k => k.kind !== "sense" &&
          near(-given.answer, k.value, k.tolerance));
        return found ? {mistake: found, kind: found.kind + "+sense"} : null;
      },
      negative_magnitude: given => !given.signed && given.answer < 0 && given.note ?
        {note: given.note} : null,
      sense_reversed: given => given.signed && reversed(given.answer, given.value) ? {
        way: m("way_reversed"), direction: given.senses[given.value > 0 ? 0 : 1],
        magnitude: Math.abs(given.answer),
        size: near(Math.abs(given.answer), Math.abs(given.value), given.tolerance) ?
          m("size_right") : off(Math.abs(given.answer), Math.abs(given.value)),
      } : null,
      wrong: given => ({off: off(given.answer, given.value),
                        amount: withUnit("amount", given.unit,
                                         {amount: Math.abs(given.answer - given.value)})}),
    };

    // the verdict on `raw` (the text typed) for a key's question; `quantity` holds what a
    // negative magnitude is told (`negative`) and what the signs mean (`senses`)
    function answerVerdict(question, raw, quantity) {
      quantity = quantity || {};
      const unit = question.unit || "";
      const given = {
        answer: read(raw), value: question.value, tolerance: question.tolerance, unit: unit,
        signed: !!question.signed, mistakes: question.mistakes || [],
        note: quantity.negative || null, senses: quantity.senses || rules.senses,
      };
      const name = question.symbol || question.id;   // as the course writes it (ω₂)
      const right = withUnit("right", unit, {value: question.value,
                                             tolerance: question.tolerance});
      const result = {id: question.id, correct: false, mistake: null,
                      answer: typeof given.answer === "number" ? given.answer : null};
      for (const verdict of rules.answers) {
        if (!(verdict.name in CLASSES)) throw new Error("unknown verdict class " + verdict.name);
        const fields = CLASSES[verdict.name](given);
        if (fields === null) continue;
        const all = Object.assign({name: name, right: right, answer: given.answer}, fields);
        if (typeof given.answer === "number") {
          all.shown = withUnit("shown", unit, {name: name, answer: given.answer});
          all.way = fields.way || way(given.answer, given.value);
          if (verdict.name === "wrong" && given.value !== 0)
            all.right = m("right_relative", {right: right, relative:
              given.tolerance / Math.abs(given.value) * 100});
        }
        if (fields.mistake) {
          all.explanation = fields.mistake.feedback;
          all.given = fields.mistake.value;
          result.mistake = fields.kind || fields.mistake.kind;
        }
        result.correct = verdict.name === "correct";
        result.verdict = verdict.name;
        result.feedback = words.say(verdict.feedback, all);
        result.hint = words.say(verdict.hint, all);
        return result;
      }
      throw new Error("no verdict class holds");
    }

    // -- a drawn plan point (planmethod.grading.plan_points.named_mistakes) -------------------
    // the mistakes whose position of the point lies within `radius` of the drawn point
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
    const joined = (mistakes, texts) => mistakes.map(mistake => texts[mistake])
      .join(words.say("mistakes_joint"));
    // the verdict on one point: `entry` [x, y, radius] where it belongs, `drawn` [x, y] or
    // undefined, `candidates` [[mistake, x, y], …], `texts` {mistake: what the student is told}
    function pointVerdict(name, entry, drawn, required, candidates, texts) {
      const [x, y, radius] = entry;
      const result = {placed: drawn !== undefined, required: required, ok: false, mistakes: []};
      if (drawn === undefined) {
        result.ok = required ? false : null;
        result.message = m(required ? "point_missing" : "point_missing_helper", {name: name});
      } else {
        const distance = Math.hypot(drawn[0] - x, drawn[1] - y);
        const fields = {name: name, distance: distance, radius: radius};
        result.distance = distance;
        result.ok = distance <= radius;
        if (!result.ok) result.mistakes = namedMistakes(candidates, drawn[0], drawn[1], radius);
        if (result.mistakes.length)
          fields.mistakes = m("point_mistakes", {mistakes: joined(result.mistakes, texts)});
        result.message = m(result.ok ? "point_right" : result.mistakes.length ?
          "point_off_mistakes" : "point_off", fields);
      }
      result.sentence = words.render(result.message);
      return result;
    }
    // the plan's summary after a check: how many of its points are right, and the mistakes
    // every wrong point is named with
    function planSummary(plan, right, total, common, texts) {
      const count = m("plan_right_" + plan, {right: right, total: total});
      if (!common.length) return words.render(count);
      return words.say("plan_summary_mistakes", {count: count, mistakes: m(
        "plan_mistakes", {mistakes: joined(common, texts)})});
    }

    return {words: words, read: read, quoted: quoted, answerVerdict: answerVerdict,
            namedMistakes: namedMistakes, commonMistakes: commonMistakes,
            pointVerdict: pointVerdict, planSummary: planSummary};
  }

  const api = {make: make};
  if (typeof module === "object" && module.exports) module.exports = api;
  else root.planmethodRules = api;
})(this);
