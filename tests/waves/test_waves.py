"""Waves against analytic results: spectra, realisations, regular-wave kinematics, pressure, ramp.

Conventions under test (ship_gym.conventions): earth frame NED, ζ positive up,
θ = ωt − k(X cos χ + Y sin χ) + ε, χ the direction the waves travel to, clockwise from north.
"""

import math

import numpy as np
import pytest
from scipy import integrate, signal, special

from ship_gym.conventions import GRAVITY, RHO_SEAWATER
from ship_gym.waves import (
    IrregularSea,
    PhasorClock,
    RegularWave,
    WaveField,
    encounter_frequency,
    frequency_range,
    jonswap,
    omega_to_wavelength,
    pierson_moskowitz,
    ramp_factor,
    spectral_moments,
    spreading_cos2s,
    spreading_cos2s_ppf,
    stack_fields,
    wavelength_to_omega,
    wavenumber,
)

RHO_G = RHO_SEAWATER * GRAVITY


# ----------------------------------------------------------------------------- spectra
@pytest.mark.parametrize("gamma", [1.0, 2.0, 3.3, 7.0])
@pytest.mark.parametrize(("hs", "tp"), [(1.0, 6.0), (5.0, 12.0)])
def test_jonswap_m0_gives_hs(hs, tp, gamma):
    # A_γ is exact to ~1e-12; what remains is the trapezoidal rule and the ω⁻⁵ tail beyond
    # 30 rad/s (relative (5/4)(ω_p/ω)⁴ ≈ 1e-7), far inside 1e-3.
    w = np.linspace(0.0, 30.0, 200_001)
    m0 = spectral_moments(w, jonswap(w, hs, tp, gamma=gamma), 0)
    assert 4.0 * math.sqrt(m0) == pytest.approx(hs, rel=1e-3)


def test_pm_m0_gives_hs_and_is_jonswap_gamma_one():
    w = np.linspace(0.0, 30.0, 200_001)
    s_pm = pierson_moskowitz(w, 3.0, 9.0)
    assert 4.0 * math.sqrt(spectral_moments(w, s_pm, 0)) == pytest.approx(3.0, rel=1e-3)
    np.testing.assert_allclose(jonswap(w, 3.0, 9.0, gamma=1.0), s_pm, rtol=1e-13, atol=0.0)


@pytest.mark.parametrize("gamma", [1.0, 3.3, 5.0])
def test_spectrum_peak_at_omega_p(gamma):
    tp = 11.0
    wp = 2.0 * math.pi / tp
    w = np.linspace(0.2, 2.0, 180_001)  # spacing 1e-5 rad/s
    s = jonswap(w, 2.0, tp, gamma=gamma)
    assert w[np.argmax(s)] == pytest.approx(wp, abs=2e-5)
    # Peak value: S(ω_p) = A_γ γ (5/16) Hs²/ω_p e^{−5/4}, i.e. γ times the normalised PM value.
    ratio = jonswap(wp, 2.0, tp, gamma=gamma) / pierson_moskowitz(wp, 2.0, tp)
    from ship_gym.waves import jonswap_normalisation

    assert ratio == pytest.approx(gamma * jonswap_normalisation(gamma), rel=1e-12)


def test_spectral_moments_of_pm_periods():
    # Closed forms for PM: m1/m0 = Γ(3/4) (5/4)^{1/4} ω_p, m2/m0 = √(5π)/2 ω_p² (ITTC).
    tp = 10.0
    wp = 2.0 * math.pi / tp
    w = np.linspace(0.0, 60.0, 600_001)
    m0, m1, m2 = spectral_moments(w, pierson_moskowitz(w, 1.0, tp), (0, 1, 2))
    assert m1 / m0 == pytest.approx(math.gamma(0.75) * 1.25**0.25 * wp, rel=1e-4)
    # m2 converges like ∫ω⁻³: the tail beyond X = 60 rad/s, (5/32) Hs² ω_p⁴/X² (1.4e-4 of m2),
    # is added analytically.
    m2 += 5.0 / 32.0 * wp**4 / 60.0**2
    assert m2 / m0 == pytest.approx(math.sqrt(5.0 * math.pi) / 2.0 * wp**2, rel=1e-5)


