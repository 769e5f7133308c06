"""Parametric-roll (Mathieu) check and the GM-in-waves hydrostatics behind it."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ship_gym.analysis import intact_stability as ist


def test_mathieu_threshold_at_exact_tuning():
    # at ω_e = 2ω_φ first-order averaging gives σ = ω_φ (h/4 − ζ): unstable iff h > 4ζ
    w = 0.35
    sigma, unstable = ist.mathieu_growth(0.2, 0.04, 2 * w, w)
    assert unstable and sigma == pytest.approx(w * (0.2 / 4 - 0.04), rel=1e-12)
    sigma, unstable = ist.mathieu_growth(0.2, 0.06, 2 * w, w)
    assert not unstable and sigma == pytest.approx(w * (0.2 / 4 - 0.06), rel=1e-12)
    # far from the tongue (ω_e = 3ω_φ) no GM variation of this size destabilises
    assert not ist.mathieu_growth(0.3, 0.0, 3 * w, w)[1]
    with pytest.raises(ValueError, match="omega_e"):
        ist.mathieu_growth(0.2, 0.01, 0.0, w)


def test_mathieu_growth_matches_floquet_integration():
    # integrate φ̈ + 2ζω φ̇ + ω²(1 + h cos ω_e t) φ = 0 over 40 roll periods and compare the
    # measured exponential growth with the first-order σ; the averaging error is O(h²) and
    # O(detuning²): 10 % at h = 0.2 with 3 % detuning
    w, h, zeta = 0.35, 0.2, 0.01
    for w_e in (2 * w, 2.06 * w):
        sigma, _ = ist.mathieu_growth(h, zeta, w_e, w)

        def rhs(t, y, w_e=w_e):
            return [y[1], -2 * zeta * w * y[1] - w**2 * (1 + h * math.cos(w_e * t)) * y[0]]

        t_end = 40 * 2 * math.pi / w
        sol = solve_ivp(rhs, (0, t_end), [0.01, 0.0], rtol=1e-10, atol=1e-14, dense_output=True)
        t = np.linspace(0, t_end, 20000)
        env = np.abs(sol.sol(t)[0])
        first = env[t < t_end / 4].max()
        last = env[t > 3 * t_end / 4].max()
        measured = math.log(last / first) / (t_end * 0.75)
        assert measured == pytest.approx(sigma, rel=0.10)


def test_gm_in_a_vanishing_wave_is_the_calm_water_gm():
    # on a 1 cm wave the GM from −∂K/∂φ of the Froude–Krylov/hydrostatic force equals the
    # hydrostatics GM (waterplane inertia) to 0.5 %: the two are independent computations
    from ship_gym.hull import equilibrium, hydrostatics, load_hull

    hull = load_hull("s175")
    eq = equilibrium(hull)
    gm = hydrostatics(hull, heave=eq.heave, trim=eq.trim).gmt
    gm_w = ist.gm_in_waves(hull, 175.0, 0.01, np.array([0.0, 87.5]))
    np.testing.assert_allclose(gm_w, gm, rtol=5e-3)


def test_check_flags_classic_head_sea_case_and_not_a_far_off_one():
    # classic: head seas, λ = L, H/λ = 1/30, speed tuned to ω_e = 2ω_φ (Fn ≈ 0.07)
    classic = ist.parametric_roll_check(wavelength_ratio=1.0, heading_deg=180.0)
    assert classic.frequency_ratio == pytest.approx(2.0, rel=1e-9)
    assert 0.05 < classic.froude < 0.1
    # crest amidships lowers GM, trough raises it (flared ends immerse)
    assert classic.gm_waves.min() < classic.gm_calm < classic.gm_waves.max()
    assert classic.h > ist.R_PR_NO_BILGE_KEELS
    assert classic.mathieu_unstable and classic.susceptible
    # same wave at Fn 0.3: ω_e ≈ 3ω_φ, far outside the principal tongue
    far = ist.parametric_roll_check(wavelength_ratio=1.0, heading_deg=180.0, froude=0.3)
    assert far.frequency_ratio > 2.8
    assert not far.mathieu_unstable and not far.susceptible
    with pytest.raises(ValueError, match="no forward speed"):
        # head seas cannot lower ω_e below ω: no speed tunes a short wave to 2ω_φ
        ist.parametric_roll_check(wavelength_ratio=0.3, heading_deg=180.0)


@pytest.mark.slow
def test_simulator_far_off_case_roll_decays():
    far = ist.parametric_roll_check(wavelength_ratio=1.0, heading_deg=180.0, froude=0.3)
    sim = ist.simulate_parametric_roll(far, duration=400.0)
    assert not sim.grows and not sim.capsized
    assert sim.late_amplitude_deg < sim.initial_heel_deg


def test_smoke_dead_ship_and_cli(tmp_path, capsys):
    import argparse
    import json

    from ship_gym.cli import capsize as cli_capsize

    res = ist.dead_ship(hs=4.0, tp=12.0, seeds=(0,), duration=10.0, dt=0.5)
    assert res.capsize_probability == 0.0 and len(res.outcomes) == 1
    assert "capsize probability" in ist.format_dead_ship(res)
    parser = argparse.ArgumentParser()
    cli_capsize.add_commands(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["parametric-roll", "--json", str(tmp_path / "pr.json")])
    assert args.func(args) == 0
    assert json.loads((tmp_path / "pr.json").read_text())["check"]["susceptible"] is True
    assert "Mathieu growth rate" in capsys.readouterr().out


@pytest.mark.slow
def test_simulator_reduced_gm_following_seas_grows():
    # GM 0.46 m (KG 10.1 m), following seas λ = L, speed tuned to ω_e = 2ω_φ: the Mathieu check
    # says unstable (h = 0.75 ≫ 4ζ) and the 6-DOF simulator agrees — a 2° heel grows to ≈ 15°
    # and stays there (limited by the nonlinear restoring), no capsize
    check = ist.parametric_roll_check(hull_overrides={"kg": 10.1}, heading_deg=0.0)
    assert check.mathieu_unstable
    sim = ist.simulate_parametric_roll(check, duration=400.0)
    assert sim.grows and sim.late_amplitude_deg > 5 * sim.initial_heel_deg
    assert not sim.capsized


def test_dead_ship_engine_equals_simulator():
    # two seeds as one engine batch vs one Simulator each: same outcomes to rounding
    kw = dict(hs=4.0, tp=12.0, seeds=(0, 1), duration=10.0, dt=0.5)
    ref = ist.dead_ship(engine="simulator", **kw)
    res = ist.dead_ship(**kw)
    for a, b in zip(ref.outcomes, res.outcomes, strict=True):
        assert a["seed"] == b["seed"] and a["capsized"] == b["capsized"]
        assert a["reason"] == b["reason"] and a["time_to_capsize"] == b["time_to_capsize"]
        for k in ("max_abs_roll_deg", "rms_roll_deg", "max_abs_pitch_deg", "mean_speed"):
            assert b[k] == pytest.approx(a[k], rel=1e-9, abs=1e-12), k


def test_parametric_roll_engine_equals_simulator():
    # surge held, 2° initial heel, 40 s: the engine's roll history is the Simulator's
    check = ist.parametric_roll_check(hull_overrides={"kg": 10.1}, heading_deg=0.0)
    ref = ist.simulate_parametric_roll(check, duration=40.0, dt=0.2, engine="simulator")
    res = ist.simulate_parametric_roll(check, duration=40.0, dt=0.2)
    np.testing.assert_array_equal(res.t, ref.t)
    np.testing.assert_allclose(res.roll, ref.roll, rtol=0, atol=1e-9 * np.abs(ref.roll).max())
    assert res.roll[0] == pytest.approx(np.radians(2.0), rel=1e-12)
    assert res.max_abs_roll_deg == pytest.approx(ref.max_abs_roll_deg, rel=1e-9)
    assert res.capsized == ref.capsized and res.grows == ref.grows
