"use strict";
// The workbook's drawing mode (see docs/workbook-drawing.md): the student draws the velocity
// and the acceleration plan of the current angle on a millimetre grid; "check" grades every
// point within its own tolerance disc and names the known mistake whose position of the point
// it lies in. Everything it compares against was computed in Python (the answer key of the
// angle: planmethod.grading.plan_points.drawing_frame); nothing here computes mechanics.
(function () {
  const PLANS = ["velocity", "acceleration"];
  const ZOOMS = [4, 5, 6, 8, 10, 12, 16, 20, 24, 32];   // CSS px per drawing millimetre
  const NUDGE_MM = 0.5, FINE_NUDGE_MM = 0.1;             // an arrow key; Shift + an arrow key
  const COARSE_NUDGE_MM = 5;                             // Control + an arrow key
  const MARK_PX = 5;          // a press this near a placed point's centre is on its mark
  const GRAB_PX = 8;          // with Alt, a press this near a placed point grabs it
  const draw = {results: {}, planMistakes: {}, checkTimes: [], tool: {}, selected: {}, armed: {},
                revealed: {}, shownPlan: {}, frame: -1, zoom: 6};
  let wb = null, meta = null, store = null, drag = null;
  // the page's words (render/page_rules.py): every sentence here is a template filled
  const say = (id, fields) => wb.rules.words.say(id, fields);

  const element = id => document.getElementById(id);
  const round2 = value => Math.round(value * 100) / 100;
  const nameOf = label => (meta.names[label] || label);
  // a point's name typeset as the course writes it (meta.runs: planmethod.render.labels.
  // label_runs): its main letter, then its subscripts — digits right after it as subscript
  // digits (b₃), anything else lowered and smaller (n with CB below, k with B₃ below), never
  // an underscore
  const SUB_DIGITS = "₀₁₂₃₄₅₆₇₈₉";
  const isSub = kind => kind === "sub" || kind === "upright";
  function runsOf(label) { return meta.runs[label] || [[nameOf(label), "main"]]; }
  // the runs as pieces [text, lowered, upright]: a subscript of digits only is set as
  // subscript digits on the line unless it follows a lowered piece, where it joins it
  function pieces(label) {
    const out = [];
    runsOf(label).forEach(([text, kind]) => {
      const last = out[out.length - 1];
      if (!isSub(kind)) out.push([text, false, false]);
      else if (/^[0-9]+$/.test(text) && !(last && last[1]))
        out.push([text.replace(/[0-9]/g, digit => SUB_DIGITS[Number(digit)]), false, false]);
      else out.push([text, true, kind === "upright"]);
    });
    return out;
  }
  function typesetHtml(label) {
    const out = document.createElement("span");
    out.className = "course-name";
    pieces(label).forEach(([text, lowered, upright]) => {
      if (!lowered) { out.append(text); return; }
      const sub = document.createElement("sub");
      sub.textContent = text;
      if (upright) sub.className = "upright";
      out.append(sub);
    });
    return out;
  }
  function typesetSvg(node, label, size) {
    let down = false;
    pieces(label).forEach(([text, lowered, upright]) => {
      const span = make("tspan", {}, node);
      if (lowered !== down) span.setAttribute("dy", (lowered ? 0.3 : -0.3) * size);
      if (lowered) span.setAttribute("font-size", 0.72 * size);
      if (upright) span.setAttribute("font-style", "normal");
      span.textContent = text;
      down = lowered;
    });
  }
  const planBox = plan => document.querySelector('.draw-plan[data-plan="' + plan + '"]');
  const svgOf = plan => document.querySelector('svg[data-draw="' + plan + '"]');
  function frameData(plan) {
    const frame = wb.data.frames[draw.frame];
    return frame && frame.draw ? frame.draw[plan] : undefined;
  }
  function notice(text) { element("draw-notice").textContent = text; }

  // -- keeping the drawing: localStorage, one record per exercise (its title and digest: two
  // variants of a template share a title) and angle --------------------------------------
  const STORE_PREFIX = "planmethod-drawing:";
  function storageKey() {
    return STORE_PREFIX + meta.title + ":" + meta.exercise + ":" + wb.data.angles[draw.frame];
  }
  // a drawing kept at this angle by the page of another exercise with this title
  function keptByAnother() {
    const head = STORE_PREFIX + meta.title + ":", tail = ":" + wb.data.angles[draw.frame];
    try {
      for (let k = 0; k < window.localStorage.length; k++) {
        const key = window.localStorage.key(k);
        if (key.startsWith(head) && key.endsWith(tail) && key !== storageKey() &&
            /^[0-9a-f]{16}$/.test(key.slice(head.length, key.length - tail.length))) return true;
      }
    } catch (error) {
      return false;
    }
    return false;
  }
  function emptyRecord() {
    const plans = {};
    PLANS.forEach(plan => { plans[plan] = {points: {}, lines: []}; });
    return {format: meta.format, version: 1, title: meta.title, exercise: meta.exercise,
            angle: wb.data.angles[draw.frame], plans: plans, help: {construction: {}, shown: {}},
            checked: []};
  }
  function restore() {
    let record = null;
    try {
      const text = window.localStorage.getItem(storageKey());
      if (text !== null) record = JSON.parse(text);
    } catch (error) {
      notice(say("kept_unreadable", {error: String(error)}));
      return emptyRecord();
    }
    if (record === null) {
      if (keptByAnother())
        notice(say("kept_by_another", {title: meta.title, phi: meta.phi,
                                       angle: wb.data.angles[draw.frame]}));
      return emptyRecord();
    }
    if (!record || record.format !== meta.format || record.exercise !== meta.exercise ||
        record.title !== meta.title || !record.plans) {
      notice(say("kept_for_another", {title: meta.title, phi: meta.phi,
                                      angle: wb.data.angles[draw.frame]}));
      return emptyRecord();
    }
    const fresh = emptyRecord();
    PLANS.forEach(plan => {
      const kept = record.plans[plan] || {};
      const points = {};
      Object.entries(kept.points || {}).forEach(([label, xy]) => {
        if (Array.isArray(xy) && xy.length === 2 && xy.every(Number.isFinite)) points[label] = xy;
      });
      fresh.plans[plan] = {points: points,
                           lines: (kept.lines || []).filter(line => line && Array.isArray(line.at))};
      // what the student asked to see of the plan, and whether it was checked
      const help = record.help || {};
      const step = (help.construction || {})[plan];
      if (Number.isInteger(step) && step >= 0) fresh.help.construction[plan] = step;
      if ((help.shown || {})[plan] === true) fresh.help.shown[plan] = true;
      if (Array.isArray(record.checked) && record.checked.includes(plan)) fresh.checked.push(plan);
    });
    return fresh;
  }
  function save() {
    try {
      window.localStorage.setItem(storageKey(), JSON.stringify(store));
    } catch (error) {
      notice(say("not_kept", {error: String(error)}));
    }
  }

  // -- the sheet: grid, pole, lines, points ---------------------------------------------------
  // a new SVG element inside ``parent`` (in its namespace: the page names no address)
  function make(name, attributes, parent) {
    const node = document.createElementNS(parent.namespaceURI, name);
    Object.entries(attributes || {}).forEach(([key, value]) => node.setAttribute(key, value));
    parent.appendChild(node);
    return node;
  }
  function sheet(plan) {
    const svg = svgOf(plan);
    const [left, bottom, right, top] = meta.extents[plan];
    svg.setAttribute("viewBox", [left, -top, right - left, top - bottom].join(" "));
    svg.style.width = (right - left) * draw.zoom + "px";
    svg.style.height = (top - bottom) * draw.zoom + "px";
    svg.replaceChildren();
    // everything drawn in one group: the loupe shows a copy of it, magnified
    const content = make("g", {"class": "content"}, svg);
    const grid = make("g", {"class": "grid"}, content);
    let minor = "", major = "";
    for (let x = Math.ceil(left); x <= right; x++) {
      const path = "M" + x + " " + (-top) + "V" + (-bottom);
      if (x % 10 === 0) major += path; else minor += path;
    }
    for (let y = Math.ceil(bottom); y <= top; y++) {
      const path = "M" + left + " " + (-y) + "H" + right;
      if (y % 10 === 0) major += path; else minor += path;
    }
    make("path", {d: minor, "class": "minor", "vector-effect": "non-scaling-stroke"}, grid);
    make("path", {d: major, "class": "major", "vector-effect": "non-scaling-stroke"}, grid);
    make("g", {"class": "lines"}, content);
    make("g", {"class": "right-plan"}, content);
    make("g", {"class": "points"}, content);
    render(plan);
  }
  // a point's mark and its name (a point id typeset, or the pole's letter)
  function marker(parent, x, y, label, css, attributes) {
    const group = make("g", Object.assign({"class": css}, attributes || {}), parent);
    make("circle", {cx: x, cy: -y, r: 3.5 / draw.zoom}, group);
    const size = 14 / draw.zoom;
    const text = make("text", {x: x + 5 / draw.zoom, y: -y - 5 / draw.zoom, "font-size": size},
                      group);
    if (label in meta.names) typesetSvg(text, label, size); else text.textContent = label;
    return group;
  }
  function render(plan) {
    const svg = svgOf(plan);
    if (!store || !svg.querySelector("g.points")) return;
    const drawn = store.plans[plan];
    const frame = frameData(plan);
    const lines = svg.querySelector("g.lines");
    lines.replaceChildren();
    drawn.lines.forEach((line, index) => {
      const at = line.through && drawn.points[line.through] ? drawn.points[line.through] :
        (line.through === meta.poles[plan] ? [0, 0] : line.at);
      const angle = line.direction_deg * Math.PI / 180, reach = 5000;
      const dx = Math.cos(angle) * reach, dy = Math.sin(angle) * reach;
      make("line", {x1: at[0] - dx, y1: -(at[1] - dy), x2: at[0] + dx, y2: -(at[1] + dy),
                    "class": "construction", "data-line": plan + ":" + index,
                    "vector-effect": "non-scaling-stroke"}, lines);
    });
    const right = svg.querySelector("g.right-plan");
    right.replaceChildren();
    if (draw.shownPlan[plan] && frame) {
      Object.entries(frame.points).forEach(([label, [x, y]]) =>
        marker(right, x, y, label, "right-point"));
    }
    const points = svg.querySelector("g.points");
    points.replaceChildren();
    marker(points, 0, 0, meta.poles[plan], "pole");
    Object.entries(drawn.points).forEach(([label, [x, y]]) => {
      const result = (draw.results[plan] || {})[label];
      const css = "placed" + (label === draw.selected[plan] ? " selected" : "") +
        (result ? (result.ok ? " ok" : " off") : "");
      marker(points, x, y, label, css,
             {"data-point": plan + ":" + label, "data-x": x, "data-y": y});
    });
    planBox(plan).querySelectorAll("[data-place]").forEach(button => {
      const label = button.dataset.place.slice(plan.length + 1);
      button.classList.toggle("selected", label === draw.selected[plan]);
      button.setAttribute("aria-pressed", String(label === draw.selected[plan]));
      button.classList.toggle("placed", label in drawn.points);
    });
  }

  // -- the list of points of the angle --------------------------------------------------------
  function buildList(plan) {
    const box = planBox(plan);
    const list = box.querySelector(".draw-points");
    list.replaceChildren();
    const frame = frameData(plan);
    box.classList.toggle("absent", !frame);
    if (!frame) return;
    const scale = box.querySelector(".draw-scale");
    scale.textContent = say("sheet_scale", {pole: meta.poles[plan], symbol: meta.scales[plan],
                                            scale: frame.scale, unit: frame.unit});
    Object.keys(frame.points).forEach(label => {
      const item = document.createElement("li");
      const button = document.createElement("button");
      button.type = "button";
      button.dataset.place = plan + ":" + label;
      button.append(typesetHtml(label));
      button.title = say(frame.required.includes(label) ? "plan_point" : "construction_point");
      button.addEventListener("click", () => select(plan, label));
      const verdict = document.createElement("span");
      verdict.className = "draw-verdict";
      verdict.dataset.verdictFor = plan + ":" + label;
      item.append(button, " ", verdict);
      list.appendChild(item);
    });
    const first = Object.keys(frame.points).find(label => !(label in store.plans[plan].points));
    draw.selected[plan] = first === undefined ? Object.keys(frame.points)[0] : first;
    draw.armed[plan] = first !== undefined;
  }
  function select(plan, label) {
    draw.selected[plan] = label;
    draw.armed[plan] = true;
    setTool(plan, "point");
    render(plan);
  }
  function nextUnplaced(plan) {
    const frame = frameData(plan);
    const labels = Object.keys(frame.points);
    const start = labels.indexOf(draw.selected[plan]);
    for (let k = 1; k <= labels.length; k++) {
      const label = labels[(start + k) % labels.length];
      if (!(label in store.plans[plan].points)) return label;
    }
    return null;
  }
  // a point moved: its verdict, and the plan's summary of the last check, no longer hold
  function clearVerdict(plan, label) {
    const cell = document.querySelector('[data-verdict-for="' + plan + ":" + label + '"]');
    if (cell) { cell.textContent = ""; delete cell.dataset.ok; }
    if (draw.results[plan]) delete draw.results[plan][label];
    draw.planMistakes[plan] = [];
    store.checked = store.checked.filter(one => one !== plan);
    element("draw-status").textContent = "";
    const summary = planBox(plan).querySelector(".draw-summary");
    if (summary.textContent) summary.textContent = say("moved");
  }
  function setTool(plan, tool) {
    draw.tool[plan] = tool;
    planBox(plan).querySelectorAll("[data-tool]").forEach(button =>
      button.setAttribute("aria-pressed", String(button.dataset.tool === tool)));
  }

  // -- placing, dragging, nudging -------------------------------------------------------------
  function planPoint(plan, event) {
    const svg = svgOf(plan);
    const point = svg.createSVGPoint();
    point.x = event.clientX; point.y = event.clientY;
    const user = point.matrixTransform(svg.getScreenCTM().inverse());
    return [user.x, -user.y];
  }
  function nearest(plan, xy, reachPx) {
    const reach = reachPx / draw.zoom;
    let best = null, distance = reach;
    const candidates = Object.entries(store.plans[plan].points);
    candidates.push([meta.poles[plan], [0, 0]]);
    candidates.forEach(([label, [x, y]]) => {
      const d = Math.hypot(x - xy[0], y - xy[1]);
      if (d <= distance) { best = label; distance = d; }
    });
    return best;
  }
  function place(plan, label, x, y) {
    store.plans[plan].points[label] = [round2(x), round2(y)];
    clearVerdict(plan, label);
    save();
    render(plan);
  }
  // -- a finger: the loupe shows the point under it magnified above it; two fingers zoom the
  // sheet (to the zoom steps) and move it --------------------------------------------------
  const LOUPE_PX = 120, LOUPE_LIFT_PX = 100, LOUPE_TIMES = 3;
  const fingers = new Map();   // pointer id -> [clientX, clientY] of the fingers on a sheet
  let pinch = null;
  function loupe(plan, event, xy) {
    const box = document.querySelector(".draw-loupe");
    if (!xy) { box.classList.remove("on"); box.replaceChildren(); return; }
    // a copy of the sheet's drawing as it is now (the page's style reaches a copy, not a
    // <use> of it), without the names the page and its tests find points by
    const view = document.createElementNS(svgOf(plan).namespaceURI, "svg");
    const copy = svgOf(plan).querySelector("g.content").cloneNode(true);
    copy.removeAttribute("id");
    copy.querySelectorAll("[data-point]").forEach(node => node.removeAttribute("data-point"));
    view.appendChild(copy);
    make("path", {"class": "cross"}, view);
    box.replaceChildren(view);
    const half = LOUPE_PX / 2 / (draw.zoom * LOUPE_TIMES);
    view.setAttribute("viewBox", [xy[0] - half, -xy[1] - half, 2 * half, 2 * half].join(" "));
    view.querySelector(".cross").setAttribute("d",
      "M" + (xy[0] - half) + " " + (-xy[1]) + "H" + (xy[0] + half) +
      "M" + xy[0] + " " + (-xy[1] - half) + "V" + (-xy[1] + half));
    const above = event.clientY - LOUPE_LIFT_PX - LOUPE_PX / 2;
    box.style.left = Math.max(0, Math.min(window.innerWidth - LOUPE_PX,
                                          event.clientX - LOUPE_PX / 2)) + "px";
    box.style.top = (above >= 0 ? above : event.clientY + LOUPE_LIFT_PX - LOUPE_PX / 2) + "px";
    box.classList.add("on");
  }
  const spread = () => {
    const [a, b] = Array.from(fingers.values());
    return [Math.hypot(a[0] - b[0], a[1] - b[1]), (a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
  };
  function startPinch(plan) {
    // the first finger's point goes back where it was: two fingers zoom, they place nothing
    if (drag && drag.plan === plan && drag.label !== undefined) {
      const points = store.plans[plan].points;
      if (drag.before) points[drag.label] = drag.before; else delete points[drag.label];
      save();
      render(plan);
    }
    drag = null;
    loupe(plan, null, null);
    const [distance, x, y] = spread();
    pinch = {plan: plan, distance: distance, zoom: draw.zoom, x: x, y: y};
  }
  function movePinch(plan) {
    const [distance, x, y] = spread();
    const wanted = pinch.zoom * distance / (pinch.distance || 1);
    const zoom = ZOOMS.reduce((best, one) =>
      Math.abs(Math.log(one / wanted)) < Math.abs(Math.log(best / wanted)) ? one : best);
    if (zoom !== draw.zoom) setZoom(zoom);
    const scroller = svgOf(plan).parentNode;
    scroller.scrollLeft -= x - pinch.x;
    scroller.scrollTop -= y - pinch.y;
    pinch.x = x; pinch.y = y;
  }

  function onPointerDown(plan, event) {
    if (event.pointerType === "touch") {
      fingers.set(event.pointerId, [event.clientX, event.clientY]);
      if (fingers.size === 2) { startPinch(plan); event.preventDefault(); return; }
      if (fingers.size > 2) return;
    }
    if (event.button !== 0 || !frameData(plan)) return;
    const xy = planPoint(plan, event);
    svgOf(plan).focus({preventScroll: true});
    if (draw.tool[plan] === "line") {
      const through = nearest(plan, xy, 10);
      const at = through === meta.poles[plan] ? [0, 0] :
        (through ? store.plans[plan].points[through] : [round2(xy[0]), round2(xy[1])]);
      drag = {plan: plan, line: {through: through, at: at.slice(), direction_deg: 0},
              start: xy};
    } else {
      // the armed point (chosen by its button, or the next one not yet placed) goes where the
      // student clicks, however near another point (points may coincide); with no point
      // armed a press on a placed point's mark drags it, and with Alt a press near one does
      const label = draw.selected[plan];
      const hit = nearest(plan, xy, event.altKey ? GRAB_PX : MARK_PX);
      if (draw.armed[plan] && label !== undefined && !event.altKey) {
        const before = store.plans[plan].points[label];
        place(plan, label, xy[0], xy[1]);
        drag = {plan: plan, label: label, moved: false, placed: true, before: before};
      } else if (hit && hit !== meta.poles[plan]) {
        draw.selected[plan] = hit;
        draw.armed[plan] = false;
        drag = {plan: plan, label: hit, moved: false, placed: false};
        render(plan);
      } else {
        return;
      }
    }
    if (event.pointerType !== "mouse" && drag && drag.label !== undefined)
      loupe(plan, event, store.plans[plan].points[drag.label]);
    svgOf(plan).setPointerCapture(event.pointerId);
    event.preventDefault();
  }
  function onPointerMove(plan, event) {
    if (fingers.has(event.pointerId)) fingers.set(event.pointerId, [event.clientX, event.clientY]);
    if (pinch && pinch.plan === plan && fingers.size === 2) { movePinch(plan); return; }
    if (!drag || drag.plan !== plan) return;
    const xy = planPoint(plan, event);
    if (drag.line) {
      const at = drag.line.at;
      drag.line.direction_deg = Math.round(
        Math.atan2(xy[1] - at[1], xy[0] - at[0]) * 1800 / Math.PI) / 10;
      drag.length = Math.hypot(xy[0] - at[0], xy[1] - at[1]) * draw.zoom;
      let preview = svgOf(plan).querySelector("line.preview");
      if (!preview) {
        preview = make("line", {"class": "construction", "vector-effect": "non-scaling-stroke"},
                       svgOf(plan).querySelector("g.lines"));
        preview.classList.add("preview");
      }
      preview.setAttribute("x1", at[0]); preview.setAttribute("y1", -at[1]);
      preview.setAttribute("x2", xy[0]); preview.setAttribute("y2", -xy[1]);
    } else {
      drag.moved = true;
      store.plans[plan].points[drag.label] = [round2(xy[0]), round2(xy[1])];
      clearVerdict(plan, drag.label);
      render(plan);
      if (event.pointerType !== "mouse") loupe(plan, event, store.plans[plan].points[drag.label]);
    }
  }
  function onPointerUp(plan, event) {
    fingers.delete(event.pointerId);
    if (fingers.size < 2) pinch = null;
    loupe(plan, null, null);
    if (!drag || drag.plan !== plan) return;
    const done = drag;
    drag = null;
    if (done.line) {
      if ((done.length || 0) >= 6) store.plans[plan].lines.push(done.line);
      render(plan);
    } else if (done.placed) {
      const next = nextUnplaced(plan);
      draw.armed[plan] = next !== null;
      if (next !== null) draw.selected[plan] = next;
      render(plan);
    }
    save();
  }
  // the middle of the part of a plan's sheet in view (mm, y up)
  function visibleMiddle(plan) {
    const scroller = svgOf(plan).parentNode.getBoundingClientRect();
    const bar = element("controls").getBoundingClientRect().bottom;
    const top = Math.max(scroller.top, bar), bottom = Math.min(scroller.bottom, window.innerHeight);
    return planPoint(plan, {clientX: (scroller.left + scroller.right) / 2,
                            clientY: bottom > top ? (top + bottom) / 2 :
                              (scroller.top + scroller.bottom) / 2});
  }
  // the line tool from the keyboard: Enter draws a line through the chosen point (the pole
  // when it is not placed) at 0°, the arrow keys turn the last line 1° (Shift 0.1°, Control
  // 15°): counter-clockwise with → and ↑. Whether the key was the tool's.
  function lineKey(plan, event) {
    const drawn = store.plans[plan];
    const turns = {ArrowRight: 1, ArrowUp: 1, ArrowLeft: -1, ArrowDown: -1};
    if (event.key === "Enter" || event.key === " ") {
      const label = draw.selected[plan];
      const through = label in drawn.points ? label : meta.poles[plan];
      const at = through === meta.poles[plan] ? [0, 0] : drawn.points[through];
      drawn.lines.push({through: through, at: at.slice(), direction_deg: 0});
    } else if (event.key in turns && drawn.lines.length) {
      const line = drawn.lines[drawn.lines.length - 1];
      const step = event.ctrlKey || event.metaKey ? 15 : event.shiftKey ? 0.1 : 1;
      line.direction_deg = Math.round(((line.direction_deg + turns[event.key] * step) % 360) *
                                      10) / 10;
    } else {
      return false;
    }
    save();
    render(plan);
    return true;
  }
  function onKey(plan, event) {
    const label = draw.selected[plan];
    const points = store.plans[plan].points;
    const steps = {ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1]};
    const onSheet = event.target === svgOf(plan);
    if (onSheet && draw.tool[plan] === "line" && lineKey(plan, event)) {
      event.preventDefault();
    } else if (onSheet && (event.key === "Enter" || event.key === " ") && label !== undefined &&
        frameData(plan)) {
      // the chosen point at the middle of the sheet in view, then the arrow keys move it
      const [x, y] = visibleMiddle(plan);
      place(plan, label, x, y);
      event.preventDefault();
    } else if (onSheet && (event.key === "+" || event.key === "=" || event.key === "-")) {
      const at = ZOOMS.indexOf(draw.zoom) + (event.key === "-" ? -1 : 1);
      setZoom(ZOOMS[Math.max(0, Math.min(ZOOMS.length - 1, at))]);
      svgOf(plan).focus({preventScroll: true});
      event.preventDefault();
    } else if (event.key in steps && label in points &&
               (onSheet || event.target.dataset.place !== undefined)) {
      const [dx, dy] = steps[event.key];
      const [x, y] = points[label];
      const nudge = event.ctrlKey || event.metaKey ? COARSE_NUDGE_MM :
        event.shiftKey ? FINE_NUDGE_MM : NUDGE_MM;
      place(plan, label, x + dx * nudge, y + dy * nudge);
      event.preventDefault();
    } else if ((event.key === "Delete" || event.key === "Backspace") && label in points &&
               event.target.tagName !== "INPUT") {
      delete points[label];
      clearVerdict(plan, label);
      save();
      render(plan);
      event.preventDefault();
    }
  }

  // -- checking -------------------------------------------------------------------------------
  // each point as grade --drawing grades it (planmethod.grading.drawings, plan_points), in the
  // words of grading's rulebook render/page_rules.py sends: page_rules.js sheet
  function check(plan) {
    const t0 = performance.now();
    const frame = frameData(plan);
    const results = {};
    if (!frame) return results;
    const drawn = store.plans[plan].points, texts = Object.fromEntries(meta.mistakes);
    const mistakes = Object.fromEntries(Object.entries(frame.mistakes).map(
      ([label, candidates]) => [label, candidates.map(
        ([index, x, y]) => [meta.mistakes[index][0], x, y])]));
    const verdict = wb.rules.sheet(Object.assign({}, frame, {mistakes: mistakes}), drawn,
                                   meta.names, texts);
    Object.keys(frame.points).forEach(label => {
      results[label] = Object.assign({label: label}, verdict(label));
    });
    draw.results[plan] = results;
    Object.values(results).forEach(result => {
      const cell = document.querySelector('[data-verdict-for="' + plan + ":" + result.label + '"]');
      if (!cell) return;
      // the sentence with the point's name typeset in it (b₃, k with B₃ below)
      cell.innerHTML = wb.rules.words.html(result.message.id, result.message.fields,
                                           {point: typesetHtml(result.label).outerHTML});
      if (result.ok === null) delete cell.dataset.ok; else cell.dataset.ok = String(result.ok);
    });
    const required = Object.values(results).filter(result => result.required);
    const common = wb.rules.commonMistakes(Object.values(results).filter(
      result => result.graded && result.placed && result.ok === false)
      .map(result => result.mistakes));
    draw.planMistakes[plan] = common;
    planBox(plan).querySelector(".draw-summary").innerHTML = wb.rules.words.formula(
      wb.rules.planSummary(plan, required.filter(result => result.ok).length, required.length,
                           common, texts));
    if (!store.checked.includes(plan)) { store.checked.push(plan); save(); }
    sayNext();
    render(plan);
    void document.body.offsetHeight;   // the verdicts laid out: part of the check
    draw.checkTimes.push(performance.now() - t0);
    return results;
  }

  // what comes next: after a right velocity plan the acceleration plan, after both another
  // angle
  function planRight(plan) {
    const results = Object.values(draw.results[plan] || {}).filter(result => result.required);
    return results.length > 0 && results.every(result => result.ok);
  }
  function sayNext() {
    const drawn = PLANS.filter(plan => frameData(plan));
    let said = "";
    if (drawn.every(planRight)) said = say("plans_right", {phi: meta.phi,
                                                         angle: wb.data.angles[draw.frame]});
    else if (planRight("velocity") && frameData("acceleration")) said = say("next_acceleration");
    element("draw-status").textContent = said;
  }

  // -- what stays hidden while drawing: every value read off a plan (the readings, the curves,
  // a radius of curvature on the mechanism, the right value in a typed answer's verdict)
  // until the student asks to see that plan ----------------------------------------------------
  const drawingOn = () => document.body.classList.contains("drawing");
  function concealed(plan) { return drawingOn() && !!plan && !draw.shownPlan[plan]; }
  function conceal() {
    PLANS.forEach(plan => document.body.classList.toggle("shown-" + plan, !!draw.shownPlan[plan]));
    document.querySelectorAll("#readings tbody tr").forEach(row =>
      row.classList.toggle("concealed", concealed(row.dataset.plan)));
    document.querySelectorAll("#charts .chart").forEach(chart =>
      chart.classList.toggle("concealed", (chart.dataset.plans || "").split(" ").some(concealed)));
  }

  // -- help: the construction step by step, the right plan on request ------------------------
  function panelOf(plan) { return element("panel-" + plan); }
  function showStep(plan) {
    const steps = wb.data.frames[draw.frame].steps[plan] || [];
    if (!steps.length || !panelOf(plan)) return;
    const next = Math.min(steps.length - 1, (draw.revealed[plan] ?? -1) + 1);
    draw.revealed[plan] = next;
    store.help.construction[plan] = next;
    save();
    // the plan's points show as its steps reach them, not all at once
    panelOf(plan).classList.add("revealed", "stepwise");
    element("step-plan").value = plan;
    wb.playStep(next);
    // the step's sentence is typeset HTML (render/workbook.py formula_html)
    planBox(plan).querySelector(".draw-step").innerHTML = wb.rules.words.html(
      "step_sentence", {number: next + 1, count: steps.length, sentence: ""},
      {sentence: wb.data.strings[steps[next][1]]});
  }
  function showPlan(plan) {
    draw.shownPlan[plan] = true;
    store.help.shown[plan] = true;
    save();
    conceal();
    const panel = panelOf(plan);
    if (panel) {
      panel.classList.add("revealed");
      panel.classList.remove("stepwise");
      panel.querySelectorAll(".step-hidden, .step-current").forEach(node =>
        node.classList.remove("step-hidden", "step-current"));
    }
    render(plan);
  }

  // -- the drawing as the JSON planmethod grade --drawing reads -------------------------------
  function exported(plan) {
    const points = {};
    points[meta.poles[plan]] = [0, 0];
    Object.assign(points, store.plans[plan].points);
    return {format: meta.format, version: 1, title: meta.title, exercise: meta.exercise,
            angle: wb.data.angles[draw.frame], plan: plan, points: points,
            lines: store.plans[plan].lines, revealed: revealed(plan)};
  }
  // what the student asked to see at the drawing's angle: the answers shown (their question
  // ids), and of this plan its construction (steps shown) and the plan itself
  function revealed(plan) {
    const out = wb.revealedAt(wb.data.angles[draw.frame]);
    if (draw.revealed[plan] !== undefined) out.push("construction:" + plan);
    if (draw.shownPlan[plan]) out.push("plan:" + plan);
    return out;
  }
  function download(plan) {
    const text = JSON.stringify(exported(plan), null, 1) + "\n";
    const link = document.createElement("a");
    link.href = URL.createObjectURL(new Blob([text], {type: "application/json"}));
    const slug = meta.title.toLowerCase().replace(/[^a-z0-9]+/g, "-").replace(/^-|-$/g, "");
    link.download = (slug || "plan") + "-" + plan + "-" + wb.data.angles[draw.frame] + "deg.json";
    document.body.appendChild(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(link.href), 1000);
  }

  // -- the page's frames ----------------------------------------------------------------------
  function onFrame(frame) {
    draw.frame = frame;
    draw.results = {};
    draw.revealed = {};
    draw.shownPlan = {};
    notice("");
    element("draw-status").textContent = "";
    element("draw-kept").textContent = "";
    conceal();
    store = restore();
    PLANS.forEach(plan => {
      if (!planBox(plan)) return;
      if (panelOf(plan)) panelOf(plan).classList.remove("revealed", "stepwise");
      planBox(plan).querySelector(".draw-summary").textContent = "";
      planBox(plan).querySelector(".draw-step").textContent = "";
      buildList(plan);
      render(plan);
    });
    reopen();
  }
  // a drawing kept at this angle as it was left: what was asked to be seen, the verdicts of
  // the plans checked, and a word of which angle it was drawn at
  function reopen() {
    const kept = PLANS.filter(plan => planBox(plan) && frameData(plan));
    kept.forEach(plan => {
      if (store.help.shown[plan]) showPlan(plan);
      const step = store.help.construction[plan];
      if (step !== undefined) {
        draw.revealed[plan] = step - 1;
        showStep(plan);
      }
    });
    const checked = kept.filter(plan => store.checked.includes(plan));
    checked.forEach(check);
    const placed = kept.some(plan => Object.keys(store.plans[plan].points).length);
    element("draw-kept").textContent = placed ? say("kept_restored", {
      phi: meta.phi, angle: wb.data.angles[draw.frame]}) : "";
  }
  function setZoom(zoom) {
    draw.zoom = zoom;
    element("draw-zoom").textContent = say("zoom", {zoom: zoom});
    PLANS.forEach(plan => { if (planBox(plan)) sheet(plan); });
  }
  function start(workbook) {
    wb = workbook;
    meta = wb.data.draw;
    if (!meta) return;
    const widest = Math.max(...PLANS.filter(plan => meta.extents[plan]).map(
      plan => meta.extents[plan][2] - meta.extents[plan][0]));
    draw.zoom = ZOOMS.filter(zoom => zoom === ZOOMS[0] || zoom * widest <= 640).pop();
    // the zoom reaches a size where every tolerance disc of the page is 6 px across or more
    let smallest = Infinity;
    wb.data.frames.forEach(frame => Object.values(frame.draw || {}).forEach(entry =>
      Object.values(entry.points).forEach(point => { smallest = Math.min(smallest, point[2]); })));
    draw.smallestRadius = Number.isFinite(smallest) ? smallest : null;
    while (draw.smallestRadius && ZOOMS[ZOOMS.length - 1] * 2 * draw.smallestRadius < 6)
      ZOOMS.push(Math.ceil(ZOOMS[ZOOMS.length - 1] * 1.5));
    draw.zooms = ZOOMS;
    PLANS.forEach(plan => {
      const box = planBox(plan);
      if (!box) return;
      const svg = svgOf(plan);
      draw.tool[plan] = "point";
      svg.addEventListener("pointerdown", event => onPointerDown(plan, event));
      svg.addEventListener("pointermove", event => onPointerMove(plan, event));
      svg.addEventListener("pointerup", event => onPointerUp(plan, event));
      svg.addEventListener("pointercancel", event => onPointerUp(plan, event));
      box.addEventListener("keydown", event => onKey(plan, event));
      box.querySelectorAll("[data-tool]").forEach(button =>
        button.addEventListener("click", () => setTool(plan, button.dataset.tool)));
      box.querySelector("[data-check]").addEventListener("click", () => check(plan));
      box.querySelector("[data-download]").addEventListener("click", () => download(plan));
      box.querySelector("[data-show-step]").addEventListener("click", () => showStep(plan));
      box.querySelector("[data-show-plan]").addEventListener("click", () => showPlan(plan));
      box.querySelector("[data-unline]").addEventListener("click", () => {
        store.plans[plan].lines.pop(); save(); render(plan);
      });
      box.querySelector("[data-clear]").addEventListener("click", () => {
        store.plans[plan] = {points: {}, lines: []};
        draw.results[plan] = {};
        draw.planMistakes[plan] = [];
        planBox(plan).querySelector(".draw-summary").textContent = "";
        save();
        buildList(plan);
        render(plan);
      });
    });
    document.addEventListener("workbook:mode", conceal);
    const planOf = Object.fromEntries(wb.data.quantities.map(q => [q.name, q.plan]));
    wb.concealed = name => concealed(planOf[name]);
    wb.planShown = name => drawingOn() && !!planOf[name] && !!draw.shownPlan[planOf[name]];
    document.querySelectorAll("[data-zoom]").forEach(button => button.addEventListener(
      "click", () => {
        const at = ZOOMS.indexOf(draw.zoom) + Number(button.dataset.zoom);
        setZoom(ZOOMS[Math.max(0, Math.min(ZOOMS.length - 1, at))]);
      }));
    wb.draw = Object.assign(draw, {check: check, place: place, exported: exported,
                                   select: select, showStep: showStep, showPlan: showPlan,
                                   drawing: plan => store.plans[plan]});
    setZoom(draw.zoom);
  }
  document.addEventListener("workbook:load", event => start(event.detail));
  document.addEventListener("workbook:frame", event => { if (meta) onFrame(event.detail.frame); });
})();
