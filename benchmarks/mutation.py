"""The mutation-testing report: ``python -m benchmarks.mutation [--root DIR]``.

Reads what ``mutmut run`` found — ``mutants/**/*.py.meta`` under ``--root`` (default: the
repository), each mutant's exit code as mutmut 3 keeps it — and writes
``benchmarks/results/mutation.{md,json}``: when, on which machine and with which mutmut, what
was mutated, the mutants counted by outcome per module and in all, the share that survived,
and every survivor with the note of ``benchmarks/mutation_notes.toml`` that says why it is
equivalent to the code; survivors without a note are counted by function as not yet looked
at (their names go to the JSON).

``--recorded`` reads a run's outcomes again from its committed JSON report (the counts per
module and the survivors' names) when the ``mutants`` folder it ran in is gone, and applies
the notes as they are now: a survivor killed since by a new test is counted so.

``--baseline`` records the survivors of a first run in ``results/mutation_baseline.json``;
later reports list, for each of them killed since, the test added for it (the notes'
``[killed_by]`` table). The counts are read, never typed.

Examples
--------
>>> outcome(1), outcome(2), outcome(0), outcome(36), outcome(-24), outcome(None)
('killed', 'killed', 'survived', 'timeout', 'timeout', 'not checked')
>>> note_for("pkg.mod.x_f__mutmut_3", {"pkg.mod.x_f__mutmut_*": "why"})
'why'
>>> module_of("planmethod.grading.keys.x__mistakes__mutmut_12"), function_of(
...     "planmethod.grading.keys.xǁGradingSettingsǁ__init____mutmut_2")
('planmethod.grading.keys', 'GradingSettings.__init__')
"""

from __future__ import annotations

import argparse
import fnmatch
import json
import math
import sys
import tomllib
from collections import Counter
from pathlib import Path

from .common import RESULTS, ROOT, machine, write_json, write_text, written_by

#: notes on survivors: why each is equivalent, and which test kills those killed since
NOTES = Path(__file__).resolve().parent / "mutation_notes.toml"
#: the command that produced the results, by default (the report says it; ``--command``)
COMMAND = "mutmut run --max-children 2"
#: mutmut 3's exit codes (``mutmut.stats.status_by_exit_code``); any other is suspicious.
#: pytest's 2, which mutmut calls "interrupted", is a test module that failed to be collected:
#: with a mutant, one that computes with the package as it is collected (tests/test_convert.py
#: drafts its exercises then) broke on it — the mutant is noticed, as by a failing test
OUTCOMES = {1: "killed", 3: "killed", 0: "survived", 5: "no tests", 33: "no tests",
            2: "killed", None: "not checked", 34: "skipped", 35: "suspicious",
            36: "timeout", 37: "caught by type check", -24: "timeout", 24: "timeout",
            152: "timeout", 255: "timeout", -11: "segfault", -9: "segfault"}
#: the outcomes counted in the report's table, in its order
COLUMNS = ("killed", "survived", "timeout", "suspicious", "skipped", "no tests",
           "not checked")
#: the outcomes of mutants whose tests did not run: not counted among those run
NOT_RUN = ("not checked", "skipped", "no tests")


def outcome(exit_code: int | None) -> str:
    """What an exit code of a mutant's test run means."""
    return OUTCOMES.get(exit_code, "suspicious")


def module_of(mutant: str) -> str:
    """The module a mutant is in (its name without the mangled function)."""
    return mutant.rpartition(".")[0]


def function_of(mutant: str) -> str:
    """The function a mutant changes: ``f`` or ``Class.method``."""
    mangled = mutant.rpartition(".")[2].rpartition("__mutmut_")[0]
    if mangled.startswith("xǁ"):
        return ".".join(mangled[2:].split("ǁ", 1))
    return mangled.removeprefix("x_")


def note_for(mutant: str, notes: dict[str, str]) -> str | None:
    """The note whose name or glob pattern matches ``mutant`` (the first one), else None."""
    if mutant in notes:
        return notes[mutant]
    return next((text for pattern, text in notes.items()
                 if fnmatch.fnmatchcase(mutant, pattern)), None)


