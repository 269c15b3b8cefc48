"""The class report: which step of the method the class gets wrong.

:func:`class_statistics` turns the graded results of many students
(:func:`planmethod.grading.answers.grade_many`) into one row per question
(:class:`~planmethod.grading.results.QuestionStatistics`): how many answered, the mean score
as a share of the points, the share answered right, and the share of answers that each named
mistake explains (the rest of the wrong answers are "unexplained").
``planmethod grade KEYS ANSWERS --report DIR`` writes them as ``questions.csv`` and
``mistakes.csv`` and draws them as ``class_report.png``.

Examples
--------
>>> from planmethod.grading.answers import grade_many
>>> key = {"student": "k", "questions": [{"id": "v_C", "value": 5.2, "tolerance": 0.1,
...        "mistakes": [{"kind": "scale", "value": 2.6, "tolerance": 0.1, "feedback": "…"}]}]}
>>> results = grade_many({"*": key}, [("s1", {"v_C": 5.2}), ("s2", {"v_C": 2.6})])
>>> row = class_statistics(results)[0]
>>> row.question, row.answered, row.mean_score, row.mistakes
('v_C', 2, 0.5, {'scale': 0.5})
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from ..io import csv_text
from .results import QuestionStatistics, StudentGrade

__all__ = ["class_statistics", "mistakes_csv", "questions_csv"]


class _Tally:
    """One question's counts over the class, as they are met."""

    def __init__(self) -> None:
        self.students = self.answered = self.right = self.unexplained = 0
        self.score = 0.0
        self.named: dict[str, int] = {}

    def row(self, question: str) -> QuestionStatistics:
        count = self.students
        return QuestionStatistics(question, count, self.answered, self.score / count,
                                  self.right / count,
                                  {name: n / count for name, n in sorted(self.named.items())},
                                  self.unexplained / count)


def class_statistics(results: Iterable[StudentGrade]) -> list[QuestionStatistics]:
    """One row per question, in the order first met: the question, the students graded on
    it, how many answered (gave a number), the mean share of the points (0…1), the share
    right, each named mistake's share of the students, and the share wrong with no named
    mistake."""
    tallies: dict[str, _Tally] = {}
    for result in results:
        for question in result.questions:
            tally = tallies.setdefault(question.id, _Tally())
            tally.students += 1
            tally.answered += question.answer is not None
            points = float(question.max_score or 0.0)
            tally.score += float(question.score) / points if points else 0.0
            if question.correct:
                tally.right += 1
            elif question.mistake:
                tally.named[question.mistake] = tally.named.get(question.mistake, 0) + 1
            else:
                tally.unexplained += 1
    return [tally.row(question) for question, tally in tallies.items()]


def questions_csv(rows: list[QuestionStatistics]) -> str:
    """``question, students, answered, mean_score, correct, unexplained, top_mistake,
    top_mistake_share`` — one line per question."""
    lines: list[list[Any]] = [["question", "students", "answered", "mean_score", "correct",
                               "unexplained", "top_mistake", "top_mistake_share"]]
    for row in rows:
        top = row.top_mistake
        lines.append([row.question, row.students, row.answered, f"{row.mean_score:.4f}",
                      f"{row.correct:.4f}", f"{row.unexplained:.4f}", top[0], f"{top[1]:.4f}"])
    return csv_text(lines)


def mistakes_csv(rows: list[QuestionStatistics]) -> str:
    """``question, mistake, share`` — one line per question and named mistake."""
    return csv_text([["question", "mistake", "share"]]
                    + [[row.question, name, f"{share:.4f}"]
                       for row in rows for name, share in row.mistakes.items()])
