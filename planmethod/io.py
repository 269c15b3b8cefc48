"""Files written whole or not at all, only where the user said, never damaging what they
replace; files read only when they are regular files, and only up to a limit.

Writing. Every file planmethod writes belongs to an :class:`OutputSet` (a command's outputs,
written together): each file is first *staged* — written in full to a temporary file — and
only when every file of the set is staged is the set *committed*: missing folders are created
and the temporary files renamed into place. An error, Ctrl-C or SIGTERM before that removes
every staged file and leaves no folder behind; a rename that fails during the commit undoes
the renames before it. What the target is decides how it is written (:class:`WriteMode`):

- a regular file, or nothing yet: the temporary file is renamed onto it (through a symbolic
  link, onto the file the link names: the link stays);
- the command's own standard output or error (``/dev/stdout``, ``/proc/self/fd/1``, or the file
  the output is redirected to): written into that stream;
- a character device (``/dev/null``, a terminal) or a FIFO: written in place, without rename,
  as shell redirection does — it stays a device or a FIFO. A FIFO that nothing reads is refused
  at once rather than waited for; ``/dev/full`` gives its one-line "No space left on device";
- a folder, a socket or a block device (a disk): refused with one line.

Names that come from user input and become part of a path (a PrairieLearn slug, a student's
folder) pass :func:`path_component`, and files written into an output folder go through
:meth:`OutputSet.files`, which refuses a relative path that would leave that folder, by name
or through a symbolic link.

Reading. :func:`read_bytes_bounded` and :func:`read_text_bounded` read every input file: a
FIFO, a device (``/dev/zero``, ``/dev/urandom``), a socket or a folder is refused with one line
before it is opened for reading, and at most ``limit + 1`` bytes are read.

Examples
--------
>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> with output_set() as outputs:
...     _ = outputs.text(folder / "a.txt", "hello")
...     _ = outputs.text(folder / "new" / "b.txt", "world")
>>> read_text_bounded(folder / "new" / "b.txt", limit=100)
'world'
>>> path_component("../../x", "--slug")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
planmethod.errors.SpecError: --slug: '../../x' is not a single folder or file name (...)
"""

from __future__ import annotations

import contextlib
import csv
import enum
import errno
import hashlib
import io
import json
import os
import re
import secrets
import shutil
import stat
import sys
import tempfile
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

from .errors import PlanmethodError, SpecError
from .words.message import Message, message, plural

__all__ = [
    "NAME_MAX",
    "OutputSet",
    "WriteMode",
    "atomic_path",
    "csv_text",
    "output_set",
    "path_component",
    "read_bytes_bounded",
    "read_text_bounded",
    "sha256_of_file",
    "spreadsheet_cell",
    "spreadsheet_text",
    "student_folder",
    "write_bytes_atomic",
    "write_files",
    "write_text_atomic",
]

#: the longest file or folder name (bytes) the common file systems take
NAME_MAX = 255

#: characters that would make a name more than one path component (or an invalid one)
_SEPARATORS = ("/", "\\", "\0")


def path_component(name: str, what: str | Message) -> str:
    """``name`` if it is one path component, else a :class:`SpecError` naming ``what`` (the
    option or key it came from): not empty, no ``/``, ``\\`` or NUL, not ``.`` or ``..``, at
    most :data:`NAME_MAX` bytes.

    Examples
    --------
    >>> path_component("fourbar-2026", "--slug")
    'fourbar-2026'
    >>> path_component("x" * 300, "--slug")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: --slug: 'xxxxxxxxxxxxxxxxxxxxxxxx'… is 300 bytes long; ...
    """
    if (not isinstance(name, str) or not name.strip() or name in (".", "..")
            or any(separator in name for separator in _SEPARATORS)):
        raise SpecError(message("{name!r} is not a single folder or file name (it must not be "
                                "empty, contain '/' or '\\', or be '.' or '..')", name=name),
                        key=what)
    length = len(os.fsencode(name))
    if length > NAME_MAX:
        raise SpecError(plural("{name!r}… is {count} byte long; a file or folder name has at "
                               "most {limit}", "{name!r}… is {count} bytes long; a file or "
                               "folder name has at most {limit}", count=length, name=name[:24],
                               limit=NAME_MAX), key=what)
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
    return path_component(name or "student", message("student id"))


