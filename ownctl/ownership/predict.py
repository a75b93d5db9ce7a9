"""Percept-based ownership prediction: per-agent kernel logistic regression on soft labels.

:class:`KernelOwnershipModel` is a scikit-learn-style estimator: ``__init__`` stores settings,
``fit(X, p)`` learns from feature rows ``X`` and claim probabilities ``p`` and returns self,
``predict_proba(X)`` gives P(owned). The model is

    f(x) = b + sum_i alpha_i k(x, x_i) + w . x,        P(owned | x) = sigmoid(f(x)),

an exact kernel expansion over the claimed objects (RBF kernel) plus a linear part, so it can
extrapolate (for example in log-recency) away from the claimed objects. It is fitted by Newton's
method on the soft cross-entropy (a claim of 0.7 is a soft target, exactly as if it were one
"owned" example of weight 0.7 and one "not owned" of weight 0.3) with a maximum-a-posteriori
penalty: RKHS norm ``alpha' K alpha / C``, ``|w|^2 / C``, and a Gaussian prior on the intercept
centred on the base rate's logit. That prior makes the model calibrated with few claims, or with
claims all on one side: far from every claim it predicts about the base rate, never exactly 0.5.
With fewer than ``min_claims`` claims it is the calibrated prior itself.

**Recalibration on held-out claims.** The penalties that keep the model sane with few claims also
make it underconfident once it has many: on Table 2's held-out objects its predictions far from an
owner's objects were about 0.03 where none was owned, and about 0.96 where all were. From
``recalibrate_min`` claims on, the fitted logit ``f`` is replaced by ``a f + b``, the logistic
regression of the claims on their leave-one-out logits (Platt scaling on held-out predictions),
with a Gaussian prior of std ``recalibrate_scale`` on ``a`` around 1 and ``b`` around 0: what the
model predicts for an object it has not been told about is then as sharp as its predictions for
claimed objects, each left out in turn, turned out to deserve. The leave-one-out logits are the
closed-form one-step approximation at the fitted optimum (:func:`loo_logits`), one linear solve
instead of a refit per claim (docs/architecture.md, section 5).

**What other agents' claims teach.** An agent that no claim says owns anything cannot learn from
its own claims what its objects look like: they only say what it does not own. How recently an
agent touched an object is read the same way for every agent, so such an agent *borrows* it from
the agents some claim says own something: :func:`fit_shared_recency` fits one logistic regression
of their claims on their log-recency (:class:`SharedRecency`), and the agent's model adds its
recency term, given as an ``offset`` per row, to its own (kernel, linear part and intercept,
which correct it). How often
the agent owns things stays its own: the intercept keeps its prior on the base rate, and without
claims the prediction is the base rate moved by the borrowed term alone (docs/architecture.md,
section 5).

**How far percepts reach.** ``C`` lets percepts move a prediction a long way, as they do in the
paper's world. Where they say nothing of who owns what, a few claims then read as patterns that
are not there. Each agent's model is fitted at every multiple of ``C`` in ``cfg.scales``
(:func:`fit_scales`), its Laplace evidence (:func:`log_evidence`) says how well each explains the
agent's claims, and every agent uses the scale most probable given all agents' claims
(:func:`pooled_scale`; docs/architecture.md, section 5).

Newton's method on these small problems (one row per claimed object) is exact and takes
milliseconds, unlike a general-purpose solver.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ownctl.config import PredictConfig
from ownctl.logic.kept import Kept
from ownctl.ownership.household import Household
from ownctl.ownership.link import logit, sigmoid
from ownctl.ownership.silence import silent_curvature, silent_loss, silent_target
from ownctl.ownership.threads import one_thread_below

MAX_NEWTON = 50
TOLERANCE = 1e-10
#: Raised whenever what the predictor computes from the same claims and percepts changes (2: the
#: recalibration on claims left out; 3: the scale pooled over agents; 4: silence weighed; 5: the
#: household's prior of the intercept, no rescaling below the full scale). A store
#: whose priors another version wrote refits them on its next load (ownctl/app/mindstore.py), so a
#: store keeps meaning what a Mind told the same things would believe.
PREDICTOR_VERSION = 5


def rbf_kernel(A: np.ndarray, B: np.ndarray, gamma: float) -> np.ndarray:
    """exp(-gamma |a - b|^2) for every pair of rows (len(A), len(B))."""
    d2 = ((A[:, None, :] - B[None, :, :]) ** 2).sum(axis=-1)
    out: np.ndarray = np.exp(-gamma * d2)
    return out


def _off_half(value: float) -> float:
    return value if abs(value - 0.5) > 1e-3 else 0.5 - 1e-3


def calibrated_base_rate(cfg: PredictConfig | None = None) -> float:
    """The prior of an agent without claims: what a model fitted on no claims predicts everywhere."""
    return KernelOwnershipModel(cfg).prior_(np.zeros(0))


class KernelOwnershipModel:
    """Kernel logistic regression of P(ownedBy(object, agent)) on one agent's percept features."""

    def __init__(self, cfg: PredictConfig | None = None) -> None:
        self.cfg = cfg or PredictConfig()

    def prior_(self, p: np.ndarray) -> float:
        """Calibrated prior: claims shrunk towards the base rate (4 pseudo-claims), off the 0.5 line."""
        pseudo = 4.0
        return _off_half((float(np.sum(p)) + pseudo * self.cfg.base_rate) / (len(p) + pseudo))

    def fit(self, X: np.ndarray, p: np.ndarray, offset: np.ndarray | None = None,
            scale: float = 1.0, kernel: np.ndarray | None = None, kappa: float = 0.0,
            household: Household | None = None) -> KernelOwnershipModel:
        """Fit on feature rows ``X`` (n, d) and soft targets ``p`` (n,) in [0, 1]; returns self.
        ``offset`` (n,): a borrowed logit term per row (:meth:`SharedRecency.term`) added to the
        model's own; pass the same rule's offset to :meth:`predict_proba`. ``scale`` multiplies
        the prior variance of the kernel and linear parts (``C``): how far percepts may move a
        prediction (:func:`fit_scales`). :attr:`evidence_` is the log marginal likelihood of the
        claims under that prior (0 without claims). ``kernel``: the RBF kernel of ``X`` with itself,
        when the caller has it. A row whose target is NaN is the agent's silence about an object
        others made claims about, weighed by ``kappa`` (:mod:`ownctl.ownership.silence`; dropped
        when ``kappa`` is 0). ``household``: the intercept's prior (:mod:`ownctl.ownership.household`;
        None: the configured base rate and ``intercept_scale``)."""
        X = np.asarray(X, dtype=float).reshape(len(p), -1) if len(p) else np.zeros((0, 0))
        p = np.clip(np.asarray(p, dtype=float).reshape(len(X)), 0.0, 1.0)
        silent = np.isnan(p)
        if kappa <= 0 and silent.any():
            X, p = X[~silent], p[~silent]
            kernel = None if kernel is None else kernel[np.ix_(~silent, ~silent)]
            offset = None if offset is None else np.asarray(offset, dtype=float).reshape(-1)[~silent]
            silent = silent[~silent]
        self.base_ = self.prior_(p[~silent])
        self.n_claims_ = int((~silent).sum())
        self.kappa_ = float(kappa) if silent.any() else 0.0
        self.offset_ = offset is not None
        self.scale_ = scale
        self.evidence_ = 0.0
        self.recalibration_: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None
        self.__dict__.pop("rescale_", None)  # a previous fit's rescaling
        self.trained_ = len(p) >= max(self.cfg.min_claims, 1)
        if not self.trained_:
            return self
        cfg = self.cfg
        K = rbf_kernel(X, X, cfg.gamma) if kernel is None else kernel
        design, penalty, mean = _system(X, cfg, scale, K, household)
        shift = np.zeros(len(p)) if offset is None else np.asarray(offset, dtype=float).reshape(len(p))
        with one_thread_below(design.shape[1]):
            self.coef_ = _newton(design, p, penalty, mean, shift, self.kappa_)
            self.evidence_ = log_evidence(X, p, cfg, scale, design @ self.coef_ + shift,
                                          _prior_term(self.coef_, penalty, mean), K, self.kappa_, household)
        self.support_ = X
        if self.n_claims_ >= cfg.recalibrate_min and scale >= max(cfg.scales):
            self.recalibration_ = (design, p, penalty, shift)
        return self

    @cached_property
    def rescale_(self) -> tuple[float, float]:
        """``(a, b)``, the rescaling of the fitted logits on the claims left out (:func:`rescaling`),
        or (1, 0) below ``recalibrate_min`` claims or below the full scale: the rescaling corrects
        what the penalties do to a model whose percepts reach far; at a smaller scale the claims
        said that percepts tell little, the logits hardly vary, and a rescaling would only fit an
        intercept again on one agent's claims, undoing its prior (ownctl/ownership/household.py).
        Computed when first needed: of the models :func:`fit_scales` fits, only the one the
        predictors use predicts."""
        if self.recalibration_ is None:
            return 1.0, 0.0
        design, p, penalty, shift = self.recalibration_
        claimed = ~np.isnan(p)
        with one_thread_below(design.shape[1]):
            logits = loo_logits(design, p, penalty, self.coef_, shift, self.kappa_)[claimed]
            return rescaling(logits, p[claimed], self.cfg.recalibrate_scale)

    def decision_function(self, X: np.ndarray, offset: np.ndarray | None = None) -> np.ndarray:
        """The logit for each row of ``X`` (n,): ``a (f(x) + offset) + b``, with ``offset`` (n,) for a
        model fitted with one and ``(a, b)`` its rescaling (:attr:`rescale_`; (1, 0) below
        ``recalibrate_min`` claims)."""
        X = np.asarray(X, dtype=float)
        design = np.hstack([rbf_kernel(X, self.support_, self.cfg.gamma), X, np.ones((len(X), 1))])
        slope, intercept = self.rescale_
        out: np.ndarray = slope * (design @ self.coef_ + self._offset(offset, len(X))) + intercept
        return out

    def predict_proba(self, X: np.ndarray, offset: np.ndarray | None = None) -> np.ndarray:
        """P(owned) for each row of ``X`` (n,), never exactly 0.5 (``offset`` as given to :meth:`fit`;
        an untrained model fitted with one predicts its base rate moved by the offset)."""
        X = np.asarray(X, dtype=float)
        if not self.trained_:
            if offset is None:
                return np.full(len(X), self.base_)
            out = sigmoid(logit(self.base_) + self._offset(offset, len(X)))
        else:
            out = sigmoid(self.decision_function(X, offset))
        return np.where(np.abs(out - 0.5) > 1e-6, out, 0.5 - 1e-6)

    def _offset(self, offset: np.ndarray | None, n: int) -> np.ndarray:
        if (offset is not None) != self.offset_:
            raise ValueError("predict with an offset exactly when the model was fitted with one")
        return np.zeros(n) if offset is None else np.asarray(offset, dtype=float).reshape(n)

    @property
    def source_(self) -> str:
        """Where predictions come from: ``prediction`` (trained, or borrowed from the other agents'
        claims) or ``base-rate`` (calibrated prior)."""
        return "prediction" if self.trained_ or self.offset_ else "base-rate"


