"""Benchmark: how many everyday utterances the parser understands, and how fast it parses.

    python benchmarks/language.py [--data benchmarks/data/utterances.toml] [--failures] [--json]
                                  [--repeats 50]

Reads the held-out utterances (``benchmarks/data/utterances.toml``: each with its speaker, the
object "this" refers to, the robot's ongoing action and the instructions it should store) and
parses each one with :func:`ownctl.language.understand` in a context built from the file's world.
Each utterance is

* **understood** when the instructions equal the expected ones (as a set; norms compared in their
  canonical form) and the reply contains the expected piece, if one is given;
* **stored wrongly** when the parser produced instructions that differ from the expected ones;
* **refused** when the parser did not understand it (or understood it but the reply lacks the
  expected piece): nothing is stored.

An utterance with a ``pending`` question (group ``answers``: the question the robot put to the
speaker, ``{kind, object, action, rule}`` as ``ownctl ask --put`` keeps it) is read as its answer
(:func:`ownctl.language.answers.answer_instructions`, as ``ownctl say`` reads it); one not taken as
an answer is refused (the question stays pending).

Prints the share understood, stored wrongly and refused per group and overall, then the median
parse time (over ``--repeats`` runs, wall and CPU) of utterances of about 20, 200 and 2,000
characters and the ratio t(2000)/t(200), and how long refusing a 100 KB utterance takes. Exits 1
when fewer than 90% are understood overall or in any group, or when anything is stored wrongly.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import statistics
import sys
import time
import tomllib
from collections import defaultdict
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ownctl.errors import OwnctlError  # noqa: E402
from ownctl.language import Context, understand  # noqa: E402
from ownctl.language.answers import answer_instructions  # noqa: E402
from ownctl.language.context import Facts  # noqa: E402
from ownctl.language.lexicon import COLORS  # noqa: E402
from ownctl.logic.rules import parse_norm  # noqa: E402

DATA = ROOT / "benchmarks" / "data" / "utterances.toml"
GROUPS = ("claims", "denials", "reprimands", "norms", "questions", "tasks", "answers", "social")
BAR = 0.90  # share understood, overall and in every group
# Sentences of the timing utterances, repeated until the wanted length.
TIMING_SENTENCES = (
    "The red mug is mine.",  # 20 characters: the 20-character utterance
    "Don't pick up Casey's stuff unless it's green.",
    "That's not Jake's, I think.",
    "Never throw away anything of Mia's.",
)


def canonical(text: str) -> str:
    """An instruction text in canonical form: norms as the norm language prints them."""
    words = text.split()
    if len(words) >= 2 and words[0] in ("forbid", "allow") and (len(words) == 2 or words[2] == "if"):
        return parse_norm(text).text()
    return " ".join(words)


def world_context(world: dict[str, Any]) -> Context:
    """The parser's context for the file's world (speaker, object and action set per utterance)."""
    objects: dict[str, dict[str, Any]] = world["objects"]
    kwargs: dict[str, Any] = {
        "agents": frozenset(world["agents"]),
        "objects": frozenset(objects),
        "colors": COLORS | {o["color"] for o in objects.values()},
        "areas": frozenset(world["areas"]),
        "categories": frozenset(c for o in objects.values() for c in o.get("categories", ())),
    }
    kwargs["facts"] = {
        name: Facts(o.get("color"), frozenset([o["area"]] if "area" in o else ()),
                    frozenset(o.get("categories", ())))
        for name, o in objects.items()
    }
    return Context(**kwargs)


def judge(entry: dict[str, Any], base: Context) -> dict[str, Any]:
    """Parse one utterance in its context; ``verdict`` is understood, wrong or refused."""
    ctx = dataclasses.replace(base, speaker=entry.get("as"), about=entry.get("about"),
                              action=entry.get("doing"))
    want = {canonical(t) for t in entry["expect"]}
    out: dict[str, Any] = {"group": entry["group"], "say": entry["say"], "expect": sorted(want)}
    if "pending" in entry:  # an answer to the robot's question: read as the store reads it
        answer = answer_instructions(entry["say"], entry["pending"], ctx)
        if answer is None:
            return {**out, "verdict": "refused", "got": [],
                    "reply": "not an answer: the question stays pending"}
        texts = {canonical(i.text()) for i in answer}
        verdict = "understood" if texts == want else "wrong"
        return {**out, "verdict": verdict, "got": sorted(texts), "reply": ""}
    try:
        got = understand(entry["say"], ctx)
    except OwnctlError as err:
        return {**out, "verdict": "refused", "got": [], "reply": str(err)}
    texts = {canonical(t) for t in got.texts()}
    verdict = "understood" if texts == want else "wrong"
    if verdict == "understood" and entry.get("reply") and entry["reply"] not in got.reply:
        verdict = "refused"
    return {**out, "verdict": verdict, "got": sorted(texts), "reply": got.reply}


def shares(results: list[dict[str, Any]]) -> dict[str, Any]:
    """Counts and shares of each verdict."""
    n = len(results)
    counts = {v: sum(r["verdict"] == v for r in results) for v in ("understood", "wrong", "refused")}
    return {"n": n, **counts, **{f"{v}_share": (c / n if n else 0.0) for v, c in counts.items()}}


def utterance_of(length: int) -> str:
    """An utterance of at most ``length`` characters (and within one sentence of it): the timing
    sentences, repeated."""
    text = ""
    i = 0
    while len(nxt := f"{text} {TIMING_SENTENCES[i % len(TIMING_SENTENCES)]}".strip()) <= length:
        text, i = nxt, i + 1
    return text


def parse_seconds(text: str, ctx: Context, repeats: int) -> tuple[float, float]:
    """Median wall time and median CPU time of parsing ``text`` (understood or refused alike).
    On a shared machine the wall time also counts waiting for a core; the CPU time is the
    parser's own."""
    wall, cpu = [], []
    for _ in range(repeats):
        start, start_cpu = time.perf_counter(), time.process_time()
        try:
            understand(text, ctx)
        except OwnctlError:
            pass
        cpu.append(time.process_time() - start_cpu)
        wall.append(time.perf_counter() - start)
    return statistics.median(wall), statistics.median(cpu)


