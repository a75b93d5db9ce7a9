"""Dialogue: questions, introductions, requests, whole tasks, greetings, thanks and remarks.

Documented choices: "Can you throw this away?" asks whether it is permitted (``check``), while
"Throw this away" / "Could you throw this away?" is a :class:`Request` (a check the application
may follow by acting). "Clear the table" and "Clean up (the workspace)" throw everything away
(``trashAll``, as in the original system); "Tidy up" puts everything away (``collectAll``): tidying
keeps things, it does not discard them.
"""

from __future__ import annotations

import re

from ownctl.language.context import NotUnderstood
from ownctl.language.grammar import Grammar, group
from ownctl.language.instructions import (
    AskActions,
    AskOwned,
    AskOwner,
    AskPermitted,
    AskWhy,
    Instruction,
    Introduce,
    Request,
    RunTask,
)
from ownctl.language.lexicon import DONT_KNOW, NOT_NAMES, STATE_PHRASES, actions_regex, alternation, is_state
from ownctl.language.resolve import Resolver

GRAMMAR = Grammar()

_TASK_OPENING = r"(?:(?:can|could|would|will) you |go |go and |go ahead and |now |let us |time to |" \
                r"i want you to |you should |you can )?"
_ALL = (
    r"(?:everything|it all|all of it|all of this|all this|all that|"
    r"(?:every|each)(?: single)? (?:thing|object|block|item|cube|one)|"
    r"all(?: of)?(?: the| this| that| these| those)?"
    r"(?: (?:objects|blocks|things|stuff|items|cubes|junk|mess|rubbish|garbage|trash|litter))?)"
    r"(?: up| away| out| off)?"
)
_PLACE = r"(?: (?:off |up )?(?:the|this|your|my) (?:table|workspace|desk|work area|surface|area)" \
         r"(?: (?:into|in) the (?:trash|bin))?)?"
#: "... you are allowed to", "... you may": a task takes only what it may anyway.
_MAY = rf"(?: (?:that |which )?you (?:are (?:allowed|permitted|able) to|may|can)(?: {actions_regex()})?)?"
_TASK_END = rf"{_MAY}(?: (?:now|for me|right now|please))?"
_QUESTION_LEAD = (r"(?:(?:do you know|can you tell me|could you tell me|tell me|i wonder|i want to know|"
                  r"(?:may|can|could) i ask(?: you)?|i would like to know|any idea) )?")
_GREETING = r"(?:hi|hello|hey|good (?:morning|afternoon|evening))(?: there)?"


# -- questions -------------------------------------------------------------------------------

