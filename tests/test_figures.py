"""Every figure of every shipped exercise passes the figure check (no code word, no two texts
overlapping, nothing outside the viewBox, every legend item drawn); Zhukovsky's lever carries
its forces and states the report's M_b; every exercise with forces has its loaded mechanism."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from planmethod.render.figures import plan_files
from planmethod.report import analyse, report_dict
from planmethod.spec import load_exercise
from planmethod.testing.figures import figure_problems

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = sorted((ROOT / "exercises").glob("*.toml"))


@pytest.fixture(scope="module", params=EXERCISES, ids=lambda path: path.stem)
def drawn(request):
    exercise = load_exercise(request.param)
    analysis = analyse(exercise)
    return exercise, analysis, plan_files(analysis.plans, analysis.forces)


def test_every_figure_passes_the_figure_check(drawn):
    _, _, files = drawn
    found = [f"{name}: {problem}" for name, svg in files.items()
             for problem in figure_problems(svg)]
    assert not found, "\n".join(found[:20])


def test_the_lever_states_the_reports_moment_and_draws_each_force(drawn):
    """Every force is drawn at its image and labelled — an inertia couple as the force pair
    the sum counts — each arm from p is labelled h₁, h₂ …, and the sum is a table beside the
    drawing ending in ΣM_p = 0 and the report's M_b."""
    _, analysis, files = drawn
    if analysis.forces is None:
        pytest.skip("no forces in this exercise")
    report = report_dict(analysis)
    moment = report["forces"]["zhukovsky_moment"]
    lever = files["lever.svg"]
    assert f"M_b = {moment:.6g} N·m (Zhukovsky's lever)" in lever
    drawn_forces = {force.name for force in analysis.forces.solution.lever.forces
                    if not force.name.startswith("M_f") and any(force.force[0])}
    labelled = set(re.findall(r'data-points="force:([^"]+)"', lever))
    assert labelled == drawn_forces | {"F_b"}                 # each force named at its image
    from defusedxml import ElementTree

    root = ElementTree.fromstring(lever.encode("utf-8"))
    results = next(group for group in root if group.get("class") == "results")
    arrows = [g for g in results if g.get("class") == "arrow lever force"]  # not the details'
    assert len(drawn_forces) // 2 < len(arrows) <= len(drawn_forces) + 1
    arms = set(re.findall(r'data-points="arm:([^"]+)"', lever))
    assert arms and arms <= labelled                            # h₁, h₂ … on the arms
    rows = re.findall(r'<text class="table"[^>]*>([^<]*)', lever)
    assert "ΣM" in rows and "+0" in rows and "force" in rows    # the sum, term by term


def test_every_exercise_with_forces_has_its_loaded_mechanism(drawn):
    """The loaded mechanism draws each weight, marks every centre of mass S and lists every
    force and moment in a table beside the drawing, down to M_b."""
    _, analysis, files = drawn
    assert ("loaded.svg" in files) == (analysis.forces is not None)
    if analysis.forces is not None:
        loaded = files["loaded.svg"]
        assert "the loaded mechanism" in loaded
        weights = [item for item in analysis.forces.solution.applied.items
                   if item.kind == "weight"]
        assert loaded.count('class="arrow load"') >= len(weights)
        masses = analysis.exercise.mechanism.masses
        marked = set(re.findall(r'<circle class="centre of mass"[^>]*data-points="S:([^"]+)"',
                                loaded))
        assert marked == set(masses)
        rows = re.findall(r'<text class="table"[^>]*>([^<]*)', loaded)
        assert len(rows) >= 4 * (len(weights) + 1) and "M" in rows     # M_b's row


def test_the_figure_check_can_fail():
    head = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 300 100">'
    text = '<text x="{x}" y="{y}" font-size="12">{t}</text>'
    assert figure_problems(head + text.format(x=10, y=50, t="load[1]") + "</svg>")
    assert figure_problems(head + text.format(x=10, y=50, t="F_u,rocker_EF") + "</svg>")
    assert not figure_problems(head + text.format(x=10, y=50, t="M_b = 4 N·m") + "</svg>")
    assert figure_problems(head + text.format(x=10, y=50, t="B")
                           + text.format(x=12, y=51, t="C") + "</svg>")
    assert not figure_problems(head + text.format(x=10, y=50, t="B")
                               + text.format(x=60, y=50, t="C") + "</svg>")
    assert figure_problems(head + text.format(x=290, y=50, t="a long text") + "</svg>")
    assert figure_problems(head + '<line x1="0" y1="0" x2="400" y2="0" stroke="#000"/></svg>')
    legend = ('<g class="text"><line x1="5" y1="5" x2="30" y2="5" stroke="#7b3fa0" '
              'stroke-dasharray="5,4"/></g>')
    drawn_line = ('<g class="construction"><line x1="5" y1="50" x2="90" y2="50" '
                  'stroke="#7b3fa0" stroke-dasharray="5,4"/></g>')
    assert figure_problems(head + legend + "</svg>")
    assert not figure_problems(head + drawn_line + legend + "</svg>")


