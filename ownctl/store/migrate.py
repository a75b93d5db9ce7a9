"""Alembic plumbing: where the migrations are, which revision a database is at, upgrading it.

The migrations ship inside the wheel at ``ownctl/_migrations`` (see setup.py); in a development
checkout they are the repository's top-level ``migrations/`` folder.

Opening a store at the head revision must not pay for importing Alembic, so the known revisions
are read from the version files' ``revision`` / ``down_revision`` lines and the database's revision
with one SELECT; Alembic itself is imported only to upgrade or downgrade (a test checks that this
reading agrees with Alembic's).
"""

from __future__ import annotations

import re
from collections.abc import Collection
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING

from sqlalchemy import inspect, text
from sqlalchemy.engine import Connection

from ownctl.errors import StoreError

if TYPE_CHECKING:
    from alembic.config import Config

_ASSIGN = r"^{name}\s*(?::[^=]+)?=\s*(?:[\"']([0-9A-Za-z_]+)[\"']|None)"
_REVISION = re.compile(_ASSIGN.format(name="revision"), re.MULTILINE)
_DOWN = re.compile(_ASSIGN.format(name="down_revision"), re.MULTILINE)


def migrations_dir() -> Path:
    """The Alembic script folder: packaged copy first, then the repository's ``migrations/``."""
    package = Path(__file__).resolve().parents[1]
    for candidate in (package / "_migrations", package.parent / "migrations"):
        if (candidate / "env.py").is_file():
            return candidate
    raise StoreError(
        f"the ownctl migrations are missing (looked in {package / '_migrations'}); reinstall ownctl"
    )


def alembic_config(connection: Connection | None = None, url: str | None = None) -> Config:
    """An Alembic config on our script folder; ``connection`` makes migrations use that connection."""
    from alembic.config import Config

    cfg = Config()
    cfg.set_main_option("script_location", str(migrations_dir()))
    if url is not None:
        cfg.set_main_option("sqlalchemy.url", url.replace("%", "%%"))
    if connection is not None:
        cfg.attributes["connection"] = connection
    return cfg


@lru_cache(maxsize=1)
def _graph() -> dict[str, str | None]:
    """revision -> down_revision, read from the version files."""
    graph: dict[str, str | None] = {}
    for path in sorted((migrations_dir() / "versions").glob("*.py")):
        source = path.read_text(encoding="utf-8")
        rev, down = _REVISION.search(source), _DOWN.search(source)
        if rev is None or down is None:
            raise StoreError(f"migration {path.name} has no revision/down_revision line")
        graph[rev.group(1)] = down.group(1)
    return graph


def known_revisions() -> list[str]:
    """Every revision this ownctl knows, oldest first (one linear history)."""
    graph = _graph()
    children = {down: rev for rev, down in graph.items()}
    out, current = [], children.get(None)
    while current is not None:
        out.append(current)
        current = children.get(current)
    if len(out) != len(graph):
        raise StoreError(f"the migrations do not form one linear history: {sorted(graph)}")
    return out


def head_revision() -> str:
    """The newest revision this ownctl knows."""
    return known_revisions()[-1]


def current_revision(connection: Connection, tables: Collection[str] | None = None) -> str | None:
    """The revision recorded in the database (None when it has no alembic_version table);
    ``tables``: the database's table names, when the caller has read them already."""
    if "alembic_version" not in (inspect(connection).get_table_names() if tables is None else tables):
        return None
    rows = connection.execute(text("SELECT version_num FROM alembic_version")).scalars().all()
    if len(rows) > 1:
        raise StoreError(f"the store has several schema heads {rows}; it was not made by ownctl")
    return rows[0] if rows else None


def upgrade(connection: Connection, target: str = "head") -> None:
    """Run the migrations up to ``target`` inside the caller's transaction on ``connection``."""
    from alembic import command

    command.upgrade(alembic_config(connection), target)


def downgrade(connection: Connection, target: str) -> None:
    """Run the downgrades down to ``target`` (``base`` drops everything)."""
    from alembic import command

    command.downgrade(alembic_config(connection), target)
