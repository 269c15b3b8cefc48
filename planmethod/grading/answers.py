"""Grading numeric answers against a key, with feedback that names common mistakes.

Answers come as CSV (a header row; a ``student`` column — or ``id``, ``student_id``, ``sid``,
``email``, ``name`` — and one column per question id such as ``v_C``, ``omega_BC``; a file
without a student column is one student's answers in one row) or as JSON
(``{"s01": {"v_C": 5.2, …}, …}``, or a list of ``{"student": "s01", "v_C": 5.2, …}`` /
``{"student": "s01", "answers": {…}}``). An answers file downloaded from the workbook page
is one student's: ``{"format": "planmethod-answers", "title": …, "exercise": …, "angle": …,
"answers": {…}, "revealed": [question id, …]}`` (:mod:`planmethod.grading.page_answers`).

An answer within the question's tolerance scores the question's points. Otherwise the
feedback says by how much it is off, and names the mistake when the answer matches one
(see :data:`planmethod.grading.mistakes.REGISTRY`): a reversed sense, a normal or Coriolis
component left out or reversed, a scale applied twice or not at all, degrees for radians,
millimetres for metres. An answer is classified first (:func:`classify`: a
:class:`~planmethod.grading.verdicts.Verdict` with its fields), and its sentences are its
verdict's templates (:mod:`planmethod.grading.verdicts`) filled with them.

Examples
--------
>>> from planmethod.grading.templates import load_template, draw_variant
>>> from planmethod.grading.keys import build_key
>>> from planmethod.words import render
>>> key = build_key(draw_variant(load_template("exercises/compressor_slider_crank.toml")))
>>> result = grade_answers(key, {"v_C": 5.27, "omega_BC": 24.25})
>>> [q.correct for q in result.questions[:1]], result.score
([True], 1.0)
>>> print(render(next(q for q in result.questions if q.id == "omega_BC").feedback))
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
from ..vocabulary import quantity, question_text, symbol, unit_words
from ..words import Message, message, plural, render, template
from .reading import read_number
from .results import GradedQuestion, KeyMistake, KeyQuestion, StudentGrade
from .verdicts import (
    AMOUNT,
    AMOUNT_BARE,
    GIVEN,
    MAGNITUDE,
    OFF,
    RIGHT,
    ROUGHLY,
    SENSES,
    WAYS,
    AnswerVerdict,
    Off,
    Verdict,
    Way,
)

__all__ = ["ANSWERS_FORMAT", "FEEDBACK_LEVELS", "MAX_ANSWER_BYTES", "STUDENT_COLUMNS",
           "answers_from_csv",
           "classify", "feedback_text", "grade_answers", "grade_many", "grade_question",
           "magnitude_note", "read_answers", "refuse_twice", "sense_words"]

MAX_ANSWER_BYTES = 20_000_000
MAX_ROWS = 200_000
#: the ``format`` of an answers file downloaded from the workbook page
ANSWERS_FORMAT = "planmethod-answers"
STUDENT_COLUMNS = ("student", "student_id", "id", "sid", "email", "name")
#: the mistake of a reversed sense (named without how far off the answer is)
SENSE = "sense"


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
_NOT_ANSWERS = message("this is planmethod grade's --json output (graded results), not an "
                       "answers file")
#: what a JSON value is, in words (``a list``, ``a number``…)
_KINDS = {"object": message("an object"), "list": message("a list"),
          "boolean": message("true/false"), "null": message("null"),
          "number": message("a number"), "text": message("a text")}


def _line(line: int) -> str:
    """A line of a file, as an error's key names it."""
    return render(message("line {line}", line=line))


def _kind(value: Any) -> Message:
    """What a JSON value is, in words: ``a list``, ``a number``…"""
    if isinstance(value, Mapping | list):
        return _KINDS["object" if isinstance(value, Mapping) else "list"]
    if isinstance(value, bool) or value is None:
        return _KINDS["boolean" if value is not None else "null"]
    return _KINDS["number" if isinstance(value, int | float) else "text"]


def _one_answer_each(answers: Mapping[str, Any], where: str, prefix: str) -> dict[str, Any]:
    """A student's answers, each a number, a text, true/false or null — never a list or an
    object (which would be graded as no answer while the file meant something else)."""
    if any(keys <= set(answers) for keys in _RESULTS_KEYS):
        raise SpecError(_NOT_ANSWERS, file=where, key=prefix or None)
    for name, value in answers.items():
        if isinstance(value, Mapping | list):
            raise SpecError(message("is {kind}, not an answer (a number): give "
                                    "{{\"question id\": answer, …}} for each student",
                                    kind=_kind(value)),
                            file=where, key=f"{prefix}.{name}" if prefix else str(name))
    # graded by id compared as grade_answers compares them: one of two would be lost
    refuse_twice([str(name) for name in answers], _folded, "answer", file=where,
                 key=prefix or None, compared=message("question ids compared ignoring case"))
    return dict(answers)


