"""``understand(utterance, ctx)``: normalise, try the grammar's rules in order, build the reply.

Rule order: statements (reprimands, claims, permissions, norms) before dialogue (questions,
introductions, tasks, requests, small talk). The forms hardly overlap because every pattern must
match the whole utterance; where they could, the order above decides, deterministically.

An utterance no rule matches as a whole is split at punctuation (. ! ? ; ,) into the fewest pieces
that each parse: "Hi, I'm Jake. Can you throw this away?" is an introduction then a question,
and the question is understood with Jake as the speaker. The combined intent is that of the first
piece that is not a greeting, thanks or introduction.
"""

from __future__ import annotations

import re
from dataclasses import replace

from ownctl.errors import OwnctlError
from ownctl.language import dialogue, statements
from ownctl.language.context import Context, NotUnderstood, Understanding
from ownctl.language.grammar import GrammarRule, first_match
from ownctl.language.instructions import Introduce
from ownctl.language.normalize import normalize
from ownctl.language.reply import reply
from ownctl.language.resolve import Resolver

#: Every grammar rule, in the order they are tried.
RULES: tuple[GrammarRule, ...] = (*statements.GRAMMAR.rules, *dialogue.GRAMMAR.rules)

_CHUNK_END = re.compile(r"[.!?;,]+")
_SOCIAL = ("greeting", "thanks", "introduction")


def understand_one(utterance: str, ctx: Context) -> Understanding:
    """Understand one sentence as a whole (no splitting); NotUnderstood if no rule matches it."""
    text = normalize(utterance)
    if not text:
        raise NotUnderstood(utterance, "there is nothing to understand")
    try:
        found = first_match(RULES, text, Resolver(ctx))
    except NotUnderstood as err:  # a rule that knows why it cannot help
        raise NotUnderstood(utterance, err.detail) from None
    if found is None:
        raise NotUnderstood(utterance)
    rule, instructions = found
    return Understanding(rule.intent, instructions, reply(rule.intent, instructions), rule.name)


def _after(ctx: Context, understood: Understanding) -> Context:
    """The context for the next sentence: an introduction makes its agent the speaker."""
    for i in understood.instructions:
        if isinstance(i, Introduce):
            ctx = replace(ctx, speaker=i.agent, agents=ctx.agents | {i.agent})
    return ctx


def _pieces(utterance: str, ctx: Context) -> list[Understanding]:
    """Split at punctuation into the fewest pieces that each parse (ties: longer first piece).

    Dynamic programming over the punctuation-delimited chunks, so punctuation inside a sentence
    ("throw this! away") does not matter. Chunks holding only a vocative or punctuation are dropped.
    """
    cuts = sorted({0, *(m.end() for m in _CHUNK_END.finditer(utterance)), len(utterance)})
    memo: dict[tuple[int, Context], list[Understanding] | None] = {}
    errors: list[OwnctlError] = []  # from pieces that matched a form but named something wrong

    def best(i: int, ctx: Context) -> list[Understanding] | None:
        if i == len(cuts) - 1:
            return []
        if (i, ctx) not in memo:
            found: list[Understanding] | None = None
            if not normalize(utterance[cuts[i]:cuts[i + 1]]):
                found = best(i + 1, ctx)
            for j in range(len(cuts) - 1, i, -1):
                try:
                    head = understand_one(utterance[cuts[i]:cuts[j]], ctx)
                except NotUnderstood:
                    continue
                except OwnctlError as err:
                    errors.append(err)
                    continue
                rest = best(j, _after(ctx, head))
                if rest is not None and (found is None or len(rest) + 1 < len(found)):
                    found = [head, *rest]
            memo[i, ctx] = found
        return memo[i, ctx]

    pieces = best(0, ctx)
    if pieces is not None:
        return pieces
    if errors:
        raise errors[0]
    bad = next((utterance[a:b] for a, b in zip(cuts, cuts[1:], strict=False)
                if normalize(utterance[a:b]) and not _parses(utterance[a:b], ctx)), "")
    raise NotUnderstood(utterance, f"in particular {bad.strip(' .!?;,')!r}" if bad else "")


def _parses(text: str, ctx: Context) -> bool:
    """True if ``text`` parses as one piece (errors other than NotUnderstood count as parsing)."""
    try:
        understand_one(text, ctx)
    except NotUnderstood:
        return False
    except OwnctlError:
        return True
    return True


def _combine(parts: list[Understanding]) -> Understanding:
    """One understanding for several sentences, instructions in order."""
    if len(parts) == 1:
        return parts[0]
    main = next((u for u in parts if u.intent not in _SOCIAL), parts[0])
    return Understanding(
        main.intent,
        tuple(i for u in parts for i in u.instructions),
        " ".join(u.reply for u in parts if u.reply),
        "+".join(u.form for u in parts),
    )


def understand(utterance: str, ctx: Context) -> Understanding:
    """What ``utterance``, said in ``ctx``, means: intent, instructions in order, and the reply.

    Raises NotUnderstood (an OwnctlError listing examples) if it cannot be parsed, MissingContext
    if it refers to a speaker, object or action the context does not give, and UnknownName or
    BadName for a name that is not known (an agent in a claim) or not valid (an introduced name).
    """
    try:
        return understand_one(utterance, ctx)
    except NotUnderstood as err:
        if not _CHUNK_END.search(utterance.strip(" .!?;,")) or "nothing to understand" in err.message:
            raise
    return _combine(_pieces(utterance, ctx))