def _inside(folder: Path, relative: str) -> Path:
    """``folder / relative`` where every part of ``relative`` is one path component."""
    parts = PurePosixPath(relative).parts
    if not parts or PurePosixPath(relative).is_absolute():
        raise SpecError(message("{path!r} is not a path inside the output folder",
                                path=relative), file=str(folder))
    for part in parts:
        path_component(part, message("output file {path!r}", path=relative))
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


class WriteMode(enum.Enum):
    """How a target is written, by what it is (see the module notes)."""

    #: a regular file or nothing yet: a temporary file renamed onto it
    RENAME = "rename"
    #: a character device or a FIFO: opened and written, as shell redirection does
    IN_PLACE = "in place"
    #: the command's own standard output or error: written into that stream
    STREAM = "stream"


#: what a file that is neither a regular file nor a folder is, by its ``stat`` test
_SPECIAL_KINDS = ((stat.S_ISCHR, message("a character device")),
                  (stat.S_ISFIFO, message("a FIFO")),
                  (stat.S_ISBLK, message("a block device (a disk)")),
                  (stat.S_ISSOCK, message("a socket")))
#: what any other file that is not a regular file is
_NOT_REGULAR = message("not a regular file")
#: what a folder given as a file is
_A_FOLDER = message("is a folder, not a file")
#: what a file given as a folder is
_A_FILE = message("is a file, not a folder")

#: the chunk in which staged content is copied into a device or a FIFO, and files are read
_CHUNK = 1 << 20


def _special_kind(mode: int) -> Message:
    """The words for a file that is not a regular file ("a FIFO", "a character device"…)."""
    return next((words for test, words in _SPECIAL_KINDS if test(mode)), _NOT_REGULAR)


def _cannot_write(error: OSError, target: str | Path) -> PlanmethodError:
    return PlanmethodError(message("cannot write the file: {reason}",
                                   reason=error.strerror or str(error)), file=str(target))


def _standard_stream(status: os.stat_result) -> int | None:
    """1 or 2 when ``status`` is the file of the command's standard output or error."""
    for descriptor in (1, 2):
        try:
            other = os.fstat(descriptor)
        except OSError:
            continue
        if (other.st_dev, other.st_ino) == (status.st_dev, status.st_ino):
            return descriptor
    return None


def _status(path: Path, target: Path) -> os.stat_result | None:
    """What ``path`` is (links followed), None if nothing is there yet."""
    try:
        return os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        return None
    except OSError as error:
        raise _cannot_write(error, target) from None


def _umask() -> int:
    """The process's umask (what an ordinary new file or folder is created without)."""
    umask = os.umask(0)
    os.umask(umask)
    return umask


def _existing_folders(folder: Path, target: Path) -> tuple[Path, list[Path]]:
    """The nearest of ``folder`` and its ancestors that exists, and the missing folders
    below it, top first; a :class:`PlanmethodError` if the one that exists is not a folder."""
    missing: list[Path] = []
    current = folder
    while True:
        try:
            status = os.stat(current)
        except (FileNotFoundError, NotADirectoryError):
            if current.parent == current:
                raise PlanmethodError(message("the folder {folder} does not exist",
                                              folder=str(current)), file=str(target)) from None
            missing.append(current)
            current = current.parent
            continue
        except OSError as error:
            raise _cannot_write(error, target) from None
        if not stat.S_ISDIR(status.st_mode):
            raise PlanmethodError(message("{folder} is a file, not a folder",
                                          folder=str(current)), file=str(target))
        for name in [path.name for path in missing]:
            if len(os.fsencode(name)) > NAME_MAX:
                raise PlanmethodError(message("the folder name {name!r}… is longer than "
                                              "{limit} bytes", name=name[:24], limit=NAME_MAX),
                                      file=str(target))
        return current, missing[::-1]


@dataclass(frozen=True)
class _Staged:
    """One file of a set: where the user asked (``target``), what is written (``final``: the
    file a link names, or the device), and the temporary file holding its content."""

    target: Path
    final: Path
    temporary: Path
    mode: WriteMode
    folders: tuple[Path, ...] = ()
    descriptor: int | None = None


