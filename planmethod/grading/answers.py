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
omega_BC = 24.25 rad/s: wrong — it looks as if the sense (sign) is reversed
(that gives 24.2536; right: -24.2536 rad/s ± 0.547)
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..errors import SpecError
from ..spec import check_nesting

__all__ = ["FEEDBACK_LEVELS", "MAX_ANSWER_BYTES", "feedback_text", "grade_answers",
           "grade_many", "read_answers"]

MAX_ANSWER_BYTES = 20_000_000
MAX_ROWS = 200_000
STUDENT_COLUMNS = ("student", "student_id", "id", "sid", "email", "name")


def _number_text(value: float) -> str:
    return f"{value:.6g}"


def _parse_number(raw: Any) -> float | str | None:
    """A number, None for no answer, or the text of what was given instead."""
    if raw is None:
        return None
    if isinstance(raw, bool):
        return repr(raw)
    if isinstance(raw, int | float):
        return float(raw) if math.isfinite(raw) else str(raw)
    text = str(raw).strip()
    if not text:
        return None
    cleaned = text.replace("\u2212", "-").replace(" ", "")
    if cleaned.count(",") == 1 and "." not in cleaned:
        cleaned = cleaned.replace(",", ".")  # a decimal comma
    try:
        value = float(cleaned)
    except ValueError:
        return text[:40]
    return value if math.isfinite(value) else text[:40]


def read_answers(path: str | Path) -> list[tuple[str, dict[str, Any]]]:
    """Read an answers file (CSV or JSON): a list of (student, {question id: raw answer}).

    Parameters
    ----------
    path
        The answers file, CSV or JSON.

    Raises
    ------
    SpecError
        If the file is missing, too large, not CSV/JSON of the forms above, answers for the
        same student twice (ids compared ignoring case), or has no student column and more
        than one row.
    """
    path = Path(path)
    try:
        size = path.stat().st_size
    except FileNotFoundError:
        raise SpecError("no such file", file=str(path)) from None
    except OSError as error:
        raise SpecError(f"cannot read the file ({error.strerror})", file=str(path)) from None
    if size > MAX_ANSWER_BYTES:
        raise SpecError(f"the file is {size} bytes, more than the {MAX_ANSWER_BYTES} accepted",
                        file=str(path))
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as error:
        raise SpecError(f"cannot read the file as UTF-8 text ({error})", file=str(path)) from None
    if path.suffix.lower() == ".json" or text.lstrip().startswith(("{", "[")):
        rows = _answers_from_json(text, str(path))
    else:
        rows = _answers_from_csv(text, str(path))
    _no_student_twice(rows, str(path))
    return rows


def _answers_from_json(text: str, where: str) -> list[tuple[str, dict[str, Any]]]:
    check_nesting(text, file=where)
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        raise SpecError(f"not valid JSON: {error}", file=where) from None
    rows: list[tuple[str, dict[str, Any]]] = []
    if isinstance(data, Mapping):
        items = list(data.items())
        if all(isinstance(v, Mapping) for _, v in items):
            rows = [(str(k), dict(v)) for k, v in items]
        else:  # one student's answers
            rows = [("*", dict(data))]
    elif isinstance(data, list):
        for index, item in enumerate(data):
            if not isinstance(item, Mapping):
                raise SpecError("each entry must be an object", file=where, key=f"[{index}]")
            student = next((item[c] for c in STUDENT_COLUMNS if c in item), None)
            if student is None:
                raise SpecError("no student id (give 'student')", file=where,
                                key=f"[{index}]")
            answers = item.get("answers", {k: v for k, v in item.items()
                                           if k not in STUDENT_COLUMNS})
            if not isinstance(answers, Mapping):
                raise SpecError("must be an object of answers", file=where,
                                key=f"[{index}].answers")
            rows.append((str(student), dict(answers)))
    else:
        raise SpecError("must be an object or a list of objects", file=where)
    if len(rows) > MAX_ROWS:
        raise SpecError(f"more than {MAX_ROWS} students", file=where)
    return rows


