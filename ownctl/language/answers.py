"""Answers to the robot's own question (docs/asking.md, section 5).

When the robot has put a question to a speaker (``ownctl ask --put``), that speaker's next utterance
is first read as its answer, into the same instructions as any claim, permission or norm:

- "May I ACTION OBJ?": a yes ("yes", "you may", "sure, go ahead") -> ``allow ACTION on OBJ``; a no
  ("no", "you may not", "no way, don't") -> ``forbid ACTION on OBJ``;
- "Does RULE hold?": a yes -> the norm ``forbid ...``; a no -> its allow norm ``allow ...``
  (nothing it describes is forbidden); "partly", "sometimes", "it depends on ..." -> nothing is
  taught;
- "Whose is OBJ?": an ownership statement ("it's Jake's", "mine", "nobody's", "owned by Xuan")
  -> its claims about OBJ, and every agent it does not name "not theirs" (the answer names the
  owners); a statement that only denies ("not mine") says nothing of the others;
- to any of them, "I don't know" ("no idea", "let me check", "ask Mia") answers without teaching
  anything.

**Clauses.** A reply is read clause by clause (split at punctuation; a clause that reads as none of
the kinds below is split again before "and", "but", "so", "because" and "since"), each clause one of:

- a *reply word*: a phrase of the tables below (YES, NO, PARTLY, DONT_KNOW), whole or made of two or
  three different phrases of one table ("of course it does", "yes exactly"), with a courtesy at either
  end, a discourse marker before it ("actually, no") or a place or afterthought after it
  (REPLY_TAILS: "that's not a rule here"); "it depends on ..." is partly, and a referral ("check
  with Mia first") a don't-know. A clause that opens with "yes", "sure", "ok" or "no" is that reply
  word and a clause after it ("no it's mine");
- an *aside*: a courtesy ("thanks"), a discourse marker ("so, ...") or a question back about the
  question (COUNTER_QUESTIONS: "Jake's, why do you ask?");
- a *statement*: what the ordinary parser (:func:`ownctl.language.understand.understand`) reads in the
  clause, with OBJ as "it" and ACTION (a rule's action) as "do that"; a prohibition that names no
  action ("leave it alone", "put it back", "leave the blue ones") refuses the asked action, which
  the question gives;
- a *remark*: a clause that states nothing the store keeps. It is one the parser refuses (or reads
  only as someone introducing themself, as "it's broken" reads) that names no agent, no object but
  OBJ, no colour, area or category, uses no action word as a verb ("junk" after "it is" is a noun),
  and holds no word of :data:`QUALIFIERS` (negation, permission, condition or time, ownership, a
  prohibition that names no action, other things or more of them) and no hedge below certainty
  ("maybe"): "Sure, it's broken", "Yes, but be gentle", "Xuan's, it has sat there for ages". The
  lexicon's asides ("I don't need it anymore", "by the way") are remarks too.

A clause of none of these kinds makes the reply no answer (None). So does a reply word that
disagrees with another ("Yes... no", "Yes, I don't know"), and a statement that says something else
than the answer: about another object ("Sure, and the mug too"), the opposite permission ("Yes, but
don't throw it away"), a norm the answer does not imply, a question.

**Per question.** "May I ACTION OBJ?": a reply led by a yes or a no (its first clause) is that
permission, with the statements beside it that agree: the same permission (a request to do it is a
yes: "Yes, throw it away"), claims about OBJ ("Sure, it's mine": the claim too), and after a no, a
clause that only says whose OBJ is is the reason a reprimand gives ("Definitely not, it's Jake's!"):
it also teaches the owner's norm (``forbid ACTION if ownedBy jake``). A reason against the answer
about throwing OBJ away makes it none ("Yes, I still need it"; "No, nobody needs it"). If a clause
of a led reply cannot be read, or the reply is not led by a reply word, the sentence as a whole must
state exactly that permission of OBJ as the ordinary parser reads it ("Don't throw it away, it's
Casey's"; "No, keep it", where "keep it" is no remark and the parser skips it), perhaps with claims
about OBJ and the owner's norm they give. "Does RULE hold?": a yes or a no, with statements that
state just the norm it gives (to "must I leave blue things?": "Yes, leave the blue ones"; "No, blue
is fine"), or a sentence that states the rule or its allow norm ("Never collect green things").
"Whose is OBJ?": the ordinary reading of the whole sentence, all claims about OBJ; else its clauses:
claims about OBJ, remarks, asides and, beside claims that only deny, a don't-know ("Not mine, no
idea whose"); a referral goes with any claims ("It's Jake's, ask him"), a don't-know with none that
names an owner. The claims of any answer must agree: no agent both owns OBJ and does not ("Jake's,
but he gave it to Mia"), and several owners are named together in one clause ("Mine and Jake's"),
not one after another ("Jake's? No, Mia's" corrects itself).

Anything that is no answer is understood as usual and the question stays pending. Pure: no I/O.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

from ownctl.errors import OwnctlError
from ownctl.language.context import Context, NotUnderstood
from ownctl.language.instructions import (
    Claim,
    Instruction,
    Introduce,
    NormInstruction,
    Permission,
    Request,
    Skip,
)
from ownctl.language.lexicon import (
    ACTION_PHRASES,
    ADJECTIVES,
    ASIDES,
    DISCOURSE,
    GERUNDS,
    HEDGES,
    NOT_NEEDED,
    PASSIVES,
    SPEAKER_WORDS,
    STILL_NEEDED,
    action_of,
    alternation,
)
from ownctl.language.normalize import normalize
from ownctl.logic.rules import Literal, Norm, Rule, parse_rule

YES = ("yes", "yes you may", "you may", "yes you can", "you can", "sure", "go ahead", "ok", "okay",
       "yes please", "yes go ahead", "of course", "yes of course", "yep", "yeah", "yup", "it is fine", "fine",
       "yes it does", "it does", "yes it holds", "it holds", "always", "yes always", "absolutely",
       "certainly", "definitely", "indeed", "yes indeed", "correct", "that is correct", "right",
       "that is right", "true", "that is true", "it is true", "go on", "go for it", "please do",
       "by all means", "be my guest", "sure thing", "no problem", "that is fine", "it is ok", "that is ok",
       "you are allowed", "you have my permission", "it is allowed", "yes it is", "it is", "yes it is true",
       "fine by me", "fine with me", "ok by me", "ok with me", "go right ahead", "help yourself", "why not",
       "sure go ahead", "of course you may", "yes you are", "exactly", "precisely", "quite right",
       "just so", "spot on", "you bet", "you got it", "feel free", "no worries",
       "that is the rule", "that is a rule", "it is a rule", "it is the rule", "that is how it works",
       "that is how it is", "affirmative", "for sure", "it sure does", "it certainly does",
       "it definitely does", "it does indeed", "it always does", "yes sir", "no exceptions",
       "without exception", "do", "do it", "do so")  # "please do": normalising drops "please"
NO = ("no", "no you may not", "you may not", "no you can not", "you can not", "do not", "no do not",
      "please do not", "no please do not", "nope", "no it does not", "it does not", "never",
      "no never", "no it does not hold", "it does not hold", "not at all", "no way", "of course not",
      "absolutely not", "certainly not", "definitely not", "not really", "by no means", "better not",
      "you must not", "you should not", "you are not allowed", "it is not allowed", "do not do that",
      "do not do it", "not true", "that is not true", "it is not true", "false", "wrong", "that is wrong",
      "no it is not", "it is not", "not ok", "that is not ok", "it is not ok",
      "i would rather you did not", "i would prefer you did not", "i would prefer not", "rather not",
      "i would rather not", "please do not do that", "no you are not", "no thank you",
      "do not you dare", "do not you dare do that", "do not even think about it", "not a chance",
      "no chance", "not on your life", "hell no", "negative", "no sir", "that is not a rule",
      "that is not the rule", "it is not a rule", "there is no such rule", "no such rule",
      "there is no rule like that", "we do not have that rule", "we have no such rule",
      "that is not how it works", "that is not it", "it does not at all", "it never does")
PARTLY = ("partly", "sometimes", "not always", "it depends", "in part", "only sometimes", "some of them",
          "partially", "in some cases", "depends", "mostly", "usually", "generally", "often", "mostly yes",
          "mostly not", "not usually", "rarely", "seldom", "occasionally", "that depends", "not quite",
          "not exactly", "not necessarily", "kind of", "sort of", "more or less", "in a way",
          "to some extent", "it varies")
DONT_KNOW = ("i do not know", "do not know", "no idea", "i have no idea", "not sure", "i am not sure",
             "dunno", "i dunno", "no clue", "i have no clue", "who knows", "i can not say", "can not say",
             "hard to say", "i can not tell", "i am not certain", "not certain", "i do not remember",
             "i forget", "beats me", "ask someone else", "i would have to check", "i have to check",
             "i need to check", "i will have to check", "i would need to check", "let me check",
             "i will check", "i would have to ask", "i will have to ask", "let me ask", "search me",
             "i can not remember", "i can not recall", "i do not recall", "i could not tell you",
             "good question", "i really do not know", "i honestly do not know", "i wish i knew",
             "i do not know whose", "i do not know whose it is", "no idea whose", "no idea whose it is",
             "i am not sure whose", "i am not sure whose it is", "not my call",
             "your guess is as good as mine")
COURTESY = ("thanks", "thank you", "sorry", "hi", "hello", "hey")
#: Questions back about the question itself ("Mia's, why?"): asides that ask nothing to be stored.
COUNTER_QUESTIONS = ("why", "why do you ask", "why do you want to know", "why are you asking",
                     "why do you need to know", "what for", "who wants to know", "does it matter")
READINGS: tuple[tuple[str, tuple[str, ...]], ...] = (("yes", YES), ("no", NO), ("partly", PARTLY),
                                                      ("unknown", DONT_KNOW))
#: Words that may follow a reply word without changing it: where ("not a rule here"), afterthoughts.
REPLY_TAILS = ("here", "around here", "in here", "in this house", "in our house", "though", "anyway",
               "after all", "all the same")
#: Words that could qualify an answer, so a clause holding one is never a remark: negation,
#: permission and obligation, condition and time, ownership, a prohibition that names no action,
#: other things or more of them, and a reply word said in passing.
QUALIFIERS = frozenset({
    "not", "never", "no", "neither", "nor", "none", "without",
    "can", "may", "must", "should", "shall", "allowed", "allow", "forbidden", "forbid", "permitted",
    "permit", "permission", "ok", "fine", "let", "dare", "mind", "rather",
    "if", "unless", "except", "only", "when", "whenever", "until", "till", "once", "first", "after",
    "before", "later", "tomorrow", "tonight", "soon", "yet", "instead",
    "own", "owns", "owned", "owner", "owners", "belong", "belongs", "belonged", "mine", "yours", "ours",
    "theirs", "his", "hers", "her", "my", "your", "our", "their", "'s", "whose", "give", "gave", "given",
    "lent", "lend", "borrow", "borrowed", "share", "shared", "shares", "sold",
    "leave", "keep", "stop", "wait", "put", "stay", "hands",
    "too", "also", "other", "others", "another", "all", "every", "everything", "anything", "any", "each",
    "both", "yes", "yeah", "yep", "yup", "sure",
})

_TABLES = {name: frozenset(phrases) for name, phrases in READINGS}
_KIND = {phrase: name for name, phrases in reversed(READINGS) for phrase in phrases}
_CLAUSES = re.compile(r"[,.;:!?\u2013\u2014]+|\s-+\s")
_CONJUNCTION = re.compile(r" (?:and|but|so|because|since) ")
_OPENER = re.compile(r"^(?:and|but|so|because|since|cause|plus) ")
_TAIL = re.compile(rf" {alternation(REPLY_TAILS)}$")
#: Discourse markers that may open a reply word ("actually no"), those that are none themselves.
_MARKERS = DISCOURSE - set(_KIND)
_MARKER = re.compile(rf"^(?:{alternation(_MARKERS)} )+(?=\S)")
#: Reply words that may open a clause without a comma ("no it's mine", "sure it's broken").
_INTERJECTION = re.compile(r"(?P<word>yes|yeah|yep|yup|sure|ok|no) (?P<rest>.+)")
_DEPENDS = re.compile(r"(?:it |that )?depends (?:on|upon|whether|if|who|whose|what|when|how|where|which) .+")
_REFERRAL = re.compile(r"(?:(?:you should|you could|you can|you will have to|you would have to|you need to|"
                       r"you had better|better|go|maybe|try) )?(?:ask|check with|talk to) (?:the )?\S+"
                       r"(?: else)?(?: about (?:it|that|this))?(?: first| instead)?")
_JOINED_WORDS = 8  # a clause of more words is no run of reply phrases
_ACTION_WORDS = re.compile(r"(?<![\w'-])" + alternation((*ACTION_PHRASES, *GERUNDS, *PASSIVES)))
#: Words after which an action word is a noun ("it's junk", "the bin"), not a verb.
_NOUN_AFTER = frozenset({"is", "are", "was", "were", "be", "been", "a", "an", "the", "some", "of", "like",
                         "just", "pure", "total", "complete", "absolute", "utter", "such"}) | ADJECTIVES
_HEDGE = re.compile(r"(?<![\w'-])" + alternation([h for h, p in HEDGES.items() if p < 1.0]))
_TOUCH = action_of("touch")  # the action of a prohibition that names none ("leave it")
_DISPOSE = action_of("throw away")  # the action a reason about needing the object is about


def reading(utterance: str) -> str | None:
    """``"yes"``, ``"no"``, ``"partly"`` or ``"unknown"`` when ``utterance`` is one such reply as a
    whole, or clause by clause with every clause the same one (courtesies aside); None otherwise."""
    whole = _label(normalize(utterance))
    if whole is not None:
        return whole
    words = (normalize(clause) for clause in _CLAUSES.split(utterance))
    labels = {_label(w) for w in words if w and w not in COURTESY}  # None: a clause that is no reply
    return next(iter(labels)) if len(labels) == 1 else None


def _bare(words: str) -> str:
    """``words`` without a courtesy at either end ("no thanks"), a discourse marker before them
    ("actually no") and a reply tail after them ("... here")."""
    for courtesy in COURTESY:
        words = words.removesuffix(f" {courtesy}").removeprefix(f"{courtesy} ")
    return _TAIL.sub("", _MARKER.sub("", words))


def _label(words: str) -> str | None:
    """The reply the clause ``words`` (normalised) is: a phrase of a table, "it depends on ...", a
    referral, or a run of different phrases of one table ("of course it does"); None otherwise."""
    words = _bare(words)
    if (kind := _KIND.get(words)) is not None:
        return kind
    if _DEPENDS.fullmatch(words):
        return "partly"
    if _REFERRAL.fullmatch(words):
        return "unknown"
    tokens = words.split()
    if len(tokens) > _JOINED_WORDS:
        return None
    kinds = [name for name, table in _TABLES.items() if _run(tokens, table, 3)]
    return kinds[0] if len(kinds) == 1 else None


def _run(tokens: list[str], table: frozenset[str], parts: int, previous: str = "") -> bool:
    """True if ``tokens`` are at most ``parts`` phrases of ``table``, none the same as the one before
    it ("ok ok" is impatience, not a yes)."""
    if not tokens:
        return True
    for end in range(1, len(tokens) + 1) if parts else ():
        head = " ".join(tokens[:end])
        if head in table and head != previous and _run(tokens[end:], table, parts - 1, head):
            return True
    return False


def _names_action(words: str) -> bool:
    """True if ``words`` use an action word as a verb ("leave it" does not; "it is junk" uses "junk"
    as a noun)."""
    for m in _ACTION_WORDS.finditer(words):
        before = words[:m.start()].split()[-1:]
        if not before or before[0] not in _NOUN_AFTER:
            return True
    return False


def _remark(words: str, ctx: Context) -> bool:
    """True if the clause ``words`` (normalised, refused by the parser) states nothing the store
    keeps: an aside of the lexicon, or words that name nothing of the world but the object in
    question, use no action word as a verb and hold no qualifier and no hedge below certainty."""
    if words in ASIDES:
        return True
    names = {n.lower() for n in (*ctx.agents, *ctx.colors, *ctx.areas, *ctx.categories)}
    names |= {o.lower() for o in ctx.objects if o != ctx.about}
    for word in words.split():
        if word in QUALIFIERS or word in names or word.removesuffix("s") in names:
            return False
    return not _names_action(words) and _HEDGE.search(words) is None


def _refused(i: Instruction, asked: str) -> Instruction:
    """A prohibition that names no action ("leave it": do not touch it) as one of the asked action."""
    if isinstance(i, Permission) and i.forbid and i.action == _TOUCH:
        return replace(i, action=asked)
    if isinstance(i, NormInstruction) and i.norm.sign == "forbid" and i.norm.rule.action == _TOUCH:
        return NormInstruction(Norm("forbid", Rule(asked, i.norm.rule.literals)))
    return i


def _as_answer(said: tuple[Instruction, ...], words: str, ctx: Context,
               asked: str | None) -> tuple[Instruction, ...]:
    """What a statement says as part of an answer: the reprimand's stop left out (the robot is not
    acting), a request for the asked action a permission, a prohibition that names no action one of
    the asked action."""
    out = []
    for i in said:
        if isinstance(i, Skip) and i.object == ctx.about:
            continue
        if type(i) is Request and (i.action, i.object) == (asked, ctx.about):
            i = Permission(i.action, i.object, forbid=False)
        out.append(i if asked is None or _names_action(words) else _refused(i, asked))
    return tuple(dict.fromkeys(out))


def _parsed(words: str, ctx: Context, asked: str | None) -> tuple[Instruction, ...] | None:
    """The ordinary reading of ``words`` as part of an answer (:func:`_as_answer`); () for a remark
    or words that say nothing (a greeting, OBJ named alone); None if the words cannot be read."""
    from ownctl.language.understand import understand

    try:
        understood = understand(words, ctx)
    except NotUnderstood:
        return () if _remark(words, ctx) else None
    except OwnctlError:  # a form the parser knows, with something it cannot resolve
        return None
    if understood.intent == "introduction":  # "it's junk": nobody new speaks in an answer
        return () if _remark(words, ctx) else None
    if any(isinstance(i, Introduce) for i in understood.instructions):  # read apart, if split
        return None
    if not understood.instructions:
        return () if understood.topic in (None, ctx.about) else None
    return _as_answer(understood.instructions, words, ctx, asked)


@dataclass
class _Reply:
    """A reply read clause by clause: its reply words in order, whether the first clause is one,
    what its statements say, the claims of the clauses that only say whose OBJ is (reasons), and
    whether a clause could not be read."""

    labels: list[str] = field(default_factory=list)
    led: bool | None = None
    said: list[Instruction] = field(default_factory=list)
    reasons: list[Claim] = field(default_factory=list)
    unread: bool = False

    @property
    def lead(self) -> str | None:
        """The reply word the reply opens with, if it opens with one."""
        return self.labels[0] if self.led else None

    def take(self, words: str, ctx: Context, asked: str | None, split: bool = True) -> None:
        """Read one clause (normalised); split it before a conjunction if it reads as nothing."""
        words = _OPENER.sub("", words)
        if not words or words in COURTESY or words in COUNTER_QUESTIONS or words in _MARKERS:
            return
        label = _label(words)
        if label is None and split and (opens := _INTERJECTION.fullmatch(words)):
            self.take(opens["word"], ctx, asked)
            self.take(opens["rest"], ctx, asked)
            return
        if self.led is None:
            self.led = label is not None
        if label is not None:
            self.labels.append(label)
            return
        said = _parsed(words, ctx, asked)
        if said is None and split and _CONJUNCTION.search(words):
            for part in _CONJUNCTION.split(words):
                self.take(part, ctx, asked, split=False)
            return
        if said is None:
            self.unread = True
            return
        self.said += said
        if said and all(isinstance(i, Claim) for i in said):
            self.reasons += [i for i in said if isinstance(i, Claim)]


def _reply(utterance: str, ctx: Context, asked: str | None, led: bool = False) -> _Reply:
    """``utterance`` read clause by clause (the whole first, when it is one reply word); with
    ``led``, only as far as its first clause when that is no reply word (the reply is then read as
    a sentence)."""
    reply = _Reply()
    whole = _label(normalize(utterance))
    if whole is not None:
        reply.labels, reply.led = [whole], True
        return reply
    for clause in _CLAUSES.split(utterance):
        reply.take(normalize(clause), ctx, asked)
        if led and reply.led is False:
            break
    return reply


def _sentence(utterance: str, ctx: Context, asked: str | None) -> tuple[Instruction, ...] | None:
    """The ordinary reading of the whole ``utterance`` as an answer (:func:`_as_answer`), or None if
    the parser cannot read it."""
    from ownctl.language.understand import understand

    try:
        understood = understand(utterance, ctx)
    except OwnctlError:
        return None
    return _as_answer(understood.instructions, normalize(utterance), ctx, asked)


def answer_instructions(utterance: str, question: Mapping[str, Any], ctx: Context
                        ) -> tuple[Instruction, ...] | None:
    """The instructions ``utterance`` means as the answer to ``question`` (a pending question's
    ``{"kind", "object", "action", "rule"}``), or None if it is no answer to it."""
    kind = question.get("kind")
    if kind == "may":
        return _may(utterance, str(question["action"]), str(question["object"]), ctx)
    if kind == "rule":
        return _rule(utterance, parse_rule(str(question["rule"])), ctx)
    if kind == "whose":
        return _owners(utterance, str(question["object"]), ctx)
    return None


def _may(utterance: str, action: str, obj: str, ctx: Context) -> tuple[Instruction, ...] | None:
    """The answer to "may I ``action`` ``obj``?": a permission of ``obj`` with the claims and the
    owner's norms beside it; () for a don't-know; None for no answer."""
    ctx = replace(ctx, about=obj, action=action)
    reply = _reply(utterance, ctx, action, led=True)
    if reply.lead is None:  # no reply word first: the sentence must state the permission
        said = _sentence(utterance, ctx, action)
        return None if said is None else _permission(said, action, obj, None, (), utterance, ctx)
    if set(reply.labels) != {reply.lead}:  # "yes... no", "yes, I don't know"
        return None
    if reply.lead not in ("yes", "no"):
        return () if reply.lead == "unknown" and not reply.said and not reply.unread else None
    forbid = reply.lead == "no"
    if not reply.unread:
        return _permission(tuple(reply.said), action, obj, forbid, tuple(reply.reasons), utterance, ctx)
    said = _sentence(utterance, ctx, action)  # a clause it cannot read: the sentence as a whole,
    if said is None or {i.forbid for i in said if isinstance(i, Permission)} != {forbid}:  # if the same
        return None
    return _permission(said, action, obj, forbid, (), utterance, ctx)


def _owner_norm(action: str, agent: str) -> NormInstruction:
    """``forbid ACTION if ownedBy AGENT``: the norm a reprimand's owner gives."""
    return NormInstruction(Norm("forbid", Rule(action, (Literal("ownedBy", agent),))))


