"""The store's tables as SQLAlchemy 2 typed ORM models (docs/architecture.md, section 6).

The schema is created and changed only by the Alembic revisions in ``migrations/versions/``; these
models describe the head revision (a test compares them). Times are absolute seconds on the store's
clock. Ground truth (``truth_owners``, ``truth_norms``) is kept in its own tables, read only by the
simulated instructor and by metrics, never by belief code.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import (
    JSON,
    BigInteger,
    Float,
    ForeignKey,
    Index,
    Integer,
    LargeBinary,
    MetaData,
    PrimaryKeyConstraint,
    String,
    Text,
    UniqueConstraint,
)
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column

#: Every constraint gets a predictable name, so batch-mode migrations can drop and alter them.
NAMING_CONVENTION = {
    "ix": "ix_%(column_0_label)s",
    "uq": "uq_%(table_name)s_%(column_0_name)s",
    "ck": "ck_%(table_name)s_%(constraint_name)s",
    "fk": "fk_%(table_name)s_%(column_0_name)s_%(referred_table_name)s",
    "pk": "pk_%(table_name)s",
}

#: The marker row that identifies an ownctl store (table ``ownctl_store``).
APPLICATION = "ownctl"

NAME = 64  # length of a name column (the naming rule allows 64 characters)


class Base(DeclarativeBase):
    """Declarative base with the naming convention."""

    metadata = MetaData(naming_convention=NAMING_CONVENTION)
    type_annotation_map = {dict[str, Any]: JSON, list[Any]: JSON}


class StoreMarker(Base):
    """One row saying "this database is an ownctl store"; a database without it is refused."""

    __tablename__ = "ownctl_store"
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    application: Mapped[str] = mapped_column(String(32))
    created: Mapped[float] = mapped_column(Float)


class Agent(Base):
    """A possible owner, addressed by a unique name."""

    __tablename__ = "agents"
    id: Mapped[int] = mapped_column(primary_key=True)
    name: Mapped[str] = mapped_column(String(NAME), unique=True)
    created: Mapped[float] = mapped_column(Float)


class Object(Base):
    """An object and its crisp percepts; ``extra`` holds free-form percepts for later features."""

    __tablename__ = "objects"
    id: Mapped[int] = mapped_column(primary_key=True)
    name: Mapped[str] = mapped_column(String(NAME), unique=True)
    color: Mapped[str | None] = mapped_column(String(NAME))
    x: Mapped[float | None] = mapped_column(Float)
    y: Mapped[float | None] = mapped_column(Float)
    z: Mapped[float | None] = mapped_column(Float)
    extra: Mapped[dict[str, Any]] = mapped_column(JSON, default=dict)
    created: Mapped[float] = mapped_column(Float)


class Category(Base):
    """``inCategory(object, category)`` facts."""

    __tablename__ = "object_categories"
    object_id: Mapped[int] = mapped_column(ForeignKey("objects.id", ondelete="CASCADE"), primary_key=True)
    category: Mapped[str] = mapped_column(String(NAME), primary_key=True)


class Touch(Base):
    """The last times (absolute, store clock) one agent interacted with a chunk of object ids, packed
    (``ownctl/store/packed.py``: float64, NaN where it never did)."""

    __tablename__ = "touches"
    __table_args__ = ({"sqlite_with_rowid": False},)
    agent_id: Mapped[int] = mapped_column(ForeignKey("agents.id", ondelete="CASCADE"), primary_key=True)
    chunk: Mapped[int] = mapped_column(Integer, primary_key=True)
    times: Mapped[bytes] = mapped_column(LargeBinary)


class Area(Base):
    """A named axis-aligned box ``(x0, y0, x1, y1)`` on the table plane."""

    __tablename__ = "areas"
    id: Mapped[int] = mapped_column(primary_key=True)
    name: Mapped[str] = mapped_column(String(NAME), unique=True)
    x0: Mapped[float] = mapped_column(Float)
    y0: Mapped[float] = mapped_column(Float)
    x1: Mapped[float] = mapped_column(Float)
    y1: Mapped[float] = mapped_column(Float)


class Ownership(Base):
    """Claims and posteriors about ``ownedBy(object, agent)``, each nullable.

    Rows exist only for the pairs that hold a claim or a posterior (written with one bulk upsert per
    set of columns); a pair without a row holds neither. Priors, held for every pair, are packed per
    agent in :class:`Prior`. The key is (agent, object), so an agent's rows lie together (on SQLite
    the table is stored by its key); lookups by object use the object_id index.
    """

    __tablename__ = "ownership"
    __table_args__ = (
        PrimaryKeyConstraint("agent_id", "object_id"),
        Index("ix_ownership_object_id", "object_id"),
        {"sqlite_with_rowid": False},
    )
    object_id: Mapped[int] = mapped_column(ForeignKey("objects.id", ondelete="CASCADE"))
    agent_id: Mapped[int] = mapped_column(ForeignKey("agents.id", ondelete="CASCADE"))
    claim_p: Mapped[float | None] = mapped_column(Float)
    claim_speaker: Mapped[str | None] = mapped_column(String(NAME))
    claim_trust: Mapped[float | None] = mapped_column(Float)
    claim_time: Mapped[float | None] = mapped_column(Float)
    posterior_p: Mapped[float | None] = mapped_column(Float)
    posterior_source: Mapped[str | None] = mapped_column(String(32))
    posterior_time: Mapped[float | None] = mapped_column(Float)


class Prior(Base):
    """The predicted priors of one agent about a chunk of object ids (``ownctl/store/packed.py``):
    probabilities (float64, NaN where none is held) and source codes, packed, and the chunk's last
    write time."""

    __tablename__ = "priors"
    __table_args__ = ({"sqlite_with_rowid": False},)
    agent_id: Mapped[int] = mapped_column(ForeignKey("agents.id", ondelete="CASCADE"), primary_key=True)
    chunk: Mapped[int] = mapped_column(Integer, primary_key=True)
    p: Mapped[bytes] = mapped_column(LargeBinary)
    source: Mapped[bytes] = mapped_column(LargeBinary)
    time: Mapped[float] = mapped_column(Float)


class Generation(Base):
    """The store generation: one row (id 1) whose ``value`` every write transaction advances."""

    __tablename__ = "generation"
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    value: Mapped[int] = mapped_column(BigInteger)


class Permission(Base):
    """``forbid|allow ACTION on OBJECT``: value 1.0 forbids, 0.0 allows (values between are soft)."""

    __tablename__ = "permissions"
    __table_args__ = (UniqueConstraint("action", "object_id"),)
    id: Mapped[int] = mapped_column(primary_key=True)
    action: Mapped[str] = mapped_column(String(32))
    object_id: Mapped[int] = mapped_column(ForeignKey("objects.id", ondelete="CASCADE"))
    value: Mapped[float] = mapped_column(Float)
    speaker: Mapped[str | None] = mapped_column(String(NAME))
    time: Mapped[float] = mapped_column(Float)
    seq: Mapped[int | None] = mapped_column(Integer)  # arrival rank (given again: moves to the end)
    seen: Mapped[dict[str, Any] | None] = mapped_column(JSON)  # the object's percepts when given


class RuleRow(Base):
    """A rule in canonical text: a forbid rule of origin "given" or "learned", or an allow norm
    (origin "allow", text ``allow ACTION if ...``) that the learner subtracts; ``rank`` orders an
    action's rules as the learner left them."""

    __tablename__ = "rules"
    __table_args__ = (UniqueConstraint("action", "text"),)
    id: Mapped[int] = mapped_column(primary_key=True)
    action: Mapped[str] = mapped_column(String(32))
    text: Mapped[str] = mapped_column(Text)
    origin: Mapped[str] = mapped_column(String(16))
    provenance: Mapped[dict[str, Any]] = mapped_column(JSON, default=dict)
    created: Mapped[float] = mapped_column(Float)
    rank: Mapped[int | None] = mapped_column(Integer)


