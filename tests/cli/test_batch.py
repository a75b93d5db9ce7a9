"""``ownctl batch``: one instruction per line, each its own transaction, stop at the first error."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl

SCRIPT = """\
# a small session
agent add alexis
agent add xuan

object add wallet --color brown --pos 0.1,0.1,0
claim wallet alexis --p 0.75   # trailing comment
forbid trash if ownedBy any
check trash wallet
ownctl rules list --quiet
"""


def test_batch_runs_every_line_in_one_process(ownctl: Ownctl, tmp_path: Path) -> None:
    script = tmp_path / "session.txt"
    script.write_text(SCRIPT)
    result = ownctl("batch", str(script))
    assert "forbidden: trash wallet" in result.stdout  # a forbidden check is an answer, not a failure
    assert result.stdout.strip().endswith(f"batch: ran 7 instructions from {script}")
    assert ownctl.json("claims", "list")[0]["p"] == 0.75
    events = ownctl.json("log")
    batch_events = [e for e in events if e["interface"] == "batch"]
    assert [e["command"] for e in batch_events][-1] == "forbid trash if ownedBy any"
    assert len(batch_events) == 5  # the mutating lines; check and rules list write nothing


def test_batch_from_stdin_with_json_summary(ownctl: Ownctl) -> None:
    result = ownctl("batch", "-", "--json", input="agent add a1 --quiet\nagent add a2 --json\n")
    data = json.loads(result.stdout)  # exactly one document, holding each line's own output
    assert data["file"] == "stdin" and data["ran"] == 2
    assert [(x["line"], x["exit"]) for x in data["lines"]] == [(1, 0), (2, 0)]
    assert data["lines"][1]["output"] == {"agent": "a2"}
    assert [a["name"] for a in ownctl.json("agent", "list")] == ["a1", "a2"]


def test_batch_json_failure_is_one_document(ownctl: Ownctl) -> None:
    result = ownctl("batch", "-", "--json", input="agent add a1\nclaim pen a1\n", code=1)
    data = json.loads(result.stdout)
    assert data["failed"] == 2 and data["ran"] == 1 and "unknown object 'pen'" in data["error"]


def test_lines_before_a_failure_stay_done(ownctl: Ownctl) -> None:
    result = ownctl("batch", "-", input="agent add a1\nagent add a1\nagent add a2\n", code=1)
    assert result.stderr.startswith("ownctl: stdin:2: agent 'a1' already exists")
    assert [a["name"] for a in ownctl.json("agent", "list")] == ["a1"]


def test_usage_error_in_a_line(ownctl: Ownctl) -> None:
    result = ownctl("batch", "-", input="agent add a1\nagent frobnicate\n", code=2)
    assert result.stderr.startswith("ownctl: stdin:2: ") and result.stderr.count("\n") == 1


def test_lines_cannot_switch_store_or_nest(ownctl: Ownctl) -> None:
    assert "--db is not allowed" in ownctl("batch", "-", input="--db x.db agent list\n", code=1).stderr
    assert "cannot run another batch" in ownctl("batch", "-", input="batch other.txt\n", code=1).stderr
    assert "cannot split" in ownctl("batch", "-", input="agent add 'unclosed\n", code=1).stderr
