"""Integrators against analytic solutions, and Holloway (2007)'s published stability limits.

References: the exact solution of the linear oscillator, the RK4 stability function
R(z) = 1 + z + z²/2 + z³/6 + z⁴/24 (the RK4 solution of a linear system is exactly R(λΔt)ᵏ per
mode), the principal root of the ABM4-PECE companion matrix, the exact solution of constant-rate
planar motion (a circle), a linear system with an auxiliary state solved by expm, and Holloway
(2007) eq. 11 and §5–6.
"""

import numpy as np
import pytest
from scipy.linalg import expm

from ship_gym.analysis.holloway import (
    HOLLOWAY_EQ11,
    HollowayReading,
    amplification_matrix,
    fit_limit_constants,
    forced_response_error,
    integrator_amplification_matrix,
    lumped_oscillator_rhs,
    oscillator_coefficients,
    spectral_radius,
    stability_limits,
    time_domain_growth,
)
from ship_gym.numerics.integrators import (
    RK4,
    AdamsBashforthMoulton,
    HollowayIntegrator,
    acceleration_from_force,
    holloway_mu,
    integrate,
)

OMEGA = 1.0  # [rad/s]
ZETA = 0.1


def oscillator(t, q, v):
    return -(OMEGA**2) * q - 2 * ZETA * OMEGA * v


def oscillator_lumped(t, q, v, acc_e):  # exact acceleration; ignores ẍ_e
    return oscillator(t, q, v)


def exact_oscillator(t):
    """x(t), ẋ(t) of ẍ + 2ζωẋ + ω²x = 0 from x = 1, ẋ = 0."""
    wd = OMEGA * np.sqrt(1 - ZETA**2)
    e = np.exp(-ZETA * OMEGA * t)
    x = e * (np.cos(wd * t) + ZETA * OMEGA / wd * np.sin(wd * t))
    v = -e * OMEGA**2 / wd * np.sin(wd * t)
    return x, v


def final_error(make, rhs, n_steps, t_end=20.0):
    tr = integrate(make(t_end / n_steps), rhs, 0.0, [1.0], [0.0], n_steps)
    x, v = exact_oscillator(t_end)
    return np.hypot(tr.q[-1, 0] - x, tr.v[-1, 0] - v)


def observed_order(make, rhs, steps):
    err = np.array([final_error(make, rhs, n) for n in steps])
    return np.log2(err[:-1] / err[1:])


# ---------------------------------------------------------------- order of convergence


@pytest.mark.parametrize(
    ("make", "rhs", "steps", "order"),
    [
        (RK4, oscillator, (200, 400, 800), 4),
        (AdamsBashforthMoulton, oscillator, (400, 800, 1600), 4),
        (lambda dt: AdamsBashforthMoulton(dt, mode="AB"), oscillator, (400, 800, 1600), 4),
        (lambda dt: HollowayIntegrator(dt, 1.0), oscillator_lumped, (200, 400, 800), 2),
        (
            lambda dt: HollowayIntegrator(dt, 1.0, startup="constant"),
            oscillator_lumped,
            (200, 400, 800),
            2,
        ),
    ],
    ids=["rk4", "abm-pece", "ab4", "holloway-mu1", "holloway-mu1-constant-start"],
)
def test_order_of_convergence_damped_oscillator(make, rhs, steps, order):
    # Halving Δt divides the global error by 2^order (16 for RK4/ABM4, 4 for Holloway's Taylor
    # scheme: its eq. 8 drops the Δt³/6 ẍ⁽³⁾ term, so local O(Δt³), global O(Δt²)). ωΔt ≤ 0.1
    # puts the ratios in the asymptotic range; ±0.25 in the exponent allows the next term.
    p = observed_order(make, rhs, steps)
    assert p[-1] == pytest.approx(order, abs=0.25), p


