"""Phone photos of drawn plan sheets, made as a phone would make them: for the tests and the
benchmark of ``grade --photo``.

:func:`drawn_plan` says what a student draws on a sheet — the plan's strokes and points — by
the right construction or by one of the named mistakes (the positions the key gives for it);
:func:`pencil_page` draws it with hand-like pencil strokes (a grey, grainy line of varying
width that wobbles, breaks, starts early and overshoots its ends; dots or small crosses at the
points; handwritten labels) onto the booklet's page rendered at phone resolution;
:func:`photograph` takes the photo: the sheet mildly curled, seen up to 30° off its normal and
turned any way, lit unevenly with a shadow across it, a colour cast, the lens's blur, sensor
noise, and saved as JPEG at quality 70. :func:`sheet_photo` does all three.

Needs OpenCV and CairoSVG (the ``paper`` extra).

Examples
--------
>>> from planmethod.grading.keys import build_key
>>> from planmethod.grading.paper import add_sheets
>>> from planmethod.grading.templates import draw_variant, load_template
>>> key = build_key(draw_variant(load_template("exercises/templates/slider_crank.toml")))
>>> _ = add_sheets([key])
>>> plan = drawn_plan(key, "velocity")
>>> sorted(plan.points)
['b', 'c', 'd']
>>> photo = sheet_photo(key, "velocity", seed=1)  # doctest: +SKIP
>>> photo.jpeg[:2]  # doctest: +SKIP
b'\\xff\\xd8'
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["Conditions", "DrawnPlan", "SheetPhoto", "drawable_constructions", "drawn_plan",
           "mistake_names", "page_image", "pencil_page", "photograph", "sheet_photo"]

#: the page is rendered at this many pixels per millimetre before it is photographed
PAGE_PX_PER_MM = 12.0
#: the photo's size (px): a 12-megapixel phone camera held upright
PHOTO_SIZE = (3000, 4000)
#: the camera's focal length, px, for :data:`PHOTO_SIZE`: a phone's main camera (26 mm
#: equivalent: 69° across the long side)
FOCAL_PX = 2900.0


@dataclass(frozen=True)
class DrawnPlan:
    """What a student drew on a sheet: the points (plan mm from the pole, y up) by label, the
    strokes (pairs of plan points) and, per label, the verdict the construction deserves
    (``right``, or the mistake that moved the point)."""

    plan: str
    construction: str | None
    points: Mapping[str, tuple[float, float]]
    strokes: tuple[tuple[tuple[float, float], tuple[float, float]], ...]
    deserved: Mapping[str, str]
    #: the points no two strokes cross at: always marked (a dot or a cross)
    marked: frozenset = frozenset()


@dataclass(frozen=True)
class Conditions:
    """How a photo is taken (each drawn at random by :meth:`random`)."""

    tilt_deg: float = 0.0          # the camera's axis off the sheet's normal
    tilt_towards_deg: float = 0.0  # the direction of that tilt, in the sheet's plane
    rotation_deg: float = 0.0      # the sheet turned in the picture
    fill: float = 0.85             # how much of the picture the sheet's outline fills
    curl_mm: float = 0.0           # the sheet's edges lifted this much above its middle
    light: float = 0.25            # how unevenly it is lit (0: evenly)
    shadow: float = 0.35           # how much a shadow darkens the part it covers
    blur_px: float = 0.8           # the lens's blur (Gaussian σ, px)
    noise: float = 3.0             # the sensor's noise (σ, of 255)
    quality: int = 70              # JPEG quality
    cast: tuple[float, float, float] = (1.0, 1.0, 1.0)   # white balance (B, G, R)

    @classmethod
    def random(cls, rng: np.random.Generator, *, max_tilt_deg: float = 30.0) -> Conditions:
        """Conditions as a class's photos vary: up to ``max_tilt_deg`` off the normal."""
        return cls(tilt_deg=float(rng.uniform(0.0, max_tilt_deg)),
                   tilt_towards_deg=float(rng.uniform(0.0, 360.0)),
                   # the phone held any way round, the sheet a little askew in it
                   rotation_deg=float(90.0 * rng.integers(0, 4) + rng.uniform(-15.0, 15.0)),
                   fill=float(rng.uniform(0.72, 0.92)),
                   curl_mm=float(rng.uniform(0.0, 4.0)),
                   light=float(rng.uniform(0.1, 0.4)),
                   shadow=float(rng.uniform(0.15, 0.45)),
                   blur_px=float(rng.uniform(0.5, 1.4)),
                   noise=float(rng.uniform(2.0, 5.0)),
                   quality=70,
                   cast=tuple(float(v) for v in rng.uniform(0.93, 1.05, 3)))


