"""Statements: reprimands, ownership claims, object-specific permissions and general norms.

A reprimand naming an owner is the paper's three-way reading of "No Baxter, that's mine!": a claim
(the object is the speaker's), an object-specific permission (the current action is forbidden on
it) and a norm (the action is forbidden on anything the speaker owns), after stopping the action.
Said while the robot is doing nothing, the same words are a bare claim.

A prohibition or permission that names the object by its owner ("don't throw away Jake's mug")
also states that ownership. A norm's class of objects may carry "or" (two rules), "unless" (the
exception's negation) and a restrictive "only" ("only throw away things nobody owns" forbids the
rest); a condition may come first ("if it's Xuan's, don't collect it", "anything nobody owns, you
can throw away") and the action may be a gerund ("stop throwing away my things") or a passive
("things owned by Casey should never be thrown away").
"""

from __future__ import annotations

import re
from itertools import product

from ownctl.errors import OwnctlError, RuleSyntaxError
from ownctl.language.context import NotUnderstood
from ownctl.language.grammar import FRAGMENTS, Grammar, group
from ownctl.language.instructions import Claim, Instruction, NormInstruction, Permission, Skip
from ownctl.language.lexicon import (
    BIN_WORDS,
    DEICTIC,
    DONT_KNOW,
    GERUNDS,
    NOT_NOUNS,
    PASSIVES,
    actions_regex,
    alternation,
    hedge_of,
)
from ownctl.language.phrases import Owned, class_alternatives, condition_phrase, owners
from ownctl.language.resolve import NOBODY, Decline, Resolver, split_determiner
from ownctl.logic.rules import ANY, Literal, Norm, Rule

GRAMMAR = Grammar()

_VERB = r"(?P<verb>is not owned by|is owned by|does not belong to|do not belong to|belongs to|belong to|" \
        r"belongs|is|are|'s)"
_STOP = r"(?:no|nope|stop|wait|whoa|halt|cancel|do not|do not do that|do not do it|stop it|stop that|" \
        r"stop doing that|not that(?: one)?)"
_LEAVE = r"(?:leave|keep away from|stay away from|hands off|keep your hands off|keep off)"
_IT = r"(?:it|that|this|that one|this one|them|those|these)"
#: where a thing left alone stays: "leave the mug where it is", "leave the red ones in place"
_IN_PLACE = r"(?: alone| be| where (?:it is|they are)| in place| there)"
#: "the mug stays put", "red things on the shelf must stay where they are" (= do not pick up)
_STAY = (r"(?:(?:must|should|has to|have to|needs to|need to|is to|are to) )?(?:stay|stays|remain|remains) "
         r"(?:put|where (?:it is|they are)|in place|there)")
_GERUND = rf"(?P<act>{actions_regex(forms=GERUNDS)})"
_PASSIVE = rf"(?P<act>{actions_regex(forms=PASSIVES)})"
_OK = r"(?:ok|fine|allowed|safe|alright|permitted|free)"
#: "in the bin", "into the trash": where thrown-away things go
_IN_BIN = rf"(?:in|into|in to) (?:the |a )?{alternation(BIN_WORDS)}"
_AND_NOR = re.compile(r" (?:and|nor) ")
_PROHIBITION = re.compile(FRAGMENTS["FORBID"])
#: A class or subject phrase longer than this is no phrase (the rule declines at once).
MAX_PHRASE_WORDS = 14


_POSSESSED = re.compile(r"(?P<neg>not )?(?P<who>my|his|her|their|\S+ 's) (?P<noun>.+)")
_POSSESSIVE_OF = {"my": "mine", "her": "hers", "their": "theirs"}


def _named_again(rest: str, m: re.Match[str], r: Resolver) -> str | None:
    """The owner phrase of ``rest`` when it names the match's object again ("it's Jake's bottle"
    of the bottle: "Jake's"), or None."""
    said = _POSSESSED.fullmatch(rest)
    if said is None or said["noun"].split()[-1] in NOT_NOUNS:
        return None
    try:
        same = r.obj(said["noun"]) == r.obj(group(m, "obj") or "that")
    except (OwnctlError, Decline):
        return None
    return (said["neg"] or "") + _POSSESSIVE_OF.get(said["who"], said["who"]) if same else None


