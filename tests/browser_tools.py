"""What browser tests share: an accessibility check of a page with axe-core.

A minimal copy in the studio's branch (engineer "workbook" writes the full module; the lead
keeps theirs): :func:`run_axe` injects axe-core into a Playwright page and returns its
violations; without axe-core the calling test is skipped with the way to get it.

axe-core is looked for at ``$PLANMETHOD_AXE`` (the path of ``axe.min.js``), then at
``~/.cache/planmethod/axe-core/axe.min.js`` — put there with::

    npm pack axe-core --pack-destination /tmp && mkdir -p ~/.cache/planmethod/axe-core &&
    tar -xzf /tmp/axe-core-*.tgz -C ~/.cache/planmethod/axe-core --strip-components=1
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest


def axe_path() -> Path | None:
    """Where axe-core's ``axe.min.js`` is, or None."""
    chosen = os.environ.get("PLANMETHOD_AXE")
    for path in ([Path(chosen)] if chosen else []) + [
            Path.home() / ".cache" / "planmethod" / "axe-core" / "axe.min.js"]:
        if path.is_file():
            return path
    return None


def run_axe(page) -> list[dict]:
    """axe-core's violations on ``page`` (each ``{"id", "impact", "help", "nodes"}``), or skip
    the test where axe-core is absent. The page's context must bypass its content security
    policy (axe is injected as a script of the test's)."""
    path = axe_path()
    if path is None:
        pytest.skip("axe-core is absent: npm pack axe-core (see tests/browser_tools.py)")
    page.add_script_tag(content=path.read_text(encoding="utf-8"))
    result = page.evaluate("() => axe.run(document, {resultTypes: ['violations']})")
    return [{"id": v["id"], "impact": v["impact"], "help": v["help"],
             "nodes": [" ".join(node["target"]) if isinstance(node["target"], list)
                       else str(node["target"]) for node in v["nodes"]]}
            for v in result["violations"]]
