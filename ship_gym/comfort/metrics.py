r"""Passenger comfort and motion sickness from the motions of a point on the ship.

Everything here works on time series (or on (N,) arrays over episodes, step by step) of the
6-DOF state; conventions of :mod:`ship_gym.conventions` (body axes x forward, y starboard, z
down; η = (x, y, z, φ, θ, ψ) in NED, ν = (u, v, w, p, q, r) in body axes).

Acceleration at a point
-----------------------
A point P fixed in the hull at body coordinates r = (x_P, y_P, z_P) has the inertial (earth-frame)
acceleration, in body axes,

    a_P = v̇ + ω × v + ω̇ × r + ω × (ω × r),                                             (1)

v = (u, v, w), ω = (p, q, r), v̇ and ω̇ the body-axis derivatives of ν (the transport theorem,
e.g. Fossen 2011, §3.1; Lloyd 1989, ch. 4). A passenger (or an accelerometer) at P feels the
**specific force** (force per unit mass the deck exerts),

    f = a_P − g_b,   g_b = Rᵀ (0, 0, g) = g (−sin θ, cos θ sin φ, cos θ cos φ),           (2)

R = R(φ, θ, ψ) body → earth. At rest f = (0, 0, −g): the deck pushes up. Its lateral component
f_y is the **lateral force estimator** (LFE, Graham 1990: the lateral force per unit mass that
tends to make a standing person slide or tip; linearised LFE = ÿ_P − g φ): in a heel φ > 0 at
rest f_y = −g sin φ, the deck pushing the person to port against the down-slope pull. The
**vertical acceleration** used by motion-sickness criteria is the earth-vertical component of
a_P, (R a_P)_z (positive down), which includes heave, pitch and roll contributions at P.

Motion sickness: ISO 2631-1 (1997)
-----------------------------------
The vertical acceleration is weighted by W_f (ISO 2631-1:1997, Annex A, eq. (A.1)–(A.6)):

    W_f(s) = H_h(s) H_l(s) H_t(s) H_s(s),
    H_h = s² / (s² + ω₁ s/Q₁ + ω₁²),              high pass, f₁ = 0.08 Hz, Q₁ = 1/√2,
    H_l = ω₂² / (s² + ω₂ s/Q₂ + ω₂²),             low pass,  f₂ = 0.63 Hz, Q₂ = 1/√2,
    H_t = 1 / (1 + s/(Q₄ω₄) + s²/ω₄²),            a-v transition (f₃ = ∞), f₄ = 0.25 Hz, Q₄ = 0.86,
    H_s = (1 + s/(Q₅ω₅) + s²/ω₅²) / (1 + s/(Q₆ω₆) + s²/ω₆²) · (ω₅/ω₆)²,
                                                  upward step, f₅ = 0.0625 Hz, Q₅ = 0.80,
                                                  f₆ = 0.1 Hz, Q₆ = 0.80,                  (3)

ωᵢ = 2π fᵢ. |W_f| peaks at ≈ 1.0 near 0.16–0.2 Hz (periods of 5–6 s, where people are most
susceptible). It reproduces the W_f factors tabulated by the standard (one-third-octave
bands: 0.695 at 0.1 Hz, 1.006 at 0.16 Hz, 0.854 at 0.25 Hz, 0.384 at 0.4 Hz, 0.116 at 0.63 Hz;
tested). The motion sickness dose value (ISO 2631-1:1997, §9.2.2) and the percentage of
unadapted adults who may vomit (Annex D) are

    MSDV_z = [∫₀ᵀ a_w(t)² dt]^{1/2}  [m/s^1.5],   MSI ≈ K_m · MSDV_z  [%],  K_m = 1/3,      (4)

(K_m = 1/3 for a mixed population of men and women; the relation was fitted to exposures of 20
minutes to 6 hours). For a sinusoid of amplitude A at frequency f, a_w has the amplitude
|W_f(i2πf)| A and MSDV_z² → |W_f|² A² T/2.

Motion sickness: O'Hanlon & McCauley (1974)
--------------------------------------------
The seakeeping form of their vomiting-incidence model for 2 hours of sinusoidal vertical motion
(McCauley et al. 1976; as used by Lloyd 1989, ch. 13, and in fast-ferry ride control):

    MSI = 100 Φ((log₁₀(ā/g) − μ_MSI) / 0.4) [%],   μ_MSI = −0.819 + 2.32 (log₁₀ ω)²,       (5)

ā the mean absolute vertical acceleration [m/s²] (2√2/π ≈ 0.900 × RMS for a sinusoid,
√(2/π) ≈ 0.798 × RMS for a Gaussian process), ω the (encounter) frequency [rad/s] of the motion,
Φ the standard normal distribution function. MSI = 50 % at
ā = g·10^μ_MSI; the most provocative frequency is ω = 1 rad/s (0.16 Hz).

Running, reward-friendly estimates
----------------------------------
:class:`RunningWeighting` applies eq. (3) sample by sample to (N,) arrays (bilinear transform of
each second-order section with pre-warping at its natural frequency, so each section's corner
frequency is exact at any sampling step; a cascade of direct-form-II-transposed biquads).
:class:`ExponentialRMS` is the exponentially weighted RMS with time constant τ,
m ← m + α (x² − m), α = 1 − e^{−Δt/τ}, RMS = √m (the discrete form of the first-order filter
τ ṁ + m = x²). :class:`RunningDose` accumulates MSDV_z² = Σ a_w² Δt per episode.

References
----------
ISO 2631-1:1997. Mechanical vibration and shock — Evaluation of human exposure to whole-body
vibration — Part 1: General requirements. §9.2, Annex A, Annex D.
O'Hanlon, J.F. & McCauley, M.E. (1974). Motion sickness incidence as a function of the
frequency and acceleration of vertical sinusoidal motion. Aerospace Medicine 45(4), 366–369.
McCauley, M.E., Royal, J.W., Wylie, C.D., O'Hanlon, J.F. & Mackie, R.R. (1976). Motion sickness
incidence: exploratory studies of habituation, pitch and roll, and the refinement of a
mathematical model. Human Factors Research Inc., Tech. Rep. 1733-2.
Lloyd, A.R.J.M. (1989). Seakeeping: Ship Behaviour in Rough Weather. Ellis Horwood.
Graham, R. (1990). Motion-induced interruptions as ship operability criteria. Naval Engineers
Journal 102(2), 65–71.
Fossen, T.I. (2011). Handbook of Marine Craft Hydrodynamics and Motion Control. Wiley.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import GRAVITY

__all__ = [
    "ISO_MSI_CONSTANT",
    "WF",
    "ComfortSample",
    "ExponentialRMS",
    "FrequencyWeighting",
    "PassengerComfort",
    "RunningDose",
    "RunningWeighting",
    "lateral_force_estimator",
    "motion_sickness_dose_value",
    "msi_iso",
    "msi_ohanlon_mccauley",
    "point_acceleration",
    "specific_force",
    "vertical_acceleration",
    "weighted_acceleration",
]

ISO_MSI_CONSTANT: float = 1.0 / 3.0
"""K_m of eq. (4) (ISO 2631-1:1997, Annex D): % vomiting per m/s^1.5, mixed population."""


# =============================================================================================
# kinematics of a point
# =============================================================================================
def _vectors(nu: ArrayLike, nu_dot: ArrayLike, point: ArrayLike) -> tuple[NDArray, ...]:
    n = np.asarray(nu, dtype=float)
    nd = np.asarray(nu_dot, dtype=float)
    r = np.asarray(point, dtype=float)
    if n.shape[-1:] != (6,) or nd.shape[-1:] != (6,):
        raise ValueError(
            f"nu and nu_dot must have a last axis of 6 (u, v, w, p, q, r); got shapes {n.shape} "
            f"and {nd.shape}"
        )
    if r.shape != (3,) or not np.all(np.isfinite(r)):
        raise ValueError(f"point must be a finite (3,) body-frame position [m]; got {point!r}")
    return n, nd, r


def point_acceleration(nu: ArrayLike, nu_dot: ArrayLike, point: ArrayLike) -> NDArray:
    """Inertial acceleration of a hull point in body axes, eq. (1) [m/s²].

    Parameters
    ----------
    nu, nu_dot : array_like
        (..., 6) body velocities (u, v, w, p, q, r) [m/s, rad/s] and their time derivatives
        [m/s², rad/s²].
    point : array_like
        (3,) body-frame position r of the point [m].

    Returns
    -------
    numpy.ndarray
        (..., 3) a_P = v̇ + ω × v + ω̇ × r + ω × (ω × r).
    """
    n, nd, r = _vectors(nu, nu_dot, point)
    v, w = n[..., :3], n[..., 3:]
    w_r = _cross(w, r)
    return nd[..., :3] + _cross(w, v) + _cross(nd[..., 3:], r) + _cross(w, w_r)


def _cross(a: NDArray, b: NDArray) -> NDArray:
    """a × b over the last axis (3): np.cross's arithmetic without its axis handling, which
    dominated an environment step for (N, 3) arrays."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def _gravity_body(eta: NDArray, g: float) -> NDArray:
    """g_b = Rᵀ (0, 0, g) of eq. (2), (..., 3)."""
    phi, theta = eta[..., 3], eta[..., 4]
    ct = np.cos(theta)
    return g * np.stack([-np.sin(theta), ct * np.sin(phi), ct * np.cos(phi)], axis=-1)


