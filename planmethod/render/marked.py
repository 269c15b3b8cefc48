"""A graded photo of a plan sheet, marked for the student: the part of the photo that holds
the plan, enlarged, each point ringed where it was found — green if right, red if not, with a
thin line to where it belongs — and the grader's sentences under it.

The photo is drawn with Pillow (the ``paper`` extra), its text in DejaVu Sans (matplotlib
ships the font), so that every symbol of the sentences (ω₂, π, aᵏ, Cyrillic) shows. Its
sentences are rendered here, in the language spoken. A point's name and the symbols of the
sentences are set as the figures set them (n with CB below, v_B₃ as v with B3 below:
:func:`~planmethod.render.canvas.formula_runs`), a subscript smaller and lower, never with
an underscore.

Examples
--------
>>> _shown("b ⟂ AB")
'b ⊥ AB'
"""

from __future__ import annotations

import io
import textwrap
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ..words import render
from .canvas import formula_runs

if TYPE_CHECKING:
    from ..grading.photos import GradedPhoto

__all__ = ["marked_photo"]

#: the marked photo's longest side (px)
LONGEST_PX = 2000
GREEN = (20, 150, 40)
RED = (210, 30, 30)


def _font(size: int):
    from matplotlib import font_manager
    from PIL import ImageFont

    return ImageFont.truetype(font_manager.findfont("DejaVu Sans"), size)


