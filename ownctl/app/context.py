"""What every use case receives: which store, what time it is, and who is speaking from where.

:class:`AppContext` opens the store lazily (so commands that fail before touching it cost nothing)
and hands out transactions. A *write* transaction appends the instruction to the event log first,
inside the same transaction, so a failing command leaves neither its changes nor its log line.
Transactions are re-entrant: while a write transaction is open on a context, ``write`` and ``read``
yield that same transaction (a nested ``write`` logs its sub-instruction into it), so a use case
made of others (``say``: a claim, a permission and a norm) commits or rolls back as one.
The CLI builds one context per process (``batch`` reuses it line after line) and passes ``now``
explicitly: nothing here reads the environment or the clock.

A context made with ``cache`` (the Python API's) keeps the whole loaded Mind between instructions
(:meth:`AppContext.kept`, :meth:`AppContext.remember`), so an instruction in a long-running
process does not read every object again. The kept Mind is used only while the store generation
(which every write transaction advances) is the one it was kept at: after another writer's
transaction it is dropped and loaded afresh. This context's own instructions bring it up to date
in place; its other writes (a setting, a world, a task run) drop it.
"""

from __future__ import annotations

import functools
import random
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Concatenate, Generic, ParamSpec, TypeVar

from ownctl.errors import StoreBusy
from ownctl.logic.names import check_name

if TYPE_CHECKING:
    from ownctl.app.mindstore import Stored
    from ownctl.store.engine import Store
    from ownctl.store.repo import Tx

T = TypeVar("T")
P = ParamSpec("P")
S = TypeVar("S")

#: A use case that failed because another writer held the store is tried again this many times,
#: waiting about 0.05 s, 0.1 s, 0.2 s, ... (with jitter, at most MAX_WAIT each) before giving up.
ATTEMPTS = 8
FIRST_WAIT = 0.05
MAX_WAIT = 2.0


@dataclass(frozen=True)
class Done:
    """The outcome of a mutating use case: ``message`` for people, ``data`` for --json."""

    message: str
    data: dict[str, Any] = field(default_factory=dict)


@dataclass
class Kept(Generic[S]):
    """State kept between instructions, valid while the store is at ``generation``."""

    generation: int
    state: S


@dataclass
class AppContext:
    """A store reference plus the instruction's circumstances.

    ``db``: ``--db`` as given (None = the default store); ``now``: store time in seconds;
    ``interface``: "cli", "batch", "say", "run", ...; ``command``: the instruction as typed, for the
    log; ``actor``: who gave it, if known; ``cache``: keep the loaded Mind between instructions
    (see the module docstring).
    """

    db: str | None
    now: float
    interface: str = "cli"
    command: str = ""
    actor: str | None = None
    cache: bool = False
    _store: Store | None = field(default=None, repr=False)
    _open: Tx | None = field(default=None, repr=False)  # the write transaction in progress, if any
    _kept: Kept[Stored] | None = field(default=None, repr=False)
    _live: bool = field(default=False, repr=False)  # the kept Mind includes the open transaction's writes

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
    def write(self, payload: dict[str, Any] | None, actor: str | None = None,
              through_mind: bool = False) -> Iterator[Tx]:
        """A write transaction whose first act is logging this instruction with ``payload``.

        ``payload`` None writes without logging (conversation state, which is not an instruction,
        nor part of the Mind). Inside an open write transaction this yields the same one, after
        logging into it. A speaker (``actor``) obeys the naming rule of agents, whatever the command
        and the backend. ``through_mind``: the instruction changes the store only by saving a Mind
        (:func:`ownctl.app.mindstore.changing`); any other instruction drops the kept Mind.
        """
        if actor is not None:
            check_name("speaker", actor)
        if self._open is not None:
            if payload is not None:
                self._open.meta.log(self.now, actor or self.actor, self.interface, self.command, payload)
                self._live = self._live and through_mind
            yield self._open
            return
        try:
            with self.store().transaction(write=True) as tx:
                # the kept Mind is the store's if nobody wrote between it and this transaction
                self._live = self._kept is not None and self._kept.generation == tx.previous
                if payload is not None:
                    tx.meta.log(self.now, actor or self.actor, self.interface, self.command, payload)
                    self._live = self._live and through_mind
                self._open = tx
                try:
                    yield tx
                finally:
                    self._open = None
        except BaseException:
            self._kept, self._live = None, False  # a failed transaction may have changed it half-way
            raise
        if self._kept is not None and self._live and tx.generation is not None:
            self._kept.generation = tx.generation
        else:
            self._kept = None
        self._live = False

    def kept(self, tx: Tx) -> Stored | None:
        """The Mind kept from an earlier instruction, if it is still the store's as ``tx`` sees it
        (nobody else wrote since); None otherwise, or when this context keeps nothing."""
        if not self.cache or self._kept is None:
            return None
        if tx is self._open:
            return self._kept.state if self._live else None
        return self._kept.state if self._kept.generation == tx.meta.generation() else None

    def remember(self, tx: Tx, stored: Stored) -> None:
        """Keep ``stored`` (a whole Mind, loaded or just saved in ``tx``) for the next instructions."""
        if not self.cache or stored.writable is not None or not stored.mind.complete:
            return
        if tx is self._open:
            self._kept, self._live = Kept(tx.generation or 0, stored), True
        else:
            self._kept = Kept(tx.meta.generation(), stored)

    def forget(self) -> None:
        """Drop the kept Mind (the next instruction loads afresh)."""
        self._kept, self._live = None, False

    def retrying(self, use_case: Callable[[], T], attempts: int = ATTEMPTS,
                 sleep: Callable[[float], None] = time.sleep) -> T:
        """Run ``use_case`` (a whole instruction: each try is its own transaction, and a failed try
        wrote nothing); when another writer made it fail (:class:`StoreBusy`), wait with jittered
        exponential backoff and try again, at most ``attempts`` times, then give up with one line.

        Inside an open transaction the caller's outermost instruction retries, not this one.
        """
        if self._open is not None:
            return use_case()
        wait = FIRST_WAIT
        for attempt in range(1, attempts + 1):
            try:
                return use_case()
            except StoreBusy as exc:
                if attempt == attempts:
                    raise StoreBusy(f"{exc} (gave up after {attempts} tries; nothing was written)") from None
            sleep(wait * (0.5 + random.random()))
            wait = min(MAX_WAIT, wait * 2)
        raise AssertionError("unreachable")

    def close(self) -> None:
        """Close the store if it was opened."""
        self.forget()
        if self._store is not None:
            self._store.close()
            self._store = None


def use_case(fn: Callable[Concatenate[AppContext, P], T]) -> Callable[Concatenate[AppContext, P], T]:
    """Mark a use case: called outside any transaction, it is tried again while another writer holds
    the store (:meth:`AppContext.retrying`); inside one (a use case made of others), it runs once."""

    @functools.wraps(fn)
    def wrapper(ctx: AppContext, /, *args: P.args, **kwargs: P.kwargs) -> T:
        return ctx.retrying(lambda: fn(ctx, *args, **kwargs))

    return wrapper
