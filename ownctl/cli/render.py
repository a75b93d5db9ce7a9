"""Times in the commands' output: table cells and JSON companions.

Times are formatted by :func:`ownctl.humanize.iso` (the one formatter, which the app's messages use
too). JSON documents keep every time as the number it is and gain an ISO 8601 string next to it
(``"time": 1000.0, "time_iso": "1970-01-01T00:16:40+00:00"``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ownctl.humanize import iso

#: the keys of ownctl's JSON documents whose values are store times (seconds), or maps to store times
TIME_KEYS = frozenset({"time", "created", "claim_time", "last_touch", "at"})


def when(value: Any) -> Any:
    """A time cell: ISO 8601 for a number of seconds, a map of them for a map (``last_touch``)."""
    if _is_seconds(value):
        return iso(value)
    if isinstance(value, Mapping):
        return {k: when(v) for k, v in value.items()}
    return value


def with_iso(data: Any) -> Any:
    """``data`` with ``KEY_iso`` beside every time ``KEY`` (of :data:`TIME_KEYS`), at any depth."""
    if isinstance(data, list | tuple):
        return [with_iso(item) for item in data]
    if not isinstance(data, Mapping):
        return data
    out: dict[str, Any] = {}
    for key, value in data.items():
        out[key] = with_iso(value)
        if key in TIME_KEYS and _holds_times(value):
            out[f"{key}_iso"] = when(value)
    return out


def _is_seconds(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _holds_times(value: Any) -> bool:
    """A number of seconds, or a non-empty map whose values all are."""
    if isinstance(value, Mapping):
        return bool(value) and all(_is_seconds(v) for v in value.values())
    return _is_seconds(value)
