"""``say UTTERANCE --as AGENT [--about OBJ]``: one utterance, understood and applied as one transaction.

The utterance is understood (:func:`ownctl.language.understand`) in the store's conversation
context: "me" is ``--as`` (else the stored current speaker), "this"/"that" is ``--about`` (else the
stored current target), "do that" / "No, that's mine!" is the current action (of the last check,
refusal or run step). Its instructions then run in order inside ONE write transaction, by the same
use cases as the CLI instructions (claims, permissions and norms with their learning; agents), so a
failure anywhere writes nothing. Questions are answered inside that transaction, so they see what
the utterance just taught: ``owners``, ``check`` (a forbidden answer is the refusal "why not?"
refers to) and ``explain``. ``skip`` is recorded (no robot is acting in a plain ``say``). A task
("Clear the table") runs after the transaction commits, with its own transaction per object as
every run does. Finally the context is updated: speaker, target, action.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ownctl.app.context import AppContext
from ownctl.errors import OwnctlError
from ownctl.humanize import plural
from ownctl.language import (
    OBJECT_ACTIONS,
    AskActions,
    AskOwned,
    AskOwner,
    AskPermitted,
    AskWhy,
    Claim,
    Context,
    Instruction,
    Introduce,
    NormInstruction,
    Permission,
    Request,
    RunTask,
    Skip,
    Understanding,
    teaching_order,
    understand,
)
from ownctl.language.context import Facts
from ownctl.language.lexicon import COLORS
from ownctl.logic.names import check_name
from ownctl.logic.prob import noisy_or
from ownctl.logic.rules import parse_norm
from ownctl.world.model import Area


@dataclass
class SayReport:
    """What was understood and done; ``data`` is the ``--json`` document."""

    utterance: str
    understood: Understanding
    speaker: str | None
    target: str | None
    results: list[dict[str, Any]] = field(default_factory=list)
    answers: list[str] = field(default_factory=list)
    forbidden: bool = False  # a question "may you ...?" was answered no (exit 3, like check)
    run: Any = None  # the RunReport of a task, if the utterance asked for one

    @property
    def reply(self) -> str:
        """The robot's answer: the parser's acknowledgement, then the answers to questions."""
        return " ".join(filter(None, [self.understood.reply, *self.answers]))

    @property
    def data(self) -> dict[str, Any]:
        """``{"utterance", "intent", "instructions", "reply", "results", ...}``."""
        return {
            "utterance": self.utterance,
            "intent": self.understood.intent,
            "instructions": list(self.understood.texts()),
            "reply": self.reply,
            "results": self.results,
            "speaker": self.speaker,
            "target": self.target,
            "forbidden": self.forbidden,
        }


def language_context(ctx: AppContext, speaker: str | None, about: str | None) -> Context:
    """The parser's context: names from the store, speaker/target/action from the conversation."""
    with ctx.read() as tx:
        talk = tx.meta.conversation()
        if about is not None:
            tx.things.object(about)  # an unknown --about is an error naming the known objects
        objects = tx.things.objects()
        categories = tx.things.categories()
        boxes = [Area(a.name, (a.x0, a.y0, a.x1, a.y1)) for a in tx.world.areas()]
        facts = {o.name: Facts(o.color, frozenset(b.name for b in boxes if o.x is not None and o.y is not None
                                                  and bool(b.contains(np.array([[o.x, o.y]]))[0])),
                               frozenset(categories.get(o.id, ())))
                 for o in objects}
        return Context(
            speaker=speaker if speaker is not None else talk.speaker,
            about=about if about is not None else talk.target,
            action=talk.action,
            agents=frozenset(a.name for a in tx.world.agents()),
            objects=frozenset(o.name for o in objects),
            colors=COLORS | {o.color for o in objects if o.color},
            areas=frozenset(b.name for b in boxes),
            categories=frozenset(c for cats in categories.values() for c in cats),
            facts=facts,
        )


def _owners_answer(data: dict[str, Any]) -> str:
    likely = [o for o in data["owners"] if o["p"] >= 0.5]
    if likely:
        parts = ", ".join(f"{o['agent']} (p={o['p']:.2g}, from {o['source']})" for o in likely)
        return f"{data['object']} belongs to {parts}."
    top = data["owners"][0] if data["owners"] else None
    best = f"; the likeliest is {top['agent']} with p={top['p']:.2g}" if top else ""
    # no agent is likely, yet several half-likely ones can make "someone owns it" likely, which is
    # what the norms on "ownedBy any" decide on: say which
    someone = float(noisy_or([o["p"] for o in data["owners"]]))
    if someone >= 0.5:
        return (f"I am not sure who owns {data['object']}: probably someone does (p={someone:.2g}), "
                f"but no one agent is likely{best}.")
    return f"I think nobody owns {data['object']} (p={1.0 - someone:.2g}){best}."


