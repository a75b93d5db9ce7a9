"""``understand(utterance, ctx)``: normalise, try the grammar's rules in order, build the reply.

A norm written in the robot's own rule language ("allow trash if isColored grey", as ``ownctl
forbid|allow`` and ``rules list`` write it) is that norm, before any English reading.

Rule order: statements (reprimands, claims, permissions, norms) before dialogue (questions,
introductions, tasks, requests, small talk). The forms hardly overlap because every pattern must
match the whole utterance; where they could, the order above decides, deterministically.

A sentence may open with a discourse marker ("so", "okay", "but") and carry a hedge at either end
("..., I think", "pretty sure ..."): the marker is dropped and the hedge lowers the confidence of
the claims the sentence makes.

An utterance no rule matches as a whole is split at punctuation (. ! ? ; , and dashes) and before
"and" or "but" into the fewest pieces that each parse: "Hi, I'm Jake. Can you throw this away?" is
an introduction then a question, and the question is understood with Jake as the speaker; "The
cup is mine and the mug is Jake's" two claims. A later piece's "it" is the object an earlier one
named, and its "he" the agent. A piece that does not parse is skipped only if
it holds no word that could carry meaning (an action, a name, an owner, a negation: "Go on",
"Whoa, whoa", "Just so you know") and the rest parses; the reply then says what was ignored. Two
splits that parse equally well but store different things are refused, with both readings shown.
Then, if nothing parses, misspelt words are corrected (:mod:`ownctl.language.spelling`) and the
utterance is tried once more; the reply says how each was read.

Time is linear in the length: a piece spans at most :data:`MAX_PIECE_CHUNKS` punctuation-delimited
chunks and :data:`MAX_PIECE_CHARS` characters, and an utterance longer than :data:`MAX_CHARS`
characters is refused at once. A piece holds one sentence unless it is short or a reprimand.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from functools import lru_cache
from itertools import product

from ownctl.errors import OwnctlError
from ownctl.language import dialogue, spelling, statements
from ownctl.language.context import Context, MissingContext, NotUnderstood, Understanding
from ownctl.language.grammar import GrammarRule, first_match
from ownctl.language.instructions import Claim, Instruction, Introduce, NormInstruction, Permission, Skip
from ownctl.language.lexicon import (
    ACTION_PHRASES,
    AFTERTHOUGHTS,
    ANYONE_WORDS,
    ASIDES,
    CLASS_HEADS,
    DISCOURSE,
    HEDGES,
    KIN,
    NOBODY_WORDS,
    SPEAKER_WORDS,
    TIME_WORDS,
    alternation,
    hedge_of,
)
from ownctl.language.normalize import normalize
from ownctl.language.reply import reply
from ownctl.language.resolve import Resolver
from ownctl.logic.rules import parse_norm

#: Every grammar rule, in the order they are tried.
RULES: tuple[GrammarRule, ...] = (*statements.GRAMMAR.rules, *dialogue.GRAMMAR.rules)
spelling.know_patterns(rule.pattern.pattern for rule in RULES)

#: The longest utterance understood (characters); longer ones are refused at once.
MAX_CHARS = 4000
#: A piece (one sentence, as parsed) spans at most this many chunks and characters.
MAX_PIECE_CHUNKS = 12
MAX_PIECE_CHARS = 200
#: A piece longer than this holds one sentence, unless it is a reprimand ("That's mine. Don't throw
#: it away!") of at most twice this length; a shorter one may hold stray punctuation ("can you
#: throw! this away?").
SHORT_PIECE_CHARS = 40

_CHUNK_END = re.compile(r"[.!?;,:]+|\s[-\u2013\u2014]+\s|[\u2013\u2014]")
#: Where a chunk may also end when splitting at punctuation finds no reading: before "and"/"but"
#: (two sentences joined: "the cup is mine and the mug is Jake's").
_CONJUNCTION = re.compile(r"\s(?=(?:and|but)\s)", re.IGNORECASE)
_SENTENCE_END = re.compile(r"[.!?;]")
_SOCIAL = ("greeting", "thanks", "introduction", "remark")
_DISCOURSE = re.compile(rf"^(?:{alternation(DISCOURSE)} )+")
_HEDGE = alternation(tuple(HEDGES))
_LEAD_HEDGE = re.compile(rf"^(?P<h>{_HEDGE}) ")
_TAIL_HEDGE = re.compile(rf" (?P<h>{_HEDGE})(?: so)?$")
#: Said after a sentence without changing it: when ("yesterday") or an afterthought ("though").
_TAIL = re.compile(rf" {alternation(TIME_WORDS | AFTERTHOUGHTS)}$")
#: Words that carry meaning: a piece holding one is never skipped.
_CONTENT = frozenset(
    {w for phrase in ACTION_PHRASES for w in phrase.split() if w not in ("me", "up", "out", "down")}
    | SPEAKER_WORDS | NOBODY_WORDS | {w for p in ANYONE_WORDS for w in p.split() if w != "people"}
    | set(CLASS_HEADS) - {"it", "them", "one", "ones"}
    | {"not", "never", "only", "unless", "except", "own", "owns", "owned", "owner", "belong", "belongs",
       "allowed", "forbidden", "permitted", "mine", "yours", "whose", "who", "why", "what", "can", "may",
       "must", "should", "do", "does", "did", "if", "clear", "clean", "tidy", "empty", "give", "gave"}
)


class TooLong(OwnctlError):
    """An utterance longer than :data:`MAX_CHARS` characters."""


@dataclass(frozen=True)
class _Piece:
    """One understood piece: its understanding and the notes its reply carries."""

    understood: Understanding
    ignored: str | None = None  # the text skipped instead of understood


def _intent(rule: GrammarRule, instructions: tuple[Instruction, ...]) -> str:
    """The intent of a statement follows what it stores ("No, that's mine!" said while the robot
    does nothing is a claim); other rules keep their own."""
    if rule.intent not in ("reprimand", "claim", "permission", "norm"):
        return rule.intent
    kinds = {type(i) for i in instructions}
    for kind, intent in ((Skip, "reprimand"), (NormInstruction, "norm"), (Permission, "permission"),
                         (Claim, "claim")):
        if kind in kinds:
            return intent
    return rule.intent


def _variants(text: str) -> list[tuple[str, float | None, str]]:
    """The text, then without an opening discourse marker, then without a hedge at either end:
    (text, confidence cap or None, what was dropped)."""
    out: list[tuple[str, float | None, str]] = [(text, None, "")]
    bare = text
    if (m := _DISCOURSE.match(text)) and m.end() < len(text):
        bare = text[m.end():]
        out.append((bare, None, m.group().strip()))
    if (t := _TAIL.search(bare)) and t.start() > 0:
        bare = bare[:t.start()]
        out.append((bare, None, t.group().strip()))
    for pattern in (_LEAD_HEDGE, _TAIL_HEDGE):
        if (h := pattern.search(bare)) and len(h.group()) < len(bare):
            rest = (bare[:h.start()] + " " + bare[h.end():]).strip()
            out.append((rest, hedge_of(h["h"]), h["h"]))
            if rest.startswith("that "):  # "pretty sure that the pen is Jake's"
                out.append((rest[5:], hedge_of(h["h"]), h["h"]))
    return out


def _hedged(instructions: tuple[Instruction, ...], cap: float) -> tuple[Instruction, ...]:
    """The claims with their confidence capped by a hedge."""
    return tuple(replace(i, p=min(i.p, cap)) if isinstance(i, Claim) else i for i in instructions)


@lru_cache(maxsize=64)
def _apposition(agents: frozenset[str]) -> re.Pattern[str]:
    names = alternation(tuple(a.lower() for a in agents))
    return re.compile(rf"\b(?:my|our|your) {alternation(tuple(KIN))} (?={names})")


def _appositions(text: str, ctx: Context) -> str:
    """``text`` with "my sister" dropped before a known agent's name ("belongs to my sister mia":
    Mia); a relation before a word that is not an agent's name stays."""
    if not ctx.agents or " " not in text:
        return text
    return _apposition(ctx.agents).sub("", text)


