"""The Python API: what a notebook or a script asks of planmethod, reachable from the top
level (``planmethod.load``), as numpy's and shapely's are.

* :func:`load` reads an exercise file (or a template, a file with ranges and choices) into
  an :class:`Exercise`; :func:`parse` reads its text;
* :meth:`Exercise.solve` → a :class:`Solution` at a crank angle: its ``plans`` (the plans
  as data), ``checks``, ``forces``, its figures (:meth:`Solution.svg`), its report as a
  course prints it (:meth:`Solution.report`) and the JSON report (:meth:`Solution.as_dict`)
  — each as ``planmethod solve`` writes it;
* :meth:`Exercise.sweep` (the full turn), :meth:`Exercise.key` and :meth:`Exercise.grade`
  (a student's answers), :meth:`Exercise.workbook` (the HTML page),
  :meth:`Exercise.variants` (a class's variants, written with
  :meth:`~planmethod.application.variants.VariantSet.write`).

Text is made in the exercise's language: the ``language`` given, else the file's ``[course]
language``, else ``PLANMETHOD_LANG``, else English.

Examples
--------
>>> import planmethod
>>> exercise = planmethod.load("exercises/compressor_slider_crank.toml")
>>> solution = exercise.solve(angle=60)
>>> sorted(solution.svg())
['acceleration', 'lever', 'position', 'velocity']
>>> print(solution.report().splitlines()[0])
Compressor slider-crank (Abduvaliev & Abduxoshimov) — crank angle φ₁ = 60°
>>> round(solution.as_dict()["links"]["BC"]["omega"], 4)
-17.4078
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, overload

from ..errors import SpecError
from ..words import message, speaking

if TYPE_CHECKING:
    from ..grading.results import StudentGrade

__all__ = ["Exercise", "Solution", "load", "parse"]


def load(path: str | Path, *, language: str | None = None) -> Exercise:
    """Read the exercise file (or template) ``path``.

    Parameters
    ----------
    path
        The TOML file: an exercise, as drawn or in link frames, or a template.
    language
        The language its texts are made in (default: the file's ``[course] language``, else
        ``PLANMETHOD_LANG``, else English).

    Raises
    ------
    SpecError
        If the file cannot be read or breaks the exercise-file contract, naming the file and
        key.

    Examples
    --------
    >>> load("exercises/slotted_lever.toml").title
    'Crank and slotted lever'
    """
    from ..spec import read_text

    return parse(read_text(path), file=str(path), language=language)


def parse(text: str, *, file: str | None = None, language: str | None = None) -> Exercise:
    """Read the TOML ``text`` of an exercise file (or template).

    Parameters
    ----------
    text
        The file's text.
    file
        The name its errors give (default: none).
    language
        As :func:`load`'s.

    Examples
    --------
    >>> text = open("exercises/templates/slider_crank.toml", encoding="utf-8").read()
    >>> parse(text).is_template
    True
    """
    from ..grading.templates import parse_template
    from ..spec import parse_exercise

    template = parse_template(text, file=file)
    model = None if template.is_random else parse_exercise(text, file=file)
    return Exercise(template, model, language)


@dataclass(frozen=True)
class Exercise:
    """An exercise file as read: the file's tables as a template (a plain exercise is a
    template without ranges or choices) and the exercise it describes (``model``: the frozen
    :class:`planmethod.model.Exercise`; None for a template, whose variants are exercises)."""

    template: Any
    model: Any = None
    language: str | None = None

    @property
    def title(self) -> str:
        """The exercise's title."""
        return str(self.template.data.get("title", ""))

    @property
    def is_template(self) -> bool:
        """Whether the file draws a variant per student (ranges, choices)."""
        return self.template.is_random

    @property
    def spoken(self) -> str:
        """The language its texts are made in: the one given, else the file's ``[course]
        language``, else ``PLANMETHOD_LANG``, else English."""
        from .language import chosen_language, course_language

        return chosen_language(self.language, course_language(self.template.data),
                               file=self.template.source, option_key="language")

    def _exercise(self):
        if self.model is None:
            raise SpecError(message("a template with ranges or choices is one exercise per "
                                    "student: draw its variants (.variants()) and solve "
                                    "those"), file=self.template.source)
        return self.model

    def solve(self, angle: float | None = None, *,
              precision_mm: float | None = None) -> Solution:
        """The solution at crank angle ``angle`` (deg; default the file's ``drive.angle``:
        the assembly chosen there is followed to ``angle``), drawn at ``precision_mm``
        (default the file's), as ``planmethod solve --angle --precision`` solves it.

        Examples
        --------
        >>> load("exercises/compressor_slider_crank.toml").solve().angle
        45.0
        """
        from .solving import solve_at

        return Solution(solve_at(self._exercise(), angle, precision_mm=precision_mm),
                        self.spoken)

    def sweep(self, step: float = 1.0, *, start: float = 0.0, stop: float = 360.0,
              forces: bool = False) -> dict[str, Any]:
        """The full turn as columns (numpy arrays by name: ``angle``, ``v_C``, … and, with
        ``forces``, the reactions and the balancing moment), as ``planmethod sweep --csv``
        writes them.

        Examples
        --------
        >>> table = load("exercises/compressor_slider_crank.toml").sweep(90)
        >>> table["angle"].tolist()
        [0.0, 90.0, 180.0, 270.0]
        """
        from ..sweep import sweep_table

        exercise = self._exercise()
        extra = None
        if forces:
            from ..forces import force_columns

            extra = force_columns(exercise)
        return sweep_table(exercise, step, start=start, stop=stop, extra=extra,
                           progress=False)

    def key(self) -> dict:
        """The answer key ``planmethod grade`` builds for this file (its ``[grading]``
        table), in its language."""
        from ..grading.keys import build_key
        from ..grading.templates import draw_variant

        self._exercise()
        with speaking(self.spoken):
            return build_key(draw_variant(self.template))

    def grade(self, answers: Mapping[str, Any], *, student: str | None = None
              ) -> StudentGrade:
        """One student's ``answers`` (question id → what they wrote: ``{"v_C": "5.27"}``)
        graded against :meth:`key`, with feedback in the exercise's language, as ``planmethod
        grade`` grades them: a :class:`~planmethod.grading.results.StudentGrade`, whose
        ``as_dict()`` is what ``grade --json`` writes of the student.

        Examples
        --------
        >>> graded = load("exercises/compressor_slider_crank.toml").grade({"v_C": "5.27"})
        >>> graded.questions[0].correct, graded.score
        (True, 1.0)
        """
        from ..grading.answers import grade_answers

        key = self.key()
        with speaking(self.spoken):
            return grade_answers(key, answers, student=student)

    def workbook(self, step: float = 5.0, *, jobs: int | None = 1, watch=None) -> str:
        """The workbook page (HTML) for a full turn, a frame every ``step`` degrees, solved in
        ``jobs`` processes (:func:`~planmethod.application.workbook.build_workbook`); ``watch``
        (:class:`~planmethod.application.tasks.Watch`) hears each frame and may cancel it."""
        from .workbook import build_workbook

        with speaking(self.spoken):
            return build_workbook(self._exercise(), step, jobs=jobs, watch=watch)

    def variants(self, count: int = 1, *, seed: int = 0, roster: str | None = None,
                 sheets: bool = True, watch=None):
        """The variants of a class — ``count`` students numbered 001…, or those of a
        ``roster`` file — drawn with ``seed``, with their keys and (``sheets``) task and plan
        sheets: a :class:`~planmethod.application.variants.VariantSet`, written with its
        ``write(folder)`` as ``planmethod variants`` writes it.

        Examples
        --------
        >>> drawn = load("exercises/templates/slider_crank.toml").variants(2, sheets=False)
        >>> [variant.student for variant in drawn.variants]
        ['001', '002']
        """
        from .variants import VariantsRequest, class_of, draw_variants

        request = VariantsRequest(self.template, class_of(count if roster is None else None,
                                                          roster), seed=seed, sheets=sheets,
                                  source=self.template.source or "")
        with speaking(self.spoken):
            return draw_variants(request, watch=watch)


