"""``import planmethod`` and the computing modules load no drawing library.

Each check runs in a fresh interpreter (a subprocess), so modules imported earlier by other
tests cannot hide or fake an import.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

HEAVY = ("matplotlib", "svgwrite", "shapely")

#: modules whose import must stay light: the package and everything that only computes
LIGHT = ("planmethod", "planmethod.kinematics", "planmethod.plans", "planmethod.report",
         "planmethod.sweep", "planmethod.scene", "planmethod.spec", "planmethod.structure",
         "planmethod.cli", "planmethod.commands.solve", "planmethod.commands.sweep")


def run_fresh(code: str) -> str:
    """What ``code`` prints, run in a fresh interpreter from the repository root."""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout


def heavy_after(code: str) -> list[str]:
    """The heavy top-level packages loaded after running ``code`` in a fresh interpreter."""
    out = run_fresh(f"import sys\n{code}\n"
                    "print('LOADED:' + ','.join(sorted({m.split('.')[0] for m in sys.modules})))")
    line = next(line for line in out.splitlines() if line.startswith("LOADED:"))
    loaded = set(line[len("LOADED:"):].split(","))
    return sorted(loaded & set(HEAVY))


def test_import_planmethod_loads_no_drawing_library():
    assert heavy_after("import planmethod") == []


@pytest.mark.parametrize("module", LIGHT[1:])
def test_computing_modules_load_no_drawing_library(module):
    assert heavy_after(f"import {module}") == []


def test_solving_and_drawing_plans_as_data_loads_no_drawing_library():
    code = ("from planmethod.spec import load_exercise\n"
            "from planmethod.report import analyse, report_dict\n"
            "analysis = analyse(load_exercise('exercises/compressor_slider_crank.toml'))\n"
            "report_dict(analysis)\n")
    assert heavy_after(code) == []


def test_the_probe_sees_a_heavy_import():
    """The check can fail: a module that does import matplotlib is reported."""
    assert heavy_after("import matplotlib") == ["matplotlib"]


def test_the_testing_helpers_import_without_mpmath():
    """mpmath (the ``test`` extra) is needed only when a 40-digit reference is evaluated."""
    code = ("import sys\nsys.modules['mpmath'] = None\n"
            "import planmethod.testing, planmethod.testing.stress\n"
            "try:\n    planmethod.testing.exact_fourbar(60.0)\n"
            "except ImportError:\n    print('NEEDS MPMATH')\n")
    assert run_fresh(code).strip() == "NEEDS MPMATH"


def test_the_command_lines_help_loads_not_even_numpy():
    """``planmethod --help`` and a command's ``--help`` build every parser, so every command
    module is imported: each keeps numpy (about 50 ms of start-up) inside ``run``."""
    code = ("import contextlib, io, sys\nfrom planmethod.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    main(['--help']); main(['sweep', '--help'])\n"
            "print('NUMPY' if 'numpy' in sys.modules else 'LIGHT')\n")
    assert run_fresh(code).strip().splitlines()[-1] == "LIGHT"