@dataclass(frozen=True)
class SharedRecency:
    """What the other agents' claims teach about recency: P(owned) = sigmoid(intercept + slope * r)
    for an object the agent touched at (weighted, standardised) log-recency ``r``. A borrower takes
    the recency term (:meth:`term`); the intercept, how often those agents own things, stays theirs."""

    slope: float
    intercept: float

    def term(self, recency: np.ndarray) -> np.ndarray:
        """The borrowed logit term of each row's recency, ``slope * r``."""
        out: np.ndarray = self.slope * np.asarray(recency, dtype=float)
        return out


def borrows(p: np.ndarray) -> bool:
    """Whether an agent with claims ``p`` borrows recency from the others: no claim says it owns
    anything (every claim below 1/2, or none)."""
    return not bool(owns_some(np.reshape(np.asarray(p, dtype=float), (-1, 1)))[0])


def owns_some(claims: np.ndarray) -> np.ndarray:
    """(m,) for claims (n, m) with NaN where none: whether some claim of each column says its agent
    owns something (the lenders; the others borrow, :func:`borrows`)."""
    with np.errstate(invalid="ignore"):  # NaN (no claim) compares False
        held = np.asarray(claims, dtype=float) >= 0.5
    return np.asarray(held.any(axis=0), dtype=bool)


