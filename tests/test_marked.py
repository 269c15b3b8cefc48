"""The marked photo (planmethod.render.marked) prints names and symbols as the course writes
them: the helper point n_CB as n with CB set below, never with an underscore."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from planmethod.cli import main

pytest.importorskip("cv2", reason="the paper course needs OpenCV (the paper extra)")
pytest.importorskip("segno", reason="the sheets' QR codes need segno (the paper extra)")
ImageDraw = pytest.importorskip("PIL.ImageDraw", reason="the marked photo needs Pillow")

from planmethod.grading.keys import load_keys  # noqa: E402
from planmethod.grading.photos import grade_photo  # noqa: E402
from planmethod.render.marked import marked_photo  # noqa: E402
from planmethod.testing.photos import sheet_photo  # noqa: E402
from planmethod.words import render  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
TEMPLATE = ROOT / "exercises" / "templates" / "slider_crank.toml"


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """A photo of one student's acceleration sheet, graded: its helper points n_CB, n_D."""
    out = tmp_path_factory.mktemp("marked") / "course"
    assert main(["variants", str(TEMPLATE), "--count", "1", "--seed", "2026",
                 "--out", str(out)]) == 0
    keys = load_keys(out / "keys.json")
    photo = sheet_photo(next(iter(keys.values())), "acceleration", seed=11)
    path = out / "acceleration.jpg"
    path.write_bytes(photo.jpeg)
    return grade_photo(keys, path)


def test_the_marked_photo_sets_helper_names_with_subscripts(graded, monkeypatch):
    """Every text the photo draws (the points' names on the photo, the sentences under it)
    has no underscore before a letter; n_CB's subscript CB is drawn as a run of its own, in
    a smaller face and lower than its n."""
    names = [point.name for point in graded.drawing.points]
    assert "n_CB" in names                               # the key's name: the course's n_CB
    sentences = [render(point.feedback) for point in graded.drawing.points]
    assert any("n_CB" in sentence for sentence in sentences)   # plain text keeps it
    drawn: list[tuple[str, float, float]] = []
    original = ImageDraw.ImageDraw.text

    def spy(self, xy, text, *args, **kwargs):
        font = kwargs.get("font")
        drawn.append((text, xy[1], getattr(font, "size", 0)))
        return original(self, xy, text, *args, **kwargs)

    monkeypatch.setattr(ImageDraw.ImageDraw, "text", spy)
    marked_photo(graded, ["acceleration.jpg (student 001, acceleration plan)"])
    texts = [text for text, _, _ in drawn]
    body = [text for text in texts if "acceleration.jpg" not in text]   # the header is a path
    assert body and not [text for text in body if re.search(r"_[A-Za-z]", text)], body
    runs = [index for index, (text, _, _) in enumerate(drawn) if text == "CB"]
    assert runs, texts
    for index in runs:
        sub, head = drawn[index], drawn[index - 1]
        assert head[0].endswith("n") and sub[2] < head[2] and sub[1] > head[1]
