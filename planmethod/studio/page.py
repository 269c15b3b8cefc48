"""The studio's page: its markup in the course's language, its words for the scripts, and the
script files it loads.

``studio.html`` beside this module is the page's markup with every word a person reads left as
a place ``⟪name⟫`` that :func:`studio_page` fills with a message of :data:`MARKUP`, rendered in
the language the studio speaks. The page's scripts — ``studio.js`` (the editor, the server's
answers, the files), ``studio_runs.js`` (variants and export as jobs) and the pages' shared
``page_words.js`` (:mod:`planmethod.render`) — are files the page loads from the studio
(:data:`PAGE_FILES`, :func:`page_file`), so that its policy allows scripts from the studio
only (``script-src 'self'``: no inline script). Every sentence the scripts show is a template
of :data:`SCRIPT_WORDS`, sent with the page as data (``#studio-words``) and filled by
``page_words.js``.

Examples
--------
>>> text = studio_page().decode("utf-8")
>>> "⟪" in text, '<script src="/studio.js"></script>' in text
(False, True)
>>> page_file("/studio_runs.js").content_type
'text/javascript; charset=utf-8'
>>> page_file("/api/state") is None
True
"""

from __future__ import annotations

import functools
import html
import json
import re
from dataclasses import dataclass
from importlib import resources

from ..render.page_rules import template_text
from ..render.workbook import marked_html
from ..words import Message, current, render, template
from ..words.render import DECIMAL_SIGN

__all__ = ["MARKUP", "PAGE_FILES", "SCRIPT_WORDS", "PageFile", "page_file", "studio_page"]

#: the words the scripts show, by id (studio.js, studio_runs.js)
SCRIPT_WORDS: dict[str, Message] = {
    "kind_structure": template("The links do not make one mechanism with one degree of "
                               "freedom"),
    "kind_assembly": template("The mechanism cannot be assembled as drawn here"),
    "kind_toggle": template("A group stands at its toggle position: its construction lines "
                            "are parallel"),
    "kind_forces": template("The forces cannot be found"),
    "kind_input": template("The exercise is not complete or not consistent"),
    "kind_exists": template("The file exists"),
    "kind_refused": template("The studio refused the request"),
    "kind_internal": template("The studio failed (a bug)"),
    "untitled": template("Mechanism"),
    "not_json": template("the server's answer is not JSON"),
    "no_answer": template("the studio does not answer (was it stopped?)"),
    "ready_points": template("Choose Point and click on the grid to place the mechanism's "
                             "points."),
    "ready_links": template("Choose Link and click points one after another to join them "
                            "into links (Enter ends a link)."),
    "ready_fix": template("Choose Fix and click the points pinned to the frame."),
    "ready_drive": template("Choose Drive and click the link that turns the mechanism (it "
                            "must be pinned to the frame)."),
    "ready": template("Drag a point: the plans redraw. Type exact coordinates in Selection."),
    "head_quantity": template("quantity"),
    "head_plan": template("plan", context="read off the plan"),
    "head_exact": template("exact", context="a value"),
    "head_unit": template("unit"),
    "solved": template("solved in {time:g} ms on the server"),
    "snap_on": template("points snap to a {step:g} mm grid (hold Alt or press G to place "
                        "them freely)"),
    "snap_off": template("points are placed freely (press G to snap them to a {step:g} mm "
                         "grid)"),
    "mode_move": template("Drag a point; click one to select it."),
    "mode_point": template("Click on the grid to add a point."),
    "mode_link": template("Click the link's points one after another; Enter or Finish link "
                          "ends it (the first two set its frame)."),
    "mode_fix": template("Click a point to pin it to the frame, again to free it."),
    "mode_slider": template("Click the sliding point, then a point its guide passes through (a "
                            "point of the link it slides along)."),
    "mode_drive": template("Click the link that drives the mechanism."),
    "mode_delete": template("Click a point, a link or a slider to delete it."),
    "no_guide": template("{point} is on no link the slider could run along"),
    "drive_unpinned": template("the drive link {link} must be pinned to the frame: fix one of "
                               "its points"),
    "field_name": template("name"),
    "field_x": template("x, m"),
    "field_y": template("y, m"),
    "field_fixed": template("fixed", context="pinned to the frame"),
    "field_direction": template("direction, °"),
    "on_links": template("on links: {links}"),
    "on_no_link": template("on links: none"),
    "link_points": template("points: {points}"),
    "slides_along": template("slides along"),
    "guide_through": template("guide through {point}"),
    "guide_moving": template("a guide on a moving link runs through its two drawn points"),
    "nothing_selected": template("Nothing selected. Click a point or a link (Move)."),
    "drawn_crank": template("({pivot}{pin}) crank"),
    "drawn_velocity": template("(p{image}) velocity"),
    "drawn_acceleration": template("(π{image}) acceleration"),
    "ask_point": template("point"),
    "ask_link": template("link"),
    "ask_sliding": template("sliding"),
    "ask_velocity_box": template("ask the velocity {symbol} of point {point}"),
    "ask_acceleration_box": template("ask the acceleration {symbol} of point {point}"),
    "ask_curvature_box": template("ask the radius of curvature {symbol} of the path of point "
                                  "{point}"),
    "ask_omega_box": template("ask the angular velocity {symbol} of link {link}"),
    "ask_epsilon_box": template("ask the angular acceleration {symbol} of link {link}"),
    "ask_sliding_box": template("ask the sliding of {link} along {along}"),
    "omega_low": template("lowest {omega} drawn, rad/s"),
    "omega_high": template("highest {omega} drawn, rad/s"),
    "omega_step": template("step of {omega}, rad/s"),
    "range_vary_box": template("vary the length of link {link}"),
    "range_low_box": template("shortest length of link {link}, m"),
    "range_high_box": template("longest length of link {link}, m"),
    "chosen_point": template("point {point} chosen: the arrows move it by a step of the grid "
                             "(Shift: ten steps)"),
    "no_files": template("no {suffix} files in this folder"),
    "file_converted": template("{path} (in link frames: shown as drawn)"),
    "replace": template("{path} exists. Replace it?"),
    "saved": template("saved {path}"),
    "range_link": template("link"),
    "range_drawn": template("drawn, m"),
    "range_vary": template("vary"),
    "range_from": template("from, m"),
    "range_to": template("to, m"),
    "refused_as": template("{kind}: {error}"),
    "preview_count": template("{count} variants."),
    "preview_rejected": template("{count} variants. Rejected draws: {rejected}"),
    "student": template("student {student}"),
    "template_saved": template("saved {path} ({command})"),
    "job_export": template("Export to {folder}/"),
    "job_preview": template("Preview of variants"),
    "job_exported": template("Export: wrote {count} files in {folder}/ ({variants} variants)"),
    "job_previewed": template("Preview: {count} variants drawn"),
    "job_failed": template("{what} failed: {error}"),
    "job_no_answer": template("no answer"),
    "job_cancelled": template("{what} cancelled"),
    "job_cancelled_export": template("{what} cancelled: nothing written"),
    "phase_starting": template("starting"),
    "phase_variants": template("drawing variants {done} of {total}"),
    "phase_packages": template("making the LMS packages"),
    "phase_writing": template("writing the files"),
    "job_phase": template("{what}: {phase}"),
    "job_progress": template("progress"),
    "job_seconds": template("{seconds} s"),
    "job_cancel": template("Cancel"),
    "job_dismiss": template("dismiss"),
}

