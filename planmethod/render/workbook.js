"use strict";
(function () {
  const wb = window.workbook = {ready: false, frame: -1, switchTimes: [], step: null};
  const status = document.getElementById("status");
  const slider = document.getElementById("angle");
  // the page's words and planmethod grade's rules, from the page's data (render/page_rules.py:
  // page_rules); the page classifies with them, it writes no sentence of its own
  let say = null, numberText = null;
  const fmt = (value, specification) =>
    value === null || value === undefined ? "—" : numberText(value, specification);
  // a quantity's page data by its question id: what a negative magnitude is told and what
  // the signs mean (planmethod.grading.answers.magnitude_note and sense_words)
  const quantityOf = {};
  // a typed answer's verdict, as planmethod grade gives it: the feedback with the right
  // value, and the hint without it
  function grade(question, raw) {
    return wb.rules.answerVerdict(question, raw, quantityOf[question.id]);
  }
  wb.grade = grade;
  // whether a quantity's value is concealed now (the drawing mode sets this: a value is
  // concealed until the student asks to see the plan it is read off); its verdict is then
  // the hint, never the right value
  wb.concealed = () => false;
  // whether the plan a quantity is read off has been shown in the drawing mode (its values
  // are then the student's to see: workbook_draw.js sets this)
  wb.planShown = () => false;
  // the answers the student asked to see in practice, by the angle they were asked at
  // {angle: [question id, …]}: the page remembers them, the downloaded drawing says so
  wb.revealed = {};
  const practising = () => document.body.classList.contains("practising");
  wb.revealedAt = angle => (wb.revealed[String(angle)] || []).slice();
  const revealedHere = name => wb.revealedAt(wb.data.angles[wb.frame]).includes(name);
  // whether an answer's right value is kept from the student now: while practising, until
  // they ask to see it (or the plan it is read off); while drawing, until that plan is shown
  // or they ask to see it
  wb.hidden = name => practising() ? !(revealedHere(name) || wb.planShown(name)) :
    wb.concealed(name) && !revealedHere(name);

  // -- what the page keeps in this browser, by exercise (its title and digest): the mode, the
  // angle, the answers shown ------------------------------------------------------------------
  const STATE_PREFIX = "planmethod-page:";
  const stateKey = () => STATE_PREFIX + JSON.stringify(wb.data.key || []);
  function readState() {
    try {
      const kept = JSON.parse(window.localStorage.getItem(stateKey()) || "null");
      return kept && typeof kept === "object" ? kept : {};
    } catch (error) {
      return {};
    }
  }
  function keepState() {
    if (!wb.ready) return;
    try {
      window.localStorage.setItem(stateKey(), JSON.stringify(
        {mode: wb.mode, angle: wb.data.angles[wb.frame], revealed: wb.revealed}));
    } catch (error) { /* a browser that keeps nothing: the page works without */ }
  }
  // answers shown as the page kept them: {angle: [question id, …]}, names only
  function keptRevealed(kept) {
    const out = {};
    Object.entries(kept && typeof kept === "object" ? kept : {}).forEach(([angle, names]) => {
      if (Array.isArray(names)) out[angle] = names.filter(name => typeof name === "string");
    });
    return out;
  }

  async function load() {
    const raw = document.getElementById("workbook-data").textContent.trim();
    const bytes = Uint8Array.from(atob(raw), c => c.charCodeAt(0));
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"));
    return JSON.parse(await new Response(stream).text());
  }

  load().then(data => {
    wb.data = data;
    wb.rules = window.planmethodRules.make(data.rules);
    say = wb.rules.words.say;
    numberText = wb.rules.words.number;
    data.quantities.forEach(q => { quantityOf[q.name] = q; });
    const panels = data.panels.map(name => document.getElementById("panel-" + name));
    const cells = Array.from(document.querySelectorAll("#readings tbody td.reading"));
    const planCells = Array.from(document.querySelectorAll("#readings tbody td.plan-reading"));
    const tolerances = Array.from(document.querySelectorAll("#readings tbody td.tolerance"));
    const verdicts = Array.from(document.querySelectorAll("#readings tbody td.verdict"));
    const answers = Array.from(document.querySelectorAll("#readings tbody input.answer"));
    const rows = cells.map(cell => cell.closest("tr"));
    const cursors = Array.from(document.querySelectorAll("#charts .chart")).map(
      chart => chart.querySelector("line.cursor"));
    const cache = new Map();
    const a0 = data.angles[0], a1 = data.angles[data.angles.length - 1];
    const stepOf = angle => data.angles.length < 2 ? 0 :
      Math.round((angle - a0) / (data.angles[1] - a0));

    function svgOf(frame, p) {
      const key = frame + ":" + p;
      let text = cache.get(key);
      if (text === undefined) {
        text = data.frames[frame].drawings[p].map(k => data.strings[k]).join("\n");
        cache.set(key, text);
      }
      return text;
    }
    // each frame's drawings are parsed once and kept: a later visit only swaps nodes
    const parsed = new Map();
    function nodesOf(frame) {
      let nodes = parsed.get(frame);
      if (nodes === undefined) {
        nodes = panels.map((_, p) => {
          const template = document.createElement("template");
          template.innerHTML = svgOf(frame, p);
          return template.content.firstElementChild;
        });
        parsed.set(frame, nodes);
      }
      return nodes;
    }
    const later = window.requestIdleCallback || (callback => setTimeout(callback, 0));
    function prepareNeighbours(frame) {
      later(() => {
        const count = data.frames.length;
        nodesOf((frame + 1) % count);
        nodesOf((frame - 1 + count) % count);
      });
    }
    function questionOf(frame, name) {
      return (data.frames[frame].questions || []).find(q => q.id === name);
    }
    function show(frame) {
      const t0 = performance.now();
      frame = Math.max(0, Math.min(data.frames.length - 1, frame));
      wb.frame = frame;
      const f = data.frames[frame];
      const nodes = nodesOf(frame);
      panels.forEach((element, p) => {
        const node = nodes[p];
        if (node) {
          node.querySelectorAll(".step-hidden, .step-current").forEach(n => {
            n.classList.remove("step-hidden", "step-current");
          });
          element.replaceChildren(node);
        } else {
          element.replaceChildren();
        }
      });
      data.quantities.forEach((q, i) => {
        const [exact, plan] = f.readings[i];
        cells[i].dataset.value = exact === null ? "" : String(exact);
        cells[i].textContent = fmt(exact, ".4g");
        planCells[i].textContent = fmt(plan, ".4g");
        const question = questionOf(frame, q.name);
        tolerances[i].textContent = !question ? "—" : question.unit ?
          say("tolerance_shown", {tolerance: question.tolerance, unit: question.unit}) :
          say("tolerance_shown_unitless", {tolerance: question.tolerance});
        verdicts[i].textContent = "";
        verdicts[i].className = "verdict";
        rows[i].classList.toggle("revealed", revealedHere(q.name));
      });
      hideAsked();
      const angle = data.angles[frame];
      cursors.forEach((cursor, c) => {
        if (!cursor) return;
        const [x0, x1] = data.charts[c];
        const x = a1 === a0 ? x0 : x0 + (angle - a0) / (a1 - a0) * (x1 - x0);
        cursor.setAttribute("x1", x); cursor.setAttribute("x2", x);
      });
      document.getElementById("angle-value").textContent = say("angle_shown", {angle: angle});
      wb.step = null;
      document.getElementById("step-text").textContent = "";
      document.getElementById("step-number").textContent = "";
      document.getElementById("equations").textContent = "";
      // other parts of the page (the drawing mode) follow the frame: part of the switch
      document.dispatchEvent(new CustomEvent("workbook:frame", {detail: {frame: frame}}));
      void document.body.offsetHeight;  // lay the page out: part of the switch
      const spent = performance.now() - t0;
      wb.switchTimes.push(spent);
      document.getElementById("switch-time").textContent = say("switch_time", {time: spent});
      prepareNeighbours(frame);
      keepState();
    }
    wb.show = show;
    wb.showAngle = angle => { slider.value = angle; show(stepOf(Number(angle))); };
    slider.addEventListener("input", () => show(stepOf(Number(slider.value))));

    let timer = null;
    const play = document.getElementById("play");
    play.addEventListener("click", () => {
      if (timer) { clearInterval(timer); timer = null; play.textContent = say("play"); return; }
      play.textContent = say("pause");
      timer = setInterval(() => {
        // the crank turns as ω₁ says: φ grows when it turns counter-clockwise
        const count = data.frames.length;
        const next = (wb.frame + (data.sense || 1) + count) % count;
        slider.value = data.angles[next];
        show(next);
      }, 60);
    });

    // construction playback: the steps of one plan, one at a time
    function playStep(number) {
      const plan = document.getElementById("step-plan").value;
      const steps = data.frames[wb.frame].steps[plan] || [];
      const element = panels[data.panels.indexOf(plan)];
      if (!element || !steps.length) {
        document.getElementById("step-text").textContent = say("no_plan_" + plan);
        return;
      }
      number = Math.max(0, Math.min(steps.length - 1, number));
      wb.step = number;
      const current = steps[number][0];
      element.querySelectorAll("[data-step]").forEach(node => {
        const n = Number(node.dataset.step);
        node.classList.toggle("step-hidden", n > current);
        node.classList.toggle("step-current", n === current);
      });
      // a point's label, mark and leader show once a step has named one of its points
      const named = new Set();
      steps.slice(0, number + 1).forEach(step => (step[3] || []).forEach(p => named.add(p)));
      element.querySelectorAll(
          "text.label[data-points], circle[data-points], line.leader[data-points]"
      ).forEach(label => {
        const points = label.dataset.points.split(" ");
        label.classList.toggle("step-hidden", !points.some(p => named.has(p)));
      });
      document.getElementById("step-number").textContent =
        say("step_of", {number: number + 1, count: steps.length});
      // the step's sentence, typeset in Python (render/workbook.py formula_html)
      document.getElementById("step-text").innerHTML = data.strings[steps[number][1]];
      // the plan's vector equations, typeset in Python (render/workbook.py formula_html)
      const equations = (data.frames[wb.frame].equations || {})[plan] || [];
      document.getElementById("equations").innerHTML =
        equations.map(k => data.strings[k]).join("<br>");
    }
    wb.playStep = playStep;
    document.getElementById("step-first").addEventListener("click", () => playStep(0));
    document.getElementById("step-prev").addEventListener("click",
      () => playStep(wb.step === null ? 0 : wb.step - 1));
    document.getElementById("step-next").addEventListener("click",
      () => playStep(wb.step === null ? 0 : wb.step + 1));
    document.getElementById("step-all").addEventListener("click", () => show(wb.frame));
    document.getElementById("step-plan").addEventListener("change", () => show(wb.frame));

    // the drawings at their own size (their text readable), or two to a row, smaller
    document.getElementById("compact").addEventListener("change", event => {
      document.body.classList.toggle("compact", event.target.checked);
    });

    // the page's modes: watch, practise (readings hidden, answers graded against the key of
    // this angle), draw (workbook_draw.js); switching to draw brings the sheets into view
    const MODES = ["watch", "practise", "draw"];
    function setMode(mode, scroll) {
      if (!MODES.includes(mode) || !document.querySelector('#modes input[value="' + mode + '"]'))
        mode = "watch";
      wb.mode = mode;
      document.querySelector('#modes input[value="' + mode + '"]').checked = true;
      document.body.classList.toggle("practising", mode === "practise");
      document.body.classList.toggle("drawing", mode === "draw");
      hideAsked();
      document.dispatchEvent(new CustomEvent("workbook:mode", {detail: {mode: mode}}));
      if (scroll && mode === "draw") {
        const bar = document.getElementById("controls").getBoundingClientRect().height;
        const target = document.querySelector(".draw-plan:not(.absent)") ||
          document.getElementById("drawing");
        window.scrollBy(0, target.getBoundingClientRect().top - bar - 4);
      }
      keepState();
    }
    wb.setMode = setMode;
    document.querySelectorAll('#modes input[name="mode"]').forEach(input =>
      input.addEventListener("change", () => { if (input.checked) setMode(input.value, true); }));
    // what the figures show of an asked value while practising: a radius of curvature on the
    // mechanism (its label gives the value, its centre the length) stays hidden until the
    // student asks to see that answer
    function hideAsked() {
      const asked = (data.frames[wb.frame].questions || []).map(q => q.id);
      const kept = asked.filter(name => practising() && !revealedHere(name));
      const keptOf = name => kept.includes(name);
      panels.forEach(element => element.querySelectorAll(
          ".rho, .centre, [data-points^='rho_'], [data-points^='O_']").forEach(node => {
        const points = (node.dataset.points || "").split(" ").filter(p => p);
        const names = points.map(p => "rho_" + p.replace(/^(rho|O)_/, ""));
        node.classList.toggle("asked-hidden", names.length ? names.some(keptOf) :
          kept.some(name => name.startsWith("rho_")));
      }));
    }
    // "show the answer": one quantity's right value at this angle, remembered
    function reveal(name) {
      const key = String(data.angles[wb.frame]);
      const listed = wb.revealed[key] = wb.revealed[key] || [];
      if (!listed.includes(name)) listed.push(name);
      keepState();
      const i = data.quantities.findIndex(q => q.name === name);
      rows[i].classList.add("revealed");
      const question = questionOf(wb.frame, name);
      if (question) {
        const result = grade(question, answers[i].value);
        verdicts[i].innerHTML = result.feedbackHtml;
        verdicts[i].className = "verdict " + (result.correct ? "correct" : "wrong");
      }
      hideAsked();
    }
    wb.reveal = reveal;
    document.querySelectorAll("#readings button.reveal").forEach(button =>
      button.addEventListener("click", () => reveal(button.dataset.reveal)));
    function check() {
      const results = {};
      answers.forEach((input, i) => {
        const name = input.dataset.answer;
        const question = questionOf(wb.frame, name);
        if (!question) { verdicts[i].textContent = say("not_graded"); return; }
        const result = grade(question, input.value);
        results[name] = result;
        verdicts[i].innerHTML = wb.hidden(name) ? result.hintHtml : result.feedbackHtml;
        verdicts[i].className = "verdict " + (result.correct ? "correct" : "wrong");
        verdicts[i].dataset.correct = String(result.correct);
      });
      wb.results = results;
      return results;
    }
    wb.check = check;
    document.getElementById("check").addEventListener("click", check);

    // -- the answers as the answers file planmethod grade reads: the exercise (its title and
    // digest) and the angle they are for, the answers typed, and the answers shown at it
    function exportedAnswers() {
      const angle = data.angles[wb.frame];
      const [title, exercise] = data.key;
      const typed = {};
      answers.forEach(input => {
        if (input.value.trim() !== "") typed[input.dataset.answer] = input.value.trim();
      });
      const out = {format: data.answers_format, version: 1, title: title};
      if (exercise) out.exercise = exercise;
      return Object.assign(out, {angle: angle, answers: typed, revealed: wb.revealedAt(angle)});
    }
    wb.exportedAnswers = exportedAnswers;
    function downloadAnswers() {
      const text = JSON.stringify(exportedAnswers(), null, 1) + "\n";
      const link = document.createElement("a");
      link.href = URL.createObjectURL(new Blob([text], {type: "application/json"}));
      const slug = data.key[0].toLowerCase().replace(/[^a-z0-9]+/g, "-").replace(/^-|-$/g, "");
      link.download = (slug || "answers") + "-answers-" + data.angles[wb.frame] + "deg.json";
      document.body.appendChild(link);
      link.click();
      link.remove();
      setTimeout(() => URL.revokeObjectURL(link.href), 1000);
    }
    document.getElementById("download-answers").addEventListener("click", downloadAnswers);

    // other parts of the page (the drawing mode) start from the loaded data
    document.dispatchEvent(new CustomEvent("workbook:load", {detail: wb}));
    // the page as this browser kept it (the mode, the angle, the answers shown), else the
    // exercise's own angle, watching
    const kept = readState();
    wb.revealed = keptRevealed(kept.revealed);
    if (data.angles.includes(kept.angle)) slider.value = kept.angle;
    show(stepOf(Number(slider.value)));
    status.textContent = "";
    wb.ready = true;
    setMode(kept.mode || "watch", kept.mode === "draw");
  }).catch(error => {
    // the page's data did not load: the one sentence said without it is in the markup
    status.textContent = window.planmethodWords.fill(status.dataset.failed, {error: String(error)},
                                                     null, ".");
    console.error(error);
  });
})();
