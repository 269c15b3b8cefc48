"""What the studio's page asks of the server, as functions of plain data.

Every function takes text and numbers (what a request carries) and returns a JSON-able dict; a
bad request is a :class:`~planmethod.errors.PlanmethodError` whose one-line message the server
sends back as ``{"error": …, "kind": …}`` (:func:`error_payload`). Files are read and written
only under the studio's folder (:class:`Workspace`), with the command line's rules: one path
component at a time, no ``..``, nothing through a link out of the folder, every file written
whole or not at all. The work itself — a template made of the drawing, variants, a teaching
run — is the application layer's (:mod:`planmethod.application`), as the command line's is;
the words of an answer are in the language spoken (the server chooses it per request).

Examples
--------
>>> from planmethod.spec import read_text
>>> answer = solve(read_text("exercises/compressor_slider_crank.toml"))
>>> sorted(answer["svg"]), answer["report"]["links"]["BC"]["omega"] < 0
(['acceleration', 'position', 'velocity'], True)
>>> error_payload(SpecError("must be a finite number, got nan", key="drive.omega"))
{'error': 'drive.omega: must be a finite number, got nan', 'kind': 'input'}
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import shutil
import stat
import time
from collections.abc import Callable, Mapping
from dataclasses import replace
from pathlib import Path, PurePosixPath
from typing import Any

from ..application.exporting import LMS_FORMATS
from ..application.templating import as_drawn, checked_number, checked_whole, exercise_of
from ..errors import (
    LIMIT_WORDS,
    AssemblyError,
    BranchJumpError,
    ConvergenceError,
    ForceError,
    PlanmethodError,
    SpecError,
    StructureError,
    ToggleError,
    limit_words,
)
from ..io import path_component, read_text_bounded, write_text_atomic
from ..words import Message, message, render

__all__ = [
    "MAX_BODY",
    "Workspace",
    "commit_folder",
    "error_payload",
    "export",
    "open_exercise",
    "prepare_export",
    "prepare_variants",
    "run_export",
    "run_variants",
    "save_exercise",
    "save_template",
    "solve",
    "stage_folder",
    "turn",
    "variants",
]

#: the largest request body, or file the studio opens (bytes)
MAX_BODY = 1_000_000
#: at most this many files are listed, this deep in the folder
MAX_LISTED, MAX_DEPTH = 500, 4
#: at most this many variants are previewed (the page shows each one's task sheet); an export
#: draws as many as ``planmethod variants``
#: (:data:`~planmethod.application.variants.MAX_VARIANTS`)
MAX_PREVIEW = 40
#: the LMS packages "export" writes
FORMATS = LMS_FORMATS

#: what went wrong, in the course's words (the page shows it above the one-line message)
KINDS = {StructureError: "structure", AssemblyError: "assembly", ConvergenceError: "assembly",
         BranchJumpError: "assembly", ToggleError: "toggle", ForceError: "forces",
         SpecError: "input"}


def error_payload(error: BaseException) -> dict[str, str]:
    """The JSON body of a refused request: the error's one line and its kind (``structure``:
    W ≠ 1 or no Assur groups; ``assembly``: it cannot be assembled; ``toggle``; ``forces``;
    ``input``: the file itself)."""
    if isinstance(error, PlanmethodError):
        kind = next((name for cls, name in KINDS.items() if isinstance(error, cls)), "input")
        return {"error": str(error).replace("\n", " "), "kind": kind}
    what = (limit_words(error) if isinstance(error, tuple(LIMIT_WORDS))
            else message("cannot do that: {error}", error=str(error)))
    return {"error": render(what).replace("\n", " "), "kind": "input"}


#: the things a path names, in the words of the line that refuses one
_WHAT = {"path": message("path"), "folder": message("folder")}


# -- files under the folder ----------------------------------------------------------------------
#: at most this many entries the listing passes over are named in its answer
MAX_SKIPPED = 50


def _why(error: BaseException) -> Message | str:
    """A file-system condition in words: a link that loops (Python before 3.13 says so with
    a RuntimeError), permission denied, a name too long… (the system's words, as it says
    them)."""
    if isinstance(error, RuntimeError) or getattr(error, "errno", None) == errno.ELOOP:
        return message("a symbolic link that loops")
    return (getattr(error, "strerror", None) or str(error)).lower()


class Workspace:
    """The folder the studio was started in: every path the page names is relative to it and
    must stay inside it (each part one path component, no ``..``, no link leading out).

    A condition of the file system — a link that loops, permission denied, a name too long, a
    file where a folder is expected, a device or a FIFO where an exercise is — is a
    :class:`SpecError` of one line naming the path as the page gave it (a 400), never an
    internal error; the listing passes over what it cannot read, and says so
    (:meth:`listing`). Exercises are written by the command line's writer, whole or not at
    all, and only as regular files (``write_text_atomic(…, devices=False)``).
    """

    def __init__(self, root: str | Path) -> None:
        self.root = Path(root).resolve()

    def path(self, relative: Any, *, suffix: str | None = None, what: str = "path") -> Path:
        """The file or folder ``relative`` names inside the folder, or a :class:`SpecError`."""
        if not isinstance(relative, str) or not relative.strip():
            raise SpecError(message("a {what} inside the studio's folder is needed",
                                    what=_WHAT.get(what, what)), key=what)
        pure = PurePosixPath(relative.strip())
        if pure.is_absolute() or "\\" in relative:
            raise SpecError(message("{path!r} is not a path inside the studio's folder",
                                    path=relative), key=what)
        for part in pure.parts:
            path_component(part, what)
        target = self.root.joinpath(*pure.parts)
        try:
            inside = target.resolve().is_relative_to(self.root)
        except (OSError, RuntimeError) as error:   # a loop, a name too long, no permission
            raise SpecError(message("{path!r} cannot be followed: {why}", path=relative,
                                    why=_why(error)), key=what) from None
        if not inside:
            raise SpecError(message("{path!r} leads out of the studio's folder",
                                    path=relative), key=what)
        if suffix is not None and target.suffix != suffix:
            raise SpecError(message("{path!r} must end in {suffix}", path=relative,
                                    suffix=suffix), key=what)
        return target

    def relative(self, path: Path) -> str:
        return path.relative_to(self.root).as_posix()

    def _here(self, error: PlanmethodError, relative: Any) -> SpecError:
        """``error`` of the command line's reader or writer, naming the path as the page gave
        it (never the folder's absolute path)."""
        root = f"{self.root}{os.sep}"
        shown = str(PlanmethodError(error.message))   # its words alone, as they are shown
        return SpecError(shown.replace(root, "") if root in shown else error.message,
                         file=str(relative).strip(), key=error.key)

    def files(self) -> list[str]:
        """The exercise files (``*.toml``) under the folder (see :meth:`listing`)."""
        return self.listing()["files"]

    def listing(self) -> dict[str, list]:
        """``{"files": [...], "skipped": [{"path", "why"}, ...]}``: the exercise files
        (``*.toml``, regular files) under the folder, at most :data:`MAX_LISTED`, at most
        :data:`MAX_DEPTH` folders deep, hidden entries and links out of the folder left out;
        and what was passed over because the file system would not say what it is (a link
        that loops or leads to nothing, a folder that cannot be read, a folder reached again
        through a link), at most :data:`MAX_SKIPPED` of them."""
        found: list[str] = []
        skipped: list[dict[str, str]] = []
        seen: set[tuple[int, int]] = set()

        def skip(path: Path, why: Message | str) -> None:
            if len(skipped) < MAX_SKIPPED:
                skipped.append({"path": self.relative(path) if path != self.root else ".",
                                "why": render(why)})

        def walk(folder: Path, depth: int) -> None:
            try:
                status = os.stat(folder)
                if (status.st_dev, status.st_ino) in seen:
                    return skip(folder, message("a folder listed already (a link back to "
                                                "it)"))
                seen.add((status.st_dev, status.st_ino))
                entries = sorted(os.scandir(folder), key=lambda entry: entry.name)
            except OSError as error:
                return skip(folder, message("the folder cannot be read: {why}",
                                            why=_why(error)))
            for entry in entries:
                if len(found) >= MAX_LISTED or entry.name.startswith("."):
                    continue
                path = Path(entry.path)
                try:
                    if entry.is_symlink() and not path.resolve(strict=True).is_relative_to(
                            self.root):
                        continue
                    mode = os.stat(path).st_mode
                except (OSError, RuntimeError) as error:
                    skip(path, _why(error) if not isinstance(error, FileNotFoundError)
                         else message("a symbolic link to nothing"))
                    continue
                if stat.S_ISDIR(mode):
                    if depth < MAX_DEPTH:
                        walk(path, depth + 1)
                elif entry.name.endswith(".toml"):
                    if stat.S_ISREG(mode):
                        found.append(self.relative(path))
                    else:
                        skip(path, message("not a regular file"))

        walk(self.root, 0)
        return {"files": found, "skipped": skipped}

    def read(self, relative: Any) -> str:
        """The text of the exercise file ``relative`` (``.toml``), read as the command line
        reads its inputs: a regular file of at most :data:`MAX_BODY` bytes, UTF-8."""
        path = self.path(relative, suffix=".toml", what="path")
        try:
            return read_text_bounded(path, MAX_BODY)
        except PlanmethodError as error:
            raise self._here(error, relative) from None

    def write(self, relative: Any, text: str, *, overwrite: bool = False) -> str:
        """Write ``text`` to the exercise file ``relative`` (``.toml``), whole or not at all,
        as a regular file (a device or a FIFO there is refused, never written into); an
        existing file only with ``overwrite`` (else a :class:`FileExistsError`). Returns the
        path written, relative to the folder."""
        path = self.path(relative, suffix=".toml")
        try:
            exists = os.path.lexists(path)
        except OSError as error:
            raise SpecError(message("cannot be written: {why}", why=_why(error)),
                            file=str(relative)) from None
        if exists and not overwrite:
            raise FileExistsError(relative)
        try:
            write_text_atomic(path, text, devices=False)
        except PlanmethodError as error:
            raise self._here(error, relative) from None
        return self.relative(path)

    def new_folder(self, relative: Any) -> Path:
        """The folder ``relative`` names, missing or empty (else a :class:`FileExistsError`),
        for a run written whole into it."""
        target = self.path(relative, what="folder")
        try:
            taken = os.path.lexists(target) and (not target.is_dir()
                                                 or any(target.iterdir()))
        except OSError as error:
            raise SpecError(message("cannot be written: {why}", why=_why(error)),
                            file=str(relative)) from None
        if taken:
            raise FileExistsError(self.relative(target))
        return target


# -- solving -------------------------------------------------------------------------------------
def solve(text: str, *, draft: bool = False) -> dict[str, Any]:
    """An exercise's TOML → ``{"report": …, "svg": {"position", "velocity", "acceleration"},
    "symbols": …, "ask_symbols": …, "drive_symbols": …, "server_ms": …}``: the report of
    ``planmethod solve
    --json``, the plans as the command line draws them but without the enlarged details of
    crowded points (a live picture, redrawn at every step of a drag: the details would jump
    about below it; ``planmethod solve --svg`` draws them) as SVG for an HTML page (no XML
    declaration), each checked quantity's course symbol under the exercise's numbering
    (``omega_BC`` → ω₂), the symbol of every quantity that could be asked (the page's labels of
    *What is asked*) and the drive's ``phi``, ``omega`` and ``epsilon`` (φ₁, ω₁, ε₁).

    A ``draft`` is a drag's intermediate step, shown for a moment: its labels are placed
    quickly (:func:`~planmethod.render.labels.drafted`) and, where everything is asked, the
    forces (which the page does not show) are left out; the page asks for the full answer when
    the drag rests, the same bytes as ever."""
    from ..numbering import course_numbers, course_symbols
    from ..render.labels import drafted
    from ..render.svg import plan_svg, position_svg
    from ..render.workbook import inline_svg
    from ..report import analyse, report_dict
    from ..vocabulary import symbol

    start = time.perf_counter()
    exercise = exercise_of(text)
    if draft and exercise.ask.everything:   # the same scene without the forces
        exercise = replace(exercise, ask=replace(exercise.ask, forces=False))
    analysis = analyse(exercise)
    report = report_dict(analysis)
    svg = {}
    plans = analysis.plans
    with drafted() if draft else contextlib.nullcontext():
        if plans is not None:
            svg["position"] = inline_svg(position_svg(plans.position, plans=plans,
                                                      details=False))
            svg["velocity"] = inline_svg(plan_svg(plans.velocity, details=False))
            if plans.acceleration is not None:
                svg["acceleration"] = inline_svg(plan_svg(plans.acceleration, details=False))
    numbers = course_numbers(analysis.exercise.mechanism)
    symbols = {check["quantity"]: symbol(check["quantity"], numbers)
               for check in report["checks"]}
    mechanism = analysis.exercise.mechanism
    drive = course_symbols(mechanism)
    askable = [f"{kind}_{point}" for link in mechanism.links.values() for point in link.points
               for kind in ("v", "a", "rho")]
    askable += [f"{kind}_{link}" for link in mechanism.links for kind in ("omega", "epsilon")]
    return {"report": report, "svg": svg, "symbols": symbols,
            "ask_symbols": {quantity: symbol(quantity, numbers) for quantity in askable},
            "drive_symbols": {name: drive[name] for name in ("phi", "omega", "epsilon")},
            "server_ms": round(1000 * (time.perf_counter() - start), 2)}


def open_exercise(workspace: Workspace, relative: Any) -> dict[str, Any]:
    """A file of the folder, written as drawn: ``{"path", "tables", "converted"}`` (the page
    edits the tables; ``converted`` says the file was in link frames)."""
    from ..spec import is_drawn, parse_toml

    text = workspace.read(relative)
    tables = as_drawn(text, file=relative)
    return {"path": relative, "tables": tables,
            "converted": not is_drawn(parse_toml(text, file=relative))}


def save_exercise(workspace: Workspace, relative: Any, text: Any, *,
                  overwrite: bool = False) -> dict[str, Any]:
    """Write the page's as-drawn TOML to ``relative`` (a ``.toml`` file under the folder),
    whole or not at all, once it reads as an exercise. An existing file is replaced only with
    ``overwrite``."""
    if not isinstance(text, str):
        raise SpecError(message("the exercise must be {format} text", format="TOML"),
                        key="toml")
    workspace.path(relative, suffix=".toml")
    exercise_of(text, file=relative)
    return {"saved": workspace.write(relative, text, overwrite=overwrite)}


def save_template(workspace: Workspace, relative: Any, text: Any, ranges: Any, *,
                  overwrite: bool = False) -> dict[str, Any]:
    """Write the template :func:`~planmethod.application.templating.make_template` makes of
    the drawing and ``ranges`` to ``relative`` (a ``.toml`` file under the folder), for
    ``planmethod variants``."""
    from ..application.templating import make_template

    if not isinstance(text, str):
        raise SpecError(message("the exercise must be {format} text", format="TOML"),
                        key="toml")
    workspace.path(relative, suffix=".toml")
    template = make_template(text, ranges or {})
    return {"saved": workspace.write(relative, template, overwrite=overwrite)}


def turn(text: str, angle: Any) -> dict[str, Any]:
    """The drawing turned to crank angle ``angle`` (deg): ``{"tables": …}``, every point where
    the mechanism, kept on the drawn assembly, puts it."""
    from ..convert import drawn_tables, frame_tables
    from ..spec import MAX_ANGLE_DEG, parse_toml

    angle = checked_number(angle, "angle", limit=MAX_ANGLE_DEG)
    return {"tables": drawn_tables(frame_tables(parse_toml(text)), angle=angle)}


# -- variants ------------------------------------------------------------------------------------
#: what a job tells of its progress: (the phase, steps done, steps in all)
Progress = Callable[[str, int, int], None]


def _seed(seed: Any) -> int:
    """A seed as the command line takes it: a whole number within 64 bits."""
    from ..spec import MAX_INTEGER

    return checked_whole(seed, "seed", -MAX_INTEGER, MAX_INTEGER)


def _students(count: int):
    """The students of a studio's run: ``01`` … (two digits at least)."""
    from ..application.variants import class_of

    return class_of(count, width=2)


def _template(text: str, ranges: Mapping[str, Any], file: str | None = None) -> str:
    """The template made of the drawing and ``ranges``, checked as a template (a problem
    named in ``file``, the file an export writes it to; a preview's is in no file)."""
    from ..application.templating import make_template
    from ..grading.templates import parse_template

    template_text = make_template(text, ranges)
    parse_template(template_text, file=file)
    return template_text


def prepare_variants(text: str, ranges: Mapping[str, Any], *, count: Any = 6,
                     seed: Any = 0) -> dict[str, Any]:
    """Check a preview of variants before it starts (the count, at most :data:`MAX_PREVIEW`;
    the random seed of the draw; the template
    :func:`~planmethod.application.templating.make_template` makes of the drawing and
    ``ranges``): the arguments of :func:`run_variants`, plain data that a job's process
    receives."""
    count = checked_whole(count, "count", 1, MAX_PREVIEW)
    seed = _seed(seed)
    return {"text": text, "template": _template(text, ranges), "count": count, "seed": seed}


def _drawn_otherwise(variant, drawn) -> Message | str:
    """Why a variant is assembled otherwise than drawn (a group on its other branch), or
    ``""``."""
    from ..kinematics import choose_branches

    branches = choose_branches(variant.exercise.mechanism)
    other = [index + 1 for index, branch in branches.items()
             if index in drawn and branch.sign != drawn[index].sign]
    return (message("assembled otherwise than drawn (group {groups} on its other branch): "
                    "narrow the crank angle's range", groups=other) if other else "")


def run_variants(arguments: Mapping[str, Any],
                 on_progress: Progress | None = None) -> dict[str, Any]:
    """Draw the variants :func:`prepare_variants` checked, and their task sheets:
    ``{"template": TOML, "variants": [{"student", "values", "attempt", "sheet", "note"}],
    "rejected": [reasons]}``. ``note`` says when a variant is assembled otherwise than drawn
    (a group on its other branch); ``on_progress("variants", done, total)`` after each."""
    from ..grading.keys import build_key
    from ..grading.sheets import task_sheet_svg
    from ..grading.templates import draw_variant, parse_template, rejection_summary
    from ..kinematics import choose_branches
    from ..plans import draw_plans
    from ..render.workbook import inline_svg
    from ..words import render

    template = parse_template(arguments["template"])   # the preview's: in no file
    drawn = choose_branches(exercise_of(arguments["text"]).mechanism)
    students = _students(arguments["count"]).students
    out, rejected = [], []
    for student in students:
        variant = draw_variant(template, seed=arguments["seed"], student=student)
        rejected += [render(reason) for reason in variant.rejected]
        key = build_key(variant)
        sheet = task_sheet_svg(key, draw_plans(variant.exercise, acceleration=False))
        out.append({"student": student, "values": dict(variant.values),
                    "attempt": variant.attempt, "sheet": inline_svg(sheet),
                    "note": render(_drawn_otherwise(variant, drawn))})
        if on_progress is not None:
            on_progress("variants", len(out), len(students))
    return {"template": arguments["template"], "variants": out,
            "rejected": rejection_summary(rejected)}


def variants(text: str, ranges: Mapping[str, Any], *, count: Any = 6,
             seed: Any = 0) -> dict[str, Any]:
    """Draw ``count`` variants of the template made of the drawing, and their task sheets,
    here and now (the studio runs :func:`prepare_variants` in the request and
    :func:`run_variants` as a job)."""
    return run_variants(prepare_variants(text, ranges, count=count, seed=seed))


# -- export --------------------------------------------------------------------------------------
def prepare_export(workspace: Workspace, text: str, ranges: Mapping[str, Any], *, folder: Any,
                   formats: Any = FORMATS, count: Any = 30, seed: Any = 0) -> dict[str, Any]:
    """Check an export before it starts: the count as ``planmethod variants`` allows it
    (:data:`~planmethod.application.variants.MAX_VARIANTS`), the random seed of the draw,
    the packages, the folder (under the studio's, new or empty: a :class:`FileExistsError`
    otherwise) and the template. The arguments of :func:`run_export`, plain data that a
    job's process receives."""
    from ..application.variants import MAX_VARIANTS

    if not isinstance(count, int) or isinstance(count, bool) or not 1 <= count <= MAX_VARIANTS:
        raise SpecError(message("must be a whole number in 1…{limit}, got {count!r} (as "
                                "planmethod variants: a run of {limit} takes about a minute)",
                                limit=MAX_VARIANTS, count=count), key="count")
    seed = _seed(seed)
    if (not isinstance(formats, list | tuple)
            or any(name not in FORMATS for name in formats)):
        raise SpecError(message("must be a list of {formats}", formats=list(FORMATS)),
                        key="formats")
    target = workspace.new_folder(folder)
    return {"template": _template(text, ranges, "template.toml"), "count": count, "seed": seed,
            "formats": list(formats), "folder": workspace.relative(target),
            "target": str(target)}


def run_export(arguments: Mapping[str, Any], staging: Path,
               on_progress: Progress | None = None) -> dict[str, Any]:
    """Write the teaching run :func:`prepare_export` checked into ``staging`` (an empty folder,
    renamed into place by :func:`commit_folder` when it is whole): ``template.toml``, the
    variants (``variants/``: as ``planmethod variants`` writes them, with the manifest a later
    ``variants --force`` checks) and the LMS packages asked for (``moodle/quiz.xml``,
    ``prairielearn/``, ``gradescope/``;
    :func:`~planmethod.application.exporting.teaching_run_files`). ``on_progress(phase,
    done, total)`` tells each variant drawn, then the ``packages`` and the ``writing``."""
    from ..application.exporting import (
        TeachingRunRequest,
        teaching_run_files,
        write_teaching_run,
    )
    from ..application.tasks import Watch

    count = arguments["count"]
    request = TeachingRunRequest(arguments["template"], count, arguments["seed"],
                                 tuple(arguments["formats"]))
    files, rejected = teaching_run_files(request, _students(count),
                                         watch=Watch(on_progress))
    if on_progress is not None:
        on_progress("writing", count, count)
    return {"written": write_teaching_run(staging, files), "variants": count,
            "rejected": rejected}


def stage_folder(target: Path) -> Path:
    """A new hidden folder to write ``target``'s content into: beside it, or beside the
    nearest folder above it that exists (so that a cancelled run leaves no folder made for
    it); :func:`commit_folder` renames it into place."""
    parent = target.parent
    while not parent.is_dir():
        parent = parent.parent
    while True:
        staging = parent / f".{target.name[:40]}.export-{secrets.token_hex(4)}"
        try:
            staging.mkdir()   # an ordinary folder's mode, as the one it becomes
            return staging
        except FileExistsError:
            continue
        except OSError as error:
            raise SpecError(message("cannot create a folder beside it ({why})",
                                    why=error.strerror), key="folder") from None


def commit_folder(staging: Path, target: Path, relative: str) -> None:
    """Rename the whole ``staging`` folder onto ``target`` (named ``relative`` in messages),
    which must still be missing or empty: a :class:`FileExistsError` otherwise, and
    ``staging`` stays for the caller to remove."""
    if target.is_symlink() or (target.exists() and (not target.is_dir()
                                                    or any(target.iterdir()))):
        raise FileExistsError(relative)
    target.parent.mkdir(parents=True, exist_ok=True)
    if target.exists():
        target.rmdir()
    try:
        os.rename(staging, target)
    except OSError as error:
        if error.errno in (errno.EEXIST, errno.ENOTEMPTY):
            raise FileExistsError(relative) from None
        raise


def export(workspace: Workspace, text: str, ranges: Mapping[str, Any], *, folder: Any,
           formats: Any = FORMATS, count: Any = 30, seed: Any = 0) -> dict[str, Any]:
    """Write a whole teaching run into ``folder`` (new or empty, under the studio's folder)
    here and now, whole or not at all (the studio runs :func:`prepare_export` in the request,
    :func:`run_export` as a job and :func:`commit_folder` when it ends):
    ``{"folder", "written", "variants", "rejected"}``."""
    arguments = prepare_export(workspace, text, ranges, folder=folder, formats=formats,
                               count=count, seed=seed)
    target = Path(arguments["target"])
    staging = stage_folder(target)
    try:
        result = run_export(arguments, staging)
        commit_folder(staging, target, arguments["folder"])
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return {"folder": arguments["folder"], **result}
