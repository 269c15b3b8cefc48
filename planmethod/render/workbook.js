"use strict";
(function () {
  const wb = window.workbook = {ready: false, frame: -1, switchTimes: [], step: null};
  const status = document.getElementById("status");
  const slider = document.getElementById("angle");
  // Python's format(value, ".{digits}g"), so that the page's feedback reads as the grader's
  function fmt(value, digits) {
    if (value === null || value === undefined) return "—";
    if (value === 0) return "0";
    if (!isFinite(value)) return String(value);
    const [mantissa, power] = Number(value).toExponential(digits - 1).split("e");
    const exponent = Number(power);
    const trim = text => text.indexOf(".") < 0 ? text : text.replace(/\.?0+$/, "");
    if (exponent < -4 || exponent >= digits) {
      const sign = exponent < 0 ? "-" : "+";
      const size = String(Math.abs(exponent)).padStart(2, "0");
      return trim(mantissa) + "e" + sign + size;
    }
    return trim(Number(value).toFixed(Math.max(0, digits - 1 - exponent)));
  }
  function numberText(value) { return fmt(value, 6); }
  function parseAnswer(raw) {
    const text = String(raw).trim();
    if (!text) return null;
    let cleaned = text.replace(/\u2212/g, "-").replace(/ /g, "");
    if ((cleaned.match(/,/g) || []).length === 1 && cleaned.indexOf(".") < 0)
      cleaned = cleaned.replace(",", ".");
    if (!/^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(cleaned)) return text.slice(0, 40);
    const value = Number(cleaned);
    return isFinite(value) ? value : text.slice(0, 40);
  }
  function off(answer, right) {
    if (right === 0) return fmt(Math.abs(answer - right), 3) + " off";
    const ratio = answer / right;
    if (ratio >= 10 || (ratio > 0 && ratio <= 0.1)) return fmt(ratio, 4) + " times the right value";
    const relative = ratio - 1;
    const magnitude = right < 0 && ratio >= 0 ? " in magnitude" : "";
    return (Math.abs(relative) * 100).toFixed(1) + " % " + (relative > 0 ? "high" : "low") + magnitude;
  }
  // what a negative answer for a magnitude is told, and what a positive and a negative value
  // mean (counter-clockwise, along the guide), by quantity (filled from the page's data:
  // planmethod.grading.answers.magnitude_note and sense_words)
  const negativeNotes = {}, senseWords = {};
  // which way an answer is off, without the right value (planmethod.grading.answers._way)
  function way(answer, right, signed) {
    if (signed && right !== 0 && answer !== 0 && (answer > 0) !== (right > 0))
      return "the sense is reversed";
    if (right < 0 && answer <= 0)
      return answer < right ? "too large in magnitude" : "too small in magnitude";
    return answer > right ? "too high" : "too low";
  }
  // the rules of planmethod.grading.answers.grade_question, on the precomputed key: the
  // feedback with the right value, and the hint without it
  function grade(q, raw) {
    const unit = q.unit || "";
    const right = (numberText(q.value) + " " + unit + " ± " + fmt(q.tolerance, 3)).replace("  ", " ");
    const answer = parseAnswer(raw);
    const name = q.symbol || q.id;  // as the course writes it (ω₂), as grade_question does
    const result = {id: q.id, correct: false, mistake: null, answer: null};
    if (answer === null) {
      result.feedback = name + ": no answer (right: " + right + ")";
      result.hint = name + ": no answer";
      return result;
    }
    if (typeof answer === "string") {
      result.feedback = name + ": '" + answer + "' is not a number (right: " + right + ")";
      result.hint = name + ": '" + answer + "' is not a number";
      return result;
    }
    result.answer = answer;
    const shown = (name + " = " + numberText(answer) + " " + unit).trimEnd();
    if (Math.abs(answer - q.value) <= q.tolerance) {
      result.correct = true;
      result.feedback = shown + ": correct (exact " + numberText(q.value) + ", tolerance ± " + fmt(q.tolerance, 3) + ")";
      result.hint = shown + ": correct";
      return result;
    }
    for (const m of q.mistakes || []) {
      if (Math.abs(answer - m.value) <= m.tolerance) {
        result.mistake = m.kind;
        const how = m.kind === "sense" ? "" : ", " + off(answer, q.value);
        result.feedback = shown + ": wrong" + how + " — it looks as if " + m.feedback +
          " (that gives " + numberText(m.value) + "; right: " + right + ")";
        result.hint = shown + ": wrong (" + way(answer, q.value, false) + ") — it looks as if " +
          m.feedback;
        return result;
      }
    }
    if (q.signed) {
      for (const m of q.mistakes || []) {
        if (m.kind !== "sense" && Math.abs(-answer - m.value) <= m.tolerance) {
          result.mistake = m.kind + "+sense";
          result.feedback = shown + ": wrong — it looks as if " + m.feedback + ", and the sense is reversed (right: " + right + ")";
          result.hint = shown + ": wrong — it looks as if " + m.feedback + ", and the sense is reversed";
          return result;
        }
      }
    }
    const note = !q.signed && answer < 0 ? negativeNotes[q.id] : undefined;
    if (note) {   // a magnitude given with a sign (planmethod.grading.answers.magnitude_note)
      result.feedback = shown + ": wrong — " + note + " (right: " + right + ")";
      result.hint = shown + ": wrong — " + note;
      return result;
    }
    if (q.signed && q.value !== 0 && answer !== 0 && (answer > 0) !== (q.value > 0)) {
      result.feedback = shown + ": wrong — the sense is reversed (the right answer is " +
        (senseWords[q.id] || ["positive", "negative"])[q.value > 0 ? 0 : 1] + ", " + right +
        ") and the magnitude " +
        numberText(Math.abs(answer)) + " is " +
        (Math.abs(Math.abs(answer) - Math.abs(q.value)) <= q.tolerance ? "right"
          : off(Math.abs(answer), Math.abs(q.value)));
    } else {
      const tol = q.value ? " = ± " + fmt(q.tolerance / Math.abs(q.value) * 100, 2) + " %" : "";
      result.feedback = shown + ": wrong — " + off(answer, q.value) + " (off by " +
        (numberText(Math.abs(answer - q.value)) + " " + unit).trimEnd() + "; right: " + right + tol + ")";
    }
    result.hint = shown + ": wrong (" + way(answer, q.value, q.signed) + ")";
    return result;
  }
  wb.grade = grade;
  // whether a quantity's value is concealed now (the drawing mode sets this: a value is
  // concealed until the student asks to see the plan it is read off); its verdict is then
  // the hint, never the right value
  wb.concealed = () => false;

  async function load() {
    const raw = document.getElementById("workbook-data").textContent.trim();
    const bytes = Uint8Array.from(atob(raw), c => c.charCodeAt(0));
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"));
    return JSON.parse(await new Response(stream).text());
  }

  load().then(data => {
    wb.data = data;
    data.quantities.forEach(q => {
      if (q.negative) negativeNotes[q.name] = q.negative;
      if (q.senses) senseWords[q.name] = q.senses;
    });
    const panels = data.panels.map(name => document.getElementById("panel-" + name));
    const cells = Array.from(document.querySelectorAll("#readings tbody td.reading"));
    const planCells = Array.from(document.querySelectorAll("#readings tbody td.plan-reading"));
    const tolerances = Array.from(document.querySelectorAll("#readings tbody td.tolerance"));
    const verdicts = Array.from(document.querySelectorAll("#readings tbody td.verdict"));
    const answers = Array.from(document.querySelectorAll("#readings tbody input.answer"));
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
        cells[i].textContent = fmt(exact, 4);
        planCells[i].textContent = fmt(plan, 4);
        const question = questionOf(frame, q.name);
        tolerances[i].textContent = question ? "± " + fmt(question.tolerance, 3) + " " + question.unit : "—";
        verdicts[i].textContent = "";
        verdicts[i].className = "verdict";
      });
      const angle = data.angles[frame];
      cursors.forEach((cursor, c) => {
        if (!cursor) return;
        const [x0, x1] = data.charts[c];
        const x = a1 === a0 ? x0 : x0 + (angle - a0) / (a1 - a0) * (x1 - x0);
        cursor.setAttribute("x1", x); cursor.setAttribute("x2", x);
      });
      document.getElementById("angle-value").textContent = angle + "°";
      wb.frame = frame;
      wb.step = null;
      document.getElementById("step-text").textContent = "";
      document.getElementById("step-number").textContent = "";
      document.getElementById("equations").textContent = "";
      // other parts of the page (the drawing mode) follow the frame: part of the switch
      document.dispatchEvent(new CustomEvent("workbook:frame", {detail: {frame: frame}}));
      void document.body.offsetHeight;  // lay the page out: part of the switch
      const spent = performance.now() - t0;
      wb.switchTimes.push(spent);
      document.getElementById("switch-time").textContent = spent.toFixed(1) + " ms";
      prepareNeighbours(frame);
    }
    wb.show = show;
    wb.showAngle = angle => { slider.value = angle; show(stepOf(Number(angle))); };
    slider.addEventListener("input", () => show(stepOf(Number(slider.value))));

    let timer = null;
    const play = document.getElementById("play");
    play.addEventListener("click", () => {
      if (timer) { clearInterval(timer); timer = null; play.textContent = "play"; return; }
      play.textContent = "pause";
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
        document.getElementById("step-text").textContent = "no " + plan + " plan at this angle";
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
        "step " + (number + 1) + " of " + steps.length;
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

    // practice mode: readings hidden, answers graded against the key of this angle
    document.getElementById("practice").addEventListener("change", event => {
      document.body.classList.toggle("practising", event.target.checked);
    });
    function check() {
      const results = {};
      answers.forEach((input, i) => {
        const name = input.dataset.answer;
        const question = questionOf(wb.frame, name);
        if (!question) { verdicts[i].textContent = "not graded at this angle"; return; }
        const result = grade(question, input.value);
        results[name] = result;
        verdicts[i].textContent = wb.concealed(name) ? result.hint : result.feedback;
        verdicts[i].className = "verdict " + (result.correct ? "correct" : "wrong");
        verdicts[i].dataset.correct = String(result.correct);
      });
      wb.results = results;
      return results;
    }
    wb.check = check;
    document.getElementById("check").addEventListener("click", check);

    // other parts of the page (the drawing mode) start from the loaded data
    document.dispatchEvent(new CustomEvent("workbook:load", {detail: wb}));
    show(stepOf(Number(slider.value)));  // the exercise's own angle
    status.textContent = "";
    wb.ready = true;
  }).catch(error => {
    status.textContent = "this page needs a browser with DecompressionStream: " + error;
    console.error(error);
  });
})();
