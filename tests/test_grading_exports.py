"""LMS exports checked against the targets' documented structure, and the three commands
end to end: template → variants → grade → export."""

from __future__ import annotations

import csv
import html
import io
import json
import re
import uuid
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import numpy as np
import pytest

from planmethod.cli import main
from planmethod.grading.answers import grade_many
from planmethod.grading.exports import (
    gradebook_csv,
    gradescope_autograder,
    gradescope_results,
    moodle_xml,
    prairielearn_questions,
)
from planmethod.grading.keys import build_key, bundle
from planmethod.grading.plan_points import graded_labels
from planmethod.grading.results import GradedQuestion, StudentGrade
from planmethod.grading.templates import draw_variant, load_template
from planmethod.testing.pseudo import texts_of_html

TEMPLATE = "exercises/templates/four_bar.toml"
EXAMPLE = "exercises/templates/slider_crank_answers_example.csv"


@pytest.fixture(scope="module")
def keys():
    template = load_template(TEMPLATE)
    return [build_key(draw_variant(template, seed=5, student=s)) for s in ("ann", "bob", "cy")]


def _cloze_fields(text: str) -> list[dict]:
    """Moodle's embedded answers read back: every {n:NUMERICAL:…} field with its weight and
    answers (fraction, value, tolerance, feedback), special characters unescaped."""
    fields = []
    for match in re.finditer(r"\{(\d+):NUMERICAL:((?:\\.|[^}])*)\}", text):
        answers = []
        for part in re.split(r"(?<!\\)~", match.group(2)):
            head, *rest = re.split(r"(?<!\\)#", part, maxsplit=1)
            feedback = rest[0] if rest else ""
            fraction = 100.0 if head.startswith("=") else float(
                re.match(r"%(-?[\d.]+)%", head).group(1))
            number = re.sub(r"^=|^%-?[\d.]+%", "", head)
            value, tolerance = number.split(":")
            answers.append({"fraction": fraction, "value": float(value),
                            "tolerance": float(tolerance),
                            "feedback": re.sub(r"\\(.)", r"\1", feedback)})
        fields.append({"weight": int(match.group(1)), "answers": answers})
    return fields


def test_moodle_xml_is_one_cloze_question_per_variant(keys):
    """Parsed back: a category, then one Cloze question per variant whose fields are, in
    order, its asked values — the right value with the drawing's tolerance first, then the
    recognised mistakes at 0 % with their feedback."""
    pytest.importorskip("defusedxml")
    from defusedxml.ElementTree import fromstring

    root = fromstring(moodle_xml(keys, sheets={"ann": "<svg/>"}))
    assert root.tag == "quiz"
    questions = root.findall("question")
    assert questions[0].get("type") == "category"
    assert "$course$/top/planmethod/" in questions[0].findtext("category/text")
    cloze = questions[1:]
    assert [q.get("type") for q in cloze] == ["cloze"] * len(keys)
    for element, key in zip(cloze, keys, strict=True):
        assert element.findtext("idnumber") == key["student"]
        text = element.findtext("questiontext/text")
        assert element.find("questiontext").get("format") == "html"
        fields = _cloze_fields(text)
        assert len(fields) == len(key["questions"])
        for field, question in zip(fields, key["questions"], strict=True):
            right, *mistakes = field["answers"]
            assert right["fraction"] == 100.0
            assert right["value"] == question["value"]              # full precision
            assert right["tolerance"] == question["tolerance"]      # absolute, from the scale
            assert field["weight"] == max(1, round(question["points"]))
            assert len(mistakes) == len(question["mistakes"])
            for answer, mistake in zip(mistakes, question["mistakes"], strict=True):
                assert answer["fraction"] == 0.0 and answer["value"] == mistake["value"]
                assert mistake["feedback"] in answer["feedback"]
            assert str(question["value"])[:6] not in right["feedback"]   # no value given away
    ann = cloze[0]
    assert ann.find("questiontext/file").get("encoding") == "base64"
    assert "@@PLUGINFILE@@/sheet_ann.svg" in ann.findtext("questiontext/text")


def test_gradescope_results_structure(keys):
    answers = {q["id"]: q["value"] for q in keys[0]["questions"]}
    answers[keys[0]["questions"][0]["id"]] = 0.0
    (result,) = grade_many({"ann": keys[0]}, [("ann", answers)])
    results = gradescope_results(result)
    assert set(results) >= {"score", "tests", "output"}
    assert results["visibility"] in ("hidden", "after_due_date", "after_published", "visible")
    assert results["score"] == sum(t["score"] for t in results["tests"])
    assert results["score"] == len(keys[0]["questions"]) - 1
    for test in results["tests"]:
        assert set(test) >= {"name", "score", "max_score", "output"}
        assert test["status"] in ("passed", "failed")
    json.dumps(results, allow_nan=False)


