"""Frequency-domain RAOs of the S175 from the bundled BEM database (ship_gym.hydro.rao).

Physics checked (Newman 1977 §6.19; Faltinsen 1990 ch. 7):

* long waves (kL ≪ 1): the ship follows the surface — heave → −ζ (z down), pitch → wave slope
  along x, roll → minus the slope along y (starboard down positive);
* a 1-DOF system peaks at its undamped natural frequency, where the reactance vanishes and
  ξ = F/(−iω B);
* the roll RAO in beam seas peaks at the roll natural period (≈ 18 s) and drops with extra
  damping;
* port/starboard symmetry: no sway/roll/yaw in head seas, mirrored response at 2π − β.
"""

from __future__ import annotations

import numpy as np
import pytest

from ship_gym.hydro.database import as_arrays, load_database
from ship_gym.hydro.rao import (
    dof_mask,
    natural_frequency,
    rao_time_series,
    response_amplitude_operator,
)

HEAD, BEAM, FOLLOWING = np.pi, np.pi / 2, 0.0
MIRROR = np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])


@pytest.fixture(scope="module")
def ds():
    return load_database("s175")


@pytest.fixture(scope="module")
def arrays(ds):
    return as_arrays(ds)


def _k(w):
    return np.asarray(w) ** 2 / 9.81


# ------------------------------------------------------------------------------ long waves
def test_heave_and_pitch_follow_long_head_waves(ds, arrays):
    w = arrays.omega[:3]  # T = 150 s … 50 s: kL ≤ 0.3
    rao = response_amplitude_operator(ds, omega=w, heading=HEAD)
    # heave (z down) = −ζ(O): RAO → −1
    np.testing.assert_allclose(rao[:, 2], -1.0, atol=0.01)
    # pitch (bow up) = ∂ζ/∂x at O = Re(ik cos β a e^{−iωt}) → −ik in head seas
    np.testing.assert_allclose(rao[1:, 4] / _k(w[1:]), -1j, atol=0.01)
    assert abs(abs(rao[0, 4]) / _k(w[0]) - 1.0) < 0.01


def test_pitch_follows_long_following_waves(ds, arrays):
    w = arrays.omega[1:3]
    rao = response_amplitude_operator(ds, omega=w, heading=FOLLOWING)
    np.testing.assert_allclose(rao[:, 2], -1.0, atol=0.01)
    np.testing.assert_allclose(rao[:, 4] / _k(w), 1j, atol=0.01)


def test_roll_follows_long_beam_waves(ds, arrays):
    # roll (starboard down) = −∂ζ/∂y = Re(−ik a e^{−iωt}) for waves toward starboard
    w = arrays.omega[1]  # T = 75 s, (ω/ω_φ)² ≈ 0.06
    rao = response_amplitude_operator(ds, omega=w, heading=BEAM)[0]
    ratio = rao[3] / _k(w)
    assert abs(abs(ratio) - 1.0) < 0.03
    assert abs(np.angle(ratio) + np.pi / 2) < np.radians(5.0)
    # sway follows the orbital motion: ζ = a cos(ωt − ky), particle y = a sin ωt = Re(i a e^{−iωt})
    assert abs(rao[1] - 1j) < 0.01


# ------------------------------------------------------------------------------ resonance
def test_heave_natural_period_of_the_s175(ds, arrays):
    wn = natural_frequency(ds, "Heave")
    assert 7.2 < 2 * np.pi / wn < 7.6  # ≈ 7.4 s for the bundled database
    a33 = np.interp(wn, arrays.omega, arrays.added_mass[:, 2, 2])
    m33, c33 = arrays.inertia_matrix[2, 2], arrays.hydrostatic_stiffness[2, 2]
    assert wn == pytest.approx(np.sqrt(c33 / (m33 + a33)), rel=1e-9)


