"""``ownctl experiment ...`` through the ownctl command group, and the app layer's world files."""

from __future__ import annotations

import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from ownctl.app import experiment as app_experiment
from ownctl.cli.main import app as ownctl_app
from ownctl.errors import OwnctlError
from tests.cli.conftest import SMALL_WORLD

ROOT = Path(__file__).resolve().parents[2]
DESK = ROOT / "scenarios" / "desk-norms.toml"
PAPER = ROOT / "scenarios" / "paper-blocks.toml"

cli = ownctl_app  # the real command group: it reports errors as every command does


def run(*args: str):
    return CliRunner().invoke(cli, ["experiment", *args])  # click 8.2+: stdout and stderr apart


def test_json_document_has_the_design_shape() -> None:
    res = run("ownership", "--trials", "2", "--json", "--seed", "3")
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    assert {"experiment", "trials", "seed", "conditions", "seconds"} <= set(doc)
    assert doc["experiment"] == "ownership" and doc["trials"] == 2 and doc["seed"] == 3
    assert [c["name"] for c in doc["conditions"]] == ["(i) no inference", "(ii) rules learned",
                                                      "(iii) rules given"]
    for c in doc["conditions"]:
        assert {"name", "accuracy", "f1", "ci95", "paper"} <= set(c)
        assert 0 <= c["accuracy"] <= 1 and set(c["ci95"]) == {"accuracy", "f1"}


def test_owners_claims_run_their_own_conditions() -> None:
    res = run("ownership", "--trials", "2", "--json", "--seed", "3", "--claims", "owners")
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    names = ["(i') no inference, owners' claims", "(ii') rules learned, owners' claims",
             "(iii') rules given, owners' claims"]
    assert [c["name"] for c in doc["conditions"]] == names
    assert [c["name"] for c in doc["calibration"]] == names
    assert all(c["paper"] == {} for c in doc["conditions"])  # not the paper's protocol
    assert "no such option: --claims" in run("norms", "--trials", "1", "--claims", "owners").stderr


@pytest.mark.slow
def test_task_selection_tables_and_files(tmp_path: Path) -> None:
    out_csv, out_png = tmp_path / "t3.csv", tmp_path / "t3.png"
    res = run("task", "--trials", "2", "--task", "trashAll", "--jobs", "2", "--csv", str(out_csv),
              "--plot", str(out_png))
    assert res.exit_code == 0, res.stderr
    assert "trashAll" in res.stdout and "collectAll" not in res.stdout
    assert "6.32" in res.stdout  # the paper's mistakes beside ours
    assert "mistakes" in res.stdout and "strict" in res.stdout  # metric definitions
    rows = list(csv.DictReader(out_csv.open()))
    assert {r["condition"] for r in rows} == {"trashAll"}
    mistakes = [r for r in rows if r["group"] == "counts" and r["row"] == "mistakes"]
    assert len(mistakes) == 1 and mistakes[0]["paper"] == "6.32"
    assert out_png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_quiet_prints_nothing() -> None:
    res = run("norms", "--trials", "1", "--quiet")
    assert res.exit_code == 0 and res.stdout == ""


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["norms", "--learner", "foil"], "unknown learner 'foil'; known learners: ours, paper"),
        (["task", "--decide", "vote"],
         "unknown decision mode 'vote'; known decision modes: map, posterior, window"),
        (["task", "--ask", "1", "--decide", "vote"], "unknown decision mode 'vote'"),
        (["norms", "--trials", "0"], "--trials must be an integer from 1 to 100,000, got 0"),
        (["norms", "--trials", "999999999999"], "--trials must be an integer from 1 to 100,000"),
        (["norms", "--jobs", "0"], "--jobs must be an integer from 1 to 1,024, got 0"),
        (["norms", "--jobs", "999999999999"], "--jobs must be an integer from 1 to 1,024"),
        (["norms", "--families", "999999999999"], "--families must be an integer from 1 to 10,000"),
        (["norms", "--plot", "table.5"], "cannot draw a plot as '.5' ('table.5'); valid suffixes: .png"),
        (["task", "--ask", "1", "--plot", ""], "--plot needs a file name such as table.png, got ''"),
        (["norms", "--world", "w" * 300], "File name too long"),
        (["norms", "--csv", "d" * 300 + "/t.csv"], "File name too long"),
        (["norms", "--seed=-1"], "--seed must be a non-negative integer, got -1"),
        (["ownership", "--seed=-2"], "--seed must be a non-negative integer, got -2"),
        (["task", "--ask", "1", "--seed=-1"], "--seed must be a non-negative integer"),
        (["norms", "--families", "2", "--family-seed=-3"], "--family-seed must be a non-negative integer"),
        (["task", "--task", "tidyAll"], "unknown task 'tidyAll'"),
        (["ownership", "--world", "no/such/world.toml"], "does not exist"),
        (["ownership", "--claims", "some"], "unknown claim mode 'some'; known claim modes: all, owners"),
        (["task", "--ask-temper", "0.5"], "--ask-temper applies only with --ask"),
        (["task", "--ask-as-given"], "--ask-read/--ask-as-given applies only with --ask"),
        (["task", "--ask", "1", "--ask-temper", "0"], "must be in (0, 1]"),
        (["task", "--ask-ahead", "2"], "--ask-ahead applies only with --ask"),
        (["task", "--ask", "1", "--ask-ahead=-1"], "look-ahead must be a whole number"),
        (["task", "--ask", "1", "--csv", "asked.csv"], "--csv does not apply with --ask"),
        (["task", "--ask", "1", "--world", "no/such/world.toml"], "does not exist"),
        (["task", "--ask", "1", "--ask-kinds", "act,why"],
         "unknown question kind 'why'; known question kinds: act, may, rule, whose"),
    ],
)
def test_bad_input_is_one_line_and_exit_1(args: list[str], message: str) -> None:
    res = run(*args, "--json")
    assert res.exit_code == 1
    assert message in res.stderr and res.stderr.count("\n") == 1
    assert json.loads(res.stdout)["error"].startswith(res.stderr.strip().removeprefix("ownctl: ")[:20])


