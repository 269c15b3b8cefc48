"use strict";
// The pages' rulebook under Node: the page's own scripts (planmethod/render/page_words.js,
// page_rules.js) against the golden file Python writes (tests/page_golden.py): every typed
// answer gets grade's verdict to the byte, every drawn point the verdict Python gives it,
// every number is written as Python's format() writes it, read as read_number reads it and
// quoted as repr() quotes it. tests/test_page_rules.py writes the file and runs this with
// PLANMETHOD_GOLDEN naming it; by hand:
//   python tests/page_golden.py /tmp/golden.json
//   PLANMETHOD_GOLDEN=/tmp/golden.json node --test tests/js/
const test = require("node:test");
const assert = require("node:assert/strict");
const fs = require("node:fs");
const path = require("node:path");

const render = path.join(__dirname, "..", "..", "planmethod", "render");
const words = require(path.join(render, "page_words.js"));
const rulebook = require(path.join(render, "page_rules.js"));

const where = process.env.PLANMETHOD_GOLDEN;
const skip = where ? false : "no golden file: PLANMETHOD_GOLDEN names none " +
  "(python tests/page_golden.py FILE writes one)";
const golden = where ? JSON.parse(fs.readFileSync(where, "utf8")) : null;
const rules = golden ? rulebook.make(golden.rules) : null;

// each failing case in full, at most a few of them
function agree(cases, check) {
  const wrong = [];
  cases.forEach(item => {
    const problem = check(item);
    if (problem && wrong.length < 5) wrong.push(problem);
  });
  assert.deepEqual(wrong, []);
}

test("every typed answer gets grade's verdict, feedback and hint", {skip}, () => {
  agree(golden.answers, item => {
    const {question, quantity} = golden.questions[item.question];
    const mine = rules.answerVerdict(question, item.raw, quantity);
    const expected = item.expected;
    const got = {correct: mine.correct, mistake: mine.mistake, feedback: mine.feedback,
                 hint: mine.hint, answer: mine.answer};
    try { assert.deepEqual(got, expected); } catch (error) {
      return {raw: item.raw, question: question.id, got: got, expected: expected};
    }
    return null;
  });
});

test("every drawn point gets grade --drawing's verdict and sentence", {skip}, () => {
  let lines = 0;
  agree(golden.drawings, item => {
    const page = golden.plans[item.plan];
    const verdict = rules.sheet(page.data, item.drawn, page.names, golden.texts);
    const results = Object.keys(page.data.points).map(label => [label, verdict(label)]);
    const got = {}, wrong = [];
    results.forEach(([label, mine]) => {
      if (!(label in item.expected)) return;       // a point at the pole: grade leaves it out
      got[label] = {ok: mine.ok, mistakes: mine.mistakes, sentence: mine.sentence};
      if (mine.graded && mine.placed && mine.ok === false) wrong.push(mine.mistakes);
      if (/ on the line /.test(mine.sentence)) lines += 1;
    });
    const right = results.filter(([, mine]) => mine.required && mine.ok).length;
    const common = rules.commonMistakes(wrong);
    const summary = rules.planSummary(page.plan, right, page.data.required.length, common,
                                      golden.texts);
    try {
      assert.deepEqual(got, item.expected);
      assert.deepEqual([right, common, summary], [item.right, item.common, item.summary]);
    } catch (error) {
      return {case: item, got: got, right: right, common: common, summary: summary};
    }
    return null;
  });
  assert.ok(lines >= 10, "points of the wrong link (on a line, off along it): " + lines);
});

// what a person reads of the page's HTML: its tags left out, its entities read
const visible = html => html.replace(/<[^>]*>/g, "").replace(/&lt;/g, "<").replace(/&gt;/g, ">")
  .replace(/&quot;/g, "\"").replace(/&#39;/g, "'").replace(/&amp;/g, "&");
// a text with its symbols' underscores and subscript digits left out (v_B₃ → vB3): what the
// page's HTML of a sentence shows, v with B3 set below
const flat = text => text.replace(/_/g, "").replace(/[\u2080-\u2089]/g,
                                                   digit => String(digit.charCodeAt(0) - 0x2080));
const codeName = /_[A-Za-z\u0370-\u03ff]/;

test("the page's feedback and hints set the symbols' subscripts: no v_C, n_CB", {skip}, () => {
  let subscripts = 0;
  agree(golden.answers, item => {
    const {question, quantity} = golden.questions[item.question];
    const mine = rules.answerVerdict(question, item.raw, quantity);
    for (const [html, text] of [[mine.feedbackHtml, mine.feedback], [mine.hintHtml, mine.hint]]) {
      subscripts += (html.match(/<sub>/g) || []).length;
      const shown = visible(html);
      if (flat(shown) !== flat(text) || (!item.raw.includes("_") && codeName.test(shown)))
        return {raw: item.raw, question: question.id, html: html, text: text};
    }
    return null;
  });
  assert.ok(subscripts > 100, "symbols set with subscripts: " + subscripts);
});

test("the page's drawn points' sentences set the symbols' subscripts", {skip}, () => {
  agree(golden.drawings, item => {
    const page = golden.plans[item.plan];
    const verdict = rules.sheet(page.data, item.drawn, page.names, golden.texts);
    for (const label of Object.keys(page.data.points)) {
      const mine = verdict(label);
      // the point's own name typeset apart, as the page sets it (workbook_draw.js)
      const point = "<span>" + rules.words.formula(page.names[label] || label) + "</span>";
      const html = rules.words.html(mine.message.id, mine.message.fields, {point: point});
      const shown = visible(html);
      if (flat(shown) !== flat(mine.sentence) || codeName.test(shown))
        return {label: label, html: html, sentence: mine.sentence};
    }
    return null;
  });
});

test("numbers are written as Python's format() writes them", {skip}, () => {
  agree(golden.numbers, ([value, specification, expected]) => {
    const got = words.formatNumber(value, specification);
    return got === expected ? null : {value, specification, expected, got};
  });
});

test("typed texts are read as read_number reads them", {skip}, () => {
  agree(golden.readings, ([text, expected]) => {
    const got = rules.read(text);
    return Object.is(got, expected) || got === expected ? null : {text, expected, got};
  });
});

test("texts are quoted as repr() quotes them", {skip}, () => {
  agree(golden.quoting, ([text, expected]) => {
    const got = rules.quoted(text);
    return got === expected ? null : {text, expected, got};
  });
});

test("a template is filled with its named fields, braces kept", () => {
  const page = words.make({templates: {a: "{x:.2f} and {{b}} {y}", b: "[{z}]"}, decimal: ","});
  assert.equal(page.say("a", {x: 0.125, y: page.message("b", {z: ["p", "q"]})}),
               "0,12 and {b} [p, q]");
  assert.throws(() => page.say("a", {x: 1}), /no field y/);
  assert.throws(() => words.formatNumber(1.5, ">10"), /not supported/);
  assert.equal(page.html("b", {z: "<i>"}, {}), "[&lt;i&gt;]");
});

test("a sentence whose words follow a number takes its count's form", () => {
  const plural = {forms: ["{count} files", "{count} file"], count: "count",
                  plural: Array.from({length: 200}, (_, n) => n === 1 ? 1 : 0)};
  const page = words.make({templates: {files: plural}, decimal: "."});
  assert.equal(page.say("files", {count: 1}), "1 file");
  assert.equal(page.say("files", {count: 3}), "3 files");
  assert.equal(page.say("files", {count: 301}), "301 files");   // as 101: 100 + its last two digits
});
