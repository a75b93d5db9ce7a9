"""Bad input: one clear line on stderr, exit 1 (2 for usage errors), ``{"error", "valid"}`` with --json,
and the store file byte-for-byte unchanged."""

from __future__ import annotations

import json
import shlex
from pathlib import Path
from typing import TYPE_CHECKING

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from ownctl.logic.names import RESERVED, composed, is_name
from ownctl.world.spec import OBJECT_KEYS
from tests.cli.conftest import TABLE_WORLD, Result, build_template, from_template, invoke

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl

HOSTILE = ["x'; DROP TABLE agents;--", 'quo"te', "bell\x07", "new\nline", "two words", "9lives", "", "a" * 65]

USER_ERRORS: list[tuple[str, ...]] = [
    *(("agent", "add", name) for name in HOSTILE),
    ("agent", "add", "any"),
    ("agent", "add", "alexis"),
    ("agent", "remove", "ghost"),
    ("agent", "remove", "xuan"),  # a rule names xuan
    ("object", "add", "wallet"),
    ("object", "add", "cup", "--pos", "1,2,x"),
    ("object", "add", "cup", "--pos", "nan,0,0"),
    ("object", "add", "cup", "--pos", "1,2,3,4"),
    ("object", "add", "cup", "--color", "re d"),
    ("object", "add", "cup", "--category", "DROP TABLE"),
    ("object", "set", "ghost", "--color", "red"),
    ("object", "set", "wallet"),
    ("object", "show", "ghost"),
    ("object", "remove", "ghost"),
    ("object", "touch", "wallet", "--by", "ghost"),
    ("object", "touch", "wallet", "--by", "alexis", "--at", "nan"),
    ("area", "add", "desk", "--box", "0,0,1,1"),
    ("area", "add", "flipped", "--box", "1,1,0,0"),
    ("area", "add", "short", "--box", "0,0,1"),
    ("claim", "ghost", "alexis"),
    ("claim", "wallet", "ghost"),
    ("claim", "wallet", "alexis", "--p", "1.5"),
    ("claim", "wallet", "alexis", "--p", "-0.1"),
    ("claim", "wallet", "alexis", "--p", "nan"),
    ("claim", "wallet", "alexis", "--only", "--not"),
    ("forbid", "thrash", "on", "wallet"),
    ("forbid", "trash", "on", "ghost"),
    ("forbid", "trash", "on"),
    ("forbid", "trash", "on", "wallet", "mug"),
    ("forbid", "trash", "on", "wallet", "--p", "2"),
    ("forbid", "trash", "wallet"),
    ("forbid", "trash", "if"),
    ("forbid", "trash", "if", "ownedBy", "ghost"),
    ("forbid", "trash", "if", "inArea", "nowhere"),
    ("forbid", "trash", "if", "isColored"),
    ("forbid", "trash", "if", "isBig", "yes"),
    ("forbid", "trash", "if", "ownedBy", "any", "or", "isColored", "red"),
    ("forbid", "trash", "if", "isColored", "red", "and", "not", "isColored", "red"),
    ("allow", "trash", "if", "ownedBy", "ghost"),
    ("check", "thrash", "wallet"),
    ("check", "trash", "ghost"),
    ("owners", "ghost"),
    ("owners", "--agent", "ghost"),
    ("owners", "--agent", "alexis", "--min", "2"),
    ("rules", "remove", "99"),
    ("perms", "remove", "99"),
    ("config", "set", "threshold", "1.5"),
    ("config", "set", "threshold", "nan"),
    ("config", "set", "threshold.thrash", "0.5"),
    ("config", "set", "nope", "1"),
    ("config", "set", "frozen.perms", "maybe"),
    ("config", "get", "nope"),
    ("reset", "perms"),
    ("log", "--limit", "0"),
    ("world", "load", "missing.toml"),
    ("run", "trashAll", "--kinematic"),  # no 'trash' area: the live table goes, the error stays one line
    ("run", "collectAll", "--kinematic", "--ask", "2"),
]

USAGE_ERRORS: list[tuple[str, ...]] = [
    ("claim", "wallet"),
    ("frobnicate",),
    ("reset", "nothing", "--yes"),
    ("freeze", "claims"),
    ("check", "trash", "wallet", "--bogus"),
    ("owners",),
    ("rules", "remove", "one"),
    ("claim", "wallet", "alexis", "--p", "0x1"),
    ("world", "load", "x.toml", "--seed", "abc"),
    ("log", "--limit", "1.5"),
    ("object",),
    (),
    ("explain", "trash"),
]


