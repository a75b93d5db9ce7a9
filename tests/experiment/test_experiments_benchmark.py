"""``benchmarks/experiments.py`` times Table 1 taught together and taught one permission at a time,
with the same figures."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_table_1_online_gives_the_figures_of_table_1() -> None:
    out = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "experiments.py"), "--only", "norms", "--only",
         "norms-online", "--trials", "3", "--jobs", "1", "--json"],
        capture_output=True, text=True, check=True, timeout=300)
    together, online = json.loads(out.stdout)["results"]
    assert (together["experiment"], online["experiment"]) == ("norms", "norms-online")
    assert together["target_seconds"] == 5.0 and online["target_seconds"] is None
    assert online["headline"] == together["headline"]
    assert together["headline"]["noiseless 1.00"]["accuracy"] == 1.0
