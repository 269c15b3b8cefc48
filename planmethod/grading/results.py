"""Grading's values, typed: a key's question and its mistakes as the grader reads them, and
what grading gives — a graded answer, a student's grade, a graded point of a drawn plan, a
graded drawing, a row of the class report.

Each is a frozen dataclass; its sentences are messages (rendered only where text leaves the
program), and :meth:`as_dict` writes it as the JSON ``planmethod grade --json`` writes (the
same keys in the same order; the sentences rendered in the language spoken).

Examples
--------
>>> question = KeyQuestion.read({"id": "v_C", "value": 5.27, "tolerance": 0.1, "unit": "m/s"})
>>> question.symbol, question.points, question.mistakes
('v_C', 1.0, ())
>>> KeyMistake.read({"kind": "sense", "value": -5.27, "tolerance": 0.1,
...                  "feedback": "the sense (sign) is reversed"}).as_dict()["feedback"]
'the sense (sign) is reversed'
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..words import Message, render
from .verdicts import AnswerVerdict, Verdict

__all__ = ["GradedDrawing", "GradedPoint", "GradedQuestion", "KeyMistake", "KeyQuestion",
           "QuestionStatistics", "StudentGrade"]


@dataclass(frozen=True, slots=True)
class KeyMistake:
    """A known mistake's answer to one question of a key: the mistake (``kind``, a name of
    :data:`~planmethod.grading.mistakes.REGISTRY`), the wrong answer it gives and its
    tolerance, what the student is told (``explanation``: a message when the key is built
    here, the key file's text when it is read), and the other mistakes that give the same
    answer (``also``: None where no other mistake gives it, empty where only this one gives
    it another way)."""

    kind: str
    value: float
    tolerance: float
    explanation: Message | str
    also: tuple[str, ...] | None = None

    @classmethod
    def read(cls, table: Mapping[str, Any]) -> KeyMistake:
        """A mistake from its table in a key (checked by the key's reader)."""
        also = table.get("also")
        return cls(str(table["kind"]), float(table["value"]), float(table["tolerance"]),
                   table.get("feedback") or "",
                   None if also is None else tuple(str(other) for other in also))

    def as_dict(self) -> dict[str, Any]:
        """The mistake's table in a key."""
        out: dict[str, Any] = {"kind": self.kind, "value": self.value,
                               "tolerance": self.tolerance, "feedback": render(self.explanation)}
        if self.also is not None:
            out["also"] = list(self.also)
        return out


@dataclass(frozen=True, slots=True)
class KeyQuestion:
    """One question of a key: the quantity asked (``id``), its right ``value`` and
    ``tolerance``, what the task asks (``text``), its course ``symbol``, ``unit``, whether
    it is ``signed``, where the tolerance comes from, its ``points`` and the known mistakes'
    answers."""

    id: str
    value: float
    tolerance: float
    symbol: str
    unit: str = ""
    text: Message | str | None = None
    signed: bool = False
    tolerance_from: str | None = None
    points: float = 1.0
    mistakes: tuple[KeyMistake, ...] = ()

    @classmethod
    def read(cls, table: Mapping[str, Any]) -> KeyQuestion:
        """A question from its table in a key (``id``, ``value`` and ``tolerance`` given; a
        key file's are checked by its reader); a table without a ``symbol`` is named by its
        id."""
        return cls(str(table["id"]), float(table["value"]), float(table["tolerance"]),
                   str(table.get("symbol") or table["id"]), str(table.get("unit") or ""),
                   table.get("text"), bool(table.get("signed")), table.get("tolerance_from"),
                   float(table.get("points", 1.0)),
                   tuple(KeyMistake.read(mistake) for mistake in table.get("mistakes") or ()))

    def as_dict(self) -> dict[str, Any]:
        """The question's table in a key."""
        return {"id": self.id, "text": render(self.text) if self.text is not None else None,
                "symbol": self.symbol, "unit": self.unit, "value": self.value,
                "signed": self.signed, "tolerance": self.tolerance,
                "tolerance_from": self.tolerance_from, "points": self.points,
                "mistakes": [mistake.as_dict() for mistake in self.mistakes]}


@dataclass(frozen=True, slots=True)
class GradedQuestion:
    """One graded answer: the question's ``id``, the ``answer`` read (None if none or not a
    number), the right ``value``, ``tolerance`` and ``unit``, the points scored of
    ``max_score``, whether it is ``correct``, the ``mistake`` it is named with (its key; with
    ``+sense`` when the sense is reversed too) and the others that give the same answer
    (``also``, only where the mistake is named alone), and its :class:`Verdict`, whose
    sentences are its :attr:`feedback` and :attr:`hint`."""

    id: str
    answer: float | None
    value: float
    tolerance: float
    unit: str
    max_score: float
    score: float
    correct: bool
    mistake: str | None
    verdict: Verdict
    also: tuple[str, ...] = ()

    @property
    def feedback(self) -> Message:
        """What the student is told with the values (the ``full`` level)."""
        return self.verdict.feedback()

    @property
    def hint(self) -> Message:
        """What the student is told without the right value (the ``hints`` level)."""
        return self.verdict.hint()

    @property
    def error_abs(self) -> float | None:
        """How far the answer is from the right value (None without an answer)."""
        return None if self.answer is None else abs(self.answer - self.value)

    @property
    def error_rel(self) -> float | None:
        """That as a share of the right value (None without an answer, or for a right value
        of zero)."""
        if self.answer is None or not self.value:
            return None
        return abs(self.answer - self.value) / abs(self.value)

    def as_dict(self) -> dict[str, Any]:
        """The graded answer as ``grade --json`` writes it."""
        out: dict[str, Any] = {"id": self.id, "answer": self.answer, "value": self.value,
                               "tolerance": self.tolerance, "unit": self.unit,
                               "max_score": self.max_score, "score": self.score,
                               "correct": self.correct, "mistake": self.mistake}
        if self.verdict.kind not in (AnswerVerdict.NO_ANSWER, AnswerVerdict.NOT_A_NUMBER):
            out["error_abs"], out["error_rel"] = self.error_abs, self.error_rel
        if self.also:
            out["also"] = list(self.also)
        out["feedback"], out["hint"] = render(self.feedback), render(self.hint)
        return out


@dataclass(frozen=True, slots=True)
class StudentGrade:
    """One student's grade: who (``student``), the variant graded against, the ``score`` of
    ``max_score``, each question's grade and the answers that matched no question
    (``ignored``); or, for a student no key is for, the ``error`` (no score of anything).
    Answers downloaded from the workbook page say which right values the page showed
    (``revealed``: question ids at the answers' angle); other answers files, None."""

    student: Any
    variant: Any
    score: float
    max_score: float | None
    questions: tuple[GradedQuestion, ...] = ()
    ignored: tuple[str, ...] = ()
    error: Message | None = None
    revealed: tuple[str, ...] | None = None

    def as_dict(self) -> dict[str, Any]:
        """The grade as ``grade --json`` writes it."""
        if self.error is not None:
            return {"student": self.student, "score": self.score, "max_score": self.max_score,
                    "questions": [], "error": render(self.error)}
        out = {"student": self.student, "variant": self.variant, "score": self.score,
               "max_score": self.max_score,
               "questions": [question.as_dict() for question in self.questions],
               "ignored": list(self.ignored)}
        if self.revealed is not None:
            out["revealed"] = list(self.revealed)
        return out


@dataclass(frozen=True, slots=True)
class GradedPoint:
    """One graded point of a drawn plan: its label in the key (``point``) and its course
    ``name`` (b₃), whether it was ``found`` and is ``correct`` (in its disc), how far it is
    from its right place and the disc's radius (mm; None if not found), the points scored of
    ``max_score`` (a helper point scores nothing), what the student is told (``feedback``)
    and the known mistakes that put a point where it lies (``mistakes``)."""

    point: str
    name: str
    found: bool
    correct: bool
    score: float
    max_score: float
    feedback: Message
    distance_mm: float | None = None
    tolerance_mm: float | None = None
    mistakes: tuple[str, ...] = ()

    def as_dict(self) -> dict[str, Any]:
        """The point as ``grade --json`` writes it."""
        out: dict[str, Any] = {"point": self.point, "found": self.found,
                               "correct": self.correct}
        if self.found:
            out["distance_mm"], out["tolerance_mm"] = self.distance_mm, self.tolerance_mm
        out |= {"score": self.score, "max_score": self.max_score,
                "feedback": render(self.feedback)}
        if self.mistakes:
            out["mistakes"] = list(self.mistakes)
        out["name"] = self.name
        return out


@dataclass(frozen=True, slots=True)
class GradedDrawing:
    """A graded drawn plan: which ``plan``, the key's ``student``, the ``score`` of
    ``max_score``, the factor the drawing was scaled by, each point's grade, the mistakes
    named on every wrong point (``plan_mistakes``), the notes on the whole drawing
    (``feedback``) and what the workbook page showed the student before the drawing was
    downloaded (``revealed``: answers by question id, ``construction:<plan>``,
    ``plan:<plan>``)."""

    plan: str
    student: Any
    score: float
    max_score: float
    scale_factor: float
    points: tuple[GradedPoint, ...]
    plan_mistakes: tuple[str, ...] = ()
    feedback: tuple[Message | str, ...] = ()
    revealed: tuple[str, ...] = ()

    def as_dict(self) -> dict[str, Any]:
        """The drawing as ``grade --json`` writes it."""
        return {"plan": self.plan, "student": self.student, "score": self.score,
                "max_score": self.max_score, "scale_factor": self.scale_factor,
                "points": [point.as_dict() for point in self.points],
                "plan_mistakes": list(self.plan_mistakes),
                "feedback": [render(note) for note in self.feedback],
                "revealed": list(self.revealed)}


@dataclass(frozen=True, slots=True)
class QuestionStatistics:
    """One question of the class report: the ``question``, the ``students`` graded on it, how
    many ``answered`` (gave a number), the mean share of the points, the share right, each
    named mistake's share of the students, and the share wrong with no mistake named."""

    question: str
    students: int
    answered: int
    mean_score: float
    correct: float
    mistakes: Mapping[str, float]
    unexplained: float

    @property
    def top_mistake(self) -> tuple[str, float]:
        """The most common named mistake and its share (``("", 0.0)`` if none)."""
        return max(self.mistakes.items(), key=lambda item: item[1], default=("", 0.0))
