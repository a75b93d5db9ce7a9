"""``ownctl --help`` starts fast: no numpy, scikit-learn, SQLAlchemy or MuJoCo on that path; and
``ownctl check`` and ``ownctl claim`` import what they need only: no SQLAlchemy ORM (the store is
read and written through Core), no pydantic (typer's value conversion), rich, scikit-learn, scipy,
MuJoCo, matplotlib or Alembic, no rule learner when no permission or norm is given, and no other
command's CLI module."""

from __future__ import annotations

import subprocess
import sys

import pytest

from ownctl.api import Ownctl

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


#: never on the way to a decision or a claim (scipy: nowhere on any command's path)
NOT_FOR_DECISIONS = (
    "sqlalchemy.orm",
    "ownctl.learn.induce",
    "numpy.ma",  # np.unique and np.isin import it
    "pydantic",
    "typer._adapters",
    "sklearn",
    "scipy",
    "mujoco",
    "matplotlib",
    "PIL",
    "imageio",
    "alembic",
    "rapidfuzz",
    "sim",
    "ownctl.language",
    "ownctl.experiment",
    "ownctl.cli.things",
    "ownctl.cli.experiment_cmd",
    "ownctl.cli.scenario_cmd",
    "ownctl.cli.run_cmd",
    "ownctl.cli.say_cmd",
    "ownctl.cli.admin",
)


def _heavy_after(*args: str, heavy: tuple[str, ...] = HEAVY) -> str:
    result = subprocess.run(
        [sys.executable, "-c", PROBE.format(heavy=heavy), *args], capture_output=True, text=True, check=True
    )
    line = [x for x in result.stdout.splitlines() if x.startswith("HEAVY:")][-1]
    return line.removeprefix("HEAVY:").strip()


@pytest.fixture(scope="module")
def store(tmp_path_factory: pytest.TempPathFactory) -> str:
    """A store with a claimed object under a norm, so that check and claim do their whole work."""
    db = str(tmp_path_factory.mktemp("startup") / "startup.db")
    with Ownctl.open(db, create=True) as robot:
        robot.add_agent("xuan")
        robot.add_object("mug", "red", (0.1, 0.1, 0.0))
        robot.claim("mug", "xuan")
        robot.forbid("trash", "if ownedBy any")
    return db


def test_help_imports_nothing_heavy() -> None:
    assert _heavy_after("--help") == ""


def test_subcommand_help_imports_nothing_heavy() -> None:
    assert _heavy_after("object", "add", "--help") == ""
    assert _heavy_after("--version") == ""


def test_check_imports_only_what_a_decision_needs(store: str) -> None:
    # ownctl.cli.query shows that the probe sees the modules it names; the steps print in plain text
    heavy = ("ownctl.cli.query", *NOT_FOR_DECISIONS, "rich")
    assert _heavy_after("--db", store, "check", "trash", "mug", heavy=heavy) == "ownctl.cli.query"


@pytest.mark.slow
def test_claim_imports_only_what_a_claim_needs(store: str) -> None:
    assert _heavy_after("--db", store, "claim", "mug", "xuan", heavy=(*NOT_FOR_DECISIONS, "rich")) == ""
    # a value other than the default goes through typer's own conversion, and nothing else changes
    given = _heavy_after("--db", store, "claim", "mug", "xuan", "--p", "0.9", heavy=NOT_FOR_DECISIONS)
    assert given == "pydantic,typer._adapters"


@pytest.mark.slow
def test_no_command_imports_scipy(store: str) -> None:
    for args in (["--db", store, "say", "whose is the mug?", "--json"], ["--db", store, "rules", "list"],
                 ["experiment", "ownership", "--trials", "1", "--quiet"]):
        assert _heavy_after(*args, heavy=("scipy", "sklearn")) == "", args


def test_the_console_script_leaves_without_a_last_collection(store: str) -> None:
    """Its heap is frozen when the command is done: the collector at exit walks nothing."""
    probe = ("import gc, sys\nfrom ownctl.cli.main import run\nsys.argv = ['ownctl', *sys.argv[1:]]\n"
             "try:\n    run()\nexcept SystemExit:\n    print('FROZEN:', gc.get_freeze_count() > 1000)\n")
    result = subprocess.run([sys.executable, "-c", probe, "--db", store, "check", "trash", "mug"],
                            capture_output=True, text=True, check=True)
    assert "FROZEN: True" in result.stdout
