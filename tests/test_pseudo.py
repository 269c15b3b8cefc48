"""The pseudo-translation harness (planmethod.testing.pseudo): a made-up language that marks
every message, and the finder of English words left outside the marks."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel (test extra)")

from planmethod.testing.pseudo import (
    PSEUDO,
    message_words,
    pseudo_catalogue,
    unmarked_words,
)
from planmethod.words import language

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def pseudo_environment(tmp_path_factory) -> dict[str, str]:
    folder = tmp_path_factory.mktemp("pseudo")
    pseudo_catalogue(folder)
    return {**os.environ, language.LOCALE_ENVIRONMENT: str(folder),
            language.ENVIRONMENT: PSEUDO}


def test_an_error_line_is_marked(pseudo_environment):
    """An error's context (its link, its crank angle) comes from the catalogue."""
    script = ("from planmethod.errors import SpecError\n"
              "print(SpecError('x', file='f.toml', link='BC', angle=30))")
    shown = subprocess.run([sys.executable, "-c", script], cwd=ROOT, env=pseudo_environment,
                           capture_output=True, text=True, check=True).stdout.strip()
    assert shown == "f.toml: ⟦link BC⟧, ⟦crank angle 30°⟧: x"
    assert unmarked_words(shown, message_words(), names=["f.toml"]) == []


def test_words_outside_the_marks_are_found():
    words = message_words()
    assert {"link", "crank", "angle"} <= words
    assert unmarked_words("crank ⟦crank⟧ BC", words) == ["crank"]
    assert unmarked_words("link frame", words, names=["frame"]) == ["link"]