def _parse_one(utterance: str, ctx: Context) -> Understanding | None:
    """One sentence as a whole, or None if no rule matches it (a rule that knows why it cannot
    help raises NotUnderstood with its reason)."""
    text = _appositions(normalize(utterance), ctx)
    if not text:
        raise NotUnderstood(utterance, "there is nothing to understand")
    first: OwnctlError | None = None  # a variant's error is reported only if no variant parses
    for variant, cap, _ in _variants(text):
        resolver = Resolver(ctx)
        try:
            found = first_match(RULES, variant, resolver)
        except NotUnderstood as err:
            first = first or NotUnderstood(utterance, err.detail)
            continue
        except OwnctlError as err:
            first = first or err
            continue
        if found is None:
            continue
        rule, instructions = found
        if cap is None and (lead := _LEAD_HEDGE.match(variant)):  # a rule that took the hedge in
            cap = hedge_of(lead["h"])
        if cap is not None:
            instructions = _hedged(instructions, cap)
        intent = _intent(rule, instructions)
        return Understanding(intent, instructions, reply(intent, instructions), rule.name, resolver.topic)
    if first is not None:
        raise first
    return None


def understand_one(utterance: str, ctx: Context) -> Understanding:
    """Understand one sentence as a whole (no splitting); NotUnderstood if no rule matches it."""
    found = _parse_one(utterance, ctx)
    if found is None:
        raise NotUnderstood(utterance)
    return found


