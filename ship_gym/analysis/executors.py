"""Executors: map a function over items in this process, in local worker processes, or on Ray.

An executor maps a picklable top-level function over picklable items and yields
``(index, result)`` pairs as the results complete (``index`` into ``items``; callers key results
by it, so completion order never changes what a result means)::

    from ship_gym.analysis.executors import make_executor

    with make_executor("processes", workers=4) as ex:
        for i, result in ex.map_unordered(run_cell, cells):
            store[cells[i].key] = result

* ``"serial"`` (:class:`SerialExecutor`): in this process, in order; no extra dependency.
* ``"processes"`` (:class:`ProcessExecutor`): a :class:`concurrent.futures.ProcessPoolExecutor`
  of ``workers`` "spawn" processes (a fresh interpreter each: no forked locks or threads).
* ``"ray"`` (:class:`RayExecutor`): one Ray task per item on a local cluster of ``workers`` CPUs
  (started and shut down by the executor) or, with ``address``, on an existing cluster. Ray is
  the optional extra ``ship_gym[distributed]``, imported only when this executor is made.

Every call runs with one BLAS thread and one numba thread, whatever the executor: multithreaded
OpenBLAS splits some products differently and the last-bit differences grow over a long nonlinear
run, so single-threaded calls make the serial, process and Ray maps bit-identical for a
deterministic function. Worker processes also start with ``OMP_NUM_THREADS``,
``MKL_NUM_THREADS``, ``OPENBLAS_NUM_THREADS`` and ``NUMBA_NUM_THREADS`` set to 1 (the workers
share the machine's cores; more threads per worker only oversubscribe them).

``close()`` (also on leaving the ``with`` block, and on ``KeyboardInterrupt`` or ``SystemExit``
inside :meth:`map_unordered`) cancels outstanding work and leaves no worker process behind:
pending items are dropped, running ones are killed. Process workers also die with this process
when it is killed (``PR_SET_PDEATHSIG`` on Linux); Ray's local cluster processes share the
driver's fate in the same way.
"""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Callable, Iterator, Sequence
from types import TracebackType
from typing import Any, Literal, Protocol, TypeVar, runtime_checkable

__all__ = [
    "RAY_MISSING_MESSAGE",
    "WORKER_ENV",
    "Executor",
    "ProcessExecutor",
    "RayExecutor",
    "SerialExecutor",
    "WorkerLostError",
    "make_executor",
    "ray_available",
]

T = TypeVar("T")
R = TypeVar("R")

KINDS = ("serial", "processes", "ray")

#: environment of every worker process: one thread per BLAS / OpenMP / numba pool
WORKER_ENV: dict[str, str] = {
    "OMP_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "OPENBLAS_NUM_THREADS": "1",
    "NUMBA_NUM_THREADS": "1",
}

RAY_MISSING_MESSAGE = "install the extra: pip install 'ship_gym[distributed]'"


