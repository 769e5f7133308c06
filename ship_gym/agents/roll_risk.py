"""The roll risk of polar operational guidance: short-term roll exceedance from the ship's response.

What onboard decision-support systems do (e.g. the polar diagrams of ABS's and DNV's heavy-weather
guidance, after IMO MSC.1/Circ.1228 §3): for every candidate course and speed, the short-term
probability that the roll exceeds a critical angle in the estimated sea, from the ship's linear
response in the frequency domain; the master takes the candidate of most progress whose risk
is below a limit (:class:`ship_gym.agents.baselines.PolarGuidanceMaster`, which keeps the
guidance's zones of the nonlinear modes the linear response cannot see).

The roll response (:class:`RollResponse`) is the uncoupled roll equation of the ship's
hydrodynamic database at the encounter frequency (Lloyd, *Seakeeping*, 1989, §9.3):

    ξ₄(ω, β, U) = F₄(ω, β) / (C₄₄ − ω_e² (I₄₄ + A₄₄(ω_e)) − i ω_e (B₄₄(ω_e) + B_v)),   (1)

with F₄ the zero-speed roll excitation per unit wave amplitude (Froude–Krylov + diffraction;
the speed terms of :mod:`ship_gym.hydro.forward_speed` act on heave, pitch and yaw), ω_e = ω −
ω² U cos β / g, C₄₄ from the observed roll period T_R of the loading (C₄₄ = (I₄₄ + A₄₄(ω_R))
ω_R²), and an equivalent-linear viscous damping B_v = 2 ζ_v √((I₄₄ + A₄₄) C₄₄) (ζ_v a tuned
parameter standing for the Ikeda damping at moderate amplitude). In a short-crested sea S(ω)
D(θ) (JONSWAP, cos-2s; the estimates of the wave radar) the roll variance and the mean
zero-up-crossing period are

    m_n = Σ_ω Σ_θ ω_e^n |ξ₄(ω, β + θ, U)|² S(ω) D(θ) Δω Δθ,   T_z = 2π √(m₀/m₂),       (2)

and the probability of exceeding φ_c in an exposure T (Rayleigh peaks, Poisson up-crossings;
Ochi, *Ocean Waves*, 1998, §8.2) is

    P = 1 − exp(−(T/T_z) exp(−φ_c²/(2 m₀))).                                                 (3)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from ship_gym.conventions import GRAVITY

__all__ = ["RollResponse", "response_of", "roll_exceedance_probability"]

_N_OMEGA = 32  # wave frequencies of eq. (2)
_N_THETA = 12  # directions of eq. (2)


@dataclass(frozen=True)
class RollResponse:
    """The uncoupled roll response of a ship, eq. (1), tabulated from its database.

    Attributes
    ----------
    omega : NDArray
        (n_ω,) wave frequencies of the excitation table [rad/s].
    headings : NDArray
        (n_β,) relative headings of the table, 0 … π [rad] (the ship is port–starboard
        symmetric: |F₄(−β)| = |F₄(β)|).
    excitation_sq : NDArray
        (n_β, n_ω) |F₄|² per unit wave amplitude [(N·m/m)²].
    radiation_omega : NDArray
        (n_r,) frequencies of the radiation table [rad/s].
    a44, b44 : NDArray
        (n_r,) roll added inertia [kg·m²] and damping [N·m·s] of the database.
    inertia : float
        Rigid-body roll inertia about O, I₄₄ [kg·m²].
    """

    omega: NDArray
    headings: NDArray
    excitation_sq: NDArray
    radiation_omega: NDArray
    a44: NDArray
    b44: NDArray
    inertia: float

    @classmethod
    def of_ship(cls, ship: str = "s175") -> RollResponse:
        """The table of a bundled ship or ship file (its BEM database and loading)."""
        from ship_gym.engine.ship import ShipSetup, database_of, ship_of
        from ship_gym.hydro import as_arrays
        from ship_gym.hydro.rao import excitation_force

        setup = ShipSetup(hull=ship, database="auto")
        database = database_of(setup)
        arrays = as_arrays(database)
        hull = ship_of(setup).hull
        w_db = np.asarray(arrays.omega, float)
        omega = np.linspace(max(0.2, w_db[0]), w_db[-1], 48)
        headings = np.linspace(0.0, math.pi, 13)
        table = np.empty((headings.size, omega.size))
        for j, beta in enumerate(headings):
            force = excitation_force(database, omega=omega, heading=float(beta), speed_terms="none")
            table[j] = np.abs(force[:, 3]) ** 2
        return cls(
            omega=omega,
            headings=headings,
            excitation_sq=table,
            radiation_omega=w_db,
            a44=np.asarray(arrays.added_mass[:, 3, 3], float),
            b44=np.asarray(arrays.radiation_damping[:, 3, 3], float),
            inertia=float(hull.mass.rigid_body_matrix()[3, 3]),
        )

    def added_inertia(self, omega: NDArray) -> NDArray:
        """A₄₄ [kg·m²] at frequencies ``omega`` [rad/s] (held constant outside the table)."""
        return np.interp(omega, self.radiation_omega, self.a44)

    def spectral_moments(
        self,
        *,
        hs: NDArray,
        tp: NDArray,
        spreading_s: NDArray,
        beta: NDArray,
        speed: NDArray,
        roll_period: NDArray,
        damping_ratio: float,
        gamma: float = 3.3,
    ) -> tuple[NDArray, NDArray]:
        """Roll moments (m₀ [rad²], m₂ [rad²/s²]) of eq. (2) for arrays broadcast together.

        Parameters
        ----------
        hs, tp, spreading_s : NDArray
            Hs [m], Tp [s] and the cos-2s exponent s [-] of the sea.
        beta : NDArray
            Relative mean wave heading β [rad] (0 following seas).
        speed : NDArray
            Ship speed U [m/s].
        roll_period : NDArray
            Roll natural period T_R of the loading [s].
        damping_ratio : float
            ζ_v of the equivalent-linear viscous damping [-].
        gamma : float
            JONSWAP γ [-].
        """
        hs, tp, s, beta, speed, t_r = np.broadcast_arrays(
            *(np.asarray(x, float) for x in (hs, tp, spreading_s, beta, speed, roll_period))
        )
        shape = beta.shape
        hs, tp, s, beta, speed, t_r = (
            np.ascontiguousarray(x).reshape(-1) for x in (hs, tp, s, beta, speed, t_r)
        )
        w_r = 2.0 * math.pi / t_r
        a_r = self.added_inertia(w_r)
        c44 = (self.inertia + a_r) * w_r**2
        b_v = 2.0 * damping_ratio * np.sqrt((self.inertia + a_r) * c44)
        x, energy = _unit_jonswap(gamma)
        theta = (np.arange(_N_THETA) + 0.5) * (2.0 * math.pi / _N_THETA) - math.pi
        w_rad, a_rad, b_rad = self._uniform_radiation()
        m0, m2 = np.empty(hs.size), np.empty(hs.size)
        _roll_moments_kernel(
            hs, s, beta, speed, c44, b_v, 2.0 * math.pi / tp, x, energy, theta,
            self.excitation_sq, self.omega[0], self.omega[1] - self.omega[0],
            self.headings[1] - self.headings[0], w_rad[1] - w_rad[0], a_rad, b_rad,
            self.inertia, GRAVITY, m0, m2,
        )  # fmt: skip
        return m0.reshape(shape), m2.reshape(shape)

    def _uniform_radiation(self) -> tuple[NDArray, NDArray, NDArray]:
        """A₄₄, B₄₄ resampled on a uniform grid 0 … ω_max (256 points) for the kernel."""
        w = np.linspace(0.0, float(self.radiation_omega[-1]), 256)
        return w, self.added_inertia(w), np.interp(w, self.radiation_omega, self.b44)


def _unit_jonswap(gamma: float) -> tuple[NDArray, NDArray]:
    """(x, e): ω = x ωp over 0.6 … 2.5 ωp and the energy S(ω) Δω of a sea of Hs = 1 m [m²],
    the same for every Tp (S(x ωp; Hs, Tp) Δω = Hs² · 2π S(2π x; 1, 1) Δx)."""
    from ship_gym.waves.spectra import jonswap

    x = np.linspace(0.6, 2.5, _N_OMEGA)
    return x, 2.0 * math.pi * jonswap(2.0 * math.pi * x, 1.0, 1.0, gamma=gamma) * (x[1] - x[0])


@numba.njit(cache=True, nogil=True)
def _roll_moments_kernel(
    hs, s, beta, speed, c44, b_v, wp, x, energy, theta, exc, w0, dw_exc, dbeta, dw_rad,
    a_rad, b_rad, inertia, g, m0, m2,
):  # fmt: skip  # pragma: no cover - compiled
    """Eq. (2) for each candidate k: m₀ and m₂ over the wave frequencies x ωp and directions
    β + θ, with |F₄|² bilinear on its uniform (|β|, ω) table and A₄₄, B₄₄ linear on their
    uniform grid at |ω_e| (held at the ends)."""
    n_b, n_w = exc.shape
    n_r = a_rad.shape[0]
    n_t = theta.shape[0]
    spread = np.empty(n_t)
    for k in range(hs.shape[0]):
        total = 0.0
        for j in range(n_t):
            spread[j] = abs(math.cos(0.5 * theta[j])) ** (2.0 * s[k])
            total += spread[j]
        acc0 = 0.0
        acc2 = 0.0
        for j in range(n_t):
            b = beta[k] + theta[j]
            cb = math.cos(b)
            b_abs = abs((b + math.pi) % (2.0 * math.pi) - math.pi)
            fj = min(b_abs / dbeta, n_b - 1.0)
            j0 = min(int(fj), n_b - 2)
            tj = fj - j0
            weight = hs[k] * hs[k] * spread[j] / total
            for i in range(x.shape[0]):
                w = wp[k] * x[i]
                we = abs(w - w * w * speed[k] * cb / g)
                fi = min(max((w - w0) / dw_exc, 0.0), n_w - 1.0)
                i0 = min(int(fi), n_w - 2)
                ti = fi - i0
                f_sq = (1.0 - tj) * ((1.0 - ti) * exc[j0, i0] + ti * exc[j0, i0 + 1]) + tj * (
                    (1.0 - ti) * exc[j0 + 1, i0] + ti * exc[j0 + 1, i0 + 1]
                )
                fr = min(we / dw_rad, n_r - 1.0)
                r0 = min(int(fr), n_r - 2)
                tr = fr - r0
                a44 = (1.0 - tr) * a_rad[r0] + tr * a_rad[r0 + 1]
                b44 = (1.0 - tr) * b_rad[r0] + tr * b_rad[r0 + 1]
                re = c44[k] - we * we * (inertia + a44)
                im = we * (b44 + b_v[k])
                r = f_sq / (re * re + im * im) * energy[i] * weight
                acc0 += r
                acc2 += r * we * we
        m0[k] = acc0
        m2[k] = acc2


def roll_exceedance_probability(
    m0: NDArray, m2: NDArray, critical_roll: float, exposure: float
) -> NDArray:
    """Eq. (3): probability [-] that |φ| exceeds ``critical_roll`` [rad] at least once in
    ``exposure`` [s], from the roll variance m₀ [rad²] and m₂ [rad²/s²]."""
    m0 = np.maximum(m0, 1e-30)
    tz = 2.0 * math.pi * np.sqrt(m0 / np.maximum(m2, 1e-30))
    rate = np.exp(-(critical_roll**2) / (2.0 * m0)) / tz
    return -np.expm1(-exposure * rate)


_RESPONSES: dict[str, RollResponse] = {}


def response_of(ship: str) -> RollResponse:
    """The ship's :class:`RollResponse`, built once per process."""
    if ship not in _RESPONSES:
        _RESPONSES[ship] = RollResponse.of_ship(ship)
    return _RESPONSES[ship]