@dataclass(frozen=True)
class _StagedFolder:
    """A folder whose entries ``replaces`` (of an earlier run) are swapped for the staged
    folder's entries; ``inside`` when the staged folder is in ``final`` (it exists)."""

    target: Path
    final: Path
    staged: Path
    replaces: tuple[str, ...]
    inside: bool
    folders: tuple[Path, ...] = ()


@dataclass
class _Commit:
    """What a commit has done so far, to be undone in reverse order if it fails."""

    folders: list[Path] = field(default_factory=list)
    renames: list[tuple[Path, Path]] = field(default_factory=list)   # (from, to)
    backups: list[tuple[Path, Path | None]] = field(default_factory=list)  # (file, its copy)

    def undo(self) -> None:
        for final, backup in reversed(self.backups):
            with contextlib.suppress(OSError):
                if backup is None:
                    os.unlink(final)
                else:
                    os.replace(backup, final)
        for source, destination in reversed(self.renames):
            with contextlib.suppress(OSError):
                os.rename(destination, source)
        for folder in reversed(self.folders):
            with contextlib.suppress(OSError):
                os.rmdir(folder)

    def forget_backups(self) -> None:
        for _, backup in self.backups:
            if backup is not None:
                with contextlib.suppress(OSError):
                    os.unlink(backup)


def _hidden_name(folder: Path, name: str, tag: str) -> Path:
    """A name in ``folder`` that nothing has yet: ``.NAME.TAG-XXXXXXXX``."""
    while True:
        candidate = folder / f".{name[:40]}.{tag}-{secrets.token_hex(4)}"
        if not os.path.lexists(candidate):
            return candidate


