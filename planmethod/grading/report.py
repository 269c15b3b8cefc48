"""The class report: which step of the method the class gets wrong.

:func:`class_statistics` turns the graded results of many students
(:func:`planmethod.grading.answers.grade_many`) into one row per question: how many answered,
the mean score as a share of the points, the share answered right, and the share of answers
that each named mistake explains (the rest of the wrong answers are "unexplained").
``planmethod grade KEYS ANSWERS --report DIR`` writes them as ``questions.csv`` and
``mistakes.csv`` and draws them as ``class_report.png``.

Examples
--------
>>> results = [{"questions": [{"id": "v_C", "score": 1.0, "max_score": 1.0, "correct": True,
...                            "answer": 5.2, "mistake": None}]},
...            {"questions": [{"id": "v_C", "score": 0.0, "max_score": 1.0, "correct": False,
...                            "answer": 2.6, "mistake": "scale"}]}]
>>> row = class_statistics(results)[0]
>>> row["question"], row["answered"], row["mean_score"], row["mistakes"]
('v_C', 2, 0.5, {'scale': 0.5})
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from ..io import csv_text

__all__ = ["class_statistics", "mistakes_csv", "questions_csv"]


def class_statistics(results: Iterable[Mapping[str, Any]]) -> list[dict]:
    """One row per question, in the order first met: ``question``, ``students`` (graded),
    ``answered`` (gave a number), ``mean_score`` (share of the points, 0…1), ``correct``
    (share right), ``mistakes`` ({mistake: share of the students}), ``unexplained`` (share
    wrong with no named mistake)."""
    rows: dict[str, dict] = {}
    for result in results:
        for question in result.get("questions", ()):
            row = rows.setdefault(question["id"], {"question": question["id"], "students": 0,
                                                   "answered": 0, "score": 0.0, "right": 0,
                                                   "named": {}, "unexplained": 0})
            row["students"] += 1
            row["answered"] += question.get("answer") is not None
            points = float(question.get("max_score") or 0.0)
            row["score"] += float(question.get("score", 0.0)) / points if points else 0.0
            if question.get("correct"):
                row["right"] += 1
            elif question.get("mistake"):
                row["named"][question["mistake"]] = row["named"].get(question["mistake"], 0) + 1
            else:
                row["unexplained"] += 1
    out = []
    for row in rows.values():
        count = row["students"]
        out.append({"question": row["question"], "students": count,
                    "answered": row["answered"], "mean_score": row["score"] / count,
                    "correct": row["right"] / count,
                    "mistakes": {name: n / count for name, n in sorted(row["named"].items())},
                    "unexplained": row["unexplained"] / count})
    return out


def questions_csv(rows: list[Mapping[str, Any]]) -> str:
    """``question, students, answered, mean_score, correct, unexplained, top_mistake,
    top_mistake_share`` — one line per question."""
    lines: list[list[Any]] = [["question", "students", "answered", "mean_score", "correct",
                               "unexplained", "top_mistake", "top_mistake_share"]]
    for row in rows:
        top = max(row["mistakes"].items(), key=lambda item: item[1], default=("", 0.0))
        lines.append([row["question"], row["students"], row["answered"],
                      f"{row['mean_score']:.4f}", f"{row['correct']:.4f}",
                      f"{row['unexplained']:.4f}", top[0], f"{top[1]:.4f}"])
    return csv_text(lines)


def mistakes_csv(rows: list[Mapping[str, Any]]) -> str:
    """``question, mistake, share`` — one line per question and named mistake."""
    return csv_text([["question", "mistake", "share"]]
                    + [[row["question"], name, f"{share:.4f}"]
                       for row in rows for name, share in row["mistakes"].items()])