def test_rk4_amplitude_and_phase_match_stability_function():
    # Undamped oscillator: the RK4 solution is exactly Re(R(iωΔt)^k) (x₀ = 1, ẋ₀ = 0), and
    # R(iθ) = e^{iθ}(1 − θ⁶/144 + …) e^{−iθ⁵/120 + …}: amplitude error −kθ⁶/144, phase lag kθ⁵/120.
    dt, n = 0.2, 1000
    theta = OMEGA * dt
    tr = integrate(RK4(dt), lambda t, q, v: -(OMEGA**2) * q, 0.0, [1.0], [0.0], n)
    z = 1j * theta
    rk = (1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24) ** np.arange(n + 1)
    np.testing.assert_allclose(tr.q[:, 0], rk.real, atol=1e-12)
    np.testing.assert_allclose(tr.v[:, 0], -OMEGA * rk.imag, atol=1e-12)
    amp = np.hypot(tr.q[-1, 0], tr.v[-1, 0] / OMEGA)
    phase = np.arctan2(-tr.v[-1, 0] / OMEGA, tr.q[-1, 0])
    phase_err = np.angle(np.exp(1j * (phase - theta * n)))
    assert amp - 1 == pytest.approx(-n * theta**6 / 144, rel=0.05)
    assert phase_err == pytest.approx(-n * theta**5 / 120, rel=0.05)


def abm_pece_principal_root(lam_dt: complex) -> complex:
    """Principal root of AB4–AM4 PECE for y' = λy (companion matrix on y, f history)."""
    mat = np.zeros((5, 5), complex)
    for c, e in enumerate(np.eye(5)):
        y, f0, f1, f2, f3 = e
        yp = y + (55 * f0 - 59 * f1 + 37 * f2 - 9 * f3) / 24
        yn = y + (9 * lam_dt * yp + 19 * f0 - 5 * f1 + f2) / 24
        mat[:, c] = [yn, lam_dt * yn, f0, f1, f2]
    roots = np.linalg.eigvals(mat)
    return roots[np.argmin(np.abs(roots - np.exp(lam_dt)))]


def test_abm_amplitude_and_phase_match_principal_root():
    # After the RK4 start-up the ABM solution follows its principal root ρ(iωΔt)^k; the
    # parasitic roots are small (|ρ| < 0.5 here) and die out. Amplitude and phase errors after
    # 160 periods match the root's prediction to 2 % (the RK4 start-up adds ~1e-8).
    dt, n = 0.1, 10000
    tr = integrate(AdamsBashforthMoulton(dt), lambda t, q, v: -(OMEGA**2) * q, 0, [1.0], [0.0], n)
    root = abm_pece_principal_root(1j * OMEGA * dt)
    amp = np.hypot(tr.q[-1, 0], tr.v[-1, 0] / OMEGA)
    phase_err = np.angle(np.exp(1j * (np.arctan2(-tr.v[-1, 0] / OMEGA, tr.q[-1, 0]) - n * dt)))
    assert amp - 1 == pytest.approx(n * np.log(abs(root)), rel=0.02)
    assert phase_err == pytest.approx(n * (np.angle(root) - OMEGA * dt), rel=0.02)
    # PECE is slightly anti-dissipative on the imaginary axis (ρ − 1 ≈ 0.16 (ωΔt)⁶ per step,
    # see the class docstring): +1.6e-3 in amplitude and a 2.4e-3 rad phase lead after 10000
    # steps (160 periods) at 63 steps per period
    assert 0 < amp - 1 < 2e-3 and 0 < phase_err < 3e-3


# ---------------------------------------------------------------- kinematics and aux states


def planar_kinematics(q, v):
    """Earth-fixed (ẋ, ẏ, ψ̇) from body (u, v, r) — the planar case of η̇ = J(η)ν."""
    c, s = np.cos(q[2]), np.sin(q[2])
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])


def circle_exact(t, u=2.0, r=0.5):
    return np.array([u / r * np.sin(r * t), u / r * (1 - np.cos(r * t)), r * t])


@pytest.mark.parametrize(
    ("make", "rhs", "min_order"),
    [
        (RK4, lambda t, q, v: np.zeros(3), 3.75),
        (AdamsBashforthMoulton, lambda t, q, v: np.zeros(3), 3.75),
        (HollowayIntegrator, lambda t, q, v, ae: np.zeros(3), 1.75),
    ],
    ids=["rk4", "abm", "holloway"],
)
def test_general_kinematics_turning_circle(make, rhs, min_order):
    # Constant surge 2 m/s and yaw rate 0.5 rad/s: the track is a circle of radius 4 m.
    # Holloway's q-update with q̇ = f(q, v) uses eq. 6–7 on the q̇ history (second order).
    t_end, errs = 12.0, []
    for n in (60, 120, 240):
        integ = (
            make(t_end / n, kinematics=planar_kinematics)
            if make is not HollowayIntegrator
            else make(t_end / n, 1.0, kinematics=planar_kinematics)
        )
        tr = integrate(integ, rhs, 0.0, np.zeros(3), [2.0, 0.0, 0.5], n)
        errs.append(np.max(np.abs(tr.q[-1] - circle_exact(t_end))))
    order = np.log2(errs[-2] / errs[-1])
    assert order >= min_order, errs
    assert errs[-1] < 1e-3


