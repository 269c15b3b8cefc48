"""Export a class: the keys of a run as an LMS import (Gradescope, PrairieLearn, Moodle, a
CSV gradebook; :mod:`planmethod.grading.exports`), and a whole teaching run — a template,
its variants and the LMS packages — written into one new folder (the studio's export).

A folder an export writes — a PrairieLearn question ``OUT/SLUG/``, a Gradescope autograder
``OUT/`` — is a run folder (:mod:`planmethod.runs`) with a ``manifest.json``: a later export
into it replaces it whole (no file of the earlier run is left, say a task figure of a student
the new keys no longer have), and only when everything there is what that manifest lists,
unchanged; a folder holding anything else is refused, never emptied. A single file (Moodle's
quiz, a CSV gradebook, Gradescope's ``results.json``) is replaced whole, as every output is.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from ..errors import SpecError
from ..runs import RunKind
from ..words import Message, message
from .tasks import Watch

__all__ = ["EXECUTABLES", "FORMATS", "LMS_FORMATS", "RUNS", "ExportRequest",
           "TeachingRunRequest", "export_files", "run_folder", "teaching_run_files",
           "write_export", "write_teaching_run"]

#: the files of a Gradescope autograder that must be executable
EXECUTABLES = ("run_autograder", "setup.sh", "grade_submission.py")

#: the largest task sheet (task.svg) a Moodle quiz embeds, bytes
MAX_SHEET_BYTES = 2_000_000

#: the formats of ``planmethod export``
FORMATS = ("gradescope", "prairielearn", "moodle", "csv")

#: the LMS packages a teaching run holds
LMS_FORMATS = ("moodle", "prairielearn", "gradescope")


def _prairielearn_file(name: str) -> bool:
    """Whether ``name`` is a file of a PrairieLearn question folder an export writes."""
    from ..grading.exports import PRAIRIELEARN_FIGURES, PRAIRIELEARN_FILES

    parts = name.split("/")
    return (name in PRAIRIELEARN_FILES
            or (len(parts) == 2 and parts[0] == PRAIRIELEARN_FIGURES
                and parts[1].endswith(".svg") and parts[1] not in ("", ".svg")))


def _gradescope_file(name: str) -> bool:
    """Whether ``name`` is a file of a Gradescope autograder folder an export writes."""
    from ..grading.exports import GRADESCOPE_FILES

    return name in GRADESCOPE_FILES


#: the run folders export writes, by format (their manifests' tags, the files they may
#: list): a PrairieLearn question ``OUT/SLUG/``, a Gradescope autograder ``OUT/``
RUNS = {"prairielearn": RunKind("export --format prairielearn",
                                "planmethod-prairielearn-manifest", _prairielearn_file,
                                force=None),
        "gradescope": RunKind("export --format gradescope", "planmethod-gradescope-manifest",
                              _gradescope_file, force=None)}


@dataclass(frozen=True)
class ExportRequest:
    """An export of the keys ``key`` (a bundle, its folder, a key or an exercise file) as
    ``format`` into ``out``; ``answers`` graded for a gradebook or a student's Gradescope
    results (of ``student``); what students see of each question (``feedback``); the
    PrairieLearn question's folder name (``slug``)."""

    key: str
    format: str
    out: str
    answers: str | None = None
    student: str | None = None
    feedback: str = "hints"
    slug: str = "planmethod"


def run_folder(request: ExportRequest) -> tuple[Path, RunKind] | None:
    """(the folder, its :class:`~planmethod.runs.RunKind`) of an export that writes a run
    folder, else None (a single file). The files of a PrairieLearn export are named with
    the slug in front (``SLUG/info.json``): its run folder is ``OUT/SLUG``."""
    from ..io import path_component

    if request.format == "prairielearn":
        path_component(request.slug, "--slug")  # before any work: it becomes a folder name
        return Path(request.out) / request.slug, RUNS["prairielearn"]
    if request.format == "gradescope" and not request.answers:
        return Path(request.out), RUNS["gradescope"]
    return None


def _task_sheets(key_path: str, keys: list) -> dict[str, str]:
    """Each student's task sheet (SVG text) that variants wrote beside the keys, by student,
    for those that are there."""
    import os

    from ..io import read_text_bounded, student_folder

    sheets = {}
    folder = Path(key_path) if Path(key_path).is_dir() else Path(key_path).parent
    for key in keys:
        sheet = folder / student_folder(str(key.get("student"))) / "task.svg"
        if os.path.lexists(sheet):
            sheets[str(key.get("student"))] = read_text_bounded(sheet, MAX_SHEET_BYTES)
    return sheets


def _gradescope_results(request: ExportRequest, keys: Mapping) -> str:
    """One student's Gradescope ``results.json`` of the graded ``answers``."""
    from ..errors import about
    from ..grading import exports
    from ..grading.answers import grade_many, read_answers

    with about(request.answers):   # an error here is about the answers, not the key
        rows = read_answers(request.answers)
        if request.student is not None:
            rows = [(request.student, a) for _, a in rows]
        if len(rows) != 1:
            raise SpecError(message("results.json is for one student; the answers hold "
                                    "{count}", count=len(rows)), file=request.answers)
        result = grade_many(keys, rows)[0]
    return json.dumps(exports.gradescope_results(result, feedback=request.feedback),
                      ensure_ascii=False, indent=1)


