"""Calm-water resistance: ITTC-1957 friction with a form factor and Holtrop–Mennen's regression.

The ship's calm-water resistance R_T(U) [N] is split as in Holtrop & Mennen (1982) and Holtrop
(1984):

    R_T = (1 + k1) R_F + R_APP + R_W + R_B + R_TR + R_A (+ R_AA),                 (1)

and acts on the hull as a surge force X = −R_T(|u|) sign(u) (:class:`CalmWaterResistance`).

Components
----------
* **Friction** (ITTC 1957 model–ship correlation line):
  R_F = ½ ρ U² S C_F,  C_F = 0.075 / (log₁₀ Rn − 2)²,  Rn = U L / ν.                (2)
* **Form factor** 1 + k1, either given or from Holtrop's regressions —
  1982 (Holtrop & Mennen 1982):
  1 + k1 = c13 {0.93 + c12 (B/L_R)^0.92497 (0.95 − C_P)^−0.521448 (1 − C_P + 0.0225 lcb)^0.6906},
  c13 = 1 + 0.003 C_stern, c12 = (T/L)^0.2228446 (T/L > 0.05),
  48.20 (T/L − 0.02)^2.078 + 0.479948 (0.02 < T/L ≤ 0.05), 0.479948 (T/L ≤ 0.02);        (3a)
  1984 (Holtrop 1984):
  1 + k1 = 0.93 + 0.487118 c14 (B/L)^1.06806 (T/L)^0.46106 (L/L_R)^0.121563
           (L³/∇)^0.36486 (1 − C_P)^−0.604247,  c14 = 1 + 0.011 C_stern.               (3b)
  Length of run L_R = L [1 − C_P + 0.06 C_P lcb / (4 C_P − 1)].                      (4)
* **Appendages**: R_APP = ½ ρ U² S_APP (1 + k2) C_F.                                 (5)
* **Wave resistance** (Fn = U/√(gL)), Holtrop & Mennen (1982), Holtrop (1984):
  R_W = c1 c2 c5 ∇ ρ g exp{m1 Fn^d + m cos(λ Fn^−2)},  d = −0.9,                    (6)
  with m = m2 = c15 C_P² exp(−0.1 Fn^−2) in 1982 and m = m4 = 0.4 c15 exp(−0.034 Fn^−3.29) in
  1984, and
  c1 = 2223105 c7^3.78613 (T/B)^1.07961 (90 − i_E)^−1.37565,
  c7 = 0.229577 (B/L)^0.33333 (B/L < 0.11), B/L (0.11 ≤ B/L ≤ 0.25), 0.5 − 0.0625 L/B (> 0.25),
  i_E = 1 + 89 exp{−(L/B)^0.80856 (1 − C_WP)^0.30484 (1 − C_P − 0.0225 lcb)^0.6367
        (L_R/B)^0.34574 (100∇/L³)^0.16302}  [deg] (half angle of entrance),
  c2 = exp(−1.89 √c3),  c3 = 0.56 A_BT^1.5 / {B T (0.31 √A_BT + T_F − h_B)},
  c5 = 1 − 0.8 A_T / (B T C_M),
  m1 = 0.0140407 L/T − 1.75254 ∇^(1/3)/L − 4.79323 B/L − c16,
  c16 = 8.07981 C_P − 13.8673 C_P² + 6.984388 C_P³ (C_P < 0.8), 1.73014 − 0.7067 C_P (≥ 0.8),
  c15 = −1.69385 (L³/∇ < 512), −1.69385 + (L/∇^(1/3) − 8)/2.36 (512 ≤ L³/∇ ≤ 1726.91),
  0 (> 1726.91),
  λ = 1.446 C_P − 0.03 L/B (L/B < 12), 1.446 C_P − 0.36 (L/B ≥ 12).
  Holtrop (1984) adds, for Fn > 0.55, R_W = c17 c2 c5 ∇ρg exp{m3 Fn^d + m4 cos(λ Fn^−2)} with
  c17 = 6919.3 C_M^−1.3346 (∇/L³)^2.00977 (L/B − 2)^1.40692, m3 = −7.2035 (B/L)^0.326869
  (T/B)^0.605375, and a linear interpolation in Fn between Fn = 0.40 and 0.55.
* **Bulbous bow**: R_B = 0.11 exp(−3 P_B^−2) Fn_i³ A_BT^1.5 ρ g / (1 + Fn_i²),
  P_B = 0.56 √A_BT / (T_F − 1.5 h_B),
  Fn_i = U / √(g (T_F − h_B − 0.25 √A_BT) + 0.15 U²).                               (7)
* **Immersed transom**: R_TR = ½ ρ U² A_T c6, c6 = 0.2 (1 − 0.2 Fn_T) for Fn_T < 5, else 0,
  Fn_T = U / √(2 g A_T / (B + B C_WP)).                                              (8)
* **Model–ship correlation**: R_A = ½ ρ U² S C_A,
  C_A = 0.006 (L + 100)^−0.16 − 0.00205 + 0.003 √(L/7.5) C_B⁴ c2 (0.04 − c4),
  c4 = min(T_F/L, 0.04), for a hull roughness k_s = 150 µm; other roughness adds
  ΔC_A = (0.105 k_s^(1/3) − 0.005579) / L^(1/3) (k_s, L in m) (Holtrop 1984).        (9)
* **Air resistance** (optional, ITTC 1978 performance prediction method, ITTC 7.5-02-03-01.4):
  R_AA = ½ ρ_air C_DA A_VT U² with the transverse projected area above the waterline A_VT and
  C_DA ≈ 0.8, in still air (relative wind = ship speed).                            (10)

Symbols: L the waterline length, B the moulded breadth, T = (T_F + T_A)/2, ∇ the displaced
volume, C_B = ∇/(LBT), C_M, C_WP, C_P = C_B/C_M (all on L), lcb the longitudinal centre of
buoyancy in per cent of L forward of L/2, A_BT and h_B the bulb's transverse area and the height
of its centroid above the keel, A_T the immersed transom area at rest, C_stern the stern-shape
coefficient (−25 pram with gondola, −10 V-shaped sections, 0 normal sections, +10 U-shaped
sections with Hogner stern), S the wetted area of the bare hull, S_APP and 1 + k2 those of the
appendages.

Low speeds and astern: below Rn = 10⁵ the friction line loses meaning; there R_T is scaled as
U² from its value at Rn = 10⁵ (continuous, R_T(0) = 0). Astern (u < 0) the same curve is used
mirrored, X = +R_T(|u|) — an approximation (real astern resistance of a ship is somewhat
higher). Drift and yaw (added resistance in turns, X_vv, X_vr, X_rr) belong to the manoeuvring
model, and added resistance in waves to the wave-force models; this module only knows u.

Validity (Holtrop & Mennen 1982, Table 1, limits of the data the regressions were fitted to; kept
for both variants): tankers and bulk carriers Fn ≤ 0.24, 0.73 ≤ C_P ≤ 0.85, 5.1 ≤ L/B ≤ 7.1,
2.4 ≤ B/T ≤ 3.2; trawlers, coasters, tugs Fn ≤ 0.38, 0.55–0.65, 3.9–6.3, 2.1–3.0; container ships
and destroyer types Fn ≤ 0.45, 0.55–0.67, 6.0–9.5, 3.0–4.0; cargo liners Fn ≤ 0.30, 0.56–0.75,
5.3–8.0, 2.4–4.0; RoRo ships and car ferries Fn ≤ 0.35, 0.55–0.67, 5.3–8.0, 3.2–4.0.
:meth:`HoltropMennen.range_report` names every violation; the S175 (C_P ≈ 0.58, L/B ≈ 6.95,
B/T ≈ 2.67) falls in the cargo-liner range, i.e. up to Fn = 0.30.

Compiled kernel: the method is written once, as ``@numba.njit`` functions of a packed float64
record (:meth:`HoltropMennen.kernel_parameters`, layout in the ``_HM_*`` index constants):
:func:`holtrop_total` (R_T), :func:`holtrop_components` (all terms of eq. 1) and
:func:`holtrop_wave_resistance` (eq. 6). :class:`HoltropMennen`'s methods call them from Python,
and compiled code (the simulation engine, per ship and step) calls them directly;
:meth:`CalmWaterResistance.kernel_parameters` raises NotImplementedError for a generic curve.

Verification: the worked example of Holtrop & Mennen (1982) (L = 205 m, B = 32 m, T = 10 m,
∇ = 37 500 m³, 25 kn: R_F = 869.63 kN, 1 + k1 = 1.156, R_W = 557.11 kN, R_A = 221.98 kN,
R_T = 1793.26 kN) is reproduced by ``variant="1982"`` in ``tests/forces/test_propulsion.py``.

References
----------
ITTC (1957). Proceedings of the 8th International Towing Tank Conference, Madrid.
ITTC (2017). Recommended procedure 7.5-02-03-01.4, 1978 ITTC performance prediction method.
Holtrop, J. & Mennen, G.G.J. (1982). An approximate power prediction method. International
Shipbuilding Progress 29(335), 166–170.
Holtrop, J. (1984). A statistical re-analysis of resistance and propulsion data. International
Shipbuilding Progress 31(363), 272–276.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal, NamedTuple

import numba as nb
import numpy as np
from numpy.typing import ArrayLike

from ship_gym.conventions import GRAVITY, RHO_SEAWATER, SURGE
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.forces.viscous import KINEMATIC_VISCOSITY_SEAWATER, midship_section_area
from ship_gym.hull.hull import Hull
from ship_gym.hull.hydrostatics import hydrostatics

RHO_AIR: float = 1.225
"""Density of air at sea level (ISA, 15 °C) [kg/m³]."""

AIR_DRAG_COEFFICIENT: float = 0.8
"""Default air-drag coefficient C_DA of the above-water hull and superstructure [-] (ITTC 1978)."""

MIN_REYNOLDS_NUMBER: float = 1.0e5
"""Below this Reynolds number the resistance is scaled as U² (the friction line is not used)."""

Variant = Literal["1982", "1984"]
OnOutOfRange = Literal["warn", "raise", "ignore"]


class ShipTypeRange(NamedTuple):
    """Range of one ship type in Holtrop & Mennen's (1982) data (Table 1)."""

    fn_max: float
    """Largest Froude number [-]."""
    cp: tuple[float, float]
    """Prismatic coefficient range [-]."""
    l_b: tuple[float, float]
    """Length–beam ratio range [-]."""
    b_t: tuple[float, float]
    """Beam–draught ratio range [-]."""

    def fits(self, cp: float, l_b: float, b_t: float) -> bool:
        """Whether a form (C_P, L/B, B/T) lies inside this type's ranges."""
        return (
            self.cp[0] <= cp <= self.cp[1]
            and self.l_b[0] <= l_b <= self.l_b[1]
            and self.b_t[0] <= b_t <= self.b_t[1]
        )


