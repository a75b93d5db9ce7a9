"""Which OpenGL backend MuJoCo renders with, and a safe check that it can draw.

MuJoCo reads ``MUJOCO_GL`` once, when it is first imported, so the choice is made before that
import: :func:`preselect` (run by ``import sim``) sets ``MUJOCO_GL`` on a Linux machine without a
display to the first headless backend whose library is installed, EGL then OSMesa, and leaves an
explicit ``MUJOCO_GL`` alone. A library can be present and still fail (no EGL device, a broken
driver), and a failing backend may print GLFW warnings or even crash the process, so
:func:`ensure_rendering` tries each candidate in a child process, drawing one small frame, before
anything is rendered or written; where none works it raises :class:`RenderUnavailable` with one line
naming the Debian package to install.
"""

from __future__ import annotations

import ctypes.util
import functools
import os
import subprocess
import sys

from sim.errors import RenderUnavailable

HEADLESS: tuple[str, ...] = ("egl", "osmesa")  # in order of preference: EGL is faster where it works
LIBRARY = {"egl": "EGL", "osmesa": "OSMesa"}
PACKAGE = "libosmesa6"  # the one Debian package that makes headless rendering work on any machine
PROBE_TIMEOUT = 120.0  # seconds; a first import of MuJoCo on a cold, busy machine can take a while
_PROBE = (
    "import mujoco\n"
    "m = mujoco.MjModel.from_xml_string('<mujoco><worldbody><geom size=\"1\"/></worldbody></mujoco>')\n"
    "r = mujoco.Renderer(m, height=8, width=8)\n"
    "r.render()\n"
    "r.close()\n"
)
_chosen_here: set[str] = set()  # MUJOCO_GL values this module set (as opposed to the user)


def _has_display() -> bool:
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def _compatible(backend: str) -> bool:
    """False if ``PYOPENGL_PLATFORM`` is set to another platform (MuJoCo would refuse ``backend``)."""
    platform = os.environ.get("PYOPENGL_PLATFORM")
    return platform is None or platform.lower() == backend


def installed_headless() -> list[str]:
    """The headless backends whose OpenGL library can be found, in order of preference."""
    return [b for b in HEADLESS if _compatible(b) and ctypes.util.find_library(LIBRARY[b])]


def _set(backend: str) -> None:
    os.environ["MUJOCO_GL"] = backend
    _chosen_here.add(backend)


def preselect() -> None:
    """Set ``MUJOCO_GL`` to the first installed headless backend, if unset, on Linux without a display.

    Cheap (a library look-up, no OpenGL call); does nothing once MuJoCo is imported.
    """
    if "MUJOCO_GL" in os.environ or "mujoco" in sys.modules or not sys.platform.startswith("linux"):
        return
    if _has_display():
        return
    found = installed_headless()
    if found:
        _set(found[0])


def probe(backend: str) -> str | None:
    """None if MuJoCo can render a frame with ``MUJOCO_GL=backend`` in a child process, else why not.

    The child's output (GLFW warnings, tracebacks) is captured, never shown; a crash is a failure.
    Answers are remembered per backend and environment (so a probe costs once per process).
    """
    return _probe(backend, tuple(sorted(os.environ.items())))


@functools.cache
def _probe(backend: str, environ: tuple[tuple[str, str], ...]) -> str | None:
    env = {**dict(environ), "MUJOCO_GL": backend}
    if backend in HEADLESS:
        env.setdefault("PYOPENGL_PLATFORM", backend)
    try:
        done = subprocess.run(
            [sys.executable, "-c", _PROBE], env=env, capture_output=True, text=True, timeout=PROBE_TIMEOUT
        )
    except subprocess.TimeoutExpired:
        return f"no frame within {PROBE_TIMEOUT:.0f} s"
    if done.returncode == 0:
        return None
    lines = [line.strip() for line in (done.stderr or done.stdout).splitlines() if line.strip()]
    return lines[-1] if lines else f"exit status {done.returncode}"


def ensure_rendering() -> str:
    """The backend MuJoCo will render with, checked to draw a frame; raises :class:`RenderUnavailable`.

    An explicit ``MUJOCO_GL`` is the only candidate; otherwise a display's default (GLFW), then the
    installed headless backends, are tried in turn, switching ``MUJOCO_GL`` while MuJoCo is not
    imported yet. The error is one line saying what to install.
    """
    current = os.environ.get("MUJOCO_GL")
    if current is not None and current not in _chosen_here:
        why = probe(current)
        if why is not None:
            raise RenderUnavailable(
                f"cannot render with MUJOCO_GL={current} ({why}); unset MUJOCO_GL, or install the "
                f"Debian package {PACKAGE} and set MUJOCO_GL=osmesa"
            )
        return current
    if "mujoco" in sys.modules:
        candidates = [current or "glfw"]  # MuJoCo has made its choice for this process
    else:
        candidates = (["glfw"] if _has_display() else []) + installed_headless()
    for backend in candidates:
        if probe(backend) is None:
            if "mujoco" not in sys.modules and backend in HEADLESS:
                _set(backend)
            return backend
    tried = ", ".join(candidates) if candidates else "no OpenGL library found"
    raise RenderUnavailable(
        f"cannot render: no working OpenGL backend ({tried}); install the Debian package {PACKAGE}"
    )
