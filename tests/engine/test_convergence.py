"""Time-step convergence of the integrators on the full S175 model (scripts/convergence_study.py).

A short run — 30 s of a regular head sea (H = 6 m, λ = 175 m = Lpp, 10 s ramp), zero speed,
heave and pitch free, state-space radiation (its states are integrated by the scheme itself, so
no commit mechanics enter), nonlinear Froude–Krylov + hydrostatics, diffraction — is compared
with RK4 at Δt = 0.0125 s on a common 0.4 s grid (relative RMS error of heave and pitch).
Roll is not free, so ψ stays put (ψ̇ = q sin φ / cos θ = 0) and the diffraction model's heading
cache never refreshes — in a rolling ship its refreshes make the force jump and cap every scheme
at first order (see the script's docstring).

Why "> 8×" and not "16×" for RK4: the wetted surface is cut at the instantaneous waterline, so
the Froude–Krylov force is only piecewise smooth in the state (its second derivative jumps when
a mesh vertex crosses the surface). Each crossing costs a local error of lower order than Δt⁵,
which shows up as scatter in the halving ratio (measured 11–24 for Δt = 0.2 → 0.025 s); the
order over two halvings is ≈ 3.9–4. Holloway's scheme (BDF2-extrapolated acceleration, Taylor
updates to Δt²) is second order and its ratio is 4.0–4.1 per halving.
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest

from ship_gym.engine.ship import ShipSetup, build_simulator
from ship_gym.waves.sea_state import RegularWave

DURATION = 30.0  # [s]
SAMPLE_DT = 0.4  # comparison grid [s]
REFERENCE_DT = 0.0125  # [s], as in scripts/convergence_study.py
DEFAULT_DT = 0.05  # ShipSetup's default
DEFAULT_TOLERANCE = 1e-5  # RK4 at 0.05 s vs the reference (measured ≈ 9e-8)
HEAVE_PITCH = (2, 4)
SEA = RegularWave(height=6.0, wavelength=175.0, ramp_time=10.0)


@cache
def _run(dt: float, integrator: str) -> np.ndarray:
    setup = ShipSetup(
        dt=dt, free_dofs=(False, False, True, False, True, False), integrator=integrator
    )
    sim = build_simulator(setup, SEA, wave_heading=math.pi)
    res = sim.run(DURATION, record_every=round(SAMPLE_DT / dt))
    return res.eta


@pytest.fixture(scope="module")
def reference() -> np.ndarray:
    return _run(REFERENCE_DT, "rk4")


def _error(eta: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """Relative RMS error of heave and pitch (normalised by the reference motion)."""
    out = []
    for i in HEAVE_PITCH:
        scale = np.sqrt(np.mean((ref[:, i] - ref[0, i]) ** 2))
        out.append(np.sqrt(np.mean((eta[:, i] - ref[:, i]) ** 2)) / scale)
    return np.array(out)


def test_reference_has_motion(reference):
    # the comparison is meaningful only if the ship moves: 2.3 m heave, 6.9° pitch peak to peak
    assert np.ptp(reference[:, 2]) > 1.5
    assert np.degrees(np.ptp(reference[:, 4])) > 4.0


def test_rk4_is_fourth_order(reference):
    e = {dt: _error(_run(dt, "rk4"), reference) for dt in (0.2, 0.1, 0.05)}
    ratios = [e[0.2] / e[0.1], e[0.1] / e[0.05]]
    for r in ratios:  # each halving: > 8 (order > 3), 16 ideally
        assert np.all(r > 8.0), ratios
    # over two halvings the mean order is ≈ 4 (> 3.5, i.e. a factor > 128)
    assert np.all(e[0.2] / e[0.05] > 2**7), e


def test_holloway_is_second_order(reference):
    e = {dt: _error(_run(dt, "holloway"), reference) for dt in (0.1, 0.05, 0.025)}
    for big, small in ((0.1, 0.05), (0.05, 0.025)):
        ratio = e[big] / e[small]
        assert np.all((ratio > 3.5) & (ratio < 4.6)), (big, ratio)


def test_default_dt_is_converged(reference):
    # the default (RK4, Δt = 0.05 s) is within 1e-5 of the Δt = 0.0125 s reference
    err = _error(_run(DEFAULT_DT, "rk4"), reference)
    assert np.all(err < DEFAULT_TOLERANCE), err
    assert ShipSetup().dt == DEFAULT_DT
    assert ShipSetup().integrator == "rk4"