def test_frequency_range_bounds_are_at_threshold():
    tp = 8.0
    lo, hi = frequency_range(tp, gamma=3.3, threshold=1e-3)
    peak = jonswap(2 * math.pi / tp, 1.0, tp)
    np.testing.assert_allclose(jonswap(np.array([lo, hi]), 1.0, tp) / peak, 1e-3, rtol=1e-8)


@pytest.mark.parametrize("s", [0.0, 1.0, 2.5, 10.0, 75.0])
def test_cos2s_integrates_to_one(s):
    theta = np.linspace(-math.pi, math.pi, 20_001)
    d = spreading_cos2s(theta, s)
    assert integrate.simpson(d, x=theta) == pytest.approx(1.0, abs=1e-9)
    # E[cos θ] = s/(s + 1) (Longuet-Higgins et al. 1963).
    assert integrate.simpson(d * np.cos(theta), x=theta) == pytest.approx(s / (s + 1), abs=1e-9)


@pytest.mark.parametrize("s", [0.0, 1.0, 15.0])
def test_cos2s_quantile_inverts_cdf(s):
    theta = np.linspace(-math.pi, math.pi, 40_001)
    cdf = integrate.cumulative_trapezoid(spreading_cos2s(theta, s), theta, initial=0.0)
    u = np.linspace(0.01, 0.99, 37)
    np.testing.assert_allclose(np.interp(spreading_cos2s_ppf(u, s), theta, cdf), u, atol=1e-6)


# ----------------------------------------------------------------------------- dispersion
def test_deep_water_dispersion():
    w = np.array([0.3, 0.628, 1.5])
    np.testing.assert_allclose(wavenumber(w), w**2 / GRAVITY, rtol=1e-15)
    lam = omega_to_wavelength(w)
    np.testing.assert_allclose(2 * np.pi / lam, w**2 / GRAVITY, rtol=1e-14)
    np.testing.assert_allclose(wavelength_to_omega(lam), w, rtol=1e-14)
    wave = RegularWave(height=2.0, period=10.0)
    assert wave.wavelength == pytest.approx(GRAVITY * 100 / (2 * math.pi), rel=1e-14)
    assert wave.wavenumber == pytest.approx(wave.omega**2 / GRAVITY, rel=1e-14)
    assert RegularWave(2.0, wavelength=wave.wavelength).period == pytest.approx(10.0, rel=1e-14)


def test_encounter_frequency():
    w, u = 0.6, 8.0
    k = w**2 / GRAVITY
    assert encounter_frequency(w, u, 0.0) == pytest.approx(w - k * u)  # following: lower
    assert encounter_frequency(w, u, math.pi) == pytest.approx(w + k * u)  # head: higher
    np.testing.assert_allclose(encounter_frequency(w, u, [math.pi / 2, -math.pi / 2]), w)
    # Vectorised over ω and β; overtaking following seas keep their (negative) sign.
    we = encounter_frequency(np.array([[0.5], [2.0]]), u, np.array([0.0, math.pi]))
    assert we.shape == (2, 2)
    assert we[1, 0] < 0.0


# ----------------------------------------------------------------------------- ramp
def test_ramp_matusiak_eq12():
    tf = 50.0
    r = ramp_factor(np.array([-1.0, 0.0, tf / 2, tf, 2 * tf]), tf)
    np.testing.assert_allclose(r, [0.0, 0.0, 0.5, 1.0, 1.0], atol=1e-15)
    # Zero slope at both ends: r'(t) = (π/2T_f) sin(πt/T_f), so a one-sided difference with
    # h = 1e-3 s is ≈ π²h/(4T_f²) ≈ 1e-6 [1/s], against a mid-ramp slope π/(2T_f) ≈ 0.031.
    h = 1e-3
    assert abs(ramp_factor(h, tf) - ramp_factor(0.0, tf)) / h < 1e-5
    assert abs(ramp_factor(tf, tf) - ramp_factor(tf - h, tf)) / h < 1e-5
    assert (ramp_factor(tf / 2 + h, tf) - ramp_factor(tf / 2 - h, tf)) / (2 * h) == pytest.approx(
        math.pi / (2 * tf), rel=1e-6
    )
    np.testing.assert_array_equal(ramp_factor([-5.0, 0.0, 3.0], 0.0), 1.0)  # T_f = 0 disables


