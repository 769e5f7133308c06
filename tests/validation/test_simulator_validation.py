"""Validation of the time-domain simulator (S175) against linear theory and hydrostatics.

What is checked (the issue's items), and against what:

1. Still water: at the free-floating equilibrium, with the full force set (nonlinear
   Froude–Krylov + hydrostatics, radiation memory, Ikeda viscous roll), the ship stays put.
2. Free decay in heave, roll and pitch (surge, sway and yaw held; the heave–pitch coupling of
   C35, A35, B35 remains, roll is uncoupled from both by port–starboard symmetry):
   * periods against the damped 1-DOF prediction T_d = T_n/√(1 − ζ²), T_n = 2π/ω_n with
     ω_n² (M_ii + A_ii(ω_n)) = C_ii (:func:`ship_gym.hydro.rao.natural_frequency`) and
     ζ = B_ii(ω_n)/(2 (M_ii + A_ii(ω_n)) ω_n);
   * the whole decay against the exact solution of the *linear Cummins equation built from the
     database A(ω), B(ω)* (a frequency-domain step response, independent of the retardation
     kernels and of the state-space fit): "damping decays as the memory dictates";
   * roll, lightly damped, against the logarithmic decrement δ = π B/((M + A) ω_n).
3. Linear limit: steady regular-wave amplitudes and phases against the frequency-domain RAO
   (:func:`ship_gym.hydro.rao.response_amplitude_operator`) from the same database, and the
   diagnosis of the one case that misses 2 % (roll in beam seas: Froude–Krylov quadrature).
4. Large amplitude: the roll period from a 40° heel against the energy-method period of the
   calm-water restoring (1-DOF and GZ curve), and the static heel under a heeling moment
   against the GZ curve, far beyond deck-edge immersion (≈ 25°).
5. Convolution against state-space radiation memory in an irregular sea, at two time steps.
6. RK4 and Holloway integrators against each other (orders of convergence).

Conventions: capytaine's x(t) = Re(ξ a e^{−iωt}) for complex amplitudes (the wave crest at O at
t = 0, :mod:`ship_gym.hydro.rao`); body axes about O, z down.

Known deviations (measured, marked ``xfail(strict=True)``):

* Roll RAO in beam seas: 5–13 % from the database RAO. The time-domain Froude–Krylov roll moment
  (exact integral of a vertex-linear pressure over the closed mesh) is 3–4 % larger than the BEM's
  (panel-centroid quadrature on the same mesh); both converge to the same value under mesh
  refinement (second order), and since FK and diffraction nearly cancel in the beam-sea roll
  moment, the excitation differs by 5–13 %. With the time domain's own linear excitation in the
  frequency-domain solution the roll amplitudes agree within 0.3 %.
* Pitch decay period: not within 2 % of the 1-DOF prediction (+7.7 %): with ζ ≈ 0.17 and
  A55 halving across the band around ω_n, the decay is no single damped mode; it agrees with the
  exact linear Cummins solution.
* Roll with radiation damping only and the state-space memory grows slowly (the fit's B44 at
  ω_φ is slightly negative, ≈ −0.3 % of the peak B44, against +0.1 % in the database).
"""

from __future__ import annotations

import functools
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from ship_gym.engine.ship import ShipSetup, build_simulator, wave_field_for
from ship_gym.engine.simulator import SimulationResult, Simulator
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.forces.diffraction import Diffraction
from ship_gym.forces.froude_krylov import (
    FroudeKrylovHydrostatics,
    HullPanels,
    WaveComponents,
    froude_krylov_hydrostatic,
)
from ship_gym.forces.radiation import RadiationMemory
from ship_gym.forces.viscous import RollDampingCoefficients, ViscousRollDamping
from ship_gym.hull import equilibrium, load_hull, righting_arm
from ship_gym.hull.hydrostatics import pressure_integral
from ship_gym.hull.mesh import immersed_part
from ship_gym.hydro import load_database
from ship_gym.hydro.database import as_arrays
from ship_gym.hydro.rao import natural_frequency, response_amplitude_operator
from ship_gym.kinematics import rotation_matrix
from ship_gym.waves.sea_state import IrregularSea, RegularWave

HEAVE, ROLL, PITCH = 2, 3, 4
# surge, sway and yaw have no restoring: held wherever a DOF would otherwise drift
HOLD_HORIZONTAL = (False, False, True, True, True, False)
ROLL_ONLY = (False, False, False, True, False, False)


# ============================================================================ shared helpers
@functools.cache
def s175() -> SimpleNamespace:
    """Hull, database and calm-water equilibrium of the S175 (loaded once per session)."""
    hull = load_hull("s175")
    db = load_database("s175")
    arr = as_arrays(db)
    eq = equilibrium(hull)
    return SimpleNamespace(
        hull=hull,
        db=db,
        arr=arr,
        eq=eq,
        base=np.array([0.0, 0.0, eq.heave, 0.0, eq.trim, 0.0]),
        M=arr.inertia_matrix,
        C=arr.hydrostatic_stiffness,
    )


@functools.cache
def ikeda_b1() -> float:
    """Linear roll damping used where a linear model is needed [N·m·s/rad].

    The simplified-Ikeda B1 of the S175 is tiny (ζ ≈ 2.5e-4); the damping that matters is the
    quadratic B2. Its equivalent linear value at a 5° roll amplitude and the roll natural
    frequency, B1 + (8/3π) ω φa B2 ≈ 8.1e6 N·m·s (ζ ≈ 0.6 %), is used as a *purely linear*
    coefficient (B2 = 0) in both the time and the frequency domain.
    """
    s = s175()
    w_roll = natural_frequency(s.db, "Roll")
    coeffs = ViscousRollDamping.from_hull(s.hull, omega=w_roll).coefficients
    return float(coeffs.equivalent_linear(np.radians(5.0), w_roll))


def simulate(
    forces: list[ForceModel],
    *,
    eta0: np.ndarray,
    duration: float,
    dt: float,
    free: tuple[bool, ...],
    wave_field=None,
) -> SimulationResult:
    s = s175()
    sim = Simulator(s.hull, forces, wave_field=wave_field, dt=dt, free_dofs=free)
    sim.reset(eta=eta0)
    return sim.run(duration)