def specific_force(
    eta: ArrayLike, nu: ArrayLike, nu_dot: ArrayLike, point: ArrayLike, g: float = GRAVITY
) -> NDArray:
    """Specific force felt at a hull point, f = a_P − Rᵀ(0, 0, g), eq. (2), body axes [m/s²].

    Parameters
    ----------
    eta : array_like
        (..., 6) positions and Euler angles [m, rad] (only φ, θ are used).
    nu, nu_dot : array_like
        (..., 6) body velocities and their derivatives.
    point : array_like
        (3,) body-frame position of the point [m].
    g : float
        Gravity [m/s²].

    Returns
    -------
    numpy.ndarray
        (..., 3); (0, 0, −g) at rest on an even keel.
    """
    e = np.asarray(eta, dtype=float)
    if e.shape[-1:] != (6,):
        raise ValueError(f"eta must have a last axis of 6; got shape {e.shape}")
    return point_acceleration(nu, nu_dot, point) - _gravity_body(e, float(g))


def lateral_force_estimator(
    eta: ArrayLike, nu: ArrayLike, nu_dot: ArrayLike, point: ArrayLike, g: float = GRAVITY
) -> NDArray:
    """Lateral specific force f_y at a hull point (LFE, Graham 1990), eq. (2) [m/s²].

    f_y = a_P,y − g cos θ sin φ: the deck's lateral push per unit mass (positive toward
    starboard); linearised, ÿ_P − g φ. Shape (...,).
    """
    return specific_force(eta, nu, nu_dot, point, g)[..., 1]


