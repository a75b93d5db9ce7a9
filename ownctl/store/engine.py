"""Opening a store: where it is, whether it is ours, its schema revision, and transactions.

Rules (docs/architecture.md, section 6):

- the default store (``user_data_dir("ownctl")/ownctl.db``) is created on first use; a store named
  explicitly that does not exist is created only when ``create`` is true (``ownctl init``);
- a file that is not an ownctl store (junk bytes, another SQLite database) is refused untouched;
- a store at an unknown (newer) revision is refused; an older one is upgraded on open;
- SQLite connections get ``foreign_keys=ON`` and a busy timeout; the file is put in WAL mode;
- one :meth:`Store.transaction` is one SQL transaction: an exception inside writes nothing;
- every write transaction advances the store generation (``generation.value``) first, in the same
  transaction, so a reader sees a consistent pair of data and generation.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from sqlalchemy import Engine, create_engine, event, inspect, text
from sqlalchemy.engine import Connection, make_url
from sqlalchemy.exc import ArgumentError, DBAPIError, NoSuchModuleError
from sqlalchemy.pool import StaticPool

from ownctl.errors import BadValue, OwnctlError, StoreBusy, StoreError
from ownctl.store import migrate
from ownctl.store.models import APPLICATION
from ownctl.store.repo import Tx

SQLITE_MAGIC = b"SQLite format 3\x00"
BUSY_TIMEOUT_MS = 30_000  # as long as PostgreSQL's lock wait: a fleet of writers queues for seconds
#: PostgreSQL: writers take this transaction-scoped advisory lock first, so that writes are
#: serialised in one order (no deadlock, no lost update) as SQLite's BEGIN IMMEDIATE does.
WRITE_LOCK_KEY = 0x6F776E63  # "ownc"
#: PostgreSQL serves the writers waiting for the lock in the order they came, so a writer waits its
#: turn for up to this long (a fleet of 32 robots queues for seconds); giving up sooner would only
#: send it to the back of the queue when it tries again.
LOCK_TIMEOUT_MS = 30_000
#: SQLSTATEs of failures that another writer caused: deadlock, serialisation, lock wait timeout.
TRANSIENT_SQLSTATES = ("40P01", "40001", "55P03")


@dataclass(frozen=True)
class Location:
    """Where a store lives: a SQLAlchemy URL, its SQLite file (if any), and how it was named."""

    url: str
    path: Path | None
    explicit: bool

    @property
    def display(self) -> str:
        """The file path for SQLite files, else the URL without its password."""
        if self.path is not None:
            return str(self.path)
        return make_url(self.url).render_as_string(hide_password=True)


def default_path() -> Path:
    """``user_data_dir("ownctl")/ownctl.db`` (honours XDG_DATA_HOME on Linux)."""
    from platformdirs import user_data_dir

    return Path(user_data_dir("ownctl")) / "ownctl.db"


def locate(db: str | None) -> Location:
    """Resolve ``--db``: None means the default store; a bare path means a SQLite file; else a URL."""
    if db is None or db == "":
        path = default_path()
        return Location(f"sqlite:///{path}", path, explicit=False)
    if "://" not in db:
        path = Path(db).expanduser().resolve()
        return Location(f"sqlite:///{path}", path, explicit=True)
    try:
        url = make_url(db)
    except (ArgumentError, ValueError):  # ValueError: a port that is not a number
        raise StoreError(
            f"invalid database URL {db!r}; use a path or a URL such as sqlite:///ownctl.db"
        ) from None
    if url.get_backend_name() == "sqlite":
        database = url.database or ""
        if database in ("", ":memory:") or database.startswith("file:"):
            return Location(db, None, explicit=True)
        return Location(db, Path(database).expanduser().resolve(), explicit=True)
    return Location(db, None, explicit=True)


def _make_engine(location: Location, foreign_keys: bool = True) -> Engine:
    """An engine whose SQLite connections have our pragmas and real (BEGIN-emitting) transactions."""
    kwargs: dict[str, Any] = {}
    url = location.url
    if location.path is not None:
        url = f"sqlite:///{location.path}"
    if url.startswith("sqlite") and location.path is None:
        kwargs["poolclass"] = StaticPool  # an in-memory database lives as long as its one connection
    try:
        engine = create_engine(url, **kwargs)
    except (ArgumentError, NoSuchModuleError, ImportError) as exc:
        raise StoreError(f"cannot use database {location.display!r}: {exc}") from None
    if engine.dialect.name == "sqlite":

        @event.listens_for(engine, "connect")
        def _on_connect(dbapi_conn: Any, _record: Any) -> None:
            dbapi_conn.isolation_level = None  # we emit BEGIN ourselves, so DDL is transactional too
            cur = dbapi_conn.cursor()
            cur.execute(f"PRAGMA foreign_keys={'ON' if foreign_keys else 'OFF'}")
            cur.execute(f"PRAGMA busy_timeout={BUSY_TIMEOUT_MS}")
            cur.execute("PRAGMA synchronous=NORMAL")  # with WAL: durable at checkpoints, never corrupt
            cur.close()

        @event.listens_for(engine, "begin")
        def _on_begin(conn: Connection) -> None:
            write = conn.get_execution_options().get("ownctl_write", False)
            conn.exec_driver_sql("BEGIN IMMEDIATE" if write else "BEGIN")

    elif engine.dialect.name == "postgresql":

        @event.listens_for(engine, "begin")
        def _on_pg_begin(conn: Connection) -> None:
            if conn.get_execution_options().get("ownctl_write", False):
                conn.exec_driver_sql(f"SET LOCAL lock_timeout = {LOCK_TIMEOUT_MS}")
                conn.exec_driver_sql(f"SELECT pg_advisory_xact_lock({WRITE_LOCK_KEY})")

    return engine


def database_error(exc: DBAPIError, location: Location) -> OwnctlError:
    """The one-line user error for a database failure a user can cause; StoreBusy when trying
    again may succeed (a busy or locked store, a deadlock or serialisation victim)."""
    orig = exc.orig
    state = getattr(orig, "sqlstate", None) or getattr(getattr(orig, "diag", None), "sqlstate", None)
    message = str(orig).strip().splitlines()[0] if str(orig).strip() else type(orig).__name__
    lowered = message.lower()
    if state in TRANSIENT_SQLSTATES or "database is locked" in lowered or "database is busy" in lowered:
        return StoreBusy(f"store {location.display} is busy: another writer holds it ({message})")
    if "readonly" in lowered or "read-only" in lowered or state == "25006":
        return StoreError(f"store {location.display} is read-only: {message}")
    if state == "22001":
        return BadValue(f"a value is too long for store {location.display}: {message}")
    return StoreError(f"the database of store {location.display} refused the change: {message}")


def _probe_file(location: Location) -> str:
    """'missing' (absent or empty file) or 'sqlite'; raise StoreError for anything else."""
    path = location.path
    assert path is not None
    try:
        if not path.exists():  # a name too long for the system is an OSError here
            return "missing"
        if not path.is_file():
            raise StoreError(f"{path} is not a file; --db needs an ownctl store file or a database URL")
        with path.open("rb") as handle:
            head = handle.read(len(SQLITE_MAGIC))
    except OSError as exc:
        raise StoreError(f"cannot read store {path}: {exc.strerror or exc}") from None
    if not head:
        return "missing"
    if head != SQLITE_MAGIC:
        raise StoreError(f"{path} is not an ownctl store (not an SQLite database); refusing to touch it")
    return "sqlite"


def _check_ours(conn: Connection, location: Location, tables: set[str]) -> str:
    """The store's revision; raise StoreError if the database (whose table names are ``tables``)
    is foreign, broken or too new."""
    if "ownctl_store" not in tables:
        listing = ", ".join(sorted(tables)) or "none"
        raise StoreError(
            f"{location.display} is a database but not an ownctl store (its tables: {listing}); "
            "refusing to touch it"
        )
    marker = conn.execute(text("SELECT application FROM ownctl_store")).scalars().all()
    revision = migrate.current_revision(conn, tables)
    if marker != [APPLICATION] or revision is None:
        raise StoreError(f"{location.display} is a damaged ownctl store (no marker or no schema revision)")
    known = migrate.known_revisions()
    if revision not in known:
        raise StoreError(
            f"store {location.display} has schema revision {revision!r}, newer than this ownctl knows "
            f"(latest {migrate.head_revision()!r}); upgrade ownctl",
            known,
        )
    return revision


class Store:
    """An open ownctl store: an engine at the head schema revision."""

    def __init__(self, engine: Engine, location: Location, previous: str | None) -> None:
        self.engine = engine
        self.location = location
        self.previous = previous  # the revision found on open (None: the store was just created)

    @property
    def created(self) -> bool:
        """True if opening created the store."""
        return self.previous is None

    @contextmanager
    def transaction(self, write: bool = True) -> Iterator[Tx]:
        """One SQL transaction as a :class:`Tx`; committed on success, rolled back on any exception."""
        try:
            with self.engine.connect() as conn:
                if write:
                    conn.execution_options(ownctl_write=True)
                elif conn.dialect.name == "postgresql":  # one snapshot: the generation and the data agree
                    conn.execution_options(isolation_level="REPEATABLE READ")
                with conn.begin():
                    tx = Tx(conn)
                    if write:
                        tx.meta.advance()  # first, inside the write lock: the generation is this tx's
                    yield tx
        except DBAPIError as exc:
            raise database_error(exc, self.location) from None

    def revision(self) -> str | None:
        """The schema revision recorded in the store."""
        with self.engine.connect() as conn:
            return migrate.current_revision(conn)

    def close(self) -> None:
        """Release the connections (SQLite then checkpoints its WAL into the file)."""
        self.engine.dispose()


def _upgrade(location: Location) -> None:
    """Migrate to head in one transaction, with foreign keys off (batch table copies must not cascade)."""
    engine = _make_engine(location, foreign_keys=False)
    try:
        with engine.connect() as conn:
            conn.execution_options(ownctl_write=True)
            with conn.begin():
                migrate.upgrade(conn)
                if engine.dialect.name == "sqlite":
                    bad = conn.exec_driver_sql("PRAGMA foreign_key_check").fetchall()
                    if bad:
                        raise StoreError(
                            f"migration left dangling references in {location.display}: {bad[:3]}"
                        )
    finally:
        engine.dispose()


def _wal(engine: Engine) -> None:
    """Put a SQLite file in WAL mode (persistent; a no-op when it already is)."""
    if engine.dialect.name != "sqlite":
        return
    raw = engine.raw_connection()
    try:
        mode = raw.driver_connection.execute("PRAGMA journal_mode").fetchone()[0]  # type: ignore[union-attr]
        if str(mode).lower() not in ("wal", "memory"):
            raw.driver_connection.execute("PRAGMA journal_mode=WAL")  # type: ignore[union-attr]
    finally:
        raw.close()


def open_store(location: Location, create: bool = False) -> Store:
    """Open (and if needed upgrade) the store at ``location``; see the module docstring for the rules."""
    state = _probe_file(location) if location.path is not None else "sqlite"
    if state == "missing":
        if location.explicit and not create:
            raise StoreError(
                f"no ownctl store at {location.display}; create it with: ownctl --db {location.url} init"
            )
        try:
            location.path.parent.mkdir(parents=True, exist_ok=True)  # type: ignore[union-attr]
        except OSError as exc:
            raise StoreError(f"cannot create store {location.display}: {exc.strerror or exc}") from None
    engine = _make_engine(location)
    try:
        with engine.connect() as conn:
            tables = set(inspect(conn).get_table_names())
            if not tables:
                in_memory = location.path is None and location.url.startswith("sqlite")
                if location.explicit and not create and not in_memory:
                    raise StoreError(
                        f"no ownctl store at {location.display} (an empty database); "
                        f"create it with: ownctl --db {location.url} init"
                    )
                revision = None
            else:
                revision = _check_ours(conn, location, tables)
    except DBAPIError as exc:
        engine.dispose()
        raise StoreError(f"cannot open store {location.display}: {exc.orig}") from None
    except StoreError:
        engine.dispose()
        raise
    if revision != migrate.head_revision():
        if location.path is None and location.url.startswith("sqlite"):
            with engine.connect() as conn:  # in-memory: migrate on the one shared connection
                conn.execution_options(ownctl_write=True)
                with conn.begin():
                    migrate.upgrade(conn)
        else:
            _upgrade(location)
    _wal(engine)
    return Store(engine, location, previous=revision)