def test_heave_only_equals_one_dof_formula(ds, arrays):
    w = np.linspace(0.2, 1.5, 27)
    rao = response_amplitude_operator(ds, omega=w, heading=2.0, free_dofs=["Heave"])
    a33 = np.interp(w, arrays.omega, arrays.added_mass[:, 2, 2])
    b33 = np.interp(w, arrays.omega, arrays.radiation_damping[:, 2, 2])
    m33, c33 = arrays.inertia_matrix[2, 2], arrays.hydrostatic_stiffness[2, 2]
    # excitation at β = 2 rad: linear between the database headings 105° and 120°
    beta = arrays.wave_direction
    j = np.searchsorted(beta, 2.0)
    t = (2.0 - beta[j - 1]) / (beta[j] - beta[j - 1])
    f_b = (1 - t) * arrays.excitation_force[:, j - 1, 2] + t * arrays.excitation_force[:, j, 2]
    f3 = np.interp(w, arrays.omega, f_b.real) + 1j * np.interp(w, arrays.omega, f_b.imag)
    expected = f3 / (-(w**2) * (m33 + a33) - 1j * w * b33 + c33)
    np.testing.assert_allclose(rao[:, 2], expected, rtol=1e-12)
    np.testing.assert_array_equal(rao[:, [0, 1, 3, 4, 5]], 0.0)


def test_one_dof_heave_resonance(ds, arrays):
    wn = natural_frequency(ds, "Heave")
    # at ω_n the reactance vanishes: ξ = F / (−iω B33)
    rao = response_amplitude_operator(ds, omega=wn, heading=BEAM, free_dofs=[2])[0, 2]
    b33 = np.interp(wn, arrays.omega, arrays.radiation_damping[:, 2, 2])
    beta = arrays.wave_direction
    i90 = int(np.argmin(np.abs(beta - BEAM)))
    fb = arrays.excitation_force[:, i90, 2]
    f = np.interp(wn, arrays.omega, fb.real) + 1j * np.interp(wn, arrays.omega, fb.imag)
    assert rao == pytest.approx(f / (-1j * wn * b33), rel=1e-9)
    # and the dynamic amplification |ξ C33/F| peaks there (dense grid, 0.1 % resolution)
    w = np.linspace(0.6, 1.1, 501)
    r = response_amplitude_operator(ds, omega=w, heading=BEAM, free_dofs=[2])[:, 2]
    fw = np.interp(w, arrays.omega, fb.real) + 1j * np.interp(w, arrays.omega, fb.imag)
    daf = np.abs(r * arrays.hydrostatic_stiffness[2, 2] / fw)
    assert w[np.argmax(daf)] == pytest.approx(wn, abs=1.5e-3)


def test_roll_resonance_in_beam_seas(ds):
    w_phi = natural_frequency(ds, "Roll")
    assert 17.0 < 2 * np.pi / w_phi < 19.0
    w = np.linspace(0.25, 0.45, 401)
    peaks = []
    for b44 in (0.0, 1e7, 5e7):  # 0, ≈ 0.7 %, ≈ 3.6 % of critical
        extra = np.zeros((6, 6))
        extra[3, 3] = b44
        roll = np.abs(response_amplitude_operator(ds, omega=w, heading=BEAM, extra_damping=extra))
        i = int(np.argmax(roll[:, 3]))
        # coupled sway-roll-yaw peak within 2 % of the uncoupled roll natural frequency
        assert w[i] == pytest.approx(w_phi, rel=0.02)
        peaks.append(roll[i, 3])
    assert peaks[0] > 10 * peaks[1] > 10 * 2 * peaks[2]


def test_roll_only_resonance_is_damping_controlled(ds, arrays):
    w_phi = natural_frequency(ds, "Roll")
    extra = np.zeros((6, 6))
    extra[3, 3] = 2e7
    rao = response_amplitude_operator(
        ds, omega=w_phi, heading=BEAM, free_dofs=["Roll"], extra_damping=extra
    )[0, 3]
    b44 = np.interp(w_phi, arrays.omega, arrays.radiation_damping[:, 3, 3]) + 2e7
    i90 = int(np.argmin(np.abs(arrays.wave_direction - BEAM)))
    fb = arrays.excitation_force[:, i90, 3]
    f = np.interp(w_phi, arrays.omega, fb.real) + 1j * np.interp(w_phi, arrays.omega, fb.imag)
    assert rao == pytest.approx(f / (-1j * w_phi * b44), rel=1e-9)


# ------------------------------------------------------------------------------ symmetry
def _symmetrised(ds):
    """The database with the (numerically small) symmetric/antisymmetric couplings removed."""
    out = ds.copy(deep=True)
    anti = MIRROR < 0
    odd = np.outer(anti, anti) | np.outer(~anti, ~anti)
    for name in ("added_mass", "radiation_damping"):
        out[name] = out[name] * odd[None]
    for name in ("hydrostatic_stiffness", "inertia_matrix"):
        out[name] = out[name] * odd
    head = int(np.argmin(np.abs(out["wave_direction"].values - HEAD)))
    exc = out["excitation_force"].values.copy()
    exc[:, head, anti] = 0.0
    out["excitation_force"] = (out["excitation_force"].dims, exc)
    return out


