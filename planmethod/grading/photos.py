"""Grading a drawn plan from a phone photo of its sheet (``planmethod grade --photo``).

A photo is read in steps, each of which may refuse it in one line (:class:`PhotoError`):

1. **the sheet** — the four ArUco markers near its corners (:data:`~planmethod.grading.paper.
   MARKER_DICTIONARY`) are found and their corners give the homography from the photo to the
   page's millimetres; the photo is refused if a marker is missing, if it is too dark or too
   blurred to read, if the camera was more than :data:`MAX_TILT_DEG` off straight above the
   sheet, or if the sheet is too small in it;
2. **which sheet** — the QR code, read from the rectified page, names the course, the student,
   the plan and the angle; a sheet that is not in the key (another course, a student the key
   does not have, a check value that does not match) is refused;
3. **the paper's curl** — the printed millimetre grid, found in the rectified page by its
   colour, measures how far a curled sheet departs from the homography; a smooth field fitted
   to it corrects every position found (:class:`Correction`);
4. **the pencil** — dark, colourless strokes are separated from the light blue grid, straight
   strokes are found and fitted (:func:`find_strokes`), and the points a student marks are
   where two strokes meet or cross, a dot, or a small cross (:func:`find_points`); where
   the lines reaching a point meet too shallowly to place it, the dot drawn there does;
5. **the grade** — each point of the key's plan is looked for at its right place, then at each
   place a named mistake puts it (within the point's own tolerance radius, or a mistake's
   place within the photo's measuring error where that is wider), and the points so found are
   graded by :func:`~planmethod.grading.drawings.grade_drawing`, exactly as a drawn plan given
   to ``grade --drawing``: the same verdicts, the same sentences.

Needs OpenCV (``opencv-python-headless``, the ``paper`` extra).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from typing import Any

import numpy as np

from ..io import read_bytes_bounded
from ..words import Message, message
from .drawings import Drawing, SubmissionError, grade_drawing
from .paper import (
    MARKER_CENTRES,
    MARKER_DICTIONARY,
    MARKER_MM,
    QR_MM,
    PhotoError,
    Sheet,
    check_value,
    page_to_plan,
    plan_to_page,
    read_sheet,
    read_sheet_code,
)
from .plan_points import graded_labels
from .results import GradedDrawing
from .sheet_area import DRAWING_MM

__all__ = ["MAX_PHOTO_BYTES", "MAX_TILT_DEG", "Correction", "GradedPhoto", "PhotoReading",
           "PointPlace", "Stroke", "find_points", "find_strokes", "grade_photo", "read_photo"]

#: the largest photo file read (bytes) and the most pixels decoded
MAX_PHOTO_BYTES = 40_000_000
MAX_PIXELS = 80_000_000
#: the most a camera may look off straight above the sheet (degrees): the generated photos
#: of the benchmark go to 30°, this leaves room for the estimate's error
MAX_TILT_DEG = 35.0
#: the fewest photo pixels per millimetre of the sheet (where it is smallest)
MIN_PX_PER_MM = 4.0
#: the widest a sharp edge may spread (mm, 10 % to 90 %): wider is too blurred to grade
MAX_EDGE_MM = 0.8
#: the dimmest the paper may be (of 255)
MIN_PAPER_LEVEL = 60.0
#: the farthest apart a marker's corners may lie from one flat sheet's (mm)
MAX_MARKER_ERROR_MM = 1.0
#: how much darker than the paper a pencil line is at least (the grid's lines are about half
#: as dark)
PENCIL_DARKNESS = 0.2
#: the rectified page's resolution (pixels per mm)
RECTIFIED_PX_PER_MM = 10.0
#: nothing is read this near the pole (mm): its printed ring, and the lines that leave it
POLE_ROOM_MM = 3.5
#: how far a photo may misplace a point (mm): the error of the benchmark's harder photos
#: (tilted, blurred), within which a mistake's place is looked for and named where the
#: point's tolerance is tighter; never a tolerance of the right place
MEASURING_MM = 0.3
#: how far (mm) a point is looked for beyond its tolerance disc when neither its right place
#: nor a mistake's holds a mark: the nearest mark within it is taken as the student's point
SEARCH_MM = 4.0

def _corner_name(number: int) -> Message:
    return (message("top left"), message("top right"), message("bottom left"),
            message("bottom right"))[number]


# -- 1. the sheet in the photo ----------------------------------------------------------------
@dataclass(frozen=True)
class PhotoReading:
    """A photo's sheet: the homography from the photo (px) to the page (mm), how the photo
    was taken, and the QR code's text."""

    source: str
    image: Any = field(repr=False)
    to_page: np.ndarray = field(repr=False)
    tilt_deg: float = 0.0
    px_per_mm: float = 0.0
    edge_mm: float = 0.0
    paper_level: float = 0.0
    code_text: str = ""

    @property
    def to_photo(self) -> np.ndarray:
        """The homography from the page (mm) to the photo (px)."""
        return np.linalg.inv(self.to_page)


def _decode(data: bytes, source: str):
    import cv2

    try:
        from PIL import Image

        with Image.open(__import__("io").BytesIO(data)) as probe:
            width, height = probe.size
    except Exception:
        width = height = None
    if width is not None and width * height > MAX_PIXELS:
        raise PhotoError(message("the photo has {pixels:.0f} megapixels, at most {limit:.0f} "
                                 "are read", pixels=width * height / 1e6,
                                 limit=MAX_PIXELS / 1e6), file=source)
    image = cv2.imdecode(np.frombuffer(data, np.uint8), cv2.IMREAD_COLOR)
    if image is None or image.ndim != 3 or min(image.shape[:2]) < 16:
        raise PhotoError(message("not a photo that can be read (a JPEG or PNG image is "
                                 "expected)"), file=source)
    return image


def _detector():
    import cv2

    parameters = cv2.aruco.DetectorParameters()
    return cv2.aruco.ArucoDetector(
        cv2.aruco.getPredefinedDictionary(getattr(cv2.aruco, MARKER_DICTIONARY)), parameters)


def _markers(gray: np.ndarray) -> dict[int, np.ndarray]:
    """The sheet's markers found (id → its four corners, photo px, OpenCV's order): looked for
    in the photo scaled down to 1800 px (quick), and at full size if some are missing there
    (a marker far off in a tilted photo is small)."""
    import cv2

    found: dict[int, np.ndarray] = {}
    for longest in (1800.0, math.inf):
        scale = min(1.0, longest / max(gray.shape))
        small = cv2.resize(gray, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA) \
            if scale < 1.0 else gray
        corners, ids, _ = _detector().detectMarkers(small)
        for quad, number in zip(corners, () if ids is None else ids.ravel(), strict=True):
            number = int(number)
            if number not in range(len(MARKER_CENTRES)):
                continue
            points = quad.reshape(4, 2).astype(np.float32) / scale
            if number not in found or _side(points) > _side(found[number]):
                found[number] = points
        if len(found) == len(MARKER_CENTRES) or scale == 1.0:
            break
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 40, 0.01)
    for number, points in found.items():
        window = max(2, min(12, int(_side(points) / 12)))
        found[number] = cv2.cornerSubPix(gray, points.reshape(-1, 1, 2), (window, window),
                                         (-1, -1), criteria).reshape(4, 2)
    return found


def _side(points: np.ndarray) -> float:
    return float(np.mean(np.hypot(*(points - np.roll(points, 1, axis=0)).T)))


def _marker_corners_mm(number: int) -> np.ndarray:
    x, y = MARKER_CENTRES[number]
    half = MARKER_MM / 2
    return np.array([(x - half, y - half), (x + half, y - half), (x + half, y + half),
                     (x - half, y + half)], np.float64)


def _apply(homography: np.ndarray, points) -> np.ndarray:
    points = np.asarray(points, np.float64).reshape(-1, 2)
    mapped = np.column_stack([points, np.ones(len(points))]) @ homography.T
    return mapped[:, :2] / mapped[:, 2:3]


def _tilt(to_photo: np.ndarray, size: tuple[int, int]) -> float:
    """How far (degrees) the camera looked off the sheet's normal, from the homography page →
    photo: its focal length estimated from the homography where that is well posed, else a
    phone's (0.75 of the long side), the principal point at the photo's centre."""
    height, width = size
    shift = np.array([[1.0, 0.0, -width / 2], [0.0, 1.0, -height / 2], [0.0, 0.0, 1.0]])
    h = shift @ to_photo
    h = h / np.linalg.norm(h[:, 0])
    a1 = h[0, 0] * h[0, 1] + h[1, 0] * h[1, 1]
    b1 = h[2, 0] * h[2, 1]
    a2 = h[0, 0] ** 2 + h[1, 0] ** 2 - h[0, 1] ** 2 - h[1, 1] ** 2
    b2 = h[2, 0] ** 2 - h[2, 1] ** 2
    long_side = max(width, height)
    focal = 0.75 * long_side
    denominator = b1 * b1 + b2 * b2
    if denominator > 0:
        squared = -(a1 * b1 + a2 * b2) / denominator
        if squared > 0 and 0.4 * long_side <= math.sqrt(squared) <= 2.5 * long_side:
            focal = math.sqrt(squared)
    inverse = np.diag([1 / focal, 1 / focal, 1.0])
    r1, r2 = inverse @ h[:, 0], inverse @ h[:, 1]
    r1, r2 = r1 / np.linalg.norm(r1), r2 / np.linalg.norm(r2)
    normal = np.cross(r1, r2)
    return math.degrees(math.acos(min(1.0, abs(normal[2]) / np.linalg.norm(normal))))


