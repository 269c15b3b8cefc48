"""planmethod — graphical methods of planar-mechanism analysis, checked against exact vectors.

The Python API is reachable from here, loaded when first used (``import planmethod`` stays
light): :func:`planmethod.load` reads an exercise file into an
:class:`~planmethod.application.api.Exercise`; its ``solve(angle=…)`` gives a
:class:`~planmethod.application.api.Solution` (docs/api.md).

Examples
--------
>>> import planmethod
>>> planmethod.load("exercises/compressor_slider_crank.toml").solve().plans.velocity.pole
'p'
"""

import sys as _sys

__version__ = "0.1.0"

#: the names of the Python API (:mod:`planmethod.application.api`), imported when first used
_API = ("Exercise", "Solution", "load", "parse")

__all__ = ["__version__", *_API]


def __getattr__(name: str):
    """The API's names, imported from :mod:`planmethod.application.api` when first asked
    for (numpy and the rest load then, not with ``import planmethod``)."""
    if name in _API:
        from .application import api

        value = getattr(api, name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'planmethod' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})


def load_ipython_extension(shell) -> None:
    """``%load_ext planmethod``: show plans as SVG in IPython and Jupyter."""
    from .notebook import register

    register(shell)


def _register_in_running_ipython() -> None:
    """Register the notebook formatters if planmethod is imported inside IPython."""
    ipython = _sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None else None
    if shell is not None:
        load_ipython_extension(shell)


_register_in_running_ipython()
