"""``explain ACTION OBJ`` (and "Why not?"): why an action is forbidden or permitted, in words.

Built on :func:`ownctl.app.decide.check` (which step decided, by which permission or rules, with
which probabilities) plus the store's provenance: who gave each permission and when, whether each
rule was given (by whom) or learned (from which examples), and where each ownership atom's number
comes from (a claim by whom and when, a percept-based prediction, the base rate, or rule-based
inference on top of one of those). For example::

    trash is forbidden on wallet: rule 3 'forbid trash if ownedBy agent1' holds with p=0.97
    (>= 0.5). ownedBy(wallet, agent1) = 0.97 from inference on a claim by agent1 at 1970-01-01T00:16:40+00:00
    (p=1).

Explaining is a question about a decision, not a decision: the conversation is left as it was.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ownctl.app.context import AppContext
from ownctl.app.decide import rested, uncertain
from ownctl.humanize import iso, plural
from ownctl.logic.rules import ANY, Literal, parse_rule

if TYPE_CHECKING:
    from ownctl.store.repo import Tx

SHOWN_AGENTS = 4  # at most this many atoms of an "ownedBy any" rule are spelled out


@dataclass(frozen=True)
class Explanation:
    """``text`` for people; ``data`` for ``--json`` (the check report plus provenance)."""

    text: str
    data: dict[str, Any]


def _when(time: float | None) -> str:
    return "" if time is None else f" at {iso(time)}"


def _rule_origin(row: Any) -> str:
    prov = row.provenance or {}
    if row.origin == "given":
        who = prov.get("speaker")
        special = ", specialised to the examples" if prov.get("specialised") else ""
        return f"given{' by ' + who if who else ''}{_when(row.created)}{special}"
    examples = prov.get("examples")
    if examples:
        return f"learned from the examples {', '.join(examples)}{_when(row.created)}"
    during = " during a task run" if prov.get("during") == "run" else ""
    return f"learned{during}{_when(row.created)}"


def _belief_origin(row: Any, claims: dict[int, int]) -> tuple[str, str]:
    """(what the number is based on, its source) for one ownership row (object, agent)."""
    if row.claim_p is not None:
        trust = f", trust {row.claim_trust:g}" if row.claim_trust not in (None, 1.0) else ""
        who = f" by {row.claim_speaker}" if row.claim_speaker else ""
        base = f"a claim{who}{_when(row.claim_time)} (p={row.claim_p:.2g}{trust})"
    elif row.prior_p is not None and row.prior_source == "prediction":
        n = claims.get(row.agent_id, 0)
        base = (f"a prediction from percepts (colour, position, recency; p={row.prior_p:.2g}, "
                f"from {plural(n, 'claim')} about this agent)")
    elif row.prior_p is not None:
        base = f"the base rate (too few claims about this agent to predict; p={row.prior_p:.2g})"
    else:
        base = "no information (p=0)"
    if row.posterior_p is not None:
        return f"inference (given the permissions on this object) on {base}", "inference"
    return base, "claim" if row.claim_p is not None else (row.prior_source or "none")


def _literal_value(lit: Literal, obj: Any, categories: set[str], own: dict[str, float],
                   areas: dict[str, Any]) -> str:
    """A literal's value on the object, as words (crisp facts) or a probability (ownership)."""
    if lit.pred == "ownedBy":
        if lit.arg == ANY:
            p_none = 1.0
            for p in own.values():
                p_none *= 1.0 - p
            p = 1.0 - p_none
        else:
            p = own.get(lit.arg, 0.0)
        return f"p={1.0 - p if lit.negated else p:.2g}"
    if lit.pred == "isColored":
        holds = obj.color == lit.arg
        fact = f"{obj.name} is {obj.color or 'of no known colour'}"
    elif lit.pred == "inArea":
        box = areas.get(lit.arg)
        holds = bool(box is not None and obj.x is not None and box.x0 <= obj.x <= box.x1
                     and box.y0 <= obj.y <= box.y1)
        fact = f"{obj.name} is {'in' if holds else 'outside'} area {lit.arg}"
    else:
        holds = lit.arg in categories
        fact = f"{obj.name} is {'' if holds else 'not '}in category {lit.arg}"
    return f"{'true' if holds != lit.negated else 'false'} ({fact})"


