"""Statements: reprimands, ownership claims, object-specific permissions and general norms.

A reprimand naming an owner is the paper's three-way reading of "No Baxter, that's mine!": a claim
(the object is the speaker's), an object-specific permission (the current action is forbidden on
it) and a norm (the action is forbidden on anything the speaker owns), after stopping the action.
"""

from __future__ import annotations

import re

from ownctl.errors import RuleSyntaxError
from ownctl.language.grammar import Grammar, group
from ownctl.language.instructions import Claim, Instruction, NormInstruction, Permission, Skip
from ownctl.language.lexicon import NOT_NOUNS, hedge_of
from ownctl.language.phrases import Owned, class_literals, owners
from ownctl.language.resolve import Resolver
from ownctl.logic.rules import Literal, Norm, Rule

GRAMMAR = Grammar()

_VERB = r"(?P<verb>is not owned by|is owned by|does not belong to|do not belong to|belongs to|belong to|" \
        r"belongs|is|are)"
_STOP = r"(?:no|nope|stop|wait|whoa|halt|cancel|do not|do not do that|do not do it|stop it|stop that|" \
        r"stop doing that|not that(?: one)?)"
_LEAVE = r"(?:leave|keep away from|stay away from|hands off|keep your hands off)"


def _owned(m: re.Match[str], r: Resolver) -> list[Owned] | None:
    """The owner phrase after the claim verb, with the verb's negation and any opening hedge."""
    verb = group(m, "verb") or "is"
    found = owners(m["rest"], verb in ("is", "are"), "not" in verb.split(), r)
    if found is None:
        return None
    cap = hedge_of((group(m, "think") or "").removesuffix(" that ").strip() or None)
    return [Owned(o.agent, o.negated, o.exclusive, min(o.p, cap)) for o in found]


def _claims(obj: str, found: list[Owned]) -> list[Claim]:
    return [Claim(obj, o.agent, o.p, o.negated, o.exclusive) for o in found]


def _action(m: re.Match[str], r: Resolver, said: str = "that") -> str:
    """The action named in the utterance, else the robot's current action."""
    phrase = group(m, "act")
    return r.action(phrase) if phrase else r.current_action(said)


# -- reprimands ------------------------------------------------------------------------------