@dataclass(frozen=True)
class Solution:
    """An exercise solved at one crank angle: the analysis (:class:`planmethod.report.
    Analysis`) and the language its texts are made in."""

    analysis: Any
    language: str | None = None

    @property
    def angle(self) -> float:
        """The crank angle (deg)."""
        return float(self.analysis.angle)

    @property
    def plans(self):
        """The plans as data (:class:`planmethod.plans.Plans`: pole, scale, labelled points in
        mm, ordered construction steps), or None for a mechanism whose plans are not drawn."""
        return self.analysis.plans

    @property
    def checks(self) -> tuple:
        """Each quantity read off the plans against its exact value."""
        return tuple(self.analysis.checks)

    @property
    def forces(self):
        """The kinetostatics (:class:`planmethod.forces.ForceAnalysis`), or None."""
        return self.analysis.forces

    @overload
    def svg(self, name: None = None) -> dict[str, str]: ...

    @overload
    def svg(self, name: str) -> str: ...

    def svg(self, name: str | None = None) -> dict[str, str] | str:
        """The figures ``planmethod solve --svg`` draws, by name (``position``,
        ``velocity``, ``acceleration``, ``lever``, and the force drawings), or the one
        ``name``d."""
        from .solving import figures

        with speaking(self.language):
            drawn = {file.removesuffix(".svg"): text
                     for file, text in figures(self.analysis).items()}
        if name is None:
            return drawn
        if name not in drawn:
            raise SpecError(message("no figure {name!r} (the figures: {names})", name=name,
                                    names=list(drawn)))
        return drawn[name]

    def report(self) -> str:
        """The report ``planmethod solve`` prints: structure, scales, the check table,
        flags and forces, in the course's notation."""
        from .solving import report_text

        with speaking(self.language):
            return report_text(self.analysis)

    def as_dict(self) -> dict:
        """The JSON report of ``planmethod solve --json`` (docs/json-report.md)."""
        from ..report import report_dict

        with speaking(self.language):
            return report_dict(self.analysis)
