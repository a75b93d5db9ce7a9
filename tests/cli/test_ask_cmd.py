"""``ownctl ask``, ``ask --put`` with ``say`` answering, ``run --ask``, and their bad inputs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.cli.conftest import SMALL_WORLD, Ownctl, from_template

WORLD = SMALL_WORLD.replace('name = "three blocks"', 'name = "four blocks"') + """
[[objects]]
name = "key"
color = "red"
position = [0.45, 0.35, 0.0]
owners = { xuan = 1.0 }
"""


def loaded(ownctl: Ownctl, tmp_path: Path) -> Ownctl:
    """The four-block world loaded, with the wallet forbidden to trash."""
    path = tmp_path / "world.toml"
    path.write_text(WORLD, encoding="utf-8")
    ownctl("world", "load", str(path))
    ownctl("forbid", "trash", "on", "wallet")
    return ownctl


@pytest.fixture
def world(tmp_path: Path, ownctl: Ownctl) -> Ownctl:
    loaded(ownctl, tmp_path)("allow", "trash", "on", "cup")
    return ownctl


@pytest.mark.slow
def test_ask_lists_questions_with_gains_and_writes_nothing(world: Ownctl) -> None:
    before = world.digest()
    data = world.json("ask", "--task", "trashAll", "--top", "2")
    assert data["task"] == "trashAll" and data["steps"] == ["find", "pickUp", "trash"]
    assert set(data["objects"]) == {"wallet", "cup", "can", "key"}
    assert 0 < len(data["questions"]) <= 2
    gains = [q["gain"] for q in data["questions"]]
    assert gains == sorted(gains, reverse=True)
    for q in data["questions"]:
        assert q["kind"] in ("may", "whose", "rule") and q["text"].endswith("?")
        assert sum(a["p"] for a in q["answers"]) == pytest.approx(1.0)
    assert data["expected_mistakes"] >= 0
    assert "expected mistakes" in world("ask", "--objects", "can,key").stdout
    assert data["permissions"] == 2 and "No permission" not in world("ask", "--top", "1").stdout
    assert world.digest() == before


@pytest.mark.slow
def test_ask_marks_the_questions_not_worth_asking(world: Ownctl) -> None:
    many = world.json("ask", "--task", "trashAll", "--top", "12")["questions"]
    assert [q["worth_asking"] for q in many] == [q["gain"] >= 0.05 and q["gain"] > 1e-9 for q in many]
    below = sum(not q["worth_asking"] for q in many)
    assert below > 0
    note = f"{below} of these would save less than ask.min_gain (0.05)"
    assert note in world("ask", "--task", "trashAll", "--top", "12").stdout
    world("config", "set", "ask.min_gain", "0")
    assert all(q["worth_asking"] == (q["gain"] > 1e-9) for q in world.json("ask", "--top", "12")["questions"])


@pytest.mark.slow
def test_ask_says_when_its_gains_rest_on_the_prior_alone(tmp_path: Path, ownctl: Ownctl) -> None:
    path = tmp_path / "world.toml"
    path.write_text(WORLD, encoding="utf-8")
    ownctl("world", "load", str(path))
    assert ownctl.json("ask", "--task", "collect", "--top", "1")["permissions"] == 0
    assert "No permission of find, pickUp, collect is known yet" in ownctl("ask", "--task", "collect").stdout
    ownctl("allow", "collect", "on", "can")  # a permission of one step is enough to say nothing
    assert "No permission" not in ownctl("ask", "--task", "collect", "--top", "1").stdout


def test_ask_with_no_object_left_says_there_is_nothing_to_ask(tmp_path: Path, ownctl: Ownctl) -> None:
    path = tmp_path / "bare.toml"
    path.write_text('name = "bare"\nagents = ["ana"]\nnorms = []\n'
                    '[[areas]]\nname = "trash"\nbox = [-0.3, 0.6, 0.2, 1.1]\n', encoding="utf-8")
    ownctl("world", "load", str(path))
    assert ownctl("ask", "--task", "trashAll").stdout == (
        "trashAll: no object is left to decide, so there is nothing to ask.\n")
    assert ownctl.json("ask", "--task", "trashAll")["questions"] == []


ANSWERS = {"may": "yes, you may", "whose": "It's xuan's", "rule": "yes"}


@pytest.mark.parametrize("objects", ["can", "key,can"])
def test_a_put_question_is_answered_by_say_through_the_ordinary_instructions(world: Ownctl,
                                                                              objects: str) -> None:
    put = world.json("ask", "--put", "--as", "alexis", "--objects", objects)["put"]
    said = world.json("say", ANSWERS[put["kind"]], "--as", "alexis")
    assert said["intent"] == "answer"
    if put["kind"] == "may":
        assert said["instructions"] == [f"allow {put['action']} on {put['object']}"]
        texts = [p["text"] for p in world.json("perms", "list")]
        assert f"allow {put['action']} on {put['object']}" in texts
    elif put["kind"] == "whose":
        assert said["instructions"] == [f"claim {put['object']} xuan", f"claim {put['object']} alexis --not"]
        owners = {o["agent"]: o for o in world.json("owners", put["object"])["owners"]}
        assert owners["xuan"]["claim"] == 1.0 and owners["alexis"]["claim"] == 0.0
    else:
        assert said["instructions"] == [put["rule"]]
    # answered: the same words are now ordinary speech again
    assert world.json("say", "Whose is the key?", "--as", "alexis")["intent"] == "question"


def test_an_utterance_that_is_no_answer_leaves_the_question_pending(world: Ownctl) -> None:
    put = world.json("ask", "--put", "--as", "xuan", "--objects", "can")["put"]
    assert world.json("say", "Hello", "--as", "xuan")["intent"] == "greeting"
    assert world.json("say", ANSWERS[put["kind"]], "--as", "xuan")["intent"] == "answer"


@pytest.mark.slow
def test_put_puts_nothing_when_no_question_is_worth_asking(world: Ownctl) -> None:
    before = world.digest()
    nothing = world("ask", "--put", "--as", "alexis", "--task", "trash", "--objects", "wallet")
    assert nothing.stdout.strip().splitlines() == [
        "no question is worth asking about trash: the best (May I find wallet?) would save 0.000 "
        "expected mistakes, below ask.min_gain 0.05; nothing was put"]
    data = world.json("ask", "--put", "--as", "alexis", "--task", "trash", "--objects", "wallet")
    assert data["put"] is None and data["min_gain"] == 0.05 and data["questions"][0]["gain"] == 0.0
    assert world.digest() == before
    world("config", "set", "ask.min_gain", "0")  # a question that saves nothing is never put
    zero = world.digest()
    assert world.json("ask", "--put", "--task", "trash", "--objects", "wallet")["put"] is None
    assert world.digest() == zero
    world("config", "set", "ask.min_gain", "1")  # the threshold is the setting's, as for run --ask
    worth = world.json("ask", "--put", "--task", "trash", "--objects", "cup")
    assert worth["put"] is None and 0.05 < worth["questions"][0]["gain"] < 1
    world("config", "set", "ask.min_gain", "default")
    assert world.json("ask", "--put", "--task", "trash", "--objects", "cup")["put"]["object"] == "cup"


def test_run_asks_the_oracle_or_only_lists(ownctl: Ownctl, tmp_path: Path) -> None:
    path = tmp_path / "world.toml"
    path.write_text(WORLD, encoding="utf-8")
    ownctl("world", "load", str(path))
    ownctl("claim", "can", "alexis", "--not")
    listed = ownctl.json("run", "trashAll", "--kinematic", "--ask", "1", "--instructor", "none")
    assert len(listed["questions"]) <= 1 and all(q["answer"] is None for q in listed["questions"])
    ownctl("config", "set", "ask.min_gain", "0")
    assert ownctl.json("config", "get")["ask.min_gain"] == 0.0


@pytest.mark.slow
def test_run_with_the_oracle_answers_the_questions(ownctl: Ownctl) -> None:
    report = ownctl.json("run", "trashAll", "--kinematic", "--seed", "2", "--ask", "2")
    assert 1 <= len(report["questions"]) <= 2
    assert all(q["answer"] for q in report["questions"])
    assert report["violations"] == [] and 0 < report["mistakes"] < 20  # the oracle stops every violation


@pytest.mark.slow
def test_ask_values_questions_at_the_configured_temper(world: Ownctl) -> None:
    exact = world.json("ask", "--task", "trashAll", "--top", "3")
    assert exact["temper"] == 0.5  # the task asker's default: one valuation for ask and run --ask
    world("config", "set", "ask.temper", "1")
    assert world.json("config", "get")["ask.temper"] == 1.0
    power = world.json("ask", "--task", "trashAll", "--top", "3")
    assert power["temper"] == 1.0
    assert ([round(q["gain"], 6) for q in power["questions"]], round(power["expected_mistakes"], 6)) != (
        [round(q["gain"], 6) for q in exact["questions"]], round(exact["expected_mistakes"], 6))
    world("config", "set", "ask.temper", "default")
    assert world.json("ask", "--task", "trashAll", "--top", "3") == exact
    assert exact["read"] is True
    world("config", "set", "ask.read", "false")
    assert world.json("config", "get")["ask.read"] is False
    assert world.json("ask", "--task", "trashAll", "--top", "3")["read"] is False


@pytest.mark.slow
def test_ask_looks_ahead_as_configured(world: Ownctl) -> None:
    assert world.json("config", "get")["ask.ahead"] == world.json("ask", "--top", "1")["ahead"]
    world("config", "set", "ask.ahead", "2")
    assert world.json("config", "get")["ask.ahead"] == 2
    ahead = world.json("ask", "--task", "trashAll", "--top", "3")
    assert ahead["ahead"] == 2 and ahead["questions"]
    world("config", "set", "ask.ahead", "0")
    myopic = world.json("ask", "--task", "trashAll", "--top", "3")
    assert myopic["ahead"] == 0
    assert [(q["text"], round(q["gain"], 6)) for q in ahead["questions"]] != [
        (q["text"], round(q["gain"], 6)) for q in myopic["questions"]]


@pytest.mark.slow
def test_run_asks_only_the_configured_kinds(ownctl: Ownctl, tmp_path: Path) -> None:
    loaded(ownctl, tmp_path)
    ownctl("config", "set", "ask.min_gain", "0")
    assert ownctl.json("config", "get")["ask.kinds"] == ["act", "may", "whose"]
    ownctl("config", "set", "ask.kinds", "whose, whose")
    assert ownctl.json("config", "get")["ask.kinds"] == ["whose"]
    listed = ownctl.json("run", "trashAll", "--kinematic", "--ask", "2", "--instructor", "none")
    assert listed["questions"] and {q["kind"] for q in listed["questions"]} == {"whose"}


def test_bad_inputs_are_one_line_and_write_nothing(world: Ownctl) -> None:
    before = world.digest()
    for args in (("ask", "--top", "0"), ("ask", "--task", "dance"), ("ask", "--objects", "nope"),
                 ("ask", "--put", "--as", "nobody"), ("run", "trashAll", "--kinematic", "--ask", "-1"),
                 ("config", "set", "ask.min_gain", "nan"), ("config", "set", "ask.min_gain", "lots"),
                 ("config", "set", "ask.kinds", "act,dance"), ("config", "set", "ask.kinds", ","),
                 ("config", "set", "ask.temper", "0"), ("config", "set", "ask.temper", "lots"),
                 ("config", "set", "ask.temper", "nan"), ("config", "set", "ask.read", "maybe"),
                 ("config", "set", "ask.ahead", "few"), ("config", "set", "ask.ahead", "2.5"),
                 ("owners", "can", "--coverage", "1.5"), ("experiment", "task", "--ask", "1,x")):
        result = world(*args, code=1)
        assert len(result.stderr.strip().splitlines()) == 1, (args, result.stderr)
        assert result.stdout == ""
    assert world.digest() == before
    world("ask", "--as", "alexis", code=2)
    assert world.digest() == before


def test_owners_with_coverage_gives_a_set_per_agent(world: Ownctl) -> None:
    for obj, agent in (("wallet", "alexis"), ("cup", "xuan"), ("key", "xuan")):
        world("claim", obj, agent)
    data = world.json("owners", "can", "--coverage", "0.9")
    assert data["coverage"] == 0.9 and data["claims_needed"] == 9
    for row in data["owners"]:
        assert set(row["conformal"]["set"]) <= {"owns", "does not own"} and row["conformal"]["set"]
    # two claims each at most: the table says why every set holds both labels
    assert "fewer than 9 claimed objects, too few for coverage 0.9" in world("owners", "can", "--coverage",
                                                                             "0.9").stdout


def test_gains_are_shown_to_the_thousandth_of_a_mistake() -> None:
    from ownctl.cli.ask_cmd import _mistakes

    assert [_mistakes(g) for g in (0.0237, -2.52e-06, 0.0, -0.5, 1.23456)] == [
        "0.024", "0.000", "0.000", "-0.500", "1.235"]


def test_a_row_lists_the_most_probable_answers() -> None:
    from ownctl.cli.ask_cmd import _answers

    answers = [{"answer": f"owners {k}", "p": p} for k, p in enumerate((0.05, 0.5, 0.02, 0.3, 0.1, 0.03))]
    assert _answers(answers) == ("owners 1 (0.50), owners 3 (0.30), owners 4 (0.10), owners 0 (0.05) "
                                 "(+2 less likely)")
    assert _answers(answers[:2]) == "owners 1 (0.50), owners 0 (0.05)"


def test_owners_says_when_the_claims_show_that_percepts_tell_little(ownctl: Ownctl, tmp_path: Path) -> None:
    """A scattered world (no percept predicts ownership): after exact claims about eight objects
    the predictors' shared scale is below the full reach, and ``owners`` says so under its table
    (and gives it in --json). A paper world keeps the full reach and says nothing."""
    from ownctl.world.generator import paper_blocks_world, scattered_world
    from ownctl.world.spec import to_toml, world_to_dict

    paper = from_template(tmp_path / "paper.db", ownctl.path.read_bytes())
    for store, draw, reach in ((ownctl, scattered_world, "of their full reach: the claims so far say"),
                               (paper, paper_blocks_world, None)):
        world = draw(np.random.default_rng(9))
        path = tmp_path / f"{draw.__name__}.toml"
        path.write_text(to_toml(world_to_dict(world)), encoding="utf-8")
        store("world", "load", str(path))
        truth = world.true_ownership()
        lines = [f"claim {o.name} {a}" + ("" if truth[i, j] else " --not")
                 for i, o in enumerate(world.objects[:8]) for j, a in enumerate(world.agents)]
        store("batch", "-", input="\n".join(lines) + "\n")
        last = world.objects[-1].name
        data = store.json("owners", last)
        shown = store("owners", last).stdout
        if reach:
            assert data["percept_scale"] < 1 and reach in shown
        else:
            assert data["percept_scale"] == 1 and "full reach" not in shown
    result = ownctl("owners", "--agent", "agent1", "--coverage", "0.9", code=2)
    assert "--coverage applies to OBJ" in result.stderr and result.stdout == ""
    before = ownctl.digest()
    result = ownctl("owners", "agent1", code=1)  # an agent where an object belongs
    assert result.stderr.strip().splitlines() == [
        "ownctl: 'agent1' is an agent, not an object; the objects it owns: ownctl owners --agent agent1"]
    assert ownctl.digest() == before


def test_owners_names_the_agents_silent_about_a_claimed_object(world: Ownctl) -> None:
    """After "that's mine" by alexis, xuan's silence about the wallet weighs, and ``owners`` says so
    (and gives it in --json); about an object nobody spoke of it says nothing of silence."""
    world("claim", "wallet", "alexis")
    data = world.json("owners", "wallet")
    assert data["silence"] > 0 and data["silent"] == ["xuan"]
    shown = world("owners", "wallet").stdout
    assert "xuan said nothing of wallet while others made claims about it: their silence weighs" in shown
    assert world.json("owners", "can")["silent"] == [] and "said nothing" not in world("owners", "can").stdout
    world("claim", "wallet", "xuan", "--not")  # said outright: nobody is silent any more
    assert world.json("owners", "wallet")["silent"] == []


@pytest.mark.slow
def test_owners_says_when_the_claims_show_that_agents_own_things_about_equally_often(
        ownctl: Ownctl, tmp_path: Path) -> None:
    """A scattered world of 24 objects whose agents each own about a quarter of them: after exact
    claims about 23 objects every intercept's prior is narrowed (ownctl/ownership/household.py),
    and ``owners`` of the last object says so (and gives the width in --json). Where the claims say
    one agent owns everything and the others nothing, the configured width stands and nothing is
    said."""
    from ownctl.world.generator import scattered_world
    from ownctl.world.spec import to_toml, world_to_dict

    skewed = from_template(tmp_path / "skewed.db", ownctl.path.read_bytes())
    world = scattered_world(np.random.default_rng(3), 24)
    path = tmp_path / "scattered.toml"
    path.write_text(to_toml(world_to_dict(world)), encoding="utf-8")
    truth = world.true_ownership() >= 0.5
    last = world.objects[-1].name
    for store, owns, narrowed in ((ownctl, lambda i, j: truth[i, j], True),
                                  (skewed, lambda i, j: j == 0, False)):
        store("world", "load", str(path))
        lines = [f"claim {o.name} {a}" + ("" if owns(i, j) else " --not")
                 for i, o in enumerate(world.objects[:23]) for j, a in enumerate(world.agents)]
        store("batch", "-", input="\n".join(lines) + "\n")
        data = store.json("owners", last)
        shown = store("owners", last).stdout
        assert data["rate_spread_configured"] == 1.0
        if narrowed:
            assert data["rate_spread"] < 1.0 and "own things about equally often" in shown
        else:
            assert data["rate_spread"] == 1.0 and "equally often" not in shown
