"""One symbol, one meaning: a load carries the number of the link it acts on (P₅ on the
slider, T₃ on the rocker, two on one link P₅′, P₅″); a point named like a force (G1 beside the
weight G₁) is set apart; no figure prints a symbol with a literal underscore (M_b, a_S, Z_g)
nor two different things alike; a slide's motion is named by its point (v_D₅D₀); a triad's
links are listed in the course's numbering order. The loaded six-bar press
(``exercises/loaded_press_sixbar.toml``, loads on three links) closes its lever: its M_b is an
independent power balance's (kinematics by central differences of closed-form positions
written here), the lever's table prints ΣM_p = 0 and every moment has its row."""

from __future__ import annotations

import json
import math
import re
from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest
from defusedxml import ElementTree
from test_lever_terms import CASES, G, _on, _rates, _table, _turn

from planmethod.numbering import course_numbers
from planmethod.render.figures import plan_files
from planmethod.render.labels import RunKind
from planmethod.render.notation import ForceNotation
from planmethod.render.report_text import check_lines
from planmethod.report import analyse, report_dict
from planmethod.spec import load_exercise

ROOT = Path(__file__).resolve().parent.parent
PRESS = ROOT / "exercises" / "loaded_press_sixbar.toml"
SHIPPED = sorted((ROOT / "exercises").glob("*.toml"))
SVG = "{http://www.w3.org/2000/svg}"

#: the press's masses {link: (m, J)}, forces {point: F}, moments {link: T}, φ₁ (°) and ω₁
MASSES = {"crank": (0.8, 6e-4), "coupler": (2.0, 0.012), "rocker": (2.5, 0.02),
          "rod": (1.8, 0.018), "slider": (5.0, 0.0)}
FORCES = {"D": (-400.0, 0.0), "K": (0.0, -50.0)}
MOMENTS = {"rocker": -15.0}
ANGLE, OMEGA = 60.0, 10.0


def _press(phi: float) -> dict:
    """The press's closed-form positions: each link's (centre of mass, angle), D and K."""
    a, o2 = 0.07 * _turn(phi), np.array([0.28, 0.05])
    gap = o2 - a
    d = float(np.hypot(*gap))
    along = (d ** 2 + 0.26 ** 2 - 0.18 ** 2) / (2 * d)
    unit = gap / d
    b = a + along * unit + math.sqrt(0.26 ** 2 - along ** 2) * np.array([-unit[1], unit[0]])
    coupler, rocker = (math.atan2(*(end - start)[::-1]) for start, end in ((a, b), (o2, b)))
    c = o2 + 0.30 * _turn(rocker)
    end = np.array([c[0] + math.sqrt(0.35 ** 2 - (0.45 - c[1]) ** 2), 0.45])
    rod = math.atan2(end[1] - c[1], end[0] - c[0])
    return {"crank": (0.035 * _turn(phi), phi), "coupler": (a + 0.13 * _turn(coupler), coupler),
            "rocker": (o2 + 0.15 * _turn(rocker), rocker), "rod": (c + 0.175 * _turn(rod), rod),
            "slider": (end, 0.0), "D": end, "K": _on(a, coupler, (0.13, 0.07)), "B": b}


def _power_balance() -> tuple[float, dict]:
    """M_b from the power balance on the independent kinematics, and each link's ω, ε."""
    velocity, acceleration = _rates(_press, math.radians(ANGLE), OMEGA)
    power, rates = 0.0, {}
    for link, (mass, inertia) in MASSES.items():
        v, a = velocity[link], acceleration[link]
        rates[link] = (float(v[2]), float(a[2]))
        power += float(np.dot(mass * (np.array([0.0, -G]) - a[:2]), v[:2]))
        power -= inertia * a[2] * v[2]
    power += sum(float(np.dot(force, velocity[point])) for point, force in FORCES.items())
    power += sum(moment * float(velocity[link][2]) for link, moment in MOMENTS.items())
    return -power / OMEGA, rates


@pytest.fixture(scope="module")
def press():
    analysis = analyse(load_exercise(str(PRESS)))
    return analysis, plan_files(analysis.plans, analysis.forces)


def test_the_press_is_where_the_closed_form_puts_it(press):
    analysis, _ = press
    points = report_dict(analysis)["points"]
    velocity, _ = _rates(_press, math.radians(ANGLE), OMEGA)
    for name in ("B", "D"):
        assert points[name]["position"] == pytest.approx(
            list(_press(math.radians(ANGLE))[name]), abs=1e-12)
        assert points[name]["velocity"] == pytest.approx(list(velocity[name]), rel=1e-6)


