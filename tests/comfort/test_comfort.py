"""Comfort measures (ship_gym.comfort.metrics) against closed forms and the ISO 2631-1 table."""

import math

import numpy as np
import pytest

from ship_gym.comfort.metrics import (
    WF,
    ExponentialRMS,
    RunningDose,
    RunningWeighting,
    lateral_force_estimator,
    motion_sickness_dose_value,
    msi_iso,
    msi_ohanlon_mccauley,
    point_acceleration,
    specific_force,
    vertical_acceleration,
    weighted_acceleration,
)
from ship_gym.kinematics import euler_rate_matrix, rotation_matrix

# W_f weighting factors of ISO 2631-1:1997 (one-third-octave band centres [Hz] → factor).
ISO_WF_TABLE = {
    0.02: 0.0242, 0.05: 0.157, 0.08: 0.461, 0.1: 0.695, 0.125: 0.895, 0.16: 1.006, 0.2: 0.992,
    0.25: 0.854, 0.315: 0.619, 0.4: 0.384, 0.5: 0.224, 0.63: 0.116, 0.8: 0.053, 1.0: 0.0235,
}  # fmt: skip


def test_wf_matches_the_iso_table():
    f = np.array(list(ISO_WF_TABLE))
    gain = np.abs(WF.response(f))
    # the table gives 3 significant figures: 0.5 % covers its rounding (0.157 vs 0.1566)
    np.testing.assert_allclose(gain, list(ISO_WF_TABLE.values()), rtol=5e-3)


def _steady_amplitude(y, t, omega):
    """Amplitude of the ω component of y(t) by least squares (steady part)."""
    basis = np.column_stack([np.sin(omega * t), np.cos(omega * t)])
    c, *_ = np.linalg.lstsq(basis, y, rcond=None)
    return float(np.hypot(*c))


@pytest.mark.parametrize(("dt", "rtol"), [(0.05, 2e-3), (0.25, 4e-2)])
def test_sinusoid_through_the_digital_filter_has_the_analytic_gain(dt, rtol):
    # Pre-warped bilinear transform: exact gain at each section's corner, O((ω dt)²) elsewhere.
    # Observed: ≤ 1e-3 at dt = 0.05 s; at dt = 0.25 s (a control step; the 0.63 Hz low pass at
    # 0.3 × Nyquist) ≤ 0.3 % up to 0.25 Hz and 2.7 % at 0.4 Hz, where |W_f| is already 0.38.
    t = np.arange(0.0, 600.0, dt)
    for f_hz in (0.1, 0.16, 0.25, 0.4):
        omega = 2.0 * np.pi * f_hz
        a = 1.5 * np.sin(omega * t)
        y = weighted_acceleration(a, dt)
        keep = t > 300.0  # transient of the 0.08 Hz high pass (Q = 0.71) long gone
        amp = _steady_amplitude(y[keep], t[keep], omega)
        assert amp == pytest.approx(1.5 * abs(WF.response(f_hz)), rel=rtol)


