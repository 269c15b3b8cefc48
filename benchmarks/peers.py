"""The open-source peers, in a virtualenv of their own, timed in a subprocess.

The peers are never dependencies of planmethod and nothing of theirs is committed: ``python -m
benchmarks.peers --setup`` makes a separate virtualenv (default ``/tmp/peers-venv``, or
``$PLANMETHOD_PEERS_VENV``) with the pinned versions below, and :func:`run_peer` runs
``benchmarks/peers_worker.py`` with that virtualenv's Python. The worker times the peer's own
full-turn call inside the subprocess, so process start-up and imports are not counted.

Examples
--------
>>> sorted(PEERS)
['fourbarhinge', 'kimech', 'kinepy', 'mechanism', 'pylinkage']
>>> venv_python(Path("/nonexistent")).name
'python'
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

#: peer → pip requirement (the versions benchmarked)
PEERS = {
    "pylinkage": "pylinkage==1.3.0",
    "mechanism": "mechanism==1.1.10",
    "kimech": "kimech==0.7.0",
    "fourbarhinge": "fourbarhinge==0.1.2",
    "kinepy": "kinepy==0.1.7",
}
#: what else the peers need to run at their best (pylinkage's fast path is numba-compiled)
EXTRAS = ["numba==0.68.1"]

WORKER = Path(__file__).resolve().parent / "peers_worker.py"


def venv_path() -> Path:
    return Path(os.environ.get("PLANMETHOD_PEERS_VENV", "/tmp/peers-venv"))


def venv_python(venv: Path | None = None) -> Path:
    return (venv or venv_path()) / "bin" / "python"


def setup(venv: Path | None = None) -> int:
    """Create the peers' virtualenv and install the pinned peers into it."""
    venv = venv or venv_path()
    if not venv_python(venv).exists():
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    command = [str(venv_python(venv)), "-m", "pip", "install", "-q", *PEERS.values(), *EXTRAS]
    print("$", " ".join(command), file=sys.stderr)
    return subprocess.run(command).returncode


def available(venv: Path | None = None) -> bool:
    return venv_python(venv).exists()


def run_peer(peer: str, mechanism: str, counts: list[int], *, budget: float = 20.0,
             min_time: float = 0.5, timeout: float = 900.0) -> tuple[dict, dict | None]:
    """Time ``peer`` on ``mechanism`` at each N in ``counts`` in the peers' virtualenv.

    Returns (the worker's JSON report, C's arrays at the largest N timed or None).
    """
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "arrays.npz"
        command = [str(venv_python()), str(WORKER), peer, mechanism,
                   ",".join(str(c) for c in counts), "--out", str(out),
                   "--budget", str(budget), "--min-time", str(min_time)]
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout,
                              env={**os.environ, "PYTHONWARNINGS": "ignore"})
        if done.returncode != 0:
            tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
            return {"peer": peer, "mechanism": mechanism, "failed": tail, "runs": {}}, None
        report = json.loads(done.stdout.strip().splitlines()[-1])
        arrays = None
        if out.exists():
            with np.load(out) as data:
                arrays = {key: np.array(data[key]) for key in data.files}
        return report, arrays


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.peers",
                                     description="set up or try the peers' virtualenv")
    parser.add_argument("--setup", action="store_true", help="create the virtualenv")
    parser.add_argument("--try", dest="attempt", action="store_true",
                        help="time each peer at N = 360 on both mechanisms")
    args = parser.parse_args(argv)
    if args.setup:
        return setup()
    if args.attempt:
        for peer in PEERS:
            for mechanism in ("fourbar", "slider_crank"):
                report, _ = run_peer(peer, mechanism, [360], min_time=0.1)
                print(json.dumps(report))
        return 0
    parser.print_help()
    return 0


if __name__ == "__main__":
    sys.exit(main())
