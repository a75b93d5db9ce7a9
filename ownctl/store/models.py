"""The store's tables as SQLAlchemy 2 Core tables (docs/architecture.md, section 6).

The schema is created and changed only by the Alembic revisions in ``migrations/versions/``; these
tables describe the head revision (a test compares them). Times are absolute seconds on the store's
clock. Ground truth (``truth_owners``, ``truth_norms``) is kept in its own tables, read only by the
simulated instructor and by metrics, never by belief code.

Core tables, not ORM classes: the repository (``ownctl/store/repo.py``) reads plain rows and
writes with explicit statements, so opening a store and deciding one action imports no ORM (a
command-line ``check`` starts in a fraction of the time).
"""

from __future__ import annotations

from sqlalchemy import (
    JSON,
    BigInteger,
    Column,
    Float,
    ForeignKey,
    Index,
    Integer,
    LargeBinary,
    MetaData,
    PrimaryKeyConstraint,
    String,
    Table,
    Text,
    UniqueConstraint,
)

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

metadata = MetaData(naming_convention=NAMING_CONVENTION)


def _name() -> String:
    return String(NAME)


def _to(target: str, ondelete: str = "CASCADE") -> ForeignKey:
    return ForeignKey(target, ondelete=ondelete)


#: One row saying "this database is an ownctl store"; a database without it is refused.
store_marker = Table(
    "ownctl_store", metadata,
    Column("id", Integer, primary_key=True),
    Column("application", String(32), nullable=False),
    Column("created", Float, nullable=False),
)

#: A possible owner, addressed by a unique name.
agents = Table(
    "agents", metadata,
    Column("id", Integer, primary_key=True),
    Column("name", _name(), nullable=False, unique=True),
    Column("created", Float, nullable=False),
)

#: An object and its crisp percepts; ``extra`` holds free-form percepts for later features.
objects = Table(
    "objects", metadata,
    Column("id", Integer, primary_key=True),
    Column("name", _name(), nullable=False, unique=True),
    Column("color", _name()),
    Column("x", Float),
    Column("y", Float),
    Column("z", Float),
    Column("extra", JSON, nullable=False, default=dict),
    Column("created", Float, nullable=False),
)

#: ``inCategory(object, category)`` facts.
categories = Table(
    "object_categories", metadata,
    Column("object_id", Integer, _to("objects.id"), primary_key=True),
    Column("category", _name(), primary_key=True),
)

#: The last times (absolute, store clock) one agent interacted with a chunk of object ids, packed
#: (``ownctl/store/packed.py``: float64, NaN where it never did).
def _per_agent_chunks(name: str, *columns: Column[object]) -> Table:
    """A table of packed values per (agent, chunk of object ids) (``ownctl/store/packed.py``)."""
    return Table(
        name, metadata,
        Column("agent_id", Integer, _to("agents.id"), primary_key=True),
        Column("chunk", Integer, primary_key=True),
        *columns,
        sqlite_with_rowid=False,
    )


touches = _per_agent_chunks("touches", Column("times", LargeBinary, nullable=False))

#: A named axis-aligned box ``(x0, y0, x1, y1)`` on the table plane.
areas = Table(
    "areas", metadata,
    Column("id", Integer, primary_key=True),
    Column("name", _name(), nullable=False, unique=True),
    *(Column(c, Float, nullable=False) for c in ("x0", "y0", "x1", "y1")),
)

