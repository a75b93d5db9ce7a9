"""Answers to the robot's own question (docs/asking.md, section 5).

When the robot has put a question to a speaker (``ownctl ask --put``), that speaker's next utterance
is first read as its answer, into the same instructions as any claim, permission or norm:

- "May I ACTION OBJ?": a yes ("yes", "you may", "sure, go ahead") -> ``allow ACTION on OBJ``; a no
  ("no", "you may not", "no way, don't") -> ``forbid ACTION on OBJ``; or a sentence that says
  exactly that permission of OBJ ("No, don't throw it away"; "Yes, throw it away" asks for what
  was asked), perhaps with the reason it gives ("No, that's Casey's": claims about OBJ and the
  norm they imply, as the sentence says anyway), read with OBJ and ACTION as "it" and "do that";
- "Does RULE hold?": a yes -> the norm ``forbid ...``; a no -> its allow norm ``allow ...``
  (nothing it describes is forbidden); "partly", "sometimes", "not always" -> nothing is taught;
- "Whose is OBJ?": an ownership statement ("it's Jake's", "mine", "nobody's", "Jake and Casey's")
  -> its claims about OBJ, and every agent it does not name "not theirs" (the answer names the
  owners);
- to any of them, "I don't know" (or "no idea", "not sure") answers without teaching anything.

A short reply is read clause by clause (between punctuation marks): every clause must be a yes,
or every one a no (courtesies such as "thanks" aside), so "Sure, go ahead, thanks!" is a yes and
"Yes... no" is no answer. Anything else is not an answer (None): the utterance is understood as
usual and the question stays pending. Pure: no I/O.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from ownctl.errors import OwnctlError
from ownctl.language.context import Context
from ownctl.language.instructions import Claim, Instruction, NormInstruction, Permission, Request, Skip
from ownctl.language.normalize import normalize
from ownctl.logic.rules import Norm, parse_rule

YES = ("yes", "yes you may", "you may", "yes you can", "you can", "sure", "go ahead", "ok", "okay",
       "yes please", "yes go ahead", "of course", "yes of course", "yep", "yeah", "yup", "it is fine", "fine",
       "yes it does", "it does", "yes it holds", "it holds", "always", "yes always", "absolutely",
       "certainly", "definitely", "indeed", "yes indeed", "correct", "that is correct", "right",
       "that is right", "true", "that is true", "it is true", "go on", "go for it", "please do",
       "by all means", "be my guest", "sure thing", "no problem", "that is fine", "it is ok", "that is ok",
       "you are allowed", "you have my permission", "it is allowed", "yes it is", "it is", "yes it is true",
       "fine by me", "fine with me", "ok by me", "ok with me", "go right ahead", "help yourself", "why not",
       "sure go ahead", "of course you may", "yes you are")
NO = ("no", "no you may not", "you may not", "no you can not", "you can not", "do not", "no do not",
      "please do not", "no please do not", "nope", "no it does not", "it does not", "never",
      "no never", "no it does not hold", "it does not hold", "not at all", "no way", "of course not",
      "absolutely not", "certainly not", "definitely not", "not really", "by no means", "better not",
      "you must not", "you should not", "you are not allowed", "it is not allowed", "do not do that",
      "do not do it", "not true", "that is not true", "it is not true", "false", "wrong", "that is wrong",
      "no it is not", "it is not", "not ok", "that is not ok", "it is not ok",
      "i would rather you did not", "i would prefer you did not", "i would prefer not", "rather not",
      "i would rather not", "please do not do that", "no you are not", "no thank you")
PARTLY = ("partly", "sometimes", "not always", "it depends", "in part", "only sometimes", "some of them",
          "partially", "in some cases", "depends", "mostly", "usually", "generally", "often", "mostly yes",
          "mostly not", "not usually", "rarely", "seldom", "occasionally")
DONT_KNOW = ("i do not know", "do not know", "no idea", "i have no idea", "not sure", "i am not sure",
             "dunno", "i dunno", "no clue", "i have no clue", "who knows", "i can not say", "can not say",
             "hard to say", "i can not tell", "i am not certain", "not certain", "i do not remember",
             "i forget", "beats me", "ask someone else")
COURTESY = ("thanks", "thank you", "sorry", "hi", "hello", "hey")
READINGS: tuple[tuple[str, tuple[str, ...]], ...] = (("yes", YES), ("no", NO), ("partly", PARTLY),
                                                      ("unknown", DONT_KNOW))
_CLAUSES = re.compile(r"[,.;:!?\u2013\u2014]+|\s-+\s")


def reading(utterance: str) -> str | None:
    """``"yes"``, ``"no"``, ``"partly"`` or ``"unknown"`` when ``utterance`` is one such reply as a
    whole, or clause by clause with every clause the same one (courtesies aside); None otherwise."""
    return _read(utterance)[0]


def _read(utterance: str) -> tuple[str | None, bool]:
    """:func:`reading`, and whether clauses of ``utterance`` say both yes and no ("yes... no")."""
    whole = _label(normalize(utterance))
    if whole is not None:
        return whole, False
    words = (normalize(clause) for clause in _CLAUSES.split(utterance))
    labels = {_label(w) for w in words if w and w not in COURTESY}  # None: a clause that is no reply
    return (next(iter(labels)) if len(labels) == 1 else None), {"yes", "no"} <= labels


def _label(words: str) -> str | None:
    """The reply ``words`` (normalised) are, a courtesy at either end aside ("no thanks")."""
    for courtesy in COURTESY:
        words = words.removesuffix(f" {courtesy}").removeprefix(f"{courtesy} ")
    return next((name for name, phrases in READINGS if words in phrases), None)


def answer_instructions(utterance: str, question: Mapping[str, Any], ctx: Context
                        ) -> tuple[Instruction, ...] | None:
    """The instructions ``utterance`` means as the answer to ``question`` (a pending question's
    ``{"kind", "object", "action", "rule"}``), or None if it is no answer to it."""
    label, mixed = _read(utterance)
    if label == "unknown":  # an answer, which teaches nothing
        return ()
    kind = question.get("kind")
    if kind == "may":
        if label in ("yes", "no"):
            return (Permission(str(question["action"]), str(question["object"]), forbid=label == "no"),)
        if mixed:  # "yes... no": no answer
            return None
        return _permission(utterance, str(question["action"]), str(question["object"]), ctx)
    if kind == "rule":
        rule = parse_rule(str(question["rule"]))
        if label in ("yes", "no"):
            return (NormInstruction(Norm("forbid" if label == "yes" else "allow", rule)),)
        return () if label == "partly" else None
    if kind == "whose":
        return _owners(utterance, str(question["object"]), ctx)
    return None


def _permission(utterance: str, action: str, obj: str, ctx: Context) -> tuple[Instruction, ...] | None:
    """The permission of ``action`` on ``obj`` a sentence states ("No, don't throw it away"), with
    the claims about ``obj`` it makes beside it ("No, that's Casey's"), read with ``obj`` and
    ``action`` as what "it" and "do that" refer to; None if it states anything else."""
    from ownctl.language.understand import understand

    try:
        understood = understand(utterance, replace(ctx, about=obj, action=action))
    except OwnctlError:
        return None
    # a reprimand ("No, don't throw it away!") also stops the action, which is not under way here;
    # a request to do it ("Yes, throw it away") lets the robot do it
    asked = (action, obj)
    said = tuple(dict.fromkeys(
        Permission(action, obj, forbid=False) if type(i) is Request and (i.action, i.object) == asked else i
        for i in understood.instructions if not (isinstance(i, Skip) and i.object == obj)))
    permissions = [i for i in said if isinstance(i, Permission)]
    if len(permissions) != 1 or (permissions[0].action, permissions[0].object) != asked:
        return None
    # the reason it gives, as the ordinary reading of the sentence does: whose it is, and the norm
    # that makes it so ("No, that's Casey's": "forbid trash if ownedBy casey")
    reasons = all(isinstance(i, Permission | Claim) and i.object == obj
                  or isinstance(i, NormInstruction) and i.norm.rule.action == action for i in said)
    return said if reasons else None


def _owners(utterance: str, obj: str, ctx: Context) -> tuple[Instruction, ...] | None:
    """The claims of an ownership statement about ``obj``, completed with "not theirs" for every
    agent it does not name, as sure as the statement ("Casey's, I think": the others' at 0.8); a
    statement that only denies ("not mine") says nothing of the others; None if the utterance states
    no ownership of ``obj``."""
    from ownctl.language.understand import understand

    try:
        understood = understand(utterance, replace(ctx, about=obj))
    except OwnctlError:  # no answer: the utterance is then understood as usual, and errs as usual
        return None
    claims = [i for i in understood.instructions if isinstance(i, Claim) and i.object == obj]
    if not claims or len(claims) != len(understood.instructions):
        return None
    if all(c.negated for c in claims):
        return tuple(claims)  # "not Jake's": nothing about the others ("nobody's" names them all)
    named = {c.agent for c in claims}
    sure = min(c.p for c in claims if not c.negated)
    rest = tuple(Claim(obj, a, sure, negated=True) for a in sorted(ctx.agents - named))
    return tuple(replace(c, exclusive=False) for c in claims) + rest


__all__ = ["DONT_KNOW", "NO", "PARTLY", "YES", "answer_instructions", "reading"]