def _owned(m: re.Match[str], r: Resolver, again: bool = False) -> list[Owned] | None:
    """The owner phrase after the claim verb, with the verb's negation and any opening hedge;
    with ``again``, the phrase may name the object once more ("it's Jake's mug")."""
    verb = group(m, "verb") or "is"
    possessive, negated = verb in ("is", "are", "'s"), "not" in verb.split()
    found = owners(m["rest"], possessive, negated, r)
    if found is None and again and possessive and (bare := _named_again(m["rest"], m, r)) is not None:
        found = owners(bare, possessive, negated, r)
    if found is None:
        return None
    cap = hedge_of((group(m, "think") or "").removesuffix(" that ").strip() or None)
    exclusive = bool(group(m, "now"))
    # a transfer ("now it's Jake's") is exclusive; to joint owners ("now it's Jake's and Mia's") only
    # the first claim is, so that it clears the others before the next one is stored
    first = next((k for k, o in enumerate(found) if not o.negated), None)
    return [Owned(o.agent, o.negated, o.exclusive or (exclusive and k == first), min(o.p, cap))
            for k, o in enumerate(found)]


def _claims(obj: str, found: list[Owned]) -> list[Claim]:
    return [Claim(obj, o.agent, o.p, o.negated, o.exclusive) for o in found]


def _acting(r: Resolver) -> bool:
    """True if the robot is doing something now (so a reprimand stops it)."""
    return r.ctx.action is not None


def _owner_claim(phrase: str, obj: str, r: Resolver) -> list[Claim]:
    """The claim a possessive object phrase makes ("Jake's mug": the mug is Jake's)."""
    who = r.possessor(phrase)
    return [] if who is None else [Claim(obj, who)]


# -- reprimands ------------------------------------------------------------------------------

def owner_norm(action: str, agent: str) -> NormInstruction:
    """``forbid ACTION if ownedBy AGENT``: the norm a reprimand or a prohibition with its reason
    ("don't, it's Casey's") states for the owner it names."""
    return NormInstruction(Norm("forbid", Rule(action, (Literal("ownedBy", agent),))))


def _reprimand(obj: str, found: list[Owned], action: str | None, r: Resolver) -> tuple[Instruction, ...]:
    """Stop (if acting), the claims, and -- when there is an action -- the permission and norms."""
    claims = _claims(obj, found)
    if action is None:
        return tuple(claims)
    norms = [owner_norm(action, o.agent) for o in found if not o.negated]
    skip = [Skip(obj)] if _acting(r) else []
    return (*skip, *claims, Permission(action, obj, True), *norms)


