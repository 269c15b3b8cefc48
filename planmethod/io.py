"""Output files written whole or not at all, and only where the user said.

Every file planmethod writes goes to a temporary file beside its target and is renamed into
place only when complete, so a failure never leaves a half-written output. Every name that
comes from user input and becomes part of a path (a PrairieLearn slug, a student's folder)
passes :func:`path_component`, and files written into an output folder go through
:func:`write_files`, which refuses any relative path that would leave that folder.

Examples
--------
>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> write_text_atomic(folder / "a.txt", "hello")
>>> (folder / "a.txt").read_text()
'hello'
>>> path_component("../../x", "--slug")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
planmethod.errors.SpecError: --slug: '../../x' is not a single folder or file name (...)
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import os
import re
import tempfile
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path, PurePosixPath

from .errors import PlanmethodError, SpecError

__all__ = [
    "atomic_path",
    "csv_text",
    "path_component",
    "spreadsheet_cell",
    "spreadsheet_text",
    "student_folder",
    "write_bytes_atomic",
    "write_files",
    "write_text_atomic",
]

#: characters that would make a name more than one path component (or an invalid one)
_SEPARATORS = ("/", "\\", "\0")


def path_component(name: str, what: str) -> str:
    """``name`` if it is one path component, else a :class:`SpecError` naming ``what`` (the
    option or key it came from): not empty, no ``/``, ``\\`` or NUL, not ``.`` or ``..``.

    Examples
    --------
    >>> path_component("fourbar-2026", "--slug")
    'fourbar-2026'
    """
    if (not isinstance(name, str) or not name.strip() or name in (".", "..")
            or any(separator in name for separator in _SEPARATORS)):
        raise SpecError(f"{name!r} is not a single folder or file name (it must not be empty, "
                        "contain '/' or '\\', or be '.' or '..')", key=what)
    return name


def student_folder(student: str) -> str:
    """The folder name of a student id: unsafe characters replaced by ``_``, dots stripped
    from the ends, at most 80 characters — always one path component.

    Examples
    --------
    >>> student_folder("Ann.Lee@uni.edu"), student_folder("../x"), student_folder("..")
    ('Ann.Lee@uni.edu', '_x', 'student')
    """
    name = re.sub(r"[^A-Za-z0-9_.@-]", "_", str(student)).strip(".")[:80].strip(".")
    return path_component(name or "student", "student id")


def _inside(folder: Path, relative: str) -> Path:
    """``folder / relative`` where every part of ``relative`` is one path component."""
    parts = PurePosixPath(relative).parts
    if not parts or PurePosixPath(relative).is_absolute():
        raise SpecError(f"{relative!r} is not a path inside the output folder", file=str(folder))
    for part in parts:
        path_component(part, f"output file {relative!r}")
    return folder.joinpath(*parts)


def json_text(data: object) -> str:
    """JSON a person can read and a program writes fast: an object's members one to a line,
    and the items of a member that is a list one to a line, each written compactly by the json
    module's C encoder (``indent`` would make json encode everything in Python, about three
    times slower for an answer key). No NaN or infinity (a ValueError).

    >>> print(json_text({"format": "key", "questions": [{"id": "v_C"}, {"id": "a_C"}]}))
    {
     "format": "key",
     "questions": [
      {"id": "v_C"},
      {"id": "a_C"}
     ]
    }
    """
    def one(value: object) -> str:
        return json.dumps(value, ensure_ascii=False, allow_nan=False)

    def member(value: object) -> str:
        if isinstance(value, list) and value:
            return "[\n" + ",\n".join(f"  {one(item)}" for item in value) + "\n ]"
        return one(value)

    if isinstance(data, Mapping) and data:
        return ("{\n" + ",\n".join(f" {one(str(k))}: {member(v)}" for k, v in data.items())
                + "\n}")
    return one(data)


def write_files(folder: str | Path, files: Mapping[str, str | bytes]) -> list[Path]:
    """Write ``files`` (relative path → text or bytes) into ``folder``, each whole or not at
    all; every path is checked to stay inside ``folder`` before anything is written."""
    folder = Path(folder)
    targets = {name: _inside(folder, name) for name in files}
    for name, data in files.items():
        if isinstance(data, bytes):
            write_bytes_atomic(targets[name], data)
        else:
            write_text_atomic(targets[name], data)
    return list(targets.values())


@contextlib.contextmanager
def atomic_path(target: str | Path, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path beside ``target``; rename it onto ``target`` on success."""
    target = Path(target)
    folder = target.parent if str(target.parent) else Path(".")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise PlanmethodError(f"cannot create the folder {folder}: {error.strerror}",
                              file=str(target)) from None
    try:
        handle, name = tempfile.mkstemp(prefix=f".{target.name}.",
                                        suffix=suffix or target.suffix, dir=folder)
    except OSError as error:
        raise PlanmethodError(f"cannot create a file in {folder}: {error.strerror}",
                              file=str(target)) from None
    temporary = Path(name)
    try:  # from here on, whatever happens (an error, Ctrl-C, SIGTERM), the file is removed
        os.close(handle)
        try:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(temporary, 0o666 & ~umask)  # an ordinary new file's mode, not 0600
        except OSError:
            pass  # a file system without modes (the file stays private)
        yield temporary
        os.replace(temporary, target)
    except OSError as error:
        raise PlanmethodError(f"cannot write the file: {error.strerror}",
                              file=str(target)) from None
    finally:
        if temporary.exists():
            temporary.unlink()


