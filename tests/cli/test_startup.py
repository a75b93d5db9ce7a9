"""``ownctl --help`` starts fast: no numpy, scikit-learn, SQLAlchemy ORM or MuJoCo on that path."""

from __future__ import annotations

import subprocess
import sys

HEAVY = (
    "numpy",
    "sklearn",
    "sqlalchemy",
    "sqlalchemy.orm",
    "mujoco",
    "alembic",
    "ownctl.app",
    "ownctl.store",
)

PROBE = """
import sys
from ownctl.cli.main import run
sys.argv = ["ownctl", *sys.argv[1:]]
try:
    run()
except SystemExit:
    pass
heavy = [m for m in {heavy!r} if m in sys.modules]
print("HEAVY:", ",".join(heavy))
"""


def _heavy_after(*args: str) -> str:
    result = subprocess.run(
        [sys.executable, "-c", PROBE.format(heavy=HEAVY), *args], capture_output=True, text=True, check=True
    )
    line = [x for x in result.stdout.splitlines() if x.startswith("HEAVY:")][-1]
    return line.removeprefix("HEAVY:").strip()


def test_help_imports_nothing_heavy() -> None:
    assert _heavy_after("--help") == ""


def test_subcommand_help_imports_nothing_heavy() -> None:
    assert _heavy_after("object", "add", "--help") == ""
    assert _heavy_after("--version") == ""
