"""The 1-DOF roll equation (McCue & Campbell eq. 1/2) against closed-form results."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from ship_gym.roll.equation import RollEquation


def test_linear_undamped_free_matches_closed_form():
    # φ̈ + ω²φ = 0: φ = φ0 cos ωt + φ̇0/ω sin ωt. RK4's global error ~ T (ωh)⁴ ω φ/120 ≈ 1e-11
    # here (ωh = 0.0062, 10 periods); 1e-9 leaves room for rounding.
    w = 0.62
    eq = RollEquation(c1=w * w)
    phi0 = np.array([0.3, -0.1, 0.0])
    phidot0 = np.array([0.0, 0.2, -0.05])
    tr = eq.integrate(phi0, phidot0, t_end=100.0, dt=0.01, record_every=10)
    t = tr.time[:, None]
    exact = phi0 * np.cos(w * t) + phidot0 / w * np.sin(w * t)
    exact_rate = -phi0 * w * np.sin(w * t) + phidot0 * np.cos(w * t)
    np.testing.assert_allclose(tr.phi, exact, atol=1e-9)
    np.testing.assert_allclose(tr.phidot, exact_rate, atol=1e-9)


def test_linear_damped_forced_matches_closed_form():
    # φ̈ + 2ζω φ̇ + ω²φ = F sin(Ωt + ε): homogeneous part decays; the steady response is
    # F/√((ω²−Ω²)² + (2ζωΩ)²) sin(Ωt + ε − δ), tan δ = 2ζωΩ/(ω²−Ω²). The full solution from rest
    # is the steady part plus the homogeneous solution fitted to φ(0) = φ̇(0) = 0.
    w, zeta, F, W, eps = 0.62, 0.05, 0.02, 0.527, 0.3
    eq = RollEquation(
        b1=2 * zeta * w, c1=w * w, forcing_amplitude=F, forcing_frequency=W, forcing_phase=eps
    )
    tr = eq.integrate(0.0, 0.0, t_end=60.0, dt=0.02, record_every=5)
    amp = F / math.hypot(w * w - W * W, 2 * zeta * w * W)
    delta = math.atan2(2 * zeta * w * W, w * w - W * W)
    wd = w * math.sqrt(1 - zeta**2)
    s0, sd0 = amp * math.sin(eps - delta), amp * W * math.cos(eps - delta)
    a = -s0  # φ(0) = 0
    b = (zeta * w * a - sd0) / wd  # φ̇(0) = 0: sd0 − ζω a + ωd b = 0
    t = tr.time
    exact = amp * np.sin(W * t + eps - delta) + np.exp(-zeta * w * t) * (
        a * np.cos(wd * t) + b * np.sin(wd * t)
    )
    # RK4 error ≈ 1e-9 at h = 0.02 over 60 s (ωh ≈ 0.012); tolerance 1e-8.
    np.testing.assert_allclose(tr.phi, exact, atol=1e-8)


def test_energy_conserved_without_damping_or_forcing():
    # Edith Terkol restoring, b = 0, F = 0: ½φ̇² + V(φ) is a first integral. RK4's energy drift is
    # O(h⁴) per unit time; at h = 0.01 over 300 s it is ≈ 4e-9 relative on the 0.7 rad orbit (the
    # quintic restoring has large higher derivatives there). Tolerance 2e-8; the b₁ = 0.0043
    # damping alone would remove ~70 % of it.
    et = RollEquation.edith_terkol()
    eq = RollEquation(c1=et.c1, c2=et.c2, c3=et.c3, c4=et.c4, c5=et.c5)
    phi0 = np.array([0.5, -0.7, 0.2, 0.0])
    phidot0 = np.array([0.1, 0.05, -0.3, 0.2])
    tr = eq.integrate(phi0, phidot0, t_end=300.0, dt=0.01, record_every=100)
    e = eq.energy(tr.phi, tr.phidot)
    np.testing.assert_allclose(e, np.broadcast_to(e[0], e.shape), rtol=2e-8)
    assert not np.any(tr.capsized)


def test_rk4_is_fourth_order():
    # Max error over the common instants (every 0.4 s) against a reference at h = 0.2/64;
    # halving h must divide it by 2⁴ = 16: observed order within ±0.15 of 4 (asymptotic regime
    # at ωh ≈ 0.03–0.12). The smooth eq. 2 model is used: the |φ|φ and |φ̇|φ̇ terms of eq. 1 have
    # a discontinuous second derivative at 0, which lowers the observed order of any RK scheme.
    eq = RollEquation.mccue_campbell(0.0098, 0.0388, 0.5147, -0.7052, 0.0220)

    def run(h: float) -> np.ndarray:
        return eq.integrate(0.6, 0.1, t_end=40.0, dt=h, record_every=round(0.4 / h)).phi

    ref = run(0.2 / 64)
    errors = np.array([np.max(np.abs(run(h) - ref)) for h in (0.2, 0.1, 0.05)])
    orders = np.log2(errors[:-1] / errors[1:])
    assert np.all(np.abs(orders - 4.0) < 0.15), orders


def test_potential_energy_derivative_is_restoring():
    # Central difference error is O(h²·V''') ≈ 1e-12 at h = 1e-6; rounding ≈ 1e-16/1e-6 = 1e-10.
    eq = RollEquation.edith_terkol()
    phi = np.linspace(-1.2, 1.2, 49)
    h = 1e-6
    dv = (eq.potential_energy(phi + h) - eq.potential_energy(phi - h)) / (2 * h)
    np.testing.assert_allclose(dv, eq.restoring(phi), atol=1e-9)
    assert eq.potential_energy(0.0) == 0.0


def test_edith_terkol_vanishing_angle_is_root_of_restoring():
    # Bracketed root of c1 + c2 x + c3 x² + c4 x³ + c5 x⁴ (the restoring divided by φ);
    # brentq to 1e-14, so the two agree to ~1e-12.
    eq = RollEquation.edith_terkol()
    pv = eq.vanishing_angle()
    x = brentq(
        lambda x: eq.c1 + eq.c2 * x + eq.c3 * x**2 + eq.c4 * x**3 + eq.c5 * x**4,
        0.5,
        1.0,
        xtol=1e-14,
    )
    assert pv == pytest.approx(x, abs=1e-12)
    assert 0.85 < pv < 0.86  # ≈ 49°
    # restoring positive below, negative just above, odd symmetry
    assert eq.restoring(0.5 * pv) > 0 > eq.restoring(pv + 1e-3)
    assert eq.restoring(-0.5 * pv) == pytest.approx(-eq.restoring(0.5 * pv))


def test_vanishing_angle_of_fitted_cubic_model():
    # Eq. 2 fit from ⟨−0.4, −0.35⟩: c_u1 φ + c_u3 φ³ = 0 at φ = √(−c_u1/c_u3).
    eq = RollEquation.mccue_campbell(0.0098, 0.0388, 0.5147, -0.7052, 0.0220)
    assert eq.vanishing_angle() == pytest.approx(math.sqrt(0.5147 / 0.7052), rel=1e-12)
    assert RollEquation(c1=0.4, c3=0.1).vanishing_angle() == math.inf
    assert RollEquation(c1=-0.1).vanishing_angle() == 0.0


def test_compiled_and_numpy_paths_agree():
    # Same arithmetic in a different order (numpy vs the numba loop): agreement to rounding.
    eq = RollEquation.edith_terkol(forcing_amplitude=0.05)
    phi0 = np.linspace(-0.8, 0.8, 7)[:, None]
    phidot0 = np.linspace(-0.5, 0.5, 5)[None, :]
    pv = eq.vanishing_angle()
    a = eq.integrate(phi0, phidot0, 80.0, 0.05, moment=0.01, stop_at=pv, record_every=4)
    b = eq.integrate(
        phi0, phidot0, 80.0, 0.05, moment=lambda t, x, v: 0.01, stop_at=pv, record_every=4
    )
    assert a.phi.shape == (401, 7, 5)
    np.testing.assert_allclose(a.phi, b.phi, atol=1e-12)
    np.testing.assert_array_equal(a.capsized, b.capsized)
    np.testing.assert_allclose(a.capsize_time, b.capsize_time, atol=1e-9)
    assert a.capsized.any() and not a.capsized.all()


def test_capsize_time_is_interpolated_and_trajectory_frozen():
    # Free drift φ = φ̇0 t (no restoring): crossing 0.55 rad at 1 rad/s happens at t = 0.55 s
    # exactly; linear interpolation between the straddling steps is exact for a linear motion.
    eq = RollEquation()
    tr = eq.integrate([0.0, 0.0], [1.0, 0.1], t_end=2.0, dt=0.1, stop_at=0.55)
    np.testing.assert_array_equal(tr.capsized, [True, False])
    assert tr.capsize_time[0] == pytest.approx(0.55, abs=1e-12)
    assert math.isnan(tr.capsize_time[1])
    assert tr.final_phi[0] == pytest.approx(0.6)  # held at the first step beyond the limit
    assert tr.final_phi[1] == pytest.approx(0.2)


def test_moment_array_is_per_trajectory():
    # φ̈ = m with φ(0) = φ̇(0) = 0: φ(t) = m t²/2 (RK4 exact for a quadratic).
    eq = RollEquation()
    m = np.array([0.1, -0.2, 0.0])
    tr = eq.integrate(np.zeros(3), 0.0, t_end=3.0, dt=0.1, moment=m, record_every=None)
    np.testing.assert_allclose(tr.final_phi, m * 4.5, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(tr.time, [0.0, 3.0])


def test_advance_equals_integrate():
    eq = RollEquation.edith_terkol(forcing_amplitude=0.02)
    phi = np.array([0.1, 0.25])
    phidot = np.array([0.0, 0.2])
    amp = np.array([0.02, 0.04])
    phase = np.array([0.0, 1.0])
    m = np.array([0.0, 0.01])
    x, v, caps = eq.advance(5.0, phi, phidot, 20, 0.05, m, amp, phase, stop_at=0.27)
    tr = eq.integrate(
        phi,
        phidot,
        6.0,
        0.05,
        t0=5.0,
        moment=m,
        forcing_amplitude=amp,
        forcing_phase=phase,
        stop_at=0.27,
    )
    np.testing.assert_array_equal(x, tr.final_phi)
    np.testing.assert_array_equal(v, tr.final_phidot)
    np.testing.assert_array_equal(caps, [False, True])


@pytest.mark.parametrize(
    "kwargs",
    [
        {"t_end": 1.0, "dt": 0.3},
        {"t_end": 1.0, "dt": 0.0},
        {"t_end": 1.0, "dt": float("nan")},
        {"t_end": -1.0, "dt": 0.1},
        {"t_end": 1.0, "dt": 0.1, "stop_at": -0.1},
        {"t_end": 1.0, "dt": 0.1, "record_every": 3},
        {"t_end": 1.0, "dt": 0.1, "moment": [np.nan]},
    ],
)
def test_bad_arguments_raise(kwargs):
    with pytest.raises(ValueError):
        RollEquation.edith_terkol().integrate(0.1, 0.0, **kwargs)


def test_bad_coefficient_and_shapes_raise():
    with pytest.raises(ValueError, match="c3"):
        RollEquation(c3=float("inf"))
    with pytest.raises(ValueError, match="broadcast"):
        RollEquation(c1=1.0).integrate(np.zeros(3), np.zeros(2), 1.0, 0.1)