def test_the_figure_check_follows_translations_and_clip_paths():
    head = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 300 200">'
    moved = ('<g transform="translate(100,0)"><text x="0" y="50" font-size="12">B</text>'
             '</g><text x="101" y="51" font-size="12">C</text>')
    assert any("overlaps" in p for p in figure_problems(head + moved + "</svg>"))
    clipped = ('<defs><clipPath id="k"><rect x="0" y="0" width="50" height="50"/></clipPath>'
               '</defs><g clip-path="url(#k)"><text x="120" y="150" font-size="12">B</text>'
               '<line x1="0" y1="0" x2="900" y2="0" stroke="#000"/></g>'
               '<text x="121" y="151" font-size="12">C</text>')
    assert not figure_problems(head + clipped + "</svg>")      # hidden by the clip path
    turned = '<g transform="rotate(30)"><text x="0" y="50" font-size="12">B</text></g>'
    assert figure_problems(head + turned + "</svg>")


def test_a_dense_region_gets_an_enlarged_detail(drawn):
    exercise, analysis, files = drawn
    from planmethod.render.details import dense_regions

    plan = analysis.plans.velocity
    where = {label: (x * 10.0, -y * 10.0) for label, (x, y) in plan.points_mm.items()}
    assert isinstance(dense_regions(where), list)
    if exercise.source.endswith("conveyor_sixbar.toml"):
        for name in ("velocity.svg", "acceleration.svg"):
            assert 'class="detail"' in files[name] and "detail I:" in files[name], name


@pytest.mark.parametrize("path", ["exercises/templates/slider_crank.toml",
                                  "exercises/templates/four_bar.toml",
                                  "exercises/conveyor_sixbar.toml"])
def test_task_and_plan_sheets_pass_the_figure_check(path):
    from planmethod.grading.keys import build_key
    from planmethod.grading.sheets import plan_sheet_for_key, task_sheet_svg
    from planmethod.grading.templates import draw_variant, load_template
    from planmethod.plans import draw_plans

    variant = draw_variant(load_template(path), seed=5, student="a")
    key = build_key(variant)
    answer_columns = [question["id"] for question in key["questions"]]
    sheets = {"task": task_sheet_svg(key, draw_plans(variant.exercise)),
              "velocity": plan_sheet_for_key(key, "velocity"),
              "acceleration": plan_sheet_for_key(key, "acceleration")}
    found = [f"{name}: {problem}" for name, svg in sheets.items()
             for problem in figure_problems(svg, allowed=answer_columns)]
    assert not found, "\n".join(found)
    # the answer-file column names are the only names printed as they are, in brackets
    assert figure_problems(sheets["task"])


def test_construction_sentences_use_the_course_notation(drawn):
    """The steps' sentences (shown in the workbook's playback, listed in the report) name
    points on links and quantities as a course does (c₁, ω₃, aʳ_CC₁), never by report name."""
    import re

    exercise, analysis, _ = drawn
    links = [name for name in exercise.mechanism.links if "_" in name]
    for plan in (analysis.plans.velocity, analysis.plans.acceleration):
        if plan is None:
            continue
        for step in plan.steps:
            assert "@" not in step.text, step.text
            assert not re.search(r"\b(?:omega|epsilon|rho|coriolis|a_rel|dds|ds)_", step.text), \
                step.text
            assert not any(re.search(rf"\b{name}\b", step.text) for name in links), step.text


