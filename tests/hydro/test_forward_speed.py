"""The forward-speed linearisation (ship_gym.hydro.forward_speed) against its theory.

* The factorised impedance (s − U Lᵀ)(A + B/s)(s + U L) equals s² A(U) + s B(U) with the
  coefficients of Salvesen, Tuck & Faltinsen (1970, Table 1, no end terms), written out here term
  by term from the paper (independently of the matrix algebra of the module).
* The Timman–Newman reverse-flow relations A_jk(U) = A_kj(−U), B_jk(U) = B_kj(−U), which STF's
  coefficients satisfy for symmetric zero-speed A, B (property test over random symmetric
  matrices, speeds and frequencies).
* The engine's radiation model at speed has, in the frequency domain, the same impedance
  (its fitted state-space memory, the Kirchhoff term included).

Tolerances: 1e-12 relative where the identities are algebraic (round-off only); the state-space
comparison is against the fit's own A(ω), B(ω), again algebraic.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ship_gym.conventions import HEAVE, PITCH, ROLL, SURGE, SWAY, YAW
from ship_gym.forces.base import ForceContext
from ship_gym.forces.radiation import RadiationMemory
from ship_gym.hydro import as_arrays, load_database
from ship_gym.hydro.forward_speed import (
    default_speed_cutoff,
    low_frequency_factor,
    momentum_rows,
    radiation_impedance,
    speed_corrected_coefficients,
    speed_coupling_matrix,
)

RTOL = 1e-12


def symmetric(rng: np.random.Generator, scale: float) -> np.ndarray:
    m = rng.normal(size=(6, 6)) * scale
    return m + m.T


def stf_table(a0: np.ndarray, b0: np.ndarray, w: float, u: float) -> tuple[np.ndarray, ...]:
    """Salvesen, Tuck & Faltinsen (1970) Table 1 without end terms, on zero-speed 3-D A⁰, B⁰.

    (Their axes are x forward, y port, z up with η₅ bow down; the rotation by π about x to ours
    flips sway, heave, pitch and yaw, and every term below keeps its form: each pairs DOFs whose
    sign products agree.)
    """
    a, b = a0.copy(), b0.copy()
    r = u / w**2
    # vertical plane
    a[HEAVE, PITCH] = a0[HEAVE, PITCH] - r * b0[HEAVE, HEAVE]
    b[HEAVE, PITCH] = b0[HEAVE, PITCH] + u * a0[HEAVE, HEAVE]
    a[PITCH, HEAVE] = a0[PITCH, HEAVE] + r * b0[HEAVE, HEAVE]
    b[PITCH, HEAVE] = b0[PITCH, HEAVE] - u * a0[HEAVE, HEAVE]
    a[PITCH, PITCH] = a0[PITCH, PITCH] + u * r * a0[HEAVE, HEAVE]
    b[PITCH, PITCH] = b0[PITCH, PITCH] + u * r * b0[HEAVE, HEAVE]
    # horizontal plane
    a[SWAY, YAW] = a0[SWAY, YAW] + r * b0[SWAY, SWAY]
    b[SWAY, YAW] = b0[SWAY, YAW] - u * a0[SWAY, SWAY]
    a[YAW, SWAY] = a0[YAW, SWAY] - r * b0[SWAY, SWAY]
    b[YAW, SWAY] = b0[YAW, SWAY] + u * a0[SWAY, SWAY]
    a[ROLL, YAW] = a0[ROLL, YAW] + r * b0[SWAY, ROLL]
    b[ROLL, YAW] = b0[ROLL, YAW] - u * a0[SWAY, ROLL]
    a[YAW, ROLL] = a0[YAW, ROLL] - r * b0[ROLL, SWAY]
    b[YAW, ROLL] = b0[YAW, ROLL] + u * a0[ROLL, SWAY]
    a[YAW, YAW] = a0[YAW, YAW] + u * r * a0[SWAY, SWAY]
    b[YAW, YAW] = b0[YAW, YAW] + u * r * b0[SWAY, SWAY]
    return a, b


def strip_theory_like(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Symmetric A⁰, B⁰ of a port–starboard symmetric hull (vertical and horizontal planes
    decoupled) without surge couplings: the structure STF's table assumes (the module's general
    form corrects any coupling)."""
    a, b = symmetric(rng, 1.0) + 10 * np.eye(6), symmetric(rng, 0.5)
    vertical, horizontal = [HEAVE, PITCH], [SWAY, ROLL, YAW]
    for m in (a, b):
        m[SURGE, 1:] = m[1:, SURGE] = 0.0
        m[np.ix_(vertical, horizontal)] = 0.0
        m[np.ix_(horizontal, vertical)] = 0.0
    return a, b