@pytest.fixture(scope="module")
def _world_store(tmp_path_factory: pytest.TempPathFactory) -> bytes:
    extra = [("forbid", "pickUp", "if", "ownedBy", "xuan"), ("forbid", "trash", "on", "wallet")]
    return build_template(tmp_path_factory, [*TABLE_WORLD, *extra])


@pytest.fixture
def world(tmp_path: Path, _world_store: bytes) -> Ownctl:
    """The table world with a rule naming xuan and a permission."""
    return from_template(tmp_path / "store.db", _world_store)


@pytest.mark.parametrize("args", USER_ERRORS, ids=lambda a: " ".join(a)[:40])
def test_user_error_is_one_line_exit_1_and_writes_nothing(world: Ownctl, args: tuple[str, ...]) -> None:
    before = world.digest()
    result = world(*args, code=1)
    assert result.stdout == ""
    assert result.stderr.startswith("ownctl: ") and result.stderr.count("\n") == 1, result.stderr
    assert world.digest() == before
    as_json = world(*args, "--json", code=1)
    error = json.loads(as_json.stdout)
    assert set(error) == {"error", "valid"} and error["error"]
    assert world.digest() == before


def test_hostile_names_are_refused_with_the_rule(world: Ownctl) -> None:
    result = world("agent", "add", "x'; DROP TABLE agents;--", code=1)
    assert "a letter, then letters, marks, digits" in result.stderr
    assert [a["name"] for a in world.json("agent", "list")] == ["alexis", "xuan"]


def test_unknown_names_list_the_valid_ones(world: Ownctl) -> None:
    error = world.json("claim", "wallet", "ghost", code=1)
    assert error["valid"] == ["alexis", "xuan"] and "known agents: alexis, xuan" in error["error"]
    assert "trash" in world.json("check", "thrash", "wallet", code=1)["valid"]


def test_a_claim_with_agent_and_object_swapped_says_which_comes_first(world: Ownctl) -> None:
    before = world.digest()
    result = world("claim", "xuan", "wallet", code=1)
    assert result.stderr.strip().splitlines() == [
        "ownctl: 'xuan' is an agent and 'wallet' an object: the object comes first, ownctl claim wallet xuan"]
    assert world.digest() == before
    assert "unknown object 'xuan'" in world("claim", "xuan", "alexis", code=1).stderr  # no object to swap


def test_a_forgotten_on_is_named_with_both_forms(world: Ownctl) -> None:
    error = world.json("forbid", "trash", "wallet", code=1)
    assert error["valid"] == ["if", "on"] and "(one object: 'forbid trash on wallet')" in error["error"]
    assert "got 'mug'" in world.json("allow", "trash", "mug", "wallet", code=1)["error"]


@pytest.mark.parametrize("args", USAGE_ERRORS, ids=lambda a: " ".join(a) or "nothing")
def test_usage_error_is_one_line_exit_2_and_writes_nothing(world: Ownctl, args: tuple[str, ...]) -> None:
    before = world.digest()
    result = world(*args, code=2)
    assert result.stderr.startswith("ownctl: ") and result.stderr.count("\n") == 1, result.stderr
    assert result.stderr.rstrip().endswith("--help)")  # and says where the help is
    assert world.digest() == before
    as_json = world(*args, "--json", code=2)  # with --json, also the document on stdout
    error = json.loads(as_json.stdout)
    assert set(error) == {"error", "valid"} and as_json.stderr == f"ownctl: {error['error']}\n"


def test_a_bad_number_is_named_with_what_it_should_be(world: Ownctl) -> None:
    assert world("claim", "wallet", "alexis", "--p", "0x1", code=2).stderr == (
        "ownctl: invalid value for --p: '0x1' is not a number (see: ownctl claim --help)\n")
    assert "'abc' is not a whole number" in world("log", "-n", "abc", code=2).stderr
    assert "commands: add, set, list, show, remove, touch" in world("object", code=2).stderr


