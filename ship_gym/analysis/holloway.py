"""Stability and accuracy of Holloway's μ-Taylor scheme on his constant-coefficient problem.

Holloway (2007) §4 studies one DOF whose force lumps the added-mass reaction with the
*extrapolated* acceleration (his eq. 10):

    m ẍ = F_w − (A ẍ_e + B ẋ + C x),     ẍ_e = (3ẋₖ − 4ẋₖ₋₁ + ẋₖ₋₂)/(2Δt)   (eq. 6)

integrated by :class:`~ship_gym.numerics.integrators.HollowayIntegrator` (eq. 4, 7–9). The
scheme is linear, so one step is an exact linear map sₖ₊₁ = M sₖ + b F_w,k of the state

    s = (x, ẋ, ẋₖ₋₁, ẋₖ₋₂, hₖ₋₁, hₖ₋₂, pₖ₋₁)

(h: the acceleration history that eq. 7 differentiates; p: the previous blended acceleration,
used only by the ``force_acceleration="previous"`` reading). The step is stable iff the spectral
radius of the amplification matrix M is below 1; :func:`stability_limits` finds the μ at which it
crosses 1, :func:`time_domain_growth` measures the same growth by running the real integrator.

Non-dimensional form: m = 1, Δt = 1, A = A/m, and ω_n, ζ define C and B through a *mass
basis* (``mass_basis``):

* ``"virtual"`` (default): ω_n = √(C/(m + A)), ζ = B/(2√(C(m + A))) — the natural frequency and
  damping ratio of the physical system (m + A)ẍ + Bẋ + Cx = F_w (Holloway eq. 1);
* ``"dry"``: ω_n = √(C/m), ζ = B/(2√(Cm)).

With the virtual basis, ẍ = μẍ_c + (1 − μ)ẍ_e = (1 − s)ẍ_e + s·(−2ζω_n ẋ − ω_n² x) with
s = μ(1 + A/m): the recurrence depends on μ and A/m only through s, so the limits are exactly of
Holloway's form μ = const/(A/m + 1) (his eq. 11, "exact to three significant figures"), and at
s = 1 (μ = m/(m + A)) the lumped scheme *is* the un-lumped scheme applied to the true equation —
the stabilisation error vanishes (Holloway §6).

Readings of the paper (:class:`HollowayReading`) that the text leaves open and that
``scripts/reproduce_holloway.py`` compares: the mass basis of ζ, ω_n; which acceleration history
eq. 7 differentiates (``"blended"`` ẍ of eq. 4, ``"computed"`` ẍ_c, or ``"extrapolated"`` ẍ_e);
and which acceleration the lumped force uses (``"extrapolated"`` ẍ_e of eq. 6 as the paper says,
or the ``"previous"`` step's blended ẍ). The default reading (virtual, blended, extrapolated) is
the one :class:`~ship_gym.numerics.integrators.HollowayIntegrator` implements and gives
0.2195 < μ(1 + A/m) < 1.1401 at ζ = 0.2, ω_nΔt = 0.25 (eq. 11: 0.22 and 1.14).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from ship_gym.numerics.integrators import HollowayIntegrator
from ship_gym.typing import FloatArray

__all__ = [
    "HOLLOWAY_EQ11",
    "HollowayReading",
    "amplification_matrix",
    "fit_limit_constants",
    "forced_response_error",
    "forcing_vector",
    "integrator_amplification_matrix",
    "lumped_oscillator_rhs",
    "max_stable_omega_dt",
    "oscillator_coefficients",
    "spectral_radius",
    "stability_limits",
    "time_domain_growth",
    "time_domain_stability_limits",
]


HOLLOWAY_EQ11: tuple[float, float] = (0.22, 1.14)
"""Holloway (2007) eq. 11: 0.22/(A/m + 1) < μ < 1.14/(A/m + 1) at ζ = 0.2, ω_nΔt = 0.25."""

N_STATE = 7
"""Size of the analytic recurrence state (x, ẋ, ẋₖ₋₁, ẋₖ₋₂, hₖ₋₁, hₖ₋₂, pₖ₋₁)."""

MassBasis = Literal["virtual", "dry"]


@dataclass(frozen=True)
class HollowayReading:
    """One reading of the details Holloway (2007) leaves implicit.

    Parameters
    ----------
    mass_basis : {"virtual", "dry"}
        Mass in ω_n = √(C/M) and ζ = B/(2√(CM)): M = m + A (virtual) or M = m (dry).
    acc_history : {"blended", "computed", "extrapolated"}
        Acceleration whose backward difference gives x⃛ in eq. 7: the blended ẍ of eq. 4, the
        computed ẍ_c = F/m, or the extrapolated ẍ_e of eq. 6.
    force_acceleration : {"extrapolated", "previous"}
        Acceleration in the lumped −Aẍ of eq. 10: ẍ_e of eq. 6 (the text) or the blended ẍ of
        the previous step.
    """

    mass_basis: MassBasis = "virtual"
    acc_history: Literal["blended", "computed", "extrapolated"] = "blended"
    force_acceleration: Literal["extrapolated", "previous"] = "extrapolated"

    def __post_init__(self) -> None:
        if self.mass_basis not in ("virtual", "dry"):
            raise ValueError(f"mass_basis = {self.mass_basis!r}; expected 'virtual' or 'dry'")
        if self.acc_history not in ("blended", "computed", "extrapolated"):
            raise ValueError(
                f"acc_history = {self.acc_history!r}; expected 'blended', 'computed' or "
                "'extrapolated'"
            )
        if self.force_acceleration not in ("extrapolated", "previous"):
            raise ValueError(
                f"force_acceleration = {self.force_acceleration!r}; expected 'extrapolated' or "
                "'previous'"
            )

    @property
    def label(self) -> str:
        """Short description for tables and legends."""
        return (
            f"ζ,ω_n on {'m+A' if self.mass_basis == 'virtual' else 'm'}; eq.7 on "
            f"{self.acc_history} ẍ; force uses {self.force_acceleration} ẍ"
        )


DEFAULT_READING = HollowayReading()


def _positive(x: npt.ArrayLike, name: str, allow_zero: bool = False) -> FloatArray:
    arr = np.asarray(x, dtype=np.float64)
    bad = ~np.isfinite(arr) | ((arr < 0.0) if allow_zero else (arr <= 0.0))
    if np.any(bad):
        bound = "≥ 0" if allow_zero else "> 0"
        raise ValueError(f"{name} = {x!r}; expected finite values {bound}")
    return arr


def oscillator_coefficients(
    mass_ratio: npt.ArrayLike,
    zeta: npt.ArrayLike,
    omega_n: npt.ArrayLike,
    mass: float = 1.0,
    mass_basis: MassBasis = "virtual",
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Added mass, damping and stiffness (A, B, C) of Holloway's test problem.

    Parameters
    ----------
    mass_ratio : array_like
        A/m [-] (≥ 0).
    zeta : array_like
        Damping ratio ζ [-] (≥ 0).
    omega_n : array_like
        Undamped natural frequency ω_n [rad/s] (> 0).
    mass : float
        Body mass m [kg].
    mass_basis : {"virtual", "dry"}
        M = m + A or M = m in ω_n = √(C/M), ζ = B/(2√(CM)).

    Returns
    -------
    A [kg], B [kg/s], C [kg/s²]
        Broadcast arrays.
    """
    r = _positive(mass_ratio, "mass_ratio", allow_zero=True)
    z = _positive(zeta, "zeta", allow_zero=True)
    w = _positive(omega_n, "omega_n")
    m = float(_positive(mass, "mass"))
    if mass_basis not in ("virtual", "dry"):
        raise ValueError(f"mass_basis = {mass_basis!r}; expected 'virtual' or 'dry'")
    added = r * m
    total = m + added if mass_basis == "virtual" else np.full_like(added, m)
    return added, 2.0 * z * w * total, w * w * total


