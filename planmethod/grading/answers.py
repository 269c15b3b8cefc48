"""Grading numeric answers against a key, with feedback that names common mistakes.

Answers come as CSV (a header row; a ``student`` column — or ``id``, ``student_id``, ``sid``,
``email``, ``name`` — and one column per question id such as ``v_C``, ``omega_BC``; a file
without a student column is one student's answers in one row) or as JSON
(``{"s01": {"v_C": 5.2, …}, …}``, or a list of ``{"student": "s01", "v_C": 5.2, …}`` /
``{"student": "s01", "answers": {…}}``).

An answer within the question's tolerance scores the question's points. Otherwise the
feedback says by how much it is off, and names the mistake when the answer matches one
(see :data:`planmethod.grading.mistakes.REGISTRY`): a reversed sense, a normal or Coriolis
component left out or reversed, a scale applied twice or not at all, degrees for radians,
millimetres for metres.

Examples
--------
>>> from planmethod.grading.templates import load_template, draw_variant
>>> from planmethod.grading.keys import build_key
>>> key = build_key(draw_variant(load_template("exercises/compressor_slider_crank.toml")))
>>> result = grade_answers(key, {"v_C": 5.27, "omega_BC": 24.25})
>>> [q["correct"] for q in result["questions"][:1]], result["score"]
([True], 1.0)
>>> print(next(q for q in result["questions"] if q["id"] == "omega_BC")["feedback"])
... # doctest: +NORMALIZE_WHITESPACE
ω₂ = 24.25 rad/s: wrong — it looks as if the sense (sign) is reversed
(that gives 24.2536; right: -24.2536 rad/s ± 0.547)
"""

from __future__ import annotations

import csv
import io
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from ..errors import SpecError
from ..io import read_text_bounded
from ..spec import parse_json
from ..vocabulary import quantity, question_text, symbol
from .reading import read_number

__all__ = ["FEEDBACK_LEVELS", "MAX_ANSWER_BYTES", "SENSE_WORDS", "STUDENT_COLUMNS",
           "answers_from_csv", "feedback_text", "grade_answers", "grade_many",
           "magnitude_note", "read_answers", "refuse_twice", "sense_words"]

MAX_ANSWER_BYTES = 20_000_000
MAX_ROWS = 200_000
STUDENT_COLUMNS = ("student", "student_id", "id", "sid", "email", "name")


def _number_text(value: float) -> str:
    return f"{value:.6g}"


def _parse_number(raw: Any) -> float | str | None:
    """A number, None for no answer, or the text of what was given instead: the one grammar
    of :mod:`planmethod.grading.reading`, which the workbook page applies too."""
    return read_number(raw)


def read_answers(path: str | Path) -> list[tuple[str, dict[str, Any]]]:
    """Read an answers file (CSV or JSON): a list of (student, {question id: raw answer}).

    Every student of the file is in the list, or the file is refused: nothing is merged,
    dropped or kept twice without a word.

    Parameters
    ----------
    path
        The answers file, CSV or JSON.

    Raises
    ------
    SpecError
        If the file is missing, too large, not CSV/JSON of the forms above, or ambiguous: a
        quote left open (naming its line), a column or JSON key given twice, a JSON object of
        students with a stray value, an answer that is a list or an object, no student at all,
        answers for the same student twice (ids compared ignoring case), no student column and
        more than one row, or grade's own ``--json`` results instead of answers.
    """
    path = Path(path)
    text = read_text_bounded(path, MAX_ANSWER_BYTES, encoding="utf-8-sig")
    if path.suffix.lower() == ".json" or text.lstrip().startswith(("{", "[")):
        rows = _answers_from_json(text, str(path))
    else:
        rows = answers_from_csv(text, str(path))
    _no_student_twice(rows, str(path))
    return rows


#: what grade's ``--json`` results hold (keys of the file, of one graded student)
_RESULTS_KEYS = ({"answers", "drawings"}, {"score", "max_score", "questions"})
_NOT_ANSWERS = ("this is planmethod grade's --json output (graded results), not an answers "
                "file")


