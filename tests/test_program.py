"""The compiled program: tracing (folding, signs, shared values, the workspace), one compilation
per mechanism, guards and redo, read-only results, threads."""

from __future__ import annotations

import dataclasses
import threading
import weakref

import numpy as np
import pytest

from planmethod.errors import AssemblyError
from planmethod.kinematics import solve
from planmethod.kinematics.program import model
from planmethod.kinematics.tracing import Redo, Tracer
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.sweep import sweep_table
from planmethod.testing import fourbar


def _fresh(path: str, title: str):
    exercise = load_exercise(path)
    mechanism = dataclasses.replace(exercise.mechanism, title=title)
    return dataclasses.replace(exercise, mechanism=mechanism)


# -- tracing --------------------------------------------------------------------------------
def test_constants_fold_and_signs_are_carried():
    tracer = Tracer()
    phi = tracer.angles()
    x = tracer.apply("cos", phi)
    assert x * 1.0 is x and x + 0.0 is x and (x * 0.0) == 0.0
    assert 2.0 * 3.0 + 1.0 == 7.0  # (plain floats stay floats)
    minus = -x
    assert minus.negated and minus.id == x.id          # a negation costs nothing …
    assert (minus * 2.0).negated is False              # … the sign goes into the constant
    assert (x - x) == 0.0 and (x + minus) == 0.0
    before = len(tracer.ops)
    assert (x * phi).id == (phi * x).id and len(tracer.ops) == before + 1  # recorded once


def test_the_workspace_is_reused():
    tracer = Tracer()
    value = tracer.apply("cos", tracer.angles())
    for step in range(50):   # a long chain: each value dies as the next is made
        value = value * 1.5 + float(step)
    tracer.output("out", value)
    compiled = tracer.compile()
    assert compiled.work <= 2
    angles = np.array([10.0, 20.0])
    expected = np.cos(angles)
    for step in range(50):
        expected = expected * 1.5 + step
    assert np.array_equal(compiled.read(compiled.evaluate(angles), "out"), expected)


def test_degrees_become_radians_bit_for_bit():
    """The crank angle's conversion is one multiply by the factor np.radians uses."""
    from planmethod.kinematics.program import RADIAN, drive_body

    angles = np.concatenate((np.arange(-720.0, 720.0, 0.37), [1e-300, 89.99999999999999]))
    assert np.array_equal(angles * RADIAN, np.radians(angles))
    mechanism = exercise_from_dict(fourbar()).mechanism
    _, theta = drive_body(mechanism, angles)
    assert np.array_equal(theta, np.radians(angles))


def test_a_magnitude_guard_catches_either_sign_and_a_change_of_sign():
    seen = []

    def check(angles, values):
        seen.append(values.copy())

    tracer = Tracer()
    value = tracer.apply("sin", tracer.angles() * (np.pi / 180.0))
    tracer.guard(value, 0.5, check, value, magnitude=True)
    tracer.output("out", value)
    compiled = tracer.compile()
    for angles, called in (([40.0, 140.0], False), ([-40.0, -140.0], False),
                           ([40.0, 20.0], True), ([-40.0, -20.0], True),
                           ([40.0, -40.0], True), ([-40.0, 40.0], True)):
        seen.clear()
        compiled.evaluate(np.array(angles))
        assert bool(seen) is called, angles


def test_a_product_and_its_negation_are_computed_once():
    """x·c and x·(−c) both wanted: sums take the one computed, bit for bit."""
    tracer = Tracer()
    x = tracer.apply("cos", tracer.angles())
    y = tracer.apply("sin", tracer.angles())
    plus = x * 3.0
    tracer.output("negated", -plus)          # x·(−3) is what the result needs …
    tracer.output("sum", y + plus)           # … and these take it: y − x·(−3)
    tracer.output("difference", y - plus)    # y + x·(−3)
    compiled = tracer.compile()
    assert compiled.source.count("multiply(") == 1
    angles = np.concatenate((np.linspace(-400.0, 400.0, 2001), [90.0, 270.0]))
    rows = compiled.evaluate(angles)
    x, y = np.cos(angles), np.sin(angles)
    assert np.array_equal(compiled.read(rows, "negated"), -(x * 3.0))
    assert np.array_equal(compiled.read(rows, "sum"), y + x * 3.0)
    assert np.array_equal(compiled.read(rows, "difference"), y - x * 3.0)