def _answers_from_csv(text: str, where: str) -> list[tuple[str, dict[str, Any]]]:
    try:
        dialect = csv.Sniffer().sniff(text[:4096], delimiters=",;\t")
    except csv.Error:
        dialect = csv.excel
    reader = csv.reader(io.StringIO(text), dialect)
    try:
        header = next(reader)
    except StopIteration:
        raise SpecError("the file is empty", file=where) from None
    except csv.Error as error:
        raise SpecError(f"not valid CSV: {error}", file=where) from None
    header = [h.strip() for h in header]
    lower = [h.lower() for h in header]
    column = next((lower.index(c) for c in STUDENT_COLUMNS if c in lower), None)
    if column is None:
        return _one_student_csv(reader, header, where)
    if len(header) < 2:
        raise SpecError("needs a header row with a student column and question columns "
                        "(e.g. student,v_C,omega_BC)", file=where)
    rows = []
    try:
        for number, row in enumerate(reader, start=2):
            if not any(cell.strip() for cell in row):
                continue
            if len(rows) >= MAX_ROWS:
                raise SpecError(f"more than {MAX_ROWS} students", file=where)
            if len(row) > len(header):
                raise SpecError(f"row {number} has {len(row)} cells, the header {len(header)}",
                                file=where)
            student = row[column].strip() if column < len(row) else ""
            if not student:
                raise SpecError(f"row {number} has no student id (column '{header[column]}')",
                                file=where)
            rows.append((student, {header[i]: row[i] for i in range(len(row)) if i != column}))
    except csv.Error as error:
        raise SpecError(f"not valid CSV: {error}", file=where) from None
    return rows


def _one_student_csv(reader, header: list[str], where: str) -> list[tuple[str, dict[str, Any]]]:
    """A CSV without a student column: one student's answers, in the one row under the
    header (the student is ``*``, the one the command is grading). Nothing is dropped."""
    try:
        rows = [(number, row) for number, row in enumerate(reader, start=2)
                if any(cell.strip() for cell in row)]
    except csv.Error as error:
        raise SpecError(f"not valid CSV: {error}", file=where) from None
    if len(rows) != 1:
        names = ", ".join(STUDENT_COLUMNS[:3])
        raise SpecError(f"has no student column ({names}, …) but {len(rows)} rows of answers: "
                        "without one, the file holds one student's answers in one row",
                        file=where)
    number, row = rows[0]
    if len(row) > len(header):
        raise SpecError(f"row {number} has {len(row)} cells, the header {len(header)}",
                        file=where)
    return [("*", {header[i]: row[i] for i in range(len(row))})]


def _no_student_twice(rows: list[tuple[str, dict[str, Any]]], where: str) -> None:
    """Refuse a file that answers for the same student twice (it would be graded twice)."""
    seen: dict[str, int] = {}
    for index, (student, _) in enumerate(rows, start=1):
        name = student.strip().lower()
        if name in seen:
            raise SpecError(f"student {student!r} answers twice (entries {seen[name]} and "
                            f"{index}); keep one", file=where)
        seen[name] = index


def _direction(value: float) -> str:
    return "counter-clockwise" if value > 0 else "clockwise"


def _off(answer: float, right: float) -> str:
    """How far off an answer is: ``24.1 % low``, ``1000 times the right value``."""
    if right == 0:
        return f"{abs(answer - right):.3g} off"
    ratio = answer / right
    if ratio >= 10 or 0 < ratio <= 0.1:
        return f"{ratio:.4g} times the right value"
    relative = ratio - 1.0
    magnitude = " in magnitude" if right < 0 and ratio > 0 else ""
    return f"{abs(relative) * 100:.1f} % {'high' if relative > 0 else 'low'}{magnitude}"


def grade_question(question: Mapping[str, Any], raw: Any) -> dict:
    """Grade one answer; returns the question's result with its feedback."""
    name, unit = question["id"], question.get("unit", "")
    value, tolerance = float(question["value"]), float(question["tolerance"])
    points = float(question.get("points", 1.0))
    right = f"{_number_text(value)} {unit} ± {tolerance:.3g}".replace("  ", " ")
    result = {"id": name, "answer": None, "value": value, "tolerance": tolerance,
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
    if signed and value != 0 and answer != 0 and (answer > 0) != (value > 0):
        text = (f"{shown}: wrong — the sense is reversed (the right answer is "
                f"{_direction(value)}, {right}) and the magnitude "
                f"{_number_text(abs(answer))} is {_off(abs(answer), abs(value))}")
    else:
        tolerance_text = (f" = ± {tolerance / abs(value) * 100:.2g} %" if value else "")
        text = (f"{shown}: wrong — {_off(answer, value)} (off by "
                f"{_number_text(abs(answer - value))} {unit}; right: {right}"
                f"{tolerance_text})").replace("  ", " ")
    result["feedback"] = text
    result["hint"] = f"{shown}: wrong ({_way(answer, value, signed)})"
    return result


def _way(answer: float, right: float, signed: bool) -> str:
    """Which way an answer is off, without the right value: ``too high``, ``too low in
    magnitude``, ``the sense is reversed``."""
    if signed and right != 0 and answer != 0 and (answer > 0) != (right > 0):
        return "the sense is reversed"
    if right < 0 and answer < 0:
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
        by_lower.setdefault(str(name).strip().lower(), name)
    results, used = [], set()
    for question in key["questions"]:
        name = question["id"]
        found = name if name in answers else by_lower.get(name.lower())
        if found is not None:
            used.add(found)
        results.append(grade_question(question, answers.get(found) if found is not None
                                      else None))
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
