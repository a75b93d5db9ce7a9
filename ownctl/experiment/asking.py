"""Asking during a task: question strategies, the oracle's answers, and the asking experiment.

Three strategies choose what to ask before the robot acts on an object (docs/asking.md, section 4):

- ``ours``: the question of largest value of information
  (:func:`ownctl.mind.ask.best_questions`) for the objects the task will still attempt, asked
  when its gain is at least ``min_gain``; with ``taught``, a permission question (``may``,
  ``act``) is valued on the decisions up to its object, since the instructor teaches each
  object's permissions when it is attempted; with ``ahead`` (by default), its best questions
  are valued again looking ahead to the permissions the object being decided gets next;
- ``entropy``: "whose is OBJ?" for the object still to attempt whose ownership is most uncertain
  (largest sum over agents of the binary entropy of the posterior; ties: task order), as ActOwL's
  information-gain choice does;
- ``random``: "whose is OBJ?" for an object still to attempt drawn at random.

Each asks at most one question before each object, while its budget lasts (the baselines whenever
budget remains), never the same question twice, and none before the robot holds a first permission:
with no example the posterior over rule sets is its prior over the cheapest rules (every step
forbidden with probability about 0.6), not a belief about the world, so no value of information
computed on it is meaningful (docs/asking.md, section 4). The simulated instructor answers from
the ground truth (:class:`OracleAnswers`), and the answer is taught through
:func:`ownctl.mind.ask.apply_answer`, the instructions of any claim, permission or norm. The
experiment runs Table 3's worlds (the same seeds: budget 0 is Table 3) for every strategy and budget.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ownctl.config import ASK_AHEAD, ASK_KINDS, ASK_MIN_GAIN, ASK_READ, ASK_TEMPER, LearnConfig, Settings
from ownctl.errors import BadValue, UnknownName
from ownctl.experiment.cluster import executor
from ownctl.experiment.kinematic import KinematicExecutor
from ownctl.experiment.norms import WorldFactory
from ownctl.experiment.online import TASK_CONDITIONS
from ownctl.experiment.oracle import OracleInstructor
from ownctl.experiment.runner import check_settings
from ownctl.experiment.student import t_quantile
from ownctl.experiment.task import get_task, run_task
from ownctl.experiment.truth import TrueNorms
from ownctl.logic.prob import p_forbidden
from ownctl.logic.vocab import object_steps
from ownctl.mind import Mind, Switches
from ownctl.mind.ask import (
    ALL_KINDS,
    Answer,
    Question,
    apply_answer,
    best_questions,
    candidates,
    check_ahead,
    check_temper,
    ownership_entropy,
    worth_asking,
)
from ownctl.mind.core import decide_mode
from ownctl.world.generator import paper_blocks_world
from ownctl.world.model import World

STRATEGIES = ("ours", "entropy", "random")
#: how ``ours`` asks during a task by default: the defaults of the ask.* settings
DEFAULT_MIN_GAIN, TASK_KINDS, TASK_TEMPER, TASK_READ = ASK_MIN_GAIN, ASK_KINDS, ASK_TEMPER, ASK_READ
TASK_AHEAD = ASK_AHEAD
#: the report's name of the default world
PAPER_TRIALS = "paper blocks world (Table 3's trials: budget 0 is Table 3)"


class OracleAnswers:
    """Answers questions truthfully from a simulated world's ground truth.

    ``whose``: the true owners; ``may``: the true permission of the step on the object as it is now;
    ``rule``: on every object as it is now, with its true owners, "yes" when the true norms forbid
    everything the rule describes, "no" when they forbid none of it, "partly" otherwise.
    """

    def __init__(self, world: World) -> None:
        self.truth = TrueNorms(world)

    def answer(self, question: Question, mind: Mind) -> Answer:
        """The true answer to ``question`` about ``mind``'s objects (the world's, in order)."""
        if question.kind == "whose":
            assert question.object is not None
            row = self.truth.owner_row(mind.obj(question.object))
            owners = tuple(a for a, p in zip(self.truth.world.agents, row, strict=True) if p >= 0.5)
            return Answer(question, owners=tuple(a for a in mind.agents if a in owners))
        if question.kind == "may":
            assert question.object is not None and question.action is not None
            i = mind.obj(question.object)
            value = self.truth.forbidden(i, mind.objects[i], [question.action])[question.action]
            return Answer(question, forbid=value >= 0.5)
        if question.kind == "act":
            assert question.object is not None
            i = mind.obj(question.object)
            values = self.truth.forbidden(i, mind.objects[i], question.steps)
            return Answer(question, forbids=tuple(s for s in question.steps if values[s] >= 0.5))
        assert question.rule is not None
        frame = self.truth.frame(mind.objects)
        covered = p_forbidden([question.rule], frame) >= 0.5
        forbidden = p_forbidden(self.truth.rules.get(question.rule.action, ()), frame) >= 0.5
        if not covered.any() or forbidden[covered].all():
            return Answer(question, holds="yes")
        return Answer(question, holds="no" if not forbidden[covered].any() else "partly")


@dataclass
class Asked:
    """One question put during a task: before which object, what, the answer, the gain (ours)."""

    before: str
    question: Question
    answer: Answer | None
    gain: float | None

    def as_dict(self) -> dict[str, Any]:
        """``{"before", "question", "answer", "gain", ...}``."""
        return {"before": self.before, **self.question.as_dict(),
                "answer": self.answer.text() if self.answer else None, "gain": self.gain}


@dataclass
class QuestionAsker:
    """Asks up to ``budget`` questions during a task, one at most before each object.

    ``taught``: value a permission question on the decisions up to its object, as the task's
    instructor teaches every attempted object's permissions (docs/asking.md, section 4; off by
    default); ``ahead``: how many of the best questions are valued again looking ahead to the
    permissions the object being decided gets next (implies ``taught``; 0: none). ``answers``
    answers them (and the answer is taught); None only lists them (each still counts
    against the budget, so ``budget`` questions are listed).
    """

    steps: tuple[str, ...]
    strategy: str = "ours"
    budget: int = 0
    min_gain: float = DEFAULT_MIN_GAIN
    answers: OracleAnswers | None = None
    rng: np.random.Generator | None = None
    kinds: tuple[str, ...] = TASK_KINDS
    taught: bool = False
    temper: float = TASK_TEMPER
    read: bool = TASK_READ
    ahead: int = TASK_AHEAD
    asked: list[Asked] = field(default_factory=list)

    def __post_init__(self) -> None:
        check_strategy(self.strategy)
        check_kinds(self.kinds)
        check_temper(self.temper)
        check_ahead(self.ahead)
        if self.budget < 0:
            raise BadValue(f"the question budget must be at least 0, got {self.budget}")

    def choose(self, mind: Mind, remaining: Sequence[int]) -> tuple[Question, float | None] | None:
        """The strategy's question (with its gain, for ``ours``), or None."""
        if not remaining:
            return None
        if self.strategy == "ours":
            seen = {a.question for a in self.asked}
            pool = [q for q in candidates(mind, self.steps, remaining, self.kinds, temper=self.temper,
                                          read=self.read) if q not in seen]
            best = best_questions(mind, self.steps, remaining, top=1, questions=pool,
                                  taught=self.taught, temper=self.temper, read=self.read,
                                  ahead=self.ahead)
            if not best or not worth_asking(best[0].gain, self.min_gain):
                return None
            return best[0].question, best[0].gain
        if self.strategy == "entropy":
            h = ownership_entropy(mind, remaining)
            k = int(np.argmax(h))  # first of the largest: task order
        else:
            rng = self.rng if self.rng is not None else np.random.default_rng(0)
            k = int(rng.integers(len(remaining)))
        return Question("whose", mind.objects[remaining[k]].name), None

    def before(self, mind: Mind, obj: int, remaining: Sequence[int]) -> None:
        """Ask one question before acting on ``obj`` if the budget and the strategy allow."""
        if len(self.asked) >= self.budget or not any(mind.perms.values()):
            return
        chosen = self.choose(mind, remaining)
        if chosen is None:
            return
        question, gain = chosen
        answer = self.answers.answer(question, mind) if self.answers is not None else None
        if answer is not None:
            apply_answer(mind, answer)
        self.asked.append(Asked(mind.objects[obj].name, question, answer, gain))