#: Claims and posteriors about ``ownedBy(object, agent)``, each nullable. Rows exist only for the
#: pairs that hold a claim or a posterior (written with one bulk upsert per set of columns); a pair
#: without a row holds neither. Priors, held for every pair, are packed per agent in ``priors``.
#: The key is (agent, object), so an agent's rows lie together (on SQLite the table is stored by its
#: key); lookups by object use the object_id index.
ownership = Table(
    "ownership", metadata,
    Column("object_id", Integer, _to("objects.id"), nullable=False),
    Column("agent_id", Integer, _to("agents.id"), nullable=False),
    Column("claim_p", Float),
    Column("claim_speaker", _name()),
    Column("claim_trust", Float),
    Column("claim_time", Float),
    Column("posterior_p", Float),
    Column("posterior_source", String(32)),
    Column("posterior_time", Float),
    PrimaryKeyConstraint("agent_id", "object_id"),
    Index("ix_ownership_object_id", "object_id"),
    sqlite_with_rowid=False,
)

#: The predicted priors of one agent about a chunk of object ids (``ownctl/store/packed.py``):
#: probabilities (float64, NaN where none is held) and source codes, packed, and the chunk's last
#: write time.
priors = _per_agent_chunks(
    "priors",
    Column("p", LargeBinary, nullable=False),
    Column("source", LargeBinary, nullable=False),
    Column("time", Float, nullable=False),
)

#: The store generation: one row (id 1) whose ``value`` every write transaction advances.
generation = Table(
    "generation", metadata,
    Column("id", Integer, primary_key=True),
    Column("value", BigInteger, nullable=False),
)

#: ``forbid|allow ACTION on OBJECT``: value 1.0 forbids, 0.0 allows (values between are soft);
#: ``seq`` is the arrival rank (given again: moves to the end), ``seen`` the object's percepts then.
permissions = Table(
    "permissions", metadata,
    Column("id", Integer, primary_key=True),
    Column("action", String(32), nullable=False),
    Column("object_id", Integer, _to("objects.id"), nullable=False),
    Column("value", Float, nullable=False),
    Column("speaker", _name()),
    Column("time", Float, nullable=False),
    Column("seq", Integer),
    Column("seen", JSON),
    UniqueConstraint("action", "object_id"),
)

#: A rule in canonical text: a forbid rule of origin "given" or "learned", or an allow norm (origin
#: "allow", text ``allow ACTION if ...``) that the learner subtracts; ``rank`` orders an action's
#: rules as the learner left them.
rules = Table(
    "rules", metadata,
    Column("id", Integer, primary_key=True),
    Column("action", String(32), nullable=False),
    Column("text", Text, nullable=False),
    Column("origin", String(16), nullable=False),
    Column("provenance", JSON, nullable=False, default=dict),
    Column("created", Float, nullable=False),
    Column("rank", Integer),
    UniqueConstraint("action", "text"),
)

#: One setting: ``key`` -> JSON value (thresholds, trust, frozen and disabled flags).
settings = Table(
    "settings", metadata,
    Column("key", String(64), primary_key=True),
    Column("value", JSON, nullable=False),
)

#: Ground truth of a simulated world: the true P(ownedBy(object, agent)).
truth_owners = Table(
    "truth_owners", metadata,
    Column("object_id", Integer, _to("objects.id"), primary_key=True),
    Column("agent_id", Integer, _to("agents.id"), primary_key=True),
    Column("p", Float, nullable=False),
)

#: Ground truth of a simulated world: a true norm, as text.
truth_norms = Table(
    "truth_norms", metadata,
    Column("id", Integer, primary_key=True),
    Column("text", Text, nullable=False, unique=True),
)

#: The conversation context (one row, id 1): speaker, current target and action, last refusal.
context = Table(
    "context", metadata,
    Column("id", Integer, primary_key=True),
    Column("speaker", _name()),
    Column("target_id", Integer, _to("objects.id", ondelete="SET NULL")),
    Column("action", String(32)),
    Column("last_refusal", JSON),
)

#: Append-only log of every instruction: who, when, from which interface, what.
events = Table(
    "events", metadata,
    Column("id", Integer, primary_key=True),
    Column("time", Float, nullable=False),
    Column("actor", _name()),
    Column("interface", String(16), nullable=False),
    Column("command", Text, nullable=False),
    Column("payload", JSON, nullable=False, default=dict),
)
