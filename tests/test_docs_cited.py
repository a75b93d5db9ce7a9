"""The project cites its own design (``docs/architecture.md``), never a document outside it."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SOURCES = [p for folder in ("ownctl", "sim", "scenarios", "benchmarks", "migrations", "tests")
           for p in (ROOT / folder).rglob("*") if p.suffix in (".py", ".toml", ".md")]
OUTSIDE = re.compile(r"DESIGN(\.md| section| \d)|reference section|shared/")
SECTION = re.compile(r"architecture(?:\.md)?,? sections? (\d+)")


def test_no_source_cites_an_outside_document() -> None:
    hits = [f"{p.relative_to(ROOT)}: {m.group(0)}" for p in SOURCES if p.name != Path(__file__).name
            for m in OUTSIDE.finditer(p.read_text(encoding="utf-8"))]
    assert not hits, hits


def test_every_cited_section_exists() -> None:
    text = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    sections = {int(n) for n in re.findall(r"^## (\d+)\.", text, flags=re.M)}
    cited = {int(m.group(1)) for p in SOURCES for m in SECTION.finditer(p.read_text(encoding="utf-8"))}
    assert cited and cited <= sections, sorted(cited - sections)