def fit_shared_recency(recency: np.ndarray, p: np.ndarray,
                       cfg: PredictConfig | None = None) -> SharedRecency | None:
    """The logistic regression of claims ``p`` on their agents' recency ``recency`` (one entry per
    claimed (object, agent) pair), with the per-agent model's priors on its linear part and
    intercept, the slope rounded to a multiple of ``cfg.share_step`` (:func:`rounded`); None when
    no claim says an agent owns something (then it teaches nothing of what owning looks like)."""
    cfg = cfg or PredictConfig()
    r = np.asarray(recency, dtype=float).reshape(-1)
    y = np.clip(np.asarray(p, dtype=float).reshape(len(r)), 0.0, 1.0)
    if borrows(y):
        return None
    design = np.stack([r, np.ones(len(r))], axis=1)
    penalty = np.diag([1.0 / cfg.C, 1.0 / cfg.intercept_scale**2])
    mean = np.array([0.0, logit(cfg.base_rate)])
    slope, intercept = _newton(design, y, penalty, mean, np.zeros(len(r)))
    return SharedRecency(rounded(float(slope), cfg.share_step), float(intercept))


def rounded(slope: float, step: float) -> float:
    """``slope`` to the nearest multiple of ``step`` (``step`` 0: as it is). A borrower's
    predictions then move only when the lenders' claims move the slope by a visible amount, so
    a claim in a large store rewrites the borrowers' priors only now and then (docs/architecture.md,
    section 5)."""
    return float(np.round(slope / step) * step) if step > 0 else slope


