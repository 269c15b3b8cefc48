"""What speaking the course's language costs (``python -m benchmarks.run --only language``).

Every sentence, label and number a user reads is rendered in one place
(:func:`planmethod.words.render`): in English the template is filled as it is; in Russian it
is first looked up in the gettext catalogue (a plural's form chosen by its count) and its
numbers are written with a decimal comma. Issue 38's target: translation costs at most 5 % of
``solve --svg`` and of a workbook's frames.

Timed here, in one process, three ways taken in turn, round after round (the order rotated
each round, so that the shared machine's load and a warm cache touch all three alike):

* *untranslated* — the baseline: render with no catalogue at all (the English template
  filled, no catalogue asked for, a decimal point written without asking the language);
* *English* — render as it runs by default (``--lang en``);
* *Russian* — render in Russian (``--lang ru``): a catalogue lookup per message, decimal
  commas.

The work timed: ``solve --svg``'s computing — read the exercise, solve at its angle, every
figure as SVG text and the printed report (the files' writing left out, which only adds the
same time to all three) — for the compressor slider-crank (plans), the four-bar with forces
(plans, force polygons, Zhukovsky's lever) and the six-link conveyor (a class III triad); and
a workbook's frames (:func:`planmethod.application.workbook.solve_frames`: analysis, the
frame's drawings, steps, key and drawing data) of the compressor and the conveyor at several
angles in one call. Each figure is the median, over the rounds, of that round's time over the
untranslated time of the same round, in CPU time of this thread (the work is single-threaded;
wall time on a shared machine also counts other processes' turns; a garbage collection is
made before each call, timeit's way); wall-time medians are kept in the JSON. One Russian run
of each task also counts its messages rendered and catalogue lookups made; those messages are
then rendered alone in each mode (the translation's own cost); and one run in each mode
counts its Python function calls (the work it does, which the machine's load does not blur:
the verdict is judged on these two, the whole runs' ratios are reported beside them).

Examples
--------
>>> sorted(MODES), TARGET
(['en', 'ru', 'untranslated'], 0.05)
"""

from __future__ import annotations

import contextlib
import gc
import importlib
import statistics
import sys
import time
from collections.abc import Callable, Iterator

from planmethod.application.solving import figures, report_text, solve_at
from planmethod.application.workbook import exercise_variant, solve_frames
from planmethod.render.steady import steady_views
from planmethod.spec import load_exercise
from planmethod.words import speaking

from .common import ROOT, load_factor, load_sentence, run_load

#: the module that renders (the package's ``render`` is its function of that name)
rendering = importlib.import_module("planmethod.words.render")

#: the ways text is made: no catalogue (the baseline), English, Russian
MODES = ("untranslated", "en", "ru")
#: issue 38: translation costs at most this share of the work
TARGET = 0.05
#: what ``solve --svg`` is timed on
SOLVE = {"compressor": "exercises/compressor_slider_crank.toml",
         "four-bar forces": "exercises/fourbar_forces.toml",
         "conveyor": "exercises/conveyor_sixbar.toml"}
#: whose workbook frames are timed, and at how many angles in one call
FRAMES = {"compressor": "exercises/compressor_slider_crank.toml",
          "conveyor": "exercises/conveyor_sixbar.toml"}


@contextlib.contextmanager
def untranslated() -> Iterator[None]:
    """Render with no catalogue: each message's English template filled, no catalogue asked
    for, numbers written with a decimal point without asking the language (the baseline)."""
    saved = rendering._translated, rendering._speaker
    plain = (None, rendering._Formatter("en", "."))
    rendering._translated = lambda text, translations, language: rendering._english(text)
    rendering._speaker = lambda language: plain
    try:
        with speaking("en"):
            yield
    finally:
        rendering._translated, rendering._speaker = saved


def _spoken(mode: str) -> contextlib.AbstractContextManager:
    return untranslated() if mode == "untranslated" else speaking(mode)


def solve_svg(path: str) -> Callable[[], object]:
    """``solve FILE --svg``'s computing: the exercise read, solved, drawn and reported."""
    def work() -> object:
        exercise = load_exercise(ROOT / path)
        analysis = solve_at(exercise, None)
        return figures(analysis), report_text(analysis)
    return work