def zero_crossings(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Times where x changes sign (linear interpolation between samples) [s]."""
    i = np.flatnonzero(np.sign(x[:-1]) != np.sign(x[1:]))
    return t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])


def peak_amplitudes(x: np.ndarray) -> np.ndarray:
    """|x| at its local maxima, refined by a parabola through the three samples around each."""
    a = np.abs(x)
    i = np.flatnonzero((a[1:-1] >= a[:-2]) & (a[1:-1] > a[2:])) + 1
    y0, y1, y2 = a[i - 1], a[i], a[i + 1]
    return y1 + (y0 - y2) ** 2 / (8.0 * (2.0 * y1 - y0 - y2))


def fit_harmonic(t: np.ndarray, x: np.ndarray, omega: float, t_start: float) -> complex:
    """Complex amplitude X of x ≈ Re(X e^{−iωt}) + mean, least squares over t ≥ t_start."""
    m = t >= t_start - 1e-9
    tt = t[m]
    design = np.column_stack([np.cos(omega * tt), np.sin(omega * tt), np.ones_like(tt)])
    c, *_ = np.linalg.lstsq(design, x[m], rcond=None)
    return complex(c[0], c[1])


def radiation_coefficients(arr, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Database A(ω), B(ω) on any grid ≥ 0: cubic spline in band (A(0) at ω = 0, B(0) = 0).

    Above the highest database frequency ω_max: A → A(∞) + (A(ω_max) − A(∞))(ω_max/ω)² and
    B ∝ ω⁻² (the tail exponent the radiation model fits for the S175). This only shapes the
    first instants of a decay; the oscillation is governed by A, B near ω_n, well inside the
    band.
    """
    wg = np.concatenate([[0.0], arr.omega])
    ag = np.concatenate([arr.added_mass_zero[None], arr.added_mass])
    bg = np.concatenate([np.zeros((1, 6, 6)), arr.radiation_damping])
    wc = np.minimum(omega, wg[-1])
    a = CubicSpline(wg, ag, axis=0)(wc)
    b = CubicSpline(wg, bg, axis=0)(wc)
    hi = omega > wg[-1]
    f = ((wg[-1] / omega[hi]) ** 2)[:, None, None]
    a[hi] = arr.added_mass_infinite + (ag[-1] - arr.added_mass_infinite) * f
    b[hi] = bg[-1] * f
    return a, b


def cummins_decay_reference(
    dofs: list[int],
    x0: np.ndarray,
    t: np.ndarray,
    *,
    extra_damping: np.ndarray | None = None,
    omega_max: float = 12.0,
    d_omega: float = 5e-4,
) -> np.ndarray:
    """Exact free decay of the linear Cummins equation from x0 at rest, database A(ω), B(ω).

    With y = x − x0 the motion is the response to the step force −C x0 applied at t = 0 to a
    system at rest, so x(t) = x0 − s(t) C x0 with the step response
    s(t) = (2/π) ∫₀^∞ Re H(ω) sin(ωt)/ω dω,  H(ω) = [C − ω²(M + A(ω)) − iω B(ω)]⁻¹
    (causal real impulse response h(t) = (2/π)∫ Re H cos ωt dω). Trapezoidal rule on a uniform
    grid (d_omega = 5e-4 rad/s: the sin(ωt)/ω factor turns by 0.06 rad per step at t = 120 s;
    the heave/pitch resonances are ≈ 0.3 rad/s wide).
    """
    s = s175()
    w = np.arange(0.0, omega_max + 0.5 * d_omega, d_omega)
    a, b = radiation_coefficients(s.arr, w)
    ix = np.ix_(dofs, dofs)
    bb = b[:, dofs][:, :, dofs] + (0.0 if extra_damping is None else extra_damping[ix])
    k = (
        s.C[ix][None]
        - w[:, None, None] ** 2 * (s.M[ix][None] + a[:, dofs][:, :, dofs])
        - 1j * w[:, None, None] * bb
    )
    f = s.C[ix] @ x0
    hf = np.linalg.solve(k, np.broadcast_to(f.astype(complex), (len(w), len(dofs)))[..., None])
    hf = hf[..., 0].real
    weights = np.full(len(w), d_omega)
    weights[[0, -1]] *= 0.5
    step = np.empty((len(t), len(dofs)))
    for i0 in range(0, len(t), 200):
        tt = t[i0 : i0 + 200]
        kernel = tt[:, None] * np.sinc(np.outer(tt, w) / np.pi) * weights  # sin(ωt)/ω
        step[i0 : i0 + 200] = (2.0 / np.pi) * kernel @ hf
    return x0[None] - step


def one_dof_prediction(dof: int) -> SimpleNamespace:
    """ω_n, T_n, ζ, damped period and log decrement of one DOF from the database."""
    s = s175()
    name = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")[dof]
    wn = natural_frequency(s.db, name)
    a = float(np.interp(wn, s.arr.omega, s.arr.added_mass[:, dof, dof]))
    b = float(np.interp(wn, s.arr.omega, s.arr.radiation_damping[:, dof, dof]))
    mass = s.M[dof, dof] + a
    zeta = b / (2.0 * mass * wn)
    tn = 2.0 * np.pi / wn
    return SimpleNamespace(
        omega=wn, added_mass=a, damping=b, mass=mass, zeta=zeta, period=tn,
        damped_period=tn / np.sqrt(1.0 - zeta**2),
    )  # fmt: skip


def decay_run(
    offsets: dict[int, float],
    *,
    duration: float,
    free: tuple[bool, ...] = HOLD_HORIZONTAL,
    method: str = "state_space",
    extra: tuple[ForceModel, ...] = (),
    dt: float = 0.1,
) -> SimulationResult:
    """Free decay from the equilibrium plus ``offsets`` (at rest); FK + radiation memory."""
    s = s175()
    eta0 = s.base.copy()
    for dof, value in offsets.items():
        eta0[dof] += value
    forces = [
        FroudeKrylovHydrostatics(s.hull),
        RadiationMemory(s.db, method=method, dt=dt),
        *extra,
    ]
    return simulate(forces, eta0=eta0, duration=duration, dt=dt, free=free)


class ConstantMoment(ForceModel):
    """A constant body-axis heeling moment about x [N·m]."""

    name = "heeling_moment"

    def __init__(self, moment: float) -> None:
        self.moment = float(moment)

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        force = np.zeros(6)
        force[ROLL] = self.moment
        return force, np.zeros(0)


class LinearDamper(ForceModel):
    """−diag(b) ν: an artificial damper that brings a static test to rest (no static effect)."""

    name = "damper"

    def __init__(self, b: np.ndarray) -> None:
        self.b = np.asarray(b, float)

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return -self.b * ctx.nu, np.zeros(0)


# ============================================================================ 1. still water
@pytest.mark.parametrize(
    "radiation", ["state_space", pytest.param("convolution", marks=pytest.mark.slow)]
)
def test_still_water_full_force_set_stays_put(radiation):
    # The numbers: drift < 1 mm and < 0.01° over 200 s. FK + radiation memory + Ikeda
    # viscous roll, all six DOFs free. The equilibrium is that of the same pressure integral as
    # the FK model, so only round-off moves the ship (measured ≈ 1e-12 m, 3e-13°).
    # Δt = 0.2 s: rounding-level drift does not depend on the step (RK4 stays well inside its
    # stability limit for the fastest memory pole, |λ|Δt = 0.39).
    sim = build_simulator(ShipSetup(radiation=radiation, dt=0.2), None)
    assert {f.name for f in sim.forces} == {
        "froude_krylov_hydrostatic",
        "radiation",
        "viscous_roll",
    }
    res = sim.run(200.0, record_every=5)
    drift = np.abs(res.eta - res.eta[0])
    assert drift[:, :3].max() < 1e-3
    assert np.degrees(drift[:, 3:].max()) < 0.01


# ============================================================================ 2. free decay
@functools.cache
def heave_decay() -> SimpleNamespace:
    # 0.1 m heave offset, 60 s (8 periods; the motion is down to 1e-4 of x0 by then).
    res = decay_run({HEAVE: 0.1}, duration=60.0)
    s = s175()
    x = res.eta[:, [HEAVE, PITCH]] - s.base[[HEAVE, PITCH]]
    ref = cummins_decay_reference([HEAVE, PITCH], np.array([0.1, 0.0]), res.t)
    return SimpleNamespace(t=res.t, x=x, ref=ref, x0=0.1)


@functools.cache
def pitch_decay() -> SimpleNamespace:
    # 0.2° pitch: small enough that the bow/stern flare (pitch restoring nonlinear at the 1 %
    # level at 0.5°, measured against the linear reference) stays below the fit errors.
    x0 = np.radians(0.2)
    res = decay_run({PITCH: x0}, duration=60.0)
    s = s175()
    x = res.eta[:, [HEAVE, PITCH]] - s.base[[HEAVE, PITCH]]
    ref = cummins_decay_reference([HEAVE, PITCH], np.array([0.0, x0]), res.t)
    return SimpleNamespace(t=res.t, x=x, ref=ref, x0=x0)


def first_period(t: np.ndarray, x: np.ndarray) -> float:
    """First full period: from the first to the third zero crossing [s]."""
    tc = zero_crossings(t, x)
    return float(tc[2] - tc[0])


def test_heave_decay_follows_linear_cummins_solution():
    # Heave and pitch free (coupled through C35, A35, B35), roll free (uncoupled by symmetry),
    # surge/sway/yaw held. The reference is the exact linear Cummins solution of the same 2-DOF
    # system built from the database A(ω), B(ω) — not from the kernels or the state-space fit.
    # Heave is heavily damped (ζ = 0.16) and its A33, B33 vary strongly around ω_n: its decay is
    # no single exponential (successive half-cycle decrements 0.35, 0.81, 0.51, 0.31 against
    # δ/2 = 0.50 for a 1-DOF system with B33(ω_n)), so the comparison is made on the whole
    # curve. Tolerance 0.5 % of x0: state-space fit ≈ 0.5 % of K per pair, heave restoring
    # nonlinear (flare) at the 0.1 % level at 0.1 m; measured 0.25 %.
    d = heave_decay()
    err = np.abs(d.x[:, 0] - d.ref[:, 0]).max() / d.x0
    assert err < 5e-3, f"heave decay differs from the linear Cummins solution by {err:.2%} of x0"
    # the pitch it drives (≈ 1e-4 rad per 0.1 m) follows the coupled reference too: 5 % of its
    # own peak (a small response, sensitive to the A35/B35 fit; measured 4.5 %)
    pitch_peak = np.abs(d.ref[:, 1]).max()
    err_p = np.abs(d.x[:, 1] - d.ref[:, 1]).max() / pitch_peak
    assert err_p < 0.06, f"coupled pitch differs by {err_p:.2%} of its peak"


def test_heave_decay_period_matches_linear_prediction():
    # First full period (zero crossings 1 → 3) against the damped 1-DOF prediction
    # T_d = T_n/√(1 − ζ²) (T_n = 7.436 s, ζ = 0.159, T_d = 7.532 s): within the 2 %.
    # The heave–pitch coupling lengthens it slightly (1-DOF heave measured 7.51 s, coupled
    # 7.59 s, +0.8 %). It also matches the zero crossings of the exact linear reference (0.5 %).
    d = heave_decay()
    p = one_dof_prediction(HEAVE)
    period = first_period(d.t, d.x[:, 0])
    assert period == pytest.approx(p.damped_period, rel=0.02)
    assert period == pytest.approx(first_period(d.t, d.ref[:, 0]), rel=0.005)


def test_pitch_decay_follows_linear_cummins_solution():
    # As for heave; pitch released from 0.2°. Tolerance 1.5 % of x0: the pitch radiation kernels
    # reproduce A55 within ≈ 1.5 % near ω_n (Ogilvie reconstruction with the BEM A(∞); documented
    # ~1–2.5 % pitch memory error) and the flare adds ≈ 0.5 % at 0.2° (measured 0.74 % at 0.1°,
    # 1.9 % at 0.5°, the linear part ≈ 0.3 % when the reference uses the fit's own A, B);
    # measured 0.93 % at 0.2°.
    d = pitch_decay()
    err = np.abs(d.x[:, 1] - d.ref[:, 1]).max() / d.x0
    assert err < 0.015, f"pitch decay differs from the linear Cummins solution by {err:.2%} of x0"
    # zero crossings of the first cycle: same period as the exact linear solution (0.5 %)
    assert first_period(d.t, d.x[:, 1]) == pytest.approx(first_period(d.t, d.ref[:, 1]), rel=5e-3)


@pytest.mark.xfail(
    strict=True,
    reason=(
        "known deviation of the 1-DOF prediction, not of the simulator: the pitch decay's first "
        "period is 7.84 s against T_d = 7.28 s (+7.7 %; T_n = 7.18 s). Pitch is heavily damped "
        "(ζ = 0.17) and A55 falls from 1.0 M55 to 0.5 M55 across 0.6–0.9 rad/s: the free decay "
        "is no single "
        "damped mode (the fitted rational model shows comparable modes at ≈ 11 s and ≈ 7 s). "
        "The exact linear Cummins solution has the same zero crossings (tested above)."
    ),
)
def test_pitch_decay_period_matches_one_dof_prediction():
    d = pitch_decay()
    p = one_dof_prediction(PITCH)
    assert first_period(d.t, d.x[:, 1]) == pytest.approx(p.damped_period, rel=0.02)


@functools.cache
def roll_decay_with_linear_viscous(method: str) -> SimpleNamespace:
    # 2° roll, 180 s = 10 periods; radiation memory + the linear viscous roll damping
    # (ikeda_b1, B2 = 0). Roll is the lightly damped DOF, where the 1-DOF decrement applies.
    res = decay_run(
        {ROLL: np.radians(2.0)},
        duration=180.0,
        method=method,
        extra=(ViscousRollDamping(RollDampingCoefficients(ikeda_b1(), 0.0)),),
    )
    return SimpleNamespace(t=res.t, x=res.eta[:, ROLL])


def decrement_per_cycle(x: np.ndarray, x0: float, skip_cycles: int = 1) -> float:
    """Mean log decrement per cycle from successive peaks of |x| (half-cycle spaced).

    The first cycle is skipped: the memory starts from rest and its start-up transient damps
    the first cycle more (≈ +0.003).
    """
    peaks = np.concatenate([[x0], peak_amplitudes(x)])
    dec = np.log(peaks[:-2] / peaks[2:])
    return float(dec[2 * skip_cycles :].mean())


@pytest.mark.parametrize(
    "method", ["state_space", pytest.param("convolution", marks=pytest.mark.slow)]
)
def test_roll_decay_period_and_decrement(method):
    # Surge/sway/yaw held; heave and pitch free (coupled to roll only at second order).
    # Period over the whole run against T_n = 2π/ω_n (sway held, as natural_frequency assumes;
    # ζ ≈ 0.6 % changes T by 2e-5): issue's 2 %, measured +0.04 % (+0.03 % convolution).
    # Decrement against δ = π (B44(ω_n) + B1)/((I44 + A44) ω_n) (1-DOF, light damping: error
    # O(ζ²)); tolerance 5 %: the memory's B44 near ω_φ is known to ±2e-4 of critical damping
    # (state-space fit −2.2e-4 from its B44(ω_φ); convolution +1.1e-4 as measured; ±0.0013 in
    # δ = 3.5 % of δ); measured −2.8 % (state space, δ = 0.0361 against 0.0371), +1.9 %
    # (convolution).
    d = roll_decay_with_linear_viscous(method)
    p = one_dof_prediction(ROLL)
    tc = zero_crossings(d.t, d.x)
    period = 2.0 * (tc[-1] - tc[0]) / (len(tc) - 1)
    assert period == pytest.approx(p.period, rel=0.02)
    assert period == pytest.approx(p.period, rel=1e-3)  # tighter: what was measured
    delta_pred = np.pi * (p.damping + ikeda_b1()) / (p.mass * p.omega)
    delta = decrement_per_cycle(d.x, np.radians(2.0))
    assert delta == pytest.approx(delta_pred, rel=0.05)


@functools.cache
def roll_decay_radiation_only(method: str) -> float:
    # Roll alone free: with heave/pitch free the second-order energy exchange with them moves
    # the decrement by ≈ 1e-3 per cycle, the size of what is measured here.
    res = decay_run({ROLL: np.radians(2.0)}, duration=180.0, method=method, free=ROLL_ONLY)
    return decrement_per_cycle(res.eta[:, ROLL], np.radians(2.0))


@pytest.mark.slow
def test_roll_radiation_damping_only_convolution():
    # Wave-radiation roll damping of the S175 at ω_φ = 0.35 rad/s is tiny: B44(ω_φ) = 1e-3 of
    # its peak, ζ = 5e-5, δ = 3.2e-4 per cycle. Absolute tolerance 1e-3 per cycle (ζ within
    # 1.6e-4, 0.2 % of the peak B44 — the kernels' Ogilvie accuracy on B44); measured 6.4e-4.
    p = one_dof_prediction(ROLL)
    delta_pred = np.pi * p.damping / (p.mass * p.omega)
    delta = roll_decay_radiation_only("convolution")
    assert delta > 0.0
    assert abs(delta - delta_pred) < 1e-3


@pytest.mark.slow
def test_roll_radiation_damping_only_state_space_does_not_grow():
    assert roll_decay_radiation_only("state_space") > 0.0


# ============================================================================ 3. linear limit
AMPLITUDE = 0.1  # [m]: steepness ≤ 1/1500, the linear limit (nonlinear FK ≲ 0.2 %, measured)
LINEAR_DT = 0.1  # [s]: RK4 phase error (ωΔt)⁴/120 < 1e-6 at ω ≤ 1.05 rad/s
# [s]: the ramp ends at 50 s; the fit uses the last ≈ 100 s (whole periods). Fitting 200–300 s
# of a 300 s run instead changes the amplitudes by ≤ 0.2 % (lightly damped roll), < 0.02 % else.
LINEAR_DURATION = 250.0
FIT_WINDOW = 100.0
DOMINANT = {180: (HEAVE, PITCH), 90: (HEAVE, ROLL), 135: (HEAVE, ROLL, PITCH)}


def linear_forces(wave_field) -> list[ForceModel]:
    s = s175()
    return [
        FroudeKrylovHydrostatics(s.hull, wave_field),
        RadiationMemory(s.db, method="state_space"),
        Diffraction(s.db, wave_field),
        ViscousRollDamping(RollDampingCoefficients(ikeda_b1(), 0.0)),
    ]


@functools.cache
def linear_run(index: int, heading_deg: int) -> np.ndarray:
    """Complex amplitude per unit wave amplitude (6,) of a regular-wave run at a database node."""
    s = s175()
    omega = float(s.arr.omega[index])
    wave = RegularWave(2 * AMPLITUDE, period=2 * np.pi / omega)
    wf = wave_field_for(wave, np.radians(heading_deg))
    res = simulate(
        linear_forces(wf),
        eta0=s.base,
        duration=LINEAR_DURATION,
        dt=LINEAR_DT,
        free=HOLD_HORIZONTAL,
        wave_field=wf,
    )
    period = 2 * np.pi / omega
    t_start = LINEAR_DURATION - np.floor(FIT_WINDOW / period) * period
    out = np.zeros(6, complex)
    for dof in (HEAVE, ROLL, PITCH):
        out[dof] = fit_harmonic(res.t, res.eta[:, dof] - s.base[dof], omega, t_start) / AMPLITUDE
    return out


def database_rao(index: int, heading_deg: int) -> np.ndarray:
    s = s175()
    return response_amplitude_operator(
        s.db,
        omega=float(s.arr.omega[index]),
        heading=np.radians(heading_deg),
        extra_damping=np.diag([0, 0, 0, ikeda_b1(), 0, 0]),
        free_dofs=HOLD_HORIZONTAL,
    )[0]


@functools.cache
def time_domain_excitation(index: int, heading_deg: int, n: int = 32) -> tuple:
    """Linear FK and diffraction force on the ship held at equilibrium, per unit amplitude.

    The first harmonic of n samples over one period, X = (2/n) Σ F(t) e^{iωt} / a (exact for
    the mean and harmonics below n − 1), of the time-domain force models in a small wave.
    """
    s = s175()
    omega = float(s.arr.omega[index])
    wave = RegularWave(2 * AMPLITUDE, period=2 * np.pi / omega, ramp_time=0.0)
    wf = wave_field_for(wave, np.radians(heading_deg))
    fk, dif = FroudeKrylovHydrostatics(s.hull, wf), Diffraction(s.db, wf)
    rot = rotation_matrix(0.0, s.eq.trim, 0.0)
    ts = np.arange(n) * (2 * np.pi / omega) / n
    f_fk, f_d = [], []
    for t in ts:
        ctx = ForceContext(t=t, eta=s.base, nu=np.zeros(6), rotation=rot, wave_phasor=wf.phasor(t))
        f_fk.append(fk.evaluate(ctx, np.zeros(0))[0])
        f_d.append(dif.evaluate(ctx, np.zeros(0))[0])
    ph = np.exp(1j * omega * ts)[:, None]
    x_fk = 2 * (np.array(f_fk) * ph).mean(0) / AMPLITUDE
    x_d = 2 * (np.array(f_d) * ph).mean(0) / AMPLITUDE
    return x_fk, x_d


def heading_index(heading_deg: int) -> int:
    return int(np.argmin(np.abs(np.degrees(s175().db["wave_direction"].values) - heading_deg)))


def frequency_domain(index: int, a: np.ndarray, b: np.ndarray, f: np.ndarray) -> np.ndarray:
    """[C − ω²(M + A) − iω(B + B1)] ξ = F on heave, roll, pitch (others held)."""
    s = s175()
    omega = float(s.arr.omega[index])
    dofs = [HEAVE, ROLL, PITCH]
    ix = np.ix_(dofs, dofs)
    b_total = b + np.diag([0, 0, 0, ikeda_b1(), 0, 0])
    k = s.C[ix] - omega**2 * (s.M[ix] + a[ix]) - 1j * omega * b_total[ix]
    out = np.zeros(6, complex)
    out[dofs] = np.linalg.solve(k, f[dofs])
    return out


# (database frequency index, heading [deg]); ω = 0.543, 0.710, 0.877, 1.044 rad/s
# (λ/L = 1.19, 0.70, 0.46, 0.32). The bow-quartering case at ω = 0.710 rad/s (heave, roll and
# pitch all excited) runs by default; the rest is slow (≈ 5 s each). The beam-sea diagnosis runs
# by default through the excitation and quadrature tests, which need no simulation.
LINEAR_CASES = [(16, 180), (16, 90), (16, 135), (12, 180), (20, 180), (24, 180)]
LINEAR_CASES += [(12, 90), (20, 90), (12, 135), (20, 135)]
BEAM_ROLL_MEASURED = {12: 0.131, 16: 0.127, 20: 0.049}


def _linear_params(with_dofs: bool):
    params = []
    for index, heading in LINEAR_CASES:
        for dof in DOMINANT[heading] if with_dofs else (None,):
            marks = [] if (index, heading) == (16, 135) else [pytest.mark.slow]
            if with_dofs and heading == 90 and dof == ROLL:
                marks.append(
                    pytest.mark.xfail(
                        strict=True,
                        reason=(
                            f"known deviation: beam-sea roll {BEAM_ROLL_MEASURED[index]:.1%} "
                            "from the database RAO, from the Froude–Krylov quadrature (time "
                            "domain exact on mesh facets, BEM panel centroids: 3–4 % apart on "
                            "the roll moment, which FK and diffraction cancel to 1/4); see "
                            "test_linear_limit_with_time_domain_excitation and "
                            "test_froude_krylov_roll_moment_quadrature_converges"
                        ),
                    )
                )
            ident = f"w{index}-beta{heading}" + ("" if dof is None else f"-{'zrp'[dof - 2]}")
            args = (index, heading, dof) if with_dofs else (index, heading)
            params.append(pytest.param(*args, marks=marks, id=ident))
    return params


@pytest.mark.parametrize(("index", "heading", "dof"), _linear_params(True))
def test_linear_limit_matches_frequency_domain_rao(index, heading, dof):
    # The criterion |ξ_td − ξ_fd|/|ξ_fd| < 2 % (amplitude and phase together), zero
    # speed, a = 0.1 m, frequency on a database node, surge/sway/yaw held in both domains,
    # linear viscous roll B1 in both. Measured (heave, roll, pitch): head seas 0.4–0.9 % /
    # – / 0.4–1.9 %; 135°: ≤ 1.0 % / ≤ 1.4 % / ≤ 1.9 %; beam seas heave ≤ 1.03 %. What remains
    # is the FK quadrature (0.2–1 % on heave/pitch excitation) and the radiation memory's A55
    # (≈ 1.5 % of A55 near ω_n with the BEM A(∞)), see the next test.
    xi_td = linear_run(index, heading)[dof]
    xi_fd = database_rao(index, heading)[dof]
    err = abs(xi_td - xi_fd) / abs(xi_fd)
    assert err < 0.02, (
        f"|ξ_td − ξ_fd|/|ξ_fd| = {err:.2%} (|ξ_td/ξ_fd| = {abs(xi_td / xi_fd):.4f}, "
        f"phase {np.degrees(np.angle(xi_td / xi_fd)):+.2f}°)"
    )


@pytest.mark.parametrize(("index", "heading"), _linear_params(False))
def test_linear_limit_with_time_domain_excitation(index, heading):
    # Diagnosis of what is left: solve the frequency-domain equations with the time domain's
    # *own* ingredients — the linear excitation of its FK + diffraction models on the held ship
    # and the A(ω), B(ω) implied by its state-space radiation fit (Ogilvie). All dominant DOFs,
    # beam-sea roll included, then agree within 0.6 % (measured ≤ 0.42 %: nonlinearity at
    # a = 0.1 m, steady-state leakage of the ramp transient): the remaining differences from the
    # database RAO are exactly the excitation quadrature and the memory fit, nothing else.
    s = s175()
    x_fk, x_d = time_domain_excitation(index, heading)
    rad = RadiationMemory(s.db, method="state_space")
    a_minus_inf, b = rad.state_space.frequency_response(np.array([s.arr.omega[index]]))
    xi_ref = frequency_domain(index, a_minus_inf[0] + rad.A_inf, b[0], x_fk + x_d)
    xi_td = linear_run(index, heading)
    for dof in DOMINANT[heading]:
        err = abs(xi_td[dof] - xi_ref[dof]) / abs(xi_ref[dof])
        assert err < 6e-3, f"DOF {dof}: {err:.3%}"


BEAM_ROLL_EXCITATION_MEASURED = {12: 0.126, 16: 0.125, 20: 0.048}


@pytest.mark.parametrize(("index", "heading"), LINEAR_CASES)
def test_linear_excitation_time_domain_vs_database(index, heading):
    # FK + diffraction on the ship held at equilibrium, against the database excitation_force.
    # Diffraction is the database's (exact at a node), so any difference is the FK's. Heave,
    # pitch, and roll at 135° within 2 %: measured ≤ 1.7 % (head-seas heave and pitch at
    # 1.044 rad/s, where the FK differs by 1 % and FK and diffraction partly cancel), ≤ 1 %
    # elsewhere. Beam-sea roll: the FK roll moment differs by 3.2–4.2 % and, FK being 1.2–3.9
    # times the total, the excitation by 4.8–12.6 %; checked against its measured size here
    # (explained by the quadrature test below).
    s = s175()
    x_fk, x_d = time_domain_excitation(index, heading)
    ib = heading_index(heading)
    exc_db = s.arr.excitation_force[index, ib]
    fk_db = s.db["Froude_Krylov_force"].sel(omega=s.arr.omega[index]).values[ib]
    for dof in DOMINANT[heading]:
        err = abs(x_fk[dof] + x_d[dof] - exc_db[dof]) / abs(exc_db[dof])
        err_fk = abs(x_fk[dof] - fk_db[dof]) / abs(fk_db[dof])
        if heading == 90 and dof == ROLL:
            assert 0.025 < err_fk < 0.05, f"FK roll moment {err_fk:.2%}"
            assert err == pytest.approx(BEAM_ROLL_EXCITATION_MEASURED[index], abs=0.01)
        else:
            assert err < 0.02, f"DOF {dof}: excitation {err:.2%} (FK alone {err_fk:.2%})"


def _centroid_froude_krylov(hull, omega: float, beta: float) -> np.ndarray:
    """BEM-style linear FK per unit amplitude: pressure at panel centroids × vector areas."""
    im = immersed_part(hull.mesh)
    k = omega**2 / hull.g
    c, n = im.centroids, im.vector_areas
    p = (
        hull.rho
        * hull.g
        * np.exp(-k * c[:, 2] + 1j * k * (c[:, 0] * np.cos(beta) + c[:, 1] * np.sin(beta)))
    )
    return np.concatenate([-(p[:, None] * n).sum(0), -(p[:, None] * np.cross(c, n)).sum(0)])


def _time_domain_froude_krylov(hull, omega: float, beta: float, n: int = 32) -> np.ndarray:
    """First harmonic per unit amplitude of the time-domain FK at the design waterline."""
    panels = HullPanels.from_mesh(hull.mesh)
    waves = WaveComponents.from_arrays(np.array([omega**2 / hull.g]), np.array([beta]))
    ts = np.arange(n) * (2 * np.pi / omega) / n
    f = np.array(
        [
            froude_krylov_hydrostatic(
                panels, waves, np.array([AMPLITUDE * np.exp(1j * omega * t)]), np.zeros(3),
                np.eye(3), rho=hull.rho, g=hull.g,
            )
            for t in ts
        ]
    )  # fmt: skip
    return 2 * (f * np.exp(1j * omega * ts)[:, None]).mean(0) / AMPLITUDE


def test_froude_krylov_roll_moment_quadrature_converges():
    # Why beam-sea roll misses: on the default mesh (60 sections × 12 panels below the
    # waterline) the BEM database's FK roll moment is the panel-centroid rule (reproduced here
    # within 0.1 %), the time domain's the exact integral of a vertex-linear pressure over the
    # facets; they differ by 3.1 % (ω = 0.543 rad/s, beam seas). Halving the panel size (120 ×
    # 24) divides the gap by ≈ 4 (measured 0.78 %): both are second-order quadratures of the
    # same integral and bracket its limit (Richardson: both → 5.66e6 N·m/m). Neither side is
    # wrong; they are inconsistent at the database's resolution.
    s = s175()
    index, beta = 12, np.pi / 2
    omega = float(s.arr.omega[index])
    fk_db = s.db["Froude_Krylov_force"].sel(omega=omega).values[heading_index(90), ROLL]
    gaps = []
    for overrides in ({}, {"n_sections": 120, "n_below": 24, "n_above": 12, "n_deck": 8}):
        hull = load_hull("s175", **overrides)
        centroid = _centroid_froude_krylov(hull, omega, beta)[ROLL]
        exact = _time_domain_froude_krylov(hull, omega, beta)[ROLL]
        if not overrides:
            assert abs(centroid - fk_db) / abs(fk_db) < 2e-3  # the database is this rule
        gaps.append(abs(exact - centroid) / abs(centroid))
    assert gaps[0] > 0.025  # the size of the inconsistency at the database's resolution
    assert 3.0 < gaps[0] / gaps[1] < 5.0  # second-order convergence of the gap


# ============================================================================ 4. large amplitude
def energy_period(phi: np.ndarray, moment: np.ndarray, phi0: float, inertia: float) -> float:
    """T = 4∫₀^φ0 dφ/√(2(V(φ0) − V(φ))/I), V(φ) = −∫₀^φ M dφ', by φ = φ0 sin u (no singularity)."""
    m = CubicSpline(phi, moment)
    w = m.antiderivative()
    m0 = float(m(phi0))

    def integrand(u: float) -> float:
        p = phi0 * np.sin(u)
        dv = -(w(phi0) - w(p))  # V(φ0) − V(φ) > 0 for a restoring M < 0
        if dv <= 0.0:  # u → π/2: dv ≈ −M(φ0) φ0 cos²u / 2
            return phi0 / np.sqrt(-m0 * phi0 / inertia)
        return phi0 * np.cos(u) / np.sqrt(2.0 * dv / inertia)

    return 4.0 * quad(integrand, 0.0, np.pi / 2, limit=200, epsabs=0.0, epsrel=1e-10)[0]


def roll_moment_fixed_pose(phi: float) -> float:
    """Calm-water roll moment about O [N·m] at heel φ, O held at the upright sinkage and trim.

    From the hydrostatics module (buoyancy and its moment about G, :func:`pressure_integral`),
    moved to O with the weight W: M_O = M_G + (r_G − r_O) × (F + W), in earth axes (body x =
    earth x up to the 5e-5 rad trim). With the sinkage held, F + W ≠ 0 at a heel.
    """
    s = s175()
    r = pressure_integral(s.hull, s.eq.heave, phi, s.eq.trim)
    og = rotation_matrix(phi, s.eq.trim, 0.0) @ s.hull.mass.cog
    total = r.force + np.array([0.0, 0.0, s.hull.mass.mass * s.hull.g])
    return float(r.moment[0] + og[1] * total[2] - og[2] * total[1])


def measured_roll_period(t: np.ndarray, x: np.ndarray) -> float:
    tc = zero_crossings(t, x)
    return float(2.0 * (tc[-1] - tc[0]) / (len(tc) - 1))


@pytest.mark.parametrize("phi0_deg", [30.0, 40.0])
def test_large_roll_period_matches_energy_method_one_dof(phi0_deg):
    # Undamped roll (FK + hydrostatics only), roll the only free DOF: a conservative 1-DOF
    # system I φ̈ = M(φ) (I = M44 about O, G 0.05 m above O), whose period is exactly the energy
    # method's with M(φ) the calm-water restoring at the held sinkage/trim (pressure_integral,
    # spline on a 1° grid: < 1e-5 on T). Tolerance 0.1 % (spline + zero-crossing interpolation
    # at Δt = 0.05 s); measured < 1e-5. The restoring is strongly nonlinear here — the linear
    # period 2π√(I/C44) = 16.65 s becomes 14.25 s at 30° (GZ hardening up to deck-edge immersion
    # at ≈ 25°) and 14.82 s at 40° (beyond the maximum GZ at 37.5°) — so the check is of the
    # nonlinear restoring in the dynamics, not of its linearisation.
    s = s175()
    phi0 = np.radians(phi0_deg)
    inertia = s.hull.mass.rigid_body_matrix()[ROLL, ROLL]
    phis = np.radians(np.arange(0.0, phi0_deg + 0.5, 1.0))
    t_energy = energy_period(
        phis, np.array([roll_moment_fixed_pose(p) for p in phis]), phi0, inertia
    )
    t_linear = 2 * np.pi * np.sqrt(inertia / s.C[ROLL, ROLL])
    assert abs(t_energy / t_linear - 1.0) > 0.1  # far from linear
    eta0 = s.base + np.array([0, 0, 0, phi0, 0, 0])
    res = simulate(
        [FroudeKrylovHydrostatics(s.hull)], eta0=eta0, duration=45.0, dt=0.05, free=ROLL_ONLY
    )
    assert measured_roll_period(res.t, res.eta[:, ROLL]) == pytest.approx(t_energy, rel=1e-3)
    assert np.abs(res.eta[:, ROLL]).max() == pytest.approx(phi0, rel=1e-4)  # energy conserved


@functools.cache
def gz_curve():
    heels = np.arange(0.0, 45.1, 2.5)
    return heels, righting_arm(s175().hull, heels, refine_vanishing=False)


def test_large_roll_period_free_heave_pitch_follows_gz_curve():
    # Heave and pitch free (sway/yaw held), started at the GZ curve's sinkage and trim for 40°.
    # The energy-method period with V = m g ∫GZ dφ (righting_arm: free sinkage and trim) is
    # 14.86 s (linear: 16.65 s). Tolerance 3 % on the mean period of 3 cycles: the GZ curve
    # assumes quasi-static sinkage, but without added mass the heave period (5.5 s) is not
    # short against the 7.4 s period of the roll-induced heave (twice the roll frequency), so
    # heave follows with a dynamic lag and exchanges energy with roll (single cycles spread
    # ±1.5 %); measured mean −0.8 % (and +1.7 % from 30°, +0.2 % from 10°).
    s = s175()
    heels, gz = gz_curve()
    phi0_deg = 40.0
    k = int(np.flatnonzero(heels == phi0_deg)[0])
    phis = np.radians(heels[heels <= phi0_deg])
    moment = -s.hull.mass.mass * s.hull.g * gz.gz[: len(phis)]
    inertia = s.hull.mass.rigid_body_matrix()[ROLL, ROLL]
    t_gz = energy_period(phis, moment, np.radians(phi0_deg), inertia)
    eta0 = np.array([0, 0, gz.heave[k], np.radians(phi0_deg), gz.trim[k], 0.0])
    res = simulate(
        [FroudeKrylovHydrostatics(s.hull)], eta0=eta0, duration=45.0, dt=0.05, free=HOLD_HORIZONTAL
    )
    assert measured_roll_period(res.t, res.eta[:, ROLL]) == pytest.approx(t_gz, rel=0.03)


def test_static_heel_under_heeling_moment_matches_gz_curve():
    # A constant heeling moment m g · 0.70 m, heave/roll/pitch free (sway/yaw held), brought to
    # rest by an artificial linear damper (≈ 0.7–0.8 of critical; it has no static effect).
    # At rest the forces balance, so the moment is a couple: m g GZ(φ) = M_h with GZ at free
    # sinkage and trim — exactly the GZ curve's definition. GZ = 0.70 m is reached at 28.6°,
    # beyond deck-edge immersion (≈ 25°); the linear estimate M_h/C44 would be 39.8°.
    # Tolerances: heel 0.02° (GZ is solved to 1e-6 m, dGZ/dφ = 1.6 m/rad: 1e-4°; the damped
    # transient has died out after 120 s: |ν| ≈ 1e-16), sinkage 1 mm, trim 2e-5 rad (the
    # body-axis heeling moment is tilted by the 4e-3 rad trim) against the GZ curve's. Measured:
    # heel 3e-4°, sinkage 3e-5 m, trim 5.5e-6 rad.
    s = s175()
    mg = s.hull.mass.mass * s.hull.g
    gz_target = 0.70
    phi_gz = brentq(
        lambda p: equilibrium(s.hull, p).righting_arm - gz_target,
        np.radians(20.0),
        np.radians(35.0),
        xtol=1e-9,
    )
    eq_gz = equilibrium(s.hull, phi_gz)
    damper = LinearDamper(np.array([0.0, 0.0, 4.5e7, 1.2e9, 0.0, 0.0]) + np.eye(6)[PITCH] * 7.5e10)
    forces = [FroudeKrylovHydrostatics(s.hull), ConstantMoment(mg * gz_target), damper]
    res = simulate(forces, eta0=s.base, duration=120.0, dt=0.1, free=HOLD_HORIZONTAL)
    eta = res.eta[-1]
    assert np.abs(res.nu[-1]).max() < 1e-6  # at rest
    assert np.degrees(phi_gz) == pytest.approx(28.6, abs=0.1)
    assert np.degrees(eta[ROLL]) == pytest.approx(np.degrees(phi_gz), abs=0.02)
    assert eta[HEAVE] == pytest.approx(eq_gz.heave, abs=1e-3)
    assert eta[PITCH] == pytest.approx(eq_gz.trim, abs=2e-5)
    linear_heel = mg * gz_target / s.C[ROLL, ROLL]
    assert np.degrees(linear_heel - eta[ROLL]) > 10.0  # far from the linear answer


# ============================================================================ 5. conv vs SS
@functools.cache
def irregular_run(radiation: str, dt: float) -> SimulationResult:
    # JONSWAP Hs 4 m, Tp 11 s, 50 components, seed 7, bow-quartering (135°), zero speed, 300 s;
    # full default force set (FK, memory, diffraction, Ikeda roll); surge/sway/yaw held.
    sea = IrregularSea(hs=4.0, tp=11.0)
    setup = ShipSetup(radiation=radiation, dt=dt, free_dofs=HOLD_HORIZONTAL)
    sim = build_simulator(setup, sea, wave_heading=np.radians(135.0), rng=np.random.default_rng(7))
    return sim.run(300.0, record_every=round(0.1 / dt))


@pytest.mark.slow
@pytest.mark.parametrize("dt", [0.05, 0.1])
def test_convolution_and_state_space_agree(dt):
    # RMS of the difference over RMS of the motion (after the 50 s ramp). Tolerance 2 %: the
    # state-space fit reproduces the kernels within 0.5 % (relative L2 per pair) and its
    # frequency response within ≈ 1.2 % for the roll force (DEFAULT_FIT_OPTIONS); the roll
    # response, lightly damped, amplifies a force error by at most ≈ 1/(2ζ) near ω_φ but the
    # sea has little energy there (Tp = 11 s vs T_φ = 18 s). Measured: heave 0.25 %, roll
    # 0.48 % (dt 0.1) / 0.38 % (dt 0.05), pitch 0.16 %. The time step changes each method by
    # < 0.15 % (convolution) and < 0.003 % (state space).
    ss, cv = irregular_run("state_space", dt), irregular_run("convolution", dt)
    m = ss.t >= 50.0
    for dof in (HEAVE, ROLL, PITCH):
        a = ss.eta[m, dof] - ss.eta[m, dof].mean()
        b = cv.eta[m, dof] - cv.eta[m, dof].mean()
        rel = np.sqrt(np.mean((a - b) ** 2) / np.mean(b**2))
        assert rel < 0.02, f"DOF {dof}: RMS difference {rel:.2%} of RMS"


# ============================================================================ 6. integrators
@functools.cache
def integrator_run(integrator: str, dt: float) -> SimulationResult:
    # Regular wave H = 2 m, T = 9 s at 135° (20 s ramp), full default force set, surge/sway/yaw
    # held, 60 s.
    setup = ShipSetup(integrator=integrator, dt=dt, free_dofs=HOLD_HORIZONTAL)
    wave = RegularWave(2.0, period=9.0, ramp_time=20.0)
    sim = build_simulator(setup, wave, wave_heading=np.radians(135.0))
    return sim.run(60.0, record_every=round(0.1 / dt))


def relative_rms_difference(a: SimulationResult, b: SimulationResult) -> np.ndarray:
    """RMS(a − b) over RMS of b's steady motion, for heave, roll, pitch."""
    steady = b.t >= 20.0
    out = []
    for dof in (HEAVE, ROLL, PITCH):
        out.append(
            np.sqrt(np.mean((a.eta[:, dof] - b.eta[:, dof]) ** 2)) / np.std(b.eta[steady, dof])
        )
    return np.array(out)


def test_integrators_agree():
    # Reference RK4 at Δt = 0.05 s. RK4 is fourth order: at 0.1 s within 1e-5 (measured
    # ≈ 1e-6). Holloway's μ-Taylor scheme is second order (global error O(Δt²)): 0.5 % at
    # 0.05 s (μ = 1: the acceleration is exact, the added mass being on the left).
    ref = integrator_run("rk4", 0.05)
    assert relative_rms_difference(integrator_run("rk4", 0.1), ref).max() < 1e-5
    assert relative_rms_difference(integrator_run("holloway", 0.05), ref).max() < 5e-3


@pytest.mark.slow
def test_holloway_is_second_order():
    # Halving Δt from 0.1 to 0.05 s divides the difference from the RK4 reference by 4 ± 1 for
    # Holloway's scheme (measured 4.0–4.2): second order, as documented.
    ref = integrator_run("rk4", 0.05)
    e1 = relative_rms_difference(integrator_run("holloway", 0.1), ref)
    e2 = relative_rms_difference(integrator_run("holloway", 0.05), ref)
    assert np.all((e1 / e2 > 3.0) & (e1 / e2 < 5.0)), f"ratios {e1 / e2}"
