"""Helpers the browser tests share: axe-core, the automated accessibility check, run on a page.

axe-core is a JavaScript file; the test extra installs it inside the ``axe-playwright-python``
package (which bundles ``axe.min.js``). It is looked for at ``$PLANMETHOD_AXE`` (a path to
``axe.min.js``), in that package, in the project's ``node_modules``, then in npm's global folder
(``npm install --global axe-core@4``). Where it is not found, a test that calls :func:`run_axe`
is skipped with the reason — never fetched at test time.
"""

from __future__ import annotations

import functools
import importlib.util
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: the impacts a page must not have (axe's four: minor, moderate, serious, critical)
BLOCKING = ("serious", "critical")


@functools.cache
def axe_script() -> str | None:
    """The text of ``axe.min.js``, or None where axe-core is not installed."""
    bundled = importlib.util.find_spec("axe_playwright_python")
    places = [os.environ.get("PLANMETHOD_AXE", ""),
              *[str(Path(folder) / "axe.min.js")
                for folder in (bundled.submodule_search_locations or [] if bundled else [])],
              str(ROOT / "node_modules" / "axe-core" / "axe.min.js")]
    npm = shutil.which("npm")
    if npm:
        try:
            found = subprocess.run([npm, "root", "--global"], capture_output=True, text=True,
                                   timeout=30, check=False).stdout.strip()
        except (OSError, subprocess.SubprocessError):
            found = ""
        if found:
            places.append(str(Path(found) / "axe-core" / "axe.min.js"))
    for place in places:
        if place and Path(place).is_file():
            return Path(place).read_text(encoding="utf-8")
    return None


def run_axe(page, *, impacts: tuple[str, ...] = BLOCKING) -> list[dict]:
    """axe-core's violations on ``page`` (a Playwright page) whose impact is one of
    ``impacts`` (default: serious or critical), each as axe gives it (``id``, ``impact``,
    ``help``, ``nodes`` …). Skips the calling test where axe-core is not installed."""
    script = axe_script()
    if script is None:
        pytest.skip("axe-core is not installed (pip install axe-playwright-python, the test "
                    "extra's, or set PLANMETHOD_AXE to axe.min.js)")
    page.add_script_tag(content=script)
    results = page.evaluate("""async () => {
        const found = await axe.run(document, {resultTypes: ["violations"]});
        return found.violations;
    }""")
    return [violation for violation in results if violation.get("impact") in impacts]


def violations_text(violations: list[dict]) -> str:
    """The violations as lines a person reads in a failed assertion: rule, impact, where."""
    return "\n".join(f"{v['id']} ({v['impact']}): {v['help']} — "
                     f"{', '.join(str(node['target']) for node in v['nodes'][:5])}"
                     for v in violations)


#: subscript digits as plain digits (a subscript's digits are set plain inside its <sub>)
_PLAIN = str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789")


def flat(text: str) -> str:
    """A sentence as a page with its symbols' subscripts set reads as plain text: no
    underscore, digits plain (v_B₃ → vB3: v with B3 set below), so that the page's text can
    be compared with ``grade``'s (which keeps v_C)."""
    return text.replace("_", "").translate(_PLAIN)


def sheet_point(page, plan: str, x: float, y: float) -> tuple[float, float]:
    """The viewport point of the plan point (x, y) mm (y up) of the workbook's drawing sheet
    of ``plan``: at user coordinates (x, −y), scrolled into the middle of the window first."""
    return tuple(page.eval_on_selector(f'svg[data-draw="{plan}"]', """(svg, [x, y]) => {
        const mark = document.createElementNS(svg.namespaceURI, "circle");
        mark.setAttribute("cx", x); mark.setAttribute("cy", y); mark.setAttribute("r", 0.01);
        svg.appendChild(mark);
        mark.scrollIntoView({block: "center", inline: "center"});
        const box = mark.getBoundingClientRect();
        mark.remove();
        return [box.x + box.width / 2, box.y + box.height / 2];
    }""", [x, -y]))


def move_slider(page, angle: float) -> None:
    """Move the workbook's crank-angle slider to ``angle`` as a hand does (an input event)."""
    page.eval_on_selector("#angle", """(slider, angle) => {
        slider.value = angle;
        slider.dispatchEvent(new Event("input", {bubbles: true}));
    }""", angle)


def start_drawing(page, angle: float) -> None:
    """The workbook at ``angle`` in drawing mode."""
    move_slider(page, angle)
    page.check("#draw-mode")
