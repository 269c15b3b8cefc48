"""Force drawings: the polygons at μF and Aliyev's combined-force construction."""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest

from planmethod.forces.combined import combined_constants, combined_construction, epsilon_senses
from planmethod.render.figures import plan_files
from planmethod.render.force_svg import combined_omitted, force_files
from planmethod.report import analyse
from planmethod.spec import load_exercise

EXERCISES = ["exercises/fourbar_forces.toml", "exercises/combined_force_slider_crank.toml",
             "exercises/conveyor_sixbar.toml"]
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module", params=EXERCISES)
def analysis(request):
    return analyse(load_exercise(request.param))


def test_files_are_well_formed_and_deterministic(analysis):
    files = force_files(analysis.forces, analysis.plans)
    groups = len(analysis.structure.groups) + 1
    assert len([name for name in files if name.startswith("forces_")]) == groups
    # the combined-force figure exactly where gravity acts (with g = 0 it degenerates)
    gravity = bool(analysis.forces.combined is not None and analysis.forces.combined.g)
    assert ("combined_force.svg" in files) == gravity
    assert (combined_omitted(analysis.forces, analysis.plans) is None) == gravity
    again = force_files(analysis.forces, analysis.plans)
    assert files == again
    for text in files.values():
        root = ElementTree.fromstring(text.encode("utf-8"))
        assert root.tag == f"{SVG}svg"
    assert set(files) <= set(plan_files(analysis.plans, forces=analysis.forces))


def test_polygon_shows_every_force_and_the_scale(analysis):
    files = force_files(analysis.forces, analysis.plans)
    for group in analysis.forces.solution.groups.groups:
        name = next(n for n in files if n.startswith("forces_") and n.endswith(
            group.name.replace("/", "_") + ".svg"))
        root = ElementTree.fromstring(files[name].encode("utf-8"))
        labels = {element.get("data-points") for element in root.iter(f"{SVG}text")}
        drawn = [edge for edge in group.polygon if float(np.hypot(*edge.vector[0])) > 0]
        for edge in drawn:
            assert edge.label in labels
        arrows = [g for g in root.iter(f"{SVG}g") if "force" in (g.get("class") or "")]
        sizes = [float(np.hypot(*edge.vector[0])) for edge in drawn]
        visible = [size for size in sizes if size > 0.01 * max(sizes)]  # longer than ~0.5 px
        assert len(arrows) >= len(visible)
        assert "μF = " in files[name]


def test_combined_force_read_off_the_plan_equals_exact(analysis):
    construction = analysis.forces.combined
    g = analysis.exercise.mechanism.gravity or 0.0
    assert construction.gravity_image_mm == pytest.approx(g / analysis.plans.scales.mu_a)
    for force in construction.forces:
        assert np.allclose(force.from_plan, force.exact, atol=1e-9 * (1 + np.hypot(
            *force.exact)))
        inertia = analysis.forces.solution.applied.inertia[force.link]
        assert np.allclose(force.exact, inertia.mass * (np.array([0.0, -g])
                                                        - inertia.acceleration[0]))


def test_combined_force_at_drafting_precision_is_close():
    exercise = load_exercise("exercises/combined_force_slider_crank.toml")
    rough = analyse(exercise, precision_mm=0.5)
    for force in rough.forces.combined.forces:
        exact = np.hypot(*force.exact)
        assert np.hypot(*np.subtract(force.from_plan, force.exact)) < 0.05 * exact + 0.05


def test_epsilon_rule_agrees_with_the_exact_sense():
    for exercise in EXERCISES:
        analysis = analyse(load_exercise(exercise))
        senses = epsilon_senses(analysis.plans)
        assert senses and all(sense.agrees for sense in senses if sense.rule is not None)


