"""``Kept``: at most ``size`` results, the least recently used dropped first; ``peek`` reads without
counting as a use."""

from __future__ import annotations

from ownctl.logic.kept import Kept


def test_the_least_recently_used_result_is_dropped_first() -> None:
    kept: Kept[str] = Kept(2)
    kept.put("a", "A")
    kept.put("b", "B")
    assert kept.get("a") == "A"  # "b" is now the least recently used
    kept.put("c", "C")
    assert len(kept) == 2
    assert kept.peek("b") is None
    assert (kept.peek("a"), kept.peek("c")) == ("A", "C")


def test_peek_does_not_count_as_a_use() -> None:
    kept: Kept[int] = Kept(2)
    kept.put("a", 1)
    kept.put("b", 2)
    assert kept.peek("a") == 1  # "a" stays the least recently used
    kept.put("c", 3)
    assert kept.get("a") is None
    assert kept.get("b") == 2


def test_put_returns_the_value_and_clear_forgets_everything() -> None:
    kept: Kept[list[int]] = Kept(4)
    value = [1]
    assert kept.put("a", value) is value
    kept.clear()
    assert len(kept) == 0 and kept.get("a") is None


def test_a_byte_budget_drops_the_least_recently_used_until_the_rest_fit() -> None:
    kept: Kept[bytes] = Kept(100, budget=10, weigh=len)
    kept.put("a", b"1234")
    kept.put("b", b"1234")
    kept.get("a")  # "b" is now the least recently used
    kept.put("c", b"123")  # 11 bytes: "b" goes
    assert kept.peek("b") is None and kept.bytes == 7
    kept.put("a", b"12345678")  # replacing a value counts only the new one: 11 bytes, "c" goes
    assert (kept.peek("a"), kept.peek("c"), kept.bytes) == (b"12345678", None, 8)
    kept.put("d", b"x" * 50)  # alone above the budget: kept, as the most recent
    assert list(kept._items) == ["d"] and kept.bytes == 50
    kept.clear()
    assert kept.bytes == 0
