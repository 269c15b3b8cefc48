"""Zhukovsky's lever closes on mechanisms the shipped exercises do not cover: a rocking block
and a slotted lever with an inertia couple on the block (a link with one point on the plan),
and a loaded shaper six-bar with loads on several links. Every moment on every link has its
row — a force pair where its link has two points, else the moment term M·ω/μv — the table's
ΣM_p prints 0, and M_b equals the groups' and an independent power balance (kinematics by
central differences of the closed-form positions written here, not the package's)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from defusedxml import ElementTree

from planmethod.render.force_svg import force_files
from planmethod.render.notation import ForceNotation
from planmethod.report import analyse
from planmethod.spec import load_exercise
from planmethod.vocabulary import numbered

SVG = "{http://www.w3.org/2000/svg}"
G = 9.81

ROCKING = """
title = "Rocking block with a heavy block"
[drive]
link = "crank"
pivot = "O1"
angle = 50
omega = 12
epsilon = 0
[links]
frame = { O1 = [0, 0], C = [0.25, 0.02] }
crank = { O1 = [0, 0], A = [0.08, 0] }
rod = { A = [0, 0], D = [0.40, 0] }
block = { C = [0, 0] }
[[slide]]
link = "block"
along = "rod"
through = "A"
direction = 0
point = "C"
[mass.crank]
m = 0.6
J = 4e-4
S = [0.04, 0]
[mass.rod]
m = 2.0
J = 0.03
S = [0.18, 0]
[mass.block]
m = 1.5
J = 0.02
S = [0, 0]
[gravity]
g = 9.81
[[load]]
link = "rod"
point = "D"
force = [0, -40]
[[load]]
link = "block"
moment = 3.0
[plan]
crank_mm = 40
velocity_mm = 40
acceleration_mm = 40
precision_mm = 0
"""

SLOTTED = """
title = "Slotted lever with a heavy block"
[drive]
link = "crank"
pivot = "O1"
angle = 30
omega = 10
epsilon = 0
[links]
frame = { O1 = [0, 0], O2 = [0, -0.30] }
crank = { O1 = [0, 0], B = [0.10, 0] }
block = { B = [0, 0] }
lever = { O2 = [0, 0], C = [0.45, 0] }
[[slide]]
link = "block"
along = "lever"
through = "O2"
direction = 0
point = "B"
[mass.crank]
m = 1.0
J = 1e-3
S = [0.05, 0]
[mass.block]
m = 0.8
J = 0.05
S = [0, 0]
[mass.lever]
m = 3.0
J = 0.06
S = [0.2, 0]
[gravity]
g = 9.81
[[load]]
link = "lever"
point = "C"
force = [0, -60]
[plan]
crank_mm = 40
velocity_mm = 40
acceleration_mm = 40
precision_mm = 0
"""

SIXBAR = """
title = "Loaded shaper six-bar"
[drive]
link = "crank"
pivot = "O1"
angle = 60
omega = 8
epsilon = 0
[links]
frame = { O1 = [0, 0.30], O2 = [0, 0], E = [0, 0.62] }
crank = { O1 = [0, 0], B = [0.10, 0] }
block = { B = [0, 0] }
lever = { O2 = [0, 0], C = [0.60, 0], K = [0.45, 0.03] }
rod = { C = [0, 0], D = [0.25, 0] }
ram = { D = [0, 0] }
[[slide]]
link = "block"
along = "lever"
through = "O2"
direction = 0
point = "B"
[[slide]]
link = "ram"
along = "frame"
through = "E"
direction = 0
point = "D"
[sketch]
C = [0.10, 0.59]
D = [0.33, 0.62]
[mass.crank]
m = 0.5
J = 5e-4
S = [0.05, 0]
[mass.block]
m = 0.4
J = 0.004
S = [0, 0]
[mass.lever]
m = 4.0
J = 0.12
S = [0.3, 0]
[mass.rod]
m = 1.5
J = 0.008
S = [0.125, 0]
[mass.ram]
m = 6.0
J = 0
S = [0, 0]
[gravity]
g = 9.81
[[load]]
link = "ram"
point = "D"
force = [-300, 0]
[[load]]
link = "lever"
point = "K"
force = [20, -35]
[[load]]
link = "rod"
moment = -4.0
[[load]]
link = "block"
moment = 1.5
[plan]
crank_mm = 20
velocity_mm = 30
acceleration_mm = 30
precision_mm = 0
"""


def _turn(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


def _on(origin, angle: float, local) -> np.ndarray:
    """A point given in a link's frame (origin, angle), in global axes."""
    c, s = math.cos(angle), math.sin(angle)
    return np.asarray(origin) + np.array([c * local[0] - s * local[1],
                                          s * local[0] + c * local[1]])