class OutputSet:
    """Files written together: each staged in full, then all committed, or none.

    Use :func:`output_set` (``with output_set() as outputs: …``): the set is committed when
    the block ends without an error, and discarded (every staged file removed, no folder
    created) when it raises. A target that exists and is a device or a FIFO is written in place
    at the commit, before any rename, so that a device that refuses (``/dev/full``) leaves the
    set's files as they were; writing a device cannot be undone, so a set with two devices may
    have written the first when the second fails.
    """

    def __init__(self) -> None:
        self._files: list[_Staged] = []
        self._folders: list[_StagedFolder] = []
        self._seen: dict[object, Path] = {}
        self._umask = _umask()
        #: each replaced folder target → the hidden folder its earlier entries were moved to
        #: by the commit (the caller removes what it knows it wrote there)
        self.retired: dict[Path, Path] = {}

    def _once(self, key: object, target: Path) -> None:
        if key in self._seen:
            raise PlanmethodError(message("is given twice as an output (also as {other})",
                                          other=str(self._seen[key])), file=str(target))
        self._seen[key] = target

    def _stage(self, target: str | Path, suffix: str | None = None, *,
               mode: int | None = None, devices: bool = True) -> Path:
        """A temporary path to write ``target``'s content into; ``mode`` sets the file's
        permission bits (default: those of the file it replaces, or an ordinary new file's).
        With ``devices`` False a target that is a device or a FIFO is refused like a socket:
        only a regular file (or nothing yet) is written."""
        target = Path(target)
        suffix = (target.suffix if suffix is None else suffix)[:16]
        status = _status(target, target)
        if status is not None and stat.S_ISDIR(status.st_mode):
            raise PlanmethodError(_A_FOLDER, file=str(target))
        if status is not None and not devices and not stat.S_ISREG(status.st_mode):
            raise PlanmethodError(message("is {kind}, not a regular file: it is never replaced, "
                                          "and only a regular file is written here",
                                          kind=_special_kind(status.st_mode)), file=str(target))
        descriptor = None if status is None or not devices else _standard_stream(status)
        if status is not None and (descriptor is not None
                                   or not stat.S_ISREG(status.st_mode)):
            how = WriteMode.STREAM if descriptor is not None else WriteMode.IN_PLACE
            if how is WriteMode.IN_PLACE and not (stat.S_ISCHR(status.st_mode)
                                                  or stat.S_ISFIFO(status.st_mode)):
                raise PlanmethodError(message("is {kind}: planmethod writes only files, "
                                              "character devices and FIFOs",
                                              kind=_special_kind(status.st_mode)),
                                      file=str(target))
            self._once((status.st_dev, status.st_ino), target)
            try:
                handle, name = tempfile.mkstemp(prefix=".planmethod-", suffix=suffix)
            except OSError as error:
                raise _cannot_write(error, target) from None
            os.close(handle)
            self._files.append(_Staged(target, target, Path(name), how,
                                       descriptor=descriptor))
            return Path(name)
        final = Path(os.path.realpath(target)) if os.path.islink(target) else target
        if len(os.fsencode(final.name)) > NAME_MAX:
            raise PlanmethodError(message("the file name is longer than {limit} bytes",
                                          limit=NAME_MAX), file=str(target))
        self._once(os.path.abspath(final), target)
        folder, missing = _existing_folders(final.parent, target)
        try:
            handle, name = tempfile.mkstemp(prefix=f".{final.name[:40]}.", suffix=suffix,
                                            dir=folder)
        except OSError as error:
            raise PlanmethodError(message("cannot create a file in {folder}: {reason}",
                                          folder=str(folder), reason=error.strerror),
                                  file=str(target)) from None
        temporary = Path(name)
        self._files.append(_Staged(target, final, temporary, WriteMode.RENAME, tuple(missing)))
        os.close(handle)
        if mode is None:
            mode = (stat.S_IMODE(status.st_mode) & 0o777 if status is not None
                    else 0o666 & ~self._umask)   # not mkstemp's 0600
        with contextlib.suppress(OSError):   # a file system without modes keeps 0600
            os.chmod(temporary, mode)
        return temporary

    @contextlib.contextmanager
    def writing(self, target: str | Path, suffix: str | None = None, *,
                mode: int | None = None) -> Iterator[Path]:
        """``with outputs.writing(target) as temporary:`` a temporary path to write
        ``target``'s content into, for writers that take a path (matplotlib, Pillow, ffmpeg,
        a CSV streamed row by row); ``mode`` sets the file's permission bits (default: those
        of the file it replaces, or an ordinary new file's).

        A write that fails in the block (a full disk, a file too large) names ``target``, not
        the command's input nor the temporary file: the error is about this output.

        >>> import errno, tempfile, pathlib
        >>> target = pathlib.Path(tempfile.mkdtemp()) / "table.csv"
        >>> with output_set() as outputs, outputs.writing(target) as temporary:
        ...     raise OSError(errno.ENOSPC, "No space left on device")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planmethod.errors.PlanmethodError: .../table.csv: cannot write the file: No space left...
        """
        temporary = self._stage(target, suffix, mode=mode)
        try:
            yield temporary
        except OSError as error:
            raise _cannot_write(error, target) from None
        except PlanmethodError as error:
            if error.file == str(temporary):   # a writer that stages its own file into this one
                error.file = None
                raise error.located(file=str(target)) from None
            raise

    def binary(self, target: str | Path, data: bytes, *, mode: int | None = None,
               devices: bool = True) -> Path:
        """Stage ``data`` as the content of ``target``; returns ``target``. With ``devices``
        False, a target that is a device or a FIFO is refused (see :meth:`_stage`)."""
        temporary = self._stage(target, mode=mode, devices=devices)
        try:
            temporary.write_bytes(data)
        except OSError as error:
            raise _cannot_write(error, target) from None
        return Path(target)

    def text(self, target: str | Path, text: str, *, mode: int | None = None,
             devices: bool = True) -> Path:
        """Stage ``text`` (UTF-8) as the content of ``target``; returns ``target``."""
        return self.binary(target, text.encode("utf-8"), mode=mode, devices=devices)

    def files(self, folder: str | Path, files: Mapping[str, str | bytes], *,
              modes: Mapping[str, int] | None = None) -> list[Path]:
        """Stage ``files`` (relative path → text or bytes) in ``folder``; every path is
        checked to stay inside ``folder`` (by name and through symbolic links) before anything
        is staged. ``modes`` gives some files their permission bits (``0o755``)."""
        folder = Path(folder)
        targets = {name: _inside(folder, name) for name in files}
        base = os.path.realpath(folder)
        for name, target in targets.items():
            if os.path.commonpath([base, os.path.realpath(target)]) != base:
                raise SpecError(message("{name!r} leads out of the output folder (through a "
                                        "symbolic link)", name=name), file=str(folder))
        for name, data in files.items():
            content = data if isinstance(data, bytes) else data.encode("utf-8")
            self.binary(targets[name], content, mode=(modes or {}).get(name))
        return list(targets.values())

    def folder(self, target: str | Path, files: Mapping[str, str | bytes], *,
               replaces: tuple[str, ...] = (), modes: Mapping[str, int] | None = None) -> Path:
        """Stage a whole folder: ``files`` (relative path → text or bytes) written into a
        private staging folder beside the entries of ``target``; at the commit the entries of
        ``target`` named in ``replaces`` (those of an earlier run) are moved to a hidden folder
        (:attr:`retired`) and the staged entries moved in. Any other entry of ``target`` is
        left alone, and one a staged entry would land on is an error before the commit.
        ``modes`` gives some files their permission bits (``0o755``)."""
        target = Path(target)
        final = Path(os.path.realpath(target)) if os.path.islink(target) else target
        for name in files:
            _inside(final, name)
        status = _status(final, target)
        if status is not None and not stat.S_ISDIR(status.st_mode):
            raise PlanmethodError(_A_FILE, file=str(target))
        if status is None:
            parent, missing = _existing_folders(final.parent, target)
            if len(os.fsencode(final.name)) > NAME_MAX:
                raise PlanmethodError(message("the folder name is longer than {limit} bytes",
                                              limit=NAME_MAX), file=str(target))
        else:
            parent, missing = final, []
            kept = {entry.name for entry in os.scandir(final)} - set(replaces)
            clash = sorted({PurePosixPath(name).parts[0] for name in files} & kept)
            if clash:
                raise PlanmethodError(message("holds {names}, which this run would replace and "
                                              "did not write", names=clash[:3]),
                                      file=str(target))
        self._once(os.path.abspath(final), target)
        try:
            staged = Path(tempfile.mkdtemp(prefix=f".{final.name[:40]}.new-", dir=parent))
        except OSError as error:
            raise PlanmethodError(message("cannot create a folder in {folder}: {reason}",
                                          folder=str(parent), reason=error.strerror),
                                  file=str(target)) from None
        self._folders.append(_StagedFolder(target, final, staged, tuple(replaces),
                                           status is not None, tuple(missing)))
        for name, data in files.items():
            path = staged.joinpath(*PurePosixPath(name).parts)
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_bytes(data if isinstance(data, bytes) else data.encode("utf-8"))
                if name in (modes or {}):
                    os.chmod(path, modes[name])
            except OSError as error:   # named as it will be: the file inside the folder
                raise _cannot_write(error, target / name) from None
        return final

    def discard(self) -> None:
        """Remove every staged file and folder (nothing is left of the set)."""
        for item in self._files:
            with contextlib.suppress(OSError):
                os.unlink(item.temporary)
        for folder in self._folders:
            shutil.rmtree(folder.staged, ignore_errors=True)
        self._files, self._folders = [], []

    def commit(self) -> None:
        """Write devices and FIFOs in place, create the missing folders, rename every staged
        file and folder into place; a failure undoes the renames and folders made so far."""
        for item in self._files:
            if item.mode is not WriteMode.RENAME:
                self._write_in_place(item)
        done = _Commit()
        current: Path = Path()   # the target being committed, for the error line
        try:
            for item in [*self._files, *self._folders]:
                current = item.target
                for folder in item.folders:
                    try:
                        os.mkdir(folder)
                    except FileExistsError:
                        if not folder.is_dir():
                            raise
                        continue
                    done.folders.append(folder)
            for item in self._files:
                current = item.target
                if item.mode is WriteMode.RENAME:
                    backup = None
                    if os.path.lexists(item.final):
                        backup = _hidden_name(item.final.parent, item.final.name, "old")
                        try:
                            os.link(item.final, backup)
                        except OSError:   # no hard links here: this file cannot be undone
                            backup = None
                    os.replace(item.temporary, item.final)
                    done.backups.append((item.final, backup))
            for folder in self._folders:
                current = folder.target
                self._swap(folder, done)
        except BaseException as error:
            done.undo()
            if isinstance(error, OSError):
                raise _cannot_write(error, current) from None
            raise
        done.forget_backups()
        for item in self._files:
            if item.mode is not WriteMode.RENAME:   # its content is copied: not needed now
                with contextlib.suppress(OSError):
                    os.unlink(item.temporary)
        for folder in self._folders:
            with contextlib.suppress(OSError):
                os.rmdir(folder.staged)
        self._files, self._folders = [], []

    def _swap(self, folder: _StagedFolder, done: _Commit) -> None:
        """Move a staged folder's entries into place (see :meth:`folder`)."""
        if not folder.inside:
            os.chmod(folder.staged, 0o777 & ~self._umask)   # not mkdtemp's 0700
            os.rename(folder.staged, folder.final)
            done.renames.append((folder.staged, folder.final))
            return
        moved = [name for name in folder.replaces if os.path.lexists(folder.final / name)]
        if moved:
            retired = _hidden_name(folder.final, folder.final.name, "old")
            os.mkdir(retired, 0o700)
            done.folders.append(retired)
            for name in moved:
                os.rename(folder.final / name, retired / name)
                done.renames.append((folder.final / name, retired / name))
            self.retired[folder.target] = retired
        for entry in sorted(os.listdir(folder.staged)):
            os.rename(folder.staged / entry, folder.final / entry)
            done.renames.append((folder.staged / entry, folder.final / entry))

    @staticmethod
    def _write_in_place(item: _Staged) -> None:
        """Copy a staged file into a character device, a FIFO or a standard stream."""
        for stream in (sys.stdout, sys.stderr, sys.__stdout__, sys.__stderr__):
            with contextlib.suppress(Exception):
                stream.flush()
        descriptor = item.descriptor
        if descriptor is None:
            fifo = stat.S_ISFIFO(os.stat(item.final).st_mode)
            flags = os.O_WRONLY | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0)
            try:   # a FIFO is opened without waiting: with no reader, ENXIO at once
                descriptor = os.open(item.final, flags | (os.O_NONBLOCK if fifo else 0))
            except OSError as error:
                if fifo and error.errno == errno.ENXIO:
                    raise PlanmethodError(message("is a FIFO that nothing reads: start its "
                                                  "reader first (planmethod does not wait "
                                                  "for one)"), file=str(item.target)) from None
                raise _cannot_write(error, item.target) from None
            if fifo:
                os.set_blocking(descriptor, True)
        try:
            with open(item.temporary, "rb") as source:
                while chunk := source.read(_CHUNK):
                    view = memoryview(chunk)
                    while view:
                        view = view[os.write(descriptor, view):]
        except OSError as error:
            raise _cannot_write(error, item.target) from None
        finally:
            if item.descriptor is None:
                os.close(descriptor)