def _kind(value: Any) -> str:
    """What a JSON value is, in words: ``a list``, ``a number``…"""
    if isinstance(value, Mapping | list):
        return "an object" if isinstance(value, Mapping) else "a list"
    if isinstance(value, bool) or value is None:
        return "true/false" if value is not None else "null"
    return "a number" if isinstance(value, int | float) else "a text"


def _one_answer_each(answers: Mapping[str, Any], where: str, prefix: str) -> dict[str, Any]:
    """A student's answers, each a number, a text, true/false or null — never a list or an
    object (which would be graded as no answer while the file meant something else)."""
    if any(keys <= set(answers) for keys in _RESULTS_KEYS):
        raise SpecError(_NOT_ANSWERS, file=where, key=prefix or None)
    for name, value in answers.items():
        if isinstance(value, Mapping | list):
            raise SpecError(f"is {_kind(value)}, not an answer (a number): give "
                            "{\"question id\": answer, …} for each student", file=where,
                            key=f"{prefix}.{name}" if prefix else str(name))
    # graded by id compared as grade_answers compares them: one of two would be lost
    refuse_twice([str(name) for name in answers], _folded, "answer", file=where,
                 key=prefix or None, compared="question ids compared ignoring case")
    return dict(answers)


def _answers_from_json(text: str, where: str) -> list[tuple[str, dict[str, Any]]]:
    data = parse_json(text, file=where, unique_keys=True)
    rows: list[tuple[str, dict[str, Any]]] = []
    if isinstance(data, Mapping):
        if not data:
            raise SpecError("no student's answers (the object is empty)", file=where)
        if any(keys <= set(data) for keys in _RESULTS_KEYS):
            raise SpecError(_NOT_ANSWERS, file=where)
        students = [name for name, value in data.items() if isinstance(value, Mapping)]
        if len(students) == len(data):       # {"s01": {"v_C": 5.2, …}, …}
            rows = [(str(name), _one_answer_each(value, where, str(name)))
                    for name, value in data.items()]
        elif not students:                   # one student's answers
            rows = [("*", _one_answer_each(data, where, ""))]
        else:   # a class with a stray value, or one student with an object among the answers
            by_student = 2 * len(students) >= len(data)   # most entries are students' objects
            odd = next(name for name, value in data.items()
                       if isinstance(value, Mapping) != by_student)
            others = len(students) if by_student else len(data) - len(students)
            like = ("an object of one student's answers" if by_student else "an answer")
            raise SpecError(f"is {_kind(data[odd])}, not {like} like the {others} "
                            f"other{'s' if others > 1 else ''}: the file "
                            "is either {\"student\": {\"question id\": answer, …}, …} or one "
                            "student's {\"question id\": answer, …}", file=where, key=str(odd))
    elif isinstance(data, list):
        if not data:
            raise SpecError("no student's answers (the list is empty)", file=where)
        for index, item in enumerate(data):
            if not isinstance(item, Mapping):
                raise SpecError("each entry must be an object", file=where, key=f"[{index}]")
            column = next((c for c in STUDENT_COLUMNS if c in item), None)
            student = item[column] if column is not None else None
            if isinstance(student, Mapping | list) or student is None or not str(student).strip():
                raise SpecError("no student id (give 'student')", file=where,
                                key=f"[{index}]" + (f".{column}" if column else ""))
            answers = item.get("answers", {k: v for k, v in item.items()
                                           if k not in STUDENT_COLUMNS})
            if not isinstance(answers, Mapping):
                raise SpecError("must be an object of answers", file=where,
                                key=f"[{index}].answers")
            rows.append((str(student), _one_answer_each(
                answers, where, f"[{index}].answers" if "answers" in item else f"[{index}]")))
    else:
        raise SpecError("must be an object or a list of objects", file=where)
    if len(rows) > MAX_ROWS:
        raise SpecError(f"more than {MAX_ROWS} students", file=where)
    return rows