def test_a_product_used_in_a_product_is_kept():
    tracer = Tracer()
    x = tracer.apply("cos", tracer.angles())
    plus = x * 3.0
    tracer.output("negated", -plus)
    tracer.output("square", plus * plus)     # a product cannot take the negation
    compiled = tracer.compile()
    assert compiled.source.count("multiply(") == 3
    angles = np.array([10.0, 200.0])
    rows = compiled.evaluate(angles)
    assert np.array_equal(compiled.read(rows, "square"), (np.cos(angles) * 3.0) ** 2)


def test_mechanisms_that_differ_in_their_numbers_share_one_compiled_code(monkeypatch):
    """A template's variants differ in their numbers only: their programs are compiled once,
    each with its own numbers, and each gives what the formulas give directly."""
    from planmethod.kinematics import tracing

    compiled_sources = []

    def counting(source, *args, **keywords):
        compiled_sources.append(source)
        return compile(source, *args, **keywords)

    monkeypatch.setattr(tracing, "compile", counting, raising=False)
    monkeypatch.setattr(tracing, "_CODE", {})
    angles = np.arange(0.0, 360.0, 7.5)
    first = exercise_from_dict(fourbar(crank=0.0812, omega=11.5)).mechanism
    second = exercise_from_dict(fourbar(crank=0.0734, coupler=0.2311, omega=-9.25)).mechanism
    compiled = []
    for mechanism in (first, second):
        solve(mechanism, angles)
        compiled.append(model(mechanism).program(2).compiled)
    assert len(compiled_sources) == 1                    # the second found it compiled
    assert compiled[0].function.__code__.co_code == compiled[1].function.__code__.co_code
    assert compiled[0].function.__code__.co_consts != compiled[1].function.__code__.co_consts
    assert "0.0812" in compiled[0].source and "0.0734" in compiled[1].source  # readable
    for mechanism in (first, second):
        fast, direct = solve(mechanism, angles), solve(mechanism, angles, reference=True)
        for point in ("B", "C", "P"):
            scale = float(np.max(np.abs(direct.acceleration(point))))
            assert np.max(np.abs(fast.acceleration(point) - direct.acceleration(point))) \
                <= 1e-12 * scale


def test_a_guard_calls_its_check_only_where_its_bound_fails():
    seen = []

    def check(angles, values):
        seen.append(list(angles))
        if np.any(values < -0.5):
            raise ValueError("refused")

    tracer = Tracer()
    c = tracer.apply("cos", tracer.angles() * (np.pi / 180.0))
    tracer.guard(c, 0.0, check, c)
    tracer.output("c", c)
    compiled = tracer.compile()
    compiled.evaluate(np.array([0.0, 10.0]))
    assert seen == []
    compiled.evaluate(np.array([0.0, 100.0]))           # cos < 0: checked, accepted
    assert seen == [[0.0, 100.0]]
    with pytest.raises(ValueError, match="refused"):
        compiled.evaluate(np.array([0.0, 180.0]))


def test_a_redo_evaluates_the_chunk_again():
    def check(angles, values):
        raise Redo

    tracer = Tracer()
    c = tracer.apply("cos", tracer.angles() * (np.pi / 180.0))
    tracer.guard(c, 0.0, check, c)
    tracer.output("c", c)
    compiled = tracer.compile()
    with pytest.raises(Redo):                        # nothing to hand the chunk back to
        compiled.evaluate(np.array([0.0, 120.0]))
    rows = compiled.evaluate(np.array([0.0, 120.0]),
                             redo=lambda angles, rows: rows[0].__setitem__(Ellipsis, -1.0))
    assert compiled.read(rows, "c").tolist() == [-1, -1]


# -- the program of a mechanism ---------------------------------------------------------------
@pytest.mark.parametrize("path", ["exercises/compressor_slider_crank.toml",
                                  "exercises/shaper_sixbar.toml",
                                  "exercises/conveyor_sixbar.toml"])
