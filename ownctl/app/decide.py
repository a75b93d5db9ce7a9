"""``check ACTION OBJ``: is the action permitted on the object, and what decided it.

See ``docs/architecture.md`` for the vocabulary and the JSON shape.

Every step of the action (its prerequisites, then the action; ``Action.steps``) is decided on its
own: the object-specific permission for that step when there is one (forbidden iff its value is at
least 0.5), else the step's rules (forbidden iff P(some rule holds) >= the step's threshold).
Object-targeted steps are always checked; target-less ones (release, goHome, ...) only when they
have a permission or rules. The action is forbidden iff some step is; its ``p_forbidden`` is the
maximum over the steps. Probabilities use the decision beliefs (posteriors).

A check is also a turn of the conversation: it makes the object the current target and the action
the current action ("No, that's mine!" then refers to them), and a forbidden answer becomes the
last refusal ("Why not?").
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ownctl.app.beliefs import belief_sources
from ownctl.app.context import AppContext, use_case
from ownctl.app.mindstore import reading
from ownctl.humanize import plural
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import parse_rule
from ownctl.logic.vocab import ACTIONS
from ownctl.logic.vocab import action as check_action
from ownctl.mind import Mind


@dataclass(frozen=True)
class CheckReport:
    """The answer of ``check``; ``data`` has architecture section 7's shape, ``reason`` is for people."""

    data: dict[str, Any]
    reason: str

    @property
    def forbidden(self) -> bool:
        """True if the action is forbidden on the object."""
        return bool(self.data["decision"] == "forbidden")


def _step(mind: Mind, i: int, step: str, permission_id: int | None,
          rule_ids: dict[str, int]) -> dict[str, Any]:
    """One step of the decision on the Mind's object ``i``, as the report shows it."""
    frame = mind.frame_of([i])
    given = mind.permission(step, i)
    rules = mind.rules[step]
    per_rule = [{"id": rule_ids.get(r.text()), "text": r.text(), "p": float(p_forbidden([r], frame)[0])}
                for r in rules]
    p_rules = mind.p_rules(step, i)
    forbidden = mind.forbidden(step, i)
    sets = mind.deciding_sets(step)
    if given is not None:
        decided_by, p = "permission", float(given.value)
    elif rules or (sets is not None and p_rules > 0.0):
        decided_by, p = "rules", p_rules
    else:
        decided_by, p = "none", 0.0
    return {
        "action": step,
        "decision": "forbidden" if forbidden else "permitted",
        "decided_by": decided_by,
        "p_forbidden": p,
        "threshold": mind.settings.threshold_for(step),
        "permission": None if given is None else float(given.value),
        "permission_id": None if given is None else permission_id,
        "p_rules": p_rules,
        "rules": per_rule,
        "rule_support": _support(mind, i, step, decided_by, per_rule),
        "decide": mind.settings.decide_rules,
        "rule_sets": sets,
    }


#: Below this support a decision is said to rest on an uncertain rule.
SURE = 0.9


def _support(mind: Mind, i: int, step: str, decided_by: str, per_rule: list[dict[str, Any]]) -> float | None:
    """When a learned rule decides: how sure the posterior over rule sets is of what it says on object
    ``i`` (None when no rule decides, a stated norm decides, or the step has no examples)."""
    if decided_by != "rules" or not per_rule or not mind.perms[step]:
        return None
    rule = parse_rule(max(per_rule, key=lambda r: r["p"])["text"])
    if rule in mind.given(step):
        return None
    return mind.rule_support(step, rule, i)


def _reason(name: str, obj: str, step: dict[str, Any]) -> str:
    if step["decided_by"] == "permission":
        verb = "forbidden" if step["decision"] == "forbidden" else "allowed"
        return f"{step['action']} is {verb} on {obj} by permission {step['permission_id']}"
    if step["decided_by"] == "rules":
        op = ">=" if step["decision"] == "forbidden" else "<"
        top = max(step["rules"], key=lambda r: r["p"], default=None)
        strongest = "" if top is None else f" (strongest: rule {top['id']} '{top['text']}', p={top['p']:.3g})"
        return (f"the rules of {step['action']} forbid it with p={step['p_forbidden']:.3g} {op} "
                f"{step['threshold']:g}{rested(step)}{strongest}" + uncertain(step, obj))
    return f"no permission or rule speaks about {name} on {obj}"


