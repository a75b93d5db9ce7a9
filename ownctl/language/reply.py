"""What the robot answers: a short sentence per intent, naming what it understood.

"No, that's mine!" -> "Sorry about that. Noted: wallet belongs to casey." Questions, requests and
tasks get an acknowledgement only; the application answers them after executing the instruction.
"""

from __future__ import annotations

from collections.abc import Sequence

from ownctl.language.instructions import (
    AskOwner,
    AskPermitted,
    AskWhy,
    Claim,
    Instruction,
    Introduce,
    NormInstruction,
    Permission,
    Request,
    RunTask,
    verb,
)
from ownctl.language.lexicon import ROBOT

Noted = Claim | Permission | NormInstruction


def _notes(instructions: Sequence[Instruction], kind: type[Noted]) -> list[str]:
    """What the robot notes from each instruction of one kind."""
    return [i.say() for i in instructions if isinstance(i, (Claim, Permission, NormInstruction))
            and isinstance(i, kind)]


def _sentence(lead: str, parts: list[str]) -> str:
    return f"{lead}{'; '.join(parts)}." if parts else ""


def _question(i: Instruction) -> str:
    if isinstance(i, AskOwner):
        return f"Let me check who owns {i.object}."
    if isinstance(i, Request):
        return f"I will {verb(i.action)} {i.object} if I am allowed to."
    if isinstance(i, AskPermitted):
        return f"Let me check whether I may {verb(i.action)} {i.object}."
    if isinstance(i, AskWhy):
        return "Let me explain."
    if isinstance(i, RunTask):
        doing = "throwing everything away" if i.task == "trashAll" else "collecting everything"
        return f"Certainly: {doing}."
    return ""


def reply(intent: str, instructions: Sequence[Instruction]) -> str:
    """The robot's answer to one understood sentence."""
    if intent == "reprimand":
        claims = _notes(instructions, Claim)
        tail = _sentence(" Noted: ", claims) if claims else _sentence(" ", _notes(instructions, Permission))
        return "Sorry about that." + tail
    if intent == "claim":
        return _sentence("Noted: ", _notes(instructions, Claim))
    if intent == "permission":
        return _sentence("Noted: ", _notes(instructions, Permission))
    if intent == "norm":
        return _sentence("Understood: ", _notes(instructions, NormInstruction))
    if intent == "introduction":
        names = [i.agent for i in instructions if isinstance(i, Introduce)]
        return f"Hi {names[0]}, I'm {ROBOT}." if names else f"Hi, I'm {ROBOT}."
    if intent == "greeting":
        return f"Hi, I'm {ROBOT}."
    if intent == "thanks":
        return "You're welcome."
    if intent == "remark":
        return "I see."
    return " ".join(filter(None, (_question(i) for i in instructions)))
