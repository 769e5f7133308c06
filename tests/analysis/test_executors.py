"""Executors: serial, local processes and Ray give bit-identical results; close() leaves no
worker process behind; a missing Ray gives an ImportError naming the extra."""

from __future__ import annotations

import gc
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from ship_gym.analysis import executors as ex

# short simulations (5 s of a ship in oblique regular waves): (amplitude m, heading deg)
ITEMS = [(2.0, 120.0), (3.0, 90.0), (4.0, 150.0), (1.5, 60.0)]


def simulate(item: tuple[float, float]) -> np.ndarray:
    """5 s of the default ship at 4 m/s in a regular wave: the motion η (N, 6)."""
    from ship_gym.engine.ship import ShipSetup, build_simulator
    from ship_gym.waves.sea_state import RegularWave

    amplitude, heading_deg = item
    sim = build_simulator(
        ShipSetup(speed=4.0),
        RegularWave(amplitude, period=9.0),
        wave_heading=np.radians(heading_deg),
    )
    return sim.run(5.0).eta


def sleep_for(seconds: float) -> float:
    time.sleep(seconds)
    return seconds


def interrupt(_: object) -> None:
    raise KeyboardInterrupt


def fail(item: int) -> None:
    raise ValueError(f"bad item {item}")


def die_once(item: tuple[int, str]) -> int:
    """SIGKILL its own worker the first time (a marker file remembers), return the item after."""
    import signal

    value, marker = item
    if marker and not os.path.exists(marker):
        Path(marker).write_text("died once")
        os.kill(os.getpid(), signal.SIGKILL)
    return value


def die_always(item: int) -> int:
    import signal

    if item == 1:
        os.kill(os.getpid(), signal.SIGKILL)
    return item


