"""planmethod — graphical methods of planar-mechanism analysis, checked against exact vectors."""

__version__ = "0.1.0"