def test_loads_are_printed_by_the_name_the_exercise_gives_them():
    import tomllib

    from planmethod.render.notation import ForceNotation
    from planmethod.spec import exercise_from_dict

    data = tomllib.loads((ROOT / "exercises/combined_force_slider_crank.toml")
                         .read_text(encoding="utf-8"))
    solution = analyse(exercise_from_dict(data)).forces.solution
    assert ForceNotation(solution).plain("load[1]") == "P₁"          # the default name
    data["load"][0]["name"] = "P_c"
    named = analyse(exercise_from_dict(data))
    assert ForceNotation(named.forces.solution).plain("load[1]") == "P_c"
    files = plan_files(named.plans, named.forces)
    from planmethod.testing.figures import text_boxes

    texts = [box.text for box in text_boxes(files["loaded.svg"])]
    assert texts.count("Pc") >= 2          # the label and the table's row: P, subscript c
    assert not any("load[" in text for text in texts)
    assert not figure_problems(files["loaded.svg"])


def test_the_crowding_check_can_fail():
    """A label nearer than the readable distance to another point's mark is a problem, unless
    the mark lies in a region drawn again as a detail."""
    head = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 300 100">'
    marks = ('<circle class="point" cx="50" cy="50" r="2.4" data-points="b"/>'
             '<circle class="point" cx="62" cy="50" r="2.4" data-points="c"/>')
    label = ('<g class="labels"><text class="label" data-points="b" x="52" y="47" '
             'font-size="15">b</text></g>')
    assert any("from the mark of c" in problem
               for problem in figure_problems(head + marks + label + "</svg>"))
    region = '<rect class="detail region" x="40" y="40" width="30" height="20" fill="none"/>'
    assert not figure_problems(head + region + marks + label + "</svg>")
    far = label.replace('x="52"', 'x="20"').replace('y="47"', 'y="30"')
    assert not figure_problems(head + marks + far + "</svg>")


#: the conventions a course may choose, as [notation] tables
CONVENTIONS = {"papers": {}, "frame last": {"frame": "last"}, "frame 1": {"frame": 1}}


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("name", ["conveyor_sixbar", "shaper_sixbar", "scotch_yoke"])
def test_every_figure_numbers_links_as_its_convention_does(name, convention):
    """The numbering rule, a test per convention: the crank's φ and ω, the points of links
    (b₃), the weights, inertia forces and reactions carry the numbers the exercise's
    [notation] gives — never a link's name, never another convention's number."""
    import tomllib

    from planmethod.numbering import course_numbers
    from planmethod.spec import exercise_from_dict
    from planmethod.testing.figures import numbering_problems

    data = tomllib.loads((ROOT / "exercises" / f"{name}.toml").read_text(encoding="utf-8"))
    if CONVENTIONS[convention]:
        data["notation"] = CONVENTIONS[convention]
    exercise = exercise_from_dict(data)
    numbers = course_numbers(exercise.mechanism)
    analysis = analyse(exercise)
    files = plan_files(analysis.plans, analysis.forces)
    drive = exercise.mechanism.drive.link
    found = [f"{file}: {problem}" for file, svg in files.items()
             for problem in numbering_problems(svg, numbers, drive)]
    assert not found, "\n".join(found[:10])
    other = "frame 1" if convention != "frame 1" else "papers"
    data["notation"] = CONVENTIONS[other]
    wrong = course_numbers(exercise_from_dict(data).mechanism)
    assert any(numbering_problems(svg, wrong, drive) for svg in files.values())   # it bites


@pytest.mark.parametrize("path", EXERCISES, ids=lambda path: path.stem)
def test_every_workbook_frame_passes_and_each_panel_keeps_one_page(path):
    """The frames of a turn as the workbook draws them (every 45°, from the exercise's own
    angle): each passes the figure check, and each panel has one viewBox over the turn."""
    from planmethod.render.steady import steady_views
    from planmethod.testing.figures import steady_problems

    exercise = load_exercise(path)
    start = exercise.mechanism.drive.angle
    angles = [(start + step) % 360.0 for step in range(0, 360, 45)]
    try:
        views = steady_views(exercise, angles)
    except Exception as error:                 # a group's toggle position on the way round
        pytest.skip(f"{path.stem}: {error}")
    panels: dict[str, list[str]] = {}
    found = []
    for angle in angles:
        analysis = analyse(exercise, angle)
        for file, svg in plan_files(analysis.plans, analysis.forces, details=False,
                                    loaded=False, views=views).items():
            panels.setdefault(file, []).append(svg)
            found += [f"{angle:g}° {file}: {problem}" for problem in figure_problems(svg)]
    for file, frames in panels.items():                      # every panel of the page
        found += steady_problems(frames, file)
    assert not found, "\n".join(found[:20])