def workbook_frames(path: str, count: int) -> Callable[[], object]:
    """A workbook's frames at ``count`` angles over the turn, in one call."""
    exercise = load_exercise(ROOT / path)
    angles = [exercise.mechanism.drive.angle + 360.0 * index / count for index in range(count)]
    views = steady_views(exercise, angles)
    variant = exercise_variant(exercise)
    return lambda: solve_frames(exercise, angles, views, variant)


class _Counting:
    """A catalogue that counts the lookups made of it."""

    def __init__(self, translations, counts: dict[str, int]) -> None:
        self.translations, self.counts = translations, counts

    def __getattr__(self, name: str):
        found = getattr(self.translations, name)
        if not name.endswith("gettext"):
            return found

        def lookup(*arguments):
            self.counts["lookups"] += 1
            return found(*arguments)
        return lookup


def counted(work: Callable[[], object]) -> tuple[dict[str, int], list]:
    """One Russian run of ``work``: the messages it renders and the catalogue lookups made
    for them (the language's decimal sign is looked up once, with its catalogue), and the
    messages themselves (a message rendered inside another one too)."""
    counts = {"messages": 0, "lookups": 0}
    texts = []
    translated, speaker = rendering._translated, rendering._speaker

    def counting_translated(text, translations, language):
        counts["messages"] += 1
        texts.append(text)
        return translated(text, translations, language)

    def counting_speaker(language):
        translations, formatter = speaker(language)
        return _Counting(translations, counts), formatter

    rendering._translated, rendering._speaker = counting_translated, counting_speaker
    try:
        with speaking("ru"):
            work()
    finally:
        rendering._translated, rendering._speaker = translated, speaker
    return counts, texts


def rendering_time(texts: list, rounds: int) -> dict[str, float]:
    """The CPU time (ms) of rendering ``texts`` once each, in each mode (medians of
    ``rounds``, the modes in turn): a message rendered inside another is counted again on
    its own, so that this is an upper bound of what rendering a run's text costs."""
    times: dict[str, list[float]] = {mode: [] for mode in MODES}
    for _ in range(rounds):
        for mode in MODES:
            with _spoken(mode):
                start = time.thread_time()
                for text in texts:
                    rendering.render(text)
                times[mode].append(1000 * (time.thread_time() - start))
    return {mode: statistics.median(spent) for mode, spent in times.items()}


def calls(work: Callable[[], object]) -> dict[str, int]:
    """The Python function calls one run of ``work`` makes in each mode (after a warm run):
    the work a run does, whatever the shared machine's load."""
    out = {}
    for mode in MODES:
        count = [0]

        def profile(frame, event, argument, count=count) -> None:
            if event == "call":
                count[0] += 1

        with _spoken(mode):
            work()
            sys.setprofile(profile)
            try:
                work()
            finally:
                sys.setprofile(None)
        out[mode] = count[0]
    return out


def interleaved(work: Callable[[], object], rounds: int) -> dict:
    """``work`` in each mode, one call of each per round, the order rotated each round: per
    mode the median CPU and wall times (ms), and per language the median of its rounds'
    ratios to the untranslated time (CPU)."""
    for mode in MODES:                    # warm: caches, catalogues, compiled programs
        with _spoken(mode):
            work()
    cpu: dict[str, list[float]] = {mode: [] for mode in MODES}
    wall: dict[str, list[float]] = {mode: [] for mode in MODES}
    for round_ in range(rounds):
        order = MODES[round_ % 3:] + MODES[:round_ % 3]
        for mode in order:
            gc.collect()                  # a collection falls in no mode's time (timeit's way)
            gc.disable()
            try:
                with _spoken(mode):
                    start, start_cpu = time.perf_counter(), time.thread_time()
                    work()
                    cpu[mode].append(1000 * (time.thread_time() - start_cpu))
                    wall[mode].append(1000 * (time.perf_counter() - start))
            finally:
                gc.enable()
    ratios = {mode: statistics.median(ours / base for ours, base in
                                      zip(cpu[mode], cpu["untranslated"], strict=True))
              for mode in MODES if mode != "untranslated"}
    return {"cpu_ms": {mode: statistics.median(times) for mode, times in cpu.items()},
            "wall_ms": {mode: statistics.median(times) for mode, times in wall.items()},
            "ratio": ratios}