def test_ramp_scales_elevation_and_pressure():
    field = WaveField.regular(RegularWave(2.0, period=8.0, ramp_time=50.0))
    free = WaveField.regular(RegularWave(2.0, period=8.0, ramp_time=0.0))
    x = np.linspace(0.0, 100.0, 7)
    np.testing.assert_allclose(field.elevation(x, 0.0, 25.0), 0.5 * free.elevation(x, 0.0, 25.0))
    np.testing.assert_array_equal(field.elevation(x, 0.0, 0.0), 0.0)
    np.testing.assert_allclose(field.pressure(x, 0.0, 3.0, 0.0), RHO_G * 3.0)


# ----------------------------------------------------------------------------- regular wave
def test_regular_crest_at_origin_and_direction_of_travel():
    a = 1.5
    for chi, (ex, ey) in [(0.0, (1, 0)), (math.pi / 2, (0, 1)), (math.pi, (-1, 0))]:
        wave = RegularWave(2 * a, period=9.0, heading=chi, ramp_time=0.0)
        field = WaveField.regular(wave)
        assert field.elevation(0.0, 0.0, 0.0) == pytest.approx(a, rel=1e-14)
        # After a quarter period the crest nearest the origin has moved λ/4 along χ.
        s = np.linspace(-wave.wavelength / 2, wave.wavelength / 2, 100_001)
        zeta = field.elevation(ex * s, ey * s, wave.period / 4)
        assert s[np.argmax(zeta)] == pytest.approx(wave.wavelength / 4, abs=2e-3)
        assert zeta.max() == pytest.approx(a, rel=1e-12)


def test_regular_wave_moves_at_phase_speed():
    chi = 0.7
    wave = RegularWave(3.0, wavelength=120.0, heading=chi, phase=0.4, ramp_time=0.0)
    field = WaveField.regular(wave)
    c = wave.phase_speed
    assert c == pytest.approx(wave.omega / wave.wavenumber, rel=1e-14)
    rng = np.random.default_rng(0)
    x, y = rng.uniform(-200, 200, (2, 50))
    t = 13.7
    shifted = field.elevation(x + c * t * math.cos(chi), y + c * t * math.sin(chi), t)
    np.testing.assert_allclose(shifted, field.elevation(x, y, 0.0), atol=1e-12)
    # Crest lines are perpendicular to χ.
    along_crest = field.elevation(x - 50 * math.sin(chi), y + 50 * math.cos(chi), t)
    np.testing.assert_allclose(along_crest, field.elevation(x, y, t), atol=1e-12)


# ----------------------------------------------------------------------------- pressure
def test_pressure_zero_on_instantaneous_surface_wheeler():
    sea = IrregularSea(hs=6.0, tp=10.0, spreading_s=4.0, ramp_time=0.0)
    field = WaveField.from_sea_state(sea, np.random.default_rng(3))
    rng = np.random.default_rng(4)
    x, y = rng.uniform(-300, 300, (2, 200))
    t = rng.uniform(0, 600, 200)
    zeta = field.elevation(x, y, t)
    np.testing.assert_allclose(field.pressure(x, y, -zeta, t), 0.0, atol=1e-9 * RHO_G)
    np.testing.assert_array_equal(field.pressure(x, y, -zeta - 0.01, t), 0.0)  # dry
    assert np.all(field.pressure(x, y, -zeta + 0.01, t) > 0.0)
    # Linear method: hydrostatic extrapolation in crests also vanishes on the surface.
    crest = zeta > 0
    p_lin = field.pressure(x[crest], y[crest], -zeta[crest], t[crest], method="linear")
    np.testing.assert_allclose(p_lin, 0.0, atol=1e-9 * RHO_G)


