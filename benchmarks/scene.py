"""Compute only what a scene needs, and the command line's start-up time.

*Scene saving*: at one crank angle, the time of everything (all groups, accelerations, both
plans, the check table, and forces when the file gives masses) against a scene that asks only
for v_C: only the groups on the way to C are solved, only up to velocities, no forces; with
``plans=False`` nothing is drawn either. Shown on the shaper six-bar (C is on the lever, so the
rod–ram group is skipped) and on the four-bar with masses (forces skipped).

*Start-up*: wall time of fresh processes — ``python -c pass`` as the floor, ``import
planmethod``, ``planmethod --help``, ``planmethod solve FILE`` (text and ``--json``) — and which
heavy modules each one imports.

Examples
--------
>>> sorted(HEAVY)
['matplotlib', 'scipy', 'shapely', 'svgwrite']
"""

from __future__ import annotations

import shutil
import statistics
import subprocess
import sys
import time
from dataclasses import replace

from planmethod.kinematics import solve
from planmethod.model import Ask
from planmethod.report import analyse
from planmethod.scene import plan_scene
from planmethod.spec import load_exercise
from planmethod.structure import analyse_structure

from .common import ROOT, best_time

HEAVY = ("matplotlib", "shapely", "svgwrite", "scipy")
SCENE_FILES = ("exercises/shaper_sixbar.toml", "exercises/fourbar_forces.toml")


def scene_saving(*, min_time: float = 0.5) -> list[dict]:
    rows = []
    for name in SCENE_FILES:
        exercise = load_exercise(ROOT / name)
        mechanism = exercise.mechanism
        everything = replace(exercise, ask=Ask(everything=True,
                                               forces=bool(mechanism.masses)))
        only_vc = replace(exercise, ask=Ask(velocity=("C",)))
        scene = plan_scene(only_vc)
        structure = analyse_structure(mechanism)
        needed = structure.groups_needed(scene.links)
        cases = [
            ("everything: all groups, a, plans, checks" + (", forces" if mechanism.masses
                                                             else ""),
             lambda e=everything: analyse(e)),
            ("v_C only: its groups, v, the velocity plan", lambda e=only_vc: analyse(e)),
            ("v_C only, exact (plans=False)",
             lambda e=only_vc: analyse(e, plans=False)),
            ("solve(): every group to accelerations", lambda m=mechanism: solve(m)),
            (f"solve(stage='velocity', links={list(scene.links)})",
             lambda m=mechanism, s=scene: solve(m, stage="velocity", links=s.links)),
        ]
        baseline = None
        for label, function in cases:
            function()
            timing = best_time(function, min_time=min_time)
            if baseline is None:
                baseline = timing["best"]
            rows.append({"file": name, "case": label, "best": timing["best"],
                         "median": timing["median"],
                         "fraction_of_everything": timing["best"] / baseline,
                         "groups": f"{len(needed)} of {len(structure.groups)}"
                         if "v_C" in label or "links=" in label else
                         f"{len(structure.groups)} of {len(structure.groups)}"})
    return rows


def _command_prefix() -> list[str]:
    """How to start the command line: the installed script if it is this interpreter's."""
    script = shutil.which("planmethod")
    if script:
        return [script]
    return [sys.executable, "-m", "planmethod.cli"]


def _probe(code: str) -> list[str]:
    """Heavy top-level packages imported after running ``code`` in a fresh interpreter."""
    probe = (f"import sys\n{code}\n"
             f"print('HEAVY:' + ','.join(sorted({{m.split('.')[0] for m in sys.modules}}"
             f" & {set(HEAVY)!r})))")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          cwd=ROOT)
    lines = [line for line in done.stdout.splitlines() if line.startswith("HEAVY:")]
    if done.returncode != 0 or not lines:
        return ["(probe failed)"]
    return [m for m in lines[-1][len("HEAVY:"):].split(",") if m]


def startup(repeats: int = 7) -> list[dict]:
    seed = "exercises/compressor_slider_crank.toml"
    cli = _command_prefix()
    commands = [
        ("python -c pass (the floor)", [sys.executable, "-c", "pass"], "pass"),
        ("python -c 'import planmethod'", [sys.executable, "-c", "import planmethod"],
         "import planmethod"),
        ("planmethod --help", [*cli, "--help"],
         "from planmethod.cli import main\ntry:\n    main(['--help'])\nexcept SystemExit:\n"
         "    pass"),
        (f"planmethod solve {seed}", [*cli, "solve", seed],
         "import contextlib, io\nfrom planmethod.cli import main\n"
         f"with contextlib.redirect_stdout(io.StringIO()):\n    main(['solve', '{seed}'])"),
        (f"planmethod solve {seed} --json", [*cli, "solve", seed, "--json"],
         "import contextlib, io\nfrom planmethod.cli import main\n"
         f"with contextlib.redirect_stdout(io.StringIO()):\n"
         f"    main(['solve', '{seed}', '--json'])"),
    ]
    rows = []
    for label, command, code in commands:
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            done = subprocess.run(command, capture_output=True, cwd=ROOT)
            times.append(time.perf_counter() - start)
            if done.returncode != 0:
                raise RuntimeError(f"{' '.join(command)} failed: {done.stderr[-300:]!r}")
        rows.append({"command": label, "best": min(times), "median": statistics.median(times),
                     "heavy_imports": _probe(code)})
    return rows


def run(quick: bool = False, *, log=print) -> dict:
    log("  scene saving …")
    saving = scene_saving(min_time=0.2 if quick else 0.5)
    log("  command-line start-up …")
    return {"scene": saving, "startup": startup(3 if quick else 7),
            "cli": " ".join(_command_prefix())}


def table(result: dict) -> str:
    lines = ["| exercise | what is computed (one crank angle) | groups | ms | share |",
             "|---|---|---|---|---|"]
    for row in result["scene"]:
        lines.append(f"| {row['file'].split('/')[-1]} | {row['case']} | {row['groups']} | "
                     f"{row['best'] * 1e3:.3g} | {row['fraction_of_everything']:.0%} |")
    lines += ["", "| command (fresh process) | best ms | median ms | heavy modules imported |",
              "|---|---|---|---|"]
    for row in result["startup"]:
        heavy = ", ".join(row["heavy_imports"]) or "none"
        lines.append(f"| `{row['command']}` | {row['best'] * 1e3:.0f} | "
                     f"{row['median'] * 1e3:.0f} | {heavy} |")
    return "\n".join(lines) + "\n"