def test_aliyev_constants():
    analysis = analyse(load_exercise("exercises/combined_force_slider_crank.toml"))
    scales = analysis.plans.scales
    constants = combined_constants(analysis.plans, analysis.forces.solution.applied,
                                   analysis.forces.mu_f)
    assert constants.force_moment == pytest.approx(analysis.forces.mu_f * scales.mu_l)
    # eq. 2: proportional to the masses
    ratio = constants.combined_moment["BC"] / constants.combined_moment["AB"]
    assert ratio == pytest.approx(1.8 / 1.2)
    # eq. 3: the inertia moment read off the plan equals −J·ε
    entry = constants.inertia_moment["BC"]
    assert entry.from_plan == pytest.approx(entry.exact_moment, rel=1e-9)
    assert entry.constant == pytest.approx(6e-3 * scales.mu_a / 0.18)


def test_combined_construction_needs_an_acceleration_plan():
    analysis = analyse(load_exercise("exercises/fourbar_forces.toml"), plans=False)
    assert combined_construction(None, analysis.forces.solution.applied, 9.81) is None
    assert analysis.forces.combined is None and analysis.forces.as_dict()


def _visible(piece, box) -> float:
    """The length of a segment inside a box."""
    (x0, y0), (x1, y1) = piece
    low, high = 0.0, 1.0
    for p, q in ((x0 - x1, x0 - box[0]), (x1 - x0, box[2] - x0), (y0 - y1, y0 - box[1]),
                 (y1 - y0, box[3] - y0)):
        if p == 0:
            if q < 0:
                return 0.0
            continue
        low, high = (max(low, q / p), high) if p < 0 else (low, min(high, q / p))
    return max(high - low, 0.0) * float(np.hypot(x1 - x0, y1 - y0))


def _unnamed_in_details(svg: str, edges) -> list[tuple[str, str]]:
    """(detail, force) of each force whose arrow a detail shows (8 px or more of it) and
    that the detail does not name."""
    root = ElementTree.fromstring(svg.encode("utf-8"))
    clips = {clip.get("id"): [float(clip[0].get(k)) for k in ("x", "y", "width", "height")]
             for clip in root.iter(SVG + "clipPath")}
    labels = {group.get("transform"): {text.get("data-points")
                                       for text in group.iter(SVG + "text")}
              for group in root.iter(SVG + "g") if group.get("class") == "detail labels"}
    out = []
    for detail in root.iter(SVG + "g"):
        if detail.get("class") != "detail":
            continue
        x, y, width, height = clips[detail.get("clip-path")[5:-1]]
        box = (x, y, x + width, y + height)
        named = labels.get(detail.get("transform"), set())
        for arrow in detail.iter(SVG + "g"):
            css = arrow.get("class") or ""
            if not css.startswith("arrow force") or "total" in css:
                continue
            line = arrow.find(SVG + "line")
            piece = ((float(line.get("x1")), float(line.get("y1"))),
                     (float(line.get("x2")), float(line.get("y2"))))
            label = edges[int(arrow.get("data-step")) - 1].label
            if _visible(piece, box) >= 8.0 and label not in named:
                out.append((detail.get("clip-path"), label))
    return out


def test_a_detail_names_every_force_it_shows():
    """In an enlarged detail of a force polygon, every force whose arrow the detail shows
    (8 px or more of it) is labelled there, by its own name: the label of a force whose
    middle lies outside the detail goes on the part of its arrow the detail shows (the
    conveyor's G₂ went unnamed in detail II, and Fᵘ₂'s label sat on its arrow)."""
    analysis = analyse(load_exercise("exercises/conveyor_sixbar.toml"))
    group = analysis.forces.solution.groups.groups[0]
    edges = [edge for edge in group.polygon if float(np.linalg.norm(edge.vector[0])) > 0]
    files = force_files(analysis.forces, analysis.plans)
    svg = files[next(name for name in files if name.startswith("forces_1_"))]
    assert 'class="detail"' in svg
    assert _unnamed_in_details(svg, edges) == []
