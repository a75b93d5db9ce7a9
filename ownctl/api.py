"""ownctl as a Python library: a robot's control loop asks and teaches without a process per decision.

Open a store by URL (or SQLite path) and call the same instructions and queries the command line
offers; each call is one transaction and returns the report the command would print with
``--json``::

    from ownctl.api import Ownctl

    with Ownctl.open("robot.db", create=True) as db:
        db.claim("mug", "xuan")
        db.forbid("trash", "if ownedBy any")
        if db.check("trash", "mug").forbidden:
            print(db.explain("trash", "mug").text)

The methods are thin: each builds the use case's context (this store, the clock, who speaks) and
calls the function of :mod:`ownctl.app` that the matching command calls, so a program and the
command line always agree. Errors are :class:`ownctl.errors.OwnctlError` with the same one-line
messages.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from types import TracebackType
from typing import Any, TypeVar

from ownctl.app import admin, decide, explain, instruct, query, things
from ownctl.app.context import AppContext, Done
from ownctl.app.decide import CheckReport
from ownctl.app.explain import Explanation
from ownctl.app.run import RunReport

__all__ = ["CheckReport", "Done", "Explanation", "Ownctl", "RunReport"]

T = TypeVar("T")


@dataclass
class Ownctl:
    """One open store; ``clock`` gives the store time of each call (default: wall-clock seconds),
    ``speaker`` who gives the instructions (None: unknown)."""

    db: str | None = None
    clock: Callable[[], float] = time.time
    speaker: str | None = None
    cache: bool = True
    _ctx: AppContext | None = field(default=None, repr=False)

    @classmethod
    def open(
        cls,
        db: str | None = None,
        *,
        create: bool = False,
        clock: Callable[[], float] = time.time,
        speaker: str | None = None,
        cache: bool = True,
    ) -> Ownctl:
        """Open the store ``db`` (a SQLAlchemy URL or SQLite path; None: the default store).

        A named store that does not exist is an error unless ``create``; the default store is
        created on first use, as on the command line. ``cache`` keeps the loaded state between calls
        while no other process writes (``docs/architecture.md``, section 6); False reads the store
        afresh on every call.
        """
        out = cls(db, clock, speaker, cache)
        out._context().store(create=create)
        return out

    def _context(self) -> AppContext:
        if self._ctx is None:
            self._ctx = AppContext(self.db, now=self.clock(), interface="api", cache=self.cache)
        self._ctx.now = self.clock()
        return self._ctx

    def _do(self, command: str, use_case: Callable[[AppContext], T]) -> T:
        """Run one use case as ``command`` (one transaction; tried again while another writer holds
        the store, as the command line does)."""
        ctx = self._context()
        ctx.command = command
        return use_case(ctx)  # app use cases retry by themselves while another writer holds the store

    def close(self) -> None:
        """Close the store."""
        if self._ctx is not None:
            self._ctx.close()
            self._ctx = None

    def __enter__(self) -> Ownctl:
        return self

    def __exit__(
        self, kind: type[BaseException] | None, error: BaseException | None, tb: TracebackType | None
    ) -> None:
        self.close()

    # -- instructions ------------------------------------------------------------------------------
    def claim(
        self, obj: str, agent: str, p: float = 1.0, *, negated: bool = False, exclusive: bool = False
    ) -> Done:
        """``claim OBJ AGENT``: a claim that ``agent`` owns (or with ``negated``: does not own) ``obj``."""
        return self._do(
            f"claim {obj} {agent}",
            lambda ctx: instruct.add_claim(ctx, obj, agent, p, negated, exclusive, self.speaker),
        )

    def permit(self, action: str, obj: str, *, forbid: bool) -> Done:
        """``forbid|allow ACTION on OBJ``: an object-specific permission."""
        sign = "forbid" if forbid else "allow"
        return self._do(
            f"{sign} {action} on {obj}",
            lambda ctx: instruct.add_permission(ctx, action, obj, 1.0 if forbid else 0.0, self.speaker),
        )

    def forbid(self, action: str, condition: str = "") -> Done:
        """``forbid ACTION if ...``: a given norm (``condition`` such as ``"if ownedBy any"``)."""
        text = f"forbid {action} {condition}".strip()
        return self._do(text, lambda ctx: instruct.add_norm(ctx, text, self.speaker))

    def allow(self, action: str, condition: str) -> Done:
        """``allow ACTION if ...``: an allow norm, subtracted from the forbid rules."""
        text = f"allow {action} {condition}".strip()
        return self._do(text, lambda ctx: instruct.add_norm(ctx, text, self.speaker))

    def touch(self, obj: str, agent: str, at: float | None = None) -> Done:
        """``object touch OBJ --by AGENT``: an interaction (a percept of prediction)."""
        return self._do(f"object touch {obj} --by {agent}", lambda ctx: things.touch(ctx, obj, agent, at))

    def move(self, obj: str, position: Sequence[float]) -> Done:
        """``object set OBJ --pos X,Y,Z``: the object is somewhere else now."""
        pos = ",".join(repr(float(v)) for v in position)
        return self._do(f"object set {obj} --pos {pos}", lambda ctx: things.set_object(ctx, obj, pos=pos))

    def add_agent(self, name: str) -> Done:
        """``agent add NAME``."""
        return self._do(f"agent add {name}", lambda ctx: things.add_agent(ctx, name))

    def add_object(
        self,
        name: str,
        color: str | None = None,
        position: Sequence[float] | None = None,
        categories: Sequence[str] = (),
    ) -> Done:
        """``object add NAME [--color C] [--pos X,Y,Z] [--category K]``."""
        pos = None if position is None else ",".join(repr(float(v)) for v in position)
        return self._do(
            f"object add {name}", lambda ctx: things.add_object(ctx, name, color, pos, categories)
        )

    def add_area(self, name: str, box: Sequence[float]) -> Done:
        """``area add NAME --box X0,Y0,X1,Y1``."""
        return self._do(
            f"area add {name}", lambda ctx: things.add_area(ctx, name, ",".join(repr(float(v)) for v in box))
        )

    def load_world(self, path: str, seed: int = 0) -> Done:
        """``world load FILE [--seed N]``: add a world file's agents, areas, objects and ground truth."""
        from ownctl.app import worldfile

        return self._do(f"world load {path}", lambda ctx: worldfile.load(ctx, path, seed))

    def reset(self, what: str) -> Done:
        """``reset perms|rules|claims|all --yes``."""
        return self._do(f"reset {what} --yes", lambda ctx: admin.reset(ctx, what, yes=True))

    # -- queries ---------------------------------------------------------------------------------
    def check(self, action: str, obj: str, *, record: bool = True) -> CheckReport:
        """``check ACTION OBJ``: the decision, with what decided it (``.forbidden``, ``.data``);
        ``record`` makes it a turn of the conversation, as the command does ("why not?")."""
        return self._do(f"check {action} {obj}", lambda ctx: decide.check(ctx, action, obj, record=record))

    def explain(self, action: str | None = None, obj: str | None = None) -> Explanation:
        """``explain [ACTION OBJ]``: why, in words (``.text``) and data."""
        return self._do("explain", lambda ctx: explain.explain(ctx, action, obj))

    def owners(self, obj: str) -> dict[str, Any]:
        """``owners OBJ``: every agent's beliefs about the object, likeliest first."""
        return self._do(f"owners {obj}", lambda ctx: query.owners(ctx, obj))

    def rules(self) -> list[dict[str, Any]]:
        """``rules list``: every rule with its origin and accuracy."""
        return self._do("rules list", lambda ctx: query.list_rules(ctx))

    def run(
        self, task: str, *, physics: bool = False, instructor: str = "oracle", seed: int = 0
    ) -> RunReport:
        """``run TASK``: play a task on the store's world (kinematically unless ``physics``)."""
        from ownctl.app.run import run

        return self._do(
            f"run {task}", lambda ctx: run(ctx, task, instructor=instructor, physics=physics, seed=seed)
        )
