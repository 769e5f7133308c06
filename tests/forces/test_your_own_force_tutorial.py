"""docs/tutorials/your_own_force.md: its example force, written to a module as the page shows it,
runs compiled, equals the numpy path and follows the closed form of its lag."""

from __future__ import annotations

import importlib
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from ship_gym.engine.batch import build_batch_simulator
from ship_gym.engine.ship import ShipSetup

PAGE = Path(__file__).resolve().parents[2] / "docs" / "tutorials" / "your_own_force.md"


@pytest.fixture(scope="module")
def thruster_module(tmp_path_factory):
    blocks = re.findall(r"```python\n(.*?)```", PAGE.read_text(encoding="utf-8"), re.S)
    module_source, usage = blocks[0], blocks[1]
    assert len(module_source.splitlines()) <= 120  # the bound on the example
    folder = tmp_path_factory.mktemp("user_force")
    (folder / "tutorial_bow_thruster.py").write_text(module_source, encoding="utf-8")
    sys.path.insert(0, str(folder))
    try:
        module = importlib.import_module("tutorial_bow_thruster")
        yield module, usage
    finally:
        sys.path.remove(str(folder))
        sys.modules.pop("tutorial_bow_thruster", None)


def test_the_page_runs_as_written(thruster_module):
    module, usage = thruster_module
    exec(usage, {"BowThruster": module.BowThruster})  # the page's own snippet


def test_the_user_force_runs_compiled_and_equals_the_numpy_path(thruster_module):
    module, _ = thruster_module
    setup = ShipSetup(integrator="rk4", dt=0.05)
    cmd = {"bow_thruster": np.array([2.0e5, -1.0e5])}
    runs = []
    for backend in ("compiled", "numpy"):
        sim = build_batch_simulator(
            setup, [None, None], extra_forces=[module.BowThruster(80.0, 6.0)], backend=backend
        )
        assert sim.compiled == (backend == "compiled")
        sim.advance(100, cmd)
        runs.append(sim)
    fast, slow = runs
    # the lag's closed form T(t) = T_c (1 − e^(−t/τ)) (RK4 on a linear ODE: ~1e-9 relative)
    expected = cmd["bow_thruster"] * (1.0 - math.exp(-5.0 / 2.0))
    np.testing.assert_allclose(fast.z[:, -1], expected, rtol=1e-8)
    np.testing.assert_allclose(fast.z, slow.z, rtol=1e-9, atol=1e-6)
    np.testing.assert_allclose(fast.eta, slow.eta, rtol=1e-9, atol=1e-9)
    assert fast.nu[0, 5] > 0.0 > fast.nu[1, 5]  # a bow thrust to starboard turns to starboard
