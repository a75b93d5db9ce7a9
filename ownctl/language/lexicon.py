"""The words the grammar knows: action phrases, pronouns, heads of noun phrases, hedges, fillers.

Everything here is lower case and already normalised (see :mod:`ownctl.language.normalize`):
contractions are expanded ("don't" -> "do not"), possessives are split ("casey's" -> "casey 's")
and phrasal verbs are joined ("throw it away" -> "throw away it").

Action phrases (documented choice): *touching* or *moving* an object means picking it up, since the
robot cannot touch or move one without grasping it; *bringing* or *putting away* means collecting it
(taking it home).
"""

from __future__ import annotations

import re
from itertools import product

#: Names the robot answers to; stripped when used as a vocative ("No Baxter, ...", "Robot, ...").
ROBOT_NAMES = ("baxter", "robot")
ROBOT = "Baxter"

#: Action phrase -> action (docs/architecture.md, section 2). Longest phrases are tried first.
ACTION_PHRASES: dict[str, str] = {
    "throw away": "trash", "throw out": "trash", "toss out": "trash", "toss away": "trash",
    "toss": "trash", "chuck out": "trash", "chuck away": "trash", "chuck": "trash",
    "trash": "trash", "bin": "trash", "discard": "trash", "dispose of": "trash",
    "get rid of": "trash", "junk": "trash", "throw": "trash",
    "pick up": "pickUp", "lift": "pickUp", "grab": "pickUp", "take": "pickUp",
    "touch": "pickUp", "hold": "pickUp", "handle": "pickUp", "get": "pickUp", "move": "pickUp",
    "shift": "pickUp",
    "collect": "collect", "bring home": "collect", "bring back": "collect", "bring": "collect",
    "put away": "collect", "fetch": "collect", "gather": "collect", "gather up": "collect",
    "take home": "collect", "bring me": "collect", "dump": "trash", "dump out": "trash",
    "put down": "putDown", "set down": "putDown", "lay down": "putDown",
}

#: Irregular past participles of the verbs above ("thrown away", "picked up" is regular).
PARTICIPLES = {"throw": "thrown", "take": "taken", "get": "gotten", "put": "put", "hold": "held",
               "bring": "brought", "lay": "laid", "set": "set"}

#: Verbs whose particle may follow the object ("throw it away"); normalisation joins them.
PARTICLE_VERBS = ("throw", "toss", "chuck", "pick", "put", "bring", "clean", "tidy", "gather", "take",
                  "set", "lay", "dump")
PARTICLES = ("away", "out", "up", "home", "back", "down")

#: Places that mean the bin: "chuck it in the bin" is "throw it away".
BIN_WORDS = ("bin", "trash", "trash can", "garbage", "rubbish", "wastebasket", "dustbin", "waste bin")
#: Verbs that, with "in the bin", mean throwing away.
BIN_VERBS = ("put", "throw", "chuck", "toss", "dump", "drop", "stick", "place")

#: Deictic phrases: the object the conversation is about (``Context.about``).
DEICTIC = ("this", "that", "it", "this one", "that one", "these", "those", "they", "them")
#: Nouns that describe rather than name an object: "this thing", "that block".
GENERIC_NOUNS = frozenset({"one", "thing", "object", "item", "block", "cube", "stuff"})
#: Heads of a class of objects in a norm: "red things", "anything of Jake's".
CLASS_HEADS = (
    "anything", "everything", "something", "things", "thing", "stuff", "objects", "items",
    "blocks", "cubes", "belongings", "property", "possessions", "ones", "it", "them",
)

#: Words that are never object names in an object phrase (so "that is mine" is no object "is").
NOT_NOUNS = frozenset({
    "is", "are", "it", "this", "that", "these", "those", "them", "they", "if", "and", "or", "not",
    "to", "of", "in", "on", "with", "for", "nothing", "all", "any", "every", "mine", "yours",
    "away", "up", "out", "home", "back", "everyone", "someone", "nobody", "anyone", "other",
    "others", "my", "your", "the", "a", "an", "because", "since", "so", "alone", "now", "do",
    "when", "whenever", "which", "who", "whose", "what", "why", "where", "must", "should", "has",
    "have", "needs", "need", "stay", "stays", "remain", "remains", *CLASS_HEADS,
}) - {"thing"}