def vertical_acceleration(
    eta: ArrayLike, nu: ArrayLike, nu_dot: ArrayLike, point: ArrayLike
) -> NDArray:
    """Earth-vertical inertial acceleration of a hull point, (R a_P)_z [m/s², positive down].

    The quantity weighted by W_f for motion sickness (heave, pitch and roll at the point).
    Shape (...,).
    """
    e = np.asarray(eta, dtype=float)
    if e.shape[-1:] != (6,):
        raise ValueError(f"eta must have a last axis of 6; got shape {e.shape}")
    a = point_acceleration(nu, nu_dot, point)
    phi, theta = e[..., 3], e[..., 4]
    ct = np.cos(theta)
    # third row of R(φ, θ, ψ): (−sin θ, cos θ sin φ, cos θ cos φ)
    return -np.sin(theta) * a[..., 0] + ct * np.sin(phi) * a[..., 1] + ct * np.cos(phi) * a[..., 2]


# =============================================================================================
# ISO 2631-1 frequency weighting
# =============================================================================================
def _bilinear(c: tuple[float, float, float], k: float) -> tuple[float, float, float]:
    """z⁻¹ coefficients of c₀ + c₁ s + c₂ s² under s = k (1 − z⁻¹)/(1 + z⁻¹), times (1 + z⁻¹)²."""
    k2 = k * k
    return (c[0] + c[1] * k + c[2] * k2, 2.0 * c[0] - 2.0 * c[2] * k2, c[0] - c[1] * k + c[2] * k2)


