"""What every use case receives: which store, what time it is, and who is speaking from where.

:class:`AppContext` opens the store lazily (so commands that fail before touching it cost nothing)
and hands out transactions. A *write* transaction appends the instruction to the event log first,
inside the same transaction, so a failing command leaves neither its changes nor its log line.
Transactions are re-entrant: while a write transaction is open on a context, ``write`` and ``read``
yield that same transaction (a nested ``write`` logs its sub-instruction into it), so a use case
made of others (``say``: a claim, a permission and a norm) commits or rolls back as one.
The CLI builds one context per process (``batch`` reuses it line after line) and passes ``now``
explicitly: nothing here reads the environment or the clock.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ownctl.logic.names import check_name

if TYPE_CHECKING:
    from ownctl.store.engine import Store
    from ownctl.store.repo import Tx


@dataclass(frozen=True)
class Done:
    """The outcome of a mutating use case: ``message`` for people, ``data`` for --json."""

    message: str
    data: dict[str, Any] = field(default_factory=dict)


@dataclass
class AppContext:
    """A store reference plus the instruction's circumstances.

    ``db``: ``--db`` as given (None = the default store); ``now``: store time in seconds;
    ``interface``: "cli", "batch", "say", "run", ...; ``command``: the instruction as typed, for the
    log; ``actor``: who gave it, if known.
    """

    db: str | None
    now: float
    interface: str = "cli"
    command: str = ""
    actor: str | None = None
    _store: Store | None = field(default=None, repr=False)
    _open: Tx | None = field(default=None, repr=False)  # the write transaction in progress, if any

    def store(self, create: bool = False) -> Store:
        """The open store (opened on first call; ``create`` allows creating an explicit store)."""
        if self._store is None:
            from ownctl.store.engine import locate, open_store

            self._store = open_store(locate(self.db), create=create)
        return self._store

    @contextmanager
    def read(self) -> Iterator[Tx]:
        """A read-only transaction (inside an open write transaction: that one, to see its changes)."""
        if self._open is not None:
            yield self._open
            return
        with self.store().transaction(write=False) as tx:
            yield tx

    @contextmanager
    def write(self, payload: dict[str, Any] | None, actor: str | None = None) -> Iterator[Tx]:
        """A write transaction whose first act is logging this instruction with ``payload``.

        ``payload`` None writes without logging (conversation state, which is not an instruction).
        Inside an open write transaction this yields the same one, after logging into it. A speaker
        (``actor``) obeys the naming rule of agents, whatever the command and the backend.
        """
        if actor is not None:
            check_name("speaker", actor)
        if self._open is not None:
            if payload is not None:
                self._open.log(self.now, actor or self.actor, self.interface, self.command, payload)
            yield self._open
            return
        with self.store().transaction(write=True) as tx:
            if payload is not None:
                tx.log(self.now, actor or self.actor, self.interface, self.command, payload)
            self._open = tx
            try:
                yield tx
            finally:
                self._open = None

    def close(self) -> None:
        """Close the store if it was opened."""
        if self._store is not None:
            self._store.close()
            self._store = None