def test_gradescope_results_list_each_question_then_each_drawn_plan(keys):
    """Gradescope's results.json: one test per question, numbered from 1, then one per drawn
    plan; a test passes when it has full marks; the total is the answers' score plus the
    plans'; what each says follows the feedback level."""
    from planmethod.grading.answers import feedback_text
    from planmethod.grading.drawings import Drawing, grade_drawing

    key = keys[0]
    answers = {q["id"]: q["value"] for q in key["questions"]}
    answers[key["questions"][0]["id"]] = 0.0
    (result,) = grade_many({"ann": key}, [("ann", answers)])
    right = {k: tuple(v) for k, v in key["plans"]["velocity"]["points_mm"].items()}
    moved = dict(right, c=(right["c"][0] + 5.0, right["c"][1]))
    drawings = [grade_drawing(key, Drawing(right, "velocity")),
                grade_drawing(key, Drawing(moved, "velocity"))]
    graded, drawn = result.as_dict(), [drawing.as_dict() for drawing in drawings]
    for level in ("full", "hints", "score"):
        results = gradescope_results(result, drawings, feedback=level)
        questions = [{"name": q["id"], "number": str(number), "score": q["score"],
                      "max_score": q["max_score"],
                      "status": "passed" if q["correct"] else "failed",
                      "output": feedback_text(q, level), "visibility": "visible"}
                     for number, q in enumerate(graded["questions"], start=1)]
        plans = [{"name": "velocity plan", "score": d["score"], "max_score": d["max_score"],
                  "status": status,
                  "output": "\n".join([p["feedback"] for p in d["points"]] + d["feedback"])
                  if level == "full" else "", "visibility": "visible"}
                 for d, status in zip(drawn, ("passed", "failed"), strict=True)]
        total = graded["score"] + drawn[0]["score"] + drawn[1]["score"]
        assert results == {"score": total, "output": f"Variant {key['student']}: {total:g} points.",
                           "visibility": "visible", "stdout_visibility": "hidden",
                           "tests": questions + plans}
    assert questions[0]["status"] == "failed" and questions[1]["status"] == "passed"
    shown = gradescope_results(result, drawings, feedback="full")["tests"][-1]["output"]
    assert shown.startswith("b: within") and "\nc is 5.0 mm off" in shown
    # a student without a key: the error is the whole output, and nothing is scored
    (lost,) = grade_many({"ann": key}, [("zed", answers)])
    assert gradescope_results(lost) == {"score": 0.0, "output": "no key for student 'zed'",
                                        "visibility": "visible", "stdout_visibility": "hidden",
                                        "tests": []}
    assert gradescope_results(StudentGrade(None, None, 0.0, None)) == {
        "score": 0.0, "output": "Variant None: 0 points.",
        "visibility": "visible", "stdout_visibility": "hidden", "tests": []}


def test_gradescope_autograder_folder(keys):
    files = gradescope_autograder(bundle(keys))
    assert {"setup.sh", "run_autograder", "keys.json"} <= set(files)
    run = files["run_autograder"]
    assert run.startswith("#!/usr/bin/env bash") and "${AUTOGRADER_ROOT:-/autograder}" in run
    grader = files["grade_submission.py"]
    assert 'os.environ.get("AUTOGRADER_ROOT", "/autograder")' in grader
    assert "submission_metadata.json" in grader and '"results" / "results.json"' in grader
    compile(grader, "grade_submission.py", "exec")
    setup = files["setup.sh"].splitlines()
    installs = [i for i, line in enumerate(setup) if "apt-get install" in line]
    updates = [i for i, line in enumerate(setup) if line.strip() == "apt-get update"]
    assert installs and updates and updates[0] < installs[0]   # the index before installing
    assert "sys.version_info < (3, 11)" in files["setup.sh"]
    # the deadsnakes Python it falls back on is named in full, no placeholder left
    assert "  apt-get install -y python3.11 python3.11-venv" in setup
    assert "  python=python3.11" in setup and "@" not in files["setup.sh"]
    assert json.loads(files["keys.json"])["format"] == "planmethod-keys"


def test_prairielearn_canvas_holds_every_variants_plan_and_the_mistakes_on_it():
    """The canvas is the smallest multiple of 40 px that keeps every variant's plan points
    40 px inside its edges (at least a 30 mm radius round the pole, 4 px a millimetre); each
    point is there in px, y down; every position a mistake gives that lies on the canvas is
    exported, and none off it; the task's paragraphs become HTML paragraphs, escaped; the
    drawing's hint tolerance is the largest point disc."""
    key = build_key(draw_variant(load_template("exercises/slotted_lever.toml")))
    key["task"] = "Find x < y.\n\nThen draw."
    files = prairielearn_questions(bundle([key]), slug="q")
    info = json.loads(files["q/info.json"])
    assert info["topic"] == "Kinematics of mechanisms" and info["type"] == "v3"
    namespace: dict = {}
    exec(compile(files["q/server.py"], "server.py", "exec"), namespace)  # our own code
    data = {"params": {}, "correct_answers": {}, "variant_seed": 1}
    namespace["generate"](data)
    params = data["params"]
    assert params["task_html"] == "<p>Find x &lt; y.</p><p>Then draw.</p>"
    size = float(re.search(r'answers-name="velocity_plan"[^>]*width="(\d+)"',
                           files["q/question.html"]).group(1))
    extent = max([30.0] + [float(np.hypot(*key["plans"][plan]["points_mm"][label]))
                           for plan in ("velocity", "acceleration")
                           for label in graded_labels(key["plans"][plan])])
    assert size % 40 == 0 and 2 * extent * 4 + 80 <= size < 2 * extent * 4 + 120
    for plan in ("velocity", "acceleration"):
        entry = key["plans"][plan]
        for label in graded_labels(entry):
            x, y = entry["points_mm"][label]
            ident = label.replace("@", "_")
            assert params["plans"][plan][ident] == {"x": round(size / 2 + 4 * x, 2),
                                                    "y": round(size / 2 - 4 * y, 2)}
            on_canvas = [[mistake, round(size / 2 + 4 * mx, 2), round(size / 2 - 4 * my, 2)]
                         for mistake, mx, my in entry["mistake_points"].get(label, ())
                         if 0 <= size / 2 + 4 * mx <= size and 0 <= size / 2 - 4 * my <= size]
            assert params["mistakes_px"][plan].get(ident, []) == on_canvas
        assert params["tol_px"][plan] == max(params["radius_px"][plan].values())
    assert any(len(entry["mistake_points"].get(label, ())) > len(
        params["mistakes_px"]["acceleration"].get(label.replace("@", "_"), []))
        for entry in [key["plans"]["acceleration"]] for label in entry["mistake_points"])


