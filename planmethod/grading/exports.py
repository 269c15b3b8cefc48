"""Exports from keys: Gradescope, PrairieLearn, Moodle XML and a CSV gradebook.

Each function returns file contents (``{relative path: text or bytes}``) and writes nothing;
the ``export`` command writes them atomically. The structures follow the targets' documents:

* **Gradescope** autograder results (``results.json``: top-level ``score``, ``output``,
  ``visibility``, ``stdout_visibility``, and ``tests`` with ``name``, ``score``, ``max_score``,
  ``status``, ``output``), and an autograder folder (``setup.sh``, ``run_autograder`` at its
  root, reading ``/autograder/submission`` and writing ``/autograder/results/results.json``).
* **PrairieLearn** v3 questions: ``info.json`` (``uuid``, ``title``, ``topic``, ``tags``,
  ``type: "v3"``), ``question.html`` with ``pl-question-panel`` (the task text and the task
  figure, a ``pl-figure`` of the variant's ``clientFilesQuestion/task_<n>_<student>.svg``: the
  mechanism at its position as the task sheet draws it), one ``pl-number-input``
  (``comparison="relabs"``, per-variant ``rtol``/``atol`` through mustache ``params``) per
  asked value, and a ``pl-drawing`` (``gradable``, ``tol`` in px) whose
  ``pl-drawing-answer`` holds one ``pl-point`` per plan point; ``server.py`` whose
  ``generate(data)`` picks the variant and fills ``data["params"]`` and
  ``data["correct_answers"]``, and whose ``grade(data)`` names the known mistake a misplaced
  point lies at, from the key's ``mistake_points`` (the workbook page names the same ones).
* **Moodle XML**: a ``<quiz>`` with a category and one embedded-answers (``cloze``) question
  per variant holding all its asked values, each ``{n:NUMERICAL:=value:tolerance#feedback~…}``
  with the absolute tolerance from the drawing scale and a 0 % answer with its feedback for each
  recognised mistake; the task sheet embedded as a base64 file.
* **CSV gradebook**: one row per student: score per question, total, maximum.

Examples
--------
>>> from planmethod.grading.templates import load_template, draw_variant
>>> from planmethod.grading.keys import build_key
>>> key = build_key(draw_variant(load_template("exercises/compressor_slider_crank.toml")))
>>> xml = moodle_xml([key])
>>> xml.count('<question type="cloze">'), xml.count(":NUMERICAL:")
(1, 7)
"""

from __future__ import annotations

import json
import math
import re
import uuid
from collections.abc import Iterable, Mapping
from typing import Any
from xml.sax.saxutils import escape

from ..io import csv_text, json_text
from ..vocabulary import shown_title, unit_words, xml_characters
from ..words import Message, message, render, template
from ..words.language import catalogue, current
from .answers import FEEDBACK_LEVELS, feedback_text
from .results import GradedDrawing, KeyQuestion, StudentGrade

__all__ = [
    "cloze_field",
    "gradebook_csv",
    "gradescope_autograder",
    "gradescope_results",
    "moodle_xml",
    "prairielearn_questions",
]

#: a double quote as XML writes it inside an attribute value
_QUOTE = {'"': "&quot;"}

#: PrairieLearn canvas pixels per drawn millimetre.
PX_PER_MM = 4.0

#: the files of a Gradescope autograder folder (:func:`gradescope_autograder`)
GRADESCOPE_FILES = ("setup.sh", "run_autograder", "grade_submission.py", "README.txt",
                    "keys.json")
#: the files of a PrairieLearn question folder (:func:`prairielearn_questions`), and the
#: folder of its task figures in it
PRAIRIELEARN_FILES = ("info.json", "question.html", "server.py")
PRAIRIELEARN_FIGURES = "clientFilesQuestion"


def _html(text: object) -> str:
    """Text set as HTML in the course's notation: escaped, what follows an underscore set as
    a subscript by the rule the figures, the task sheet and the workbook use
    (:func:`planmethod.render.workbook.formula_html`), so that ``|v_C|`` reads v with C below.

    >>> _html("speed of C, |v_C| <")
    'speed of C, |v<sub>C</sub>| &lt;'
    """
    from ..render.workbook import formula_html

    return formula_html(str(text))


def _identifier(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_]", "_", name)


def _format(value: float) -> str:
    return f"{value:.6g}"


def _spoken(sentence: Message) -> str:
    """A template in the language spoken, its fields left in it for code that fills them
    itself (an exported script, which cannot import planmethod)."""
    return catalogue(current()).gettext(sentence.template)


def _level(feedback: str) -> None:
    if feedback not in FEEDBACK_LEVELS:
        raise ValueError(render(message("feedback level {level!r} is not one of {levels}",
                                        level=feedback, levels=list(FEEDBACK_LEVELS))))


#: a drawn plan by its name (a Gradescope test's name)
PLAN_NAMES = {"velocity": message("velocity plan"),
              "acceleration": message("acceleration plan")}


