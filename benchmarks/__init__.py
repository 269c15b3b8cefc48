"""Benchmarks and the long stress run of planmethod (not part of the installed package).

Run everything with ``python -m benchmarks.run`` (``--quick`` for a short run); see
docs/benchmarks.md.
"""