def timings(base: Context, repeats: int) -> dict[str, Any]:
    """Parse times of 20-, 200- and 2,000-character utterances and of a 100 KB one."""
    ctx = dataclasses.replace(base, speaker="xuan", about="mug")
    out: dict[str, Any] = {}
    for n in (20, 200, 2000):
        text = utterance_of(n)
        understand(text, ctx)  # warm the caches of the grammar (compiled once per process)
        wall, cpu = parse_seconds(text, ctx, repeats)
        out[str(n)] = {"chars": len(text), "ms": wall * 1000, "cpu_ms": cpu * 1000}
    out["ratio_2000_200"] = out["2000"]["ms"] / out["200"]["ms"]
    out["cpu_ratio_2000_200"] = out["2000"]["cpu_ms"] / out["200"]["cpu_ms"]
    huge = ("The red mug is mine. " * 5000)[:100_000]
    out["100KB_ms"] = parse_seconds(huge, ctx, 3)[0] * 1000
    out["load_average"] = os.getloadavg()[0]
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, default=DATA)
    parser.add_argument("--failures", action="store_true", help="list every utterance not understood")
    parser.add_argument("--json", action="store_true", help="print one JSON document")
    parser.add_argument("--repeats", type=int, default=50, help="runs per timing (median)")
    args = parser.parse_args()
    data = tomllib.loads(args.data.read_text(encoding="utf-8"))
    base = world_context(data["world"])
    results = [judge(entry, base) for entry in data["u"]]
    by_group: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for r in results:
        by_group[r["group"]].append(r)
    report = {
        "groups": {g: shares(by_group[g]) for g in GROUPS},
        "overall": shares(results),
        "timing": timings(base, args.repeats),
    }
    ok = report["overall"]["wrong"] == 0 and all(
        s["understood_share"] >= BAR for s in [report["overall"], *report["groups"].values()])
    if args.json:
        print(json.dumps({**report, "ok": ok,
                          "failures": [r for r in results if r["verdict"] != "understood"]}, indent=2))
        return 0 if ok else 1
    print(f"{'group':<12}{'n':>5}{'understood':>12}{'wrong':>8}{'refused':>9}")
    for name, s in [*report["groups"].items(), ("overall", report["overall"])]:
        print(f"{name:<12}{s['n']:>5}{s['understood_share']:>11.1%}{s['wrong_share']:>8.1%}"
              f"{s['refused_share']:>9.1%}")
    t = report["timing"]
    for n in ("20", "200", "2000"):
        print(f"parse {t[n]['chars']:>5} chars: median {t[n]['ms']:.3f} ms wall, {t[n]['cpu_ms']:.3f} ms CPU "
              f"over {args.repeats} runs")
    print(f"t(2000)/t(200) = {t['ratio_2000_200']:.1f} wall, {t['cpu_ratio_2000_200']:.1f} CPU; "
          f"a 100 KB utterance: {t['100KB_ms']:.1f} ms; load average {t['load_average']:.1f}")
    print("bar (>= 90% understood overall and per group, 0 stored wrongly):", "met" if ok else "NOT met")
    if args.failures:
        for r in results:
            if r["verdict"] != "understood":
                print(f"\n[{r['verdict']}] {r['group']}: {r['say']!r}\n  expected {r['expect']}\n"
                      f"  got      {r['got']}\n  reply    {r['reply'][:200]}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