#: a symbol of the drive in the markup, which the script sets to the exercise's own (φ₁, θ₂)
_SYMBOL = '<span data-drive-symbol="{0}">{1}</span>'
_PHI, _OMEGA = _SYMBOL.format("phi", "φ₁"), _SYMBOL.format("omega", "ω₁")
_EPSILON = _SYMBOL.format("epsilon", "ε₁")

#: the words of the markup, by the place ``⟪name⟫`` they fill: a message, and the markup set
#: in its fields (a symbol, a control)
MARKUP: dict[str, tuple[Message, dict[str, str]]] = {
    "page": (template("{product} studio"), {"product": "planmethod"}),
    "title_label": (template("title", context="of an exercise"), {}),
    "untitled": (SCRIPT_WORDS["untitled"], {}),
    "not_saved": (template("not saved"), {}),
    "open": (template("Open…"), {}),
    "save_path": (template("file to save"), {}),
    "save": (template("Save"), {}),
    "variants": (template("Variants…"), {}),
    "export": (template("Export…"), {}),
    "jobs": (template("jobs: long work running on the server"), {}),
    "move": (template("Move"), {}),
    "move_tip": (template("drag points; click to select"), {}),
    "point": (template("Point"), {}),
    "point_tip": (template("click on the grid to add a point"), {}),
    "link": (template("Link"), {}),
    "link_tip": (template("click points one after another; Enter or Finish ends the link"), {}),
    "finish": (template("Finish link"), {}),
    "finish_tip": (template("end the link being drawn"), {}),
    "fix": (template("Fix"), {}),
    "fix_tip": (template("click a point to pin it to the frame (or free it)"), {}),
    "slider": (template("Slider"), {}),
    "slider_tip": (template("click the sliding point, then a point its guide passes through"),
                   {}),
    "drive": (template("Drive"), {}),
    "drive_tip": (template("click the link that drives the mechanism (pinned to the frame)"),
                  {}),
    "delete": (template("Delete"), {}),
    "delete_tip": (template("click a point, link or slider to delete it"), {}),
    "fit": (template("Fit"), {}),
    "fit_tip": (template("fit the drawing in the view"), {}),
    "snap": (template("snap to grid (G)"), {}),
    "editor": (template("the mechanism as drawn: drag its points, or press ] and [ to choose a "
                        "point and the arrows to move it"), {}),
    "selection": (template("Selection"), {}),
    "nothing": (template("Nothing selected."), {}),
    "drive_link": (SCRIPT_WORDS["ask_link"], {}),
    "pivot": (template("pivot"), {}),
    "angle": (template("angle {phi}, °"), {"phi": _PHI}),
    "omega": (template("{omega}, rad/s"), {"omega": _OMEGA}),
    "epsilon": (template("{epsilon}, rad/s²"), {"epsilon": _EPSILON}),
    "plans": (template("Plans (drawn lengths, mm)"), {}),
    "crank": (SCRIPT_WORDS["drawn_crank"].replace(pivot="A", pin="B"), {}),
    "velocity": (SCRIPT_WORDS["drawn_velocity"].replace(image="b"), {}),
    "acceleration": (SCRIPT_WORDS["drawn_acceleration"].replace(image="b"), {}),
    "asked": (template("What is asked (none ticked: everything)"), {}),
    "position_plan": (template("Position plan (the server's drawing at μl)"), {}),
    "velocity_plan": (template("Velocity plan"), {}),
    "acceleration_plan": (template("Acceleration plan"), {}),
    "open_title": (template("Open an exercise file"), {}),
    "open_note": (template("Files under the studio's folder. A file in link frames is shown as "
                           "drawn; saving writes it as drawn."), {}),
    "cancel": (SCRIPT_WORDS["job_cancel"], {}),
    "variants_title": (template("Variants: ranges of the lengths and the crank angle"), {}),
    "angle_from": (template("{phi} from", context="a range"), {"phi": _PHI}),
    "to": (template("to", context="a range"), {}),
    "step": (template("step", context="a range's"), {}),
    "vary_omega": (template("vary {omega} from"), {"omega": _OMEGA}),

    "count": (template("variants", context="how many"), {}),
    "seed": (template("seed"), {}),
    "preview": (template("Preview task sheets"), {}),
    "template_file": (template("template file"), {}),
    "save_template": (template("Save template"), {}),
    "close": (template("Close"), {}),
    "export_title": (template("Export: variants, answer keys and LMS packages"), {}),
    "export_note": (template(
        "Uses the ranges of the Variants dialog. Writes {template}, the variants (as "
        "{command} does) and each package into a new folder, whole when the export ends: "
        "cancelled, it writes nothing. It runs on the server while you go on drawing; its "
        "progress stays at the top of the page."),
        {"template": "template.toml", "command": "<code>planmethod variants</code>"}),
    "folder": (template("folder"), {}),
    "moodle": (template("{system} quiz"), {"system": "Moodle"}),
    "prairielearn": (template("{system} question"), {"system": "PrairieLearn"}),
    "gradescope": (template("{system} autograder"), {"system": "Gradescope"}),
    "students": (template("students"), {}),
    "export_run": (template("Export", context="a button"), {}),
}