def test_bad_world_file_names_file_and_key(world: Ownctl, tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text('agents = ["a1"]\n[[objects]]\nname = "cup"\ncolour = "red"\n')
    before = world.digest()
    error = world.json("world", "load", str(bad), code=1)
    assert str(bad) in error["error"] and "'colour'" in error["error"] and "color" in error["valid"]
    assert world.digest() == before


def test_bad_clock_is_refused(world: Ownctl) -> None:
    before = world.digest()
    result = world("agent", "add", "bob", code=1, now="soon")
    assert "OWNCTL_NOW" in result.stderr
    assert world.digest() == before


def test_failing_batch_line_reports_its_number(world: Ownctl, tmp_path: Path) -> None:
    script = tmp_path / "bad.txt"
    script.write_text("# a comment\n\nclaim wallet ghost\nagent add bob\n")
    before = world.digest()
    result = world("batch", str(script), code=1)
    assert result.stderr.startswith(f"ownctl: {script}:3: unknown agent 'ghost'")
    assert result.stderr.count("\n") == 1
    assert world.digest() == before


# -- a generated battery: names, numbers, files, URLs and flags, on the command line, in batch and
# -- in scenario steps ---------------------------------------------------------------------------

# the command line is read in composed form (ownctl/cli/common.py): "²" is "2" there, and
# full-width "ａｌｅｘｉｓ" names alexis, so neither is bad input
def _not_a_float(text: str) -> bool:
    try:
        float(composed(text))
    except ValueError:
        return True
    return False


def _not_an_int(text: str) -> bool:
    try:
        int(composed(text))
    except ValueError:
        return True
    return False


# never an option (a leading "-" would be parsed as one, e.g. --help); NUL cannot be in an argument
_text = st.text(st.characters(exclude_characters="\x00"), max_size=80).filter(lambda s: not s.startswith("-"))
BAD_NAMES = st.one_of(
    _text.filter(lambda s: not is_name(composed(s))),
    st.sampled_from(sorted(RESERVED)),
    st.text(st.sampled_from("abcxyz_-09"), min_size=65, max_size=300).map(lambda s: "a" + s),
)
OUT_OF_RANGE = st.floats().filter(lambda x: not 0.0 <= x <= 1.0).map(repr)
NOT_FINITE = st.sampled_from(["nan", "inf", "-inf", "NaN", "Infinity", "-Infinity"])
NOT_NUMBERS = _text.filter(_not_a_float)
NOT_INTEGERS = _text.filter(_not_an_int)
FLAG = st.text(st.sampled_from("abcdefghijklmnopqrstuvwxyz-"), min_size=1, max_size=12).map(
    lambda s: "--x" + s)

V = "{}"  # where a template command line takes the bad value
NAME_COMMANDS = [
    ("agent", "add", V), ("object", "add", V), ("area", "add", V, "--box", "0,0,1,1"),
    ("claim", "wallet", V), ("claim", V, "alexis"), ("owners", V), ("agent", "remove", V),
    ("claim", "wallet", "alexis", "--as", V), ("forbid", "trash", "on", "wallet", "--as", V),
    ("forbid", "trash", "on", V), ("forbid", "pickUp", "if", "ownedBy", V),
    ("object", "touch", "wallet", "--by", V), ("check", V, "wallet"),
    ("say", "No, that's mine!", "--as", V, "--about", "wallet"),
]
NUMBER_COMMANDS = [
    ("claim", "wallet", "alexis", "--p", V), ("forbid", "trash", "on", "wallet", "--p", V),
    ("config", "set", "threshold", V), ("config", "set", "trust", V),
    ("owners", "--agent", "alexis", "--min", V),
]
COORDINATE_COMMANDS = [  # any finite number will do here
    ("object", "touch", "wallet", "--by", "alexis", "--at", V),
    ("object", "set", "wallet", "--pos", V + ",0,0"), ("area", "add", "box", "--box", "0,0," + V + ",1"),
]
INTEGER_COMMANDS = [
    ("log", "--limit", V), ("rules", "remove", V), ("perms", "remove", V),
    ("world", "load", "missing.toml", "--seed", V), ("run", "trashAll", "--seed", V),
]
FILE_COMMANDS = [("world", "load", V), ("batch", V), ("scenario", "play", V)]
FLAG_COMMANDS = [("agent", "list", V), ("claim", "wallet", "alexis", V), (V, "agent", "list"),
                 ("check", "trash", "wallet", V + "=1")]


@st.composite
def bad_files(draw: st.DrawFn, where: Path) -> str:
    """A path that is no good as a world, batch or scenario file (missing, a folder, bytes, not TOML)."""
    kind = draw(st.sampled_from(["missing", "folder", "bytes", "not toml", "bad key"]))
    path = where / f"f{draw(st.integers(0, 10**9))}-{kind.replace(' ', '-')}.toml"
    if path.exists() and path.is_dir() != (kind == "folder"):
        path = where / f"{path.stem}-{len(list(where.iterdir()))}.toml"  # drawn before as the other kind
    if kind == "folder":
        path.mkdir(exist_ok=True)
    elif kind == "bytes":
        path.write_bytes(b"\xff" + draw(st.binary(max_size=200)))
    elif kind == "not toml":
        path.write_text("= " + draw(_text), encoding="utf-8")
    elif kind == "bad key":
        key = draw(st.from_regex(r"[a-z]{1,12}", fullmatch=True).filter(lambda k: k not in OBJECT_KEYS))
        path.write_text(f'agents = ["a1"]\nnorms = ["forbid trash if ownedBy any"]\n'
                        f'[[objects]]\nname = "cup"\n{key} = 1\n[[steps]]\nsay = "hello"\n', encoding="utf-8")
    return str(path)


def bad_urls(where: Path) -> st.SearchStrategy[tuple[str, ...]]:
    """A global --db that names no usable store."""
    return st.one_of(
        st.from_regex(r"[a-z]{2,10}", fullmatch=True).map(lambda d: f"no{d}://user@host/db"),
        st.from_regex(r"[a-z]{1,10}", fullmatch=True).map(lambda n: f"sqlite:///{where}/missing/{n}.db"),
        st.sampled_from([f"sqlite:///{where}", "http://example.com/store", "sqlite://:memory:x",
                         f"{where}/missing/store.db"]),
    ).map(lambda url: ("--db", url, "agent", "list"))


def bad_args(where: Path) -> st.SearchStrategy[tuple[str, ...]]:
    """One bad command line (without the global --db)."""
    def each(templates: list[tuple[str, ...]], values: st.SearchStrategy[str]) -> st.SearchStrategy:
        return st.tuples(st.sampled_from(templates), values).filter(_still_bad).map(
            lambda tv: tuple(word.replace(V, tv[1]) for word in tv[0]))

    numbers = st.one_of(OUT_OF_RANGE, NOT_NUMBERS)
    return st.one_of(each(NAME_COMMANDS, BAD_NAMES), each(NUMBER_COMMANDS, numbers),
                     each(COORDINATE_COMMANDS, st.one_of(NOT_FINITE, NOT_NUMBERS)),
                     each(INTEGER_COMMANDS, NOT_INTEGERS), each(FILE_COMMANDS, bad_files(where)),
                     each(FLAG_COMMANDS, FLAG))


def _still_bad(template_value: tuple[tuple[str, ...], str]) -> bool:
    """A reserved word is a bad name except where the language gives it a meaning: ``ownedBy any``."""
    template, value = template_value
    return not (value == "any" and template[-2:] == ("ownedBy", V))


def _one_error_line(result: Result, prefix: str = "ownctl: ") -> None:
    assert result.exit_code in (1, 2), result
    assert result.stdout == "", result
    assert result.stderr.startswith(prefix) and result.stderr.count("\n") == 1, result.stderr
    assert "Traceback" not in result.stderr


@pytest.mark.slow
@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_a_battery_of_bad_input_is_one_line_and_writes_nothing(
    world: Ownctl, tmp_path: Path, data: st.DataObject
) -> None:
    files = tmp_path / "files"
    files.mkdir(exist_ok=True)
    args = data.draw(st.one_of(bad_args(files), bad_urls(files)), label="args")
    before = world.digest()
    _one_error_line(world(*args, code=None))
    assert world.digest() == before
    line = shlex.join(args)
    # the same line inside a batch (a batch line cannot name another store; standard input is
    # UTF-8, so it cannot carry the lone surrogates undecodable argv bytes become)
    if args[0] != "--db" and line.encode("utf-8", "surrogatepass").decode("utf-8", "replace") == line:
        result = world("batch", "-", input=line + "\n", code=None)
        first = "stdin:1: " if "\n" not in line and "\r" not in line else "stdin:"
        _one_error_line(result, prefix=f"ownctl: {first}")
        assert world.digest() == before


@pytest.mark.slow
@settings(max_examples=25, deadline=None)
@given(data=st.data())
def test_a_bad_command_step_fails_its_scenario_with_the_lines_one_error(
    tmp_path_factory: pytest.TempPathFactory, data: st.DataObject
) -> None:
    where = tmp_path_factory.mktemp("scenario")
    args = data.draw(bad_args(where).filter(lambda a: a[0] not in ("scenario", "batch")), label="args")
    scenario = where / "bad-step.toml"
    scenario.write_text('name = "bad step"\nagents = ["alexis"]\n[[objects]]\nname = "wallet"\n'
                        f"[[steps]]\ncommand = {json.dumps(shlex.join(args))}\n", encoding="utf-8")
    result = invoke(CliRunner(), ["scenario", "play", str(scenario), "--json"], None,
                    {"OWNCTL_DB": None, "OWNCTL_NOW": "1000"})
    if result.exit_code == 1:  # the step's words were refused when the scenario was read
        _one_error_line(Result("", result.stderr, 1), prefix=f"ownctl: {scenario}: ")
        return
    assert result.exit_code == 4, result
    (step,) = json.loads(result.stdout)["steps"]
    assert step["ok"] is False and step["result"]["exit_code"] in (1, 2), step
    assert step["error"].startswith("ownctl: step 1: ") and step["error"].count("ownctl: ") == 1, step
    assert "Usage:" not in step["error"] and "Traceback" not in step["error"]