@contextlib.contextmanager
def output_set() -> Iterator[OutputSet]:
    """``with output_set() as outputs:`` stage files with ``outputs.text(…)``,
    ``outputs.writing(…)``, ``outputs.files(…)``; they are committed together when the block
    ends, and none of them is written if it raises (see :class:`OutputSet`).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> (folder / "b.svg").mkdir()
    >>> with output_set() as outputs:  # doctest: +ELLIPSIS
    ...     _ = outputs.text(folder / "a.svg", "<svg/>")
    ...     _ = outputs.text(folder / "b.svg", "<svg/>")
    Traceback (most recent call last):
    ...
    planmethod.errors.PlanmethodError: .../b.svg: is a folder, not a file
    >>> sorted(path.name for path in folder.iterdir())
    ['b.svg']
    """
    outputs = OutputSet()
    try:
        yield outputs
        outputs.commit()
    except OSError as error:   # never the command's input: the outputs it was writing
        staged = {item.temporary: item.target for item in outputs._files}
        targets = dict.fromkeys(str(target) for target in
                                [*staged.values(), *(item.target for item in outputs._folders)])
        where = staged.get(Path(error.filename or ""), error.filename) or ", ".join(targets)
        raise _cannot_write(error, where) from None
    finally:
        outputs.discard()


