"""Student's t quantiles without SciPy agree with SciPy's."""

from __future__ import annotations

import pytest
from scipy.stats import t as scipy_t

from ownctl.experiment.student import t_cdf, t_quantile


@pytest.mark.parametrize("df", [1, 2, 3, 5, 9, 19, 29, 99, 199, 1000])
@pytest.mark.parametrize("p", [0.025, 0.3, 0.6, 0.9, 0.95, 0.975, 0.995, 0.9995])
def test_quantiles_match_scipy(df: int, p: float) -> None:
    assert t_quantile(p, df) == pytest.approx(scipy_t.ppf(p, df), abs=1e-9)
    assert t_cdf(t_quantile(p, df), df) == pytest.approx(p, abs=1e-12)


def test_bad_arguments_are_refused() -> None:
    with pytest.raises(ValueError):
        t_quantile(1.0, 3)
    with pytest.raises(ValueError):
        t_quantile(0.5, 0)
