"""Protocols of Tables 1-3 and the runner: seeds, determinism whatever the job count, aggregation."""

from __future__ import annotations

import numpy as np
import pytest

from ownctl.errors import BadValue, UnknownName
from ownctl.experiment.norms import NORM_CONDITIONS, norms_result
from ownctl.experiment.online import TASK_CONDITIONS, task_trial
from ownctl.experiment.ownership import OWNERSHIP_CONDITIONS, ownership_trial, protocol
from ownctl.experiment.runner import run_experiment
from ownctl.world.generator import paper_blocks_world


def numbers(result, conditions=None) -> list[float]:
    out = []
    for c in result.conditions if conditions is None else conditions:
        for g in c.groups.values():
            for r in (*g.rows, g.average):
                out += [cell.mean for cell in r.cells.values()] + [cell.ci95 for cell in r.cells.values()]
        out += [cell.mean for cell in c.counts.values()]
    return out


def test_table2_conditions_agree_on_the_held_out_half_by_construction() -> None:
    # inference only touches objects with permissions and prediction learns from claims alone, so
    # the three conditions give the same held-out ownership for the same world (reference 7.4)
    for t in range(3):
        held_out = []
        for cond in (c for c in OWNERSHIP_CONDITIONS if c.claims == "all"):
            res = ownership_trial(paper_blocks_world, cond, "ours", np.random.default_rng([5, t]))
            held_out.append([s.as_array() for s in res.groups["test"].values()])
        assert np.array_equal(held_out[0], held_out[1]) and np.array_equal(held_out[0], held_out[2])


def test_table2_claimed_objects_are_known_exactly() -> None:
    res = ownership_trial(paper_blocks_world, OWNERSHIP_CONDITIONS[2], "ours", np.random.default_rng(3))
    test, every = res.groups["test"], res.groups["all"]
    for agent in test:  # all = half known exactly + the held-out half
        assert every[agent].accuracy == pytest.approx(0.5 + 0.5 * test[agent].accuracy)


def test_with_owners_claims_only_owners_say_that_s_mine() -> None:
    owners = next(c for c in OWNERSHIP_CONDITIONS if c.claims == "owners" and not c.inference)
    mind, world, test = protocol(paper_blocks_world, owners, "ours", np.random.default_rng(5))
    truth = world.true_ownership() >= 0.5
    claimed = ~np.isnan(mind.claims)
    train = np.setdiff1d(np.arange(len(world.objects)), test)
    assert claimed.sum() == truth[train].sum() > 0  # one claim per owner of a claimed object
    assert (truth[claimed]).all() and (mind.claims[claimed] == 1.0).all()
    assert not claimed[test].any()


def test_table1_baseline_and_full_permissions() -> None:
    base = norms_result(paper_blocks_world, NORM_CONDITIONS[-1], "ours", np.random.default_rng(0))
    assert all(s.f1 == 0.0 for s in base.groups["rules"].values())
    full = norms_result(paper_blocks_world, NORM_CONDITIONS[0], "ours", np.random.default_rng(0))
    assert all(s.accuracy == 1.0 for s in full.groups["rules"].values())


def test_table3_trial_reports_counts_and_both_rule_averages() -> None:
    res = task_trial(paper_blocks_world, TASK_CONDITIONS[1], "ours", np.random.default_rng(4))
    assert set(res.groups) == {"rules", "rules_all", "ownership"}
    assert list(res.groups["rules"]) == ["pickUp", "trash"]
    assert set(res.groups["rules_all"]) == {"trash", "pickUp", "collect"}
    assert res.counts["delivered"] + res.counts["skipped"] <= 20
    assert res.counts["violations"] == 0 and res.counts["mistakes"] >= 1


@pytest.mark.slow
def test_results_do_not_depend_on_the_number_of_jobs() -> None:
    one = run_experiment("task", 3, 11, 1, paper_blocks_world, "ours")
    two = run_experiment("task", 3, 11, 2, paper_blocks_world, "ours")
    assert numbers(one) == numbers(two)
    other = run_experiment("task", 3, 12, 1, paper_blocks_world, "ours")
    assert numbers(one) != numbers(other)