def test_the_presss_balancing_moment_is_the_independent_power_balances(press):
    analysis, _ = press
    expected, _ = _power_balance()
    assert analysis.forces.balancing_moment == pytest.approx(expected, rel=1e-6)
    assert analysis.forces.zhukovsky_moment == pytest.approx(expected, rel=1e-6)


def test_the_presss_lever_prints_zero_and_every_moment_has_its_row(press):
    analysis, files = press
    rows = _table(files["lever.svg"])
    names = [row[0] for row in rows]
    assert names[-1] == "ΣMp" and rows[-1][-1] == "0"
    printed = [float(row[-1].replace("−", "-")) for row in rows[2:-1]]
    assert abs(sum(printed)) <= 1e-4 * sum(abs(value) for value in printed)
    notation = ForceNotation(analysis.forces.solution)
    couples = {notation.plain(item.name, item.link) for item in
               analysis.forces.solution.applied.items
               if item.moment is not None and float(item.moment[0]) != 0.0}
    assert couples == {"Mᵘ₂", "Mᵘ₃", "Mᵘ₄", "T₃"}       # the slider has no J, the crank no ε
    for couple in couples:          # each a force pair at its link's two points on the lever
        assert sum(1 for name in names if name.startswith(f"{couple} (pair, ")) == 2, couple
    # the pair's moment term about the pole adds up to the couple times ω/μv (N·mm)
    _, rates = _power_balance()
    mu_v = analysis.plans.scales.mu_v
    for couple, moment in (("T₃", MOMENTS["rocker"]),
                           ("Mᵘ₃", -MASSES["rocker"][1] * rates["rocker"][1])):
        terms = [float(row[-1].replace("−", "-")) for row in rows
                 if row[0].startswith(f"{couple} (pair, ")]
        assert sum(terms) == pytest.approx(moment * rates["rocker"][0] / mu_v,
                                           rel=2e-4, abs=0.01)


def test_loads_carry_the_number_of_their_link(press):
    analysis, files = press
    notation = ForceNotation(analysis.forces.solution)
    assert [notation.plain(f"load[{index}]") for index in (1, 2, 3)] == ["P₅", "T₃", "P₂"]
    loads = analysis.forces.as_dict()["loads"]
    assert [(load["name"], load["symbol"], load["link"]) for load in loads] == [
        ("load[1]", "P₅", "slider"), ("load[2]", "T₃", "rocker"), ("load[3]", "P₂", "coupler")]
    assert "P₁" not in files["loaded.svg"] and ">P</tspan><tspan" in files["loaded.svg"]


def test_two_loads_of_one_letter_on_one_link_are_primed(tmp_path):
    text = PRESS.read_text(encoding="utf-8").replace("[plan]", """[[load]]
link = "slider"
point = "D"
force = [0, -30]

[[load]]
link = "rocker"
moment = 2

[plan]""")
    path = tmp_path / "press.toml"
    path.write_text(text, encoding="utf-8")
    analysis = analyse(load_exercise(str(path)))
    notation = ForceNotation(analysis.forces.solution)
    assert [notation.plain(f"load[{index}]") for index in range(1, 6)] == [
        "P₅′", "T₃′", "P₂", "P₅″", "T₃″"]
    assert notation.runs("load[4]") == (("P", RunKind.MAIN), ("5", RunKind.SUB),
                                        ("″", RunKind.MAIN))
    assert len({notation.plain(f"load[{index}]") for index in range(1, 6)}) == 5


def test_a_slides_motion_is_named_by_its_point(press):
    analysis, _ = press
    table = "\n".join(check_lines(analysis))
    for shown in ("v_D₅D₀", "aʳ_D₅D₀", "aᵏ_D₅D₀", "s₅₀"):
        assert re.search(rf"^  {shown} ", table, re.MULTILINE), shown
    assert "ds/dt" not in table and "d²s/dt²" not in table
    steps = [step["text"] for kind in ("velocity", "acceleration")
             for step in report_dict(analysis)["plans"][kind]["steps"]]
    assert any(re.search(r"\(d₀d\) = [\d.]+ mm → v_D₅D₀ = ", step) for step in steps)
    assert any("→ aʳ_D₅D₀ = " in step for step in steps)
    assert not any("ds/dt" in step or "d²s/dt²" in step for step in steps)