@pytest.mark.parametrize("u", [0.0, 3.0, -5.0, 12.4])
@pytest.mark.parametrize("w", [0.2, 0.9, 2.5, -0.7])
def test_coefficients_are_salvesen_tuck_faltinsen(u, w):
    rng = np.random.default_rng(int(10 * abs(w)) + 7)
    a0, b0 = strip_theory_like(rng)
    a_u, b_u = speed_corrected_coefficients(a0, b0, [w], u)
    a_ref, b_ref = stf_table(a0, b0, w, u)
    np.testing.assert_allclose(a_u[0], a_ref, rtol=RTOL, atol=RTOL * np.abs(a_ref).max())
    np.testing.assert_allclose(b_u[0], b_ref, rtol=RTOL, atol=RTOL * np.abs(b_ref).max())
    # the factorised impedance is the same operator
    s = -1j * w
    r = radiation_impedance(a0, b0, [w], u)[0]
    np.testing.assert_allclose(r, s * s * a_u[0] + s * b_u[0], rtol=RTOL, atol=1e-12 * abs(r).max())


def test_vertical_terms_leave_the_yaw_row_at_zero_speed_form():
    rng = np.random.default_rng(3)
    a0, b0 = strip_theory_like(rng)
    w, u = 0.8, 6.0
    a_all, b_all = speed_corrected_coefficients(a0, b0, [w], u, "all")
    a_v, b_v = speed_corrected_coefficients(a0, b0, [w], u, "vertical")
    a_n, b_n = speed_corrected_coefficients(a0, b0, [w], u, "none")
    rows = [SURGE, SWAY, HEAVE, ROLL, PITCH]
    np.testing.assert_allclose(a_v[0][rows], a_all[0][rows], rtol=RTOL)
    np.testing.assert_allclose(b_v[0][rows], b_all[0][rows], rtol=RTOL)
    # "vertical": the yaw row keeps only the inner (body-axis velocity) terms, as "none"
    np.testing.assert_allclose(a_v[0][YAW], a_n[0][YAW], rtol=RTOL)
    np.testing.assert_allclose(b_v[0][YAW], b_n[0][YAW], rtol=RTOL)
    # "none" is the zero-speed model fed with body-axis velocities: B35 = B35⁰ + U A33 only
    assert b_n[0][PITCH, HEAVE] == pytest.approx(b0[PITCH, HEAVE])
    assert b_n[0][HEAVE, PITCH] == pytest.approx(b0[HEAVE, PITCH] + u * a0[HEAVE, HEAVE])


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**31 - 1),
    u=st.floats(-15.0, 15.0, allow_nan=False),
    w=st.floats(0.05, 5.0, allow_nan=False),
)
def test_timman_newman_reverse_flow_relations(seed, u, w):
    # any symmetric A⁰, B⁰ without surge couplings (Kirchhoff's moment takes no surge momentum;
    # the inner kinematics give surge rows U A₁₃-like terms without a reverse-flow partner)
    rng = np.random.default_rng(seed)
    a0, b0 = symmetric(rng, 1.0), symmetric(rng, 1.0)
    for m in (a0, b0):
        m[SURGE, 1:] = m[1:, SURGE] = 0.0
    a_p, b_p = speed_corrected_coefficients(a0, b0, [w], u)
    a_m, b_m = speed_corrected_coefficients(a0, b0, [w], -u)
    scale = max(np.abs(a_p).max(), np.abs(b_p).max(), 1.0)
    np.testing.assert_allclose(a_p[0], a_m[0].T, atol=1e-12 * scale)
    np.testing.assert_allclose(b_p[0], b_m[0].T, atol=1e-12 * scale)