def write_text_atomic(target: str | Path, text: str) -> None:
    """Write ``text`` (UTF-8) to ``target`` whole or not at all."""
    with atomic_path(target) as temporary:
        temporary.write_text(text, encoding="utf-8")


def write_bytes_atomic(target: str | Path, data: bytes) -> None:
    """Write ``data`` to ``target`` whole or not at all."""
    with atomic_path(target) as temporary:
        temporary.write_bytes(data)


# -- CSV a spreadsheet opens safely ------------------------------------------------------------
#: what makes a spreadsheet (Excel, LibreOffice Calc, Google Sheets) read a text cell as a
#: formula when it starts the cell: ``= + - @``, tab and carriage return (OWASP, "CSV
#: Injection"), NUL (OWASP ASVS 1.2.10) and line feed
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r", "\n", "\0")
#: a plain decimal number, which a spreadsheet reads as a number and never as a formula
_PLAIN_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def spreadsheet_cell(value: object) -> object:
    """A CSV cell that no spreadsheet runs as a formula, as OWASP advises: text that starts
    with one of :data:`FORMULA_STARTS` (after any spaces) gets a ``'`` in front, and so does text
    that starts with ``'`` itself, so that :func:`spreadsheet_text` gives back exactly the text
    written. Numbers, and text that is a plain decimal number (``-1.5``), stay as they are;
    None is an empty cell.

    Examples
    --------
    >>> spreadsheet_cell("=1+2"), spreadsheet_cell("@SUM(A1)"), spreadsheet_cell(" +x")
    ("'=1+2", "'@SUM(A1)", "' +x")
    >>> spreadsheet_cell(-1.5), spreadsheet_cell("-1.5"), spreadsheet_cell("s01")
    (-1.5, '-1.5', 's01')
    """
    if value is None:
        return ""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return value
    text = str(value)
    if (text.startswith("'") or text.lstrip(" ").startswith(FORMULA_STARTS)) \
            and not _PLAIN_NUMBER.fullmatch(text):
        return "'" + text
    return text


def spreadsheet_text(cell: str) -> str:
    """The text a cell written through :func:`spreadsheet_cell` stands for (its ``'`` taken
    off): what a reader of planmethod's own CSV files uses, so that ids survive a round trip.

    >>> spreadsheet_text(spreadsheet_cell("=1+1")), spreadsheet_text(spreadsheet_cell("'x"))
    ('=1+1', "'x")
    """
    return cell[1:] if cell.startswith("'") else cell


def csv_text(rows: Iterable[Iterable[object]]) -> str:
    """CSV text (comma-separated, quoted where needed, one line per row ending in a line feed)
    whose every cell went through :func:`spreadsheet_cell`: every CSV planmethod writes is made
    here.

    >>> print(csv_text([["student", "score"], ["=cmd|' /C calc'!A0", -1.5]]), end="")
    student,score
    '=cmd|' /C calc'!A0,-1.5
    """
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    for row in rows:
        writer.writerow([spreadsheet_cell(cell) for cell in row])
    return buffer.getvalue()
