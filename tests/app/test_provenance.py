"""Each belief says what it is: base rate, prediction, claim or inference, through runs and resets."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from ownctl.app import admin, explain, instruct, query, run
from ownctl.app.context import AppContext


@pytest.fixture
def ctx(tmp_path: Path) -> Iterator[AppContext]:
    ctx = AppContext(str(tmp_path / "p.db"), now=1000.0)
    ctx.store(create=True)
    yield ctx
    ctx.close()


def sources(ctx: AppContext) -> set[str]:
    with ctx.read() as tx:
        names = [o.name for o in tx.things.objects()]
    return {o["source"] for n in names for o in query.owners(ctx, n)["owners"]}


def test_a_run_without_claims_leaves_base_rates_labelled_as_such(ctx: AppContext) -> None:
    run.run(ctx, "trashAll", instructor="none", physics=False)
    assert sources(ctx) == {"base-rate"}
    instruct.add_norm(ctx, "forbid trash if ownedBy any")
    text = explain.explain(ctx, "trash", "block1").text
    assert "base rate" in text and "prediction" not in text


def test_an_oracle_run_labels_claims_predictions_and_inference(ctx: AppContext) -> None:
    run.run(ctx, "trashAll", instructor="oracle", physics=False)
    with ctx.read() as tx:
        permitted = {p.object_id for p in tx.knowledge.permission_table()}
        rows = tx.beliefs.belief_table()
        claimed_agents = {b.agent_id for b in rows if b.claim_p is not None}
        assert claimed_agents
        for b in rows:
            assert b.prior_source == ("prediction" if b.agent_id in claimed_agents else "base-rate")
            assert (b.posterior_source == "inference") == (b.object_id in permitted)
    assert sources(ctx) == {"inference"}  # the oracle gave permissions on every object it was asked about
    admin.reset(ctx, "perms", yes=True)
    assert sources(ctx) == {"claim", "prediction", "base-rate"} - (set() if len(claimed_agents) < 3 else
                                                                   {"base-rate"})
    admin.reset(ctx, "claims", yes=True)
    assert sources(ctx) == {"base-rate"}


def test_a_played_scenario_labels_its_beliefs_as_what_they_are(tmp_path: Path) -> None:
    from ownctl.app.scenario import play_file

    db = str(tmp_path / "s.db")
    AppContext(db, now=1.0).store(create=True).close()
    scenarios = Path(__file__).resolve().parents[2] / "scenarios"
    report = play_file(str(scenarios / "demo1-thats-mine.toml"), db, 2000.0)
    assert report.passed
    ctx = AppContext(db, now=3000.0)
    try:
        with ctx.read() as tx:
            permitted = {p.object_id for p in tx.knowledge.permission_table()}
            rows = tx.beliefs.belief_table()
        claimed_agents = {b.agent_id for b in rows if b.claim_p is not None}
        for b in rows:
            assert b.prior_source == ("prediction" if b.agent_id in claimed_agents else "base-rate")
            inferred = b.object_id in permitted and b.posterior_p is not None
            assert (b.posterior_source == "inference") == inferred
            if b.object_id not in permitted:
                assert b.posterior_p is None
    finally:
        ctx.close()