def test_coupling_matrix_is_the_body_axis_kinematics():
    # w = ż + U θ (bow-up pitch tilts body z aft), v = ẏ − U ψ: ν_p = ẋ + U L x to first order
    u, theta, psi = 7.0, 1e-4, -2e-4
    x = np.array([0.0, 0.0, 0.0, 0.0, theta, psi])
    # body-axis velocity of a ship moving at (U, 0, 0) in the earth frame, rotated by θ, ψ
    c_t, s_t, c_p, s_p = np.cos(theta), np.sin(theta), np.cos(psi), np.sin(psi)
    r_earth_to_body = np.array([[c_t, 0, -s_t], [0, 1, 0], [s_t, 0, c_t]]) @ np.array(
        [[c_p, s_p, 0], [-s_p, c_p, 0], [0, 0, 1]]
    )
    v_body = r_earth_to_body @ np.array([u, 0.0, 0.0])
    expected = (u * speed_coupling_matrix() @ x)[:3]
    np.testing.assert_allclose(v_body[1:], expected[1:], rtol=1e-6)


def test_bad_arguments():
    a = np.eye(6)
    with pytest.raises(ValueError, match="speed_terms='both'"):
        radiation_impedance(a, a, [1.0], 1.0, "both")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="ω_e = 0"):
        radiation_impedance(a, a, [0.0], 1.0)
    with pytest.raises(ValueError, match="forward_speed"):
        speed_corrected_coefficients(a, a, [1.0], float("nan"))
    with pytest.raises(ValueError, match="shape"):
        momentum_rows(np.eye(5))
    with pytest.raises(ValueError, match="speed_terms"):
        RadiationMemory(load_database("s175"), speed_terms="horizontal")  # type: ignore[arg-type]


def test_engine_radiation_has_the_same_impedance():
    """The state-space memory with its Kirchhoff term, probed by a harmonic ν_p at speed: its
    steady force equals −(s − U Lᵀ)(A_fit + B_fit/s) ν̂_p, A_fit, B_fit the fit's own."""
    db = load_database("s175")
    rad = RadiationMemory(db, method="state_space")
    ss = rad.state_space
    u, w = 8.0, 0.8
    s = -1j * w
    v_hat = np.zeros(6, complex)
    v_hat[HEAVE], v_hat[PITCH], v_hat[SWAY] = 1.0, 0.02j, 0.3
    # steady state of ż = A z + B ν_p: ẑ = (sI − A)⁻¹ B ν̂
    z_hat = np.linalg.solve(s * np.eye(ss.order) - ss.A, ss.B @ v_hat)

    # the model is linear in (ν_p, z): evaluate it on the real and imaginary parts
    def force(v: np.ndarray, z: np.ndarray) -> np.ndarray:
        nu = v.copy()
        nu[SURGE] += u
        ctx = ForceContext(t=0.0, eta=np.zeros(6), nu=nu, rotation=np.eye(3), forward_speed=u)
        return rad.evaluate(ctx, z)[0]

    f_hat = force(v_hat.real, z_hat.real) + 1j * force(v_hat.imag, z_hat.imag)
    am, b = ss.frequency_response(np.array([w]))
    a = am[0] + rad.A_inf
    lt = speed_coupling_matrix().T
    # −(A∞ s ν̂) is the left-hand side's; the model returns the rest of eq. (3) applied to ν̂_p
    expected = -(s * (a - rad.A_inf) + b[0]) @ v_hat + u * lt @ (a + b[0] / s) @ v_hat
    np.testing.assert_allclose(f_hat, expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())


def test_database_scale_coefficients_stay_finite_and_shift_as_expected():
    arr = as_arrays(load_database("s175"))
    i = 16
    w, u = float(arr.omega[i]), 8.28  # Fn 0.2
    a_u, b_u = speed_corrected_coefficients(arr.added_mass[i], arr.radiation_damping[i], [w], u)
    assert np.all(np.isfinite(a_u)) and np.all(np.isfinite(b_u))
    # the heave–pitch damping couplings become antisymmetric by ±U A33
    a33 = arr.added_mass[i, HEAVE, HEAVE]
    delta = b_u[0][HEAVE, PITCH] - b_u[0][PITCH, HEAVE]
    zero_speed = arr.radiation_damping[i, HEAVE, PITCH] - arr.radiation_damping[i, PITCH, HEAVE]
    assert delta - zero_speed == pytest.approx(2 * u * a33, rel=1e-12)