def test_no_antisymmetric_response_in_head_seas(ds, arrays):
    w = arrays.omega
    exact = response_amplitude_operator(_symmetrised(ds), omega=w, heading=HEAD)
    np.testing.assert_array_equal(exact[:, [1, 3, 5]], 0.0)
    # the raw database has BEM noise only: < 0.5 % of the symmetric motions
    raw = response_amplitude_operator(ds, omega=w[w > 0.2], heading=HEAD)
    scale = np.abs(exact[:, [0, 2, 4]]).max(axis=0)
    assert np.all(np.abs(raw[:, [1, 3, 5]]).max(axis=0) < 5e-3 * scale)


def test_mirrored_headings(ds, arrays):
    w = arrays.omega[5:30]
    for beta in (np.radians(60.0), BEAM, np.radians(150.0), np.radians(100.0)):
        r = response_amplitude_operator(ds, omega=w, heading=beta)
        m = response_amplitude_operator(ds, omega=w, heading=2 * np.pi - beta)
        scale = np.abs(r).max(axis=0)
        assert np.all(np.abs(m - MIRROR * r).max(axis=0) <= 1e-2 * scale)
    # negative headings wrap: −π/2 is 3π/2
    np.testing.assert_allclose(
        response_amplitude_operator(ds, omega=w, heading=-BEAM),
        response_amplitude_operator(ds, omega=w, heading=1.5 * np.pi),
        rtol=1e-12,
    )


# ------------------------------------------------------------------------------ constraints
def test_stiff_springs_equal_held_dofs(ds):
    w = np.linspace(0.3, 1.2, 10)
    springs = np.diag([1e16, 1e16, 0.0, 0.0, 0.0, 1e18])
    sprung = response_amplitude_operator(ds, omega=w, heading=2.5, restoring_extra=springs)
    held = response_amplitude_operator(
        ds, omega=w, heading=2.5, free_dofs=("Heave", "Roll", "Pitch")
    )
    for i in (2, 3, 4):
        np.testing.assert_allclose(sprung[:, i], held[:, i], rtol=1e-4)
    assert np.abs(sprung[:, [0, 1, 5]]).max() < 1e-6
    np.testing.assert_array_equal(held[:, [0, 1, 5]], 0.0)
    mask = [False, False, True, True, True, False]
    np.testing.assert_array_equal(
        response_amplitude_operator(ds, omega=w, heading=2.5, free_dofs=mask), held
    )


def test_dof_mask():
    np.testing.assert_array_equal(dof_mask(None), np.ones(6, bool))
    np.testing.assert_array_equal(dof_mask(["heave", 4]), [0, 0, 1, 0, 1, 0])
    for bad in ([], ["Heave", "Spin"], [6], [1.5]):
        with pytest.raises(ValueError):
            dof_mask(bad)


# ------------------------------------------------------------------------------ forward speed
def test_forward_speed(ds, arrays):
    w = arrays.omega[3:20]
    # beam seas: ω_e = ω, so the two frequency choices coincide at speed (the speed still acts
    # through the forward-speed terms of the radiation, tests/hydro/test_forward_speed.py)
    np.testing.assert_allclose(
        response_amplitude_operator(ds, omega=w, heading=BEAM, forward_speed=8.0),
        response_amplitude_operator(ds, omega=w, heading=BEAM, forward_speed=8.0, frequency="wave"),
        rtol=1e-12,
    )
    # zero speed: encounter and wave frequencies coincide
    np.testing.assert_allclose(
        response_amplitude_operator(ds, omega=w, heading=2.0, frequency="wave"),
        response_amplitude_operator(ds, omega=w, heading=2.0),
        rtol=1e-12,
    )
    # long head waves at speed: still quasi-static, heave → −1
    low = response_amplitude_operator(ds, omega=arrays.omega[1], heading=HEAD, forward_speed=8.0)
    assert abs(low[0, 2] + 1.0) < 0.01
    # head seas at speed: A and B read at ω_e > ω → a different (finite) answer
    fast = response_amplitude_operator(ds, omega=w, heading=HEAD, forward_speed=8.0)
    assert np.all(np.isfinite(fast)) and not np.allclose(fast, low[0])
    # ω_e = 0 with free surge is singular
    w0 = 9.81 / 8.0  # following seas, U cos β = g/ω
    with pytest.raises(ValueError, match="singular"):
        response_amplitude_operator(ds, omega=w0, heading=FOLLOWING, forward_speed=8.0)