VALIDITY_RANGES: dict[str, ShipTypeRange] = {
    "tankers, bulk carriers": ShipTypeRange(0.24, (0.73, 0.85), (5.1, 7.1), (2.4, 3.2)),
    "trawlers, coasters, tugs": ShipTypeRange(0.38, (0.55, 0.65), (3.9, 6.3), (2.1, 3.0)),
    "container ships, destroyer types": ShipTypeRange(0.45, (0.55, 0.67), (6.0, 9.5), (3.0, 4.0)),
    "cargo liners": ShipTypeRange(0.30, (0.56, 0.75), (5.3, 8.0), (2.4, 4.0)),
    "RoRo ships, car ferries": ShipTypeRange(0.35, (0.55, 0.67), (5.3, 8.0), (3.2, 4.0)),
}
"""Holtrop & Mennen (1982), Table 1: ranges of the data behind the regressions, per ship type."""


class HoltropRangeWarning(UserWarning):
    """A hull form or speed lies outside the data Holtrop–Mennen's regressions were fitted to."""


# ------------------------------------------------------------------------------ helpers
def _positive(name: str, value: float, unit: str) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be a positive finite value [{unit}]; got {value!r}")
    return v


def _nonnegative(name: str, value: float, unit: str) -> float:
    v = float(value)
    if not (math.isfinite(v) and v >= 0.0):
        raise ValueError(f"{name} must be a finite value >= 0 [{unit}]; got {value!r}")
    return v


def _finite(name: str, value: float, unit: str) -> float:
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite [{unit}]; got {value!r}")
    return v


def reynolds_number(
    speed: ArrayLike, length: float, kinematic_viscosity: float = KINEMATIC_VISCOSITY_SEAWATER
) -> np.ndarray | float:
    """Reynolds number Rn = U L / ν [-].

    Parameters
    ----------
    speed : array_like
        Speed U [m/s].
    length : float
        Reference length L [m] (waterline length for ship resistance).
    kinematic_viscosity : float, optional
        ν [m²/s] (default sea water at 15 °C, ITTC 2011).
    """
    length = _positive("length", length, "m")
    nu = _positive("kinematic_viscosity", kinematic_viscosity, "m^2/s")
    out = np.abs(np.asarray(speed, dtype=float)) * length / nu
    return float(out) if out.ndim == 0 else out


def froude_number(speed: ArrayLike, length: float, g: float = GRAVITY) -> np.ndarray | float:
    """Froude number Fn = U / √(g L) [-].

    Parameters
    ----------
    speed : array_like
        Speed U [m/s].
    length : float
        Reference length L [m].
    g : float, optional
        Gravitational acceleration [m/s²].
    """
    length = _positive("length", length, "m")
    g = _positive("g", g, "m/s^2")
    out = np.abs(np.asarray(speed, dtype=float)) / math.sqrt(g * length)
    return float(out) if out.ndim == 0 else out


def ittc57_friction_coefficient(reynolds: ArrayLike) -> np.ndarray | float:
    """ITTC-1957 model–ship correlation line C_F = 0.075 / (log₁₀ Rn − 2)² [-].

    Parameters
    ----------
    reynolds : array_like
        Reynolds number Rn [-]; must exceed 100 (where the formula is singular). The line is
        meant for Rn ≳ 10⁵ (turbulent flow).

    Raises
    ------
    ValueError
        If any Rn is not finite or not above 100.
    """
    rn = np.asarray(reynolds, dtype=float)
    if not np.all(np.isfinite(rn)) or np.any(rn <= 100.0):
        raise ValueError(
            f"reynolds must be finite and > 100 (ITTC-1957 line is singular at Rn = 100); "
            f"got {reynolds!r}"
        )
    out = 0.075 / (np.log10(rn) - 2.0) ** 2
    return float(out) if out.ndim == 0 else out


