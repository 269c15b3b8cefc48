"""The pages under the pseudo language ``qps``: every word the workbook and the studio show —
their markup, and every template their scripts fill — comes from the catalogue (marked ⟦…⟧),
none is written in English around it (planmethod.testing.pseudo)."""

from __future__ import annotations

import base64
import gzip
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel (test extra)")

from planmethod.testing.pseudo import (
    PSEUDO,
    message_words,
    pseudo_catalogue,
    texts_of_html,
    unmarked_words,
)
from planmethod.words import language

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"


@pytest.fixture(scope="module")
def pseudo_environment(tmp_path_factory) -> dict[str, str]:
    folder = tmp_path_factory.mktemp("pseudo")
    pseudo_catalogue(folder)
    return {**os.environ, language.LOCALE_ENVIRONMENT: str(folder),
            language.ENVIRONMENT: PSEUDO, "PYTHONPATH": str(ROOT)}


def marked(text: str) -> bool:
    return text.startswith("⟦") and text.endswith("⟧")


def templates_marked(templates: dict) -> list[str]:
    """The templates (or plural forms) that are not marked as the catalogue's."""
    out = []
    for name, template in templates.items():
        forms = template["forms"] if isinstance(template, dict) else [template]
        out += [name for form in forms if not marked(form)]
    return out


def test_the_workbook_says_every_word_from_the_catalogue(pseudo_environment, tmp_path):
    """A workbook built while ``qps`` is spoken: its markup's words and every template its
    scripts fill are marked, the notes under the title too. Left out, with their owners: the
    drawings (the plans' figures, filled in by the script from the frames)."""
    page = tmp_path / "page.html"
    subprocess.run([sys.executable, "-m", "planmethod", "workbook", str(COMPRESSOR), "-o",
                    str(page), "--step", "120"], cwd=ROOT, env=pseudo_environment, check=True,
                   capture_output=True)
    text = page.read_text(encoding="utf-8")
    packed = re.search(r'id="workbook-data">([^<]*)<', text).group(1)
    data = json.loads(gzip.decompress(base64.b64decode(packed)))
    rules = data["rules"]
    assert rules["language"] == PSEUDO and '<html lang="qps">' in text
    assert templates_marked(rules["templates"]) == []
    quantities = data["quantities"]
    assert all(marked(sense) for quantity in quantities for sense in quantity["senses"])
    assert all(marked(quantity["negative"]) for quantity in quantities if quantity["negative"])
    assert any(quantity["negative"] for quantity in quantities)
    notes = re.findall(r'<p class="note">([^<]*)</p>', text)
    assert len(notes) == 2 and all(marked(note) for note in notes)
    names = [data["draw"]["title"], *data["draw"]["names"].values(), "φ₁", "μv", "μa"]
    shown = texts_of_html(text)
    assert len(shown) > 40
    # one text: a mark opens before a control inside its sentence and closes after it
    assert unmarked_words(" ".join(shown), message_words(), names) == []
    failed = re.search(r'data-failed="([^"]*)"', text).group(1)
    assert marked(failed)


def test_the_studio_says_every_word_from_the_catalogue(pseudo_environment):
    script = ("import sys; from planmethod.studio.page import studio_page; "
              "sys.stdout.buffer.write(studio_page())")
    text = subprocess.run([sys.executable, "-c", script], cwd=ROOT, env=pseudo_environment,
                          check=True, capture_output=True).stdout.decode("utf-8")
    words = json.loads(re.search(r'id="studio-words">(.*?)</script>', text, re.S).group(1))
    assert templates_marked(words["templates"]) == []
    shown = texts_of_html(text)
    assert len(shown) > 60
    names = ["exercise.toml", "template.toml", "export", "φ₁", "ω₁", "ε₁"]
    assert unmarked_words(" ".join(shown), message_words(), names) == []
