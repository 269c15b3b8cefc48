"""Every figure of every shipped exercise passes the figure check (no code word, no two texts
overlapping, nothing outside the viewBox, every legend item drawn); Zhukovsky's lever carries
its forces and states the report's M_b; every exercise with forces has its loaded mechanism."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from defusedxml import ElementTree

from planmethod.render.figures import plan_files
from planmethod.render.plan_words import step_text
from planmethod.report import analyse, report_dict
from planmethod.spec import load_exercise
from planmethod.testing.figures import figure_problems

_SVG = "{http://www.w3.org/2000/svg}"

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
    # M_b set with its subscript b: the line's text reads "Mb = …"
    lines = ["".join(element.itertext()) for element in
             ElementTree.fromstring(lever.encode("utf-8")).iter(f"{_SVG}text")]
    assert any(f"Mb = {moment:.6g} N·m (Zhukovsky's lever)" in line for line in lines)
    assert f"M_b = {moment:.6g}" not in lever
    drawn_forces = {force.name for force in analysis.forces.solution.lever.forces
                    if not force.name.startswith("M_f") and any(force.force[0])}
    labelled = set(re.findall(r'data-points="force:([^"]+)"', lever))
    assert labelled == drawn_forces | {"F_b"}                 # each force named at its image

    root = ElementTree.fromstring(lever.encode("utf-8"))
    results = next(group for group in root if group.get("class") == "results")
    arrows = [g for g in results if g.get("class") == "arrow lever force"]  # not the details'
    assert len(drawn_forces) // 2 < len(arrows) <= len(drawn_forces) + 1
    arms = set(re.findall(r'data-points="arm:([^"]+)"', lever))
    assert arms and arms <= labelled                            # h₁, h₂ … on the arms
    rows = re.findall(r'<text class="table"[^>]*>([^<]*)', lever)
    assert "ΣM" in rows and "0" in rows and "force" in rows     # the sum, term by term


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


TEMPLATES = sorted((ROOT / "exercises" / "templates").glob("*.toml"))


@pytest.mark.parametrize("path", TEMPLATES, ids=lambda path: path.stem)
def test_task_and_plan_sheets_pass_the_figure_check(path):
    """The sheets of a template's first five variants, as ``planmethod variants --count 5``
    writes them: each passes the figure check."""
    import json

    from planmethod.application.variants import VariantsRequest, class_of, draw_variants
    from planmethod.grading.templates import load_template

    files = draw_variants(VariantsRequest(load_template(path), class_of(5), seed=0)).files
    found = []
    for name, text in files.items():
        if not name.endswith(".svg"):
            continue
        key = json.loads(files[f"{name.partition('/')[0]}/key.json"])
        answer_columns = [question["id"] for question in key["questions"]]
        found += [f"{name}: {problem}"
                  for problem in figure_problems(text, allowed=answer_columns)]
    assert not found, "\n".join(found)
    # the answer-file column names are the only names printed as they are, in brackets
    assert figure_problems(files["001/task.svg"])


def test_the_conveyors_sheets_pass_the_figure_check():
    from planmethod.grading.keys import build_key
    from planmethod.grading.sheets import plan_sheet_for_key, task_sheet_svg
    from planmethod.grading.templates import draw_variant, load_template
    from planmethod.plans import draw_plans

    variant = draw_variant(load_template(ROOT / "exercises/conveyor_sixbar.toml"), seed=5,
                           student="a")
    key = build_key(variant)
    answer_columns = [question["id"] for question in key["questions"]]
    sheets = {"task": task_sheet_svg(key, draw_plans(variant.exercise)),
              "velocity": plan_sheet_for_key(key, "velocity"),
              "acceleration": plan_sheet_for_key(key, "acceleration")}
    found = [f"{name}: {problem}" for name, svg in sheets.items()
             for problem in figure_problems(svg, allowed=answer_columns)]
    assert not found, "\n".join(found)


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
            text = step_text(step, plan)
            assert "@" not in text, text
            assert not re.search(r"\b(?:omega|epsilon|rho|coriolis|a_rel|dds|ds)_", text), text
            assert not any(re.search(rf"\b{name}\b", text) for name in links), text


def test_loads_are_printed_by_the_name_the_exercise_gives_them():
    import tomllib

    from planmethod.render.notation import ForceNotation
    from planmethod.spec import exercise_from_dict

    data = tomllib.loads((ROOT / "exercises/combined_force_slider_crank.toml")
                         .read_text(encoding="utf-8"))
    solution = analyse(exercise_from_dict(data)).forces.solution
    assert ForceNotation(solution).plain("load[1]") == "P₃"     # the default: its link, 3
    data["load"][0]["name"] = "P_c"
    named = analyse(exercise_from_dict(data))
    assert ForceNotation(named.forces.solution).plain("load[1]") == "P_c"
    files = plan_files(named.plans, named.forces)
    from planmethod.testing.figures import text_boxes

    texts = [box.text for box in text_boxes(files["loaded.svg"])]
    assert texts.count("Pc") >= 2          # the label and the table's row: P, subscript c
    assert not any("load[" in text for text in texts)
    assert not figure_problems(files["loaded.svg"])


_HEAD = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 300 200">'


def _label(points: str, x: float, y: float, text: str = "", size: float = 15) -> str:
    return (f'<text class="label" data-points="{points}" x="{x}" y="{y}" font-size="{size}">'
            f'{text or points}</text>')


def _mark(points: str, x: float, y: float) -> str:
    return f'<circle class="point" cx="{x}" cy="{y}" r="2.4" data-points="{points}"/>'


def _problems(*elements: str, **options) -> list[str]:
    return figure_problems(_HEAD + "".join(elements) + "</svg>", **options)


def test_the_crowding_check_can_fail():
    """A point's label nearer than the clearance (a quarter of the readable distance, 7.5 px
    at 15 px labels) to another point's mark is a problem, unless the mark lies in a region
    drawn again as a detail; a force's label only may not touch a mark."""
    marks = _mark("b", 50, 50) + _mark("c", 90, 50)
    near = _label("b", 75, 54)                       # its text 3 px from the mark of c
    assert any("from the mark of c" in problem for problem in _problems(marks, near))
    region = '<rect class="detail region" x="40" y="40" width="60" height="20" fill="none"/>'
    assert not _problems(region, marks, near)
    assert not _problems(marks, _label("b", 30, 40))
    force = _label("force:G", 75, 54, "G")          # the same place, a force's label
    assert not _problems(marks, force)
    assert any("from the mark of c" in problem
               for problem in _problems(marks, _label("force:G", 82, 56, "G")))