@runtime_checkable
class Executor(Protocol):
    """What the campaign drivers need from an executor (see the module docstring)."""

    workers: int

    def map_unordered(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[tuple[int, R]]:
        """Yield ``(index into items, fn(items[index]))`` in completion order."""
        ...

    def close(self) -> None:
        """Cancel outstanding work and stop every worker (idempotent)."""
        ...

    def __enter__(self) -> Executor: ...

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None: ...


# ---------------------------------------------------------------------------------------------
# single-threaded calls


@contextlib.contextmanager
def single_threaded() -> Iterator[None]:
    """Run the block with one thread in every BLAS library loaded and in numba's pool (when numba
    is loaded); the previous limits are restored afterwards."""
    from threadpoolctl import threadpool_limits

    numba = sys.modules.get("numba")
    previous: int | None = None
    if numba is not None:
        with contextlib.suppress(Exception):
            previous = int(numba.get_num_threads())
            numba.set_num_threads(1)
    try:
        with threadpool_limits(limits=1, user_api="blas"):
            yield
    finally:
        if numba is not None and previous is not None:
            with contextlib.suppress(Exception):
                numba.set_num_threads(previous)


def _call(fn: Callable[[T], R], item: T) -> R:
    """``fn(item)`` with one BLAS / numba thread (what every executor runs)."""
    with single_threaded():
        return fn(item)


def _check_workers(workers: int) -> int:
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be a positive integer, got {workers!r}")
    return workers


class _Closing:
    """Context-manager support: ``__exit__`` calls ``close()``."""

    def close(self) -> None:  # pragma: no cover - overridden
        raise NotImplementedError

    def __enter__(self) -> Any:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    def __del__(self) -> None:
        with contextlib.suppress(Exception):
            self.close()


# ---------------------------------------------------------------------------------------------
# serial


class SerialExecutor(_Closing):
    """Run the items one after the other in this process, in order (``workers`` is 1)."""

    workers: int = 1

    def __init__(self) -> None:
        self.workers = 1
        self._closed = False

    def map_unordered(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[tuple[int, R]]:
        """Yield ``(index, fn(items[index]))`` for each item, in order."""
        if self._closed:
            raise RuntimeError("this SerialExecutor is closed")
        for index, item in enumerate(items):
            yield index, _call(fn, item)

    def close(self) -> None:
        """Nothing to stop (idempotent)."""
        self._closed = True


# ---------------------------------------------------------------------------------------------
# local processes


def die_with_parent(parent_pid: int) -> None:
    """Worker initializer: ask Linux to SIGKILL this worker when its parent dies (even by
    SIGKILL, ``PR_SET_PDEATHSIG``), and exit now if the parent is already gone."""
    if sys.platform.startswith("linux"):
        import ctypes
        import signal

        with contextlib.suppress(OSError, AttributeError):
            libc = ctypes.CDLL("libc.so.6", use_errno=True)
            libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
    if os.getppid() != parent_pid:
        os._exit(1)


def _process_initializer(parent_pid: int, env: dict[str, str]) -> None:
    """Worker initializer: one-thread environment, :func:`die_with_parent`."""
    os.environ.update(env)
    die_with_parent(parent_pid)
    with contextlib.suppress(Exception):
        from threadpoolctl import threadpool_limits

        threadpool_limits(limits=1)  # libraries already loaded by the unpickling imports


class WorkerLostError(RuntimeError):
    """A worker process died (killed, out of memory) every time it ran an item.

    Attributes
    ----------
    index : int
        The item's index.
    attempts : int
        How many times it was started.
    """

    def __init__(self, index: int, attempts: int) -> None:
        super().__init__(
            f"item {index}: its worker process died {attempts} times (killed by a signal or out "
            "of memory)"
        )
        self.index = index
        self.attempts = attempts


class ProcessExecutor(_Closing):
    """``workers`` local worker processes (:class:`concurrent.futures.ProcessPoolExecutor`).

    Parameters
    ----------
    workers : int
        Number of worker processes (≥ 1).
    context : {"spawn", "forkserver"}
        Multiprocessing start method. "spawn" (default) starts each worker as a fresh
        interpreter; the function and items must be importable / picklable there.

    Notes
    -----
    At most ``2 × workers`` items are in flight at a time, so closing never has a long queue to
    cancel. A worker that dies (killed, out of memory) breaks the pool and every item in flight
    with it: the pool is restarted and those items are run again, each at most ``max_retries``
    times (default 2, as Ray retries a task whose worker died); ``on_retry(index, attempt)`` is
    called for each and :attr:`lost` lists their indices. An item whose worker died more often
    raises :class:`WorkerLostError` naming it.
    """

    def __init__(
        self,
        workers: int = 1,
        *,
        context: str = "spawn",
        max_retries: int = 2,
        on_retry: Callable[[int, int], None] | None = None,
    ) -> None:
        self.workers = _check_workers(workers)
        if context not in ("spawn", "forkserver"):
            raise ValueError(f"context must be 'spawn' or 'forkserver', got {context!r}")
        if isinstance(max_retries, bool) or not isinstance(max_retries, int) or max_retries < 0:
            raise ValueError(f"max_retries must be an integer >= 0, got {max_retries!r}")
        self.max_retries = max_retries
        self.on_retry = on_retry
        self.lost: list[int] = []
        self._context = context
        self._closed = False
        self._pool: Any = self._new_pool()

    def _new_pool(self) -> Any:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        return ProcessPoolExecutor(
            max_workers=self.workers,
            mp_context=multiprocessing.get_context(self._context),
            initializer=_process_initializer,
            initargs=(os.getpid(), dict(WORKER_ENV)),
        )

    def map_unordered(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[tuple[int, R]]:
        """Yield ``(index, fn(items[index]))`` as the workers finish them.

        An exception raised by ``fn`` is re-raised here (after cancelling this map's pending
        items); ``KeyboardInterrupt`` and ``SystemExit`` close the executor.
        """
        from collections import deque
        from concurrent.futures import FIRST_COMPLETED, Future, wait
        from concurrent.futures.process import BrokenProcessPool

        if self._closed or self._pool is None:
            raise RuntimeError("this ProcessExecutor is closed")
        window = 2 * self.workers
        pending: dict[Future[R], int] = {}
        queue = deque(range(len(items)))  # items to submit; a retried one goes first
        attempts: dict[int, int] = {}
        try:
            while queue or pending:
                while queue and len(pending) < window:
                    index = queue.popleft()
                    pending[self._pool.submit(_call, fn, items[index])] = index
                done, _ = wait(pending, return_when=FIRST_COMPLETED)
                lost: list[int] = []
                if any(isinstance(f.exception(), BrokenProcessPool) for f in done):
                    # a worker died: the pool fails every item in flight, now or soon
                    done, _ = wait(pending)
                for future in sorted(done, key=pending.__getitem__):
                    index = pending.pop(future)
                    if isinstance(future.exception(), BrokenProcessPool):
                        lost.append(index)
                        continue
                    yield index, future.result()
                if lost:
                    self._restart()
                    for index in lost:
                        attempts[index] = attempts.get(index, 0) + 1
                        if attempts[index] > self.max_retries:
                            raise WorkerLostError(index, attempts[index])
                        self.lost.append(index)
                        if self.on_retry is not None:
                            self.on_retry(index, attempts[index] + 1)
                    queue.extendleft(reversed(lost))
        except (KeyboardInterrupt, SystemExit):
            self.close()
            raise
        finally:
            for future in pending:
                future.cancel()

    def _restart(self) -> None:
        """Replace a broken pool by a fresh one (its processes reaped first)."""
        self._shutdown(self._pool)
        self._pool = self._new_pool()

    def close(self) -> None:
        """Cancel pending items, kill the worker processes and reap them (idempotent)."""
        self._closed = True
        pool, self._pool = self._pool, None
        self._shutdown(pool)

    @staticmethod
    def _shutdown(pool: Any) -> None:
        if pool is None:
            return
        processes = list((getattr(pool, "_processes", None) or {}).values())
        pool.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            with contextlib.suppress(Exception):
                if process.is_alive():
                    process.terminate()
        for process in processes:
            with contextlib.suppress(Exception):
                process.join(timeout=5.0)
                if process.is_alive():
                    process.kill()
                    process.join(timeout=5.0)
        with contextlib.suppress(Exception):
            pool.shutdown(wait=True)


# ---------------------------------------------------------------------------------------------
# Ray


def ray_available() -> bool:
    """Whether Ray (the ``distributed`` extra) can be imported."""
    try:
        import ray  # noqa: F401
    except ImportError:
        return False
    return True


def import_ray() -> Any:
    """Import Ray; :class:`ImportError` naming the extra when it is not installed."""
    try:
        import ray
    except ImportError as exc:
        raise ImportError(f"Ray is not installed; {RAY_MISSING_MESSAGE}") from exc
    return ray


def start_ray(ray: Any, *, workers: int, address: str | None) -> bool:
    """Connect to Ray: reuse an initialised Ray, join ``address``, or start a local cluster of
    ``workers`` CPUs. Returns whether Ray was started here (the caller then shuts it down)."""
    if ray.is_initialized():
        return False
    runtime_env = {"env_vars": dict(WORKER_ENV)}
    if address is not None:
        ray.init(
            address=address, log_to_driver=False, runtime_env=runtime_env, ignore_reinit_error=True
        )
    else:
        ray.init(
            num_cpus=workers,
            include_dashboard=False,
            log_to_driver=False,
            ignore_reinit_error=True,
            runtime_env=runtime_env,
        )
    return True


# A local cluster's raylet and GCS share the driver's fate, but Ray's dashboard and runtime-env
# agents outlive a SIGKILLed driver (measured, Ray 2.60). This watchdog (a child process that
# ignores Ctrl-C) reads the cluster's pids on its stdin; EOF without "exit" means the driver died,
# and it SIGKILLs those still alive (same pid and start time, so no recycled pid is hit).
_WATCHDOG = r"""
import os, signal, sys
signal.signal(signal.SIGINT, signal.SIG_IGN)
def start(pid):
    with open(f"/proc/{pid}/stat") as f:
        return f.read().rsplit(")", 1)[1].split()[19]
pids = {}
for line in sys.stdin:
    if line.strip() == "exit":
        sys.exit(0)
    pid, started = line.split()
    pids[int(pid)] = started
for pid, started in pids.items():
    try:
        if start(pid) == started:
            os.kill(pid, signal.SIGKILL)
    except (OSError, IndexError):
        pass
"""


def _descendants_with_start() -> list[tuple[int, str]]:
    """This process's descendants (pid, start time in clock ticks), from /proc (Linux)."""
    children: dict[int, list[tuple[int, str]]] = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append((int(entry), fields[19]))
    found: list[tuple[int, str]] = []
    stack = [os.getpid()]
    while stack:
        for pid, started in children.get(stack.pop(), []):
            found.append((pid, started))
            stack.append(pid)
    return found


def _start_watchdog(before: set[int]) -> Any:
    """The watchdog of the cluster processes started since ``before`` (None off Linux)."""
    if not sys.platform.startswith("linux"):
        return None
    import subprocess

    try:
        cluster = [(p, s) for p, s in _descendants_with_start() if p not in before]
        watchdog = subprocess.Popen(
            [sys.executable, "-c", _WATCHDOG], stdin=subprocess.PIPE, text=True
        )
        assert watchdog.stdin is not None
        watchdog.stdin.write("".join(f"{p} {s}\n" for p, s in cluster))
        watchdog.stdin.flush()
    except Exception:
        return None
    return watchdog


def _stop_watchdog(watchdog: Any) -> None:
    with contextlib.suppress(Exception):
        watchdog.stdin.write("exit\n")
        watchdog.stdin.close()
    with contextlib.suppress(Exception):
        watchdog.wait(timeout=5.0)
    with contextlib.suppress(Exception):
        if watchdog.poll() is None:
            watchdog.kill()
            watchdog.wait(timeout=5.0)


class RayExecutor(_Closing):
    """One Ray task (one CPU) per item.

    Parameters
    ----------
    workers : int
        CPUs of the local cluster started when Ray is not initialised and no ``address`` is
        given (≥ 1). With ``address``, or a Ray the caller initialised, ``workers`` becomes the
        cluster's CPU count.
    address : str, optional
        Address of an existing cluster (``"auto"``, ``"ray://host:10001"``, ``"host:6379"``).

    Raises
    ------
    ImportError
        Ray is not installed (the message names the ``distributed`` extra).

    Notes
    -----
    Ray is shut down by :meth:`close` only when this executor started it; a local cluster it
    started is also killed when this process is (a watchdog process, Linux). At most
    ``2 × workers`` tasks are in flight; :meth:`close` cancels them (``force=True``: the
    workers running them are killed).
    """

    def __init__(self, workers: int = 1, *, address: str | None = None) -> None:
        self.workers = _check_workers(workers)
        if address is not None and (not isinstance(address, str) or not address):
            raise ValueError(f"address must be a non-empty string or None, got {address!r}")
        ray = import_ray()
        self._ray = ray
        self._closed = False
        self._outstanding: set[Any] = set()
        self._watchdog: Any = None
        before = (
            {p for p, _ in _descendants_with_start()} if sys.platform.startswith("linux") else set()
        )
        self._started = start_ray(ray, workers=self.workers, address=address)
        if self._started and address is None:
            self._watchdog = _start_watchdog(before)
        if address is not None or not self._started:
            with contextlib.suppress(Exception):
                self.workers = max(1, int(ray.cluster_resources().get("CPU", self.workers)))
        self._task = ray.remote(num_cpus=1)(_call)

    @property
    def started_ray(self) -> bool:
        """Whether this executor started Ray (and so shuts it down on close)."""
        return self._started

    def map_unordered(self, fn: Callable[[T], R], items: Sequence[T]) -> Iterator[tuple[int, R]]:
        """Yield ``(index, fn(items[index]))`` as the tasks finish.

        A task's exception is re-raised here (Ray's ``RayTaskError`` subclasses the original
        exception type) after cancelling this map's outstanding tasks; ``KeyboardInterrupt`` and
        ``SystemExit`` close the executor.
        """
        if self._closed:
            raise RuntimeError("this RayExecutor is closed")
        ray = self._ray
        fn_ref = ray.put(fn)
        window = 2 * self.workers
        pending: dict[Any, int] = {}
        next_index = 0
        try:
            while next_index < len(items) or pending:
                while next_index < len(items) and len(pending) < window:
                    ref = self._task.remote(fn_ref, items[next_index])
                    pending[ref] = next_index
                    self._outstanding.add(ref)
                    next_index += 1
                ready, _ = ray.wait(list(pending), num_returns=1)
                for ref in ready:
                    index = pending.pop(ref)
                    self._outstanding.discard(ref)
                    yield index, ray.get(ref)
        except (KeyboardInterrupt, SystemExit):
            self.close()
            raise
        finally:
            if not self._closed:  # close() has cancelled everything already
                self._cancel(list(pending))

    def _cancel(self, refs: list[Any]) -> None:
        # never call Ray after it was shut down: its API calls would start a new local cluster
        if not refs or not self._ray.is_initialized():
            self._outstanding.difference_update(refs)
            return
        for ref in refs:
            with contextlib.suppress(Exception):
                self._ray.cancel(ref, force=True)
            self._outstanding.discard(ref)

    def close(self) -> None:
        """Cancel outstanding tasks; shut Ray down if this executor started it (idempotent)."""
        if self._closed:
            return
        self._closed = True
        self._cancel(list(self._outstanding))
        if self._started:
            with contextlib.suppress(Exception):
                self._ray.shutdown()
        if self._watchdog is not None:
            _stop_watchdog(self._watchdog)
            self._watchdog = None


# ---------------------------------------------------------------------------------------------


def make_executor(
    kind: Literal["serial", "processes", "ray"] = "serial",
    *,
    workers: int = 1,
    address: str | None = None,
) -> SerialExecutor | ProcessExecutor | RayExecutor:
    """An executor of the given kind (see the module docstring).

    Parameters
    ----------
    kind : {"serial", "processes", "ray"}
        Where the items run.
    workers : int
        Worker processes ("processes") or local-cluster CPUs ("ray"); ignored by "serial"
        (must still be ≥ 1).
    address : str, optional
        Ray cluster to join ("ray" only).

    Raises
    ------
    ValueError
        Unknown ``kind``, ``workers`` < 1, or ``address`` with a kind other than "ray".
    ImportError
        ``kind="ray"`` without Ray installed.
    """
    _check_workers(workers)
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
    if address is not None and kind != "ray":
        raise ValueError(f"address is only for kind='ray', got address={address!r} with {kind!r}")
    if kind == "serial":
        return SerialExecutor()
    if kind == "processes":
        return ProcessExecutor(workers)
    return RayExecutor(workers, address=address)