def test_running_filter_and_dose_equal_the_batch_series():
    dt = 0.1
    rng = np.random.default_rng(0)
    series = rng.standard_normal((3, 500))
    running = RunningWeighting(3, dt)
    dose = RunningDose(3, dt)
    out = np.empty_like(series)
    for k in range(series.shape[1]):
        out[:, k] = running.update(series[:, k])
        dose.update(out[:, k])
    # the same recursion in the same order: equal to rounding
    np.testing.assert_allclose(out, weighted_acceleration(series, dt), rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(dose.msdv, motion_sickness_dose_value(out, dt), rtol=1e-12)
    np.testing.assert_allclose(dose.msi, dose.msdv / 3.0, rtol=1e-15)
    running.reset([1])
    dose.reset([1])
    assert np.all(running.state[:, :, 1] == 0.0) and dose.dose_squared[1] == 0.0
    assert np.all(running.state[:, :, 0] != 0.0)


def test_msdv_of_a_sinusoid_is_the_closed_form():
    # MSDV² = ∫ (|W| A sin ωt)² dt → |W|² A² T / 2 over whole periods (transient ≈ 1 %)
    dt, f_hz, amp, duration = 0.05, 0.2, 1.0, 3600.0
    t = np.arange(0.0, duration, dt)
    msdv = motion_sickness_dose_value(
        weighted_acceleration(amp * np.sin(2 * np.pi * f_hz * t), dt), dt
    )
    expected = abs(WF.response(f_hz)) * amp * math.sqrt(duration / 2.0)
    assert msdv == pytest.approx(expected, rel=1e-2)
    assert msi_iso(msdv) == pytest.approx(msdv / 3.0)


def _motion(t):
    """An analytic 6-DOF motion η(t), η̇(t) (large enough angles to exercise the couplings)."""
    w = np.array([0.3, 0.5, 0.7, 0.4, 0.6, 0.2])
    a = np.array([2.0, 1.0, 1.5, 0.3, 0.1, 0.4])
    drift = np.array([8.0, 0.5, 0.0, 0.0, 0.0, 0.05])
    eta = a * np.sin(w * t) + drift * t
    eta_dot = a * w * np.cos(w * t) + drift
    return eta, eta_dot


def _nu(t):
    eta, eta_dot = _motion(t)
    r = rotation_matrix(*eta[3:])
    v = r.T @ eta_dot[:3]
    omega = np.linalg.solve(euler_rate_matrix(eta[3], eta[4]), eta_dot[3:])
    return np.concatenate([v, omega])


def test_point_acceleration_matches_finite_differences_of_the_point_position():
    point = np.array([60.0, -10.0, 5.0])
    h = 1e-3
    for t in (1.0, 7.3, 12.9):
        # earth-frame acceleration of P: central second difference of x_O + R r
        def position(tt):
            eta, _ = _motion(tt)
            return eta[:3] + rotation_matrix(*eta[3:]) @ point

        accel_fd = (position(t + h) - 2.0 * position(t) + position(t - h)) / h**2
        nu_dot = (_nu(t + 1e-5) - _nu(t - 1e-5)) / 2e-5
        eta, _ = _motion(t)
        a_body = point_acceleration(_nu(t), nu_dot, point)
        # truncation O(h²) ≈ 1e-6 and rounding ε|x|/h² ≈ 1e-8 · 100 … of a few m/s²
        np.testing.assert_allclose(rotation_matrix(*eta[3:]) @ a_body, accel_fd, atol=2e-4)
        az = vertical_acceleration(eta, _nu(t), nu_dot, point)
        assert az == pytest.approx(accel_fd[2], abs=2e-4)


def test_specific_force_at_rest_is_gravity_tilted():
    phi, theta = 0.2, -0.05
    eta = np.array([0.0, 0.0, 0.0, phi, theta, 1.0])
    zero = np.zeros(6)
    f = specific_force(eta, zero, zero, (10.0, 3.0, -4.0))
    g = 9.81
    np.testing.assert_allclose(
        f,
        [g * np.sin(theta), -g * np.cos(theta) * np.sin(phi), -g * np.cos(theta) * np.cos(phi)],
        rtol=1e-14,
    )
    assert lateral_force_estimator(eta, zero, zero, (0, 0, 0)) == pytest.approx(f[1])
    # a pure sway acceleration adds to the lateral force of an upright ship
    nu_dot = np.array([0.0, 0.5, 0.0, 0.0, 0.0, 0.0])
    assert lateral_force_estimator(np.zeros(6), zero, nu_dot, (0, 0, 0)) == pytest.approx(0.5)


def test_exponential_rms_converges_to_the_rms():
    dt, tau = 0.1, 200.0
    rms = ExponentialRMS(2, dt, tau)
    t = np.arange(0.0, 3000.0, dt)
    for tk in t:
        out = rms.update(np.array([2.0 * np.sin(0.5 * tk), -3.0]))
    # after 15 τ the start-up is gone (e^-15); the sinusoid's ripple is ≈ dt/(τ ω) relative
    assert out[0] == pytest.approx(2.0 / math.sqrt(2.0), rel=1e-2)
    assert out[1] == pytest.approx(3.0, rel=1e-6)
    rms.reset([0])
    assert rms.mean_square[0] == 0.0 and rms.mean_square[1] > 0.0


def test_ohanlon_mccauley_closed_form_points():
    g = 9.81
    # 50 % where log10(ā/g) = μ = −0.819 + 2.32 (log10 ω)²; at ω = 1 rad/s: ā = 0.1517 g
    assert msi_ohanlon_mccauley(g * 10**-0.819, 1.0) == pytest.approx(50.0, abs=1e-9)
    omega = 2.0
    mu = -0.819 + 2.32 * math.log10(omega) ** 2
    # one standard deviation (0.4 decades) above: Φ(1) = 84.13 %
    assert msi_ohanlon_mccauley(g * 10 ** (mu + 0.4), omega) == pytest.approx(84.134, abs=1e-3)
    # ω = 1 rad/s is the most provocative frequency
    values = msi_ohanlon_mccauley(np.full(3, 1.0), np.array([0.5, 1.0, 2.0]))
    assert values[1] > values[0] and values[1] > values[2]


def test_bad_inputs_raise():
    with pytest.raises(ValueError, match="point"):
        point_acceleration(np.zeros(6), np.zeros(6), (1.0, 2.0))
    with pytest.raises(ValueError, match="nu"):
        point_acceleration(np.zeros(5), np.zeros(6), (1.0, 2.0, 3.0))
    with pytest.raises(ValueError, match="too coarse"):
        WF.sos(1.0)
    with pytest.raises(ValueError, match="finite"):
        weighted_acceleration([0.0, np.nan], 0.1)
    with pytest.raises(ValueError, match="frequency"):
        msi_ohanlon_mccauley(1.0, 0.0)
    with pytest.raises(ValueError, match="time_constant"):
        ExponentialRMS(1, 0.1, -1.0)