def _objects_named(understood: Understanding) -> list[str]:
    return [o for i in understood.instructions if (o := getattr(i, "object", None))]


def _after(ctx: Context, understood: Understanding) -> Context:
    """The context for the next piece: an introduction makes its agent the speaker; "it" is the
    last object named, "he"/"she" the last agent named other than the speaker."""
    for i in understood.instructions:
        if isinstance(i, Introduce):
            ctx = replace(ctx, speaker=i.agent, agents=ctx.agents | {i.agent})
    objects = _objects_named(understood) or ([understood.topic] if understood.topic else [])
    if objects:
        ctx = replace(ctx, about=objects[-1])
    agents = [i.agent for i in understood.instructions if isinstance(i, Claim) and i.agent != ctx.speaker]
    if agents:
        ctx = replace(ctx, mentioned=agents[-1])
    return ctx


def _has_content(text: str, ctx: Context) -> bool:
    """True if a piece holds a word that could carry meaning, so it must not be skipped: a word
    that names an action, an owner, a negation or a thing, or one the parser does not know (it may
    be a name: "that's Bob's")."""
    known = spelling.vocabulary()
    names = ctx.names()
    words = normalize(text)
    if words in ASIDES:
        return False
    return any(w in _CONTENT or w in names or w.removesuffix("s") in names or w not in known
               for w in words.split())


def _chunks(utterance: str, conjunctions: bool = False) -> list[tuple[int, int]]:
    """The punctuation-delimited chunks (start, end) of an utterance; with ``conjunctions``, also
    cut before each "and" and "but"."""
    ends = [m.end() for m in _CHUNK_END.finditer(utterance)]
    if conjunctions:
        ends += [m.end() for m in _CONJUNCTION.finditer(utterance)]
    cuts = sorted({0, *ends, len(utterance)})
    return list(zip(cuts, cuts[1:], strict=False))


_Cost = tuple[int, int, int]  # (pieces skipped, pieces, sentence ends inside pieces)


