"""The README's tour runs as written: every line, in order, in a shell, on a fresh default store.

Each line is run by ``bash`` in a scratch directory holding a copy of ``scenarios/``, with a fresh
HOME (so the default store is new) and neither OWNCTL_DB nor OWNCTL_NOW set, as a newcomer would
run it. A line must exit 0, or the code its comment names ("exits 3"), and never print a traceback.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def tour_lines(readme: str) -> list[str]:
    """The command lines of the code block under the README's "A tour" heading."""
    section = readme.split("\n## A tour\n", 1)[1]
    block = section.split("```\n", 2)[1]
    return [line for line in block.splitlines() if line.strip()]


def allowed_codes(line: str) -> set[int]:
    """0, and any exit code the line's comment names ("exits 3 when forbidden")."""
    comment = line.split("#", 1)[1] if "#" in line else ""
    return {0, *(int(code) for code in re.findall(r"\bexits? (\d+)", comment))}


def test_the_tour_is_found_and_its_exit_codes_are_read() -> None:
    lines = tour_lines((ROOT / "README.md").read_text(encoding="utf-8"))
    assert lines[0].startswith("ownctl init") and len(lines) > 20
    assert allowed_codes("ownctl check trash wallet   # exits 3 when forbidden") == {0, 3}
    assert allowed_codes("ownctl agent list") == {0}
    commands = [line.split("#")[0] for line in lines]
    assert all("[" not in c and "|" not in c for c in commands)  # real values, not a synopsis


@pytest.mark.slow
def test_every_tour_line_runs_as_written(tmp_path: Path) -> None:
    work, home, bin_dir = tmp_path / "clone", tmp_path / "home", tmp_path / "bin"
    for folder in (work, home, bin_dir):
        folder.mkdir()
    shutil.copytree(ROOT / "scenarios", work / "scenarios")
    shim = bin_dir / "ownctl"  # this checkout's ownctl on this interpreter, in or out of a venv
    shim.write_text(f'#!/bin/sh\nexec "{sys.executable}" -c "from ownctl.cli.main import run; run()" "$@"\n')
    shim.chmod(0o755)
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OWNCTL_", "XDG_"))}
    env.update(HOME=str(home), PATH=f"{bin_dir}{os.pathsep}{env.get('PATH', '/usr/bin:/bin')}",
               PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")])))  # this checkout
    for line in tour_lines((ROOT / "README.md").read_text(encoding="utf-8")):
        done = subprocess.run(["bash", "-c", line], cwd=work, env=env, capture_output=True, text=True)
        assert done.returncode in allowed_codes(line), (line, done.returncode, done.stdout, done.stderr)
        assert "Traceback" not in done.stderr, (line, done.stderr)
    store = home / ".local" / "share" / "ownctl" / "ownctl.db"  # where the quick start says it is
    assert store.is_file()
    path = subprocess.run(["ownctl", "db", "path"], cwd=work, env=env, capture_output=True, text=True)
    assert path.stdout.strip() == str(store)
