"""Results kept by key: the last few results of a pure function, least recently used dropped first.

The learner's re-induction traces, the posteriors over rule sets, the claim calibrations' objectives
and the steps' marginals are each kept this way: valuing a question asks for the same results of
many what-if Minds (docs/asking.md, section 6). A kept result is what computing it again gives, so
keeping changes no result, only the time.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Generic, TypeVar

V = TypeVar("V")


class Kept(Generic[V]):
    """At most ``size`` results by key, least recently used dropped first; with ``weigh`` (a
    result's size in bytes), also at most ``budget`` bytes of them, so that results that grow with
    the store (a marginal per object) cannot fill the memory of a large one."""

    def __init__(self, size: int, budget: int | None = None, weigh: Callable[[V], int] | None = None) -> None:
        self.size, self.budget, self.weigh = size, budget, weigh
        self.bytes = 0
        self._items: OrderedDict[Hashable, V] = OrderedDict()

    def get(self, key: Hashable) -> V | None:
        """The result kept for ``key`` (now the most recently used), or None."""
        value = self._items.get(key)
        if value is not None:
            self._items.move_to_end(key)
        return value

    def peek(self, key: Hashable) -> V | None:
        """The result kept for ``key``, or None, leaving the order of use as it is."""
        return self._items.get(key)

    def put(self, key: Hashable, value: V) -> V:
        """Keep ``value`` for ``key`` as the most recently used, dropping the least recently used
        beyond ``size``; returns ``value``."""
        old = self._items.get(key)
        if old is not None:
            self.bytes -= self._weight(old)
        self._items[key] = value
        self._items.move_to_end(key)
        self.bytes += self._weight(value)
        while len(self._items) > self.size or (self.budget is not None and self.bytes > self.budget
                                                and len(self._items) > 1):
            self.bytes -= self._weight(self._items.popitem(last=False)[1])
        return value

    def _weight(self, value: V) -> int:
        return self.weigh(value) if self.weigh is not None else 0

    def clear(self) -> None:
        """Forget every kept result."""
        self._items.clear()
        self.bytes = 0

    def __len__(self) -> int:
        return len(self._items)