# -- Gradescope ------------------------------------------------------------------------------
def gradescope_results(result: StudentGrade, drawings: Iterable[GradedDrawing] = (),
                       *, feedback: str = "hints") -> dict:
    """Gradescope's ``results.json`` for one graded submission (numeric answers and,
    optionally, drawn plans graded by :func:`~planmethod.grading.drawings.grade_drawing`).

    ``feedback`` is what the student sees of each question (see
    :func:`~planmethod.grading.answers.feedback_text`): ``hints`` (default) names the mistake
    and which way the answer is off without the right value; ``full`` gives the values;
    ``score`` only the points. A drawn plan's point-by-point feedback is shown at ``full``.
    """
    tests = []
    for number, question in enumerate(result.questions, start=1):
        tests.append({"name": question.id, "number": str(number),
                      "score": question.score, "max_score": question.max_score,
                      "status": "passed" if question.correct else "failed",
                      "output": render(feedback_text(question, feedback)),
                      "visibility": "visible"})
    score = float(result.score)
    for drawing in drawings:
        lines = ([point.feedback for point in drawing.points] + list(drawing.feedback)
                 if feedback == "full" else [])
        tests.append({"name": render(PLAN_NAMES[drawing.plan]), "score": drawing.score,
                      "max_score": drawing.max_score,
                      "status": "passed" if drawing.score == drawing.max_score
                      else "failed", "output": "\n".join(render(line) for line in lines),
                      "visibility": "visible"})
        score += float(drawing.score)
    output = render(result.error if result.error is not None else
                    message("Variant {variant}: {score:.6g} points.", variant=result.variant,
                            score=score))
    return {"score": score, "output": output, "visibility": "visible",
            "stdout_visibility": "hidden", "tests": tests}


#: the Python the exported autograder needs (pyproject's requires-python)
AUTOGRADER_PYTHON = "3.11"

_GRADE_SUBMISSION = r"""# Grade one Gradescope submission against the student's planmethod variant.
# Gradescope runs run_autograder, which runs this with the Python that setup.sh installed.
# Every path is under $AUTOGRADER_ROOT (default /autograder), so the same script runs end to
# end in a test folder.

import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(os.environ.get("AUTOGRADER_ROOT", "/autograder"))
SOURCE = Path(__file__).resolve().parent
RESULTS = ROOT / "results" / "results.json"
FEEDBACK = "@FEEDBACK@"


ROSTER = @ROSTER@
SUBMIT = @SUBMIT@
UNREADABLE = @UNREADABLE@
UNKNOWN = @UNKNOWN@


def finish(output):
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    RESULTS.write_text(json.dumps({"score": 0, "output": output, "visibility": "visible",
                                   "tests": []}))
    sys.exit(0)


def identities():
    # the submitter's e-mails, SIDs and names, lower case
    try:
        users = json.loads((ROOT / "submission_metadata.json").read_text())["users"]
    except (OSError, ValueError, KeyError, TypeError):
        return []
    found = []
    for user in users if isinstance(users, list) else []:
        for field in ("email", "sid", "name"):
            value = str((user or {}).get(field) or "").strip().lower()
            if value and value not in found:
                found.append(value)
    return found


def variant(bundle, who):
    # the key of the submitter: matched by id, e-mail or SID (any case); without a roster
    # (variants --count), picked from the submitter's e-mail by a hash, the same every time
    keys = bundle["keys"]
    for key in keys:
        names = {str(key.get("student", "")).lower()}
        names |= {str(alias).lower() for alias in key.get("identities", ())}
        if names & set(who):
            return key
    if not any(key.get("roster") for key in keys) and who:
        digest = hashlib.sha256(who[0].encode("utf-8")).hexdigest()
        return keys[int(digest, 16) % len(keys)]
    return None


def main():
    bundle = json.loads((SOURCE / "keys.json").read_text(encoding="utf-8"))
    who = identities()
    key = variant(bundle, who)
    if key is None:
        finish(ROSTER)
    submitted = [ROOT / "submission" / name for name in ("answers.json", "answers.csv")]
    answers = next((path for path in submitted if path.is_file()), None)
    if answers is None:
        finish(SUBMIT)
    done = subprocess.run([sys.executable, "-m", "planmethod", "grade", str(SOURCE / "keys.json"),
                           str(answers), "--student", str(key["student"]), "--feedback",
                           FEEDBACK, "--gradescope", str(RESULTS), "--quiet"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        finish(UNREADABLE.format(problem=(done.stderr.strip().splitlines() or
                                          [UNKNOWN])[-1]))


main()
"""

_RUN_AUTOGRADER = """#!/usr/bin/env bash
# Gradescope runs this for every submission (see grade_submission.py).
set -u
root="${AUTOGRADER_ROOT:-/autograder}"
python="${PLANMETHOD_PYTHON:-$root/venv/bin/python}"
[ -x "$python" ] || python=python3
exec "$python" "$(dirname "$0")/grade_submission.py"
"""