def _smallest_scale(to_photo: np.ndarray) -> float:
    """Photo px per page mm where the drawing area is seen smallest (its corners)."""
    left, top, right, bottom = DRAWING_MM
    least = math.inf
    for x, y in ((left, top), (right, top), (left, bottom), (right, bottom)):
        centre = _apply(to_photo, [(x, y), (x + 1, y), (x, y + 1)])
        jacobian = np.column_stack([centre[1] - centre[0], centre[2] - centre[0]])
        least = min(least, float(np.linalg.svd(jacobian, compute_uv=False)[-1]))
    return least


def _edge_and_paper(gray: np.ndarray, to_photo: np.ndarray, found: Sequence[int]
                    ) -> tuple[float, float]:
    """How wide (mm, 10–90 %) the markers' outer edges spread, and the paper's level beside
    them (of 255)."""
    import cv2

    offsets = np.arange(-1.5, 1.5001, 0.05)
    widths, papers = [], []
    half = MARKER_MM / 2
    for number in found:
        cx, cy = MARKER_CENTRES[number]
        for nx, ny in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            # along the middle half of the edge whose outward normal is (nx, ny)
            along = np.linspace(-half * 0.5, half * 0.5, 15)[:, None]
            xs = cx + nx * half - ny * along + nx * offsets[None, :]
            ys = cy + ny * half + nx * along + ny * offsets[None, :]
            mapped = _apply(to_photo, np.column_stack([xs.ravel(), ys.ravel()]))
            samples = cv2.remap(gray, mapped[:, 0].reshape(xs.shape).astype(np.float32),
                                mapped[:, 1].reshape(xs.shape).astype(np.float32),
                                cv2.INTER_LINEAR)
            profile = samples.astype(np.float64).mean(axis=0)
            dark, light = profile[:8].mean(), profile[-8:].mean()
            papers.append(light)
            if light - dark < 20:
                continue
            level = (profile - dark) / (light - dark)
            low = np.argmax(level >= 0.1)
            high = np.argmax(level >= 0.9)
            widths.append(max(0.0, (high - low) * 0.05))
    edge = float(np.median(widths)) if widths else math.inf
    return edge, float(np.median(papers)) if papers else 0.0


def _sharpness_px(gray: np.ndarray) -> float:
    """The blur (Gaussian σ, px) of the photo's sharpest edges, without knowing the sheet:
    an edge's contrast over its steepest slope (for a photo whose markers were not found)."""
    import cv2

    scale = min(1.0, 1800.0 / max(gray.shape))
    small = cv2.resize(gray, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA) \
        if scale < 1.0 else gray
    image = small.astype(np.float32)
    gx = cv2.Sobel(image, cv2.CV_32F, 1, 0, ksize=3) / 8.0
    gy = cv2.Sobel(image, cv2.CV_32F, 0, 1, ksize=3) / 8.0
    slope = np.hypot(gx, gy)
    kernel = np.ones((9, 9), np.uint8)
    contrast = (cv2.dilate(small, kernel).astype(np.float32)
                - cv2.erode(small, kernel).astype(np.float32))
    strong = slope > np.percentile(slope, 99.8)
    if not strong.any():
        return math.inf
    ratio = contrast[strong] / np.maximum(slope[strong], 1e-3)
    return float(np.median(ratio)) / math.sqrt(2 * math.pi) / scale


def _qr_text(image: np.ndarray, to_page: np.ndarray) -> str:
    """The QR code's text, read from its square of the page rectified at a few resolutions
    (cut close, then given a white quiet zone: the grid above it is kept out), by OpenCV's two
    QR readers in turn; empty if neither reads it."""
    import cv2

    left, top, side = QR_MM
    readers = (cv2.QRCodeDetectorAruco(), cv2.QRCodeDetector())
    for resolution in (8.0, 12.0, 5.0):
        margin = 1.5
        placed = np.array([[resolution, 0, -resolution * (left - margin)],
                           [0, resolution, -resolution * (top - margin)], [0, 0, 1]])
        size = round((side + 2 * margin) * resolution)
        crop = cv2.warpPerspective(image, placed @ to_page, (size, size),
                                   flags=cv2.INTER_LINEAR, borderValue=(255, 255, 255))
        gray = cv2.cvtColor(crop, cv2.COLOR_BGR2GRAY)
        quiet = round(4 * resolution)
        gray = cv2.copyMakeBorder(gray, quiet, quiet, quiet, quiet, cv2.BORDER_CONSTANT,
                                  value=255)
        for reader in readers:
            text, _, _ = reader.detectAndDecode(gray)
            if text:
                return text
    return ""


def read_photo(data: bytes, source: str) -> PhotoReading:
    """Find the sheet in a photo: its markers, the homography to the page, and its QR code's
    text; refuse, in one line, a photo that cannot be read (see the module notes)."""
    import cv2

    image = _decode(data, source)
    gray = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
    found = _markers(gray)
    if len(found) < len(MARKER_CENTRES):
        if float(np.percentile(gray, 99)) < MIN_PAPER_LEVEL:
            raise PhotoError(message("the photo is too dark to read the sheet: photograph it "
                                     "in better light"), file=source)
        if _sharpness_px(gray) > max(3.0, 0.0011 * max(gray.shape)):
            raise PhotoError(message("the photo is too blurred to read the sheet: hold the "
                                     "phone still and let it focus"), file=source)
        missing = [_corner_name(number) for number in range(len(MARKER_CENTRES))
                   if number not in found]
        raise PhotoError(message("the photo shows {found} of the sheet's 4 corner squares "
                                 "(not the {missing}): photograph the whole sheet, all four "
                                 "in view", found=len(found), missing=missing), file=source)
    photo = np.concatenate([found[number] for number in sorted(found)])
    page = np.concatenate([_marker_corners_mm(number) for number in sorted(found)])
    to_page, _ = cv2.findHomography(photo.astype(np.float64), page, 0)
    if to_page is None:
        raise PhotoError(message("the corner squares do not lie on one sheet"), file=source)
    error = float(np.max(np.hypot(*(_apply(to_page, photo) - page).T)))
    if error > MAX_MARKER_ERROR_MM:
        raise PhotoError(message("the corner squares do not lie on one flat sheet ({error:.1f} "
                                 "mm off): lay the sheet flat", error=error), file=source)
    to_photo = np.linalg.inv(to_page)
    tilt = _tilt(to_photo, gray.shape)
    if tilt > MAX_TILT_DEG:
        raise PhotoError(message("the sheet is photographed {tilt:.0f}° off straight above "
                                 "(at most {limit:.0f}°): hold the phone over the sheet",
                                 tilt=tilt, limit=MAX_TILT_DEG), file=source)
    resolution = _smallest_scale(to_photo)
    if resolution < MIN_PX_PER_MM:
        raise PhotoError(message("the sheet is too small in the photo ({resolution:.1f} pixels "
                                 "a millimetre, at least {limit:g}): come closer",
                                 resolution=resolution, limit=MIN_PX_PER_MM), file=source)
    edge, paper = _edge_and_paper(gray, to_photo, sorted(found))
    if paper < MIN_PAPER_LEVEL:
        raise PhotoError(message("the photo is too dark to read the sheet: photograph it in "
                                 "better light"), file=source)
    if edge > MAX_EDGE_MM:
        raise PhotoError(message("the photo is too blurred to read the sheet (edges spread over "
                                 "{width:.1f} mm, at most {limit:g}): hold the phone still and "
                                 "let it focus", width=edge, limit=MAX_EDGE_MM), file=source)
    text = _qr_text(image, to_page)
    if not text:
        raise PhotoError(message("the sheet's QR code cannot be read: keep it uncovered, in "
                                 "view and in focus"), file=source)
    return PhotoReading(source, image, to_page, tilt, resolution, edge, paper, text)


# -- 2. which sheet ---------------------------------------------------------------------------
def sheet_of(reading: PhotoReading, keys: Mapping[str, Mapping[str, Any]], key_source: str
             ) -> tuple[Mapping[str, Any], Sheet]:
    """The key and the sheet a photo's QR code names; refused in one line if the key does not
    have that sheet."""
    code = read_sheet_code(reading.code_text)
    source = reading.source
    if code is None:
        raise PhotoError(message("the QR code is not a planmethod sheet's"), file=source)
    key = keys.get(code.student)
    if key is None or code.student == "*":
        raise PhotoError(message("the sheet is of student {student}, who is not in {key}",
                                 student=code.student, key=key_source), file=source)
    sheets = key.get("sheets")
    recorded = sheets.get(code.plan) if isinstance(sheets, Mapping) else None
    course = (read_sheet_code(str(recorded.get("qr", ""))) if isinstance(recorded, Mapping)
              else None)
    if course is None:
        said = (message("{key} records no velocity plan sheet of student {student}: run "
                        "`planmethod variants` again and print its booklet", key=key_source,
                        student=code.student) if code.plan == "velocity" else
                message("{key} records no acceleration plan sheet of student {student}: run "
                        "`planmethod variants` again and print its booklet", key=key_source,
                        student=code.student))
        raise PhotoError(said, file=source)
    if course.course != code.course:
        raise PhotoError(message("the sheet is of another course ({sheet}; {key} is of "
                                 "{course})", sheet=code.course, key=key_source,
                                 course=course.course), file=source)
    if code.check != course.check or code.check != check_value(code.course, key, code.plan):
        raise PhotoError(message("the sheet's check value {check} does not match {key}: it was "
                                 "printed from another version of the course",
                                 check=code.check, key=key_source), file=source)
    return key, read_sheet(key, code.plan, file=key_source)