def check_strategy(strategy: str) -> str:
    """``strategy`` if known; UnknownName listing the strategies otherwise."""
    if strategy not in STRATEGIES:
        raise UnknownName("question strategy", strategy, STRATEGIES)
    return strategy


def check_kinds(kinds: Sequence[str]) -> tuple[str, ...]:
    """``kinds`` if each is a question kind and there is one; UnknownName or BadValue otherwise."""
    for kind in kinds:
        if kind not in ALL_KINDS:
            raise UnknownName("question kind", kind, ALL_KINDS)
    if not kinds:
        raise BadValue(f"name at least one question kind of {', '.join(ALL_KINDS)}", ALL_KINDS)
    return tuple(kinds)


def parse_kinds(text: str) -> tuple[str, ...]:
    """``"act,may,whose"`` as question kinds (duplicates dropped, order kept), checked."""
    return check_kinds(tuple(dict.fromkeys(k.strip() for k in text.split(",") if k.strip())))


# -- the experiment -------------------------------------------------------------------------------
@dataclass(frozen=True)
class Unit:
    """One run: a task condition (Table 3 index), a trial, a strategy and a budget."""

    condition: int
    trial: int
    strategy: str
    budget: int


@dataclass(frozen=True)
class Policy:
    """How ``ours`` asks in the experiment: the least gain worth a question, the kinds it may
    ask, the power of the rule-set posteriors it values them on, whether it values permission
    questions on the decisions up to their object (``taught``), whether the truth reads
    ownership as the learner does (``read``) and how many of its best questions it values again
    with the look-ahead (``ahead``; docs/asking.md, section 4); ``decide``: how every robot's learned
    rules decide (``decide.rules``)."""

    min_gain: float = DEFAULT_MIN_GAIN
    kinds: tuple[str, ...] = TASK_KINDS
    temper: float = TASK_TEMPER
    taught: bool = False
    read: bool = TASK_READ
    ahead: int = TASK_AHEAD
    decide: str = "map"

    def __post_init__(self) -> None:
        decide_mode(self.decide)
        check_kinds(self.kinds)
        check_temper(self.temper)
        check_ahead(self.ahead)