_SETUP = """#!/usr/bin/env bash
# Gradescope runs this once when the autograder image is built. planmethod needs Python
# @PYTHON@ or newer; Gradescope's Ubuntu 22.04 image ships 3.10, so a newer Python comes from
# the deadsnakes archive when the image's own is too old. Put planmethod's source folder
# (planmethod-src/) or a wheel next to this file before zipping.
set -eu
cd "$(dirname "$0")"
export DEBIAN_FRONTEND=noninteractive
apt-get update
python=python3
if ! python3 -c 'import sys; sys.exit(sys.version_info < (@PYTHON_TUPLE@))' 2>/dev/null; then
  apt-get install -y software-properties-common
  add-apt-repository -y ppa:deadsnakes/ppa
  apt-get update
  apt-get install -y python@PYTHON@ python@PYTHON@-venv
  python=python@PYTHON@
else
  apt-get install -y python3-venv
fi
"$python" -m venv /autograder/venv
if [ -d planmethod-src ]; then
  /autograder/venv/bin/pip install ./planmethod-src
else
  /autograder/venv/bin/pip install ./planmethod-*.whl
fi
"""


def gradescope_autograder(bundle: Mapping[str, Any], *, feedback: str = "hints"
                          ) -> dict[str, str]:
    """An autograder folder for Gradescope (zip its contents: ``setup.sh`` and
    ``run_autograder`` must sit at the zip's root).

    Students submit ``answers.json`` (``{"v_C": …}``) or ``answers.csv`` (one row). A
    submission is matched to its variant by the e-mail, SID or name in
    ``submission_metadata.json`` against the roster's ids and e-mails (any case); a bundle
    made without a roster (``variants --count``) gives each submitter the variant picked by
    a hash of their e-mail. ``feedback`` is the level the student sees (``hints``: no right
    values). Every path is under ``$AUTOGRADER_ROOT`` (default ``/autograder``).

    Parameters
    ----------
    bundle
        The bundle of keys (``keys.json``).
    feedback
        The feedback level students see.
    """
    _level(feedback)
    version = tuple(int(part) for part in AUTOGRADER_PYTHON.split("."))
    setup = (_SETUP.replace("@PYTHON_TUPLE@", ", ".join(map(str, version)))
             .replace("@PYTHON@", AUTOGRADER_PYTHON))
    readme = render(message("Gradescope autograder for planmethod variants.\n"
                            "1. Copy planmethod's source folder here as planmethod-src/ (or a "
                            "wheel).\n"
                            "2. Zip the contents of this folder (setup.sh and run_autograder at "
                            "the root).\n"
                            "3. setup.sh installs Python {python} if the image's is older.\n"
                            "4. Students submit answers.json or answers.csv with the question "
                            "ids:\n   {ids}\n", python=AUTOGRADER_PYTHON,
                            ids=[question["id"] for question in bundle["keys"][0]["questions"]]))
    texts = {"@ROSTER@": render(message("Your e-mail or SID is not on this assignment's "
                                        "roster: ask your instructor.")),
             "@SUBMIT@": render(message("Submit answers.json or answers.csv with your "
                                        "answers.")),
             "@UNREADABLE@": _spoken(template("Your answers could not be read: {problem}")),
             "@UNKNOWN@": render(message("unknown error"))}
    script = _GRADE_SUBMISSION.replace("@FEEDBACK@", feedback)
    for mark, text in texts.items():
        script = script.replace(mark, json.dumps(text, ensure_ascii=False))
    return dict(zip(GRADESCOPE_FILES, (setup, _RUN_AUTOGRADER, script, readme,
                                       json_text(bundle)), strict=True))


# -- PrairieLearn ----------------------------------------------------------------------------
def _canvas(entry: Mapping[str, Any], size_px: float, labels: list[str]) -> dict:
    centre = size_px / 2
    points = {}
    for label in labels:
        x, y = entry["points_mm"][label]
        points[_identifier(label)] = {"x": round(centre + x * PX_PER_MM, 2),
                                      "y": round(centre - y * PX_PER_MM, 2)}
    return points


def _canvas_mistakes(entry: Mapping[str, Any], size_px: float, labels: list[str]) -> dict:
    """Where the known mistakes put each point, in canvas px (those on the canvas)."""
    centre = size_px / 2
    out = {}
    for label in labels:
        found = [[mistake, round(centre + x * PX_PER_MM, 2), round(centre - y * PX_PER_MM, 2)]
                 for mistake, x, y in entry.get("mistake_points", {}).get(label, ())]
        found = [item for item in found if 0 <= item[1] <= size_px and 0 <= item[2] <= size_px]
        if found:
            out[_identifier(label)] = found
    return out