def _stray(data: Mapping[str, Any], students: list, where: str) -> SpecError:
    """The error of a JSON object of students with a stray value, or of one student's
    answers with an object among them (whichever most entries are)."""
    by_student = 2 * len(students) >= len(data)   # most entries are students' objects
    odd = next(name for name, value in data.items()
               if isinstance(value, Mapping) != by_student)
    others = len(students) if by_student else len(data) - len(students)
    like = message("an object of one student's answers") if by_student else message("an answer")
    return SpecError(plural("is {kind}, not {like} like the {count} other: the file is either "
                            "{{\"student\": {{\"question id\": answer, …}}, …}} or one "
                            "student's {{\"question id\": answer, …}}",
                            "is {kind}, not {like} like the {count} others: the file is either "
                            "{{\"student\": {{\"question id\": answer, …}}, …}} or one "
                            "student's {{\"question id\": answer, …}}",
                            count=others, kind=_kind(data[odd]), like=like),
                     file=where, key=str(odd))


def _answers_of_object(data: Mapping[str, Any], where: str) -> list[tuple[str, dict[str, Any]]]:
    """The rows of a JSON object: of students' objects, or one student's answers."""
    if not data:
        raise SpecError(message("no student's answers (the object is empty)"), file=where)
    if any(keys <= set(data) for keys in _RESULTS_KEYS):
        raise SpecError(_NOT_ANSWERS, file=where)
    if data.get("format") == ANSWERS_FORMAT:   # the page's: one student's, with what it was
        answers = data.get("answers")
        if not isinstance(answers, Mapping):
            raise SpecError(message("must be an object of answers"), file=where, key="answers")
        return [("*", _one_answer_each(answers, where, "answers"))]
    students = [name for name, value in data.items() if isinstance(value, Mapping)]
    if len(students) == len(data):       # {"s01": {"v_C": 5.2, …}, …}
        return [(str(name), _one_answer_each(value, where, str(name)))
                for name, value in data.items()]
    if not students:                     # one student's answers
        return [("*", _one_answer_each(data, where, ""))]
    raise _stray(data, students, where)


def _answers_of_list(data: list, where: str) -> list[tuple[str, dict[str, Any]]]:
    """The rows of a JSON list of students' entries."""
    if not data:
        raise SpecError(message("no student's answers (the list is empty)"), file=where)
    rows = []
    for index, item in enumerate(data):
        if not isinstance(item, Mapping):
            raise SpecError(message("each entry must be an object"), file=where,
                            key=f"[{index}]")
        column = next((c for c in STUDENT_COLUMNS if c in item), None)
        student = item[column] if column is not None else None
        if isinstance(student, Mapping | list) or student is None or not str(student).strip():
            raise SpecError(message("no student id (give 'student')"), file=where,
                            key=f"[{index}]" + (f".{column}" if column else ""))
        answers = item.get("answers", {k: v for k, v in item.items()
                                       if k not in STUDENT_COLUMNS})
        if not isinstance(answers, Mapping):
            raise SpecError(message("must be an object of answers"), file=where,
                            key=f"[{index}].answers")
        rows.append((str(student), _one_answer_each(
            answers, where, f"[{index}].answers" if "answers" in item else f"[{index}]")))
    return rows


def _too_many_students(where: str) -> SpecError:
    return SpecError(plural("more than {count} student", "more than {count} students",
                            count=MAX_ROWS), file=where)


def _answers_from_json(text: str, where: str) -> list[tuple[str, dict[str, Any]]]:
    data = parse_json(text, file=where, unique_keys=True)
    if isinstance(data, Mapping):
        rows = _answers_of_object(data, where)
    elif isinstance(data, list):
        rows = _answers_of_list(data, where)
    else:
        raise SpecError(message("must be an object or a list of objects"), file=where)
    if len(rows) > MAX_ROWS:
        raise _too_many_students(where)
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
                raise SpecError(message("not valid CSV: {problem} (is a quote (\") left open "
                                        "or a cell quoted twice?)", problem=str(error)),
                                file=self.where, key=_line(line)) from None
            if any("\n" in cell or "\r" in cell for cell in row):
                raise SpecError(message("a quoted cell runs on to line {line}: is a closing "
                                        "quote (\") missing?", line=self.reader.line_num),
                                file=self.where, key=_line(line))
            yield line, row


