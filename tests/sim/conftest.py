"""Shared fixtures of the simulator tests.

Nothing here chooses an OpenGL backend: ``import sim`` does (EGL, then OSMesa, see :mod:`sim.gl`),
and tests that render ask for the ``rendering`` fixture, which skips them with the reason where no
backend can draw. Every test runs in its own temporary working directory so MuJoCo can never leave
MUJOCO_LOG.TXT in the tree.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from sim.errors import RenderUnavailable
from sim.gl import ensure_rendering


@pytest.fixture(autouse=True)
def _in_tmp_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    monkeypatch.chdir(tmp_path)
    yield
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists(), "MuJoCo wrote a log file into the working directory"


@pytest.fixture(scope="session")
def rendering() -> str:
    """The OpenGL backend rendering uses here; skips the test where none can draw."""
    try:
        return ensure_rendering()
    except RenderUnavailable as exc:
        pytest.skip(f"no OpenGL backend can render here: {exc}")
