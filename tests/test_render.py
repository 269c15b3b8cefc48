"""The SVG drawings and the sweep plots: well-formed, deterministic, complete, legible."""

from __future__ import annotations

import dataclasses
import math
import subprocess
import sys
import xml.etree.ElementTree as ET
from itertools import combinations

import numpy as np
import pytest

from planmethod.errors import PlanmethodError
from planmethod.plans import draw_plans
from planmethod.render.figures import plan_files
from planmethod.render.labels import label_runs, plain
from planmethod.render.plots import save_sweep_plot
from planmethod.render.svg import (
    lever_drawing,
    plan_drawing,
    plan_svg,
    position_drawing,
    position_svg,
    turning_arrow,
)
from planmethod.spec import exercise_from_dict, load_exercise

SEED = "exercises/compressor_slider_crank.toml"
SVG = "{http://www.w3.org/2000/svg}"


def four_bar(angle: float = 60.0):
    """A crank-rocker four-bar with a coupler point E off the coupler line."""
    return exercise_from_dict({
        "title": "Four-bar with coupler point",
        "drive": {"link": "crank", "pivot": "A", "angle": angle, "omega": 10, "epsilon": 5},
        "links": {"frame": {"A": [0, 0], "D": [0.12, 0]},
                  "crank": {"A": [0, 0], "B": [0.04, 0]},
                  "coupler": {"B": [0, 0], "C": [0.10, 0], "E": [0.05, 0.04]},
                  "rocker": {"D": [0, 0], "C": [0.08, 0]}},
        "sketch": {"C": [0.12, 0.08]},
        "plan": {"crank_mm": 30, "velocity_mm": 30, "acceleration_mm": 30},
        "ask": {"velocity": ["C", "E"], "acceleration": ["C", "E"], "curvature": ["E"]},
    })


def slotted_lever(angle: float = 60.0):
    """A crank and slotted lever: the block B slides on the lever (Coriolis)."""
    return exercise_from_dict({
        "title": "Crank and slotted lever",
        "drive": {"link": "crank", "pivot": "O1", "angle": angle, "omega": 10, "epsilon": 0},
        "links": {"frame": {"O1": [0, 0.1], "O2": [0, 0]},
                  "crank": {"O1": [0, 0], "B": [0.05, 0]},
                  "block": {"B": [0, 0]},
                  "lever": {"O2": [0, 0], "C": [0.25, 0]}},
        "slide": [{"link": "block", "along": "lever", "through": "O2", "direction": 0,
                   "point": "B"}],
        "plan": {"crank_mm": 30, "velocity_mm": 40, "acceleration_mm": 40},
    })


def _seed(angle=None, precision=None):
    exercise = load_exercise(SEED)
    settings = (dataclasses.replace(exercise.plan, precision_mm=precision)
                if precision is not None else None)
    return draw_plans(exercise, angle, settings=settings)


CASES = {
    "seed 45°": lambda: _seed(),
    "seed dead centre": lambda: _seed(0.0),
    "seed 0.5 mm": lambda: _seed(45.0, 0.5),
    "four-bar": lambda: draw_plans(four_bar()),
    "slotted lever": lambda: draw_plans(slotted_lever()),
}


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request):
    return request.param


@pytest.fixture(scope="module")
def plans(case):
    return CASES[case]()


def _drawings(plans):
    return {"position": position_drawing(plans.position, plans=plans),
            "velocity": plan_drawing(plans.velocity),
            "acceleration": plan_drawing(plans.acceleration),
            "lever": lever_drawing(plans)}


def _label_points(svg_text: str) -> set[str]:
    """The points named by labels (not the numerals of enlarged details)."""
    root = ET.fromstring(svg_text.encode("utf-8"))
    names = set()
    for text in root.iter(SVG + "text"):
        if text.get("class") in ("label", "faint"):
            names.update(name for name in text.get("data-points", "").split()
                         if not name.startswith("detail:"))
    return names


def test_every_drawing_is_well_formed_svg(plans):
    for name, text in plan_files(plans).items():
        root = ET.fromstring(text.encode("utf-8"))
        assert root.tag == SVG + "svg", name
        width, height = float(root.get("width")), float(root.get("height"))
        assert width > 100 and height > 100, name
        assert len(root.get("viewBox").split()) == 4


