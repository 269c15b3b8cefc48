"""Run folders: what one command writes into a folder as a whole — a ``variants`` run, an
``export`` package — with a manifest, so that a later run replaces it whole and never mixes
with it, and never removes a file it did not write.

A run's folder holds its files and ``manifest.json``: every file of the run with its size in
bytes and its SHA-256, under a format tag of the command that wrote it. A later run into the
same folder (:func:`earlier_run`) replaces the earlier one only when everything in the folder is
what that manifest lists, unchanged — another file or folder, a symbolic link, an edited file,
a folder without a manifest or with another command's is refused in one line, and nothing is
touched. The new run is written beside the earlier one and swapped in whole
(:meth:`planmethod.io.OutputSet.folder`); then the earlier run's files are removed one by one,
each checked again against its manifest (:func:`write_run`). ``variants`` replaces its earlier
run only with ``--force``; ``export`` always replaces its own (it is made from the keys again).

Examples
--------
>>> import tempfile, pathlib
>>> kind = RunKind("example", "planmethod-example-manifest", lambda name: name == "a.txt")
>>> folder = pathlib.Path(tempfile.mkdtemp()) / "run"
>>> write_run(folder, kind, {"a.txt": b"first"}, earlier_run(folder, kind))
>>> write_run(folder, kind, {"a.txt": b"second"}, earlier_run(folder, kind, force=True))
>>> sorted(path.name for path in folder.iterdir()), (folder / "a.txt").read_text()
(['a.txt', 'manifest.json'], 'second')
>>> (folder / "notes.txt").write_text("mine")
4
>>> earlier_run(folder, kind, force=True)  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
planmethod.errors.SpecError: .../run holds files no example run wrote (notes.txt): ...
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
import stat
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

from .errors import SpecError
from .io import json_text, output_set, read_text_bounded, sha256_of_file
from .words.message import Message, message, plural
from .words.render import render

__all__ = ["MANIFEST", "EarlierRun", "RunKind", "earlier_run", "manifest_text",
           "remove_retired", "write_run"]

#: the run's list of its own files, in its folder
MANIFEST = "manifest.json"
#: the largest manifest read (bytes)
MAX_MANIFEST_BYTES = 200_000_000


@dataclass(frozen=True)
class RunKind:
    """What writes a run folder: ``command`` (named in messages: ``variants``), the format
    tag of its manifest, ``writes`` — whether a relative path (``001/key.json``) is one the
    command writes: a manifest naming any other is refused — and ``force``, the option that
    lets it replace an earlier run (None: it always replaces its own)."""

    command: str
    format: str
    writes: Callable[[str], bool]
    force: str | None = "--force"

    @property
    def replacer(self) -> str:
        """What replaces an earlier run, as the sentences name it: the option (``--force``),
        or the command for a kind that always replaces its own run."""
        return self.force or self.command


@dataclass(frozen=True)
class EarlierRun:
    """A run found in a folder: its entries there (files, folders, manifest) and every file
    its manifest lists, relative path → (bytes, SHA-256)."""

    entries: tuple[str, ...]
    files: Mapping[str, tuple[int, str]]


def manifest_text(kind: RunKind, files: Mapping[str, bytes]) -> str:
    """The manifest of a run of ``kind``: each file's relative path, size and SHA-256.

    >>> kind = RunKind("variants", "planmethod-variants-manifest", bool)
    >>> print(manifest_text(kind, {"001/key.json": b"{}"}))  # doctest: +ELLIPSIS
    {
     "format": "planmethod-variants-manifest",
     "note": "written by planmethod variants: the files `variants --force` may remove, ...",
     "files": [
      ["001/key.json", 2, "44136fa355b3678a1146ad16f7e8649e94fb4fc21fe77e8310c060f61caaff8a"]
     ]
    }
    """
    note = (message("written by planmethod {command}: the files `{command} {option}` may "
                    "remove, each only while its size and SHA-256 are these",
                    command=kind.command, option=kind.force) if kind.force else
            message("written by planmethod {command}: the files a later `{command}` may "
                    "remove, each only while its size and SHA-256 are these",
                    command=kind.command))
    return json_text({"format": kind.format, "note": render(note),
                      "files": [[name, len(data), hashlib.sha256(data).hexdigest()]
                                for name, data in sorted(files.items())]})


def _read_manifest(folder: Path, kind: RunKind, name: str) -> dict[str, tuple[int, str]]:
    """The files the manifest in ``folder`` lists, or a :class:`SpecError`."""
    path = folder / MANIFEST
    if not os.path.lexists(path):
        raise SpecError(message("{folder} holds no {manifest}, so no {command} run of this "
                                "version wrote it: {replacer} replaces only such a run; choose "
                                "another folder", folder=name, manifest=MANIFEST,
                                command=kind.command, replacer=kind.replacer))
    if os.path.islink(path):
        raise SpecError(message("is a symbolic link, which {command} never writes: {replacer} "
                                "replaces only an earlier run", command=kind.command,
                                replacer=kind.replacer), file=str(path))
    try:
        data = json.loads(read_text_bounded(path, MAX_MANIFEST_BYTES))
    except json.JSONDecodeError as error:
        raise SpecError(message("not valid JSON ({reason})", reason=str(error)),
                        file=str(path)) from None
    if not isinstance(data, dict) or data.get("format") != kind.format:
        raise SpecError(message("not a manifest of {command} (format {format!r}): {replacer} "
                                "replaces only its own earlier run", command=kind.command,
                                format=kind.format, replacer=kind.replacer), file=str(path))
    files: dict[str, tuple[int, str]] = {}
    rows = data.get("files")
    for index, row in enumerate(rows if isinstance(rows, list) else [None]):
        if not (isinstance(row, list) and len(row) == 3 and isinstance(row[0], str)
                and row[0] != MANIFEST and kind.writes(row[0])
                and type(row[1]) is int and isinstance(row[2], str)
                and re.fullmatch(r"[0-9a-f]{64}", row[2])):
            raise SpecError(message("lists {row!r}, not a file {command} writes with its size "
                                    "and SHA-256", row=str(row)[:60], command=kind.command),
                            file=str(path), key=f"files[{index}]")
        files[row[0]] = (row[1], row[2])
    return files


def _unchanged(path: Path, size: int, digest: str) -> bool:
    """Whether ``path`` is a regular file (not a link) of ``size`` bytes and SHA-256
    ``digest``."""
    try:
        status = os.lstat(path)
    except OSError:
        return False
    return (stat.S_ISREG(status.st_mode) and status.st_size == size
            and sha256_of_file(path) == digest)


def _survey(folder: Path, files: Mapping[str, tuple[int, str]]
            ) -> tuple[list[str], list[str], list[str]]:
    """What in ``folder`` is not the run its manifest lists: (entries it does not list,
    symbolic links, listed files that changed), each a relative path."""
    folders = {"/".join(parts[:end]) for parts in (name.split("/") for name in files)
               for end in range(1, len(parts))}
    foreign: list[str] = []
    linked: list[str] = []
    changed: list[str] = []

    def walk(path: Path, relative: str) -> None:
        for name in sorted(os.listdir(path)):
            inner = f"{relative}/{name}" if relative else name
            entry = path / name
            if os.path.islink(entry):
                linked.append(inner)
            elif inner == MANIFEST:
                continue
            elif inner in files:
                if not _unchanged(entry, *files[inner]):
                    changed.append(inner)
            elif inner in folders and entry.is_dir():
                walk(entry, inner)
            else:
                foreign.append(inner)

    walk(folder, "")
    return foreign, linked, changed


def _listed(names: list[str]) -> list[str]:
    """At most three names, and an ellipsis for the rest (a list field, joined with commas)."""
    return [*names[:3], "…"] if len(names) > 3 else names


def earlier_run(folder: str | Path, kind: RunKind, *, force: bool = False,
                name: str | None = None) -> EarlierRun | None:
    """The earlier run of ``kind`` in ``folder`` that a new run replaces; None for a folder
    that is missing or empty. A :class:`SpecError` (``name`` names the folder in it) if the
    folder is not empty and ``force`` is not given (a kind without a ``force`` option always
    replaces its own run), or if anything there is not what the run's manifest lists,
    unchanged: another file, a symbolic link, an edited file (an ``index.csv`` edited to name
    ``notes.txt`` is one)."""
    folder = Path(folder)
    name = name or str(folder)
    try:
        if not os.path.lexists(folder):
            return None
        if not folder.is_dir():
            raise SpecError(message("{folder} is a file, not a folder", folder=name))
        entries = sorted(os.listdir(folder))
        if not entries:
            return None
        if kind.force and not force:
            raise SpecError(plural(
                "{folder} is not empty ({count} entry): choose an empty folder, or give "
                "{option} to replace an earlier {command} run there",
                "{folder} is not empty ({count} entries): choose an empty folder, or give "
                "{option} to replace an earlier {command} run there", count=len(entries),
                folder=name, option=kind.force, command=kind.command))
        files = _read_manifest(folder, kind, name)
        foreign, linked, changed = _survey(folder, files)
    except OSError as error:
        raise SpecError(message("cannot read the folder: {reason}",
                                reason=error.strerror or str(error)), file=str(folder)) from None
    if foreign or linked or changed:
        raise SpecError(_not_a_run(name, kind, foreign, linked, changed))
    return EarlierRun(tuple(entries), files)


def _not_a_run(name: str, kind: RunKind, foreign: list[str], linked: list[str],
               changed: list[str]) -> Message:
    """Why a folder holds more than an earlier run: files it did not write, symbolic links,
    or its files changed since."""
    if foreign:
        return message("{folder} holds files no {command} run wrote ({names}): {replacer} "
                       "replaces only an earlier run; move them away or choose another folder",
                       folder=name, command=kind.command, names=_listed(foreign),
                       replacer=kind.replacer)
    if linked:
        return message("{folder} holds symbolic links ({names}), which {command} never "
                       "writes: {replacer} replaces only an earlier run; choose another folder",
                       folder=name, names=_listed(linked), command=kind.command,
                       replacer=kind.replacer)
    if len(changed) == 1:
        return message("{folder}: {names} changed since {command} wrote it (size or SHA-256 "
                       "differs from {manifest}): {replacer} replaces only what {command} "
                       "wrote; move it away or choose another folder", folder=name,
                       names=changed, command=kind.command, manifest=MANIFEST,
                       replacer=kind.replacer)
    return message("{folder}: {names} changed since {command} wrote them (size or SHA-256 "
                   "differs from {manifest}): {replacer} replaces only what {command} wrote; "
                   "move them away or choose another folder", folder=name,
                   names=_listed(changed), command=kind.command, manifest=MANIFEST,
                   replacer=kind.replacer)


def remove_retired(retired: Path, earlier: EarlierRun | None) -> list[str]:
    """Remove an earlier run moved aside into ``retired``: each file its manifest lists, if
    still unchanged, then the manifest and the emptied folders. Returns what is left there
    (changed since the check), which stays."""
    files = earlier.files if earlier is not None else {}
    for name, (size, digest) in files.items():
        path = retired / name
        if _unchanged(path, size, digest):
            os.unlink(path)
    manifest = retired / MANIFEST
    if os.path.lexists(manifest) and not os.path.islink(manifest) and manifest.is_file():
        os.unlink(manifest)
    folders = {"/".join(parts[:end]) for parts in (name.split("/") for name in files)
               for end in range(1, len(parts))}
    for name in sorted(folders, key=lambda folder: -folder.count("/")):   # deepest first
        with contextlib.suppress(OSError):
            os.rmdir(retired / name)
    left = sorted(os.listdir(retired))
    if not left:
        os.rmdir(retired)
    return left


def write_run(folder: str | Path, kind: RunKind, files: Mapping[str, bytes],
              earlier: EarlierRun | None, *, modes: Mapping[str, int] | None = None
              ) -> str | None:
    """Write ``files`` (relative path → bytes; ``modes``: some files' permission bits) and
    their manifest as the run in ``folder``, whole or not at all, in place of ``earlier``
    (found by :func:`earlier_run` before the run's work); then remove the earlier run's
    files. Returns a note (text in the language spoken now, for the command to print) when
    something of the earlier run changed meanwhile and was kept (where it is), else None."""
    folder = Path(folder)
    data = {**files, MANIFEST: manifest_text(kind, files).encode("utf-8")}
    with output_set() as outputs:   # the whole run, beside the earlier one, then swapped in
        outputs.folder(folder, data, replaces=earlier.entries if earlier else (), modes=modes)
    retired = outputs.retired.get(folder)
    left = remove_retired(retired, earlier) if retired is not None else []
    if not left:
        return None
    return render(message("{folder} keeps what changed in the earlier run during this one "
                          "({names})", folder=str(retired), names=_listed(left)))
