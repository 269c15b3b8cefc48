"""The browser the browser tests drive: Playwright's synchronous API and the system Chromium.

A test module calls :func:`require` at import time; where either is missing, the whole module
is skipped with the reason (CI installs both: .ci/run). Never ``playwright install``.
"""

from __future__ import annotations

import shutil
from collections.abc import Iterator

import pytest


def require():
    """(``playwright.sync_api``, the path of Chromium), or skip the calling module."""
    sync_api = pytest.importorskip(
        "playwright.sync_api",
        reason="Playwright is not installed (pip install 'planmethod[test]')")
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        pytest.skip("no system Chromium on the PATH (apt-get install chromium)",
                    allow_module_level=True)
    return sync_api, chromium


def launched(sync_api, chromium: str) -> Iterator:
    """The system Chromium launched headless for a module's tests (a fixture's body: yields
    the browser, closes it after)."""
    with sync_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium, args=["--no-sandbox"])
        yield browser
        browser.close()