@dataclass(frozen=True)
class SheetPhoto:
    """A photo of a drawn sheet: the JPEG, what was drawn, and how the photo was taken (with
    where each page millimetre landed: ``page_to_photo``)."""

    jpeg: bytes
    drawn: DrawnPlan
    conditions: Conditions
    page_to_photo: Any = field(repr=False, default=None)


# -- what is drawn ---------------------------------------------------------------------------
#: a drawn plan is read only where its points stand clear of the printed pole's ring (mm)
POLE_ROOM_MM = 6.0


def mistake_names(key: Mapping[str, Any], plan: str) -> list[str]:
    """The named mistakes the key gives positions for on ``plan``: those that re-draw the whole
    plan first, then those that place single points, each once."""
    entry = key["plans"][plan]
    names = list(entry.get("mistakes", {}))
    for candidates in entry.get("mistake_points", {}).values():
        names += [name for name, *_ in candidates if name not in names]
    return names


def drawable_constructions(key: Mapping[str, Any], plan: str
                           ) -> list[tuple[str | None, str | None]]:
    """The constructions a benchmark draws on a sheet: the right one ``(None, None)``, each
    mistake that re-draws the plan ``(mistake, None)``, and each mistake that places a single
    point, on each point it moves ``(mistake, label)`` — those whose plan can be drawn on the
    sheet and read: every point on the drawing area, clear of the pole's ring
    (:data:`POLE_ROOM_MM`), at least one point moved beyond its tolerance."""
    from ..grading.paper import read_sheet

    sheet = read_sheet(key, plan)
    left, top, right, bottom = sheet.drawing_mm
    entry = key["plans"][plan]
    out: list[tuple[str | None, str | None]] = [(None, None)]
    for name in mistake_names(key, plan):
        labels = [None] if name in entry.get("mistakes", {}) else sorted(
            {label for label, candidates in entry.get("mistake_points", {}).items()
             for mistake, *_ in candidates if mistake == name})
        for label in labels:
            drawn = drawn_plan(key, plan, name, label)
            moved = [point for point, verdict in drawn.deserved.items() if verdict != "right"]
            inside = all(left + 3 <= sheet.pole_mm[0] + x <= right - 3
                         and top + 3 <= sheet.pole_mm[1] - y <= bottom - 3
                         for x, y in drawn.points.values())
            clear = all(math.hypot(x, y) >= POLE_ROOM_MM for x, y in drawn.points.values())
            if moved and inside and clear and (name, label) not in out:
                out.append((name, label))
    return out


def drawn_plan(key: Mapping[str, Any], plan: str, construction: str | None = None,
               label: str | None = None) -> DrawnPlan:
    """The plan a student draws by the right construction (``None``) or by the named mistake
    ``construction``: a mistake that re-draws the plan moves every point as the key's re-drawn
    plan has it; one that places single points moves ``label`` (default: the first point it
    moves) where the key says. The strokes are the construction's steps between the points as
    placed, and every point that no two strokes cross at is marked with a dot or a cross."""
    from ..grading.plan_points import graded_labels

    entry = key["plans"][plan]
    right = {name: tuple(map(float, xy)) for name, xy in entry["points_mm"].items()}
    redrawn = entry.get("mistakes", {}).get(construction) if construction else None
    placed = dict(right)
    if redrawn is not None:
        placed.update({name: tuple(map(float, xy)) for name, xy in redrawn.items()})
    elif construction is not None:
        for name, candidates in entry.get("mistake_points", {}).items():
            found = [(x, y) for mistake, x, y in candidates if mistake == construction]
            if found and (label is None or name == label):
                placed[name] = (float(found[0][0]), float(found[0][1]))
                if label is None:
                    break
    labels = graded_labels(entry)
    deserved = {}
    for name in labels:
        moved = math.dist(placed[name], right[name]) > entry["tolerance_mm"].get(name, 0.5)
        deserved[name] = construction if (construction and moved) else "right"
    strokes = tuple(_strokes(entry, placed))
    # a student marks the point they decide on: every moved one, and each that no two lines
    # cross at clearly
    marked = frozenset(name for name in labels if deserved[name] != "right"
                       or not _crossed(placed[name], strokes))
    return DrawnPlan(plan, construction, {name: placed[name] for name in labels}, strokes,
                     deserved, marked)


