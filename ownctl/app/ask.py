"""Use cases: the questions the robot would ask, and putting the best one to the current speaker.

``questions`` loads the whole Mind (read only) and ranks the candidate questions by their value of
information for a task (:mod:`ownctl.mind.ask`; docs/asking.md). ``put`` stores the best one as
pending for the speaker, in the store's settings (key ``ask.pending``: speaker -> question; ``*``
when nobody is speaking yet), and makes its object the conversation's target; ``ownctl say`` then
reads that speaker's next utterance as the answer (:mod:`ownctl.language.answers`). A best question
that is not worth asking by ``ask.min_gain`` (the test ``run --ask`` applies) is not put.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from ownctl.app.context import AppContext, Done, use_case
from ownctl.app.mindstore import load
from ownctl.errors import BadValue, OwnctlError, UnknownName
from ownctl.store.repo import Tx

PENDING = "ask.pending"
ANYONE = "*"


def task_scope(mind: Any, task: str, objects: Sequence[str] | None) -> tuple[tuple[str, ...], list[int]]:
    """The steps decided and the objects asked about for ``task`` (trashAll, collectAll or an
    object action): a task's objects not yet in its area, or every object, or ``objects``."""
    from ownctl.experiment.task import TASKS, area_named, remaining
    from ownctl.logic.vocab import OBJECT_ACTIONS, object_steps

    if task in TASKS:
        chosen = TASKS[task]
        steps = object_steps(chosen.action)
        idx = remaining(mind, area_named(mind.areas, chosen.area), 0)
    elif task in OBJECT_ACTIONS:
        steps, idx = object_steps(task), list(range(len(mind.objects)))
    else:
        raise UnknownName("task", task, [*TASKS, *OBJECT_ACTIONS])
    if objects is not None:
        for name in objects:
            if name not in mind.index:
                raise UnknownName("object", name, mind.index)
        idx = [mind.index[n] for n in dict.fromkeys(objects)]
    return steps, idx


def _ranked(tx: Tx, now: float, task: str, objects: Sequence[str] | None, top: int,
            progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    from ownctl.app.settings import asking
    from ownctl.mind.ask import IDENTITY, best_questions, expected_mistakes, task_reading, worth_asking

    if top < 1:
        raise BadValue(f"--top must be at least 1, got {top}")
    min_gain, _, temper, read, ahead = asking(tx.meta.settings())
    mind = load(tx, now).mind
    steps, idx = task_scope(mind, task, objects)
    before = expected_mistakes(mind, steps, idx, temper, task_reading(mind, steps) if read else IDENTITY)
    ranked = (best_questions(mind, steps, idx, top=top, temper=temper, read=read, ahead=ahead,
                             progress=progress) if idx else [])
    return {"task": task, "steps": list(steps), "objects": list(before.objects),
            "expected_mistakes": before.total, "min_gain": min_gain, "temper": temper, "read": read,
            "ahead": ahead,
            "permissions": sum(len(mind.perms[s]) for s in steps),
            "per_object": [{"object": n, "decision": "forbidden" if d else "permitted",
                            "p_forbidden": float(p), "p_wrong": float(w)}
                           for n, d, p, w in zip(before.objects, before.decisions, before.p_forbidden,
                                                 before.p_wrong, strict=True)],
            "questions": [{**s.as_dict(), "worth_asking": worth_asking(s.gain, min_gain)} for s in ranked]}


def questions(ctx: AppContext, task: str = "trashAll", objects: Sequence[str] | None = None,
              top: int = 3, progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """``{"task", "steps", "objects", "expected_mistakes", "permissions", "per_object", "questions"}``
    (``permissions``: how many the task's steps hold; each question's ``worth_asking``: whether its
    gain reaches ``ask.min_gain``, as ``run --ask`` and ``ask --put`` require); writes nothing.
    ``progress`` is told (questions valued, to value) as they are."""
    with ctx.read() as tx:
        return _ranked(tx, ctx.now, task, objects, top, progress)


def pending_questions(tx: Tx) -> dict[str, dict[str, Any]]:
    """Speaker -> the question put to them and not yet answered."""
    value = tx.meta.settings().get(PENDING)
    return dict(value) if isinstance(value, dict) else {}


def pending_for(tx: Tx, speaker: str | None) -> dict[str, Any] | None:
    """The question pending for ``speaker`` (else one put to anyone), or None."""
    table = pending_questions(tx)
    return table.get(speaker or ANYONE) or table.get(ANYONE)


def clear_pending(tx: Tx, speaker: str | None) -> None:
    """Forget the question pending for ``speaker`` (and one put to anyone)."""
    table = pending_questions(tx)
    for key in (speaker or ANYONE, ANYONE):
        table.pop(key, None)
    tx.meta.set_setting(PENDING, table or None)


@use_case
def put(ctx: AppContext, task: str = "trashAll", objects: Sequence[str] | None = None,
        speaker: str | None = None, progress: Callable[[int, int], None] | None = None) -> Done:
    """Put the best question to ``speaker`` (default: the current speaker): pending until answered.
    When its gain is not worth asking by ``ask.min_gain``, nothing is put (``"put": None``) and the
    store is left as it was."""
    from ownctl.mind.ask import worth_asking

    with ctx.read() as tx:
        ranked = _ranked(tx, ctx.now, task, objects, 1, progress)
        who = speaker if speaker is not None else tx.meta.conversation().speaker
        if who is not None:
            tx.world.agent(who)  # an unknown speaker is an error naming the known agents
    if not ranked["questions"]:
        raise OwnctlError(f"there is nothing to ask about {task}: no object is left to decide")
    best = ranked["questions"][0]
    if not worth_asking(best["gain"], ranked["min_gain"]):
        return Done(f"no question is worth asking about {task}: the best ({best['text']}) would save "
                    f"{shown_below(best['gain'], ranked['min_gain'])} expected mistakes, below ask.min_gain "
                    f"{ranked['min_gain']:g}; "
                    "nothing was put", {**ranked, "put": None, "speaker": who})
    with ctx.write({"op": "ask.put", "question": best["text"], "speaker": who}, actor=who) as tx:
        table = pending_questions(tx)
        table[who or ANYONE] = {k: best[k] for k in ("kind", "object", "action", "rule", "text", "gain")}
        tx.meta.set_setting(PENDING, table)
        if best["object"] is not None:
            tx.meta.converse(target=best["object"], action=best["action"] or None)
        if who is not None:
            tx.meta.converse(speaker=who)
    return Done(f"asked {who or 'anyone'}: {best['text']} (expected gain {best['gain']:.3f} mistakes)",
                {**ranked, "put": best, "speaker": who})


def shown_below(gain: float, min_gain: float) -> str:
    """``gain`` with three decimals, or with as many more as it takes not to read as ``min_gain`` or
    above when it is below it (0.04996 against 0.05 is "0.04996", not "0.050")."""
    for digits in range(3, 10):
        text = f"{gain:.{digits}f}"
        if gain >= min_gain or float(text) < min_gain:
            return text
    return f"{gain!r}"

