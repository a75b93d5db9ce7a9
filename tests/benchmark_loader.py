"""Load a script of ``benchmarks/`` as a module, for the tests of benchmarks."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"


def load_benchmark(name: str, module: str | None = None) -> ModuleType:
    """``benchmarks/NAME.py`` as the module ``module`` (default ``name``), registered in
    ``sys.modules`` (worker processes and dataclasses look it up by that name), with the benchmarks
    folder importable (a benchmark may import another)."""
    if str(BENCHMARKS) not in sys.path:
        sys.path.insert(0, str(BENCHMARKS))
    spec = importlib.util.spec_from_file_location(module or name, BENCHMARKS / f"{name}.py")
    assert spec is not None and spec.loader is not None
    loaded = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = loaded
    spec.loader.exec_module(loaded)
    return loaded