def test_the_spacing_check_can_fail():
    """Marks of distinct points nearer than the readable distance — 2 em of the figure's
    point labels — need an enlarged detail; in a detail (a translated, clipped group) its own
    marks are held to it too, unless a region of that detail is drawn again (nested)."""
    labels = _label("b", 20, 20) + _label("c", 200, 20)
    close = _mark("b", 50, 50) + _mark("c", 70, 50)
    assert any("marks of b and c are 20.0 px apart, nearer than the readable 30 px" in problem
               for problem in _problems(close, labels))
    assert not _problems(_mark("b", 50, 50) + _mark("c", 85, 50), labels)
    region = '<rect class="detail region" x="40" y="40" width="40" height="20" fill="none"/>'
    assert not _problems(region, close, labels)
    small = _label("b", 20, 20, size=10) + _label("c", 200, 20, size=10)
    assert not _problems(close + _mark("d", 150, 50), small)       # 20 px at 10 px labels
    assert not _problems(_mark("b", 50, 50) + _mark("c", 50, 50), labels)   # coincide
    detail = ('<defs><clipPath id="k"><rect x="0" y="0" width="100" height="60"/></clipPath>'
              '</defs><g class="detail" clip-path="url(#k)" transform="translate(150,100)">'
              + _mark("b", 20, 20) + _mark("c", 28, 20) + '</g>')
    assert any("marks of b and c are 8.0 px apart" in problem
               for problem in _problems(region, close, labels, detail))
    nested = ('<g class="detail" transform="translate(150,100)"><rect class="detail region" '
              'x="10" y="10" width="30" height="20" fill="none"/></g>')
    assert not _problems(region, close, labels, detail, nested)