class Setting(Base):
    """One setting: ``key`` -> JSON value (thresholds, trust, frozen and disabled flags)."""

    __tablename__ = "settings"
    key: Mapped[str] = mapped_column(String(64), primary_key=True)
    value: Mapped[Any] = mapped_column(JSON)


class TruthOwner(Base):
    """Ground truth of a simulated world: the true P(ownedBy(object, agent))."""

    __tablename__ = "truth_owners"
    object_id: Mapped[int] = mapped_column(ForeignKey("objects.id", ondelete="CASCADE"), primary_key=True)
    agent_id: Mapped[int] = mapped_column(ForeignKey("agents.id", ondelete="CASCADE"), primary_key=True)
    p: Mapped[float] = mapped_column(Float)


class TruthNorm(Base):
    """Ground truth of a simulated world: a true norm, as text."""

    __tablename__ = "truth_norms"
    id: Mapped[int] = mapped_column(primary_key=True)
    text: Mapped[str] = mapped_column(Text, unique=True)


class Conversation(Base):
    """The conversation context (one row, id 1): speaker, current target and action, last refusal."""

    __tablename__ = "context"
    id: Mapped[int] = mapped_column(primary_key=True)
    speaker: Mapped[str | None] = mapped_column(String(NAME))
    target_id: Mapped[int | None] = mapped_column(ForeignKey("objects.id", ondelete="SET NULL"))
    action: Mapped[str | None] = mapped_column(String(32))
    last_refusal: Mapped[dict[str, Any] | None] = mapped_column(JSON)


class Event(Base):
    """Append-only log of every instruction: who, when, from which interface, what."""

    __tablename__ = "events"
    id: Mapped[int] = mapped_column(primary_key=True)
    time: Mapped[float] = mapped_column(Float)
    actor: Mapped[str | None] = mapped_column(String(NAME))
    interface: Mapped[str] = mapped_column(String(16))
    command: Mapped[str] = mapped_column(Text)
    payload: Mapped[dict[str, Any]] = mapped_column(JSON, default=dict)
