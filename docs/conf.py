"""Sphinx configuration of planmethod's documentation site (``pip install ".[docs]"``).

Build it with warnings as errors, offline (nothing is fetched: no intersphinx)::

    python -m sphinx -W --keep-going -n -b html docs docs/_build/html
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

project = "planmethod"
author = "the planmethod authors"
copyright = "the planmethod authors, MIT licence"
from planmethod import __version__  # noqa: E402 (after the path is set)

release = version = __version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "numpydoc",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "README.md"]

# MyST: Markdown with directives in ``{name}`` fences; headings get anchors for links to them.
myst_enable_extensions = ["colon_fence"]
myst_heading_anchors = 3

# The API reference: documented members in source order, parameters checked.
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# Undocumented, unknown or misordered parameters of a public function are build errors.
numpydoc_validation_checks = {"PR01", "PR02", "PR03"}
# The check is for the functions the API reference lists (api.md, each ``:members:`` line).
# Classes (frozen dataclasses whose fields are their documented attributes), their methods and
# constants are named with a capital and not validated; neither are the modules' other
# functions, which autodoc reads while it documents the listed ones.


def _unlisted_functions() -> set[str]:
    import importlib
    import inspect
    import re

    text = (Path(__file__).with_name("api.md")).read_text(encoding="utf-8")
    excluded = {r"\.[A-Z][A-Za-z0-9_]*(\.|$)"}
    for module_name, members in re.findall(r"```\{automodule\} (\S+)\n:members:(.*)\n", text):
        listed = {name.strip() for name in members.split(",") if name.strip()}
        if not listed:
            continue
        module = importlib.import_module(module_name)
        for name, value in vars(module).items():
            if inspect.isfunction(value) and name not in listed and not name.startswith("_"):
                excluded.add(rf"^{re.escape(module_name)}\.{name}$")
    return excluded


numpydoc_validation_exclude = _unlisted_functions()

nitpicky = True
highlight_language = "text"
html_theme = "alabaster"
html_title = "planmethod"
html_static_path: list[str] = []