@dataclass
class _Path:
    """The best way found to understand the chunks before one boundary: its last piece and the
    path before it (a chain, so extending a path costs nothing), the context it leaves, a
    fingerprint of what it stores in order (equal fingerprints store the same), and another way as
    good that would store something else."""

    cost: _Cost
    ctx: Context
    prev: _Path | None = None
    piece: _Piece | None = None
    stored: int = 0
    other: _Path | None = None

    def then(self, piece: _Piece, skipped: bool, ctx: Context, crosses: bool = False) -> _Path:
        """This path followed by ``piece`` (which may hold a sentence end: "That's mine. Don't!")."""
        skip, count, crossed = self.cost
        cost = (skip + skipped, count + (not skipped), crossed + crosses)
        stored = self.stored
        for text in piece.understood.texts():
            stored = hash((stored, text))
        other = None if self.other is None else self.other.then(piece, skipped, ctx, crosses)
        return _Path(cost, ctx, self, piece, stored, other)

    def pieces(self) -> list[_Piece]:
        """The pieces of the path, in order."""
        out: list[_Piece] = []
        path: _Path | None = self
        while path is not None and path.piece is not None:
            out.append(path.piece)
            path = path.prev
        return out[::-1]


def _offer(paths: list[_Path | None], j: int, path: _Path) -> None:
    """Keep the better of two ways to reach boundary ``j``; remember a tie that stores otherwise."""
    old = paths[j]
    if old is None or path.cost < old.cost:
        paths[j] = path
    elif (path.cost == old.cost and old.other is None and path.stored != old.stored
          and set(_stored(path.pieces())) != set(_stored(old.pieces()))):
        old.other = path  # the same things in another order is no second reading


def _pieces(utterance: str, ctx: Context, conjunctions: bool = False) -> list[_Piece]:
    """Split at punctuation (and, with ``conjunctions``, before "and"/"but") into the fewest pieces
    that each parse, skipping only pieces that say
    nothing, and of those splits the one whose pieces hold fewest sentence ends (dynamic
    programming from left to right: each boundary keeps its best way there, and a piece spans a
    bounded number of characters, so the time is linear). Raises NotUnderstood naming the first
    piece that does not parse, or showing two readings when two best splits would store different
    things."""
    spans = _chunks(utterance, conjunctions)
    n = len(spans)
    errors: list[OwnctlError] = []  # from pieces that matched a form but named something wrong
    paths: list[_Path | None] = [_Path((0, 0, 0), ctx), *([None] * n)]
    for i in range(n):
        here = paths[i]
        if here is None:
            continue
        start, named_wrong = spans[i][0], False
        for j in range(i + 1, min(n, i + MAX_PIECE_CHUNKS) + 1):
            text = utterance[start:spans[j - 1][1]]
            if len(text) > MAX_PIECE_CHARS:
                break
            crosses = bool(_SENTENCE_END.search(utterance, start, spans[j - 2][1])) if j > i + 1 else False
            if crosses and len(text) > 2 * SHORT_PIECE_CHARS:
                break
            if not normalize(text):
                _offer(paths, j, here)
                continue
            try:
                head = _parse_one(text, here.ctx)
            except NotUnderstood:
                continue
            except OwnctlError as err:
                errors.append(err)
                named_wrong = named_wrong or (j == i + 1 and not isinstance(err, MissingContext))
                continue
            if head is None or (crosses and len(text) > SHORT_PIECE_CHARS and head.intent != "reprimand"):
                continue
            _offer(paths, j, here.then(_Piece(head), False, _after(here.ctx, head), crosses))
        text = utterance[start:spans[i][1]]
        if normalize(text) and not named_wrong and not _has_content(text, here.ctx):  # says nothing
            skipped = _Piece(Understanding("greeting", (), ""), text.strip(" .!?;,:-\u2013\u2014"))
            _offer(paths, i + 1, here.then(skipped, True, here.ctx))
    result = paths[n]
    if result is None:
        if errors:
            raise errors[0]
        bad = next((utterance[a:b] for a, b in spans if normalize(utterance[a:b])
                    and _has_content(utterance[a:b], ctx) and not _parses(utterance[a:b], ctx)), "")
        raise NotUnderstood(utterance, f"in particular {bad.strip(' .!?;,:-')!r}" if bad else "")
    if result.other is not None:
        readings = " or ".join(f"[{'; '.join(_stored(p.pieces())) or 'nothing'}]"
                               for p in (result, result.other))
        raise NotUnderstood(utterance, f"it has two readings: {readings}; say it in one sentence")
    return result.pieces()


