"""Which language a command speaks: ``--lang`` (before or after the command's name), else the
``[course] language`` of the file it reads, else ``PLANMETHOD_LANG``, else English; a language
that cannot be spoken is one line and exit status 2.

The pseudo language ``qps`` (every message marked ⟦…⟧, :mod:`planmethod.testing.pseudo`)
shows which language a run spoke: its lines are marked, or not.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel (test extra)")

from planmethod import spec
from planmethod.application.language import chosen_language, course_language, file_language
from planmethod.errors import SpecError
from planmethod.testing.pseudo import PSEUDO, pseudo_catalogue
from planmethod.words import language

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"

#: whether the exercise file's [course] table is read by the model yet (front-words adds it;
#: until then a file with one is refused by the reader, in the run's language all the same)
COURSE_IN_MODEL = "course" in spec.TOP_LEVEL_KEYS


@pytest.fixture(scope="module")
def environment(tmp_path_factory) -> dict[str, str]:
    folder = tmp_path_factory.mktemp("pseudo")
    pseudo_catalogue(folder)
    env = {**os.environ, language.LOCALE_ENVIRONMENT: str(folder), "COLUMNS": "100"}
    env.pop(language.ENVIRONMENT, None)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), *filter(None, [env.get("PYTHONPATH")])])
    return env


def _course_file(folder: Path, spoken: str) -> Path:
    path = folder / f"course_{spoken.replace(' ', '_')}.toml"
    path.write_text(COMPRESSOR.read_text(encoding="utf-8")
                    + f'\n[course]\nlanguage = "{spoken}"\n', encoding="utf-8")
    return path


def _run(environment, *argv, lang: str | None = None) -> subprocess.CompletedProcess:
    env = dict(environment)
    if lang is not None:
        env[language.ENVIRONMENT] = lang
    return subprocess.run([sys.executable, "-m", "planmethod", *map(str, argv)], cwd=ROOT,
                          env=env, capture_output=True, text=True, timeout=300)


def _marked(done: subprocess.CompletedProcess) -> bool:
    """Whether the run spoke the pseudo language: its lines carry the marks."""
    shown = done.stdout + done.stderr
    assert shown.strip(), "the run printed nothing"
    return "⟦" in shown


def test_the_option_the_file_and_the_environment_in_that_order(environment, tmp_path):
    pseudo_file, english_file = _course_file(tmp_path, PSEUDO), _course_file(tmp_path, "en")
    # the file's language over the environment's (and over English)
    spoken = _run(environment, "solve", pseudo_file)
    assert _marked(spoken)
    assert spoken.returncode == (0 if COURSE_IN_MODEL else 2)
    assert not _marked(_run(environment, "solve", english_file, lang=PSEUDO))
    # the option over the file, after the command's name or before it
    assert not _marked(_run(environment, "solve", pseudo_file, "--lang", "en"))
    assert not _marked(_run(environment, "--lang", "en", "solve", pseudo_file))
    assert _marked(_run(environment, "solve", english_file, "--lang", PSEUDO, lang="en"))
    # the environment where the file names none; English where nothing does
    assert _marked(_run(environment, "solve", COMPRESSOR, lang=PSEUDO))
    english = _run(environment, "solve", COMPRESSOR)
    assert not _marked(english) and english.returncode == 0
    assert english.stdout.startswith("Compressor slider-crank")


def test_the_help_speaks_the_option_or_the_environment(environment):
    assert _marked(_run(environment, "--lang", PSEUDO, "solve", "--help"))
    assert _marked(_run(environment, "solve", "--help", lang=PSEUDO))
    assert not _marked(_run(environment, "solve", "--help"))


@pytest.mark.parametrize(("argv", "lang", "line"), [
    (["solve", COMPRESSOR, "--lang", "xx"], None,
     "planmethod: error: option --lang: no catalogue for the language xx (shipped: en, ru; a "
     "course adds one as docs/languages.md says)"),
    (["--lang", "x y", "solve", "--help"], None,
     "planmethod: error: option --lang: 'x y' is no language code (such as en or ru)"),
    (["solve", COMPRESSOR], "x y",
     "planmethod: error: PLANMETHOD_LANG: 'x y' is no language code (such as en or ru)"),
])
def test_a_language_that_cannot_be_spoken_is_one_line(environment, argv, lang, line):
    done = _run(environment, *argv, lang=lang)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr == line + "\n"


def test_a_files_language_that_cannot_be_spoken_names_the_file_and_key(environment, tmp_path):
    path = _course_file(tmp_path, "xx")
    done = _run(environment, "solve", path)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr == (f"planmethod: error: {path}: course.language: no catalogue for the "
                           "language xx (shipped: en, ru; a course adds one as "
                           "docs/languages.md says)\n")


def test_the_files_language_is_read_from_its_course_table(tmp_path):
    assert course_language({"course": {"language": "ru"}}) == "ru"
    assert course_language({"course": "ru"}) is None and course_language({}) is None
    assert file_language(_course_file(tmp_path, "ru")) == "ru"
    assert file_language(COMPRESSOR) is None
    assert file_language(tmp_path / "missing.toml") is None     # its command says why
    assert file_language(ROOT / "exercises" / "conveyor_sixbar_table2.csv") is None
    assert chosen_language(None, "ru", environment={language.ENVIRONMENT: "en"}) == "ru"
    assert chosen_language("en", "ru", environment={}) == "en"
    assert chosen_language(None, None, environment={}) == "en"
    with pytest.raises(SpecError,
                       match=r"^t\.toml: course\.language: must be a non-empty string, got 5$"):
        chosen_language(None, 5, file="t.toml", environment={})