def _legend_texts(svg_text: str) -> list[str]:
    root = ET.fromstring(svg_text.encode("utf-8"))
    return [text.text or "" for text in root.iter(SVG + "text") if text.get("class") == "legend"]


def test_each_plan_has_its_own_plans_legend(plans):
    """The velocity plans (and the lever, the velocity plan turned) speak of velocities, the
    acceleration plan of accelerations."""
    files = plan_files(plans)
    for name in ("velocity", "lever", "acceleration"):
        legend = " ".join(_legend_texts(files[f"{name}.svg"]))
        own, other = (("velocity", "acceleration") if name != "acceleration"
                      else ("acceleration", "velocity"))
        assert f"absolute {own} (result)" in legend, (name, legend)
        assert f"absolute {other}" not in legend, (name, legend)


def test_output_is_byte_identical_for_the_same_input(case, plans):
    again = CASES[case]()              # a fresh solve: nothing shared with the first
    assert again is not plans
    assert plan_files(plans) == plan_files(again)


def _zero_coriolis(plan) -> set[str]:
    """The Coriolis points of a zero Coriolis term (a guide that does not turn)."""
    return {step.end for step in plan.steps if getattr(step, "component", None) == "coriolis"
            and np.allclose(plan.points_mm[step.end], plan.points_mm[step.start], atol=1e-9)}


def test_every_plan_point_is_labelled(plans):
    """Every plan point is labelled but a Coriolis point of a zero term: the course neither
    draws nor names it."""
    for plan in (plans.velocity, plans.acceleration):
        hidden = _zero_coriolis(plan)
        assert _label_points(plan_svg(plan)) == set(plan.points_mm) - hidden
    names = set(plans.position.points_mm)
    assert _label_points(position_svg(plans.position)) >= names
    lever = _label_points(lever_drawing(plans).svg)
    assert lever >= names | set(plans.velocity.points_mm)


def test_no_two_label_boxes_overlap(plans):
    for name, drawing in _drawings(plans).items():
        for first, second in combinations(drawing.labels, 2):
            ax0, ay0, ax1, ay1 = first.box
            bx0, by0, bx1, by1 = second.box
            apart = ax1 <= bx0 or bx1 <= ax0 or ay1 <= by0 or by1 <= ay0
            assert apart, (name, first.text, second.text)


def test_labels_keep_clear_of_drawn_lines(plans, monkeypatch):
    """No drawn line runs through the text of a label (its box less the padding)."""
    from shapely import unary_union
    from shapely.geometry import LineString, box

    import planmethod.render.canvas as canvas_module

    seen = []
    original = canvas_module.place_labels

    def spy(requests, lines, areas, **keywords):
        placed = original(requests, lines, areas, **keywords)
        seen.append((placed, unary_union([LineString(line) for line in lines])))
        return placed

    monkeypatch.setattr(canvas_module, "place_labels", spy)
    _drawings(plans)
    assert len(seen) >= 4                       # the four drawings, and any detail of them
    for placed, lines in seen:
        for label in placed:
            x0, y0, x1, y1 = label.box
            assert box(x0 + 2, y0 + 2, x1 - 2, y1 - 2).intersection(lines).length < 0.5, \
                label.text


def test_every_laid_off_vector_is_an_arrow(plans):
    for plan in (plans.velocity, plans.acceleration):
        drawing = plan_drawing(plan)
        root = ET.fromstring(drawing.svg.encode("utf-8"))
        arrows = {g.get("data-step") for g in root.iter(SVG + "g")
                  if "arrow" in (g.get("class") or "")}
        for step in plan.steps:
            if step.action == "lay_off" and step.length_mm > 0.05:
                assert str(step.number) in arrows, (plan.kind, step)
                assert step.number in drawing.arrow_steps
        # every arrow has its head: a filled polygon ending at the plan point
        for group in root.iter(SVG + "g"):
            if "arrow" in (group.get("class") or ""):
                assert group.find(SVG + "polygon") is not None