LAM, K_Z = 0.7, 0.4  # aux filter rate [1/s], coupling [1/s²]


def aux_exact(t):
    """ẍ = −ω²x − K z, ż = −λz + ẋ from x = 1: y = (x, ẋ, z), y(t) = expm(Mt) y₀."""
    m = np.array([[0, 1, 0], [-(OMEGA**2), 0, -K_Z], [0, 1, -LAM]])
    return expm(m * t) @ np.array([1.0, 0.0, 0.0])


def aux_rhs(t, q, v, z):
    return -(OMEGA**2) * q - K_Z * z, -LAM * z + v


@pytest.mark.parametrize(
    ("make", "rhs", "order"),
    [
        (RK4, aux_rhs, 4),
        (AdamsBashforthMoulton, aux_rhs, 4),
        (lambda dt: HollowayIntegrator(dt, 1.0), lambda t, q, v, z, ae: aux_rhs(t, q, v, z), 2),
    ],
    ids=["rk4", "abm", "holloway"],
)
def test_auxiliary_states_converge(make, rhs, order):
    t_end, errs = 10.0, []
    for n in (200, 400, 800):
        tr = integrate(make(t_end / n), rhs, 0.0, [1.0], [0.0], n, z0=[0.0])
        errs.append(np.max(np.abs([tr.q[-1, 0], tr.v[-1, 0], tr.z[-1, 0]] - aux_exact(t_end))))
    assert np.log2(errs[-2] / errs[-1]) == pytest.approx(order, abs=0.25), errs


# ---------------------------------------------------------------- Holloway, lumped added mass

MASS_RATIO, ZETA_H, W_DT = 2.0, 0.2, 0.25  # A/m, ζ, ω_nΔt of the test case
MU_OPT = 1 / (1 + MASS_RATIO)  # m/(m + A)


def lumped_run(mu, n_steps, startup="rk4", dt=1.0):
    """Free decay x₀ = 1 of m ẍ = −(A ẍ_e + Bẋ + Cx) (Holloway eq. 10), m = 1."""
    a, b, c = oscillator_coefficients(MASS_RATIO, ZETA_H, W_DT / dt)
    rhs = lumped_oscillator_rhs(1.0, a, b, c)
    with np.errstate(over="ignore", invalid="ignore"):
        return integrate(HollowayIntegrator(dt, mu, startup=startup), rhs, 0, [1.0], [0.0], n_steps)


def envelope(tr, w=W_DT):
    with np.errstate(over="ignore", invalid="ignore"):
        return np.hypot(w * tr.q[:, 0], tr.v[:, 0])


def test_unstabilised_lumped_scheme_diverges_and_mu_opt_does_not():
    # μ = 1 feeds the added-mass error back with gain ≈ A/m per step (Holloway §1): the
    # response grows by orders of magnitude within 2 natural periods (50 steps), while
    # μ = m/(m + A) decays like the physical system (e^{−ζω_n t}: 1e-5 after 9 periods).
    bad = envelope(lumped_run(1.0, 50))
    assert not np.isfinite(bad[-1]) or bad[-1] > 1e6
    good = envelope(lumped_run(MU_OPT, 230))
    assert np.all(good[1:] <= good[0] * 1.0001) and good[-1] < 1e-4


def test_lumped_scheme_at_mu_opt_equals_unlumped_scheme_and_exact_solution():
    # At μ = m/(m + A), μẍ_c + (1 − μ)ẍ_e = −(Bẋ + Cx)/(m + A) exactly: the stabilisation
    # error vanishes (Holloway §6) and only the Taylor scheme's discretisation error remains.
    n = 200
    lumped = lumped_run(MU_OPT, n)
    a, b, c = oscillator_coefficients(MASS_RATIO, ZETA_H, W_DT)
    true_rhs = lambda t, q, v, ae: -(b * v + c * q) / (1 + a)  # noqa: E731
    plain = integrate(HollowayIntegrator(1.0, 1.0), true_rhs, 0, [1.0], [0.0], n)
    np.testing.assert_allclose(lumped.q, plain.q, atol=1e-12)
    # exact damped decay; O(Δt²) error: |error| < 2 % of the initial amplitude at ω_nΔt = 0.25
    wn = W_DT
    wd = wn * np.sqrt(1 - ZETA_H**2)
    t = lumped.t
    x_exact = np.exp(-ZETA_H * wn * t) * (np.cos(wd * t) + ZETA_H * wn / wd * np.sin(wd * t))
    assert np.max(np.abs(lumped.q[:, 0] - x_exact)) < 0.02