def _literals(rule: dict[str, Any]) -> str:
    """The literals' values, when they say more than the rule's probability already does."""
    lits = rule["literals"]
    if len(lits) == 1 and lits[0].startswith("ownedBy"):
        return ""
    return " [" + ", ".join(lits) + "]" if lits else ""


def _step_sentence(step: dict[str, Any], obj: str) -> str:
    action = step["action"]
    if step["decided_by"] == "permission":
        perm = step["permission_row"]
        verb = "forbids" if step["decision"] == "forbidden" else "allows"
        who = f" from {perm['speaker']}" if perm["speaker"] else ""
        return (f"permission {perm['id']} '{perm['text']}'{who}{_when(perm['time'])} {verb} {action} "
                f"on {obj} (value {perm['value']:g}; a permission outweighs the rules)")
    if step["decided_by"] == "rules":
        rules = sorted(step["rules"], key=lambda r: (-r["p"], r["id"]))
        op = ">=" if step["decision"] == "forbidden" else "<"
        if len(rules) == 1 and step.get("rule_sets") is None:
            r = rules[0]
            return (f"rule {r['id']} '{r['text']}' holds with p={r['p']:.2g} ({op} {step['threshold']:g})"
                    f"{_literals(r)}; it was {r['origin']}{uncertain(step, obj)}")
        each = "; ".join(f"rule {r['id']} '{r['text']}' p={r['p']:.2g}{_literals(r)} ({r['origin']})"
                         for r in rules)
        together = "together hold" if step.get("rule_sets") is None else "forbid it"
        listed = f": {each}" if each else "; the most probable rule set has no rule"
        return (f"the rules of {action} {together} with p={step['p_forbidden']:.2g} "
                f"({op} {step['threshold']:g}){rested(step)}{listed}{uncertain(step, obj)}")
    return f"no permission or rule speaks about {action} on {obj}"


def _sentences(data: dict[str, Any]) -> list[str]:
    obj, steps = data["object"], data["steps"]
    own = [s for s in steps if s["action"] == data["action"]]
    if data["decision"] == "forbidden":
        if own and own[0]["decision"] == "forbidden":
            return [_step_sentence(own[0], obj)]
        bad = [s for s in steps if s["decision"] == "forbidden"]
        return [f"its prerequisite {s['action']} is forbidden: {_step_sentence(s, obj)}" for s in bad]
    speaking = [s for s in steps if s["decided_by"] != "none"]
    if not speaking:
        return [f"no permission or rule speaks about {data['action']} or its steps on {obj}"]
    return [_step_sentence(s, obj) if s["action"] == data["action"]
            else f"its step {s['action']}: {_step_sentence(s, obj)}" for s in speaking]


def _relevant_agents(data: dict[str, Any], agents: list[str]) -> list[str]:
    """The agents whose atoms the deciding rules read (every agent for ``ownedBy any``)."""
    named: set[str] = set()
    for step in data["steps"]:
        if step["decided_by"] != "rules":
            continue
        for rule in step["rules"]:
            for lit in parse_rule(rule["text"]).literals:
                if lit.pred == "ownedBy":
                    named |= set(agents) if lit.arg == ANY else {lit.arg}
    return [a for a in agents if a in named]


