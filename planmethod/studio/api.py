"""What the studio's page asks of the server, as functions of plain data.

Every function takes text and numbers (what a request carries) and returns a JSON-able dict; a
bad request is a :class:`~planmethod.errors.PlanmethodError` whose one-line message the server
sends back as ``{"error": …, "kind": …}`` (:func:`error_payload`). Files are read and written
only under the studio's folder (:class:`Workspace`), with the command line's rules: one path
component at a time, no ``..``, nothing through a link out of the folder, every file written
whole or not at all.

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

import errno
import json
import math
import os
import secrets
import shutil
import stat
import time
from collections.abc import Callable, Mapping
from pathlib import Path, PurePosixPath
from typing import Any

from ..errors import (
    AssemblyError,
    BranchJumpError,
    ConvergenceError,
    ForceError,
    PlanmethodError,
    SpecError,
    StructureError,
    ToggleError,
    value_text,
)
from ..io import path_component, read_text_bounded, write_files, write_text_atomic
from ..model import FRAME

__all__ = [
    "MAX_BODY",
    "Workspace",
    "commit_folder",
    "error_payload",
    "export",
    "make_template",
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
#: draws as many as ``planmethod variants`` (:data:`~planmethod.commands.variants.MAX_VARIANTS`)
MAX_PREVIEW = 40
#: the LMS packages "export" writes
FORMATS = ("moodle", "prairielearn", "gradescope")

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
    what = {OverflowError: "a number is too large to compute with",
            RecursionError: "the input is nested too deeply",
            MemoryError: "the input asks for more memory than there is"}
    return {"error": what.get(type(error), f"cannot do that: {error}").replace("\n", " "),
            "kind": "input"}


# -- files under the folder ----------------------------------------------------------------------
#: at most this many entries the listing passes over are named in its answer
MAX_SKIPPED = 50


def _why(error: BaseException) -> str:
    """A file-system condition in words: a link that loops (Python before 3.13 says so with
    a RuntimeError), permission denied, a name too long…"""
    if isinstance(error, RuntimeError) or getattr(error, "errno", None) == errno.ELOOP:
        return "a symbolic link that loops"
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
            raise SpecError(f"a {what} inside the studio's folder is needed", key=what)
        pure = PurePosixPath(relative.strip())
        if pure.is_absolute() or "\\" in relative:
            raise SpecError(f"{relative!r} is not a path inside the studio's folder", key=what)
        for part in pure.parts:
            path_component(part, what)
        target = self.root.joinpath(*pure.parts)
        try:
            inside = target.resolve().is_relative_to(self.root)
        except (OSError, RuntimeError) as error:   # a loop, a name too long, no permission
            raise SpecError(f"{relative!r} cannot be followed: {_why(error)}",
                            key=what) from None
        if not inside:
            raise SpecError(f"{relative!r} leads out of the studio's folder", key=what)
        if suffix is not None and target.suffix != suffix:
            raise SpecError(f"{relative!r} must end in {suffix}", key=what)
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

        def skip(path: Path, why: str) -> None:
            if len(skipped) < MAX_SKIPPED:
                skipped.append({"path": self.relative(path) if path != self.root else ".",
                                "why": why})

        def walk(folder: Path, depth: int) -> None:
            try:
                status = os.stat(folder)
                if (status.st_dev, status.st_ino) in seen:
                    return skip(folder, "a folder listed already (a link back to it)")
                seen.add((status.st_dev, status.st_ino))
                entries = sorted(os.scandir(folder), key=lambda entry: entry.name)
            except OSError as error:
                return skip(folder, f"the folder cannot be read: {_why(error)}")
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
                         else "a symbolic link to nothing")
                    continue
                if stat.S_ISDIR(mode):
                    if depth < MAX_DEPTH:
                        walk(path, depth + 1)
                elif entry.name.endswith(".toml"):
                    if stat.S_ISREG(mode):
                        found.append(self.relative(path))
                    else:
                        skip(path, "not a regular file")

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
            raise SpecError(f"cannot be written: {_why(error)}", file=str(relative)) from None
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
            raise SpecError(f"cannot be written: {_why(error)}", file=str(relative)) from None
        if taken:
            raise FileExistsError(self.relative(target))
        return target


# -- solving -------------------------------------------------------------------------------------
def _exercise(text: str, file: str | None = None):
    from ..spec import parse_exercise

    return parse_exercise(text, file=file)


def solve(text: str) -> dict[str, Any]:
    """An exercise's TOML → ``{"report": …, "svg": {"position", "velocity", "acceleration"},
    "symbols": …, "drive_symbols": …, "server_ms": …}``: the report of ``planmethod solve
    --json``, the plans as the command line draws them but without the enlarged details of
    crowded points (a live picture, redrawn at every step of a drag: the details would jump
    about below it; ``planmethod solve --svg`` draws them) as SVG for an HTML page (no XML
    declaration), each checked quantity's course symbol under the exercise's numbering
    (``omega_BC`` → ω₂) and the drive's ``phi``, ``omega`` and ``epsilon`` (φ₁, ω₁, ε₁)."""
    from ..numbering import course_numbers, course_symbols
    from ..render.svg import plan_svg, position_svg
    from ..render.workbook import inline_svg
    from ..report import analyse, report_dict
    from ..vocabulary import symbol

    start = time.perf_counter()
    analysis = analyse(_exercise(text))
    report = report_dict(analysis)
    svg = {}
    plans = analysis.plans
    if plans is not None:
        svg["position"] = inline_svg(position_svg(plans.position, plans=plans, details=False))
        svg["velocity"] = inline_svg(plan_svg(plans.velocity, details=False))
        if plans.acceleration is not None:
            svg["acceleration"] = inline_svg(plan_svg(plans.acceleration, details=False))
    numbers = course_numbers(analysis.exercise.mechanism)
    symbols = {check["quantity"]: symbol(check["quantity"], numbers)
               for check in report["checks"]}
    drive = course_symbols(analysis.exercise.mechanism)
    return {"report": report, "svg": svg, "symbols": symbols,
            "drive_symbols": {name: drive[name] for name in ("phi", "omega", "epsilon")},
            "server_ms": round(1000 * (time.perf_counter() - start), 2)}


