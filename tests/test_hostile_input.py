"""Hostile and careless input: every case gives one line on stderr, exit 2, no traceback, and
nothing is written anywhere — above all, nothing outside the output folder the user named."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from planmethod.cli import main
from planmethod.io import path_component, student_folder, write_files

TEMPLATE = "exercises/templates/slider_crank.toml"


def _tree(root: Path) -> set[str]:
    """Every file and folder under ``root`` (relative paths)."""
    return {str(path.relative_to(root)) for path in root.rglob("*")}


def _error_line(capsys, code: int) -> str:
    out, err = capsys.readouterr()
    assert code == 2, (code, out, err)
    assert "Traceback" not in err and "Traceback" not in out
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("planmethod: error: "), err
    return lines[0]


@pytest.fixture(scope="module")
def keys_file(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("course")
    assert main(["variants", TEMPLATE, "--count", "2", "--seed", "3", "--out", str(folder),
                 "--no-sheets"]) == 0
    return folder / "keys.json"


@pytest.mark.parametrize("slug", ["../../x", "..", ".", "", "   ", "/tmp/evil", "a/b",
                                  "a\\b", "x/../../y", "nul\0byte"])
def test_prairielearn_slug_cannot_leave_the_output_folder(tmp_path, keys_file, capsys, slug):
    sandbox = tmp_path / "a" / "b"
    sandbox.mkdir(parents=True)
    capsys.readouterr()
    cwd = os.getcwd()
    os.chdir(sandbox)
    try:
        code = main(["export", str(keys_file), "--format", "prairielearn", "--out", "DIR",
                     "--slug", slug])
    finally:
        os.chdir(cwd)
    line = _error_line(capsys, code)
    assert "--slug" in line and "single folder or file name" in line
    assert _tree(tmp_path) == {"a", "a/b"}  # nothing written, above or below
    assert not Path("/tmp/evil").exists()


def test_prairielearn_slug_that_is_a_name_writes_inside(tmp_path, keys_file, capsys):
    assert main(["export", str(keys_file), "--format", "prairielearn", "--out",
                 str(tmp_path / "DIR"), "--slug", "fourbar-2026"]) == 0
    figures = {"DIR/fourbar-2026/clientFilesQuestion"} | {
        f"DIR/fourbar-2026/clientFilesQuestion/task_{number}_{student}.svg"
        for number, student in enumerate(("001", "002"), start=1)}
    assert _tree(tmp_path) == {"DIR", "DIR/fourbar-2026", "DIR/fourbar-2026/info.json",
                               "DIR/fourbar-2026/question.html", "DIR/fourbar-2026/server.py",
                               "DIR/fourbar-2026/manifest.json", *figures}


def test_student_ids_that_climb_stay_inside(tmp_path, capsys):
    roster = tmp_path / "roster.csv"
    roster.write_text("student\n../../evil\n/etc/passwd\n..\nAnn.Lee@uni.edu\n",
                      encoding="utf-8")
    out = tmp_path / "course"
    assert main(["variants", TEMPLATE, "--students", str(roster), "--out", str(out),
                 "--no-sheets"]) == 0
    assert _tree(tmp_path) - {"roster.csv"} == {"course"} | {
        f"course/{name}" for name in ("keys.json", "index.csv", "manifest.json")} | {
        f"course/{folder}{file}" for folder in ("_.._evil", "_etc_passwd", "student",
                                                "Ann.Lee@uni.edu")
        for file in ("", "/exercise.toml", "/key.json")}


@pytest.mark.parametrize("relative", ["../x.txt", "/abs.txt", "a/../../x.txt", "", "a//..",
                                      "a\\..\\x"])
def test_write_files_refuses_paths_that_leave_the_folder(tmp_path, relative):
    with pytest.raises(ValueError):
        write_files(tmp_path / "out", {"fine.txt": "ok", relative: "no"})
    assert _tree(tmp_path) == set()  # checked before anything is written


@pytest.mark.parametrize("name", ["..", ".", "", "a/b", "a\\b", "\0"])
def test_path_component_rules(name):
    with pytest.raises(ValueError, match="--slug"):
        path_component(name, "--slug")


@pytest.mark.parametrize("student", ["..", ".", "", "../..", "/", "\\", "." * 200])
def test_student_folder_is_always_one_component(student):
    assert path_component(student_folder(student), "student id") not in ("", ".", "..")


def test_unwritable_output_is_one_line(tmp_path, keys_file, capsys):
    code = main(["export", str(keys_file), "--format", "moodle", "--out", "/proc/quiz.xml"])
    line = _error_line(capsys, code)
    assert "/proc/quiz.xml" in line