def marked_photo(graded: GradedPhoto, header: Sequence[str], *, quality: int = 85) -> bytes:
    """The part of the photo of ``graded`` (a :class:`~planmethod.grading.photos.GradedPhoto`)
    that holds the plan, enlarged, each point ringed where it was found, with a line to where
    it belongs if it is wrong, or a dashed ring where it belongs if it was not found; the
    lines of ``header`` and each point's sentence under it; as JPEG bytes. (It is as long as
    the marks it draws.)"""
    from PIL import Image, ImageDraw

    image = graded.image
    millimetre = float(graded.reading.px_per_mm or 8.0)
    places = [place for spot in graded.places
              for place in (spot.photo_px, spot.right_photo_px) if place]
    places.append(graded.pole_photo_px)
    height, width = image.shape[:2]
    margin = 12.0 * millimetre
    xs, ys = [x for x, _ in places], [y for _, y in places]
    left, top = max(0, int(min(xs) - margin)), max(0, int(min(ys) - margin))
    right, bottom = min(width, int(max(xs) + margin)), min(height, int(max(ys) + margin))
    crop = np.ascontiguousarray(image[top:bottom, left:right, ::-1])
    scale = min(4.0, LONGEST_PX / max(crop.shape[:2]))
    photo = Image.fromarray(crop).convert("RGB").resize(
        (max(1, round(crop.shape[1] * scale)), max(1, round(crop.shape[0] * scale))),
        Image.LANCZOS)
    draw = ImageDraw.Draw(photo)
    unit = max(2.0, millimetre * scale)              # a millimetre of the sheet, in px
    ring_size = max(8, round(1.4 * unit))
    line = max(2, round(0.25 * unit))
    name_font = _Faces(max(16, round(2.6 * unit)))
    small_font = _Faces(max(12, round(1.6 * unit)))

    def at(place) -> tuple[float, float]:
        return ((place[0] - left) * scale, (place[1] - top) * scale)

    # the helper points (n, k: not scored) first and small, the plan's points over them
    for point, spot in sorted(zip(graded.drawing.points, graded.places, strict=True),
                              key=lambda pair: pair[0].max_score):
        colour = GREEN if point.correct else RED
        scored = point.max_score > 0
        ring = ring_size if scored else ring_size * 0.6
        label_font = name_font if scored else small_font
        if point.found and spot.photo_px is not None:
            x, y = at(spot.photo_px)
            if not point.correct:
                rx, ry = at(spot.right_photo_px)
                draw.line([(x, y), (rx, ry)], fill=RED, width=max(1, line // 2))
                draw.ellipse([rx - ring / 2, ry - ring / 2, rx + ring / 2, ry + ring / 2],
                             outline=GREEN, width=max(1, line // 2))
            draw.ellipse([x - ring, y - ring, x + ring, y + ring], outline=colour, width=line)
            # a helper point's name below, clear of the point's it usually lies beside
            label_font.draw(draw, (x + ring * 1.1, y - ring * 2.0 if scored else y + ring * 0.4),
                            point.name, colour)
        else:
            x, y = at(spot.right_photo_px)
            _dashed_ring(draw, (x, y), ring, RED, line)
            label_font.draw(draw, (x + ring * 1.1, y - ring * 2.0), point.name + "?", RED)
    return _with_text(photo, graded, header, quality)


#: a subscript's size and how far it is lowered, in the text's size (the figures' 0.72)
SUB_SCALE, SUB_DROP = 0.72, 0.35


class _Faces:
    """A text size's face and its subscripts' smaller face, and how a text is set in them:
    its symbols' subscripts smaller and lower (:func:`_runs`)."""

    def __init__(self, size: int) -> None:
        self.size = size
        self.main, self.sub = _font(size), _font(max(8, round(size * SUB_SCALE)))

    def draw(self, draw, place: tuple[float, float], text: str, colour) -> None:
        """``text`` set at ``place`` (its top left), run by run."""
        x, y = place
        for part, small in _runs(text):
            face = self.sub if small else self.main
            draw.text((x, y + (SUB_DROP * self.size if small else 0.0)), part, fill=colour,
                      font=face)
            x += draw.textlength(part, font=face)


def _runs(text: str) -> list[tuple[str, bool]]:
    """A sentence's or a name's runs as the photo sets them: (text, set as a subscript).

    >>> _runs("n_CB is 2.8 mm off: (bn_CB) ⟂ CB")
    [('n', False), ('CB', True), (' is 2.8 mm off: (bn', False), ('CB', True), (') ⊥ CB', False)]
    """
    return formula_runs(_shown(text)) or [("", False)]


#: characters DejaVu Sans lacks, drawn as the nearest it has
_SHOWN = str.maketrans({"⟂": "⊥"})


def _shown(text: str) -> str:
    """``text`` as the photo's font can draw it."""
    return text.translate(_SHOWN)


def _dashed_ring(draw, centre, radius: float, colour, width: int) -> None:
    for start in range(0, 360, 30):
        draw.arc([centre[0] - radius, centre[1] - radius, centre[0] + radius,
                  centre[1] + radius], start, start + 18, fill=colour, width=width)


def _with_text(photo, graded: GradedPhoto, header: Sequence[str], quality: int) -> bytes:
    """The photo with the sentences set under it."""
    from PIL import Image, ImageDraw

    size = max(16, photo.width // 55)
    font, bold = _Faces(size), _font(round(size * 1.15))
    characters = max(30, int(photo.width / (0.55 * size)) - 4)
    rows: list[tuple[str, tuple[int, int, int], Any]] = []   # the header plain (a path)
    for text in header:          # a long path wraps too, in the larger bold face
        for index, piece in enumerate(textwrap.wrap(_shown(text), int(characters / 1.15))):
            rows.append((("   " if index else "") + piece, (0, 0, 0), bold))
    for point in graded.drawing.points:
        mark = "✓ " if point.correct else "✗ "
        colour = GREEN if point.correct else RED
        for index, piece in enumerate(textwrap.wrap(_shown(render(point.feedback)),
                                                    characters) or [""]):
            rows.append(((mark if index == 0 else "   ") + piece, colour, font))
    for text in graded.drawing.feedback:
        for index, piece in enumerate(textwrap.wrap(_shown(render(text)), characters)):
            rows.append((("! " if index == 0 else "   ") + piece, (150, 80, 0), font))
    step = round(size * 1.45)
    panel = Image.new("RGB", (photo.width, photo.height + step * len(rows) + 2 * size),
                      (255, 255, 255))
    panel.paste(photo, (0, 0))
    draw = ImageDraw.Draw(panel)
    y = photo.height + size
    for text, colour, face in rows:
        if isinstance(face, _Faces):
            face.draw(draw, (size, y), text, colour)
        else:
            draw.text((size, y), text, fill=colour, font=face)
        y += step
    out = io.BytesIO()
    panel.save(out, "JPEG", quality=quality)
    return out.getvalue()