def _drawn(text: str, file: str | None = None) -> dict[str, Any]:
    """The tables of an exercise file, written as drawn (converted if it is in link frames)."""
    from ..convert import drawn_tables, refuse_template
    from ..spec import is_drawn, parse_toml

    data = parse_toml(text, file=file)
    refuse_template(data, "is not edited in the studio, one exercise is", file=file)
    if is_drawn(data):
        _exercise(text, file)    # it must be a whole exercise
        return data
    return drawn_tables(data, file=file)


def open_exercise(workspace: Workspace, relative: Any) -> dict[str, Any]:
    """A file of the folder, written as drawn: ``{"path", "tables", "converted"}`` (the page
    edits the tables; ``converted`` says the file was in link frames)."""
    from ..spec import is_drawn, parse_toml

    text = workspace.read(relative)
    tables = _drawn(text, file=relative)
    return {"path": relative, "tables": tables,
            "converted": not is_drawn(parse_toml(text, file=relative))}


def save_exercise(workspace: Workspace, relative: Any, text: Any, *,
                  overwrite: bool = False) -> dict[str, Any]:
    """Write the page's as-drawn TOML to ``relative`` (a ``.toml`` file under the folder),
    whole or not at all, once it reads as an exercise. An existing file is replaced only with
    ``overwrite``."""
    if not isinstance(text, str):
        raise SpecError("the exercise must be TOML text", key="toml")
    workspace.path(relative, suffix=".toml")
    _exercise(text, file=relative)
    return {"saved": workspace.write(relative, text, overwrite=overwrite)}


def save_template(workspace: Workspace, relative: Any, text: Any, ranges: Any, *,
                  overwrite: bool = False) -> dict[str, Any]:
    """Write the template :func:`make_template` makes of the drawing and ``ranges`` to
    ``relative`` (a ``.toml`` file under the folder), for ``planmethod variants``."""
    if not isinstance(text, str):
        raise SpecError("the exercise must be TOML text", key="toml")
    workspace.path(relative, suffix=".toml")
    template = make_template(text, ranges or {})
    return {"saved": workspace.write(relative, template, overwrite=overwrite)}


