"""One BLAS thread for the predictors' small linear algebra (docs/architecture.md, section 10).

An agent's fit solves systems of the size of its claimed objects plus a few features: about 30
unknowns on the paper's 20-object world. A multi-threaded BLAS hands such a system to threads
that have gone to sleep between instructions, and waking them costs far more than the solve: on a
2-core machine whose cores ran other work, a profile of 60 claims on the paper's world found each
29 x 29 symmetric eigendecomposition taking 8 ms on two threads and 0.2 ms on one. Below
:data:`SMALL` unknowns the predictors therefore run on one thread; larger systems keep the BLAS
library's own setting, where threads pay for themselves.
"""

from __future__ import annotations

from contextlib import AbstractContextManager, nullcontext
from typing import Any

#: Systems with fewer unknowns than this are solved on one BLAS thread.
SMALL = 256

_controller: Any = None  # threadpoolctl's ThreadpoolController, made on first use (about 1 ms)


def one_thread_below(unknowns: int) -> AbstractContextManager[Any]:
    """A context in which BLAS uses one thread if a system has fewer than :data:`SMALL`
    ``unknowns`` (a no-op otherwise); entering and leaving it costs about 10 microseconds."""
    global _controller
    if unknowns >= SMALL:
        return nullcontext()
    if _controller is None:
        from threadpoolctl import ThreadpoolController

        _controller = ThreadpoolController()
    limited: AbstractContextManager[Any] = _controller.limit(limits=1, user_api="blas")
    return limited