def _descendants() -> list[int]:
    """Live (non-zombie) descendants of this process, from /proc (Linux); multiprocessing's
    resource tracker (one per interpreter, it exits with this process) is not counted."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        fields = stat.rsplit(")", 1)[1].split()
        if fields[0] == "Z":
            continue
        children.setdefault(int(fields[1]), []).append(int(entry.name))
    found: list[int] = []
    stack = [os.getpid()]
    while stack:
        for pid in children.get(stack.pop(), []):
            found.append(pid)
            stack.append(pid)
    return [pid for pid in found if not _is_resource_tracker(pid)]


def _is_resource_tracker(pid: int) -> bool:
    try:
        return b"multiprocessing.resource_tracker" in Path(f"/proc/{pid}/cmdline").read_bytes()
    except OSError:
        return False


def _wait_no_descendants(before: set[int], timeout: float = 15.0) -> list[int]:
    deadline = time.monotonic() + timeout
    while True:
        left = [p for p in _descendants() if p not in before]
        if not left or time.monotonic() > deadline:
            return left
        time.sleep(0.2)


linux_only = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")


@pytest.fixture(scope="module")
def serial_results() -> dict[int, np.ndarray]:
    with ex.make_executor("serial") as serial:
        return dict(serial.map_unordered(simulate, ITEMS))


def _check_identical(results: dict[int, np.ndarray], reference: dict[int, np.ndarray]) -> None:
    assert sorted(results) == list(range(len(ITEMS)))
    for i in range(len(ITEMS)):
        assert np.array_equal(results[i], reference[i]), f"item {i} differs"


def test_serial_in_order(serial_results):
    with ex.make_executor() as serial:
        assert [i for i, _ in serial.map_unordered(abs, [-3, 1, -2])] == [0, 1, 2]
    assert all(np.abs(r[:, 3]).max() > 0 for r in serial_results.values())  # the ship rolls


def test_bad_arguments():
    with pytest.raises(ValueError, match="kind must be one of"):
        ex.make_executor("threads")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="workers must be a positive integer, got 0"):
        ex.make_executor("processes", workers=0)
    with pytest.raises(ValueError, match="address is only for kind='ray'"):
        ex.make_executor("processes", address="auto")


@linux_only
def test_processes_identical_and_close_kills_workers(serial_results):
    before = set(_descendants())
    with ex.make_executor("processes", workers=2) as procs:
        assert procs.workers == 2
        _check_identical(dict(procs.map_unordered(simulate, ITEMS)), serial_results)
        # close while two items run and two are queued: everything stops at once
        gen = procs.map_unordered(sleep_for, [0.0, 60.0, 60.0, 60.0, 60.0])
        assert next(gen) == (0, 0.0)
        assert len(_descendants()) > len(before)
        t0 = time.perf_counter()
        procs.close()
        assert time.perf_counter() - t0 < 10.0
        procs.close()  # idempotent
    assert _wait_no_descendants(before, timeout=5.0) == []
    with pytest.raises(RuntimeError, match="closed"):
        next(procs.map_unordered(abs, [1]))


@linux_only
def test_processes_keyboard_interrupt_closes():
    before = set(_descendants())
    procs = ex.ProcessExecutor(2)
    with pytest.raises(ValueError, match="bad item 2"):  # the task's exception, re-raised
        list(procs.map_unordered(fail, [2]))
    with pytest.raises(KeyboardInterrupt):
        for _ in procs.map_unordered(interrupt, [1, 2, 3]):
            pass
    assert _wait_no_descendants(before, timeout=5.0) == []


_KILLED_PARENT = """
import os, sys, time
from ship_gym.analysis.executors import ProcessExecutor
from tests.analysis.test_executors import sleep_for
procs = ProcessExecutor(2)
gen = procs.map_unordered(sleep_for, [0.0, 60.0, 60.0])
next(gen)
print(" ".join(str(p) for p in procs._pool._processes), flush=True)
time.sleep(60)
"""


@linux_only
def test_process_workers_die_with_a_killed_parent():
    parent = subprocess.Popen(
        [sys.executable, "-c", _KILLED_PARENT], stdout=subprocess.PIPE, text=True
    )
    try:
        assert parent.stdout is not None
        workers = [int(p) for p in parent.stdout.readline().split()]
        assert len(workers) == 2
    finally:
        parent.kill()  # SIGKILL: no clean-up code runs in the parent
        parent.wait()
    deadline = time.monotonic() + 5.0
    while any(Path(f"/proc/{p}").exists() for p in workers) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not any(Path(f"/proc/{p}").exists() for p in workers)


def test_ray_missing_is_a_clear_import_error(monkeypatch):
    monkeypatch.setitem(sys.modules, "ray", None)
    assert not ex.ray_available()
    with pytest.raises(ImportError, match=r"pip install 'ship_gym\[distributed\]'"):
        ex.make_executor("ray", workers=2)


def test_importing_executors_does_not_import_ray():
    code = "import sys, ship_gym.analysis.executors; print('ray' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


# --- Ray: one local 2-CPU cluster for the module, started (and shut down) by the executor ----


@pytest.fixture(scope="module")
def ray_executor():
    ray = pytest.importorskip("ray")
    if ray.is_initialized():  # pragma: no cover - another module left Ray running
        ray.shutdown()
    # processes this test process already had (an earlier test's reusable joblib/loky pool
    # under pytest-xdist) are not the cluster's
    executor_preexisting.update(_descendants())
    t0 = time.perf_counter()
    executor = ex.make_executor("ray", workers=2)
    print(f"Ray local start-up: {time.perf_counter() - t0:.1f} s")
    assert executor.started_ray
    yield executor
    executor.close()


executor_preexisting: set[int] = set()


def test_ray_identical(ray_executor, serial_results):
    assert ray_executor.workers == 2
    _check_identical(dict(ray_executor.map_unordered(simulate, ITEMS)), serial_results)


def test_ray_task_error_is_raised(ray_executor):
    with pytest.raises(ValueError, match="bad item 1"):  # RayTaskError subclasses ValueError
        list(ray_executor.map_unordered(fail, [1]))
    assert [i for i, _ in ray_executor.map_unordered(abs, [-1, 2])] in ([0, 1], [1, 0])


@linux_only
def test_ray_close_leaves_no_process(ray_executor):  # last: shuts the module's cluster down
    import ray

    before_ray = set(_descendants())
    gen = ray_executor.map_unordered(sleep_for, [0.0, 60.0, 60.0, 60.0, 60.0])
    assert next(gen) == (0, 0.0)
    t0 = time.perf_counter()
    ray_executor.close()
    assert time.perf_counter() - t0 < 20.0
    assert not ray.is_initialized()
    del gen  # the abandoned map's clean-up must not start a new cluster
    gc.collect()
    assert not ray.is_initialized()
    left = _wait_no_descendants(executor_preexisting, timeout=60.0)
    assert left == [], f"left behind: {left} (Ray's processes were {sorted(before_ray)})"


@linux_only
def test_processes_retry_the_items_of_a_killed_worker(tmp_path):
    # a worker killed mid-item (SIGKILL, out of memory) breaks the pool: it is restarted, the
    # items in flight run again, the map finishes and the loss is reported
    marker = str(tmp_path / "died")
    items = [(0, ""), (1, marker), (2, ""), (3, "")]
    retried: list[tuple[int, int]] = []
    with ex.ProcessExecutor(workers=2, on_retry=lambda i, a: retried.append((i, a))) as procs:
        results = dict(procs.map_unordered(die_once, items))
        assert results == {0: 0, 1: 1, 2: 2, 3: 3}
        assert 1 in procs.lost and (1, 2) in retried
        assert dict(procs.map_unordered(abs, [-5])) == {0: 5}  # the new pool keeps working


@linux_only
def test_processes_give_up_on_an_item_whose_worker_always_dies():
    before = set(_descendants())
    with ex.ProcessExecutor(workers=1, max_retries=2) as procs:
        with pytest.raises(ex.WorkerLostError, match=r"item 1: its worker process died 3 times"):
            dict(procs.map_unordered(die_always, [0, 1, 2]))
    assert _wait_no_descendants(before, timeout=5.0) == []
    with pytest.raises(ValueError, match="max_retries"):
        ex.ProcessExecutor(workers=1, max_retries=-1)
