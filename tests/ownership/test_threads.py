"""The predictors' small systems run on one BLAS thread, larger ones keep the library's setting."""

from __future__ import annotations

import numpy as np
from threadpoolctl import threadpool_info, threadpool_limits

from ownctl.ownership.threads import SMALL, one_thread_below


def _blas_threads() -> list[int]:
    assert np.__name__ == "numpy"  # numpy loads its BLAS on import
    return [int(info["num_threads"]) for info in threadpool_info() if info["user_api"] == "blas"]


def test_a_small_system_runs_on_one_thread_and_the_setting_comes_back() -> None:
    with threadpool_limits(limits=2, user_api="blas"):
        before = _blas_threads()
        assert before and max(before) == 2  # numpy's BLAS is loaded
        with one_thread_below(SMALL - 1):
            assert _blas_threads() == [1] * len(before)
        assert _blas_threads() == before
        with one_thread_below(SMALL):  # large enough for threads to pay: left as it is
            assert _blas_threads() == before
