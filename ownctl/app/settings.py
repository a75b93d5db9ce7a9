"""The settings a store keeps (`ownctl config`, `freeze`, `disable`): keys, validation, defaults.

Keys: ``threshold`` and ``threshold.ACTION`` (obedience thresholds in [0, 1]), ``trust`` (in [0, 1]),
``frozen.perms`` / ``frozen.rules`` and ``disabled.inference`` / ``disabled.prediction`` (booleans),
``learner`` (the rule learner: ``ours`` or ``paper``), ``decide.rules`` (decisions on the most
probable rule set, ``map``, or on P(forbidden) marginalised over the posterior of rule sets,
``posterior``, or on the mean over the rule sets within ``decide.window`` nats of the most
probable, ``window``), ``decide.window`` (that width, a non-negative number of nats),
``ask.min_gain`` (the expected mistakes a question must save before the robot asks it during a
run, a non-negative number), ``ask.kinds`` (the kinds of question the robot asks
during ``run --ask``: some of act, may, whose, rule), ``ask.temper`` (the power of the rule-set
posteriors questions are valued on, in (0, 1]), ``ask.read`` (whether questions are valued with
ownership read through the claim calibration the learner chose, a boolean) and ``ask.ahead`` (how
many of the best questions are valued again looking ahead to the permissions the instructor gives
the object being decided, a whole number, 0 for none), the last three for both ``run --ask`` and
``ownctl ask`` (docs/asking.md, section 4).
Stored values override the defaults of :class:`ownctl.config.Settings`.
"""

from __future__ import annotations

import math
from typing import Any

from ownctl.config import ASK_AHEAD as ASK_AHEAD  # the ask.* defaults have one home, the config
from ownctl.config import ASK_KINDS as ASK_KINDS
from ownctl.config import ASK_MIN_GAIN as ASK_MIN_GAIN
from ownctl.config import ASK_READ as ASK_READ
from ownctl.config import ASK_TEMPER as ASK_TEMPER
from ownctl.config import DECIDE_WINDOW, LearnConfig, Settings
from ownctl.errors import BadValue, OwnctlError
from ownctl.logic.vocab import ACTIONS

FLAGS = ("frozen.perms", "frozen.rules", "disabled.inference", "disabled.prediction")
PROBABILITIES = ("threshold", "trust", *(f"threshold.{a}" for a in ACTIONS))
LEARNERS = ("ours", "paper")
ASKING = ("ask.min_gain", "ask.kinds", "ask.temper", "ask.read", "ask.ahead")
KEYS = (*PROBABILITIES, *FLAGS, "learner", "decide.rules", "decide.window", *ASKING)
DEFAULTS: dict[str, Any] = {"threshold": Settings().threshold, "trust": Settings().trust,
                            "learner": Settings().learn.learner, "decide.rules": Settings().decide_rules,
                            "decide.window": DECIDE_WINDOW,
                            "ask.min_gain": ASK_MIN_GAIN, "ask.kinds": list(ASK_KINDS),
                            "ask.temper": ASK_TEMPER, "ask.read": ASK_READ, "ask.ahead": ASK_AHEAD}
TRUE = ("true", "yes", "on", "1")
FALSE = ("false", "no", "off", "0")


def check_key(key: str) -> str:
    """``key`` if it is a settings key; else an error listing the valid keys."""
    if key not in KEYS:
        raise OwnctlError(f"unknown setting {key!r}; valid keys: {', '.join(KEYS)}", KEYS)
    return key


def probability(what: str, value: float | str) -> float:
    """``value`` as a probability in [0, 1]; BadValue naming ``what`` for text, NaN or out-of-range."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise BadValue(f"{what} must be a number in [0, 1], got {value!r}") from None
    if math.isnan(number) or not 0.0 <= number <= 1.0:
        raise BadValue(f"{what} must be a number in [0, 1], got {value!r}")
    return number


def _non_negative(value: float | str, demand: str) -> float:
    """``value`` as a finite number of at least 0; BadValue "``demand``, got VALUE" otherwise."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise BadValue(f"{demand}, got {value!r}") from None
    if not math.isfinite(number) or number < 0:
        raise BadValue(f"{demand}, got {value!r}")
    return number


def min_gain(value: float | str) -> float:
    """``value`` as a non-negative number of mistakes; BadValue naming ask.min_gain otherwise."""
    return _non_negative(value, "ask.min_gain must be a non-negative number")


