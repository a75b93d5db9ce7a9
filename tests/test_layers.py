"""The layers of docs/architecture.md, section 1 hold (import-linter's contracts pass), and modules
import one another without cycles."""

import subprocess
import sys
from pathlib import Path

import pytest

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


#: the packages whose modules must not import each other in a cycle; widen to ("ownctl",) once the
#: whole package is free of cycles
CYCLE_FREE_PACKAGES: tuple[str, ...] = ("ownctl",)


def import_cycles(package: str, within: tuple[str, ...]) -> list[list[str]]:
    """Every set of modules of ``within`` (packages of ``package``) that import one another in a cycle.

    Imports inside functions count (they still tie the modules together); imports under
    ``TYPE_CHECKING`` do not (they never run). Tarjan's strongly connected components.
    """
    import grimp

    graph = grimp.build_graph(package, exclude_type_checking_imports=True, cache_dir=None)
    inside = {m for m in graph.modules if any(m == p or m.startswith(p + ".") for p in within)}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    cycles: list[list[str]] = []

    def visit(module: str) -> None:
        index[module] = low[module] = len(index)
        stack.append(module)
        for other in sorted(graph.find_modules_directly_imported_by(module) & inside):
            if other not in index:
                visit(other)
                low[module] = min(low[module], low[other])
            elif other in stack:
                low[module] = min(low[module], index[other])
        if low[module] == index[module]:
            component = []
            while True:
                top = stack.pop()
                component.append(top)
                if top == module:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for module in sorted(inside):
        if module not in index:
            visit(module)
    return cycles


def test_no_import_cycles() -> None:
    assert import_cycles("ownctl", CYCLE_FREE_PACKAGES) == []


def test_the_cycle_finder_finds_a_cycle(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    package = tmp_path / "loopy"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "a.py").write_text("def f():\n    from loopy import b\n")  # a lazy import counts
    (package / "b.py").write_text("from loopy import a\n")
    (package / "c.py").write_text("import typing\n\nif typing.TYPE_CHECKING:\n    from loopy import d\n")
    (package / "d.py").write_text("from loopy import c\n")  # the import back only for type checkers does not
    monkeypatch.syspath_prepend(str(tmp_path))
    assert import_cycles("loopy", ("loopy",)) == [["loopy.a", "loopy.b"]]