def turn(text: str, angle: Any) -> dict[str, Any]:
    """The drawing turned to crank angle ``angle`` (deg): ``{"tables": …}``, every point where
    the mechanism, kept on the drawn assembly, puts it."""
    from ..convert import drawn_tables, frame_tables
    from ..spec import MAX_ANGLE_DEG, parse_toml

    angle = _number(angle, "angle", limit=MAX_ANGLE_DEG)
    return {"tables": drawn_tables(frame_tables(parse_toml(text)), angle=angle)}


def _number(value: Any, key: str, *, limit: float = 1e6, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise SpecError(f"must be a finite number, got {value_text(value)}", key=key)
    if abs(value) > limit or (positive and value <= 0):
        raise SpecError(f"must be {'positive and ' if positive else ''}at most {limit:g} in "
                        f"magnitude, got {value_text(value)}", key=key)
    return float(value)


def _whole(value: Any, key: str, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise SpecError(f"must be a whole number in {low}…{high}, got {value_text(value)}", key=key)
    return value


# -- variants ------------------------------------------------------------------------------------
def _range(value: Any, key: str, *, positive: bool = False) -> tuple[float, float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise SpecError(f"must be [low, high], got {value_text(value)}", key=key)
    low, high = (_number(v, key, positive=positive) for v in value)
    if low > high:
        raise SpecError(f"low {low:g} is above high {high:g}", key=key)
    return low, high


def make_template(text: str, ranges: Mapping[str, Any]) -> str:
    """A template (in link frames) made of the drawing: each link listed in
    ``ranges["lengths"]`` (``{"BC": [0.16, 0.20]}``, m) scaled to a length drawn from that
    range (its first two points' distance; the frame's: its farthest point from the crank's
    pivot), the crank angle from ``ranges["angle"]`` (``[from, to, step]``, deg) and ω1 from
    ``ranges["omega"]`` (``[low, high, step]``, rad/s), each drawn on its grid. The assembly is
    picked by the drawing's points (a ``[sketch]`` at the drawn angle).

    Examples
    --------
    >>> from planmethod.spec import read_text
    >>> text = read_text("exercises/compressor_slider_crank.toml")
    >>> template = make_template(text, {"lengths": {"BC": [0.16, 0.2]}, "angle": [30, 60, 5]})
    >>> "l_BC = { range = [0.16, 0.2], step = 0.001 }" in template
    True
    """
    from ..convert import frame_tables
    from ..grading.templates import to_toml
    from ..spec import exercise_from_dict

    if not isinstance(ranges, Mapping):
        raise SpecError("must be a table of ranges", key="ranges")
    frames = frame_tables(_drawn(text))
    mechanism = exercise_from_dict(frames).mechanism
    step = _number(ranges.get("step", 0.001), "ranges.step", positive=True)
    lengths = ranges.get("lengths") or {}
    if not isinstance(lengths, Mapping):
        raise SpecError("must be a table of link → [low, high]", key="ranges.lengths")
    variables: dict[str, Any] = {}
    scaled: dict[str, tuple[str, float, tuple[float, float]]] = {}
    for link, bounds in lengths.items():
        if link not in mechanism.links:
            raise SpecError(f"unknown link '{link}'", key=f"ranges.lengths.{link}")
        low, high = _range(bounds, f"ranges.lengths.{link}", positive=True)
        base, origin = _base_length(mechanism, link)
        if base <= 0:
            raise SpecError(f"'{link}' has no length to vary (one point)",
                            key=f"ranges.lengths.{link}")
        name = f"l_{link}"
        variables[name] = {"range": [low, high], "step": step}
        scaled[link] = (name, base, origin)
    tables: dict[str, Any] = {"title": None}
    tables["title"] = frames.get("title", "mechanism")
    words = [f"{link.replace('_', ' ')} = {{{name}:.3f}} m" for link, (name, _, _) in
             scaled.items()]
    drive = dict(frames["drive"])
    if ranges.get("angle") is not None:
        low, high, angle_step = _grid(ranges["angle"], "ranges.angle", limit=36000)
        variables["phi"] = {"range": [low, high], "step": angle_step}
        drive["angle"] = "= phi"
    if ranges.get("omega") is not None:
        low, high, omega_step = _grid(ranges["omega"], "ranges.omega", limit=1e4)
        variables["omega"] = {"range": [low, high], "step": omega_step}
        drive["omega"] = "= omega"
    angle_text = "{phi:g}" if "phi" in variables else f"{float(mechanism.drive.angle):g}"
    omega_text = "{omega:g}" if "omega" in variables else f"{mechanism.drive.omega:g}"
    tables["description"] = (       # the title by its placeholder: its text is never read
        "{title}. " + (f"Lengths: {', '.join(words)}. " if words else "")
        + f"The crank {drive['link']} turns about {drive['pivot']} at {{symbol.omega}} = "
        f"{omega_text} rad/s; at {{symbol.phi}} = {angle_text}° construct the plans and find "
        "the quantities asked.")     # the crank's symbols by its number (course_symbols)
    tables["vars"] = variables
    tables["template"] = {"max_attempts": 400}
    for key, value in frames.items():
        if key in ("title", "description"):
            continue
        if key == "drive":
            tables["drive"] = drive
        elif key == "links":
            tables["links"] = {link: {p: _scaled(xy, scaled.get(link)) for p, xy in points.items()}
                               for link, points in value.items()}
        elif key == "mass":
            tables["mass"] = {link: (dict(props, S=_scaled(props["S"], scaled.get(link)))
                                     if isinstance(props, Mapping) and "S" in props else props)
                              for link, props in value.items()}
        else:
            tables[key] = value
    return to_toml(tables)


def _base_length(mechanism, link: str) -> tuple[float, tuple[float, float]]:
    """(the length a range scales, the point it scales about): a moving link's first two
    points' distance (about its first point); the frame's farthest point from the crank's
    pivot (about the pivot)."""
    points = mechanism.links[link].points
    names = list(points)
    if link == FRAME:
        pivot = points[mechanism.drive.pivot]
        far = max((math.hypot(x - pivot[0], y - pivot[1]) for x, y in points.values()),
                  default=0.0)
        return far, pivot
    if len(names) < 2:
        return 0.0, (0.0, 0.0)
    (x1, y1), (x2, y2) = points[names[0]], points[names[1]]
    return math.hypot(x2 - x1, y2 - y1), points[names[0]]


def _scaled(xy, scaling) -> Any:
    """A point's coordinates as expressions scaling them about ``origin`` by ``name/base``."""
    if scaling is None:
        return xy
    name, base, origin = scaling
    out = []
    for value, centre in zip(xy, origin, strict=True):
        offset = float(value) - float(centre)
        if offset == 0:
            out.append(float(value))
        else:
            prefix = f"{float(centre)!r} + " if centre else ""
            out.append(f"= {prefix}{offset!r} * {name} / {base!r}")
    return out


def _grid(value: Any, key: str, *, limit: float) -> tuple[float, float, float]:
    if not isinstance(value, list | tuple) or len(value) != 3:
        raise SpecError(f"must be [from, to, step], got {value_text(value)}", key=key)
    low, high = _range(list(value[:2]), key)
    step = _number(value[2], key, positive=True)
    if max(abs(low), abs(high)) > limit:
        raise SpecError(f"must be within ±{limit:g}", key=key)
    if (high - low) / step > 1e6:
        raise SpecError(f"gives more than a million values (step {step:g})", key=key)
    return low, high, step


def _students(count: int) -> list[str]:
    width = max(2, len(str(count)))
    return [str(number).zfill(width) for number in range(1, count + 1)]


#: what a job tells of its progress: (the phase, steps done, steps in all)
Progress = Callable[[str, int, int], None]


def _seed(seed: Any) -> int:
    """A seed as the command line takes it: a whole number within 64 bits."""
    from ..spec import MAX_INTEGER

    return _whole(seed, "seed", -MAX_INTEGER, MAX_INTEGER)


def prepare_variants(text: str, ranges: Mapping[str, Any], *, count: Any = 6,
                     seed: Any = 0) -> dict[str, Any]:
    """Check a preview of variants before it starts (the count, at most :data:`MAX_PREVIEW`;
    the random seed of the draw; the template :func:`make_template` makes of the drawing and
    ``ranges``): the arguments of :func:`run_variants`, plain data that a job's process
    receives."""
    from ..grading.templates import parse_template

    count = _whole(count, "count", 1, MAX_PREVIEW)
    seed = _seed(seed)
    template_text = make_template(text, ranges)
    parse_template(template_text, file="template.toml")
    return {"text": text, "template": template_text, "count": count, "seed": seed}


def run_variants(arguments: Mapping[str, Any],
                 on_progress: Progress | None = None) -> dict[str, Any]:
    """Draw the variants :func:`prepare_variants` checked, and their task sheets:
    ``{"template": TOML, "variants": [{"student", "values", "attempt", "sheet", "note"}],
    "rejected": [reasons]}``. ``note`` says when a variant is assembled otherwise than drawn
    (a group on its other branch); ``on_progress("variants", done, total)`` after each."""
    from ..commands.variants import rejection_summary
    from ..grading.keys import build_key
    from ..grading.sheets import task_sheet_svg
    from ..grading.templates import draw_variant, parse_template
    from ..kinematics import choose_branches
    from ..plans import draw_plans
    from ..render.workbook import inline_svg
    from ..words import render

    template = parse_template(arguments["template"], file="template.toml")
    drawn = choose_branches(_exercise(arguments["text"]).mechanism)
    students = _students(arguments["count"])
    out, rejected = [], []
    for student in students:
        variant = draw_variant(template, seed=arguments["seed"], student=student)
        rejected += [render(reason) for reason in variant.rejected]
        key = build_key(variant)
        sheet = task_sheet_svg(key, draw_plans(variant.exercise, acceleration=False))
        branches = choose_branches(variant.exercise.mechanism)
        other = [index + 1 for index, branch in branches.items()
                 if index in drawn and branch.sign != drawn[index].sign]
        note = (f"assembled otherwise than drawn (group {', '.join(map(str, other))} on its "
                "other branch): narrow the crank angle's range" if other else "")
        out.append({"student": student, "values": dict(variant.values),
                    "attempt": variant.attempt, "sheet": inline_svg(sheet), "note": note})
        if on_progress is not None:
            on_progress("variants", len(out), len(students))
    return {"template": arguments["template"], "variants": out,
            "rejected": rejection_summary(rejected)}


def variants(text: str, ranges: Mapping[str, Any], *, count: Any = 6,
             seed: Any = 0) -> dict[str, Any]:
    """Draw ``count`` variants of the template :func:`make_template` makes, and their task
    sheets, here and now (the studio runs :func:`prepare_variants` in the request and
    :func:`run_variants` as a job)."""
    return run_variants(prepare_variants(text, ranges, count=count, seed=seed))


def prepare_export(workspace: Workspace, text: str, ranges: Mapping[str, Any], *, folder: Any,
                   formats: Any = FORMATS, count: Any = 30, seed: Any = 0) -> dict[str, Any]:
    """Check an export before it starts: the count as ``planmethod variants`` allows it
    (:data:`~planmethod.commands.variants.MAX_VARIANTS`), the random seed of the draw, the
    packages, the folder (under the studio's, new or empty: a :class:`FileExistsError`
    otherwise) and the template. The arguments of :func:`run_export`, plain data that a job's
    process receives."""
    from ..commands.variants import MAX_VARIANTS
    from ..grading.templates import parse_template

    if not isinstance(count, int) or isinstance(count, bool) or not 1 <= count <= MAX_VARIANTS:
        raise SpecError(f"must be a whole number in 1…{MAX_VARIANTS}, got {count!r} (as "
                        f"planmethod variants: a run of {MAX_VARIANTS} takes about a minute)",
                        key="count")
    seed = _seed(seed)
    if (not isinstance(formats, list | tuple)
            or any(name not in FORMATS for name in formats)):
        raise SpecError(f"must be a list of {', '.join(FORMATS)}", key="formats")
    target = workspace.new_folder(folder)
    template_text = make_template(text, ranges)
    parse_template(template_text, file="template.toml")
    return {"template": template_text, "count": count, "seed": seed, "formats": list(formats),
            "folder": workspace.relative(target), "target": str(target)}


def run_export(arguments: Mapping[str, Any], staging: Path,
               on_progress: Progress | None = None) -> dict[str, Any]:
    """Write the teaching run :func:`prepare_export` checked into ``staging`` (an empty folder,
    renamed into place by :func:`commit_folder` when it is whole): ``template.toml``, the
    variants (``variants/``: as ``planmethod variants`` writes them, with the manifest a later
    ``variants --force`` checks) and the LMS packages asked for (``moodle/quiz.xml``,
    ``prairielearn/``, ``gradescope/``). ``on_progress(phase, done, total)`` tells each
    variant drawn, then the ``packages`` and the ``writing``."""
    from ..commands.export import EXECUTABLES, RUNS
    from ..commands.variants import MANIFEST, manifest_text, variant_files
    from ..grading import exports
    from ..grading.keys import bundle
    from ..grading.templates import parse_template
    from ..io import student_folder

    count, seed, formats = arguments["count"], arguments["seed"], arguments["formats"]
    template = parse_template(arguments["template"], file="template.toml")
    students = _students(count)
    folders = [student_folder(student) for student in students]
    told = (None if on_progress is None else
            lambda done, total: on_progress("variants", done, total))
    files, rejected, _ = variant_files(template, students, folders, seed=seed,
                                       source="template.toml", progress=False, on_advance=told)
    if on_progress is not None:
        on_progress("packages", count, count)
    written: dict[str, str] = {"template.toml": arguments["template"]}
    written |= {f"variants/{name}": data for name, data in files.items()}
    written[f"variants/{MANIFEST}"] = manifest_text(
        {name: data.encode("utf-8") for name, data in files.items()})
    keys = json.loads(files["keys.json"])["keys"]
    the_bundle = bundle(keys, source="template.toml", seed=seed, count=len(keys))
    if "moodle" in formats:
        sheets = {student: files[f"{name}/task.svg"] for student, name in zip(students, folders,
                                                                             strict=True)}
        written["moodle/quiz.xml"] = exports.moodle_xml(keys, sheets=sheets)
    if "prairielearn" in formats:
        written |= _run_files("prairielearn", exports.prairielearn_questions(the_bundle),
                              RUNS["prairielearn"], in_slug=True)
    if "gradescope" in formats:
        written |= _run_files("gradescope", exports.gradescope_autograder(the_bundle),
                              RUNS["gradescope"], in_slug=False)
    if on_progress is not None:
        on_progress("writing", count, count)
    paths = write_files(staging, written)
    for name in EXECUTABLES:
        if f"gradescope/{name}" in written:
            (staging / "gradescope" / name).chmod(0o755)
    return {"written": len(paths), "variants": count, "rejected": len(rejected)}


def _run_files(folder: str, files: Mapping[str, str], kind, *, in_slug: bool
               ) -> dict[str, str]:
    """An LMS package's files under ``folder``, with the manifest that ``planmethod export``
    writes beside them (in the question's folder ``SLUG/`` for PrairieLearn, in the
    autograder's folder for Gradescope), so that a later ``export`` into it replaces the run
    whole instead of refusing a folder it did not write."""
    from ..runs import MANIFEST, manifest_text

    runs: dict[str, dict[str, bytes]] = {}
    for name, data in files.items():
        run, _, inside = name.partition("/") if in_slug else ("", "", name)
        runs.setdefault(run, {})[inside] = data.encode("utf-8")
    written = {f"{folder}/{name}": data for name, data in files.items()}
    for run, content in runs.items():
        prefix = f"{folder}/{run}/" if run else f"{folder}/"
        written[prefix + MANIFEST] = manifest_text(kind, content)
    return written


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
            raise SpecError(f"cannot create a folder beside it ({error.strerror})",
                            key="folder") from None


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