class _Records:
    """The records of a CSV text, each with the line it starts on; a quoted cell that runs
    over a line end (a quote left open, which would swallow the students below it) or a quote
    never closed is a :class:`SpecError` naming that line."""

    def __init__(self, text: str, where: str) -> None:
        try:   # the separator and spaces after it are guessed; quotes are always "…"
            sniffed = csv.Sniffer().sniff(text[:4096], delimiters=",;\t")
            delimiter, spaces = sniffed.delimiter, sniffed.skipinitialspace
        except csv.Error:
            delimiter, spaces = ",", False
        self.reader = csv.reader(io.StringIO(text), delimiter=delimiter, quotechar='"',
                                 doublequote=True, skipinitialspace=spaces, strict=True)
        self.where = where

    def __iter__(self):
        while True:
            line = self.reader.line_num + 1
            try:
                row = next(self.reader)
            except StopIteration:
                return
            except csv.Error as error:
                raise SpecError(f"not valid CSV: {error} (is a quote (\") left open or a "
                                "cell quoted twice?)", file=self.where,
                                key=f"line {line}") from None
            if any("\n" in cell or "\r" in cell for cell in row):
                raise SpecError(f"a quoted cell runs on to line {self.reader.line_num}: is a "
                                "closing quote (\") missing?", file=self.where,
                                key=f"line {line}")
            yield line, row


def _header(records, where: str) -> tuple[int, list[str]]:
    """The header row (its line, its stripped cells); a column given twice is refused."""
    try:
        line, header = next(iter(records))
    except StopIteration:
        raise SpecError("the file is empty", file=where) from None
    header = [h.strip() for h in header]
    refuse_twice(header, str.lower, "column", file=where, key=f"line {line}",
                 places="columns", advice=": which one holds the answers?")
    return line, header


def answers_from_csv(text: str, where: str) -> list[tuple[str, dict[str, Any]]]:
    """The rows of a CSV of answers (any of , ; or tab): [(student, {column: cell})], one per
    student row, or the one student of a file without a student column; ``where`` names the
    file in errors.

    >>> answers_from_csv("student,v_C\\ns01,5.27\\n", "answers.csv")
    [('s01', {'v_C': '5.27'})]
    """
    records = iter(_Records(text, where))
    header_line, header = _header(records, where)
    lower = [h.lower() for h in header]
    column = next((lower.index(c) for c in STUDENT_COLUMNS if c in lower), None)
    if column is None:
        return _one_student_csv(records, header, where)
    if len(header) < 2:
        raise SpecError("needs a header row with a student column and question columns "
                        "(e.g. student,v_C,omega_BC)", file=where)
    rows = []
    for line, row in records:
        if not any(cell.strip() for cell in row):
            continue
        if len(rows) >= MAX_ROWS:
            raise SpecError(f"more than {MAX_ROWS} students", file=where)
        if len(row) > len(header):
            raise SpecError(f"has {len(row)} cells, the header {len(header)}", file=where,
                            key=f"line {line}")
        student = row[column].strip() if column < len(row) else ""
        if not student:
            raise SpecError(f"no student id (column '{header[column]}')", file=where,
                            key=f"line {line}")
        rows.append((student, {header[i]: row[i] for i in range(len(row)) if i != column}))
    if not rows:
        raise SpecError(f"a header (line {header_line}) and no student's answers under it",
                        file=where)
    return rows


def _one_student_csv(records, header: list[str], where: str) -> list[tuple[str, dict[str, Any]]]:
    """A CSV without a student column: one student's answers, in the one row under the
    header (the student is ``*``, the one the command is grading). Nothing is dropped."""
    rows = [(line, row) for line, row in records if any(cell.strip() for cell in row)]
    if len(rows) != 1:
        names = ", ".join(STUDENT_COLUMNS[:3])
        raise SpecError(f"has no student column ({names}, …) but {len(rows)} rows of answers: "
                        "without one, the file holds one student's answers in one row",
                        file=where)
    line, row = rows[0]
    if len(row) > len(header):
        raise SpecError(f"has {len(row)} cells, the header {len(header)}", file=where,
                        key=f"line {line}")
    return [("*", {header[i]: row[i] for i in range(len(row))})]


def _no_student_twice(rows: list[tuple[str, dict[str, Any]]], where: str) -> None:
    """Refuse a file that answers for the same student twice (it would be graded twice)."""
    refuse_twice([student for student, _ in rows], _folded, "student", file=where,
                 verb="answers", places="entries")