# ------------------------------------------------------------------------------ particulars
@dataclass(frozen=True)
class ResistanceParticulars:
    """Hull-form particulars used by Holtrop–Mennen (coefficients on the waterline length).

    Parameters
    ----------
    length : float
        Waterline length L [m].
    beam : float
        Moulded breadth B [m].
    draught_fore, draught_aft : float
        Draughts T_F, T_A at the perpendiculars [m]; T = (T_F + T_A)/2.
    volume : float
        Displaced volume ∇ [m³].
    lcb : float
        Longitudinal centre of buoyancy [% of L], positive forward of L/2.
    midship_coefficient : float
        C_M [-].
    waterplane_coefficient : float
        C_WP on L [-].
    wetted_area : float, optional
        Wetted area of the bare hull S [m²]; default Holtrop & Mennen's (1982) estimate
        S = L(2T + B)√C_M (0.453 + 0.4425 C_B − 0.2862 C_M − 0.003467 B/T + 0.3696 C_WP)
        + 2.38 A_BT/C_B.
    bulb_area : float, optional
        Transverse area of the bulbous bow at the forward perpendicular A_BT [m²] (0: no bulb).
    bulb_centre_height : float, optional
        Height of the centroid of A_BT above the keel h_B [m].
    transom_area : float, optional
        Immersed transom area at rest A_T [m²].
    stern_shape : float, optional
        Holtrop's C_stern [-]: −25 pram with gondola, −10 V-shaped sections, 0 normal sections,
        +10 U-shaped sections with Hogner stern.
    appendage_area : float, optional
        Wetted area of the appendages S_APP [m²].
    appendage_form_factor : float, optional
        Their (equivalent) 1 + k2 [-] (Holtrop & Mennen 1982: e.g. rudder behind skeg 1.5–2.0,
        rudder behind stern 1.3–1.5, bilge keels 1.4, shaft brackets 3.0).
    half_entrance_angle_deg : float, optional
        Half angle of entrance of the waterline i_E [deg]; default Holtrop & Mennen's regression.
    """

    length: float
    beam: float
    draught_fore: float
    draught_aft: float
    volume: float
    lcb: float
    midship_coefficient: float
    waterplane_coefficient: float
    wetted_area: float | None = None
    bulb_area: float = 0.0
    bulb_centre_height: float = 0.0
    transom_area: float = 0.0
    stern_shape: float = 0.0
    appendage_area: float = 0.0
    appendage_form_factor: float = 1.5
    half_entrance_angle_deg: float | None = None

    def __post_init__(self) -> None:
        for name in ("length", "beam", "draught_fore", "draught_aft"):
            object.__setattr__(self, name, _positive(name, getattr(self, name), "m"))
        object.__setattr__(self, "volume", _positive("volume", self.volume, "m^3"))
        object.__setattr__(self, "lcb", _finite("lcb", self.lcb, "% of L"))
        if abs(self.lcb) > 10.0:
            raise ValueError(f"lcb must be a percentage of L within ±10 %; got {self.lcb!r}")
        for name in ("midship_coefficient", "waterplane_coefficient"):
            v = _positive(name, getattr(self, name), "-")
            if v > 1.0:
                raise ValueError(f"{name} must lie in (0, 1]; got {v!r}")
            object.__setattr__(self, name, v)
        cb = self.block_coefficient
        if not 0.0 < cb < 1.0:
            raise ValueError(
                f"block coefficient ∇/(L B T) = {cb:.4g} must lie in (0, 1); check volume, "
                "length, beam and draughts"
            )
        cp = self.prismatic_coefficient
        if not 0.3 < cp < 0.95:
            raise ValueError(
                f"prismatic coefficient C_B/C_M = {cp:.4g} must lie in (0.3, 0.95) for "
                "Holtrop–Mennen's regressions (singular at 0.25 and 0.95)"
            )
        if self.wetted_area is not None:
            object.__setattr__(
                self, "wetted_area", _positive("wetted_area", self.wetted_area, "m^2")
            )
        for name, unit in (
            ("bulb_area", "m^2"),
            ("bulb_centre_height", "m"),
            ("transom_area", "m^2"),
            ("appendage_area", "m^2"),
        ):
            object.__setattr__(self, name, _nonnegative(name, getattr(self, name), unit))
        if self.bulb_area > 0.0:
            submerged = self.draught_fore - self.bulb_centre_height - 0.25 * self.bulb_area**0.5
            if not (0.0 < self.bulb_centre_height and submerged > 0.0):
                raise ValueError(
                    "with a bulb, need 0 < bulb_centre_height and T_F − h_B − 0.25 √A_BT > 0 "
                    f"(bulb below the surface); got h_B={self.bulb_centre_height!r}, "
                    f"A_BT={self.bulb_area!r}, T_F={self.draught_fore!r}"
                )
            if self.draught_fore - 1.5 * self.bulb_centre_height <= 0.0:
                raise ValueError(
                    "with a bulb, need T_F − 1.5 h_B > 0 (Holtrop's P_B); got "
                    f"h_B={self.bulb_centre_height!r}, T_F={self.draught_fore!r}"
                )
        if self.transom_area >= 1.25 * self.beam * self.draught * self.midship_coefficient:
            raise ValueError(
                f"transom_area {self.transom_area!r} m² must be below 1.25 B T C_M (c5 > 0)"
            )
        stern = _finite("stern_shape", self.stern_shape, "-")
        if not -25.0 <= stern <= 10.0:
            raise ValueError(f"stern_shape (C_stern) must lie in [-25, 10]; got {stern!r}")
        object.__setattr__(self, "stern_shape", stern)
        k2 = _finite("appendage_form_factor", self.appendage_form_factor, "-")
        if k2 < 1.0:
            raise ValueError(f"appendage_form_factor (1 + k2) must be >= 1; got {k2!r}")
        object.__setattr__(self, "appendage_form_factor", k2)
        if self.half_entrance_angle_deg is not None:
            ie = _finite("half_entrance_angle_deg", self.half_entrance_angle_deg, "deg")
            if not 0.0 < ie < 90.0:
                raise ValueError(f"half_entrance_angle_deg must lie in (0, 90); got {ie!r}")
            object.__setattr__(self, "half_entrance_angle_deg", ie)

    # -- derived coefficients -------------------------------------------------------------
    @property
    def draught(self) -> float:
        """Mean draught T = (T_F + T_A)/2 [m]."""
        return 0.5 * (self.draught_fore + self.draught_aft)

    @property
    def block_coefficient(self) -> float:
        """C_B = ∇ / (L B T) [-]."""
        return self.volume / (self.length * self.beam * self.draught)

    @property
    def prismatic_coefficient(self) -> float:
        """C_P = C_B / C_M [-]."""
        return self.block_coefficient / self.midship_coefficient

    @property
    def length_of_run(self) -> float:
        """L_R = L [1 − C_P + 0.06 C_P lcb / (4 C_P − 1)] [m] (eq. 4)."""
        cp = self.prismatic_coefficient
        return self.length * (1.0 - cp + 0.06 * cp * self.lcb / (4.0 * cp - 1.0))

    @property
    def wetted_area_estimate(self) -> float:
        """Holtrop & Mennen's (1982) wetted-area regression [m²]."""
        L, B, T = self.length, self.beam, self.draught
        cb, cm, cwp = self.block_coefficient, self.midship_coefficient, self.waterplane_coefficient
        return (
            L
            * (2.0 * T + B)
            * math.sqrt(cm)
            * (0.453 + 0.4425 * cb - 0.2862 * cm - 0.003467 * B / T + 0.3696 * cwp)
            + 2.38 * self.bulb_area / cb
        )

    @property
    def hull_wetted_area(self) -> float:
        """S used for friction and correlation: the given area, else the estimate [m²]."""
        return self.wetted_area if self.wetted_area is not None else self.wetted_area_estimate

    @property
    def entrance_angle_deg(self) -> float:
        """Half angle of entrance i_E [deg]: the given value, else Holtrop & Mennen's (1982)."""
        if self.half_entrance_angle_deg is not None:
            return self.half_entrance_angle_deg
        L, B = self.length, self.beam
        cp, cwp, lcb = self.prismatic_coefficient, self.waterplane_coefficient, self.lcb
        arg = (
            (L / B) ** 0.80856
            * (1.0 - cwp) ** 0.30484
            * (1.0 - cp - 0.0225 * lcb) ** 0.6367
            * (self.length_of_run / B) ** 0.34574
            * (100.0 * self.volume / L**3) ** 0.16302
        )
        return 1.0 + 89.0 * math.exp(-arg)

    @classmethod
    def from_hull(
        cls,
        hull: Hull,
        *,
        wetted_area: float | None = None,
        bulb_area: float = 0.0,
        bulb_centre_height: float = 0.0,
        transom_area: float = 0.0,
        stern_shape: float = 0.0,
        appendage_area: float = 0.0,
        appendage_form_factor: float = 1.5,
        half_entrance_angle_deg: float | None = None,
    ) -> ResistanceParticulars:
        """Particulars of a :class:`~ship_gym.hull.hull.Hull` at its design waterline.

        L is the waterline length of the immersed mesh (x-extent of its vertices on z = 0), lcb
        the centre of buoyancy of the mesh relative to the middle of that waterline, C_M from
        the section at x = 0 (:func:`ship_gym.forces.viscous.midship_section_area`), C_WP from
        the waterplane area, T_F = T_A = T (even keel), S the area of the immersed mesh unless
        given. Bulb, transom, stern shape and appendages are not in the mesh data: pass them
        (defaults: none, normal stern sections C_stern = 0, no appendages).
        """
        if not isinstance(hull, Hull):
            raise ValueError(f"hull must be a Hull; got {type(hull).__name__}")
        p = hull.particulars
        mesh = hull.immersed_mesh
        verts = mesh.vertices
        on_wl = np.abs(verts[:, 2]) < 1e-6 * p.lpp
        if np.count_nonzero(on_wl) >= 2:
            x_aft, x_fwd = float(verts[on_wl, 0].min()), float(verts[on_wl, 0].max())
        else:  # pragma: no cover - every library hull has waterline vertices
            x_aft, x_fwd = -0.5 * p.lpp, 0.5 * p.lpp
        length = x_fwd - x_aft
        hs = hydrostatics(hull)
        lcb = 100.0 * (float(hs.centre_of_buoyancy[0]) - 0.5 * (x_aft + x_fwd)) / length
        return cls(
            length=length,
            beam=p.beam,
            draught_fore=p.draught,
            draught_aft=p.draught,
            volume=hs.volume,
            lcb=lcb,
            midship_coefficient=midship_section_area(hull) / (p.beam * p.draught),
            waterplane_coefficient=hs.waterplane_area / (length * p.beam),
            wetted_area=(float(mesh.areas.sum()) if wetted_area is None else wetted_area),
            bulb_area=bulb_area,
            bulb_centre_height=bulb_centre_height,
            transom_area=transom_area,
            stern_shape=stern_shape,
            appendage_area=appendage_area,
            appendage_form_factor=appendage_form_factor,
            half_entrance_angle_deg=half_entrance_angle_deg,
        )