@pytest.mark.parametrize(
    ("factor", "limit", "stable"),
    [(1.05, 1, False), (0.95, 1, True), (0.95, 0, False), (1.05, 0, True)],
    ids=["above-upper", "below-upper", "below-lower", "above-lower"],
)
def test_lumped_stability_band_edges_in_time_domain(factor, limit, stable):
    # Holloway eq. 11: 0.22/(A/m + 1) < μ < 1.14/(A/m + 1). 5 % outside either limit the
    # free response (start-up error deliberately introduced, as in his Fig. 1) grows by orders
    # of magnitude in 4000 steps (160 periods); 5 % inside it decays.
    mu = factor * HOLLOWAY_EQ11[limit] / (1 + MASS_RATIO)
    env = envelope(lumped_run(mu, 4000, startup="constant"))
    if stable:
        assert env[-1] < 1e-6 * env[0]
    else:
        assert not np.isfinite(env[-1]) or env[-1] > 1e3 * env[0]


def test_reproduces_holloway_eq11():
    # The acceptance: limits within 5 % of 0.22/(A/m + 1) and 1.14/(A/m + 1) over
    # A/m = 0.1…10 at ζ = 0.2, ω_nΔt = 0.25 (ζ, ω_n of m + A). The form c/(A/m + 1) is exact
    # (the recurrence depends on μ(1 + A/m) only), hence the 1e-9 spread.
    r = np.geomspace(0.1, 10, 15)
    lo, up = stability_limits(r, 0.2, 0.25)
    for mu, ref in ((lo, HOLLOWAY_EQ11[0]), (up, HOLLOWAY_EQ11[1])):
        fit = fit_limit_constants(r, mu, ref)
        assert fit["max_rel_deviation"] < 0.05
        assert fit["const_spread"] < 1e-9
        assert fit["c2"] == pytest.approx(1.0, abs=1e-6)
    assert lo[0] * 1.1 == pytest.approx(0.2194, abs=5e-4)
    assert up[0] * 1.1 == pytest.approx(1.1401, abs=5e-4)


def test_dry_mass_reading_does_not_reproduce_eq11():
    # Defining ζ and ω_n with m instead of m + A breaks the c/(A/m + 1) form: the lower limit
    # is off by far more than 5 % at A/m = 10 — the paper's numbers need the virtual mass.
    r = np.array([0.1, 10.0])
    lo, _ = stability_limits(r, 0.2, 0.25, HollowayReading(mass_basis="dry"))
    assert abs(lo[1] * 11 / HOLLOWAY_EQ11[0] - 1) > 0.5


def test_integrator_implements_the_analysed_recurrence():
    # The amplification matrix measured on HollowayIntegrator equals the analytic one.
    for mu in (0.1, MU_OPT, 0.4):
        measured = integrator_amplification_matrix(MASS_RATIO, mu, ZETA_H, W_DT)
        analytic = amplification_matrix(MASS_RATIO, mu, ZETA_H, W_DT)[:6, :6]
        np.testing.assert_allclose(measured, analytic, atol=1e-13)


def test_time_domain_growth_equals_spectral_radius():
    # Growth per step of the integrator's free response over 2000 steps vs the largest
    # |eigenvalue|: equal to the accuracy of the envelope estimate (≈ 1e-4).
    mu = np.array([0.2, 0.23, 1.1, 1.18]) / (1 + MASS_RATIO)
    growth = time_domain_growth(MASS_RATIO, mu, ZETA_H, W_DT, n_steps=4000)
    rho = spectral_radius(MASS_RATIO, mu, ZETA_H, W_DT)
    np.testing.assert_allclose(growth, rho, atol=2e-4)
    assert list(rho > 1) == [True, False, False, True]


