"""Median wall time of ``ownctl --help`` (and, for comparison, of a command that opens the store).

Usage: python benchmarks/cli_startup.py [--runs 20]

``--help`` must stay light: it imports typer, click and rich but no numpy, SQLAlchemy ORM,
scikit-learn or MuJoCo (tests/cli/test_startup.py checks the imports; this measures the time).
The console script is located next to the running interpreter, so a pyenv or venv shim does not
add its own start-up to the figure.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def ownctl_executable() -> list[str]:
    """The ``ownctl`` console script of this interpreter (else ``python -m``-style fallback)."""
    script = Path(sys.executable).with_name("ownctl")
    if script.exists():
        return [str(script)]
    found = shutil.which("ownctl")
    return [found] if found else [sys.executable, "-c", "from ownctl.cli.main import run; run()"]


def median_seconds(cmd: list[str], runs: int, env: dict[str, str]) -> float:
    """Median wall time of ``runs`` runs of ``cmd`` (after one warm-up run)."""
    subprocess.run(cmd, env=env, capture_output=True, check=True)
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(cmd, env=env, capture_output=True, check=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=20)
    args = parser.parse_args()
    exe = ownctl_executable()
    env = {**os.environ, "OWNCTL_NOW": "0"}
    help_s = median_seconds([*exe, "--help"], args.runs, env)
    print(f"ownctl --help: median {help_s * 1000:.0f} ms over {args.runs} runs")
    with tempfile.TemporaryDirectory() as tmp:
        db = f"sqlite:///{tmp}/bench.db"
        subprocess.run([*exe, "--db", db, "init"], env=env, capture_output=True, check=True)
        list_s = median_seconds([*exe, "--db", db, "agent", "list", "--json"], args.runs, env)
    print(f"ownctl agent list (opens the store): median {list_s * 1000:.0f} ms over {args.runs} runs")


if __name__ == "__main__":
    main()