def _folded(name: str) -> str:
    """A name as ids are compared: without the spaces around it, ignoring case."""
    return name.strip().lower()


def refuse_twice(names: Sequence[str], normal: Callable[[str], str], what: str, *,
                 file: str | None, key: str | None = None, verb: str = "is given",
                 compared: str = "compared ignoring case", places: str | None = None,
                 advice: str = "; keep one", error: type[SpecError] = SpecError) -> None:
    """Refuse two of ``names`` that are one after ``normal`` (how they are compared): one
    value would be kept and the other lost without a word. The :class:`SpecError` names
    both as written, and their places (``places``: what the 1-based positions count,
    ``columns``; None for names whose order says nothing, the keys of a JSON object).
    Empty names are not compared. Answers files, drawn plans and ``check``'s coordinate
    tables are read through it; ``error`` is the kind of error raised (a drawing's
    :class:`~planmethod.grading.drawings.SubmissionError`).

    Examples
    --------
    >>> refuse_twice(["student", "v_C", "V_c"], str.lower, "column", file="a.csv",
    ...              places="columns")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: a.csv: column 'v_C' and column 'V_c' are one column, \
compared ignoring case (columns 2 and 3); keep one
    >>> refuse_twice(["s1", "s1"], str.lower, "student", file="a.csv", verb="answers",
    ...              places="entries")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: a.csv: student 's1' answers twice (entries 1 and 2); keep one
    """
    seen: dict[str, int] = {}
    for number, name in enumerate(names, start=1):
        form = normal(name) if name else ""
        if form in seen:
            first = names[seen[form] - 1]
            where = f" ({places} {seen[form]} and {number})" if places else ""
            if first == name:
                text = f"{what} {name!r} {verb} twice{where}"
            else:
                text = (f"{what} {first!r} and {what} {name!r} are one {what}, {compared}"
                        f"{where}")
            raise error(text + advice, file=file, key=key)
        if form:
            seen[form] = number


#: how the sign of a signed quantity is told, by what the quantity is of (its kind's
#: ``subject``): a link turns counter-clockwise or clockwise; a slide's travel, sliding
#: velocity and acceleration are along or against its guide's direction
SENSE_WORDS: dict[str, tuple[str, str]] = {
    "link": ("counter-clockwise", "clockwise"),
    "pair": ("positive, along the guide", "negative, against the guide"),
}


def sense_words(name: str) -> tuple[str, str]:
    """What a positive and a negative value of the quantity ``name`` (an id: ``omega_BC``,
    ``ds_slider/frame``) mean, in words (:data:`SENSE_WORDS`); ``grade`` and the workbook
    page both tell a reversed sign with them.

    >>> sense_words("omega_BC")
    ('counter-clockwise', 'clockwise')
    >>> sense_words("s_slider/frame")
    ('positive, along the guide', 'negative, against the guide')
    """
    try:
        subject = quantity(name).kind.subject
    except KeyError:
        return ("positive", "negative")
    return SENSE_WORDS.get(subject, ("positive", "negative"))


def _direction(name: str, value: float) -> str:
    positive, negative = sense_words(name)
    return positive if value > 0 else negative


def _off(answer: float, right: float) -> str:
    """How far off an answer is: ``24.1 % low``, ``1000 times the right value``."""
    if right == 0:
        return f"{abs(answer - right):.3g} off"
    ratio = answer / right
    if ratio >= 10 or 0 < ratio <= 0.1:
        return f"{ratio:.4g} times the right value"
    relative = ratio - 1.0
    magnitude = " in magnitude" if right < 0 and ratio >= 0 else ""
    return f"{abs(relative) * 100:.1f} % {'high' if relative > 0 else 'low'}{magnitude}"