def _course_names(key: Mapping[str, Any]):
    """A plan label as the course writes it (``b@lever`` → b₃), from the key's exercise."""
    from ..model import FRAME
    from ..render.plan_words import label_text
    from ..vocabulary import link_numbers

    exercise = key.get("exercise") or {}
    links = list((exercise.get("links") or {}).keys())
    drive = str((exercise.get("drive") or {}).get("link", ""))
    numbers = link_numbers(links, drive, FRAME) if links and drive else {}
    return lambda label: label_text(label, numbers)


def _task_figure(key: Mapping[str, Any]) -> str | None:
    """The task figure of a key's variant (:func:`~planmethod.grading.sheets.task_figure_svg`),
    or None for a key that does not carry its exercise."""
    from ..plans import draw_plans
    from .keys import key_exercise
    from .sheets import task_figure_svg

    exercise = key_exercise(key)   # an error in its tables names the key's file
    if exercise is None:
        return None
    return task_figure_svg(draw_plans(exercise, acceleration=False))


# words: code written for PrairieLearn (its comments are for the course's developers)
_PRAIRIELEARN_SERVER = '''"""One planmethod variant per PrairieLearn variant (generated by
`planmethod export --format prairielearn`).

generate() picks the variant from PrairieLearn's data["variant_seed"], so a reload shows the
student the same numbers; grade() re-grades each numeric part with the tolerance that follows
from the drawing scale and says which way a wrong answer is off, never the right value, and
grades each drawn plan point by point, each point within its own tolerance disc; a point not
found is named with the known mistake a placed point lies at (the positions come from
planmethod's answer key; the workbook page names the same mistakes).
"""

import math
import random

VARIANTS = @VARIANTS@

#: what a student is told of a point drawn where a known mistake puts it (planmethod's
#: mistake registry), and how those are worded
MISTAKE_TEXTS = @MISTAKE_TEXTS@
MISTAKE_WORDING = @MISTAKE_WORDING@
#: what a student is told (planmethod's sentences, their fields filled in here)
TEXTS = @TEXTS@


@NAMED_MISTAKES@

@WORD_MISTAKES@


def _variant(data):
    return VARIANTS[random.Random(str(data["variant_seed"])).randrange(len(VARIANTS))]


def generate(data):
    variant = _variant(data)
    data["params"].update(variant["params"])
    data["correct_answers"].update(variant["correct_answers"])


def _grade_plan(points, radii, labels, submitted, mistakes=None):
    """(score, feedback): each plan point found within its disc (px) by one point the student
    placed (the pole is given, so each point fixes its vector from the pole); a point not
    found is named with the known mistake a free placed point lies at (``mistakes``: ident →
    [[mistake, x, y], …] in px)."""
    placed = [(float(o["left"]), float(o["top"])) for o in submitted or []
              if isinstance(o, dict) and o.get("gradingName") == "pl-point"
              and isinstance(o.get("left"), (int, float))
              and isinstance(o.get("top"), (int, float))]
    pairs = sorted((math.hypot(x - points[i]["x"], y - points[i]["y"]) / radii[i], i, k)
                   for i in points for k, (x, y) in enumerate(placed))
    found, used = {}, set()
    for ratio, ident, k in pairs:
        if ratio <= 1.0 and ident not in found and k not in used:
            found[ident] = k
            used.add(k)
    missing = [ident for ident in points if ident not in found]
    notes = []
    explained = 0
    for ident in missing:
        named = None
        for k, (x, y) in enumerate(placed):
            named = (None if k in used else
                     named_mistakes((mistakes or {}).get(ident, ()), x, y, radii[ident]))
            if named:
                used.add(k)
                explained += 1
                away = math.hypot(x - points[ident]["x"], y - points[ident]["y"]) / 4
                notes.append(TEXTS["mistaken"].format(
                    point=labels[ident], away=away,
                    where=word_mistakes(named, MISTAKE_TEXTS, MISTAKE_WORDING)))
                break
        if named:
            continue
        near = min((math.hypot(x - points[ident]["x"], y - points[ident]["y"])
                    for k, (x, y) in enumerate(placed) if k not in used), default=None)
        notes.append(TEXTS["missing"].format(point=labels[ident]) if near is None else
                     TEXTS["missing_near"].format(point=labels[ident], near=near / 4,
                                                  tolerance=radii[ident] / 4))
    extra = len(placed) - len(found) - explained
    if extra > 0:
        notes.append(TEXTS["extra"].format(count=extra))
    score = len(found) / max(len(points), len(placed), 1)
    feedback = "; ".join([TEXTS["found"].format(found=len(found), total=len(points)), *notes])
    return score, feedback


def grade(data):
    tolerance = data["params"].get("tolerance", {})
    scores = []
    for name, points in data["params"].get("plans", {}).items():
        answer = f"{name}_plan"
        score, feedback = _grade_plan(points, data["params"]["radius_px"][name],
                                      data["params"]["plan_labels"][name],
                                      data["submitted_answers"].get(answer),
                                      data["params"].get("mistakes_px", {}).get(name))
        data["partial_scores"][answer] = {"score": score, "weight": 1, "feedback": feedback}
    for name, right in data["correct_answers"].items():
        if name not in tolerance:
            continue
        answer = data["submitted_answers"].get(name)
        try:
            answer = float(answer)
        except (TypeError, ValueError):
            answer = None
        if answer is None:
            score, feedback = 0.0, TEXTS["no_number"]
        elif abs(answer - right) <= tolerance[name]:
            score, feedback = 1.0, TEXTS["correct"]
        elif right != 0 and answer != 0 and (answer > 0) != (right > 0):
            score, feedback = 0.0, TEXTS["sense"]
        else:
            score = 0.0
            feedback = TEXTS["high" if answer > right else "low"]
        data["partial_scores"][name] = {"score": score, "weight": 1, "feedback": feedback}
        scores.append(score)
    others = [part["score"] for name, part in data["partial_scores"].items()
              if name not in tolerance and isinstance(part.get("score"), (int, float))]
    parts = scores + others
    data["score"] = sum(parts) / len(parts) if parts else 0.0
'''


