"""The naming rule for agents, objects, areas, colours and categories (docs/architecture.md, section 2)."""

from __future__ import annotations

import re

from ownctl.errors import BadName

NAME_RULE = "a letter, then letters, digits, '_' or '-' (at most 64 characters)"
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_-]{0,63}")
RESERVED = frozenset({"any", "none", "not", "and", "if", "on", "forbid", "allow"})


def is_name(text: str) -> bool:
    """True if ``text`` obeys the naming rule (reserved words included)."""
    return _NAME.fullmatch(text) is not None


def check_name(kind: str, name: str) -> str:
    """Return ``name`` if it is a valid, unreserved name for a new ``kind``; raise BadName otherwise."""
    if not isinstance(name, str) or not is_name(name):
        raise BadName(f"invalid {kind} name {name!r}: a name is {NAME_RULE}")
    if name.lower() in RESERVED:
        raise BadName(f"{kind} name {name!r} is reserved; reserved words: {', '.join(sorted(RESERVED))}")
    return name