def read_results(root: Path) -> dict[str, int | None]:
    """Every mutant's exit code: mutant name → exit code (None: not yet run)."""
    found: dict[str, int | None] = {}
    for meta in sorted((root / "mutants").rglob("*.py.meta")):
        found.update(json.loads(meta.read_text(encoding="utf-8"))["exit_code_by_key"])
    return found


def sample(names: list[str], count: int, seed: int) -> list[str]:
    """A uniform random sample of ``count`` of the mutants ``names`` (all of them if fewer),
    drawn with ``seed`` from their sorted list, in that order: a run of them estimates the
    share that would survive a run of all.

    >>> sample(["m.x_f__mutmut_1", "m.x_f__mutmut_2", "m.x_g__mutmut_1"], 2, seed=1)
    ['m.x_f__mutmut_1', 'm.x_g__mutmut_1']

    The draws of one seed grow: a smaller sample is part of a larger one.

    >>> names = [f"m.x_f__mutmut_{number}" for number in range(1, 20000)]
    >>> set(sample(names, 160, seed=7)) <= set(sample(names, 500, seed=7))
    True
    """
    import random

    chosen = random.Random(seed).sample(sorted(names), min(count, len(names)))
    return sorted(chosen)


def _mutated(root: Path) -> list[str]:
    data = tomllib.loads((root / "pyproject.toml").read_text(encoding="utf-8"))
    return list(data["tool"]["mutmut"].get("only_mutate", []))


def _table(by_module: dict[str, Counter]) -> list[str]:
    lines = ["| module | mutants | " + " | ".join(COLUMNS) + " | survived % |",
             "| --- | ---: | " + " | ".join("---:" for _ in COLUMNS) + " | ---: |"]
    total: Counter = Counter()
    for module, counts in sorted(by_module.items()):
        total.update(counts)
        lines.append(_row(f"`{module}`", counts))
    lines.append(_row("**all**", total))
    return lines


def ran(counts: Counter) -> int:
    """How many of the mutants counted had their tests run.

    >>> ran(Counter({"killed": 3, "survived": 1, "not checked": 9}))
    4
    """
    return sum(counts[c] for c in COLUMNS if c not in NOT_RUN)


def _row(name: str, counts: Counter) -> str:
    run = ran(counts)
    share = f"{100 * counts['survived'] / run:.1f}" if run else "–"
    return (f"| {name} | {sum(counts.values())} | "
            + " | ".join(str(counts[c]) for c in COLUMNS) + f" | {share} |")


def wilson(survived: int, run: int, z: float = 1.96) -> tuple[float, float]:
    """The 95 % (Wilson score) interval of the share that survives, from ``survived`` of a
    random sample of ``run`` mutants.

    >>> [round(bound, 4) for bound in wilson(5, 200)]
    [0.0107, 0.0572]
    """
    if not run:
        return 0.0, 1.0
    share = survived / run
    middle = (share + z * z / (2 * run)) / (1 + z * z / run)
    half = z * math.sqrt(share * (1 - share) / run + z * z / (4 * run * run)) / (1 + z * z / run)
    return max(0.0, middle - half), min(1.0, middle + half)