#: what the exported grader tells a student (its fields filled in by the grader)
_SERVER_TEXTS = {
    "no_number": template("no number given"),
    "correct": template("correct within the drawing's tolerance"),
    "sense": template("wrong: the sense (sign) is reversed"),
    "high": template("wrong: too high"),
    "low": template("wrong: too low"),
    "mistaken": template("{point} is not where the construction puts it: a point placed "
                         "{away:.1f} mm from it lies {where}"),
    "missing": template("{point} is not where the construction puts it"),
    "missing_near": template("{point} is not where the construction puts it (the nearest free "
                             "point is {near:.1f} mm away; tolerance {tolerance:.1f} mm)"),
    "extra": template("{count} point(s) more than the plan has"),
    "found": template("{found} of {total} plan points within the drawing's tolerance"),
}

#: what a student is asked to draw in a question, by plan
_DRAW = {"velocity": template("Draw the velocity plan at the given scale (one grid square is "
                              "10 mm of the drawing; the pole {pole} is marked): place the "
                              "points {points}."),
         "acceleration": template("Draw the acceleration plan at the given scale (one grid "
                                  "square is 10 mm of the drawing; the pole {pole} is marked): "
                                  "place the points {points}.")}


def _canvas_size(keys: list[Mapping[str, Any]], plans: list[str],
                 labels: Mapping[str, list[str]]) -> int:
    """The canvas (px, square) that holds every variant's plans with a margin."""
    extent = max([30.0] + [math.hypot(*key["plans"][name]["points_mm"][label])
                           for key in keys for name in plans for label in labels[name]
                           if label in key["plans"][name]["points_mm"]])
    return 40 * math.ceil((2 * extent * PX_PER_MM + 80) / 40)


def _answer_params(params: dict[str, Any], key: Mapping[str, Any], question_ids: list[str]
                   ) -> dict[str, float]:
    """Each question's tolerance as PrairieLearn's relabs compares (into ``params``); the
    right answers."""
    questions = {question.id: question for question in _questions(key)}
    correct: dict[str, Any] = {}
    for name in question_ids:
        value, tolerance = questions[name].value, questions[name].tolerance
        ident = _identifier(name)
        # relabs accepts |x − v| ≤ atol + rtol·|v|: put the whole tolerance in rtol
        # (atol a hair above zero for a zero answer)
        params["rtol"][ident] = tolerance / abs(value) if value else 0.0
        params["atol"][ident] = 1e-12 if value else tolerance
        correct[ident] = value
        params.setdefault("tolerance", {})[ident] = tolerance
    return correct


def _plan_params(params: dict[str, Any], key: Mapping[str, Any], plans: list[str],
                 labels: Mapping[str, list[str]], size_px: int) -> None:
    """Each plan's points, discs, names and mistakes on the canvas (into ``params``)."""
    name_of = _course_names(key)
    for name in plans:
        entry = key["plans"][name]
        drawn = [label for label in labels[name] if label in entry["points_mm"]]
        params["plans"][name] = _canvas(entry, size_px, drawn)
        # each point's own disc (px), at least half a millimetre of the drawing
        params["radius_px"][name] = {
            _identifier(label): round(max(0.5, entry["tolerance_mm"].get(label, 0.5))
                                      * PX_PER_MM, 2) for label in drawn}
        params["plan_labels"][name] = {_identifier(label): name_of(label) for label in drawn}
        params["mistakes_px"][name] = _canvas_mistakes(entry, size_px, drawn)
        params["tol_px"][name] = max(params["radius_px"][name].values(),
                                     default=round(0.5 * PX_PER_MM, 2))


