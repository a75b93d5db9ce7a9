"""Alembic plumbing: where the migrations are, which revision a database is at, upgrading it.

The migrations ship inside the wheel at ``ownctl/_migrations`` (see setup.py); in a development
checkout they are the repository's top-level ``migrations/`` folder.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from alembic import command
from alembic.config import Config
from alembic.runtime.migration import MigrationContext
from alembic.script import ScriptDirectory
from sqlalchemy.engine import Connection

from ownctl.errors import StoreError


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
    cfg = Config()
    cfg.set_main_option("script_location", str(migrations_dir()))
    if url is not None:
        cfg.set_main_option("sqlalchemy.url", url.replace("%", "%%"))
    if connection is not None:
        cfg.attributes["connection"] = connection
    return cfg


@lru_cache(maxsize=1)
def _script() -> ScriptDirectory:
    return ScriptDirectory.from_config(alembic_config())


def head_revision() -> str:
    """The newest revision this ownctl knows."""
    head = _script().get_current_head()
    assert head is not None, "no migrations"
    return head


def known_revisions() -> list[str]:
    """Every revision this ownctl knows, oldest first."""
    return [rev.revision for rev in reversed(list(_script().walk_revisions()))]


def current_revision(connection: Connection) -> str | None:
    """The revision recorded in the database (None when it has no alembic_version)."""
    return MigrationContext.configure(connection).get_current_revision()


def upgrade(connection: Connection, target: str = "head") -> None:
    """Run the migrations up to ``target`` inside the caller's transaction on ``connection``."""
    command.upgrade(alembic_config(connection), target)


def downgrade(connection: Connection, target: str) -> None:
    """Run the downgrades down to ``target`` (``base`` drops everything)."""
    command.downgrade(alembic_config(connection), target)
