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


def text_report(analysis) -> str:
    """The report a course prints: structure, scales, check table, flags — every quantity,
    link and force in the course's notation (docs/notation.md: ω₂, v_B₃, R₀₁; the crank's
    φ and ω by its number), never a report name (those are the JSON report's)."""
    from ..numbering import course_numbers
    from ..render.report_text import check_lines, flag_lines, force_lines, published_lines
    from ..structure import describe
    from ..vocabulary import numbered, shown_title

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
        lines += ["", "Scales"] + ["  " + line for line in analysis.plans.scales.describe()]
        precision = analysis.plans.velocity.precision_mm
        lines.append(f"  drafting precision: {precision:g} mm" if precision else
                     "  drafting precision: exact construction")
    lines += check_lines(analysis)
    lines += published_lines(analysis)
    if analysis.flags:
        lines += ["", "Flags", *flag_lines(analysis.flags)]
    if analysis.forces is not None:
        lines += ["", *force_lines(analysis.forces)]
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
            from ..words import render

            why = combined_omitted(analysis.forces, analysis.plans)
            if why:
                print(render(why))
    return 0