def _permission(said: tuple[Instruction, ...], action: str, obj: str, forbid: bool | None,
                reasons: tuple[Claim, ...], utterance: str, ctx: Context) -> tuple[Instruction, ...] | None:
    """The permission of ``action`` on ``obj`` the reply gives (``forbid``, or with None the one
    ``said`` states), the claims about ``obj`` said beside it and the owner's norm of a no given
    with its owner (from ``reasons`` or as said); None if ``said`` states anything else or another
    permission, if its claims disagree (:func:`_agree`) or it gives a reason against the answer."""
    signs = {i.forbid for i in said if isinstance(i, Permission)}
    if forbid is None:
        if len(signs) != 1:
            return None
        forbid = next(iter(signs))
    claims = [i for i in said if isinstance(i, Claim)]
    owners = [c.agent for c in claims if not c.negated]
    norms = [_owner_norm(action, agent) for agent in owners] if forbid else []
    for i in said:
        fits = (isinstance(i, Permission) and (i.action, i.object, i.forbid) == (action, obj, forbid)
                or isinstance(i, Claim) and i.object == obj or isinstance(i, NormInstruction) and i in norms)
        if not fits:
            return None
    if _against(normalize(utterance), action, forbid) or not _agree(claims, utterance, ctx):
        return None
    given = [i for i in said if isinstance(i, NormInstruction)]
    if forbid:
        given += [_owner_norm(action, c.agent) for c in reasons if not c.negated]
    return tuple(dict.fromkeys((*claims, Permission(action, obj, forbid), *given)))