def _header(records, where: str) -> tuple[int, list[str]]:
    """The header row (its line, its stripped cells); a column given twice is refused."""
    try:
        line, header = next(iter(records))
    except StopIteration:
        raise SpecError(message("the file is empty"), file=where) from None
    header = [h.strip() for h in header]
    refuse_twice(header, str.lower, "column", file=where, key=_line(line),
                 places="columns", advice="which")
    return line, header


def _too_long_row(row: list[str], header: list[str], line: int, where: str) -> SpecError:
    return SpecError(plural("has {count} cell, the header {header}",
                            "has {count} cells, the header {header}",
                            count=len(row), header=len(header)), file=where, key=_line(line))


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
        raise SpecError(message("needs a header row with a student column and question "
                                "columns (e.g. student,v_C,omega_BC)"), file=where)
    rows = []
    for line, row in records:
        if not any(cell.strip() for cell in row):
            continue
        if len(rows) >= MAX_ROWS:
            raise _too_many_students(where)
        if len(row) > len(header):
            raise _too_long_row(row, header, line, where)
        student = row[column].strip() if column < len(row) else ""
        if not student:
            raise SpecError(message("no student id (column '{column}')", column=header[column]),
                            file=where, key=_line(line))
        rows.append((student, {header[i]: row[i] for i in range(len(row)) if i != column}))
    if not rows:
        raise SpecError(message("a header (line {line}) and no student's answers under it",
                                line=header_line), file=where)
    return rows


def _one_student_csv(records, header: list[str], where: str) -> list[tuple[str, dict[str, Any]]]:
    """A CSV without a student column: one student's answers, in the one row under the
    header (the student is ``*``, the one the command is grading). Nothing is dropped."""
    rows = [(line, row) for line, row in records if any(cell.strip() for cell in row)]
    if len(rows) != 1:
        raise SpecError(plural("has no student column ({columns}, …) but {count} row of "
                               "answers: without one, the file holds one student's answers in "
                               "one row",
                               "has no student column ({columns}, …) but {count} rows of "
                               "answers: without one, the file holds one student's answers in "
                               "one row", count=len(rows), columns=list(STUDENT_COLUMNS[:3])),
                        file=where)
    line, row = rows[0]
    if len(row) > len(header):
        raise _too_long_row(row, header, line, where)
    return [("*", {header[i]: row[i] for i in range(len(row))})]


def _no_student_twice(rows: list[tuple[str, dict[str, Any]]], where: str) -> None:
    """Refuse a file that answers for the same student twice (it would be graded twice)."""
    refuse_twice([student for student, _ in rows], _folded, "student", file=where,
                 places="entries")


def _folded(name: str) -> str:
    """A name as ids are compared: without the spaces around it, ignoring case."""
    return name.strip().lower()


#: what is given twice, by what it is (a name given twice, two spellings of one name)
_TWICE = {"column": template("column {name!r} is given twice"),
          "answer": template("answer {name!r} is given twice"),
          "student": template("student {name!r} answers twice"),
          "point": template("point {name!r} is given twice")}
_ONE = {"column": template("column {first!r} and column {name!r} are one column, {compared}"),
        "answer": template("answer {first!r} and answer {name!r} are one answer, {compared}"),
        "student": template("student {first!r} and student {name!r} are one student, "
                            "{compared}"),
        "point": template("point {first!r} and point {name!r} are one point, {compared}")}
#: where the two are, by what the places count
_PLACES = {"columns": template("{sentence} (columns {first} and {second})"),
           "entries": template("{sentence} (entries {first} and {second})")}
#: how names are compared, unless said otherwise
_IGNORING_CASE = message("compared ignoring case")
#: what to do about it
_ADVICE = {"keep": template("{sentence}; keep one"),
           "which": template("{sentence}: which one holds the answers?")}


