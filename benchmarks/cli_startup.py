"""Start-up of every ownctl command group beside the floor ``python -c "import sqlalchemy, numpy"``.

Usage: python benchmarks/cli_startup.py [--runs 10] [--script] [--json] [--instructions]

Each command runs ``--runs`` times (after one warm-up) on a small temporary store, interleaved round
by round with the floor so that a change in the machine's load touches every figure alike. For each
command: the median wall time, the median CPU time of the process (user + system, from
``resource.getrusage(RUSAGE_CHILDREN)`` deltas), and both minus the floor's medians. ``check`` and
``claim`` must take at most 100 ms more wall time than the floor (PASS/FAIL); the floor is what any
program that opens a store and holds beliefs as arrays pays, so the difference is ownctl's own
start-up and work. ownctl's console script freezes its heap when the command is done, so that the
interpreter's last collection at exit has nothing to walk (``ownctl/cli/main.py``); the floor
does not, so the figures are also given over the floor with its heap frozen the same way, which
is ownctl's own start-up and work alone. ``tests/cli/test_startup.py`` checks which modules these
paths import.

Bytecode caches are used as for an installed package (``PYTHONDONTWRITEBYTECODE`` is dropped from
the commands' environment, and the warm-up writes the caches): without them every ownctl module
is compiled from source on every start, which alone costs more than the target. Commands run as
``python -c "from ownctl.cli.main import run; run()"`` with this interpreter (the
console script's entry point, without a launcher); ``--script`` runs the ``ownctl`` console script
next to the interpreter instead, so a pyenv or venv shim does not add its own start-up.

``--instructions`` also counts, once each under ``valgrind --tool=callgrind`` (when installed), the
instructions the floor, ``check`` and ``claim`` execute: a figure a busy machine does not change,
to compare versions when wall times are noisy (the process's hash seed is fixed for it).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path
from time import perf_counter

ROOT = Path(__file__).resolve().parents[1]
FLOOR = [sys.executable, "-c", "import sqlalchemy, numpy"]
#: the floor as ownctl leaves: heap frozen, so the interpreter's last collection walks nothing
FROZEN = [sys.executable, "-c", "import gc, sqlalchemy, numpy; gc.freeze()"]
LIMIT_MS = 100.0  # check and claim: at most this much over the floor
GATED = ("check", "claim")

#: (label, arguments after ``ownctl --db DB``, stdin): one or more commands of every group
COMMANDS: list[tuple[str, list[str], str | None]] = [
    ("--help", ["--help"], None),
    ("--version", ["--version"], None),
    ("check", ["check", "trash", "mug"], None),
    ("check --json", ["check", "trash", "mug", "--json"], None),
    ("claim", ["claim", "mug", "xuan"], None),
    ("forbid ... on", ["forbid", "pickUp", "on", "cup"], None),
    ("allow ... on", ["allow", "pickUp", "on", "cup"], None),
    ("forbid ... if", ["forbid", "wait", "if", "ownedBy", "jake"], None),
    ("owners", ["owners", "mug"], None),
    ("explain", ["explain", "trash", "mug"], None),
    ("rules list", ["rules", "list"], None),
    ("perms list", ["perms", "list"], None),
    ("claims list", ["claims", "list"], None),
    ("agent list", ["agent", "list"], None),
    ("object list", ["object", "list"], None),
    ("object touch", ["object", "touch", "cup", "--by", "jake"], None),
    ("area list", ["area", "list"], None),
    ("log", ["log", "--limit", "5"], None),
    ("db path", ["db", "path"], None),
    ("config get", ["config", "get", "threshold"], None),
    ("say", ["say", "whose is the mug?"], None),
    ("batch (one line)", ["batch", "-"], "check trash mug\n"),
    ("world --help", ["world", "--help"], None),
    ("scenario --help", ["scenario", "--help"], None),
    ("run --help", ["run", "--help"], None),
    ("experiment --help", ["experiment", "--help"], None),
]

SETUP = """\
agent add xuan
agent add jake
object add mug --color red --pos 0.1,0.1,0
object add cup --color blue --pos 0.4,0.4,0
claim mug xuan
forbid trash if ownedBy any
"""


@dataclass
class Figure:
    """One command's medians, and their differences to the floor's (milliseconds)."""

    label: str
    wall_ms: float
    cpu_ms: float
    wall_over_floor_ms: float
    cpu_over_floor_ms: float
    verdict: str  # PASS / FAIL for check and claim, "" for the others


def ownctl_command(script: bool) -> list[str]:
    """How to start ownctl: the console script next to this interpreter, or its entry point."""
    found = Path(sys.executable).with_name("ownctl")
    if script and found.exists():
        return [str(found)]
    return [sys.executable, "-c", "from ownctl.cli.main import run; run()"]


def timed(cmd: list[str], env: dict[str, str], stdin: str | None) -> tuple[float, float]:
    """Wall and CPU seconds of one run of ``cmd`` (it must exit 0, or 3 for a forbidden check)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = perf_counter()
    done = subprocess.run(cmd, env=env, input=stdin, capture_output=True, text=True)
    wall = perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 3):
        raise SystemExit(f"{' '.join(cmd)} failed ({done.returncode}): {done.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def _environment() -> dict[str, str]:
    env = {**os.environ, "OWNCTL_NOW": "1000", "PYTHONPATH": os.pathsep.join(
        [str(ROOT), os.environ.get("PYTHONPATH", "")])}
    env.pop("OWNCTL_DB", None)
    # as an installed ownctl, and the floor's libraries, run: from bytecode caches (the warm-up
    # writes them), not compiling every module from source on every start
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def _prepared(exe: list[str], env: dict[str, str], folder: str) -> list[str]:
    """A small store in ``folder`` with the set-up's agents, objects, claim and norm: its --db."""
    db = ["--db", f"sqlite:///{folder}/startup.db"]
    subprocess.run([*exe, *db, "init", "--quiet"], env=env, check=True, capture_output=True)
    subprocess.run([*exe, *db, "batch", "-", "--quiet"], env=env, input=SETUP, check=True,
                   capture_output=True, text=True)
    return db


def instructions(script: bool) -> dict[str, int]:
    """Instructions executed by the floor and by ``check`` and ``claim`` (callgrind, one run each,
    after a warm-up run that writes bytecode caches)."""
    valgrind = shutil.which("valgrind")
    if valgrind is None:
        raise SystemExit("--instructions needs valgrind (apt-get install valgrind)")
    exe = ownctl_command(script)
    env = {**_environment(), "PYTHONHASHSEED": "0"}
    counted = [valgrind, "--tool=callgrind", "--callgrind-out-file=/dev/null"]
    out: dict[str, int] = {}
    with tempfile.TemporaryDirectory(prefix="ownctl-startup-") as folder:
        db = _prepared(exe, env, folder)
        jobs = [("floor", FLOOR)] + [(label, [*exe, *db, *args]) for label, args, _ in COMMANDS
                                     if label in GATED]
        for label, cmd in jobs:
            timed(cmd, env, None)
            done = subprocess.run([*counted, *cmd], env=env, capture_output=True, text=True)
            found = re.search(r"Collected\s*:\s*(\d+)", done.stderr)
            if done.returncode not in (0, 3) or found is None:
                raise SystemExit(f"callgrind on {label} failed ({done.returncode}): {done.stderr[-300:]}")
            out[label] = int(found.group(1))
    return out


def measure(runs: int, script: bool) -> tuple[tuple[float, float], tuple[float, float], list[Figure]]:
    """The floor's medians (wall, CPU seconds), the frozen floor's, and every command's figures."""
    exe = ownctl_command(script)
    env = _environment()
    with tempfile.TemporaryDirectory(prefix="ownctl-startup-") as folder:
        db = _prepared(exe, env, folder)
        jobs = [("floor", FLOOR, None), ("frozen floor", FROZEN, None)]
        jobs += [(label, [*exe, *db, *args], stdin) for label, args, stdin in COMMANDS]
        samples: dict[str, list[tuple[float, float]]] = {label: [] for label, _, _ in jobs}
        for _, cmd, stdin in jobs:  # warm-up: file caches, compiled bytecode
            timed(cmd, env, stdin)
        for _ in range(runs):
            for label, cmd, stdin in jobs:
                samples[label].append(timed(cmd, env, stdin))
    wall0 = statistics.median(w for w, _ in samples["floor"])
    cpu0 = statistics.median(c for _, c in samples["floor"])
    figures = []
    for label, _, _ in COMMANDS:
        wall = statistics.median(w for w, _ in samples[label])
        cpu = statistics.median(c for _, c in samples[label])
        verdict = ""
        if label in GATED:
            verdict = "PASS" if (wall - wall0) * 1e3 <= LIMIT_MS else "FAIL"
        over = ((wall - wall0) * 1e3, (cpu - cpu0) * 1e3)
        figures.append(Figure(label, wall * 1e3, cpu * 1e3, *over, verdict))
    frozen = (statistics.median(w for w, _ in samples["frozen floor"]),
              statistics.median(c for _, c in samples["frozen floor"]))
    return (wall0, cpu0), frozen, figures


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=10)
    parser.add_argument("--script", action="store_true", help="time the ownctl console script")
    parser.add_argument("--json", action="store_true", help="print one JSON document")
    parser.add_argument("--instructions", action="store_true",
                        help="also count the instructions of the floor, check and claim (callgrind)")
    args = parser.parse_args()
    (wall0, cpu0), frozen, figures = measure(args.runs, args.script)
    counts = instructions(args.script) if args.instructions else {}
    if args.json:
        print(json.dumps({"runs": args.runs, "floor": {"wall_ms": wall0 * 1e3, "cpu_ms": cpu0 * 1e3},
                          "frozen_floor": {"wall_ms": frozen[0] * 1e3, "cpu_ms": frozen[1] * 1e3},
                          "limit_ms": LIMIT_MS, "commands": [asdict(f) for f in figures],
                          "instructions": counts,
                          "python": platform.python_version(), "load_average": list(os.getloadavg())}))
        return
    print(f"medians over {args.runs} runs; floor {' '.join(FLOOR[1:])!s}: "
          f"wall {wall0 * 1e3:.0f} ms, CPU {cpu0 * 1e3:.0f} ms")
    print(f"{'command':20s} {'wall ms':>8s} {'CPU ms':>8s} {'wall-floor':>11s} {'CPU-floor':>10s}")
    for f in figures:
        print(f"{f.label:20s} {f.wall_ms:8.0f} {f.cpu_ms:8.0f} {f.wall_over_floor_ms:+11.0f} "
              f"{f.cpu_over_floor_ms:+10.0f}  {f.verdict}")
    print(f"the floor with its heap frozen at exit, as ownctl leaves: wall {frozen[0] * 1e3:.0f} ms, "
          f"CPU {frozen[1] * 1e3:.0f} ms; over it: "
          + ", ".join(f"{f.label} {f.wall_ms - frozen[0] * 1e3:+.0f} ms"
                      for f in figures if f.label in GATED))
    print(f"check and claim may take at most {LIMIT_MS:.0f} ms more wall time than the floor; "
          f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    for label, count in counts.items():
        extra = "" if label == "floor" else f" (floor + {(count - counts['floor']) / 1e6:,.0f} million)"
        print(f"instructions, {label}: {count / 1e6:,.0f} million{extra}")


if __name__ == "__main__":
    main()