def temper(value: float | str) -> float:
    """``value`` as the power of the rule-set posteriors, in (0, 1]; BadValue naming ask.temper
    otherwise (the range is :func:`ownctl.mind.ask.check_temper`'s)."""
    from ownctl.mind.ask import check_temper

    try:
        number = float(value)
    except (TypeError, ValueError):
        raise BadValue(f"ask.temper must be a number in (0, 1], got {value!r}") from None
    if math.isnan(number):
        raise BadValue(f"ask.temper must be a number in (0, 1], got {value!r}")
    return check_temper(number)


def ahead(value: int | str) -> int:
    """``value`` as the number of questions valued with the look-ahead, a whole number of at least 0;
    BadValue naming ask.ahead otherwise (the range is :func:`ownctl.mind.ask.check_ahead`'s)."""
    from ownctl.mind.ask import check_ahead

    try:
        number = int(str(value).strip())
    except ValueError:
        raise BadValue(f"ask.ahead must be a whole number of at least 0 (0: no look-ahead), "
                       f"got {value!r}") from None
    return check_ahead(number)


def asking(stored: dict[str, Any]) -> tuple[float, tuple[str, ...], float, bool, int]:
    """(ask.min_gain, ask.kinds, ask.temper, ask.read, ask.ahead): the stored values, else the
    defaults."""
    return (float(stored.get("ask.min_gain", ASK_MIN_GAIN)), tuple(stored.get("ask.kinds", ASK_KINDS)),
            float(stored.get("ask.temper", ASK_TEMPER)), bool(stored.get("ask.read", ASK_READ)),
            int(stored.get("ask.ahead", ASK_AHEAD)))


def window(value: float | str) -> float:
    """``value`` as the width of the window of near-best rule sets, a finite number of nats of at
    least 0; BadValue naming it otherwise."""
    return _non_negative(value, "decide.window must be a number of nats of at least 0")


def parse_value(key: str, text: str) -> Any:
    """The typed value of ``text`` for ``key``; ``default`` means "remove the override" (None)."""
    check_key(key)
    if text == "default":
        return None
    if key == "decide.rules":
        from ownctl.mind.core import decide_mode  # the Mind's modules only when this key is set

        return decide_mode(text)
    if key == "decide.window":
        return window(text)
    if key == "ask.min_gain":
        return min_gain(text)
    if key == "ask.kinds":
        from ownctl.experiment.asking import parse_kinds

        return list(parse_kinds(text))
    if key == "ask.temper":
        return temper(text)
    if key == "ask.ahead":
        return ahead(text)
    if key == "learner":
        if text not in LEARNERS:
            raise BadValue(f"unknown learner {text!r}; valid learners: {', '.join(LEARNERS)}", LEARNERS)
        return text
    if key in (*FLAGS, "ask.read"):
        if text.lower() in TRUE:
            return True
        if text.lower() in FALSE:
            return False
        raise BadValue(f"{key} must be true or false, got {text!r}", ("true", "false"))
    return probability(key, text)


def effective(stored: dict[str, Any]) -> dict[str, Any]:
    """Every key with its value: stored, else default (per-action thresholds only when set)."""
    out: dict[str, Any] = {k: stored.get(k, DEFAULTS.get(k)) for k in
                           ("threshold", "trust", "learner", "decide.rules", "decide.window", *ASKING)}
    out.update({k: bool(stored.get(k, False)) for k in FLAGS})
    out.update({k: v for k, v in sorted(stored.items()) if k.startswith("threshold.")})
    return out


def to_config(stored: dict[str, Any]) -> Settings:
    """The core's :class:`Settings` from the stored keys."""
    thresholds = {k.split(".", 1)[1]: float(v) for k, v in stored.items() if k.startswith("threshold.")}
    return Settings(
        threshold=float(stored.get("threshold", DEFAULTS["threshold"])),
        thresholds=thresholds,
        trust=float(stored.get("trust", DEFAULTS["trust"])),
        learn=LearnConfig(learner=str(stored.get("learner", DEFAULTS["learner"]))),
        decide_rules=str(stored.get("decide.rules", DEFAULTS["decide.rules"])),
        decide_window=float(stored.get("decide.window", DEFAULTS["decide.window"])),
    )
