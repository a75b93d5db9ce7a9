"""Choosing the OpenGL backend: EGL then OSMesa by themselves, an explicit MUJOCO_GL respected, and
one line naming the package to install where nothing can draw (before anything is written)."""

from __future__ import annotations

import ctypes.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

from sim import gl
from sim.errors import RenderUnavailable


@pytest.fixture
def clean_env(monkeypatch: pytest.MonkeyPatch) -> pytest.MonkeyPatch:
    """No MUJOCO_GL, no display, MuJoCo not imported yet, nothing chosen by sim.gl so far."""
    for name in ("MUJOCO_GL", "DISPLAY", "WAYLAND_DISPLAY", "PYOPENGL_PLATFORM"):
        monkeypatch.setenv(name, "placeholder")  # so that teardown restores the original value
        monkeypatch.delenv(name)
    monkeypatch.setitem(sys.modules, "mujoco", None)
    monkeypatch.delitem(sys.modules, "mujoco")
    monkeypatch.setattr(gl, "_chosen_here", set())
    return monkeypatch


def _libraries(monkeypatch: pytest.MonkeyPatch, *present: str) -> None:
    found = {name: f"lib{name}.so" for name in present}
    monkeypatch.setattr(ctypes.util, "find_library", found.get)


def _probe(monkeypatch: pytest.MonkeyPatch, working: set[str]) -> list[str]:
    calls: list[str] = []

    def fake(backend: str) -> str | None:
        calls.append(backend)
        return None if backend in working else f"{backend} cannot draw"

    monkeypatch.setattr(gl, "probe", fake)
    return calls


@pytest.mark.parametrize(
    ("present", "chosen"), [(("EGL", "OSMesa"), "egl"), (("OSMesa",), "osmesa"), ((), None)]
)
def test_preselect_prefers_egl_then_osmesa(
    clean_env: pytest.MonkeyPatch, present: tuple[str, ...], chosen: str | None
) -> None:
    _libraries(clean_env, *present)
    gl.preselect()
    assert os.environ.get("MUJOCO_GL") == chosen


def test_preselect_leaves_an_explicit_choice_and_a_display_alone(clean_env: pytest.MonkeyPatch) -> None:
    _libraries(clean_env, "EGL", "OSMesa")
    clean_env.setenv("MUJOCO_GL", "glfw")
    gl.preselect()
    assert os.environ["MUJOCO_GL"] == "glfw"
    clean_env.delenv("MUJOCO_GL")
    clean_env.setenv("DISPLAY", ":0")
    gl.preselect()
    assert "MUJOCO_GL" not in os.environ


def test_a_failing_backend_is_skipped_for_the_next_one(clean_env: pytest.MonkeyPatch) -> None:
    _libraries(clean_env, "EGL", "OSMesa")
    gl.preselect()
    calls = _probe(clean_env, {"osmesa"})
    assert gl.ensure_rendering() == "osmesa"
    assert calls == ["egl", "osmesa"] and os.environ["MUJOCO_GL"] == "osmesa"


def test_an_explicit_backend_is_the_only_candidate(clean_env: pytest.MonkeyPatch) -> None:
    _libraries(clean_env, "EGL", "OSMesa")
    clean_env.setenv("MUJOCO_GL", "egl")
    calls = _probe(clean_env, {"osmesa"})
    with pytest.raises(RenderUnavailable, match="MUJOCO_GL=egl") as err:
        gl.ensure_rendering()
    assert calls == ["egl"] and "\n" not in str(err.value) and "libosmesa6" in str(err.value)


@pytest.mark.parametrize("present", [("EGL", "OSMesa"), ()])
def test_nothing_working_is_one_line_naming_the_package(
    clean_env: pytest.MonkeyPatch, present: tuple[str, ...]
) -> None:
    _libraries(clean_env, *present)
    _probe(clean_env, set())
    with pytest.raises(RenderUnavailable) as err:
        gl.ensure_rendering()
    message = str(err.value)
    assert "\n" not in message and "install the Debian package libosmesa6" in message


@pytest.mark.slow
def test_the_probe_reports_a_backend_that_cannot_draw(monkeypatch: pytest.MonkeyPatch) -> None:
    if not ctypes.util.find_library("EGL"):
        pytest.skip("no EGL library here")
    monkeypatch.setenv("MUJOCO_EGL_DEVICE_ID", "99")  # there is no such device: EGL fails for real
    why = gl.probe("egl")
    assert why is not None and "MUJOCO_EGL_DEVICE_ID" in why


def _ownctl(tmp_path: Path, env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    code = "import sys; from ownctl.cli.main import run; sys.argv[0] = 'ownctl'; run()"
    full = {**os.environ, "OWNCTL_NOW": "1000", **env}
    return subprocess.run([sys.executable, "-c", code, "--db", str(tmp_path / "store.db"), *args],
                          cwd=tmp_path, env=full, capture_output=True, text=True, timeout=600)


@pytest.mark.slow
def test_run_that_cannot_render_prints_one_line_and_changes_nothing(tmp_path: Path) -> None:
    if not ctypes.util.find_library("EGL"):
        pytest.skip("no EGL library here")
    broken = {"MUJOCO_GL": "egl", "MUJOCO_EGL_DEVICE_ID": "99"}
    assert _ownctl(tmp_path, {}, "init").returncode == 0
    before = (tmp_path / "store.db").read_bytes()
    done = _ownctl(tmp_path, broken, "run", "trashAll", "--render", "x.mp4")
    assert done.returncode == 1 and done.stdout == ""
    assert len(done.stderr.splitlines()) == 1 and "libosmesa6" in done.stderr, done.stderr
    assert (tmp_path / "store.db").read_bytes() == before and not (tmp_path / "x.mp4").exists()


@pytest.mark.slow
def test_run_with_render_says_where_the_file_went(tmp_path: Path, rendering: str) -> None:
    assert _ownctl(tmp_path, {}, "init").returncode == 0
    done = _ownctl(tmp_path, {}, "run", "trashAll", "--render", "shot.png", "--quiet")
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "shot.png").stat().st_size > 1000
    assert "wrote" not in done.stderr  # --quiet prints nothing but errors
    done = _ownctl(tmp_path, {}, "run", "trashAll", "--render", "again.png", "--camera", "shoulder", "--json")
    assert done.stderr.strip().splitlines()[-1] == "wrote again.png"
    assert (tmp_path / "again.png").read_bytes() != (tmp_path / "shot.png").read_bytes()
