"""Fixtures of the store laws: a store holding the small world of the instruction streams."""

from __future__ import annotations

from pathlib import Path

import pytest

from ownctl.app import things
from ownctl.app.context import AppContext
from tests.app.test_store_equals_mind import AGENTS, AREAS, START, world_objects


@pytest.fixture(scope="module")
def template(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A store holding the world (made once; each example starts from a copy)."""
    path = tmp_path_factory.mktemp("template") / "t.db"
    ctx = AppContext(str(path), now=START)
    ctx.store(create=True)
    for a in AGENTS:
        things.add_agent(ctx, a)
    for area in AREAS:
        things.add_area(ctx, area.name, ",".join(str(v) for v in area.box))
    for o in world_objects():
        assert o.position is not None
        things.add_object(ctx, o.name, color=o.color, pos=",".join(str(v) for v in o.position))
    ctx.close()
    return path
