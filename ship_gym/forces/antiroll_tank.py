"""A passive U-tube anti-roll tank with its own ODE states (gravity-coupled U-tube oscillator).

Two wing reservoirs of athwartships width b_r and fore-and-aft length x_t [m], their centres
w [m] apart, filled to a mean height h_r [m], are joined by a duct of height h_d [m] (and the
same length x_t). The tank's coordinate is the rise η [m] of the liquid in the starboard
reservoir (the port one falls by η). From the liquid's kinetic and potential energy
(Lloyd 1989, ch. 13; Holden, Perez & Fossen 2011, the linear U-tube model), with
A_r = b_r x_t and A_d = h_d x_t,

    m_t η̈ + b_t η̇ + k_t η = ρ_t g A_r w sin φ,                                    (1)

    m_t = ρ_t A_r (2 h_r + A_r w / A_d),   k_t = 2 ρ_t g A_r,   b_t = 2 ζ_t √(k_t m_t),

so that the tank's natural frequency is the classical ω_t² = 2 g / (2 h_r + b_r w / h_d), and
the liquid moved to starboard heels the ship by the roll moment about O (body axes, z down)

    K = ρ_t g A_r w η.                                                             (2)

At rest (1) gives η = w φ / 2 and (2) the free-surface moment ρ_t g A_r w² φ / 2 (the tank's
loss of GM); tuned near the roll natural frequency, the liquid lags the roll by about 90° and
(2) damps it — the passive tank of Lloyd's chapter 13. The roll-acceleration coupling of
Lloyd's full model (the duct's and reservoirs' height above the roll axis) is neglected: the
model keeps the gravity coupling that dominates for a tank near the roll axis. The liquid's
weight at rest is part of the ship's loading. The two states are (η, η̇) per ship.

References
----------
Lloyd, A. R. J. M. (1989). Seakeeping: Ship Behaviour in Rough Weather. Ellis Horwood, ch. 13.
Holden, C., Perez, T. & Fossen, T. I. (2011). A Lagrangian approach to nonlinear modeling of
anti-roll tanks. Ocean Engineering 38, 341–359.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb

from ship_gym.conventions import GRAVITY, RHO_SEAWATER
from ship_gym.forces.base import RowKernelModel, RowLayout

__all__ = ["TankRecord", "UTubeTank", "u_tube_tank_row"]


class TankRecord(NamedTuple):
    """:func:`u_tube_tank_row`'s parameters: m_t [kg/m·m], b_t, k_t, and the coupling
    ρ_t g A_r w [N] (the roll moment per metre of η and the forcing per unit sin φ)."""

    mass: float
    damping: float
    stiffness: float
    coupling: float


@nb.njit(cache=True, nogil=True)
def u_tube_tank_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: eq. (1) for ż = (η̇, η̈) and the roll moment (2) added to ``out``."""
    eta_t = z[0]
    rate = z[1]
    zdot[0] = rate
    forcing = rec.coupling * math.sin(q[3])
    zdot[1] = (forcing - rec.damping * rate - rec.stiffness * eta_t) / rec.mass
    out[3] += rec.coupling * eta_t


class UTubeTank(RowKernelModel):
    """A passive U-tube anti-roll tank (module docstring), two ODE states per ship.

    Parameters
    ----------
    reservoir_width : float
        b_r [m], athwartships width of each reservoir.
    length : float
        x_t [m], fore-and-aft length of the tank.
    separation : float
        w [m], distance between the reservoirs' centres.
    liquid_height : float
        h_r [m], mean liquid height in the reservoirs.
    duct_height : float
        h_d [m], height of the connecting duct.
    damping_ratio : float
        ζ_t [-] of the liquid's flow (duct losses, linearised).
    rho : float
        ρ_t [kg/m³] of the liquid.
    """

    name = "antiroll_tank"
    n_states = 2
    kernel = u_tube_tank_row

    def __init__(
        self,
        reservoir_width: float,
        length: float,
        separation: float,
        liquid_height: float,
        duct_height: float,
        damping_ratio: float = 0.3,
        *,
        rho: float = RHO_SEAWATER,
        g: float = GRAVITY,
    ) -> None:
        for name, value in (
            ("reservoir_width", reservoir_width), ("length", length), ("separation", separation),
            ("liquid_height", liquid_height), ("duct_height", duct_height), ("rho", rho),
        ):  # fmt: skip
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"{name} must be positive [m, kg/m³], got {value!r}")
        if not (math.isfinite(damping_ratio) and damping_ratio >= 0.0):
            raise ValueError(f"damping_ratio must be >= 0, got {damping_ratio!r}")
        a_r = reservoir_width * length
        a_d = duct_height * length
        self.mass = rho * a_r * (2.0 * liquid_height + a_r * separation / a_d)
        """m_t of eq. (1) [kg]."""
        self.stiffness = 2.0 * rho * g * a_r
        """k_t of eq. (1) [N/m]."""
        self.damping = 2.0 * damping_ratio * math.sqrt(self.stiffness * self.mass)
        """b_t of eq. (1) [N·s/m]."""
        self.coupling = rho * g * a_r * separation
        """ρ_t g A_r w [N]."""
        self.liquid_mass = rho * (2.0 * a_r * liquid_height + a_d * separation)
        """Mass of the liquid [kg] (part of the loading)."""

    @property
    def natural_frequency(self) -> float:
        """ω_t = √(k_t/m_t) = √(2 g / (2 h_r + b_r w / h_d)) [rad/s]."""
        return math.sqrt(self.stiffness / self.mass)

    @classmethod
    def tuned(
        cls,
        omega: float,
        reservoir_width: float,
        length: float,
        separation: float,
        liquid_height: float,
        damping_ratio: float = 0.3,
        **kwargs: float,
    ) -> UTubeTank:
        """The tank whose duct height puts ω_t at ``omega`` [rad/s] (e.g. the roll natural
        frequency): h_d = b_r w / (2 g/ω² − 2 h_r)."""
        g = kwargs.get("g", GRAVITY)
        length_eff = 2.0 * g / omega**2 - 2.0 * liquid_height
        if length_eff <= 0.0:
            raise ValueError(f"no duct tunes the tank to {omega!r} rad/s with this liquid height")
        h_d = reservoir_width * separation / length_eff
        return cls(reservoir_width, length, separation, liquid_height, h_d, damping_ratio, **kwargs)

    def record(self, layout: RowLayout) -> TankRecord:
        return TankRecord(self.mass, self.damping, self.stiffness, self.coupling)
