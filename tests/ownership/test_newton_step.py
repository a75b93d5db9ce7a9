"""The ownership fit's Newton step: an LU solve where the system is positive definite, the
least-squares (pseudo-inverse) step where a pivot is exactly zero."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from ownctl.ownership.predict import _newton_step


@given(st.integers(1, 40), st.integers(0, 2**32 - 1))
def test_a_positive_definite_step_is_the_least_squares_step(n: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, n))
    hess = a @ a.T + 1e-3 * np.eye(n)
    grad = rng.normal(size=n)
    want = np.linalg.lstsq(hess, grad, rcond=None)[0]
    assert np.allclose(_newton_step(hess, grad), want, rtol=1e-7, atol=1e-9)


def test_an_exactly_singular_system_takes_the_pseudo_inverse_step() -> None:
    hess = np.array([[1.0, 1.0], [1.0, 1.0]])  # LU meets a zero pivot
    grad = np.array([2.0, 2.0])
    assert np.allclose(_newton_step(hess, grad), [1.0, 1.0])  # the least-norm solution
