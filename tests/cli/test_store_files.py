"""Which store a command uses, through the CLI: default, --db, OWNCTL_DB; missing, foreign, too new."""

from __future__ import annotations

import hashlib
import sqlite3
from pathlib import Path

from typer.testing import CliRunner

from ownctl.cli.main import app


def _run(args: list[str], env: dict[str, str | None], code: int) -> tuple[str, str]:
    result = CliRunner().invoke(app, args, env={"OWNCTL_NOW": "5", **env})
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    assert result.exit_code == code, (args, result.stdout, result.stderr)
    return result.stdout, result.stderr


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_default_store_is_created_on_first_use(tmp_path: Path) -> None:
    env = {"XDG_DATA_HOME": str(tmp_path / "xdg"), "OWNCTL_DB": None}
    _run(["agent", "add", "alexis"], env, 0)
    assert (tmp_path / "xdg" / "ownctl" / "ownctl.db").is_file()
    out, _ = _run(["agent", "list", "--json"], env, 0)
    assert "alexis" in out
    out, _ = _run(["db", "path"], env, 0)
    assert out.strip() == str(tmp_path / "xdg" / "ownctl" / "ownctl.db")


def test_missing_explicit_store_needs_init(tmp_path: Path) -> None:
    path = tmp_path / "typo.db"
    for args, env in (
        (["--db", str(path), "agent", "list"], {"OWNCTL_DB": None}),
        (["agent", "list"], {"OWNCTL_DB": f"sqlite:///{path}"}),
    ):
        _, err = _run(args, env, 1)
        assert str(path) in err and "ownctl --db" in err and "init" in err and err.count("\n") == 1
        assert not path.exists()
    _run(["--db", str(path), "init"], {"OWNCTL_DB": None}, 0)
    _run(["--db", str(path), "agent", "list"], {"OWNCTL_DB": None}, 0)


def test_a_store_name_too_long_for_the_system_is_one_line(tmp_path: Path) -> None:
    for path in (tmp_path / ("s" * 300), tmp_path / ("d" * 300) / "store.db"):
        for args in (["init"], ["agent", "list"]):
            _, err = _run(["--db", str(path), *args], {"OWNCTL_DB": None}, 1)
            assert "File name too long" in err and err.count("\n") == 1


def test_foreign_and_junk_files_are_refused_untouched(tmp_path: Path) -> None:
    other = tmp_path / "other.db"
    with sqlite3.connect(other) as conn:
        conn.execute("CREATE TABLE notes (body TEXT)")
    conn.close()
    junk = tmp_path / "junk.db"
    junk.write_bytes(b"PK\x03\x04 this is a zip, maybe" * 10)
    for path in (other, junk):
        before = _digest(path)
        for args in (["init"], ["agent", "add", "a"], ["agent", "list", "--json"]):
            out, err = _run(["--db", str(path), *args], {"OWNCTL_DB": None}, 1)
            assert "not an ownctl store" in err and err.count("\n") == 1
        assert _digest(path) == before


def test_newer_schema_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "s.db"
    _run(["--db", str(path), "init"], {"OWNCTL_DB": None}, 0)
    with sqlite3.connect(path) as conn:
        conn.execute("UPDATE alembic_version SET version_num = '9999_future'")
    conn.close()
    before = _digest(path)
    out, err = _run(["--db", str(path), "db", "current", "--json"], {"OWNCTL_DB": None}, 1)
    assert "newer than this ownctl" in err and '"error"' in out
    assert _digest(path) == before
