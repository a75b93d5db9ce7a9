"""Where an experiment's trials run: this process, local worker processes, or a Dask cluster.

The runner hands chunks of trials to a :class:`concurrent.futures.Executor`; which one is the only
thing that differs between ``--jobs N`` (a local process pool) and ``--scheduler ADDRESS`` (the
workers of a running ``dask.distributed`` scheduler, through its ``concurrent.futures`` executor).
Trials carry their own seeds (docs/architecture.md, section 8), so every backend gives the same
numbers. Dask is imported only when a scheduler is named; its workers need the same version of
ownctl importable.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from concurrent.futures import Executor, ProcessPoolExecutor
from contextlib import contextmanager
from typing import Any

from ownctl.errors import BadValue, OwnctlError

#: seconds to wait for the scheduler to answer before giving up
CONNECT_TIMEOUT = 10.0
INSTALL_HINT = "pip install 'ownctl[cluster]' (or: pip install 'dask[distributed]')"


@contextmanager
def executor(jobs: int, scheduler: str | None = None,
             timeout: float | None = None) -> Iterator[tuple[Executor, int]]:
    """An executor for trial chunks and how many run at once: ``jobs`` local processes, or, with
    ``scheduler`` (``tcp://host:8786``), the threads of that Dask cluster's workers.

    A missing dask, or a scheduler that does not answer within ``timeout`` seconds (default
    :data:`CONNECT_TIMEOUT`), is an :class:`~ownctl.errors.OwnctlError` of one line.
    """
    if scheduler is None:
        with ProcessPoolExecutor(max_workers=jobs, initializer=share_cores, initargs=(jobs,)) as pool:
            yield pool, jobs
        return
    with _dask(scheduler, CONNECT_TIMEOUT if timeout is None else timeout) as (pool, slots):
        yield pool, slots


def share_cores(jobs: int) -> None:
    """Start of a local worker: the threads of its linear algebra (BLAS, OpenMP) limited to its
    share of the machine's cores. Each of ``jobs`` workers would otherwise start a thread per core
    for every large enough matrix, and on a machine with as many workers as cores those threads
    wait on one another (docs/architecture.md, section 8)."""
    from threadpoolctl import threadpool_limits

    threadpool_limits(max(1, (os.cpu_count() or 1) // max(jobs, 1)))


@contextmanager
def _dask(address: str, timeout: float) -> Iterator[tuple[Executor, int]]:
    try:
        from distributed import Client
    except ImportError:
        raise OwnctlError(f"--scheduler needs dask.distributed, which is not installed: {INSTALL_HINT}") \
            from None
    _check_address(address)
    client = _connect(Client, address, timeout)
    try:
        slots = max(1, sum(client.nthreads().values()))
        pool = client.get_executor(pure=False)  # chunks are distinct work, never deduplicated
        yield pool, slots
    finally:
        client.close()


def _check_address(address: str) -> None:
    """BadValue unless ``address`` is one Dask can connect to (a known scheme; a port for tcp and tls)."""
    from distributed.comm import parse_address
    from distributed.comm.addressing import parse_host_port
    from distributed.comm.registry import backends

    try:
        scheme, location = parse_address(address)
        if scheme not in backends:
            raise ValueError(f"unknown scheme {scheme!r}")
        if scheme in ("tcp", "tls"):
            parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise BadValue(f"invalid Dask scheduler address {address!r}: {exc}; use one such as tcp://host:8786",
                       sorted(backends)) from None


def _connect(client_class: Any, address: str, timeout: float) -> Any:
    """A client of the scheduler at ``address``, or a one-line error saying why there is none."""
    try:
        return client_class(address, timeout=timeout, set_as_default=False)
    except (OSError, TimeoutError, ValueError, TypeError) as exc:
        detail = " ".join(str(exc).split()) or type(exc).__name__
        raise OwnctlError(
            f"cannot reach the Dask scheduler at {address!r} (an address such as tcp://host:8786, "
            f"where dask scheduler runs): {detail}"
        ) from None