def _variant(key: Mapping[str, Any], number: int, slug: str, question_ids: list[str],
             plans: list[str], labels: Mapping[str, list[str]], size_px: int,
             figures: dict[str, str]) -> dict[str, Any]:
    """One variant of the question: its parameters and right answers (its task figure into
    ``figures``)."""
    params: dict[str, Any] = {
        "student": key.get("student"), "title": shown_title(str(key.get("title", ""))),
        "task_html": "<p>" + _html(key.get("task", "")).replace("\n\n", "</p><p>")
        + "</p>", "rtol": {}, "atol": {}, "plans": {}, "tol_px": {}, "radius_px": {},
        "plan_labels": {}, "mistakes_px": {}}
    figure = _task_figure(key)
    if figure is not None:
        # numbered: two students whose ids differ only in punctuation get two files
        params["task_figure"] = f"task_{number}_{_identifier(str(key.get('student')))}.svg"
        figures[f"{slug}/{PRAIRIELEARN_FIGURES}/{params['task_figure']}"] = figure
    correct = _answer_params(params, key, question_ids)
    _plan_params(params, key, plans, labels, size_px)
    return {"params": params, "correct_answers": correct}


def _server(variants: list[dict[str, Any]]) -> str:
    """The question's ``server.py``: the variants, the mistakes' texts and the sentences, and
    the very source of the point rule it shares with planmethod."""
    import inspect

    from .mistakes import REGISTRY, drawn_explanation
    from .plan_points import named_mistakes, page_wording, word_mistakes

    texts = {mistake: render(drawn_explanation(mistake)) for mistake in REGISTRY}
    sentences = {name: _spoken(sentence) for name, sentence in _SERVER_TEXTS.items()}
    return (_PRAIRIELEARN_SERVER
            .replace("@MISTAKE_TEXTS@", json.dumps(texts, ensure_ascii=False, indent=1))
            .replace("@MISTAKE_WORDING@", repr(page_wording()[:2]))
            .replace("@TEXTS@", json.dumps(sentences, ensure_ascii=False, indent=1))
            .replace("@NAMED_MISTAKES@", inspect.getsource(named_mistakes).strip())
            .replace("@WORD_MISTAKES@", inspect.getsource(word_mistakes).strip())
            .replace("@VARIANTS@", json.dumps(variants, ensure_ascii=False, indent=1)))


def _drawing_html(first: Mapping[str, Any], name: str, labels: list[str],
                  size_px: int) -> list[str]:
    """The lines of one plan's drawing: what to draw, the canvas with the pole given, the
    points to place and the controls."""
    pole = first["plans"][name]["pole"]
    centre = size_px / 2
    first_names = _course_names(first)
    asked = render(_DRAW[name].replace(pole=pole,
                                       points=[first_names(label) for label in labels]))
    html = ["", f"<p>{escape(asked)}</p>",
            f'<pl-drawing answers-name="{name}_plan" gradable="true" width="{size_px}" '
            f'height="{size_px}" grid-size="{int(10 * PX_PER_MM)}" '
            f'tol="{{{{params.tol_px.{name}}}}}" show-tolerance-hint="true">',
            "  <pl-drawing-initial>",
            f'    <pl-point x1="{centre:g}" y1="{centre:g}" label="{pole}"></pl-point>',
            "  </pl-drawing-initial>", '  <pl-drawing-answer draw-error-box="true">']
    for label in labels:
        ident = _identifier(label)
        html.append(f'    <pl-point x1="{{{{params.plans.{name}.{ident}.x}}}}" '
                    f'y1="{{{{params.plans.{name}.{ident}.y}}}}" '
                    f'label="{escape(first_names(label))}"></pl-point>')
    points, delete = (escape(render(text), _QUOTE) for text in (message("Plan points:"),
                                                                  message("Delete:")))
    return [*html, "  </pl-drawing-answer>", "  <pl-controls>",
                   f'    <pl-controls-group label="{points}">',
                   '      <pl-drawing-button type="pl-point"></pl-drawing-button>',
                   "    </pl-controls-group>",
                   f'    <pl-controls-group label="{delete}">',
                   '      <pl-drawing-button type="delete"></pl-drawing-button>',
                   "    </pl-controls-group>", "  </pl-controls>", "</pl-drawing>"]


def _question_html(first: Mapping[str, Any], plans: list[str],
                   labels: Mapping[str, list[str]], size_px: int, figured: bool) -> str:
    """The question's ``question.html``: the task panel (with the variant's figure when every
    variant has one), a number input a question, a drawing a plan."""
    html = ["<pl-question-panel>", "  <p><b>{{params.title}}</b></p>",
            "  {{{params.task_html}}}"]
    if figured:       # every variant's mechanism, above the drawing
        html.append('  <pl-figure file-name="{{params.task_figure}}" '
                    'directory="clientFilesQuestion"></pl-figure>')
    html += ["</pl-question-panel>", ""]
    for question in first["questions"]:
        ident = _identifier(question["id"])
        html.append(
            f'<pl-number-input answers-name="{ident}" comparison="relabs" '
            f'rtol="{{{{params.rtol.{ident}}}}}" atol="{{{{params.atol.{ident}}}}}" '
            f'label="{escape(_html(question["text"]), _QUOTE)} =" '
            f'suffix="{escape(render(unit_words(question["unit"])), _QUOTE)}">'
            "</pl-number-input>")
    for name in plans:
        html += _drawing_html(first, name, labels[name], size_px)
    return "\n".join(html) + "\n"


