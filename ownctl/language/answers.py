"""Answers to the robot's own question (docs/asking.md, section 5).

When the robot has put a question to a speaker (``ownctl ask --put``), that speaker's next utterance
is first read as its answer, into the same instructions as any claim, permission or norm:

- "May I ACTION OBJ?": a yes ("yes", "you may", "sure, go ahead") -> ``allow ACTION on OBJ``; a no
  ("no", "you may not", "no way, don't") -> ``forbid ACTION on OBJ``;
- "Does RULE hold?": a yes -> the norm ``forbid ...``; a no -> its allow norm ``allow ...``
  (nothing it describes is forbidden); "partly", "sometimes", "it depends on ...", a restriction
  ("only for her books", "only when she is home", "unless it is broken") -> nothing is taught;
- "Whose is OBJ?": an ownership statement ("it's Jake's", "mine", "nobody's", "owned by Xuan")
  -> its claims about OBJ, and every agent it does not name "not theirs" (the answer names the
  owners); a statement that only denies ("not mine") says nothing of the others; "ours" ("both
  of ours", "we share it") is the speaker and the others named beside it ("Both of ours, mine and
  Jake's"), and no answer when it names no other owner;
- to any of them, "I don't know" ("no idea", "not a clue", "let me check", "ask Mia", "let me ask
  Jake", "hold on, ask Mia") answers without teaching anything.

**Clauses.** A reply is read clause by clause (split at punctuation; a clause that reads as none of
the kinds below is split again before "and", "but", "so", "because" and "since"), each clause one of:

- a *reply word*: a phrase of the tables below (YES, NO, PARTLY) or of DONT_KNOW (in the lexicon),
  whole or made of two or three different phrases of one table ("of course it does", "yes exactly"),
  with a courtesy at either end, a discourse marker before it ("actually, no") or a place or
  afterthought after it (REPLY_TAILS: "that's not a rule here"); "it depends on ..." and a
  restriction ("only for her books") are partly, a referral ("check with Mia first", "let me ask
  Jake") a don't-know; the don't-knows include the phrases built from parts ("not a" / "no" / "the
  faintest" + "idea" / "clue"). A clause that opens with "yes", "sure", "ok" or "no" is that reply
  word and a clause after it ("no it's mine");
- an *aside*: a courtesy ("thanks"), a discourse marker ("so, ...") or a question back about the
  question (COUNTER_QUESTIONS: "Jake's, why do you ask?"); a hold marker (HOLD: "hold on", "wait",
  "hang on a second") before a clause or as one, only in a reply that is nothing but a don't-know
  ("Hold on, ask Jake"); with anything else the clause is unread;
- a *note*: a clause the parser reads nothing in that says someone uses or needs OBJ ("Jake is
  still drinking from it", "my son needs it for school": kept), that nobody does ("nobody is using
  it": freed), or that the speaker owns OBJ with others ("both of ours", "it belongs to us", "we
  share it": shared). What a note allows depends on the question (below);
- a *statement*: what the ordinary parser (:func:`ownctl.language.understand.understand`) reads in the
  clause, with OBJ as "it" and ACTION (a rule's action) as "do that"; a prohibition that names no
  action ("leave it alone", "put it back", "leave the blue ones") refuses the asked action, which
  the question gives. A clause the parser refuses that says how someone feels about others doing
  something to their things states the norm it implies, read by the parser: "Xuan doesn't like
  people touching her stuff" as "never touch Xuan's stuff", "Jake doesn't mind people taking his
  things" as "you may take Jake's things" ("he", "she", "they": the agent a rule asks about);
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
it also teaches the owner's norm (``forbid ACTION if ownedBy jake``). Someone using or needing OBJ
is a reason that goes with a no only ("No! Mia is still reading it": the prohibition alone; "Yes,
Jake is still using it" is none), nobody using it never with a no, and a shared note makes a reply
to it none. A reason against the answer about throwing OBJ away makes it none ("Yes, I still need
it"; "No, nobody needs it"). If a clause of a led reply cannot be read, or the reply is not led by a
reply word, the sentence as a whole must state exactly that permission of OBJ as the ordinary parser
reads it ("Don't throw it away, it's Casey's"; "No, keep it", where "keep it" is no remark and the
parser skips it), perhaps with claims about OBJ and the owner's norm they give. "Does RULE hold?": a
yes or a no, with statements that state just the norm it gives (to "must I leave blue things?":
"Yes, leave the blue ones"; "No, blue is fine"; to "must I not pick up Xuan's things?": "Yes, she
hates people touching her stuff"), and no note but a freed one, or a sentence that states the rule
or its allow norm ("Never collect green things", "Xuan doesn't like people touching her things").
"Whose is OBJ?": the ordinary reading of the whole sentence, all claims about OBJ; else its clauses:
claims about OBJ, remarks, asides and, beside claims that only deny, a don't-know ("Not mine, no
idea whose"); a referral goes with any claims ("It's Jake's, ask him"), a don't-know (one the
speaker makes too: "let me ask him") with none that names an owner; a kept note makes it none
("Jake's, but Mia uses it"). The claims of any answer must agree: no agent both owns OBJ and does
not ("Jake's, but he gave it to Mia"), several owners are named together in one clause ("Mine and
Jake's"), not one after another ("Jake's? No, Mia's" corrects itself), and an answer that says
"ours" names the speaker and at least one other owner (exactly one with "both": "Both of ours, mine
and Jake's"); "It's ours" alone cannot tell whose OBJ is not.

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
    DONT_KNOW,
    GERUNDS,
    HEDGES,
    NOT_NEEDED,
    PASSIVES,
    SPEAKER_WORDS,
    STILL_NEEDED,
    action_of,
    alternation,
    inflect,
    phrases,
)
from ownctl.language.normalize import normalize
from ownctl.language.statements import owner_norm
from ownctl.logic.rules import Norm, Rule, parse_rule

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
      "that is not how it works", "that is not it", "it does not at all", "it never does",
      "not yet", "no not yet", "not just yet", "not now", "no not now", "not right now",
      "not at the moment", "not for now", "not today")
PARTLY = ("partly", "sometimes", "not always", "it depends", "in part", "only sometimes", "some of them",
          "partially", "in some cases", "depends", "mostly", "usually", "generally", "often", "mostly yes",
          "mostly not", "not usually", "rarely", "seldom", "occasionally", "that depends", "not quite",
          "not exactly", "not necessarily", "kind of", "sort of", "more or less", "in a way",
          "to some extent", "it varies")
COURTESY = ("thanks", "thank you", "sorry", "hi", "hello", "hey")
#: Questions back about the question itself ("Mia's, why?"): asides that ask nothing to be stored.
COUNTER_QUESTIONS = ("why", "why do you ask", "why do you want to know", "why are you asking",
                     "why do you need to know", "what for", "who wants to know", "does it matter")
#: Said to hold the question off while the speaker finds out ("Hold on, ask Jake", "Wait, let me check"):
#: they go only with a don't-know.
HOLD = (phrases(("hold on", "hang on", "wait", "wait up"),
                ("", "a second", "a sec", "a minute", "a moment", "a bit", "one second", "one moment"))
        | phrases(("one", "just a", "give me a"), ("second", "sec", "minute", "moment"))
        | {"let me think", "let me see"})
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
#: A referral to someone the speaker will ask ("let me ask Jake", "I'll check with Mia"): a don't-know
#: that, unlike sending the robot to them, leaves the speaker unsure of anything said beside it.
_SELF_REFERRAL = re.compile(r"(?:let me|let us|i will|i would|i will have to|i would have to|i have to|"
                            r"i need to|i would need to|i should|i must|i can|i could|we will have to|"
                            r"we should|we need to) (?:go )?(?:ask|check with|talk to) (?:the )?\S+(?: else)?"
                            r"(?: about (?:it|that|this))?(?: first)?")
#: A restriction ("only for her books", "only when she is home", "except on Sundays", "unless it is
#: broken"): what it restricts holds in part.
_RESTRICTION = re.compile(r"(?:(?:only|just|except|excepting) (?:for|when|whenever|if|on|in|at|with|during|"
                          r"while|after|before|where|around|near)|(?:apart|aside) from|unless) .+")
_JOINED_WORDS = 8  # a clause of more words is no run of reply phrases
_ACTION_WORDS = re.compile(r"(?<![\w'-])" + alternation((*ACTION_PHRASES, *GERUNDS, *PASSIVES)))
#: Words after which an action word is a noun ("it's junk", "the bin"), not a verb.
_NOUN_AFTER = frozenset({"is", "are", "was", "were", "be", "been", "a", "an", "the", "some", "of", "like",
                         "just", "pure", "total", "complete", "absolute", "utter", "such"}) | ADJECTIVES
_HEDGE = re.compile(r"(?<![\w'-])" + alternation([h for h, p in HEDGES.items() if p < 1.0]))
#: Words that cannot be the one who uses the object ("who is using it" asks; "nobody needs it" frees it).
_NOT_USERS = frozenset({"it", "this", "that", "what", "who", "which", "whoever", "nothing", "something",
                        "everything", "anything", "there", "here", "anyone", "one", "nobody else"})
#: Someone using the object, after "is" ("Jake is still drinking from it"), or needing it ("Mia needs it").
_USING = ("using", "drinking from", "drinking out of", "eating from", "eating off", "eating out of",
          "reading", "wearing", "playing with", "working with", "working on", "writing with", "writing in",
          "watching", "listening to", "charging", "looking at", "sitting on", "sleeping with", "filling")
_NEEDING = (("needs", "need", "uses", "use")
            + tuple(phrases(("will", "might", "may", "could"), ("", "still"), ("need",)))
            + tuple(phrases(("is", "are", "am", "'s"),
                            ("going to need", "not done with", "not finished with", "not through with")))
            + tuple(phrases(("has", "have"), ("not finished with",))))
#: When, after a clause saying someone uses the object ("Mia needs it for school").
_WHEN_USED = ("now", "right now", "at the moment", "today", "tonight", "tomorrow", "later", "every day",
              "all the time", "again", "for school", "for work", "for now")
_IN_USE = re.compile(rf"(?P<who>(?:my|our|the|his|her|their) \S+|\S+(?: else)?) "
                     rf"(?:(?:is|are|am|'s) (?:still )?{alternation(_USING)}|"
                     rf"(?:still )?{alternation(_NEEDING)}) (?:it|that|this)(?: one)?"
                     rf"(?: {alternation(_WHEN_USED)})?")
#: The speaker saying they own the object with others: "both of ours", "it belongs to us", "we share it".
_SHARED = re.compile(r"(?:(?:it|that|this)(?: one)? is )?(?:(?:both|all)(?: of)? )?ours(?: both| all)?"
                     r"|(?:(?:it|that|this)(?: one)? )?belongs to (?:(?:both|all|the two) of )?us"
                     r"(?: both| all)?|we (?:both |all |two )?(?:own|share) (?:it|that|this)(?: together)?")
_NEGATIONS = frozenset({"not", "no", "never", "neither", "nor", "nobody"})
#: How someone feels about others doing something to their things, and the sign of the norm that states:
#: "Xuan doesn't like people touching her stuff" (never touch Xuan's stuff); "Jake doesn't mind ..."
#: (you may).
_NOT_FEELING = ("does not", "do not", "would not")
_DISLIKES = {"hates", "hate", "can not stand", "dislikes", "dislike", "minds", "objects to", "object to"}
_FEELINGS = {
    **dict.fromkeys(phrases(_NOT_FEELING, ("like", "want", "appreciate", "allow", "let")) | _DISLIKES,
                    "forbid"),
    **dict.fromkeys(phrases(_NOT_FEELING, ("mind", "care"))
                    | phrases(("is", "am", "are"), ("fine with", "ok with")), "allow"),
}
_OTHERS = ("people", "anyone", "anyone else", "someone", "someone else", "others", "other people", "you",
           "us", "the robot", "robots", "strangers", "everyone", "them")
_BASE_OF_GERUND = {" ".join(filter(None, (inflect(first, "ing"), rest))): phrase
                   for phrase in ACTION_PHRASES for first, _, rest in [phrase.partition(" ")]}
_FEELING = re.compile(rf"(?P<who>\S+) (?:(?:really|just|absolutely|totally|truly) )?"
                      rf"(?P<feeling>{alternation(tuple(_FEELINGS))}) (?:it )?(?:when |if |about )?"
                      rf"(?:{alternation(_OTHERS)} )?(?:to )?"
                      rf"(?P<act>{alternation((*ACTION_PHRASES, *GERUNDS))}) "
                      r"(?P<owner>her|his|their|my|\S+ 's) (?P<things>.+)")
_PRONOUNS = frozenset({"he", "she", "they"})
_HOLD = re.compile(rf"{alternation(HOLD)}(?: |$)")
_TOUCH = action_of("touch")  # the action of a prohibition that names none ("leave it")
_DISPOSE = action_of("throw away")  # the action a reason about needing the object is about


def reading(utterance: str) -> str | None:
    """``"yes"``, ``"no"``, ``"partly"`` or ``"unknown"`` when ``utterance`` is one such reply as a
    whole, or clause by clause with every clause the same one (courtesies and discourse markers
    aside: "Well, only if it is red" is partly); None otherwise."""
    whole = _whole(utterance)
    if whole is not None:
        return whole
    words = (normalize(clause) for clause in _CLAUSES.split(utterance))
    labels = {_label(w) for w in words if w and w not in COURTESY and w not in _MARKERS}  # None: no reply
    return next(iter(labels)) if len(labels) == 1 else None


def _whole(utterance: str) -> str | None:
    """The reply ``utterance`` is as a whole (:func:`_label`), unless it is of several clauses and
    read whole opens a reply word that takes any words after it ("it depends on ...", "only for
    ..."), which would swallow the clauses after its own."""
    words = normalize(utterance)
    label = _label(words)
    if label is None or sum(1 for c in _CLAUSES.split(utterance) if c.strip()) < 2:
        return label
    bare = _bare(words)
    return None if _DEPENDS.fullmatch(bare) or _RESTRICTION.fullmatch(bare) else label


def _bare(words: str) -> str:
    """``words`` without a courtesy at either end ("no thanks"), a discourse marker before them
    ("actually no") and a reply tail after them ("... here")."""
    for courtesy in COURTESY:
        words = words.removesuffix(f" {courtesy}").removeprefix(f"{courtesy} ")
    return _TAIL.sub("", _MARKER.sub("", words))


def _label(words: str) -> str | None:
    """The reply the clause ``words`` (normalised) is: a phrase of a table, "it depends on ..." or a
    restriction ("only for her books": partly), a referral ("ask Jake", "let me ask Jake": don't-know),
    or a run of different phrases of one table ("of course it does"); None otherwise."""
    words = _bare(words)
    if (kind := _KIND.get(words)) is not None:
        return kind
    if _DEPENDS.fullmatch(words):
        return "partly"
    if _REFERRAL.fullmatch(words) or _SELF_REFERRAL.fullmatch(words):
        return "unknown"
    if _RESTRICTION.fullmatch(words):
        return "partly"
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
    names = ctx.names(besides=ctx.about)
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
        if (felt := _feeling(words, ctx, asked)) is not None:
            return felt
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


def _refused_by_parser(words: str, ctx: Context) -> bool:
    """True if the parser reads nothing in ``words`` (it refuses them, or reads only someone introducing
    themself or how the speaker is), so reading them otherwise leaves out nothing it would store."""
    from ownctl.language.understand import understand

    try:
        return understand(words, ctx).intent in ("introduction", "remark")
    except NotUnderstood:
        return True
    except OwnctlError:
        return False


def _agent_names(ctx: Context) -> frozenset[str]:
    """The known agents' names as normalised words are spelled."""
    return frozenset(a.lower() for a in ctx.agents)


def _use(words: str) -> str | None:
    """``"kept"`` if the clause ``words`` says someone uses or needs the object ("Jake is still drinking
    from it", "my son needs it for school"), ``"freed"`` if it says nobody does ("nobody is using it"),
    None if it says neither. Someone using it is a reason to keep it, after a no; nobody using it one
    to let it go, never after a no."""
    m = _IN_USE.fullmatch(words)
    if m is None or m["who"] in _NOT_USERS:
        return None
    return "freed" if m["who"] == "nobody" else "kept"


def _feeling(words: str, ctx: Context, asked: str | None) -> tuple[Instruction, ...] | None:
    """The norm the clause ``words`` states by how someone feels about others doing something to their
    things ("Xuan doesn't like people touching her stuff": never touch Xuan's stuff; "I don't mind people
    taking my things": you may), read by the parser as that prohibition or permission; None if the clause
    says no such thing. "He", "she" or "they" is the agent last mentioned (the one a rule asked about)."""
    from ownctl.language.understand import understand

    m = _FEELING.fullmatch(words)
    if m is None:
        return None
    who = (ctx.mentioned or "").lower() if m["who"] in _PRONOUNS else m["who"]
    if who == "i" and m["owner"] == "my":
        possessor = "my"
    elif who in _agent_names(ctx) and m["owner"] in ("her", "his", "their", f"{who} 's"):
        possessor = f"{who} 's"
    else:
        return None
    lead = "never" if _FEELINGS[m["feeling"]] == "forbid" else "you may"
    stated = f"{lead} {_BASE_OF_GERUND.get(m['act'], m['act'])} {possessor} {m['things']}"
    try:
        understood = understand(stated, ctx)
    except OwnctlError:
        return None
    norms = understood.instructions
    return norms if norms and all(isinstance(i, NormInstruction) for i in norms) else None


@dataclass
class _Reply:
    """A reply read clause by clause: its reply words in order, whether the first clause is one,
    what its statements say, the claims of the clauses that only say whose OBJ is (reasons), whether
    a clause could not be read, whether one holds the question off ("hold on"), and the notes of
    clauses the parser reads nothing in: that someone uses or needs OBJ (``"kept"``), that nobody
    does (``"freed"``), that the speaker owns it with others (``"shared"``)."""

    labels: list[str] = field(default_factory=list)
    led: bool | None = None
    said: list[Instruction] = field(default_factory=list)
    reasons: list[Claim] = field(default_factory=list)
    unread: bool = False
    held: bool = False
    notes: set[str] = field(default_factory=set)

    @property
    def lead(self) -> str | None:
        """The reply word the reply opens with, if it opens with one."""
        return self.labels[0] if self.led else None

    def take(self, words: str, ctx: Context, asked: str | None, split: bool = True) -> None:
        """Read one clause (normalised): a hold marker before it, a reply word, a note, a statement or a
        remark; split it before a conjunction if it reads as nothing."""
        words = _OPENER.sub("", words)
        if (hold := _HOLD.match(words)) is not None:  # "hold on, ask Jake": checked in _reply
            self.held, words = True, words[hold.end():]
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
        if self.note(words, ctx):
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

    def note(self, words: str, ctx: Context) -> bool:
        """Note the clause ``words`` if it says whether someone uses or needs OBJ or that the speaker owns
        it with others and the parser reads nothing in it; False if it is no such clause."""
        note = _use(words) or ("shared" if _SHARED.fullmatch(words) else None)
        if note is None or not _refused_by_parser(words, ctx):
            return False
        self.notes.add(note)
        return True


def _reply(utterance: str, ctx: Context, asked: str | None, led: bool = False) -> _Reply:
    """``utterance`` read clause by clause (the whole first, when it is one reply word); with
    ``led``, only as far as its first clause when that is no reply word (the reply is then read as
    a sentence)."""
    reply = _Reply()
    whole = _whole(utterance)
    if whole is not None:
        reply.labels, reply.led = [whole], True
        return reply
    for clause in _CLAUSES.split(utterance):
        reply.take(normalize(clause), ctx, asked)
        if led and reply.led is False:
            break
    if reply.held and (set(reply.labels) != {"unknown"} or reply.said):  # held off only for a don't-know
        reply.unread = True
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
    if not _reasons_fit(reply.notes, reply.lead):  # "Yes, Jake is still using it"
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


def _reasons_fit(notes: set[str], lead: str) -> bool:
    """True if the notes of a reply to "may I ...?" fit the reply word it leads with: someone using the
    object only with a no, nobody using it never with one, and nobody else owning it with the speaker
    (a permission answer says nothing of that)."""
    return not ("shared" in notes or "kept" in notes and lead != "no" or "freed" in notes and lead == "no")


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
    norms = [owner_norm(action, agent) for agent in owners] if forbid else []
    for i in said:
        fits = (isinstance(i, Permission) and (i.action, i.object, i.forbid) == (action, obj, forbid)
                or isinstance(i, Claim) and i.object == obj or isinstance(i, NormInstruction) and i in norms)
        if not fits:
            return None
    if _against(normalize(utterance), action, forbid) or not _agree(claims, utterance, ctx):
        return None
    given = [i for i in said if isinstance(i, NormInstruction)]
    if forbid:
        given += [owner_norm(action, c.agent) for c in reasons if not c.negated]
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
    named = {lit.arg for lit in rule.literals if lit.pred == "ownedBy" and lit.arg in ctx.agents}
    mentioned = ctx.mentioned or (named.pop() if len(named) == 1 else None)  # "she": the rule's owner
    ctx = replace(ctx, action=rule.action, mentioned=mentioned)
    reply = _reply(utterance, ctx, rule.action, led=True)
    if reply.lead is None:  # no reply word first: the sentence must state the norm, and only it
        said = _sentence(utterance, ctx, rule.action) or _feeling(normalize(utterance), ctx, rule.action)
        stated = set(said or ())
        norm = stated.pop() if len(stated) == 1 else None
        return (norm,) if isinstance(norm, NormInstruction) and norm.norm.rule == rule else None
    if set(reply.labels) != {reply.lead} or reply.unread or reply.notes - {"freed"}:
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
        if (reply.unread or "kept" in reply.notes or len(claims) != len(reply.said)
                or set(reply.labels) - {"unknown"}):
            return None
        if not claims:
            return () if reply.labels else None
    if _doubts(utterance) and any(not c.negated for c in claims):  # "Jake's, no idea": unsure
        return None
    if not _agree(claims, utterance, ctx) or not _shares(claims, utterance, ctx):
        return None
    return _completed(claims, obj, ctx)


def _shared(utterance: str) -> str | None:
    """``"both"`` or ``"some"`` if a clause of ``utterance`` says the speaker owns the object with others
    ("both of ours", "it's ours", "we share it"), None if none does."""
    for clause in _CLAUSES.split(utterance):
        words = _bare(_OPENER.sub("", normalize(clause)))
        tokens = set(words.split())
        if _SHARED.fullmatch(words) or "ours" in tokens and not tokens & _NEGATIONS:
            return "both" if tokens & {"both", "two"} else "some"
    return None


def _shares(claims: list[Claim], utterance: str, ctx: Context) -> bool:
    """True unless the answer says the speaker owns the object with others ("both of ours", "it's ours")
    and the owners it names are not the speaker and at least one other (exactly one with "both"): "ours"
    alone names nobody else, so it cannot say whose the object is not."""
    shared = _shared(utterance)
    if shared is None:
        return True
    owners = {c.agent for c in claims if not c.negated}
    return ctx.speaker in owners and (len(owners) == 2 if shared == "both" else len(owners) > 1)


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
