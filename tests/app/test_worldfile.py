"""World files: validation (pure), load into a store, export, and the round trip."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from ownctl.app import query, worldfile
from ownctl.app.context import AppContext
from ownctl.errors import BadName, BadValue, RuleSyntaxError
from ownctl.world.spec import to_toml, world_from_dict, world_to_dict

WORLD = """\
name = "kitchen"
agents = ["alexis", "xuan"]
norms = ["forbid trash if ownedBy any", "forbid pickUp if not isColored red and ownedBy xuan"]

[[areas]]
name = "home"
box = [-0.1, -0.1, 0.1, 0.1]

[[objects]]
name = "wallet"
color = "brown"
position = [0.3, 0.1, 0.0]
categories = ["personal"]
owners = { alexis = 1.0 }
last_touch = { alexis = 5.0, xuan = 250.0 }

[[objects]]
name = "mug"
position = [0.05, 0.0]

[[steps]]
say = "No Baxter, that's mine!"
as = "alexis"
"""


def _ctx(tmp_path: Path, now: float = 1000.0) -> AppContext:
    ctx = AppContext(str(tmp_path / "w.db"), now)
    ctx.store(create=True)
    return ctx


def test_world_from_dict_validates_and_canonicalises() -> None:
    world = world_from_dict(tomllib.loads(WORLD), "w.toml")
    assert world.agents == ("alexis", "xuan")
    assert world.norms[1] == "forbid pickUp if ownedBy xuan and not isColored red"
    assert world.object("mug").position == (0.05, 0.0, 0.0)
    assert world.owners == {"wallet": {"alexis": 1.0}}


@pytest.mark.parametrize(
    ("patch", "error", "words"),
    [
        ({"colour": 1}, BadValue, ["unknown key 'colour'", "agents"]),
        ({"agents": ["a b"]}, BadName, ["w.toml", "invalid agent name"]),
        ({"norms": ["forbid thrash"]}, RuleSyntaxError, ["w.toml", "unknown action"]),
        ({"norms": ["forbid trash if ownedBy bob"]}, BadValue, ["unknown agent 'bob'"]),
        ({"norms": ["allow trash if isColored red"]}, BadValue, ["is an allow norm", "forbid rules"]),
        ({"areas": [{"name": "a", "box": [1, 1, 0, 0]}]}, BadValue, ["x0 <= x1"]),
        ({"areas": [{"name": "a", "box": [0, 0, 1]}]}, BadValue, ["4 finite numbers"]),
        ({"objects": [{"name": "o", "owners": {"bob": 1.0}}]}, BadValue, ["unknown key 'bob'"]),
        ({"objects": [{"name": "o", "owners": {"alexis": 2.0}}]}, BadValue, ["[0, 1]"]),
        ({"objects": [{"name": "o", "last_touch": {"alexis": -1}}]}, BadValue, ["last_touch"]),
        ({"objects": [{"name": "o", "position": [0, float("nan"), 0]}]}, BadValue, ["finite"]),
        ({"objects": [{"name": "o"}, {"name": "o"}]}, BadValue, ["listed twice"]),
        ({"objects": [{"name": "o", "size": 3}]}, BadValue, ["'size'", "categories"]),
        ({"generator": {"kind": "mystery"}}, BadValue, ["w.toml", "[generator]", "paper-blocks, scattered"]),
        ({"generator": {"kind": "scattered", "owner_age": 0}}, BadValue, ["owner_age", "(0, 1000000]"]),
        ({"generator": {"kind": "scattered", "owner_age": True}}, BadValue, ["owner_age"]),
        ({"generator": {"owner_age": 10}}, BadValue, ["'owner_age' is for kind 'scattered'"]),
    ],
)
def test_bad_world_files(patch: dict, error: type, words: list[str]) -> None:
    data = {"agents": ["alexis"], **patch}
    with pytest.raises(error) as info:
        world_from_dict(data, "w.toml")
    for word in words:
        assert word in str(info.value)


def test_a_scattered_world_says_nothing_of_owners_by_place_or_colour() -> None:
    """Owners are drawn apart from everything else: over many objects, every agent's and nobody's
    objects are spread alike (mean position and colour shares agree within sampling error), and
    by default the owner touched them as long ago as anyone; with ``owner_age`` much more recently."""
    data = {"generator": {"kind": "scattered", "objects": 4000}}
    world = world_from_dict(data, "s.toml", np.random.default_rng(5))
    assert world_from_dict(data, "s.toml", np.random.default_rng(5)) == world
    owner = [next(iter(world.owners.get(o.name, {})), None) for o in world.objects]
    xy = np.array([o.position[:2] for o in world.objects if o.position is not None])
    for who in (*world.agents, None):
        mine = np.array([w == who for w in owner])
        assert 0.2 < mine.mean() < 0.3  # a quarter each: three agents and nobody
        assert np.all(np.abs(xy[mine].mean(axis=0) - xy.mean(axis=0)) < 0.05)
        reds = np.mean([o.color == "red" for o, m in zip(world.objects, mine, strict=True) if m])
        assert 0.2 < reds < 0.3
    mine_age = np.mean([o.last_touch[w] for o, w in zip(world.objects, owner, strict=True) if w])
    assert 900 < mine_age < 1100
    touched = world_from_dict({"generator": {"kind": "scattered", "objects": 400, "owner_age": 10}},
                              "s.toml", np.random.default_rng(5))
    owned = [(o, next(iter(touched.owners[o.name]))) for o in touched.objects if touched.owners.get(o.name)]
    assert np.mean([o.last_touch[w] for o, w in owned]) < 20


def test_generator_section_draws_the_paper_world() -> None:
    data = {"generator": {"kind": "paper-blocks", "objects": 8}, "objects": [{"name": "wallet"}]}
    world = world_from_dict(data, "g.toml", np.random.default_rng(3))
    assert world.agents == ("agent1", "agent2", "agent3")
    assert len(world.objects) == 9 and "forbid trash if ownedBy any" in world.norms
    again = world_from_dict(data, "g.toml", np.random.default_rng(3))
    assert again == world


def test_load_turns_ages_into_absolute_times_and_keeps_truth_apart(tmp_path: Path) -> None:
    path = tmp_path / "kitchen.toml"
    path.write_text(WORLD)
    ctx = _ctx(tmp_path)
    done = worldfile.load(ctx, str(path))
    assert done.data == {"world": "kitchen", "agents": 2, "areas": 1, "objects": 2, "norms": 2}
    with ctx.read() as tx:
        touches = {(o, a): t for (o, a), t in tx.touches.pairs().items()}
        assert sorted(touches.values()) == [750.0, 995.0]
        assert tx.knowledge.truth_norms()[0] == "forbid trash if ownedBy any"
        assert tx.knowledge.rules() == []  # true norms are not beliefs
    owners = query.owners(ctx, "wallet")["owners"]  # nor are true owners: only the calibrated prior
    assert all(o["claim"] is None and o["source"] == "base-rate" and o["p"] < 0.5 for o in owners)
    ctx.close()


def test_export_round_trips(tmp_path: Path) -> None:
    path = tmp_path / "kitchen.toml"
    path.write_text(WORLD)
    first = _ctx(tmp_path / "a")
    worldfile.load(first, str(path))
    text = worldfile.export_toml(worldfile.export(first, "kitchen"))
    again = tmp_path / "again.toml"
    again.write_text(text)
    second = _ctx(tmp_path / "b")
    worldfile.load(second, str(again))
    assert worldfile.current_world(second, "kitchen") == worldfile.current_world(first, "kitchen")
    assert world_from_dict(tomllib.loads(text), "again.toml") == worldfile.current_world(first, "kitchen")
    first.close()
    second.close()


def test_to_toml_parses_back() -> None:
    world = world_from_dict(tomllib.loads(WORLD), "w.toml")
    data = world_to_dict(world)
    assert tomllib.loads(to_toml(data)) == data


def test_loading_twice_is_refused_whole(tmp_path: Path) -> None:
    path = tmp_path / "kitchen.toml"
    path.write_text(WORLD)
    ctx = _ctx(tmp_path)
    worldfile.load(ctx, str(path))
    with pytest.raises(Exception, match="already exists"):
        worldfile.load(ctx, str(path))
    assert len(worldfile.export(ctx)["objects"]) == 2
    ctx.close()
