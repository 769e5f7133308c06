"""Linear diffraction force against capytaine's frequency-domain convention (bundled S175).

The reference is the database itself: for one regular wave with complex amplitude a_c at O
(capytaine's convention, ζ_O(t) = Re(a_c e^{−iωt})) the force is Re(X_D a_c e^{−iωt}). At database
nodes (ω, β) the model must reproduce it to rounding (rtol 1e-10); between nodes the bilinear
interpolation is checked against its own definition (means of neighbouring nodes).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from ship_gym.conventions import DOF_NAMES
from ship_gym.forces.base import ForceContext
from ship_gym.forces.diffraction import Diffraction
from ship_gym.hydro import load_database, mirror_headings
from ship_gym.waves import WaveField, encounter_frequency

MIRROR = np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])


@pytest.fixture(scope="module")
def db():
    return load_database("s175")


@pytest.fixture(scope="module")
def table(db):
    """(omega, beta, X_D[ω, β, dof]) at finite frequencies, headings mirrored to 0..345°."""
    ds = mirror_headings(db)
    ds = ds.isel(omega=np.flatnonzero(np.isfinite(ds.omega.values) & (ds.omega.values > 0)))
    x = ds["diffraction_force"].sel(influenced_dof=list(DOF_NAMES))
    x = x.transpose("omega", "wave_direction", "influenced_dof").values
    return ds.omega.values, ds.wave_direction.values, x


def regular(a, w, chi, eps=0.0):
    return WaveField.from_components([a], [w], [chi], [eps], ramp_time=0.0)


def ctx_at(t, field, x=0.0, y=0.0, psi=0.0, speed=0.0, phasor=True):
    return ForceContext(
        t=t,
        eta=np.array([x, y, 0.0, 0.0, 0.0, psi]),
        nu=np.array([speed, 0.0, 0.0, 0.0, 0.0, 0.0]),
        rotation=np.eye(3),
        forward_speed=speed,
        wave_phasor=field.phasor(t) if phasor else None,
    )


TIMES = np.linspace(0.0, 20.0, 23)


def test_single_wave_at_rest_reproduces_capytaine_force(db, table):
    """ε = 0, O at the origin, ψ = 0: F(t) = Re(X_D a e^{−iωt}) exactly at a node."""
    omega, beta, x = table
    i, j, a = 14, 9, 1.3
    field = regular(a, omega[i], beta[j])
    model = Diffraction(db, field)
    for t in TIMES:
        f, sd = model.evaluate(ctx_at(t, field), np.zeros(0))
        expected = np.real(x[i, j] * a * np.exp(-1j * omega[i] * t))
        np.testing.assert_allclose(f, expected, rtol=1e-10, atol=1e-10 * np.abs(x[i, j]).max())
        assert sd.shape == (0,)
    # without a phasor in the context the model uses the wave field's own phasor
    f_none, _ = model.evaluate(ctx_at(3.3, field, phasor=False), np.zeros(0))
    f_ctx, _ = model.evaluate(ctx_at(3.3, field), np.zeros(0))
    np.testing.assert_allclose(f_none, f_ctx, rtol=1e-12)


def test_phase_mapping_with_offset_position_heading_and_phase(db, table):
    """a_c read off the wave field's own elevation at O; β = χ − ψ; body-frame wave pattern.

    ζ_O(0) = Re(a_c) and ζ_O(T/4) = Im(a_c) from WaveField.elevation (no phasor algebra), then
    F(t) = Re(X_D(ω, β) a_c e^{−iωt}). The capytaine incident wave written in body axes,
    Re(a_c e^{ik(x cos β + y sin β)} e^{−iωt}), is also checked against the earth-frame field.
    """
    omega, beta, x = table
    i, j = 20, 15  # β = 225°
    psi = 0.4
    chi = beta[j] + psi
    x_o, y_o = 37.0, -12.0
    w = omega[i]
    field = regular(0.8, w, chi, eps=1.1)
    zeta = field.elevation(np.array([x_o, x_o]), np.array([y_o, y_o]), [0.0, 0.5 * math.pi / w])
    a_c = zeta[0] + 1j * zeta[1]
    model = Diffraction(db, field)
    for t in TIMES:
        f, _ = model.evaluate(ctx_at(t, field, x_o, y_o, psi), np.zeros(0))
        expected = np.real(x[i, j] * a_c * np.exp(-1j * w * t))
        np.testing.assert_allclose(f, expected, rtol=1e-9, atol=1e-9 * np.abs(x[i, j]).max())
    # body-frame pattern of capytaine's incident wave
    k = w * w / field.g
    xb, yb, t = np.array([50.0, -80.0, 10.0]), np.array([5.0, 14.0, -9.0]), 2.7
    big_x = x_o + xb * math.cos(psi) - yb * math.sin(psi)
    big_y = y_o + xb * math.sin(psi) + yb * math.cos(psi)
    body = np.real(
        a_c * np.exp(1j * k * (xb * np.cos(beta[j]) + yb * np.sin(beta[j])) - 1j * w * t)
    )
    np.testing.assert_allclose(body, field.elevation(big_x, big_y, t), atol=1e-12)


def test_bilinear_interpolation_between_nodes(db, table):
    omega, beta, x = table
    field = regular(1.0, 0.5, 0.0)
    model = Diffraction(db, field)
    i, j = 10, 4
    w_mid, b_mid = 0.5 * (omega[i] + omega[i + 1]), 0.5 * (beta[j] + beta[j + 1])
    np.testing.assert_allclose(
        model.diffraction_transfer(w_mid, beta[j]), 0.5 * (x[i, j] + x[i + 1, j]), rtol=1e-12
    )
    np.testing.assert_allclose(
        model.diffraction_transfer(w_mid, b_mid),
        0.25 * (x[i, j] + x[i + 1, j] + x[i, j + 1] + x[i + 1, j + 1]),
        rtol=1e-12,
    )
    # periodic in β across 2π (345° … 360° = 0°)
    np.testing.assert_allclose(
        model.diffraction_transfer(omega[i], math.radians(352.5)),
        0.5 * (x[i, -1] + x[i, 0]),
        rtol=1e-12,
    )
    np.testing.assert_allclose(
        model.diffraction_transfer(omega[i], beta[j] - 2 * math.pi), x[i, j], rtol=1e-12
    )


def test_heading_symmetry(db):
    """β and 2π − β: equal surge/heave/pitch, opposite sway/roll/yaw (off-node heading)."""
    w, b = 0.63, math.radians(100.0)
    f_a = regular(1.0, w, b)
    f_b = regular(1.0, w, 2 * math.pi - b)
    m_a, m_b = Diffraction(db, f_a), Diffraction(db, f_b)
    for t in TIMES:
        fa, _ = m_a.evaluate(ctx_at(t, f_a), np.zeros(0))
        fb, _ = m_b.evaluate(ctx_at(t, f_b), np.zeros(0))
        np.testing.assert_allclose(fb, MIRROR * fa, rtol=1e-10, atol=1e-10 * np.abs(fa).max())
    # the same sea seen from a ship turned by ψ: β = χ − ψ
    f_c = regular(1.0, w, b + 0.3)
    m_c = Diffraction(db, f_c)
    fa, _ = m_a.evaluate(ctx_at(4.0, f_a), np.zeros(0))
    fc, _ = m_c.evaluate(ctx_at(4.0, f_c, psi=0.3), np.zeros(0))
    np.testing.assert_allclose(fc, fa, rtol=1e-10)


def test_encounter_frequency_in_head_seas(db, table):
    """Head seas at U: F(t) = Re(X_D(ω_e, π) a e^{−iω_e t}) with ω_e = ω + kU > ω."""
    omega, beta, x = table
    i, j = 30, 12  # β = π
    assert beta[j] == pytest.approx(math.pi)
    speed, g = 8.0, 9.81
    # ω + ω² U/g = ω_node
    w = (-1.0 + math.sqrt(1.0 + 4.0 * speed / g * omega[i])) / (2.0 * speed / g)
    w_e = float(encounter_frequency(w, speed, math.pi, g))
    assert w_e == pytest.approx(omega[i]) and w_e > w
    field = WaveField.from_components([0.9], [w], [math.pi], [0.0], ramp_time=0.0, g=g)
    model = Diffraction(db, field, frequency="encounter")
    for t in TIMES:
        f, _ = model.evaluate(ctx_at(t, field, x=speed * t, speed=speed), np.zeros(0))
        expected = np.real(x[i, j] * 0.9 * np.exp(-1j * w_e * t))
        np.testing.assert_allclose(f, expected, rtol=1e-9, atol=1e-9 * np.abs(x[i, j]).max())
    np.testing.assert_allclose(model.omega_lookup, [w_e])
    # frequency="wave" looks X_D up at ω (the incident pattern), and the force still oscillates
    # at ω_e: F = Re(X_D(ω, π) a e^{−iω_e t}) without the speed correction (speed_terms="none";
    # the correction is tested below)
    wave = Diffraction(db, field, speed_terms="none")
    x_w = wave.diffraction_transfer(w, math.pi)
    for t in TIMES:
        f, _ = wave.evaluate(ctx_at(t, field, x=speed * t, speed=speed), np.zeros(0))
        expected = np.real(x_w * 0.9 * np.exp(-1j * w_e * t))
        np.testing.assert_allclose(f, expected, rtol=1e-9, atol=1e-9 * np.abs(x_w).max())
    np.testing.assert_allclose(wave.omega_lookup, [w])


def test_speed_correction_is_the_relative_motion_form(db):
    # forward_speed eq. (4)-(6), against the database's own A(ω), B(ω) (xarray interpolation,
    # independent of the model's table): at U, F_D → (ω_e Z(ω_e))/(ω Z(ω)) F_D (Z₃₃ for surge,
    # heave, pitch; Z₂₂ for sway, roll, yaw) and the pitch/yaw moments gain u Lᵀ P_D with
    # P_D = Z(ω_e)/(iω Z(ω)) F_D (+heave on pitch, −sway on yaw). Z is interpolated linearly
    # in A and in B/ω (the stated rule); tolerance 1e-9: the same arithmetic in another order.
    speed, g, w, beta = 7.0, 9.81, 0.62, math.radians(150.0)
    w_e = float(encounter_frequency(w, speed, beta, g))
    field = WaveField.from_components([1.0], [w], [beta], [0.0], ramp_time=0.0, g=g)
    plain = Diffraction(db, field, speed_terms="none")
    model = Diffraction(db, field)
    finite = db.sel(omega=db.omega[np.isfinite(db.omega) & (db.omega > 0)])

    def z(dof: str, freq: float) -> complex:
        grid = finite.omega.values
        a = finite.added_mass.sel(radiating_dof=dof, influenced_dof=dof).values
        b = finite.radiation_damping.sel(radiating_dof=dof, influenced_dof=dof).values
        return complex(np.interp(freq, grid, a) + 1j * np.interp(freq, grid, b / grid))

    ratio = {d: z(d, w_e) / z(d, w) for d in ("Heave", "Sway")}
    x_d = plain.diffraction_transfer(w, beta)
    for t in TIMES:
        ctx = ctx_at(t, field, x=speed * t, speed=speed)
        f0, _ = plain.evaluate(ctx, np.zeros(0))
        f, _ = model.evaluate(ctx, np.zeros(0))
        phasor = np.exp(-1j * w_e * t)
        expected = np.empty(6)
        for dof in range(6):
            r = ratio["Heave"] if dof in (0, 2, 4) else ratio["Sway"]
            expected[dof] = np.real(x_d[dof] * w_e / w * r * phasor)
        p_heave = np.real(x_d[2] * ratio["Heave"] / (1j * w) * phasor)
        p_sway = np.real(x_d[1] * ratio["Sway"] / (1j * w) * phasor)
        expected[4] += speed * p_heave
        expected[5] -= speed * p_sway
        scale = np.abs(x_d).max()
        np.testing.assert_allclose(f, expected, rtol=1e-9, atol=1e-9 * scale)
        np.testing.assert_allclose(f0, np.real(x_d * phasor), rtol=1e-9, atol=1e-9 * scale)
    # at rest nothing changes, bit for bit
    at_rest = ctx_at(3.0, field)
    resting, resting_plain = Diffraction(db, field), Diffraction(db, field, speed_terms="none")
    np.testing.assert_array_equal(
        resting.evaluate(at_rest, np.zeros(0))[0], resting_plain.evaluate(at_rest, np.zeros(0))[0]
    )


def test_speed_correction_is_taken_at_the_speed_of_the_reset(db):
    # U_s of the correction is the ship's surge velocity at its reset (the linear theory's
    # steady speed), not the instantaneous u, whose wave-frequency oscillation times the
    # wave-frequency force would make mean forces: a model reset at 6 m/s and evaluated while
    # surging at 6.4 m/s equals one reset at 6 m/s evaluated at 6 m/s but for Kirchhoff's
    # moment, which takes u (pitch and yaw only)
    field = regular(1.0, 0.55, math.radians(160.0))
    surging, steady = Diffraction(db, field), Diffraction(db, field)
    for model in (surging, steady):
        model.reset(0.0, ctx_at(0.0, field, speed=6.0))
    f_a, _ = surging.evaluate(ctx_at(2.0, field, x=12.0, speed=6.4), np.zeros(0))
    f_b, _ = steady.evaluate(ctx_at(2.0, field, x=12.0, speed=6.0), np.zeros(0))
    np.testing.assert_array_equal(f_a[:4], f_b[:4])
    assert f_a[4] != f_b[4]
    fresh = Diffraction(db, field)
    fresh.reset(0.0, ctx_at(0.0, field, speed=6.4))
    f_c, _ = fresh.evaluate(ctx_at(2.0, field, x=12.0, speed=6.4), np.zeros(0))
    assert not np.allclose(f_c[:4], f_a[:4], rtol=1e-4)  # another U_s, another correction


def test_negative_encounter_frequency_uses_conjugate(db):
    """Overtaking following seas: X_D = conj(X_D(|ω_e|, 0)) and the signal turns at ω_e < 0."""
    speed, g, w = 12.0, 9.81, 1.2
    w_e = float(encounter_frequency(w, speed, 0.0, g))
    assert w_e < 0
    field = WaveField.from_components([1.0], [w], [0.0], [0.0], ramp_time=0.0, g=g)
    model = Diffraction(db, field, frequency="encounter")
    x_d = model.diffraction_transfer(abs(w_e), 0.0)
    for t in TIMES:
        f, _ = model.evaluate(ctx_at(t, field, x=speed * t, speed=speed), np.zeros(0))
        expected = np.real(np.conj(x_d) * np.exp(-1j * w_e * t))
        np.testing.assert_allclose(f, expected, rtol=1e-9, atol=1e-9 * np.abs(x_d).max())


def test_frequency_range_extension(db, table):
    omega, beta, x = table
    field = WaveField.from_components([1.0, 1.0], [0.02, 2.0], [0.5, 0.5], [0.0, 0.0])
    model = Diffraction(db, field)
    # below ω_min: the ω² law from the first node
    np.testing.assert_allclose(
        model.diffraction_transfer(0.5 * omega[0], beta[3]), 0.25 * x[0, 3], rtol=1e-12
    )
    np.testing.assert_array_equal(model.diffraction_transfer(0.0, beta[3]), 0.0)
    # above ω_max: zero, counted
    np.testing.assert_array_equal(model.diffraction_transfer(2.0, beta[3]), 0.0)
    model.evaluate(ctx_at(1.0, field), np.zeros(0))
    assert model.n_above_range == 1
    strict = Diffraction(db, field, above_range="raise")
    with pytest.raises(ValueError, match="ω_max"):
        strict.evaluate(ctx_at(1.0, field), np.zeros(0))


def test_heading_cache_tolerance(db):
    field = regular(1.0, 0.7, 2.0)
    model = Diffraction(db, field, heading_tolerance_deg=0.5, frequency="encounter")
    model.evaluate(ctx_at(0.0, field, psi=0.0), np.zeros(0))
    b0 = model.beta_lookup.copy()
    model.evaluate(ctx_at(0.0, field, psi=math.radians(0.3)), np.zeros(0))
    np.testing.assert_array_equal(model.beta_lookup, b0)  # within tolerance: cached
    model.evaluate(ctx_at(0.0, field, psi=math.radians(1.0)), np.zeros(0))
    np.testing.assert_allclose(model.beta_lookup, b0 - math.radians(1.0))
    # the speed of the look-up is the ship's at its reset (module docstring)
    model.evaluate(ctx_at(0.0, field, psi=math.radians(1.0), speed=3.0), np.zeros(0))
    assert model.omega_lookup[0] == pytest.approx(0.7)  # no reset: same speed, cached
    model.reset(0.0, ctx_at(0.0, field, speed=3.0))
    model.evaluate(ctx_at(0.0, field, psi=math.radians(1.0), speed=3.0), np.zeros(0))
    assert model.omega_lookup[0] != pytest.approx(0.7)  # reset at another speed: recomputed


def test_calm_water_and_errors(db):
    calm = Diffraction(db, WaveField.calm())
    f, _ = calm.evaluate(ctx_at(1.0, WaveField.calm(), phasor=False), np.zeros(0))
    np.testing.assert_array_equal(f, 0.0)
    field = regular(1.0, 0.7, 2.0)
    model = Diffraction(db, field)
    bad = ForceContext(
        t=0.0, eta=np.zeros(6), nu=np.zeros(6), rotation=np.eye(3), wave_phasor=np.ones(3)
    )
    with pytest.raises(ValueError, match="wave_phasor"):
        model.evaluate(bad, np.zeros(0))
    with pytest.raises(ValueError, match="frequency"):
        Diffraction(db, field, frequency="doppler")
    with pytest.raises(ValueError, match="interpolation"):
        Diffraction(db, field, interpolation="cubic")
    with pytest.raises(ValueError, match="diffraction_force"):
        Diffraction(db.drop_vars("diffraction_force"), field)
    with pytest.raises(ValueError, match="WaveField"):
        Diffraction(db, None)