@GRAMMAR.rule(
    "question",
    _QUESTION_LEAD + r"whose (?:(?P<noun><NAME>) )?(?:is|are) <LOBJ>(?P<guess> (?:mine|<NAME> 's)"
                     r"(?: or (?:mine|<NAME> 's))*)?",
    _QUESTION_LEAD + r"who (?:owns|is the owner of|has|is the owner of|are the owners of) <LOBJ>",
    _QUESTION_LEAD + r"who does <LOBJ> belong to",
    _QUESTION_LEAD + r"to whom does <OBJ> belong",
    _QUESTION_LEAD + r"who is <OBJ> owned by",
    _QUESTION_LEAD + r"(?:is|are) <OBJ> (?:mine|<NAME> 's|owned(?: by <NAME>)?)(?: or (?:mine|<NAME> 's))*",
    _QUESTION_LEAD + r"does <OBJ> belong to (?:me|<NAME>)(?: or (?:me|<NAME>))*",
    _QUESTION_LEAD + r"(?:do|does) (?:anyone|someone|anybody|<NAME>) own <OBJ>",
    _QUESTION_LEAD + r"(?:is|are) <OBJ> owned by (?:anyone|someone)",
    _QUESTION_LEAD + r"whose (?:(?P<noun2><NAME>) )?<OBJ> (?:is|are)",
    _QUESTION_LEAD + r"who <OBJ> belongs to",
    _QUESTION_LEAD + r"who owns <OBJ>",
    _QUESTION_LEAD + r"(?:whether|if) <OBJ> (?:is|are) (?:mine|<NAME> 's|owned by (?:me|<NAME>))",
    _QUESTION_LEAD + r"(?:whether|if) (?:i|<NAME>) (?:owns?) <OBJ>",
)
def ask_owner(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Whose is this?", "Who owns that?", "Who does this belong to?", "Is this Jake's?", "Do you
    know whose wallet this is?", "Whose keys are these, Jake's?" (a guess asks, it claims nothing),
    "Who owns the mug on the table?"."""
    noun = group(m, "noun") or group(m, "noun2")
    obj = r.obj(noun) if noun and r.is_object(noun) else r.obj(m["obj"])
    return (AskOwner(obj),)


@GRAMMAR.rule(
    "question",
    r"what (?:do|does) (?P<who>i|<NAME>) own",
    r"what (?:is|are) (?P<who>mine|<NAME> 's)",
    r"what (?:belongs|belong) to (?P<who>me|<NAME>)",
    r"(?:which|what) (?:things|objects|stuff|items|ones) (?:belong|belongs) to (?P<who>me|<NAME>)",
    r"(?:which|what) (?:things|objects|items|ones) (?:do|does) (?P<who>i|<NAME>) own",
    r"(?:what|which things) (?:is|are) owned by (?P<who>me|<NAME>)",
    r"(?:do|does) (?P<who>i|<NAME>) own (?:anything|something|any of (?:this|these|them|the things))",
    r"(?:which|what) (?:ones |things |objects |items )?(?:here )?"
    r"(?:of (?:these|those|them|the)(?: things| objects| items)?(?: here)? )?"
    r"(?:is|are) (?P<who>mine|<NAME> 's)",
    r"(?:is|are) (?:anything|something|any of (?:this|these|them|the things)) (?P<who>mine|<NAME> 's)",
)
def ask_owned(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"What do I own?", "What does Casey own?", "What's mine?", "Which things belong to Jake?",
    "Does Casey own anything?"."""
    word = m["who"]
    who = r.owner("me" if word in ("i", "mine") else word)
    return None if who.startswith("\0") or who == "any" else (AskOwned(who),)


@GRAMMAR.rule(
    "question",
    r"what (?:else )?(?:are|am)(?: not)? (?:you|i) (?:not )?(?:allowed|permitted|supposed) to do with <OBJ>",
    r"what (?:else )?(?:can|may|could|must|should)(?: not)? (?:you|i)(?: not)? do with <OBJ>",
    r"what (?:is|are) (?:it|you) (?:not )?(?:ok|fine|allowed) (?:for you )?to do with <OBJ>",
    r"what (?:are you|you are) (?:forbidden|not allowed) to do with <OBJ>",
    r"what (?:may|can) (?:you|i) do to <OBJ>",
)
def ask_actions(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"What are you not allowed to do with the book?", "What can you do with the mug?"."""
    return (AskActions(r.obj(m["obj"])),)


@GRAMMAR.rule(
    "question",
    r"why (?:can|could|may|would|will|did|do|are|is|must|should)(?: not)? (?:you|it)(?: not)? "
    r"(?:(?:allowed|permitted|forbidden|able) to |be )?<ACT> <OBJ>",
    r"why (?:you|it) (?:can|could|may|would|will|did|do|are|is|must|should) not "
    r"(?:(?:allowed|permitted|forbidden|able) to |be )?<ACT> <OBJ>",
)
def ask_why_action(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Why can't you throw this away?": explain that decision."""
    return (AskWhy(r.action(m["act"]), r.obj(m["obj"])),)


@GRAMMAR.rule("question", r"why(?: .*)?")
def ask_why(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"Why not?", "Why?": explain the last refusal; not a question joined to another sentence
    by "and" or "but" (each is then understood on its own)."""
    if re.search(r" (?:and|but) ", m.group()):
        return None
    return (AskWhy(),)


@GRAMMAR.rule(
    "question",
    r"(?:can|may) you <ACT> <OBJ>",
    r"are you (?:allowed|permitted|able) to <ACT> <OBJ>",
    r"(?:are you|is it) (?:not allowed|forbidden) (?:for you )?to <ACT> <OBJ>",
    r"is it (?:ok|fine|allowed|alright|safe) (?:for you )?to <ACT> <OBJ>",
    r"(?:can|may) you <DO>",
    r"(?:is|are) <OBJ> (?:ok|fine|allowed|safe) (?:for you )?to <ACT>(?: it| them)?",
)
def ask_permitted(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Can you throw this away?", "Are you allowed to trash this?", "Can you do that?"."""
    obj = r.obj(group(m, "obj") or "that")
    act = group(m, "act")
    return (AskPermitted(r.action(act) if act else r.current_action("do that"), obj),)


# -- introductions ---------------------------------------------------------------------------

@GRAMMAR.rule(
    "introduction",
    rf"(?:{_GREETING} )?(?P<lead>i am|my name is|call me|i am called|it is|this is) (?P<name><NAME>)"
    r"(?P<tail> here| speaking)?",
)
def introduce(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"I'm Jake", "Hi, I'm Jake", "Hello Baxter, I'm Jake", "My name is Jake", "It's Jake here".

    "I am" and "it is" also say how someone or something is ("I'm tired", "It's broken"): after
    "I am" a word of :data:`NOT_NAMES` or one :func:`is_state` reads as a state ("I'm exhausted")
    is no name, unless it names a known agent; after "it is" or "this is" only a
    known agent is, or a name followed by "here" or "speaking" ("This is Sam speaking"), so that
    a remark about an object never adds an agent."""
    name = m["name"]
    if name in NOT_NAMES or r.colour(name) or r.is_object(name):
        return None
    if m["lead"] == "i am" and is_state(name) and not r.is_agent(name):
        return None
    if m["lead"] in ("it is", "this is") and not m["tail"] and not r.is_agent(name):
        return None
    return (Introduce(r.new_agent(name)),)


# -- tasks and requests ----------------------------------------------------------------------

@GRAMMAR.rule(
    "task",
    rf"{_TASK_OPENING}{actions_regex('trash')} {_ALL}{_PLACE}{_TASK_END}",
    rf"{_TASK_OPENING}(?:clear|clean up|clean|empty|clear off|clear up){_PLACE}{_TASK_END}",
    rf"{_TASK_OPENING}clear everything(?: away| off)?{_TASK_END}",
)
def trash_all(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Throw everything away", "Trash everything", "Clear the table", "Clean up the workspace"."""
    return (RunTask("trashAll"),)


@GRAMMAR.rule(
    "task",
    rf"{_TASK_OPENING}(?:{actions_regex('collect')}|pick up|bring back|take back|put back) {_ALL}{_PLACE}"
    rf"(?: home| back home)?"
    rf"(?: and (?:(?:bring|take|put) (?:home|back|away) (?:it|them)|(?:bring|take|put) (?:it|them) "
    rf"(?:home|back|away)))?{_TASK_END}",
    rf"{_TASK_OPENING}tidy(?: up)?{_PLACE}{_TASK_END}",
    rf"{_TASK_OPENING}tidy(?: up)? {_ALL}{_PLACE}{_TASK_END}",
)
def collect_all(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Collect all the blocks", "Collect everything", "Put everything away", "Tidy up", "Tidy
    everything up"."""
    return (RunTask("collectAll"),)


@GRAMMAR.rule("request", r"(?:(?:could|would|will|can) you (?:please )?|go |go and |now |time to |"
                         r"i want you to |i need you to |you should |let us )?<ACT> <OBJ>"
                         r"(?: now| for me| right now)?")
def request(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Throw this away", "Pick that up", "Could you collect the wallet?"."""
    return (Request(r.action(m["act"]), r.obj(m["obj"])),)


@GRAMMAR.rule("question", r"(?:may|can|could|am) i .+")
def ask_for_self(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"May I throw this away?": the norms are about the robot's own actions, so say so."""
    raise NotUnderstood(m.string, "my norms are about what I may do; ask \"Can you throw this away?\"")


# -- small talk ------------------------------------------------------------------------------

@GRAMMAR.rule("greeting", _GREETING)
def greeting(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Hello": nothing to do but answer."""
    return ()


@GRAMMAR.rule("thanks", r"(?:thanks|thank you)(?: very much| so much| a lot)?(?: .*)?")
def thanks(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"Thank you": nothing to do but answer."""
    return ()


_DEGREE = (r"(?:so|really|very|a bit|a little|a little bit|quite|pretty|too|kind of|sort of|totally|"
           r"completely|super|extremely|just|rather|absolutely|incredibly|utterly|terribly|awfully|"
           r"a tad|somewhat|fairly|still|getting|a lot|much|way) ")
_REMARK_TAIL = (r"(?: (?:today|tonight|now|right now|at the moment|again|already|in here|out here|"
                r"these days|lately|this morning|this afternoon|this evening|after work|to be honest|"
                r"about (?P<about>\w+(?: \w+){0,3})))?")


@GRAMMAR.rule("remark", rf"(?:{alternation(DONT_KNOW)})(?: (?:sorry|either|then))?")
def not_knowing(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...]:
    """"No idea whose it is", "I don't know", "Beats me": the speaker knows nothing to tell."""
    return ()


@GRAMMAR.rule(
    "remark",
    rf"(?:i am|i feel|i am feeling|i have been|i was|i am getting) (?:not )?(?:feeling )?(?:{_DEGREE})*"
    rf"(?:(?P<state>[a-z]+)(?: out| up)?|(?P<phrase>{alternation(STATE_PHRASES)})){_REMARK_TAIL}",
)
def remark(m: re.Match[str], r: Resolver) -> tuple[Instruction, ...] | None:
    """"I'm exhausted", "I feel sick", "I'm so tired today", "I'm in a hurry": how the speaker is
    (:func:`ownctl.language.lexicon.is_state`) stores nothing; the robot acknowledges it. A word
    that is no state declines ("I'm Jake" is an introduction), and so does a remark about a known
    object or agent ("I'm worried about the mug, it's Jake's": there "it" is the mug)."""
    state = m["state"]
    if state is not None and (not is_state(state) or r.is_agent(state)):
        return None
    if m["about"] and any(r.is_object(w) or r.is_agent(w) for w in m["about"].split()):
        return None  # about something the robot knows: not small talk
    return ()