def _resolve(template: str, params: dict) -> str:
    def value(match):
        node = {"params": params}
        for part in match.group(1).split("."):
            node = node[part]
        return str(node)

    return re.sub(r"\{\{\{?([A-Za-z0-9_.]+)\}?\}\}", value, template)


def test_prairielearn_question_structure(keys):
    files = prairielearn_questions(bundle(keys, seed=5), slug="fourbar")
    info = json.loads(files["fourbar/info.json"])
    uuid.UUID(info["uuid"])
    assert info["type"] == "v3" and info["title"] and info["topic"]
    assert isinstance(info["tags"], list)
    namespace: dict = {}
    exec(compile(files["fourbar/server.py"], "server.py", "exec"), namespace)  # our own code
    seen = set()
    for seed in range(60):
        data = {"params": {}, "correct_answers": {}, "variant_seed": seed}
        namespace["generate"](data)
        again = {"params": {}, "correct_answers": {}, "variant_seed": seed}
        namespace["generate"](again)
        assert again == data            # a reload shows the same variant
        seen.add(data["params"]["student"])
        html = _resolve(files["fourbar/question.html"], data["params"])
        assert "{{" not in html
        root = ElementTree.fromstring(f"<root>{html}</root>")
        key = next(k for k in keys if k["student"] == data["params"]["student"])
        inputs = root.findall("pl-number-input")
        assert [i.get("answers-name") for i in inputs] == [q["id"] for q in key["questions"]]
        for element, question in zip(inputs, key["questions"], strict=True):
            assert element.get("comparison") == "relabs"
            value = data["correct_answers"][element.get("answers-name")]
            accepted = float(element.get("atol")) + float(element.get("rtol")) * abs(value)
            assert accepted == pytest.approx(question["tolerance"], rel=1e-9, abs=1e-11)
        for drawing in root.findall("pl-drawing"):
            assert drawing.get("gradable") == "true" and float(drawing.get("tol")) > 0
            plan = drawing.get("answers-name").removesuffix("_plan")
            points = drawing.findall("pl-drawing-answer/pl-point")
            assert points and all(p.get("x1") and p.get("y1") for p in points)
            entry = key["plans"][plan]
            for point in points:
                x, y = entry["points_mm"][point.get("label")]
                centre = float(drawing.get("width")) / 2
                assert float(point.get("x1")) == pytest.approx(centre + 4 * x, abs=0.01)
                assert float(point.get("y1")) == pytest.approx(centre - 4 * y, abs=0.01)
    assert seen == {"ann", "bob", "cy"}


def test_gradebook_csv(keys):
    rows = [(k["student"], {q["id"]: q["value"] for q in k["questions"]}) for k in keys]
    rows.append(("dan", {}))
    text = gradebook_csv(grade_many({k["student"]: k for k in keys}, rows))
    table = list(csv.DictReader(io.StringIO(text)))
    assert [r["student"] for r in table] == ["ann", "bob", "cy", "dan"]
    assert table[0]["total"] == table[0]["max"] == str(len(keys[0]["questions"]))
    assert "no key for student 'dan'" in table[3]["note"]


def test_the_instructor_workflow_end_to_end(tmp_path, capsys):
    out = tmp_path / "course"
    roster = tmp_path / "roster.csv"
    roster.write_text("email,name\nann@uni.edu,Ann\nbob@uni.edu,Bob\n")
    assert main(["variants", "exercises/templates/slider_crank.toml", "--students",
                 str(roster), "--seed", "3", "--out", str(out)]) == 0
    for student in ("ann@uni.edu", "bob@uni.edu"):
        folder = out / student
        for name in ("exercise.toml", "key.json", "task.svg", "task.txt",
                     "velocity_sheet.svg", "acceleration_sheet.svg"):
            assert (folder / name).stat().st_size > 0, name
    # a variant is a plain exercise file: `planmethod solve` reads it
    assert main(["solve", str(out / "ann@uni.edu" / "exercise.toml")]) == 0
    keys = json.loads((out / "keys.json").read_text())["keys"]
    answers = tmp_path / "answers.csv"
    ids = [q["id"] for q in keys[0]["questions"]]
    answers.write_text("email," + ",".join(ids) + "\n" + "\n".join(
        k["student"] + "," + ",".join(f"{q['value']:.5g}" for q in k["questions"])
        for k in keys) + "\n")
    capsys.readouterr()
    assert main(["grade", str(out), str(answers), "--csv", str(tmp_path / "gb.csv"),
                 "--quiet"]) == 0
    printed = capsys.readouterr().out
    assert f"ann@uni.edu: {len(ids)}/{len(ids)}" in printed
    assert main(["export", str(out / "keys.json"), "--format", "moodle", "--out",
                 str(tmp_path / "quiz.xml")]) == 0
    quiz = ElementTree.parse(tmp_path / "quiz.xml").getroot()
    assert len(quiz.findall("question")) == 1 + 2   # a category, one Cloze per student
    assert all(q.findtext("questiontext/text").count(":NUMERICAL:") == len(ids)
               for q in quiz.findall("question")[1:])
    # variants are reproducible from (template, seed, student)
    again = tmp_path / "again"
    assert main(["variants", "exercises/templates/slider_crank.toml", "--students",
                 str(roster), "--seed", "3", "--out", str(again), "--no-sheets"]) == 0
    assert (again / "keys.json").read_text() == (out / "keys.json").read_text()