def test_malformed_world_file_is_a_user_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "x"\nagents = ["a"]\nnorms = ["forbid trash if ownedBy b"]\n')
    with pytest.raises(OwnctlError, match="unknown agent 'b'"):
        app_experiment.load_world(bad)
    bad.write_text("name = \n")
    with pytest.raises(OwnctlError, match="not valid TOML"):
        app_experiment.load_world(bad)


@pytest.mark.slow
def test_paper_world_file_equals_the_builtin_world() -> None:
    built = app_experiment.run("task", trials=2, seed=1)
    filed = app_experiment.run("task", trials=2, seed=1, world=PAPER)
    assert filed.extra["paper_comparable"] and built.extra["paper_comparable"]
    for a, b in zip(built.conditions, filed.conditions, strict=True):
        assert a.accuracy == b.accuracy and a.counts == b.counts


@pytest.mark.slow
def test_a_scattered_world_runs_table_2_and_is_not_the_paper_s() -> None:
    """Table 2 on a world no percept predicts: few held-out objects are predicted far from how
    often the agents own things (a quarter each), since no percept can back such a prediction."""
    res = run("ownership", "--trials", "6", "--world", str(ROOT / "scenarios" / "scattered.toml"), "--json")
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    assert doc["paper_comparable"] is False
    bins = doc["calibration"][0]["reliability"]
    far = sum(b["count"] for b in bins if b["hi"] <= 0.1 + 1e-9 or b["lo"] >= 0.6 - 1e-9)
    assert far < 0.2 * sum(b["count"] for b in bins)


@pytest.mark.slow
def test_a_different_norm_set_runs_end_to_end() -> None:
    factory = app_experiment.load_world(DESK)
    assert not app_experiment.is_paper_world(factory)
    world = factory(None)
    assert "forbid pickUp if not ownedBy xuan and inArea desk_xuan" in world.norms
    norms = app_experiment.run("norms", trials=3, world=DESK)
    full = norms.conditions[0]
    assert full.name == "noiseless 1.00" and full.accuracy.mean > 0.95
    assert {r.name for r in full.groups["rules"].rows} == {"trash", "pickUp", "collect"}
    assert full.paper == {}  # the paper's numbers are for its blocks world only
    task = app_experiment.run("task", trials=1, world=DESK)
    trash = task.conditions[1]
    assert trash.counts["violations"].mean == 0
    assert trash.counts["mistakes"].mean < 11  # baseline: 11 objects the norms protect from trashing
    res = run("ownership", "--trials", "2", "--world", str(DESK))
    assert res.exit_code == 0 and "blocks world only" in res.stdout


@pytest.mark.slow
def test_same_numbers_under_another_hash_seed() -> None:
    code = ("import json; from ownctl.app.experiment import run; "
            "print(json.dumps([c['groups'] for c in run('task', trials=2, seed=7).as_dict()['conditions']]))")
    outs = []
    for hash_seed in ("1", "2"):
        env = {**os.environ, "PYTHONHASHSEED": hash_seed}
        proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=ROOT)
        assert proc.returncode == 0, proc.stderr
        outs.append(proc.stdout)
    assert outs[0] == outs[1]


@pytest.mark.slow
def test_the_asking_experiment_reports_how_ours_reads_ownership() -> None:
    res = run("task", "--ask", "1", "--trials", "1", "--task", "trashAll", "--ask-as-given", "--json")
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    assert (doc["read"], doc["temper"], doc["kinds"]) == (False, 0.5, ["act", "may", "whose"])
    assert {r["strategy"] for r in doc["tasks"][0]["runs"]} == {"ours", "entropy", "random"}


@pytest.mark.slow
def test_the_asking_experiment_runs_on_a_world_file(tmp_path: Path) -> None:
    strays = SMALL_WORLD.replace("owners = { alexis = 1.0 }\n", "")  # nobody owns anything
    assert "owners" not in strays
    world = tmp_path / "strays.toml"
    world.write_text(strays)
    res = run("task", "--ask", "0,1", "--trials", "2", "--task", "trashAll", "--world", str(world), "--json")
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    assert doc["world"] == str(world)
    runs = {(r["strategy"], r["budget"]): r for r in doc["tasks"][0]["runs"]}
    # nothing is forbidden there: the robot trashes every object unasked
    assert all(runs[s, 0]["per_trial"] == [0, 0] for s in ("ours", "entropy", "random"))
    assert runs["entropy", 1]["questions"] <= 1 and len(runs["ours", 1]["per_trial"]) == 2
    without = tmp_path / "nobin.toml"
    without.write_text(strays.replace('name = "trash"', 'name = "shelf"'))
    res = run("task", "--ask", "1", "--trials", "1", "--task", "trashAll", "--world", str(without))
    assert res.exit_code == 1 and "the task needs an area 'trash'" in res.stderr
