"""Benchmark: where the task experiment's mistakes come from, and what questions could save at best.

    python benchmarks/asking.py [--trials 8] [--seed 0] [--budget 4] [--kinds act,may,whose]
        [--temper 0.5] [--min-gain 0.05] [--taught] [--ahead K] [--as-given] [--hindsight] [--predictions]
        [--scripted] [--json]

On the asking experiment's worlds (``ownctl experiment task --ask``: trial ``t`` of task ``c`` is
the paper's blocks world drawn with ``[seed, c, t]``), for collectAll and trashAll:

- **classes of mistakes**, with no question and with ``--budget`` questions of our strategy
  (``--kinds``: the kinds it may ask, ``--temper``: the power of the rule-set posteriors it values
  them on, ``--min-gain``, ``--taught``, ``--ahead``: how many of the best questions are valued
  again looking ahead to the permissions the object being decided is given next (0: none),
  ``--as-given``: ownership not read through the learner's
  claim calibration; the task asker's defaults otherwise; the strategy before them is ``--kinds
  act,may,whose,rule --temper 1 --as-given``): each mistake is taken just before the robot
  acts, with the beliefs it decides on. ``first``: no permission yet (no question may be asked
  before the first one); ``ownership``: its learned rules decide right on the object's true owners
  but the true norms decide wrong on its believed ownership (so the ownership belief is to blame);
  ``rules``: the reverse; ``both``: both decide wrong; ``neither``: both decide right (the mistake
  comes from their combination, e.g. several half-believed owners under "ownedBy any");
- **perfect knowledge**, no question: every true owner claimed before the task (ownership known,
  rules learned), the true norms stated before it (rules known, ownership learned), both;
- ``--hindsight``: an upper bound on what a question strategy can save with ``--budget`` questions
  in this protocol: before each object, once the robot holds a permission, among the same
  candidate questions as ours (``ownctl.mind.ask.candidates`` of ``--kinds``, on the stated model's
  posterior) the one whose *true* answer leads to
  the fewest actual mistakes over the rest of the task (the rest run on a fork of the Mind and a
  copy of the executor, no further question) is asked if it saves at least one, greedily. It reads
  the future, so no strategy that does not can do as well on average; it is slow (one run of the
  rest of the task per candidate and object, about a minute per trial);
- ``--scripted`` (instead of ours): a scripted strategy with no value of information, "whose" of
  the earliest permitted object of uncertain ownership, then "whose" of each object about to be
  decided while its ownership is uncertain (``GroundExamples``: every permission the instructor
  gives next is of an object with known owners); seconds per trial;
- ``--predictions`` (instead of the above): with no question, how well the expected-mistakes
  model predicts each decision after the first permission: per task the decisions, the actual
  mistakes, and the sum and log loss of P(wrong) with ownership as given and read as the learner
  reads it (``ownctl.mind.ask.task_reading``), on the stated model's posterior and at ``--temper``.

Prints the mean mistakes per task and, per class, the mistakes per task; ``--json`` one document.
"""

from __future__ import annotations

import argparse
import copy
import json
import sys
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ownctl.config import LearnConfig, Settings  # noqa: E402
from ownctl.experiment.asking import (  # noqa: E402
    TASK_AHEAD,
    TASK_KINDS,
    TASK_TEMPER,
    OracleAnswers,
    QuestionAsker,
)
from ownctl.experiment.kinematic import KinematicExecutor  # noqa: E402
from ownctl.experiment.online import TASK_CONDITIONS  # noqa: E402
from ownctl.experiment.oracle import OracleInstructor  # noqa: E402
from ownctl.experiment.task import Asker, Task, get_task, run_objects  # noqa: E402
from ownctl.experiment.truth import TrueNorms  # noqa: E402
from ownctl.logic.prob import p_forbidden  # noqa: E402
from ownctl.logic.rules import Norm, parse_rule  # noqa: E402
from ownctl.logic.vocab import object_steps  # noqa: E402
from ownctl.mind import Mind, Switches  # noqa: E402
from ownctl.mind.ask import (  # noqa: E402
    ALL_KINDS,
    IDENTITY,
    Question,
    apply_answer,
    candidates,
    expected_mistakes,
    task_reading,
)
from ownctl.world.generator import paper_blocks_world  # noqa: E402
from ownctl.world.model import World, make_frame  # noqa: E402