# ------------------------------------------------------------------------------ components
def _same_kind(x: np.ndarray) -> np.ndarray | float:
    return float(x) if np.ndim(x) == 0 else x


@dataclass(frozen=True)
class ResistanceComponents:
    """Resistance components at one or more speeds (scalars or arrays of the speeds' shape).

    Attributes
    ----------
    speed : float or numpy.ndarray
        Ship speed U [m/s].
    froude_number, reynolds_number : float or numpy.ndarray
        Fn = U/√(gL), Rn = UL/ν [-].
    friction_coefficient : float or numpy.ndarray
        ITTC-1957 C_F [-] (at Rn = 10⁵ below that).
    form_factor : float
        1 + k1 [-].
    correlation_allowance : float
        C_A [-].
    friction, appendage, wave, bulb, transom, correlation, air : float or numpy.ndarray
        R_F (without form factor), R_APP, R_W, R_B, R_TR, R_A, R_AA [N].
    total : float or numpy.ndarray
        R_T = (1 + k1) R_F + R_APP + R_W + R_B + R_TR + R_A + R_AA [N].
    """

    speed: np.ndarray | float
    froude_number: np.ndarray | float
    reynolds_number: np.ndarray | float
    friction_coefficient: np.ndarray | float
    form_factor: float
    correlation_allowance: float
    friction: np.ndarray | float
    appendage: np.ndarray | float
    wave: np.ndarray | float
    bulb: np.ndarray | float
    transom: np.ndarray | float
    correlation: np.ndarray | float
    air: np.ndarray | float
    total: np.ndarray | float

    @property
    def viscous(self) -> np.ndarray | float:
        """(1 + k1) R_F [N]."""
        return _same_kind(self.form_factor * np.asarray(self.friction))

    @property
    def effective_power(self) -> np.ndarray | float:
        """P_E = R_T U [W]."""
        return _same_kind(np.asarray(self.total) * np.asarray(self.speed))

    def as_dict(self) -> dict[str, np.ndarray | float]:
        """Components by name (for tables and plots), viscous part and P_E included."""
        out = {k: getattr(self, k) for k in self.__dataclass_fields__}
        out["viscous"] = self.viscous
        out["effective_power"] = self.effective_power
        return out


# ------------------------------------------------------------------------------ compiled kernel
# Layout of the packed parameter record of one Holtrop–Mennen model (a 1-D float64 array,
# :meth:`HoltropMennen.kernel_parameters`): everything independent of speed that eq. (1)
# needs at run time. The compiled functions below are the one implementation of R_T(U); the
# Python methods of :class:`HoltropMennen` call them too.
_HM_MIN_SPEED = 0  # U below which R_T is scaled as U² (Rn = 10⁵) [m/s]
_HM_RN_PER_SPEED = 1  # L / ν: Rn = U · this [s/m]
_HM_FN_PER_SPEED = 2  # 1 / √(g L): Fn = U · this [s/m]
_HM_HALF_RHO_S = 3  # ½ ρ S (eqs. 2, 9) [kg/m]
_HM_HALF_RHO_SAPP_K2 = 4  # ½ ρ S_APP (1 + k2) (eq. 5) [kg/m]
_HM_RB_FACTOR = 5  # 0.11 exp(−3 P_B^−2) A_BT^1.5 ρ g (eq. 7), 0 without a bulb [N]
_HM_FNI_DEPTH = 6  # g (T_F − h_B − 0.25 √A_BT) (eq. 7) [m²/s²] (1 without a bulb)
_HM_FNT_SCALE = 7  # √(2 g A_T / (B + B C_WP)): Fn_T = U / this (eq. 8), 0 without transom [m/s]
_HM_RHO = 8  # water density ρ [kg/m³]
_HM_TRANSOM_AREA = 9  # A_T [m²]
_HM_CORRELATION_ALLOWANCE = 10  # C_A (eq. 9) [-]
_HM_HALF_RHO_AIR = 11  # ½ ρ_air C_DA A_VT (eq. 10) [kg/m]
_HM_FORM_FACTOR = 12  # 1 + k1 (eq. 3a / 3b) [-]
_HM_VARIANT_1984 = 13  # 1.0: Holtrop (1984) wave resistance (m4, high-speed branch); 0.0: 1982
_HM_M1 = 14  # m1 (eq. 6) [-]
_HM_M2_FACTOR = 15  # c15 C_P²: m2 = this · exp(−0.1 Fn^−2) (eq. 6, 1982) [-]
_HM_C15 = 16  # c15 (eq. 6) [-]
_HM_LAMBDA = 17  # λ (eq. 6) [-]
_HM_RW_A = 18  # c1 c2 c5 ∇ ρ g (eq. 6) [N]
_HM_RW_B = 19  # c17 c2 c5 ∇ ρ g (Holtrop 1984, Fn > 0.55) [N]
_HM_M3 = 20  # m3 (Holtrop 1984) [-]
_HM_SIZE = 21  # length of the record


@nb.njit(cache=True, nogil=True)
def _holtrop_wave_low(params, fn):  # pragma: no cover - compiled
    """Eq. (6) (Holtrop's R_W-A) at Froude number fn > 0 [N]: m2 (1982) or m4 (1984)."""
    fn2 = fn * fn
    if params[_HM_VARIANT_1984] == 0.0:
        m = params[_HM_M2_FACTOR] * math.exp(-0.1 / fn2)
    else:
        m = 0.4 * params[_HM_C15] * math.exp(-0.034 * fn**-3.29)
    return params[_HM_RW_A] * math.exp(
        params[_HM_M1] * fn**-0.9 + m * math.cos(params[_HM_LAMBDA] / fn2)
    )


@nb.njit(cache=True, nogil=True)
def _holtrop_wave_high(params, fn):  # pragma: no cover - compiled
    """Holtrop's (1984) R_W-B (Fn > 0.55) [N]."""
    m4 = 0.4 * params[_HM_C15] * math.exp(-0.034 * fn**-3.29)
    return params[_HM_RW_B] * math.exp(
        params[_HM_M3] * fn**-0.9 + m4 * math.cos(params[_HM_LAMBDA] / (fn * fn))
    )