def _check_answer(data: dict[str, Any], reason: str) -> str:
    from ownctl.language.instructions import verb

    if data["decision"] == "forbidden":
        return f"Sorry, I may not {verb(data['action'])} {data['object']}: {reason}."
    return f"Yes, I may {verb(data['action'])} {data['object']}."


def _why(ctx: AppContext, ins: AskWhy) -> dict[str, Any]:
    from ownctl.app.explain import explain

    return explain(ctx, ins.action, ins.object).data


class _Turn:
    """Applies one utterance's instructions in order, tracking who speaks and what was named."""

    def __init__(self, ctx: AppContext, report: SayReport) -> None:
        self.ctx, self.report = ctx, report
        self.action: str | None = None
        self.tasks: list[RunTask] = []

    def apply(self, ins: Instruction) -> dict[str, Any]:
        """Carry out one understood instruction by its use case (see :data:`USE_CASES`)."""
        use_case = USE_CASES.get(type(ins))
        if use_case is None:
            raise OwnctlError(f"no use case carries out {type(ins).__name__} instructions; known: "
                              f"{', '.join(sorted(t.__name__ for t in USE_CASES))}")
        message, data = use_case(self, ins)
        return {"instruction": ins.text(), "message": message, "data": data}

    def _claim(self, ins: Claim) -> tuple[str, dict[str, Any]]:
        from ownctl.app.instruct import add_claim

        self.report.target = ins.object
        done = add_claim(self.ctx, ins.object, ins.agent, ins.p, ins.negated, ins.exclusive,
                         self.report.speaker)
        return done.message, done.data

    def _permission(self, ins: Permission) -> tuple[str, dict[str, Any]]:
        from ownctl.app.instruct import add_permission

        self.report.target, self.action = ins.object, ins.action
        done = add_permission(self.ctx, ins.action, ins.object, 1.0 if ins.forbid else 0.0,
                              self.report.speaker)
        return done.message, done.data

    def _norminstruction(self, ins: NormInstruction) -> tuple[str, dict[str, Any]]:
        from ownctl.app.instruct import add_norm

        done = add_norm(self.ctx, ins.norm.text(), self.report.speaker)
        if done.data["specialised"]:  # the stored permissions narrowed what was said: say so
            taken = [NormInstruction(parse_norm(t)).say() for t in done.data["taken_as"]]
            self.report.answers.append(f"Some of my permissions say otherwise, so I take it as: "
                                       f"{'; '.join(taken)}.")
        return done.message, done.data

    def _introduce(self, ins: Introduce) -> tuple[str, dict[str, Any]]:
        from ownctl.app.things import add_agent

        with self.ctx.read() as tx:
            known = ins.agent in {a.name for a in tx.world.agents()}
        self.report.speaker = ins.agent
        if known:
            return f"{ins.agent} is speaking", {"agent": ins.agent, "added": False}
        done = add_agent(self.ctx, ins.agent)
        return f"{done.message}; {ins.agent} is speaking", {**done.data, "added": True}

    def _skip(self, ins: Skip) -> tuple[str, dict[str, Any]]:
        self.report.target = ins.object
        with self.ctx.write({"op": "skip", "object": ins.object}, actor=self.report.speaker) as tx:
            tx.things.object(ins.object)
        return f"noted: stop acting on {ins.object} (no robot is acting now)", {"object": ins.object}

    def _askowner(self, ins: AskOwner) -> tuple[str, dict[str, Any]]:
        from ownctl.app.query import owners

        self.report.target = ins.object
        data = owners(self.ctx, ins.object)
        answer = _owners_answer(data)
        self.report.answers.append(answer)
        return answer, data

    def _askpermitted(self, ins: AskPermitted) -> tuple[str, dict[str, Any]]:
        from ownctl.app.decide import check

        self.report.target, self.action = ins.object, ins.action
        result = check(self.ctx, ins.action, ins.object)
        answer = _check_answer(result.data, result.reason)
        self.report.forbidden = self.report.forbidden or result.forbidden
        self.report.answers.append(answer)
        return answer, result.data


    def _askowned(self, ins: AskOwned) -> tuple[str, dict[str, Any]]:
        from ownctl.app.query import owned_by

        rows = owned_by(self.ctx, ins.agent)
        things = ", ".join(f"{r['object']} (p={r['p']:.2g})" for r in rows)
        answer = f"{ins.agent} probably owns {things}." if rows else f"I know of nothing {ins.agent} owns."
        self.report.answers.append(answer)
        return answer, {"agent": ins.agent, "objects": rows}

    def _askactions(self, ins: AskActions) -> tuple[str, dict[str, Any]]:
        from ownctl.app.decide import check
        from ownctl.language.instructions import verb

        self.report.target = ins.object
        results = [check(self.ctx, action, ins.object, record=False) for action in OBJECT_ACTIONS]
        may = [verb(r.data["action"]) for r in results if not r.forbidden]
        may_not = [f"{verb(r.data['action'])} ({r.reason})" for r in results if r.forbidden]
        parts = [f"I may: {', '.join(may)}" if may else "",
                 f"I may not: {'; '.join(may_not)}" if may_not else ""]
        answer = f"With {ins.object}, " + ". ".join(p for p in parts if p) + "."
        self.report.answers.append(answer)
        return answer, {"object": ins.object, "checks": [r.data for r in results]}

    def _askwhy(self, ins: AskWhy) -> tuple[str, dict[str, Any]]:
        data = _why(self.ctx, ins)
        self.report.answers.append(data["text"])
        return data["text"], data

    def _runtask(self, ins: RunTask) -> tuple[str, dict[str, Any]]:
        self.tasks.append(ins)
        return f"{ins.task} starts once this utterance is stored", {"task": ins.task}  # then: its report