def test_results_are_bold_and_heads_sit_on_the_images():
    plans = _seed()
    plan = plans.velocity
    root = ET.fromstring(plan_svg(plan).encode("utf-8"))
    layer = next(g for g in root.iter(SVG + "g") if g.get("class") == "results")
    tips, zoom = [], None
    b = plan.points_mm["b"]
    for group in layer:
        line = group.find(SVG + "line")
        assert float(line.get("stroke-width")) > 2                          # bold
        assert (float(line.get("x1")), float(line.get("y1"))) == (0.0, 0.0)  # from p
        first = group.find(SVG + "polygon").get("points").split()[0]
        tips.append(tuple(float(v) for v in first.split(",")))
        if group.get("data-step") == "3":        # step 3 lays off v_B from p
            zoom = tips[-1][0] / b[0]
    assert len(tips) == 3                                                    # pb, pc, pd
    assert zoom > 0
    expected = sorted((zoom * plan.points_mm[k][0], -zoom * plan.points_mm[k][1])
                      for k in ("b", "c", "d"))
    assert np.allclose(sorted(tips), expected, atol=0.02)


def test_coincident_points_share_one_merged_label():
    plans = _seed(0.0)                 # dead centre: c is at the pole
    labels = plan_drawing(plans.velocity).labels
    at_pole = next(label for label in labels if "p" in label.points)
    assert at_pole.points[0] == "p"
    assert {"a", "c@frame", "c"} <= set(at_pole.points)
    assert at_pole.text.startswith("p ≡ a ≡")


def test_scales_are_printed_with_units():
    plans = _seed()
    assert "μv = 0.2 (m/s)/mm" in plan_svg(plans.velocity)
    assert "μa = 20 (m/s²)/mm" in plan_svg(plans.acceleration)
    assert "μl = 0.002 m/mm" in position_svg(plans.position)
    assert "drafting precision 0.5 mm" in plan_svg(_seed(45.0, 0.5).velocity)


def test_coriolis_and_relative_components_have_their_own_style():
    plans = draw_plans(slotted_lever())
    root = ET.fromstring(plan_svg(plans.acceleration).encode("utf-8"))
    classes = {g.get("class") for g in root.iter(SVG + "g")}
    assert {"arrow coriolis", "arrow normal", "arrow tangential", "arrow result"} <= classes
    colours = {}
    for group in root.iter(SVG + "g"):
        if (group.get("class") or "").startswith("arrow "):
            colours.setdefault(group.get("class"), set()).add(
                group.find(SVG + "line").get("stroke"))
    assert len({frozenset(c) for c in colours.values()}) == len(colours)
    legend = plan_svg(plans.acceleration)
    assert "Coriolis component aᵏ" in legend and "relative (sliding) component aʳ" in legend


def test_flagged_intersection_is_marked():
    plans = _seed()
    plan = plans.velocity
    steps = tuple(step._replace(flagged=True, angle_deg=0.7)
                  if step.action == "intersect" else step for step in plan.steps)
    flagged = dataclasses.replace(plan, steps=steps,
                                  flags=("velocity plan, group BC: the lines meet at 0.7°",))
    text = plan_svg(flagged)
    root = ET.fromstring(text.encode("utf-8"))
    rings = [c for c in root.iter(SVG + "circle") if c.get("class") == "flagged"]
    assert len(rings) == 1
    assert "0.7°" in text and "the lines meet at 0.7°" in text
    assert "flagged" not in plan_svg(plan)


def test_position_plan_symbols():
    plans = _seed()
    root = ET.fromstring(position_svg(plans.position, plans=plans).encode("utf-8"))
    classes = [element.get("class") or "" for element in root.iter()]
    assert classes.count("support") == 1               # one fixed pivot, A
    assert any(c.startswith("slider") for c in classes)
    assert classes.count("pair") == 3                  # A, B, C
    assert "omega" in " ".join(classes)
    # the curvature of D's path: tangent, normal, centre and ρ
    assert {"tangent", "normal", "centre", "arrow rho"} <= set(classes)
    text = position_svg(plans.position)
    assert "ρ" in text and "0.07377 m" in text


def test_ternary_link_is_a_polygon_and_lever_lies_on_the_mechanism():
    plans = draw_plans(four_bar())
    root = ET.fromstring(position_svg(plans.position).encode("utf-8"))
    polygons = [p for p in root.iter(SVG + "polygon") if p.get("class") == "link coupler"]
    assert len(polygons) == 1 and len(polygons[0].get("points").split()) == 3
    lever = lever_drawing(plans)
    pole = next(label for label in lever.labels if "p" in label.points)
    pivot = next(label for label in lever.labels if label.points == ("A",))
    assert pole.anchor == pivot.anchor                 # p at the drive's pivot A