@nb.njit(cache=True, nogil=True)
def holtrop_wave_resistance(params, froude):  # pragma: no cover - compiled
    """Wave resistance R_W [N] (eq. 6 and Holtrop's 1984 high-speed branch), compiled.

    Parameters
    ----------
    params : numpy.ndarray
        Packed record (21,) of :meth:`HoltropMennen.kernel_parameters` [mixed units].
    froude : float
        Froude number Fn [-].

    Returns
    -------
    float
        R_W [N]: 0 for Fn < 0.01 (where exp(m1 Fn^−0.9) < 10⁻⁴⁰); the 1982 variant uses eq.
        (6) with m2 throughout; the 1984 variant uses m4 up to Fn = 0.40, R_W-B from Fn =
        0.55 and interpolates linearly in Fn in between (Holtrop 1984).
    """
    fn = froude
    if fn <= 0.0:
        return 0.0
    if fn < 0.01:  # exp(m1 Fn^-0.9) < 1e-40: nothing left, avoid overflow of powers
        return 0.0
    if params[_HM_VARIANT_1984] == 0.0 or fn <= 0.40:
        return _holtrop_wave_low(params, fn)
    if fn >= 0.55:
        return _holtrop_wave_high(params, fn)
    low, high = _holtrop_wave_low(params, 0.40), _holtrop_wave_high(params, 0.55)
    return low + (10.0 * fn - 4.0) * (high - low) / 1.5


@nb.njit(cache=True, nogil=True)
def holtrop_components(params, speed):  # pragma: no cover - compiled
    """All terms of eq. (1) at one speed, compiled (the one implementation of R_T).

    Callable from Python and from other ``@njit`` functions (``nogil``: also from threads).

    Parameters
    ----------
    params : numpy.ndarray
        Packed record (21,) of :meth:`HoltropMennen.kernel_parameters` [mixed units].
    speed : float
        Speed U [m/s]; its magnitude |U| is used.

    Returns
    -------
    tuple of 11 float
        (Fn [-], Rn [-], C_F [-], R_F [N], R_APP [N], R_W [N], R_B [N], R_TR [N], R_A [N],
        R_AA [N], R_T [N]): eqs. (2), (5)–(10) and their sum (1). Fn and Rn are those of |U|;
        below U_min (Rn = 10⁵) the forces are those at U_min scaled by (|U|/U_min)² and C_F
        is the one at U_min.
    """
    v = abs(speed)
    min_speed = params[_HM_MIN_SPEED]
    scale = 1.0
    if v < min_speed:
        scale = (v / min_speed) ** 2
        v_eval = min_speed
    else:
        v_eval = v
    rn = v_eval * params[_HM_RN_PER_SPEED]
    fn = v_eval * params[_HM_FN_PER_SPEED]
    cf = 0.075 / (math.log10(rn) - 2.0) ** 2  # (2)
    v2 = v_eval * v_eval
    r_f = params[_HM_HALF_RHO_S] * v2 * cf  # (2)
    r_app = params[_HM_HALF_RHO_SAPP_K2] * v2 * cf  # (5)
    r_w = holtrop_wave_resistance(params, fn)  # (6)
    rb_factor = params[_HM_RB_FACTOR]
    if rb_factor > 0.0:  # (7)
        fni = v_eval / math.sqrt(params[_HM_FNI_DEPTH] + 0.15 * v2)
        # float exponent: libm pow, as CPython's fni**3 (numba would expand an int literal into
        # multiplications, which may round differently)
        r_b = rb_factor * fni**3.0 / (1.0 + fni**2.0)
    else:
        r_b = 0.0
    fnt_scale = params[_HM_FNT_SCALE]
    if fnt_scale > 0.0:  # (8)
        fnt = v_eval / fnt_scale
        c6 = 0.2 * (1.0 - 0.2 * fnt) if fnt < 5.0 else 0.0
        r_tr = 0.5 * params[_HM_RHO] * v2 * params[_HM_TRANSOM_AREA] * c6
    else:
        r_tr = 0.0
    r_a = params[_HM_HALF_RHO_S] * v2 * params[_HM_CORRELATION_ALLOWANCE]  # (9)
    r_aa = params[_HM_HALF_RHO_AIR] * v2  # (10)
    if scale != 1.0:
        r_f *= scale
        r_app *= scale
        r_w *= scale
        r_b *= scale
        r_tr *= scale
        r_a *= scale
        r_aa *= scale
    total = params[_HM_FORM_FACTOR] * r_f + r_app + r_w + r_b + r_tr + r_a + r_aa  # (1)
    return (
        v * params[_HM_FN_PER_SPEED],
        v * params[_HM_RN_PER_SPEED],
        cf,
        r_f,
        r_app,
        r_w,
        r_b,
        r_tr,
        r_a,
        r_aa,
        total,
    )


@nb.njit(cache=True, nogil=True)
def holtrop_total(params, speed):  # pragma: no cover - compiled
    """Total calm-water resistance R_T(|U|) ≥ 0 [N] (eq. 1), compiled.

    Parameters
    ----------
    params : numpy.ndarray
        Packed record (21,) of :meth:`HoltropMennen.kernel_parameters` [mixed units].
    speed : float
        Speed U [m/s]; its magnitude is used (the surge force is −R_T(|u|) sign(u)).

    Returns
    -------
    float
        R_T [N], the last term of :func:`holtrop_components`.
    """
    return holtrop_components(params, speed)[10]