def _strokes(entry: Mapping[str, Any], placed: Mapping[str, tuple[float, float]]):
    """The strokes of a plan's construction: the vectors laid off, each construction line from
    its point to where it is intersected, the similarity steps and the pole's vectors read."""
    pole = entry["pole"]
    intersections = {}
    for step in entry["steps"]:
        if step["action"] == "intersect":
            for number in step.get("lines", ()):
                intersections[number] = step["end"]
    for step in entry["steps"]:
        action = step["action"]
        start, end = step.get("start"), step.get("end")
        if action in ("lay_off", "similarity") and start in placed and end in placed:
            if math.dist(placed[start], placed[end]) > 1e-6:
                yield (placed[start], placed[end])
        elif action == "line" and start in placed:
            end = intersections.get(step["number"])
            if end is not None and math.dist(placed[start], placed[end]) > 1e-6:
                yield (placed[start], placed[end])
        elif action == "read" and start == pole and end in placed:
            yield (placed[start], placed[end])


def _crossed(point, strokes, *, angle_deg: float = 30.0) -> bool:
    """Whether two of ``strokes`` that reach ``point`` (end at it or pass through it) cross
    there at ``angle_deg`` or more."""
    directions = []
    for a, b in strokes:
        a, b = np.asarray(a), np.asarray(b)
        length = float(np.hypot(*(b - a)))
        if length < 3.0:
            continue
        direction = (b - a) / length
        offset = np.asarray(point) - a
        along = float(offset @ direction)
        if abs(float(offset[0] * direction[1] - offset[1] * direction[0])) <= 0.05 \
                and -0.05 <= along <= length + 0.05:
            directions.append(direction)
    return any(abs(float(u[0] * v[1] - u[1] * v[0])) >= math.sin(math.radians(angle_deg))
               for index, u in enumerate(directions) for v in directions[index + 1:])


# -- drawing on the page ---------------------------------------------------------------------
def page_image(svg: str, px_per_mm: float = PAGE_PX_PER_MM) -> np.ndarray:
    """An SVG page (mm) as an RGB image (uint8) at ``px_per_mm``."""
    import cairosvg
    import cv2

    png = cairosvg.svg2png(bytestring=svg.encode("utf-8"), dpi=25.4 * px_per_mm,
                           background_color="#ffffff")
    image = cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR)
    return image