def test_a_condition_alone_gives_the_same_numbers_as_within_all() -> None:
    both = run_experiment("task", 2, 5, 1, paper_blocks_world, "paper")
    alone = run_experiment("task", 2, 5, 1, paper_blocks_world, "paper", conditions=["trashAll"])
    assert [c.name for c in alone.conditions] == ["trashAll"]
    assert numbers(alone) == numbers(both, both.conditions[1:])


def test_progress_and_aggregation() -> None:
    calls: list[tuple[int, int]] = []
    res = run_experiment("ownership", 4, 0, 1, paper_blocks_world, "ours",
                         progress=lambda d, t: calls.append((d, t)))
    assert calls[0] == (0, 12) and calls[-1] == (12, 12)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)
    cond = res.conditions[0]
    rows = cond.groups["test"].rows
    assert [r.name for r in rows] == ["agent1", "agent2", "agent3"]
    mean_of_rows = np.mean([r["accuracy"].mean for r in rows])
    assert cond.accuracy.mean == pytest.approx(mean_of_rows)
    assert cond.accuracy.ci95 >= 0
    doc = res.as_dict()
    assert doc["experiment"] == "ownership" and doc["trials"] == 4 and doc["seed"] == 0
    first = doc["conditions"][0]
    assert set(first) >= {"name", "accuracy", "f1", "ci95", "paper"}
    assert first["paper"] == {"accuracy": 0.904, "f1": 0.757}
    assert doc["seconds"] > 0


def test_bad_settings_are_user_errors() -> None:
    with pytest.raises(BadValue):
        run_experiment("norms", 0, 0, 1, paper_blocks_world, "ours")
    with pytest.raises(BadValue):
        run_experiment("norms", 1, 0, 0, paper_blocks_world, "ours")
    with pytest.raises(UnknownName, match="ours, paper"):
        run_experiment("norms", 1, 0, 1, paper_blocks_world, "foil")
    with pytest.raises(UnknownName, match="norms, ownership, task"):
        run_experiment("tables", 1, 0, 1, paper_blocks_world, "ours")
    with pytest.raises(UnknownName, match="map, posterior"):
        run_experiment("norms", 1, 0, 1, paper_blocks_world, "ours", decide="mode")


def test_posterior_decisions_score_the_marginal_over_rule_sets() -> None:
    """``decide="posterior"`` scores each action's decisions on P(forbidden) marginalised over the
    rule-set posterior of the very Mind the trial taught, on the objects' true owners: recomputed here."""
    from ownctl.config import LearnConfig, Settings
    from ownctl.experiment.metrics import rule_scores
    from ownctl.experiment.norms import norms_setup, norms_trial
    from ownctl.mind import Mind, Switches

    cond = NORM_CONDITIONS[5]  # noisy, a quarter of the objects: the rule sets are uncertain
    got = norms_trial(paper_blocks_world, cond, "ours", np.random.default_rng(3), "posterior")
    setup = norms_setup(paper_blocks_world, cond, np.random.default_rng(3))
    mind = Mind(setup.world.agents, list(setup.world.objects), setup.world.areas,
                Settings(learn=LearnConfig()), Switches(inference=False, prediction=False))
    mind.claims[:] = setup.claims
    for obj in setup.chosen:
        for action in setup.rules:
            mind.permit(action, int(obj), float(setup.answers[action][obj]))
    uncertain = 0
    for action in setup.rules:
        p = mind.rule_posterior(action).p_forbidden(setup.true_frame)
        uncertain += int(((p > 0.01) & (p < 0.99)).any())
        assert got[action] == rule_scores(setup.answers[action], (p >= 0.5).astype(float))
    assert uncertain  # the marginal is not a single rule set's 0/1 on this trial


def test_rules_are_scored_on_the_decisions_they_make() -> None:
    """Exactly 0.5 is a refusal (the threshold is reached): right where the action is forbidden,
    wrong where it is allowed, unlike the paper's measure, which counts it right either way."""
    from ownctl.experiment.metrics import decision_scores, rule_scores

    actual = np.array([1.0, 0.0, 0.0, 1.0])
    p = np.array([0.5, 0.5, 0.2, 0.9])
    assert rule_scores(actual, p).accuracy == 1.0
    assert decision_scores(actual, p).accuracy == 0.75
    assert decision_scores(actual, p, threshold=0.6).accuracy == 0.75  # 0.5 allowed: the first wrong
    assert decision_scores(actual, np.array([1.0, 0.0, 0.0, 1.0])) == rule_scores(actual, actual)