#: How a person is, said after "I am" or "I feel" ("I'm tired", "I feel sick", "I'm running
#: late"): a remark that stores nothing (``dialogue.remark``), and never a name after "I am"
#: (``dialogue.introduce``). :func:`is_state` also reads their endings.
STATE_WORDS = frozenset({
    "sorry", "done", "back", "here", "ok", "fine", "good", "ready", "going", "leaving", "finished",
    "busy", "afraid", "glad", "happy", "tired", "hungry", "thirsty", "sleepy", "sick", "ill", "well",
    "cold", "hot", "warm", "bored", "angry", "sad", "upset", "annoyed", "worried", "scared",
    "confused", "lost", "late", "early", "home", "out", "off", "away", "coming", "working",
    "cooking", "eating", "sleeping", "listening", "serious", "kidding", "joking", "okay", "alright",
    "free", "alone", "hurt", "cool", "great", "fantastic", "excited", "pleased", "grateful",
    "starving", "freezing", "boiling", "sweating", "shaking", "dying", "struggling", "melting",
    "waiting", "resting", "relaxing", "studying", "travelling", "traveling", "moving", "packing",
    "better", "worse", "awake", "asleep", "alive", "stuck", "beat", "wrecked", "broke", "prepared",
    "ashamed", "alarmed", "overwhelmed", "charmed", "informed", "thrilled", "sore", "dizzy",
    "grumpy", "cranky", "moody", "lonely", "calm", "knackered", "shattered", "wet", "soaked", "dry",
    "full", "stuffed", "unwell", "awful", "terrible", "mad", "fed", "worn", "burnt", "burned",
    "wiped", "impressed", "interested",
})

#: States of more than one word ("I'm in a hurry", "I'm off to bed").
STATE_PHRASES = (
    "in a hurry", "in a rush", "on my way", "on my way out", "out of breath", "running late",
    "off to bed", "off to work", "off to school", "off to sleep", "off to lunch", "off now",
    "done for today", "done for the day", "under the weather", "all set",
)

#: Endings of English participles and adjectives that no common given name has, read in words of
#: six letters or more ("frustrated", "stressed", "hopeful", "nervous", "miserable"). Names such
#: as Alfred, Mildred or Mohammed end in -red or -med, and Sterling or Xing in -ing, so those
#: endings are not read; states that have them are words of :data:`STATE_WORDS`.
STATE_ENDINGS = ("ted", "ded", "sed", "ked", "ped", "zed", "hed", "ved", "ned", "led", "ged", "ced",
                 "xed", "ied", "yed", "ful", "less", "ous", "able", "ible", "ive")

#: Words that cannot be a name in "I'm NAME" ("I'm sorry", "I'm done"): how a person is
#: (:data:`STATE_WORDS`), how a thing is (condition, worth), and words that point rather than name.
NOT_NAMES = STATE_WORDS | frozenset({
    "not", "sure", "the", "a", "an", "mine", "yours", "it", "this", "that", "allowed", "robot",
    "baxter", "you", "me", "red", "someone", "nobody", "anyone", "everyone", "in", "right", "wrong",
    "new",
    # how a thing is
    "broken", "old", "empty", "clean", "dirty", "junk", "rubbish", "garbage", "trash",
    "useless", "torn", "dead", "expired", "fresh", "used", "damaged",
    "missing", "ruined", "nothing", "everything", "something", "fragile", "heavy", "light",
    "expensive", "cheap", "precious", "important", "valuable", "worthless", "gone", "open",
    "closed", "ours", "theirs", "his", "hers", "there", "true", "false",
})


def is_state(word: str) -> bool:
    """True if ``word`` (one normalised word) says how someone is ("exhausted", "starving") rather
    than naming them: a word of :data:`STATE_WORDS`, or of six letters or more with one of
    :data:`STATE_ENDINGS`."""
    return word in STATE_WORDS or (len(word) >= 6 and word.isalpha() and word.endswith(STATE_ENDINGS))


#: Default colour words (``Context.colors``); "none" is a colour value but never an adjective.
COLORS = frozenset({
    "red", "green", "blue", "yellow", "orange", "purple", "pink", "black", "white", "brown",
    "grey", "gray", "cyan", "magenta", "none",
})

#: Hedges and the confidence they give a claim ("that's probably mine" -> p = 0.8).
HEDGES: dict[str, float] = {
    "probably": 0.8, "likely": 0.8, "i think": 0.8, "i believe": 0.8, "i guess": 0.6,
    "maybe": 0.6, "perhaps": 0.6, "definitely": 1.0, "certainly": 1.0, "really": 1.0,
    "actually": 1.0, "surely": 1.0, "i am sure": 1.0, "i am pretty sure": 0.8, "pretty sure": 0.8,
    "i reckon": 0.8, "i suppose": 0.6, "for sure": 1.0, "i am certain": 1.0, "i bet": 0.8,
    "as far as i know": 0.8, "if i am not mistaken": 0.8, "if i remember correctly": 0.8,
    "fairly sure": 0.8, "i am fairly sure": 0.8, "quite sure": 0.8, "i am quite sure": 0.8,
    "almost certain": 0.8, "i am almost certain": 0.8, "most likely": 0.8, "possibly": 0.6,
}
#: How sure a degree word makes "sure", "certain" or "confident" ("pretty certain": 0.8), with or
#: without "I am" before it; the table above keeps the phrases that are not of this form.
_DEGREES = {"pretty": 0.8, "fairly": 0.8, "quite": 0.8, "reasonably": 0.8, "almost": 0.8,
            "absolutely": 1.0, "completely": 1.0, "totally": 1.0, "very": 1.0, "": 1.0}