def test_time_step_and_damping_dependence():
    # Holloway §5: μ_min → 0 as Δt → 0; the band narrows as ζ grows (Fig. 2b–c); no μ works
    # beyond ≈ 3.7 steps per natural period.
    lo, up = stability_limits(1.0, 0.2, [0.01, 0.1, 0.25, 0.5])
    assert np.all(np.diff(lo) > 0) and lo[0] * 2 < 0.01
    assert np.all(up * 2 > 1.1)
    lo_z, up_z = stability_limits(1.0, [0.1, 0.2, 0.4, 0.8], 0.25)
    assert np.all(np.diff(lo_z) > 0) and np.all(np.diff(up_z) < 0)
    lo_big, _ = stability_limits(1.0, 0.2, 2 * np.pi / 3.5)
    assert np.isnan(lo_big)


def test_discretisation_error_matches_holloway_section6():
    # Forced response at ω = ω_n, A/m = 1, μ = m/(m + A), ω_nΔt = 0.25. Holloway §6: amplitude
    # −0.70, −0.32, −0.15 % and phase 17.5, 15.9, 15.1° for ζ = 0.1, 0.2, 0.4. Amplitudes
    # agree to his rounding (±0.015 %-points); his phases are ours + ω_nΔt (a one-step
    # offset in his phase reference), to ±0.1°.
    amp, phase = forced_response_error(1.0, 0.5, [0.1, 0.2, 0.4], 0.25)
    np.testing.assert_allclose(100 * amp, [-0.70, -0.32, -0.15], atol=0.015)
    np.testing.assert_allclose(np.degrees(phase + 0.25), [17.5, 15.9, 15.1], atol=0.1)


def test_per_dof_mu_keeps_dofs_independent():
    # Holloway §7: each DOF's μ can be chosen independently; a vector μ runs each DOF exactly as
    # its own scalar integrator would.
    r = np.array([2.0, 0.5])
    a, b, c = oscillator_coefficients(r, 0.2, 0.25)
    rhs = lumped_oscillator_rhs(1.0, a, b, c)
    mu = 1 / (1 + r)
    both = integrate(HollowayIntegrator(1.0, mu), rhs, 0, [1.0, -0.5], [0.0, 0.3], 100)
    for i in range(2):
        one = integrate(
            HollowayIntegrator(1.0, mu[i]),
            lumped_oscillator_rhs(1.0, a[i], b[i], c[i]),
            0,
            [[1.0, -0.5][i]],
            [[0.0, 0.3][i]],
            100,
        )
        np.testing.assert_array_equal(both.q[:, i], one.q[:, 0])


def test_history_round_trip_continues_identically():
    a, b, c = oscillator_coefficients(MASS_RATIO, ZETA_H, W_DT)
    rhs = lumped_oscillator_rhs(1.0, a, b, c)
    ref = integrate(HollowayIntegrator(1.0, 0.3), rhs, 0, [1.0], [0.0], 20)
    integ = HollowayIntegrator(1.0, 0.3)
    q, v = np.array([1.0]), np.array([0.0])
    for k in range(10):
        q, v, _ = integ.step(float(k), q, v, rhs)
    hist = integ.history
    other = HollowayIntegrator(1.0, 0.3)
    other.set_history(10.0, **hist)
    for k in range(10, 20):
        q, v, _ = other.step(float(k), q, v, rhs)
    np.testing.assert_array_equal(q, ref.q[-1])


# ---------------------------------------------------------------- bookkeeping and validation


def test_evaluations_per_step():
    rhs = lambda t, q, v: -q  # noqa: E731
    for integ, per_step, startup in (
        (RK4(0.1), 4, 0),
        (AdamsBashforthMoulton(0.1), 2, 3 * 4 + 1),
        (AdamsBashforthMoulton(0.1, mode="AB"), 1, 3 * 4 + 1),
    ):
        integrate(integ, rhs, 0, [1.0], [0.0], 10)
        assert integ.n_evaluations == startup + per_step * (10 - (startup > 0) * 3)
    # Holloway: one evaluation per μ-Taylor step; the RK4 start-up costs ≤ n + 17 (Jacobian
    # n + 1, then 2 per stage for a force that is affine in ẍ_e)
    a, b, c = oscillator_coefficients([2.0, 1.0, 0.5], 0.2, 0.25)
    hol = HollowayIntegrator(1.0, 0.3)
    integrate(hol, lumped_oscillator_rhs(1.0, a, b, c), 0, np.ones(3), np.zeros(3), 2)
    n_start = hol.n_evaluations
    assert n_start <= 3 + 17
    integrate(hol, lumped_oscillator_rhs(1.0, a, b, c), 0, np.ones(3), np.zeros(3), 12)
    assert hol.n_evaluations - n_start == n_start + 10