def _stored(pieces: list[_Piece]) -> tuple[str, ...]:
    """What a reading stores or asks, in order (duplicates once)."""
    return tuple(dict.fromkeys(t for p in pieces for t in p.understood.texts()))


def _parses(text: str, ctx: Context) -> bool:
    """True if ``text`` parses as one piece (errors other than NotUnderstood count as parsing)."""
    try:
        understand_one(text, ctx)
    except NotUnderstood:
        return False
    except OwnctlError:
        return True
    return True


def _combine(pieces: list[_Piece]) -> Understanding:
    """One understanding for several pieces, instructions in order (an exact repeat once)."""
    parts = [p.understood for p in pieces if p.ignored is None]
    ignored = [p.ignored for p in pieces if p.ignored]
    note = " ".join(f"(ignored {text!r})" for text in ignored)
    if len(parts) == 1 and not ignored:
        return parts[0]
    main = next((u for u in parts if u.intent not in _SOCIAL), parts[0])
    return Understanding(
        main.intent,
        tuple(dict.fromkeys((*(i for u in parts for i in u.instructions), *_reasons(parts)))),
        " ".join(dict.fromkeys(filter(None, (*(u.reply for u in parts), note)))),
        "+".join(u.form for u in parts),
    )


def _reasons(parts: list[Understanding]) -> list[NormInstruction]:
    """The owners' norms a prohibition given with its reason states, across pieces ("Careful, that's
    not yours to throw away, it's Jake's": forbid trash if ownedBy jake), as one sentence states
    them (:func:`ownctl.language.statements.reprimand_claim`): for a forbidden action on an object
    in one piece, each agent another piece says owns that object. Within one piece the rule that
    read it decides ("Don't touch my book" states no norm)."""
    out = []
    for k, u in enumerate(parts):
        for forbid in (i for i in u.instructions if isinstance(i, Permission) and i.forbid):
            for other in parts[:k] + parts[k + 1:]:
                out += [statements.owner_norm(forbid.action, c.agent) for c in other.instructions
                        if isinstance(c, Claim) and c.object == forbid.object and not c.negated]
    return out


def _understand(utterance: str, ctx: Context) -> Understanding:
    """Understand as a whole, else split into pieces (if the pieces do not parse either, an error
    the whole raised that names a bad value is the one reported)."""
    whole: OwnctlError = NotUnderstood(utterance)
    if len(utterance) <= MAX_PIECE_CHARS:
        try:
            return understand_one(utterance, ctx)
        except OwnctlError as err:
            whole = err
            if (not _CHUNK_END.search(utterance.strip(" .!?;,:")) and not _CONJUNCTION.search(utterance)) \
                    or "nothing to understand" in err.message:
                raise
    try:
        pieces = _split(utterance, ctx)
        if all(p.ignored is not None for p in pieces):  # every piece says nothing ("ok, ok")
            raise NotUnderstood(utterance)
        return _combine(pieces)
    except NotUnderstood:
        if isinstance(whole, NotUnderstood) and not whole.detail:
            raise
        raise whole from None


def _split(utterance: str, ctx: Context) -> list[_Piece]:
    """The pieces of a split at punctuation; if it finds no reading, of a split also before "and"
    and "but", when that one does (otherwise the first split's error stands)."""
    try:
        return _pieces(utterance, ctx)
    except OwnctlError as err:
        if not _CONJUNCTION.search(utterance):
            raise
        first = err
    try:
        return _pieces(utterance, ctx, conjunctions=True)
    except OwnctlError:
        raise first from None