def prairielearn_questions(bundle: Mapping[str, Any], *, slug: str = "planmethod",
                           topic: str | None = None) -> dict[str, str]:
    """A PrairieLearn question folder ``<slug>/`` for a bundle of keys: one question whose
    ``server.py`` draws one of the bundle's variants, with each variant's task figure in
    ``clientFilesQuestion/``.

    Parameters
    ----------
    bundle
        The bundle of keys (``keys.json``).
    slug
        The question folder's name.
    topic
        The question's topic (default: kinematics of mechanisms, in the language spoken).
    """
    from .plan_points import graded_labels

    keys = bundle["keys"]
    first = keys[0]
    question_ids = [q["id"] for q in first["questions"]]
    plans = [name for name in ("velocity", "acceleration") if name in first["plans"]]
    labels = {name: graded_labels(first["plans"][name]) for name in plans}
    size_px = _canvas_size(keys, plans, labels)
    figures: dict[str, str] = {}
    variants = [_variant(key, number, slug, question_ids, plans, labels, size_px, figures)
                for number, key in enumerate(keys, start=1)]
    seed = f"planmethod:{slug}:{first.get('title')}:{bundle.get('seed')}:{len(keys)}"
    info = {"uuid": str(uuid.uuid5(uuid.NAMESPACE_URL, seed)),
            "title": shown_title(str(first.get("title"))),
            "topic": topic if topic is not None else render(message("Kinematics of mechanisms")),
            "tags": ["planmethod", "graphical-method"], "type": "v3",
            "gradingMethod": "Internal"}
    texts = (json.dumps(info, indent=2, ensure_ascii=False) + "\n",
             _question_html(first, plans, labels, size_px, len(figures) == len(keys)),
             _server(variants))
    return {**{f"{slug}/{name}": text
               for name, text in zip(PRAIRIELEARN_FILES, texts, strict=True)}, **figures}


def _questions(key: Mapping[str, Any]) -> tuple[KeyQuestion, ...]:
    from .keys import key_questions

    return key_questions(key)


# -- Moodle ----------------------------------------------------------------------------------
def _cdata(text: str) -> str:
    return "<![CDATA[" + text.replace("]]>", "]]]]><![CDATA[>") + "]]>"


def _cloze_text(text: object) -> str:
    """Text of a Cloze question outside its fields (a title, the task, a student id, a
    question's words): HTML-escaped, and its braces written as character references, so that
    no text can open a field (``{1:MULTICHOICE:…}``) or repeat one (``{#1}``) — Moodle finds
    the fields in the HTML source before it decodes references.

    >>> _cloze_text("{1:MULTICHOICE:=a~b} <i>")
    '&#123;1:MULTICHOICE:=a~b&#125; &lt;i&gt;'
    """
    return _braces(escape(str(text)))


def _braces(html: str) -> str:
    return html.replace("{", "&#123;").replace("}", "&#125;")


def _category_name(name: object) -> str:
    """One name of a Moodle category path: a ``/`` in it doubled, as Moodle writes it, so
    that a title cannot make more categories (and XML-escaped)."""
    doubled = str(name).replace("/", "//")
    doubled = (" " if doubled.startswith("/") else "") + doubled
    return escape(doubled + (" " if doubled.endswith("/") else ""))


def _cloze_escape(text: str) -> str:
    """Text inside a Cloze answer or feedback: HTML-escaped, and Moodle's special characters
    escaped with a backslash (Moodle decodes the feedback's references when it reads it)."""
    text = escape(text)
    for char in ("\\", "}", "#", "~", "/", '"'):
        text = text.replace(char, "\\" + char)
    return text


def _cloze_number(value: float) -> str:
    return repr(float(value))