def fit_scales(X: np.ndarray, p: np.ndarray, offset: np.ndarray | None = None,
               cfg: PredictConfig | None = None, kappa: float = 0.0,
               household: Household | None = None) -> list[KernelOwnershipModel]:
    """One agent's model fitted at each of ``cfg.scales`` (their :attr:`evidence_` says how well
    each prior explains the claims; :func:`pooled_scale` picks one for every agent); rows whose
    target is NaN are silences weighed by ``kappa``, ``household`` the intercept's prior
    (:meth:`KernelOwnershipModel.fit`).

    A pure function of its arguments' contents, so its models are kept by content and shared,
    read-only (:data:`FITS`): valuing a question teaches its answers to many what-if Minds, and
    most of their agents' predictors are fitted on claims some other Mind fitted them on already
    (on a six-agent store, 282 distinct fits of 2,664 for one ``ownctl ask``)."""
    cfg = cfg or PredictConfig()
    X = np.asarray(X, dtype=float)
    targets = np.asarray(p, dtype=float)
    shift = None if offset is None else np.asarray(offset, dtype=float)
    key = (X.shape, X.tobytes(), targets.shape, targets.tobytes(),
           None if shift is None else (shift.shape, shift.tobytes()), cfg, float(kappa), household)
    hit = _fits.get(key)
    if hit is None:
        X = X.copy()  # the models keep it, read-only
        K = rbf_kernel(X, X, cfg.gamma) if len(targets) else None
        models = tuple(KernelOwnershipModel(cfg).fit(X, targets, shift, scale, K, kappa, household)
                       for scale in cfg.scales)
        for array in _arrays(models):
            array.setflags(write=False)
        hit = _fits.put(key, models)
    return list(hit)


def _arrays(models: Sequence[KernelOwnershipModel]) -> list[np.ndarray]:
    """The arrays fitted models hold: coefficients, support rows, the recalibration's system."""
    out = []
    for model in models:
        for array in (getattr(model, "coef_", None), getattr(model, "support_", None),
                      *(model.recalibration_ or ())):
            if isinstance(array, np.ndarray):
                out.append(array)
    return out


def _fit_bytes(models: tuple[KernelOwnershipModel, ...]) -> int:
    """The memory a kept fit holds: its models' arrays (the recalibration's system the largest)."""
    return sum(a.nbytes for a in _arrays(models))


#: Fits kept by content, least recently used dropped first, at most 128 MiB of them: a fit on a
#: few hundred claims holds a few MB (its leave-one-out system), one on the paper's 20 objects a
#: few kB.
FITS = 1024
_fits: Kept[tuple[KernelOwnershipModel, ...]] = Kept(FITS, budget=128 << 20, weigh=_fit_bytes)


def pooled_scale(evidence: Iterable[Sequence[float]], cfg: PredictConfig | None = None) -> int:
    """The index into ``cfg.scales`` that every agent's predictor uses: the most probable scale
    given every agent's claims, its log prior ``cfg.scale_bonus`` for the first (percepts predict
    ownership, the paper's premise) and 0 for the others, plus the sum of the agents' log
    evidence at each scale (one entry per scale and agent; an agent without claims adds 0). The
    first of equals wins.

    How far percepts predict ownership is a property of the household, not of one agent: a scale
    chosen on one agent's few claims follows chance patterns, a scale chosen on all agents' claims
    tells a world where position and recency say who owns what (the paper's) from one where they
    say nothing (docs/architecture.md, section 5)."""
    cfg = cfg or PredictConfig()
    total = np.zeros(len(cfg.scales))
    total[0] = cfg.scale_bonus
    for row in evidence:
        total += np.asarray(row, dtype=float)
    return int(np.flatnonzero(total >= total.max() - 1e-9)[0])