@pytest.mark.parametrize("argv", [
    ["variants", "exercises/templates/slider_crank.toml", "--count", "0"],
    ["variants", "no/such/template.toml", "--count", "2"],
    ["grade", "exercises/templates/slider_crank.toml", EXAMPLE],   # random: needs keys.json
    ["grade", "exercises/compressor_slider_crank.toml", "tests/data/grading/junk_malformed.svg"],
    ["grade", "exercises/compressor_slider_crank.toml", "--drawing",
     "tests/data/grading/junk_external.svg"],
    ["export", "exercises/compressor_slider_crank.toml", "--format", "csv"],
])
def test_bad_input_is_one_line_exit_2_and_writes_nothing(tmp_path, capsys, argv):
    target = tmp_path / "out"
    argv = [*argv, "--out", str(target)] if argv[0] != "grade" else [
        *argv, "--json", str(target)]
    assert main(argv) == 2
    error = capsys.readouterr().err.strip()
    assert error.startswith("planmethod: error: ") and "\n" not in error
    assert not target.exists()


def test_grading_the_seed_answers_from_the_command_line(capsys):
    assert main(["grade", "exercises/compressor_slider_crank.toml",
                 "tests/data/grading/compressor_paper_answers.csv"]) == 0
    printed = capsys.readouterr().out
    assert "paper: 0/7" in printed
    assert "v_C = 4 m/s: wrong — 24.1 % low" in printed
    assert Path(EXAMPLE).is_file()


# -- Gradescope, end to end ---------------------------------------------------------------------
def _autograder(tmp_path, roster: str | None, count: int = 3):
    """variants (from a roster or --count) → export --format gradescope into
    <root>/source, as Gradescope unpacks an autograder."""
    from planmethod.cli import main

    root = tmp_path / "autograder"
    argv = ["variants", "exercises/templates/slider_crank.toml", "--out",
            str(tmp_path / "run"), "--no-sheets"]
    if roster is not None:
        (tmp_path / "roster.csv").write_text(roster)
        argv += ["--students", str(tmp_path / "roster.csv")]
    else:
        argv += ["--count", str(count)]
    assert main(argv) == 0
    assert main(["export", str(tmp_path / "run"), "--format", "gradescope", "--out",
                 str(root / "source")]) == 0
    return root, json.loads((tmp_path / "run" / "keys.json").read_text())["keys"]