def export_files(request: ExportRequest) -> dict[str, str]:
    """Every file of the export, computed (nothing is written): by its path inside ``out``
    (``""`` for an export that is one file)."""
    from ..errors import about
    from ..grading import exports
    from ..grading.answers import grade_many, read_answers
    from ..grading.keys import bundle
    from .grades import load_any_key

    keys = load_any_key(request.key)
    unique = list({id(k): k for k in keys.values()}.values())
    the_bundle = bundle(unique, source=str(request.key))
    if request.format == "csv":
        if not request.answers:
            raise SpecError(message("--format csv needs --answers (the gradebook scores "
                                    "them)"))
        with about(request.answers):   # an error here is about the answers, not the key
            return {"": exports.gradebook_csv(grade_many(keys, read_answers(request.answers)))}
    if request.format == "gradescope":
        if request.answers:
            return {"results.json": _gradescope_results(request, keys)}
        return dict(exports.gradescope_autograder(the_bundle, feedback=request.feedback))
    if request.format == "prairielearn":
        return dict(exports.prairielearn_questions(the_bundle, slug=request.slug))
    return {"": exports.moodle_xml(unique, sheets=_task_sheets(request.key, unique))}


def write_export(request: ExportRequest, files: Mapping[str, str], earlier
                 ) -> tuple[list[str], Message | str | None]:
    """Write the export's ``files``: a run folder whole, in place of the ``earlier`` export
    there (:func:`planmethod.runs.earlier_run` of :func:`run_folder`), or its files as one
    set. The paths written, and a note if a file of the earlier export changed meanwhile and
    stays in a hidden folder."""
    from ..io import output_set
    from ..runs import write_run

    found = run_folder(request)
    if found is not None:   # the run folder, whole, in place of an earlier export
        folder, kind = found
        prefix = f"{request.slug}/" if request.format == "prairielearn" else ""
        inside = {name.removeprefix(prefix): text.encode("utf-8")
                  for name, text in files.items()}
        note = write_run(folder, kind, inside, earlier,
                         modes={name: 0o755 for name in EXECUTABLES if name in inside})
        return [str(folder / name) for name in inside], note or None
    with output_set() as outputs:   # every file or none
        if "" in files:  # one output file
            return [str(outputs.text(request.out, files[""]))], None
        # results.json inside the output folder
        return [str(path) for path in outputs.files(request.out, files)], None


# -- a whole teaching run (the studio's export) -------------------------------------------------
@dataclass(frozen=True)
class TeachingRunRequest:
    """A teaching run: the template's TOML, ``count`` variants drawn with ``seed``, and the
    LMS packages of ``formats`` (of :data:`LMS_FORMATS`)."""

    template: str
    count: int
    seed: int = 0
    formats: tuple[str, ...] = LMS_FORMATS


def _run_files(folder: str, files: Mapping[str, str], kind: RunKind, *, in_slug: bool
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


def _packages(files: Mapping[str, str], group, formats: tuple[str, ...],
              seed: int) -> dict[str, str]:
    """The LMS packages of a teaching run's variants (``files``, as a run of variants
    writes them, for the students of ``group``)."""
    from ..grading import exports
    from ..grading.keys import bundle

    keys = json.loads(files["keys.json"])["keys"]
    the_bundle = bundle(keys, source="template.toml", seed=seed, count=len(keys))
    written: dict[str, str] = {}
    if "moodle" in formats:
        sheets = {student: files[f"{folder}/task.svg"]
                  for student, folder in zip(group.students, group.folders, strict=True)}
        written["moodle/quiz.xml"] = exports.moodle_xml(keys, sheets=sheets)
    if "prairielearn" in formats:
        written |= _run_files("prairielearn", exports.prairielearn_questions(the_bundle),
                              RUNS["prairielearn"], in_slug=True)
    if "gradescope" in formats:
        written |= _run_files("gradescope", exports.gradescope_autograder(the_bundle),
                              RUNS["gradescope"], in_slug=False)
    return written


def teaching_run_files(request: TeachingRunRequest, students, *,
                       watch: Watch | None = None) -> tuple[dict[str, str], int]:
    """Every file of a teaching run, computed: ``template.toml``, the variants of
    ``students`` (:class:`~planmethod.application.variants.Class`) in ``variants/`` as
    ``planmethod variants`` writes them (with the manifest a later ``variants --force``
    checks) and the LMS packages asked for (``moodle/quiz.xml``, ``prairielearn/``,
    ``gradescope/``); and how many draws were rejected. ``watch`` hears each variant
    drawn, then the ``packages``."""
    from ..grading.templates import parse_template
    from .variants import MANIFEST, VariantsRequest, draw_variants, manifest_text

    watch = watch or Watch()
    template = parse_template(request.template, file="template.toml")
    drawn = draw_variants(VariantsRequest(template, students, seed=request.seed,
                                          source="template.toml"), watch=watch)
    watch.step("packages", request.count, request.count)
    written: dict[str, str] = {"template.toml": request.template}
    written |= {f"variants/{name}": data for name, data in drawn.files.items()}
    written[f"variants/{MANIFEST}"] = manifest_text(
        {name: data.encode("utf-8") for name, data in drawn.files.items()})
    written |= _packages(drawn.files, students, request.formats, request.seed)
    return written, len(drawn.rejected)


def write_teaching_run(folder: Path, files: Mapping[str, str]) -> int:
    """Write a teaching run's files into ``folder`` (an empty one), its Gradescope
    autograder's scripts executable; how many files were written."""
    from ..io import write_files

    paths = write_files(folder, files)
    for name in EXECUTABLES:
        if f"gradescope/{name}" in files:
            (folder / "gradescope" / name).chmod(0o755)
    return len(paths)