def _against(words: str, action: str, forbid: bool) -> bool:
    """True if the reply ``words`` give a reason against their own answer about throwing the object
    away: a yes with "I still need it", a no with "I don't need it anymore"."""
    if action != _DISPOSE:
        return False
    padded = f" {words} "
    return any(f" {phrase} " in padded for phrase in (NOT_NEEDED if forbid else STILL_NEEDED))


def _rule(utterance: str, rule: Rule, ctx: Context) -> tuple[Instruction, ...] | None:
    """The answer to "does ``rule`` hold?": its forbid norm (a yes), its allow norm (a no), ()
    for "partly" or a don't-know; None for no answer."""
    ctx = replace(ctx, action=rule.action)
    reply = _reply(utterance, ctx, rule.action, led=True)
    if reply.lead is None:  # no reply word first: the sentence must state the norm, and only it
        stated = set(_sentence(utterance, ctx, rule.action) or ())
        norm = stated.pop() if len(stated) == 1 else None
        return (norm,) if isinstance(norm, NormInstruction) and norm.norm.rule == rule else None
    if set(reply.labels) != {reply.lead} or reply.unread:
        return None
    if reply.lead not in ("yes", "no"):
        return () if not reply.said else None
    norm = NormInstruction(Norm("forbid" if reply.lead == "yes" else "allow", rule))
    return (norm,) if all(i == norm for i in reply.said) else None


