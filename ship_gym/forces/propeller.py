"""Propeller: Wageningen B-series open-water curves, hull–propeller interaction, self-propulsion.

Open water
----------
Oosterveld & van Oossanen (1975) fitted the open-water tests of the Wageningen B-screw series
(Reynolds number 2·10⁶) with polynomials

    K_T = Σᵢ Cᵢ J^sᵢ (P/D)^tᵢ (A_E/A_0)^uᵢ Z^vᵢ   (39 terms),
    K_Q = Σᵢ Cᵢ J^sᵢ (P/D)^tᵢ (A_E/A_0)^uᵢ Z^vᵢ   (47 terms),                           (1)

with J = V_A/(nD), thrust T = ρ n² D⁴ K_T, torque Q = ρ n² D⁵ K_Q and open-water efficiency
η₀ = J K_T / (2π K_Q). Their stated range: 2 ≤ Z ≤ 7, 0.30 ≤ A_E/A_0 ≤ 1.05,
0.5 ≤ P/D ≤ 1.4. For a given propeller (Z, A_E/A_0, P/D) the sums collapse to cubics in J,
evaluated by Horner's rule (:class:`WageningenB`). The Reynolds-number correction of the paper
(ΔK_T, ΔK_Q for Rn > 2·10⁶) is not applied.

Outside the first quadrant (documented approximations, chosen to be continuous and monotone
rather than accurate; the B-series polynomials themselves hold only for 0 ≤ J ≤ J₀, J₀ the
zero-thrust advance ratio):

* **Bollard** (J = 0) is the polynomial's value at J = 0.
* **Negative J** (n > 0 while the inflow is reversed, e.g. going astern with the propeller
  turning ahead): K_T, K_Q continue linearly with the polynomial's slope at J = 0.
* **J > J₀** (windmilling / over-running, e.g. the shaft slowed down at speed): K_T, K_Q
  continue linearly from J₀ with the polynomial's slopes there — negative thrust (drag) and,
  further on, negative torque (turbine). As n → 0 the thrust T = ρ D³ n K_T'(J₀)(V_A − J₀ n D)
  tends to 0: a stopped (n = 0) propeller produces neither thrust nor drag (locked- or
  free-wheeling-propeller drag is not modelled).
* **Astern** (n < 0): the mirror image of the ahead curves, T(n, V_A) = −κ T(|n|, −V_A),
  Q(n, V_A) = −Q(|n|, −V_A), with κ = ``astern_thrust_factor`` (default 0.7) standing for the
  lower efficiency of a fixed-pitch propeller running astern. The true four-quadrant
  characteristics of the B-series (van Lammeren et al. 1969) are not used.

Behind the hull
---------------
With the effective wake fraction w and thrust deduction factor t (Harvald 1983; Holtrop &
Mennen 1982, Holtrop 1984):

    V_A = (1 − w) u,   X = (1 − t) T,   Q_B = Q / η_R,                                   (2)

η_R the relative rotative efficiency. The force acts at the propeller's position
r_P = (x_P, y_P, z_P) in the body frame, so its moment about O is r_P × (X, 0, 0) =
(0, z_P X, −y_P X): a propeller below the waterline (z_P > 0) pushing ahead trims the ship by
the bow up (positive pitch moment). Optionally (``roll_reaction=True``) the hull takes the shaft
torque's reaction K = −h Q_B about x, h = +1 for a right-handed propeller (turning clockwise
seen from astern when going ahead), which heels the ship to port at ahead rpm.

w, t, η_R come from Holtrop's (1984) single-screw regressions (or Holtrop & Mennen's 1982
twin-screw ones) at the design speed, or are given; they are then held constant. The changes
of w in waves, with drift or in turns (e.g. the MMG w_P(β_P) correction) are not modelled.

Single-screw (Holtrop 1984), with C_V = (1 + k) C_F + C_A the viscous resistance coefficient:

    w = c9 c20 C_V (L/T_A) [0.050776 + 0.93405 c11 C_V / (1 − C_P1)]
        + 0.27915 c20 √(B / (L (1 − C_P1))) + c19 c20,
    t = 0.25014 (B/L)^0.28956 (√(BT)/D)^0.2624 / (1 − C_P + 0.0225 lcb)^0.01762 + 0.0015 C_stern,
    η_R = 0.9922 − 0.05908 A_E/A_0 + 0.07424 (C_P − 0.0225 lcb),                         (3)

c8 = B S/(L D T_A) (B/T_A < 5) or S (7 B/T_A − 25)/(L D (B/T_A − 3)) (≥ 5);
c9 = c8 (c8 < 28) or 32 − 16/(c8 − 24); c11 = T_A/D (T_A/D < 2) or 0.0833333 (T_A/D)³ + 1.33333;
c19 = 0.12997/(0.95 − C_B) − 0.11056/(0.95 − C_P) (C_P < 0.7) or
0.18567/(1.3571 − C_M) − 0.71276 + 0.38648 C_P; c20 = 1 + 0.015 C_stern;
C_P1 = 1.45 C_P − 0.315 − 0.0225 lcb. Twin-screw (Holtrop & Mennen 1982):
w = 0.3095 C_B + 10 C_V C_B − 0.23 D/√(BT), t = 0.325 C_B − 0.1885 D/√(BT),
η_R = 0.9737 + 0.111 (C_P − 0.0225 lcb) − 0.06325 P/D.

Self-propulsion
---------------
The steady speed U for a shaft speed n (and the shaft speed for a wanted speed — the
"commanded speed" of the environments) satisfy the surge balance in calm water

    (1 − t) T(n, (1 − w) U) = R_T(U),                                                   (4)

solved by Brent's method (:meth:`Propeller.shaft_speed_for`, :meth:`Propeller.steady_speed_for`,
:meth:`Propeller.self_propulsion`). :func:`design_propeller_for` picks a B-series propeller for
a hull: diameter (default 0.7 T), blade-area ratio from Keller's cavitation criterion
A_E/A_0 = (1.3 + 0.3 Z) T / ((p₀ − p_v) D²) + K (K = 0.2 single screw, 0.1 twin screw; p₀ the
static pressure at the shaft), and the pitch ratio of the highest open-water efficiency at the
design point (or the one that gives a wanted rpm).

Shaft-speed command
-------------------
:class:`Propeller` reads the shaft speed n in **revolutions per second** [rev/s = Hz] from
``ctx.commands["shaft_speed"]`` (:data:`SHAFT_SPEED_COMMAND`); 1 rev/s = 60 rpm. Without that
command it uses its ``shaft_speed`` attribute, and fails if that is None.

References
----------
Oosterveld, M.W.C. & van Oossanen, P. (1975). Further computer-analyzed data of the Wageningen
B-screw series. International Shipbuilding Progress 22(251), 251–262.
Bernitsas, M.M., Ray, D. & Kinley, P. (1981). K_T, K_Q and efficiency curves for the Wageningen
B-series propellers. Report 237, Dept. of Naval Architecture and Marine Engineering, University
of Michigan.
Holtrop, J. & Mennen, G.G.J. (1982). An approximate power prediction method. International
Shipbuilding Progress 29(335), 166–170.
Holtrop, J. (1984). A statistical re-analysis of resistance and propulsion data. International
Shipbuilding Progress 31(363), 272–276.
Harvald, S.A. (1983). Resistance and Propulsion of Ships. Wiley.
Keller, J. auf'm (1966). Enige aspecten bij het ontwerpen van scheepsschroeven. Schip en Werf 24.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal, NamedTuple

import numba as nb
import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq, minimize_scalar

from ship_gym.conventions import RHO_SEAWATER, SURGE
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.forces.resistance import CalmWaterResistance, HoltropMennen, ResistanceParticulars
from ship_gym.hull.hull import Hull
from ship_gym.typing import FloatArray

SHAFT_SPEED_COMMAND: str = "shaft_speed"
"""Key of the shaft-speed command in ``ForceContext.commands``; value in rev/s."""

ATMOSPHERIC_PRESSURE: float = 101_325.0
"""Standard atmospheric pressure [Pa]."""

VAPOUR_PRESSURE: float = 1_700.0
"""Vapour pressure of sea water at 15 °C [Pa] (ITTC 2011 fresh/sea water tables: ≈ 1.7 kPa)."""

# Oosterveld & van Oossanen (1975), Rn = 2e6: (C, s, t, u, v) for C J^s (P/D)^t (AE/A0)^u Z^v
KT_TERMS: tuple[tuple[float, int, int, int, int], ...] = (
    (+0.00880496, 0, 0, 0, 0),
    (-0.204554, 1, 0, 0, 0),
    (+0.166351, 0, 1, 0, 0),
    (+0.158114, 0, 2, 0, 0),
    (-0.147581, 2, 0, 1, 0),
    (-0.481497, 1, 1, 1, 0),
    (+0.415437, 0, 2, 1, 0),
    (+0.0144043, 0, 0, 0, 1),
    (-0.0530054, 2, 0, 0, 1),
    (+0.0143481, 0, 1, 0, 1),
    (+0.0606826, 1, 1, 0, 1),
    (-0.0125894, 0, 0, 1, 1),
    (+0.0109689, 1, 0, 1, 1),
    (-0.133698, 0, 3, 0, 0),
    (+0.00638407, 0, 6, 0, 0),
    (-0.00132718, 2, 6, 0, 0),
    (+0.168496, 3, 0, 1, 0),
    (-0.0507214, 0, 0, 2, 0),
    (+0.0854559, 2, 0, 2, 0),
    (-0.0504475, 3, 0, 2, 0),
    (+0.010465, 1, 6, 2, 0),
    (-0.00648272, 2, 6, 2, 0),
    (-0.00841728, 0, 3, 0, 1),
    (+0.0168424, 1, 3, 0, 1),
    (-0.00102296, 3, 3, 0, 1),
    (-0.0317791, 0, 3, 1, 1),
    (+0.018604, 1, 0, 2, 1),
    (-0.00410798, 0, 2, 2, 1),
    (-0.000606848, 0, 0, 0, 2),
    (-0.0049819, 1, 0, 0, 2),
    (+0.0025983, 2, 0, 0, 2),
    (-0.000560528, 3, 0, 0, 2),
    (-0.00163652, 1, 2, 0, 2),
    (-0.000328787, 1, 6, 0, 2),
    (+0.000116502, 2, 6, 0, 2),
    (+0.000690904, 0, 0, 1, 2),
    (+0.00421749, 0, 3, 1, 2),
    (+0.0000565229, 3, 6, 1, 2),
    (-0.00146564, 0, 3, 2, 2),
)
"""The 39 K_T terms (C, s, t, u, v) of Oosterveld & van Oossanen (1975)."""

KQ_TERMS: tuple[tuple[float, int, int, int, int], ...] = (
    (+0.00379368, 0, 0, 0, 0),
    (+0.00886523, 2, 0, 0, 0),
    (-0.032241, 1, 1, 0, 0),
    (+0.00344778, 0, 2, 0, 0),
    (-0.0408811, 0, 1, 1, 0),
    (-0.108009, 1, 1, 1, 0),
    (-0.0885381, 2, 1, 1, 0),
    (+0.188561, 0, 2, 1, 0),
    (-0.00370871, 1, 0, 0, 1),
    (+0.00513696, 0, 1, 0, 1),
    (+0.0209449, 1, 1, 0, 1),
    (+0.00474319, 2, 1, 0, 1),
    (-0.00723408, 2, 0, 1, 1),
    (+0.00438388, 1, 1, 1, 1),
    (-0.0269403, 0, 2, 1, 1),
    (+0.0558082, 3, 0, 1, 0),
    (+0.0161886, 0, 3, 1, 0),
    (+0.00318086, 1, 3, 1, 0),
    (+0.015896, 0, 0, 2, 0),
    (+0.0471729, 1, 0, 2, 0),
    (+0.0196283, 3, 0, 2, 0),
    (-0.0502782, 0, 1, 2, 0),
    (-0.030055, 3, 1, 2, 0),
    (+0.0417122, 2, 2, 2, 0),
    (-0.0397722, 0, 3, 2, 0),
    (-0.00350024, 0, 6, 2, 0),
    (-0.0106854, 3, 0, 0, 1),
    (+0.00110903, 3, 3, 0, 1),
    (-0.000313912, 0, 6, 0, 1),
    (+0.0035985, 3, 0, 1, 1),
    (-0.00142121, 0, 6, 1, 1),
    (-0.00383637, 1, 0, 2, 1),
    (+0.0126803, 0, 2, 2, 1),
    (-0.00318278, 2, 3, 2, 1),
    (+0.00334268, 0, 6, 2, 1),
    (-0.00183491, 1, 1, 0, 2),
    (+0.000112451, 3, 2, 0, 2),
    (-0.0000297228, 3, 6, 0, 2),
    (+0.000269551, 1, 0, 1, 2),
    (+0.00083265, 2, 0, 1, 2),
    (+0.00155334, 0, 2, 1, 2),
    (+0.000302683, 0, 6, 1, 2),
    (-0.0001843, 0, 0, 2, 2),
    (-0.000425399, 0, 3, 2, 2),
    (+0.0000869243, 3, 3, 2, 2),
    (-0.0004659, 0, 6, 2, 2),
    (+0.0000554194, 1, 6, 2, 2),
)
"""The 47 K_Q terms (C, s, t, u, v) of Oosterveld & van Oossanen (1975)."""

B_SERIES_RANGE: dict[str, tuple[float, float]] = {
    "z_blades": (2, 7),
    "ae_a0": (0.30, 1.05),
    "p_d": (0.5, 1.4),
}
"""Range of the polynomials stated by Oosterveld & van Oossanen (1975)."""

Handedness = Literal["right", "left"]


def _positive(name: str, value: float, unit: str) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be a positive finite value [{unit}]; got {value!r}")
    return v


def _fraction(name: str, value: float, low: float = -0.5, high: float = 0.95) -> float:
    v = float(value)
    if not (math.isfinite(v) and low <= v <= high):
        raise ValueError(f"{name} must be a finite number in [{low}, {high}] [-]; got {value!r}")
    return v


def _horner(coeffs: tuple[float, float, float, float], j: Any) -> Any:
    """a₀ + a₁ j + a₂ j² + a₃ j³ for a float or an array j."""
    return coeffs[0] + j * (coeffs[1] + j * (coeffs[2] + j * coeffs[3]))


# ------------------------------------------------------------------------------ open water
class WageningenB:
    """Open-water curves K_T(J), K_Q(J) of a Wageningen B-series propeller (eq. 1, Rn = 2·10⁶).

    Parameters
    ----------
    z_blades : int
        Number of blades Z (2–7).
    ae_a0 : float
        Expanded blade-area ratio A_E/A_0 [-] (0.30–1.05).
    p_d : float
        Pitch–diameter ratio P/D [-] (0.5–1.4).
    allow_extrapolation : bool, optional
        Accept A_E/A_0 and P/D outside the series' range (the polynomials are then
        extrapolated); Z must stay an integer from 2 to 7 in any case.

    Attributes
    ----------
    kt_coefficients, kq_coefficients : tuple of float
        (a₀, a₁, a₂, a₃) of K_T = Σ aₛ Jˢ and K_Q = Σ aₛ Jˢ for this propeller.
    j_zero_thrust : float
        J₀ with K_T(J₀) = 0 (the first sign change for J > 0).
    """

    def __init__(
        self, z_blades: int, ae_a0: float, p_d: float, *, allow_extrapolation: bool = False
    ) -> None:
        if isinstance(z_blades, bool) or not float(z_blades).is_integer():
            raise ValueError(f"z_blades must be an integer number of blades; got {z_blades!r}")
        z = int(z_blades)
        if not 2 <= z <= 7:
            raise ValueError(f"z_blades must be from 2 to 7 (B-series range); got {z_blades!r}")
        ae = _positive("ae_a0", ae_a0, "-")
        pd = _positive("p_d", p_d, "-")
        if not allow_extrapolation:
            for name, value in (("ae_a0", ae), ("p_d", pd)):
                lo, hi = B_SERIES_RANGE[name]
                if not lo <= value <= hi:
                    raise ValueError(
                        f"{name} must lie in [{lo}, {hi}] (Wageningen B-series range); got "
                        f"{value!r} (pass allow_extrapolation=True to extrapolate)"
                    )
        self.z_blades, self.ae_a0, self.p_d = z, ae, pd
        self.kt_coefficients = self._collapse(KT_TERMS)
        self.kq_coefficients = self._collapse(KQ_TERMS)
        self.j_zero_thrust = self._zero_thrust()

    def _collapse(self, terms) -> tuple[float, float, float, float]:
        a = [0.0, 0.0, 0.0, 0.0]
        for c, s, t, u, v in terms:
            a[s] += c * self.p_d**t * self.ae_a0**u * float(self.z_blades) ** v
        return (a[0], a[1], a[2], a[3])

    def _zero_thrust(self) -> float:
        a0, a1, a2, a3 = self.kt_coefficients
        if a0 <= 0.0:
            raise ValueError(
                f"K_T(0) = {a0:.4g} <= 0 for Z={self.z_blades}, A_E/A_0={self.ae_a0}, "
                f"P/D={self.p_d}: no thrust at the bollard"
            )
        roots = np.roots([a3, a2, a1, a0])
        real = sorted(float(r.real) for r in roots if abs(r.imag) < 1e-9 and 0.0 < r.real < 5.0)
        for r in real:  # first crossing from K_T > 0 to K_T < 0
            if _horner(self.kt_coefficients, r + 1e-6) < 0.0:
                return float(brentq(lambda j: _horner(self.kt_coefficients, j), 0.0, r + 1e-6))
        raise ValueError(
            f"K_T(J) has no zero crossing in (0, 5) for Z={self.z_blades}, "
            f"A_E/A_0={self.ae_a0}, P/D={self.p_d}"
        )

    def __repr__(self) -> str:
        return (
            f"WageningenB(z_blades={self.z_blades}, ae_a0={self.ae_a0:.4g}, p_d={self.p_d:.4g}, "
            f"J0={self.j_zero_thrust:.4f})"
        )

    @property
    def name(self) -> str:
        """Series designation, e.g. ``"B4-70"``."""
        return f"B{self.z_blades}-{round(100 * self.ae_a0):d}"

    def kt(self, j: ArrayLike) -> np.ndarray | float:
        """Thrust coefficient K_T(J) [-] of the polynomial (valid for 0 ≤ J ≤ J₀)."""
        jj = np.asarray(j)
        if jj.ndim == 0:
            return _horner(self.kt_coefficients, float(jj))
        return _horner(self.kt_coefficients, np.asarray(jj, dtype=float))

    def kq(self, j: ArrayLike) -> np.ndarray | float:
        """Torque coefficient K_Q(J) [-] of the polynomial (valid for 0 ≤ J ≤ J₀)."""
        jj = np.asarray(j)
        if jj.ndim == 0:
            return _horner(self.kq_coefficients, float(jj))
        return _horner(self.kq_coefficients, np.asarray(jj, dtype=float))

    def efficiency(self, j: ArrayLike) -> np.ndarray | float:
        """Open-water efficiency η₀ = J K_T / (2π K_Q) [-]."""
        arr = np.asarray(j)
        jj = float(arr) if arr.ndim == 0 else np.asarray(arr, dtype=float)
        return jj * self.kt(jj) / (2.0 * math.pi * self.kq(jj))

    def coefficients_extended(self, j: float) -> tuple[float, float]:
        """(K_T, K_Q) for any real J: the polynomial on [0, J₀], linear continuations outside.

        Parameters
        ----------
        j : float
            Advance ratio [-].
        """
        kt, kq = open_water_kt_kq(float(j), *self._kernel_coefficients)
        return float(kt), float(kq)

    @property
    def _kernel_coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        """(K_T coefficients, K_Q coefficients, J₀): the arguments of :func:`open_water_kt_kq`."""
        cached = self.__dict__.get("_kernel_cache")
        if cached is None:
            cached = (
                np.array(self.kt_coefficients, dtype=float),
                np.array(self.kq_coefficients, dtype=float),
                float(self.j_zero_thrust),
            )
            self.__dict__["_kernel_cache"] = cached
        return cached

    def advance_ratio_for_load(self, kt_over_j2: float) -> float:
        """J ∈ (0, J₀) with K_T(J) = c J², c = T/(ρ D² V_A²) > 0 [-] (the loading line)."""
        c = _positive("kt_over_j2", kt_over_j2, "-")
        return float(brentq(lambda j: self.kt(j) - c * j * j, 0.0, self.j_zero_thrust, xtol=1e-14))


# ------------------------------------------------------------------------------ records
@dataclass(frozen=True)
class PropellerOperatingPoint:
    """State of the propeller at one (u, n).

    Attributes
    ----------
    shaft_speed : float
        n [rev/s].
    advance_speed : float
        V_A = (1 − w) u [m/s].
    advance_ratio : float
        J = V_A / (|n| D) [-] (inf at n = 0).
    kt, kq : float
        Thrust and torque coefficients used (extended curves) [-].
    thrust : float
        Open-water thrust T [N] (positive ahead).
    torque : float
        Torque absorbed behind the hull Q_B = Q/η_R [N·m] (sign of n).
    surge_force : float
        (1 − t) T [N].
    delivered_power : float
        P_D = 2π n Q_B [W].
    """

    shaft_speed: float
    advance_speed: float
    advance_ratio: float
    kt: float
    kq: float
    thrust: float
    torque: float
    surge_force: float
    delivered_power: float


@dataclass(frozen=True)
class SelfPropulsionPoint:
    """Calm-water self-propulsion point (1 − t) T = R_T(U) (eq. 4).

    Attributes
    ----------
    speed : float
        U [m/s].
    shaft_speed : float
        n [rev/s]; ``rpm`` = 60 n.
    advance_ratio, kt, kq : float
        J, K_T, K_Q at the point [-].
    thrust : float
        T [N].
    torque : float
        Q_B behind the hull [N·m].
    resistance : float
        R_T(U) [N].
    effective_power, delivered_power : float
        P_E = R_T U, P_D = 2π n Q_B [W].
    eta_open_water, eta_hull, eta_relative_rotative, eta_propulsive : float
        η₀, η_H = (1 − t)/(1 − w), η_R, η_D = P_E/P_D [-].
    """

    speed: float
    shaft_speed: float
    advance_ratio: float
    kt: float
    kq: float
    thrust: float
    torque: float
    resistance: float
    effective_power: float
    delivered_power: float
    eta_open_water: float
    eta_hull: float
    eta_relative_rotative: float
    eta_propulsive: float

    @property
    def rpm(self) -> float:
        """Shaft speed [1/min]."""
        return 60.0 * self.shaft_speed


@dataclass(frozen=True)
class PropulsionFactors:
    """Hull–propeller interaction factors.

    Attributes
    ----------
    wake_fraction : float
        Effective (Taylor) wake fraction w [-].
    thrust_deduction : float
        Thrust deduction factor t [-].
    relative_rotative_efficiency : float
        η_R [-].
    source : str
        Where they come from.
    """

    wake_fraction: float
    thrust_deduction: float
    relative_rotative_efficiency: float
    source: str


def holtrop_propulsion_factors(
    particulars: ResistanceParticulars,
    *,
    diameter: float,
    viscous_resistance_coefficient: float,
    ae_a0: float,
    p_d: float = 1.0,
    twin_screw: bool = False,
) -> PropulsionFactors:
    """w, t, η_R from Holtrop (1984) single-screw or Holtrop & Mennen (1982) twin-screw (eq. 3).

    Parameters
    ----------
    particulars : ResistanceParticulars
        Hull form (L, B, T_A, C_B, C_P, C_M, lcb, S, C_stern).
    diameter : float
        Propeller diameter D [m].
    viscous_resistance_coefficient : float
        C_V = (1 + k) C_F + C_A at the speed of interest [-]
        (:meth:`ship_gym.forces.resistance.HoltropMennen.viscous_resistance_coefficient`).
    ae_a0 : float
        Blade-area ratio [-] (for η_R).
    p_d : float, optional
        Pitch ratio [-] (twin-screw η_R only).
    twin_screw : bool, optional
        Use the twin-screw formulas.
    """
    if not isinstance(particulars, ResistanceParticulars):
        raise ValueError(
            f"particulars must be a ResistanceParticulars; got {type(particulars).__name__}"
        )
    d = _positive("diameter", diameter, "m")
    cv = _positive("viscous_resistance_coefficient", viscous_resistance_coefficient, "-")
    ae = _positive("ae_a0", ae_a0, "-")
    p = particulars
    L, B, T, ta = p.length, p.beam, p.draught, p.draught_aft
    cb, cp, cm, lcb = p.block_coefficient, p.prismatic_coefficient, p.midship_coefficient, p.lcb
    if twin_screw:
        w = 0.3095 * cb + 10.0 * cv * cb - 0.23 * d / math.sqrt(B * T)
        t = 0.325 * cb - 0.1885 * d / math.sqrt(B * T)
        eta_r = 0.9737 + 0.111 * (cp - 0.0225 * lcb) - 0.06325 * p_d
        return PropulsionFactors(w, t, eta_r, "Holtrop & Mennen (1982), twin screw")
    s = p.hull_wetted_area
    b_ta = B / ta
    c8 = B * s / (L * d * ta) if b_ta < 5.0 else s * (7.0 * b_ta - 25.0) / (L * d * (b_ta - 3.0))
    c9 = c8 if c8 < 28.0 else 32.0 - 16.0 / (c8 - 24.0)
    ta_d = ta / d
    c11 = ta_d if ta_d < 2.0 else 0.0833333 * ta_d**3 + 1.33333
    if cp < 0.7:
        c19 = 0.12997 / (0.95 - cb) - 0.11056 / (0.95 - cp)
    else:
        c19 = 0.18567 / (1.3571 - cm) - 0.71276 + 0.38648 * cp
    c20 = 1.0 + 0.015 * p.stern_shape
    cp1 = 1.45 * cp - 0.315 - 0.0225 * lcb
    w = (
        c9 * c20 * cv * (L / ta) * (0.050776 + 0.93405 * c11 * cv / (1.0 - cp1))
        + 0.27915 * c20 * math.sqrt(B / (L * (1.0 - cp1)))
        + c19 * c20
    )
    t = (
        0.25014
        * (B / L) ** 0.28956
        * (math.sqrt(B * T) / d) ** 0.2624
        / (1.0 - cp + 0.0225 * lcb) ** 0.01762
        + 0.0015 * p.stern_shape
    )
    eta_r = 0.9922 - 0.05908 * ae + 0.07424 * (cp - 0.0225 * lcb)
    return PropulsionFactors(w, t, eta_r, "Holtrop (1984), single screw")


@dataclass(frozen=True)
class PropellerDesign:
    """Record of :func:`design_propeller_for`: inputs, choices and the design point.

    Attributes
    ----------
    speed : float
        Design speed U [m/s].
    froude_number : float
        U / √(g Lpp) [-].
    diameter : float
        D [m].
    z_blades : int
        Z.
    ae_a0, p_d : float
        Blade-area and pitch ratios [-].
    ae_a0_source, p_d_source : str
        How they were chosen.
    factors : PropulsionFactors
        w, t, η_R used.
    point : SelfPropulsionPoint
        The design point.
    """

    speed: float
    froude_number: float
    diameter: float
    z_blades: int
    ae_a0: float
    p_d: float
    ae_a0_source: str
    p_d_source: str
    factors: PropulsionFactors
    point: SelfPropulsionPoint


# ------------------------------------------------------------------------------ force model

# the arguments of propeller_force after (u, n): K_T and K_Q coefficients, J₀, D, ρD⁴, 1 − w,
# 1 − t, η_R, the astern factor, z_P, y_P and the sign of the roll reaction
PropellerKernelParameters = tuple[
    FloatArray, FloatArray, float, float, float, float, float, float, float, float, float, float
]


class Propeller(ForceModel):
    """A propeller behind the hull, driven by a shaft-speed command (eq. 2).

    Force (body axes, about O): (X, 0, 0, K, z_P X, −y_P X) with X = (1 − t) T(n, (1 − w) u)
    and K = −h Q_B if ``roll_reaction`` else 0. No states.

    Parameters
    ----------
    open_water : WageningenB
        Open-water curves.
    diameter : float
        D [m].
    wake_fraction : float
        w [-] (−0.5 … 0.95).
    thrust_deduction : float
        t [-] (−0.5 … 0.95).
    position : array_like
        (x_P, y_P, z_P) of the propeller disc centre in the body frame [m] (z down).
    relative_rotative_efficiency : float, optional
        η_R [-] (default 1).
    rho : float, optional
        Water density [kg/m³].
    shaft_speed : float, optional
        n [rev/s] used when ``ctx.commands`` has no ``"shaft_speed"``; None (default): the
        command is required.
    roll_reaction : bool, optional
        Apply the shaft torque's reaction on the hull in roll (default False).
    handedness : {"right", "left"}, optional
        Right-handed: clockwise seen from astern when going ahead.
    astern_thrust_factor : float, optional
        κ of the astern approximation (default 0.7).
    resistance : CalmWaterResistance, optional
        The calm-water resistance used by the self-propulsion helpers.
    design : PropellerDesign, optional
        Record of the design (set by :func:`design_propeller_for`).
    name : str, optional
        Key in the force breakdown (default ``"propeller"``).
    """

    def __init__(
        self,
        open_water: WageningenB,
        diameter: float,
        *,
        wake_fraction: float,
        thrust_deduction: float,
        position: ArrayLike,
        relative_rotative_efficiency: float = 1.0,
        rho: float = RHO_SEAWATER,
        shaft_speed: float | None = None,
        roll_reaction: bool = False,
        handedness: Handedness = "right",
        astern_thrust_factor: float = 0.7,
        resistance: CalmWaterResistance | None = None,
        design: PropellerDesign | None = None,
        name: str = "propeller",
    ) -> None:
        if not isinstance(open_water, WageningenB):
            raise ValueError(f"open_water must be a WageningenB; got {type(open_water).__name__}")
        self.open_water = open_water
        self.diameter = _positive("diameter", diameter, "m")
        self.wake_fraction = _fraction("wake_fraction", wake_fraction)
        self.thrust_deduction = _fraction("thrust_deduction", thrust_deduction)
        pos = np.asarray(position, dtype=float)
        if pos.shape != (3,) or not np.all(np.isfinite(pos)):
            raise ValueError(f"position must be three finite coordinates [m]; got {position!r}")
        self.position = pos
        self.relative_rotative_efficiency = _positive(
            "relative_rotative_efficiency", relative_rotative_efficiency, "-"
        )
        if self.relative_rotative_efficiency > 1.5:
            raise ValueError(
                f"relative_rotative_efficiency must be <= 1.5; got {relative_rotative_efficiency!r}"
            )
        self.rho = _positive("rho", rho, "kg/m^3")
        if shaft_speed is not None:
            shaft_speed = float(shaft_speed)
            if not math.isfinite(shaft_speed):
                raise ValueError(f"shaft_speed must be finite [rev/s]; got {shaft_speed!r}")
        self.shaft_speed = shaft_speed
        self.roll_reaction = bool(roll_reaction)
        if handedness not in ("right", "left"):
            raise ValueError(f"handedness must be 'right' or 'left'; got {handedness!r}")
        self.handedness: Handedness = handedness
        self.astern_thrust_factor = _fraction(
            "astern_thrust_factor", astern_thrust_factor, 0.0, 1.0
        )
        if resistance is not None and not isinstance(resistance, CalmWaterResistance):
            raise ValueError(
                f"resistance must be a CalmWaterResistance; got {type(resistance).__name__}"
            )
        self.resistance = resistance
        self.design = design
        if not isinstance(name, str) or not name:
            raise ValueError(f"name must be a non-empty string; got {name!r}")
        self.name = name
        self._rho_d4 = self.rho * self.diameter**4
        self._last_inputs: tuple[float, float] | None = None
        """Operating point of the latest :meth:`evaluate` call (diagnostics)."""

    def __repr__(self) -> str:
        return (
            f"Propeller({self.open_water!r}, D={self.diameter:.4g} m, w={self.wake_fraction:.4f}, "
            f"t={self.thrust_deduction:.4f}, eta_R={self.relative_rotative_efficiency:.4f}, "
            f"position={self.position.tolist()}, name={self.name!r})"
        )

    # -- open water -------------------------------------------------------------------------
    def thrust_torque(self, shaft_speed: float, advance_speed: float) -> tuple[float, float]:
        """Open-water thrust T [N] and torque Q [N·m] at n [rev/s] and V_A [m/s], any quadrant.

        See the module notes for the approximations outside 0 ≤ J ≤ J₀ and for n < 0.
        """
        n = float(shaft_speed)
        va = float(advance_speed)
        if abs(n) < 1e-12:  # stopped shaft (and no overflow of J = V_A/(nD))
            return 0.0, 0.0
        if n < 0.0:
            t, q = self.thrust_torque(-n, -va)
            return -self.astern_thrust_factor * t, -q
        nd = n * self.diameter
        kt, kq = self.open_water.coefficients_extended(va / nd)
        return self._rho_d4 * n * n * kt, self._rho_d4 * self.diameter * n * n * kq

    def operating_point(self, u: float, shaft_speed: float) -> PropellerOperatingPoint:
        """Full state of the propeller at surge velocity u [m/s] and shaft speed n [rev/s].

        ``kt``, ``kq`` are the effective coefficients T/(ρ n² D⁴), Q/(ρ n² D⁵) (0 at n = 0).
        """
        n = float(shaft_speed)
        va = (1.0 - self.wake_fraction) * float(u)
        thrust, q_open = self.thrust_torque(n, va)
        q_b = q_open / self.relative_rotative_efficiency
        if n != 0.0:
            scale = self._rho_d4 * n * n
            j, kt, kq = (
                va / (abs(n) * self.diameter),
                thrust / scale,
                q_open / (scale * self.diameter),
            )
        else:
            j, kt, kq = math.inf, 0.0, 0.0
        return PropellerOperatingPoint(
            shaft_speed=n,
            advance_speed=va,
            advance_ratio=j,
            kt=kt,
            kq=kq,
            thrust=thrust,
            torque=q_b,
            surge_force=(1.0 - self.thrust_deduction) * thrust,
            delivered_power=2.0 * math.pi * n * q_b,
        )

    # -- force model -------------------------------------------------------------------------
    def _command(self, ctx: ForceContext) -> float:
        value = ctx.commands.get(SHAFT_SPEED_COMMAND, None)
        if value is None:
            if self.shaft_speed is None:
                raise ValueError(
                    f"no shaft speed: ctx.commands has no {SHAFT_SPEED_COMMAND!r} [rev/s] and the "
                    "propeller has no default shaft_speed"
                )
            return self.shaft_speed
        n = float(value)
        if not math.isfinite(n):
            raise ValueError(f"commands[{SHAFT_SPEED_COMMAND!r}] must be finite [rev/s]; got {n!r}")
        return n

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Force and moment (6,) about O [N, N·m]; no states.

        The operating point (J, T, Q_B, P_D …) is kept in :attr:`last_operating_point`.
        """
        u, n = float(ctx.nu[SURGE]), self._command(ctx)
        force = np.empty(6)
        thrust = propeller_force(u, n, *self.kernel_parameters(), force)
        self._last_inputs = (u, n)
        ctx.shared["propeller_thrust"] = thrust  # for the rudder's slipstream (evaluated later)
        return force, np.zeros(0)

    @property
    def last_operating_point(self) -> PropellerOperatingPoint | None:
        """The operating point (J, T, Q_B, P_D …) of the last :meth:`evaluate` (None before)."""
        if self._last_inputs is None:
            return None
        return self.operating_point(*self._last_inputs)

    def kernel_parameters(self) -> PropellerKernelParameters:
        """The arguments of :func:`propeller_force` after (u, n): open-water coefficients and
        J₀, D [m], ρD⁴ [kg·m], 1 − w, 1 − t, η_R, the astern factor, z_P, y_P [m] and the sign
        of the roll reaction (0 without it)."""
        kt, kq, j0 = self.open_water._kernel_coefficients
        roll = 0.0 if not self.roll_reaction else (-1.0 if self.handedness == "right" else 1.0)
        return (
            kt, kq, j0, float(self.diameter), float(self._rho_d4), 1.0 - self.wake_fraction,
            1.0 - self.thrust_deduction, float(self.relative_rotative_efficiency),
            float(self.astern_thrust_factor), float(self.position[2]), float(self.position[1]),
            roll,
        )  # fmt: skip

    # -- self-propulsion --------------------------------------------------------------------------
    def _resistance_model(self, resistance: CalmWaterResistance | None) -> CalmWaterResistance:
        model = resistance if resistance is not None else self.resistance
        if model is None:
            raise ValueError(
                "no resistance: pass resistance=CalmWaterResistance(...) or build the propeller "
                "with one (design_propeller_for attaches it)"
            )
        if not isinstance(model, CalmWaterResistance):
            raise ValueError(
                f"resistance must be a CalmWaterResistance; got {type(model).__name__}"
            )
        return model

    def _net_force(self, n: float, speed: float, model: CalmWaterResistance) -> float:
        thrust, _ = self.thrust_torque(n, (1.0 - self.wake_fraction) * speed)
        return (1.0 - self.thrust_deduction) * thrust - float(model.resistance(speed))

    def shaft_speed_for(self, speed: float, resistance: CalmWaterResistance | None = None) -> float:
        """Shaft speed n ≥ 0 [rev/s] that holds speed U ≥ 0 [m/s] in calm water (eq. 4)."""
        return self.self_propulsion(speed, resistance).shaft_speed

    def self_propulsion(
        self, speed: float, resistance: CalmWaterResistance | None = None
    ) -> SelfPropulsionPoint:
        """The self-propulsion point at speed U ≥ 0 [m/s] (eq. 4), by Brent's method on n."""
        model = self._resistance_model(resistance)
        u = float(speed)
        if not (math.isfinite(u) and u >= 0.0):
            raise ValueError(f"speed must be finite and >= 0 [m/s]; got {speed!r}")
        r = float(model.resistance(u))
        if u == 0.0 or r == 0.0:
            n = 0.0
        else:
            va = (1.0 - self.wake_fraction) * u
            # T(n) >= 0 and increasing for n >= V_A/(J0 D) (the zero-thrust shaft speed)
            lo = max(va, 0.0) / (self.open_water.j_zero_thrust * self.diameter)
            hi = max(2.0 * lo, 0.1)
            while self._net_force(hi, u, model) < 0.0:
                hi *= 2.0
                if hi > 1e4:
                    raise ValueError(f"no shaft speed below 1e4 rev/s holds {u!r} m/s")
            n = float(brentq(self._net_force, lo, hi, args=(u, model), xtol=1e-14, rtol=1e-15))
        return self._point(u, n, r)

    def _point(self, u: float, n: float, r: float) -> SelfPropulsionPoint:
        op = self.operating_point(u, n)
        w, t = self.wake_fraction, self.thrust_deduction
        eta0 = (
            op.advance_ratio * op.kt / (2.0 * math.pi * op.kq) if n > 0.0 and op.kq != 0.0 else 0.0
        )
        pe = r * u
        return SelfPropulsionPoint(
            speed=u,
            shaft_speed=n,
            advance_ratio=op.advance_ratio,
            kt=op.kt,
            kq=op.kq,
            thrust=op.thrust,
            torque=op.torque,
            resistance=r,
            effective_power=pe,
            delivered_power=op.delivered_power,
            eta_open_water=eta0,
            eta_hull=(1.0 - t) / (1.0 - w),
            eta_relative_rotative=self.relative_rotative_efficiency,
            eta_propulsive=pe / op.delivered_power if op.delivered_power > 0.0 else 0.0,
        )

    def steady_speed_for(
        self, shaft_speed: float, resistance: CalmWaterResistance | None = None
    ) -> float:
        """Steady calm-water speed U ≥ 0 [m/s] reached at shaft speed n ≥ 0 [rev/s] (eq. 4)."""
        model = self._resistance_model(resistance)
        n = float(shaft_speed)
        if not (math.isfinite(n) and n >= 0.0):
            raise ValueError(f"shaft_speed must be finite and >= 0 [rev/s]; got {shaft_speed!r}")
        if n == 0.0:
            return 0.0
        hi = max(1.0, n * self.diameter * self.open_water.j_zero_thrust)
        while self._net_force(n, hi, model) > 0.0:
            hi *= 2.0
            if hi > 1e3:
                raise ValueError(f"no steady speed below 1000 m/s at {n!r} rev/s")
        return float(brentq(lambda u: self._net_force(n, u, model), 0.0, hi, xtol=1e-13))