def test_the_line_and_leader_checks_can_fail():
    """A label crossed by a line that is not its own leader, a leader that crosses another
    leader or an arrow away from the point it starts at: each is a problem."""
    label = _label("b", 40, 60)
    assert any("label 'b' is crossed by a line (construction)" in problem for problem in
               _problems(label, '<line class="construction" x1="30" y1="55" x2="70" y2="55" '
                                'stroke="#777"/>'))
    assert not _problems(label, '<line class="construction" x1="30" y1="75" x2="70" y2="75" '
                                'stroke="#777"/>')
    own = '<line class="leader" data-points="b" x1="80" y1="80" x2="45" y2="56" stroke="#000"/>'
    assert not _problems(label, own)                          # its own leader ends on it
    other = own.replace('data-points="b"', 'data-points="c"')
    assert any("label 'b' is crossed by the leader of 'c'" in problem
               for problem in _problems(label, _label("c", 200, 150), other))
    first = '<line class="leader" data-points="b" x1="100" y1="100" x2="160" y2="160" ' \
            'stroke="#000"/>'
    second = '<line class="leader" data-points="c" x1="100" y1="160" x2="160" y2="100" ' \
             'stroke="#000"/>'
    found = _problems(_label("b", 162, 175), _label("c", 162, 95), first, second)
    assert any("the leader of 'b' crosses the leader of 'c'" in problem for problem in found)
    from_one = second.replace('x1="100" y1="160"', 'x1="100" y1="100"')
    assert not _problems(_label("b", 162, 175), _label("c", 162, 95), first, from_one)
    arrow = ('<g class="arrow result"><line x1="100" y1="140" x2="140" y2="140" '
             'stroke="#000"/><polygon points="150,140 140,136 140,144" fill="#000"/></g>')
    found = _problems(_label("b", 162, 175), first, arrow)
    assert any("the leader of 'b' crosses an arrow (arrow result)" in problem
               for problem in found)
    through = ('<g class="arrow result"><line x1="100" y1="100" x2="60" y2="100" '
               'stroke="#000"/><polygon points="50,100 60,96 60,104" fill="#000"/></g>')
    assert not any("crosses an arrow" in problem          # it leaves its point across it
                   for problem in _problems(_label("b", 162, 175), first, through))


def test_a_figure_without_details_is_held_to_what_it_can_give():
    """A workbook frame, drawn without details: crowded marks and leaders across a crowded
    point's arrows are not its problems, a label touching another point's mark (3 px) and a
    line through a label are."""
    close = _mark("b", 50, 50) + _mark("c", 70, 50)
    assert not _problems(close, _label("b", 20, 20), _label("c", 200, 20), details=False)
    assert any("from the mark of c" in problem for problem in
               _problems(close, _label("b", 58, 48), details=False))
    assert _problems(_label("b", 40, 60), '<line x1="30" y1="55" x2="70" y2="55" '
                                          'stroke="#777"/>', details=False)


def _unnamed(svg: str) -> set[str]:
    """The points of a figure with a mark and no label naming them."""
    marked = {name for names in re.findall(r'<circle[^>]*data-points="([^"]+)"', svg)
              for name in names.split()}
    named = {name for names in re.findall(r'<text[^>]*data-points="([^"]+)"', svg)
             for name in names.split()}
    return marked - named


@pytest.mark.parametrize("angle, plan, crowded", [
    (150.0, "acceleration", {"b", "c", "e"}), (180.0, "velocity", {"b", "c", "e"}),
    (330.0, "velocity", {"c"})])
def test_a_crowded_point_keeps_its_label_on_a_leader_without_details(angle, plan, crowded):
    """The conveyor's plans at angles where b, c, e crowd round d and s*: drawn without
    details (the studio), each crowded point is still named, on a leader, and the figure keeps
    what a figure without details must (no label on a line or another point's mark); with
    details, the enlarged detail names them as before."""
    analysis = analyse(load_exercise(ROOT / "exercises" / "conveyor_sixbar.toml"), angle)
    svg = plan_files(analysis.plans, details=False, loaded=False)[f"{plan}.svg"]
    assert not _unnamed(svg)
    led = {name for names in re.findall(r'<line[^>]*class="leader"[^>]*data-points="([^"]+)"',
                                        svg) for name in names.split()}
    assert crowded <= led
    assert not figure_problems(svg, details=False)
    detailed = plan_files(analysis.plans)[f"{plan}.svg"]
    assert "detail region" in detailed and not figure_problems(detailed)


