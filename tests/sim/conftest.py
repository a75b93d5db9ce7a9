"""Shared fixtures of the simulator tests.

``MUJOCO_GL`` is chosen before anything imports MuJoCo (it is read once, at import), and every test
runs in its own temporary working directory so MuJoCo can never leave MUJOCO_LOG.TXT in the tree.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import pytest

os.environ.setdefault("MUJOCO_GL", "osmesa")


@pytest.fixture(autouse=True)
def _in_tmp_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    monkeypatch.chdir(tmp_path)
    yield
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists(), "MuJoCo wrote a log file into the working directory"