# ------------------------------------------------------------------------------ design
def keller_blade_area_ratio(
    thrust: float,
    diameter: float,
    shaft_immersion: float,
    z_blades: int,
    *,
    twin_screw: bool = False,
    rho: float = RHO_SEAWATER,
    g: float = 9.81,
) -> float:
    """Keller's minimum blade-area ratio A_E/A_0 = (1.3 + 0.3 Z) T / ((p₀ − p_v) D²) + K.

    Parameters
    ----------
    thrust : float
        T [N].
    diameter : float
        D [m].
    shaft_immersion : float
        Depth of the shaft centre below the free surface h [m]; p₀ = p_atm + ρ g h.
    z_blades : int
        Z.
    twin_screw : bool, optional
        K = 0.1 for twin screw, 0.2 for single screw.
    rho, g : float, optional
        Water density [kg/m³] and gravity [m/s²].
    """
    t = _positive("thrust", thrust, "N")
    d = _positive("diameter", diameter, "m")
    h = float(shaft_immersion)
    if not (math.isfinite(h) and h >= 0.0):
        raise ValueError(f"shaft_immersion must be finite and >= 0 [m]; got {shaft_immersion!r}")
    p0 = ATMOSPHERIC_PRESSURE + rho * g * h
    k = 0.1 if twin_screw else 0.2
    return (1.3 + 0.3 * int(z_blades)) * t / ((p0 - VAPOUR_PRESSURE) * d * d) + k