def _linear_step(
    s: list[FloatArray],
    forcing: FloatArray | float,
    r: FloatArray,
    mu: FloatArray,
    b: FloatArray,
    c: FloatArray,
    reading: HollowayReading,
) -> list[FloatArray]:
    """One μ-Taylor step of the non-dimensional lumped oscillator (m = 1, Δt = 1)."""
    x, v, v1, v2, h1, h2, p1 = s
    ae = 0.5 * (3.0 * v - 4.0 * v1 + v2)  # eq. 6
    a_force = ae if reading.force_acceleration == "extrapolated" else p1
    ac = forcing - (r * a_force + b * v + c * x)  # eq. 10, m = 1
    a = mu * ac + (1.0 - mu) * ae  # eq. 4
    h = {"blended": a, "computed": ac, "extrapolated": ae}[reading.acc_history]
    j = 0.5 * (3.0 * h - 4.0 * h1 + h2)  # eq. 7
    v_new = v + a + 0.5 * j  # eq. 8
    x_new = x + v + 0.5 * a + j / 6.0  # eq. 9
    return [x_new, v_new, v, v1, h, h1, a]


def _broadcast_params(
    mass_ratio: npt.ArrayLike,
    mu: npt.ArrayLike,
    zeta: npt.ArrayLike,
    omega_n_dt: npt.ArrayLike,
    reading: HollowayReading,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    r = _positive(mass_ratio, "mass_ratio", allow_zero=True)
    mu_a = _positive(mu, "mu")
    z = _positive(zeta, "zeta", allow_zero=True)
    w = _positive(omega_n_dt, "omega_n_dt")
    if not isinstance(reading, HollowayReading):
        raise ValueError(f"reading = {reading!r}; expected a HollowayReading")
    r, mu_a, z, w = np.broadcast_arrays(r, mu_a, z, w)
    _, b, c = oscillator_coefficients(r, z, w, 1.0, reading.mass_basis)
    return r, mu_a, b, c


def amplification_matrix(
    mass_ratio: npt.ArrayLike,
    mu: npt.ArrayLike,
    zeta: npt.ArrayLike,
    omega_n_dt: npt.ArrayLike,
    reading: HollowayReading = DEFAULT_READING,
) -> FloatArray:
    """Exact one-step amplification matrix M of the lumped oscillator (sₖ₊₁ = M sₖ, F_w = 0).

    Parameters
    ----------
    mass_ratio : array_like
        A/m [-].
    mu : array_like
        Blending coefficient μ [-] (eq. 4).
    zeta : array_like
        Damping ratio ζ [-] (basis per ``reading.mass_basis``).
    omega_n_dt : array_like
        ω_nΔt [rad] (basis per ``reading.mass_basis``).
    reading : HollowayReading
        Which reading of the paper to build.

    Returns
    -------
    numpy.ndarray
        Shape (*broadcast, 7, 7), state order (x, ẋ, ẋₖ₋₁, ẋₖ₋₂, hₖ₋₁, hₖ₋₂, pₖ₋₁) with x in
        units of the initial displacement and velocities and accelerations per Δt.
    """
    r, mu_a, b, c = _broadcast_params(mass_ratio, mu, zeta, omega_n_dt, reading)
    ex = (r[..., None], mu_a[..., None], b[..., None], c[..., None])
    eye = np.eye(N_STATE)
    cols = _linear_step([eye[i] for i in range(N_STATE)], 0.0, *ex, reading)
    return np.stack([np.broadcast_to(x, (*r.shape, N_STATE)) for x in cols], axis=-2)


def forcing_vector(
    mass_ratio: npt.ArrayLike,
    mu: npt.ArrayLike,
    zeta: npt.ArrayLike,
    omega_n_dt: npt.ArrayLike,
    reading: HollowayReading = DEFAULT_READING,
) -> FloatArray:
    """Input vector b of sₖ₊₁ = M sₖ + b F_w,k for a unit force F_w/m = 1 (per Δt²).

    Parameters and shapes as :func:`amplification_matrix`; returns (*broadcast, 7).
    """
    r, mu_a, b, c = _broadcast_params(mass_ratio, mu, zeta, omega_n_dt, reading)
    zero = np.zeros(r.shape)
    out = _linear_step([zero] * N_STATE, 1.0, r, mu_a, b, c, reading)
    return np.stack([np.broadcast_to(x, r.shape) for x in out], axis=-1)


def spectral_radius(
    mass_ratio: npt.ArrayLike,
    mu: npt.ArrayLike,
    zeta: npt.ArrayLike,
    omega_n_dt: npt.ArrayLike,
    reading: HollowayReading = DEFAULT_READING,
) -> FloatArray:
    """max |eigenvalue| of the amplification matrix [-]; the scheme is stable iff < 1."""
    mat = amplification_matrix(mass_ratio, mu, zeta, omega_n_dt, reading)
    return np.max(np.abs(np.linalg.eigvals(mat)), axis=-1)


def stability_limits(
    mass_ratio: npt.ArrayLike,
    zeta: npt.ArrayLike,
    omega_n_dt: npt.ArrayLike,
    reading: HollowayReading = DEFAULT_READING,
    s_range: tuple[float, float] = (1e-4, 4.0),
    n_grid: int = 3000,
    rtol: float = 1e-9,
) -> tuple[FloatArray, FloatArray]:
    """Lower and upper μ stability limits from the spectral radius of the amplification matrix.

    The spectral radius is sampled on a log grid of s = μ(1 + A/m) over ``s_range``; the
    stable run (ρ < 1) containing s = 1 (μ = m/(m + A)) is taken, or the longest one (in log s)
    when s = 1 is unstable, and its ends are refined by bisection on ρ = 1.

    Parameters
    ----------
    mass_ratio, zeta, omega_n_dt : array_like
        A/m [-], ζ [-], ω_nΔt [rad]; broadcast against each other.
    reading : HollowayReading
        Reading of the paper.
    s_range : (float, float)
        Search range of μ(1 + A/m) [-].
    n_grid : int
        Grid points; a stable band narrower than the grid spacing (≈ 0.3 % in s by default,
        which happens only near the largest usable Δt) can be missed.
    rtol : float
        Relative bisection tolerance on μ [-].

    Returns
    -------
    mu_lower, mu_upper : numpy.ndarray
        Limits [-] with the broadcast shape; NaN where no stable μ was found or the stable run
        reaches the end of the search range.
    """
    r = _positive(mass_ratio, "mass_ratio", allow_zero=True)
    z = _positive(zeta, "zeta", allow_zero=True)
    w = _positive(omega_n_dt, "omega_n_dt")
    s_lo, s_hi = (float(x) for x in s_range)
    if not (0.0 < s_lo < 1.0 < s_hi and np.isfinite(s_hi)):
        raise ValueError(f"s_range = {s_range!r}; expected 0 < s_min < 1 < s_max < ∞")
    if int(n_grid) < 10:
        raise ValueError(f"n_grid = {n_grid!r}; expected at least 10 points")
    r, z, w = np.broadcast_arrays(r, z, w)
    shape = r.shape
    r, z, w = r.ravel(), z.ravel(), w.ravel()
    s = np.geomspace(s_lo, s_hi, int(n_grid))
    lower = np.full(r.size, np.nan)
    upper = np.full(r.size, np.nan)
    brackets: list[tuple[int, float, float, bool]] = []  # (case, s_stable, s_unstable, is_upper)
    for k in range(r.size):  # one vectorised eigen-solve per case
        rho = spectral_radius(r[k], s / (1.0 + r[k]), z[k], w[k], reading)
        stable = rho < 1.0
        if not stable.any():
            continue
        edges = np.flatnonzero(np.diff(stable.astype(np.int8)))
        starts = np.concatenate(([0] if stable[0] else [], edges[~stable[edges]] + 1))
        ends = np.concatenate((edges[stable[edges]], [s.size - 1] if stable[-1] else []))
        starts, ends = starts.astype(int), ends.astype(int)
        i_one = int(np.searchsorted(s, 1.0))
        holds_one = (starts <= i_one) & (ends >= i_one) & stable[min(i_one, s.size - 1)]
        pick = (
            int(np.flatnonzero(holds_one)[0]) if holds_one.any() else int(np.argmax(ends - starts))
        )
        i0, i1 = starts[pick], ends[pick]
        if i0 > 0:
            brackets.append((k, s[i0], s[i0 - 1], False))
        if i1 < s.size - 1:
            brackets.append((k, s[i1], s[i1 + 1], True))
    if brackets:
        case = np.array([b[0] for b in brackets])
        good = np.array([b[1] for b in brackets])
        bad = np.array([b[2] for b in brackets])
        while np.max(np.abs(good - bad) / good) > rtol:
            mid = np.sqrt(good * bad)
            ok = spectral_radius(r[case], mid / (1.0 + r[case]), z[case], w[case], reading) < 1.0
            good = np.where(ok, mid, good)
            bad = np.where(ok, bad, mid)
        limit = 0.5 * (good + bad) / (1.0 + r[case])
        is_upper = np.array([b[3] for b in brackets])
        lower[case[~is_upper]] = limit[~is_upper]
        upper[case[is_upper]] = limit[is_upper]
    return lower.reshape(shape), upper.reshape(shape)


def max_stable_omega_dt(
    mass_ratio: float,
    zeta: float,
    reading: HollowayReading = DEFAULT_READING,
    bracket: tuple[float, float] = (0.25, 3.0),
    s_range: tuple[float, float] = (0.3, 3.0),
    n_grid: int = 6000,
    rtol: float = 1e-6,
) -> float:
    """Largest ω_nΔt [rad] for which some μ gives a stable scheme (bisection on ω_nΔt).

    Stability at a given ω_nΔt means min over s = μ(1 + A/m) of the spectral radius < 1, the
    minimum taken on a log grid of s over ``s_range`` and polished by a bounded scalar search.
    Holloway §5: the method stops working at about 3.7 steps per natural period.

    Parameters
    ----------
    mass_ratio, zeta : float
        A/m [-], ζ [-].
    reading : HollowayReading
        Reading of the paper.
    bracket : (float, float)
        ω_nΔt [rad] known stable / unstable.
    s_range : (float, float)
        Search range of μ(1 + A/m) [-].
    n_grid : int
        Grid points in s.
    rtol : float
        Relative tolerance on ω_nΔt.

    Returns
    -------
    float
        The limit [rad]; NaN when the bracket does not change stability.
    """
    from scipy.optimize import minimize_scalar

    r = float(_positive(mass_ratio, "mass_ratio", allow_zero=True))
    z = float(_positive(zeta, "zeta", allow_zero=True))
    s = np.geomspace(*s_range, int(n_grid))

    def min_rho(w: float) -> float:
        rho = spectral_radius(r, s / (1.0 + r), z, w, reading)
        i = int(np.argmin(rho))
        lo, hi = s[max(i - 1, 0)], s[min(i + 1, s.size - 1)]
        res = minimize_scalar(
            lambda x: float(spectral_radius(r, x / (1.0 + r), z, w, reading)),
            bounds=(lo, hi),
            method="bounded",
            options={"xatol": 1e-12},
        )
        return min(float(rho[i]), float(res.fun))

    good, bad = (float(x) for x in bracket)
    if not (min_rho(good) < 1.0 <= min_rho(bad)):
        return float("nan")
    while bad - good > rtol * good:
        mid = 0.5 * (good + bad)
        if min_rho(mid) < 1.0:
            good = mid
        else:
            bad = mid
    return 0.5 * (good + bad)


def forced_response_error(
    mass_ratio: npt.ArrayLike,
    mu: npt.ArrayLike,
    zeta: npt.ArrayLike,
    omega_n_dt: npt.ArrayLike,
    frequency_ratio: npt.ArrayLike = 1.0,
    reading: HollowayReading = DEFAULT_READING,
) -> tuple[FloatArray, FloatArray]:
    """Steady-state error of the scheme's response to F_w = cos ωt against the exact response.

    The discrete steady state is X_num = e_x·(e^{iωΔt} I − M)⁻¹ b (sampled at tₖ); the exact one
    X = F/(C − (m + A)ω² + iωB). Holloway §6 (Fig. 3) reports these errors at ω = ω_n.

    Parameters
    ----------
    mass_ratio, mu, zeta, omega_n_dt : array_like
        As for :func:`amplification_matrix`.
    frequency_ratio : array_like
        ω/ω_n [-].
    reading : HollowayReading
        Reading of the paper.

    Returns
    -------
    amplitude_error : numpy.ndarray
        |X_num|/|X| − 1 [-].
    phase_error : numpy.ndarray
        arg(X_num/X) [rad]; positive when the numerical response leads.
    """
    r, mu_a, z, w, fr = np.broadcast_arrays(
        _positive(mass_ratio, "mass_ratio", allow_zero=True),
        _positive(mu, "mu"),
        _positive(zeta, "zeta", allow_zero=True),
        _positive(omega_n_dt, "omega_n_dt"),
        _positive(frequency_ratio, "frequency_ratio"),
    )
    mat = amplification_matrix(r, mu_a, z, w, reading)
    b_vec = forcing_vector(r, mu_a, z, w, reading)
    _, bb, cc = oscillator_coefficients(r, z, w, 1.0, reading.mass_basis)
    w_dt = w * fr
    zz = np.exp(1j * w_dt)[..., None, None]
    resp = np.linalg.solve(zz * np.eye(N_STATE) - mat, b_vec[..., None].astype(complex))
    x_num = resp[..., 0, 0]
    x_exact = 1.0 / (cc - (1.0 + r) * w_dt**2 + 1j * w_dt * bb)  # m = 1, Δt = 1
    ratio = x_num / x_exact
    return np.abs(ratio) - 1.0, np.angle(ratio)


def lumped_oscillator_rhs(
    mass: npt.ArrayLike,
    added_mass: npt.ArrayLike,
    damping: npt.ArrayLike,
    stiffness: npt.ArrayLike,
    wave_force: Callable[[float], npt.ArrayLike] | None = None,
) -> Callable[[float, FloatArray, FloatArray, FloatArray], FloatArray]:
    """Right-hand side ẍ_c = [F_w(t) − (A ẍ_e + B ẋ + C x)]/m (Holloway eq. 10) per DOF.

    For :class:`~ship_gym.numerics.integrators.HollowayIntegrator`: independent DOF (all arguments
    broadcast per DOF), the added-mass force lumped with the extrapolated acceleration.

    Parameters
    ----------
    mass : array_like
        m [kg] (> 0).
    added_mass, damping, stiffness : array_like
        A [kg], B [kg/s], C [kg/s²].
    wave_force : callable, optional
        F_w(t) [N]; default zero.

    Returns
    -------
    callable
        ``rhs(t, x, v, acc_extrapolated) -> acc_computed``.
    """
    m = _positive(mass, "mass")
    a = np.asarray(added_mass, dtype=np.float64)
    b = np.asarray(damping, dtype=np.float64)
    c = np.asarray(stiffness, dtype=np.float64)
    inv_m = 1.0 / m

    if wave_force is None:

        def rhs(t: float, x: FloatArray, v: FloatArray, acc_e: FloatArray) -> FloatArray:
            return -(a * acc_e + b * v + c * x) * inv_m

    else:

        def rhs(t: float, x: FloatArray, v: FloatArray, acc_e: FloatArray) -> FloatArray:
            return (np.asarray(wave_force(t)) - (a * acc_e + b * v + c * x)) * inv_m

    return rhs


def integrator_amplification_matrix(
    mass_ratio: float, mu: float, zeta: float, omega_n_dt: float
) -> FloatArray:
    """Amplification matrix measured on
    :class:`~ship_gym.numerics.integrators.HollowayIntegrator` itself.

    Six copies of the oscillator (one per DOF) start from the unit vectors of the state
    (x, ẋ, ẋₖ₋₁, ẋₖ₋₂, ẍₖ₋₁, ẍₖ₋₂), installed with ``set_history``; one step gives the
    columns. Virtual mass basis. Must equal ``amplification_matrix(...)[:6, :6]`` of the default
    reading — a check that the integrator implements the analysed recurrence.

    Returns
    -------
    numpy.ndarray
        (6, 6).
    """
    eye = np.eye(6)
    a_m, b, c = oscillator_coefficients(mass_ratio, zeta, omega_n_dt, 1.0, "virtual")
    integ = HollowayIntegrator(1.0, mu)
    integ.set_history(0.0, v=eye[2:4], a=eye[4:6])
    rhs = lumped_oscillator_rhs(1.0, a_m, b, c)
    x_new, v_new, _ = integ.step(0.0, eye[0], eye[1], rhs)
    hist = integ.history
    assert hist is not None
    return np.stack([x_new, v_new, hist["v"][0], hist["v"][1], hist["a"][0], hist["a"][1]])


def time_domain_growth(
    mass_ratio: npt.ArrayLike,
    mu: npt.ArrayLike,
    zeta: npt.ArrayLike,
    omega_n_dt: npt.ArrayLike,
    n_steps: int = 4000,
    window: int = 100,
) -> FloatArray:
    """Growth factor per step of a free response computed by the real integrator [-].

    All cases run at once as independent DOF of one :class:`HollowayIntegrator` (vector μ),
    with ``startup="constant"`` — a deliberate start-up error that excites every mode — from
    x = 1, ẋ = 0 under the lumped force of eq. 10 (virtual mass basis, m = 1, Δt = 1). The
    growth factor is exp(Δ ln E / (n_steps/2)) between the maxima of
    E = √((ω_n x)² + ẋ²) over the ``window`` steps ending at n_steps/2 and at n_steps: it tends
    to the spectral radius once the dominant mode dominates (> 1: unstable). inf when the
    response overflowed.

    Parameters
    ----------
    mass_ratio, mu, zeta, omega_n_dt : array_like
        A/m [-], μ [-], ζ [-], ω_nΔt [rad]; broadcast together.
    n_steps : int
        Steps to run (even, ≥ 4·window).
    window : int
        Envelope window [steps].

    Returns
    -------
    numpy.ndarray
        Growth factor per step with the broadcast shape.
    """
    if int(window) < 1 or int(n_steps) < 4 * int(window):
        raise ValueError(
            f"n_steps = {n_steps!r}, window = {window!r}; expected window ≥ 1, n_steps ≥ 4 window"
        )
    r, mu_a, z, w = np.broadcast_arrays(
        _positive(mass_ratio, "mass_ratio", allow_zero=True),
        _positive(mu, "mu"),
        _positive(zeta, "zeta", allow_zero=True),
        _positive(omega_n_dt, "omega_n_dt"),
    )
    shape = r.shape
    r, mu_a, z, w = (x.ravel().copy() for x in (r, mu_a, z, w))
    a_m, b, c = oscillator_coefficients(r, z, w, 1.0, "virtual")
    rhs = lumped_oscillator_rhs(1.0, a_m, b, c)
    integ = HollowayIntegrator(1.0, mu_a, startup="constant")
    n = int(n_steps)
    half = n // 2
    x = np.ones(r.size)
    v = np.zeros(r.size)
    env = np.empty((n, r.size))
    with np.errstate(over="ignore", invalid="ignore"):
        for k in range(n):
            x, v, _ = integ.step(float(k), x, v, rhs)
            env[k] = np.hypot(w * x, v)
        e_mid = np.max(env[half - window : half], axis=0)
        e_end = np.max(env[n - window :], axis=0)
        growth = np.exp((np.log(e_end) - np.log(e_mid)) / (n - half))
    growth = np.where(np.isfinite(growth), growth, np.inf)
    return growth.reshape(shape)


def time_domain_stability_limits(
    mass_ratio: npt.ArrayLike,
    zeta: npt.ArrayLike,
    omega_n_dt: npt.ArrayLike,
    n_steps: int = 4000,
    n_bisect: int = 24,
    brackets: tuple[tuple[float, float], tuple[float, float]] = ((0.01, 1.0), (1.0, 2.0)),
) -> tuple[FloatArray, FloatArray]:
    """μ stability limits by bisection on the time-domain growth of :func:`time_domain_growth`.

    Independent of the amplification matrix: runs the integrator. Bisection in
    s = μ(1 + A/m) on each bracket (stable at s = 1, unstable at the outer ends), all cases and
    both limits in one vectorised integrator run per iteration.

    Parameters
    ----------
    mass_ratio, zeta, omega_n_dt : array_like
        A/m [-], ζ [-], ω_nΔt [rad]; broadcast together.
    n_steps : int
        Steps per run.
    n_bisect : int
        Bisection iterations (the bracket shrinks by 2^n_bisect).
    brackets : ((float, float), (float, float))
        Initial brackets of s for the lower and the upper limit.

    Returns
    -------
    mu_lower, mu_upper : numpy.ndarray
        NaN where a bracket does not change stability at its ends.
    """
    r, z, w = np.broadcast_arrays(
        _positive(mass_ratio, "mass_ratio", allow_zero=True),
        _positive(zeta, "zeta", allow_zero=True),
        _positive(omega_n_dt, "omega_n_dt"),
    )
    shape = r.shape
    r, z, w = (np.tile(x.ravel(), 2) for x in (r, z, w))
    n_case = r.size // 2
    (l0, l1), (u0, u1) = brackets
    lo = np.concatenate([np.full(n_case, l0), np.full(n_case, u1)])  # unstable ends
    hi = np.concatenate([np.full(n_case, l1), np.full(n_case, u0)])  # stable ends
    g_lo = time_domain_growth(r, lo / (1 + r), z, w, n_steps)
    g_hi = time_domain_growth(r, hi / (1 + r), z, w, n_steps)
    valid = (g_lo > 1.0) & (g_hi <= 1.0)
    bad, good = lo.copy(), hi.copy()
    for _ in range(int(n_bisect)):
        mid = np.sqrt(bad * good)
        unstable = time_domain_growth(r, mid / (1 + r), z, w, n_steps) > 1.0
        bad = np.where(unstable, mid, bad)
        good = np.where(unstable, good, mid)
    limit = np.where(valid, 0.5 * (bad + good) / (1.0 + r), np.nan)
    return limit[:n_case].reshape(shape), limit[n_case:].reshape(shape)


def fit_limit_constants(
    mass_ratio: npt.ArrayLike, mu_limit: npt.ArrayLike, reference: float | None = None
) -> dict[str, float]:
    """Fit μ_lim = c/(A/m + 1) and Holloway's c₁/(A/m + c₂) to limits (NaNs ignored).

    Parameters
    ----------
    mass_ratio : array_like
        A/m [-].
    mu_limit : array_like
        Limits μ [-], same shape.
    reference : float, optional
        Holloway's constant (0.22 or 1.14) to measure the deviation from.

    Returns
    -------
    dict
        ``const`` (mean of μ(1 + A/m)), ``const_spread`` (max |μ(1 + A/m)/const − 1|), ``c1``,
        ``c2`` (least squares of 1/μ = (A/m + c₂)/c₁), and with ``reference``:
        ``max_rel_deviation`` = max |μ(1 + A/m)/reference − 1| and ``const_rel_deviation``.
    """
    r = np.asarray(mass_ratio, dtype=np.float64).ravel()
    mu = np.asarray(mu_limit, dtype=np.float64).ravel()
    if r.shape != mu.shape:
        raise ValueError(f"mass_ratio {r.shape} and mu_limit {mu.shape} differ in shape")
    ok = np.isfinite(mu) & (mu > 0)
    out = {k: float("nan") for k in ("const", "const_spread", "c1", "c2")}
    if reference is not None:
        out["max_rel_deviation"] = float("nan")
        out["const_rel_deviation"] = float("nan")
    if ok.sum() < 2:
        return out
    prod = mu[ok] * (1.0 + r[ok])
    const = float(np.mean(prod))
    slope, intercept = np.polyfit(r[ok], 1.0 / mu[ok], 1)
    out.update(
        const=const,
        const_spread=float(np.max(np.abs(prod / const - 1.0))),
        c1=float(1.0 / slope),
        c2=float(intercept / slope),
    )
    if reference is not None:
        out["max_rel_deviation"] = float(np.max(np.abs(prod / reference - 1.0)))
        out["const_rel_deviation"] = float(const / reference - 1.0)
    return out