def test_pressure_hydrostatic_deep_below():
    wave = RegularWave(4.0, wavelength=100.0, ramp_time=0.0)
    field = WaveField.regular(wave)
    x = np.linspace(0, 100, 11)
    z = 3 * wave.wavelength  # e^{−kd} ≈ e^{−6π} ≈ 7e-9: dynamic part ≈ 1e-8 m of 300 m
    for method in ("wheeler", "linear"):
        p = field.pressure(x, 0.0, z, 5.0, method=method)
        np.testing.assert_allclose(p, RHO_G * z, rtol=1e-9)


def test_pressure_small_amplitude_is_airy():
    a, lam = 0.01, 100.0
    wave = RegularWave(2 * a, wavelength=lam, heading=0.3, ramp_time=0.0)
    field = WaveField.regular(wave)
    k, w, chi = wave.wavenumber, wave.omega, wave.heading
    x, z = np.meshgrid(np.linspace(0, lam, 9), np.linspace(0.5, 30.0, 7))
    y, t = 0.3 * x, 4.2
    theta = w * t - k * (x * math.cos(chi) + y * math.sin(chi))
    airy = RHO_G * (z + a * np.exp(-k * z) * np.cos(theta))
    # "linear" is Airy by construction; Wheeler differs by ρ g a (e^{−k(Z+ζ)} − e^{−kZ}), i.e.
    # at most ρ g a · k a ≈ 6e-4 of the dynamic amplitude: allow 2 k a.
    np.testing.assert_allclose(field.pressure(x, y, z, t, method="linear"), airy, rtol=1e-13)
    err = np.abs(field.pressure(x, y, z, t) - airy)
    assert err.max() < RHO_G * a * 2 * k * a


def test_pressure_linear_above_mean_surface_is_hydrostatic():
    field = WaveField.regular(RegularWave(4.0, period=10.0, ramp_time=0.0))
    zeta = field.elevation(0.0, 0.0, 0.0)  # crest, 2 m
    z = np.array([-1.5, -0.5])
    np.testing.assert_allclose(
        field.pressure(0.0, 0.0, z, 0.0, method="linear"), RHO_G * (z + zeta), rtol=1e-14
    )


# ----------------------------------------------------------------------------- velocity
def test_velocity_matches_airy_and_kinematic_condition():
    a = 0.5
    wave = RegularWave(2 * a, period=8.0, heading=math.pi / 3, ramp_time=0.0)
    field = WaveField.regular(wave)
    k, w, chi = wave.wavenumber, wave.omega, wave.heading
    z = 4.0
    # Under a crest (θ = 0, ζ = a): forward velocity a ω e^{−k s}, s = Z (linear) or the
    # depth below the instantaneous surface Z + a (Wheeler).
    direction = np.array([math.cos(chi), math.sin(chi), 0.0])
    for method, depth in (("linear", z), ("wheeler", z + a)):
        u = field.velocity(0.0, 0.0, z, 0.0, method=method)
        np.testing.assert_allclose(u, a * w * math.exp(-k * depth) * direction, atol=1e-14)
    np.testing.assert_array_equal(field.velocity(0.0, 0.0, -a - 0.01, 0.0), 0.0)  # dry
    # Kinematic free-surface condition (linear), u_D(Z = 0) = −∂ζ/∂t (ζ up, Z down), checked
    # through u_D(Z) = −e^{−kZ} ∂ζ/∂t at Z = 0.6 m > a, which stays wet in troughs.
    t, h, zw = np.linspace(0.0, 8.0, 9), 1e-5, 0.6
    dzdt = (field.elevation(3.0, 1.0, t + h) - field.elevation(3.0, 1.0, t - h)) / (2 * h)
    ud = field.velocity(3.0, 1.0, zw, t, method="linear")[:, 2]
    np.testing.assert_allclose(ud, -math.exp(-k * zw) * dzdt, atol=1e-8)