@GRAMMAR.rule(
    "reprimand",
    rf"<REPRIMAND><OBJ> {_VERB} (?P<rest>.+)",
    r"(?:(?:no|nope|hey|stop|wait|whoa) )*(?:do not|never) <ACT> <OBJ> (?:because |since |as )?"
    rf"(?:it|that|this|that one|this one) {_VERB} (?P<rest>.+)",
    rf"<OBJ> {_VERB} (?P<rest>.+?) (?:so )?(?:do not|never) <ACT> (?:it|that|this|that one|this one)",
)
def reprimand_claim(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"No, that's mine!", "Don't, that's Casey's!", "Don't throw that away, it's Jake's"."""
    found = _owned(m, r)
    if not found or found[0].negated:
        return None
    obj = r.obj(m["obj"])
    action = _action(m, r)
    norms = [NormInstruction(Norm("forbid", Rule(action, (Literal("ownedBy", o.agent),))))
             for o in found if not o.negated]
    return (Skip(obj), *_claims(obj, found), Permission(action, obj, True), *norms)


@GRAMMAR.rule("reprimand", rf"{_STOP}(?: {_STOP})*", "<FORBID><DO>")
def reprimand(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"No!", "Stop", "Don't do that", "You can't do that": stop, and forbid the action on the object."""
    obj = r.about()
    return (Skip(obj), Permission(r.current_action(m.group()), obj, True))


# -- claims ----------------------------------------------------------------------------------

@GRAMMAR.rule("claim", rf"(?:(?:no|nope|yes|yeah) )?<THINK><OBJ> {_VERB} (?P<rest>.+)",
              r"<THINK>(?P<rest>(?:all |only )?mine(?: alone| now)?)")
def claim(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"This is mine", "That belongs to Xuan", "It's not Jake's", "It's mine now, not Xuan's"."""
    found = _owned(m, r)
    return None if found is None else tuple(_claims(r.obj(group(m, "obj") or "that"), found))


@GRAMMAR.rule(
    "claim",
    r"<THINK>(?P<who>(?!(?:you|who|what|which|whose|does|do) )<NAME>) (?P<neg>do not |does not )?owns? "
    r"<OBJ>(?P<tail> now| alone| too)?",
)
def claim_owns(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"I own this", "Xuan owns that", "Nobody owns this", "Jake doesn't own it"."""
    rest = ("not " if m["neg"] else "") + ("me" if m["who"] == "i" else m["who"]) + (m["tail"] or "")
    found = owners(rest, False, False, r)
    return None if found is None else tuple(_claims(r.obj(m["obj"]), found))


@GRAMMAR.rule(
    "claim",
    r"<THINK>(?P<obj>(?:this|that|it)(?: one)?) is (?P<neg>not )?(?P<who>my|<NAME> 's) (?P<noun><NAME>)"
    r"(?P<tail> now| alone| too)?",
)
def claim_my_noun(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"This is my wallet", "That's not Jake's cup" (the noun names the object when it is one)."""
    if m["noun"] in NOT_NOUNS:
        return None
    who = "mine" if m["who"] == "my" else m["who"]
    found = owners(("not " if m["neg"] else "") + who + (m["tail"] or ""), True, False, r)
    if found is None:
        return None
    obj = r.obj(m["noun"]) if r.is_object(m["noun"]) else r.about(m["obj"])
    return tuple(_claims(obj, found))


# -- object-specific permissions -------------------------------------------------------------

@GRAMMAR.rule("permission", "<FORBID><ACT> <OBJ>", rf"{_LEAVE} <OBJ>(?: alone)?")
def forbid_object(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Don't throw this wallet away", "Don't trash that", "Leave that alone" (= don't pick it up)."""
    obj = r.obj(m["obj"])
    return (Permission(r.action(group(m, "act") or "touch"), obj, True),)


@GRAMMAR.rule("permission", "<ALLOW><ACT> <OBJ>")
def allow_object(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"You can pick that up", "You may collect it", "It's ok to throw that away"."""
    obj = r.obj(m["obj"])
    return (Permission(r.action(m["act"]), obj, False),)


@GRAMMAR.rule("permission", r"(?:go ahead|carry on|that is (?:ok|fine)|it is (?:ok|fine)|<ALLOW><DO>)")
def allow_current(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Go ahead", "You can do that", "That's fine": allow the current action on the object."""
    obj = r.about()
    return (Permission(r.current_action(m.group()), obj, False),)


# -- norms -----------------------------------------------------------------------------------

def _norm(sign: str, m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """A norm over a class of objects; "do that if/to ..." uses the current action."""
    cond = group(m, "cond")
    if cond is None:
        phrase = m["cls"]
    elif cond.startswith("to "):
        phrase = cond[3:]
    elif cond.startswith(("if ", "when ", "whenever ")):
        phrase = "anything " + cond
    else:
        return None
    literals = class_literals(phrase, r)
    if literals is None:
        return None
    action = r.action(group(m, "act") or "touch") if cond is None else r.current_action("do that")
    rule = Rule(action, literals)
    if rule.is_contradictory():
        raise RuleSyntaxError(f"the norm {rule.text(sign)!r} could never apply (contradictory conditions)")
    return (NormInstruction(Norm(sign, rule)),)


@GRAMMAR.rule("norm", "<FORBID><ACT> (?P<cls>.+)", rf"{_LEAVE} (?P<cls>.+?)(?: alone)?",
              "<FORBID><DO> (?P<cond>.+)")
def forbid_norm(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Don't touch my stuff", "Never trash red things", "Don't do that if it's red"."""
    return _norm("forbid", m, r)


@GRAMMAR.rule("norm", "<ALLOW><ACT> (?P<cls>.+)", "<ALLOW><DO> (?P<cond>.+)")
def allow_norm(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"You can throw away anything red", "You may trash things nobody owns"."""
    return _norm("allow", m, r)