HEDGES.update({
    f"{lead}{degree} {word}".replace("  ", " ").strip(): p
    for degree, p in _DEGREES.items() for word in ("sure", "certain", "confident")
    for lead in ("", "i am ")
    if degree or lead
})

#: Who someone is to the speaker, said before their name ("my sister Mia": Mia).
KIN = frozenset({
    "sister", "brother", "friend", "colleague", "coworker", "co-worker", "roommate", "flatmate",
    "housemate", "wife", "husband", "partner", "son", "daughter", "mom", "mum", "dad", "mother",
    "father", "boss", "neighbour", "neighbor", "cousin", "aunt", "uncle", "grandma", "grandpa",
    "girlfriend", "boyfriend", "kid", "child", "niece", "nephew", "guest", "flat-mate", "room-mate",
})


def phrases(*parts: tuple[str, ...]) -> frozenset[str]:
    """Every phrase made of one choice from each part, in order (an empty choice adds no word)."""
    return frozenset(" ".join(w for w in pick if w) for pick in product(*parts))


#: Not knowing, said as having no notion of it: "no idea", "not a clue", "I haven't the faintest idea",
#: "no clue whose it is", "not the foggiest".
_NOTIONS = ("idea", "clue", "notion")
_NOTION_TAILS = ("", "whose", "whose it is", "at all", "whatsoever")
_NOT_HAVE = ("not", "i have not", "i have not got", "i do not have", "have not", "have not got")
_NOT_THE = ("the faintest", "the slightest", "the foggiest")
_NO_NOTION = tuple(sorted(
    phrases(("", "i have", "i have got", "absolutely", "i have absolutely"), ("no",), ("", "real"), _NOTIONS,
            _NOTION_TAILS)
    | phrases(_NOT_HAVE, ("a", "any", "the least", "the first", *_NOT_THE), _NOTIONS, _NOTION_TAILS)
    | phrases(_NOT_HAVE, _NOT_THE)))
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
             "your guess is as good as mine", "god knows", "heaven knows", "nobody knows", "i would not know",
             "how would i know", "how should i know") + _NO_NOTION
"""Saying one does not know: a reply that answers a pending question with nothing
(``ownctl.language.answers``), and a remark that stores nothing (``dialogue.remark``)."""


_IT_WORDS = ("it", "that", "this")
#: Asides saying the speaker still needs the object ("No, I still need it"): reasons to keep it.
STILL_NEEDED = (phrases(("i", "we"), ("", "still"), ("need", "use", "want"), _IT_WORDS)
                | phrases(("i am", "we are"), ("using", "still using", "keeping"), _IT_WORDS)
                | phrases(("i", "we"), ("will", "want to", "would like to"), ("keep",), _IT_WORDS))
#: Asides saying nobody needs the object any more ("Sure, I don't need it anymore"): reasons to let
#: it go.
NOT_NEEDED = (phrases(("i", "we"), ("do not", "no longer", "never"), ("need", "use", "want"), _IT_WORDS,
                      ("", "anymore", "any more", "now"))
              | phrases(("nobody",), ("needs", "uses", "wants"), _IT_WORDS, ("", "anymore", "any more"))
              | phrases(("i am", "we are"), ("done with",), _IT_WORDS))
#: Asides that say nothing when they stand alone between commas ("The keys are Xuan's, by the way").
ASIDES = frozenset({
    "by the way", "btw", "fyi", "for the record", "for your information", "just saying", "you know",
    "i mean", "to be honest", "honestly", "in fact", "of course", "as you know", "mind you",
}) | STILL_NEEDED | NOT_NEEDED

#: Discourse markers that may open a sentence without changing what it says ("So, whose is it?").
DISCOURSE = frozenset({
    "so", "and", "but", "ok", "well", "yes", "yeah", "yep", "sure", "right", "also", "then",
    "anyway", "oh", "ah", "alright", "actually", "listen", "look", "see", "just", "and also",
    "ugh", "phew", "whew", "gosh", "argh", "hmm", "um", "uh", "wow", "aw", "oops",
})

