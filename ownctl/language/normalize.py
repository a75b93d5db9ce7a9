"""Utterance normalisation: one lower-case word string for the many ways of typing a sentence.

The grammar sees only this form, so it never deals with case, punctuation, curly apostrophes,
contractions, vocatives ("No Baxter, ...") or "please". Steps, in order:

1. straight apostrophes, lower case;
2. a vocative at the start ("Baxter, ...", "No Baxter ..."), after a comma in the middle or after
   punctuation at the end is dropped (a name inside a sentence, "that belongs to baxter", stays);
3. punctuation becomes spaces; apostrophes inside words and hyphens inside names stay;
4. contractions are expanded and spelling variants unified ("that's" -> "that is", "don't" ->
   "do not", "no one" -> "nobody", "okay" -> "ok"); a remaining "'s" is a possessive, split off
   as its own word ("casey's" -> "casey 's");
5. fillers ("please", "um", "just") go;
6. a phrasal verb's particle is moved before its object ("throw this wallet away" -> "throw away
   this wallet"), so each action phrase is one contiguous string, and putting something in the bin
   is throwing it away ("chuck it in the bin" -> "throw away it");
7. a reproach for what was done forbids doing it ("you shouldn't have picked that up" -> "do not
   pick up that").

Some phrases are said in the words the grammar knows: "Jake's the owner" -> "jake is the owner",
"I'm the one who owns" -> "i own", "belonging to" -> "owned by", "did you refuse to" -> "did you
not", "that would be Jake's" -> "that is jake 's" (a polite "is", not a conditional).

Spaces are collapsed before the rewrites, so punctuation inside a phrase ("never, ever") does not
break it.
"""

from __future__ import annotations

import re
from functools import lru_cache

from ownctl.language.lexicon import (
    BASE_OF_PARTICIPLE,
    BIN_VERBS,
    BIN_WORDS,
    FILLERS,
    PARTICLE_VERBS,
    PARTICLES,
    ROBOT_NAMES,
    alternation,
    inflect,
)
from ownctl.logic.names import composed, marks

_QUOTES = str.maketrans({"\u2019": "'", "\u2018": "'", "`": "'", "\u00b4": "'", "\u02bc": "'"})
_VOC = alternation(ROBOT_NAMES)
_INTERJECTIONS = r"(hey|hi|hello|ok|okay|oh|no|nope|so|well|please|stop|wait|yes|thanks|thank you)"
_PUNCT = r"[\s,.!?;:\u2013\u2014-]"
_LEAD_VOC = re.compile(rf"^[\s\W]*(?:{_INTERJECTIONS}{_PUNCT}+)?{_VOC}(?={_PUNCT}|$)")
_MID_VOC = re.compile(rf"[,\u2013\u2014-]\s*{_VOC}\s*[,\u2013\u2014-]")
_TAIL_VOC = re.compile(rf"[,.!?;:\u2013\u2014-]\s*{_VOC}{_PUNCT}*$")

REWRITES: tuple[tuple[re.Pattern[str], str], ...] = tuple(
    (re.compile(p), r)
    for p, r in (
        (r"\bno[ -]?one\b|\bnobody\b", "nobody"),
        (r"\bcan't\b|\bcannot\b|\bcant\b", "can not"),
        (r"\bwon't\b", "will not"),
        (r"\bain't\b", "is not"),
        (r"\bshan't\b", "shall not"),
        (r"\b(do|does|did|is|are|was|were|should|must|could|would|have|has)n'?t\b", r"\1 not"),
        (r"(\w)n't\b", r"\1 not"),
        (r"\bi'm\b|\bim\b", "i am"),
        (r"\bwhos\b(?= (?:is|the|that|this|it|going|owning|speaking)\b)", "who is"),
        (r"\bwhos\b", "whose"),
        (r"\b(?:nah|naw|nope)\b", "no"),
        (r"\byou're\b|\byoure\b", "you are"),
        (r"\blet's\b", "let us"),
        (r"\b(that|this|it|what|who|where|there|here|he|she|one)'s\b", r"\1 is"),
        (r"\b(that|what|it)s\b", r"\1 is"),
        (r"'re\b", " are"),
        (r"'ll\b", " will"),
        (r"'ve\b", " have"),
        (r"\bi'd\b", "i would"),
        (r"\b(that|this|it|they|these|those)'d be\b", r"\1 would be"),
        (r"\b(that|this|it) would be\b", r"\1 is"),
        (r"\b(they|these|those) would be\b", r"\1 are"),
        (r"'s\b", " 's"),
        (r"\b([\w-]+) 's (?=the (?:owner|owners|one|person|people)\b)", r"\1 is "),
        (r"\bi am the (?:one|person) (?:who|that) owns?\b", "i own"),
        (r"\b(?:is|are) the (?:one|ones|person|people) (?:who|that) owns?\b", "owns"),
        (r"\bbelonging to\b", "owned by"),
        (r"\b(did|do|does|would|will|are|were) you (?:refuse|refusing) to\b", r"\1 you not"),
        (r"\b(anybody)\b", "anyone"),
        (r"\bsomebody\b", "someone"),
        (r"\beverybody\b", "everyone"),
        (r"\bokay\b|\balright\b|\ball right\b", "ok"),
        (r"\bcolou?red\b", "colored"),
        (r"\bcolour\b", "color"),
        (r"\bgonna\b", "going to"),
        (r"\bwanna\b", "want to"),
        (r"\bnever ever\b|\bdo not ever\b|\bdo not you ever\b|\bnever ever ever\b", "never"),
        (r"\bhow come\b", "why"),
        (r"\b(is|are|was|were) still\b", r"\1"),
        (r"\bwhatever\b(?= (?:is|are|belongs|belong|has|does|nobody|someone|you)\b)", "anything that"),
    )
)