CLASSES = ("first", "ownership", "rules", "both", "neither")


def setup(c: int, t: int, seed: int) -> tuple[Task, World, Mind]:
    """Task ``c``'s world of trial ``t`` and a Mind that knows nothing, as the experiment draws them."""
    world = paper_blocks_world(np.random.default_rng([seed, c, t]))
    mind = Mind(world.agents, list(world.objects), world.areas, Settings(learn=LearnConfig(learner="ours")),
                Switches())
    return get_task(TASK_CONDITIONS[c].task), world, mind


def classify(mind: Mind, truth: TrueNorms, steps: Sequence[str], i: int) -> str | None:
    """The class of the decision on object ``i`` if it is a mistake (see the module's docstring)."""
    forbidden, _ = mind.decide(steps[-1], i, steps)
    violated = truth.violated(i, mind.objects[i], steps)
    if forbidden == violated:
        return None
    if not any(mind.perms.values()):
        return "first"
    obj, true_own = mind.objects[i], truth.owner_row(i)[None].astype(float)
    on_true = make_frame([obj], mind.areas, mind.agents, true_own)
    on_belief = make_frame([obj], mind.areas, mind.agents, mind.posterior()[i][None])
    rules_dec = False
    for s in steps:
        given = mind.permission(s, i)
        rules_dec |= (given.value >= 0.5 if given is not None
                      else p_forbidden(mind.rules[s], on_true)[0] >= mind.settings.threshold_for(s))
    own_dec = any(p_forbidden(truth.rules.get(s, ()), on_belief)[0] >= 0.5 for s in steps)
    rules_ok, own_ok = rules_dec == violated, own_dec == violated
    return {(True, False): "ownership", (False, True): "rules", (False, False): "both"}.get(
        (rules_ok, own_ok), "neither")


class Classifier:
    """An asker that lets ``inner`` ask, then records the class of the decision that follows."""

    def __init__(self, inner: Asker | None, world: World, steps: Sequence[str]) -> None:
        self.inner, self.truth, self.steps = inner, TrueNorms(world), tuple(steps)
        self.classes: list[str] = []

    def before(self, mind: Mind, obj: int, remaining: Sequence[int]) -> None:
        """Ask (inner), then classify the decision on ``obj``."""
        if self.inner is not None:
            self.inner.before(mind, obj, remaining)
        kind = classify(mind, self.truth, self.steps, obj)
        if kind is not None:
            self.classes.append(kind)


class Hindsight:
    """The greedy hindsight chooser (see the module's docstring)."""

    def __init__(self, world: World, task: Task, executor: KinematicExecutor, budget: int,
                 kinds: Sequence[str]) -> None:
        self.world, self.task, self.executor, self.budget = world, task, executor, budget
        self.kinds, self.steps = tuple(kinds), object_steps(task.action)
        self.oracle, self.truth = OracleAnswers(world), TrueNorms(world)
        self.asked: list[Question] = []

    def future(self, mind: Mind, obj: int, question: Question | None) -> int:
        """Actual mistakes from ``obj`` to the end after asking ``question`` (None: nothing)."""
        fork = mind.fork()
        if question is not None:
            apply_answer(fork, self.oracle.answer(question, fork))
        rest = run_objects(fork, self.truth, self.task, copy.deepcopy(self.executor),
                           OracleInstructor(self.world), start=obj)
        return sum(r.mistake for r in rest)

    def before(self, mind: Mind, obj: int, remaining: Sequence[int]) -> None:
        """Ask the candidate with the fewest actual future mistakes, if it saves one."""
        if len(self.asked) >= self.budget or not any(mind.perms.values()):
            return
        pool = [q for q in candidates(mind, self.steps, remaining, self.kinds) if q not in self.asked]
        base = self.future(mind, obj, None)
        scored = [(self.future(mind, obj, q), k, q) for k, q in enumerate(pool)]
        if scored and min(scored)[0] < base:
            question = min(scored)[2]
            apply_answer(mind, self.oracle.answer(question, mind))
            self.asked.append(question)