#: Which use case carries out each kind of understood instruction (a new kind plugs in here).
USE_CASES: dict[type, Callable[[_Turn, Any], tuple[str, dict[str, Any]]]] = {
    Claim: _Turn._claim,
    Permission: _Turn._permission,
    NormInstruction: _Turn._norminstruction,
    Introduce: _Turn._introduce,
    Skip: _Turn._skip,
    AskOwner: _Turn._askowner,
    AskPermitted: _Turn._askpermitted,
    Request: _Turn._askpermitted,
    AskWhy: _Turn._askwhy,
    AskOwned: _Turn._askowned,
    AskActions: _Turn._askactions,
    RunTask: _Turn._runtask,
}


def run_function() -> Callable[..., Any]:
    """The task runner (:func:`ownctl.app.run.run`), imported when a task is asked for."""
    from ownctl.app.run import run

    return run


def say(
    ctx: AppContext,
    utterance: str,
    speaker: str | None = None,
    about: str | None = None,
    physics: bool = False,
    instructor: str = "none",
) -> SayReport:
    """Understand ``utterance`` and apply it (see the module docstring). ``physics`` and
    ``instructor`` are for a task the utterance asks for ("Clear the table")."""
    from ownctl.experiment.task import get_task

    if speaker is not None:
        check_name("speaker", speaker)  # before the words are read: a bad name is the error to report
    lctx = language_context(ctx, speaker, about)
    pending, understood = answered(ctx, utterance, lctx)
    if pending is None:
        understood = understand(utterance, lctx)
    report = SayReport(utterance, understood, lctx.speaker, lctx.about)
    turn = _Turn(ctx, report)
    payload = {"op": "say", "utterance": utterance, "speaker": lctx.speaker, "about": lctx.about,
               "instructions": list(understood.texts())}
    saved = ctx.interface, ctx.command
    try:
        with ctx.write(payload, actor=lctx.speaker) as tx:
            ctx.interface = "say"
            done: dict[int, dict[str, Any]] = {}
            for i, ins in teaching_order(understood.instructions):
                ctx.command = ins.text()
                done[i] = turn.apply(ins)
            report.results = [done[i] for i in sorted(done)]  # shown in the order understood
            if report.speaker is not None:
                tx.world.agent(report.speaker)  # an unknown --as is an error naming the known agents
            action = turn.action if turn.action is not None else lctx.action
            tx.meta.converse(speaker=report.speaker, target=report.target, action=action)
            if pending is not None:
                from ownctl.app.ask import clear_pending

                clear_pending(tx, lctx.speaker)
    finally:
        ctx.interface, ctx.command = saved
    for task in turn.tasks:
        report.run = run_function()(ctx, task.task, physics=physics, instructor=instructor)
        data = report.run.as_json()
        entry = next(r for r in report.results
                     if r["instruction"] == task.text() and "delivered" not in r["data"])
        entry.update(message=_run_summary(data), data=data)
        report.answers.append(_run_summary(data))
        with ctx.write(None) as tx:
            tx.meta.converse(action=get_task(task.task).action)
    return report


def answered(ctx: AppContext, utterance: str, lctx: Context) -> tuple[dict[str, Any] | None, Any]:
    """The question pending for the speaker and what ``utterance`` means as its answer (an
    Understanding of intent ``answer``), or (None, None) when nothing is pending or it is no answer
    (docs/asking.md, section 5)."""
    from ownctl.app.ask import pending_for
    from ownctl.language.answers import answer_instructions

    with ctx.read() as tx:
        pending = pending_for(tx, lctx.speaker)
    if pending is None:
        return None, None
    instructions = answer_instructions(utterance, pending, lctx)
    if instructions is None:
        return None, None
    said = "; ".join(getattr(i, "say", i.text)() for i in instructions) or "nothing to learn from that"
    reply = f"Thank you ({pending['text']}): {said}."
    return pending, Understanding("answer", instructions, reply, form="answer", topic=pending.get("object"))


def _run_summary(data: dict[str, Any]) -> str:
    return (f"Done with {data['task']}: {len(data['delivered'])} delivered, {len(data['skipped'])} left, "
            f"{plural(data['mistakes'], 'mistake')}.")


__all__ = ["SayReport", "language_context", "run_function", "say"]