def _rocking(phi: float) -> dict:
    """Closed-form positions: each link's (centre of mass, angle) and the loads' points."""
    a = 0.08 * _turn(phi)
    rod = math.atan2(0.02 - a[1], 0.25 - a[0])
    return {"crank": (0.04 * _turn(phi), phi), "rod": (a + 0.18 * _turn(rod), rod),
            "block": (np.array([0.25, 0.02]), rod), "D": a + 0.40 * _turn(rod)}


def _slotted(phi: float) -> dict:
    b = 0.10 * _turn(phi)
    lever = math.atan2(b[1] + 0.30, b[0])
    o2 = np.array([0.0, -0.30])
    return {"crank": (0.05 * _turn(phi), phi), "block": (b, lever),
            "lever": (o2 + 0.2 * _turn(lever), lever), "C": o2 + 0.45 * _turn(lever)}


def _sixbar(phi: float) -> dict:
    b = np.array([0.0, 0.30]) + 0.10 * _turn(phi)
    lever = math.atan2(b[1], b[0])
    c = 0.60 * _turn(lever)
    d = np.array([c[0] + math.sqrt(0.25 ** 2 - (0.62 - c[1]) ** 2), 0.62])
    rod = math.atan2(d[1] - c[1], d[0] - c[0])
    return {"crank": (np.array([0.0, 0.30]) + 0.05 * _turn(phi), phi), "block": (b, lever),
            "lever": (0.30 * _turn(lever), lever), "rod": (c + 0.125 * _turn(rod), rod),
            "ram": (d, 0.0), "D": d, "K": _on((0.0, 0.0), lever, (0.45, 0.03))}


#: (file text, positions, masses {link: (m, J)}, forces {point: (link, F)}, moments {link: T},
#:  the drive's angle (°) and ω1)
CASES = {
    "rocking": (ROCKING, _rocking, {"crank": (0.6, 4e-4), "rod": (2.0, 0.03),
                                     "block": (1.5, 0.02)},
                {"D": (0.0, -40.0)}, {"block": 3.0}, 50.0, 12.0),
    "slotted": (SLOTTED, _slotted, {"crank": (1.0, 1e-3), "block": (0.8, 0.05),
                                     "lever": (3.0, 0.06)},
                {"C": (0.0, -60.0)}, {}, 30.0, 10.0),
    "sixbar": (SIXBAR, _sixbar, {"crank": (0.5, 5e-4), "block": (0.4, 0.004),
                                 "lever": (4.0, 0.12), "rod": (1.5, 0.008), "ram": (6.0, 0.0)},
               {"D": (-300.0, 0.0), "K": (20.0, -35.0)}, {"rod": -4.0, "block": 1.5},
               60.0, 8.0)}


def _rates(positions, phi: float, omega: float):
    """Velocities and accelerations of every entry (a point, or a link's S and angle) by
    central differences of the closed form in φ (ε1 = 0: d/dt = ω1·d/dφ)."""
    step = 1e-4

    def flat(value) -> np.ndarray:
        return {key: np.hstack([np.ravel(v) for v in (item if isinstance(item, tuple)
                                                      else (item,))])
                for key, item in value.items()}

    here, ahead, back = (flat(positions(phi + k * step)) for k in (0, 1, -1))
    velocity = {key: omega * (ahead[key] - back[key]) / (2 * step) for key in here}
    acceleration = {key: omega ** 2 * (ahead[key] - 2 * here[key] + back[key]) / step ** 2
                    for key in here}
    return velocity, acceleration