_STOP = alternation((*PARTICLES, "and", "if", "then", "when", "because"))
_PARTICLE_FORMS = sorted({f for v in PARTICLE_VERBS for f in (v, inflect(v, "ing"), inflect(v, "en"))})
_PARTICLE = re.compile(
    rf"\b({'|'.join(_PARTICLE_FORMS)}) ((?:(?!{_STOP})[\w'-]+ ){{1,5}}?)({'|'.join(PARTICLES)})\b"
)


def _drop_vocatives(text: str) -> str:
    """Remove the robot's name where it is only addressed, keeping a leading interjection."""
    text = _LEAD_VOC.sub(lambda m: f"{m.group(1) or ''} ", text, count=1)
    text = _MID_VOC.sub(",", text)
    return _TAIL_VOC.sub(" ", text)


#: Punctuation (anything but word characters, combining marks, spaces, apostrophes and hyphens).
_PUNCTUATION = re.compile(rf"[^\w\s'{marks()}-]|_(?![\w-])")


def _strip_punctuation(text: str) -> str:
    """Punctuation to spaces; keep apostrophes and hyphens inside words; split plural possessives."""
    text = _PUNCTUATION.sub(" ", text)
    text = re.sub(r"(\w)s'(?=\s|$)", r"\1s 's", text)
    return re.sub(r"(?<![\w])(?:-+|'(?!s\b))|['-]+(?![\w])", " ", text)


_BIN = re.compile(
    rf"\b(?:{'|'.join(BIN_VERBS)}) ((?:(?!{_STOP})[\w'-]+ ){{1,6}}?)(?:in|into|in to) (?:the |a |your )?"
    rf"{alternation(BIN_WORDS)}(?! area| zone)"
)


def _move_particles(text: str) -> str:
    """``throw this away`` -> ``throw away this``: the particle joins its verb; ``put this in the
    bin`` -> ``throw away this``."""
    text = _BIN.sub(lambda m: f"throw away {m.group(1).strip()}", text)
    return _PARTICLE.sub(lambda m: f"{m.group(1)} {m.group(3)} {m.group(2)}", text)


_UNDONE = re.compile(
    rf"\byou (?:should|must|ought to) (?:not|never) have ({alternation(tuple(BASE_OF_PARTICIPLE))})"
)


def _undone(text: str) -> str:
    """``you should not have picked up that`` -> ``do not pick up that``: a reproach for what was
    done forbids doing it."""
    return _UNDONE.sub(lambda m: f"do not {BASE_OF_PARTICIPLE[m.group(1)]}", text)


@lru_cache(maxsize=4096)
def normalize(utterance: str) -> str:
    """The canonical word string of an utterance (lower case, single spaces, no punctuation)."""
    text = _drop_vocatives(composed(utterance).translate(_QUOTES).lower())
    text = " ".join(_strip_punctuation(text).split())
    for pattern, repl in REWRITES:
        text = pattern.sub(repl, text)
    text = " ".join(w for w in text.split() if w not in FILLERS)
    return " ".join(_undone(_move_particles(text)).split())
