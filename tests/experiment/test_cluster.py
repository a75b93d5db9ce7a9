"""Trials on a Dask cluster give exactly the numbers of local runs (--jobs 1, --jobs 2), and a
missing dask or an unreachable scheduler is one line."""

from __future__ import annotations

import builtins
import json
import socket
from collections.abc import Iterator
from typing import Any

import pytest
from typer.testing import CliRunner

from ownctl.cli.main import app as ownctl_app
from ownctl.errors import BadValue, OwnctlError
from ownctl.experiment import cluster
from ownctl.experiment.registry import get_experiment
from ownctl.experiment.runner import Unit, run_experiment, run_trials
from ownctl.world.generator import paper_blocks_world


def _per_trial(done: dict[Unit, Any]) -> str:
    """Every trial's numbers, exactly (repr keeps every float bit, and NaN equals NaN)."""
    return repr(sorted((unit, result) for unit, (result, _) in done.items()))


def _numbers(doc: dict[str, Any]) -> list[Any]:
    """A JSON document's figures without timings and without where the trials ran."""
    return [{k: v for k, v in c.items() if k != "trial_seconds"} for c in doc["conditions"]]


@pytest.fixture(scope="module")
def scheduler() -> Iterator[str]:
    """A local Dask cluster of two worker processes (one thread each); its scheduler's address."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as local:
        yield local.scheduler_address


@pytest.mark.slow
def test_trials_on_a_dask_cluster_equal_local_trials(scheduler: str) -> None:
    exp = get_experiment("norms")
    units = [(0, c, t) for t in range(3) for c in range(len(exp.conditions))]
    one = run_trials("norms", [paper_blocks_world], "ours", 7, units, jobs=1)
    two = run_trials("norms", [paper_blocks_world], "ours", 7, units, jobs=2)
    dask = run_trials("norms", [paper_blocks_world], "ours", 7, units, scheduler=scheduler)
    assert set(dask) == set(units)
    assert _per_trial(dask) == _per_trial(one) == _per_trial(two)
    other = run_trials("norms", [paper_blocks_world], "ours", 8, units, jobs=1)
    assert _per_trial(other) != _per_trial(one)  # the comparison sees a different seed


@pytest.mark.slow
def test_experiment_command_runs_on_a_scheduler(scheduler: str) -> None:
    args = ["experiment", "ownership", "--trials", "2", "--seed", "4", "--json", "--quiet"]
    local = CliRunner().invoke(ownctl_app, args)
    remote = CliRunner().invoke(ownctl_app, [*args, "--scheduler", scheduler])
    assert local.exit_code == 0 and remote.exit_code == 0, remote.stderr
    local_doc, remote_doc = json.loads(local.stdout), json.loads(remote.stdout)
    assert remote_doc["scheduler"] == scheduler and local_doc["scheduler"] is None
    assert _numbers(remote_doc) == _numbers(local_doc)
    result = run_experiment("ownership", 2, 4, 1, paper_blocks_world, "ours", scheduler=scheduler)
    assert result.scheduler == scheduler and result.as_dict()["scheduler"] == scheduler


def test_jobs_and_scheduler_are_alternatives() -> None:
    with pytest.raises(BadValue, match="--jobs 2 and --scheduler tcp://h:8786 are alternatives"):
        run_experiment("norms", 1, 0, 2, paper_blocks_world, "ours", scheduler="tcp://h:8786")


def test_missing_dask_is_one_line(monkeypatch: pytest.MonkeyPatch) -> None:
    real_import = builtins.__import__

    def no_dask(name: str, *args: Any, **kwargs: Any) -> Any:
        if name.split(".")[0] in ("dask", "distributed"):
            raise ImportError(f"No module named {name!r}")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_dask)
    with pytest.raises(OwnctlError, match=r"needs dask.distributed, which is not installed: pip install"):
        with cluster.executor(1, "tcp://127.0.0.1:8786"):
            pass


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.mark.slow
def test_unreachable_scheduler_is_one_line() -> None:
    pytest.importorskip("distributed")
    address = f"tcp://127.0.0.1:{_free_port()}"  # nothing listens there
    with pytest.raises(OwnctlError) as caught:
        with cluster.executor(1, address, timeout=0.5):
            pass
    message = caught.value.message
    assert message.startswith(f"cannot reach the Dask scheduler at {address!r}") and "\n" not in message


@pytest.mark.slow
def test_unreachable_scheduler_from_the_command_line(monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("distributed")
    monkeypatch.setattr(cluster, "CONNECT_TIMEOUT", 0.5)
    address = f"tcp://127.0.0.1:{_free_port()}"
    res = CliRunner().invoke(ownctl_app, ["experiment", "norms", "--trials", "1", "--quiet",
                                          "--scheduler", address])
    assert res.exit_code == 1 and res.stdout == ""
    assert res.stderr.startswith(f"ownctl: cannot reach the Dask scheduler at {address!r}")
    assert res.stderr.count("\n") == 1


@pytest.mark.parametrize(("address", "why"), [("nonsense", "missing port number"),
                                              ("tcp://host", "missing port number"),
                                              ("foo://host:1", "unknown scheme 'foo'")])
def test_malformed_scheduler_address_is_one_line(address: str, why: str) -> None:
    pytest.importorskip("distributed")
    with pytest.raises(BadValue, match=f"invalid Dask scheduler address '{address}': {why}") as caught:
        with cluster.executor(1, address):
            pass
    assert "tcp" in caught.value.valid
