"use strict";
// The studio's page: an exercise drawn by clicks, solved by the server at every change (see
// docs/studio.md). The page edits the exercise's tables as drawn and sends them as data; the
// server writes the TOML (planmethod/studio/exercise_data.py) and answers with the report and
// the plans' drawings. Every sentence it shows is a template the server sent with the page
// (planmethod/studio/page.py), filled by page_words.js; studio_runs.js follows the long work
// (variants, export).
(() => {
const SVG = "http://www.w3.org/2000/svg";
const FRAME = "frame";
const $ = (id) => document.getElementById(id);
const words = window.planmethodWords.make(JSON.parse($("studio-words").textContent));
const say = words.say;
// what went wrong, in the course's words, by the kind the server names
const kindText = (kind) => say("kind_" + (["structure", "assembly", "toggle", "forces", "input",
  "exists", "refused", "internal"].includes(kind) ? kind : "input"));

// ---- the exercise, as drawn: the tables the server reads ----------------------------------
const studio = window.studio = {
  tables: emptyTables(), selected: null, mode: "move", building: [], sliderPoint: null,
  view: {cx: 0.12, cy: 0.02, scale: 1800}, timings: [], serverTimes: [], solves: 0,
  snap: {on: true, held: false}, askSymbols: {}, draftTimings: [], drafted: false,
  restMs: 250,   // a drag held still this long rests: solved in full
  report: null, ready: false, path: null, lastError: null,
  driveSymbols: {phi: "φ₁", omega: "ω₁", epsilon: "ε₁"},   // until a solve names them
};

function emptyTables() {
  return {title: say("untitled"),
          drive: {link: "", pivot: "", angle: 0, omega: 10, epsilon: 0},
          points: {}, links: {frame: []}, slide: [],
          plan: {crank_mm: 30, velocity_mm: 30, acceleration_mm: 30}};
}

function points() { return studio.tables.points; }
function links() { return studio.tables.links; }
function slides() { return studio.tables.slide || (studio.tables.slide = []); }
function linksOf(point) { return Object.keys(links()).filter((name) => links()[name].includes(point)); }
function isFixed(point) { return (links()[FRAME] || []).includes(point); }
function slideOfLink(link) { return slides().find((s) => s.link === link); }
function degrees(dx, dy) { return Math.atan2(dy, dx) * 180 / Math.PI; }

function nextPointName() {
  const used = new Set(Object.keys(points()));
  for (let digit = 0; digit < 100; digit++) {
    for (const letter of "ABCDEFGHIJKLMNOPQRSTUVWXYZ") {
      const name = digit ? letter + digit : letter;
      if (!used.has(name)) return name;
    }
  }
  throw new Error("too many points");
}

function uniqueLinkName(base) {
  let name = base.replace(/[^A-Za-z0-9_]/g, "_");
  if (!/^[A-Za-z_]/.test(name)) name = "L" + name;
  const lower = new Set(Object.keys(links()).map((n) => n.toLowerCase()));
  if (!lower.has(name.toLowerCase())) return name;
  for (let i = 2; ; i++) if (!lower.has((name + i).toLowerCase())) return name + i;
}

// the crank's pin: the first point of the drive link after its pivot
function drivePin() {
  const drive = studio.tables.drive;
  const members = links()[drive.link] || [];
  const chosen = studio.tables.plan && studio.tables.plan.scale_point;
  if (chosen && members.includes(chosen) && chosen !== drive.pivot) return chosen;
  return members.find((p) => p !== drive.pivot);
}

// what the drawing fixes: the drive angle from the crank, a moving guide's direction from its
// two points, a point sliding on a fixed guide on its line
function syncDrawing() {
  const drive = studio.tables.drive;
  const pin = drivePin();
  if (drive.link && drive.pivot && pin && points()[pin] && points()[drive.pivot]) {
    const [x0, y0] = points()[drive.pivot], [x1, y1] = points()[pin];
    if (x1 !== x0 || y1 !== y0) {
      const drawn = degrees(x1 - x0, y1 - y0);
      const previous = Number(drive.angle) || 0;
      const turned = drawn + 360 * Math.round((previous - drawn) / 360);
      // a crank turned to a typed angle comes back from the server within rounding of it:
      // keep the typed number (60, not 60.00000000000001) unless the crank was really moved
      if (Math.abs(turned - previous) > 1e-9) drive.angle = turned;
    }
  }
  for (const slide of slides()) {
    const point = slide.point || (links()[slide.link] || [])[0];
    const through = points()[slide.through], at = points()[point];
    if (!through || !at) continue;
    if (slide.along !== FRAME) {
      if (at[0] !== through[0] || at[1] !== through[1]) {
        const drawn = degrees(at[0] - through[0], at[1] - through[1]);
        const previous = Number(slide.direction) || 0;
        let best = drawn;
        for (const turn of [drawn + 180, drawn - 180]) {
          if (Math.abs(turn - previous) < Math.abs(best - previous)) best = turn;
        }
        slide.direction = best + 360 * Math.round((previous - best) / 360);
      }
    } else {
      points()[point] = onLine(at, through, slide.direction);
    }
  }
  $("drive-angle").value = round(drive.angle, 9);
}

// a point's name as the course prints it: the digits of O2 as a subscript, O₂
function pointText(name) {
  return String(name).replace(/[0-9]/g, (d) => "₀₁₂₃₄₅₆₇₈₉"[Number(d)]);
}

function onLine(point, through, direction) {
  const a = direction * Math.PI / 180, ux = Math.cos(a), uy = Math.sin(a);
  const t = (point[0] - through[0]) * ux + (point[1] - through[1]) * uy;
  return [through[0] + t * ux, through[1] + t * uy];
}

function round(value, digits) { return Number(Number(value).toFixed(digits)); }

// ---- talking to the server ----------------------------------------------------------------
// the exercise as the page holds it: its tables as drawn, the title as typed (the server
// writes them as TOML: planmethod/studio/exercise_data.py)
function exercise() {
  syncDrawing();
  return Object.assign({}, studio.tables, {title: $("title").value});
}

async function call(path, body) {
  const response = await fetch(path, {
    method: body === undefined ? "GET" : "POST", credentials: "same-origin",
    headers: {"Content-Type": "application/json"},
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  let data;
  try { data = await response.json(); } catch (error) { data = {error: say("not_json"), kind: "internal"}; }
  return {ok: response.ok, status: response.status, data};
}

function ready() {
  const t = studio.tables;
  const moving = Object.keys(t.links).filter((name) => name !== FRAME && t.links[name].length);
  if (!Object.keys(t.points).length) return say("ready_points");
  if (moving.length < 2) return say("ready_links");
  if (!(t.links[FRAME] || []).length) return say("ready_fix");
  if (!t.drive.link) return say("ready_drive");
  return null;
}

// A drag's intermediate steps are drafts (labels placed quickly, no forces: the server's
// api.solve), the step where it rests — released, or held still for studio.restMs — in full
let inFlight = false, pending = false, draftWanted = false, restTimer = null;
function requestSolve({draft = false} = {}) {
  pending = true;
  draftWanted = draft;
  clearTimeout(restTimer);
  if (draft) restTimer = setTimeout(() => requestSolve(), studio.restMs);
  if (!inFlight) sendSolve();
}

async function sendSolve() {
  pending = false;
  const draft = draftWanted;
  const waiting = ready();
  $("hint").textContent = waiting || say("ready");
  if (waiting) { showProblem(null); clearPlans(); return; }
  inFlight = true;
  const started = performance.now();
  try {
    const answer = await call("/api/solve", draft ? {exercise: exercise(), draft: true} : {exercise: exercise()});
    if (answer.ok) {
      showSolve(answer.data);
      studio.drafted = draft;
      (draft ? studio.draftTimings : studio.timings).push(performance.now() - started);
      studio.serverTimes.push(answer.data.server_ms);
    } else {
      showProblem(answer.data);
    }
    studio.solves += 1;
  } catch (error) {
    showProblem({error: say("no_answer"), kind: "refused"});
  } finally {
    inFlight = false;
    if (pending) sendSolve();
  }
}

function setPlan(id, svg) {
  const box = $(id);
  box.innerHTML = svg || "";
  box.classList.remove("stale");
}

function clearPlans() {
  for (const id of ["plan-position", "plan-velocity-drawing", "plan-acceleration-drawing"]) setPlan(id, "");
  $("checks").innerHTML = ""; $("flags").innerHTML = "";
}

function showSolve(data) {
  studio.report = data.report;
  studio.lastError = null;
  showProblem(null);
  setPlan("plan-position", data.svg.position);
  setPlan("plan-velocity-drawing", data.svg.velocity);
  setPlan("plan-acceleration-drawing", data.svg.acceleration);
  const rows = [`<tr><th>${escapeHtml(say("head_quantity"))}</th><th>${escapeHtml(say("head_plan"))}</th>` +
    `<th>${escapeHtml(say("head_exact"))}</th><th>${escapeHtml(say("head_unit"))}</th></tr>`];
  for (const check of data.report.checks) {
    const show = (v) => v === null || v === undefined ? "—" : escapeHtml(words.number(v, ".5g"));
    rows.push(`<tr data-quantity="${escapeHtml(check.quantity)}" data-value="${check.analytic}"><td>${escapeHtml((data.symbols || {})[check.quantity] || check.quantity)}</td><td>${show(check.plan)}</td><td>${show(check.analytic)}</td><td>${escapeHtml(check.unit)}</td></tr>`);
  }
  $("checks").innerHTML = rows.join("");
  $("flags").innerHTML = (data.report.flags || []).map((flag) => `<li>${escapeHtml(flag)}</li>`).join("");
  $("status").textContent = say("solved", {time: data.server_ms});
  // the drive's symbols follow the crank's number in the exercise's notation (φ₁ or θ₂ …)
  Object.assign(studio.driveSymbols, data.drive_symbols || {});
  studio.askSymbols = data.ask_symbols || {};
  labelAsk();
  showDriveSymbols();
}

function showDriveSymbols() {
  for (const node of document.querySelectorAll("[data-drive-symbol]"))
    node.textContent = studio.driveSymbols[node.dataset.driveSymbol];
  for (const node of document.querySelectorAll("[data-drive-label]"))
    node.setAttribute("aria-label", say(node.dataset.driveLabel, studio.driveSymbols));
}

function showProblem(data) {
  studio.lastError = data;
  if (!data) { $("problem").hidden = true; return; }
  $("problem").hidden = false;
  $("problem-kind").textContent = kindText(data.kind);
  $("problem-text").textContent = data.error;
  for (const id of ["plan-position", "plan-velocity-drawing", "plan-acceleration-drawing"]) $(id).classList.add("stale");
}

function escapeHtml(text) {
  return String(text).replace(/[&<>"']/g, (c) => ({"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;"}[c]));
}

// ---- the editor: world (m, y up) on the screen (px, y down) ---------------------------------
const editor = $("editor");
function size() { const box = editor.getBoundingClientRect(); return [box.width || 600, box.height || 520]; }
function toScreen([x, y]) {
  const [w, h] = size(), v = studio.view;
  return [w / 2 + (x - v.cx) * v.scale, h / 2 - (y - v.cy) * v.scale];
}
function toWorld(px, py) {
  const [w, h] = size(), v = studio.view;
  return [v.cx + (px - w / 2) / v.scale, v.cy - (py - h / 2) / v.scale];
}
// the snap grid: a round step in the drawing's millimetres that suits the mechanism's size
// (about a hundredth of its extent, at most a tenth of its shortest link; not the zoom's),
// never putting a point onto another point or nearer to one than a step
const ROUND_MM = [0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000];
function snapStep() {
  const p = points(), values = Object.values(p);
  let wanted = 2;   // mm: an empty page, a mechanism of about 200 mm to come
  if (values.length >= 2) {
    const span = Math.max(Math.max(...values.map((v) => v[0])) - Math.min(...values.map((v) => v[0])),
                          Math.max(...values.map((v) => v[1])) - Math.min(...values.map((v) => v[1])));
    wanted = span * 1000 / 100;
    for (const [name, members] of Object.entries(links())) {
      if (name === FRAME) continue;
      for (let i = 0; i < members.length; i++) for (let j = i + 1; j < members.length; j++) {
        const a = p[members[i]], b = p[members[j]];
        const length = a && b ? Math.hypot(b[0] - a[0], b[1] - a[1]) * 1000 : 0;
        if (length > 0) wanted = Math.min(wanted, length / 10);
      }
    }
  }
  return (ROUND_MM.filter((step) => step <= wanted).pop() || ROUND_MM[0]) / 1000;
}
function snapOn(event) { return studio.snap.on && !(event && event.altKey) && !studio.snap.held; }
function snapped([x, y], {moving = null, event = null, step = null} = {}) {
  if (!snapOn(event)) return [x, y];
  const unit = step || snapStep();
  const grid = [round(Math.round(x / unit) * unit, 9), round(Math.round(y / unit) * unit, 9)];
  for (const [name, other] of Object.entries(points())) {
    if (name !== moving && Math.hypot(grid[0] - other[0], grid[1] - other[1]) < unit * (1 - 1e-9)) return [x, y];
  }
  return grid;
}
// the grid drawn: lines on the snap step, every so many steps so that they stay apart
function gridLines(step) {
  return step * ([1, 2, 5, 10, 20, 50, 100, 200, 500, 1000].find((k) => k * step * studio.view.scale >= 14) || 1000);
}
function showSnap() {
  const step = round(snapStep() * 1000, 3);
  $("snap").checked = studio.snap.on;
  $("grid-note").textContent = snapOn() ? say("snap_on", {step: step}) : say("snap_off", {step: step});
  $("grid-note").dataset.snap = snapOn() ? "on" : "off";
}
function element(name, attributes, parent) {
  const node = document.createElementNS(SVG, name);
  for (const [key, value] of Object.entries(attributes || {})) node.setAttribute(key, value);
  if (parent) parent.appendChild(node);
  return node;
}

function draw() {
  const [w, h] = size();
  editor.setAttribute("viewBox", `0 0 ${w} ${h}`);
  editor.replaceChildren();
  const step = gridLines(dragging && dragging.step || snapStep());
  showSnap();
  const [x0, y1] = toWorld(0, 0), [x1, y0] = toWorld(w, h);
  const grid = element("g", {}, editor);
  const first = (low) => Math.ceil(low / step);
  for (let i = first(x0); i * step <= x1; i++) {
    const [sx] = toScreen([i * step, 0]);
    element("line", {x1: sx, y1: 0, x2: sx, y2: h, class: i % 5 ? "grid-minor" : "grid-major"}, grid);
  }
  for (let i = first(y0); i * step <= y1; i++) {
    const [, sy] = toScreen([0, i * step]);
    element("line", {x1: 0, y1: sy, x2: w, y2: sy, class: i % 5 ? "grid-minor" : "grid-major"}, grid);
  }
  const [ox, oy] = toScreen([0, 0]);
  element("line", {x1: ox, y1: 0, x2: ox, y2: h, class: "axis"}, grid);
  element("line", {x1: 0, y1: oy, x2: w, y2: oy, class: "axis"}, grid);
  const layer = element("g", {}, editor);
  const p = points();
  // guides of the slides
  for (const [index, slide] of slides().entries()) {
    const through = p[slide.through];
    if (!through) continue;
    const a = slide.direction * Math.PI / 180, reach = 4 * Math.max(w, h) / studio.view.scale;
    const [ax, ay] = toScreen([through[0] - reach * Math.cos(a), through[1] - reach * Math.sin(a)]);
    const [bx, by] = toScreen([through[0] + reach * Math.cos(a), through[1] + reach * Math.sin(a)]);
    element("line", {x1: ax, y1: ay, x2: bx, y2: by, class: "guide", "data-slide": index}, layer);
  }
  // links
  for (const [name, members] of Object.entries(links())) {
    if (name === FRAME || !members.length) continue;
    const slide = slideOfLink(name);
    if (members.length === 1) {
      if (!p[members[0]]) continue;
      const [sx, sy] = toScreen(p[members[0]]);
      const angle = slide ? -slide.direction : 0;
      const block = element("rect", {x: sx - 16, y: sy - 9, width: 32, height: 18, rx: 2,
        transform: `rotate(${angle} ${sx} ${sy})`, class: "block" + (isSelected("link", name) ? " selected" : ""),
        "data-link": name}, layer);
      block.appendChild(document.createElementNS(SVG, "title")).textContent = name;
      continue;
    }
    const coordinates = members.filter((m) => p[m]).map((m) => toScreen(p[m]).join(","));
    const shape = members.length > 2 ? "polygon" : "polyline";
    const cls = "link" + (name === studio.tables.drive.link ? " drive" : "") + (isSelected("link", name) ? " selected" : "");
    element(shape, {points: coordinates.join(" "), class: cls}, layer);
    element(shape, {points: coordinates.join(" "), class: "link-hit", "data-link": name}, layer);
    // the name beside the middle of the link's first side, on its left
    const [first, second] = members.slice(0, 2).map((m) => toScreen(p[m] || [0, 0]));
    const length = Math.hypot(second[0] - first[0], second[1] - first[1]) || 1;
    const nx = (second[1] - first[1]) / length, ny = -(second[0] - first[0]) / length;
    element("text", {x: (first[0] + second[0]) / 2 + 12 * nx, y: (first[1] + second[1]) / 2 + 12 * ny + 4,
                     "text-anchor": "middle", class: "link-name"}, layer).textContent = name;
  }
  // the frame's hatching under each fixed point
  for (const name of links()[FRAME] || []) {
    if (!p[name]) continue;
    const [sx, sy] = toScreen(p[name]);
    element("path", {d: `M ${sx} ${sy} L ${sx - 9} ${sy + 13} L ${sx + 9} ${sy + 13} Z M ${sx - 13} ${sy + 13} L ${sx + 13} ${sy + 13}` +
      [-10, -4, 2, 8].map((dx) => ` M ${sx + dx} ${sy + 13} L ${sx + dx - 5} ${sy + 19}`).join(""), class: "ground"}, layer);
  }
  // the drive's ω
  const drive = studio.tables.drive;
  if (drive.link && p[drive.pivot]) {
    const [sx, sy] = toScreen(p[drive.pivot]);
    element("text", {x: sx - 28, y: sy - 10, class: "omega"}, layer).textContent = studio.driveSymbols.omega;
  }
  // the link being drawn
  if (studio.building.length > 1) {
    element("polyline", {points: studio.building.map((m) => toScreen(p[m]).join(",")).join(" "), class: "building-line"}, layer);
  }
  // points
  for (const [name, xy] of Object.entries(p)) {
    const [sx, sy] = toScreen(xy);
    const cls = "point" + (isFixed(name) ? " fixed" : "") + (isSelected("point", name) ? " selected" : "") +
      (studio.building.includes(name) || studio.sliderPoint === name ? " building" : "");
    element("circle", {cx: sx, cy: sy, r: 5.5, class: cls}, layer);
    element("circle", {cx: sx, cy: sy, r: 11, class: "point-hit", "data-point": name}, layer);
    element("text", {x: sx + 8, y: sy - 8, class: "point-name"}, layer).textContent = name;
  }
}

function isSelected(kind, name) { return studio.selected && studio.selected.kind === kind && studio.selected.name === name; }

function fit() {
  const values = Object.values(points());
  const [w, h] = size();
  if (!values.length) { studio.view = {cx: 0.12, cy: 0.02, scale: 1800}; draw(); return; }
  const xs = values.map((v) => v[0]), ys = values.map((v) => v[1]);
  const spanX = Math.max(...xs) - Math.min(...xs), spanY = Math.max(...ys) - Math.min(...ys);
  const span = Math.max(spanX / (w * 0.8), spanY / (h * 0.8), 1e-3 / w);
  studio.view = {cx: (Math.max(...xs) + Math.min(...xs)) / 2, cy: (Math.max(...ys) + Math.min(...ys)) / 2,
                 scale: 1 / span};
  draw();
}

// ---- editing ----------------------------------------------------------------------------------
function setMode(mode) {
  studio.mode = mode;
  studio.building = []; studio.sliderPoint = null;
  for (const button of document.querySelectorAll("#tools [data-mode]")) button.classList.toggle("on", button.dataset.mode === mode);
  const modes = ["move", "point", "link", "fix", "slider", "drive", "delete"];
  $("hint").textContent = modes.includes(mode) ? say("mode_" + mode) : "";
  draw();
}

function changed({solve = true, draft = false} = {}) {
  syncDrawing();
  draw();
  refreshPanels();
  if (solve) requestSolve({draft});
}

function addPoint(xy) {
  const name = nextPointName();
  points()[name] = xy;
  studio.selected = {kind: "point", name};
  changed();
  return name;
}

function finishLink() {
  const members = studio.building;
  studio.building = [];
  if (members.length >= 2) {
    const name = uniqueLinkName(members[0] + members[1]);
    links()[name] = members.slice();
    studio.selected = {kind: "link", name};
  }
  changed();
}

function toggleFixed(point) {
  const frame = links()[FRAME] || (links()[FRAME] = []);
  const index = frame.indexOf(point);
  if (index >= 0) frame.splice(index, 1); else frame.push(point);
  changed();
}

function makeSlider(point, through) {
  if (point === through) return;
  const carriers = linksOf(through).filter((name) => !links()[name].includes(point) || name === FRAME);
  const along = carriers.includes(FRAME) ? FRAME : carriers[0];
  if (!along) { showProblem({error: say("no_guide", {point: through}), kind: "input"}); return; }
  const name = uniqueLinkName("slider");
  links()[name] = [point];
  const [x0, y0] = points()[through], [x1, y1] = points()[point];
  slides().push({link: name, along, through, direction: round(degrees(x1 - x0, y1 - y0), 12), point});
  studio.selected = {kind: "link", name};
  changed();
}

function setDrive(link) {
  const pivot = (links()[link] || []).find((p) => isFixed(p));
  if (link === FRAME) return;
  if (!pivot) { showProblem({error: say("drive_unpinned", {link: link}), kind: "input"}); return; }
  studio.tables.drive.link = link;
  studio.tables.drive.pivot = pivot;
  changed();
}

function deletePoint(name) {
  delete points()[name];
  for (const [link, members] of Object.entries(links())) {
    const kept = members.filter((m) => m !== name);
    if (link !== FRAME && kept.length < (slideOfLink(link) ? 1 : 2) && members.includes(name)) deleteLink(link);
    else links()[link] = kept;
  }
  studio.tables.slide = slides().filter((s) => s.through !== name && s.point !== name);
  if (studio.tables.drive.pivot === name) studio.tables.drive = {...studio.tables.drive, link: "", pivot: ""};
  cleanAsk();
}

function deleteLink(name) {
  delete links()[name];
  studio.tables.slide = slides().filter((s) => s.link !== name && s.along !== name);
  if (studio.tables.drive.link === name) studio.tables.drive = {...studio.tables.drive, link: "", pivot: ""};
  cleanAsk();
}

function cleanAsk() {
  const ask = studio.tables.ask;
  if (!ask) return;
  const known = new Set([...Object.keys(points()), ...Object.keys(links()), ...slides().map((s) => `${s.link}/${s.along}`)]);
  for (const key of Object.keys(ask)) if (Array.isArray(ask[key])) ask[key] = ask[key].filter((item) => known.has(item.split("@")[0]));
}

function renamePoint(old, name) {
  if (!/^[A-Z][0-9]*$/.test(name) || points()[name]) return false;
  const replaced = {};
  for (const [key, value] of Object.entries(points())) replaced[key === old ? name : key] = value;
  studio.tables.points = replaced;
  for (const link of Object.keys(links())) links()[link] = links()[link].map((m) => m === old ? name : m);
  for (const slide of slides()) { if (slide.through === old) slide.through = name; if (slide.point === old) slide.point = name; }
  if (studio.tables.drive.pivot === old) studio.tables.drive.pivot = name;
  const ask = studio.tables.ask || {};
  for (const key of ["velocity", "acceleration", "curvature"]) if (ask[key]) ask[key] = ask[key].map((m) => m === old ? name : m);
  studio.selected = {kind: "point", name};
  return true;
}

function renameLink(old, name) {
  if (!/^[A-Za-z_][A-Za-z0-9_]*$/.test(name) || old === FRAME || name.toLowerCase() === FRAME ||
      Object.keys(links()).some((n) => n.toLowerCase() === name.toLowerCase())) return false;
  const replaced = {};
  for (const [key, value] of Object.entries(links())) replaced[key === old ? name : key] = value;
  studio.tables.links = replaced;
  for (const slide of slides()) { if (slide.link === old) slide.link = name; if (slide.along === old) slide.along = name; }
  if (studio.tables.drive.link === old) studio.tables.drive.link = name;
  const ask = studio.tables.ask || {};
  for (const key of ["omega", "epsilon"]) if (ask[key]) ask[key] = ask[key].map((m) => m === old ? name : m);
  if (studio.tables.mass && studio.tables.mass[old]) { studio.tables.mass[name] = studio.tables.mass[old]; delete studio.tables.mass[old]; }
  studio.selected = {kind: "link", name};
  return true;
}

// ---- pointer input ------------------------------------------------------------------------------
let dragging = null, panning = null;
function eventWorld(event) {
  const box = editor.getBoundingClientRect();
  return toWorld(event.clientX - box.left, event.clientY - box.top);
}

editor.addEventListener("pointerdown", (event) => {
  const target = event.target;
  const point = target.dataset ? target.dataset.point : undefined;
  const link = target.dataset ? target.dataset.link : undefined;
  const mode = studio.mode;
  if (point) {
    if (mode === "move") {
      studio.selected = {kind: "point", name: point};
      dragging = {point, moved: false, step: snapStep()};
      editor.setPointerCapture(event.pointerId);
      draw(); refreshPanels();
    } else if (mode === "link") {
      if (studio.building[studio.building.length - 1] === point) finishLink();
      else if (!studio.building.includes(point)) { studio.building.push(point); draw(); }
    } else if (mode === "fix") toggleFixed(point);
    else if (mode === "slider") {
      if (!studio.sliderPoint) { studio.sliderPoint = point; draw(); }
      else { const first = studio.sliderPoint; studio.sliderPoint = null; makeSlider(first, point); }
    } else if (mode === "delete") { deletePoint(point); studio.selected = null; changed(); }
    else if (mode === "drive") { const carrier = linksOf(point).find((n) => n !== FRAME); if (carrier) setDrive(carrier); }
    event.preventDefault();
    return;
  }
  if (link) {
    if (mode === "drive") setDrive(link);
    else if (mode === "delete") { deleteLink(link); studio.selected = null; changed(); }
    else { studio.selected = {kind: "link", name: link}; draw(); refreshPanels(); }
    event.preventDefault();
    return;
  }
  if (mode === "point") { addPoint(snapped(eventWorld(event), {event})); event.preventDefault(); return; }
  if (mode === "move") {
    studio.selected = null; refreshPanels(); draw();
    panning = {x: event.clientX, y: event.clientY, cx: studio.view.cx, cy: studio.view.cy};
    editor.setPointerCapture(event.pointerId);
  }
});

editor.addEventListener("pointermove", (event) => {
  if (dragging) {
    points()[dragging.point] = snapped(eventWorld(event), {moving: dragging.point, event, step: dragging.step});
    dragging.moved = true;
    changed({draft: true});
  } else if (panning) {
    studio.view.cx = panning.cx - (event.clientX - panning.x) / studio.view.scale;
    studio.view.cy = panning.cy + (event.clientY - panning.y) / studio.view.scale;
    draw();
  }
});

function endDrag() {
  if (dragging && dragging.moved) requestSolve();   // at rest: the full answer
  dragging = null; panning = null;
}
editor.addEventListener("pointerup", endDrag);
editor.addEventListener("pointercancel", endDrag);
editor.addEventListener("wheel", (event) => {
  event.preventDefault();
  const before = eventWorld(event);
  studio.view.scale *= Math.exp(-event.deltaY * 0.0015);
  const after = eventWorld(event);
  studio.view.cx += before[0] - after[0]; studio.view.cy += before[1] - after[1];
  draw();
}, {passive: false});

// Alt held places freely while it is held; G turns the snap off and on
document.addEventListener("keydown", (event) => {
  if (event.key === "Alt" && !studio.snap.held) { studio.snap.held = true; showSnap(); }
  if (event.target.tagName === "INPUT" || event.target.tagName === "SELECT") return;
  if ((event.key === "g" || event.key === "G") && !event.ctrlKey && !event.metaKey && !event.altKey) {
    studio.snap.on = !studio.snap.on; showSnap();
  }
  if (event.key === "Enter" && studio.mode === "link") finishLink();
  if (event.key === "Escape") { studio.building = []; studio.sliderPoint = null; draw(); }
  if ((event.key === "Delete" || event.key === "Backspace") && studio.selected) {
    if (studio.selected.kind === "point") deletePoint(studio.selected.name); else deleteLink(studio.selected.name);
    studio.selected = null; changed();
  }
});

for (const button of document.querySelectorAll("#tools [data-mode]")) button.addEventListener("click", () => setMode(button.dataset.mode));
$("finish-link").addEventListener("click", finishLink);
$("fit").addEventListener("click", fit);
// the editor from the keyboard: [ and ] choose the previous or next point, the arrows move it by
// a step of the snap grid (with Shift ten)
const ARROWS = {ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1]};
editor.addEventListener("keydown", (event) => {
  const names = Object.keys(points());
  const chosen = studio.selected && studio.selected.kind === "point" ? names.indexOf(studio.selected.name) : -1;
  if ((event.key === "]" || event.key === "[") && names.length) {
    const next = chosen < 0 ? (event.key === "]" ? 0 : names.length - 1)
      : (chosen + (event.key === "]" ? 1 : names.length - 1)) % names.length;
    studio.selected = {kind: "point", name: names[next]};
    draw(); refreshPanels();
    $("key-note").textContent = say("chosen_point", {point: pointText(names[next])});
    event.preventDefault();
  } else if (ARROWS[event.key] && chosen >= 0) {
    const step = snapStep() * (event.shiftKey ? 10 : 1), [dx, dy] = ARROWS[event.key];
    const [x, y] = points()[names[chosen]];
    points()[names[chosen]] = [round(x + dx * step, 9), round(y + dy * step, 9)];
    changed();
    event.preventDefault();
  }
});
document.addEventListener("keyup", (event) => { if (event.key === "Alt") { studio.snap.held = false; showSnap(); } });
window.addEventListener("blur", () => { if (studio.snap.held) { studio.snap.held = false; showSnap(); } });
$("snap").addEventListener("change", () => { studio.snap.on = $("snap").checked; showSnap(); });
window.addEventListener("resize", draw);

// ---- panels -------------------------------------------------------------------------------------
function field(label, id, value, type = "number", extra = "") {
  return `<label><span>${escapeHtml(label)}</span><input id="${id}" type="${type}" ${type === "number" ? 'step="any"' : ""} value="${escapeHtml(value)}" ${extra}></label>`;
}

function refreshPanels() {
  const body = $("selection-body");
  const s = studio.selected;
  if (s && s.kind === "point" && points()[s.name]) {
    const [x, y] = points()[s.name];
    const on = linksOf(s.name);
    body.innerHTML = field(say("field_name"), "point-name", s.name, "text") + field(say("field_x"), "point-x", x) +
      field(say("field_y"), "point-y", y) +
      `<label><span>${escapeHtml(say("field_fixed"))}</span><input id="point-fixed" type="checkbox" ${isFixed(s.name) ? "checked" : ""}></label>` +
      `<div class="muted">${escapeHtml(on.length ? say("on_links", {links: on}) : say("on_no_link"))}</div>`;
    $("point-name").addEventListener("change", (e) => { if (!renamePoint(s.name, e.target.value.trim())) e.target.value = s.name; changed(); });
    for (const [axis, id] of [[0, "point-x"], [1, "point-y"]]) {
      $(id).addEventListener("change", (e) => {
        const value = Number(e.target.value);
        if (e.target.value.trim() === "" || !Number.isFinite(value)) return;
        points()[s.name][axis] = value;
        changed();
      });
    }
    $("point-fixed").addEventListener("change", () => toggleFixed(s.name));
  } else if (s && s.kind === "link" && links()[s.name]) {
    const slide = slideOfLink(s.name);
    let html = field(say("field_name"), "link-name", s.name, "text") +
      `<div class="muted">${escapeHtml(say("link_points", {points: links()[s.name]}))}</div>`;
    if (slide) {
      const carriers = linksOf(slide.through).filter((n) => n !== s.name);
      html += `<label><span>${escapeHtml(say("slides_along"))}</span><select id="slide-along">${carriers.map((n) => `<option ${n === slide.along ? "selected" : ""}>${escapeHtml(n)}</option>`).join("")}</select></label>` +
        `<div class="muted">${escapeHtml(say("guide_through", {point: slide.through}))}</div>` +
        field(say("field_direction"), "slide-direction", round(slide.direction, 9), "number",
              slide.along === FRAME ? "" : `readonly title="${escapeHtml(say("guide_moving"))}"`);
    }
    body.innerHTML = html;
    $("link-name").addEventListener("change", (e) => { if (!renameLink(s.name, e.target.value.trim())) e.target.value = s.name; changed(); });
    if (slide) {
      $("slide-along").addEventListener("change", (e) => { slide.along = e.target.value; changed(); });
      $("slide-direction").addEventListener("change", (e) => {
        const value = Number(e.target.value);
        if (slide.along === FRAME && Number.isFinite(value)) { slide.direction = value; changed(); }
      });
    }
  } else {
    studio.selected = null;
    body.innerHTML = `<span class="muted">${escapeHtml(say("nothing_selected"))}</span>`;
  }
  // the drive
  const drive = studio.tables.drive;
  const candidates = Object.keys(links()).filter((n) => n !== FRAME && links()[n].some(isFixed));
  $("drive-link").innerHTML = '<option value="">—</option>' + candidates.map((n) => `<option ${n === drive.link ? "selected" : ""}>${escapeHtml(n)}</option>`).join("");
  $("drive-pivot").value = drive.pivot || "";
  if (document.activeElement !== $("drive-angle")) $("drive-angle").value = round(drive.angle || 0, 9);
  if (document.activeElement !== $("drive-omega")) $("drive-omega").value = drive.omega;
  if (document.activeElement !== $("drive-epsilon")) $("drive-epsilon").value = drive.epsilon || 0;
  const plan = studio.tables.plan || (studio.tables.plan = {});
  // the drawn lengths are of the drive link's pivot–pin segment and of its pin's images
  const pin = drivePin();
  if (drive.pivot && pin) {
    const image = pointText(pin).toLowerCase();
    $("plan-crank-label").textContent = say("drawn_crank", {pivot: pointText(drive.pivot), pin: pointText(pin)});
    $("plan-velocity-label").textContent = say("drawn_velocity", {image: image});
    $("plan-acceleration-label").textContent = say("drawn_acceleration", {image: image});
  }
  for (const [id, key] of [["plan-crank", "crank_mm"], ["plan-velocity", "velocity_mm"], ["plan-acceleration", "acceleration_mm"]]) {
    if (document.activeElement !== $(id)) $(id).value = plan[key] === undefined ? "" : plan[key];
  }
  refreshAsk();
}

// a box of What is asked, in the course's words: "ask the angular velocity ω₂ of link rod"
const ASK_QUANTITY = {velocity: "v", acceleration: "a", curvature: "rho", omega: "omega", epsilon: "epsilon"};
function askLabel(key, name) {
  if (key === "sliding") {
    const [link, along] = name.split("/");
    return say("ask_sliding_box", {link: link, along: along});
  }
  const quantity = ASK_QUANTITY[key] + "_" + name;
  const symbol = studio.askSymbols[quantity] || quantity;
  return say("ask_" + key + "_box", ["omega", "epsilon"].includes(key) ? {symbol: symbol, link: name}
    : {symbol: symbol, point: pointText(name)});
}
function labelAsk() {
  for (const input of $("ask-body").querySelectorAll("input[data-ask]"))
    input.setAttribute("aria-label", askLabel(input.dataset.ask, input.dataset.name));
}

function refreshAsk() {
  const ask = studio.tables.ask || {};
  const has = (key, name) => (ask[key] || []).includes(name);
  const box = (key, name) => `<input type="checkbox" data-ask="${key}" data-name="${escapeHtml(name)}" aria-label="${escapeHtml(askLabel(key, name))}" ${has(key, name) ? "checked" : ""}>`;
  const moving = Object.keys(points()).filter((p) => !isFixed(p));
  const turning = Object.keys(links()).filter((n) => n !== FRAME && n !== studio.tables.drive.link);
  let html = `<table id="ask-table"><tr><th>${escapeHtml(say("ask_point"))}</th><th>v</th><th>a</th><th>ρ</th></tr>`;
  for (const p of moving) html += `<tr><td>${escapeHtml(p)}</td><td>${box("velocity", p)}</td><td>${box("acceleration", p)}</td><td>${box("curvature", p)}</td></tr>`;
  html += `<tr><th>${escapeHtml(say("ask_link"))}</th><th>ω</th><th>ε</th><td></td></tr>`;
  for (const n of turning) html += `<tr><td>${escapeHtml(n)}</td><td>${box("omega", n)}</td><td>${box("epsilon", n)}</td><td></td></tr>`;
  for (const s of slides()) html += `<tr><td>${escapeHtml(s.link + "/" + s.along)}</td><td colspan="3">${escapeHtml(say("ask_sliding"))} ${box("sliding", s.link + "/" + s.along)}</td></tr>`;
  html += "</table>";
  $("ask-body").innerHTML = html;
  for (const input of $("ask-body").querySelectorAll("input[data-ask]")) {
    input.addEventListener("change", () => {
      const table = studio.tables.ask || (studio.tables.ask = {});
      const list = table[input.dataset.ask] || (table[input.dataset.ask] = []);
      const index = list.indexOf(input.dataset.name);
      if (input.checked && index < 0) list.push(input.dataset.name);
      if (!input.checked && index >= 0) list.splice(index, 1);
      for (const key of Object.keys(table)) if (Array.isArray(table[key]) && !table[key].length) delete table[key];
      if (!Object.keys(table).length) delete studio.tables.ask;
      requestSolve();
    });
  }
}

$("drive-link").addEventListener("change", (e) => { if (e.target.value) setDrive(e.target.value); else { studio.tables.drive.link = ""; studio.tables.drive.pivot = ""; changed(); } });
$("drive-omega").addEventListener("change", (e) => { const v = Number(e.target.value); if (Number.isFinite(v)) { studio.tables.drive.omega = v; changed(); } });
$("drive-epsilon").addEventListener("change", (e) => { const v = Number(e.target.value); if (Number.isFinite(v)) { studio.tables.drive.epsilon = v; changed(); } });
$("drive-angle").addEventListener("change", (e) => turnTo(Number(e.target.value)));
for (const [id, key] of [["plan-crank", "crank_mm"], ["plan-velocity", "velocity_mm"], ["plan-acceleration", "acceleration_mm"]]) {
  $(id).addEventListener("change", (e) => {
    const v = Number(e.target.value);
    if (Number.isFinite(v) && v > 0) { studio.tables.plan[key] = v; delete studio.tables.plan[key.replace("_mm", "").replace("crank", "mu_l").replace("velocity", "mu_v").replace("acceleration", "mu_a")]; changed(); }
  });
}
$("title").addEventListener("change", () => { studio.tables.title = $("title").value; requestSolve(); });

async function turnTo(angle) {
  if (!Number.isFinite(angle) || ready()) return;
  const answer = await call("/api/turn", {exercise: exercise(), angle});
  if (!answer.ok) { showProblem(answer.data); $("drive-angle").value = round(studio.tables.drive.angle, 9); return; }
  load(answer.data.tables, {keepView: true});
}

// ---- files ------------------------------------------------------------------------------------
function load(tables, {keepView = false} = {}) {
  const t = JSON.parse(JSON.stringify(tables));
  t.links = t.links || {frame: []};
  if (!t.links[FRAME]) t.links[FRAME] = [];
  t.slide = t.slide ? (Array.isArray(t.slide) ? t.slide : [t.slide]) : [];
  for (const slide of t.slide) {
    if (slide.direction === undefined) slide.direction = 0;
    if (!slide.point && (t.links[slide.link] || []).length === 1) slide.point = t.links[slide.link][0];
  }
  t.drive = Object.assign({link: "", pivot: "", angle: 0, omega: 10, epsilon: 0}, t.drive || {});
  t.plan = t.plan || {};
  studio.tables = t;
  $("title").value = t.title || say("untitled");
  studio.selected = null; studio.building = [];
  if (!keepView) fit(); else draw();
  refreshPanels();
  requestSolve();
}
studio.load = load;
studio.movePoint = (name, x, y, {draft = false} = {}) => { points()[name] = [x, y]; changed({draft}); };
studio.snapStep = snapStep;
// the drawing's point (m) under a point of the editor (px from its corner)
studio.toWorld = toWorld;
studio.exercise = exercise;

$("open-button").addEventListener("click", async () => {
  const answer = await call("/api/files");
  const list = $("file-list");
  list.innerHTML = "";
  for (const path of (answer.data.files || [])) {
    const item = document.createElement("li");
    item.textContent = path;
    item.addEventListener("click", () => { $("open-dialog").close(); openFile(path); });
    list.appendChild(item);
  }
  if (!list.children.length) list.innerHTML = `<li class="muted">${escapeHtml(say("no_files", {suffix: ".toml"}))}</li>`;
  $("open-dialog").showModal();
});
$("open-cancel").addEventListener("click", () => $("open-dialog").close());

async function openFile(path) {
  const answer = await call("/api/open", {path});
  if (!answer.ok) { showProblem(answer.data); return; }
  studio.path = path;
  $("file").textContent = answer.data.converted ? say("file_converted", {path: path}) : path;
  $("save-path").value = answer.data.converted ? path.replace(/\.toml$/, "_drawn.toml") : path;
  load(answer.data.tables);
}

async function save(overwrite = false) {
  const path = $("save-path").value.trim();
  const answer = await call("/api/save", {path, exercise: exercise(), overwrite});
  if (answer.status === 409 && !overwrite) {
    if (window.confirm(say("replace", {path: path}))) return save(true);
    return;
  }
  if (!answer.ok) { showProblem(answer.data); return; }
  studio.path = answer.data.saved;
  $("file").textContent = answer.data.saved;
  $("status").textContent = say("saved", {path: answer.data.saved});
}
$("save-button").addEventListener("click", () => save(false));

// what studio_runs.js uses of this page
studio.page = {call: call, say: say, words: words, kindText: kindText, escapeHtml: escapeHtml,
               round: round, exercise: exercise, links: links, points: points, FRAME: FRAME};

// ---- start ------------------------------------------------------------------------------------
async function start() {
  if (window.location.search) window.history.replaceState(null, "", window.location.pathname);
  setMode("move");
  showDriveSymbols();
  refreshPanels();
  draw();
  const answer = await call("/api/state");
  // the limits of the runs, and a run still going after a reload (studio_runs.js)
  if (answer.ok) document.dispatchEvent(new CustomEvent("studio:state", {detail: answer.data}));
  if (answer.ok && answer.data.initial) await openFile(answer.data.initial);
  else $("hint").textContent = ready() || "";
  studio.ready = true;
}
// every script of the page loaded first (studio_runs.js listens for the state)
document.addEventListener("DOMContentLoaded", start);
})();