def _formal_norm(utterance: str) -> Understanding | None:
    """A norm in the robot's own rule language ("allow trash if isColored grey", as ``ownctl
    forbid|allow`` and ``rules list`` write it), said as it is written; None if it is not one."""
    words = utterance.strip().rstrip(".!").split()
    if not words or words[0].lower() not in ("forbid", "allow"):
        return None
    try:
        norm = parse_norm(" ".join([words[0].lower(), *words[1:]]))
    except OwnctlError:
        return None
    instructions = (NormInstruction(norm),)
    return Understanding("norm", instructions, reply("norm", instructions), "formal norm")


#: At most this many ways of reading the words near several others are tried.
MAX_READINGS = 16


def _corrected(utterance: str, readings: list[spelling.Reading], unclear: dict[str, list[str]],
               ctx: Context) -> tuple[Understanding | None, MissingContext | None]:
    """The utterance understood with its misspelt words read as the words they are near: each
    word near one word is read as it; a word near several is read as each in turn, and taken as
    read when every reading that parses stores the same ("Who ownes the book?": only "owns"
    parses). None when no reading parses, or when readings that parse store different things;
    beside it, when no reading parses, the one context every reading that parsed was missing
    ("Who ownes this?" with no current object: which object is 'this'?), if there is one."""
    choices = [[spelling.Reading(w, c) for c in near] for w, near in unclear.items()]
    found: list[tuple[frozenset[str], Understanding]] = []
    errors: dict[str, MissingContext] = {}
    for k, pick in enumerate(product(*choices)):
        if k == MAX_READINGS:
            return None, None
        tried = [*readings, *pick]
        try:
            got = _understand(spelling.apply(utterance, tried), ctx)
        except MissingContext as err:  # understood, but for what "this" is: worth telling
            errors.setdefault(err.message, err)
            continue
        except OwnctlError:
            continue
        notes = " ".join(r.note() for r in tried)
        found.append((frozenset(got.texts()), replace(got, reply=f"{got.reply} {notes}".strip())))
    if not found:
        return None, next(iter(errors.values())) if len(errors) == 1 else None
    if len({texts for texts, _ in found}) > 1:
        return None, None
    return found[0][1], None


def understand(utterance: str, ctx: Context) -> Understanding:
    """What ``utterance``, said in ``ctx``, means: intent, instructions in order, and the reply.

    Raises NotUnderstood (an OwnctlError listing examples) if it cannot be parsed, TooLong if it
    is longer than MAX_CHARS characters, MissingContext if it refers to a speaker, object or action
    the context does not give, and UnknownName or BadName for a name that is not known (an agent in
    a claim) or not valid (an introduced name).
    """
    if len(utterance) > MAX_CHARS:
        raise TooLong(f"the utterance is {len(utterance)} characters long; I understand at most "
                      f"{MAX_CHARS} at once: say it in shorter parts")
    formal = _formal_norm(utterance)
    if formal is not None:
        return formal
    try:
        return _understand(utterance, ctx)
    except OwnctlError as err:
        first = err
    readings, unclear = spelling.corrections(normalize(utterance).split(), ctx)
    if readings or unclear:
        got, why = _corrected(utterance, readings, unclear, ctx)
        if got is not None:
            return got
        if why is not None and isinstance(first, NotUnderstood):
            raise why from None
    if unclear and isinstance(first, NotUnderstood):
        maybe = "; ".join(f"{w!r} could be {' or '.join(repr(c) for c in cs)}" for w, cs in unclear.items())
        raise NotUnderstood(utterance, "; ".join(filter(None, (first.detail, maybe)))) from None
    raise first


__all__ = ["MAX_CHARS", "RULES", "TooLong", "understand", "understand_one"]