def test_velocity_divergence_free_irregular():
    sea = IrregularSea(hs=3.0, tp=9.0, spreading_s=2.0, ramp_time=0.0)
    field = WaveField.from_sea_state(sea, np.random.default_rng(11))
    p = np.array([12.0, -7.0, 5.0])
    h, t = 1e-3, 40.0
    div = 0.0
    for i in range(3):
        dp = np.zeros(3)
        dp[i] = h
        up = field.velocity(*(p + dp), t, method="linear")[i]
        um = field.velocity(*(p - dp), t, method="linear")[i]
        div += (up - um) / (2 * h)
    assert abs(div) < 1e-6  # central differences: O(h² k³ a ω) ≈ 1e-8


# ----------------------------------------------------------------------------- realisations
@pytest.fixture(scope="module")
def long_record():
    sea = IrregularSea(hs=4.0, tp=10.0, n_components=200, ramp_time=0.0)
    field = WaveField.from_sea_state(sea, np.random.default_rng(2024))
    dt = 0.5
    t = np.arange(0.0, 3 * 3600.0, dt)
    return sea, field, dt, field.elevation(0.0, 0.0, t)


def test_long_realisation_hs(long_record):
    # With 200 jittered components the realised m0 = Σ a²/2 deviates from Hs²/16 by the
    # sampling error of S at random points (≈ 1 %) minus the ≈ 0.3 % outside the band; the 3-h
    # time average of ζ² adds O(1/(T Δω)) ≈ 1e-2 of cross terms. 5 % is several σ.
    sea, field, _, zeta = long_record
    assert 4.0 * zeta.std() == pytest.approx(sea.hs, rel=0.05)
    assert field.significant_height == pytest.approx(sea.hs, rel=0.03)


def test_long_realisation_welch_spectrum(long_record):
    # Power in 4 bands of 12 component bins (B ≈ 0.13 rad/s ≈ 0.2 ω_p) over 0.75-1.56 ω_p,
    # band edges on component-bin edges so each band holds whole bins. Statistical tolerance:
    # for a Gaussian sea a band power measured over T has relative σ ≈ 1/√(BT/2π) = 1/√220
    # ≈ 7 % (3 h), so 15 % is ≈ 2σ for a Gaussian record; a sum of 200 sinusoids with fixed
    # amplitudes scatters less — the realised Σ a²/2 per band is within ≈ 2 % of ∫S, and what
    # remains is jittered neighbours closer than 2π/T beating during the record plus Hann-window
    # leakage across band edges (nperseg = 8192: main lobe ±0.003 rad/s). Over 30 seeds the
    # worst of the 4 bands was 12 %.
    sea, _, dt, zeta = long_record
    f, pxx = signal.welch(zeta, fs=1 / dt, nperseg=8192)
    omega, s_welch = 2 * np.pi * f, pxx / (2 * np.pi)  # one-sided [m² s/rad]
    lo, hi = sea.omega_range
    d_omega = (hi - lo) / sea.n_total
    first = math.floor((0.75 * sea.omega_peak - lo) / d_omega)
    for b in range(first, first + 48, 12):
        w0, w1 = lo + b * d_omega, lo + (b + 12) * d_omega
        sel = (omega >= w0) & (omega < w1)
        measured = np.sum(s_welch[sel]) * (omega[1] - omega[0])
        fine = np.linspace(w0, w1, 2001)
        target = integrate.trapezoid(sea.spectral_density(fine), fine)
        assert measured == pytest.approx(target, rel=0.15), (w0, w1)


def test_same_seed_same_sea_different_seed_different_sea():
    sea = IrregularSea(hs=3.0, tp=8.0, spreading_s=5.0)
    x, y = np.meshgrid(np.linspace(-50, 50, 5), np.linspace(-20, 20, 3))
    a = WaveField.from_sea_state(sea, np.random.default_rng(7)).elevation(x, y, 60.0)
    b = WaveField.from_sea_state(sea, np.random.default_rng(7)).elevation(x, y, 60.0)
    c = WaveField.from_sea_state(sea, np.random.default_rng(8)).elevation(x, y, 60.0)
    np.testing.assert_array_equal(a, b)
    assert np.max(np.abs(a - c)) > 0.1 * sea.hs


