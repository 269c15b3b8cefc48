"""Every command line and Python snippet of README.md and docs/**/*.md (the guides in other
languages too: docs/ru/) runs as the text shows it.

The documents are read by Sybil (a library for testing documentation); the convention, written
for authors in docs/contributing.md:

- a ```` ```console ```` block holds commands after ``$ `` (a line ending in ``\\`` continues
  the command); the lines up to the next ``$ `` are what it prints, stdout and stderr together
  as a terminal shows them (``...`` matches anything, runs of white space compare equal). A
  command shown without output is checked for its exit status only. The status must be 0 unless
  the command ends with the comment ``# exit status N``;
- a ```` ```python ```` block is run as code, or as a doctest when it starts with ``>>>``;
- a ```` ```toml ```` block must be valid TOML, and one with a ``[drive]`` table a valid
  exercise file (or, with ``[vars]`` or ``[template]``, a template a variant can be drawn from);
- ``% skip: next if(not has_ffmpeg, reason="…")`` (a MyST comment) before a block skips it, with the
  reason, when an optional tool is missing (``has_cairosvg``, ``has_ffmpeg``, ``has_chromium``);
  ``% skip: next "reason"`` always skips it (say why in the reason).

Each document runs in its own temporary copy of the repository, its blocks in order (a block
may use what an earlier one of the same document wrote), with the copy's ``planmethod`` first on
``PYTHONPATH``.
"""

from __future__ import annotations

import contextlib
import doctest
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from unittest import SkipTest

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCUMENTS = sorted([ROOT / "README.md", *(path for path in (ROOT / "docs").glob("**/*.md")
                                          if "_build" not in path.parts)])
COPY_IGNORED = shutil.ignore_patterns(".git", "_build", "__pycache__", ".hypothesis",
                                      ".pytest_cache", ".ruff_cache", "*.egg-info")
EXIT_STATUS = re.compile(r"#\s*exit status (\d+)\s*$")
OPTIONS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
COMMAND_TIMEOUT_S = 900

sybil = pytest.importorskip("sybil", reason="Sybil is not installed (pip install '.[test]')")
from sybil.parsers.myst import (  # noqa: E402 (after the skip)
    CodeBlockParser,
    PythonCodeBlockParser,
    SkipParser,
)


@dataclass(frozen=True)
class Command:
    """One ``$ `` command of a console block, what it should print and its exit status."""

    line: int
    text: str
    expected: str
    status: int


def console_commands(source: str, first_line: int = 1) -> list[Command]:
    r"""Split a console block into its commands.

    >>> [(c.text, c.expected, c.status)
    ...  for c in console_commands("$ echo a\n a\n$ false  # exit status 1\n")]
    [('echo a', ' a', 0), ('false  # exit status 1', '', 1)]
    """
    commands: list[Command] = []
    lines = source.splitlines()
    index = 0
    while index < len(lines):
        line = lines[index]
        if not line.startswith("$ "):
            if line.strip():
                raise ValueError(f"line {first_line + index}: output before any '$ ' command")
            index += 1
            continue
        start = index
        text = [line[2:]]
        while text[-1].endswith("\\") and index + 1 < len(lines):
            index += 1
            text.append(lines[index])
        index += 1
        output = []
        while index < len(lines) and not lines[index].startswith("$ "):
            output.append(lines[index])
            index += 1
        command = "\n".join(text)
        match = EXIT_STATUS.search(text[-1])
        commands.append(Command(first_line + start, command, "\n".join(output).strip("\n"),
                                int(match.group(1)) if match else 0))
    return commands


def output_matches(expected: str, got: str) -> bool:
    """Doctest's comparison: ``...`` matches anything, white space runs compare equal.

    >>> output_matches("v_C  5.27...  m/s", "v_C 5.27163 m/s")
    True
    """
    return doctest.OutputChecker().check_output(expected + "\n", got, OPTIONS)


def run_console(example) -> None:
    """Run the commands of a console block in the document's copy of the repository."""
    copy = example.namespace["repository"]
    environment = dict(os.environ)
    environment["PYTHONPATH"] = os.pathsep.join(
        [str(copy), *filter(None, [environment.get("PYTHONPATH")])])
    environment["PATH"] = os.pathsep.join([str(Path(sys.executable).parent),
                                           environment.get("PATH", "")])
    environment["COLUMNS"] = "100"
    for command in console_commands(example.parsed, example.line + 1):
        done = subprocess.run(["bash", "-c", command.text], cwd=copy, env=environment,
                              stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, timeout=COMMAND_TIMEOUT_S)
        where = f"{example.path}:{command.line}: $ {command.text}"
        if done.returncode != command.status:
            raise AssertionError(f"{where}\nexit status {done.returncode}, the text says "
                                 f"{command.status}; it printed:\n{done.stdout[-4000:]}")
        if command.expected and not output_matches(command.expected, done.stdout):
            raise AssertionError(f"{where}\nthe text shows:\n{command.expected}\n"
                                 f"it printed:\n{done.stdout[-4000:]}")


