"""Baselines of every shipped exercise's reports, and the comparison that keeps them.

The restructuring of the solver, the plans and the forces must change no number: each shipped
exercise's ``planmethod solve --json`` report at ``drive.angle`` and at ``drive.angle + 97°``,
its kinematic sweep every 10° (``planmethod sweep --csv``) and, with masses, its force sweep
every 30°, were written here before the change (``python -m tests.baselines``, run from the
project's root) and are compared by ``tests/test_baselines.py``.

Numbers must agree to 1e-12 relative — relative to the larger of the two values and of the
largest magnitude among their siblings (the other component of the same vector, the other
entries of the same row), so that a component that is zero up to rounding compares sensibly.
Rounding noise itself is compared to 1e-12 of the quantity it measures: a check's
``abs_error`` to its analytic value, ``rel_error`` and the power residual and whole-system
difference (already relative) to 1, a difference of two computations of one moment to that
moment (the largest magnitude of what it sits among). The angle between two construction lines
is compared by its sine (its arcsine has no digits to spare near 90°: a sine of 1 − 1 ulp is
89.9999991°). Text must be identical, except a title that said "seed": it may now cite the
paper instead. A sweep table may gain the columns ``ADDED_COLUMNS`` names (a later extension
of the CSV); every column it had is compared.

Drawing scales are now the standard series' values (docs/exercise-file.md), so what
depends on the scale alone is left out of the comparison — and nothing else: the scales
themselves (``scale``, ``mu_*``), lengths and points on the drawings (every key ending in
``_mm``, with all it holds), a construction step's sentence (it quotes drawn lengths), and
Aliyev's constants that are products of scales (``J_mu_a_over_l``, ``m_mu_a_mu_l``). Every
value in SI units — exact, read off the plan, forces, moments, checks — is still compared.
"""

from __future__ import annotations

import csv
import io
import json
import math
import tomllib
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FOLDER = Path(__file__).resolve().parent / "data" / "baselines"
RELATIVE = 1e-12
#: keys whose values are rounding noise: compared to RELATIVE of the quantity they measure
NOISE = {"abs_error", "rel_error", "power_residual", "max_rel_difference", "residual",
         "difference"}
#: relative noise: compared to RELATIVE absolutely
RELATIVE_NOISE = {"rel_error", "power_residual", "max_rel_difference", "residual"}
#: angles between construction lines (deg): compared by their sine
LINE_ANGLES = {"angle_deg", "line_angle_deg"}
#: columns a sweep table may have gained since (by prefix): the friction's sense per pair
ADDED_COLUMNS = ("friction_sense_",)


def exercises() -> list[Path]:
    return sorted((ROOT / "exercises").glob("*.toml"))


def _run(*argv: str) -> tuple[int, str, str]:
    """Run the CLI; the project's folder in messages reads ``<root>``, wherever it is checked
    out (a worktree, a CI runner)."""
    from planmethod.cli import main

    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        code = main(list(argv))
    return code, out.getvalue(), err.getvalue().replace(str(ROOT), "<root>")


def _sweep(path: Path, *extra: str) -> dict:
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        target = Path(folder) / "sweep.csv"
        code, _, err = _run("sweep", str(path), "--csv", str(target), *extra)
        if code:
            return {"error": err.strip()}
        rows = list(csv.reader(target.read_text(encoding="utf-8").splitlines()))
    return {"header": rows[0], "rows": [[float(cell) for cell in row] for row in rows[1:]]}