def test_every_frame_of_a_workbook_names_every_point():
    """The conveyor's workbook frames (its panels kept steady over the turn, no details),
    every 30°: every point with a mark is named and no frame has a figure problem — before
    the crowded labels went on leaders, 162 marks of 1,080 such figures had no name."""
    from planmethod.application.workbook import turn_angles
    from planmethod.render.steady import steady_views

    exercise = load_exercise(ROOT / "exercises" / "conveyor_sixbar.toml")
    views = steady_views(exercise, turn_angles(5.0, start=exercise.mechanism.drive.angle))
    found = []
    for angle in range(0, 360, 30):
        analysis = analyse(exercise, float(angle))
        files = plan_files(analysis.plans, forces=analysis.forces, details=False,
                           loaded=False, views=views)
        for plan in ("position", "velocity", "acceleration"):
            svg = files[f"{plan}.svg"]
            found += [f"{plan} at {angle}°: {name} unnamed" for name in _unnamed(svg)]
            found += [f"{plan} at {angle}°: {problem}"
                      for problem in figure_problems(svg, details=False)]
    assert not found, "\n".join(found)


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
    angle): each passes the figure check of a figure without enlarged details (the page
    draws none), and each panel has one viewBox over the turn."""
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
            found += [f"{angle:g}° {file}: {problem}"
                      for problem in figure_problems(svg, details=False)]
    for file, frames in panels.items():                      # every panel of the page
        found += steady_problems(frames, file)
    assert not found, "\n".join(found[:20])


@pytest.mark.parametrize("angle", [135.0, 200.0, 250.0])
def test_details_go_two_levels_deep_and_a_cluster_still_crowded_is_a_table(angle):
    """The conveyor's acceleration plan at 250° nested details three deep (×294): now a
    detail is marked on the figure or in one of its details, never deeper, and the points a
    detail of a detail still cannot set apart are listed beside the plan with their place
    (mm from the pole, as laid off); a tall plan has its details beside it."""
    from planmethod.plans import draw_plans
    from planmethod.render.canvas import Canvas, fit_zoom
    from planmethod.render.details import DEPTH, crowded_points, detail_regions
    from planmethod.render.style import PLAN_SIZE
    from planmethod.render.svg import plan_svg

    assert DEPTH == 2
    plans = draw_plans(load_exercise(ROOT / "exercises" / "conveyor_sixbar.toml"), angle)
    for plan in (plans.velocity, plans.acceleration):
        svg = plan_svg(plan)
        parents = dict(re.findall(r"([IVX]+): detail ×[\d.]+ \(marked in detail ([IVX]+)\)",
                                  svg))
        assert not set(parents.values()) & set(parents), parents      # no third level
        figure = Canvas(fit_zoom(list(plan.points_mm.values()), PLAN_SIZE))
        where = {label: figure.px(xy) for label, xy in plan.points_mm.items()}
        crowded = crowded_points(detail_regions(figure, where, depth=DEPTH))
        rows = re.findall(r'<text class="table crowded"[^>]*>([^<]*)</text>', svg)
        for name in crowded:
            x, y = plan.points_mm[name]
            assert f"{x:.2f}" in rows and f"{y:.2f}" in rows, name
        if angle == 250.0 and plan is plans.acceleration:
            assert crowded and "points too close to read (from the pole π)" in svg


# -- pages framed on what they draw, details two deep (issue 37) -------------------------------
#: a 0.1 m four-bar whose heavy rocker turns about a centre of mass next to its pivot: the
#: single equivalent inertia force's line lies h ≈ 2.5 m from S (25 times the mechanism)
FAR_LINE = """
title = "Small four-bar with a heavy rocker"
[drive]
link = "crank"
pivot = "A"
angle = 40
omega = 20
epsilon = 0
[links]
frame = { A = [0, 0], D = [0.08, 0] }
crank = { A = [0, 0], B = [0.02, 0] }
coupler = { B = [0, 0], C = [0.08, 0] }
rocker = { D = [0, 0], C = [0.05, 0] }
[mass.crank]
m = 0.2
J = 1e-5
S = [0.01, 0]
[mass.coupler]
m = 0.5
J = 3e-4
S = [0.04, 0]
[mass.rocker]
m = 0.4
J = 0.004
S = [0.004, 0]
[gravity]
g = 9.81
[plan]
crank_mm = 40
velocity_mm = 40
acceleration_mm = 40
precision_mm = 0
"""


def _unseen():
    """The unseen-style mechanisms the tests use: the rocking block, the slotted lever and
    the loaded six-bar of the lever's terms, the screen on a pinned block, the far line."""
    import tomllib

    from test_lever_terms import ROCKING, SIXBAR, SLOTTED
    from test_triad_slider import slot

    return {"rocking block": tomllib.loads(ROCKING), "slotted lever": tomllib.loads(SLOTTED),
            "loaded six-bar": tomllib.loads(SIXBAR), "screen on a block": slot(),
            "far line": tomllib.loads(FAR_LINE)}


