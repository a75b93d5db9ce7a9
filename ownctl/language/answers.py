"""Answers to the robot's own question (docs/asking.md, section 5).

When the robot has put a question to a speaker (``ownctl ask --put``), that speaker's next utterance
is first read as its answer, into the same instructions as any claim, permission or norm:

- "May I ACTION OBJ?": "yes", "you may", "sure", "go ahead" -> ``allow ACTION on OBJ``; "no",
  "you may not", "don't" -> ``forbid ACTION on OBJ``;
- "Does RULE hold?": "yes" -> the norm ``forbid ...``; "no" -> its allow norm ``allow ...`` (nothing
  it describes is forbidden); "partly", "sometimes", "not always" -> nothing is taught;
- "Whose is OBJ?": an ownership statement ("it's Jake's", "mine", "nobody's", "Jake and Casey's")
  -> its claims about OBJ, and every agent it does not name "not theirs" (the answer names the
  owners).

Anything else is not an answer (None): the utterance is understood as usual and the question stays
pending. Pure: no I/O.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from ownctl.language.context import Context, NotUnderstood
from ownctl.language.instructions import Claim, Instruction, NormInstruction, Permission
from ownctl.language.normalize import normalize
from ownctl.logic.rules import Norm, parse_rule

YES = ("yes", "yes you may", "you may", "yes you can", "you can", "sure", "go ahead", "ok", "okay",
       "yes please", "yes go ahead", "of course", "yes of course", "yep", "yeah", "it is fine", "fine",
       "yes it does", "it does", "yes it holds", "it holds", "always", "yes always")
NO = ("no", "no you may not", "you may not", "no you can not", "you can not", "do not", "no do not",
      "please do not", "no please do not", "nope", "no it does not", "it does not", "never",
      "no never", "no it does not hold", "it does not hold", "not at all")
PARTLY = ("partly", "sometimes", "not always", "it depends", "in part", "only sometimes", "some of them")


def answer_instructions(utterance: str, question: Mapping[str, Any], ctx: Context
                        ) -> tuple[Instruction, ...] | None:
    """The instructions ``utterance`` means as the answer to ``question`` (a pending question's
    ``{"kind", "object", "action", "rule"}``), or None if it is no answer to it."""
    words = normalize(utterance)
    kind = question.get("kind")
    if kind == "may":
        if words in YES or words in NO:
            return (Permission(str(question["action"]), str(question["object"]), forbid=words in NO),)
        return None
    if kind == "rule":
        rule = parse_rule(str(question["rule"]))
        if words in YES or words in NO:
            return (NormInstruction(Norm("forbid" if words in YES else "allow", rule)),)
        return () if words in PARTLY else None
    if kind == "whose":
        return _owners(utterance, str(question["object"]), ctx)
    return None


def _owners(utterance: str, obj: str, ctx: Context) -> tuple[Instruction, ...] | None:
    """The claims of an ownership statement about ``obj``, completed with "not theirs" for every
    agent it does not name; None if the utterance states no ownership of ``obj``."""
    from ownctl.language.understand import understand

    try:
        understood = understand(utterance, replace(ctx, about=obj))
    except NotUnderstood:
        return None
    claims = [i for i in understood.instructions if isinstance(i, Claim) and i.object == obj]
    if not claims or len(claims) != len(understood.instructions):
        return None
    named = {c.agent for c in claims}
    rest = tuple(Claim(obj, a, negated=True) for a in sorted(ctx.agents - named))
    if all(c.negated for c in claims):
        return tuple(claims) + rest  # "not Jake's": nothing about the others
    return tuple(replace(c, exclusive=False) for c in claims) + rest


__all__ = ["NO", "PARTLY", "YES", "answer_instructions"]
