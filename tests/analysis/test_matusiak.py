"""Matusiak study: wave ramp, scenario construction, constant coefficients at ω_e."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from ship_gym.analysis import matusiak as mt
from ship_gym.forces.radiation import ConstantCoefficientRadiation
from ship_gym.hydro import load_database
from ship_gym.kinematics import encounter_frequency
from ship_gym.waves.wave_field import WaveField


def test_wave_scaled_to_the_s175():
    # A_w = 4.5 m × 175/150, λ = 1.5 L (same steepness 2 A_w/λ = 9/225 as his)
    amplitude, wavelength = mt.scaled_wave(175.0)
    assert amplitude == pytest.approx(5.25, rel=1e-12)
    assert wavelength == pytest.approx(262.5, rel=1e-12)
    assert 2 * amplitude / wavelength == pytest.approx(9.0 / 225.0, rel=1e-12)
    sea = mt.Scenario(0.3, 30.0).sea()
    assert sea.height == pytest.approx(10.5)
    # deep water: ω = √(2πg/λ) = 0.4846 rad/s for λ = 262.5 m
    assert sea.omega == pytest.approx(math.sqrt(2 * math.pi * 9.81 / 262.5), rel=1e-3)
    with pytest.raises(ValueError, match="length"):
        mt.scaled_wave(-1.0)


def test_froude_to_speed():
    # U = Fn √(gL): Fn 0.2 on L = 175 m → 8.287 m/s
    assert mt.speed_from_froude(0.2, 175.0, 9.81) == pytest.approx(0.2 * math.sqrt(9.81 * 175))
    setup = mt.Scenario(0.4, 30.0, "2b", kg=10.25).setup()
    assert setup.speed == pytest.approx(0.4 * math.sqrt(setup_g() * 175.0), rel=1e-12)
    assert setup.rudder == "autopilot" and setup.propulsion and setup.manoeuvring
    assert setup.radiation == "2b" and setup.hull_overrides == {"kg": 10.25}
    assert setup.integrator == "rk4" and setup.dt == 0.1
    with pytest.raises(ValueError, match="radiation"):
        mt.Scenario(0.2, 0.0, "memory")


def setup_g() -> float:
    from ship_gym.hull import load_hull

    return load_hull("s175").g


def test_wave_ramp_is_eq12_with_tf_50s():
    # A(t) = A_final [1 − cos²(πt/(2T_f))] for t < T_f (eq. 12): 0, ½, 1 at t = 0, T_f/2, T_f
    field = WaveField.regular(mt.Scenario(0.2, 0.0).sea())
    t = np.array([0.0, 12.5, 25.0, 50.0, 300.0])
    expected = 1.0 - np.cos(np.pi * np.minimum(t, 50.0) / 100.0) ** 2
    np.testing.assert_allclose(field.ramp(t), expected, atol=1e-14)
    np.testing.assert_allclose(field.ramp(t)[[0, 2, 3, 4]], [0.0, 0.5, 1.0, 1.0], atol=1e-14)


def test_study_has_his_four_conditions():
    runs = mt.study_scenarios((None, 10.25))
    pairs = {(r.froude, r.heading_deg) for r in runs}
    assert pairs == {(0.2, 0.0), (0.2, 45.0), (0.3, 30.0), (0.4, 30.0)}
    # 4 pairs × 3 models × 2 conditions + one convolution reference per condition
    assert len(runs) == 26
    assert sum(r.radiation == "convolution" for r in runs) == 2
    assert all(r.duration == 720.0 and r.ramp_time == 50.0 for r in runs)
    # his table: only Fn 0.3 / 30° separates the memory model from constant coefficients
    differ = [r for r in mt.MATUSIAK_TABLE if r.case_1 != r.case_2ab]
    assert [(r.froude, r.heading_deg) for r in differ] == [(0.3, 30.0)]


@pytest.mark.parametrize("kg", [None, 10.25])
def test_constant_coefficients_taken_at_encounter_frequency(kg):
    sc = mt.Scenario(0.3, 30.0, "2a", kg=kg)
    sim = sc.build()
    rad = next(f for f in sim.forces if isinstance(f, ConstantCoefficientRadiation))
    sea = sc.sea()
    # ω_e = ω − ω² U cos β / g = 0.2269 rad/s for Fn 0.3 at 30° (ship slower than the waves)
    w_e = float(encounter_frequency(sea.omega, sim.forward_speed, math.radians(30.0), sim.hull.g))
    assert rad.omega_c == pytest.approx(abs(w_e), rel=1e-12)
    assert rad.omega_c == pytest.approx(0.2269, abs=5e-4)
    db = load_database("s175")
    w = db["omega"].values
    finite = np.isfinite(w) & (w > 0)
    spline_a = CubicSpline(w[finite], db["added_mass"].values[finite], axis=0)
    spline_b = CubicSpline(w[finite], db["radiation_damping"].values[finite], axis=0)
    # heave/pitch block at ω_e: the database's cubic spline there (tolerance: round-off)
    a_e, b_e = spline_a(rad.omega_c), spline_b(rad.omega_c)
    for i, j in ((2, 2), (4, 4), (2, 4), (1, 1), (5, 5)):
        assert rad.added_mass[i, j] == pytest.approx(a_e[i, j], rel=1e-6)
        assert rad.damping[i, j] == pytest.approx(b_e[i, j], rel=1e-6, abs=1e-6 * b_e[2, 2])
    # case 2a: roll row at ω_φ of *this* loading condition (GM 1.0 m → 0.352 rad/s,
    # GM 0.31 m → lower); the database roll natural frequency follows the KG override
    from ship_gym.engine.ship import roll_natural_frequency

    w_roll = roll_natural_frequency(sim.hull, db)
    assert rad.omega_roll == pytest.approx(w_roll, rel=1e-9)
    assert rad.added_mass[3, 3] == pytest.approx(float(spline_a(w_roll)[3, 3]), rel=1e-6)
    if kg is None:
        assert w_roll == pytest.approx(0.352, abs=2e-3)
    else:
        assert w_roll < 0.25


@pytest.mark.slow
def test_memory_model_following_seas_fn02_no_capsize():
    # Matusiak's case 1 at Fn 0.2, following seas: no capsize (design loading, GM ≈ 1.0 m);
    # the wave hardly excites roll of a symmetric ship in exactly following seas
    res = mt.run_scenario(mt.Scenario(0.2, 0.0, "state_space"))
    assert not res.capsized and res.reason == "none"
    assert res.t[-1] == pytest.approx(720.0)
    assert res.max_abs_roll_deg < 5.0
    assert res.max_heading_deviation_deg < 5.0


def test_engine_scenario_equals_simulator():
    # case 2a on the engine (one-ship BatchSimulator) vs the single-ship Simulator, 20 s: same
    # outcome, time histories to rounding (the paths agree to ≈ 1e-12)
    sc = mt.Scenario(0.3, 30.0, "2a", duration=20.0)
    ref = mt.run_scenario(sc, engine="simulator")
    res = mt.run_scenario(sc)
    assert ref.engine == "simulator" and res.engine == "compiled"
    assert res.capsized == ref.capsized and res.reason == ref.reason
    np.testing.assert_array_equal(res.t, ref.t)
    for name in ("roll", "pitch", "yaw", "rudder", "u"):
        a, b = getattr(ref, name), getattr(res, name)
        np.testing.assert_allclose(b, a, rtol=0, atol=1e-9 * max(np.abs(a).max(), 1e-6))
    assert res.max_abs_roll_deg == pytest.approx(ref.max_abs_roll_deg, rel=1e-9)
    assert res.rms_roll_deg == pytest.approx(ref.rms_roll_deg, rel=1e-9)
    assert res.row()["engine"] == "compiled"


def test_convolution_scenario_runs_on_the_numpy_path():
    sc = mt.Scenario(0.3, 30.0, "convolution", duration=0.5)
    res = mt.run_scenario(sc)
    assert res.engine == "numpy"
    ref = mt.run_scenario(sc, engine="simulator")
    np.testing.assert_allclose(res.roll, ref.roll, rtol=0, atol=1e-12)