def service_speed(hull: Hull, froude: float = 0.25) -> float:
    """Speed U = Fn √(g Lpp) [m/s] of a hull at a Froude number (default 0.25, the S175's)."""
    if not isinstance(hull, Hull):
        raise ValueError(f"hull must be a Hull; got {type(hull).__name__}")
    fn = _positive("froude", froude, "-")
    return fn * math.sqrt(hull.g * hull.particulars.lpp)


def design_propeller_for(
    hull: Hull,
    speed: float | None = None,
    *,
    resistance: CalmWaterResistance | None = None,
    diameter: float | None = None,
    z_blades: int = 4,
    ae_a0: float | None = None,
    p_d: float | None = None,
    rpm: float | None = None,
    wake_fraction: float | None = None,
    thrust_deduction: float | None = None,
    relative_rotative_efficiency: float | None = None,
    position: ArrayLike | None = None,
    twin_screw: bool = False,
    **propeller_kwargs,
) -> Propeller:
    """A Wageningen B-series propeller that drives a hull at a design speed.

    Steps: resistance R_T(U) (default Holtrop–Mennen 1984 of the hull); w, t, η_R (default
    Holtrop's regressions at U, eq. 3); required thrust T = R_T/(1 − t); A_E/A_0 (default Keller's
    criterion, clipped to the series range, not below 0.40); P/D of the best open-water
    efficiency on the loading line K_T = T/(ρ D² V_A²) J² over the series' P/D range, or the one
    that gives ``rpm`` at U; finally the self-propulsion point. Keller's value is rounded up to
    the next 0.05.

    Parameters
    ----------
    hull : Hull
        The ship.
    speed : float, optional
        Design speed U [m/s]; default Fn = 0.25 on Lpp (:func:`service_speed`; S175: 10.36 m/s).
    resistance : CalmWaterResistance, optional
        Calm-water resistance (attached to the propeller); default
        ``CalmWaterResistance.from_hull(hull)``.
    diameter : float, optional
        D [m]; default 0.7 T.
    z_blades : int, optional
        Z (default 4).
    ae_a0, p_d : float, optional
        Fix the blade-area ratio / pitch ratio instead of choosing them.
    rpm : float, optional
        Wanted shaft speed at U [1/min] (then P/D is solved for it; exclusive with ``p_d``).
    wake_fraction, thrust_deduction, relative_rotative_efficiency : float, optional
        Given values instead of Holtrop's regressions.
    position : array_like, optional
        (x_P, y_P, z_P) [m]; default x_P = −Lpp/2 + D/2 (half a diameter forward of the aft
        perpendicular), y_P = 0, z_P = T − 0.55 D (tip clearance 0.05 D above the keel line).
    twin_screw : bool, optional
        Use the twin-screw regressions (the returned model is one of the two propellers,
        producing half the required thrust; place a mirrored copy at −y_P).
    **propeller_kwargs
        Further keywords of :class:`Propeller` (``roll_reaction``, ``handedness``,
        ``astern_thrust_factor``, ``name``…).

    Returns
    -------
    Propeller
        With ``resistance`` attached and ``design`` recorded.
    """
    if not isinstance(hull, Hull):
        raise ValueError(f"hull must be a Hull; got {type(hull).__name__}")
    if p_d is not None and rpm is not None:
        raise ValueError("give either p_d or rpm, not both")
    lpp, draught = hull.particulars.lpp, hull.particulars.draught
    u = service_speed(hull) if speed is None else _positive("speed", speed, "m/s")
    if resistance is None:
        resistance = CalmWaterResistance.from_hull(hull)
    if not isinstance(resistance, CalmWaterResistance):
        raise ValueError(f"resistance must be a CalmWaterResistance; got {type(resistance)!r}")
    holtrop = resistance.holtrop
    if holtrop is None:
        holtrop = HoltropMennen.from_hull(hull)
    d = 0.7 * draught if diameter is None else _positive("diameter", diameter, "m")
    if position is None:
        position = (-0.5 * lpp + 0.5 * d, 0.0, draught - 0.55 * d)
    pos = np.asarray(position, dtype=float)
    r_total = float(resistance.resistance(u))
    n_screws = 2 if twin_screw else 1

    def factors(ae: float, pd: float) -> PropulsionFactors:
        auto = holtrop_propulsion_factors(
            holtrop.particulars,
            diameter=d,
            viscous_resistance_coefficient=holtrop.viscous_resistance_coefficient(u),
            ae_a0=ae,
            p_d=pd,
            twin_screw=twin_screw,
        )
        given = (wake_fraction, thrust_deduction, relative_rotative_efficiency)
        if all(v is None for v in given):
            return auto
        return PropulsionFactors(
            auto.wake_fraction if wake_fraction is None else float(wake_fraction),
            auto.thrust_deduction if thrust_deduction is None else float(thrust_deduction),
            auto.relative_rotative_efficiency
            if relative_rotative_efficiency is None
            else float(relative_rotative_efficiency),
            auto.source + " (partly overridden by given values)",
        )

    first = factors(0.7, 1.0)
    thrust = r_total / (1.0 - first.thrust_deduction) / n_screws
    if ae_a0 is None:
        keller = keller_blade_area_ratio(
            thrust, d, float(pos[2]), z_blades, twin_screw=twin_screw, rho=hull.rho, g=hull.g
        )
        # round up to the next 0.05 (series practice: B4-55, B4-70 …), within the series range
        ae = min(max(math.ceil(keller / 0.05 - 1e-9) * 0.05, 0.40), B_SERIES_RANGE["ae_a0"][1])
        ae_source = f"Keller's criterion ({keller:.3f}) rounded up to 0.05, within [0.40, 1.05]"
    else:
        ae = float(ae_a0)
        ae_source = "given"
    va = (1.0 - first.wake_fraction) * u
    load = thrust / (hull.rho * d * d * va * va)

    def efficiency(pd: float) -> float:
        prop = WageningenB(z_blades, ae, pd)
        j = prop.advance_ratio_for_load(load)
        return float(prop.efficiency(j))

    def shaft_speed(pd: float) -> float:
        prop = WageningenB(z_blades, ae, pd)
        return va / (prop.advance_ratio_for_load(load) * d)

    lo, hi = B_SERIES_RANGE["p_d"]
    if p_d is not None:
        pd, pd_source = float(p_d), "given"
    elif rpm is not None:
        n_target = _positive("rpm", rpm, "1/min") / 60.0
        n_lo, n_hi = shaft_speed(hi), shaft_speed(lo)
        if not n_lo <= n_target <= n_hi:
            raise ValueError(
                f"rpm {rpm!r} is out of reach with P/D in [{lo}, {hi}] (possible "
                f"{60 * n_lo:.1f}–{60 * n_hi:.1f} rpm at {u:.3f} m/s); change the diameter"
            )
        pd = float(brentq(lambda x: shaft_speed(x) - n_target, lo, hi, xtol=1e-10))
        pd_source = f"solved for {rpm:g} rpm"
    else:
        res = minimize_scalar(
            lambda x: -efficiency(x), bounds=(lo, hi), method="bounded", options={"xatol": 1e-5}
        )
        pd = float(res.x)
        pd_source = "highest open-water efficiency on the loading line"
    final = factors(ae, pd)
    if n_screws == 2:
        # each of two propellers carries half the resistance: a halved curve for the helpers
        full = resistance
        resistance = CalmWaterResistance(lambda v: 0.5 * float(full.resistance(v)))
    propeller = Propeller(
        WageningenB(z_blades, ae, pd),
        d,
        wake_fraction=final.wake_fraction,
        thrust_deduction=final.thrust_deduction,
        position=pos,
        relative_rotative_efficiency=final.relative_rotative_efficiency,
        rho=hull.rho,
        resistance=resistance,
        **propeller_kwargs,
    )
    point = propeller.self_propulsion(u)
    propeller.design = PropellerDesign(
        speed=u,
        froude_number=u / math.sqrt(hull.g * lpp),
        diameter=d,
        z_blades=int(z_blades),
        ae_a0=ae,
        p_d=pd,
        ae_a0_source=ae_source,
        p_d_source=pd_source,
        factors=final,
        point=point,
    )
    return propeller