def refuse_twice(names: Sequence[str], normal: Callable[[str], str], what: str, *,
                 file: str | None, key: str | None = None,
                 compared: Message | str = _IGNORING_CASE,
                 places: str | None = None, advice: str = "keep",
                 error: type[SpecError] = SpecError) -> None:
    """Refuse two of ``names`` that are one after ``normal`` (how they are compared): one
    value would be kept and the other lost without a word. The :class:`SpecError` names
    both as written, and their places (``places``: what the 1-based positions count,
    ``columns`` or ``entries``; None for names whose order says nothing, the keys of a JSON
    object). ``what`` the names are: a ``column``, ``answer``, ``student`` or ``point``;
    ``advice``: ``keep`` (one) or ``which`` (one holds the answers?). Empty names are not
    compared. Answers files, drawn plans and ``check``'s coordinate tables are read through
    it; ``error`` is the kind of error raised (a drawing's
    :class:`~planmethod.grading.drawings.SubmissionError`).

    Examples
    --------
    >>> refuse_twice(["student", "v_C", "V_c"], str.lower, "column", file="a.csv",
    ...              places="columns")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: a.csv: column 'v_C' and column 'V_c' are one column, \
compared ignoring case (columns 2 and 3); keep one
    >>> refuse_twice(["s1", "s1"], str.lower, "student", file="a.csv", places="entries")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: a.csv: student 's1' answers twice (entries 1 and 2); keep one
    """
    seen: dict[str, int] = {}
    for number, name in enumerate(names, start=1):
        form = normal(name) if name else ""
        if form in seen:
            first = names[seen[form] - 1]
            sentence = (_TWICE[what].replace(name=name) if first == name else
                        _ONE[what].replace(first=first, name=name, compared=compared))
            if places:
                sentence = _PLACES[places].replace(sentence=sentence, first=seen[form],
                                                   second=number)
            raise error(_ADVICE[advice].replace(sentence=sentence), file=file, key=key)
        if form:
            seen[form] = number


def sense_words(name: str) -> tuple[Message, Message]:
    """What a positive and a negative value of the quantity ``name`` (an id: ``omega_BC``,
    ``ds_slider/frame``) mean, in words (:data:`~planmethod.grading.verdicts.SENSES`);
    ``grade`` and the workbook page both tell a reversed sign with them.

    >>> [render(word) for word in sense_words("omega_BC")]
    ['counter-clockwise', 'clockwise']
    >>> [render(word) for word in sense_words("s_slider/frame")]
    ['positive, along the guide', 'negative, against the guide']
    """
    try:
        subject = quantity(name).kind.subject
    except KeyError:
        return SENSES[""]
    return SENSES.get(subject, SENSES[""])


def _amount(number: float, unit: str) -> Message:
    """A number with its unit (the unit left out where there is none)."""
    return AMOUNT.replace(number=number, unit=unit_words(unit)) if unit else AMOUNT_BARE.replace(
        number=number)


def _off(answer: float, right: float) -> Message:
    """How far off an answer is: ``24.1 % low``, ``1000 times the right value``."""
    if right == 0:
        return OFF[Off.BY].replace(amount=abs(answer - right))
    ratio = answer / right
    if ratio >= 10 or 0 < ratio <= 0.1:
        return OFF[Off.TIMES].replace(ratio=ratio)
    relative = ratio - 1.0
    if right < 0 and ratio >= 0:
        way = Off.HIGH_IN_MAGNITUDE if relative > 0 else Off.LOW_IN_MAGNITUDE
    else:
        way = Off.HIGH if relative > 0 else Off.LOW
    return OFF[way].replace(percent=abs(relative) * 100)


def _rough(value: float) -> float:
    """``value`` to one significant digit (``12.4`` → ``10``): how far off a hint tells."""
    return float(format(value, ".1g"))


def _way(answer: float, right: float, signed: bool) -> Message:
    """Which way an answer is off and about how far, without the right value: ``about 10 %
    too high``, ``about 20 % too small in magnitude``, ``about 30 times what it should be``,
    ``the sense is reversed``; ``too high`` alone where no share of the right value tells
    (a right value of 0, an answer of 0 or of the other sign)."""
    if signed and right != 0 and answer != 0 and (answer > 0) != (right > 0):
        return WAYS[Way.SENSE]
    if right < 0 and answer <= 0:
        way = Way.LARGER if answer < right else Way.SMALLER
    else:
        way = Way.HIGH if answer > right else Way.LOW
    ratio = answer / right if right else 0.0
    if ratio <= 0:
        return WAYS[way]
    if ratio >= 2 or ratio <= 0.1:
        return ROUGHLY["times"].replace(ratio=_rough(ratio))
    return ROUGHLY[way].replace(percent=_rough(abs(ratio - 1.0) * 100))


def _verdict(kind: AnswerVerdict, **fields: Any) -> Verdict:
    return Verdict(kind, tuple(fields.items()))