def _owners(utterance: str, obj: str, ctx: Context) -> tuple[Instruction, ...] | None:
    """The claims of an ownership statement about ``obj``, completed with "not theirs" for every
    agent it does not name, as sure as the statement ("Casey's, I think": the others' at 0.8); a
    statement that only denies ("not mine") says nothing of the others; () for a don't-know; None
    if the utterance states no ownership of ``obj``. The sentence is read as a whole, else clause
    by clause."""
    ctx = replace(ctx, about=obj)
    said = _sentence(utterance, ctx, None) or ()
    claims = [i for i in said if isinstance(i, Claim) and i.object == obj]
    if not claims or len(claims) != len(said):
        reply = _reply(utterance, ctx, None)
        claims = [i for i in reply.said if isinstance(i, Claim) and i.object == obj]
        if reply.unread or len(claims) != len(reply.said) or set(reply.labels) - {"unknown"}:
            return None
        if not claims:
            return () if reply.labels else None
    if _doubts(utterance) and any(not c.negated for c in claims):  # "Jake's, no idea": unsure
        return None
    return _completed(claims, obj, ctx) if _agree(claims, utterance, ctx) else None


def _agree(claims: list[Claim], utterance: str, ctx: Context) -> bool:
    """True if the claims of an answer agree: no agent both owns the object and does not ("Jake's,
    but he gave it to Mia" tells a story), and the owners named are named together in one clause
    ("Mine and Jake's"), not one after another ("Jake's? No, Mia's" corrects itself)."""
    owners = {c.agent for c in claims if not c.negated}
    if owners & {c.agent for c in claims if c.negated}:
        return False
    if len(owners) < 2:
        return True
    clauses = (set(normalize(clause).split()) for clause in _CLAUSES.split(utterance))
    return any(all(a.lower() in words or a == ctx.speaker and words & SPEAKER_WORDS for a in owners)
               for words in clauses)


def _doubts(utterance: str) -> bool:
    """True if a clause of ``utterance`` says the speaker does not know ("Jake's, no idea"); a
    referral does not ("It's Jake's, ask him")."""
    for clause in _CLAUSES.split(utterance):
        words = _bare(normalize(clause))
        if _label(words) == "unknown" and not _REFERRAL.fullmatch(words):
            return True
    return False


def _completed(claims: list[Claim], obj: str, ctx: Context) -> tuple[Instruction, ...]:
    """The claims, and every agent they do not name "not theirs" unless they only deny."""
    if all(c.negated for c in claims):
        return tuple(claims)  # "not Jake's": nothing about the others ("nobody's" names them all)
    named = {c.agent for c in claims}
    sure = min(c.p for c in claims if not c.negated)
    rest = tuple(Claim(obj, a, sure, negated=True) for a in sorted(ctx.agents - named))
    return tuple(dict.fromkeys(replace(c, exclusive=False) for c in claims)) + rest


__all__ = ["COUNTER_QUESTIONS", "DONT_KNOW", "NO", "PARTLY", "QUALIFIERS", "YES", "answer_instructions",
           "reading"]