def grade_question(question: Mapping[str, Any], raw: Any,
                   numbers: Mapping[str, int] | None = None) -> dict:
    """Grade one answer; returns the question's result with its feedback (which names the
    quantity as the course writes it, the key's ``symbol``, where the key has one; the
    links' ``numbers`` name it in what a negative magnitude is told)."""
    name, unit = question.get("symbol") or question["id"], question.get("unit", "")
    value, tolerance = float(question["value"]), float(question["tolerance"])
    points = float(question.get("points", 1.0))
    right = f"{_number_text(value)} {unit} ± {tolerance:.3g}".replace("  ", " ")
    result = {"id": question["id"], "answer": None, "value": value, "tolerance": tolerance,
              "unit": unit, "max_score": points, "score": 0.0, "correct": False,
              "mistake": None}
    answer = _parse_number(raw)
    if answer is None:
        result["feedback"] = f"{name}: no answer (right: {right})"
        result["hint"] = f"{name}: no answer"
        return result
    if isinstance(answer, str):
        result["feedback"] = f"{name}: {answer!r} is not a number (right: {right})"
        result["hint"] = f"{name}: {answer!r} is not a number"
        return result
    result["answer"] = answer
    result["error_abs"] = abs(answer - value)
    result["error_rel"] = abs(answer - value) / abs(value) if value else None
    shown = f"{name} = {_number_text(answer)} {unit}".rstrip()
    if abs(answer - value) <= tolerance:
        result.update(score=points, correct=True,
                      feedback=f"{shown}: correct (exact {_number_text(value)}, "
                               f"tolerance ± {tolerance:.3g})", hint=f"{shown}: correct")
        return result
    for mistake in question.get("mistakes", ()):
        if abs(answer - mistake["value"]) <= mistake["tolerance"]:
            result["mistake"] = mistake["kind"]
            if mistake.get("also"):   # other mistakes that give the same answer
                result["also"] = list(mistake["also"])
            how = "" if mistake["kind"] == "sense" else f", {_off(answer, value)}"
            result["feedback"] = (f"{shown}: wrong{how} — it looks as if "
                                  f"{mistake['feedback']} (that gives "
                                  f"{_number_text(mistake['value'])}; right: {right})")
            result["hint"] = (f"{shown}: wrong ({_way(answer, value, signed=False)}) — it "
                              f"looks as if {mistake['feedback']}")
            return result
    signed = bool(question.get("signed"))
    if signed:
        for mistake in question.get("mistakes", ()):
            if mistake["kind"] != "sense" and abs(-answer - mistake["value"]) <= \
                    mistake["tolerance"]:
                result["mistake"] = mistake["kind"] + "+sense"
                result["feedback"] = (f"{shown}: wrong — it looks as if {mistake['feedback']}, "
                                      f"and the sense is reversed (right: {right})")
                result["hint"] = (f"{shown}: wrong — it looks as if {mistake['feedback']}, "
                                  "and the sense is reversed")
                return result
    note = None if signed or answer >= 0 else magnitude_note(question["id"], numbers)
    if note is not None:
        result["feedback"] = f"{shown}: wrong — {note} (right: {right})"
        result["hint"] = f"{shown}: wrong — {note}"
        return result
    if signed and value != 0 and answer != 0 and (answer > 0) != (value > 0):
        size = ("right" if abs(abs(answer) - abs(value)) <= tolerance
                else _off(abs(answer), abs(value)))
        text = (f"{shown}: wrong — the sense is reversed (the right answer is "
                f"{_direction(question['id'], value)}, {right}) and the magnitude "
                f"{_number_text(abs(answer))} is {size}")
    else:
        tolerance_text = (f" = ± {tolerance / abs(value) * 100:.2g} %" if value else "")
        off_by = f"{_number_text(abs(answer - value))} {unit}".rstrip()
        text = (f"{shown}: wrong — {_off(answer, value)} (off by {off_by}; right: {right}"
                f"{tolerance_text})")
    result["feedback"] = text
    result["hint"] = f"{shown}: wrong ({_way(answer, value, signed)})"
    return result


