"""``world load`` and ``world export`` through the CLI."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

from tests.cli.conftest import Ownctl

WORLD = """\
name = "desk"
agents = ["alexis", "xuan"]
norms = ["forbid trash if ownedBy any"]

[[areas]]
name = "home"
box = [-0.1, -0.1, 0.1, 0.1]

[[objects]]
name = "wallet"
color = "brown"
position = [0.3, 0.1, 0.0]
owners = { alexis = 1.0 }
last_touch = { alexis = 5.0 }

[[steps]]
command = "forbid trash on wallet"
"""


def test_load_then_export(ownctl: Ownctl, tmp_path: Path) -> None:
    path = tmp_path / "desk.toml"
    path.write_text(WORLD)
    assert ownctl.json("world", "load", str(path))["objects"] == 1
    assert ownctl.json("object", "list")[0]["last_touch"] == {"alexis": 995.0}
    exported = tomllib.loads(ownctl("world", "export", "--name", "desk").stdout)
    assert exported["objects"][0]["last_touch"] == {"alexis": 5.0}
    assert exported["norms"] == ["forbid trash if ownedBy any"]
    as_json = json.loads(ownctl("world", "export", "--json", "--name", "desk").stdout)
    assert as_json == exported
    out = tmp_path / "out.toml"
    ownctl("world", "export", "-o", str(out), "--name", "desk")
    assert tomllib.loads(out.read_text()) == exported


def test_export_writes_back_the_name_the_world_was_loaded_with(ownctl: Ownctl, tmp_path: Path) -> None:
    path = tmp_path / "desk.toml"
    path.write_text(WORLD)
    ownctl("world", "load", str(path))
    exported = tomllib.loads(ownctl("world", "export").stdout)
    assert exported["name"] == "desk"
    assert json.loads(ownctl("world", "export", "--json").stdout)["name"] == "desk"
    assert tomllib.loads(ownctl("world", "export", "--name", "study").stdout)["name"] == "study"
    other = tmp_path / "other.toml"  # a later file adds to the named world, it does not rename it
    other.write_text('name = "garage"\nagents = ["alexis"]\n[[objects]]\nname = "drill"\n')
    ownctl("world", "load", str(other))
    assert tomllib.loads(ownctl("world", "export").stdout)["name"] == "desk"
    out = tmp_path / "out.toml"
    ownctl("world", "export", "-o", str(out))
    again = Ownctl(tmp_path / "again.db")
    again("init")
    assert again.json("world", "load", str(out))["world"] == "desk"
    assert tomllib.loads(again("world", "export").stdout) == tomllib.loads(out.read_text())


def test_generated_world(ownctl: Ownctl, tmp_path: Path) -> None:
    path = tmp_path / "blocks.toml"
    path.write_text('[generator]\nkind = "paper-blocks"\nobjects = 20\n')
    assert ownctl.json("world", "load", str(path), "--seed", "7") == {
        "world": "paper blocks world",
        "agents": 3,
        "areas": 3,
        "objects": 20,
        "norms": 3,
    }
    assert len(ownctl.json("object", "list")) == 20
