"""Decisions and rules carry the posterior over rule sets: how sure a learned rule is, and the
marginal P(forbidden) when ``decide.rules`` is ``posterior``."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from ownctl.app import admin, decide, explain, instruct, query, things
from ownctl.app.context import AppContext
from ownctl.app.mindstore import load


@pytest.fixture
def ctx(tmp_path: Path) -> Iterator[AppContext]:
    ctx = AppContext(str(tmp_path / "r.db"), now=1000.0)
    ctx.store(create=True)
    for agent in ("xuan", "jake"):
        things.add_agent(ctx, agent)
    for i in range(4):
        things.add_object(ctx, f"o{i}", color=("red", "blue")[i % 2], pos=f"0.{i},0.1,0")
    instruct.add_claim(ctx, "o0", "xuan", exclusive=True)
    instruct.add_claim(ctx, "o2", "jake", exclusive=True)
    instruct.add_claim(ctx, "o1", "xuan", negated=True)
    yield ctx
    ctx.close()


def test_a_rule_learned_from_one_example_is_uncertain_and_says_so(ctx: AppContext) -> None:
    instruct.add_permission(ctx, "trash", "o0", 1.0)
    report = decide.check(ctx, "trash", "o2", record=False)
    (step,) = [s for s in report.data["steps"] if s["action"] == "trash"]
    assert step["decided_by"] == "rules" and 0.0 < step["rule_support"] < 0.9
    said = f"the posterior over rule sets says the same of o2 with p={step['rule_support']:.2f}"
    assert said in report.reason and said in explain.explain(ctx, "trash", "o2").text
    rules = query.list_rules(ctx)
    assert all(r["posterior"] is not None and 0.0 <= r["posterior"] <= 1.0 for r in rules)


def test_a_stated_norm_is_not_called_uncertain(ctx: AppContext) -> None:
    instruct.add_norm(ctx, "forbid trash if ownedBy any")
    instruct.add_permission(ctx, "trash", "o0", 1.0)
    report = decide.check(ctx, "trash", "o2", record=False)
    assert "uncertain" not in report.reason


def test_posterior_decisions_marginalise_over_rule_sets(ctx: AppContext) -> None:
    instruct.add_permission(ctx, "trash", "o0", 1.0)
    instruct.add_permission(ctx, "trash", "o1", 0.0)
    on_map = decide.check(ctx, "trash", "o3", record=False).data
    admin.config_set(ctx, "decide.rules", "posterior")
    marginal = decide.check(ctx, "trash", "o3", record=False).data
    with ctx.read() as tx:
        mind = load(tx, ctx.now).mind
    expected = mind.rule_posterior("trash").p_forbidden(mind.frame().take([mind.index["o3"]]))[0]
    (step,) = [s for s in marginal["steps"] if s["action"] == "trash"]
    assert step["p_rules"] == pytest.approx(expected, abs=1e-12)
    assert on_map["steps"][-1]["p_rules"] != pytest.approx(step["p_rules"], abs=1e-6)
    with pytest.raises(Exception, match="known decision modes: map, posterior"):
        admin.config_set(ctx, "decide.rules", "mode")


def test_window_decisions_are_the_mean_over_the_near_best_sets_and_say_so(ctx: AppContext) -> None:
    from ownctl.learn.posterior import window_p_forbidden, window_size
    from ownctl.mind.ask import decisions

    instruct.add_permission(ctx, "trash", "o0", 1.0)
    admin.config_set(ctx, "decide.rules", "window")
    admin.config_set(ctx, "decide.window", "1.5")
    report = decide.check(ctx, "trash", "o3", record=False)
    with ctx.read() as tx:
        mind = load(tx, ctx.now).mind
    assert mind.settings.decide_rules == "window" and mind.settings.decide_window == 1.5
    i = mind.index["o3"]
    post = mind.rule_posterior("trash")
    expected = window_p_forbidden(post, mind.rules["trash"], mind.frame().take([i]), 1.5)[0]
    (step,) = [s for s in report.data["steps"] if s["action"] == "trash"]
    assert step["p_rules"] == pytest.approx(expected, abs=1e-12)
    assert step["decide"] == "window" and step["rule_sets"] == window_size(post, mind.rules["trash"], 1.5) > 1
    text = explain.explain(ctx, "trash", "o3").text
    if step["decided_by"] == "rules":
        assert "near-best rule sets" in report.reason and "near-best rule sets" in text
    # every decision, one implementation: the asking core decides as the Mind does
    idx = list(range(len(mind.objects)))
    assert decisions(mind, ["trash"], idx).tolist() == [mind.forbidden("trash", j) for j in idx]


@pytest.mark.parametrize("bad", ["-1", "abc", "inf", "nan"])
def test_a_bad_window_width_is_refused_with_its_value(ctx: AppContext, bad: str) -> None:
    with pytest.raises(Exception, match=f"decide.window must be a number of nats of at least 0, got '{bad}'"):
        admin.config_set(ctx, "decide.window", bad)
    assert admin.config_get(ctx)["decide.window"] == 2.0