def _atoms(tx: Tx, row: Any) -> list[dict[str, Any]]:
    """Every agent's ownership atom for the object: the decision belief and where it comes from."""
    from ownctl.app.beliefs import decision_belief

    agents = {a.id: a.name for a in tx.world.agents()}
    claims: dict[int, int] = {}
    for b in tx.beliefs.ownership():
        if b.claim_p is not None:
            claims[b.agent_id] = claims.get(b.agent_id, 0) + 1
    atoms: list[dict[str, Any]] = []
    for b in tx.beliefs.ownership(object_id=row.id):
        p, source = decision_belief(b)
        atoms.append({
            "agent": agents[b.agent_id], "p": p, "source": source, "because": _belief_origin(b, claims)[0],
            "claim": None if b.claim_p is None else {
                "p": b.claim_p, "speaker": b.claim_speaker, "time": b.claim_time, "trust": b.claim_trust},
            "prior": None if b.prior_p is None else {"p": b.prior_p, "source": b.prior_source},
            "posterior": None if b.posterior_p is None else {"p": b.posterior_p},
        })
    return atoms


def _steps(tx: Tx, row: Any, steps: list[dict[str, Any]], own: dict[str, float]) -> list[dict[str, Any]]:
    """The check's steps with each rule's origin and literal values, and each permission's row."""
    categories = tx.things.categories([row.id]).get(row.id, set())
    areas = {a.name: a for a in tx.world.areas()}
    rule_rows = {r.id: r for r in tx.knowledge.rules()}
    perms = {p.action: p for p in tx.knowledge.permissions(row.id)}
    out = []
    for step in steps:
        step = dict(step)
        step["rules"] = [
            {**r, "origin": _rule_origin(rule_rows[r["id"]]),
             "literals": [f"{lit.text()} {_literal_value(lit, row, categories, own, areas)}"
                          for lit in parse_rule(r["text"]).literals]}
            for r in step["rules"]
        ]
        perm = perms.get(step["action"])
        step["permission_row"] = None if perm is None else {
            "id": perm.id, "value": perm.value, "speaker": perm.speaker, "time": perm.time,
            "text": f"{'forbid' if perm.value >= 0.5 else 'allow'} {perm.action} on {row.name}"}
        out.append(step)
    return out


def last_refusal(ctx: AppContext) -> tuple[str, str]:
    """The (action, object) of the conversation's last refusal ("why not?"); an error if none."""
    from ownctl.language import MissingContext

    with ctx.read() as tx:
        refusal = tx.meta.conversation().refusal
    if not refusal:
        raise MissingContext(
            "why not what? nothing was refused yet; ask about an action "
            "(\"Why can't you throw this away?\") or run: ownctl explain ACTION OBJECT"
        )
    return refusal["action"], refusal["object"]


def explain(ctx: AppContext, action: str | None = None, obj: str | None = None) -> Explanation:
    """Why ``action`` is forbidden or permitted on ``obj`` (both omitted: the last refusal): the
    deciding permission or rules, and the ownership atoms they read with their provenance (see the
    module docstring)."""
    from ownctl.app.decide import check

    if action is None or obj is None:
        action, obj = last_refusal(ctx)

    data = dict(check(ctx, action, obj, record=False).data)
    with ctx.read() as tx:
        row = tx.things.object(obj)
        atoms = _atoms(tx, row)
        data["steps"] = _steps(tx, row, data["steps"], {a["agent"]: a["p"] for a in atoms})
    relevant = _relevant_agents(data, [a["agent"] for a in atoms])
    for atom in atoms:
        atom["relevant"] = atom["agent"] in relevant
    data["atoms"] = sorted(atoms, key=lambda a: (-a["p"], a["agent"]))
    sentences = _sentences(data)
    shown = [a for a in data["atoms"] if a["relevant"]][:SHOWN_AGENTS]
    facts = [f"ownedBy({obj}, {a['agent']}) = {a['p']:.2g} from {a['because']}" for a in shown]
    text = f"{action} is {data['decision']} on {obj}: " + "; ".join(sentences) + "."
    if facts:
        text += " " + ". ".join(facts) + "."
    data["text"] = text
    data["reasons"] = sentences + facts
    return Explanation(text, data)
