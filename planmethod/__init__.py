"""planmethod — graphical methods of planar-mechanism analysis, checked against exact vectors."""

import sys as _sys

__version__ = "0.1.0"


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
