"""The built wheel carries its migrations: install it in a fresh venv and create a store from elsewhere."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SOURCES = ("pyproject.toml", "setup.py", "MANIFEST.in", "README.md", "ownctl", "sim", "migrations")


def _build_wheel(tmp: Path) -> Path:
    """``pip wheel --no-deps`` on a copy of the sources (so no build/ lands in the repository)."""
    src = tmp / "src"
    src.mkdir()
    for name in SOURCES:
        path = ROOT / name
        if path.is_dir():
            shutil.copytree(path, src / name, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
        elif path.exists():
            shutil.copy2(path, src / name)
    dist = tmp / "dist"
    cmd = [sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", str(dist), str(src)]
    if subprocess.run(cmd, capture_output=True, text=True).returncode != 0:  # offline: use what is installed
        subprocess.run([*cmd, "--no-build-isolation"], capture_output=True, text=True, check=True)
    (wheel,) = dist.glob("ownctl-*.whl")
    return wheel


def _venv_with_our_dependencies(venv: Path) -> Path:
    """A plain venv that sees the running interpreter's installed packages (not this checkout).

    ``--system-site-packages`` would show the *base* interpreter's site-packages, which lack the
    dependencies when the tests themselves run in a venv. Instead the directories of ``sys.path``
    that hold installed packages are listed in a ``.pth`` file: the wheel's dependencies resolve from
    them, while the wheel itself, installed into the venv's own site-packages, comes first (the
    checkout is left out, so its sources cannot stand in for the wheel's). Works inside a venv and
    outside one, without network.
    """
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    site = subprocess.run(
        [str(venv / "bin" / "python"), "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"],
        capture_output=True, text=True, check=True,
    ).stdout.strip()
    dirs = [p for p in dict.fromkeys(sys.path) if p and Path(p).is_dir() and Path(p).resolve() != ROOT]
    (Path(site) / "outer-site.pth").write_text("".join(f"{p}\n" for p in dirs), encoding="utf-8")
    return venv


@pytest.mark.slow
def test_wheel_ships_migrations(tmp_path: Path) -> None:
    wheel = _build_wheel(tmp_path)
    venv = _venv_with_our_dependencies(tmp_path / "venv")
    python = venv / "bin" / "python"
    subprocess.run(
        [sys.executable, "-m", "pip", "--python", str(python), "install", "-q", "--no-deps", str(wheel)],
        check=True,
        capture_output=True,
    )
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    where = subprocess.run(
        [str(python), "-c", "from ownctl.store.migrate import migrations_dir; print(migrations_dir())"],
        cwd=elsewhere,
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    assert where.startswith(str(venv)) and where.endswith("ownctl/_migrations")
    ownctl = str(venv / "bin" / "ownctl")
    db = f"sqlite:///{tmp_path / 'x.db'}"
    env = {"PATH": "/usr/bin:/bin", "OWNCTL_NOW": "10", "HOME": str(tmp_path)}
    for args in (
        ["init"],
        ["agent", "add", "alexis"],
        ["object", "add", "wallet"],
        ["claim", "wallet", "alexis"],
    ):
        subprocess.run([ownctl, "--db", db, *args], cwd=elsewhere, env=env, check=True, capture_output=True)
    current = subprocess.run(
        [ownctl, "--db", db, "db", "current", "--json"],
        cwd=elsewhere,
        env=env,
        capture_output=True,
        text=True,
    )
    assert current.returncode == 0, current.stderr
    assert json.loads(current.stdout)["current"] is True
    version = subprocess.run([ownctl, "--version"], cwd=elsewhere, env=env, capture_output=True, text=True)
    assert version.stdout.startswith("ownctl ")
    sim_file = subprocess.run([str(python), "-c", "import sim; print(sim.__file__)"], cwd=elsewhere, env=env,
                              capture_output=True, text=True, check=True).stdout.strip()
    assert sim_file.startswith(str(venv))  # the simulation ships in the wheel too
    fresh = f"sqlite:///{tmp_path / 'task.db'}"
    subprocess.run([ownctl, "--db", fresh, "init"], cwd=elsewhere, env=env, check=True, capture_output=True)
    task = subprocess.run([ownctl, "--db", fresh, "run", "trashAll", "--json"],
                          cwd=elsewhere, env=env, capture_output=True, text=True)
    assert task.returncode == 0, task.stderr
    assert json.loads(task.stdout)["sim_seconds"] > 0