def cloze_field(question: KeyQuestion | Mapping[str, Any]) -> str:
    """One asked value (a key's question, typed or its table) as a Cloze NUMERICAL field: the
    right value with its tolerance (from the drawing scale), each recognised mistake as a 0 %
    answer with its feedback, and the feedback of a right answer. The question's points are
    the field's weight.

    Examples
    --------
    >>> print(cloze_field({"id": "s_C", "value": 0.27, "tolerance": 0.009, "unit": "m",
    ...                    "points": 2, "mistakes": []}))
    {2:NUMERICAL:=0.27:0.009#Right: within the drawing's tolerance ± 0.009 m.}
    """
    if not isinstance(question, KeyQuestion):
        question = KeyQuestion.read(question)
    points = max(1, round(question.points))
    tolerance = question.tolerance
    right = _cloze_escape(render(
        message("Right: within the drawing's tolerance ± {tolerance:.3g} {unit}.",
                tolerance=tolerance, unit=unit_words(question.unit)) if question.unit else
        message("Right: within the drawing's tolerance ± {tolerance:.3g}.",
                tolerance=tolerance)))
    parts = [f"={_cloze_number(question.value)}:{_cloze_number(tolerance)}#{right}"]
    for mistake in question.mistakes:
        feedback = _cloze_escape(render(message("It looks as if {mistake}.",
                                                mistake=mistake.explanation)))
        parts.append(f"%0%{_cloze_number(mistake.value)}:"
                     f"{_cloze_number(mistake.tolerance)}#{feedback}")
    return "{" + f"{points}:NUMERICAL:" + "~".join(parts) + "}"


def moodle_xml(keys: list[Mapping[str, Any]], *, category: str = "planmethod",
               sheets: Mapping[str, str] | None = None) -> str:
    """A Moodle XML quiz: a category, then for every variant one embedded-answers (Cloze)
    question holding all its asked values (:func:`cloze_field`), with the task text and the
    variant's task sheet embedded as an SVG file (``@@PLUGINFILE@@``) when ``sheets`` maps the
    student to it.

    Parameters
    ----------
    keys
        The keys of the variants.
    category
        The question category.
    sheets
        Student → task sheet SVG text, to embed (optional).
    """
    out = ['<?xml version="1.0" encoding="UTF-8"?>', "<quiz>"]
    title = shown_title(str(keys[0].get("title", "planmethod")) if keys else "planmethod")
    out += ['  <question type="category">',
            f"    <category><text>$course$/top/{_category_name(category)}/"
            f"{_category_name(title)}</text>"
            "</category>", "  </question>"]
    for key in keys:
        student = str(key.get("student"))
        text, files = _cloze_question(key, title, student, sheets)
        out += ['  <question type="cloze">',
                f"    <name><text>{escape(title)} — {escape(student)}</text></name>",
                f'    <questiontext format="html"><text>{_cdata(text)}</text>{files}'
                "</questiontext>",
                '    <generalfeedback format="html"><text></text></generalfeedback>',
                "    <penalty>0.3333333</penalty>", "    <hidden>0</hidden>",
                f"    <idnumber>{escape(student)}</idnumber>", "  </question>"]
    out.append("</quiz>")
    return xml_characters("\n".join(out) + "\n")     # no control character of a file


def _cloze_question(key: Mapping[str, Any], title: str, student: str,
                    sheets: Mapping[str, str] | None) -> tuple[str, str]:
    """(the question's text, its embedded files) of one variant's Cloze question."""
    import base64

    task = _braces(_html(key.get("task", ""))).replace("\n\n", "</p><p>")
    image, files = "", ""
    if sheets and student in sheets:
        name = f"sheet_{_identifier(student)}.svg"
        data = base64.b64encode(sheets[student].encode("utf-8")).decode("ascii")
        alt = escape(render(message("the mechanism, task sheet")), _QUOTE)
        image = f'<p><img src="@@PLUGINFILE@@/{name}" alt="{alt}" /></p>'
        files = f'<file name="{name}" path="/" encoding="base64">{data}</file>'
    # words: vocabulary (a question's text and a unit alone: its text until it is a message)
    rows = "".join(
        f"<tr><td>{_braces(_html(question['text']))}</td><td>{cloze_field(question)}</td>"
        f"<td>{_cloze_text(render(unit_words(question.get('unit', ''))))}</td></tr>"
        for question in key["questions"])
    variant = _cloze_text(render(message("— variant {student}", student=student)))
    give = _cloze_text(render(message("Give in SI units (counter-clockwise positive):")))
    return (f"<p><b>{_cloze_text(title)}</b> {variant}</p><p>{task}</p>"
            f"{image}<p>{give}</p><table>{rows}</table>"), files


# -- CSV gradebook ---------------------------------------------------------------------------
def gradebook_csv(results: list[StudentGrade]) -> str:
    """One row per student: variant, score per question, total and maximum (text cells made
    safe to open in a spreadsheet: :func:`~planmethod.io.csv_text`).

    Parameters
    ----------
    results
        Graded students, as :func:`~planmethod.grading.answers.grade_many` returns.
    """
    ids: list[str] = []
    for result in results:
        for question in result.questions:
            if question.id not in ids:
                ids.append(question.id)
    rows: list[list[Any]] = [["student", "variant", *ids, "total", "max", "note"]]
    for result in results:
        scores = {question.id: question.score for question in result.questions}
        rows.append([result.student, result.variant if result.variant is not None else "",
                     *[_format(scores[i]) if i in scores else "" for i in ids],
                     _format(float(result.score)),
                     "" if result.max_score is None else _format(float(result.max_score)),
                     render(result.error) if result.error is not None else ""])
    return csv_text(rows)