#: a place of the markup that a word fills
_PLACE = re.compile("⟪([a-z_]+)⟫")


@dataclass(frozen=True)
class PageFile:
    """A file the page loads: its bytes and their type."""

    content: bytes
    content_type: str


#: the files the page loads, by address: (package, file)
PAGE_FILES = {"/page_words.js": ("planmethod.render", "page_words.js"),
              "/studio.js": ("planmethod.studio", "studio.js"),
              "/studio_runs.js": ("planmethod.studio", "studio_runs.js")}


@functools.cache
def page_file(path: str) -> PageFile | None:
    """The file of the page at ``path`` (``/studio.js``), or None: no other address is a
    file."""
    found = PAGE_FILES.get(path)
    if found is None:
        return None
    package, name = found
    return PageFile(resources.files(package).joinpath(name).read_bytes(),
                    "text/javascript; charset=utf-8")


def _words_json(language: str) -> str:
    """The scripts' words as JSON inside the page (a ``</`` cannot end its element)."""
    data = {"templates": {name: template_text(text, language)
                          for name, text in SCRIPT_WORDS.items()},
            "decimal": render(DECIMAL_SIGN, language)}
    return json.dumps(data, ensure_ascii=False).replace("</", "<\\/")


def studio_page(language: str | None = None) -> bytes:
    """The page in ``language`` (default: the one spoken now): its markup's words filled in,
    its scripts' words as data."""
    language = language or current()
    markup = resources.files("planmethod.studio").joinpath("studio.html").read_text(
        encoding="utf-8")

    def said(found: re.Match) -> str:
        text, fields = MARKUP[found.group(1)]
        return (marked_html(text, fields, language) if fields else
                html.escape(render(text, language)))

    with_words = markup.replace("{language}", html.escape(language)).replace(
        "{words}", _words_json(language))
    return _PLACE.sub(said, with_words).encode("utf-8")
