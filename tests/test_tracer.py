"""The tracer's emitted program (kinematics/algebra.py + tracing.py + program.py), kind by kind,
against numbers it has no part in.

For every registered group kind, random mechanisms containing it (the generators of
``tests/test_group_kinds.py``) are compiled into their straight-line program — positions,
velocities and accelerations of every link and named point — and the program is run at random
crank angles. What it writes is compared with an independent solution: the whole mechanism's
constraint equations solved by Newton and two exact linear solves
(:func:`planmethod.testing.reference_motion`, which shares no formula with the kinds), each
point then placed, and its velocity and acceleration found, by the rigid-body formulas written
out here (on :mod:`planmethod.vectors`, which the program does not use). The drive link is
evaluated here from its angle, ω1 and ε1. The program must run straight through (no chunk
handed back to the direct evaluation) and agree to 1e-12 relative.

``docs/architecture.md`` shows one emitted program; the last test keeps that page true.
"""

from __future__ import annotations

import contextlib
import copy
import io
import re
from pathlib import Path

import numpy as np
import pytest
from test_group_kinds import CASES, _grid

from planmethod.kinematics.groups import kind_module
from planmethod.kinematics.program import STAGES, Result, model, owners
from planmethod.model import FRAME
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.testing import reference_motion
from planmethod.vectors import perp, rotate, unit_angle

ROOT = Path(__file__).resolve().parent.parent
RELATIVE = 1e-12
ANGLES = 24


def _rigid(theta, origin, omega, velocity, epsilon, acceleration, local):
    """A material point of a rigid link: place, velocity, acceleration."""
    r = rotate(local, theta)
    return (origin + r, velocity + omega[:, None] * perp(r),
            acceleration + epsilon[:, None] * perp(r) - (omega ** 2)[:, None] * r)


def _expected(mechanism, angles: np.ndarray) -> dict[str, dict]:
    """Every link's motion: the frame at rest, the drive turning about its pivot at ω1, ε1,
    the others from the oracle."""
    drive = mechanism.drive
    count = angles.shape[0]
    theta = np.radians(angles)
    pivot = np.asarray(mechanism.local(FRAME, drive.pivot), dtype=float)
    arm = -rotate(mechanism.local(drive.link, drive.pivot), theta)     # pivot → origin
    j_arm = perp(arm)
    out = reference_motion(mechanism, angles)
    out[drive.link] = {"theta": theta, "origin": pivot + arm,
                       "omega": np.full(count, drive.omega), "velocity": drive.omega * j_arm,
                       "epsilon": np.full(count, drive.epsilon),
                       "acceleration": drive.epsilon * j_arm - drive.omega ** 2 * arm}
    zero, zeros = np.zeros(count), np.zeros((count, 2))
    out[FRAME] = {"theta": zero, "origin": zeros, "omega": zero, "velocity": zeros,
                  "epsilon": zero, "acceleration": zeros}
    return out


def _close(got, expected, scale: float, what: str) -> None:
    got, expected = np.asarray(got, dtype=float), np.asarray(expected, dtype=float)
    assert np.abs(got - expected).max() <= RELATIVE * max(scale, 1e-300), what


def _straight_through(program, angles: np.ndarray) -> Result:
    """The program's outputs, with no chunk handed back to the direct evaluation."""
    handed_back = []
    rows = program.compiled.evaluate(angles, redo=lambda angles_deg, rows: handed_back.append(1))
    assert not handed_back, "a chunk was handed back to the direct evaluation"
    rows.flags.writeable = False
    return Result(program.schema, rows, angles.shape[0], {})


def _mechanisms(name: str):
    rng = np.random.default_rng(sum(map(ord, name)) + 25)
    for _ in range(2):
        mechanism = exercise_from_dict(copy.deepcopy(CASES[name](rng))).mechanism
        grid = _grid(mechanism)
        angles = rng.choice(grid, size=min(ANGLES, grid.size), replace=False)
        yield mechanism, np.sort(angles + rng.uniform(-1.0, 1.0, size=angles.size))


@pytest.mark.parametrize("name", sorted(CASES))
def test_the_emitted_program_agrees_with_an_independent_solution(name):
    for mechanism, angles in _mechanisms(name):
        found = model(mechanism)
        groups = found.groups()
        assert name in {kind_module(group).name for group in groups}, name
        level = STAGES.index("acceleration")
        program = found.program(level, groups, found.branches(groups))
        result = _straight_through(program, angles)
        schema = result.schema
        expected = _expected(mechanism, angles)
        speed = max(float(np.abs(e["velocity"]).max()) for e in expected.values())
        accel = max(float(np.abs(e["acceleration"]).max()) for e in expected.values())
        rate = max(float(np.abs(e["omega"]).max()) for e in expected.values())
        spin = max(float(np.abs(e["epsilon"]).max()) for e in expected.values())
        size = max(float(np.abs(e["origin"]).max()) for e in expected.values())
        for link, motion in expected.items():
            axes = unit_angle(motion["theta"])
            rows = schema.links[link]
            _close(result.read(rows.axes), axes, 1.0, (name, link, "axes"))
            _close(result.read(rows.omega), motion["omega"], rate, (name, link, "omega"))
            _close(result.read(rows.epsilon), motion["epsilon"], spin, (name, link, "epsilon"))
        assert dict(schema.owners) == owners(mechanism, expected)
        for point, link in schema.owners.items():
            m = expected[link]
            place, velocity, acceleration = _rigid(
                m["theta"], m["origin"], m["omega"], m["velocity"], m["epsilon"],
                m["acceleration"], mechanism.local(link, point))
            rows = schema.points[point]
            _close(result.read(rows.position), place, size, (name, point, "p"))
            _close(result.read(rows.velocity), velocity, speed, (name, point, "v"))
            _close(result.read(rows.acceleration), acceleration, accel, (name, point, "a"))


def test_the_comparison_can_fail():
    """A program whose numbers are off by more than the tolerance is caught."""
    mechanism, angles = next(_mechanisms("rrr"))
    expected = _expected(mechanism, angles)
    link = next(name for name in mechanism.links if name not in (FRAME, mechanism.drive.link))
    with pytest.raises(AssertionError):
        _close(expected[link]["omega"] * (1 + 1e-9), expected[link]["omega"],
               float(np.abs(expected[link]["omega"]).max()), "omega")


def _block(page: str, tag: str) -> str:
    """The page's code block opened by ```python TAG."""
    return re.search(rf"^```python {tag}\n(.*?)^```", page, re.S | re.M).group(1)


def test_the_architecture_page_shows_real_programs():
    page = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(_block(page, "example"), {})
    assert printed.getvalue().startswith(_block(page, "printed"))
    mechanism = load_exercise(ROOT / "exercises" / "compressor_slider_crank.toml").mechanism
    found = model(mechanism)
    groups = found.groups()
    program = found.program(STAGES.index("velocity"), groups, found.branches(groups))
    assert _block(page, "program").strip() == program.compiled.source.strip()
