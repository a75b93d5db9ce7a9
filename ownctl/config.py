"""Every tunable of the system with its default, as frozen dataclasses.

The core receives these objects explicitly; nothing reads the environment.
"""

from __future__ import annotations

from dataclasses import dataclass, field

#: How learned rules decide a step: on the most probable rule set, or marginalised over the
#: posterior over rule sets (docs/learning.md).
DECIDE_RULES = ("map", "posterior", "window")

#: The default width, in nats of log posterior, of the window of near-best rule sets that decide
#: under ``decide.rules = window`` (setting ``decide.window``; chosen on tuning norm families,
#: docs/norm-families.md).
DECIDE_WINDOW = 2.0

#: How the robot asks during a task, by default (docs/asking.md, section 4): the expected mistakes
#: a question must save before it is put (setting ``ask.min_gain``); the kinds of question asked
#: (``ask.kinds``: no rule questions, whose usual answer during a task, "partly", teaches nothing);
#: the power of the rule-set posteriors questions are valued on (``ask.temper``); whether
#: ownership is read as the learner reads it (``ask.read``); and how many of the best questions
#: are valued again looking ahead to the permissions the object being decided is given next
#: (``ask.ahead``, 0: none).
ASK_MIN_GAIN = 0.05
ASK_KINDS = ("act", "may", "whose")
ASK_TEMPER = 0.5
ASK_READ = True
ASK_AHEAD = 3


@dataclass(frozen=True)
class LearnConfig:
    """Rule induction settings (paper section "Learning ownership"; docs/architecture.md, section 4)."""

    accuracy_gate: float = 0.9  # induce only when soft accuracy on stored permissions drops below this
    beam: int = 3  # beam width of rule_search
    max_conditions: int = 4  # depth bound (the original code allowed one more by mistake)
    example_tolerance: float = 0.1  # fraction of the other class a learned rule may misclassify
    rule_tolerance: float = 0.1  # same, for given (one-shot) rules
    cover_threshold: float = 0.5  # a value counts as "forbid" at or above this
    learner: str = "ours"  # "paper" reproduces the paper's algorithm; "ours" adds re-induction


@dataclass(frozen=True)
class PredictConfig:
    """Per-agent kernel logistic regression on percepts (docs/architecture.md, section 5).

    Position and log-recency are standardised over the known objects before weighting, so the
    weights and the kernel width are in units of their spread (tuned on Table 2, see
    ``ownctl.experiment.ownership``).
    """

    color_weight: float = 0.25  # colour mismatch adds color_weight**2 to the squared distance
    position_weight: float = 1.0  # per unit of the objects' position spread (RMS distance from their mean)
    recency_weight: float = 1.0  # per unit of spread of log1p(seconds since the agent last touched it)
    gamma: float = 0.3  # RBF kernel width: k = exp(-gamma * squared distance)
    C: float = 10.0  # inverse regularisation of the kernel and linear parts
    intercept_scale: float = 1.0  # prior std (logits) of the intercept around logit(base_rate)
    min_claims: int = 1  # below this, the calibrated prior is used
    base_rate: float = 0.25  # prior ownership of an agent without claims (never 0.5)
    share_recency: bool = True  # an agent no claim says owns anything borrows recency from the others
    share_step: float = 0.25  # the borrowed recency slope is rounded to a multiple of this (logits)
    recalibrate_min: int = 6  # from this many claims, the logits are rescaled on their leave-one-out fit
    recalibrate_scale: float = 1.0  # prior std of that rescaling's slope (around 1) and intercept (around 0)
    scales: tuple[float, ...] = (1.0, 0.1, 0.01)  # multipliers of C: how far percepts may move predictions
    scale_bonus: float = 2.0  # log prior odds (nats) of the first scale over each other one
    # what an agent's silence about a claimed object says (ownctl/ownership/silence.py): the weight
    # kappa is rounded down to a multiple of silence_step and kept at most silence_max (0: off)
    silence_step: float = 0.2
    silence_max: float = 0.8
    # the width of every agent's intercept prior (ownctl/ownership/household.py): the most probable
    # of household_spreads times intercept_scale given every agent's claims, with a log prior of
    # household_bonus (nats) for the first (one value: always the configured width)
    household_spreads: tuple[float, ...] = (1.0, 0.5, 0.2)
    household_bonus: float = 0.0


@dataclass(frozen=True)
class InferConfig:
    """Rule-based Bayesian inference of ownership (docs/architecture.md, section 3)."""

    noise: float = 0.05  # probability an instructor's permission is not explained by the rules


@dataclass(frozen=True)
class Settings:
    """Thresholds and switches that a store keeps and `ownctl config` edits."""

    threshold: float = 0.5
    thresholds: dict[str, float] = field(default_factory=dict)
    trust: float = 1.0
    learn: LearnConfig = field(default_factory=LearnConfig)
    predict: PredictConfig = field(default_factory=PredictConfig)
    infer: InferConfig = field(default_factory=InferConfig)
    decide_rules: str = "map"  # one of DECIDE_RULES
    decide_window: float = DECIDE_WINDOW  # nats, for decide_rules = "window"

    def threshold_for(self, action: str) -> float:
        """The obedience threshold of ``action`` (per-action override, else the default)."""
        return self.thresholds.get(action, self.threshold)