def test_textbook_labels():
    assert label_runs("c4") == (("c", "main"), ("4", "upright"))
    assert plain(label_runs("b@lever")) == "b lever"      # no numbering: the link's name
    assert label_runs("k_block/lever")[1] == ("block/lever", "upright")
    plans = draw_plans(slotted_lever())
    assert plans.velocity.numbers == {"frame": 0, "crank": 1, "block": 2, "lever": 3}

    def spans(svg: str, point: str) -> list[str]:
        root = ET.fromstring(svg.encode("utf-8"))
        label = next(text for text in root.iter(SVG + "text")
                     if point in text.get("data-points", "").split())
        return [span.text for span in label.iter(SVG + "tspan")]

    assert spans(plan_svg(plans.velocity), "b@lever") == ["b", "3"]    # b₃: B of link 3
    assert spans(plan_svg(plans.acceleration), "k_B@lever") == ["k", "B", "3"]    # k_B₃


def test_jupyter_shows_plans_as_svg():
    """In IPython, a plan and the position plan display as their SVG drawings (the formatters
    are registered from the top of the import graph; the plans themselves draw nothing)."""
    pytest.importorskip("IPython")
    from IPython.core.formatters import DisplayFormatter

    import planmethod

    class Shell:
        display_formatter = DisplayFormatter()

    planmethod.load_ipython_extension(Shell())
    plans = _seed()
    svg = Shell.display_formatter.formatters["image/svg+xml"]
    assert svg(plans.velocity) == plan_svg(plans.velocity)
    assert svg(plans.position) == position_svg(plans.position)
    assert not hasattr(plans.velocity, "_repr_svg_")


def test_plan_files_without_acceleration():
    plans = draw_plans(load_exercise(SEED), acceleration=False)
    assert sorted(plan_files(plans)) == ["lever.svg", "position.svg", "velocity.svg"]