def check_toml(example) -> None:
    """A TOML block parses; one with a ``[drive]`` table is a valid exercise file, or, with
    ``[vars]`` or ``[template]``, a template that ``planmethod variants`` can draw from."""
    from planmethod.grading.templates import draw_variant, parse_template
    from planmethod.spec import parse_exercise, parse_toml

    where = f"{example.path}:{example.line}"
    data = parse_toml(str(example.parsed), file=where)
    if "drive" not in data:
        return
    if "vars" in data or "template" in data:
        draw_variant(parse_template(str(example.parsed), file=where), student="001")
    else:
        parse_exercise(str(example.parsed), file=where)


PARSER = sybil.Sybil(parsers=[
    CodeBlockParser("console", evaluator=run_console),
    CodeBlockParser("toml", evaluator=check_toml),
    PythonCodeBlockParser(doctest_optionflags=OPTIONS),
    SkipParser(),
])
PARSED = {path: PARSER.parse(path) for path in DOCUMENTS if path.exists()}
EXAMPLES = [(path, example) for path, document in PARSED.items() for example in document]


def _has_cairosvg() -> bool:
    try:
        import cairosvg  # noqa: F401
    except (ImportError, OSError):
        return False
    return True


@pytest.fixture(scope="session")
def repository_copies(tmp_path_factory):
    """One copy of the repository per document, made when its first example runs."""
    copies: dict[Path, Path] = {}

    def copy_for(path: Path) -> Path:
        if path not in copies:
            target = tmp_path_factory.mktemp(path.stem) / "planmethod"
            shutil.copytree(ROOT, target, ignore=COPY_IGNORED)
            copies[path] = target
        return copies[path]
    return copy_for


def test_every_document_has_examples():
    """The documents are found and each guide with commands yields examples (no silent 0)."""
    with_examples = {path.name for path, _ in EXAMPLES}
    assert {"tutorial.md", "teaching.md", "workbook.md", "languages.md",
            "quickstart.md"} <= with_examples, with_examples


@pytest.mark.parametrize(("path", "example"), EXAMPLES,
                         ids=[f"{path.relative_to(ROOT)}:{example.line}"
                              for path, example in EXAMPLES])
def test_example(path, example, repository_copies, monkeypatch):
    """Run one block of a document in the document's own copy of the repository, after the
    document's earlier blocks that this process has not run: a block may use what an earlier
    one wrote or defined, and a run spread over processes (``pytest -n``) may hand a process
    a document's later block first."""
    copy = repository_copies(path)
    namespace = example.namespace
    namespace.setdefault("repository", copy)
    namespace.setdefault("has_cairosvg", _has_cairosvg())
    namespace.setdefault("has_ffmpeg", shutil.which("ffmpeg") is not None)
    namespace.setdefault("has_chromium", shutil.which("chromium") is not None
                         or shutil.which("chromium-browser") is not None)
    monkeypatch.chdir(copy)
    evaluated = _EVALUATED.setdefault(path, set())
    for earlier in PARSED[path]:
        if earlier.start >= example.start:
            break
        if earlier.start not in evaluated:
            evaluated.add(earlier.start)
            with contextlib.suppress(SkipTest):
                earlier.evaluate()
    evaluated.add(example.start)
    example.evaluate()


#: the blocks evaluated in this process, by document (their offsets in it)
_EVALUATED: dict[Path, set[int]] = {}


#: README is the front door: what it is, the two set-up commands, three starts; guides go to docs/
README_LIMIT_BYTES = 15_000
#: a relative Markdown link's target, without its #anchor
_LINK = re.compile(r"\]\((?!https?://|mailto:|#)([^)#\s]+)(?:#[^)]*)?\)")


def test_readme_is_a_front_door_whose_links_resolve():
    readme = ROOT / "README.md"
    assert len(readme.read_bytes()) <= README_LIMIT_BYTES
    targets = _LINK.findall(readme.read_text(encoding="utf-8"))
    assert len(targets) >= 5, targets          # the three starts link to their guides
    assert [target for target in targets if not (ROOT / target).exists()] == []
    assert _LINK.findall("[a](docs/x.md#y) [b](https://e.org) [c](#top)") == ["docs/x.md"]