def write_files(folder: str | Path, files: Mapping[str, str | bytes]) -> list[Path]:
    """Write ``files`` (relative path → text or bytes) into ``folder``, all or none; every
    path is checked to stay inside ``folder`` before anything is written."""
    with output_set() as outputs:
        return outputs.files(folder, files)


@contextlib.contextmanager
def atomic_path(target: str | Path, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path to write ``target`` into; it becomes ``target`` on success (a
    set of one file: see :class:`OutputSet`)."""
    with output_set() as outputs, outputs.writing(target, suffix) as temporary:
        yield temporary


def write_text_atomic(target: str | Path, text: str, *, devices: bool = True) -> None:
    """Write ``text`` (UTF-8) to ``target`` whole or not at all; with ``devices`` False a
    target that is a device or a FIFO is refused rather than written in place (the studio
    saves an exercise only as a regular file)."""
    with output_set() as outputs:
        outputs.text(target, text, devices=devices)


def write_bytes_atomic(target: str | Path, data: bytes) -> None:
    """Write ``data`` to ``target`` whole or not at all."""
    with output_set() as outputs:
        outputs.binary(target, data)


def read_bytes_bounded(path: str | Path, limit: int, *,
                       error: type[PlanmethodError] = SpecError) -> bytes:
    """The bytes of the regular file ``path``, at most ``limit`` of them.

    A folder, a FIFO, a device or a socket is refused before it is opened for reading (a FIFO
    would block, ``/dev/zero`` never ends); then at most ``limit + 1`` bytes are read, so a
    file that grows while it is read is refused too. Every refusal is an ``error`` (a
    :class:`SpecError` unless told) naming the file.

    Examples
    --------
    >>> read_bytes_bounded("/dev/zero", limit=10)
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: /dev/zero: is a character device, not a regular file
    """
    name = str(path)
    try:
        status = os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        raise error(message("no such file"), file=name) from None
    except OSError as failure:
        raise error(_cannot_read(failure), file=name) from None
    if stat.S_ISDIR(status.st_mode):
        raise error(_A_FOLDER, file=name)
    if not stat.S_ISREG(status.st_mode):
        raise error(message("is {kind}, not a regular file",
                            kind=_special_kind(status.st_mode)), file=name)
    if status.st_size > limit:
        raise error(plural("the file is {count} byte; at most {limit} are accepted",
                           "the file is {count} bytes; at most {limit} are accepted",
                           count=status.st_size, limit=limit), file=name)
    flags = (os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)
             | getattr(os, "O_CLOEXEC", 0))
    try:
        descriptor = os.open(path, flags)
    except OSError as failure:
        raise error(_cannot_read(failure), file=name) from None
    chunks, total = [], 0
    try:
        if not stat.S_ISREG(os.fstat(descriptor).st_mode):   # replaced since the stat
            raise error(message("is not a regular file"), file=name)
        while total <= limit:
            chunk = os.read(descriptor, min(_CHUNK, limit + 1 - total))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
    except OSError as failure:
        raise error(_cannot_read(failure), file=name) from None
    finally:
        os.close(descriptor)
    if total > limit:
        raise error(message("the file is more than {limit} bytes; at most {limit} are "
                            "accepted", limit=limit), file=name)
    return b"".join(chunks)


def read_text_bounded(path: str | Path, limit: int, *, encoding: str = "utf-8-sig",
                      error: type[PlanmethodError] = SpecError) -> str:
    """The text of the regular file ``path`` (UTF-8, a byte-order mark at its start dropped, as
    Windows' Notepad and Excel write one; or ``encoding``), at most ``limit`` bytes of it (see
    :func:`read_bytes_bounded`).

    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "big.csv"
    >>> _ = path.write_text("x" * 11)
    >>> read_text_bounded(path, limit=10)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: .../big.csv: the file is 11 bytes; at most 10 are accepted
    """
    data = read_bytes_bounded(path, limit, error=error)
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as failure:
        raise error(message("cannot read the file as UTF-8 text ({reason})",
                            reason=str(failure)), file=str(path)) from None


def _cannot_read(failure: OSError) -> Message:
    return message("cannot read the file ({reason})", reason=failure.strerror)


def sha256_of_file(path: str | Path) -> str | None:
    """The SHA-256 (hex) of the regular file ``path``, read in chunks; None if ``path`` is not
    a regular file, is a symbolic link, or cannot be read.

    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "a.txt"
    >>> _ = path.write_bytes(b"abc")
    >>> sha256_of_file(path)[:16], sha256_of_file("/dev/zero")
    ('ba7816bf8f01cfea', None)
    """
    flags = (os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0)
             | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0))
    try:
        descriptor = os.open(path, flags)
    except OSError:
        return None
    with open(descriptor, "rb") as handle:
        if not stat.S_ISREG(os.fstat(handle.fileno()).st_mode):
            return None
        try:
            return hashlib.file_digest(handle, "sha256").hexdigest()
        except OSError:
            return None


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