def report(root: Path, *, baseline: bool = False, command: str = COMMAND,
           name: str = "mutation", sampled: bool = False,
           recorded: dict | None = None) -> tuple[str, dict]:
    """The report's Markdown and JSON from the results under ``root`` or, ``recorded``, from
    the JSON report of a run whose ``mutants`` folder is gone (its counts per module and its
    survivors, read again with today's notes).

    Raises
    ------
    SystemExit
        If there are no results to read, or a recorded report has a first run to compare
        with (which of its survivors were killed is not recorded).
    """
    notes = tomllib.loads(NOTES.read_text(encoding="utf-8"))
    equivalent, killed_by = notes.get("equivalent", {}), notes.get("killed_by", {})
    first_run = f"{name}_baseline.json"
    results: dict[str, int | None] = {}
    if recorded is None:
        import mutmut

        results = read_results(root)
        if not results:
            raise SystemExit(f"no mutmut results under {root / 'mutants'}: run `{command}` "
                             "first")
        by_module: dict[str, Counter] = {}
        for mutant, code in results.items():
            by_module.setdefault(module_of(mutant), Counter())[outcome(code)] += 1
        survivors = sorted(m for m, code in results.items() if outcome(code) == "survived")
        mutated, about, reread = _mutated(root), machine(), ""
        version = mutmut.__version__
    else:
        if baseline or (RESULTS / first_run).exists():
            raise SystemExit(f"{name}.json: a recorded report cannot be compared with a first "
                             "run (which of its survivors were killed is not recorded)")
        by_module = {module: Counter(counts) for module, counts in recorded["by_module"].items()}
        survivors = sorted(recorded["survivors"])
        mutated, about, command = recorded["mutated"], recorded["machine"], recorded["command"]
        version = recorded["mutmut"]
        reread = machine()["time"]
    if baseline:
        write_json(first_run, {"survived": survivors})
    first = json.loads((RESULTS / first_run).read_text()).get("survived", []) \
        if (RESULTS / first_run).exists() else []
    # survivors of this run that a test added since kills, each checked by running the
    # mutant by name in a fresh process against that test (the notes' [killed_by])
    by_name = [m for m in survivors if note_for(m, equivalent) is None
               and note_for(m, killed_by) is not None and m not in first]
    missing = [m for m in survivors if note_for(m, equivalent) is None and m not in by_name]
    total: Counter = sum(by_module.values(), Counter())
    mutants = sum(total.values())
    run = ran(total)
    share = total["survived"] / run if run else 0.0
    left = total["survived"] - len(by_name)
    since = [m for m in first if results.get(m) is not None and outcome(results[m]) == "killed"]
    lines = [written_by("python -m benchmarks.mutation", about).strip(), "",
             f"From the results of `{command}` (mutmut {version}).", ""]
    if reread:
        lines += [f"Read again from this report's JSON (`--recorded`: the run's mutants folder "
                  f"is gone) on {reread}: the counts are the run's; the notes, and with "
                  "them which of its survivors a test added since kills, are that day's.", ""]
    lines += [f"Mutated: {', '.join(f'`{path}`' for path in mutated)} "
              f"({mutants} mutants); tests: `[tool.mutmut]` of pyproject.toml.", "",
             *_table(by_module), "",
             f"Survived: {total['survived']} of {run} run ({100 * share:.2f} %)."
             + (f" Killed since by a test added for it: {len(by_name)} (each mutant run by "
                "name in a fresh process, `MUTANT_UNDER_TEST=NAME python -m pytest "
                "tests/FILE`, fails that test). **Survive now: "
                f"{left} of {run} ({100 * left / run:.2f} %; the bound is 5 %)**, each "
                "listed below with why it is equivalent to the code or, marked *not "
                "killed*, why no test tells it apart yet." if by_name else
                " The bound is 5 %."), ""]
    if sampled:
        low, high = wilson(left, run)
        lines += [f"The mutants run are a random sample of all {mutants} (`--sample`: "
                  f"each equally likely; the other {total['not checked']} were not run), so "
                  f"the share that survives is an estimate of the whole's: 95 % interval "
                  f"(Wilson) {100 * low:.1f}–{100 * high:.1f} %.", ""]
    elif total["not checked"]:
        lines += [f"**Not yet run: {total['not checked']} mutants** (the run covered the "
                  "modules whose *not checked* column is 0).", ""]
    noted = [m for m in survivors if m not in missing and m not in by_name]
    if noted:
        lines += ["The survivors looked at, and why each is equivalent to the code:", "",
                  "| mutant | function | why it survives |", "| --- | --- | --- |"]
        lines += [f"| `{m.rpartition('.')[2]}` | `{module_of(m)}.{function_of(m)}` | "
                  f"{note_for(m, equivalent)} |" for m in noted]
        lines.append("")
    if missing:
        by_function = Counter(f"{module_of(m)}.{function_of(m)}" for m in missing)
        lines += [f"**Not yet looked at: {len(missing)} survivors** (each needs a test that "
                  f"kills it or a note in `{NOTES.name}`; their names are in "
                  f"`{name}.json`), by function:", "",
                  "| function | survivors |", "| --- | ---: |"]
        lines += [f"| `{name}` | {count} |" for name, count in sorted(
            by_function.items(), key=lambda item: (-item[1], item[0]))]
        lines.append("")
    if by_name:
        lines += [f"Killed since the run ({len(by_name)} of its survivors), by the tests "
                  "added for them:", "", "| mutant | function | killed by |",
                  "| --- | --- | --- |"]
        lines += [f"| `{m.rpartition('.')[2]}` | `{module_of(m)}.{function_of(m)}` | "
                  f"{note_for(m, killed_by)} |" for m in by_name]
        lines.append("")
    if since:
        tests: dict[str, list[str]] = {}
        for mutant in since:
            tests.setdefault(note_for(mutant, killed_by) or "a test added since", []).append(
                mutant)
        lines += [f"Killed since the first run ({len(since)} of its {len(first)} survivors), "
                  "by the tests added for them:", "", "| test | mutants |", "| --- | ---: |"]
        lines += [f"| {test} | {len(names)} |" for test, names in sorted(tests.items())]
        lines.append("")
    data = {"machine": about, "mutmut": version, "command": command,
            "mutated": mutated, "counts": {c: total[c] for c in COLUMNS},
            "run": run, "survived_share": share, "sampled": sampled,
            "interval_95": list(wilson(left, run)) if sampled else None,
            "killed_since_by_name": {m: note_for(m, killed_by) for m in by_name},
            "survive_now": left,
            "by_module": {m: dict(c) for m, c in sorted(by_module.items())},
            "survivors": {m: note_for(m, equivalent) for m in survivors},
            "not_looked_at": missing,
            "killed_since_first_run": len(since)}
    if reread:
        data["reread"] = reread
    return "\n".join(lines), data


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.mutation",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", type=Path, default=ROOT,
                        help="the folder mutmut ran in (default: the repository)")
    parser.add_argument("--baseline", action="store_true",
                        help="record the current survivors as the first run's")
    parser.add_argument("--command", default=COMMAND,
                        help="the mutmut command that was run (the report says it)")
    parser.add_argument("--name", default="mutation",
                        help="the report's file name, without .md / .json (default: mutation; "
                             "a run of other modules, in another folder, keeps its own)")
    parser.add_argument("--sampled", action="store_true",
                        help="the run was of a --sample: say so, with the interval of the "
                             "share that survives")
    parser.add_argument("--sample", type=int, metavar="N",
                        help="print N mutants drawn at random from those under --root (after "
                             "mutmut has generated them) for `mutmut run`, and stop")
    parser.add_argument("--seed", type=int, default=2026,
                        help="the seed of --sample's draw (default: 2026)")
    parser.add_argument("--recorded", action="store_true",
                        help="read the run's outcomes from the committed report's JSON (when "
                             "its mutants folder is gone) and apply today's notes to them")
    args = parser.parse_args(argv)
    if args.sample is not None:
        names = list(read_results(args.root))
        if not names:
            raise SystemExit(f"no mutants under {args.root / 'mutants'}: let `mutmut run` "
                             "generate them first")
        print("\n".join(sample(names, args.sample, args.seed)))
        return 0
    recorded = None
    if args.recorded:
        path = RESULTS / f"{args.name}.json"
        try:
            recorded = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as error:
            raise SystemExit(f"{path}: no recorded report to read again ({error})") from None
        missing = [key for key in ("by_module", "survivors", "mutated", "machine", "command",
                                   "mutmut") if key not in recorded]
        if missing:
            raise SystemExit(f"{path}: not a report to read again (no {', '.join(missing)})")
        args.sampled = bool(recorded.get("sampled"))
    text, data = report(args.root, baseline=args.baseline, command=args.command,
                        name=args.name, sampled=args.sampled, recorded=recorded)
    write_text(f"{args.name}.md", text + "\n")
    write_json(f"{args.name}.json", data)
    print(next(line for line in text.splitlines() if line.startswith("Survived:")),
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