@dataclass(frozen=True)
class FrequencyWeighting:
    """Parameters of an ISO 2631-1 frequency weighting, eq. (3) (Annex A, Table A.2 form).

    Frequencies in Hz; ``f3 = math.inf`` removes the numerator of the a-v transition.
    """

    f1: float
    f2: float
    f3: float
    f4: float
    q4: float
    f5: float
    q5: float
    f6: float
    q6: float
    q1: float = 1.0 / math.sqrt(2.0)
    q2: float = 1.0 / math.sqrt(2.0)

    def sections(self) -> list[tuple[tuple[float, float, float], tuple[float, float, float]]]:
        """Second-order sections (b₀, b₁, b₂), (a₀, a₁, a₂) of H = Σbₖsᵏ / Σaₖsᵏ (s in rad/s)."""
        w = [2.0 * math.pi * f for f in (self.f1, self.f2, self.f3, self.f4, self.f5, self.f6)]
        w1, w2, w3, w4, w5, w6 = w
        gain = (w5 / w6) ** 2
        out: list[tuple[tuple[float, float, float], tuple[float, float, float]]] = [
            ((0.0, 0.0, 1.0), (w1 * w1, w1 / self.q1, 1.0)),  # H_h
            ((w2 * w2, 0.0, 0.0), (w2 * w2, w2 / self.q2, 1.0)),  # H_l
            # H_t = (1 + s/ω₃) / (1 + s/(Q₄ω₄) + s²/ω₄²)
            (
                (1.0, 0.0 if math.isinf(w3) else 1.0 / w3, 0.0),
                (1.0, 1.0 / (self.q4 * w4), 1 / w4**2),
            ),
            # H_s = (1 + s/(Q₅ω₅) + s²/ω₅²)(ω₅/ω₆)² / (1 + s/(Q₆ω₆) + s²/ω₆²)
            (
                (1.0 * gain, 1.0 / (self.q5 * w5) * gain, 1.0 / w5**2 * gain),
                (1.0, 1.0 / (self.q6 * w6), 1.0 / w6**2),
            ),
        ]
        return out

    def response(self, frequency_hz: ArrayLike) -> NDArray:
        """Complex W(i 2π f) at frequencies f [Hz] (analytic, eq. 3)."""
        f = np.asarray(frequency_hz, dtype=float)
        s = 2j * np.pi * f
        out = np.ones_like(s)
        for b, a in self.sections():
            out = out * (b[0] + s * (b[1] + s * b[2])) / (a[0] + s * (a[1] + s * a[2]))
        return out

    def natural_frequencies(self) -> list[float]:
        """The pre-warping frequency of each section [rad/s] (its corner / √(ω₅ω₆))."""
        two_pi = 2.0 * math.pi
        return [
            two_pi * self.f1,
            two_pi * self.f2,
            two_pi * self.f4,
            two_pi * math.sqrt(self.f5 * self.f6),
        ]

    def sos(self, dt: float) -> NDArray:
        """(4, 6) digital second-order sections [b0, b1, b2, 1, a1, a2] for a sampling step dt.

        Bilinear transform s = K (1 − z⁻¹)/(1 + z⁻¹) with K = ω₀ / tan(ω₀ dt/2) per section
        (pre-warped at its natural frequency ω₀, which must lie below the Nyquist frequency).
        """
        dt = float(dt)
        if not (math.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be a positive sampling step [s]; got {dt!r}")
        rows = []
        for (b, a), w0 in zip(self.sections(), self.natural_frequencies(), strict=True):
            if w0 * dt / 2.0 >= 0.5 * math.pi * 0.95:
                raise ValueError(
                    f"sampling step dt = {dt} s is too coarse for a weighting corner at "
                    f"{w0 / (2 * math.pi):.3g} Hz (Nyquist {0.5 / dt:.3g} Hz)"
                )
            k = w0 / math.tan(w0 * dt / 2.0)
            bz, az = _bilinear(b, k), _bilinear(a, k)
            rows.append(
                [bz[0] / az[0], bz[1] / az[0], bz[2] / az[0], 1.0, az[1] / az[0], az[2] / az[0]]
            )
        return np.array(rows)


WF = FrequencyWeighting(
    f1=0.08, f2=0.63, f3=math.inf, f4=0.25, q4=0.86, f5=0.0625, q5=0.80, f6=0.1, q6=0.80
)
"""ISO 2631-1:1997 weighting W_f (motion sickness, vertical), Annex A."""


def weighted_acceleration(
    acceleration: ArrayLike, dt: float, weighting: FrequencyWeighting = WF
) -> NDArray:
    """A time series filtered by the weighting (zero initial state), along the last axis.

    Parameters
    ----------
    acceleration : array_like
        (..., n) samples at a constant step [m/s²].
    dt : float
        Sampling step [s].
    weighting : FrequencyWeighting
        Default W_f.
    """
    from scipy.signal import sosfilt

    a = np.asarray(acceleration, dtype=float)
    if not np.all(np.isfinite(a)):
        raise ValueError("acceleration must be finite")
    return sosfilt(weighting.sos(dt), a, axis=-1)


def motion_sickness_dose_value(weighted: ArrayLike, dt: float) -> NDArray | float:
    """MSDV_z = [Σ a_w² Δt]^{1/2} over the last axis, eq. (4) [m/s^1.5]."""
    a = np.asarray(weighted, dtype=float)
    if not (math.isfinite(dt) and dt > 0.0):
        raise ValueError(f"dt must be a positive sampling step [s]; got {dt!r}")
    out = np.sqrt(np.sum(a * a, axis=-1) * float(dt))
    return float(out) if np.ndim(out) == 0 else out


def msi_iso(msdv: ArrayLike, k_m: float = ISO_MSI_CONSTANT) -> NDArray | float:
    """Percentage of people who may vomit, MSI = K_m MSDV_z, eq. (4) [%]."""
    m = np.asarray(msdv, dtype=float)
    if np.any(m < 0.0) or not np.all(np.isfinite(m)):
        raise ValueError(f"msdv must be finite and >= 0 [m/s^1.5]; got {msdv!r}")
    out = k_m * m
    return float(out) if np.ndim(out) == 0 else out


def msi_ohanlon_mccauley(
    mean_abs_acceleration: ArrayLike, frequency: ArrayLike, g: float = GRAVITY
) -> NDArray | float:
    """O'Hanlon & McCauley (1974) motion sickness incidence after 2 h, eq. (5) [%].

    Parameters
    ----------
    mean_abs_acceleration : array_like
        ā, mean absolute vertical acceleration [m/s²] (> 0).
    frequency : array_like
        ω of the motion [rad/s] (> 0; the model was fitted for ≈ 0.5–4 rad/s).
    g : float
        Gravity [m/s²].
    """
    from scipy.special import ndtr

    a = np.asarray(mean_abs_acceleration, dtype=float)
    w = np.asarray(frequency, dtype=float)
    if np.any(~np.isfinite(a)) or np.any(a < 0.0):
        raise ValueError(f"mean_abs_acceleration must be finite and >= 0 [m/s²]; got {a!r}")
    if np.any(~np.isfinite(w)) or np.any(w <= 0.0):
        raise ValueError(f"frequency must be finite and > 0 [rad/s]; got {w!r}")
    mu = -0.819 + 2.32 * np.log10(w) ** 2
    with np.errstate(divide="ignore"):
        z = (np.log10(a / g) - mu) / 0.4
    out = 100.0 * ndtr(z)
    return float(out) if np.ndim(out) == 0 else out


# =============================================================================================
# running estimates over N episodes
# =============================================================================================
def _ids(ids: ArrayLike | None, n: int) -> NDArray[np.int64] | slice:
    return slice(None) if ids is None else np.asarray(ids, dtype=np.int64).reshape(-1)


class RunningWeighting:
    """Eq. (3) applied sample by sample to (N,) signals (one filter state per episode).

    Parameters
    ----------
    num_envs : int
        N.
    dt : float
        Sampling step [s] (the env's control step).
    weighting : FrequencyWeighting
        Default W_f.
    """

    def __init__(self, num_envs: int, dt: float, weighting: FrequencyWeighting = WF) -> None:
        self.sos = weighting.sos(dt)
        self.state = np.zeros((self.sos.shape[0], 2, int(num_envs)))

    def reset(self, ids: ArrayLike | None = None) -> None:
        """Zero the filter state of episodes ``ids`` (default all)."""
        self.state[:, :, _ids(ids, self.state.shape[2])] = 0.0

    def update(self, x: ArrayLike) -> NDArray:
        """Filter one sample per episode; returns the (N,) weighted output."""
        y = np.asarray(x, dtype=float).copy()
        for k in range(self.sos.shape[0]):
            b0, b1, b2, _, a1, a2 = self.sos[k]
            z1, z2 = self.state[k, 0], self.state[k, 1]
            out = b0 * y + z1
            z1[:] = b1 * y - a1 * out + z2
            z2[:] = b2 * y - a2 * out
            y = out
        return y


class ExponentialRMS:
    """Exponentially weighted RMS of (N,) signals: m ← m + α (x² − m), α = 1 − e^{−Δt/τ}.

    Parameters
    ----------
    num_envs : int
        N.
    dt : float
        Sampling step [s].
    time_constant : float
        τ [s].
    """

    def __init__(self, num_envs: int, dt: float, time_constant: float) -> None:
        if not (math.isfinite(time_constant) and time_constant > 0.0):
            raise ValueError(f"time_constant must be a positive time [s]; got {time_constant!r}")
        if not (math.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be a positive sampling step [s]; got {dt!r}")
        self.alpha = 1.0 - math.exp(-float(dt) / float(time_constant))
        self.mean_square = np.zeros(int(num_envs))

    def reset(self, ids: ArrayLike | None = None) -> None:
        """Forget the history of episodes ``ids`` (default all)."""
        self.mean_square[_ids(ids, self.mean_square.size)] = 0.0

    def update(self, x: ArrayLike) -> NDArray:
        """Add one sample per episode; returns the (N,) running RMS."""
        xx = np.asarray(x, dtype=float)
        self.mean_square += self.alpha * (xx * xx - self.mean_square)
        return np.sqrt(self.mean_square)


class RunningDose:
    """MSDV² = Σ a_w² Δt per episode, eq. (4), and the ISO MSI from it."""

    def __init__(self, num_envs: int, dt: float) -> None:
        if not (math.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be a positive sampling step [s]; got {dt!r}")
        self.dt = float(dt)
        self.dose_squared = np.zeros(int(num_envs))

    def reset(self, ids: ArrayLike | None = None) -> None:
        """Zero the dose of episodes ``ids`` (default all)."""
        self.dose_squared[_ids(ids, self.dose_squared.size)] = 0.0

    def update(self, weighted: ArrayLike) -> NDArray:
        """Add one weighted sample per episode; returns the (N,) increment a_w² Δt [m²/s³]."""
        a = np.asarray(weighted, dtype=float)
        inc = a * a * self.dt
        self.dose_squared += inc
        return inc

    @property
    def msdv(self) -> NDArray:
        """(N,) MSDV_z so far [m/s^1.5]."""
        return np.sqrt(self.dose_squared)

    @property
    def msi(self) -> NDArray:
        """(N,) ISO MSI so far [%] (eq. 4)."""
        return ISO_MSI_CONSTANT * self.msdv


@dataclass(frozen=True)
class ComfortSample:
    """Comfort quantities at a passenger point at the end of one control step, (N,) each.

    Attributes
    ----------
    lateral : NDArray
        Lateral specific force f_y (LFE), eq. (2) [m/s²].
    vertical : NDArray
        Earth-vertical acceleration (R a_P)_z [m/s², positive down].
    weighted_vertical : NDArray
        W_f-weighted vertical acceleration a_w [m/s²] (running filter, eq. 3).
    lateral_rms, vertical_rms : NDArray
        Exponentially weighted RMS of f_y and of the vertical acceleration [m/s²].
    msdv : NDArray
        MSDV_z of the episode so far [m/s^1.5], eq. (4).
    """

    lateral: NDArray
    vertical: NDArray
    weighted_vertical: NDArray
    lateral_rms: NDArray
    vertical_rms: NDArray
    msdv: NDArray


@numba.njit(cache=True, nogil=True)
def _comfort_kernel(
    nu, nu_prev, dt, point, g, sin_theta, cos_theta, sin_phi, cos_phi, sos, state, dose_squared,
    dose_dt, lateral_alpha, lateral_ms, vertical_alpha, vertical_ms,
    lateral, vertical, weighted, lateral_rms, vertical_rms, msdv,
):  # fmt: skip  # pragma: no cover - compiled
    """One :meth:`PassengerComfort.update` of N episodes: eq. (1)–(3), the dose and the RMS.

    The operations of :func:`specific_force`, :func:`vertical_acceleration`,
    :class:`RunningWeighting`, :class:`RunningDose` and :class:`ExponentialRMS` in their order
    (bit for bit the same results); ``nu_prev`` and the filter, dose and RMS states are updated
    in place, the sample goes to the last six arrays.
    """
    rx, ry, rz = point[0], point[1], point[2]
    for i in range(nu.shape[0]):
        u, v, w, p, q, r = nu[i, 0], nu[i, 1], nu[i, 2], nu[i, 3], nu[i, 4], nu[i, 5]
        d0 = (u - nu_prev[i, 0]) / dt
        d1 = (v - nu_prev[i, 1]) / dt
        d2 = (w - nu_prev[i, 2]) / dt
        d3 = (p - nu_prev[i, 3]) / dt
        d4 = (q - nu_prev[i, 4]) / dt
        d5 = (r - nu_prev[i, 5]) / dt
        for k in range(6):
            nu_prev[i, k] = nu[i, k]
        # eq. (1): a = v̇ + ω × v + ω̇ × r + ω × (ω × r)
        wr0 = q * rz - r * ry
        wr1 = r * rx - p * rz
        wr2 = p * ry - q * rx
        a0 = d0 + (q * w - r * v) + (d4 * rz - d5 * ry) + (q * wr2 - r * wr1)
        a1 = d1 + (r * u - p * w) + (d5 * rx - d3 * rz) + (r * wr0 - p * wr2)
        a2 = d2 + (p * v - q * u) + (d3 * ry - d4 * rx) + (p * wr1 - q * wr0)
        # eq. (2), lateral: f_y = a_y − g cos θ sin φ; vertical: (R a)_z
        st, ct, sp, cp = sin_theta[i], cos_theta[i], sin_phi[i], cos_phi[i]
        f1 = a1 - g * (ct * sp)
        vert = -st * a0 + ct * sp * a1 + ct * cp * a2
        # eq. (3): the cascade of biquads
        y = vert
        for k in range(sos.shape[0]):
            b0, b1, b2, a1k, a2k = sos[k, 0], sos[k, 1], sos[k, 2], sos[k, 4], sos[k, 5]
            out = b0 * y + state[k, 0, i]
            state[k, 0, i] = b1 * y - a1k * out + state[k, 1, i]
            state[k, 1, i] = b2 * y - a2k * out
            y = out
        dose_squared[i] += y * y * dose_dt
        lateral_ms[i] += lateral_alpha * (f1 * f1 - lateral_ms[i])
        vertical_ms[i] += vertical_alpha * (vert * vert - vertical_ms[i])
        lateral[i] = f1
        vertical[i] = vert
        weighted[i] = y
        lateral_rms[i] = math.sqrt(lateral_ms[i])
        vertical_rms[i] = math.sqrt(vertical_ms[i])
        msdv[i] = math.sqrt(dose_squared[i])


class PassengerComfort:
    """Per-episode comfort bookkeeping at one hull point, sampled once per control step.

    The body-axis accelerations ν̇ come from the backward difference of ν over the sampling step
    Δt (the simulator exposes states, not accelerations): first order, a lag of Δt/2 and an
    amplitude factor sin(ωΔt/2)/(ωΔt/2) at frequency ω (≥ 0.99 for ωΔt ≤ 0.35, e.g. a 4.5 s
    encounter period sampled every 0.25 s).

    Parameters
    ----------
    num_envs : int
        N.
    dt : float
        Sampling step Δt [s] (the control step).
    point : array_like
        (3,) body-frame position of the passenger [m].
    rms_time_constant : float
        τ of the running RMS [s].
    g : float
        Gravity [m/s²].
    """

    def __init__(
        self,
        num_envs: int,
        dt: float,
        point: ArrayLike,
        *,
        rms_time_constant: float = 60.0,
        g: float = GRAVITY,
    ) -> None:
        r = np.asarray(point, dtype=float)
        if r.shape != (3,) or not np.all(np.isfinite(r)):
            raise ValueError(f"point must be a finite (3,) body-frame position [m]; got {point!r}")
        self.point = r
        self.dt = float(dt)
        self.g = float(g)
        n = int(num_envs)
        self.weighting = RunningWeighting(n, dt)
        self.dose = RunningDose(n, dt)
        self.lateral_rms = ExponentialRMS(n, dt, rms_time_constant)
        self.vertical_rms = ExponentialRMS(n, dt, rms_time_constant)
        self._nu_prev = np.zeros((n, 6))

    def reset(self, ids: ArrayLike, nu: ArrayLike) -> None:
        """Start episodes ``ids`` from body velocities ``nu`` ((len(ids), 6) or (6,))."""
        idx = np.asarray(ids, dtype=np.int64).reshape(-1)
        self._nu_prev[idx] = np.asarray(nu, dtype=float)
        for running in (self.weighting, self.dose, self.lateral_rms, self.vertical_rms):
            running.reset(idx)

    def update(self, eta: NDArray, nu: NDArray) -> ComfortSample:
        """Take the states at the end of a control step; returns the (N,) comfort sample."""
        prev = self._nu_prev
        if not (
            type(eta) is np.ndarray
            and type(nu) is np.ndarray
            and eta.dtype == np.float64
            and nu.dtype == np.float64
            and eta.shape == nu.shape == prev.shape
        ):
            return self._update_numpy(eta, nu)
        n = prev.shape[0]
        lateral, vertical, weighted = np.empty(n), np.empty(n), np.empty(n)
        lateral_rms, vertical_rms, msdv = np.empty(n), np.empty(n), np.empty(n)
        # the trigonometric functions from NumPy, as in specific_force/vertical_acceleration
        phi, theta = eta[:, 3], eta[:, 4]
        _comfort_kernel(
            nu,
            prev,
            self.dt,
            self.point,
            self.g,
            np.sin(theta),
            np.cos(theta),
            np.sin(phi),
            np.cos(phi),
            self.weighting.sos,
            self.weighting.state,
            self.dose.dose_squared,
            self.dose.dt,
            self.lateral_rms.alpha,
            self.lateral_rms.mean_square,
            self.vertical_rms.alpha,
            self.vertical_rms.mean_square,
            lateral,
            vertical,
            weighted,
            lateral_rms,
            vertical_rms,
            msdv,
        )
        return ComfortSample(
            lateral=lateral,
            vertical=vertical,
            weighted_vertical=weighted,
            lateral_rms=lateral_rms,
            vertical_rms=vertical_rms,
            msdv=msdv,
        )

    def _update_numpy(self, eta: NDArray, nu: NDArray) -> ComfortSample:
        """:meth:`update` with the array functions of this module (any input; the kernel's
        reference)."""
        nu_dot = (nu - self._nu_prev) / self.dt
        self._nu_prev = np.array(nu, dtype=float)
        f = specific_force(eta, nu, nu_dot, self.point, self.g)
        vertical = vertical_acceleration(eta, nu, nu_dot, self.point)
        weighted = self.weighting.update(vertical)
        self.dose.update(weighted)
        return ComfortSample(
            lateral=f[:, 1],
            vertical=vertical,
            weighted_vertical=weighted,
            lateral_rms=self.lateral_rms.update(f[:, 1]),
            vertical_rms=self.vertical_rms.update(vertical),
            msdv=self.dose.msdv,
        )