class GroundExamples:
    """A scripted asker (no value of information): once the robot holds a permission, "whose" of
    the earliest example (an object holding a permission of the task's steps) whose ownership is
    uncertain, then before each object "whose" of that object while its ownership is uncertain,
    so every permission the instructor gives next is of an object with known owners."""

    def __init__(self, world: World, steps: Sequence[str], budget: int) -> None:
        self.oracle, self.steps, self.budget = OracleAnswers(world), tuple(steps), budget
        self.asked: list[Question] = []

    def before(self, mind: Mind, obj: int, remaining: Sequence[int]) -> None:
        """Ask one "whose" question before ``obj`` while the budget lasts."""
        if len(self.asked) >= self.budget or not any(mind.perms.values()):
            return
        def unsure(i: int) -> bool:
            row = mind.posterior_rows([i])[0]
            return bool(np.any((row > 0.01) & (row < 0.99)))
        pick: int | None = None
        if not self.asked:
            examples = dict.fromkeys(mind.obj(n) for s in self.steps for n in mind.perms[s])
            pick = next((i for i in sorted(examples) if unsure(i)), None)
        if pick is None and unsure(obj):
            pick = obj
        if pick is None:
            return
        question = Question("whose", mind.objects[pick].name)
        apply_answer(mind, self.oracle.answer(question, mind))
        self.asked.append(question)


class Predictions:
    """An asker that asks nothing and records, before each decision once the robot holds a
    permission, P(wrong) of that decision as the expected-mistakes model gives it."""

    def __init__(self, world: World, steps: Sequence[str], temper: float) -> None:
        self.truth, self.steps, self.temper = TrueNorms(world), tuple(steps), temper
        self.rows: list[tuple[int, float, float, float]] = []  # mistake, P(wrong): given, read, read at T

    def before(self, mind: Mind, obj: int, remaining: Sequence[int]) -> None:
        """Record the decision on ``obj`` and its predicted P(wrong)."""
        if not any(mind.perms.values()):
            return
        forbidden, _ = mind.decide(self.steps[-1], obj, self.steps)
        wrong = int(forbidden != self.truth.violated(obj, mind.objects[obj], self.steps))
        reading = task_reading(mind, self.steps)
        self.rows.append((wrong, *(float(expected_mistakes(mind, self.steps, [obj], t, r).p_wrong[0])
                                   for t, r in ((1.0, IDENTITY), (1.0, reading), (self.temper, reading)))))


def prediction_summary(rows: Sequence[tuple[int, float, float, float]], temper: float) -> dict[str, Any]:
    """Decisions, mistakes, and per way of predicting the sum and mean log loss of P(wrong)."""
    y = np.array([r[0] for r in rows], dtype=float)
    out: dict[str, Any] = {"decisions": len(rows), "mistakes": int(y.sum())}
    for k, name in enumerate(("as given", "read", f"read, temper {temper}"), start=1):
        p = np.clip(np.array([r[k] for r in rows]), 1e-3, 1 - 1e-3)
        loss = -np.mean(y * np.log(p) + (1 - y) * np.log(1 - p))
        out[name] = {"sum": float(p.sum()), "log_loss": float(loss)}
    return out


def run(c: int, t: int, seed: int, mode: str, budget: int, kinds: Sequence[str], min_gain: float,
        temper: float = TASK_TEMPER, taught: bool = False, read: bool = True,
        ahead: int = TASK_AHEAD) -> tuple[int, list[str]]:
    """(mistakes, their classes) of one trial: ``mode`` ours, own (owners known), rules (norms
    known), both, or hindsight."""
    task, world, mind = setup(c, t, seed)
    truth, steps, executor = TrueNorms(world), object_steps(task.action), KinematicExecutor(world)
    if mode in ("own", "both"):
        for i in range(len(mind.objects)):
            for j, agent in enumerate(world.agents):
                mind.claim(i, agent, float(truth.ownership[i, j]))
    if mode in ("rules", "both"):
        for text in world.norms:
            mind.instruct(Norm("forbid", parse_rule(text)))
    inner: Asker | None = None
    if mode == "ours" and budget:
        inner = QuestionAsker(steps, "ours", budget, min_gain, OracleAnswers(world),
                              np.random.default_rng([seed, c, t, 1]), kinds=tuple(kinds), taught=taught,
                              temper=temper, read=read, ahead=ahead)
    elif mode == "hindsight":
        inner = Hindsight(world, task, executor, budget, kinds)
    elif mode == "scripted":
        inner = GroundExamples(world, steps, budget)
    probe = Classifier(inner, world, steps)
    records = run_objects(mind, truth, task, executor, OracleInstructor(world), asker=probe)
    return sum(r.mistake for r in records), probe.classes


