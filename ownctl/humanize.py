"""Numbers and times as people read them: counted nouns, and store times in ISO 8601 local time.

The one place ownctl turns these into words, for the app's messages and the CLI's tables alike.
Pure: no I/O beyond the process's time zone.
"""

from __future__ import annotations

import math
from datetime import datetime


def plural(count: int, noun: str, many: str | None = None) -> str:
    """``1 instruction``, ``2 instructions``, ``0 instructions`` (``many``: an irregular plural)."""
    return f"{count} {noun if count == 1 else (many or noun + 's')}"


def iso(seconds: float) -> str:
    """``seconds`` since the epoch as local ISO 8601 with its UTC offset, to the second
    (``2026-12-01T14:21:40+01:00``).

    A time outside the calendar (not finite, or too far from now for the platform) is printed as the
    number it is, so a human view never fails on a stored value.
    """
    if not math.isfinite(seconds):
        return repr(float(seconds))
    try:
        return datetime.fromtimestamp(seconds).astimezone().isoformat(timespec="seconds")
    except (OverflowError, OSError, ValueError):
        return f"{seconds:.10g}"