def ask_run(unit: Unit, seed: int, policy: Policy = Policy(), learner: str = "ours",
            make_world: WorldFactory = paper_blocks_world) -> tuple[int, int]:
    """(mistakes, questions asked) of one run; the world is Table 3's trial ``[seed, c, t]`` of
    ``make_world`` (the paper's blocks world by default, or a world file's)."""
    cond = TASK_CONDITIONS[unit.condition]
    world = make_world(np.random.default_rng([seed, unit.condition, unit.trial]))
    settings = Settings(learn=LearnConfig(learner=learner), decide_rules=policy.decide)
    mind = Mind(world.agents, list(world.objects), world.areas, settings, Switches())
    asker = QuestionAsker(object_steps(get_task(cond.task).action), unit.strategy, unit.budget,
                          policy.min_gain, OracleAnswers(world),
                          np.random.default_rng([seed, unit.condition, unit.trial, 1]), policy.kinds,
                          taught=policy.taught, temper=policy.temper, read=policy.read, ahead=policy.ahead)
    report = run_task(mind, world, cond.task, KinematicExecutor(world), OracleInstructor(world), asker=asker)
    return report.mistakes, len(asker.asked)


def _chunk(units: Sequence[Unit], seed: int, policy: Policy,
           make_world: WorldFactory) -> list[tuple[Unit, tuple[int, int]]]:
    return [(u, ask_run(u, seed, policy, make_world=make_world)) for u in units]


def mean_ci(values: Sequence[float]) -> tuple[float, float]:
    """The mean and the half-width of its 95% t-interval (0 for fewer than two values)."""
    x = np.asarray(values, dtype=float)
    if len(x) < 2:
        return float(x.mean()) if len(x) else math.nan, 0.0
    return float(x.mean()), float(t_quantile(0.975, len(x) - 1) * x.std(ddof=1) / math.sqrt(len(x)))


