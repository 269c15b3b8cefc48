"""Write the example answers of the teaching quick start, with planted mistakes of known kinds.

    python exercises/templates/make_answers.py

draws the variants of ``slider_crank.toml`` exactly as the quick start's ``planmethod variants``
command does (the same template, count and random number), answers the first students' variants
as a careful student would (each right value read to four significant digits), plants one
mistake of a known kind per student (the value the answer key predicts for it), and writes

- ``slider_crank_answers_example.csv`` — the answers file the quick start grades;
- ``slider_crank_answers_example.md`` — what grading it gives: how many answers are right and
  which mistakes are named, included by docs/teaching.md (each number is stated once, here).

Every planted answer is graded before it is written: the script stops with an error when the
grader would not name exactly the planted mistake (a variant drawn differently, a mistake no
longer predicted), so the file and the text cannot drift apart silently. ``tests/
test_docs_answers.py`` runs the script and grades the committed file as the quick start does.
"""

from __future__ import annotations

import csv
import io
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
TEMPLATE = HERE / "slider_crank.toml"
ANSWERS = HERE / "slider_crank_answers_example.csv"
SUMMARY = HERE / "slider_crank_answers_example.md"
#: the quick start's ``planmethod variants`` options (docs/teaching.md runs the same)
COUNT = 30
RANDOM_NUMBER = 2026
#: students answered, and the mistake each one makes: (student, question, mistake key)
PLANTED = (
    ("001", "omega_BC", "sense"),
    ("002", "v_C", "scale_none"),
    ("003", "a_C", "scale_tenth"),
    ("004", "rho_D", "full_acceleration"),
    ("005", "v_D", "millimetres"),
    ("006", "epsilon_BC", "scale_inverted"),
)
STUDENTS = tuple(student for student, _, _ in PLANTED)


def reading(value: float) -> float:
    """A value as a student writes it down: four significant digits.

    >>> reading(5.271634), reading(-24.25361), reading(0.07377123)
    (5.272, -24.25, 0.07377)
    """
    return float(f"{value:.4g}")


def draw_keys(folder: Path) -> dict[str, dict]:
    """The answer keys of the quick start's variants, drawn by ``planmethod variants``."""
    subprocess.run([sys.executable, "-m", "planmethod", "variants", str(TEMPLATE),
                    "--count", str(COUNT), "--seed", str(RANDOM_NUMBER), "--no-sheets",
                    "--out", str(folder)], check=True, cwd=ROOT, stdout=subprocess.DEVNULL)
    from planmethod.grading.keys import load_keys

    return load_keys(folder / "keys.json")


def answers_for(key: dict, planted: dict[str, str]) -> dict[str, float]:
    """One student's answers: every right value read off, the planted mistakes' values."""
    answers = {}
    for question in key["questions"]:
        value = question["value"]
        kind = planted.get(question["id"])
        if kind is not None:
            matches = [m for m in question["mistakes"] if m["kind"] == kind]
            if not matches:
                raise SystemExit(f"make_answers: {key['student']}: {question['id']}: the key "
                                 f"predicts no {kind!r} answer; plant another mistake")
            value = matches[0]["value"]
        answers[question["id"]] = reading(value)
    return answers


def grade(keys: dict[str, dict], answers: dict[str, dict[str, float]]) -> list[dict]:
    """Grade the answers as ``planmethod grade`` does; check each planted mistake is named."""
    from planmethod.grading.answers import grade_many

    results = [result.as_dict() for result in grade_many(keys, list(answers.items()))]
    planted = {(student, question): kind for student, question, kind in PLANTED}
    for result in results:
        for graded in result["questions"]:
            expected = planted.get((result["student"], graded["id"]))
            named = graded["mistake"]
            if expected is None and not graded["correct"]:
                raise SystemExit(f"make_answers: {result['student']}: {graded['id']}: a right "
                                 f"value read to four digits is graded wrong")
            if expected is not None and (named != expected or graded.get("also")):
                raise SystemExit(f"make_answers: {result['student']}: {graded['id']}: planted "
                                 f"{expected!r}, the grader names {named!r}"
                                 f"{' and ' + str(graded['also']) if graded.get('also') else ''}")
    return results


def answers_csv(keys: dict[str, dict], answers: dict[str, dict[str, float]]) -> str:
    """The answers file: a student column, then one column per question id."""
    questions = [question["id"] for question in keys[STUDENTS[0]]["questions"]]
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["student", *questions])
    for student in STUDENTS:
        writer.writerow([student, *(f"{answers[student][q]:g}" for q in questions)])
    return out.getvalue()


def summary(results: list[dict]) -> str:
    """What grading the file gives, as docs/teaching.md states it."""
    from planmethod.grading.mistakes import REGISTRY
    from planmethod.words import render

    told = {key: render(mistake.explanation) for key, mistake in REGISTRY.items()}
    answered = sum(len(result["questions"]) for result in results)
    right = sum(graded["correct"] for result in results for graded in result["questions"])
    lines = [
        f"The example answers file holds the answers of {len(results)} students (variants "
        f"{results[0]['student']}–{results[-1]['student']}): {right} of {answered} answers are "
        f"right, and each of the {answered - right} wrong ones carries a planted mistake that "
        "the grader names:",
        "",
        "| student | question | mistake | what the student is told |",
        "|---|---|---|---|",
    ]
    for student, question, kind in PLANTED:
        lines.append(f"| {student} | `{question}` | `{kind}` | {told[kind]} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    """Draw the keys, write the answers and the summary beside the template."""
    with tempfile.TemporaryDirectory() as folder:
        keys = draw_keys(Path(folder) / "course")
    planted: dict[str, dict[str, str]] = {student: {} for student in STUDENTS}
    for student, question, kind in PLANTED:
        planted[student][question] = kind
    answers = {student: answers_for(keys[student], planted[student]) for student in STUDENTS}
    results = grade(keys, answers)
    ANSWERS.write_text(answers_csv(keys, answers), encoding="utf-8")
    SUMMARY.write_text(summary(results), encoding="utf-8")
    print(f"wrote {ANSWERS.relative_to(ROOT)} and {SUMMARY.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