def log_evidence(X: np.ndarray, p: np.ndarray, cfg: PredictConfig, scale: float, f: np.ndarray,
                 prior_term: float, kernel: np.ndarray | None = None, kappa: float = 0.0,
                 household: Household | None = None) -> float:
    """The Laplace approximation of log p(claims | scale) at the fit's logits ``f`` of the claimed
    rows ``X``: the soft log-likelihood, minus the prior term ``prior_term`` (half the penalty at
    the fit), minus half the log determinant of ``I + W^1/2 S W^1/2``, with ``S`` the prior
    covariance of the logits (``scale C (K + X X') + spread^2``, the intercept's prior std from
    ``household``, default ``intercept_scale``) and ``W`` the logistic
    curvature at ``f`` (Rasmussen and Williams, Gaussian Processes for Machine Learning, 3.4.4).
    ``kernel``: the RBF kernel of ``X`` with itself, when the caller has it. Rows whose target is
    NaN are silences weighed by ``kappa`` (their curvature where convex)."""
    n = len(p)
    K = rbf_kernel(X, X, cfg.gamma) if kernel is None else kernel
    spread = (household or Household.configured(cfg)).spread
    cov = scale * cfg.C * (K + X @ X.T) + spread**2
    s = sigmoid(f)
    root = np.sqrt(_curvature(s, p, kappa))
    chol = np.linalg.cholesky(np.eye(n) + root[:, None] * cov * root[None, :])
    return -_loss(f, p, kappa) - prior_term - float(np.sum(np.log(np.diag(chol))))


def _prior_term(theta: np.ndarray, penalty: np.ndarray, mean: np.ndarray) -> float:
    diff = theta - mean
    return float(0.5 * diff @ penalty @ diff)


def _soft_loss(f: np.ndarray, p: np.ndarray) -> float:
    """The soft cross-entropy of targets ``p`` under logits ``f``, summed."""
    return float(np.sum(np.logaddexp(0.0, -f) * p + np.logaddexp(0.0, f) * (1.0 - p)))


def _loss(f: np.ndarray, p: np.ndarray, kappa: float) -> float:
    """:func:`_soft_loss` of the rows with a target, plus the silent rows' (NaN target) loss."""
    silent = np.isnan(p)
    if not silent.any():
        return _soft_loss(f, p)
    return _soft_loss(f[~silent], p[~silent]) + silent_loss(f[silent], kappa)


def _residual(s: np.ndarray, p: np.ndarray, kappa: float) -> np.ndarray:
    """The loss's gradient in each row's logit: ``s - p``, ``s - q`` for a silent row."""
    silent = np.isnan(p)
    target = np.where(silent, silent_target(s, kappa), p) if silent.any() else p
    out: np.ndarray = s - target
    return out


def _curvature(s: np.ndarray, p: np.ndarray, kappa: float) -> np.ndarray:
    """The loss's second derivative in each row's logit: ``s (1 - s)``, a silent row's where convex."""
    silent = np.isnan(p)
    if not silent.any():
        return s * (1.0 - s)
    out: np.ndarray = np.where(silent, silent_curvature(s, kappa), s * (1.0 - s))
    return out