def parse_budgets(text: str) -> tuple[int, ...]:
    """``"0,1,2,4,8"`` as sorted distinct budgets; BadValue naming the bad item."""
    out = set()
    for item in text.split(","):
        item = item.strip()
        if not item.isdigit():
            raise BadValue(f"--ask takes question budgets like 0,1,2,4,8 (non-negative integers), "
                           f"got {item!r}")
        out.add(int(item))
    return tuple(sorted(out))


def ask_experiment(budgets: Sequence[int], trials: int, seed: int = 0, jobs: int = 1,
                   tasks: Sequence[str] = ("collectAll", "trashAll"), min_gain: float = DEFAULT_MIN_GAIN,
                   progress: Callable[[int, int], None] | None = None, kinds: Sequence[str] = TASK_KINDS,
                   temper: float = TASK_TEMPER, read: bool = TASK_READ, ahead: int = TASK_AHEAD,
                   decide: str = "map", make_world: WorldFactory = paper_blocks_world,
                   world_name: str = PAPER_TRIALS) -> dict[str, Any]:
    """Mistakes per task and questions asked for every strategy and budget, on the same seeds.

    Budget 0 is one run per trial shared by the strategies (Table 3 itself, on ``make_world``'s
    trials: the paper's blocks world, or a world file's, named ``world_name``). Returns the JSON
    document: per task, per strategy, per budget the mean mistakes with its 95% interval and the
    mean number of questions asked, and the paired difference ours - entropy per budget.
    """
    check_settings(trials, jobs, "ours", seed=seed)
    policy = Policy(min_gain, tuple(kinds), temper, read=read, ahead=ahead, decide=decide)
    names = [c.name for c in TASK_CONDITIONS]
    conds = [names.index(t) for t in tasks]
    units = [Unit(c, t, s, b) for c in conds for t in range(trials) for b in budgets
             for s in (STRATEGIES if b else ("ours",))]
    start = time.perf_counter()
    done: dict[Unit, tuple[int, int]] = {}
    if jobs == 1:
        for u in units:
            done[u] = ask_run(u, seed, policy, make_world=make_world)
            if progress:
                progress(len(done), len(units))
    else:
        size = max(1, math.ceil(len(units) / (jobs * 4)))
        with executor(jobs) as (pool, _):
            futures = [pool.submit(_chunk, units[i : i + size], seed, policy, make_world)
                       for i in range(0, len(units), size)]
            for fut in futures:
                done.update(dict(fut.result()))
                if progress:
                    progress(len(done), len(units))

    def run_of(c: int, t: int, s: str, b: int) -> tuple[int, int]:
        return done[Unit(c, t, s if b else "ours", b)]

    results = []
    for c in conds:
        rows = []
        for s in STRATEGIES:
            for b in budgets:
                mistakes = [run_of(c, t, s, b)[0] for t in range(trials)]
                asked = [run_of(c, t, s, b)[1] for t in range(trials)]
                mean, ci = mean_ci(mistakes)
                rows.append({"strategy": s, "budget": b, "mistakes": mean, "ci95": ci,
                             "questions": float(np.mean(asked)), "per_trial": mistakes})
        paired = []
        for b in budgets:
            if b == 0:
                continue
            diff = [run_of(c, t, "ours", b)[0] - run_of(c, t, "entropy", b)[0] for t in range(trials)]
            mean, ci = mean_ci(diff)
            paired.append({"budget": b, "ours_minus_entropy": mean, "ci95": ci,
                           "better": sum(d < 0 for d in diff), "worse": sum(d > 0 for d in diff)})
        results.append({"task": names[c], "runs": rows, "paired": paired})
    return {"experiment": "task-ask", "trials": trials, "seed": seed, "jobs": jobs,
            "budgets": list(budgets), "strategies": list(STRATEGIES), "min_gain": min_gain,
            "kinds": list(policy.kinds), "temper": policy.temper, "read": policy.read,
            "ahead": policy.ahead, "decide": policy.decide, "tasks": results,
            "world": world_name,
            "seconds": time.perf_counter() - start}
