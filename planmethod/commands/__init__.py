"""Subcommands of the ``planmethod`` command line (see :mod:`planmethod.cli`)."""