def test_holloway_mu_and_mass_matrix_helpers():
    np.testing.assert_allclose(holloway_mu(2.0, 6.0), 0.25)
    m = np.diag([1.0, 2.0]) + 0.1
    a_e = np.diag([1.0, 6.0])
    np.testing.assert_allclose(holloway_mu(m, a_e), [1.1 / 2.1, 2.1 / 8.1])
    integ = HollowayIntegrator.from_added_mass(0.1, m, a_e)
    np.testing.assert_allclose(integ.mu, [1.1 / 2.1, 2.1 / 8.1])
    k = np.array([[3.0, -1.0], [-1.0, 2.0]])
    rhs = acceleration_from_force(lambda t, q, v: -k @ q, m)
    np.testing.assert_allclose(rhs(0, np.array([1.0, 2.0]), None), -np.linalg.solve(m, k @ [1, 2]))
    rhs_z = acceleration_from_force(lambda t, q, v, z: (-k @ q, -z), m)
    acc, zd = rhs_z(0, np.array([1.0, 2.0]), None, np.array([3.0]))
    np.testing.assert_allclose(acc, -np.linalg.solve(m, k @ [1, 2]))
    np.testing.assert_allclose(zd, [-3.0])


def test_holloway_startup_is_independent_of_mu():
    # The RK4 start-up solves ẍ = rhs(…, ẍ) exactly, so the first two steps do not depend on μ.
    a, b, c = oscillator_coefficients(MASS_RATIO, ZETA_H, W_DT)
    rhs = lumped_oscillator_rhs(1.0, a, b, c)
    runs = [integrate(HollowayIntegrator(1.0, mu), rhs, 0, [1.0], [0.0], 2) for mu in (0.1, 1.0)]
    np.testing.assert_allclose(runs[0].q, runs[1].q, atol=1e-12)


@pytest.mark.parametrize(
    ("factory", "match"),
    [
        (lambda: RK4(0.0), "dt"),
        (lambda: RK4(float("nan")), "dt"),
        (lambda: RK4(0.1, kinematics=3), "kinematics"),
        (lambda: AdamsBashforthMoulton(0.1, mode="PEC"), "mode"),
        (lambda: HollowayIntegrator(0.1, 0.0), "mu"),
        (lambda: HollowayIntegrator(0.1, [[0.5]]), "mu"),
        (lambda: HollowayIntegrator(0.1, 0.5, startup="euler"), "startup"),
        (lambda: holloway_mu(-1.0, 1.0), "mass"),
        (lambda: holloway_mu(1.0, -2.0), "virtual"),
        (lambda: acceleration_from_force(lambda *a: 0, np.zeros((2, 2))), "singular"),
        (lambda: stability_limits(1.0, 0.2, -0.25), "omega_n_dt"),
        (lambda: HollowayReading(mass_basis="wet"), "mass_basis"),
    ],
)
def test_bad_construction_raises(factory, match):
    with pytest.raises(ValueError, match=match):
        factory()


def test_bad_steps_raise():
    rhs = lambda t, q, v: -q  # noqa: E731
    with pytest.raises(ValueError, match="must match"):
        RK4(0.1).step(0.0, np.zeros(2), np.zeros(3), rhs)
    with pytest.raises(ValueError, match="shape"):
        RK4(0.1).step(0.0, np.zeros(2), np.zeros(2), lambda t, q, v: np.zeros(3))
    with pytest.raises(ValueError, match="1-D"):
        RK4(0.1).step(0.0, np.zeros((2, 2)), np.zeros(2), rhs)
    with pytest.raises(ValueError, match=r"\(acceleration, zdot\)"):
        RK4(0.1).step(0.0, np.zeros(2), np.zeros(2), lambda t, q, v, z: -q, z=np.zeros(1))
    abm = AdamsBashforthMoulton(0.1)
    q, v, _ = abm.step(0.0, [1.0], [0.0], rhs)
    with pytest.raises(ValueError, match="reset"):
        abm.step(0.5, q, v, rhs)  # time jump
    with pytest.raises(ValueError, match="reset"):
        abm.step(0.1, np.zeros(2), np.zeros(2), rhs)  # size change
    abm.reset()
    abm.step(0.5, np.zeros(2), np.zeros(2), rhs)  # fine after reset
    hol = HollowayIntegrator(0.1, np.array([0.5, 0.5, 0.5]))
    with pytest.raises(ValueError, match="mu has shape"):
        hol.step(0.0, np.zeros(2), np.zeros(2), lambda t, q, v, ae: -q)