def magnitude_note(name: str, numbers: Mapping[str, int] | None = None) -> str | None:
    """What a negative answer for the magnitude ``name`` (a quantity id: ``v_B@lever``) is
    told, in the course's symbols under the links' ``numbers`` (None for a signed quantity
    or an unknown name). ``grade`` and the workbook page both say it from here.

    >>> magnitude_note("v_C")
    'v_C is the speed of C, |v_C|: a magnitude, never negative'
    >>> magnitude_note("v_B@lever", {"frame": 0, "crank": 1, "block": 2, "lever": 3})
    'v_B₃ is the speed of B₃, |v_B₃|: a magnitude, never negative'
    >>> magnitude_note("omega_BC") is None
    True
    """
    try:
        found = quantity(name)
    except KeyError:
        return None
    if found.signed:
        return None
    return (f"{symbol(name, numbers)} is the {question_text(name, numbers)}: a magnitude, "
            "never negative")


def _way(answer: float, right: float, signed: bool) -> str:
    """Which way an answer is off, without the right value: ``too high``, ``too low in
    magnitude``, ``the sense is reversed``."""
    if signed and right != 0 and answer != 0 and (answer > 0) != (right > 0):
        return "the sense is reversed"
    if right < 0 and answer <= 0:
        return "too large in magnitude" if answer < right else "too small in magnitude"
    return "too high" if answer > right else "too low"


#: what a student is shown of each graded question, by feedback level
FEEDBACK_LEVELS = ("full", "hints", "score")


def feedback_text(question: Mapping[str, Any], level: str = "full") -> str:
    """The feedback on one graded question at a level: ``full`` (the values: the right answer
    and its tolerance), ``hints`` (the mistake named and which way the answer is off, never
    the right value) or ``score`` (nothing but the points).

    Examples
    --------
    >>> graded = grade_question({"id": "v_C", "value": 5.27, "tolerance": 0.1}, 6.0)
    >>> feedback_text(graded, "hints")
    'v_C = 6: wrong (too high)'
    >>> "5.27" in feedback_text(graded, "full"), feedback_text(graded, "score")
    (True, '')
    """
    if level not in FEEDBACK_LEVELS:
        raise ValueError(f"feedback level {level!r} is not one of {', '.join(FEEDBACK_LEVELS)}")
    if level == "score":
        return ""
    return question["feedback"] if level == "full" else question.get("hint", "")


def grade_answers(key: Mapping[str, Any], answers: Mapping[str, Any],
                  student: str | None = None) -> dict:
    """Grade one student's answers ({question id: raw answer}) against a key.

    Answers keyed by an unknown id are reported in ``ignored``; a question id is matched
    exactly first, then ignoring case.

    Parameters
    ----------
    key
        The answer key of the student's variant.
    answers
        The answers, {question id: raw answer}.
    student
        The student named in the result (default: the key's).
    """
    by_lower = {}
    for name in answers:
        by_lower.setdefault(_folded(str(name)), name)
    from .keys import key_numbers

    numbers = key_numbers(key)
    results, used = [], set()
    for question in key["questions"]:
        name = question["id"]
        found = name if name in answers else by_lower.get(name.lower())
        if found is not None:
            used.add(found)
        results.append(grade_question(question, answers.get(found) if found is not None
                                      else None, numbers))
    ignored = sorted(str(n) for n in answers if n not in used)
    score = sum(r["score"] for r in results)
    total = sum(r["max_score"] for r in results)
    return {"student": student if student is not None else key.get("student"),
            "variant": key.get("student"), "score": score, "max_score": total,
            "questions": results, "ignored": ignored}


def grade_many(keys: Mapping[str, Mapping[str, Any]],
               rows: list[tuple[str, Mapping[str, Any]]]) -> list[dict]:
    """Grade many students: each against the key of their own variant (or the key ``*``).

    A student with no key of their own and no common key gets a result with ``error``.

    Parameters
    ----------
    keys
        Student → key, as :func:`~planmethod.grading.keys.load_keys` returns.
    rows
        (student, answers) pairs, as :func:`read_answers` returns.
    """
    out = []
    for student, answers in rows:
        key = keys.get(student, keys.get("*"))
        if key is None:
            out.append({"student": student, "score": 0.0, "max_score": None, "questions": [],
                        "error": f"no key for student {student!r}"})
            continue
        out.append(grade_answers(key, answers, student=student))
    return out