def _independent_balancing_moment(case: str) -> tuple[float, dict]:
    """M_b from the power balance on the independent kinematics, and each link's ω, ε."""
    _, positions, masses, forces, moments, angle, omega = CASES[case]
    phi = math.radians(angle)
    velocity, acceleration = _rates(positions, phi, omega)
    power = 0.0
    rates = {}
    for link, (mass, inertia) in masses.items():
        v, a = velocity[link], acceleration[link]
        rates[link] = (float(v[2]), float(a[2]))
        power += float(np.dot(mass * (np.array([0.0, -G]) - a[:2]), v[:2]))
        power += -inertia * a[2] * v[2]
    for point, force in forces.items():
        power += float(np.dot(force, velocity[point]))
    for link, moment in moments.items():
        power += moment * float(velocity[link][2])
    return -power / omega, rates


def _table(svg: str) -> list[list[str]]:
    """The lever's table: its rows of cells (text), top to bottom."""
    root = ElementTree.fromstring(svg.encode("utf-8"))
    rows: dict[float, list[tuple[float, str]]] = {}
    for element in root.iter(f"{SVG}text"):
        if element.get("class") == "table":
            rows.setdefault(float(element.get("y")), []).append(
                (float(element.get("x")), "".join(element.itertext())))
    return [[text for _, text in sorted(cells)] for _, cells in sorted(rows.items())]


@pytest.fixture(scope="module", params=sorted(CASES))
def solved(request, tmp_path_factory):
    path = tmp_path_factory.mktemp("lever") / f"{request.param}.toml"
    path.write_text(CASES[request.param][0], encoding="utf-8")
    analysis = analyse(load_exercise(str(path)))
    return request.param, analysis, force_files(analysis.forces, analysis.plans)


def test_the_balancing_moment_is_the_independent_power_balances(solved):
    case, analysis, _ = solved
    expected, _ = _independent_balancing_moment(case)
    forces = analysis.forces
    assert forces.balancing_moment == pytest.approx(expected, rel=1e-6, abs=1e-9)
    assert forces.zhukovsky_moment == pytest.approx(forces.balancing_moment, rel=1e-12)


def test_every_moment_has_its_row_and_the_sum_prints_zero(solved):
    case, analysis, files = solved
    rows = _table(files["lever.svg"])
    names = [row[0] for row in rows]
    assert names[-1] == "ΣMp" and rows[-1][-1] == "0"            # the heading's "= 0"
    terms = rows[2:-1]
    printed = [float(row[-1].replace("−", "-")) for row in terms]
    # the printed terms add up to zero to their printed precision (5 significant digits)
    assert abs(sum(printed)) <= 1e-4 * sum(abs(value) for value in printed)
    mechanism = analysis.exercise.mechanism
    notation = ForceNotation(analysis.forces.solution)
    couples = [(item.name, item.link) for item in analysis.forces.solution.applied.items
               if item.moment is not None and float(item.moment[0]) != 0.0]
    assert couples
    _, rates = _independent_balancing_moment(case)
    mu_v = analysis.plans.scales.mu_v
    for name, link in couples:
        printed = notation.plain(name, link)
        if len(mechanism.links[link].points) >= 2:       # a force pair at two points
            assert sum(1 for row in names if row.startswith(f"{printed} (pair, ")) == 2
            continue
        omega_symbol = numbered("ω", notation.number(link))
        row = next(row for row in terms if row[0] == f"{printed}·{omega_symbol}/μv (couple)")
        omega, epsilon = rates[link]
        given = (-CASES[case][2][link][1] * epsilon if name.startswith("M_u")
                 else CASES[case][4][link])
        assert float(row[-1]) == pytest.approx(given * omega / mu_v, rel=2e-4)    # N·mm


def test_the_block_couple_is_drawn_on_the_lever(solved):
    case, _, files = solved
    lever = files["lever.svg"]
    assert re.search(r'data-points="term:M_u,block:block"', lever), case
    assert "M·ω/μv" in lever


def test_the_reports_lever_gives_each_terms_omega(solved):
    case, analysis, _ = solved
    _, rates = _independent_balancing_moment(case)
    entries = [entry for entry in analysis.forces.as_dict()["zhukovsky"]["forces"]
               if "omega" in entry]
    assert {entry["link"] for entry in entries} == {"block"}
    for entry in entries:
        assert entry["force"] == [0.0, 0.0]
        assert entry["omega"] == pytest.approx(rates["block"][0], rel=1e-6)