def _submit(root, user: dict, answers: dict | None) -> dict:
    """Run run_autograder as Gradescope does (bash, in $AUTOGRADER_ROOT) on one submission."""
    import os
    import subprocess
    import sys

    (root / "submission").mkdir(parents=True, exist_ok=True)
    for old in (root / "submission").iterdir():
        old.unlink()
    (root / "results").mkdir(exist_ok=True)
    (root / "submission_metadata.json").write_text(json.dumps({"users": [user]}))
    if answers is not None:
        (root / "submission" / "answers.json").write_text(json.dumps(answers))
    env = {**os.environ, "AUTOGRADER_ROOT": str(root), "PLANMETHOD_PYTHON": sys.executable,
           "PYTHONPATH": str(Path(__file__).resolve().parent.parent)}
    done = subprocess.run(["bash", str(root / "source" / "run_autograder")], env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    results = json.loads((root / "results" / "results.json").read_text())
    # Gradescope's results format: a score, and tests with name, score, max_score, output
    assert isinstance(results["score"], int | float) and isinstance(results["tests"], list)
    for test in results["tests"]:
        assert {"name", "score", "max_score", "output"} <= set(test)
    return results


def _right(key) -> dict:
    return {q["id"]: q["value"] for q in key["questions"]}


def test_gradescope_roster_by_id_and_by_email_in_any_case(tmp_path):
    root, keys = _autograder(tmp_path, "student,email\nann,Ann@Uni.EDU\nbob,bob@uni.edu\n")
    by_student = {k["student"]: k for k in keys}
    # matched by e-mail, whatever its case: full marks with bob's own answers
    results = _submit(root, {"email": "BOB@uni.edu", "sid": "", "name": "Bob"},
                      _right(by_student["bob"]))
    assert results["score"] == len(by_student["bob"]["questions"])
    results = _submit(root, {"email": "ann@uni.edu"}, _right(by_student["ann"]))
    assert results["score"] == len(by_student["ann"]["questions"])
    # matched by id (a SID equal to the roster's student id)
    results = _submit(root, {"email": "x@y.z", "sid": "ann"}, _right(by_student["ann"]))
    assert results["score"] == len(by_student["ann"]["questions"])
    # not on the roster: a message, no score
    results = _submit(root, {"email": "eve@uni.edu"}, _right(by_student["ann"]))
    assert results["score"] == 0 and "roster" in results["output"]
    # no answers file
    results = _submit(root, {"email": "ann@uni.edu"}, None)
    assert results["score"] == 0 and "answers.json" in results["output"]


def test_gradescope_without_a_roster_gives_each_submitter_a_stable_variant(tmp_path):
    root, keys = _autograder(tmp_path, None, count=3)
    user = {"email": "carol@uni.edu", "sid": "", "name": "Carol"}
    scores = {key["student"]: _submit(root, user, _right(key))["score"] for key in keys}
    # exactly one variant is carol's (its answers get full marks), and it stays hers
    full = [student for student, score in scores.items()
            if score == len(keys[0]["questions"])]
    assert len(full) == 1
    again = next(k for k in keys if k["student"] == full[0])
    assert _submit(root, user, _right(again))["score"] == len(again["questions"])


def test_gradescope_hints_never_show_the_right_value(tmp_path):
    root, keys = _autograder(tmp_path, "student,email\nann,ann@uni.edu\n")
    answers = {q["id"]: 3 * q["value"] + 1.0 for q in keys[0]["questions"]}
    results = _submit(root, {"email": "ann@uni.edu"}, answers)
    assert results["score"] == 0
    for test, question in zip(results["tests"], keys[0]["questions"], strict=True):
        assert test["output"].startswith(question["symbol"]) and "wrong" in test["output"]
        assert f"{question['value']:.6g}" not in test["output"], test["output"]
        assert "right" not in test["output"]


def test_the_autograder_installs_the_python_the_package_requires():
    import tomllib

    from planmethod.grading.exports import AUTOGRADER_PYTHON

    project = tomllib.loads((Path(__file__).resolve().parent.parent / "pyproject.toml")
                            .read_text())["project"]
    assert project["requires-python"] == f">={AUTOGRADER_PYTHON}"


def test_prairielearn_grade_uses_the_drawing_tolerance_and_hides_the_value(keys):
    files = prairielearn_questions(bundle(keys, seed=5), slug="fourbar")
    namespace: dict = {}
    exec(compile(files["fourbar/server.py"], "server.py", "exec"), namespace)  # our own code
    data = {"params": {}, "correct_answers": {}, "variant_seed": 12345}
    namespace["generate"](data)
    key = next(k for k in keys if k["student"] == data["params"]["student"])
    questions = key["questions"]
    first, second, third = (q["id"] for q in questions[:3])
    submitted = {q["id"]: q["value"] for q in questions}
    submitted[first] = questions[0]["value"] + 0.9 * questions[0]["tolerance"]  # inside
    submitted[second] = questions[1]["value"] + 1.1 * questions[1]["tolerance"]  # outside
    submitted[third] = "twelve"
    plans = data["params"]["plans"]
    for name, points in plans.items():     # every plan drawn right
        submitted[f"{name}_plan"] = [{"gradingName": "pl-point", "left": p["x"], "top": p["y"]}
                                     for p in points.values()]
    data.update(submitted_answers=submitted, partial_scores={})
    namespace["grade"](data)
    parts = data["partial_scores"]
    assert parts[first]["score"] == 1.0 and parts[second]["score"] == 0.0
    assert parts[third]["score"] == 0.0 and "no number" in parts[third]["feedback"]
    assert "too high" in parts[second]["feedback"] or "reversed" in parts[second]["feedback"]
    assert f"{questions[1]['value']:.4g}" not in parts[second]["feedback"]
    assert all(parts[f"{name}_plan"]["score"] == 1.0 for name in plans)
    count = len(questions) + len(plans)
    assert data["score"] == pytest.approx((count - 2) / count)


def test_prairielearn_grades_a_plan_point_by_point_within_each_disc(keys):
    """Each plan point is found within its own tolerance disc (the key's, in px); the feedback
    names the points not found and how far the nearest free point is, never where they go."""
    files = prairielearn_questions(bundle(keys, seed=5), slug="fourbar")
    namespace: dict = {}
    exec(compile(files["fourbar/server.py"], "server.py", "exec"), namespace)  # our own code
    data = {"params": {}, "correct_answers": {}, "variant_seed": 7}
    namespace["generate"](data)
    params = data["params"]
    points, radii = params["plans"]["velocity"], params["radius_px"]["velocity"]
    labels = params["plan_labels"]["velocity"]
    key = next(k for k in keys if k["student"] == params["student"])
    entry = key["plans"]["velocity"]
    for ident, label in labels.items():        # the discs are the key's, 4 px a millimetre
        assert radii[ident] == pytest.approx(max(0.5, entry["tolerance_mm"][label]) * 4,
                                             abs=0.01)
    idents = list(points)
    moved, dropped = idents[0], idents[-1]
    placed = []
    for ident in idents:
        if ident == dropped:
            continue
        x, y = points[ident]["x"], points[ident]["y"]
        shift = (0.8 if ident != moved else 1.5) * radii[ident]   # inside / outside its disc
        placed.append({"gradingName": "pl-point", "left": x + shift, "top": y})
    placed.append({"gradingName": "pl-point", "left": 1.0, "top": 1.0})    # a stray point
    placed.append({"gradingName": "pl-line", "x1": 0, "y1": 0})           # not a point
    data.update(submitted_answers={"velocity_plan": placed}, partial_scores={})
    namespace["grade"](data)
    part = data["partial_scores"]["velocity_plan"]
    found = len(idents) - 2
    assert part["score"] == pytest.approx(found / len(idents))
    feedback = part["feedback"]
    assert feedback.startswith(f"{found} of {len(idents)} plan points")
    assert labels[moved] in feedback and labels[dropped] in feedback
    assert labels[idents[1]] + " is not" not in feedback          # a point found is not named
    for ident in idents:                                           # no right position given
        assert f"{points[ident]['x']:g}" not in feedback
    # nothing placed at all: no point found, and the plan still graded (score 0)
    data.update(submitted_answers={}, partial_scores={})
    namespace["grade"](data)
    assert data["partial_scores"]["velocity_plan"]["score"] == 0.0


def test_prairielearn_shows_each_variants_task_figure_above_the_drawing(keys):
    """The question panel shows the variant's mechanism at its position, drawn as the task
    sheet draws it, above the drawing canvases."""
    from planmethod.grading.sheets import task_sheet_svg
    from planmethod.plans import draw_plans

    template = load_template(TEMPLATE)
    files = prairielearn_questions(bundle(keys, seed=5), slug="fourbar")
    namespace: dict = {}
    exec(compile(files["fourbar/server.py"], "server.py", "exec"), namespace)  # our own code
    figures = {}
    for seed in range(40):
        data = {"params": {}, "correct_answers": {}, "variant_seed": seed}
        namespace["generate"](data)
        params = data["params"]
        html = _resolve(files["fourbar/question.html"], params)
        root = ElementTree.fromstring(f"<root>{html}</root>")
        panel = root.find("pl-question-panel")
        figure = panel.find("pl-figure")
        assert figure.get("directory") == "clientFilesQuestion"
        order = [child.tag for child in root]
        assert order.index("pl-question-panel") < order.index("pl-drawing")
        text = files[f"fourbar/clientFilesQuestion/{figure.get('file-name')}"]
        figures[params["student"]] = text
    assert sorted(figures) == ["ann", "bob", "cy"]
    assert len(set(figures.values())) == 3                 # each variant its own mechanism
    for student, text in figures.items():
        variant = draw_variant(template, seed=5, student=student)
        key = next(k for k in keys if k["student"] == student)
        sheet = task_sheet_svg(key, draw_plans(variant.exercise, acceleration=False))
        root = ElementTree.fromstring(text)
        drawn = [ElementTree.tostring(e) for e in root.iter()
                 if e.tag.rpartition("}")[2] in ("line", "polyline", "path", "circle")]
        sheet_elements = {ElementTree.tostring(e) for e in ElementTree.fromstring(sheet).iter()}
        assert drawn and all(element in sheet_elements for element in drawn)
        assert f"φ₁ = {key['angle']:g}°" in text and "Find" not in text


def test_prairielearn_grade_names_the_mistake_of_a_misplaced_point():
    """A point placed where the construction without the Coriolis component puts it is named
    with that mistake in grade(), as the workbook page names it."""
    from planmethod.grading.mistakes import mistaken_plans

    variant = draw_variant(load_template("exercises/slotted_lever.toml"))
    key = build_key(variant)
    files = prairielearn_questions(bundle([key]), slug="slotted")
    namespace: dict = {}
    exec(compile(files["slotted/server.py"], "server.py", "exec"), namespace)  # our own code
    data = {"params": {}, "correct_answers": {}, "variant_seed": 3}
    namespace["generate"](data)
    params = data["params"]
    assert params["plan_labels"]["acceleration"]["b_lever"] == "b₃"
    points = params["plans"]["acceleration"]
    centre = float(re.search(r'answers-name="acceleration_plan"[^>]*width="(\d+)"',
                             files["slotted/question.html"]).group(1)) / 2
    wrong = mistaken_plans(variant.exercise, "no_coriolis").acceleration.points_mm["b@lever"]
    placed = [{"gradingName": "pl-point", "left": p["x"], "top": p["y"]}
              for ident, p in points.items() if ident != "b_lever"]
    placed.append({"gradingName": "pl-point", "left": centre + 4 * wrong[0],
                   "top": centre - 4 * wrong[1]})
    data.update(submitted_answers={"acceleration_plan": placed}, partial_scores={})
    namespace["grade"](data)
    part = data["partial_scores"]["acceleration_plan"]
    assert part["score"] == pytest.approx(2 / 3)
    assert "b₃ is not where the construction puts it" in part["feedback"]
    assert "the Coriolis component aᵏ was left out" in part["feedback"]
    assert "more than the plan has" not in part["feedback"]
    # a point placed nowhere in particular is not named with any mistake
    placed[-1] = {"gradingName": "pl-point", "left": 3.0, "top": 3.0}
    data.update(submitted_answers={"acceleration_plan": placed}, partial_scores={})
    namespace["grade"](data)
    assert "left out" not in data["partial_scores"]["acceleration_plan"]["feedback"]


def test_moodle_xml_of_two_variants_whole():
    """Moodle XML as Moodle reads it, for two small variants: the category path (its slashes
    doubled, a leading and a trailing one set off by a space), each variant's Cloze question
    (task paragraphs, braces as references, the sheet as an embedded file, one row a
    question with its field — Moodle's special characters escaped in the feedback — and its
    unit), weight at least 1."""
    keys = [{"title": "Lever / crank <A&B>", "student": "s/01",
             "task": "Find ω.\n\nUse {braces} ]]> here.",
             "questions": [{"id": "omega_BC", "text": "angular velocity ω₂", "unit": "rad/s",
                            "value": -24.5, "tolerance": 0.5, "points": 2,
                            "mistakes": [{"kind": "sense", "value": 24.5, "tolerance": 0.5,
                                          "feedback": 'the sense "~#/}\\ was reversed'}]},
                           {"id": "rho_D", "text": "ρ of D", "unit": "m", "value": 0.07,
                            "tolerance": 0.006, "mistakes": []}]},
            {"title": "not read", "student": "s02", "task": "t",
             "questions": [{"id": "n", "text": "n", "value": 1.0, "tolerance": 0.1,
                            "points": 0.4}]}]
    assert moodle_xml(keys, category="/Course/2026/", sheets={"s/01": "<svg/>"}) == (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<quiz>\n'
        '  <question type="category">\n'
        '    <category><text>$course$/top/ //Course//2026// /Lever // crank &lt;A&amp;B&gt;</te'
        'xt></category>\n'
        '  </question>\n'
        '  <question type="cloze">\n'
        '    <name><text>Lever / crank &lt;A&amp;B&gt; — s/01</text></name>\n'
        '    <questiontext format="html"><text><![CDATA[<p><b>Lever / crank &lt;A&amp;B&gt;</b>'
        ' — variant s/01</p><p>Find ω.</p><p>Use &#123;braces&#125; ]]&gt; here.</p><p><img src'
        '="@@PLUGINFILE@@/sheet_s_01.svg" alt="the mechanism, task sheet" /></p><p>Give in SI u'
        'nits (counter-clockwise positive):</p><table><tr><td>angular velocity ω₂</td><td>{2:NU'
        "MERICAL:=-24.5:0.5#Right: within the drawing's tolerance ± 0.5 rad\\/s.~%0%24.5:0.5#It"
        ' looks as if the sense \\"\\~\\#\\/\\}\\\\ was reversed.}</td><td>rad/s</td></tr><tr><'
        "td>ρ of D</td><td>{1:NUMERICAL:=0.07:0.006#Right: within the drawing's tolerance ± 0.0"
        '06 m.}</td><td>m</td></tr></table>]]></text><file name="sheet_s_01.svg" path="/" encod'
        'ing="base64">PHN2Zy8+</file></questiontext>\n'
        '    <generalfeedback format="html"><text></text></generalfeedback>\n'
        '    <penalty>0.3333333</penalty>\n'
        '    <hidden>0</hidden>\n'
        '    <idnumber>s/01</idnumber>\n'
        '  </question>\n'
        '  <question type="cloze">\n'
        '    <name><text>Lever / crank &lt;A&amp;B&gt; — s02</text></name>\n'
        '    <questiontext format="html"><text><![CDATA[<p><b>Lever / crank &lt;A&amp;B&gt;</b>'
        ' — variant s02</p><p>t</p><p>Give in SI units (counter-clockwise positive):</p><table>'
        "<tr><td>n</td><td>{1:NUMERICAL:=1.0:0.1#Right: within the drawing's tolerance ± 0.1.}<"
        '/td><td></td></tr></table>]]></text></questiontext>\n'
        '    <generalfeedback format="html"><text></text></generalfeedback>\n'
        '    <penalty>0.3333333</penalty>\n'
        '    <hidden>0</hidden>\n'
        '    <idnumber>s02</idnumber>\n'
        '  </question>\n'
        '</quiz>\n')
    assert moodle_xml([]) == (
        '<?xml version="1.0" encoding="UTF-8"?>\n<quiz>\n  <question type="category">\n'
        "    <category><text>$course$/top/planmethod/planmethod</text></category>\n"
        "  </question>\n</quiz>\n")


def _small_key() -> dict:
    """A hand-made key: two questions (one of value 0), a velocity plan with a helper point
    and a point that mistakes put on and off the canvas."""
    return {"format": "planmethod-key", "title": 'Lever "L" & crank ω₁', "student": "s01",
            "task": "Find it.",
            "questions": [{"id": "v_C", "text": 'speed of C, "v"', "unit": "m/s", "value": 2.0,
                           "tolerance": 0.1, "mistakes": []},
                          {"id": "omega_BC", "text": "angular velocity <ω>", "unit": "rad/s",
                           "value": 0.0, "tolerance": 0.2, "mistakes": []}],
            "plans": {"velocity": {
                "pole": "p", "scale": 0.1, "unit": "(m/s)/mm", "steps": [],
                "points_mm": {"p": [0, 0], "b": [10.0, 0.0], "c": [0.0, -20.0],
                              "n_CB": [1.0, 1.0]},
                "tolerance_mm": {"p": 0.0, "b": 0.25, "c": 0.75, "n_CB": 0.3},
                "mistake_points": {"c": [["sense", 0.0, 20.0], ["scale_ten", 0.0, -2.0],
                                         ["scale_tenth", 0.0, -200.0]]}}}}


def test_prairielearn_question_of_a_small_key_whole():
    """info.json and question.html as PrairieLearn reads them (attributes escaped; a number
    input's label is HTML, which PrairieLearn inserts as it is, so its text is escaped twice),
    one number input per question, one drawing per plan on a 320 px canvas — a 30 mm plan and its
    margin — with the pole given and the graded points to place), and the variant's
    parameters: relabs tolerances (a zero answer's in atol), discs of at least 0.5 mm, the
    mistakes on the canvas, the points' names."""
    files = prairielearn_questions(bundle([_small_key()], seed=3), slug="lever",
                                   topic="Mechanisms")
    assert sorted(files) == ["lever/info.json", "lever/question.html", "lever/server.py"]
    seed = 'planmethod:lever:Lever "L" & crank ω₁:3:1'
    assert json.loads(files["lever/info.json"]) == {
        "uuid": str(uuid.uuid5(uuid.NAMESPACE_URL, seed)), "title": 'Lever "L" & crank ω₁',
        "topic": "Mechanisms", "tags": ["planmethod", "graphical-method"], "type": "v3",
        "gradingMethod": "Internal"}
    assert files["lever/info.json"] == json.dumps(json.loads(files["lever/info.json"]), indent=2,
                                                  ensure_ascii=False) + "\n"
    assert "ω₁" in files["lever/info.json"]                           # written as it is
    assert files["lever/question.html"] == "\n".join([
        "<pl-question-panel>", "  <p><b>{{params.title}}</b></p>", "  {{{params.task_html}}}",
        "</pl-question-panel>", "",
        '<pl-number-input answers-name="v_C" comparison="relabs" rtol="{{params.rtol.v_C}}" '
        'atol="{{params.atol.v_C}}" label="speed of C, &amp;quot;v&amp;quot; =" suffix="m/s">'
        "</pl-number-input>",
        '<pl-number-input answers-name="omega_BC" comparison="relabs" '
        'rtol="{{params.rtol.omega_BC}}" atol="{{params.atol.omega_BC}}" '
        'label="angular velocity &amp;lt;ω&amp;gt; =" suffix="rad/s"></pl-number-input>', "",
        "<p>Draw the velocity plan at the given scale (one grid square is 10 mm of the drawing; "
        "the pole p is marked): place the points b, c.</p>",
        '<pl-drawing answers-name="velocity_plan" gradable="true" width="320" height="320" '
        'grid-size="40" tol="{{params.tol_px.velocity}}" show-tolerance-hint="true">',
        "  <pl-drawing-initial>", '    <pl-point x1="160" y1="160" label="p"></pl-point>',
        "  </pl-drawing-initial>", '  <pl-drawing-answer draw-error-box="true">',
        '    <pl-point x1="{{params.plans.velocity.b.x}}" y1="{{params.plans.velocity.b.y}}" '
        'label="b"></pl-point>',
        '    <pl-point x1="{{params.plans.velocity.c.x}}" y1="{{params.plans.velocity.c.y}}" '
        'label="c"></pl-point>',
        "  </pl-drawing-answer>", "  <pl-controls>",
        '    <pl-controls-group label="Plan points:">',
        '      <pl-drawing-button type="pl-point"></pl-drawing-button>',
        "    </pl-controls-group>", '    <pl-controls-group label="Delete:">',
        '      <pl-drawing-button type="delete"></pl-drawing-button>',
        "    </pl-controls-group>", "  </pl-controls>", "</pl-drawing>", ""])
    namespace: dict = {}
    exec(compile(files["lever/server.py"], "server.py", "exec"), namespace)  # our own code
    data = {"params": {}, "correct_answers": {}, "variant_seed": 1}
    namespace["generate"](data)
    assert data["correct_answers"] == {"v_C": 2.0, "omega_BC": 0.0}
    assert data["params"] == {
        "student": "s01", "title": 'Lever "L" & crank ω₁', "task_html": "<p>Find it.</p>",
        "rtol": {"v_C": 0.1 / 2.0, "omega_BC": 0.0}, "atol": {"v_C": 1e-12, "omega_BC": 0.2},
        "tolerance": {"v_C": 0.1, "omega_BC": 0.2},
        "plans": {"velocity": {"b": {"x": 200.0, "y": 160.0}, "c": {"x": 160.0, "y": 240.0}}},
        "radius_px": {"velocity": {"b": 2.0, "c": 3.0}}, "tol_px": {"velocity": 3.0},
        "plan_labels": {"velocity": {"b": "b", "c": "c"}},
        "mistakes_px": {"velocity": {"c": [["sense", 160.0, 80.0],
                                           ["scale_ten", 160.0, 168.0]]}}}


#: a symbol written with its underscore (``v_C``): an underscore followed by a letter
UNDERSCORED = re.compile(r"_[^\W\d_]")


def prairielearn_texts(files: dict[str, str], slug: str) -> list[str]:
    """What a student sees of a PrairieLearn question: question.html's text, its number
    inputs' labels (HTML, which PrairieLearn inserts as it is) and each variant's task
    (the page's ``{{params…}}`` fields left out)."""
    page = re.sub(r"\{\{\{?[^{}]*\}?\}\}", " ", files[f"{slug}/question.html"])  # its fields
    shown = texts_of_html(page) + [text for label in re.findall(r'label="([^"]*)"', page)
                                   for text in texts_of_html(html.unescape(label))]
    namespace: dict = {}
    exec(compile(files[f"{slug}/server.py"], "server.py", "exec"), namespace)  # our own code
    for seed in range(1, 4):
        data = {"params": {}, "correct_answers": {}, "variant_seed": seed}
        namespace["generate"](data)
        shown += texts_of_html(data["params"]["task_html"])
    return shown


def test_the_lms_questions_set_symbols_with_subscripts():
    """Moodle's question texts and PrairieLearn's question (its labels and task too) set
    ``v_C``, ``ρ_D`` as v and ρ with a subscript, as the task sheet does; the answers keep
    their values, the plain-text README its ids."""
    template = load_template("exercises/templates/slider_crank.toml")
    keys = [build_key(draw_variant(template, seed=5, student=s)) for s in ("ann", "bob")]
    assert "ρ_D" in keys[0]["task"] and "|v_C|" in keys[0]["questions"][0]["text"]
    quiz = ElementTree.fromstring(moodle_xml(keys).encode("utf-8"))
    questions = [q.findtext("questiontext/text") for q in quiz.iter("question")
                 if q.get("type") == "cloze"]
    for key, text in zip(keys, questions, strict=True):
        shown = texts_of_html(text)
        assert not [run for run in shown if UNDERSCORED.search(run)], shown
        assert "|v<sub>C</sub>|" in text and "ρ<sub>D</sub>" in text
        assert [field["answers"][0]["value"] for field in _cloze_fields(text)] == [
            question["value"] for question in key["questions"]]
    files = prairielearn_questions(bundle(keys, seed=3), slug="q")
    shown = prairielearn_texts(files, "q")
    assert not [run for run in shown if UNDERSCORED.search(run)], shown
    assert 'label="speed of C, |v&lt;sub&gt;C&lt;/sub&gt;| ="' in files["q/question.html"]
    namespace: dict = {}
    exec(compile(files["q/server.py"], "server.py", "exec"), namespace)  # our own code
    for seed in range(1, 5):
        data = {"params": {}, "correct_answers": {}, "variant_seed": seed}
        namespace["generate"](data)
        key = next(key for key in keys if key["student"] == data["params"]["student"])
        assert data["correct_answers"] == {q["id"]: q["value"] for q in key["questions"]}
    assert "v_C, v_D" in gradescope_autograder(bundle(keys))["README.txt"]    # the ids


def test_gradebook_csv_whole():
    """One row a student: each question's score in the first-seen order of the questions
    (empty where a student has none), the total, the maximum (empty when unknown) and the
    note (an error)."""
    from planmethod.grading.verdicts import AnswerVerdict, Verdict
    from planmethod.words import message

    def scored(question, score):
        return GradedQuestion(question, None, 1.0, 0.1, "", 1.0, score, False, None,
                              Verdict(AnswerVerdict.NO_ANSWER))

    assert gradebook_csv([
        StudentGrade("s01", "v1", 1.5, 2.0, (scored("a", 1.0), scored("b", 0.5))),
        StudentGrade("s02", None, 0.0, None, error=message("no key for student 's02'")),
        StudentGrade("s03", "v3", 1.0, 3.0, (scored("c", 1.0), scored("a", 0.0))),
        StudentGrade("s04", None, 0, None)]) == ("student,variant,a,b,c,total,max,note\n"
                                 "s01,v1,1,0.5,,1.5,2,\n"
                                 "s02,,,,,0,,no key for student 's02'\n"
                                 "s03,v3,0,,1,1,3,\n"
                                 "s04,,,,,0,,\n")