def run(quick: bool = False) -> dict:
    rounds, count = (5, 4) if quick else (31, 12)
    before = load_factor()
    tasks = {f"solve --svg: {name}": solve_svg(path) for name, path in SOLVE.items()}
    tasks |= {f"workbook frames: {name} ({count} angles)": workbook_frames(path, count)
              for name, path in FRAMES.items()}
    results = {}
    for name, work in tasks.items():
        counts, texts = counted(work)
        results[name] = interleaved(work, rounds) | {"counts": counts}
        spent = rendering_time(texts, 3 * rounds)
        results[name]["render_ms"] = spent
        results[name]["render_cost"] = ((spent["ru"] - spent["untranslated"])
                                        / results[name]["cpu_ms"]["untranslated"])
        results[name]["calls"] = calls(work)
    load = run_load(before, load_factor())
    worst = max(result["ratio"]["ru"] for result in results.values()) - 1.0
    worst_render = max(result["render_cost"] for result in results.values())
    worst_calls = max(result["calls"]["ru"] / result["calls"]["untranslated"]
                      for result in results.values()) - 1.0
    return {"rounds": rounds, "tasks": results, "worst_cost": worst,
            "worst_render_cost": worst_render, "worst_calls": worst_calls, "target": TARGET,
            "met": max(worst_render, worst_calls) <= TARGET, "load": load}


def table(result: dict) -> str:
    lines = [f"Whole runs: text in each language against text with no catalogue (medians of "
             f"{result['rounds']} rounds, the three in turn; CPU time of the thread, ms; ×: the "
             "median of the rounds' ratios to the untranslated time). *Rendering*: the "
             "messages of one run rendered alone, untranslated / Russian (ms), and what "
             "Russian adds as a share of the whole untranslated run. *Calls*: the Python "
             "function calls of one run, Russian over untranslated.", "",
             "| work | untranslated ms | English ms (×) | Russian ms (×) | messages / "
             "catalogue lookups (Russian) | rendering ms | Russian adds | calls × |",
             "|---|---|---|---|---|---|---|---|"]
    for name, task in result["tasks"].items():
        cpu, ratio, counts, spent = (task["cpu_ms"], task["ratio"], task["counts"],
                                     task["render_ms"])
        lines.append(f"| {name} | {cpu['untranslated']:.1f} | {cpu['en']:.1f} "
                     f"({ratio['en']:.3f}) | {cpu['ru']:.1f} ({ratio['ru']:.3f}) | "
                     f"{counts['messages']} / {counts['lookups']} | "
                     f"{spent['untranslated']:.2f} / {spent['ru']:.2f} | "
                     f"{100 * task['render_cost']:+.2f} % | "
                     f"{task['calls']['ru'] / task['calls']['untranslated']:.3f} |")
    verdict = "met" if result["met"] else "not met"
    spread = [task["ratio"]["en"] for task in result["tasks"].values()]
    lines += ["", f"Target (issue 38): translation costs ≤ {100 * result['target']:g} % of "
              f"`solve --svg` and of a workbook's frames — **{verdict}**, judged on the work "
              "a Russian run adds, which this shared machine's load does not blur: rendering "
              f"its messages in Russian adds at most {100 * result['worst_render_cost']:+.2f} % "
              "of the run (one catalogue lookup per message, decimal commas), and the whole "
              "Russian run — its longer labels laid out too — makes at most "
              f"{100 * result['worst_calls']:+.1f} % more Python calls than the untranslated "
              "one. The whole runs' time ratios are as precise as the load lets them be: "
              f"English, which does the baseline's work, measured {min(spread):.3f}–"
              f"{max(spread):.3f} (Russian at most "
              f"{100 * result['worst_cost']:+.1f} %).", "", load_sentence(result["load"])]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(table(run(quick=True)))