__all__ = [
    "B_SERIES_RANGE",
    "KQ_TERMS",
    "KT_TERMS",
    "SHAFT_SPEED_COMMAND",
    "Propeller",
    "PropellerDesign",
    "PropellerOperatingPoint",
    "PropulsionFactors",
    "SelfPropulsionPoint",
    "WageningenB",
    "design_propeller_for",
    "holtrop_propulsion_factors",
    "keller_blade_area_ratio",
    "service_speed",
]


# =============================================================================================
# row kernels (numba; the engine's numpy path and its compiled loop call these)
# =============================================================================================
@nb.njit(cache=True)
def open_water_kt_kq(j, kt_c, kq_c, j0):  # pragma: no cover - compiled
    """WageningenB.coefficients_extended (polynomial on [0, J₀], linear outside)."""
    if j < 0.0:
        return kt_c[0] + kt_c[1] * j, kq_c[0] + kq_c[1] * j
    if j > j0:
        dkt = kt_c[1] + j0 * (2.0 * kt_c[2] + 3.0 * j0 * kt_c[3])
        dkq = kq_c[1] + j0 * (2.0 * kq_c[2] + 3.0 * j0 * kq_c[3])
        kq0 = kq_c[0] + j0 * (kq_c[1] + j0 * (kq_c[2] + j0 * kq_c[3]))
        return dkt * (j - j0), kq0 + dkq * (j - j0)
    kt = kt_c[0] + j * (kt_c[1] + j * (kt_c[2] + j * kt_c[3]))
    kq = kq_c[0] + j * (kq_c[1] + j * (kq_c[2] + j * kq_c[3]))
    return kt, kq


