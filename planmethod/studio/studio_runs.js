"use strict";
// The studio's long work: a preview of variants and their task sheets, and an export of a whole
// teaching run, each started from its dialog and run on the server as a job whose progress the
// page follows (see docs/studio.md). It uses the page's exercise, words and server calls
// (studio.js: window.studio.page); every sentence is a template the server sent.
(() => {
const studio = window.studio;
const {call, say, words, kindText, escapeHtml, round, exercise, links, points, FRAME} = studio.page;
const $ = (id) => document.getElementById(id);

// ---- variants and export ----------------------------------------------------------------------
function baseLength(name) {
  const members = links()[name] || [];
  if (name === FRAME) {
    const pivot = points()[studio.tables.drive.pivot];
    if (!pivot) return 0;
    return Math.max(0, ...members.map((m) => Math.hypot(points()[m][0] - pivot[0], points()[m][1] - pivot[1])));
  }
  if (members.length < 2) return 0;
  const [a, b] = [points()[members[0]], points()[members[1]]];
  return Math.hypot(b[0] - a[0], b[1] - a[1]);
}

function fillRanges() {
  const heads = ["range_link", "range_drawn", "range_vary", "range_from", "range_to"];
  const rows = ["<tr>" + heads.map((id) => `<th>${escapeHtml(say(id))}</th>`).join("") + "</tr>"];
  for (const name of Object.keys(links())) {
    const length = baseLength(name);
    if (!(length > 0)) continue;
    const low = round(length * 0.9, 3), high = round(length * 1.1, 3);
    const label = (id) => escapeHtml(say(id, {link: name}));
    rows.push(`<tr><td>${escapeHtml(name)}</td><td>${round(length, 4)}</td><td><input type="checkbox" data-range="${escapeHtml(name)}" aria-label="${label("range_vary_box")}" ${name === FRAME ? "" : "checked"}></td>` +
      `<td><input type="number" step="any" data-low="${escapeHtml(name)}" aria-label="${label("range_low_box")}" value="${low}"></td><td><input type="number" step="any" data-high="${escapeHtml(name)}" aria-label="${label("range_high_box")}" value="${high}"></td></tr>`);
  }
  $("ranges-table").innerHTML = rows.join("");
  const angle = Number(studio.tables.drive.angle) || 0;
  $("angle-from").value = round(angle - 30, 3); $("angle-to").value = round(angle + 30, 3);
  const omega = Number(studio.tables.drive.omega) || 10;
  $("omega-from").value = round(omega * 0.8, 3); $("omega-to").value = round(omega * 1.2, 3);
}

function ranges() {
  const lengths = {};
  for (const box of $("ranges-table").querySelectorAll("input[data-range]")) {
    if (!box.checked) continue;
    const name = box.dataset.range;
    const low = Number($("ranges-table").querySelector(`[data-low="${CSS.escape(name)}"]`).value);
    const high = Number($("ranges-table").querySelector(`[data-high="${CSS.escape(name)}"]`).value);
    lengths[name] = [low, high];
  }
  const out = {lengths, angle: [Number($("angle-from").value), Number($("angle-to").value), Number($("angle-step").value)]};
  if ($("vary-omega").checked) out.omega = [Number($("omega-from").value), Number($("omega-to").value), Number($("omega-step").value)];
  return out;
}

$("variants-button").addEventListener("click", () => { fillRanges(); $("variants-message").textContent = ""; $("variants-dialog").showModal(); });
$("variants-close").addEventListener("click", () => $("variants-dialog").close());
$("preview-variants").addEventListener("click", async () => {
  $("variants-message").textContent = "";
  $("sheets").innerHTML = "";
  const answer = await call("/api/variants", {exercise: exercise(), ranges: ranges(),
    count: Number($("variant-count").value), seed: Number($("variant-seed").value)});
  if (!answer.ok) {
    $("variants-message").textContent = say("refused_as", {kind: kindText(answer.data.kind),
                                                           error: answer.data.error});
    return;
  }
  follow(answer.data.job, "variants-job", showSheets);
});

function showSheets(job) {
  if (job.state !== "done") return;
  const result = job.result;
  const count = result.variants.length;
  $("variants-message").textContent = result.rejected.length ?
    say("preview_rejected", {count: count, rejected: result.rejected.join("; ")}) :
    say("preview_count", {count: count});
  for (const variant of result.variants) {
    const figure = document.createElement("figure");
    const values = Object.entries(variant.values).map(([k, v]) =>
      `${k} = ${typeof v === "number" ? words.number(v, ".6g") : v}`).join(", ");
    figure.innerHTML = `<figcaption><strong>${escapeHtml(say("student", {student: variant.student}))}</strong>` +
      ` — ${escapeHtml(values)}</figcaption>` +
      (variant.note ? `<div class="note">${escapeHtml(variant.note)}</div>` : "") + variant.sheet;
    $("sheets").appendChild(figure);
  }
}
$("save-template").addEventListener("click", async () => {
  const body = {template: true, path: $("template-path").value.trim(), exercise: exercise(), ranges: ranges()};
  let answer = await call("/api/save", body);
  if (answer.status === 409 && window.confirm(say("replace", {path: body.path}))) answer = await call("/api/save", {...body, overwrite: true});
  $("variants-message").textContent = answer.ok ? say("template_saved", {path: answer.data.saved,
    command: ["planmethod", "variants", answer.data.saved, "--out", "DIR"].join(" ")}) : answer.data.error;
});

$("export-button").addEventListener("click", () => { if (!$("ranges-table").children.length) fillRanges(); $("export-message").textContent = ""; $("export-dialog").showModal(); });
$("export-close").addEventListener("click", () => $("export-dialog").close());
$("export-run").addEventListener("click", async () => {
  $("export-message").textContent = "";
  const formats = [...document.querySelectorAll("[data-format]")].filter((b) => b.checked).map((b) => b.dataset.format);
  const answer = await call("/api/export", {exercise: exercise(), ranges: ranges(), folder: $("export-folder").value.trim(),
    formats, count: Number($("export-count").value), seed: Number($("export-seed").value)});
  if (!answer.ok) { $("export-message").textContent = answer.data.error; return; }
  follow(answer.data.job, "export-job");
});

// ---- jobs: long work on the server, followed here ---------------------------------------------
// A job (a preview of variants, an export) runs on the server in a process of its own; the page
// asks for its progress every few tenths of a second and shows it in the bar under the header
// and in the dialog it was started from (a dialog keeps the rest of the page out of reach).
studio.jobs = {};
const JOB_POLL_MS = 300;
let polling = false;

function follow(job, place = null, onEnd = null) {
  studio.jobs[job.id] = {job, place, onEnd, ended: false};
  showJobs();
  if (!polling) pollJobs();
}

async function pollJobs() {
  polling = true;
  while (Object.values(studio.jobs).some((entry) => entry.job.state === "running")) {
    await new Promise((resolve) => setTimeout(resolve, JOB_POLL_MS));
    for (const entry of Object.values(studio.jobs)) {
      if (entry.job.state !== "running") continue;
      let answer;
      try { answer = await call(`/api/job?id=${encodeURIComponent(entry.job.id)}`); } catch (error) { continue; }
      if (!answer.ok) { entry.job = {...entry.job, state: "failed", error: answer.data}; }
      else entry.job = answer.data;
      if (entry.job.state !== "running" && !entry.ended) {
        entry.ended = true;
        if (entry.onEnd) entry.onEnd(entry.job);
      }
    }
    showJobs();
  }
  polling = false;
}

function jobText(job) {
  const exporting = job.kind === "export";
  const what = exporting ? words.message("job_export", {folder: job.folder}) : words.message("job_preview");
  if (job.state === "done") {
    const r = job.result || {};
    return exporting ? say("job_exported", {count: r.written, folder: r.folder, variants: r.variants})
      : say("job_previewed", {count: (r.variants || []).length});
  }
  if (job.state === "failed")
    return say("job_failed", {what: what, error: (job.error || {}).error || say("job_no_answer")});
  if (job.state === "cancelled") return say(exporting ? "job_cancelled_export" : "job_cancelled", {what: what});
  const phases = ["starting", "variants", "packages", "writing"];
  const phase = phases.includes(job.phase) ?
    words.message("phase_" + job.phase, {done: job.done, total: job.total}) : job.phase;
  return say("job_phase", {what: what, phase: phase});
}

function jobRow(job) {
  const running = job.state === "running";
  const value = job.phase === "starting" ? 0 : job.phase === "variants" ? job.done : job.total;
  return `<div class="job" data-job="${escapeHtml(job.id)}" data-state="${escapeHtml(job.state)}">` +
    `<span class="job-text">${escapeHtml(jobText(job))}</span>` +
    (running ? `<progress max="${job.total}" value="${value}" aria-label="${escapeHtml(say("job_progress"))}"></progress>` : "") +
    `<span class="job-time">${escapeHtml(say("job_seconds", {seconds: Math.round(job.seconds)}))}</span>` +
    (running ? `<button data-cancel-job="${escapeHtml(job.id)}">${escapeHtml(say("job_cancel"))}</button>`
      : `<button data-dismiss-job="${escapeHtml(job.id)}" aria-label="${escapeHtml(say("job_dismiss"))}">×</button>`) + "</div>";
}

function showJobs() {
  const entries = Object.values(studio.jobs);
  $("jobs").innerHTML = entries.map((entry) => jobRow(entry.job)).join("");
  for (const place of ["variants-job", "export-job"])
    $(place).innerHTML = entries.filter((entry) => entry.place === place).slice(-1).map((entry) => jobRow(entry.job)).join("");
}

document.addEventListener("click", async (event) => {
  const cancel = event.target.closest("[data-cancel-job]");
  const dismiss = event.target.closest("[data-dismiss-job]");
  if (cancel) {
    const entry = studio.jobs[cancel.dataset.cancelJob];
    cancel.disabled = true;
    const answer = await call("/api/cancel", {id: cancel.dataset.cancelJob});
    if (answer.ok && entry) { entry.job = answer.data; entry.ended = true; }
    showJobs();
  } else if (dismiss) {
    delete studio.jobs[dismiss.dataset.dismissJob];
    showJobs();
  }
});


// the limits the server sets, and a run still going after a reload
document.addEventListener("studio:state", (event) => {
  $("variant-count").max = event.detail.limits.variants;
  $("export-count").max = event.detail.limits.export;
  for (const job of event.detail.jobs) if (job.state === "running") follow(job);
});
})();
