"""Grade a class: numeric answers (CSV or JSON, one row per student) and drawn plans (SVG or
JSON) against a key, with feedback, and what a grader writes of it (a JSON of every result,
a gradebook, a class report, Gradescope's results).

A key is a key (``key.json``), a bundle (``keys.json`` or the folder that holds it), or a
plain exercise file (its key is built on the spot). Each student is graded against their own
variant's key when the bundle has one, else against the single key. A drawing downloaded from
the workbook page names its exercise (title and digest) and crank angle: it is refused in one
line if it is of another exercise, and graded against the key of its own angle, built from the
exercise the key keeps (docs/workbook-drawing.md). A phone photo of a plan sheet printed by
``planmethod booklet`` is graded as the drawn plan it shows (:mod:`planmethod.grading.photos`),
many in a bounded pool of processes; a photo that cannot be read is refused in one line and
the others are graded.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..errors import SpecError
from ..words import Message, message, render

if TYPE_CHECKING:
    from ..grading.photos import GradedPhoto
    from ..grading.results import GradedDrawing, StudentGrade
    from ..io import OutputSet

__all__ = [
    "GradeOutputs",
    "GradeRequest",
    "Graded",
    "PhotoRefused",
    "grade",
    "graded_lines",
    "load_any_key",
    "marked_names",
    "write_grades",
]


@dataclass(frozen=True)
class GradeRequest:
    """What to grade: the answers file and the drawings (at least one of them) against the
    key (a key, a bundle, its folder or an exercise file); ``plan`` says which plan the
    drawings are (default: told by each one's pole label), ``student`` whose they are
    (picks the variant's key; for a single submission). ``photos`` are phone photos of plan
    sheets (each names its student and plan), graded in ``jobs`` worker processes (default:
    by their number, at most the CPUs this process may use), each kept for marking if
    ``marked``."""

    key: str
    answers: str | None = None
    drawings: tuple[str, ...] = ()
    plan: str | None = None
    student: str | None = None
    photos: tuple[str, ...] = ()
    jobs: int | None = None
    marked: bool = False


@dataclass(frozen=True)
class PhotoRefused:
    """A photo that could not be graded, and why (one line)."""

    photo: str
    reason: str


@dataclass(frozen=True)
class Graded:
    """A class graded: the keys (student → key), each student's answers graded, each
    drawing graded (by its file), each photo graded (with its marked picture, JPEG, if asked)
    and each photo refused."""

    keys: Mapping[str, Any]
    answers: tuple[StudentGrade, ...]
    drawings: tuple[tuple[str, GradedDrawing], ...]
    photos: tuple[tuple[GradedPhoto, bytes | None], ...] = ()
    refused: tuple[PhotoRefused, ...] = ()


@dataclass(frozen=True)
class GradeOutputs:
    """What to write of a grading: every result as JSON, a CSV gradebook, the class report
    (a folder), Gradescope's results.json (one student); ``feedback`` is what each
    question's feedback shows (``full``, ``hints`` or ``score``; default: full in the JSON,
    hints for Gradescope, which the student sees); ``marked`` is the folder each graded
    photo is written into, marked for the student."""

    json: str | None = None
    csv: str | None = None
    report: str | None = None
    gradescope: str | None = None
    feedback: str | None = None
    marked: str | None = None


def load_any_key(path: str) -> dict:
    """student → key from a key, a bundle, a folder, or an exercise file."""
    from pathlib import Path

    from ..grading.keys import build_key, load_keys

    if Path(path).suffix.lower() == ".toml":
        from ..grading.templates import draw_variant, load_template

        template = load_template(path)
        if template.is_random:
            raise SpecError(message("a template with ranges or choices has one key per "
                                    "student: run `planmethod variants` and grade against its "
                                    "keys.json"), file=path)
        key = build_key(draw_variant(template))
        return {"*": key, str(key["student"]): key}
    return load_keys(path)


def _drawings(request: GradeRequest, keys: Mapping[str, Any], key_of_student
              ) -> tuple[tuple[str, dict], ...]:
    from ..errors import about
    from ..grading.drawings import grade_drawing, key_for_drawing, read_drawing

    drawings = []
    for path in request.drawings:
        key = key_of_student or keys.get("*")
        if key is None:
            raise SpecError(message("grading a drawing against a bundle needs --student"),
                            file=path)
        with about(path):   # an error here is about this drawing, not the key
            drawing = read_drawing(path)
            # a drawing from the workbook page is graded at its own angle, on its own exercise
            drawings.append((path, grade_drawing(key_for_drawing(key, drawing), drawing,
                                                 request.plan)))
    return tuple(drawings)


def _page_graded(request: GradeRequest, keys: Mapping[str, Any], key_of_student,
                 rows: list) -> list[StudentGrade] | None:
    """The answers downloaded from the workbook page graded at their own angle, on their own
    exercise, with what the page showed; None for any other answers file."""
    from dataclasses import replace

    from ..grading.answers import grade_answers
    from ..grading.page_answers import key_for_answers, read_page_answers

    page = read_page_answers(request.answers)
    if page is None:
        return None
    key = key_of_student or keys.get("*")
    if key is None:
        raise SpecError(message("grading the page's answers against a bundle needs "
                                "--student"), file=request.answers)
    student, answers = rows[0]
    graded = grade_answers(key_for_answers(key, page), answers, student=student)
    return [replace(graded, revealed=page.revealed)]


def grade(request: GradeRequest) -> Graded:
    """Grade the answers and drawings of ``request``.

    Raises
    ------
    SpecError
        Where nothing is to be graded, a student has no key, or an input cannot be read
        (naming it).
    """
    from ..errors import about
    from ..grading.answers import grade_many, read_answers

    if not request.answers and not request.drawings and not request.photos:
        raise SpecError(message("give ANSWERS, --drawing FILE and/or --photo IMAGE"))
    if (request.marked or request.jobs is not None) and not request.photos:
        raise SpecError(message("{option} is for --photo",
                                option="--marked" if request.marked else "--jobs"))
    keys = load_any_key(request.key)
    photos, refused = _photos(request, keys) if request.photos else ((), ())
    key_of_student = None
    if request.student is not None:
        key_of_student = keys.get(request.student, keys.get("*"))
        if key_of_student is None:
            raise SpecError(message("no key for student {student!r}",
                                    student=request.student), file=request.key)
    results = []
    if request.answers:
        with about(request.answers):   # an error here is about the answers, not the key
            rows = read_answers(request.answers)
            if request.student is not None:
                rows = [(request.student if s == "*" or len(rows) == 1 else s, a)
                        for s, a in rows]
            results = _page_graded(request, keys, key_of_student, rows) or grade_many(keys,
                                                                                     rows)
    return Graded(keys, tuple(results), _drawings(request, keys, key_of_student), photos,
                  refused)


# -- photos ------------------------------------------------------------------------------------
#: what a photo worker grades against (set once in each worker by :func:`_start_photos`)
_PHOTO_WORK: dict[str, Any] = {}


def _start_photos(keys: Mapping[str, Any], key_source: str, marked: bool,
                  language: str) -> None:
    """What every photo of a run is graded against, kept in this process (a worker's: one
    OpenCV thread each, the pool is the bound)."""
    import cv2

    cv2.setNumThreads(1)
    _PHOTO_WORK.update(keys=keys, key_source=key_source, marked=marked, language=language)


def _photo_header(graded: GradedPhoto) -> Message:
    """A graded photo's first line: the photo, whose sheet, which plan, the score."""
    drawing = graded.drawing
    return message("{photo} (student {student}, {plan}): {score:g}/{total:g}",
                   photo=graded.photo, student=str(graded.sheet.student),
                   plan=_PLANS.get(drawing.plan, drawing.plan), score=drawing.score,
                   total=drawing.max_score)


def _grade_photo(path: str) -> tuple[str, GradedPhoto | None, bytes | None, str | None]:
    """One photo graded (the photo itself left out: it stays here), with its marked picture if
    asked; or why it was refused, in one line."""
    from dataclasses import replace

    from ..errors import PlanmethodError
    from ..grading.photos import grade_photo
    from ..words.language import speaking

    work = _PHOTO_WORK
    with speaking(work["language"]):
        try:
            graded = grade_photo(work["keys"], path, key_source=work["key_source"])
        except PlanmethodError as error:
            return path, None, None, str(error)
        marked = None
        if work["marked"]:
            from ..render.marked import marked_photo

            marked = marked_photo(graded, [render(_photo_header(graded))])
    return path, replace(graded, reading=replace(graded.reading, image=None)), marked, None


def _photos(request: GradeRequest, keys: Mapping[str, Any]
            ) -> tuple[tuple[tuple[GradedPhoto, bytes | None], ...], tuple[PhotoRefused, ...]]:
    """Every photo of ``request`` graded, in order — in a pool of worker processes that ends
    with this one — and those refused."""
    import importlib.util
    import sys

    from ..words.language import current
    from .workers import in_workers, worker_count

    if importlib.util.find_spec("cv2") is None:
        raise SpecError(message("grading photos needs OpenCV: pip install "
                                "'planmethod[paper]'"))
    count = len(request.photos)
    # a photo takes about a second: one worker a photo by default, as many as the CPUs
    workers = min(worker_count(request.jobs, 12 * count), count)
    setup = (keys, str(request.key), request.marked, current())
    done: list[tuple[str, GradedPhoto | None, bytes | None, str | None]] = []
    if workers <= 1:
        _start_photos(*setup)
        done = [_grade_photo(path) for path in request.photos]
    else:
        # OpenCV's threads do not survive a fork: once it runs here (a notebook, a test), the
        # workers are started afresh
        in_workers(_grade_photo, list(request.photos), workers, done.append,
                   setup=_start_photos, arguments=setup, fork="cv2" not in sys.modules)
    graded = tuple((photo, marked) for _, photo, marked, _ in done if photo is not None)
    refused = tuple(PhotoRefused(path, why) for path, photo, _, why in done
                    if photo is None and why is not None)
    return graded, refused


#: a verdict's mark in front of a question's or a point's feedback
_MARKS = {True: message("ok ", context="mark"), False: message("XX ", context="mark")}
#: the plans a drawing is of, as a line names them
_PLANS = {"velocity": message("velocity plan"), "acceleration": message("acceleration plan")}


def graded_lines(graded: Graded, *, feedback: str = "full", quiet: bool = False) -> list[str]:
    """The lines a grader reads: each student's score and, unless ``quiet``, each question's
    feedback; each drawing's score and each point's feedback; in the language spoken."""
    from ..grading.answers import feedback_text
    from ..grading.page_answers import revealed_answers_note

    lines: list[Message | str] = []
    for result in graded.answers:
        total = result.max_score
        who = message("the answers") if result.student == "*" else result.student
        lines.append(message("{who}: {score:g}/{total:g}", who=who, score=result.score,
                             total=total) if total is not None else
                     message("{who}: {error}", who=who, error=result.error))
        if not quiet:
            lines += [f"  {render(_MARKS[bool(q.correct)])} "
                      f"{render(feedback_text(q, feedback))}" for q in result.questions]
        if result.revealed and not quiet:   # the workbook page showed these right values
            key = graded.keys.get(str(result.student), graded.keys.get("*", {}))
            lines.append(f"  !  {render(revealed_answers_note(result.revealed, key))}")
    for path, drawing in graded.drawings:
        lines.append(message("{path} ({plan}): {score:g}/{total:g}", path=path,
                             plan=_PLANS.get(drawing.plan, drawing.plan),
                             score=drawing.score, total=drawing.max_score))
        if not quiet:
            lines += [f"  {render(_MARKS[bool(p.correct)])} {render(p.feedback)}"
                      for p in drawing.points]
            lines += [f"  !  {render(line)}" for line in drawing.feedback]
    for photo, _ in graded.photos:
        lines.append(_photo_header(photo))
        if not quiet:
            lines += [f"  {render(_MARKS[bool(p.correct)])} {render(p.feedback)}"
                      for p in photo.drawing.points]
            lines += [f"  !  {render(line)}" for line in photo.drawing.feedback]
    return [render(line) for line in lines]


def marked_names(paths: list[str]) -> list[str]:
    """The marked photos' file names: each photo's name with ``_marked.jpg``, numbered where
    two photos share a name.

    >>> marked_names(["a/s1.jpg", "b/s1.jpg", "s2.png"])
    ['s1_marked.jpg', 's1_2_marked.jpg', 's2_marked.jpg']
    """
    from pathlib import Path

    seen: dict[str, int] = {}
    out = []
    for path in paths:
        stem = Path(path).stem
        seen[stem] = seen.get(stem, 0) + 1
        out.append(f"{stem}_marked.jpg" if seen[stem] == 1 else f"{stem}_{seen[stem]}_marked.jpg")
    return out


def _stage_class_report(outputs: OutputSet, report: str, keys: Mapping[str, Any],
                        results: tuple[StudentGrade, ...]) -> None:
    """Stage the class report (questions.csv, mistakes.csv, class_report.png) in the folder
    ``report`` of the output set ``outputs``."""
    import textwrap
    from pathlib import Path

    from ..grading.keys import key_numbers
    from ..grading.report import class_statistics, mistakes_csv, questions_csv
    from ..render.plots import save_class_report_plot
    from ..vocabulary import symbol

    rows = class_statistics(list(results))
    if not rows:
        raise SpecError(message("--report needs graded answers (give ANSWERS)"))
    folder = Path(report)
    first = next(iter(keys.values()))
    numbers = key_numbers(first)
    symbols = {row.question: symbol(row.question, numbers) for row in rows}
    words = {mistake["kind"]: textwrap.shorten(mistake["feedback"], 48, placeholder="…")
             for key in keys.values() for question in key.get("questions", ())
             for mistake in question.get("mistakes", ())}
    outputs.text(folder / "questions.csv", questions_csv(rows))
    outputs.text(folder / "mistakes.csv", mistakes_csv(rows))
    with outputs.writing(folder / "class_report.png") as temporary:
        save_class_report_plot(rows, temporary, title=str(first.get("title", "")),
                               symbols=symbols, mistakes=words)


def check_outputs(graded: Graded, outputs: GradeOutputs, request: GradeRequest) -> None:
    """Refuse outputs that cannot be made of this grading, before any is written."""
    if outputs.gradescope and len(graded.answers) > 1:
        raise SpecError(message("--gradescope writes one student's results; the answers "
                                "hold {count}", count=len(graded.answers)),
                        file=request.answers)


def write_grades(graded: Graded, outputs: GradeOutputs, request: GradeRequest) -> None:
    """Write what ``outputs`` asks of the grading: every file, or none."""
    import json
    from pathlib import Path

    from ..grading.exports import gradebook_csv, gradescope_results
    from ..grading.results import StudentGrade
    from ..io import output_set

    check_outputs(graded, outputs, request)
    answers, drawings = list(graded.answers), [drawing for _, drawing in graded.drawings]
    with output_set() as files:   # every output file, or none
        if outputs.json:
            data: dict[str, Any] = {
                "answers": [result.as_dict() for result in answers],
                "drawings": [*(drawing.as_dict() for drawing in drawings),
                             *(photo.as_dict() for photo, _ in graded.photos)]}
            if request.photos:
                data["refused"] = [{"photo": refused.photo, "error": refused.reason}
                                   for refused in graded.refused]
            files.text(outputs.json, json.dumps(data, ensure_ascii=False, indent=1,
                                                allow_nan=False))
        if outputs.marked:
            pictures = [(photo.photo, picture) for photo, picture in graded.photos
                        if picture is not None]
            for name, (_, picture) in zip(marked_names([path for path, _ in pictures]),
                                          pictures, strict=True):
                files.binary(Path(outputs.marked) / name, picture)
        if outputs.csv:
            files.text(outputs.csv, gradebook_csv(answers))
        if outputs.report:
            _stage_class_report(files, outputs.report, graded.keys, graded.answers)
        if outputs.gradescope:
            result = answers[0] if answers else StudentGrade(request.student,
                                                             request.student, 0.0, None)
            drawings += [photo.drawing for photo, _ in graded.photos]
            files.text(outputs.gradescope, json.dumps(
                gradescope_results(result, drawings, feedback=outputs.feedback or "hints"),
                ensure_ascii=False, indent=1))
