"""``benchmarks/generalisation.py`` runs end to end (without ProbFOIL) and reports, per condition,
ours, the paper learner and allowing everything, in either decision mode."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
@pytest.mark.parametrize("decide", ["map", "posterior"])
def test_the_benchmark_reports_every_condition(decide: str, tmp_path: Path) -> None:
    out = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "generalisation.py"), "--families", "2",
         "--trials", "1", "--jobs", "1", "--no-probfoil", "--json", "--decide", decide,
         "--cache", str(tmp_path / "none.json")],
        capture_output=True, text=True, check=True, timeout=600)
    report = json.loads(out.stdout)
    assert report["decide"] == decide and report["families"] == 2
    names = [row["name"] for row in report["conditions"]]
    assert names == [f"{k} {share}" for k in ("noiseless", "noisy") for share in ("1.00", "0.50", "0.25")]
    exact = report["conditions"][0]["accuracy"]
    assert exact["ours"]["mean"] == 1.0 and exact["ours"]["families"] == 2
    assert exact["allow"]["mean"] < 1.0
    assert report["conditions"][0]["accuracy"]["probfoil"]["families"] == 0