def _stroke_polyline(a, b, rng: np.random.Generator, scale: float) -> list[np.ndarray]:
    """A pencil stroke from ``a`` to ``b`` (page px): started a little early, ended a little
    late, wobbling, sometimes broken; as pieces of polyline."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    length = float(np.hypot(*(b - a)))
    if length < 1e-9:
        return []
    direction = (b - a) / length
    normal = np.array([-direction[1], direction[0]])
    start = -rng.uniform(0.0, 0.8) * scale
    stop = length + rng.uniform(0.2, 1.2) * scale
    count = max(8, int((stop - start) / (0.5 * scale)))
    along = np.linspace(start, stop, count)
    phase = rng.uniform(0, 2 * math.pi, 3)
    wobble = (0.03 * scale * np.sin(along / (9 * scale) + phase[0])
              + 0.015 * scale * np.sin(along / (2.3 * scale) + phase[1])
              + rng.normal(0.0, 0.006 * scale, count))
    points = a + along[:, None] * direction + wobble[:, None] * normal
    pieces = [points]
    for _ in range(rng.integers(0, 3)):               # a gap where the pencil lifted
        index = max(range(len(pieces)), key=lambda i: len(pieces[i]))
        piece = pieces.pop(index)
        if len(piece) < 12:
            pieces.append(piece)
            break
        cut = int(rng.integers(3, len(piece) - 3))
        gap = max(1, int(rng.uniform(0.3, 0.8) * scale / (0.5 * scale)))
        pieces += [piece[:cut], piece[cut + gap:]]
    return [piece for piece in pieces if len(piece) >= 2]


def pencil_page(page: np.ndarray, drawn: DrawnPlan, pole_mm: Sequence[float],
                rng: np.random.Generator, *, px_per_mm: float = PAGE_PX_PER_MM,
                labels: bool = True) -> np.ndarray:
    """``page`` with ``drawn`` pencilled on it: grey grainy strokes 0.3–0.5 mm wide, a dot or
    a small cross at some points, and each point's label written beside it; the pencil works
    in the window of the page round what it draws."""
    from ..grading.paper import plan_to_page

    def to_px(xy) -> np.ndarray:
        x, y = plan_to_page(pole_mm, xy)      # a pixel's centre is at (i + ½)/px_per_mm
        return np.array([x * px_per_mm - 0.5, y * px_per_mm - 0.5])

    corners = np.array([to_px(xy) for stroke in drawn.strokes for xy in stroke]
                       + [to_px(xy) for xy in drawn.points.values()] + [to_px((0, 0))])
    margin = 10 * px_per_mm
    height, width = page.shape[:2]
    x0, y0 = np.maximum(np.floor(corners.min(axis=0) - margin), 0).astype(int)
    x1 = int(min(math.ceil(corners[:, 0].max() + margin), width))
    y1 = int(min(math.ceil(corners[:, 1].max() + margin), height))
    pencil = _Pencil(np.zeros((y1 - y0, x1 - x0), np.float32), np.array([x0, y0], float),
                     px_per_mm)
    for a, b in drawn.strokes:
        width_mm = rng.uniform(0.3, 0.5)
        strength = rng.uniform(0.55, 0.85)
        for piece in _stroke_polyline(to_px(a), to_px(b), rng, px_per_mm):
            pencil.line(piece, width_mm, strength)
    for label, xy in drawn.points.items():
        centre = to_px(xy)
        pencil.mark(centre, rng.choice(["dot", "cross"] if label in drawn.marked else
                                       ["dot", "cross", "none"]), rng)
        if labels:               # written beside the point, where no line leaves it
            side = _free_side(xy, drawn.strokes, rng)
            pencil.write(label.split("@")[0],
                         centre + 3.5 * px_per_mm * np.array([math.cos(side), -math.sin(side)]),
                         rng)
    grain = rng.uniform(0.75, 1.0, pencil.cover.shape).astype(np.float32)
    graphite = np.array([92, 90, 88], np.float32) / 255.0    # a slightly warm grey (B, G, R)
    paper = page[y0:y1, x0:x1].astype(np.float32)
    alpha = (pencil.cover * grain)[..., None]
    out = page.copy()
    out[y0:y1, x0:x1] = np.clip(paper * (1 - alpha * (1 - graphite)), 0, 255).astype(np.uint8)
    return out


@dataclass
class _Pencil:
    """How much pencil covers each pixel of a window of the page (0…1), the window's
    top-left corner (page px) and the page's px per mm: the pencil draws lines, marks points
    and writes their names on it."""

    cover: np.ndarray
    origin: np.ndarray
    px_per_mm: float
    #: OpenCV draws at 1/2**shift px
    shift: int = 4

    def line(self, points: np.ndarray, thickness_mm: float, strength: float) -> None:
        """A polyline (page px), ``thickness_mm`` wide, ``strength`` dark."""
        import cv2

        thickness = max(1, round(thickness_mm * self.px_per_mm))
        layer = np.zeros_like(self.cover)
        cv2.polylines(layer, [np.round((points - self.origin) * (1 << self.shift)
                                       ).astype(np.int32)], False, 1.0, thickness,
                      cv2.LINE_AA, self.shift)
        np.maximum(self.cover, layer * strength, out=self.cover)

    def mark(self, centre: np.ndarray, shape: str, rng: np.random.Generator) -> None:
        """A ``dot`` or a small ``cross`` at ``centre`` (page px), or ``none``."""
        import cv2

        unit = float(1 << self.shift)
        if shape == "dot":
            radius = rng.uniform(0.5, 0.75) * self.px_per_mm
            cv2.circle(self.cover, tuple(np.round((centre - self.origin) * unit).astype(int)),
                       round(radius * unit), rng.uniform(0.6, 0.85), -1, cv2.LINE_AA,
                       self.shift)
        elif shape == "cross":
            turn = rng.uniform(0, math.pi / 2)
            arm = rng.uniform(1.2, 1.8) * self.px_per_mm
            for angle in (turn, turn + math.pi / 2):
                offset = arm * np.array([math.cos(angle), math.sin(angle)])
                self.line(np.array([centre - offset, centre + offset]), 0.3,
                          rng.uniform(0.6, 0.8))

    def write(self, text: str, middle: np.ndarray, rng: np.random.Generator) -> None:
        """``text`` handwritten round ``middle`` (page px)."""
        import cv2

        at = middle + np.array([-1.2, 1.4]) * self.px_per_mm - self.origin   # the letter's box
        layer = np.zeros(self.cover.shape, np.uint8)
        cv2.putText(layer, text, tuple(int(v) for v in at), cv2.FONT_HERSHEY_SCRIPT_SIMPLEX,
                    0.13 * self.px_per_mm, 255, max(1, int(0.3 * self.px_per_mm)), cv2.LINE_AA)
        np.maximum(self.cover, layer.astype(np.float32) / 255.0 * rng.uniform(0.5, 0.75),
                   out=self.cover)


def _free_side(point, strokes, rng: np.random.Generator) -> float:
    """The direction (radians, plan axes) of the widest gap between the strokes that leave
    ``point``, a little off its middle: where a student writes the point's name."""
    angles = []
    for a, b in strokes:
        for near, far in ((a, b), (b, a)):
            if math.dist(near, point) < 0.5 and math.dist(far, point) > 1.0:
                angles.append(math.atan2(far[1] - near[1], far[0] - near[0]))
            elif math.dist(near, point) >= 0.5 and math.dist(far, point) >= 0.5:
                # a stroke passing through the point leaves it both ways
                direction = np.subtract(far, near)
                offset = np.subtract(point, near)
                if abs(direction[0] * offset[1] - direction[1] * offset[0]) <= 0.5 * np.hypot(
                        *direction) and 0 < offset @ direction < direction @ direction:
                    angle = math.atan2(direction[1], direction[0])
                    angles += [angle, angle + math.pi]
    if not angles:
        return float(rng.uniform(0, 2 * math.pi))
    angles = sorted(angle % (2 * math.pi) for angle in angles)
    gaps = [(angles[(i + 1) % len(angles)] - angles[i]) % (2 * math.pi) or 2 * math.pi
            for i in range(len(angles))]
    widest = int(np.argmax(gaps))
    return angles[widest] + gaps[widest] * float(rng.uniform(0.35, 0.65))