# ------------------------------------------------------------------------------ the method
class HoltropMennen:
    """Calm-water resistance of a displacement ship by Holtrop & Mennen (1982) / Holtrop (1984).

    Everything independent of speed is computed once here and packed into one float64 record
    (:meth:`kernel_parameters`); every evaluation (:meth:`total`, :meth:`total_scalar`,
    :meth:`components`, :meth:`wave_resistance`) is done by the compiled functions
    :func:`holtrop_total`, :func:`holtrop_components` and :func:`holtrop_wave_resistance`
    on that record, which ``@njit`` code (the compiled simulation engine) calls directly.

    Parameters
    ----------
    particulars : ResistanceParticulars
        The hull form.
    variant : {"1984", "1982"}, optional
        "1984" (default): Holtrop's (1984) form factor (3b) and wave resistance (m4, with the
        high-speed branch above Fn = 0.55); "1982": Holtrop & Mennen's (1982) form factor (3a)
        and wave resistance (m2), as in their worked example.
    form_factor : float, optional
        Given 1 + k1 [-] (e.g. from a Prohaska plot) instead of the regression.
    correlation_allowance : float, optional
        Given C_A [-] instead of eq. (9).
    hull_roughness : float, optional
        k_s [m] (default 150 µm, for which eq. (9)'s roughness term vanishes).
    air_frontal_area : float, optional
        Transverse projected area above the waterline A_VT [m²]; 0 (default) switches the air
        resistance off.
    air_drag_coefficient : float, optional
        C_DA [-] (default 0.8).
    rho, g, kinematic_viscosity, rho_air : float, optional
        Water density [kg/m³], gravity [m/s²], ν [m²/s], air density [kg/m³].
    """

    def __init__(
        self,
        particulars: ResistanceParticulars,
        *,
        variant: Variant = "1984",
        form_factor: float | None = None,
        correlation_allowance: float | None = None,
        hull_roughness: float = 150e-6,
        air_frontal_area: float = 0.0,
        air_drag_coefficient: float = AIR_DRAG_COEFFICIENT,
        rho: float = RHO_SEAWATER,
        g: float = GRAVITY,
        kinematic_viscosity: float = KINEMATIC_VISCOSITY_SEAWATER,
        rho_air: float = RHO_AIR,
    ) -> None:
        if not isinstance(particulars, ResistanceParticulars):
            raise ValueError(
                f"particulars must be a ResistanceParticulars; got {type(particulars).__name__}"
            )
        if variant not in ("1982", "1984"):
            raise ValueError(f"variant must be '1982' or '1984'; got {variant!r}")
        self.particulars = particulars
        self.variant: Variant = variant
        self.rho = _positive("rho", rho, "kg/m^3")
        self.g = _positive("g", g, "m/s^2")
        self.kinematic_viscosity = _positive("kinematic_viscosity", kinematic_viscosity, "m^2/s")
        self.rho_air = _positive("rho_air", rho_air, "kg/m^3")
        self.air_frontal_area = _nonnegative("air_frontal_area", air_frontal_area, "m^2")
        self.air_drag_coefficient = _nonnegative("air_drag_coefficient", air_drag_coefficient, "-")
        self.hull_roughness = _positive("hull_roughness", hull_roughness, "m")
        if form_factor is not None:
            form_factor = _finite("form_factor", form_factor, "-")
            if not 1.0 <= form_factor < 2.0:
                raise ValueError(f"form_factor (1 + k1) must lie in [1, 2); got {form_factor!r}")
        if correlation_allowance is not None:
            correlation_allowance = _finite("correlation_allowance", correlation_allowance, "-")
            if abs(correlation_allowance) > 0.01:
                raise ValueError(
                    f"correlation_allowance C_A must be within ±0.01; got {correlation_allowance!r}"
                )
        self._setup(form_factor, correlation_allowance)

    # -- speed-independent part -----------------------------------------------------------
    def _setup(self, form_factor: float | None, correlation_allowance: float | None) -> None:
        p = self.particulars
        L, B, T, vol = p.length, p.beam, p.draught, p.volume
        tf = p.draught_fore
        cb, cp, cm = p.block_coefficient, p.prismatic_coefficient, p.midship_coefficient
        lcb, lr = p.lcb, p.length_of_run
        rho, g = self.rho, self.g
        c: dict[str, float] = {"L_R": lr, "C_B": cb, "C_P": cp}

        # form factor (3a) / (3b)
        t_l = T / L
        if t_l > 0.05:
            c12 = t_l**0.2228446
        elif t_l > 0.02:
            c12 = 48.20 * (t_l - 0.02) ** 2.078 + 0.479948
        else:
            c12 = 0.479948
        c13 = 1.0 + 0.003 * p.stern_shape
        c14 = 1.0 + 0.011 * p.stern_shape
        k1_1982 = c13 * (
            0.93
            + c12
            * (B / lr) ** 0.92497
            * (0.95 - cp) ** -0.521448
            * (1.0 - cp + 0.0225 * lcb) ** 0.6906
        )
        k1_1984 = (
            0.93
            + 0.487118
            * c14
            * (B / L) ** 1.06806
            * (T / L) ** 0.46106
            * (L / lr) ** 0.121563
            * (L**3 / vol) ** 0.36486
            * (1.0 - cp) ** -0.604247
        )
        c.update(c12=c12, c13=c13, c14=c14, k1_1982=k1_1982, k1_1984=k1_1984)
        regression = k1_1984 if self.variant == "1984" else k1_1982
        self.form_factor = regression if form_factor is None else form_factor

        # wave resistance (6)
        b_l = B / L
        if b_l < 0.11:
            c7 = 0.229577 * b_l**0.33333
        elif b_l <= 0.25:
            c7 = b_l
        else:
            c7 = 0.5 - 0.0625 * L / B
        ie = p.entrance_angle_deg
        c1 = 2223105.0 * c7**3.78613 * (T / B) ** 1.07961 * (90.0 - ie) ** -1.37565
        if p.bulb_area > 0.0:
            abt = p.bulb_area
            c3 = 0.56 * abt**1.5 / (B * T * (0.31 * math.sqrt(abt) + tf - p.bulb_centre_height))
        else:
            c3 = 0.0
        c2 = math.exp(-1.89 * math.sqrt(c3))
        c5 = 1.0 - 0.8 * p.transom_area / (B * T * cm)
        if cp < 0.8:
            c16 = 8.07981 * cp - 13.8673 * cp**2 + 6.984388 * cp**3
        else:
            c16 = 1.73014 - 0.7067 * cp
        m1 = 0.0140407 * L / T - 1.75254 * vol ** (1.0 / 3.0) / L - 4.79323 * B / L - c16
        l3_v = L**3 / vol
        if l3_v < 512.0:
            c15 = -1.69385
        elif l3_v <= 1726.91:
            c15 = -1.69385 + (L / vol ** (1.0 / 3.0) - 8.0) / 2.36
        else:
            c15 = 0.0
        lam = 1.446 * cp - 0.03 * L / B if L / B < 12.0 else 1.446 * cp - 0.36
        c17 = 6919.3 * cm**-1.3346 * (vol / L**3) ** 2.00977 * max(L / B - 2.0, 0.0) ** 1.40692
        m3 = -7.2035 * (B / L) ** 0.326869 * (T / B) ** 0.605375
        c.update(
            c1=c1, c2=c2, c3=c3, c5=c5, c7=c7, c15=c15, c16=c16, c17=c17, m1=m1, m3=m3,
            i_E=ie, lambda_=lam, d=-0.9,
        )  # fmt: skip
        self._rw_a = c1 * c2 * c5 * vol * rho * g
        self._rw_b = c17 * c2 * c5 * vol * rho * g
        self._m1, self._m3, self._c15, self._lam = m1, m3, c15, lam
        self._m2_factor = c15 * cp**2

        # bulb (7)
        if p.bulb_area > 0.0:
            abt, hb = p.bulb_area, p.bulb_centre_height
            pb = 0.56 * math.sqrt(abt) / (tf - 1.5 * hb)
            self._rb_factor = 0.11 * math.exp(-3.0 * pb**-2) * abt**1.5 * rho * g
            self._fni_depth = g * (tf - hb - 0.25 * math.sqrt(abt))
            c["P_B"] = pb
        else:
            self._rb_factor = 0.0
            self._fni_depth = 1.0

        # transom (8)
        if p.transom_area > 0.0:
            wl_breadth = B + B * p.waterplane_coefficient
            self._fnt_scale = math.sqrt(2.0 * g * p.transom_area / wl_breadth)
        else:
            self._fnt_scale = 0.0

        # correlation allowance (9)
        c4 = min(tf / L, 0.04)
        ca = (
            0.006 * (L + 100.0) ** -0.16
            - 0.00205
            + 0.003 * math.sqrt(L / 7.5) * cb**4 * c2 * (0.04 - c4)
        )
        ca += (0.105 * self.hull_roughness ** (1.0 / 3.0) - 0.005579) / L ** (1.0 / 3.0)
        c["c4"] = c4
        c["C_A_regression"] = ca
        self.correlation_allowance = ca if correlation_allowance is None else correlation_allowance
        self.coefficients = c
        """Intermediate coefficients of the method (names as in the papers) for inspection."""

        s = p.hull_wetted_area
        self.wetted_area = s
        self._half_rho_s = 0.5 * rho * s
        self._half_rho_sapp_k2 = 0.5 * rho * p.appendage_area * p.appendage_form_factor
        self._half_rho_air = 0.5 * self.rho_air * self.air_drag_coefficient * self.air_frontal_area
        self._rn_per_speed = L / self.kinematic_viscosity
        self._fn_per_speed = 1.0 / math.sqrt(g * L)
        self.min_speed = MIN_REYNOLDS_NUMBER / self._rn_per_speed
        """Speed below which R_T is scaled as U² [m/s] (Rn = 10⁵)."""
        self._params = self._pack()

    def _pack(self) -> np.ndarray:
        """The packed record of :meth:`kernel_parameters` from the speed-independent fields."""
        params = np.zeros(_HM_SIZE)
        params[_HM_MIN_SPEED] = self.min_speed
        params[_HM_RN_PER_SPEED] = self._rn_per_speed
        params[_HM_FN_PER_SPEED] = self._fn_per_speed
        params[_HM_HALF_RHO_S] = self._half_rho_s
        params[_HM_HALF_RHO_SAPP_K2] = self._half_rho_sapp_k2
        params[_HM_RB_FACTOR] = self._rb_factor
        params[_HM_FNI_DEPTH] = self._fni_depth
        params[_HM_FNT_SCALE] = self._fnt_scale
        params[_HM_RHO] = self.rho
        params[_HM_TRANSOM_AREA] = self.particulars.transom_area
        params[_HM_CORRELATION_ALLOWANCE] = self.correlation_allowance
        params[_HM_HALF_RHO_AIR] = self._half_rho_air
        params[_HM_FORM_FACTOR] = self.form_factor
        params[_HM_VARIANT_1984] = 1.0 if self.variant == "1984" else 0.0
        params[_HM_M1] = self._m1
        params[_HM_M2_FACTOR] = self._m2_factor
        params[_HM_C15] = self._c15
        params[_HM_LAMBDA] = self._lam
        params[_HM_RW_A] = self._rw_a
        params[_HM_RW_B] = self._rw_b
        params[_HM_M3] = self._m3
        return params

    def kernel_parameters(self) -> np.ndarray:
        """Packed record of the method for the compiled functions (a fresh copy).

        :func:`holtrop_total` (R_T [N]), :func:`holtrop_components` (all terms of eq. 1) and
        :func:`holtrop_wave_resistance` (eq. 6) evaluate the method from it, in Python or in
        ``@njit`` code (the compiled simulation engine); :meth:`total` and :meth:`components`
        are those same functions.

        Returns
        -------
        numpy.ndarray
            (21,) float64, the speed-independent quantities of eqs. (1)–(10) in the order of
            the module's ``_HM_*`` index constants: U_min [m/s], L/ν [s/m], 1/√(gL) [s/m],
            ½ρS [kg/m], ½ρS_APP(1 + k2) [kg/m], the bulb factor of eq. (7) [N], its depth term
            g(T_F − h_B − 0.25√A_BT) [m²/s²], the transom speed scale of eq. (8) [m/s], ρ
            [kg/m³], A_T [m²], C_A [-], ½ρ_air C_DA A_VT [kg/m], 1 + k1 [-], the variant flag
            (1.0: 1984, 0.0: 1982), m1, c15 C_P², c15, λ [-], c1 c2 c5 ∇ρg [N], c17 c2 c5 ∇ρg
            [N], m3 [-].
        """
        return self._params.copy()

    # -- wave resistance --------------------------------------------------------------------
    def _wave_low(self, fn: float) -> float:
        """Eq. (6) (Holtrop's R_W-A) at Froude number fn > 0 [N]."""
        return _holtrop_wave_low(self._params, float(fn))

    def _wave_high(self, fn: float) -> float:
        """Holtrop's (1984) R_W-B (Fn > 0.55) [N]."""
        return _holtrop_wave_high(self._params, float(fn))

    def wave_resistance(self, froude: float) -> float:
        """Wave resistance R_W [N] at a Froude number (eq. 6 and Holtrop's high-speed branch).

        Evaluated by :func:`holtrop_wave_resistance` (0 for Fn < 0.01).
        """
        return holtrop_wave_resistance(self._params, float(froude))

    # -- components ---------------------------------------------------------------------------
    def _scalar(self, speed: float) -> tuple[float, ...]:
        """(Fn, Rn, C_F, R_F, R_APP, R_W, R_B, R_TR, R_A, R_AA, R_T) at one speed |U| [m/s].

        Evaluated by :func:`holtrop_components`.
        """
        return holtrop_components(self._params, float(speed))

    def total_scalar(self, speed: float) -> float:
        """R_T(|U|) [N] at one speed U [m/s] (the fast path; :func:`holtrop_total`)."""
        return holtrop_total(self._params, float(speed))

    def total(self, speed: ArrayLike) -> np.ndarray | float:
        """Total calm-water resistance R_T(|U|) ≥ 0 [N] (eq. 1) at speed(s) U [m/s]."""
        arr = np.asarray(speed)
        if arr.ndim == 0:
            return holtrop_total(self._params, float(arr))
        arr = np.asarray(arr, dtype=float)
        params = self._params
        return np.array([holtrop_total(params, v) for v in arr.ravel().tolist()]).reshape(arr.shape)

    def components(self, speed: ArrayLike) -> ResistanceComponents:
        """All components of eq. (1) at speed(s) U ≥ 0 [m/s].

        Raises
        ------
        ValueError
            If a speed is negative or not finite.
        """
        arr = np.asarray(speed, dtype=float)
        if not np.all(np.isfinite(arr)) or np.any(arr < 0.0):
            raise ValueError(f"speed must be finite and >= 0 [m/s]; got {speed!r}")
        rows = np.array([self._scalar(v) for v in arr.ravel()]).reshape(*arr.shape, 11)
        cols = [rows[..., i] if arr.ndim else float(rows[i]) for i in range(11)]
        fn, rn, cf, r_f, r_app, r_w, r_b, r_tr, r_a, r_aa, total = cols
        return ResistanceComponents(
            speed=arr.copy() if arr.ndim else float(arr),
            froude_number=fn,
            reynolds_number=rn,
            friction_coefficient=cf,
            form_factor=float(self.form_factor),
            correlation_allowance=float(self.correlation_allowance),
            friction=r_f,
            appendage=r_app,
            wave=r_w,
            bulb=r_b,
            transom=r_tr,
            correlation=r_a,
            air=r_aa,
            total=total,
        )

    def viscous_resistance_coefficient(self, speed: float) -> float:
        """C_V = (1 + k) C_F + C_A [-], the input of Holtrop's wake-fraction regression.

        1 + k is the hull's form factor combined with the appendages' as Holtrop & Mennen
        (1982): 1 + k = 1 + k1 + [(1 + k2) − (1 + k1)] S_APP / S_tot, S_tot = S + S_APP.
        """
        v = max(abs(float(speed)), self.min_speed)
        cf = 0.075 / (math.log10(v * self._rn_per_speed) - 2.0) ** 2
        p = self.particulars
        s_tot = self.wetted_area + p.appendage_area
        k = self.form_factor + (p.appendage_form_factor - self.form_factor) * (
            p.appendage_area / s_tot
        )
        return k * cf + self.correlation_allowance

    # -- validity -------------------------------------------------------------------------------
    def range_report(self, speed: ArrayLike | None = None) -> tuple[str, ...]:
        """Violations of Holtrop & Mennen's (1982) Table-1 ranges (empty when inside).

        The hull form must fit at least one ship type (C_P, L/B, B/T); with ``speed`` [m/s],
        the largest Froude number also must not exceed the largest Fn_max of the fitting types.
        """
        p = self.particulars
        cp, l_b, b_t = p.prismatic_coefficient, p.length / p.beam, p.beam / p.draught
        fitting = [name for name, r in VALIDITY_RANGES.items() if r.fits(cp, l_b, b_t)]
        out: list[str] = []
        if not fitting:
            out.append(
                f"hull form C_P={cp:.3f}, L/B={l_b:.2f}, B/T={b_t:.2f} fits none of Holtrop & "
                f"Mennen's (1982) ship types {sorted(VALIDITY_RANGES)}"
            )
            fn_max = max(r.fn_max for r in VALIDITY_RANGES.values())
        else:
            fn_max = max(VALIDITY_RANGES[n].fn_max for n in fitting)
        if speed is not None:
            fn = float(np.max(np.abs(np.asarray(speed, dtype=float)))) * self._fn_per_speed
            if fn > fn_max + 1e-12:
                out.append(
                    f"Froude number {fn:.3f} exceeds Fn_max = {fn_max:.2f} of the ship types this "
                    f"form fits ({', '.join(fitting) or 'none'})"
                )
        return tuple(out)

    def check_range(
        self, speed: ArrayLike | None = None, on_out_of_range: OnOutOfRange = "warn"
    ) -> tuple[str, ...]:
        """Warn (:class:`HoltropRangeWarning`), raise ValueError or ignore range violations.

        Returns the :meth:`range_report`.
        """
        if on_out_of_range not in ("warn", "raise", "ignore"):
            raise ValueError(
                f"on_out_of_range must be 'warn', 'raise' or 'ignore'; got {on_out_of_range!r}"
            )
        report = self.range_report(speed)
        if report and on_out_of_range == "raise":
            raise ValueError("Holtrop–Mennen outside its range: " + "; ".join(report))
        if report and on_out_of_range == "warn":
            warnings.warn(
                "Holtrop–Mennen outside its range: " + "; ".join(report),
                HoltropRangeWarning,
                stacklevel=3,
            )
        return report

    @classmethod
    def from_hull(cls, hull: Hull, **kwargs) -> HoltropMennen:
        """The method for a hull: particulars by :meth:`ResistanceParticulars.from_hull`.

        Keyword arguments of :meth:`ResistanceParticulars.from_hull` (bulb, transom, stern
        shape, appendages, wetted area, entrance angle) and of this class (variant, form
        factor, …) may be mixed; ``rho`` and ``g`` default to the hull's.
        """
        part_keys = (
            "wetted_area", "bulb_area", "bulb_centre_height", "transom_area", "stern_shape",
            "appendage_area", "appendage_form_factor", "half_entrance_angle_deg",
        )  # fmt: skip
        part_kwargs = {k: kwargs.pop(k) for k in part_keys if k in kwargs}
        if not isinstance(hull, Hull):
            raise ValueError(f"hull must be a Hull; got {type(hull).__name__}")
        kwargs.setdefault("rho", hull.rho)
        kwargs.setdefault("g", hull.g)
        return cls(ResistanceParticulars.from_hull(hull, **part_kwargs), **kwargs)

    def __repr__(self) -> str:
        p = self.particulars
        return (
            f"HoltropMennen(variant={self.variant!r}, L={p.length:.4g} m, B={p.beam:.4g} m, "
            f"T={p.draught:.4g} m, C_B={p.block_coefficient:.4f}, 1+k1={self.form_factor:.4f}, "
            f"C_A={self.correlation_allowance:.3e})"
        )