def predict(c: int, trials: int, seed: int, temper: float) -> dict[str, Any]:
    """``--predictions`` for task ``c`` over ``trials`` trials with no question."""
    rows: list[tuple[int, float, float, float]] = []
    for t in range(trials):
        task, world, mind = setup(c, t, seed)
        probe = Predictions(world, object_steps(task.action), temper)
        run_objects(mind, TrueNorms(world), task, KinematicExecutor(world), OracleInstructor(world),
                    asker=probe)
        rows += probe.rows
    return prediction_summary(rows, temper)


def summary(results: list[tuple[int, list[str]]]) -> dict[str, Any]:
    """Mean mistakes per task and per class."""
    n = len(results)
    counts = Counter(k for _, classes in results for k in classes)
    return {"mistakes": float(np.mean([m for m, _ in results])), "per_trial": [m for m, _ in results],
            "classes": {k: counts[k] / n for k in CLASSES}}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=8)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--budget", type=int, default=4)
    parser.add_argument("--kinds", default=",".join(TASK_KINDS))
    parser.add_argument("--temper", type=float, default=TASK_TEMPER)
    parser.add_argument("--min-gain", type=float, default=0.05)
    parser.add_argument("--taught", action="store_true")
    parser.add_argument("--ahead", type=int, default=TASK_AHEAD)
    parser.add_argument("--as-given", action="store_true")
    parser.add_argument("--hindsight", action="store_true")
    parser.add_argument("--predictions", action="store_true")
    parser.add_argument("--scripted", action="store_true")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    kinds = [k.strip() for k in args.kinds.split(",")]
    unknown = [k for k in kinds if k not in ALL_KINDS]
    if unknown:
        parser.error(f"unknown question kind {unknown[0]!r}; valid kinds: {', '.join(ALL_KINDS)}")
    modes = [("none", "ours", 0), (f"ours, {args.budget} questions", "ours", args.budget),
             ("ownership known", "own", 0), ("rules known", "rules", 0), ("both known", "both", 0)]
    if not args.budget:
        del modes[1]
    if args.predictions:
        modes = []
    elif args.hindsight:
        modes.append((f"hindsight, {args.budget} questions", "hindsight", args.budget))
    if args.scripted and not args.predictions:  # instead of ours (no value of information: seconds)
        modes = [m for m in modes if m[1] != "ours" or not m[2]]
        modes.insert(1, (f"examples' owners, {args.budget} questions", "scripted", args.budget))
    if not 0 < args.temper <= 1:
        parser.error(f"--temper must be in (0, 1], got {args.temper}")
    doc: dict[str, Any] = {"trials": args.trials, "seed": args.seed, "budget": args.budget,
                           "kinds": kinds, "temper": args.temper, "min_gain": args.min_gain,
                           "taught": args.taught, "read": not args.as_given, "ahead": args.ahead,
                           "tasks": {}}
    for c, cond in enumerate(TASK_CONDITIONS):
        rows = {}
        for label, mode, budget in modes:
            rows[label] = summary([run(c, t, args.seed, mode, budget, kinds, args.min_gain, args.temper,
                                       args.taught, not args.as_given, args.ahead)
                                   for t in range(args.trials)])
            if not args.json:
                row = rows[label]
                parts = ", ".join(f"{k} {v:.2f}" for k, v in row["classes"].items() if v)
                print(f"{cond.name:10} {label:24} {row['mistakes']:.2f} mistakes per task ({parts})",
                      flush=True)
        if args.predictions:
            rows["predictions"] = predict(c, args.trials, args.seed, args.temper)
            if not args.json:
                pred = rows["predictions"]
                parts = "; ".join(f"{k}: sum {v['sum']:.2f}, log loss {v['log_loss']:.3f}"
                                  for k, v in pred.items() if isinstance(v, dict))
                print(f"{cond.name:10} P(wrong) of {pred['decisions']} decisions, "
                      f"{pred['mistakes']} mistakes ({parts})", flush=True)
        doc["tasks"][cond.name] = rows
    if args.json:
        print(json.dumps(doc))


if __name__ == "__main__":
    main()