# -- the photo -------------------------------------------------------------------------------
def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    axis = axis / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k


def _camera(conditions: Conditions, page_mm: Sequence[float], size: tuple[int, int]):
    """The camera's rotation and the page centre's distance: the page's points X (mm, page
    centred, z towards the camera) are seen at K (R X + t)."""
    width, height = size
    tilt = math.radians(conditions.tilt_deg)
    towards = math.radians(conditions.tilt_towards_deg)
    spin = _rotation(np.array([0.0, 0.0, 1.0]), math.radians(conditions.rotation_deg))
    lean = _rotation(np.array([math.cos(towards), math.sin(towards), 0.0]), tilt)
    # the camera's axes (x right, y down, z ahead) are the page's (u right, v down, z into
    # the desk) before it leans and turns
    rotation = lean @ spin
    # the distance at which the sheet's outline fills ``fill`` of the picture (its larger
    # share of the width or the height)
    corners = np.array([[-page_mm[0] / 2, -page_mm[1] / 2, 0.0], [page_mm[0] / 2,
                        -page_mm[1] / 2, 0.0], [page_mm[0] / 2, page_mm[1] / 2, 0.0],
                        [-page_mm[0] / 2, page_mm[1] / 2, 0.0]])
    translation = np.array([0.0, 0.0, 1000.0])
    for _ in range(4):            # the outline fills ``fill`` of the picture, in its middle
        seen = _project(corners, rotation, translation, size)
        share = max(np.ptp(seen[:, 0]) / width, np.ptp(seen[:, 1]) / height)
        middle = (seen.min(axis=0) + seen.max(axis=0)) / 2 - np.array([width, height]) / 2
        translation[:2] -= middle * translation[2] / FOCAL_PX
        translation *= share / conditions.fill
    return rotation, translation


def _project(points: np.ndarray, rotation, translation, size) -> np.ndarray:
    camera = points @ rotation.T + translation
    width, height = size
    return np.stack([FOCAL_PX * camera[..., 0] / camera[..., 2] + width / 2,
                     FOCAL_PX * camera[..., 1] / camera[..., 2] + height / 2], axis=-1)