# ------------------------------------------------------------------------------ force model
class CalmWaterResistance(ForceModel):
    """Calm-water resistance as a surge force: X = −R_T(|u|) sign(u), other components zero.

    The force acts along the body x axis through O (no moment: the resistance's line of action
    is taken at the origin's height; its small trimming moment is neglected). It depends on the
    instantaneous surge velocity u = ν[0] only — not on the linearisation speed of the radiation
    model, and not on v, r (the manoeuvring model's X_vv, X_vr, X_rr give the added resistance
    in turns).

    Parameters
    ----------
    model : HoltropMennen or callable
        R_T(U) [N] for U ≥ 0 [m/s]: a :class:`HoltropMennen` or any function of one float
        (e.g. an interpolated towing-tank curve); it must return a finite value ≥ 0.
    name : str, optional
        Key in the simulator's force breakdown (default ``"resistance"``).
    """

    def __init__(
        self,
        model: HoltropMennen | Callable[[float], float],
        *,
        name: str = "resistance",
    ) -> None:
        if isinstance(model, HoltropMennen):
            self.holtrop: HoltropMennen | None = model
            self._curve: Callable[[float], float] = model.total_scalar
        elif callable(model):
            self.holtrop = None
            self._curve = model
            probe = float(model(1.0))
            if not (math.isfinite(probe) and probe >= 0.0):
                raise ValueError(
                    f"model(1.0) must return a finite resistance >= 0 [N]; got {probe!r}"
                )
        else:
            raise ValueError(
                "model must be a HoltropMennen or a callable R_T(U) [N]; "
                f"got {type(model).__name__}"
            )
        if not isinstance(name, str) or not name:
            raise ValueError(f"name must be a non-empty string; got {name!r}")
        self.name = name

    def __repr__(self) -> str:
        return f"CalmWaterResistance({self.holtrop or self._curve!r}, name={self.name!r})"

    @property
    def curve(self) -> Callable[[float], float]:
        """The curve R_T(U) [N] for U ≥ 0 [m/s], read-only.

        :meth:`HoltropMennen.total_scalar` of :attr:`holtrop`, or the callable given.
        """
        return self._curve

    def kernel_parameters(self) -> np.ndarray:
        """Packed record of the Holtrop–Mennen method for :func:`holtrop_total` in ``@njit`` code.

        Returns
        -------
        numpy.ndarray
            (21,) float64, :meth:`HoltropMennen.kernel_parameters` of :attr:`holtrop`.

        Raises
        ------
        NotImplementedError
            If the model was built from a generic callable curve: it has no compiled form, and
            compiled code must fall back to calling :attr:`curve` from Python.
        """
        if self.holtrop is None:
            raise NotImplementedError(
                f"resistance model {self.name!r} is a generic callable curve "
                f"({self._curve!r}), which has no compiled form; only a Holtrop–Mennen-based "
                "CalmWaterResistance has kernel_parameters() — call .curve from Python instead"
            )
        return self.holtrop.kernel_parameters()

    def resistance(self, speed: ArrayLike) -> np.ndarray | float:
        """R_T(|U|) ≥ 0 [N] at speed(s) U [m/s] (the magnitude of the surge force)."""
        arr = np.asarray(speed)
        if arr.ndim == 0:
            return float(self._curve(abs(float(arr))))
        arr = np.abs(np.asarray(arr, dtype=float))
        return np.array([float(self._curve(v)) for v in arr.ravel()]).reshape(arr.shape)

    def surge_force(self, u: ArrayLike) -> np.ndarray | float:
        """X = −R_T(|u|) sign(u) [N] for surge velocity u [m/s]."""
        return _same_kind(-np.sign(np.asarray(u, dtype=float)) * self.resistance(u))

    def effective_power(self, speed: float) -> float:
        """P_E = R_T(U) U [W]."""
        return float(self.resistance(speed)) * abs(float(speed))

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Force (6,) [N] with only the surge component −R_T(|u|) sign(u); no states."""
        u = float(ctx.nu[SURGE])
        force = np.zeros(6)
        if u != 0.0:
            force[SURGE] = -math.copysign(float(self._curve(abs(u))), u)
        return force, np.zeros(0)

    @classmethod
    def from_hull(cls, hull: Hull, *, name: str = "resistance", **kwargs) -> CalmWaterResistance:
        """Holtrop–Mennen resistance of a hull (keywords: :meth:`HoltropMennen.from_hull`)."""
        return cls(HoltropMennen.from_hull(hull, **kwargs), name=name)


def resistance_curve(
    hull: Hull | HoltropMennen | CalmWaterResistance,
    speeds: ArrayLike,
    *,
    on_out_of_range: OnOutOfRange = "warn",
    **kwargs,
) -> ResistanceComponents:
    """Resistance components over a range of speeds, for tables and plots.

    Parameters
    ----------
    hull : Hull, HoltropMennen or CalmWaterResistance
        A hull (the method is built by :meth:`HoltropMennen.from_hull` with ``kwargs``), or an
        already built method / Holtrop-based force model.
    speeds : array_like
        Speeds U ≥ 0 [m/s].
    on_out_of_range : {"warn", "raise", "ignore"}, optional
        What to do when the hull form or the top speed lies outside Holtrop & Mennen's ranges.
    **kwargs
        Passed to :meth:`HoltropMennen.from_hull` when ``hull`` is a Hull.

    Returns
    -------
    ResistanceComponents
        Arrays of the speeds' shape.
    """
    if isinstance(hull, Hull):
        model = HoltropMennen.from_hull(hull, **kwargs)
    elif kwargs:
        raise ValueError(f"keyword arguments {sorted(kwargs)} only apply when hull is a Hull")
    elif isinstance(hull, HoltropMennen):
        model = hull
    elif isinstance(hull, CalmWaterResistance) and hull.holtrop is not None:
        model = hull.holtrop
    else:
        raise ValueError(
            "hull must be a Hull, a HoltropMennen or a Holtrop-based CalmWaterResistance; "
            f"got {type(hull).__name__}"
        )
    arr = np.atleast_1d(np.asarray(speeds, dtype=float))
    if arr.size == 0:
        raise ValueError("speeds must not be empty")
    model.check_range(arr, on_out_of_range)
    return model.components(arr)


__all__ = [
    "AIR_DRAG_COEFFICIENT",
    "MIN_REYNOLDS_NUMBER",
    "RHO_AIR",
    "VALIDITY_RANGES",
    "CalmWaterResistance",
    "HoltropMennen",
    "HoltropRangeWarning",
    "ResistanceComponents",
    "ResistanceParticulars",
    "ShipTypeRange",
    "froude_number",
    "holtrop_components",
    "holtrop_total",
    "holtrop_wave_resistance",
    "ittc57_friction_coefficient",
    "resistance_curve",
    "reynolds_number",
]


@nb.njit(cache=True, nogil=True, inline="always")
def resistance_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: X = −R_T(|u|) sign(u) [N] (Holtrop–Mennen, :func:`holtrop_total`), ``rec``
    a 1-tuple of the parameter array of :meth:`CalmWaterResistance.kernel_parameters`."""
    u = v[0]
    if u != 0.0:
        out[0] += -math.copysign(holtrop_total(rec[0], abs(u)), u)