def _typed(question: KeyQuestion | Mapping[str, Any]) -> KeyQuestion:
    return question if isinstance(question, KeyQuestion) else KeyQuestion.read(question)


def _named_mistake(question: KeyQuestion, answer: float, given: Message, right: Message
                   ) -> tuple[Verdict, KeyMistake, str] | None:
    """The verdict of an answer that a known mistake gives (with the sense reversed too,
    for a signed quantity), with the mistake and the name it is graded by."""
    value = question.value
    for mistake in question.mistakes:
        if abs(answer - mistake.value) <= mistake.tolerance:
            kind = AnswerVerdict.SENSE_MISTAKE if mistake.kind == SENSE else \
                AnswerVerdict.MISTAKE
            return _verdict(kind, answer=given, off=_off(answer, value),
                            mistake=mistake.explanation, gives=mistake.value, right=right,
                            way=_way(answer, value, signed=False)), mistake, mistake.kind
    if not question.signed:
        return None
    for mistake in question.mistakes:
        if mistake.kind != SENSE and abs(-answer - mistake.value) <= mistake.tolerance:
            return (_verdict(AnswerVerdict.MISTAKE_AND_SENSE, answer=given,
                             mistake=mistake.explanation, right=right), mistake,
                    mistake.kind + "+sense")
    return None


def _wrong(question: KeyQuestion, answer: float, given: Message, right: Message) -> Verdict:
    """The verdict of a wrong answer that no known mistake gives."""
    value, tolerance, signed = question.value, question.tolerance, question.signed
    way = _way(answer, value, signed)
    if signed and value != 0 and answer != 0 and (answer > 0) != (value > 0):
        sense = sense_words(question.id)[0 if value > 0 else 1]
        if abs(abs(answer) - abs(value)) <= tolerance:
            return _verdict(AnswerVerdict.SENSE_REVERSED, answer=given, sense=sense,
                            right=right, magnitude=abs(answer), way=way)
        return _verdict(AnswerVerdict.SENSE_AND_SIZE, answer=given, sense=sense, right=right,
                        magnitude=abs(answer), off=_off(abs(answer), abs(value)), way=way)
    fields = {"answer": given, "off": _off(answer, value), "right": right, "way": way,
              "off_by": _amount(abs(answer - value), question.unit)}
    if not value:
        return _verdict(AnswerVerdict.WRONG_OF_ZERO, **fields)
    return _verdict(AnswerVerdict.WRONG, share=tolerance / abs(value) * 100, **fields)


def classify(question: KeyQuestion, answer: float, numbers: Mapping[str, int] | None = None
             ) -> tuple[Verdict, KeyMistake | None, str | None]:
    """The verdict on a number given for ``question``: right (within the tolerance), the
    answer of a known mistake (the mistake, and the name it is graded by: its kind, with
    ``+sense`` when the sense is reversed too), a negative number for a magnitude (told in
    the course's symbols under the links' ``numbers``), or wrong (how far off, and which way).

    >>> question = KeyQuestion.read({"id": "v_C", "value": 5.27, "tolerance": 0.1})
    >>> verdict, mistake, name = classify(question, 6.0)
    >>> verdict.kind, round(dict(verdict.fields)["share"], 2), mistake, name
    (<AnswerVerdict.WRONG: 'wrong'>, 1.9, None, None)
    >>> render(verdict.feedback())
    'v_C = 6: wrong — 13.9 % high (off by 0.73; right: 5.27 ± 0.1 = ± 1.9 %)'
    """
    value, tolerance = question.value, question.tolerance
    given = GIVEN.replace(symbol=question.symbol, amount=_amount(answer, question.unit))
    right = RIGHT.replace(amount=_amount(value, question.unit), tolerance=tolerance)
    if abs(answer - value) <= tolerance:
        return (_verdict(AnswerVerdict.CORRECT, answer=given, value=value, tolerance=tolerance),
                None, None)
    named = _named_mistake(question, answer, given, right)
    if named is not None:
        return named
    note = None if question.signed or answer >= 0 else magnitude_note(question.id, numbers)
    if note is not None:
        return _verdict(AnswerVerdict.NEGATIVE_MAGNITUDE, answer=given, note=note,
                        right=right), None, None
    return _wrong(question, answer, given, right), None, None


