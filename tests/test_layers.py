"""The layers of docs/architecture.md, section 1 hold: import-linter's contracts pass."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_import_contracts_hold() -> None:
    lint = Path(sys.executable).with_name("lint-imports")
    cmd = [str(lint)] if lint.exists() else ["lint-imports"]
    result = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Contracts: 3 kept, 0 broken" in result.stdout


def test_only_declared_dependencies_are_imported_for_the_cli() -> None:
    """typer ships its own copy of click, so `click` itself may be absent from a fresh install."""
    offenders = [
        str(path.relative_to(ROOT))
        for folder in ("ownctl", "sim")
        for path in (ROOT / folder).rglob("*.py")
        if any(line.strip().startswith(("import click", "from click"))
               for line in path.read_text(encoding="utf-8").splitlines())
    ]
    assert offenders == []