def _surface(u: np.ndarray, v: np.ndarray, page_mm, curl_mm: float) -> np.ndarray:
    """The curled sheet: page mm (u right, v down) → 3-D mm (z into the desk), page
    centred, the long edges lifted ``curl_mm`` (a cylinder's bend across the width)."""
    half = page_mm[0] / 2
    x = u - half
    z = -curl_mm * (x / half) ** 2
    return np.stack([x, v - page_mm[1] / 2, z], axis=-1)


def photograph(page: np.ndarray, page_mm: Sequence[float], conditions: Conditions,
               rng: np.random.Generator, *, px_per_mm: float = PAGE_PX_PER_MM,
               size: tuple[int, int] = PHOTO_SIZE):
    """A phone's photo of ``page`` (its image at ``px_per_mm``) on a desk, taken under
    ``conditions``: (JPEG bytes, a function page mm → photo px)."""
    import cv2

    width, height = size
    rotation, translation = _camera(conditions, page_mm, size)
    # where each photo pixel sees the sheet, on a coarse grid of the photo (the mapping is
    # smooth): the flat sheet's homography inverted, then Newton's method on the curled sheet
    coarse = 8
    grid_w, grid_h = width // coarse + 2, height // coarse + 2
    gx, gy = np.meshgrid(np.arange(grid_w, dtype=np.float64) * coarse,
                         np.arange(grid_h, dtype=np.float64) * coarse)
    inverse = np.linalg.inv(_plane_homography(rotation, translation, page_mm, size))
    guess = np.stack([gx, gy, np.ones_like(gx)], axis=-1) @ inverse.T
    u, v = guess[..., 0] / guess[..., 2], guess[..., 1] / guess[..., 2]

    def seen(u, v):
        return _project(_surface(u, v, page_mm, conditions.curl_mm), rotation, translation,
                        size)

    for _ in range(5 if conditions.curl_mm else 0):
        projected = seen(u, v)
        error_x, error_y = projected[..., 0] - gx, projected[..., 1] - gy
        step = 0.5
        du, dv = (seen(u + step, v) - projected) / step, (seen(u, v + step) - projected) / step
        det = du[..., 0] * dv[..., 1] - dv[..., 0] * du[..., 1]
        u = u - (dv[..., 1] * error_x - dv[..., 0] * error_y) / det
        v = v - (-du[..., 1] * error_x + du[..., 0] * error_y) / det
    # a page pixel's centre is at (i + ½)/px_per_mm mm; remap's at the whole number i
    full_u, full_v = _aligned((u * px_per_mm - 0.5).astype(np.float32),
                              (v * px_per_mm - 0.5).astype(np.float32), coarse, width, height)
    image = _desk(rng, height, width)
    cv2.remap(page, full_u, full_v, cv2.INTER_LINEAR, dst=image,
              borderMode=cv2.BORDER_TRANSPARENT)       # the sheet on the desk
    light = _light(conditions, rng, height, width)
    image = image.astype(np.float32)
    image *= light[..., None]
    image *= np.asarray(conditions.cast, np.float32)
    if conditions.blur_px > 0:
        image = cv2.GaussianBlur(image, (0, 0), conditions.blur_px)
    noise = np.empty_like(image)
    # OpenCV's generator is one for the process (grading seeds it too): seeded from ``rng``,
    # a photo is the same whatever ran before it
    cv2.setRNGSeed(int(rng.integers(0, 2**31 - 1)))
    cv2.randn(noise, 0.0, float(conditions.noise))
    image += noise
    image = np.clip(image, 0, 255).astype(np.uint8)
    ok, jpeg = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, int(conditions.quality)])
    assert ok

    def page_to_photo(points_mm) -> np.ndarray:
        points = np.asarray(points_mm, float)
        return _project(_surface(points[..., 0], points[..., 1], page_mm, conditions.curl_mm),
                        rotation, translation, size)

    return jpeg.tobytes(), page_to_photo