def test_a_sweep_compiles_the_mechanism_once(path):
    exercise = _fresh(path, "compiled once")
    found = model(exercise.mechanism)
    assert found.compilations == 0
    sweep_table(exercise, step=10)
    sweep_table(exercise, step=7)
    for angle in (10.0, 20.0, 30.0):
        solve(load_exercise(path).mechanism, angle)  # an equal model … of another title
    again = _fresh(path, "compiled once")            # … and one equal in every way
    assert model(again.mechanism) is found
    solve(again.mechanism, np.arange(0.0, 360.0, 10.0))
    assert found.compilations == 1


@pytest.mark.parametrize("path, shared", [("exercises/compressor_slider_crank.toml", True),
                                          ("exercises/shaper_sixbar.toml", True),
                                          ("exercises/conveyor_sixbar.toml", False)])
def test_a_posed_mechanism_shares_its_dyads_program(path, shared):
    """Posed at another crank angle (drive.angle and the sketch changed), a mechanism of dyads
    runs the program compiled for it before; a class III group follows its path from
    drive.angle, so the conveyor's posed mechanism compiles its own."""
    from planmethod.kinematics.continuation import pose

    exercise = _fresh(path, f"posed {path}")
    solve(exercise.mechanism, stage="acceleration")
    posed = pose(exercise.mechanism, 100.0).mechanism
    assert posed.drive.angle == 100.0 and posed.sketch != exercise.mechanism.sketch
    motion = solve(posed, stage="acceleration")
    assert (model(posed).compilations == 0) is shared
    exact = solve(exercise.mechanism, 100.0, stage="acceleration", reference=True)
    for point in motion.mechanism.links[posed.drive.link].points:
        assert np.allclose(motion.acceleration(point), exact.acceleration(point), rtol=1e-12,
                           atol=0.0)
    for link in motion.solved:
        for point in posed.links[link].points:
            assert np.allclose(motion.position(point), exact.position(point), rtol=1e-12,
                               atol=1e-15)
            assert np.allclose(motion.acceleration(point), exact.acceleration(point),
                               rtol=1e-11, atol=1e-12)


def test_a_reference_solve_and_a_posed_check_compile_nothing():
    """The reference path runs the group kinds' formulas directly: it compiles no program,
    and gives the compiled program's motion; so posing the conveyor (its class III group's
    search checked by the reference path) leaves the posed mechanism nothing compiled."""
    from planmethod.kinematics.continuation import pose

    exercise = _fresh("exercises/conveyor_sixbar.toml", "reference compiles nothing")
    found = model(exercise.mechanism)
    angles = np.array([10.0, 200.0])
    direct = solve(exercise.mechanism, angles, stage="acceleration", reference=True)
    assert found.compilations == 0
    compiled = solve(exercise.mechanism, angles, stage="acceleration")
    assert found.compilations == 1
    assert direct.branches == compiled.branches and direct.solved == compiled.solved
    for link in direct.solved:
        for point in exercise.mechanism.links[link].points:
            assert np.allclose(direct.position(point), compiled.position(point), rtol=1e-12,
                               atol=1e-15)
    posed = pose(exercise.mechanism, 100.0).mechanism
    assert model(posed).compilations == 0