def record(path: Path) -> dict:
    """Everything the baseline of one exercise holds."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    angle = float(data["drive"]["angle"])
    reports = {}
    for at in (angle, angle + 97.0):
        code, out, err = _run("solve", str(path), "--angle", repr(at), "--json")
        reports[repr(at)] = json.loads(out) if code == 0 else {"error": err.strip()}
    out = {"reports": reports, "sweep": _sweep(path, "--step", "10")}
    if "mass" in data:
        out["force_sweep"] = _sweep(path, "--step", "30", "--forces")
    return out


def write() -> None:
    FOLDER.mkdir(parents=True, exist_ok=True)
    for path in exercises():
        target = FOLDER / f"{path.stem}.json"
        target.write_text(json.dumps(record(path), ensure_ascii=False, indent=0,
                                     allow_nan=False) + "\n", encoding="utf-8")
        print(f"wrote {target.relative_to(ROOT)}")


# -- comparison ----------------------------------------------------------------------------------
#: sections a report may have gained since (what a book prints, compared with the exact)
ADDED_SECTIONS = {"published"}

#: Aliyev's constants that are products of drawing scales
SCALE_PRODUCTS = {"J_mu_a_over_l", "m_mu_a_mu_l"}


def _scale_dependent(key: str, where: str) -> bool:
    """A value that depends on the drawing scale alone (see the module docstring)."""
    return (key.endswith("_mm") or key.startswith("mu_") or key == "scale"
            or key in SCALE_PRODUCTS or (key == "text" and ".steps[" in where))


def _scale(siblings) -> float:
    values = [abs(v) for v in siblings if isinstance(v, (int, float)) and not isinstance(v, bool)]
    return max(values, default=0.0)


def _deep_scale(value) -> float:
    """The largest magnitude of any number in ``value`` (nested)."""
    if isinstance(value, dict):
        return max((_deep_scale(v) for v in value.values()), default=0.0)
    if isinstance(value, list):
        return max((_deep_scale(v) for v in value), default=0.0)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return abs(value)
    return 0.0


def _without_added_columns(header: list[str], table: dict) -> dict:
    """``table`` (a sweep: header and rows) without the columns it gained, by ADDED_COLUMNS."""
    keep = [index for index, name in enumerate(table["header"])
            if name in header or not name.startswith(ADDED_COLUMNS)]
    return {**table, "header": [table["header"][index] for index in keep],
            "rows": [[row[index] for index in keep] for row in table["rows"]]}


def differences(old, new, where: str = "", siblings=(), reference: float | None = None
                ) -> list[str]:
    """Where ``new`` differs from ``old`` beyond the rules of the module docstring."""
    if isinstance(old, dict) and isinstance(new, dict):
        if {"header", "rows"} <= set(old) and {"header", "rows"} <= set(new):
            new = _without_added_columns(old["header"], new)
        out = []
        changed = set(old) ^ set(new)
        if where.startswith(".reports.") and where.count(".") <= 3:   # a report itself
            changed -= ADDED_SECTIONS - set(old)    # a report may gain these sections
        if changed:
            out.append(f"{where}: keys {sorted(changed)} added or missing")
        measured = None
        if "analytic" in old and isinstance(old["analytic"], (int, float)):
            measured = abs(old["analytic"])
        siblings = [v for v in old.values() if not isinstance(v, (dict, list))]
        for key in sorted(set(old) & set(new)):
            if _scale_dependent(key, where):
                continue
            ref = None
            if key in RELATIVE_NOISE:
                ref = 1.0
            elif key in NOISE:
                ref = measured if measured is not None else _deep_scale(old)
            if key in LINE_ANGLES and isinstance(old[key], float) and isinstance(
                    new[key], float):
                a, b = (math.sin(math.radians(v)) for v in (old[key], new[key]))
                if abs(a - b) > RELATIVE:
                    out.append(f"{where}.{key}: {old[key]!r} before, {new[key]!r} now")
                continue
            out += differences(old[key], new[key], f"{where}.{key}", siblings, ref)
        return out
    if isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            return [f"{where}: {len(old)} entries before, {len(new)} now"]
        out = []
        for index, (a, b) in enumerate(zip(old, new, strict=True)):
            out += differences(a, b, f"{where}[{index}]", old, reference)
        return out
    if isinstance(old, (int, float)) and isinstance(new, (int, float)) and not isinstance(
            old, bool):
        if reference is not None:
            tolerance = RELATIVE * max(reference, 1e-300)
        else:
            tolerance = RELATIVE * max(abs(old), abs(new), _scale(siblings))
        if not math.isclose(old, new, rel_tol=0.0, abs_tol=tolerance) and old != new:
            return [f"{where}: {old!r} before, {new!r} now"]
        return []
    if isinstance(old, str) and isinstance(new, str):
        if old == new or ("seed" in old.lower() and where.endswith(("title", ".name"))):
            return []
        return [f"{where}: {old!r} before, {new!r} now"]
    if old != new:
        return [f"{where}: {old!r} before, {new!r} now"]
    return []


if __name__ == "__main__":
    write()