@pytest.mark.parametrize("w", [0.04, 0.15, 0.8])
def test_high_passed_moment_has_the_same_impedance(w):
    """Eq. (5): with the cut-off, the model's two filter states make the Kirchhoff moment
    H(ω) = s/(s + ω_c) times that without, exactly (harmonic steady state of the model's own
    state equations; algebraic, 1e-9), and the solver's impedance applies the same H."""
    db = load_database("s175")
    cutoff = 0.06
    plain = RadiationMemory(db, method="state_space")
    rad = RadiationMemory(db, method="state_space", speed_cutoff=cutoff)
    assert rad.n_states == plain.n_states + 2 and rad.n_filter_states == 2
    ss = rad.state_space
    u = 8.0
    s = -1j * w
    v_hat = np.zeros(6, complex)
    v_hat[HEAVE], v_hat[PITCH], v_hat[SWAY] = 1.0, 0.02j, 0.3
    z_mem = np.linalg.solve(s * np.eye(ss.order) - ss.A, ss.B @ v_hat)
    # the filter states' steady state: m̄ = ω_c/(s + ω_c) m, m the unfiltered moment rows
    m = rad.momentum_added_mass @ v_hat + rad.momentum_memory @ z_mem
    z_hat = np.concatenate([z_mem, cutoff / (s + cutoff) * m])

    def force(model: RadiationMemory, v: np.ndarray, z: np.ndarray) -> np.ndarray:
        nu = v.copy()
        nu[SURGE] += u
        ctx = ForceContext(t=0.0, eta=np.zeros(6), nu=nu, rotation=np.eye(3), forward_speed=u)
        return model.evaluate(ctx, z)[0]

    f_cut = force(rad, v_hat.real, z_hat.real) + 1j * force(rad, v_hat.imag, z_hat.imag)
    f_all = force(plain, v_hat.real, z_mem.real) + 1j * force(plain, v_hat.imag, z_mem.imag)
    f_none = f_all.copy()
    f_none[[PITCH, YAW]] -= u * m
    expected = f_none.copy()
    expected[[PITCH, YAW]] += u * m * s / (s + cutoff)
    np.testing.assert_allclose(f_cut, expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())
    # the state derivative of the filter is ω_c (m − m̄) = s m̄ in the steady state
    nu = v_hat.real.copy()
    nu[SURGE] += u
    ctx = ForceContext(t=0.0, eta=np.zeros(6), nu=nu, rotation=np.eye(3), forward_speed=u)
    zdot_re = rad.evaluate(ctx, z_hat.real)[1]
    nu = v_hat.imag.copy()
    nu[SURGE] += u
    ctx = ForceContext(t=0.0, eta=np.zeros(6), nu=nu, rotation=np.eye(3), forward_speed=u)
    zdot_im = rad.evaluate(ctx, z_hat.imag)[1]
    zdot = zdot_re + 1j * zdot_im
    np.testing.assert_allclose(zdot, s * z_hat, rtol=1e-9, atol=1e-9 * np.abs(s * z_hat).max())
    # the solver's impedance: the moment part scaled by H as well
    arr = as_arrays(db)
    a, b = arr.added_mass[10], arr.radiation_damping[10]
    r0 = radiation_impedance(a, b, [w], u, cutoff=0.0)
    r_none = radiation_impedance(a, b, [w], u, speed_terms="none")
    r_cut = radiation_impedance(a, b, [w], u, cutoff=cutoff)
    h = s / (s + cutoff)
    np.testing.assert_allclose(r_cut, r_none + h * (r0 - r_none), rtol=1e-12, atol=1e-3)


def test_cutoff_and_filter_bad_values():
    db = load_database("s175")
    with pytest.raises(ValueError, match="speed_cutoff"):
        RadiationMemory(db, speed_cutoff=-1.0)
    with pytest.raises(ValueError, match="cutoff"):
        radiation_impedance(np.eye(6), np.eye(6), [0.5], 3.0, cutoff=float("nan"))
    assert low_frequency_factor([0.0, 1e9], 0.1) == pytest.approx([0.0, 1.0])
    assert default_speed_cutoff(175.0, 9.81) == pytest.approx(0.25 * np.sqrt(9.81 / 175.0))