@pytest.fixture(scope="module", params=["rocking block", "slotted lever", "loaded six-bar",
                                        "screen on a block", "far line"])
def unseen(request):
    from planmethod.spec import exercise_from_dict

    analysis = analyse(exercise_from_dict(_unseen()[request.param]))
    return analysis, plan_files(analysis.plans, analysis.forces)


def _framing_problems(files: dict[str, str]) -> list[str]:
    from planmethod.testing.figures import detail_depth, page_ratio

    found = []
    for name, svg in files.items():
        if page_ratio(svg) > 3.0:
            found.append(f"{name}: the page is {page_ratio(svg):.2f}× what it draws")
        if detail_depth(svg) > 2:
            found.append(f"{name}: details {detail_depth(svg)} levels deep")
    return found


def test_every_figure_is_framed_on_what_it_draws_with_details_two_deep(drawn):
    """No shipped exercise's figure has a viewBox more than 3× the extent of what it draws
    (its mechanism, its plan, its polygon) — the legend's column and the details sit beside
    the drawing within that page — and no figure nests details deeper than two."""
    _, _, files = drawn
    assert not _framing_problems(files), "\n".join(_framing_problems(files))


def test_unseen_mechanisms_figures_are_framed_and_two_deep(unseen):
    """The same on mechanisms no shipped exercise covers."""
    _, files = unseen
    assert not _framing_problems(files), "\n".join(_framing_problems(files))


def test_a_far_line_of_action_is_clipped_to_the_mechanisms_frame():
    """h ≈ 2.5 m from S on a 0.1 m four-bar: the loaded mechanism is framed on the
    mechanism (the page was 30× it), the line's h is in the table, and a dashed pointer
    from S₃ shows the side the line lies on."""
    import tomllib

    from planmethod.spec import exercise_from_dict
    from planmethod.testing.figures import drawn_extent, page_ratio

    analysis = analyse(exercise_from_dict(tomllib.loads(FAR_LINE)))
    offset = float(analysis.forces.solution.applied.inertia["rocker"].offset[0])
    assert abs(offset) > 2.0                                      # 25× the mechanism
    loaded = plan_files(analysis.plans, analysis.forces)["loaded.svg"]
    assert page_ratio(loaded) < 3.0
    assert f"one force on a line h = {abs(offset):.4g} m from S" in loaded
    assert 'class="inertia line off"' in loaded
    x0, y0, x1, y1 = drawn_extent(loaded)
    margin = 0.2 * max(x1 - x0, y1 - y0)
    from defusedxml import ElementTree

    root = ElementTree.fromstring(loaded.encode("utf-8"))        # the figure's, not a detail's
    construction = next(group for group in root if group.get("class") == "construction")
    lines = [line for line in construction if line.tag.endswith("}line")
             and (line.get("class") or "").startswith("inertia line")]
    assert len(lines) == 2                    # the coupler's line, the rocker's pointer
    for line in lines:
        for axis, low, high in (("x", x0, x1), ("y", y0, y1)):
            for end in ("1", "2"):
                assert low - margin <= float(line.get(axis + end)) <= high + margin