def rested(step: dict[str, Any]) -> str:
    """What a rule decision rests on when not the learned rule set alone (``decide.rules``)."""
    sets = step.get("rule_sets")
    if sets is None:
        return ""
    if step.get("decide") == "window":
        return f", the mean over {plural(sets, 'near-best rule set')} (decide.rules window)"
    return f", marginalised over {plural(sets, 'rule set')} (decide.rules posterior)"


def uncertain(step: dict[str, Any], obj: str) -> str:
    """The warning that a decision rests on an uncertain rule ("" when it does not): the share of
    the posterior over rule sets that says what the deciding rule says of ``obj`` (its support on
    that object, which can be far below the rule's support on the examples that ``rules list``
    shows)."""
    support = step.get("rule_support")
    if support is None or support >= SURE:
        return ""
    return (f"; this rests on an uncertain rule: the posterior over rule sets says the same of "
            f"{obj} with p={support:.2f}")


def remember(ctx: AppContext, report: CheckReport) -> None:
    """Record a check in the conversation: current target and action, and a refusal if forbidden."""
    data = report.data
    turn: dict[str, Any] = {"target": data["object"], "action": data["action"]}
    if report.forbidden:
        steps = [s["action"] for s in data["steps"] if s["decision"] == "forbidden"]
        turn["refusal"] = {"action": data["action"], "object": data["object"], "steps": steps,
                           "reason": report.reason, "at": ctx.now}
    with ctx.write(None) as tx:
        tx.meta.converse(**turn)


@use_case
def check(ctx: AppContext, action: str, obj: str, record: bool = True) -> CheckReport:
    """Decide ``action`` on ``obj``; see the module docstring (``record``: remember it as a turn)."""
    act = check_action(action)
    with ctx.read() as tx:
        row = tx.things.object(obj)
        mind = reading(ctx, tx, only=[obj], permitted=True)  # the examples: rule posteriors
        i = mind.index[obj]
        settings = mind.settings
        beliefs, sources = mind.posterior_rows([i])[0], belief_sources(mind, i)
        permissions = {p.action: p.id for p in tx.knowledge.permissions(row.id)}
        rule_ids = {r.text: r.id for r in tx.knowledge.rules()}
        steps = []
        for name in act.steps:
            if ACTIONS[name].target != "object" and not mind.rules[name] and name not in permissions:
                continue
            steps.append(_step(mind, i, name, permissions.get(name), rule_ids))
    own = [s for s in steps if s["action"] == action]
    prereq = [s for s in steps if s["action"] != action]
    forbidden_prereq = [s for s in prereq if s["decision"] == "forbidden"]
    if own and own[0]["decision"] == "forbidden":
        decided_by, reason = own[0]["decided_by"], _reason(action, obj, own[0])
    elif forbidden_prereq:
        first = forbidden_prereq[0]
        decided_by = "prerequisite"
        reason = f"its prerequisite {first['action']} is forbidden: {_reason(first['action'], obj, first)}"
    else:
        speaking = [s for s in own + prereq if s["decided_by"] != "none"]
        decided_by = speaking[0]["decided_by"] if speaking else "none"
        reason = (
            _reason(action, obj, speaking[0]) if speaking else _reason(action, obj, {"decided_by": "none"})
        )
    decision = "forbidden" if (own and own[0]["decision"] == "forbidden") or forbidden_prereq else "permitted"
    data = {
        "action": action,
        "object": obj,
        "decision": decision,
        "p_forbidden": max((s["p_forbidden"] for s in steps), default=0.0),
        "threshold": settings.threshold_for(action),
        "decided_by": decided_by,
        "reason": reason,
        "steps": steps,
        "atoms": [
            {"agent": a, "p": float(beliefs[j]), "source": sources[j]} for j, a in enumerate(mind.agents)
        ],
    }
    report = CheckReport(data, reason)
    if record:
        remember(ctx, report)
    return report