def test_import_planmethod_imports_no_drawing_library():
    code = ("import sys, planmethod, planmethod.render, planmethod.render.svg; "
            "print(sorted(m for m in ('svgwrite', 'matplotlib', 'shapely') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]"


# -- sweep plots -----------------------------------------------------------------------------------
def _table():
    angle = np.arange(0.0, 360.0, 5.0)
    radians = np.radians(angle)
    return {"angle": angle, "x_C": np.cos(radians), "v_C": np.abs(np.sin(radians)),
            "a_C": np.abs(np.cos(radians)), "omega_BC": np.cos(radians),
            "epsilon_BC": np.sin(radians), "s_slider/frame": 1 + np.cos(radians),
            "ds_slider/frame": -np.sin(radians), "dds_slider/frame": -np.cos(radians),
            "rho_D": np.where(np.abs(np.sin(radians)) > 1e-9, 1 / np.abs(np.sin(radians) + 2),
                              np.inf),
            "M_balancing": 3 * np.sin(2 * radians)}


@pytest.mark.parametrize("suffix", ["png", "svg", "pdf"])
def test_sweep_plot_is_written_and_reproducible(tmp_path, suffix):
    first, second = tmp_path / f"a.{suffix}", tmp_path / f"b.{suffix}"
    save_sweep_plot(_table(), first, title="Test")
    save_sweep_plot(_table(), second, title="Test")
    assert first.stat().st_size > 1000
    assert first.read_bytes() == second.read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == [first.name, second.name]


def test_sweep_plot_panels():
    from planmethod.render.plots import panels
    from planmethod.words import render

    titles = [render(title) for title, _, _ in panels(_table())]
    assert titles[0].startswith("speed") and titles[-1] == "other columns"
    grouped = {render(title): columns for title, _, columns in panels(_table())}
    assert grouped["sliding acceleration d²s/dt²"] == ["dds_slider/frame"]
    assert grouped["other columns"] == ["M_balancing"]
    assert all("x_C" not in columns for columns in grouped.values())


def test_a_curve_that_repeats_another_is_dashed_over_it():
    """A block turning with its lever has the lever's ω over the whole turn: the second curve
    is dashed so that the first shows through; a curve that differs stays solid."""
    from planmethod.render.plots import Panel, _draw_panel, _new_figure

    angle = np.arange(0.0, 360.0, 5.0)
    omega = 10 + 3 * np.sin(np.radians(angle))
    table = {"angle": angle, "omega_block": omega, "omega_lever": omega.copy(),
             "omega_rod": omega * 1.001}
    axis = _new_figure().add_subplot()
    _draw_panel(axis, table, angle, Panel("ω", "rad/s", ["omega_block", "omega_lever",
                                                            "omega_rod"]), None)
    styles = [line.get_linestyle() for line in axis.get_lines()]
    assert styles == ["-", "--", "-"]


@pytest.mark.parametrize("table, name", [
    (_table(), "curves.jpg"),
    ({"v_C": np.ones(3)}, "curves.png"),
    ({"angle": np.arange(3.0), "v_C": np.ones(4)}, "curves.png"),
    ({"angle": np.arange(3.0)}, "curves.png"),
])
def test_sweep_plot_bad_input_leaves_no_file(tmp_path, table, name):
    with pytest.raises(PlanmethodError):
        save_sweep_plot(table, tmp_path / name, title="Test")
    assert list(tmp_path.iterdir()) == []


def test_sweep_plot_failure_while_writing_leaves_no_file(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    def broken(self, target, **kwargs):
        with open(target, "wb") as handle:
            handle.write(b"half a picture")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(Figure, "savefig", broken)
    with pytest.raises(PlanmethodError, match="cannot write"):
        save_sweep_plot(_table(), tmp_path / "curves.png", title="Test")
    assert list(tmp_path.iterdir()) == []


# -- plots leave the caller's matplotlib alone -------------------------------------------------
def _force_table():
    angle = np.arange(0.0, 360.0, 15.0)
    radians = np.radians(angle)
    return {"angle": angle, "Rx_B": np.cos(radians), "Ry_B": np.sin(radians),
            "R_B": np.ones_like(angle), "M_b": np.sin(2 * radians)}


def test_plots_use_neither_pyplot_nor_the_callers_settings(tmp_path):
    """Every plot is drawn through matplotlib's object API: the caller's backend and rcParams
    are the same afterwards, pyplot is never imported, and what the caller set does not change
    the picture."""
    code = r"""
import sys, pathlib, matplotlib, numpy as np
matplotlib.use("svg")
from planmethod.render.plots import save_force_plot, save_sweep_plot
sys.path.insert(0, "tests")
from test_render import _force_table, _table
out = pathlib.Path(sys.argv[1])
save_sweep_plot(_table(), out / "plain.svg", title="T")
save_force_plot(_force_table(), out / "plain_forces.svg", title="T")
matplotlib.rcParams.update({"lines.linewidth": 7.0, "axes.facecolor": "#ffff00",
                            "axes.titlesize": 30.0})
before = dict(matplotlib.rcParams)
save_sweep_plot(_table(), out / "styled.svg", title="T")
save_force_plot(_force_table(), out / "styled_forces.svg", title="T")
changed = sorted(k for k, v in matplotlib.rcParams.items() if before[k] != v)
print(matplotlib.get_backend(), changed, "matplotlib.pyplot" in sys.modules)
"""
    done = subprocess.run([sys.executable, "-c", code, str(tmp_path)], capture_output=True,
                          text=True, check=True)
    assert done.stdout.split() == ["svg", "[]", "False"], done.stdout + done.stderr
    assert (tmp_path / "plain.svg").read_bytes() == (tmp_path / "styled.svg").read_bytes()
    assert ((tmp_path / "plain_forces.svg").read_bytes()
            == (tmp_path / "styled_forces.svg").read_bytes())


def test_a_plot_with_an_unknown_suffix_names_the_formats(tmp_path):
    from planmethod.render.plots import save_force_plot

    with pytest.raises(PlanmethodError, match=r"plot format '\.txt' not supported; use "
                                              r"\.png, \.svg or \.pdf"):
        save_force_plot(_force_table(), tmp_path / "curves.txt", title="T")
    assert list(tmp_path.iterdir()) == []


def test_the_blank_sheet_has_its_grid_drawn():
    """The blank plan sheet is drawn on the canvas: a 10 mm grid pattern whose path has its
    geometry, a rectangle filled with it, the pole, and the root markers the reader uses."""
    from planmethod.grading.sheets import blank_plan_sheet

    sheet = blank_plan_sheet("velocity", pole="p", scale=0.2, unit="(m/s)/mm", size_mm=120,
                             student="s01", title="T")
    root = ET.fromstring(sheet.encode("utf-8"))
    pattern = root.find(f"{SVG}defs/{SVG}pattern")
    assert pattern.get("id") == "grid" and pattern.get("width") == "10"
    assert pattern.find(f"{SVG}path").get("d") == "M 10 0 L 0 0 0 10"
    assert any(rect.get("fill") == "url(#grid)" for rect in root.iter(f"{SVG}rect"))
    assert root.get("width") == "120mm" and root.get("data-planmethod-student") == "s01"


@pytest.mark.parametrize("path", ["exercises/compressor_slider_crank.toml",
                                  "exercises/conveyor_sixbar.toml",
                                  "exercises/slotted_lever.toml",
                                  "exercises/shaper_sixbar.toml"])
def test_every_construction_element_says_its_step_for_playback(path):
    """The workbook's construction playback shows an element from the step that draws it: so
    every arrow, line and link image of a plan carries that step's number."""
    from defusedxml import ElementTree as SafeTree

    from planmethod.plans import draw_plans
    from planmethod.render.svg import plan_svg

    plans = draw_plans(load_exercise(path))
    for plan in (plans.velocity, plans.acceleration):
        steps = {step.number for step in plan.steps}
        root = SafeTree.fromstring(plan_svg(plan, details=False).encode("utf-8"))
        for layer in root.iter("{http://www.w3.org/2000/svg}g"):
            if layer.get("class") not in ("components", "results", "similarity",
                                          "construction"):
                continue
            for element in layer:
                assert element.get("data-step") is not None, (plan.kind, element.attrib)
                assert int(element.get("data-step")) in steps


def test_labels_that_find_no_free_spot_go_below_all_others():
    """Crowd one point with more labels than its candidate spots hold: the ones that find no
    free spot are put below everything (with a leader), and still no two boxes overlap."""
    from planmethod.render.labels import LabelRequest, place_labels

    requests = [LabelRequest((f"p{k}",), (0.0, 0.0), label_runs(f"p{k}"), 15.0)
                for k in range(160)]
    placed = place_labels(requests, [((-300.0, 0.0), (300.0, 0.0))], [(-3, -3, 3, 3)])
    assert len(placed) == len(requests)
    below = [label for label in placed if label.leader and label.box[1] > 84.0]
    assert below                                   # some had to go below everything
    for first, second in combinations(placed, 2):
        ax0, ay0, ax1, ay1 = first.box
        bx0, by0, bx1, by1 = second.box
        assert ax1 <= bx0 or bx1 <= ax0 or ay1 <= by0 or by1 <= ay0, (first.text, second.text)


def _curved_arrow_in_a_grid(along_its_arc: bool):
    """A moment's curved arrow (radius 100 px round the origin) whose label's point, the
    middle of its arc, is the middle of a grid of ten arrows 16 px apart: every spot near it
    is on a line, every leader from it crosses an arrow. ``along_its_arc``: the label names
    its arc (as :func:`turning_arrow` asks), else only its point."""
    from planmethod.render.canvas import Canvas
    from planmethod.render.labels import RunKind

    figure = Canvas()
    turning_arrow(figure, (0.0, 0.0), 100.0, 0.0, 1.0, "#000000", "M", (("M", RunKind.MAIN),))
    if not along_its_arc:
        figure.requests[-1] = dataclasses.replace(figure.requests[-1], span=None)
    x, y = figure.requests[-1].anchor
    for step in (-32.0, -16.0, 0.0, 16.0, 32.0):
        for start, end in (((x - 32, y + step), (x + 32, y + step)),
                           ((x + step, y - 32), (x + step, y + 32))):
            figure.arrow(np.array(start), np.array(end), "relative", layer="results",
                         color="#000000", css="load")
    figure.place()
    return figure, (x, y)


def test_a_crowded_moment_label_leads_from_elsewhere_on_its_arc():
    """A curved arrow's label whose every spot round the arc's middle is crowded takes a
    clear spot with its leader from another place on its arc (it names the arc), where from
    the middle alone its leader would cross an arrow."""
    from planmethod.testing.figures import figure_problems

    alone, _ = _curved_arrow_in_a_grid(False)
    assert "the leader of 'M' crosses an arrow" in " ".join(figure_problems(alone.svg("").svg))
    figure, middle = _curved_arrow_in_a_grid(True)
    assert figure_problems(figure.svg("").svg) == []
    label = figure.labels[0]
    assert label.requested == middle and label.anchor != middle
    assert math.hypot(*label.anchor) == pytest.approx(100.0, abs=0.5)   # on the arc


def test_a_keys_blank_sheet_whole():
    """The blank velocity sheet of the compressor's key, as a student prints it: 120 mm
    square (the plan and a 20 mm margin, at least 120 mm) under a 12 mm header of three
    lines at most — title, plan, student, scale, the given first vector, what to do, the
    grid — a faint 10 mm grid in a frame, the pole p marked at the centre."""
    from planmethod.grading.keys import build_key
    from planmethod.grading.sheets import plan_sheet_for_key
    from planmethod.grading.templates import draw_variant, load_template

    key = build_key(draw_variant(load_template("exercises/compressor_slider_crank.toml")))
    assert plan_sheet_for_key(key, "velocity") == (
        '<?xml version="1.0" encoding="utf-8"?>\n'
        '<svg baseProfile="full" data-planmethod-plan="velocity" data-planmethod-student="1" '
        'height="132mm" version="1.1" viewBox="0 0 120 132" width="120mm" xmlns="http://www.w'
        '3.org/2000/svg" xmlns:ev="http://www.w3.org/2001/xml-events" xmlns:xlink="http://www'
        '.w3.org/1999/xlink">\n'
        '<title>Compressor slider-crank (Abduvaliev &amp; Abduxoshimov) — blank velocity plan'
        ' sheet</title>\n'
        '<defs><pattern height="10" id="grid" patternUnits="userSpaceOnUse" width="10"><path '
        'd="M 10 0 L 0 0 0 10" fill="none" stroke="#c9cede" stroke-width="0.2" /></pattern></'
        'defs>\n'
        '<rect class="background" fill="#ffffff" height="132" width="120" x="0" y="0" />\n'
        '<g class="ground">\n'
        '<rect class="grid" fill="url(#grid)" height="120" stroke="#99a" stroke-width="0.3" w'
        'idth="120" x="0" y="12" />\n'
        '</g>\n'
        '<g class="points">\n'
        '<circle class="pole" cx="60" cy="72" fill="#000000" r="0.8" />\n'
        '</g>\n'
        '<g class="text">\n'
        '<text class="header" fill="#000000" font-family="DejaVu Sans, Verdana, Arial, Helvet'
        'ica, sans-serif" font-size="2.6" x="3" y="4">Compressor slider-crank (Abduvaliev &am'
        'p; Abduxoshimov) — velocity plan — 1 — μv = 0.2</text>\n'
        '<text class="header" fill="#000000" font-family="DejaVu Sans, Verdana, Arial, Helvet'
        'ica, sans-serif" font-size="2.6" x="3" y="7.2">(m/s)/mm. (pb) = 30 mm. Draw the plan'
        ' from the pole p; label every point (b, c, …)</text>\n'
        '<text class="header" fill="#000000" font-family="DejaVu Sans, Verdana, Arial, Helvet'
        'ica, sans-serif" font-size="2.6" x="3" y="10.4">next to it. (grid: 10 mm)</text>\n'
        '<text class="pole-label" fill="#000000" font-family="DejaVu Serif, Georgia, Times Ne'
        'w Roman, serif" font-size="5" x="61.5" y="70.5">p</text>\n'
        '</g>\n'
        '</svg>\n')
    # a plan of 79 mm from the pole gets a sheet of 2·79 + 40 → 200 mm; no lay-off: no given
    wide = {**key, "student": "s9", "title": "W"}
    entry = dict(key["plans"]["acceleration"], steps=[])
    entry["points_mm"] = {**entry["points_mm"], "far": [0.0, 79.0]}
    wide["plans"] = {**key["plans"], "acceleration": entry}
    root = ET.fromstring(plan_sheet_for_key(wide, "acceleration").encode("utf-8"))
    assert (root.get("width"), root.get("viewBox")) == ("200mm", "0 0 200 212")
    header = " ".join(text.text for text in root.iter(f"{SVG}text")
                      if text.get("class") == "header")
    assert header == ("W — acceleration plan — s9 — μa = " + f"{entry['scale']:g}" + " (m/s²)/mm.  "
                      "Draw the plan from the pole π; label every point (b, c, …) next to it. "
                      "(grid: 10 mm)")


@pytest.mark.parametrize("unit, attributes, title", [
    ("", {}, "a plan, φ₁ = 45°"),
    ("mm", {"data-kind": "plan", "aria-label": 'a "plan" & <more>\n\tx'}, "T & <x> \"q\"\n"),
    ("", {"data-x": "a\x01b"}, "bad \x02 character"),
])
def test_the_svg_shell_is_what_svgwrite_and_elementtree_write(unit, attributes, title):
    """The document's shell is written by hand; svgwrite with ElementTree writes the same."""
    import svgwrite

    from planmethod.render.canvas import _shell
    from planmethod.render.style import num
    from planmethod.vocabulary import xml_characters

    width, height, x0, y0 = 1057.567, 623.661, -524.4, -118.04
    drawing = svgwrite.Drawing(size=(num(width) + unit, num(height) + unit), profile="full",
                               debug=False)
    drawing["viewBox"] = f"{num(x0)} {num(y0)} {num(width)} {num(height)}"
    for key, value in attributes.items():
        drawing[key] = xml_characters(value)
    drawing.set_desc(title=xml_characters(title))
    drawing.add(drawing.rect(insert=(num(x0), num(y0)), size=(num(width), num(height)),
                             fill="#ffffff", class_="background"))
    expected = ET.tostring(drawing.get_xml(), encoding="unicode")
    assert _shell(width, height, unit, (x0, y0), attributes, title) == expected


# -- the animation's frames ---------------------------------------------------------------------
def _shaper_frames(angles=(60.0, 200.0)):
    from planmethod.application.animating import _drawings
    from planmethod.report import analyse

    exercise = load_exercise("exercises/shaper_sixbar.toml")
    analyses = [analyse(exercise, angle) for angle in angles]
    return analyses, _drawings(exercise, list(angles), analyses)


def test_an_animations_frames_are_the_projects_own_drawings_at_their_proportions():
    """A GIF's frame is the row of drawings the SVG animation shows (the same labels), each
    drawing as high as a cell and as wide as its steady page: no frame letterboxed, and every
    frame of the turn the same size."""
    pytest.importorskip("cairosvg", reason="the GIF's frames are drawn by CairoSVG")
    from planmethod.render.animation import CELL_HEIGHT, frame_svg, rendered_frames

    _, frames = _shaper_frames()
    widths = [sum(CELL_HEIGHT * figure.view[2] / figure.view[3] for figure in row)
              for row in frames]
    images = rendered_frames(frames)
    assert [image.size for image in images] == [(round(widths[0]), CELL_HEIGHT)] * 2
    text = frame_svg(frames[0])     # each drawing whole: its texts, labels placed as it placed them
    assert text.count("<text") == sum(figure.svg.count("<text") for figure in frames[0])
    pixels = np.asarray(images[0])
    assert (pixels < 128).any() and (pixels > 250).mean() > 0.5


def test_the_raster_fallback_names_points_as_the_course_writes_them():
    """Without CairoSVG the frames are drawn by matplotlib: points named O₁, b₃ (never O1,
    b@lever), coincident ones joined by ≡, the frame not drawn as a bar, the lever's slot
    drawn through the block."""
    from planmethod.render.animation import _draw_mechanism, _draw_plan
    from planmethod.render.plots import _new_figure

    analyses, _ = _shaper_frames((60.0,))
    plans = analyses[0].plans
    figure = _new_figure()
    mechanism, velocity = figure.subplots(1, 2)
    mechanism.set_xlim(-200, 200), mechanism.set_ylim(-200, 200)
    _draw_mechanism(mechanism, plans.position)
    _draw_plan(velocity, plans.velocity)
    named = {text.get_text() for text in mechanism.texts}
    assert {"O₁", "O₂", "B", "C", "D"} <= named and not any("1" in name for name in named)
    frame = plans.position.points_mm
    bars = [line.get_xydata() for line in mechanism.get_lines() if line.get_linewidth() > 2]
    assert not any({tuple(point) for point in bar} <= {tuple(frame[name]) for name in
                                                       plans.position.links["frame"]}
                   for bar in bars if len(bar) >= 2)
    labels = {text.get_text() for text in velocity.texts}
    assert "b₃" in labels and not any("@" in label for label in labels)
    assert any("≡" in label for label in labels)