@nb.njit(cache=True, nogil=True)
def propeller_force(
    u, n, kt_c, kq_c, j0, diameter, rho_d4, one_minus_w, one_minus_t, eta_r, astern, z_p, y_p,
    roll_sign, out,
):  # fmt: skip  # pragma: no cover - compiled
    """Propeller.evaluate for one ship: X = (1 − t) T(n, (1 − w) u) at r_P, roll reaction
    optional; writes out (6,) and returns the open-water thrust T [N]."""
    va = one_minus_w * u
    if abs(n) < 1e-12:
        thrust, torque = 0.0, 0.0
    else:
        sign = 1.0
        if n < 0.0:  # mirror image of the ahead curves (Propeller.thrust_torque)
            n, va, sign = -n, -va, -1.0
        kt, kq = open_water_kt_kq(va / (n * diameter), kt_c, kq_c, j0)
        thrust = rho_d4 * n * n * kt
        torque = rho_d4 * diameter * n * n * kq
        if sign < 0.0:
            thrust = -astern * thrust
            torque = -torque
    x = one_minus_t * thrust
    out[0] = x
    out[1] = 0.0
    out[2] = 0.0
    out[3] = roll_sign * (torque / eta_r)
    out[4] = z_p * x
    out[5] = -y_p * x
    return thrust


class PropellerRecord(NamedTuple):
    """:func:`propeller_force`'s parameters after (u, n), the shaft-speed command's column and
    the shared slot that receives the open-water thrust T [N] (the rudder's slipstream)."""

    kt_c: FloatArray
    kq_c: FloatArray
    j0: float
    diameter: float
    rho_d4: float
    one_minus_w: float
    one_minus_t: float
    eta_r: float
    astern: float
    z_p: float
    y_p: float
    roll_sign: float
    shaft_col: int
    thrust_slot: int


@nb.njit(cache=True, nogil=True, inline="always")
def propeller_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: :func:`propeller_force` at the shaft speed n = cmd[s, shaft_col] [rev/s];
    T goes to ``ctx.shared[thrust_slot]``."""
    work = ctx.work
    ctx.shared[rec.thrust_slot] = propeller_force(
        v[0], ctx.cmd[s, rec.shaft_col], rec.kt_c, rec.kq_c, rec.j0, rec.diameter, rec.rho_d4,
        rec.one_minus_w, rec.one_minus_t, rec.eta_r, rec.astern, rec.z_p, rec.y_p,
        rec.roll_sign, work,
    )  # fmt: skip
    for i in range(6):
        out[i] += work[i]