def test_jittered_bins_remove_repeat_period():
    # Bin centres 0.31 + 0.01 j are integer multiples of Δω = 0.01 rad/s, so with equal bins the
    # record repeats exactly after T_r = 2π/Δω ≈ 628 s; jittering leaves a correlation
    # ≈ Σ a² cos(ω_j T_r)/Σ a², a sum of ~M random cosines weighted by energy: O(0.1).
    common = dict(hs=2.0, tp=9.0, n_components=200, omega_min=0.305, omega_max=2.305)
    t_r = 2 * math.pi / 0.01
    t = np.arange(0.0, 7200.0, 0.5)
    corr = {}
    for sampling in ("equal", "jittered"):
        sea = IrregularSea(**common, frequency_sampling=sampling, ramp_time=0.0)
        field = WaveField.from_sea_state(sea, np.random.default_rng(5))
        z0, z1 = field.elevation(0.0, 0.0, t), field.elevation(0.0, 0.0, t + t_r)
        corr[sampling] = np.mean(z0 * z1) / math.sqrt(np.mean(z0**2) * np.mean(z1**2))
        if sampling == "jittered":
            a2 = field.amplitude**2
            predicted = np.sum(a2 * np.cos(field.omega * t_r)) / np.sum(a2)
            assert corr[sampling] == pytest.approx(predicted, abs=0.05)
    assert corr["equal"] > 1 - 1e-9
    assert abs(corr["jittered"]) < 0.3


@pytest.mark.parametrize("sampling", ["equal_energy", "random"])
@pytest.mark.parametrize("n_directions", [1, 5])
def test_short_crested_spreading_statistics(sampling, n_directions):
    # E[cos θ] = s/(s+1) and E[sin θ] = 0 for cos-2s. Stratified ("equal_energy") sampling is
    # unbiased and its scatter is far below that of independent draws, whose σ ≈ 0.3/√400
    # ≈ 0.015 per statistic (var cos θ ≈ 0.07 for s = 3): 0.05 is > 3σ for both.
    s = 3.0
    sea = IrregularSea(
        hs=2.0,
        tp=8.0,
        heading=2.5,
        spreading_s=s,
        n_components=400 // n_directions,
        n_directions=n_directions,
        direction_sampling=sampling,
    )
    field = WaveField.from_sea_state(sea, np.random.default_rng(1))
    assert field.n_components == 400
    theta = (field.direction - sea.heading + math.pi) % (2 * math.pi) - math.pi
    assert np.mean(np.cos(theta)) == pytest.approx(s / (s + 1), abs=0.05)
    assert abs(np.mean(np.sin(theta))) < 0.05
    assert np.all((field.direction >= -math.pi) & (field.direction < math.pi))
    if sampling == "equal_energy":
        # Each equal-probability sector is used exactly once (per bin when n_directions > 1):
        # CDF F(θ) = ½ + ½ sign θ I_{sin²(θ/2)}(½, s + ½).
        cdf = 0.5 + 0.5 * np.sign(theta) * special.betainc(0.5, s + 0.5, np.sin(theta / 2) ** 2)
        n_sectors = n_directions if n_directions > 1 else 400
        sector = np.floor(cdf * n_sectors).reshape(-1, n_sectors)
        np.testing.assert_array_equal(np.sort(sector, axis=1) - np.arange(n_sectors), 0.0)


def test_long_crested_all_components_along_heading():
    sea = IrregularSea(hs=2.0, tp=8.0, heading=-1.0, spectrum="pm")
    field = WaveField.from_sea_state(sea, np.random.default_rng(0))
    np.testing.assert_array_equal(field.direction, -1.0)
    np.testing.assert_allclose(field.wavenumber, field.omega**2 / GRAVITY, rtol=1e-15)
    assert np.all((field.phase >= 0) & (field.phase < 2 * math.pi))
    lo, hi = sea.omega_range
    assert np.all((field.omega >= lo) & (field.omega < hi))