def test_a_motion_is_over_arrays_and_at_reads_one_angle():
    """A motion's readers return arrays over its angles whether one angle or many was asked
    (no flag changes what they return); ``at(i)`` reads the same values at angle i — a vector
    of shape (2,), a number — bit for bit what the arrays hold there."""
    mechanism = load_exercise("exercises/slotted_lever.toml").mechanism
    one, default = solve(mechanism, 60.0), solve(mechanism)
    assert one.position("B").shape == default.position("B").shape == (1, 2)
    assert one.omega("lever").shape == (1,) and one.angles.tolist() == [60.0]
    angles = np.array([0.0, 60.0, 200.0])
    motion = solve(mechanism, angles)
    slide = mechanism.slides[0].key
    for index, angle in enumerate(angles):
        here = motion.at(index)
        assert here.angle == angle and here.motion is motion
        single = solve(mechanism, angle).at(0)
        for reader in ("position", "velocity", "acceleration"):
            for point in ("B", "B@lever", "C"):
                value = getattr(here, reader)(point)
                assert value.shape == (2,)
                assert np.array_equal(value, getattr(motion, reader)(point)[index])
                assert np.allclose(getattr(single, reader)(point), value, rtol=1e-12, atol=0)
        for reader in ("theta", "omega", "epsilon"):
            value = getattr(here, reader)("lever")
            assert np.ndim(value) == 0 and value == getattr(motion, reader)("lever")[index]
        assert np.array_equal(here.place("lever", (0.1, 0.0)),
                              motion.place("lever", (0.1, 0.0))[index])
        sliding, sliding_all = here.sliding(slide), motion.sliding(slide)
        for field in ("s", "velocity", "acceleration", "coriolis"):
            assert np.array_equal(getattr(sliding, field), getattr(sliding_all, field)[index])
        curvature, curvature_all = here.curvature("C"), motion.curvature("C")
        assert curvature.straight is curvature_all.straight
        for field in ("rho", "center", "inflection", "stationary"):
            assert np.array_equal(getattr(curvature, field), getattr(curvature_all, field)[index],
                                  equal_nan=field in ("rho", "center"))
    with pytest.raises(IndexError):
        motion.at(3)
    position = solve(mechanism, angles, stage="position").at(1).sliding(slide)
    assert position.velocity is None and position.coriolis is None


def test_results_are_read_only_values():
    mechanism = exercise_from_dict(fourbar()).mechanism
    motion = solve(mechanism, [0.0, 60.0])
    for array in (motion.position("C"), motion.velocity("P"), motion.omega("CD"),
                  motion.links["BC"].origin):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        motion.stage = "velocity"
    first = motion.acceleration("C").copy()
    solve(mechanism, [0.0, 60.0])                    # another solve changes nothing here
    assert np.array_equal(motion.acceleration("C"), first)


def test_a_dropped_motion_is_freed_at_once():
    """A motion holds nothing that refers back to it: dropping it frees its result rows at
    once (not at the next garbage collection), so the next solve reuses that memory instead of
    paying page faults on fresh pages."""
    mechanism = exercise_from_dict(fourbar()).mechanism
    motion = solve(mechanism, np.arange(0.0, 360.0, 0.5))
    group = motion.groups[0]
    assert group.construction is group.construction      # made once, kept by the motion
    assert group.error_estimate is group.error_estimate
    held = weakref.ref(motion)
    del motion, group
    assert held() is None


def test_threads_share_a_program_but_not_its_workspace():
    mechanism = exercise_from_dict(fourbar()).mechanism
    expected = {start: solve(mechanism, np.arange(start, start + 360.0, 0.5)).acceleration("C")
                for start in (0.0, 0.25)}
    failures = []

    def work(start):
        for _ in range(30):
            found = solve(mechanism, np.arange(start, start + 360.0, 0.5)).acceleration("C")
            if not np.array_equal(found, expected[start]):
                failures.append(start)

    threads = [threading.Thread(target=work, args=(start,)) for start in (0.0, 0.25) * 2]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not failures


def test_errors_name_the_first_angle_in_long_sweeps_too():
    data = fourbar(crank=0.2)          # a crank too long for the rocker: cannot go round
    mechanism = exercise_from_dict(data).mechanism
    with pytest.raises(AssemblyError) as short:
        solve(mechanism, np.arange(60.0, 420.0, 1.0))
    angles = np.linspace(60.0, 420.0, 360_001)   # many chunks
    with pytest.raises(AssemblyError) as long:
        solve(mechanism, angles)
    assert long.value.link == short.value.link
    assert short.value.angle - 1.0 < long.value.angle <= short.value.angle
    first = int(np.flatnonzero(angles == long.value.angle)[0])
    solve(mechanism, angles[:first])                 # every angle before it assembles
    with pytest.raises(AssemblyError):
        solve(mechanism, angles[first])
