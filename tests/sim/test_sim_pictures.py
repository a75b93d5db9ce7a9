"""The README's pictures are committed, small, and what docs/make_pictures.py makes."""

from __future__ import annotations

from pathlib import Path

from PIL import Image

DOCS = Path(__file__).resolve().parents[2] / "docs"


def test_the_still_frame_and_the_refusal_gif_are_small_files_of_the_right_kind() -> None:
    still, gif = DOCS / "baxter.png", DOCS / "refusal.gif"
    assert still.stat().st_size < 300_000 and gif.stat().st_size <= 2_000_000
    with Image.open(still) as img:
        assert img.format == "PNG" and img.size == (640, 480)
    with Image.open(gif) as anim:
        assert anim.format == "GIF" and anim.n_frames > 20  # an animation, not a still
    readme = (DOCS.parent / "README.md").read_text(encoding="utf-8")
    assert "docs/baxter.png" in readme and "docs/refusal.gif" in readme and "docs/make_pictures.py" in readme
