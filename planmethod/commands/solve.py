"""``planmethod solve FILE``: structure, scales, plans and a check table at one crank angle."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", help="exercise file (TOML)")
    parser.add_argument("--angle", type=float, metavar="DEG",
                        help="crank angle in degrees (default: drive.angle of the file); "
                             "the assembly chosen at drive.angle is followed there, as a "
                             "sweep follows it")
    parser.add_argument("--svg", metavar="DIR",
                        help="write the drawings into DIR as SVG: the position, velocity, "
                             "acceleration and lever plans (and the force drawings with "
                             "forces)")
    parser.add_argument("--json", action="store_true", help="print the JSON report")
    parser.add_argument("--precision", type=float, metavar="MM",
                        help="drafting precision in mm (overrides [plan] precision_mm)")
    parser.add_argument("--png", action="store_true",
                        help="with --svg, also write PNG renderings (needs cairosvg)")


def _format(value: float | None, digits: int = 6) -> str:
    if value is None:
        return "—"
    return f"{value:.{digits}g}"


def text_report(analysis) -> str:
    """The report a course prints: structure, scales, check table, flags — every quantity,
    link and force in the course's notation (docs/notation.md: ω₂, v_B₃, R₀₁; the crank's
    φ and ω by its number), never a report name (those are the JSON report's)."""
    from ..numbering import course_numbers
    from ..render.plan_words import scale_lines
    from ..structure import describe
    from ..vocabulary import numbered, shown_title, symbol
    from ..words import render

    exercise, motion = analysis.exercise, analysis.motion
    numbers = course_numbers(exercise.mechanism)
    crank = numbers[exercise.mechanism.drive.link]
    lines = [f"{shown_title(exercise.mechanism.title)} — crank angle {numbered('φ', crank)} = "
             f"{analysis.angle:g}°", "", "Structural analysis"]
    lines += ["  " + line for line in describe(analysis.structure, numbers).splitlines()]
    for index, branch in sorted(motion.branches.items()):
        analysis.structure.groups[index]
        lines.append(f"  group {index + 1} assembly: branch {branch.sign:+d} ({branch.reason})")
    if analysis.plans:
        lines += ["", "Scales"] + ["  " + render(line)
                                   for line in scale_lines(analysis.plans.scales)]
        precision = analysis.plans.velocity.precision_mm
        lines.append(f"  drafting precision: {precision:g} mm" if precision else
                     "  drafting precision: exact construction")
    shown = {check.quantity: symbol(check.quantity, numbers) for check in analysis.checks}
    width = max([len(text) for text in shown.values()] + [8])
    lines += ["", f"  {'quantity':<{width}} {'plan':>12}  {'exact':>12}  {'abs. error':>10}   "
                  f"{'rel. error':>10}  unit"]
    for check in analysis.checks:
        rel = "—" if check.rel_error is None else f"{check.rel_error:.2e}"
        lines.append(f"  {shown[check.quantity]:<{width}} {_format(check.plan):>12}  "
                     f"{_format(check.analytic):>12}  {_format(check.abs_error, 3):>10}   "
                     f"{rel:>10}  {check.unit}")
    if exercise.published:
        from ..report import published_comparison

        source = exercise.published_source or "the book"
        lines += ["", f"Published values ({source}) against the exact ones (magnitudes)",
                  f"  {'quantity':<22}{'published':>12}{'exact':>14}{'difference':>12}"]
        for row in published_comparison(analysis):
            exact = "—" if row["exact"] is None else f"{row['exact']:.6g}"
            off = ("—" if row["difference_percent"] is None
                   else f"{row['difference_percent']:+.1f} %")
            slip = "   likely a slip (> 5 %)" if row["likely_slip"] else ""
            lines.append(f"  {symbol(row['quantity'], numbers):<22}{row['published']:>12.6g}"
                         f"{exact:>14}"
                         f"{off:>12}{slip}")
    if analysis.flags:
        lines += ["", "Flags"] + [f"  ! {flag}" for flag in analysis.flags]
    if analysis.forces is not None:
        from ..render.notation import ForceNotation

        lines += ["", analysis.forces.describe(ForceNotation(analysis.forces.solution))]
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    from ..errors import PlanmethodError, SpecError
    from ..io import output_set
    from ..report import analyse, report_dict
    from ..spec import MAX_ANGLE_DEG, load_exercise

    if args.precision is not None and not args.precision >= 0:
        raise SpecError(f"--precision must be a non-negative number of mm, got {args.precision}")
    if args.angle is not None and not (math.isfinite(args.angle)
                                       and abs(args.angle) <= MAX_ANGLE_DEG):
        raise SpecError(f"must be a finite number of degrees within ±{MAX_ANGLE_DEG:g}°, got "
                        f"{args.angle:g}", key="option --angle")
    exercise = load_exercise(args.file)
    analysis = analyse(exercise, args.angle, precision_mm=args.precision)
    files: dict[str, str] = {}
    if args.svg:
        from ..render.figures import plan_files

        files = plan_files(analysis.plans, forces=analysis.forces)
    pngs: dict[str, bytes] = {}
    if args.svg and args.png:
        try:
            import cairosvg
        except ImportError:
            raise PlanmethodError("--png needs cairosvg: pip install 'planmethod[png]'") from None
        pngs = {Path(name).with_suffix(".png").name: cairosvg.svg2png(
            bytestring=text.encode("utf-8"), output_width=1200) for name, text in files.items()}
    written: list[str] = []
    if args.svg:  # everything is computed: now write, every drawing or none
        with output_set() as outputs:
            written = [str(path) for path in outputs.files(args.svg, {**files, **pngs})]
    if args.json:
        json.dump(report_dict(analysis), sys.stdout, ensure_ascii=False, indent=2,
                  allow_nan=False)
        print()
    else:
        print(text_report(analysis))
        if written:
            print("\nWrote " + ", ".join(written))
        if args.svg and analysis.forces is not None:
            from ..render.force_svg import combined_omitted

            why = combined_omitted(analysis.forces, analysis.plans)
            if why:
                print(why)
    return 0