# ------------------------------------------------------------------------------ interpolation
def test_interpolation_exact_on_grid(ds, arrays):
    w = arrays.omega[4:30]
    lin = response_amplitude_operator(ds, omega=w, heading=HEAD)
    cub = response_amplitude_operator(ds, omega=w, heading=HEAD, interpolation="cubic")
    np.testing.assert_allclose(cub, lin, rtol=1e-9, atol=1e-12)
    mid = 0.5 * (w[:-1] + w[1:])
    lin_m = response_amplitude_operator(ds, omega=mid, heading=HEAD)
    cub_m = response_amplitude_operator(ds, omega=mid, heading=HEAD, interpolation="cubic")
    assert np.abs(cub_m[:, 2] - lin_m[:, 2]).max() < 0.05  # smooth heave RAO: ≤ 0.05 m/m apart


# ------------------------------------------------------------------------------ time series
def test_time_series_phase_mapping():
    # a heave RAO of −1 (ship follows the surface): x3(t) = −ζ(O, t) = −a cos(ωt + ε)
    t = np.linspace(0.0, 30.0, 301)
    rao = np.array([0, 0, -1.0, 0, 0, 0], dtype=complex)
    x = rao_time_series(rao, 0.7, 1.5, t, phase=0.4)
    np.testing.assert_allclose(x[:, 2], -1.5 * np.cos(0.7 * t + 0.4), atol=1e-12)
    np.testing.assert_array_equal(x[:, [0, 1, 3, 4, 5]], 0.0)
    # a pure −i pitch RAO (wave slope in head seas): θ = −k a sin(ωt + ε)
    rao = np.array([0, 0, 0, 0, -1j * 0.05, 0])
    x = rao_time_series(rao, 0.7, 2.0, t, phase=0.3)
    np.testing.assert_allclose(x[:, 4], -0.1 * np.sin(0.7 * t + 0.3), atol=1e-12)


def test_time_series_superposition():
    rng = np.random.default_rng(3)
    rao = rng.normal(size=(3, 6)) + 1j * rng.normal(size=(3, 6))
    w, a, eps = np.array([0.4, 0.7, 1.1]), np.array([1.0, 0.5, 0.2]), np.array([0.0, 1.0, 2.0])
    t = np.linspace(0.0, 50.0, 101)
    total = rao_time_series(rao, w, a, t, eps)
    parts = sum(rao_time_series(rao[j], w[j], a[j], t, eps[j]) for j in range(3))
    np.testing.assert_allclose(total, parts, atol=1e-12)
    with pytest.raises(ValueError):
        rao_time_series(rao, w[:2], a, t)
    with pytest.raises(ValueError):
        rao_time_series(rao[:, :5], w, a, t)
    with pytest.raises(ValueError):
        rao_time_series(rao, w, -a, t)


# ------------------------------------------------------------------------------ bad input
def test_bad_input_raises(ds, arrays):
    w = arrays.omega[5:8]
    bad_calls = [
        {"omega": [0.5, -0.1], "heading": HEAD},
        {"omega": [0.01], "heading": HEAD},  # below the lowest database frequency
        {"omega": [2.5], "heading": HEAD},  # above the highest
        {"omega": w, "heading": np.nan},
        {"omega": w, "heading": HEAD, "frequency": "absolute"},
        {"omega": w, "heading": HEAD, "interpolation": "spline"},
        {"omega": w, "heading": HEAD, "extra_damping": np.zeros((3, 3))},
        {"omega": w, "heading": HEAD, "mass_matrix": np.full((6, 6), np.nan)},
        {"omega": w, "heading": HEAD, "free_dofs": ["Heave", "Surf"]},
        {"omega": [1.5], "heading": HEAD, "forward_speed": 10.0},  # ω_e beyond the database
    ]
    for kwargs in bad_calls:
        with pytest.raises(ValueError):
            response_amplitude_operator(ds, **kwargs)
    with pytest.raises(ValueError):
        response_amplitude_operator(arrays, omega=w, heading=HEAD)
    with pytest.raises(ValueError):
        response_amplitude_operator(ds.drop_vars("inertia_matrix"), omega=w, heading=HEAD)
    with pytest.raises(ValueError):
        natural_frequency(ds, "Surge")  # no restoring
