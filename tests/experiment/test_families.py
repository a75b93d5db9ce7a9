"""Norm families (``ownctl.world.families``): the generator's laws, and Table 1 run over families."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from ownctl.cli.main import app as ownctl_app
from ownctl.errors import BadValue
from ownctl.experiment.norms import NORM_CONDITIONS, norms_trial
from ownctl.experiment.runner import run_experiment
from ownctl.logic.rules import parse_rule
from ownctl.world.families import (
    EVALUATION_SEEDS,
    FAMILY_ACTIONS,
    FEATURES,
    forbidden_count,
    norm_families,
    norm_family,
)
from ownctl.world.generator import paper_blocks_world
from ownctl.world.spec import world_from_dict, world_to_dict

QUICK = range(0, 25)


@pytest.mark.slow
def test_a_family_is_a_pure_function_of_its_seed() -> None:
    assert norm_family(7) == norm_family(7)
    assert len({norm_family(s).norms for s in QUICK}) > 20
    with pytest.raises(BadValue, match="non-negative integer"):
        norm_family(-1)


@pytest.mark.slow
@pytest.mark.parametrize("seeds", [range(0, 100), EVALUATION_SEEDS], ids=["tuning", "evaluation"])
def test_every_feature_has_its_minimum_share_in_every_window_of_five(seeds: range) -> None:
    feats = {s: norm_family(s).features() for s in seeds}
    for start in range(seeds.start, seeds.stop - 4):
        window = [feats[s] for s in range(start, start + 5)]
        for f in FEATURES:
            assert sum(f in fs for fs in window) >= 1, (f, start)
    for f in FEATURES:
        assert sum(f in fs for fs in feats.values()) >= len(seeds) / 5, f


def test_features_are_forced_on_a_cycle_of_five() -> None:
    feats = [norm_family(s).features() for s in range(10)]
    for f in FEATURES:
        assert sum(f in fs for fs in feats) >= 2, f


@pytest.mark.parametrize("seed", list(QUICK))
def test_every_family_loads_and_its_norms_parse(seed: int) -> None:
    family = norm_family(seed)
    assert family.norms and family.actions == FAMILY_ACTIONS
    rules = family.rules()
    for text in family.norms:
        rule = parse_rule(text)
        assert rule.text() == text and rule.is_satisfiable() and rule.simplified() == rule
        assert 1 <= len(rule.literals) <= 3
    assert all(len(rs) <= 3 for rs in rules.values())
    world = family(np.random.default_rng(seed))
    loaded = world_from_dict(world_to_dict(world), f"family {seed}")
    assert loaded.norms == family.norms and len(loaded.objects) == 20
    assert np.array_equal(loaded.true_ownership(), world.true_ownership())


def test_a_rare_norm_forbids_one_or_two_objects_of_every_world() -> None:
    rare = [f for f in (norm_family(s) for s in range(1, 40, 5)) if f.rare]
    assert rare
    for family in rare:
        rules = family.rules()
        rng = np.random.default_rng(family.seed)
        for _ in range(10):
            world = family(rng)
            for action in family.rare:
                assert len(rules[action]) == 1
                assert 1 <= forbidden_count(rules[action], world) <= 2


def _home_owners(world) -> list[float]:
    from ownctl.world.model import positions

    home = next(a for a in world.areas if a.name == "home")
    inside = home.contains(positions(world.objects)[:, :2])
    own = world.true_ownership()
    return [own[i].sum() for i in np.flatnonzero(inside)]


def test_an_owned_home_layout_puts_one_agents_objects_in_the_home_area() -> None:
    family = next(norm_family(s) for s in range(4, 40, 5))
    assert family.home_agent is not None
    j = family.agents.index(family.home_agent)
    rng = np.random.default_rng(0)
    inside = []
    for _ in range(20):
        world = family(rng)
        own = world.true_ownership()
        from ownctl.world.model import positions

        home = next(a for a in world.areas if a.name == "home")
        idx = np.flatnonzero(home.contains(positions(world.objects)[:, :2]))
        inside += [bool(own[i, j]) for i in idx]
    assert inside and np.mean(inside) > 0.9
    paper = [_home_owners(paper_blocks_world(np.random.default_rng(s))) for s in range(20)]
    assert np.mean([v == 0 for vs in paper for v in vs]) > 0.9  # the paper's layout: unowned at home


def test_the_default_home_cluster_is_the_papers_layout() -> None:
    a = paper_blocks_world(np.random.default_rng(3))
    b = paper_blocks_world(np.random.default_rng(3), home_cluster=0)
    assert a == b
    c = paper_blocks_world(np.random.default_rng(3), home_cluster=2)
    assert [o.color for o in a.objects] == [o.color for o in c.objects]
    with pytest.raises(BadValue, match="home_cluster"):
        paper_blocks_world(np.random.default_rng(3), home_cluster=4)


def test_actions_without_a_norm_are_given_permissions_and_scored() -> None:
    family = next(f for f in (norm_family(s) for s in range(2, 40, 5)) if "no_norm" in f.features())
    empty = [a for a, rs in family.rules().items() if not rs]
    scores = norms_trial(family, NORM_CONDITIONS[0], "ours", np.random.default_rng(1))
    assert set(scores) == set(FAMILY_ACTIONS)
    for action in empty:  # nothing is forbidden, nothing was learned: a perfect score, F1 1 by convention
        assert scores[action].accuracy == 1.0 and scores[action].f1 == 1.0
    base = norms_trial(family, NORM_CONDITIONS[-1], "ours", np.random.default_rng(1))
    assert all(base[a].f1 == 1.0 for a in empty)


def test_a_run_over_families_reports_the_mean_over_families_and_the_worst() -> None:
    fams = norm_families(3, first=0)
    res = run_experiment("norms", 2, 0, 1, paper_blocks_world, "ours", conditions=["noiseless 0.25"],
                         families=fams)
    (cond,) = res.conditions
    assert cond.trials == 3 and res.trials == 2
    per_family = [d["conditions"]["noiseless 0.25"] for d in res.extra["families"]]
    assert cond.accuracy.mean == pytest.approx(np.mean([d["accuracy"] for d in per_family]))
    seed, worst = cond.worst["accuracy"]
    assert worst == pytest.approx(min(d["accuracy"] for d in per_family))
    assert res.extra["families"][seed]["conditions"]["noiseless 0.25"]["accuracy"] == worst
    doc = res.as_dict()
    assert doc["conditions"][0]["worst_family"]["accuracy"]["seed"] == seed
    assert not doc["paper_comparable"] and doc["families"][0]["norms"] == list(fams[0].norms)
    again = run_experiment("norms", 2, 0, 2, paper_blocks_world, "ours", conditions=["noiseless 0.25"],
                           families=fams)
    assert again.as_dict()["families"] == doc["families"]  # whatever the number of jobs


@pytest.mark.slow
def test_families_on_the_command_line(tmp_path) -> None:
    runner = CliRunner()
    png = tmp_path / "f.png"
    res = runner.invoke(ownctl_app, ["experiment", "norms", "--families", "2", "--family-seed", "5",
                                     "--trials", "1", "--json", "--plot", str(png)])
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    assert [f["seed"] for f in doc["families"]] == [5, 6]
    assert all("worst_family" in c for c in doc["conditions"])
    assert png.read_bytes()[:4] == b"\x89PNG"
    text = runner.invoke(ownctl_app, ["experiment", "norms", "--families", "1", "--trials", "1"])
    assert text.exit_code == 0 and "worst acc" in text.stdout and "(1000)" in text.stdout
    for args, message in ((["norms", "--family-seed", "3"], "--family-seed needs --families"),
                          (["norms", "--families", "0"], "--families must be an integer from 1 to 10,000"),
                          (["norms", "--families", "1", "--world", "w.toml"], "exclude each other")):
        bad = runner.invoke(ownctl_app, ["experiment", *args])
        assert bad.exit_code == 1 and message in bad.stderr


def test_a_quick_generalisation_run_on_tuning_families() -> None:
    """On a few tuning families: with every permission and exact ownership ours is exact in every
    family (one-shot learning of rare norms included); with noisy ownership it is well above
    allowing everything on average."""
    fams = norm_families(4, first=0)
    res = run_experiment("norms", 2, 0, 1, paper_blocks_world, "ours",
                         conditions=["noiseless 1.00", "noisy 1.00", "allow everything"], families=fams)
    exact_, noisy, allow = res.conditions
    assert exact_.worst["accuracy"][1] == 1.0 and exact_.worst["f1"][1] == 1.0
    assert noisy.accuracy.mean > allow.accuracy.mean + 0.1