# -- 3. the paper's curl ----------------------------------------------------------------------
@dataclass(frozen=True)
class Correction:
    """How far the rectified page departs from the true page: a smooth field (mm) fitted to
    the printed grid's lines, ``true = rectified − field(rectified)``."""

    centre: tuple[float, float]
    x_terms: np.ndarray = field(repr=False)
    y_terms: np.ndarray = field(repr=False)
    samples: int = 0
    rms_mm: float = 0.0

    def true(self, points: np.ndarray) -> np.ndarray:
        """Rectified page mm → true page mm."""
        points = np.asarray(points, np.float64).reshape(-1, 2)
        basis = _basis(points, self.centre)
        return points - np.column_stack([basis @ self.x_terms, basis @ self.y_terms])

    def seen(self, points: np.ndarray) -> np.ndarray:
        """True page mm → rectified page mm (where the homography put them)."""
        points = np.asarray(points, np.float64).reshape(-1, 2)
        out = points.copy()
        for _ in range(4):
            out = points + (out - self.true(out))
        return out


def _basis(points: np.ndarray, centre) -> np.ndarray:
    u = (points[:, 0] - centre[0]) / 100.0
    v = (points[:, 1] - centre[1]) / 100.0
    return np.column_stack([np.ones_like(u), u, v, u * u, u * v, v * v, u ** 3, u * u * v,
                            u * v * v, v ** 3])


def _line_peaks(profile: np.ndarray, expected: Sequence[float], origin: float,
                resolution: float) -> list[tuple[float, float]]:
    """Where a grid line's peak lies in ``profile`` near each expected position (mm): (the
    expected position, the offset found), for peaks that stand out."""
    out = []
    reach = int(3.5 * resolution)
    for position in expected:
        index = (position - origin) * resolution - 0.5
        low, high = round(index) - reach, round(index) + reach + 1
        if low < 0 or high > len(profile):
            continue
        window = profile[low:high]
        peak = int(np.argmax(window))
        floor = float(np.median(window))
        height = float(window[peak]) - floor
        if height < 6.0 or peak < 2 or peak > len(window) - 3:
            continue
        around = window[peak - 2:peak + 3] - floor
        weights = np.clip(around, 0, None)
        offset = float(np.sum(weights * np.arange(-2, 3)) / max(weights.sum(), 1e-9))
        found = (low + peak + offset + 0.5) / resolution + origin
        out.append((position, found - position))
    return out


def measure_curl(rectified: np.ndarray, sheet: Sheet, resolution: float,
                 box: Sequence[float]) -> Correction:
    """The correction of a rectified page (``rectified``: the area ``box`` of the page, mm,
    at ``resolution`` px/mm) measured on its grid's 10 mm lines: each line's place in bands
    between the lines across it, the median over each band's rows or columns (a pencil line
    crossing the band moves it little), a robust fit over all (a pencil line drawn along a grid
    line is left out)."""
    import cv2

    left, top, right, bottom = box
    # the luminance, which a JPEG keeps at full resolution (its colour at half)
    signal = 255.0 - cv2.cvtColor(rectified, cv2.COLOR_BGR2GRAY).astype(np.float32)
    px, py = sheet.pole_mm
    samples_x, samples_y = [], []
    vertical = [px + 10 * k for k in range(math.ceil((left + 3 - px) / 10),
                                           math.floor((right - 3 - px) / 10) + 1)]
    horizontal = [py + 10 * k for k in range(math.ceil((top + 3 - py) / 10),
                                             math.floor((bottom - 3 - py) / 10) + 1)]
    for low, high in itertools.pairwise(horizontal):
        rows = slice(int((low + 1.5 - top) * resolution), int((high - 1.5 - top) * resolution))
        profile = np.median(signal[rows], axis=0)
        middle = (low + high) / 2
        samples_x += [(x, middle, offset) for x, offset in
                      _line_peaks(profile, vertical, left, resolution)]
    for low, high in itertools.pairwise(vertical):
        columns = slice(int((low + 1.5 - left) * resolution),
                        int((high - 1.5 - left) * resolution))
        profile = np.median(signal[:, columns], axis=1)
        middle = (low + high) / 2
        samples_y += [(middle, y, offset) for y, offset in
                      _line_peaks(profile, horizontal, top, resolution)]
    centre = (px, py)
    x_terms, rms_x = _robust_fit(samples_x, centre)
    y_terms, rms_y = _robust_fit(samples_y, centre)
    return Correction(centre, x_terms, y_terms, len(samples_x) + len(samples_y),
                      max(rms_x, rms_y))


def _robust_fit(samples, centre) -> tuple[np.ndarray, float]:
    """A smooth field fitted to (x, y, offset) samples, outliers (a pencil line along a grid
    line) left out; no samples: no correction."""
    if len(samples) < 12:
        return np.zeros(10), math.inf
    data = np.asarray(samples, np.float64)
    basis = _basis(data[:, :2], centre)
    keep = np.ones(len(data), bool)
    terms = np.zeros(10)
    for _ in range(3):
        count = basis[keep].shape[0]
        columns = 10 if count >= 40 else 6 if count >= 20 else 3
        solution, *_ = np.linalg.lstsq(basis[keep][:, :columns], data[keep, 2], rcond=None)
        terms = np.zeros(10)
        terms[:columns] = solution
        residual = data[:, 2] - basis @ terms
        spread = 1.4826 * float(np.median(np.abs(residual[keep] - np.median(residual[keep]))))
        keep = np.abs(residual) <= max(3.0 * spread, 0.05)
    rms = float(np.sqrt(np.mean((data[keep, 2] - basis[keep] @ terms) ** 2)))
    return terms, rms


# -- 4. the pencil ----------------------------------------------------------------------------
@dataclass(frozen=True)
class Stroke:
    """A straight pencil stroke in the rectified page (mm): a point on it, its unit direction,
    its extent along that direction (``start``, ``stop``) and how straight it is (rms, mm)."""

    point: tuple[float, float]
    direction: tuple[float, float]
    start: float
    stop: float
    rms_mm: float

    @property
    def length(self) -> float:
        return self.stop - self.start

    def at(self, along: float) -> np.ndarray:
        return np.asarray(self.point) + along * np.asarray(self.direction)


