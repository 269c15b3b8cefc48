"""Time one open-source peer on one mechanism, inside the peers' own virtualenv.

This file is run by :mod:`benchmarks.run` as a plain script with the Python of the peers'
virtualenv (``python -m benchmarks.peers --setup`` makes it); it imports neither planmethod nor
the ``benchmarks`` package, only the one peer it is asked about. Timing happens here, in the
subprocess, around the peer's own full-turn call (model building and JIT compilation excluded,
as planmethod's row reuses its model, compiled once).

Usage::

    python benchmarks/peers_worker.py PEER MECHANISM N1,N2,... --out FILE.npz [--budget S]

``MECHANISM`` is ``fourbar`` (reference case A: A = (0, 0), D = (0.30, 0), AB = 0.08,
BC = 0.22, CD = 0.18 m, C above AD, ω = 10 rad/s) or ``slider_crank`` (the compressor: AB = 0.06,
BC = 0.18 m, C on the x-axis through A, ω = 100 rad/s). The crank angles are
φ_k = 360°·k/N, k = 0…N−1. Prints one JSON line: per N the best and median wall time of the
repeats (s), or why that N was skipped; the arrays of C's position, velocity and acceleration
at the largest N timed are written to ``FILE.npz`` so the parent can measure their error.

Examples
--------
>>> angles(4).round(6).tolist()
[0.0, 1.570796, 3.141593, 4.712389]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import statistics
import sys
import time
from collections.abc import Callable

import numpy as np

FOURBAR = {"ground": 0.30, "crank": 0.08, "coupler": 0.22, "rocker": 0.18, "omega": 10.0}
SLIDER = {"crank": 0.06, "rod": 0.18, "omega": 100.0}

#: repeats per N: at least this many, more while under ``min_time`` seconds in total
MIN_REPEATS = 3
#: after this many seconds on one N, stop repeating (noise is small against such times)
SLOW = 2.0


def angles(count: int) -> np.ndarray:
    """Crank angles φ_k = 2π·k/N (rad)."""
    return 2.0 * math.pi * np.arange(count) / count


# -- the peers: each returns run(count) -> (positions, velocities, accelerations) of C ----------
def pylinkage_runner(mechanism: str) -> Callable[[int], tuple]:
    """pylinkage 1.3 ``Linkage.step_fast_with_kinematics`` (numba). Its row k is the state after
    k + 1 steps of 2π/N, so the rows are rolled by one to line up with φ_k."""
    import pylinkage as pl

    def build(count: int):
        step = 2.0 * math.pi / count
        if mechanism == "fourbar":
            f = FOURBAR
            a = pl.Ground(0.0, 0.0, name="A")
            d = pl.Ground(f["ground"], 0.0, name="D")
            crank = pl.Crank(anchor=a, radius=f["crank"], angular_velocity=step,
                             initial_angle=0.0, name="B")
            c = pl.RRRDyad(anchor1=crank.output, anchor2=d, distance1=f["coupler"],
                           distance2=f["rocker"], x=0.227, y=0.165, name="C")
            linkage = pl.Linkage([a, d, crank, c])
        else:
            s = SLIDER
            a = pl.Ground(0.0, 0.0, name="A")
            g = pl.Ground(1.0, 0.0, name="G")
            crank = pl.Crank(anchor=a, radius=s["crank"], angular_velocity=step,
                             initial_angle=0.0, name="B")
            c = pl.RRPDyad(revolute_anchor=crank.output, line_anchor1=a, line_anchor2=g,
                           distance=s["rod"], name="C")
            linkage = pl.Linkage([a, g, crank, c])
        omega = FOURBAR["omega"] if mechanism == "fourbar" else SLIDER["omega"]
        linkage.set_input_velocity(crank, omega, 0.0)
        index = [component.name for component in linkage.components].index("C")
        return linkage, index

    cache: dict[int, tuple] = {}

    def prepare(count: int) -> None:
        linkage, index = build(count)
        linkage.step_fast_with_kinematics(iterations=count)  # JIT compile, warm up
        cache[count] = (linkage, index)

    def run(count: int):
        if count not in cache:
            prepare(count)
        linkage, index = cache[count]
        positions, velocities, accelerations = linkage.step_fast_with_kinematics(iterations=count)
        return tuple(np.roll(array[:, index, :], 1, axis=0)
                     for array in (positions, velocities, accelerations))

    run.prepare = prepare
    return run


def mechanism_runner(mechanism: str) -> Callable[[int], tuple]:
    """mechanism 1.1 (gabemorris12): vector loops solved by scipy ``fsolve`` at each angle."""
    from mechanism import Mechanism, Vector, get_joints

    def run(count: int):
        phi = angles(count)
        if mechanism == "fourbar":
            f = FOURBAR
            a_, b_, c_, d_ = get_joints("A B C D")
            a = Vector((a_, b_), r=f["crank"])
            b = Vector((b_, c_), r=f["coupler"])
            c = Vector((a_, d_), r=f["ground"], theta=0, style="ground")
            d = Vector((d_, c_), r=f["rocker"])

            def loop(x, i):
                return a(i) + b(x[0]) - c() - d(x[1])

            guess = (np.array([0.8, 1.9]), np.array([1.0, 1.0]), np.array([1.0, 1.0]))
            vectors, omega, target = (a, b, c, d), f["omega"], c_
        else:
            s = SLIDER
            a_, b_, c_ = get_joints("A B C")
            a = Vector((a_, b_), r=s["crank"])
            b = Vector((b_, c_), r=s["rod"])
            c = Vector((a_, c_), theta=0, style="ground")

            def loop(x, i):
                return a(i) + b(x[0]) - c(x[1])

            guess = (np.array([0.0, 0.24]), np.array([1.0, 1.0]), np.array([1.0, 1.0]))
            vectors, omega, target = (a, b, c), s["omega"], c_
        model = Mechanism(vectors=vectors, origin=a_, loops=loop, pos=phi,
                          vel=np.full(count, omega), acc=np.zeros(count), guess=guess)
        model.iterate()
        return (np.stack((target.x_positions, target.y_positions), axis=-1),
                np.stack((target.x_velocities, target.y_velocities), axis=-1),
                np.stack((target.x_accelerations, target.y_accelerations), axis=-1))

    return run


def kimech_runner(mechanism: str) -> Callable[[int], tuple]:
    """kimech 0.7: Newton continuation over the sweep, exact linear velocity/acceleration solves."""
    from kimech import KinematicDriver, Mechanism, solve

    def run(count: int):
        phi = angles(count)
        model = Mechanism("peer")
        ground = model.ground
        if mechanism == "fourbar":
            f = FOURBAR
            ga, gd = ground.add_point("A", (0.0, 0.0)), ground.add_point("D", (f["ground"], 0.0))
            crank = model.add_link("crank")
            ca, cb = crank.add_point("A", (0, 0)), crank.add_point("B", (f["crank"], 0))
            coupler = model.add_link("coupler")
            ob, oc = coupler.add_point("B", (0, 0)), coupler.add_point("C", (f["coupler"], 0))
            rocker = model.add_link("rocker")
            rc, rd = rocker.add_point("C", (0, 0)), rocker.add_point("D", (f["rocker"], 0))
            joint = model.revolute(ga, ca, name="input")
            model.revolute(cb, ob)
            model.revolute(oc, rc)
            model.revolute(rd, gd)
            guess = {crank: (0, 0, 0.0), coupler: (0.08, 0.0, 0.84),
                     rocker: (0.227, 0.165, -1.15)}
            omega, target = f["omega"], oc
        else:
            s = SLIDER
            ga = ground.add_point("A", (0.0, 0.0))
            crank = model.add_link("crank")
            ca, cb = crank.add_point("A", (0, 0)), crank.add_point("B", (s["crank"], 0))
            rod = model.add_link("rod")
            ob, oc = rod.add_point("B", (0, 0)), rod.add_point("C", (s["rod"], 0))
            slider = model.add_link("slider")
            sc = slider.add_point("C", (0, 0))
            joint = model.revolute(ga, ca, name="input")
            model.revolute(cb, ob)
            model.revolute(oc, sc)
            model.prismatic(ga, sc, axis_a=(1.0, 0.0), axis_b=(1.0, 0.0))
            guess = {crank: (0, 0, 0.0), rod: (0.06, 0.0, 0.0),
                     slider: (0.24, 0.0, 0.0)}
            omega, target = s["omega"], oc
        driver = KinematicDriver(joint, position=phi, velocity=omega, acceleration=0.0)
        solution = solve(model, drivers=driver, initial_guess=guess)
        return (np.asarray(solution.point_positions(target)),
                np.asarray(solution.point_velocities(target)),
                np.asarray(solution.point_accelerations(target)))

    return run


def fourbarhinge_runner(mechanism: str) -> Callable[[int], tuple]:
    """fourbarhinge 0.1: closed-form four-bar, one angle at a time (four-bars only)."""
    if mechanism != "fourbar":
        raise NotImplementedError("fourbarhinge models four-bar hinges only")
    from fourbarhinge import Bar, BarId, FourBarGeometry, FourBarKinematics, Point

    f = FOURBAR
    geometry = FourBarGeometry(position_ground=Point(x=0, y=0), bar={
        BarId.GROUND: Bar(length=f["ground"]), BarId.INPUT: Bar(length=f["crank"]),
        BarId.COUPLER: Bar(length=f["coupler"]), BarId.OUTPUT: Bar(length=f["rocker"])})
    model = FourBarKinematics(geometry, 0.0)
    c_local = Point(x=f["coupler"], y=0.0)

    def run(count: int):
        out = np.empty((3, count, 2))
        for k, phi in enumerate(angles(count)):
            model.solve_configuration(float(phi), -1)  # branch −1: C above AD
            model.solve_theta_dot(f["omega"])
            model.solve_theta_ddot(0.0)
            out[0, k] = model.get_joint_positions()["C"]
            out[1, k] = model.get_point_velocity(BarId.COUPLER, c_local)
            out[2, k] = model.get_point_acceleration(BarId.COUPLER, c_local)
        return out[0], out[1], out[2]

    return run


def kinepy_runner(mechanism: str) -> Callable[[int], tuple]:
    """kinepy 0.1.7: vectorised closed-form positions; it has no velocity or acceleration
    solver, so v and a are central differences of its positions on the angle grid (periodic),
    as a user of it would compute them."""
    from kinepy import System
    from kinepy.units import SI, set_unit_system

    set_unit_system(SI)
    quiet = contextlib.redirect_stdout(io.StringIO())
    with quiet:
        system = System()
        if mechanism == "fourbar":
            f = FOURBAR
            crank, coupler, rocker = (system.add_solid(n) for n in ("AB", "BC", "CD"))
            drive = system.add_revolute(0, crank, (0.0, 0.0), (0.0, 0.0))
            system.add_revolute(crank, coupler, (f["crank"], 0.0), (0.0, 0.0))
            system.add_revolute(coupler, rocker, (f["coupler"], 0.0), (0.0, 0.0))
            system.add_revolute(rocker, 0, (f["rocker"], 0.0), (f["ground"], 0.0))
            omega, body, local = f["omega"], coupler, (f["coupler"], 0.0)
        else:
            s = SLIDER
            crank, rod, slider = (system.add_solid(n) for n in ("AB", "BC", "slider"))
            drive = system.add_revolute(0, crank, (0.0, 0.0), (0.0, 0.0))
            system.add_revolute(crank, rod, (s["crank"], 0.0), (0.0, 0.0))
            system.add_revolute(rod, slider, (s["rod"], 0.0), (0.0, 0.0))
            system.add_prismatic(slider, 0, 0.0, 0.0, 0.0, 0.0)
            omega, body, local = s["omega"], rod, (s["rod"], 0.0)
        system.pilot(drive)
        system.compile()
        # kinepy's default assembly is the other one in both cases (C below AD; C on −x)
        system.change_signs({key: -value for key, value in system._object.signs.items()})

    def run(count: int):
        phi = angles(count)
        with contextlib.redirect_stdout(io.StringIO()):
            system.solve_kinematics(phi[None, :].copy())
        position = np.asarray(body.get_point(local), dtype=float).T
        h = 2.0 * math.pi / count / omega  # time step between samples
        ahead, behind = np.roll(position, -1, axis=0), np.roll(position, 1, axis=0)
        velocity = (ahead - behind) / (2.0 * h)
        acceleration = (ahead - 2.0 * position + behind) / (h * h)
        return position, velocity, acceleration

    return run


RUNNERS = {"pylinkage": pylinkage_runner, "mechanism": mechanism_runner,
           "kimech": kimech_runner, "fourbarhinge": fourbarhinge_runner,
           "kinepy": kinepy_runner}


def version_of(peer: str) -> str:
    from importlib.metadata import version

    return version(peer)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("peer", choices=sorted(RUNNERS))
    parser.add_argument("mechanism", choices=("fourbar", "slider_crank"))
    parser.add_argument("counts", help="comma-separated numbers of angles")
    parser.add_argument("--out", required=True, help="npz file for C's arrays")
    parser.add_argument("--budget", type=float, default=20.0,
                        help="skip an N whose estimated single run exceeds this (s)")
    parser.add_argument("--min-time", type=float, default=0.5,
                        help="repeat each N until this much time was spent (s)")
    args = parser.parse_args(argv)
    report: dict = {"peer": args.peer, "mechanism": args.mechanism, "python": sys.version,
                    "numpy": np.__version__, "runs": {}}
    try:
        report["version"] = version_of(args.peer)
        run = RUNNERS[args.peer](args.mechanism)
    except (ImportError, NotImplementedError) as error:
        report["unsupported"] = f"{type(error).__name__}: {error}"
        print(json.dumps(report))
        return 0
    per_angle = None
    arrays = None
    for count in (int(c) for c in args.counts.split(",")):
        if per_angle is not None and per_angle * count > args.budget:
            report["runs"][count] = {"skipped": f"estimated {per_angle * count:.0f} s for one "
                                                f"run, over the {args.budget:g} s budget"}
            continue
        if hasattr(run, "prepare"):
            run.prepare(count)  # model building and JIT compilation are not timed
        elif per_angle is None:
            run(count)  # warm-up: imports, caches, first allocations
        times: list[float] = []
        while len(times) < 200 and (len(times) < MIN_REPEATS or sum(times) < args.min_time):
            start = time.perf_counter()
            result = run(count)
            times.append(time.perf_counter() - start)
            if sum(times) > SLOW:  # a peer this slow: one run tells enough
                break
        per_angle = min(times) / count
        report["runs"][count] = {"best": min(times), "median": statistics.median(times),
                                 "repeats": len(times)}
        arrays = (count, result)
    if arrays is not None:
        count, (position, velocity, acceleration) = arrays
        np.savez(args.out, count=count, position=position, velocity=velocity,
                 acceleration=acceleration)
    print(json.dumps(report))
    return 0


if __name__ == "__main__":
    sys.exit(main())
