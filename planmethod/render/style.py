"""Drawing style of the SVG figures: fonts, sizes, colours, line styles, number formats.

One fixed style, so that the same input always gives the same bytes. Sizes are SVG user units
("px"); the plan itself is scaled to a comfortable size and carries a scale bar, so the printed
scales (μl, μv, μa) stay true whatever the zoom.

Text widths are estimated from the advance widths of the DejaVu fonts (tabulated below, in em),
which is what the figures name first and what cairosvg finds on a typical Linux machine; label
boxes are padded a little so that other fonts still fit.

Examples
--------
>>> num(-0.0), num(12.345678)
('0', '12.35')
>>> round(text_width("pb", 10.0, LABEL), 2)
12.8
>>> STYLES["normal"].color
'#1f5fbf'
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

from ..vocabulary import PlanKind
from ..words import Message, message

__all__ = [
    "CLEARANCE_PX",
    "LABEL",
    "LABEL_SIZE",
    "LEGEND_ORDER",
    "MECHANISM_SIZE",
    "PLAN_SIZE",
    "READABLE_EM",
    "READABLE_PX",
    "SANS",
    "SANS_BOLD",
    "STYLES",
    "SUB_SCALE",
    "SUB_SHIFT",
    "TEXT_SIZE",
    "TITLE_SIZE",
    "TOUCH_PX",
    "LineStyle",
    "num",
    "significant",
    "text_width",
]

#: font families (first choice DejaVu, whose metrics are tabulated here)
LABEL_FAMILY = "DejaVu Serif, Georgia, Times New Roman, serif"
TEXT_FAMILY = "DejaVu Sans, Verdana, Arial, Helvetica, sans-serif"

LABEL = "label"          # metric keys for text_width
SANS = "sans"
SANS_BOLD = "sans-bold"

LABEL_SIZE = 15.0        # plan and position labels
#: the readable distance, in em of the point labels: marks of distinct points nearer each
#: other than this crowd, and an enlarged detail shows them (docs/outputs.md, "Legible
#: figures"): 2 em, 30 px at 15 px labels
READABLE_EM = 2.0
READABLE_PX = READABLE_EM * LABEL_SIZE
#: the room (px) a label keeps from another point's mark: a quarter of the readable distance
CLEARANCE_PX = READABLE_PX / 4.0
#: without enlarged details (a workbook frame, the studio), a point's label still keeps this
#: far (px) from another point's mark
TOUCH_PX = 3.0
SUB_SCALE = 0.72         # a subscript's size relative to its label
SUB_SHIFT = 0.28         # a subscript's drop below the baseline, in em of the label
TEXT_SIZE = 12.5         # scales, legend, notes
TITLE_SIZE = 15.0
SMALL_SIZE = 11.0
NBSP = "\u00a0"         # kept by every SVG renderer, unlike a plain space at a tspan's edge

#: the longest side of a plan's points is drawn this long (px); a scale bar keeps it honest
PLAN_SIZE = 440.0
#: the longest side of the mechanism is drawn this long (px)
MECHANISM_SIZE = 600.0

INK = "#000000"
FAINT = "#9a9a9a"        # the mechanism under the rotated velocity plan
FLAG = "#d00000"
LINK_FILL = "#dfe7f1"
GROUND = "#333333"


@dataclass(frozen=True, slots=True)
class LineStyle:
    """How one kind of vector is drawn: colour, width, dash pattern, arrowhead size, and what
    its legend row says on a velocity and on an acceleration plan."""

    color: str
    width: float
    dash: str | None
    head: float
    legend_velocity: Message
    legend_acceleration: Message

    def legend(self, kind: str) -> Message:
        """The legend row's text on a plan of ``kind`` (an acceleration plan's on any other
        than a velocity plan)."""
        return self.legend_velocity if kind == PlanKind.VELOCITY else self.legend_acceleration


#: vector styles by a step's ``component`` (plus ``result`` for pole → image, ``construction``
#: for construction lines, ``similarity`` and ``projection``)
STYLES: dict[str, LineStyle] = {
    "result": LineStyle(INK, 2.6, None, 13.0, message("absolute velocity (result)"),
                        message("absolute acceleration (result)")),
    "absolute": LineStyle(INK, 2.6, None, 13.0, message("absolute velocity (result)"),
                          message("absolute acceleration (result)")),
    "normal": LineStyle("#1f5fbf", 1.7, None, 10.0, message("normal component"),
                        message("normal component aⁿ")),
    "tangential": LineStyle("#1b8a3a", 1.7, "8,3", 10.0, message("tangential component"),
                            message("tangential component aᵗ")),
    "coriolis": LineStyle("#c0392b", 1.7, "9,3,2,3", 10.0, message("Coriolis component"),
                          message("Coriolis component aᵏ")),
    "relative": LineStyle("#7b3fa0", 1.7, None, 10.0, message("relative velocity"),
                          message("relative (sliding) component aʳ")),
    "construction": LineStyle("#777777", 0.8, "5,4", 0.0, message("construction line"),
                              message("construction line (colour of its component)")),
    "similarity": LineStyle("#555555", 1.0, None, 0.0, message("image of a link (similarity)"),
                            message("image of a link (similarity)")),
    "projection": LineStyle("#555555", 0.9, "1.5,2.5", 0.0, message("projection"),
                            message("projection on the normal to the path")),
}

#: legend entries in this order, those used by a figure only
LEGEND_ORDER = ("result", "normal", "tangential", "coriolis", "relative", "construction",
                "similarity", "projection")


def num(value: float) -> str:
    """A coordinate as written into the SVG: two decimals, no trailing zeros, no ``-0``.

    >>> num(1.5), num(-0.001), num(12.0), num(3.14159)
    ('1.5', '0', '12', '3.14')
    """
    text = "%.2f" % value  # noqa: UP031  (the quickest formatting: called per coordinate)
    if text[-1] != "0":
        return text
    text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def significant(value: float, digits: int = 4) -> str:
    """A printed value with ``digits`` significant digits (``0.002``, ``20``, ``5.272``).

    >>> significant(5.27159), significant(0.002, 6)
    ('5.272', '0.002')
    """
    return f"{value:.{digits}g}"


def text_width(text: str, size: float, font: str = SANS) -> float:
    """Estimated advance width of ``text`` at ``size`` (px) in ``font``.

    >>> round(text_width("ab", 10.0), 3) == round(text_width("a", 10.0) + text_width("b", 10.0), 3)
    True
    """
    return size * _em_width(text, font)


@functools.lru_cache(maxsize=8192)
def _em_width(text: str, font: str) -> float:
    """The advance width of ``text`` in ems (the same texts recur in every frame of a turn:
    remembered)."""
    table = _METRICS[font]
    return sum(table.get(ch, 0.62) for ch in text.replace(NBSP, " "))


# advance widths (em) of the DejaVu fonts, read once with FreeType
WIDTH_CHARS = (
    ' !"#$%&\'()*+,-./0123456789:;<=>?@ABCDEFG'
    'HIJKLMNOPQRSTUVWXYZ[\\]^_`abcdefghijklmno'
    'pqrstuvwxyz{|}~πμωρτηεφαθΔ≡′—–²·ⁿᵗᵏʳ°→−×'
    '≈±…₁₂'
    # the Russian course's letters (and its quotation marks)
    'АБВГДЕЁЖЗИЙКЛМНОПРСТУФХЦЧШЩЪЫЬЭЮЯ'
    'абвгдеёжзийклмнопрстуфхцчшщъыьэюя«»'
)
SERIF_ITALIC = (
    0.318, 0.402, 0.46, 0.838, 0.636, 0.95, 0.89, 0.275, 0.39, 0.39, 0.5, 0.838, 0.318, 0.338,
    0.318, 0.337, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.337,
    0.337, 0.838, 0.838, 0.838, 0.536, 1, 0.722, 0.735, 0.765, 0.802, 0.73, 0.694, 0.799, 0.872,
    0.395, 0.401, 0.747, 0.664, 1.024, 0.875, 0.82, 0.673, 0.82, 0.753, 0.685, 0.667, 0.843,
    0.722, 1.028, 0.712, 0.66, 0.695, 0.39, 0.337, 0.39, 0.838, 0.5, 0.5, 0.596, 0.64, 0.56,
    0.64, 0.592, 0.37, 0.64, 0.644, 0.32, 0.31, 0.606, 0.32, 0.948, 0.644, 0.602, 0.64, 0.64,
    0.478, 0.513, 0.402, 0.644, 0.565, 0.856, 0.564, 0.565, 0.527, 0.636, 0.337, 0.636, 0.838,
    0.657, 0.65, 0.815, 0.588, 0.553, 0.599, 0.537, 0.7, 0.675, 0.602, 0.722, 0.838, 0.227, 1,
    0.5, 0.401, 0.318, 0.405, 0.247, 0.365, 0.347, 0.5, 0.838, 0.838, 0.838, 0.838, 0.838, 1,
    0.401, 0.401, 0.757, 0.735, 0.735, 0.662, 0.813, 0.73, 0.73, 1.124, 0.623, 0.872, 0.872,
    0.774, 0.834, 1.024, 0.872, 0.82, 0.872, 0.673, 0.765, 0.667, 0.723, 0.83, 0.712, 0.872,
    0.773, 1.141, 1.141, 0.794, 0.984, 0.674, 0.765, 1.193, 0.808, 0.596, 0.61, 0.582, 0.505,
    0.634, 0.592, 0.592, 1.137, 0.545, 0.644, 0.644, 0.597, 0.637, 0.829, 0.659, 0.602, 0.644,
    0.64, 0.56, 0.948, 0.58, 0.783, 0.564, 0.698, 0.622, 0.947, 1.001, 0.667, 0.814, 0.544,
    0.56, 0.88, 0.662, 0.612, 0.612
)
SANS_WIDTHS = (
    0.318, 0.401, 0.46, 0.838, 0.636, 0.95, 0.78, 0.275, 0.39, 0.39, 0.5, 0.838, 0.318, 0.361,
    0.318, 0.337, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.337,
    0.337, 0.838, 0.838, 0.838, 0.531, 1, 0.684, 0.686, 0.698, 0.77, 0.632, 0.575, 0.775, 0.752,
    0.295, 0.295, 0.656, 0.557, 0.863, 0.748, 0.787, 0.603, 0.787, 0.695, 0.635, 0.611, 0.732,
    0.684, 0.989, 0.685, 0.611, 0.685, 0.39, 0.337, 0.39, 0.838, 0.5, 0.5, 0.613, 0.635, 0.55,
    0.635, 0.615, 0.352, 0.635, 0.634, 0.278, 0.278, 0.579, 0.278, 0.974, 0.634, 0.612, 0.635,
    0.635, 0.411, 0.521, 0.392, 0.634, 0.592, 0.818, 0.592, 0.592, 0.525, 0.636, 0.337, 0.636,
    0.838, 0.602, 0.636, 0.837, 0.635, 0.602, 0.634, 0.541, 0.66, 0.659, 0.612, 0.684, 0.838,
    0.227, 1, 0.5, 0.401, 0.318, 0.398, 0.295, 0.426, 0.259, 0.5, 0.838, 0.838, 0.838, 0.838,
    0.838, 1, 0.401, 0.401, 0.684, 0.686, 0.686, 0.61, 0.781, 0.632, 0.632, 1.077, 0.641, 0.748,
    0.748, 0.71, 0.752, 0.863, 0.752, 0.787, 0.752, 0.603, 0.698, 0.611, 0.609, 0.861, 0.685,
    0.776, 0.686, 1.069, 1.094, 0.833, 0.882, 0.686, 0.698, 1.08, 0.695, 0.613, 0.617, 0.589,
    0.525, 0.691, 0.615, 0.615, 0.901, 0.532, 0.65, 0.65, 0.604, 0.639, 0.754, 0.654, 0.612,
    0.654, 0.635, 0.55, 0.583, 0.592, 0.855, 0.592, 0.681, 0.591, 0.915, 0.942, 0.707, 0.79,
    0.589, 0.549, 0.842, 0.602, 0.612, 0.612
)
SANS_BOLD_WIDTHS = (
    0.348, 0.456, 0.521, 0.838, 0.696, 1.002, 0.872, 0.306, 0.457, 0.457, 0.523, 0.838, 0.38,
    0.415, 0.38, 0.365, 0.696, 0.696, 0.696, 0.696, 0.696, 0.696, 0.696, 0.696, 0.696, 0.696,
    0.4, 0.4, 0.838, 0.838, 0.838, 0.58, 1, 0.774, 0.762, 0.734, 0.83, 0.683, 0.683, 0.821,
    0.837, 0.372, 0.372, 0.775, 0.637, 0.995, 0.837, 0.85, 0.733, 0.85, 0.77, 0.72, 0.682,
    0.812, 0.774, 1.103, 0.771, 0.724, 0.725, 0.457, 0.365, 0.457, 0.838, 0.5, 0.5, 0.675,
    0.716, 0.593, 0.716, 0.678, 0.435, 0.716, 0.712, 0.343, 0.343, 0.665, 0.343, 1.042, 0.712,
    0.687, 0.716, 0.716, 0.493, 0.595, 0.478, 0.712, 0.652, 0.924, 0.645, 0.652, 0.582, 0.712,
    0.365, 0.712, 0.838, 0.791, 0.736, 0.869, 0.716, 0.638, 0.712, 0.557, 0.782, 0.687, 0.687,
    0.774, 0.838, 0.264, 1, 0.5, 0.438, 0.38, 0.456, 0.388, 0.487, 0.315, 0.5, 0.838, 0.838,
    0.838, 0.838, 0.838, 1, 0.438, 0.438, 0.774, 0.762, 0.762, 0.637, 0.891, 0.683, 0.683,
    1.224, 0.71, 0.837, 0.837, 0.817, 0.831, 0.995, 0.837, 0.85, 0.837, 0.733, 0.734, 0.682,
    0.771, 0.992, 0.771, 0.928, 0.808, 1.235, 1.326, 0.939, 1.036, 0.762, 0.734, 1.174, 0.77,
    0.675, 0.698, 0.633, 0.522, 0.808, 0.678, 0.678, 0.995, 0.581, 0.701, 0.701, 0.679, 0.732,
    0.817, 0.691, 0.687, 0.691, 0.716, 0.593, 0.58, 0.652, 0.992, 0.645, 0.741, 0.687, 1.062,
    1.105, 0.751, 0.904, 0.632, 0.593, 0.972, 0.642, 0.646, 0.646
)


_METRICS = {LABEL: dict(zip("".join(WIDTH_CHARS), SERIF_ITALIC, strict=True)),
            SANS: dict(zip("".join(WIDTH_CHARS), SANS_WIDTHS, strict=True)),
            SANS_BOLD: dict(zip("".join(WIDTH_CHARS), SANS_BOLD_WIDTHS, strict=True))}