# ----------------------------------------------------------------------------- phasors
def test_phasor_reproduces_elevation():
    sea = IrregularSea(hs=3.0, tp=8.0, spreading_s=2.0, ramp_time=50.0)
    field = WaveField.from_sea_state(sea, np.random.default_rng(9))
    x, y = np.meshgrid(np.linspace(-60, 60, 7), np.linspace(-10, 10, 4))
    for t in (10.0, 80.0):
        np.testing.assert_allclose(
            field.elevation_from_phasor(field.phasor(t), x, y),
            field.elevation(x, y, t),
            atol=1e-12,
        )


@pytest.mark.parametrize("reanchor_every", [None, 4096])
def test_phasor_clock_1e5_steps(reanchor_every):
    # Pure rotation accumulates O(n ε) ≈ 1e-11 relative error in 1e5 steps; re-anchoring
    # resets it every 4096 steps. Both stay far inside 1e-9 m.
    sea = IrregularSea(hs=5.0, tp=10.0, ramp_time=50.0)
    field = WaveField.from_sea_state(sea, np.random.default_rng(12))
    dt = 0.05
    clock = field.clock(dt, t0=3.0, reanchor_every=reanchor_every)
    worst = 0.0
    for _ in range(10):
        clock.step(10_000)
        exact = field.phasor(3.0 + clock.steps * dt)
        worst = max(worst, np.max(np.abs(clock.phasor() - exact)))
    assert clock.steps == 100_000
    assert clock.t == pytest.approx(3.0 + 5000.0)
    assert worst < 1e-9


def test_phasor_clock_ramp_and_batch():
    fields = [
        WaveField.regular(RegularWave(2.0, period=7.0, heading=0.5, ramp_time=20.0)),
        WaveField.from_sea_state(IrregularSea(hs=2.0, tp=9.0), np.random.default_rng(1)),
        WaveField.calm(),
    ]
    stack = stack_fields(fields)
    assert stack.amplitude.shape == (3, 50)
    clock = stack.clock(0.1)
    for _ in range(3):
        clock.step(137)
        np.testing.assert_allclose(clock.phasor(), stack.phasor(clock.t), atol=1e-12)
    assert isinstance(clock, PhasorClock)
    # Stacked elevation equals each field's own, at per-ship times and points.
    x = np.array([[0.0, 10.0, 20.0], [5.0, -5.0, 0.0], [1.0, 2.0, 3.0]])
    times = np.array([5.0, 60.0, 7.0])
    zeta = stack.elevation(x, 2 * x, times)
    for i, f in enumerate(fields):
        np.testing.assert_allclose(zeta[i], f.elevation(x[i], 2 * x[i], times[i]), atol=1e-12)
    np.testing.assert_array_equal(zeta[2], 0.0)


# ----------------------------------------------------------------------------- validation
@pytest.mark.parametrize(
    ("factory", "match"),
    [
        (lambda: IrregularSea(hs=-1.0, tp=8.0), "hs"),
        (lambda: IrregularSea(hs=1.0, tp=0.0), "tp"),
        (lambda: IrregularSea(hs=1.0, tp=8.0, spectrum="bretschneider"), "spectrum"),
        (lambda: IrregularSea(hs=1.0, tp=8.0, gamma=0.5), "gamma"),
        (lambda: IrregularSea(hs=1.0, tp=8.0, n_components=0), "n_components"),
        (lambda: IrregularSea(hs=1.0, tp=8.0, omega_min=2.0, omega_max=1.0), "omega_min"),
        (lambda: RegularWave(1.0), "period"),
        (lambda: RegularWave(1.0, period=10.0, wavelength=50.0), "disagree"),
        (lambda: RegularWave(30.0, wavelength=100.0), "steepness"),
        (lambda: jonswap([0.5, -1.0], 1.0, 8.0), "omega"),
        (lambda: spreading_cos2s(0.0, -1.0), "spreading"),
        (lambda: ramp_factor(1.0, -2.0), "ramp_time"),
        (lambda: WaveField.from_sea_state(IrregularSea(1.0, 8.0), 42), "Generator"),
        (lambda: WaveField.from_components([1.0, 2.0], [1.0], [0.0], [0.0]), "omega"),
    ],
)
def test_bad_input_raises_value_error(factory, match):
    with pytest.raises(ValueError, match=match):
        factory()