def _system(X: np.ndarray, cfg: PredictConfig, scale: float = 1.0, kernel: np.ndarray | None = None,
            household: Household | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The fit's design ``[K, X, 1]`` over the claimed rows ``X`` (``kernel``: ``K``, when the
    caller has it), its penalty (RKHS norm and ``|w|^2`` over ``scale * C``, the intercept's prior
    precision) and the prior mean of the coefficients (``household``: the intercept's prior,
    default the configured one)."""
    intercept = household or Household.configured(cfg)
    n, d = X.shape
    K = rbf_kernel(X, X, cfg.gamma) if kernel is None else kernel
    design = np.hstack([K, X, np.ones((n, 1))])
    m = design.shape[1]
    penalty = np.zeros((m, m))
    penalty[:n, :n] = K / (scale * cfg.C)
    penalty[n : n + d, n : n + d] = np.eye(d) / (scale * cfg.C)
    penalty[-1, -1] = 1.0 / intercept.spread**2
    mean = np.zeros(m)
    mean[-1] = intercept.mean
    return design, penalty, mean


def loo_logits(design: np.ndarray, p: np.ndarray, penalty: np.ndarray, theta: np.ndarray,
               offset: np.ndarray, kappa: float = 0.0) -> np.ndarray:
    """(n,) the logit of each row under the fit without it, by one Newton step from the fit
    ``theta`` of all rows (the minimiser of :func:`_newton`'s objective): with ``H`` the
    objective's Hessian at ``theta``, ``w_i = s_i (1 - s_i)`` and ``q_i = d_i' H^-1 d_i``,
    leaving row ``i`` out moves its logit by ``(s_i - p_i) q_i / (1 - w_i q_i)`` (the
    Sherman-Morrison update of ``H`` without row ``i``). Exact for a quadratic objective, and
    close to a refit for logistic ones (tests/ownership/test_ownership_recalibrate.py)."""
    f = design @ theta + offset
    s = sigmoid(f)
    w = _curvature(s, p, kappa)
    hess = design.T @ (design * w[:, None]) + penalty + 1e-9 * np.eye(len(theta))
    # d_i' H^+ d_i from one symmetric eigendecomposition (H's pseudo-inverse, as a least-squares
    # solve takes it: eigenvalues below its relative cut-off count as 0)
    values, vectors = np.linalg.eigh(hess)
    keep = values > values.max() * np.finfo(float).eps * len(values)
    q = np.sum((design @ vectors[:, keep]) ** 2 / values[keep], axis=1)
    out: np.ndarray = f + _residual(s, p, kappa) * q / np.maximum(1.0 - w * q, 1e-12)
    return out


def rescaling(logits: np.ndarray, p: np.ndarray, scale: float) -> tuple[float, float]:
    """``(a, b)``: the logistic regression of soft targets ``p`` on ``a logits + b`` (Platt
    scaling) with a Gaussian prior of std ``scale`` on ``a - 1`` and ``b``. The identity (1, 0)
    when the targets do not vary (nothing to tell sharp from flat) or when the fitted slope is not
    positive: held-out logits that order the claims no better than chance (identical objects
    claimed both ways) say nothing about how sharp the model should be, and a rescaling must keep
    the model's order of the objects."""
    y = np.clip(np.asarray(p, dtype=float), 0.0, 1.0)
    if np.ptp(y) < 1e-12:
        return 1.0, 0.0
    design = np.stack([np.asarray(logits, dtype=float), np.ones(len(y))], axis=1)
    a, b = _newton(design, y, np.eye(2) / scale**2, np.array([1.0, 0.0]), np.zeros(len(y)))
    return (float(a), float(b)) if a > 0 else (1.0, 0.0)


def _newton_step(hess: np.ndarray, grad: np.ndarray) -> np.ndarray:
    """``H^-1 g`` for the Newton step. ``H`` is the loss's curvature plus the prior's penalty and a
    1e-9 ridge, so it is positive definite and an LU solve is exact (about 13 microseconds on the
    paper's world against 110 for a least-squares solve); a pivot that is exactly zero falls back
    to the least-squares (pseudo-inverse) step."""
    try:
        step: np.ndarray = np.linalg.solve(hess, grad)
    except np.linalg.LinAlgError:
        step = np.linalg.lstsq(hess, grad, rcond=None)[0]
    return step


def _newton(design: np.ndarray, p: np.ndarray, penalty: np.ndarray, mean: np.ndarray,
            offset: np.ndarray, kappa: float = 0.0) -> np.ndarray:
    """Minimise soft cross-entropy of sigmoid(design t + offset) + 0.5 (t - mean)' P (t - mean) by
    damped Newton steps (rows whose target is NaN: the silence loss weighed by ``kappa``, with its
    curvature where convex; the line search keeps every step downhill)."""

    def objective(theta: np.ndarray) -> float:
        return _loss(design @ theta + offset, p, kappa) + _prior_term(theta, penalty, mean)

    theta = mean.copy()
    current = objective(theta)
    ridge = 1e-9 * np.eye(len(theta))
    for _ in range(MAX_NEWTON):
        s = sigmoid(design @ theta + offset)
        grad = design.T @ _residual(s, p, kappa) + penalty @ (theta - mean)
        hess = design.T @ (design * _curvature(s, p, kappa)[:, None]) + penalty + ridge
        step = _newton_step(hess, grad)
        t = 1.0
        new = objective(theta - step)
        while new > current + 1e-12 and t > 1e-4:
            t /= 2
            new = objective(theta - t * step)
        if new > current + 1e-12:
            break
        theta = theta - t * step
        done = current - new < TOLERANCE
        current = new
        if done:
            break
    return theta