def test_a_triads_links_are_listed_in_the_courses_order():
    exercise = load_exercise(str(ROOT / "exercises" / "conveyor_sixbar.toml"))
    analysis = analyse(exercise)
    numbers = course_numbers(exercise.mechanism)
    report = json.loads(json.dumps(report_dict(analysis), default=str))
    triad = report["structure"]["groups"][0]
    assert triad["type"] == "triad"
    assert triad["links"] == ["rod", "tray", "rocker_EF", "rocker_DG"]
    assert [numbers[link] for link in triad["links"]] == [2, 3, 4, 5]
    assert report["forces"]["groups"][0]["links"] == triad["links"]


# -- every figure: no underscore shown, no two things alike -----------------------------------
def _guide_points_like_weights(folder: Path) -> Path:
    """The press with its guide point named G1 and the coupler's point G2: beside the weights
    G₁, G₂ of links 1 and 2."""
    text = PRESS.read_text(encoding="utf-8")
    text = text.replace("E = [0, 0.45]", "G1 = [0, 0.45]").replace('through = "E"',
                                                                     'through = "G1"')
    text = text.replace("K = [0.13, 0.07]", "G2 = [0.13, 0.07]").replace('point = "K"',
                                                                          'point = "G2"')
    path = folder / "guides.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _unseen(folder: Path) -> list[Path]:
    """The unseen-style mechanisms: the lever's (a rocking block, a slotted lever, a loaded
    shaper) and the press with points named like weights."""
    paths = [_guide_points_like_weights(folder)]
    for name, case in CASES.items():
        paths.append(folder / f"{name}.toml")
        paths[-1].write_text(case[0], encoding="utf-8")
    return paths


@pytest.fixture(scope="module")
def figures(tmp_path_factory):
    folder = tmp_path_factory.mktemp("symbols")
    out = {}
    for path in SHIPPED + _unseen(folder):
        analysis = analyse(load_exercise(str(path)))
        for name, svg in plan_files(analysis.plans, analysis.forces).items():
            out[f"{path.stem}/{name}"] = svg
    return out


def _shown(element) -> str:
    """A text element as it reads: a run set small written _{…}."""
    parts = [element.text or ""]
    for child in element:
        small = child.get("font-size") is not None and child.text
        parts.append(f"_{{{child.text}}}" if small else child.text or "")
        parts.append(child.tail or "")
    return "".join(parts).replace("\u00a0", " ")


def test_no_figure_shows_an_underscore_before_a_letter(figures):
    assert len(figures) > 60
    for name, svg in figures.items():
        root = ElementTree.fromstring(svg.encode("utf-8"))
        for element in root.iter(f"{SVG}text"):
            text = re.sub(r"\[[^\]]*\]", "", "".join(element.itertext()))
            assert not re.search(r"_[^\W\d_]", text), (name, text)


def _alike(svg: str) -> dict[str, set[str]]:
    """Each label's printed text with what it names, where two different things print
    alike (a couple's force pair, ``M_u,BC at B`` and ``at C``, is one thing)."""
    root = ElementTree.fromstring(svg.encode("utf-8"))
    named: dict[str, set[str]] = defaultdict(set)
    for element in root.iter(f"{SVG}text"):
        points = element.get("data-points")
        if points is not None and (element.get("class") or "").startswith("label"):
            named[_shown(element)].add(re.sub(r" at \S+$", "", points))
    return {text: what for text, what in named.items() if len(what) > 1}


def test_no_figure_prints_two_things_alike(figures):
    for name, svg in figures.items():
        assert not _alike(svg), (name, _alike(svg))


def test_points_named_like_weights_print_as_they_are_written(figures):
    loaded = figures["guides/loaded.svg"]
    root = ElementTree.fromstring(loaded.encode("utf-8"))
    shown = {element.get("data-points"): _shown(element) for element in root.iter(f"{SVG}text")
             if element.get("data-points")}
    assert shown["G1"] == "G1" and shown["G2"] == "G2"
    weights = {shown[key] for key in shown if key.startswith("force:G_")}
    assert {"G_{1}", "G_{2}"} <= weights
    # the check can fail: the guide point set as the weight's letter and subscript would not
    # pass it
    subscripted = loaded.replace('<tspan font-style="normal">G1</tspan>',
                                 '<tspan>G</tspan><tspan dy="4.2" font-size="10.8">1</tspan>')
    assert subscripted != loaded
    assert _alike(subscripted) == {"G_{1}": {"G1", "force:G_crank:crank"}}