#: When something happened, said after a statement without changing what it stores ("I gave it to
#: Jake yesterday"); "now" is not among them: "it's Jake's now" means Jake's alone.
TIME_WORDS = frozenset({
    "yesterday", "today", "earlier", "earlier today", "this morning", "last week", "last night",
    "a while ago", "recently", "already", "just now", "the other day", "a minute ago", "before",
})

#: Said after a statement or a question without changing it: afterthoughts ("it's still mine
#: though") and question tags ("who owns this, do you know?").
AFTERTHOUGHTS = frozenset({
    "though", "anyway", "after all", "all the same", "do you know", "any idea", "if you know",
    "can you tell me", "do you remember",
})

#: Adjectives that may describe an object without naming it ("the little mug").
ADJECTIVES = frozenset({
    "little", "small", "big", "large", "old", "new", "empty", "full", "dirty", "clean", "broken",
    "tall", "short", "round", "square", "plastic", "metal", "wooden", "favourite",
    "favorite", "same", "whole", "last", "first", "own",
})

#: Words meaning the speaker, any agent, or no agent, in owner positions ("ours": the speaker owns
#: it, with others the sentence may name: "that's ours, mine and Jake's").
SPEAKER_WORDS = frozenset({"me", "mine", "my", "i", "myself", "ours"})
ANYONE_WORDS = frozenset({
    "someone", "anyone", "everyone", "someone else", "anyone else", "other people", "others",
    "another person", "other agents", "somebody else", "people",
})
NOBODY_WORDS = frozenset({"nobody"})

#: Words dropped wherever they occur.
FILLERS = frozenset({"please", "pls", "plz", "kindly", "um", "umm", "uh", "uhh", "erm", "er", "hmm",
                     "oh"})  # not "well": "as well", "I am not well"

#: What the parser says it understands when it does not (NotUnderstood's message).
EXAMPLES = (
    "No, that's mine!",
    "Don't throw this away, it's Jake's",
    "Never trash red things",
    "Whose is this?",
)


def alternation(words: tuple[str, ...] | frozenset[str] | list[str]) -> str:
    """A non-capturing regex alternation of phrases, longest first, each ending at a word boundary."""
    ordered = sorted(set(words), key=lambda w: (-len(w), w))
    return "(?:" + "|".join(re.escape(w) for w in ordered) + r")(?![\w-])"


def inflect(verb: str, form: str) -> str:
    """A verb's ``ing`` form or past participle (``en``): "throw" -> "throwing", "thrown"; "get"
    -> "getting", "gotten"; "take" -> "taking", "taken"; "collect" -> "collecting", "collected"."""
    if form == "en" and verb in PARTICIPLES:
        return PARTICIPLES[verb]
    tail = "ing" if form == "ing" else "ed"
    if verb.endswith("e") and not verb.endswith("ee"):
        return verb[:-1] + tail
    vowels = "aeiou"
    short = (len(verb) <= 4 and len(verb) >= 3 and verb[-1] not in vowels + "wxy"
             and verb[-2] in vowels and verb[-3] not in vowels)
    return verb + verb[-1] + tail if short else verb + tail


def _inflected(form: str) -> dict[str, str]:
    out: dict[str, str] = {}
    for phrase, act in ACTION_PHRASES.items():
        first, _, rest = phrase.partition(" ")
        if form == "en" and rest == "me":
            continue
        out[" ".join(filter(None, (inflect(first, form), rest)))] = act
    return out


#: An action phrase's past participle -> the phrase ("thrown away" -> "throw away").
BASE_OF_PARTICIPLE: dict[str, str] = {
    " ".join(filter(None, (inflect(first, "en"), rest))): phrase
    for phrase in ACTION_PHRASES for first, _, rest in [phrase.partition(" ")] if rest != "me"
}

#: "throwing away" -> trash ("stop throwing away my things").
GERUNDS: dict[str, str] = _inflected("ing")
#: "thrown away" -> trash ("things owned by Casey should never be thrown away").
PASSIVES: dict[str, str] = {**_inflected("en"), "got rid of": "trash"}
_FORMS = {**ACTION_PHRASES, **GERUNDS, **PASSIVES}


def actions_regex(action: str | None = None, forms: dict[str, str] | None = None) -> str:
    """Regex for the phrases of one action (or of every action), as said or in ``forms``."""
    table = ACTION_PHRASES if forms is None else forms
    return alternation([p for p, a in table.items() if action is None or a == action])


def action_of(phrase: str) -> str:
    """The action an action phrase names (``"throw away"``, ``"throwing away"``, ``"thrown
    away"`` -> ``trash``)."""
    return _FORMS[" ".join(phrase.split())]


def hedge_of(phrase: str | None) -> float:
    """The confidence a hedge gives (1.0 for none)."""
    return HEDGES.get(" ".join(phrase.split()), 1.0) if phrase else 1.0
