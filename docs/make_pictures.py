"""Make the README's pictures of the simulated Baxter: a still frame and a GIF of a refusal.

    python docs/make_pictures.py [--out docs]

Loads the paper's blocks world (scenarios/paper-blocks.toml, seed 0) into a temporary store, tells
the robot that block2 is agent1's and that trashing what someone owns is forbidden, and asks the
store, with ``ownctl check``, whether each block may be trashed. It then builds the MuJoCo scene of
that world and writes

- ``baxter.png``: the default camera at rest (the whole robot, the table, the bin and the blocks);
- ``refusal.gif``: the robot trashes the first block the store allows, then reaches for the owned
  block, stops short over it and goes back, leaving it where it is.

Needs an OpenGL backend (Debian ``libosmesa6`` is enough). Prints the path of every file it writes.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image

ROOT = Path(__file__).resolve().parents[1]
OWNED, OWNER = "block2", "agent1"
GIF_SIZE = (400, 300)  # GIF frames are scaled down: 8 frames a second stay well under 2 MB
GIF_FPS = 8
EXIT_FORBIDDEN = 3


def ownctl(db: Path, *args: str) -> subprocess.CompletedProcess[str]:
    """Run ``ownctl --db DB ARGS`` with this interpreter (so it uses this checkout's ownctl)."""
    code = "import sys; from ownctl.cli.main import run; sys.argv[0] = 'ownctl'; run()"
    done = subprocess.run([sys.executable, "-c", code, "--db", str(db), *args],
                          capture_output=True, text=True, cwd=ROOT)
    if done.returncode not in (0, EXIT_FORBIDDEN):
        raise SystemExit(f"ownctl {' '.join(args)} failed: {done.stderr.strip()}")
    return done


def store_world(db: Path) -> tuple[list[dict[str, Any]], list[dict[str, Any]], dict[str, bool]]:
    """The world's objects and areas, and whether the store allows trashing each object."""
    ownctl(db, "init")
    ownctl(db, "world", "load", str(ROOT / "scenarios" / "paper-blocks.toml"), "--seed", "0")
    ownctl(db, "claim", OWNED, OWNER)
    ownctl(db, "forbid", "trash", "if", "ownedBy", "any")
    objects = json.loads(ownctl(db, "object", "list", "--json").stdout)
    areas = json.loads(ownctl(db, "area", "list", "--json").stdout)
    allowed = {o["name"]: ownctl(db, "check", "trash", o["name"]).returncode == 0 for o in objects}
    return objects, areas, allowed


def save_gif(frames: list[np.ndarray], path: Path) -> None:
    """Write ``frames`` scaled to ``GIF_SIZE`` as a looping GIF at ``GIF_FPS``."""
    images = [Image.fromarray(f).resize(GIF_SIZE, Image.LANCZOS).quantize(colors=128) for f in frames]
    images[0].save(path, save_all=True, append_images=images[1:], duration=int(1000 / GIF_FPS), loop=0,
                   optimize=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs", help="directory for the pictures")
    args = parser.parse_args()

    from sim.world import PhysicsWorld, SimArea, SimBlock

    with tempfile.TemporaryDirectory() as tmp:
        objects, areas, allowed = store_world(Path(tmp) / "store.db")
    if allowed[OWNED]:
        raise SystemExit(f"the store allows trashing {OWNED}; nothing to refuse")
    free = next(o["name"] for o in objects if allowed[o["name"]])
    blocks = [SimBlock(o["name"], o.get("color"), tuple(o["position"])) for o in objects]
    world = PhysicsWorld(blocks, [SimArea(a["name"], tuple(a["box"])) for a in areas],
                         render=str(args.out / "refusal.gif"))
    args.out.mkdir(parents=True, exist_ok=True)
    still = world.render_png(args.out / "baxter.png")
    print(f"wrote {still}")
    world.recorder.fps = GIF_FPS
    for outcome in (world.trash(free), world.stop_short(OWNED)):
        if not outcome.ok:
            raise SystemExit(f"{outcome.action} {outcome.object} failed: {outcome.error}")
    gif = args.out / "refusal.gif"
    save_gif(world.recorder.frames, gif)
    world.close()
    print(f"wrote {gif} ({len(world.recorder.frames)} frames, {gif.stat().st_size // 1024} KB): "
          f"trashed {free}, refused {OWNED}")


if __name__ == "__main__":
    main()