def _aligned(map_u, map_v, coarse: int, width: int, height: int):
    """The coarse maps (sampled at photo px ``coarse·i``) interpolated to every photo px."""
    import cv2

    xs = (np.arange(width, dtype=np.float32) / coarse)
    ys = (np.arange(height, dtype=np.float32) / coarse)
    grid_x = np.broadcast_to(xs[None, :], (height, width))
    grid_y = np.broadcast_to(ys[:, None], (height, width))
    full_u = cv2.remap(map_u, grid_x.astype(np.float32), grid_y.astype(np.float32),
                       cv2.INTER_LINEAR)
    full_v = cv2.remap(map_v, grid_x.astype(np.float32), grid_y.astype(np.float32),
                       cv2.INTER_LINEAR)
    return full_u, full_v


def _plane_homography(rotation, translation, page_mm, size) -> np.ndarray:
    """The flat sheet's homography: page mm (u, v, 1) → photo px (homogeneous)."""
    width, height = size
    camera = np.array([[FOCAL_PX, 0, width / 2], [0, FOCAL_PX, height / 2], [0, 0, 1]])
    offset = np.array([[1, 0, -page_mm[0] / 2], [0, 1, -page_mm[1] / 2], [0, 0, 1]])
    extrinsic = np.column_stack([rotation[:, 0], rotation[:, 1], translation])
    return camera @ extrinsic @ offset


def _desk(rng: np.random.Generator, height: int, width: int) -> np.ndarray:
    """A wooden desk (uint8, B G R): brown, with a grain along it."""
    import cv2

    base = np.array([60, 95, 140], np.float32) * rng.uniform(0.8, 1.1)
    grain = rng.normal(0, 1, (height // 16 + 1, 8)).astype(np.float32)
    grain = cv2.GaussianBlur(grain, (0, 0), 2)
    small = np.clip(base[None, None, :] * (1 + 0.12 * grain[..., None]), 0, 255)
    return cv2.resize(small.astype(np.uint8), (width, height), interpolation=cv2.INTER_LINEAR)


def _light(conditions: Conditions, rng: np.random.Generator, height: int, width: int
           ) -> np.ndarray:
    """The light over the photo: a smooth slope from one side to the other, and a soft-edged
    shadow (a hand's or the phone's) over part of it."""
    import cv2

    small = (height // 8, width // 8)
    ys, xs = np.mgrid[0:small[0], 0:small[1]].astype(np.float32)
    angle = rng.uniform(0, 2 * math.pi)
    slope = (xs / small[1] - 0.5) * math.cos(angle) + (ys / small[0] - 0.5) * math.sin(angle)
    light = 1.0 - conditions.light * (slope + 0.5)
    # the shadow: a wide band whose edge crosses the sheet somewhere
    edge_angle = rng.uniform(0, 2 * math.pi)
    offset = rng.uniform(-0.25, 0.25)
    side = ((xs / small[1] - 0.5) * math.cos(edge_angle)
            + (ys / small[0] - 0.5) * math.sin(edge_angle) - offset)
    soft = 0.04
    shade = 1.0 - conditions.shadow / (1.0 + np.exp(-side / soft))
    out = (light * shade).astype(np.float32)
    return cv2.resize(out, (width, height), interpolation=cv2.INTER_LINEAR)


def sheet_photo(key: Mapping[str, Any], plan: str, construction: str | None = None,
                label: str | None = None, *, seed: int = 0,
                conditions: Conditions | None = None, labels: bool = True,
                pages: int | None = None, page: np.ndarray | None = None) -> SheetPhoto:
    """A phone photo of ``key``'s blank ``plan`` sheet with the plan drawn on it by the right
    construction (``construction`` None) or by a named mistake; ``conditions`` at random from
    ``seed`` unless given. The page says it is of ``pages`` (default: the last of this
    student's sheets)."""
    from ..grading.paper import read_sheet
    from ..grading.sheets import paper_plan_sheet

    rng = np.random.default_rng(seed)
    if conditions is None:
        conditions = Conditions.random(rng)
    sheet = read_sheet(key, plan)
    if page is None:
        last = max(entry["page"] for entry in key["sheets"].values())
        page = page_image(paper_plan_sheet(key, sheet, pages or last))
    drawn = drawn_plan(key, plan, construction, label)
    drawn_page = pencil_page(page, drawn, sheet.pole_mm, rng, labels=labels)
    jpeg, page_to_photo = photograph(drawn_page, sheet.page_mm, conditions, rng)
    return SheetPhoto(jpeg, drawn, conditions, page_to_photo)
