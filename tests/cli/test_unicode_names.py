"""Names in any script (docs/architecture.md, section 2): stored composed, found however they are
typed, understood in sentences, and exported and loaded back unchanged."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl

JOSE = "Jos\u00e9"
JOSE_TYPED = "Jose\u0301"  # the same name with a combining accent
RAM = "\u0930\u093e\u092e"  # Devanagari: a vowel sign (a combining mark) inside the word
DIMA = "\u0414\u0438\u043c\u0430"
CUP = "ta\u0301za"  # typed with a combining accent, stored as "táza"


def _world(store: Ownctl) -> None:
    for agent in (JOSE_TYPED, RAM, DIMA):
        store("agent", "add", agent)
    store("object", "add", CUP, "--color", "gr\u00fcn", "--pos", "0.1,0.1")
    store("object", "add", "kap", "--color", "red", "--pos", "0.3,0.1")


def test_a_name_typed_decomposed_is_stored_composed_and_found_either_way(ownctl: Ownctl) -> None:
    _world(ownctl)
    assert {a["name"] for a in ownctl.json("agent", "list")} == {JOSE, RAM, DIMA}
    assert "t\u00e1za" in {o["name"] for o in ownctl.json("object", "list")}
    ownctl("claim", CUP, JOSE)  # composed object, decomposed at creation
    ownctl("claim", "kap", JOSE_TYPED)  # decomposed agent, composed in the store
    owners = ownctl.json("owners", "t\u00e1za")["owners"]
    assert owners[0] == {**owners[0], "agent": JOSE, "p": 1.0, "source": "claim"}


def test_sentences_name_people_and_things_in_their_scripts(ownctl: Ownctl) -> None:
    _world(ownctl)
    said = ownctl.json("say", "kap is mine", "--as", RAM)
    assert said["instructions"] == [f"claim kap {RAM}"]
    said = ownctl.json("say", f"Don't throw away {RAM}'s things", "--as", DIMA)
    assert said["instructions"] == [f"forbid trash if ownedBy {RAM}"]
    said = ownctl.json("say", "You may not pick up anything gr\u00fcn", "--as", JOSE_TYPED)
    assert said["instructions"] == ["forbid pickUp if isColored gr\u00fcn"]
    assert ownctl("check", "trash", "kap", code=3).exit_code == 3
    assert ownctl("check", "pickUp", "t\u00e1za", code=3).exit_code == 3
    assert ownctl.json("log", "-n", "1")[0]["actor"] == JOSE  # the speaker composed too


def test_a_mixed_script_name_is_refused_and_nothing_is_written(ownctl: Ownctl) -> None:
    before = ownctl.digest()
    result = ownctl("agent", "add", "\u0430gent", code=1)
    assert result.stderr.count("\n") == 1 and "it mixes Cyrillic, Latin" in result.stderr
    assert ownctl.digest() == before


def test_export_keeps_the_names_readable_and_loads_back(ownctl: Ownctl, tmp_path: Path) -> None:
    _world(ownctl)
    ownctl("claim", "kap", RAM)
    text = ownctl("world", "export").stdout
    assert RAM in text and "\\u" not in text  # the names as written, not escaped
    exported = tomllib.loads(text)
    assert set(exported["agents"]) == {JOSE, RAM, DIMA}
    path = tmp_path / "again.toml"
    path.write_text(text, encoding="utf-8")
    other = tmp_path / "other.db"
    from tests.cli.conftest import Ownctl as Store

    again = Store(other)
    again("init")
    again("world", "load", str(path))
    assert tomllib.loads(again("world", "export").stdout) == exported
