"""The only exceptions users see.

Every user mistake is an :class:`OwnctlError` whose message names the bad value and lists the
valid ones (of more than :data:`MAX_LISTED` names, the closest and how to list them all); the CLI
prints it as one line on stderr and exits with ``exit_code``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence


class OwnctlError(Exception):
    """A user error: bad name, bad value, bad file. Exit code 1 unless a subclass says otherwise.

    ``message`` is complete (it already names the valid values); ``valid`` repeats them for --json.
    """

    exit_code = 1

    def __init__(self, message: str, valid: Iterable[str] | None = None) -> None:
        self.valid = sorted(set(valid)) if valid is not None else []
        super().__init__(message)
        self.message = message


class UnknownName(OwnctlError):
    """A name that the store or the vocabulary does not know."""

    def __init__(self, kind: str, name: str, known: Iterable[str]) -> None:
        known = sorted(set(known))
        if len(known) <= MAX_LISTED:
            listing = ", ".join(known) if known else "(none yet)"
            super().__init__(f"unknown {kind} {name!r}; known {kind}s: {listing}")
        else:  # a store of thousands of objects: the closest names, not a line of every name
            close = closest(name, known)
            nearest = f", the closest: {', '.join(close)}" if close else ""
            how = f" (ownctl {kind} list lists them all)" if kind in LISTED_KINDS else ""
            super().__init__(f"unknown {kind} {name!r}; {len(known):,} known {kind}s{nearest}{how}")
        self.valid = known


#: Up to this many known names, an unknown name's error lists them all; beyond, the closest.
MAX_LISTED = 20
LISTED_KINDS = ("object", "agent", "area")  # the kinds ``ownctl KIND list`` lists


def closest(name: str, known: Sequence[str], n: int = 5) -> list[str]:
    """Up to ``n`` names of ``known`` most like ``name`` (difflib's ratio at least 0.6), best first;
    on a large list only those of about its length that start with its first letter are compared."""
    import difflib

    pool = known
    if len(known) > 2000 and name:
        pool = [k for k in known if k[:1].lower() == name[:1].lower() and abs(len(k) - len(name)) <= 2]
    return difflib.get_close_matches(name, pool, n=n, cutoff=0.6)


class BadName(OwnctlError):
    """A name that breaks the naming rule (docs/architecture.md, section 2) or is reserved."""


class DuplicateName(OwnctlError):
    """A name that is already taken."""


class RuleSyntaxError(OwnctlError):
    """A malformed rule or literal list; the message points at the bad word."""


class BadValue(OwnctlError):
    """A number or option out of its range (a probability outside [0, 1], NaN, ...)."""


class StoreError(OwnctlError):
    """A missing, foreign, unreadable or too-new store."""


class StoreBusy(StoreError):
    """Another writer held the store too long, or the database chose this transaction as a deadlock
    or serialisation victim; nothing was written, and the whole instruction may be tried again."""


class ScenarioFailed(OwnctlError):
    """A scenario expectation or a task step failed (exit code 4)."""

    exit_code = 4