def _darkness(rectified: np.ndarray, resolution: float) -> np.ndarray:
    """How much darker than the paper round it each pixel is (0…1), in the brightest channel:
    the light blue grid barely darkens it, a grey pencil line does. The paper's level is the
    median over 8 mm round each place (where lines crowd, they are still too few to move it),
    taken at 2 px/mm and smoothed back."""
    import cv2

    brightest = cv2.GaussianBlur(rectified.max(axis=2), (0, 0), 0.6)
    height, width = brightest.shape
    factor = max(1, round(resolution / 2.0))
    small = cv2.resize(brightest, (max(1, width // factor), max(1, height // factor)),
                       interpolation=cv2.INTER_AREA)
    paper = cv2.medianBlur(small, 17)
    paper = cv2.resize(paper, (width, height), interpolation=cv2.INTER_LINEAR).astype(np.float32)
    return np.clip(1.0 - brightest.astype(np.float32) / np.maximum(paper, 1.0), 0.0, 1.0)


def _pencil_pixels(darkness: np.ndarray, sheet: Sheet, box, resolution: float,
                   threshold: float):
    """The pencil's pixels (mm, rectified page) and their darkness, the printed pole and its
    name left out: the ring round the pole, and in the box where the name is printed, what
    lies within 0.4 mm of printed ink (darker than pencil is: :data:`PRINTED_DARKNESS`) or
    within 4.5 mm of the pole (where the lines that leave it crowd), so that a line drawn
    past the name, or a point drawn beside it, is still read."""
    import cv2

    left, top, right, bottom = box
    mask = darkness > threshold
    px, py = sheet.pole_mm
    name = (px - 7.5, py - 7.8, px - 1.2, py - 0.6)          # where the name is printed
    first = (max(0, int((name[0] - left) * resolution)), max(0, int((name[1] - top) * resolution)))
    last = (max(0, int((name[2] - left) * resolution) + 1),
            max(0, int((name[3] - top) * resolution) + 1))
    ink = darkness[first[1]:last[1], first[0]:last[0]] > PRINTED_DARKNESS
    if ink.size:
        reach = 2 * round(0.4 * resolution) + 1
        ink = cv2.dilate(ink.astype(np.uint8), cv2.getStructuringElement(
            cv2.MORPH_ELLIPSE, (reach, reach))).astype(bool)
        rows, columns = np.mgrid[first[1]:last[1], first[0]:last[0]]
        near = np.hypot(left + (columns + 0.5) / resolution - px,
                        top + (rows + 0.5) / resolution - py) < 4.5
        mask[first[1]:last[1], first[0]:last[0]] &= ~(ink | near)
    rows, columns = np.nonzero(mask)
    xs = left + (columns + 0.5) / resolution
    ys = top + (rows + 0.5) / resolution
    keep = np.hypot(xs - px, ys - py) > 2.4                       # the pole's ring
    keep &= (xs > left + 1.0) & (xs < right - 1.0) & (ys > top + 1.0) & (ys < bottom - 1.0)
    return np.column_stack([xs[keep], ys[keep]]), darkness[rows[keep], columns[keep]]


#: printed ink is darker than this (of 1: black); a pencil line, grey, is lighter
PRINTED_DARKNESS = 0.72


def find_strokes(points: np.ndarray, weights: np.ndarray, resolution: float,
                 origin: Sequence[float], shape: tuple[int, int],
                 darkness: np.ndarray | None = None) -> list[Stroke]:
    """The straight strokes among the pencil's pixels (mm), one at a time: the longest
    segment a probabilistic Hough transform finds among the pixels left is fitted to the
    pixels along it (weighted by their darkness, far ones weighed down) and its pixels are
    taken away, until no segment of 2 mm is left; then pieces of one line are joined, each
    stroke is grown over the pixels on its course, and moved onto the middle of its pencil
    line (:func:`_polished`). The transform draws at random: its generator is seeded first,
    so that a photo is graded the same whatever was graded before it in the process."""
    import cv2

    cv2.setRNGSeed(20261129)
    left = np.ones(len(points), bool)
    lines: list[Stroke] = []
    cells = np.column_stack([((points[:, 0] - origin[0]) * resolution - 0.5).round(),
                             ((points[:, 1] - origin[1]) * resolution - 0.5).round()]
                            ).astype(int) if len(points) else np.zeros((0, 2), int)
    for _ in range(80):
        if left.sum() < 8:
            break
        chosen = cells[left]
        low = chosen.min(axis=0)
        size = chosen.max(axis=0) - low + 1
        mask = np.zeros((size[1], size[0]), np.uint8)
        mask[chosen[:, 1] - low[1], chosen[:, 0] - low[0]] = 255
        segments = cv2.HoughLinesP(mask, 1, math.pi / 720, int(1.6 * resolution),
                                   minLineLength=int(2.0 * resolution),
                                   maxLineGap=int(1.2 * resolution))
        if segments is None:
            break
        segments = segments.reshape(-1, 4).astype(np.float64)
        x1, y1, x2, y2 = segments[int(np.argmax(np.hypot(segments[:, 2] - segments[:, 0],
                                                           segments[:, 3] - segments[:, 1])))]
        a = np.array([origin[0] + (x1 + low[0] + 0.5) / resolution,
                      origin[1] + (y1 + low[1] + 0.5) / resolution])
        b = np.array([origin[0] + (x2 + low[0] + 0.5) / resolution,
                      origin[1] + (y2 + low[1] + 0.5) / resolution])
        line = _segment_stroke(a, b)
        for _ in range(2):
            near = left & _on(line, points, _BAND_MM)
            if near.sum() < 8:
                break
            fitted = _fit(points[near], weights[near])
            line = _extent(fitted, points[left]) if fitted is not None else line
        taken = left & _on(line, points, max(0.3, 2.5 * line.rms_mm))
        if not taken.any():
            taken = left & _on(_segment_stroke(a, b), points, 0.3)
        if not taken.any():
            break
        left &= ~taken
        lines.append(line)
    lines = _merged(lines, points, weights)
    lines = [_reaching(line, points) for line in lines]
    lines = [line for line in lines if line.length >= 1.5 and line.rms_mm <= 0.3]
    lines = _unique(lines, points, None if darkness is None else
                    [_track_darkness(line, darkness, origin, resolution) for line in lines])
    if darkness is not None:
        lines = [_polished(line, lines, darkness, origin, resolution) for line in lines]
    return lines


def _unique(lines: Sequence[Stroke], points: np.ndarray, dark: Sequence[float] | None = None,
            *, band_mm: float = 0.3, share: float = 0.75) -> list[Stroke]:
    """``lines`` without those whose pixels the others hold. First a line between two that
    leave a point a few degrees apart (:func:`_doubled`): their pencil runs together near it,
    and a line fitted to both at once (found besides each) would move where they cross another;
    then the least dark along their course (``dark``: :func:`_track_darkness`; else the least
    straight): the lines fitted to the edges of a line drawn twice over run on lighter pencil
    than the one along its middle."""
    kept = list(lines)
    order = [-line.rms_mm for line in lines] if dark is None else list(dark)
    for index in sorted(range(len(lines)),
                        key=lambda index: (_doubled(lines[index], lines) != "between",
                                           order[index])):
        line = lines[index]
        mine = _on(line, points, band_mm)
        if not mine.any():
            continue
        others = np.zeros(len(points), bool)
        for other in kept:
            if other is not line:
                others |= _on(other, points, band_mm)
        if (mine & others).sum() >= share * mine.sum():
            kept.remove(line)
    return kept


def _track_darkness(line: Stroke, darkness: np.ndarray, origin: Sequence[float],
                    resolution: float) -> float:
    """The median darkness under ``line`` (every 0.25 mm along it): high on a pencil line's
    middle, lower along its edge or between two lines.

    >>> line = Stroke((1.0, 1.5), (1.0, 0.0), 0.0, 2.0, 0.1)
    >>> darkness = np.zeros((30, 40), np.float32); darkness[14:16] = 0.8
    >>> _track_darkness(line, darkness, (0.0, 0.0), 10.0)
    0.8
    """
    import cv2

    along = np.arange(line.start, line.stop + 1e-9, 0.25)
    centres = np.asarray(line.point) + along[:, None] * np.asarray(line.direction)
    columns = ((centres[:, 0] - origin[0]) * resolution - 0.5).astype(np.float32)
    rows = ((centres[:, 1] - origin[1]) * resolution - 0.5).astype(np.float32)
    sampled = cv2.remap(darkness, columns[None, :], rows[None, :], cv2.INTER_LINEAR,
                        borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    return round(float(np.median(sampled)), 6)


def _doubled(line: Stroke, lines: Sequence[Stroke], *, angle_deg: float = 3.0,
             ends_mm: float = 1.5, across_mm: float = 0.6) -> str | None:
    """Whether ``line`` runs between two nearly parallel lines within its extent, one each
    side: ``"doubled"`` along the middle of a line drawn twice over (a construction line and
    the vector read along it, or two drawn from one point along one course; its pencil is found
    as three lines, the two along its edges as long as each other), else ``"between"`` two
    lines that leave a point a few degrees apart (not as long as each other); else None.

    >>> middle = Stroke((0.0, 0.0), (1.0, 0.0), 0.0, 18.0, 0.12)
    >>> edges = [Stroke((0.0, y), (1.0, 0.0), 0.3, 12.2, 0.05) for y in (-0.3, 0.35)]
    >>> _doubled(middle, [middle, *edges]), _doubled(edges[0], [middle, *edges])
    ('doubled', None)
    """
    direction = np.asarray(line.direction)
    normal = np.array([-direction[1], direction[0]])
    middle = line.at((line.start + line.stop) / 2)
    sides: list[tuple[bool, float, float]] = []
    for other in lines:
        turned = np.asarray(other.direction)
        if other is line or abs(float(turned @ direction)) < math.cos(math.radians(angle_deg)):
            continue
        low, high = sorted(float((other.at(t) - np.asarray(line.point)) @ direction)
                           for t in (other.start, other.stop))
        across = float((np.asarray(other.point) - middle) @ normal)
        if (low >= line.start - ends_mm and high <= line.stop + ends_mm
                and 0.1 <= abs(across) <= across_mm):
            sides.append((across > 0, low, high))
    if any(first[0] != second[0] and abs(first[1] - second[1]) <= ends_mm
           and abs(first[2] - second[2]) <= ends_mm
           for first, second in itertools.combinations(sides, 2)):
        return "doubled"
    return "between" if len({side for side, _, _ in sides}) == 2 else None


def _polished(line: Stroke, lines: Sequence[Stroke], darkness: np.ndarray,
              origin: Sequence[float], resolution: float) -> Stroke:
    """``line`` moved onto the middle of its pencil line: at stations every 0.25 mm along it,
    the centre of the darkness across it (the whole profile, not only what passes the
    threshold), where no other stroke comes within 1 mm; a straight line fitted to those
    centres (Tukey's biweight)."""
    import cv2

    if line.length < LONG_STROKE_MM:
        return line
    direction = np.asarray(line.direction)
    normal = np.array([-direction[1], direction[0]])
    stations = np.arange(line.start + 0.5, line.stop - 0.5, 0.25)
    if len(stations) < 8:
        return line
    centres = np.asarray(line.point) + stations[:, None] * direction
    clear = np.ones(len(stations), bool)
    for other in lines:
        if other is line:
            continue
        od = np.asarray(other.direction)
        offsets = centres - np.asarray(other.point)
        along = offsets @ od
        across = np.abs(offsets @ np.array([-od[1], od[0]]))
        clear &= ~((across < 1.0) & (along > other.start - 1.0) & (along < other.stop + 1.0))
    if clear.sum() < 8:
        return line
    stations, centres = stations[clear], centres[clear]
    offsets = np.arange(-0.6, 0.6001, 0.05)
    samples = centres[:, None, :] + offsets[None, :, None] * normal
    columns = ((samples[..., 0] - origin[0]) * resolution - 0.5).astype(np.float32)
    rows = ((samples[..., 1] - origin[1]) * resolution - 0.5).astype(np.float32)
    profile = cv2.remap(darkness, columns, rows, cv2.INTER_LINEAR).astype(np.float64)
    profile = np.clip(profile - np.minimum(profile[:, :3].mean(axis=1),
                                           profile[:, -3:].mean(axis=1))[:, None], 0, None)
    mass = profile.sum(axis=1)
    # a station with far more pencil across it than the line's own is touched by something
    # else (a label's letter, a dot): its centre would be pulled towards it
    good = (mass > 0.5 * np.median(mass)) & (mass < 1.5 * np.median(mass))
    if good.sum() < 8:
        return line
    shift = (profile[good] * offsets).sum(axis=1) / mass[good]
    along = stations[good]
    weights = np.ones(len(along))
    for _ in range(3):
        design = np.column_stack([np.ones_like(along), along]) * weights[:, None]
        (a, b), *_ = np.linalg.lstsq(design, shift * weights, rcond=None)
        residual = shift - (a + b * along)
        weights = np.clip(1.0 - (residual / 0.15) ** 2, 0.0, None) ** 2
        if weights.sum() < 4:
            return line
    # the line's offset across it is a + b·t: its new point and direction
    point = np.asarray(line.point) + a * normal
    turned = direction + b * normal
    turned /= np.linalg.norm(turned)
    start = float((line.at(line.start) - point) @ turned)
    stop = float((line.at(line.stop) - point) @ turned)
    return Stroke((float(point[0]), float(point[1])), (float(turned[0]), float(turned[1])),
                  start, stop, line.rms_mm)


def _extent(line: Stroke, points: np.ndarray, *, gap_mm: float = 1.2) -> Stroke:
    """``line`` with its extent where its pixels (among ``points``) run without a gap longer
    than ``gap_mm``, the run holding its middle."""
    along = np.sort((points - np.asarray(line.point))[_on(line, points, 0.3)]
                    @ np.asarray(line.direction))
    if not len(along):
        return line
    middle = (line.start + line.stop) / 2
    breaks = np.nonzero(np.diff(along) > gap_mm)[0]
    starts = np.concatenate([[0], breaks + 1])
    stops = np.concatenate([breaks, [len(along) - 1]])
    best = max(range(len(starts)), key=lambda i: (along[starts[i]] <= middle <= along[stops[i]],
                                                  along[stops[i]] - along[starts[i]]))
    return Stroke(line.point, line.direction, float(along[starts[best]]),
                  float(along[stops[best]]), line.rms_mm)


def _segment_stroke(a: np.ndarray, b: np.ndarray) -> Stroke:
    length = float(np.hypot(*(b - a)))
    direction = (b - a) / max(length, 1e-9)
    return Stroke((float(a[0]), float(a[1])), (float(direction[0]), float(direction[1])), 0.0,
                  length, 0.0)


def _joins(line: Stroke, a: np.ndarray, b: np.ndarray, *, angle_deg: float,
           distance_mm: float, gap_mm: float = 2.5) -> bool:
    """Whether the segment ``a``–``b`` continues ``line``: nearly parallel, on it, and no
    farther from its ends than a pencil's gap."""
    direction = np.asarray(line.direction)
    other = (b - a) / max(float(np.hypot(*(b - a))), 1e-9)
    if abs(float(direction @ other)) < math.cos(math.radians(angle_deg)):
        return False
    normal = np.array([-direction[1], direction[0]])
    base = np.asarray(line.point)
    if max(abs(float((a - base) @ normal)), abs(float((b - base) @ normal))) > distance_mm:
        return False
    along = sorted((float((a - base) @ direction), float((b - base) @ direction)))
    return along[0] <= line.stop + gap_mm and along[1] >= line.start - gap_mm


#: a pixel belongs to a stroke within this distance of its line (mm): a pencil line's half
#: width and its blur
_BAND_MM = 0.45


def _fit(points: np.ndarray, weights: np.ndarray) -> Stroke | None:
    """The line through ``points`` (weighted least squares), pixels far off it (a cross's arm
    along it, a letter's stroke touching it) weighed down (Tukey's biweight, twice)."""
    robust = weights
    for _ in range(3):
        centre = (points * robust[:, None]).sum(axis=0) / robust.sum()
        spread = points - centre
        covariance = (spread * robust[:, None]).T @ spread / robust.sum()
        values, vectors = np.linalg.eigh(covariance)
        direction = vectors[:, 1]
        across = spread @ np.array([-direction[1], direction[0]])
        robust = weights * np.clip(1.0 - (across / 0.35) ** 2, 0.0, None) ** 2
        if robust.sum() <= 1e-9:
            break
    if direction[0] < 0 or (direction[0] == 0 and direction[1] < 0):
        direction = -direction
    projected = spread @ direction
    return Stroke((float(centre[0]), float(centre[1])), (float(direction[0]),
                                                         float(direction[1])),
                  float(projected.min()), float(projected.max()),
                  float(math.sqrt(max(values[0], 0.0))))


def _merged(strokes: Sequence[Stroke], points: np.ndarray, weights: np.ndarray
            ) -> list[Stroke]:
    """Pieces of one line joined (a line broken by a gap, or drawn twice, is found in more
    than one piece) and fitted again to the pixels along them all."""
    out: list[Stroke] = []
    for stroke in sorted(strokes, key=lambda stroke: -stroke.length):
        a, b = stroke.at(stroke.start), stroke.at(stroke.stop)
        for index, kept in enumerate(out):
            if _joins(kept, a, b, angle_deg=3.0, distance_mm=0.35, gap_mm=2.5):
                joined = _span(kept, a, b)
                near = _on(joined, points, 0.35)
                fitted = _fit(points[near], weights[near]) if near.sum() >= 8 else None
                out[index] = _span(fitted, joined.at(joined.start), joined.at(joined.stop)) \
                    if fitted is not None else joined
                break
        else:
            out.append(stroke)
    return out


def _reaching(line: Stroke, points: np.ndarray, *, band_mm: float = 0.3,
              gap_mm: float = 0.5) -> Stroke:
    """``line`` with its extent grown along its own course over every pencil pixel on it
    (whoever owns it), across gaps of up to ``gap_mm``: where two strokes meet, the pixels of
    the meeting belong to both."""
    direction = np.asarray(line.direction)
    offsets = points - np.asarray(line.point)
    across = np.abs(offsets @ np.array([-direction[1], direction[0]]))
    along = np.sort((offsets @ direction)[across <= band_mm])
    start, stop = line.start, line.stop
    beyond = along[along > stop]
    for value in beyond:
        if value - stop > gap_mm:
            break
        stop = float(value)
    before = along[along < start][::-1]
    for value in before:
        if start - value > gap_mm:
            break
        start = float(value)
    return Stroke(line.point, line.direction, start, stop, line.rms_mm)


def _span(line: Stroke, a: np.ndarray, b: np.ndarray) -> Stroke:
    direction = np.asarray(line.direction)
    base = np.asarray(line.point)
    along = [float((a - base) @ direction), float((b - base) @ direction)]
    return Stroke(line.point, line.direction, min(line.start, *along), max(line.stop, *along),
                  line.rms_mm)


class MarkKind(StrEnum):
    """How a point is marked on paper, most trusted first: a small cross or a dot the student
    drew at the end or crossing of the construction's lines (marked), two lines that cross
    (implied), a line's free end; last a ``loose`` mark, a spot or small cross that no line of
    the construction ends at or crosses at (most likely a piece of a handwritten label)."""

    CROSS = "cross"
    DOT = "dot"
    CROSSING = "crossing"
    END = "end"
    LOOSE = "loose"

    @property
    def marked(self) -> bool:
        """Whether the student marked the point (a cross or a dot)."""
        return self in (MarkKind.CROSS, MarkKind.DOT)

    @property
    def rank(self) -> int:
        """Its place in the order of trust (0 first)."""
        return list(MarkKind).index(self)

    @property
    def evidence(self) -> int:
        """How strongly it says a point is there: 2 marked where lines end or cross, 1 lines
        that end or cross, 0 a loose mark."""
        return 2 if self.marked else 0 if self is MarkKind.LOOSE else 1


@dataclass(frozen=True)
class Mark:
    """A point a student marked, found in the rectified page (mm): where, and how — marked
    (a small ``cross`` or a ``dot``), or implied (two strokes that meet or cross: a
    ``crossing``; a stroke's free ``end``)."""

    at: tuple[float, float]
    kind: MarkKind
    #: how exactly the place is known: the sine of the angle two crossing lines make (1 for
    #: a dot or an end)
    sharpness: float = 1.0
    #: how many of the construction's lines end at it or pass through it
    lines: int = 0


def find_points(strokes: Sequence[Stroke], points: np.ndarray, weights: np.ndarray, *,
                resolution: float) -> list[Mark]:
    r"""The marked points: where two strokes meet or cross (within a pencil's overshoot of
    both) — a ``cross`` where more pencil is there than the long lines explain (a small cross or
    a dot drawn on it), else a ``crossing``; the ``dot``\ s that no crossing explains; and the
    free ``end``\ s of long strokes."""
    long = [stroke for stroke in strokes if stroke.length >= LONG_STROKE_MM]
    residual = np.ones(len(points), bool)
    for stroke in long:
        residual &= ~_on(stroke, points, 0.3)
    spare, spare_weights = points[residual], weights[residual]
    marks: list[Mark] = []
    for first in range(len(strokes)):
        for second in range(first + 1, len(strokes)):
            at = _meeting(strokes[first], strokes[second], 1.0)
            if at is not None:
                kind = MarkKind.CROSS if _ink(at, spare, spare_weights, 1.0) >= MARK_INK_MM2 \
                    else MarkKind.CROSSING
                a, b = strokes[first].direction, strokes[second].direction
                sine = abs(a[0] * b[1] - a[1] * b[0])
                marks.append(Mark((float(at[0]), float(at[1])), kind, sine))
    for dot in _dots(spare, spare_weights, resolution):
        if all(math.dist(dot, mark.at) > 1.0 for mark in marks
               if mark.kind is MarkKind.CROSS):
            marks.append(Mark(_onto_ends(dot, long), MarkKind.DOT))
    for stroke in long:
        if stroke.length < 5.0:
            continue
        for along, inward in ((stroke.start, 1.0), (stroke.stop, -1.0)):
            end = stroke.at(along)
            if all(math.dist(end, mark.at) > 2.0 for mark in marks):
                dot = _dot_at_end(stroke, along, inward, points, weights)
                marks.append(Mark((float(end[0]), float(end[1])), MarkKind.END) if dot is None
                             else Mark((float(dot[0]), float(dot[1])), MarkKind.DOT))
    out = []
    for mark in _gathered(marks):
        ends, through = _reached(mark.at, long)
        kind = mark.kind if mark.kind is MarkKind.END or ends or through >= 2 else MarkKind.LOOSE
        out.append(Mark(mark.at, kind, mark.sharpness, ends + through))
    return out


def _onto_ends(dot: tuple[float, float], long: Sequence[Stroke], *, across_mm: float = 0.9,
               end_mm: float = 1.5) -> tuple[float, float]:
    """A dot moved onto the lines that end at it, where two or more do (within ``across_mm``
    across and ``end_mm`` along of an end; the mean of its places on each): a dot found among
    the pixels the lines leave is what the lines do not cover of it, off its middle where they
    cover it unevenly, and the lines tell where across them more exactly than the dot. (One
    line ending at a spot may be a stray one reaching a written label.)

    >>> lines = [Stroke((0.0, 0.0), (1.0, 0.0), 0.0, 10.0, 0.1),
    ...          Stroke((20.0, 0.0), (1.0, 0.0), -10.0, 0.0, 0.1)]
    >>> _onto_ends((10.2, 0.6), lines), _onto_ends((10.2, 0.4), lines[:1])
    ((10.2, 0.0), (10.2, 0.4))
    """
    placed = []
    for stroke in long:
        direction = np.asarray(stroke.direction)
        offset = np.asarray(dot) - np.asarray(stroke.point)
        along = float(offset @ direction)
        if (abs(float(offset @ np.array([-direction[1], direction[0]]))) <= across_mm
                and min(abs(along - stroke.start), abs(along - stroke.stop)) <= end_mm):
            placed.append(stroke.at(along))
    if len(placed) < 2:
        return dot
    x, y = np.mean(placed, axis=0)
    return (round(float(x), 9), round(float(y), 9))


def _dot_at_end(stroke: Stroke, along: float, inward: float, points: np.ndarray,
                weights: np.ndarray, *, reach_mm: float = 2.2, across_mm: float = 0.9
                ) -> np.ndarray | None:
    """The dot drawn where a stroke ends, if one is: the pencil (``points``) within
    ``across_mm`` of the stroke, every 0.25 mm over its last ``reach_mm`` (and a little beyond
    its end), beyond what the stroke holds farther in (the line itself, one drawn along it) —
    a dot on a line's end widens it there — with a dot's ink (:data:`DOT_INK_MM2`); placed on
    the stroke at the centre of that excess along it (the line tells where across it more
    exactly than the dot)."""
    if not len(points) or stroke.length < reach_mm + 2.5:
        return None
    direction = np.asarray(stroke.direction)
    offsets = points - np.asarray(stroke.point)
    inside = (offsets @ direction - along) * inward
    beside = np.abs(offsets @ np.array([-direction[1], direction[0]])) <= across_mm
    edges = np.arange(-0.5, reach_mm + 2.5 + 1e-9, 0.25)
    ink, _ = np.histogram(inside[beside], edges, weights=weights[beside])
    middles = (edges[:-1] + edges[1:]) / 2
    near = middles <= reach_mm
    excess = np.clip(ink[near] - float(np.median(ink[~near])), 0.0, None)
    if float(excess.sum()) / RECTIFIED_PX_PER_MM ** 2 < DOT_INK_MM2:
        return None
    return stroke.at(along + inward * float((middles[near] * excess).sum() / excess.sum()))


def _reached(at, long: Sequence[Stroke], *, band_mm: float = 0.5, end_mm: float = 1.5
             ) -> tuple[int, int]:
    """How the construction's lines (``long``) reach ``at``: how many end there (within
    ``band_mm`` across and ``end_mm`` along of an end: a pencil's overshoot or early stop),
    and how many pass through it (within ``band_mm``). A point is reached where one ends or
    two pass."""
    ends = through = 0
    for stroke in long:
        direction = np.asarray(stroke.direction)
        offset = np.asarray(at) - np.asarray(stroke.point)
        if abs(float(offset @ np.array([-direction[1], direction[0]]))) > band_mm:
            continue
        along = float(offset @ direction)
        if not stroke.start - end_mm <= along <= stroke.stop + end_mm:
            continue
        if min(abs(along - stroke.start), abs(along - stroke.stop)) <= end_mm:
            ends += 1
        else:
            through += 1
    return ends, through


def _gathered(marks: Sequence[Mark], radius: float = 0.3) -> list[Mark]:
    """Marks of one place as one: where three lines and a cross's arms meet, their crossings
    lie a fraction of a millimetre apart, and a dot is drawn over a crossing. A group is the
    most trusted kind among its marks (what the student marked), placed where its lines cross
    — steep crossings weighing most, as their error goes with 1/sine — or, with no crossing
    in it, at its dot or end."""
    order = sorted(range(len(marks)), key=lambda i: marks[i].kind.rank)
    used = [False] * len(marks)
    out = []
    for index in order:
        if used[index]:
            continue
        reach = 2 * radius if marks[index].kind in (MarkKind.DOT, MarkKind.END) else radius
        group = [marks[other] for other in order if not used[other]
                 and math.dist(marks[other].at, marks[index].at) <= reach]
        for other in order:
            if not used[other] and math.dist(marks[other].at, marks[index].at) <= reach:
                used[other] = True
        crossed = [mark for mark in group if mark.kind in (MarkKind.CROSS, MarkKind.CROSSING)]
        placing = crossed or [marks[index]]
        weights = np.array([mark.sharpness for mark in placing]) ** 4
        x, y = (np.array([mark.at for mark in placing]) * weights[:, None]).sum(axis=0) / max(
            weights.sum(), 1e-12)
        out.append(Mark((float(x), float(y)), marks[index].kind,
                        max(mark.sharpness for mark in placing)))
    return out


#: a stroke at least this long (mm) is a line of the construction, not a mark's
LONG_STROKE_MM = 4.0
#: a point is marked (a dot, a small cross) where at least this much pencil (mm² of full
#: darkness) lies within 1 mm of it beyond the construction's lines
MARK_INK_MM2 = 0.04
#: a dot on a line's end widens it by at least this much pencil (mm² of full darkness): a
#: dot 1 mm across, half of it beyond the line, half dark
DOT_INK_MM2 = 0.12


def _on(stroke: Stroke, points: np.ndarray, band_mm: float) -> np.ndarray:
    """Which ``points`` lie on ``stroke`` (within ``band_mm`` of its line, along its extent)."""
    direction = np.asarray(stroke.direction)
    offsets = points - np.asarray(stroke.point)
    along = offsets @ direction
    return ((np.abs(offsets @ np.array([-direction[1], direction[0]])) <= band_mm)
            & (along >= stroke.start - band_mm) & (along <= stroke.stop + band_mm))


def _ink(at, points: np.ndarray, weights: np.ndarray, radius: float) -> float:
    """The pencil (mm² of full darkness) among ``points`` within ``radius`` of ``at``; a
    pixel of the rectified page is 1/RECTIFIED_PX_PER_MM² mm²."""
    if not len(points):
        return 0.0
    near = np.hypot(*(points - np.asarray(at)).T) <= radius
    return float(weights[near].sum()) / RECTIFIED_PX_PER_MM ** 2


def _meeting(a: Stroke, b: Stroke, reach: float) -> np.ndarray | None:
    """Where two strokes meet or cross (within ``reach`` beyond their ends), if they do: two
    strokes of 3 mm or more at any angle over 6°; a shorter one only where it is crossed near
    its middle at over 40° (the arm of a small cross)."""
    da, db = np.asarray(a.direction), np.asarray(b.direction)
    sine = float(da[0] * db[1] - da[1] * db[0])
    if abs(sine) < math.sin(math.radians(6.0)):
        return None
    offset = np.asarray(b.point) - np.asarray(a.point)
    ta = float(offset[0] * db[1] - offset[1] * db[0]) / sine
    tb = float(offset[0] * da[1] - offset[1] * da[0]) / sine
    if not (a.start - reach <= ta <= a.stop + reach and b.start - reach <= tb <= b.stop + reach):
        return None
    if min(a.length, b.length) >= 3.0:
        return a.at(ta)
    # a short stroke counts where it is crossed near its middle, steeply: a small cross's arm
    middle = all(abs(t - (stroke.start + stroke.stop) / 2) <= 0.3 * stroke.length
                 for t, stroke in ((ta, a), (tb, b)) if stroke.length < 3.0)
    if middle and abs(sine) >= math.sin(math.radians(40.0)):
        return a.at(ta)
    return None


def _dots(points: np.ndarray, weights: np.ndarray, resolution: float
          ) -> list[tuple[float, float]]:
    """Round spots of pencil among the pixels the construction's lines leave (a dot on a line
    leaves two crescents, joined here): at most 1.8 mm across, with a mark's ink."""
    import cv2

    if len(points) == 0:
        return []
    low = points.min(axis=0) - 1.0
    size = np.ceil((points.max(axis=0) - low + 1.0) * resolution).astype(int) + 1
    mask = np.zeros((size[1], size[0]), np.uint8)
    cells = np.floor((points - low) * resolution).astype(int)
    mask[cells[:, 1], cells[:, 0]] = 255
    bridge = round(0.8 * resolution) | 1
    joined = cv2.dilate(mask, cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (bridge, bridge)))
    count, labels = cv2.connectedComponents(joined, connectivity=8)
    owner = labels[cells[:, 1], cells[:, 0]]
    out = []
    for index in range(1, count):
        inside = owner == index
        chosen, weight = points[inside], weights[inside]
        if len(chosen) < 3:
            continue
        extent = chosen.max(axis=0) - chosen.min(axis=0)
        if max(extent) > 1.8 or float(weight.sum()) / resolution ** 2 < MARK_INK_MM2:
            continue
        centre = (chosen * weight[:, None]).sum(axis=0) / weight.sum()
        out.append((float(centre[0]), float(centre[1])))
    return out


def _on_dot(mark: Mark, darkness: np.ndarray, origin: Sequence[float], resolution: float,
            *, reach_mm: float = 0.9) -> Mark:
    """``mark`` moved onto the dot drawn on it, where its lines meet too shallowly to place it
    (sine under :data:`SHALLOW_SINE`: their crossing's error grows as 1/sine): the strongest
    blob of a dot's size (a difference of Gaussians, 0.45 mm and 1.2 mm) within ``reach_mm``
    of it, placed to a fraction of a pixel (a parabola through the peak and its neighbours), if
    it is as strong as a dot (:data:`DOT_BLOB`) — a pencil line, or lines running together,
    give less."""
    import cv2

    if mark.kind not in (MarkKind.CROSS, MarkKind.CROSSING) or mark.sharpness >= SHALLOW_SINE:
        return mark
    half = math.ceil(4.5 * resolution)
    column = round((mark.at[0] - origin[0]) * resolution - 0.5)
    row = round((mark.at[1] - origin[1]) * resolution - 0.5)
    height, width = darkness.shape
    if not (half <= row < height - half and half <= column < width - half):
        return mark
    patch = darkness[row - half:row + half + 1, column - half:column + half + 1]
    blob = (cv2.GaussianBlur(patch, (0, 0), 0.45 * resolution)
            - cv2.GaussianBlur(patch, (0, 0), 1.2 * resolution))
    ys, xs = np.mgrid[-half:half + 1, -half:half + 1]
    blob = np.where(np.hypot(xs, ys) <= reach_mm * resolution, blob, -np.inf)
    y, x = np.unravel_index(int(np.argmax(blob)), blob.shape)
    if blob[y, x] < DOT_BLOB or not (0 < y < blob.shape[0] - 1 and 0 < x < blob.shape[1] - 1):
        return mark

    def vertex(low: float, middle: float, high: float) -> float:
        bend = low - 2 * middle + high
        return 0.0 if not np.isfinite(bend) or bend >= 0 else 0.5 * (low - high) / bend

    dx = vertex(blob[y, x - 1], blob[y, x], blob[y, x + 1])
    dy = vertex(blob[y - 1, x], blob[y, x], blob[y + 1, x])
    at = (origin[0] + (column - half + x + dx + 0.5) / resolution,
          origin[1] + (row - half + y + dy + 0.5) / resolution)
    return Mark((float(at[0]), float(at[1])), mark.kind, mark.sharpness, mark.lines)


#: lines that meet at a sine under this place their point less exactly than a dot drawn there
SHALLOW_SINE = 0.35
#: the least response of a dot to the blob filter of :func:`_on_dot` (darkness)
DOT_BLOB = 0.13


# -- 5. the grade -----------------------------------------------------------------------------
def _rectified(image: np.ndarray, to_page: np.ndarray, box, resolution: float) -> np.ndarray:
    import cv2

    left, top, right, bottom = box
    placed = np.array([[resolution, 0, -resolution * left - 0.5],
                       [0, resolution, -resolution * top - 0.5], [0, 0, 1]])
    size = (round((right - left) * resolution), round((bottom - top) * resolution))
    return cv2.warpPerspective(image, placed @ to_page, size, flags=cv2.INTER_LINEAR,
                               borderMode=cv2.BORDER_REPLICATE)




def _assign(entry: Mapping[str, Any], marks: Sequence[tuple[np.ndarray, Mark]]
            ) -> dict[str, int]:
    """Which mark is each point of the plan (index into ``marks``, whose first item is the
    mark's position in plan mm).

    A point is where the student put it: at its right place (within its tolerance radius) or
    at a place a named mistake puts it (within that radius or :data:`MEASURING_MM`). The
    stronger evidence wins (:func:`_stronger`):
    a point the student marked where lines end or cross is trusted over one where lines merely
    end or cross, and that over a loose mark (a piece of a label); of two alike, one where two
    lines end or cross over one that a single line reaches: a point with stronger
    evidence at a mistake's place than at its right place is taken at the mistake's. Points
    with nothing but loose marks at their right place choose first, each mark going to one of
    them. A point found at neither is the nearest mark left within :data:`SEARCH_MM`, a loose
    one only if no other is there. A helper point (n, k) is taken only at its
    right place or a mistake's. A mistake's place nearer the pole than :data:`POLE_ROOM_MM` and
    2.5 mm is not looked at: the lines that leave the pole cross there whatever was drawn."""
    radii = entry["tolerance_mm"]
    wrong = entry.get("mistake_points", {})
    graded = graded_labels(entry)
    helpers = [label for label in entry["points_mm"] if label not in graded and "_" in label]
    positions = np.array([at for at, _ in marks]).reshape(-1, 2)
    kinds = [mark.kind for _, mark in marks]

    def within(target, radius) -> list[int]:
        if not len(positions):
            return []
        distance = np.hypot(*(positions - np.asarray(target, float)).T)
        return sorted((int(i) for i in np.nonzero(distance <= radius)[0]),
                      key=lambda i: (kinds[i].rank, distance[i]))

    found = {}
    for label in [*graded, *helpers]:
        radius = float(radii.get(label, 0.5))
        right = within(entry["points_mm"][label], radius)
        mistaken = []
        for _, x, y in wrong.get(label, ()):
            if math.hypot(x, y) < POLE_ROOM_MM + 2.5:    # where the pole's lines crowd
                continue
            mistaken += [index for index in within((x, y), max(radius, MEASURING_MM))
                         if index not in right and index not in mistaken]
        mistaken.sort(key=lambda i: kinds[i].rank)
        found[label] = (right, mistaken)
    chosen: dict[str, int] = {}
    claimed: set[int] = set()
    # the plan's points first, a found one not within its radius the nearest mark left; the
    # helpers from the marks they leave (a helper's mistaken place is often a plan point's)
    _claim({label: found[label] for label in graded}, marks, chosen, claimed)
    _nearest_left(entry, graded, positions, kinds, chosen, claimed)
    _claim({label: found[label] for label in helpers}, marks, chosen, claimed, share=True)
    return chosen


def _claim(found: Mapping[str, tuple[list[int], list[int]]],
           marks: Sequence[tuple[np.ndarray, Mark]], chosen: dict[str, int],
           claimed: set[int], *, share: bool = False) -> None:
    """Give each point of ``found`` (the marks at its right place and at its mistakes' places,
    most trusted first) its mark, as :func:`_assign` says: first those with nothing but loose
    marks at their right place — with ``share``, at a mark a point took already (a helper
    drawn on a plan point: n_CB at b when aⁿ is left out) — then the others."""
    kinds = [mark.kind for _, mark in marks]
    for label, (right, mistaken) in found.items():       # nothing at the right place
        free = [index for index in mistaken if (share or index not in claimed)
                and kinds[index].evidence > (kinds[right[0]].evidence if right else -1)]
        if (not right or not kinds[right[0]].evidence) and free:
            chosen[label] = free[0]
            claimed.add(free[0])
    for label, (right, mistaken) in found.items():
        if label in chosen or not right:
            continue
        stronger = [index for index in mistaken if index not in claimed
                    and _stronger(marks[index][1], marks[right[0]][1])]
        chosen[label] = stronger[0] if stronger else right[0]
        claimed.add(chosen[label])


def _stronger(mark: Mark, other: Mark) -> bool:
    """Whether ``mark`` says more strongly than ``other`` that a point is there: its kind's
    evidence (:attr:`MarkKind.evidence`) is stronger, or as strong and two lines or more reach
    it where one reaches ``other`` (a piece of a label that a stray line happens to end at is
    marked as a dot that one line reaches, a point of the construction where its lines meet)."""
    if mark.kind.evidence != other.kind.evidence:
        return mark.kind.evidence > other.kind.evidence
    return other.lines <= 1 < mark.lines


def _nearest_left(entry: Mapping[str, Any], graded: Sequence[str], positions: np.ndarray,
                  kinds: Sequence[MarkKind], chosen: dict[str, int], taken: set[int]) -> None:
    """Give each plan point not found yet the nearest mark no point took, within
    :data:`SEARCH_MM` of its right place; a loose mark only where no other is."""
    for label in graded:
        if label in chosen or not len(positions):
            continue
        distance = np.hypot(*(positions - np.asarray(entry["points_mm"][label], float)).T)
        free = sorted((int(i) for i in np.nonzero(distance <= SEARCH_MM)[0]
                       if int(i) not in taken),
                      key=lambda i: (kinds[i] is MarkKind.LOOSE, distance[i]))
        if free:
            chosen[label] = free[0]
            taken.add(free[0])


@dataclass(frozen=True, slots=True)
class PointPlace:
    """Where a graded point of a photo is: where it belongs in the photo (``right_photo_px``)
    and, if it was found, where (``photo_px``; ``page_mm``, as measured on the page) and what
    the student drew there (``mark``: a :class:`MarkKind`)."""

    point: str
    right_photo_px: tuple[float, float]
    photo_px: tuple[float, float] | None = None
    page_mm: tuple[float, float] | None = None
    mark: str | None = None

    def as_dict(self) -> dict[str, Any]:
        """The place as ``grade --photo --json`` writes it beside the point's verdict."""
        out: dict[str, Any] = {"right_photo_px": list(self.right_photo_px)}
        if self.photo_px is not None:
            out |= {"page_mm": list(self.page_mm or ()), "photo_px": list(self.photo_px),
                    "mark": self.mark}
        return out


def _places(drawing: GradedDrawing, entry: Mapping[str, Any], sheet: Sheet,
            marked: Mapping[str, tuple[tuple[float, float], Mark]], correction: Correction,
            photo_of: np.ndarray) -> tuple[tuple[PointPlace, ...], tuple[float, float]]:
    """Where each graded point was found (as measured, in the photo and on the page, and the
    mark) and where it belongs in the photo; and where the pole is in the photo."""

    def in_photo(plan_xy) -> tuple[float, float]:
        page = correction.seen(np.asarray([plan_to_page(sheet.pole_mm, plan_xy)]))
        found = _apply(photo_of, page)[0]
        return (round(float(found[0]), 1), round(float(found[1]), 1))

    places = []
    for point in drawing.points:
        right = in_photo(entry["points_mm"][point.point])
        if point.found and point.point in marked:
            xy, mark = marked[point.point]
            page = plan_to_page(sheet.pole_mm, xy)
            places.append(PointPlace(point.point, right, in_photo(xy),
                                     (round(page[0], 3), round(page[1], 3)), str(mark.kind)))
        else:
            places.append(PointPlace(point.point, right))
    return tuple(places), in_photo((0.0, 0.0))




def _matched(entry: Mapping[str, Any], label: str, xy: tuple[float, float]
             ) -> tuple[float, float]:
    """A point found in a photo, as graded: at the place a named mistake puts it, if it lies
    within the photo's measuring error (:data:`MEASURING_MM`) of that place and nearer to it
    than to the right one (a point a mistake moves just beyond the tolerance is never called
    right for the photo's error), that place lying beyond the right one's tolerance and the
    measuring error (a point found within the tolerance is never called wrong for it); else
    where it was found."""
    right = entry["points_mm"].get(label)
    radius = float(entry["tolerance_mm"].get(label, 0.5))
    if right is None:
        return xy
    best = None
    for _, x, y in entry.get("mistake_points", {}).get(label, ()):
        off = math.dist(xy, (x, y))
        if (off <= MEASURING_MM and off < math.dist(xy, right)
                and math.dist((x, y), right) > radius + MEASURING_MM
                and (best is None or off < best[0])):
            best = (off, (float(x), float(y)))
    return xy if best is None else best[1]


@dataclass(frozen=True)
class GradedPhoto:
    """A photo graded: the plan drawn on its sheet graded as ``grade --drawing`` grades a
    drawn plan (``drawing``), where each of its points is in the photo (``places``, in the
    drawing's points' order) and its pole, the sheet its QR code names, how the photo was
    taken (``reading``, which keeps the photo itself for marking it), and what was measured
    of the paper's curl (the grid lines it was fitted to and their spread, mm) and of the
    pencil (strokes and marks found)."""

    photo: str
    drawing: GradedDrawing
    places: tuple[PointPlace, ...]
    pole_photo_px: tuple[float, float]
    sheet: Sheet
    reading: PhotoReading = field(repr=False)
    grid_lines: int = 0
    grid_rms_mm: float | None = None
    strokes: int = 0
    marks: int = 0

    @property
    def image(self) -> np.ndarray:
        """The photo (B G R)."""
        return self.reading.image

    def as_dict(self) -> dict[str, Any]:
        """The graded photo as ``grade --photo --json`` writes it: the drawn plan's verdicts as
        ``grade --drawing --json`` writes them, each point with its place in the photo, then
        the photo, its sheet and how it was read."""
        out = self.drawing.as_dict()
        for point, place in zip(out["points"], self.places, strict=True):
            point |= place.as_dict()
        reading = self.reading
        return out | {
            "pole_photo_px": list(self.pole_photo_px), "photo": self.photo,
            "sheet": {"student": self.sheet.student, "plan": self.sheet.plan,
                      "page": self.sheet.page, "code": self.sheet.code.text},
            "reading": {"tilt_deg": round(reading.tilt_deg, 1),
                        "px_per_mm": round(reading.px_per_mm, 2),
                        "edge_mm": round(reading.edge_mm, 2),
                        "paper_level": round(reading.paper_level, 1),
                        "grid_lines": self.grid_lines, "grid_rms_mm": self.grid_rms_mm,
                        "strokes": self.strokes, "marks": self.marks}}


#: how a key given as data (no file) is named in what a photo's grading says
_THE_KEY = message("the key")


def grade_photo(keys: Mapping[str, Mapping[str, Any]], path: str | Path, *,
                key_source: Message | str = _THE_KEY) -> GradedPhoto:
    """Grade the plan drawn on the sheet a photo shows (see the module notes): the plan graded
    by :func:`~planmethod.grading.drawings.grade_drawing` from the points found (a point within
    the photo's measuring error of a named mistake's place is graded there), with where each
    point was found and where it belongs in the photo.

    Raises
    ------
    PhotoError
        In one line, for a photo that cannot be read or a sheet the key does not have.
    """
    source = str(path)
    data = read_bytes_bounded(path, MAX_PHOTO_BYTES, error=SubmissionError)
    reading = read_photo(data, source)
    key, sheet = sheet_of(reading, keys, key_source)
    to_page = _to_page(reading, sheet)
    resolution = RECTIFIED_PX_PER_MM
    box = sheet.drawing_mm
    rectified = _rectified(reading.image, to_page, box, resolution)
    correction = measure_curl(rectified, sheet, resolution, box)
    darkness = _darkness(rectified, resolution)
    pixels, weights = _pencil_pixels(darkness, sheet, box, resolution, PENCIL_DARKNESS)
    strokes = find_strokes(pixels, weights, resolution, box[:2], darkness.shape, darkness)
    marks = find_points(strokes, pixels, weights, resolution=resolution)
    marks = [_on_dot(mark, darkness, box[:2], resolution) for mark in marks]
    seen = [np.asarray(mark.at) for mark in marks]
    true = correction.true(np.asarray(seen).reshape(-1, 2)) if seen else np.zeros((0, 2))
    placed = [(np.asarray(page_to_plan(sheet.pole_mm, xy)), mark)
              for xy, mark in zip(true, marks, strict=True)]
    # the strokes from the pole cross there, and end where its printed ring hides them
    placed = [(xy, mark) for xy, mark in placed if math.hypot(*xy) > POLE_ROOM_MM]
    entry = key["plans"][sheet.plan]
    chosen = _assign(entry, placed)
    measured = {label: (float(placed[index][0][0]), float(placed[index][0][1]))
                for label, index in chosen.items()}
    points = {sheet.pole: (0.0, 0.0)}
    points |= {label: _matched(entry, label, xy) for label, xy in measured.items()}
    drawing = Drawing(points, sheet.plan, (), source, title=key.get("title"),
                      angle=float(key.get("angle", 0.0)), exact_scale=True)
    graded = grade_drawing(key, drawing, sheet.plan, rescale=False)
    marked = {label: (measured[label], placed[index][1]) for label, index in chosen.items()}
    places, pole = _places(graded, entry, sheet, marked, correction, np.linalg.inv(to_page))
    return GradedPhoto(source, graded, places, pole, sheet, reading, correction.samples,
                       round(correction.rms_mm, 3) if math.isfinite(correction.rms_mm)
                       else None, len(strokes), len(marks))


def _to_page(reading: PhotoReading, sheet: Sheet) -> np.ndarray:
    """The homography from the photo to the page of ``sheet``: the reading's, unless the key's
    sheet puts its markers elsewhere than the booklet does."""
    if all(tuple(marker.centre) == MARKER_CENTRES[marker.number] for marker in sheet.markers):
        return reading.to_page
    import cv2

    photo = np.concatenate([_apply(reading.to_photo, _marker_corners_mm(marker.number))
                            for marker in sheet.markers])
    page = np.concatenate([np.asarray(sheet.corners(marker.number))
                           for marker in sheet.markers])
    to_page, _ = cv2.findHomography(photo, page, 0)
    return to_page