def grade_question(question: KeyQuestion | Mapping[str, Any], raw: Any,
                   numbers: Mapping[str, int] | None = None) -> GradedQuestion:
    """Grade one answer (``raw``, as given) to one question of a key (typed, or its table
    in the key); the result's feedback names the quantity as the course writes it (the
    key's ``symbol``, where the key has one; the links' ``numbers`` name it in what a
    negative magnitude is told)."""
    question = _typed(question)
    answer = _parse_number(raw)
    graded = {"id": question.id, "value": question.value, "tolerance": question.tolerance,
              "unit": question.unit, "max_score": question.points}
    if answer is None or isinstance(answer, str):
        right = RIGHT.replace(amount=_amount(question.value, question.unit),
                              tolerance=question.tolerance)
        verdict = (_verdict(AnswerVerdict.NO_ANSWER, symbol=question.symbol, right=right)
                   if answer is None else _verdict(AnswerVerdict.NOT_A_NUMBER,
                                                   symbol=question.symbol, given=answer,
                                                   right=right))
        return GradedQuestion(answer=None, score=0.0, correct=False, mistake=None,
                              verdict=verdict, **graded)
    verdict, mistake, name = classify(question, answer, numbers)
    correct = verdict.kind is AnswerVerdict.CORRECT
    alone = mistake is not None and not name.endswith("+sense")
    return GradedQuestion(answer=answer, score=question.points if correct else 0.0,
                          correct=correct, mistake=name, verdict=verdict,
                          also=(mistake.also or ()) if alone else (), **graded)


def magnitude_note(name: str, numbers: Mapping[str, int] | None = None) -> Message | None:
    """What a negative answer for the magnitude ``name`` (a quantity id: ``v_B@lever``) is
    told, in the course's symbols under the links' ``numbers`` (None for a signed quantity
    or an unknown name). ``grade`` and the workbook page both say it from here.

    >>> render(magnitude_note("v_C"))
    'v_C is the speed of C, |v_C|: a magnitude, never negative'
    >>> render(magnitude_note("v_B@lever", {"frame": 0, "crank": 1, "block": 2, "lever": 3}))
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
    # words: vocabulary (question_text is English text until it returns a message)
    return MAGNITUDE.replace(symbol=symbol(name, numbers),
                             question=question_text(name, numbers))


#: what a student is shown of each graded question, by feedback level
FEEDBACK_LEVELS = ("full", "hints", "score")


def feedback_text(question: GradedQuestion | Mapping[str, Any], level: str = "full"
                  ) -> Message | str:
    """The feedback on one graded question (typed, or as ``grade --json`` writes it) at a
    level: ``full`` (the values: the right answer and its tolerance), ``hints`` (the
    mistake named and which way the answer is off, never the right value) or ``score``
    (nothing but the points).

    Examples
    --------
    >>> graded = grade_question({"id": "v_C", "value": 5.27, "tolerance": 0.1}, 6.0)
    >>> render(feedback_text(graded, "hints"))
    'v_C = 6: wrong (about 10 % too high)'
    >>> "5.27" in render(feedback_text(graded, "full")), feedback_text(graded, "score")
    (True, '')
    """
    if level not in FEEDBACK_LEVELS:
        raise ValueError(render(message("feedback level {level!r} is not one of {levels}",
                                        level=level, levels=list(FEEDBACK_LEVELS))))
    if level == "score":
        return ""
    if isinstance(question, GradedQuestion):
        return question.feedback if level == "full" else question.hint
    return question["feedback"] if level == "full" else question.get("hint", "")


def grade_answers(key: Mapping[str, Any], answers: Mapping[str, Any],
                  student: str | None = None) -> StudentGrade:
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
    from .keys import key_numbers, key_questions

    numbers = key_numbers(key)
    results, used = [], set()
    for question in key_questions(key):
        name = question.id
        found = name if name in answers else by_lower.get(name.lower())
        if found is not None:
            used.add(found)
        results.append(grade_question(question, answers.get(found) if found is not None
                                      else None, numbers))
    ignored = sorted(str(n) for n in answers if n not in used)
    return StudentGrade(student if student is not None else key.get("student"),
                        key.get("student"), sum(r.score for r in results),
                        sum(r.max_score for r in results), tuple(results), tuple(ignored))


def grade_many(keys: Mapping[str, Mapping[str, Any]],
               rows: list[tuple[str, Mapping[str, Any]]]) -> list[StudentGrade]:
    """Grade many students: each against the key of their own variant (or the key ``*``).

    A student with no key of their own and no common key gets a grade with an ``error``.

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
            out.append(StudentGrade(student, None, 0.0, None,
                                    error=message("no key for student {student!r}",
                                                  student=student)))
            continue
        out.append(grade_answers(key, answers, student=student))
    return out