@GRAMMAR.rule(
    "reprimand",
    rf"<REPRIMAND><OBJ> {_VERB} (?P<rest>.+)",
    r"(?:(?:no|nope|hey|stop|wait|whoa) )*(?:do not|never) <ACT> <OBJ> (?:because |since |as )?"
    rf"(?:it|that|this|that one|this one) {_VERB} (?P<rest>.+)",
    rf"<OBJ> {_VERB} (?P<rest>.+?) (?:so )?(?:do not|never) <ACT> (?:it|that|this|that one|this one)",
    r"(?:(?:no|nope|hey|stop|wait|whoa) )*(?P<obj>that|this|it)(?: one)? is not (?:yours|for you) to <ACT> "
    rf"(?:because |since |as )?(?:it|that|this|that one|this one) {_VERB} (?P<rest>.+)",
)
def reprimand_claim(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"No, that's mine!", "Don't, that's Casey's!", "Don't throw that away, it's Jake's (mug)"."""
    found = _owned(m, r, again=True)
    if not found or found[0].negated:
        return None
    obj = r.obj(m["obj"])
    named = group(m, "act")
    action = r.action(named) if named else (r.ctx.action and r.current_action())
    return _reprimand(obj, found, action, r)


_REASON = rf" (?:because |since |as )?(?:it|that|this|that one|this one|they) {_VERB} (?P<rest>.+)"


@GRAMMAR.rule(
    "reprimand",
    rf"(?:(?:no|nope|hey|stop|wait|whoa) )*put back <OBJ>(?:{_REASON})?",
    rf"(?:(?:no|nope|hey|stop|wait|whoa) )*put down <OBJ>{_REASON}",
    rf"(?:(?:no|nope|hey|stop|wait|whoa) )*{_LEAVE} <OBJ>{_IN_PLACE}?{_REASON}",
)
def reprimand_leave(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Put the book back, that's Mia's!" (stops the robot if it is acting; without a reason, only
    that and "do not pick it up"), "Put that down, it's Mia's" (without a reason, "put that down"
    asks to put it down), "Leave the mug alone, it's Jake's" (a prohibition with its reason: the
    claim and the owner's norm too, as a reprimand; "it's Mia's scarf" is such a reason too)."""
    obj = r.obj(m["obj"])
    action = r.action("touch")
    if group(m, "rest") is None:
        return (*([Skip(obj)] if _acting(r) else []), Permission(action, obj, True))
    found = _owned(m, r, again=True)
    if not found or found[0].negated:
        return None
    return _reprimand(obj, found, action, r)


@GRAMMAR.rule(
    "reprimand",
    r"<REPRIMAND>(?P<obj>this|that|it)(?: one)? is (?P<who>my|<NAME> 's) (?P<noun><NAME>)",
    r"(?:<REPRIMAND>)?(?P<obj>this|that|it)(?: one)? is (?P<who>my|<NAME> 's) (?P<noun><NAME>) "
    rf"(?:that |which )?you are {_GERUND}",
)
def reprimand_my_noun(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Hey, that's my scarf!" while the robot handles it; "That's my phone you're throwing
    away!" (the action said)."""
    if m["noun"] in NOT_NOUNS:
        return None
    found = owners("mine" if m["who"] == "my" else m["who"], True, False, r)
    if not found:
        return None
    obj = r.obj(m["noun"]) if r.is_object(m["noun"]) else r.about(m["obj"])
    named = group(m, "act")
    return _reprimand(obj, found, r.action(named) if named else (r.ctx.action and r.current_action()), r)


@GRAMMAR.rule("reprimand", rf"{_STOP}(?: {_STOP})*", "<FORBID><DO>")
def reprimand(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"No!", "Stop", "Don't do that", "You can't do that": stop, and forbid the action on the object."""
    obj = r.about()
    return (Skip(obj), Permission(r.current_action(m.group()), obj, True))


@GRAMMAR.rule("norm", r"(?P<cls>.+?) (?:is|are) (?:off limits|off-limits|out of bounds|not to be touched)"
                      r"(?: (?:to|for) you)?")
def off_limits(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Jake's stuff is off limits" (not to be picked up: a norm), "The mug is off limits" (a
    permission about one object). Before the claims: "... are off limits" names no owner."""
    return _subject_norm("forbid", m["cls"], "touch", r)


# -- claims ----------------------------------------------------------------------------------

@GRAMMAR.rule("claim", rf"(?:(?:no|nope|yes|yeah) )?(?P<now>now )?<THINK><LOBJ> {_VERB} (?P<rest>.+)",
              r"<THINK>(?P<rest>(?:not )?(?:all |only )?(?:mine|<NAME> 's)(?: .+)?)",
              r"<THINK>(?P<verb>belongs to|does not belong to|owned by|not owned by) (?P<rest>.+)")
def claim(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"This is mine", "That belongs to Xuan", "It's not Jake's", "The mug's mine", "The mug on the
    table is mine", "Not mine",
    "(but) now it's Jake's" (a transfer: Jake's alone); without its subject, of the object in
    question ("Belongs to nobody", "Owned by Mia")."""
    found = _owned(m, r)
    return None if found is None else tuple(_claims(r.obj(group(m, "obj") or "that"), found))


@GRAMMAR.rule(
    "claim",
    r"<THINK>(?P<who>(?!(?:you|who|what|which|whose|does|do) )<NAME>) (?P<neg>do not |does not )?owns? "
    r"<OBJ>(?P<tail> now| alone| too)?(?: not (?P<other>me|<NAME>))?",
)
def claim_owns(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"I own this", "Xuan owns that", "Nobody owns this", "Casey owns it now, not me"."""
    rest = ("not " if m["neg"] else "") + ("me" if m["who"] == "i" else m["who"]) + (m["tail"] or "")
    if m["other"]:
        rest += " not " + m["other"]
    found = owners(rest, False, False, r)
    return None if found is None else tuple(_claims(r.obj(m["obj"]), found))


@GRAMMAR.rule("claim", r"<THINK>neither (?P<a>i|me|<NAME>) nor (?P<b>i|me|<NAME>) (?:owns?|do|does) <OBJ>",
              r"<THINK><OBJ> (?:belongs|belong) to neither (?P<a>me|<NAME>) nor (?P<b>me|<NAME>)")
def claim_neither(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Neither Jake nor Mia owns the can", "It belongs to neither me nor Xuan": not theirs."""
    agents = _two_owners(m, r)
    return None if agents is None else tuple(Claim(r.obj(m["obj"]), a, negated=True) for a in agents)


def _two_owners(m: re.Match[str], r: Resolver) -> list[str] | None:
    """The two agents named by groups ``a`` and ``b`` ("I"/"me": the speaker), or None unless they
    are two different agents (not "someone", not "nobody")."""
    agents = [r.owner("me" if w in ("i", "me") else w) for w in (m["a"], m["b"])]
    return None if agents[0] == agents[1] or {ANY, NOBODY} & set(agents) else agents


@GRAMMAR.rule("claim", rf"<THINK><OBJ> {_VERB} (?P<rest>.+?),? and so (?:is|are|does|do) (?P<also>.+)")
def claim_and_so(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"The scarf is mine and so is the wallet": the same owners for both objects."""
    if len(m["also"].split()) > 4:
        return None
    found = _owned(m, r)
    if found is None:
        return None
    return (*_claims(r.obj(m["obj"]), found), *_claims(r.obj(m["also"]), found))


@GRAMMAR.rule(
    "claim",
    r"<THINK>(?P<obj>(?:this|that|it)(?: one)?|these|those|they) (?:is|are) (?P<neg>not )?"
    r"(?P<who>my|<NAME> 's|<NAME>(?: 's)? and (?:my|<NAME> 's)) (?P<noun><NAME>)"
    r"(?P<tail> now| alone| too)?",
)
def claim_my_noun(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"This is my wallet", "That's not Jake's cup", "This is Jake and Mia's mug" (both own it; the
    noun names the object when it is one)."""
    if m["noun"] in NOT_NOUNS:
        return None
    who = re.sub(r"\bmy$", "mine", m["who"])  # "my" and "Jake and my" as owner phrases
    found = owners(("not " if m["neg"] else "") + who + (m["tail"] or ""), True, False, r)
    if found is None:
        return None
    obj = r.obj(m["noun"]) if r.is_object(m["noun"]) else r.about(m["obj"])
    return tuple(_claims(obj, found))


_WHO = r"(?!(?:who|what|which|whose|you|it|this|that|there|here)\b)"


@GRAMMAR.rule("claim", rf"<THINK>(?P<who>i|me|{_WHO}<NAME>) (?:am|is|are) the (?:owner|owners) of <OBJ>",
              rf"<THINK>(?P<who>i|{_WHO}<NAME>|nobody) (?:do|does)(?: too| as well)?",
              r"(?P<who>nobody)")
def claim_owner_is(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Jake is the owner of that"; the answers "Jake does", "I do", "Nobody does"."""
    who = "me" if m["who"] in ("i", "me") else m["who"]
    found = owners(who, False, False, r)
    return None if found is None else tuple(_claims(r.obj(group(m, "obj") or "that"), found))


@GRAMMAR.rule("claim", r"<OBJ> (?:used to be|was) (?P<rest>(?:mine|<NAME> 's)(?: and (?:mine|<NAME> 's))?)",
              r"<OBJ> (?:used to belong|belonged) to (?P<to>me|<NAME>)",
              r"<OBJ> (?:is|are) (?:not|no longer) (?P<rest>mine|<NAME> 's) (?:anymore|any more|now)"
              r"(?: (?:but )?(?:now )?(?:it|they) (?:is|are) (?P<new>mine|<NAME> 's)(?: now)?)?")
def claim_former(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"It used to be mine", "The notebook was Jake's", "It's not Casey's anymore, it's Mia's": the
    former owners own it no longer (and a new owner named with them owns it alone)."""
    rest = group(m, "rest") or ("mine" if m["to"] == "me" else m["to"])
    found = owners(rest, group(m, "to") is None, False, r)
    if not found or any(o.negated for o in found):
        return None
    obj = r.obj(m["obj"])
    out = [Claim(obj, o.agent, o.p, negated=True) for o in found]
    if group(m, "new"):
        out += [Claim(obj, o.agent, o.p, exclusive=True) for o in owners(m["new"], True, False, r) or []]
    return tuple(out)


_GIVE = r"(?:just |have |has |had |will |already )?(?:gave|give|gives|given|giving|sold|sell|sells|" \
        r"selling|handed|hand|hands|handing|passed|pass|passes|passing|donated|traded)(?: over)?"


_LENT = r"(?:have |has |had )?(?:lent|loaned|lend|lends)"
_LENDER = rf"(?P<owner>i|we|he|she|they|{_WHO}<NAME>)"
_BORROWER = r"(?P<to>me|us|him|her|them|<NAME>)"


@GRAMMAR.rule("claim",
              rf"{_LENDER} {_LENT} {_BORROWER} <OBJ>",
              rf"{_LENDER} {_LENT} <OBJ> to {_BORROWER}",
              r"(?:i|we) (?:am |are |have |had )?(?:borrowed|borrowing|borrow) <OBJ> from "
              r"(?P<owner>him|her|them|<NAME>)",
              r"<OBJ> (?:is|was|are|were) (?:borrowed|on loan) from (?P<owner>him|her|them|<NAME>)")
def claim_lent(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Mia lent me the book", "I lent Casey my phone", "I borrowed the pen from Jake", "The scarf
    is on loan from Xuan": the lender still owns it (who holds it now is not said to own it)."""
    owner = r.owner("me" if m["owner"] in ("i", "we") else m["owner"])
    to = group(m, "to")
    holder = r.ctx.speaker if to is None else r.owner("me" if to in ("me", "us") else to)
    if owner in (ANY, NOBODY) or owner == holder:
        return None
    return (Claim(r.obj(m["obj"]), owner),)


@GRAMMAR.rule("claim", rf"(?P<giver>i|he|she|they|{_WHO}<NAME>) (?:am |is |are )?{_GIVE} <OBJ> (?:over )?to "
                       rf"(?P<to>me|him|her|them|<NAME>)(?: now)?",
              rf"(?P<giver>i|he|she|they|{_WHO}<NAME>) (?:am |is |are )?{_GIVE} "
              r"(?P<to>me|him|her|them|<NAME>) <OBJ>")
def claim_gift(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"I gave the book to Mia", "Jake gave me his pen", "I'm giving this to Casey": the giver owns
    it no longer, the receiver owns it alone."""
    giver = r.owner("me" if m["giver"] == "i" else m["giver"])
    taker = r.owner(m["to"])
    if giver == taker or NOBODY in (giver, taker):
        return None
    obj = r.obj(m["obj"])
    return (Claim(obj, giver, negated=True), Claim(obj, taker, exclusive=True))


@GRAMMAR.rule("claim",
              rf"<THINK>(?:both )?(?P<a>i|{_WHO}<NAME>) and (?P<b>i|me|{_WHO}<NAME>) (?:both )?"
              r"(?:share|co-own|own) <OBJ>(?: together| jointly)?",
              rf"<THINK>(?P<a>i|{_WHO}<NAME>) (?:share|shares|owns?) <OBJ> (?:with|together with) "
              r"(?P<b>me|<NAME>)",
              r"<THINK><OBJ> (?:belongs|belong) to (?P<a>me|<NAME>) as well as (?P<b>me|<NAME>)",
              r"<THINK><OBJ> (?:is|are) (?:shared|co-owned|owned jointly|jointly owned) by (?P<a>me|<NAME>) "
              r"and (?P<b>me|<NAME>)")
def claim_shared(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Jake and I share the bottle", "Both Jake and Mia own it", "I share the lamp with Mia", "Jake
    owns it with Mia", "It belongs to Jake as well as Mia", "The bottle is shared by Jake and Casey":
    each of the two owns it (neither alone)."""
    agents = _two_owners(m, r)
    return None if agents is None else tuple(Claim(r.obj(m["obj"]), a) for a in agents)


def _subjects(phrase: str, r: Resolver) -> tuple[list[str], bool] | None:
    """The objects a plural subject names, and whether it denies ("none of", "neither ... nor"):
    "the pen and the notebook", "both ...", "the blocks", "everything on the shelf"."""
    if len(phrase.split()) > MAX_PHRASE_WORDS:
        return None
    negated = False
    for lead, neg in (("none of ", True), ("neither ", True), ("both ", False), ("all of ", False)):
        if phrase.startswith(lead):
            phrase, negated = phrase[len(lead):], neg
            break
    parts = _AND_NOR.split(phrase)
    if len(parts) > 1:
        return [r.obj(p) for p in parts], negated
    alternatives = class_alternatives(phrase, r)
    if alternatives is None:
        return None
    found = {o for alt in alternatives for o in r.select(alt, phrase)}
    return sorted(found), negated


_FINE = r"(?:ok|fine|allowed|alright|permitted)"


@GRAMMAR.rule("norm", rf"(?P<cls>.+?) (?:is|are) (?P<neg>not )?{_FINE}(?: too| as well)?")
def fine_norm(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Red ones are fine", "Jake's things are not ok", said while the robot does something: the
    norm for what it does on that class. A class without its head word is the same class ("red is
    fine": red ones). Only a class with a condition: said of one thing ("the mug is fine") or of
    everything, it may tell how things are rather than what may be done with them. It is tried
    before the claims about many objects, which would look for "Jake's things" among the objects
    seen and fail."""
    if r.ctx.action is None:
        return None
    sign = "forbid" if m["neg"] else "allow"
    action = r.current_action("do that")
    for phrase in (m["cls"], f"{m['cls']} ones"):
        alternatives = _alternatives(phrase, sign, action, r)
        if alternatives is not None:
            return None if any(not alt for alt in alternatives) else _rules(sign, action, alternatives)
    return None


@GRAMMAR.rule("claim", r"<THINK>(?P<subj>.+?) (?P<verb>are|is) (?:all |both )?(?P<rest>.+)",
              r"<THINK>(?P<subj>.+?) (?:all )?(?P<verb>belong to|belongs to|do not belong to|"
              r"does not belong to|are owned by|are not owned by|is owned by) (?P<rest>.+)")
def claim_many(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"The blocks are all mine", "Everything on the shelf is mine", "Both the pen and the notebook
    are mine", "None of the blocks are mine": one claim per object."""
    subjects = _subjects(m["subj"], r)
    if subjects is None:
        return None
    objects, negated = subjects
    found = _owned(m, r)
    if not found:
        return None
    if negated:
        if any(o.negated or o.exclusive for o in found):
            return None
        found = [Owned(o.agent, True, False, o.p) for o in found]
    return tuple(c for obj in objects for c in _claims(obj, found))


@GRAMMAR.rule("claim", r"not (?P<who>me|<NAME>)")
def claim_not(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"..., not me" / "not Jake": the object in question is not theirs."""
    who = m["who"]
    if who != "me" and not r.is_agent(who):
        return None
    found = owners("not " + who, False, False, r)
    return None if found is None else tuple(_claims(r.about(), found))


@GRAMMAR.rule("claim", r"<OBJ>(?: (?:over )?(?:there|here))?")
def topic(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"The scarf?", "That phone over there?": names what the next sentence is about (nothing to
    store); a bare "this" or "that one" names nothing new."""
    phrase = re.sub(r"(?: over)? (?:there|here)$", "", m["obj"])
    if phrase in DEICTIC or phrase.split()[0] == "it" or not r.is_object(phrase.split()[-1]):
        return None
    r.topic = r.obj(phrase)
    return ()


# -- object-specific permissions -------------------------------------------------------------

_DARE = "do not you dare "  # "Don't you dare ...": a reprimand in itself, as "Hey, don't ..." is


@GRAMMAR.rule("permission", "(?P<stop><REPRIMAND>)?<FORBID><ACT> <OBJ>", rf"{_LEAVE} <OBJ>{_IN_PLACE}?",
              "(?P<stop><REPRIMAND>)?<OBJ> is not (?:yours|for you) to <ACT>",
              rf"(?P<stop><REPRIMAND>)?(?:stop|quit) {_GERUND} <OBJ>", rf"<OBJ> {_STAY}",
              rf"(?:would|do) you mind not {_GERUND} <OBJ>")
def forbid_object(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Don't throw this wallet away", "Leave that alone" (= don't pick it up), "Hey, don't throw
    that away!" and "Don't you dare bin that" (a reprimand: stops it too, if the robot is acting),
    "Don't touch my book" (the book is mine)."""
    obj = r.obj(m["obj"])
    action = r.action(group(m, "act") or "touch")
    stop = group(m, "stop") is not None or m.group().startswith(_DARE)
    skip = [Skip(obj)] if stop and _acting(r) else []
    return (*skip, *_owner_claim(m["obj"], obj, r), Permission(action, obj, True))


@GRAMMAR.rule("reprimand", r"(?:(?:no|nope|hey|stop|wait|whoa) )*not <OBJ>(?: please)?")
def contrast_object(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"No, not the mug!": not the current action on that object ("Not sure" says one does not
    know: no object)."""
    if f"not {m['obj']}" in DONT_KNOW:
        return None
    obj = r.obj(m["obj"])
    action = r.current_action(m.group())
    return (*([Skip(obj)] if obj == r.ctx.about else []), Permission(action, obj, True))


@GRAMMAR.rule("permission", "<ALLOW><ACT> <OBJ>",
              rf"<OBJ> (?:is|are) {_OK} (?:for you )?to <ACT>(?: {_IT})?")
def allow_object(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"You can pick that up", "You may collect it", "It's ok to throw that away", "That's okay to
    throw away"."""
    obj = r.obj(m["obj"])
    return (*_owner_claim(m["obj"], obj, r), Permission(r.action(m["act"]), obj, False))


@GRAMMAR.rule("permission", r"(?:go ahead|carry on|that is (?:ok|fine)|it is (?:ok|fine)|<ALLOW><DO>)")
def allow_current(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Go ahead", "You can do that", "That's fine": allow the current action on the object."""
    obj = r.about()
    return (Permission(r.current_action(m.group()), obj, False),)


# -- norms -----------------------------------------------------------------------------------

def _rules(sign: str, action: str, alternatives: list[tuple[Literal, ...]]) -> tuple[Instruction, ...]:
    """One norm per alternative; a contradictory one is an error."""
    out = []
    for literals in alternatives:
        rule = Rule(action, literals)
        if rule.is_contradictory():
            raise RuleSyntaxError(f"the norm {rule.text(sign)!r} could never apply "
                                  "(contradictory conditions)")
        out.append(NormInstruction(Norm(sign, rule)))
    return tuple(dict.fromkeys(out))


def _alternatives(phrase: str, sign: str, act: str, r: Resolver) -> list[tuple[Literal, ...]] | None:
    """The class phrase's alternatives. An allow with "unless" has two readings that store different
    things (the allow alone, or the allow and a forbid of the exception), so it is refused with
    both shown."""
    if len(phrase.split()) > MAX_PHRASE_WORDS:
        return None
    alternatives = class_alternatives(phrase, r)
    if alternatives is not None and sign == "allow" and " unless " in phrase:
        main, _, exception = phrase.partition(" unless ")
        allows = [Rule(act, alt).text("allow") for alt in alternatives]
        forbids = [Rule(act, tuple(dict.fromkeys(a + e))).text("forbid")
                   for a in class_alternatives(main, r) or [()]
                   for e in class_alternatives(condition_phrase(exception), r) or [()]]
        raise NotUnderstood(phrase, f"it has two readings: [{'; '.join(allows)}] or "
                                    f"[{'; '.join(allows + forbids)}]; say the exception as a norm of "
                                    "its own")
    return alternatives


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
    action = r.action(group(m, "act") or "touch") if cond is None else r.current_action("do that")
    alternatives = _alternatives(phrase, sign, action, r)
    return None if alternatives is None else _rules(sign, action, alternatives)


@GRAMMAR.rule("norm", "<FORBID><ACT> (?P<cls>.+)", rf"{_LEAVE} (?P<cls>.+?){_IN_PLACE}?",
              "<FORBID><DO> (?P<cond>.+)", rf"(?:stop|quit) {_GERUND} (?P<cls>.+)", rf"(?P<cls>.+?) {_STAY}",
              rf"(?:would|do) you mind not {_GERUND} (?P<cls>.+)")
def forbid_norm(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Don't touch my stuff", "Never trash red things", "Don't do that if it's red", "Stop throwing
    away my things", "Don't trash things of Jake's or Xuan's" (two rules)."""
    return _norm("forbid", m, r)


@GRAMMAR.rule("norm", "<ALLOW><ACT> (?P<cls>.+)", "<ALLOW><DO> (?P<cond>.+)")
def allow_norm(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"You can throw away anything red", "You may trash things nobody owns"."""
    return _norm("allow", m, r)


def _only(phrase: str, act: str, r: Resolver) -> tuple[Instruction, ...] | None:
    """Only the class may be acted on: forbid everything outside it (one rule per way of being
    outside: "only throw away red things nobody owns" forbids non-red things and owned things)."""
    alternatives = class_alternatives(phrase, r)
    if not alternatives or any(not alt for alt in alternatives):
        return None
    outside = [tuple(dict.fromkeys(lit.negate() for lit in pick)) for pick in product(*alternatives)]
    return _rules("forbid", r.action(act), outside)


@GRAMMAR.rule("norm", r"(?:you (?:can|may|should|must|are allowed to) )?only <ACT> (?P<cls>.+)",
              r"<FORBID><ACT> (?:anything|things|stuff|objects) (?:but|except|other than|apart from) "
              r"(?P<cls>.+)")
def only_norm(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Only throw away things nobody owns" (forbid trash if ownedBy any), "Only pick up my things",
    "Don't collect anything except red things"."""
    return _only(m["cls"], m["act"], r)


@GRAMMAR.rule("norm", rf"(?:if|when|whenever) (?P<cond>.+?) (?:then )?(?P<sign><FORBID>|<ALLOW>)<ACT> {_IT}")
def fronted_norm(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"If something belongs to someone, don't throw it away", "If it's Xuan's, don't collect it"."""
    sign = "forbid" if _PROHIBITION.fullmatch(m["sign"]) else "allow"
    action = r.action(m["act"])
    alternatives = _alternatives(condition_phrase(m["cond"]), sign, action, r)
    return None if alternatives is None else _rules(sign, action, alternatives)


def _subject_norm(sign: str, phrase: str, act: str, r: Resolver) -> tuple[Instruction, ...] | None:
    """A statement about a subject: a class gets a norm, an object a permission."""
    alternatives = _alternatives(phrase, sign, r.action(act), r)
    if alternatives is not None:
        return _rules(sign, r.action(act), alternatives)
    if phrase not in DEICTIC and not r.is_object("".join(split_determiner(phrase)[1][-2:])) \
            and not r.is_object(phrase.split()[-1]):
        raise Decline(phrase)
    obj = r.obj(phrase)
    return (*_owner_claim(phrase, obj, r), Permission(r.action(act), obj, sign == "forbid"))


@GRAMMAR.rule("norm",
              rf"nothing (?P<rest>.+?) (?:should|must|can|may|could|is to|shall) (?:ever )?be {_PASSIVE}",
              rf"nothing (?P<rest>.+?) (?:(?:should|must|can|may|could|shall) (?:ever )?go|goes|ever goes) "
              rf"{_IN_BIN}")
def nothing_norm(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Nothing on the desk should be thrown away", "Nothing that's Jake's may be collected",
    "Nothing red goes in the bin"."""
    return _subject_norm("forbid", "anything " + m["rest"], group(m, "act") or "trash", r)


@GRAMMAR.rule("norm", rf"(?P<cls>.+?) (?:is|are) (?P<neg>not )?{_OK} (?:for you )?to <ACT>(?: {_IT})?",
              rf"(?P<cls>.+?) (?:can|may|could) (?:always |safely )?be {_PASSIVE}",
              rf"(?P<cls>.+?) (?:(?:can|may|could) go|goes|go) {_IN_BIN}",
              rf"(?P<cls>.+?) (?P<neg>can not|may not|must not|must never|should not|should never|"
              rf"is not to|are not to|are never to|is never to|shall not) be {_PASSIVE}",
              rf"(?P<cls>.+?) (?P<neg>can not|may not|must not|should not|should never|never|do not|"
              rf"does not|must never|can never) go {_IN_BIN}",
              rf"(?P<cls>.+?) (?P<neg>never) goes {_IN_BIN}",
              rf"(?P<cls>.+?) (?P<sign><ALLOW>|<FORBID>)<ACT>(?: {_IT})?")
def subject_norm(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Anything green is fine to throw away", "Anything in the trash area can be thrown away",
    "Things owned by Casey should never be thrown away", "Anything nobody owns, you can throw
    away"; about one object it is a permission ("The mug must not be thrown away")."""
    sign_words = group(m, "sign")
    if sign_words is not None:
        sign = "forbid" if _PROHIBITION.fullmatch(sign_words) else "allow"
    else:
        sign = "forbid" if group(m, "neg") else "allow"
    return _subject_norm(sign, m["cls"], group(m, "act") or "trash", r)
