"""Viscous roll damping: Ikeda's component method and a linear + quadratic roll damping force.

Potential flow (the BEM database) gives the wave-making part of the roll damping, which for a
ship at its roll resonance is a small fraction of the total; the rest is viscous. This module
estimates the viscous parts with Ikeda's component-discrete method, reduces them to a linear +
quadratic law, and applies that law as a force model.

Damping law and equivalent linearisation
----------------------------------------
The roll damping moment about the body x axis is

    M = −(B1 p + B2 |p| p),                                                       (1)

with p the roll rate [rad/s], B1 [N·m·s/rad] and B2 [N·m·s²/rad²]. For a harmonic roll
φ = φa cos ωt, the linear damping that dissipates the same energy per cycle is (ITTC 7.5-02-07-04.5,
§3.2)

    B44_eq(φa, ω) = B1 + (8/(3π)) ω φa B2.                                         (2)

Nondimensional forms (ITTC 7.5-02-07-04.5, §3; Ikeda, Himeno & Tanaka 1978), with ∇ the
displaced volume and B the beam:

    B̂ = B44 / (ρ ∇ B²) · √(B/(2g)),   B̂1 likewise,   B̂2 = B2 / (ρ ∇ B²),   ω̂ = ω √(B/(2g)),

so that B̂_eq = B̂1 + (8/(3π)) ω̂ φa B̂2.

Ikeda's components (equivalent linear, at roll amplitude φa and frequency ω)
---------------------------------------------------------------------------
The method is the *simplified Ikeda method* of Kawahara, Maekawa & Ikeda (2009) — regression
formulas fitted to Ikeda's original component method (Ikeda, Himeno & Tanaka 1978; Himeno 1981)
over a systematic series of cargo-ship forms — completed by Ikeda's original forward-speed
formulas (Himeno 1981; ITTC 7.5-02-07-04.5 §2.2):

* **Friction** B_F (Kato 1958, as used by Ikeda): B_F0 = (4/(3π)) ρ S_f r_f³ φa ω C_f with
  S_f = L (1.75 d + C_b B) (Kawahara et al.) or a given wetted area, the mean lever
  r_f = d [(0.887 + 0.145 C_b)(1.7 + C_b B/d) − 2 OG/d] / π, and
  C_f = 1.328 R_n^{−1/2} (+ 0.014 R_n^{−0.114}, Himeno's turbulent term, on by default),
  R_n = 0.512 (r_f φa)² ω / ν. Speed (Tamiya & Komura): B_F = B_F0 (1 + 4.1 U/(ω L)).
* **Eddy making** B_E (hull without appendages, Kawahara et al. regression of Ikeda's
  formula): B̂_E0 = 4 ω̂ φa C_R / (3π C_b (B/d)³) with
  C_R = A_E exp(B_E1 + B_E2 C_m^{B_E3}) and the polynomials A_E, B_E1..3 of C_b, B/d, OG/d.
  Speed (Ikeda, Himeno & Tanaka 1978): B_E = B_E0 (0.04K)²/(1 + (0.04K)²), K = ω L/U.
* **Hull lift** B_L (Ikeda, Himeno & Tanaka 1978; zero at U = 0):
  B_L = ½ ρ L d U k_N l_o l_R [1 − 1.4 OG/l_R + 0.7 OG²/(l_o l_R)], l_o = 0.3 d, l_R = 0.5 d,
  k_N = 2π d/L + κ (4.1 B/L − 0.045), κ = 0 (C_m ≤ 0.92), 0.1 (0.92 < C_m ≤ 0.97),
  0.3 (C_m > 0.97).
* **Bilge keels** B_BK (normal-force and hull-pressure parts, Kawahara et al. regression):
  B̂_BK = A_BK exp(B_BK1 + B_BK2 C_m^{B_BK3}) ω̂ with A_BK, B_BK1..3 functions of C_b, B/d, OG/d,
  b_BK/B, l_BK/L and φa [deg]; taken speed-independent (Ikeda: the normal-force component
  hardly changes with speed).
* **Wave making** B_W is *not* included: the BEM radiation damping already contains it.

OG is the distance of the roll axis (taken through G) below the calm waterline, positive
downward — in our body frame (origin on the waterline, z down) OG = z_G.

Validity (Kawahara, Maekawa & Ikeda 2009, their table of the regression ranges):
0.5 ≤ C_b ≤ 0.85, 2.5 ≤ B/d ≤ 4.5, −1.5 ≤ OG/d ≤ 0.2, 0.9 ≤ C_m ≤ 0.99, ω̂ ≤ 1.0 and, with
bilge keels, 0.01 ≤ b_BK/B ≤ 0.06, 0.05 ≤ l_BK/L ≤ 0.4. Outside them the formulas are
extrapolated; :func:`ikeda_roll_damping` reports each violation (``out_of_range``) and warns
(:class:`IkedaRangeWarning`), raises, or stays silent as asked.

Split into B1 and B2
--------------------
:func:`fit_linear_quadratic` evaluates the equivalent linear damping of all components at two or
more roll amplitudes and fits eq. (2) by least squares. Friction and lift do not depend (lift) or
hardly depend (friction: ∝ φa^{−0.23} with the turbulent term, constant without it) on φa, so they
go to B1; the eddy component is ∝ ω φa and goes to B2; the bilge-keel regression has a part
independent of φa (the constant 0.4794 of its amplitude polynomial, which reflects Ikeda's drag
coefficient C_D = 22.5 b_BK/(π l φa f) + 2.4: its 1/φa part gives a moment linear in p) and parts
growing with φa, so it feeds both. With the default amplitudes 5°–20° the fit reproduces the
equivalent damping within a few per cent; for a simulation at other amplitudes, pass those.

References
----------
Ikeda, Y., Himeno, Y. & Tanaka, N. (1978). A prediction method for ship roll damping. Report
no. 00405, Department of Naval Architecture, University of Osaka Prefecture.
Himeno, Y. (1981). Prediction of ship roll damping — state of the art. Report no. 239,
Department of Naval Architecture and Marine Engineering, University of Michigan.
Kato, H. (1958). On the frictional resistance to the rolling of ships. J. Zosen Kiokai 102.
Kawahara, Y., Maekawa, K. & Ikeda, Y. (2009). A simple prediction formula of roll damping of
conventional cargo ships on the basis of Ikeda's method and its limitation. Proc. 10th Int. Conf.
on Stability of Ships and Ocean Vehicles (STAB 2009), St Petersburg, 387–398; also J. Shipping
and Ocean Engineering 2 (2012) 201–210.
ITTC (2011). Recommended Procedure 7.5-02-07-04.5, Numerical estimation of roll damping.
IMO (2008). International Code on Intact Stability (2008 IS Code), Part A, 2.3.4 (roll period).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Literal

import numba as nb
import numpy as np
from numpy.typing import ArrayLike

from ship_gym.conventions import GRAVITY, RHO_SEAWATER, ROLL
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.hull.hull import Hull
from ship_gym.hull.hydrostatics import hydrostatics

KINEMATIC_VISCOSITY_SEAWATER: float = 1.1883e-6
"""Kinematic viscosity of sea water at 15 °C, salinity 35 g/kg [m²/s] (ITTC 7.5-02-01-03)."""

EIGHT_OVER_THREE_PI: float = 8.0 / (3.0 * math.pi)
"""Factor of the equivalent linearisation of |p| p (eq. 2) [-]."""

DEFAULT_ROLL_AMPLITUDES: tuple[float, ...] = tuple(math.radians(a) for a in (5.0, 10.0, 15.0, 20.0))
"""Roll amplitudes of the default linear + quadratic fit: 5°, 10°, 15°, 20° [rad]."""

OnOutOfRange = Literal["warn", "raise", "ignore"]

VALIDITY_RANGES: dict[str, tuple[float, float]] = {
    "Cb": (0.5, 0.85),
    "B/d": (2.5, 4.5),
    "OG/d": (-1.5, 0.2),
    "Cm": (0.9, 0.99),
    "omega_hat": (0.0, 1.0),
    "bBK/B": (0.01, 0.06),
    "lBK/L": (0.05, 0.4),
}
"""Ranges of the simplified Ikeda method's regressions (Kawahara, Maekawa & Ikeda 2009)."""


class IkedaRangeWarning(UserWarning):
    """A parameter lies outside the range of the simplified Ikeda regressions."""


# ------------------------------------------------------------------------------ helpers
def _positive(name: str, value: float, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a positive number [{unit}]; got {value!r}") from None
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be a positive finite number [{unit}]; got {value!r}")
    return v


def _finite(name: str, value: float, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number [{unit}]; got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite [{unit}]; got {value!r}")
    return v


def _nonnegative(name: str, value: float, unit: str) -> float:
    v = _finite(name, value, unit)
    if v < 0.0:
        raise ValueError(f"{name} must be >= 0 [{unit}]; got {value!r}")
    return v


def nondimensional_roll_damping(
    damping: float, *, rho: float, volume: float, beam: float, g: float = GRAVITY, order: int = 1
) -> float:
    """Nondimensional roll damping coefficient (ITTC 7.5-02-07-04.5).

    B̂1 = B1/(ρ∇B²) √(B/(2g)) for ``order=1`` (linear or equivalent-linear damping),
    B̂2 = B2/(ρ∇B²) for ``order=2`` (quadratic damping).

    Parameters
    ----------
    damping : float
        B1 [N·m·s/rad] or B2 [N·m·s²/rad²].
    rho : float
        Water density [kg/m³].
    volume : float
        Displaced volume ∇ [m³].
    beam : float
        Beam B [m].
    g : float, optional
        Gravitational acceleration [m/s²].
    order : {1, 2}
        Power of the roll rate in the damping term.
    """
    scale = _roll_scale(rho, volume, beam, g, order)
    return _finite("damping", damping, "SI") / scale


def dimensional_roll_damping(
    damping_hat: float,
    *,
    rho: float,
    volume: float,
    beam: float,
    g: float = GRAVITY,
    order: int = 1,
) -> float:
    """Inverse of :func:`nondimensional_roll_damping`: B [SI] from B̂ [-]."""
    return _finite("damping_hat", damping_hat, "-") * _roll_scale(rho, volume, beam, g, order)


def _roll_scale(rho: float, volume: float, beam: float, g: float, order: int) -> float:
    rho = _positive("rho", rho, "kg/m^3")
    volume = _positive("volume", volume, "m^3")
    beam = _positive("beam", beam, "m")
    g = _positive("g", g, "m/s^2")
    if order == 1:
        return rho * volume * beam**2 * math.sqrt(2.0 * g / beam)
    if order == 2:
        return rho * volume * beam**2
    raise ValueError(f"order must be 1 (linear) or 2 (quadratic); got {order!r}")


def critical_roll_damping(inertia: float, stiffness: float) -> float:
    """Critical damping 2√((I44 + A44) C44) [N·m·s/rad] of a 1-DOF roll oscillator.

    Parameters
    ----------
    inertia : float
        Total roll inertia I44 + A44 about the roll axis [kg·m²].
    stiffness : float
        Roll restoring C44 = ρ g ∇ GM [N·m/rad].
    """
    return 2.0 * math.sqrt(
        _positive("inertia", inertia, "kg m^2") * _positive("stiffness", stiffness, "N m/rad")
    )


def imo_roll_period(beam: float, draught: float, length: float, gm: float) -> float:
    """Natural roll period T = 2 C B/√GM [s] of the IMO 2008 IS Code (Part A, 2.3.4).

    C = 0.373 + 0.023 (B/d) − 0.043 (L_wl/100), lengths in metres.

    Parameters
    ----------
    beam, draught, length : float
        Moulded breadth B, mean draught d and waterline length L_wl [m].
    gm : float
        Metacentric height GM [m] (> 0).
    """
    b = _positive("beam", beam, "m")
    d = _positive("draught", draught, "m")
    lwl = _positive("length", length, "m")
    gm = _positive("gm", gm, "m")
    c = 0.373 + 0.023 * b / d - 0.043 * lwl / 100.0
    if c <= 0.0:
        raise ValueError(f"IMO roll coefficient C = {c:.4g} <= 0 for L = {lwl} m, B/d = {b / d}")
    return 2.0 * c * b / math.sqrt(gm)


def midship_section_area(hull: Hull, x: float = 0.0) -> float:
    """Immersed area of the hull's transverse section at body x [m²] (design waterline).

    The immersed mesh is cut by the plane x = const; each cut segment is oriented along
    n × e_x (n the outward panel normal), so that the segments form the section contour with one
    orientation and the area is ½ ∮ (y dz − z dy); the open side on the waterline z = 0 adds
    nothing. The plane is nudged by 1e-9 L to avoid vertices lying exactly on it.
    """
    mesh = hull.immersed_mesh
    tri, owner = mesh.triangles_with_owner
    normals = mesh.normals[owner]
    x0 = float(x) + 1e-9 * hull.particulars.lpp
    s = tri[:, :, 0] - x0
    cut = (s.min(axis=1) < 0.0) & (s.max(axis=1) > 0.0)
    tri, s, normals = tri[cut], s[cut], normals[cut]
    points = []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        sa, sb = s[:, a], s[:, b]
        crosses = (sa < 0.0) != (sb < 0.0)
        frac = np.where(crosses, sa / np.where(crosses, sa - sb, 1.0), np.nan)
        p = tri[:, a] + frac[:, None] * (tri[:, b] - tri[:, a])
        points.append(np.where(crosses[:, None], p, np.nan))
    pts = np.stack(points, axis=1)  # (n, 3 edges, 3); exactly two edges cross
    ok = ~np.isnan(pts[:, :, 0])
    if not np.all(ok.sum(axis=1) == 2):
        raise ValueError(f"degenerate cut of the hull mesh at x = {x} m")
    seg = pts[ok].reshape(-1, 2, 3)
    tangent = np.cross(normals, np.array([1.0, 0.0, 0.0]))
    flip = np.einsum("ij,ij->i", seg[:, 1] - seg[:, 0], tangent) < 0.0
    seg[flip] = seg[flip][:, ::-1]
    y0, z0, y1, z1 = seg[:, 0, 1], seg[:, 0, 2], seg[:, 1, 1], seg[:, 1, 2]
    return float(abs(0.5 * np.sum(y0 * z1 - y1 * z0)))


# ------------------------------------------------------------------------------ value objects
@dataclass(frozen=True)
class RollDampingCoefficients:
    """Linear and quadratic roll damping of eq. (1): M = −(B1 p + B2 |p| p).

    Parameters
    ----------
    b1 : float
        Linear coefficient B1 ≥ 0 [N·m·s/rad].
    b2 : float, optional
        Quadratic coefficient B2 ≥ 0 [N·m·s²/rad²].
    """

    b1: float
    b2: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "b1", _nonnegative("b1", self.b1, "N m s/rad"))
        object.__setattr__(self, "b2", _nonnegative("b2", self.b2, "N m s^2/rad^2"))

    def moment(self, roll_rate: ArrayLike) -> np.ndarray | float:
        """Damping moment M = −(B1 p + B2 |p| p) [N·m] at roll rate p [rad/s]."""
        p = np.asarray(roll_rate, dtype=float)
        out = -(self.b1 * p + self.b2 * np.abs(p) * p)
        return float(out) if out.ndim == 0 else out

    def equivalent_linear(self, roll_amplitude: float, omega: float) -> float:
        """Equivalent linear damping B1 + (8/(3π)) ω φa B2 [N·m·s/rad] (eq. 2).

        Parameters
        ----------
        roll_amplitude : float
            Roll amplitude φa ≥ 0 [rad].
        omega : float
            Roll frequency ω > 0 [rad/s].
        """
        phi = _nonnegative("roll_amplitude", roll_amplitude, "rad")
        w = _positive("omega", omega, "rad/s")
        return self.b1 + EIGHT_OVER_THREE_PI * w * phi * self.b2

    def nondimensional(
        self, *, rho: float, volume: float, beam: float, g: float = GRAVITY
    ) -> tuple[float, float]:
        """(B̂1, B̂2) of ITTC 7.5-02-07-04.5 (:func:`nondimensional_roll_damping`) [-]."""
        kw = {"rho": rho, "volume": volume, "beam": beam, "g": g}
        return (
            nondimensional_roll_damping(self.b1, order=1, **kw),
            nondimensional_roll_damping(self.b2, order=2, **kw),
        )

    @classmethod
    def from_nondimensional(
        cls,
        b1_hat: float,
        b2_hat: float = 0.0,
        *,
        rho: float,
        volume: float,
        beam: float,
        g: float = GRAVITY,
    ) -> RollDampingCoefficients:
        """Coefficients from their nondimensional values B̂1, B̂2 [-]."""
        kw = {"rho": rho, "volume": volume, "beam": beam, "g": g}
        return cls(
            dimensional_roll_damping(b1_hat, order=1, **kw),
            dimensional_roll_damping(b2_hat, order=2, **kw),
        )


@dataclass(frozen=True)
class BilgeKeel:
    """A pair of bilge keels (one each side).

    Parameters
    ----------
    length : float
        Length l_BK of each keel [m].
    breadth : float
        Breadth (height normal to the hull) b_BK [m].
    x_centre : float, optional
        Body x of the keels' mid-length [m] (0: centred amidships). The regression assumes keels
        on the parallel middle body; the position is only checked to lie on the hull.
    """

    length: float
    breadth: float
    x_centre: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "length", _positive("bilge keel length", self.length, "m"))
        object.__setattr__(self, "breadth", _positive("bilge keel breadth", self.breadth, "m"))
        object.__setattr__(self, "x_centre", _finite("bilge keel x_centre", self.x_centre, "m"))


@dataclass(frozen=True)
class RollDampingParticulars:
    """Main particulars used by the Ikeda method.

    Parameters
    ----------
    lpp : float
        Length between perpendiculars L [m].
    beam : float
        Beam B [m].
    draught : float
        Draught d [m].
    block_coefficient : float
        C_b = ∇/(L B d) [-].
    midship_coefficient : float
        C_m = A_M/(B d) [-].
    og : float
        Distance of the roll axis (through G) below the calm waterline, positive downward [m];
        equals z_G in ship_gym's body frame.
    wetted_area : float, optional
        Wetted hull area S_f [m²]; default the Kawahara et al. estimate L (1.75 d + C_b B).
    rho : float, optional
        Water density [kg/m³].
    g : float, optional
        Gravitational acceleration [m/s²].
    kinematic_viscosity : float, optional
        ν [m²/s].
    """

    lpp: float
    beam: float
    draught: float
    block_coefficient: float
    midship_coefficient: float
    og: float
    wetted_area: float | None = None
    rho: float = RHO_SEAWATER
    g: float = GRAVITY
    kinematic_viscosity: float = KINEMATIC_VISCOSITY_SEAWATER

    def __post_init__(self) -> None:
        for name, unit in (
            ("lpp", "m"),
            ("beam", "m"),
            ("draught", "m"),
            ("rho", "kg/m^3"),
            ("g", "m/s^2"),
            ("kinematic_viscosity", "m^2/s"),
        ):
            object.__setattr__(self, name, _positive(name, getattr(self, name), unit))
        for name in ("block_coefficient", "midship_coefficient"):
            v = _positive(name, getattr(self, name), "-")
            if v > 1.0:
                raise ValueError(f"{name} must lie in (0, 1]; got {v!r}")
            object.__setattr__(self, name, v)
        object.__setattr__(self, "og", _finite("og", self.og, "m"))
        if self.wetted_area is not None:
            object.__setattr__(
                self, "wetted_area", _positive("wetted_area", self.wetted_area, "m^2")
            )

    @property
    def volume(self) -> float:
        """Displaced volume ∇ = C_b L B d [m³]."""
        return self.block_coefficient * self.lpp * self.beam * self.draught

    @property
    def friction_area(self) -> float:
        """Wetted area S_f used by the friction component [m²]."""
        if self.wetted_area is not None:
            return self.wetted_area
        return self.lpp * (1.75 * self.draught + self.block_coefficient * self.beam)

    @classmethod
    def from_hull(
        cls, hull: Hull, *, kinematic_viscosity: float = KINEMATIC_VISCOSITY_SEAWATER
    ) -> RollDampingParticulars:
        """Particulars of a :class:`~ship_gym.hull.hull.Hull` at its design waterline.

        C_b from the mesh's displaced volume, C_m from its midship section
        (:func:`midship_section_area`), S_f the area of the immersed mesh, OG = z_G.
        """
        p = hull.particulars
        volume = hydrostatics(hull).volume
        return cls(
            lpp=p.lpp,
            beam=p.beam,
            draught=p.draught,
            block_coefficient=volume / (p.lpp * p.beam * p.draught),
            midship_coefficient=midship_section_area(hull) / (p.beam * p.draught),
            og=float(hull.mass.cog[2]),
            wetted_area=float(hull.immersed_mesh.areas.sum()),
            rho=hull.rho,
            g=hull.g,
            kinematic_viscosity=kinematic_viscosity,
        )


@dataclass(frozen=True)
class IkedaRollDamping:
    """Equivalent-linear viscous roll damping components at one (ω, φa, U) [N·m·s/rad].

    Attributes
    ----------
    friction, eddy, lift, bilge_keel : float
        B_F, B_E, B_L, B_BK [N·m·s/rad] (wave making excluded: it is in the BEM damping).
    omega : float
        Roll frequency [rad/s].
    roll_amplitude : float
        φa [rad].
    forward_speed : float
        U [m/s].
    particulars : RollDampingParticulars
        The particulars used.
    out_of_range : tuple of str
        Description of each parameter outside :data:`VALIDITY_RANGES` (empty if none).
    """

    friction: float
    eddy: float
    lift: float
    bilge_keel: float
    omega: float
    roll_amplitude: float
    forward_speed: float
    particulars: RollDampingParticulars
    out_of_range: tuple[str, ...] = field(default_factory=tuple)

    @property
    def total(self) -> float:
        """B_F + B_E + B_L + B_BK [N·m·s/rad]."""
        return self.friction + self.eddy + self.lift + self.bilge_keel

    def nondimensional(self) -> dict[str, float]:
        """B̂ of each component and of the total (keys as the attributes, plus ``"total"``)."""
        p = self.particulars
        names = ("friction", "eddy", "lift", "bilge_keel", "total")
        return {
            n: nondimensional_roll_damping(
                getattr(self, n), rho=p.rho, volume=p.volume, beam=p.beam, g=p.g, order=1
            )
            for n in names
        }


# ------------------------------------------------------------------------------ Ikeda method
def _particulars(ship: Hull | RollDampingParticulars) -> RollDampingParticulars:
    if isinstance(ship, RollDampingParticulars):
        return ship
    if isinstance(ship, Hull):
        return RollDampingParticulars.from_hull(ship)
    raise ValueError(f"ship must be a Hull or RollDampingParticulars; got {type(ship).__name__}")


def _lift_kappa(cm: float) -> float:
    """κ of Ikeda's hull-lift slope k_N as a function of C_m (Himeno 1981)."""
    if cm <= 0.92:
        return 0.0
    if cm <= 0.97:
        return 0.1
    return 0.3


def _range_report(
    p: RollDampingParticulars, omega_hat: float, bilge_keel: BilgeKeel | None
) -> tuple[str, ...]:
    values = {
        "Cb": p.block_coefficient,
        "B/d": p.beam / p.draught,
        "OG/d": p.og / p.draught,
        "Cm": p.midship_coefficient,
        "omega_hat": omega_hat,
    }
    if bilge_keel is not None:
        values["bBK/B"] = bilge_keel.breadth / p.beam
        values["lBK/L"] = bilge_keel.length / p.lpp
    out = []
    for key, value in values.items():
        lo, hi = VALIDITY_RANGES[key]
        if not lo <= value <= hi:
            out.append(f"{key} = {value:.4g} outside [{lo}, {hi}]")
    return tuple(out)


def _handle_range(report: tuple[str, ...], on_out_of_range: OnOutOfRange) -> None:
    if not report or on_out_of_range == "ignore":
        return
    message = (
        "simplified Ikeda method (Kawahara, Maekawa & Ikeda 2009) used outside its validity "
        "ranges: " + "; ".join(report)
    )
    if on_out_of_range == "raise":
        raise ValueError(message)
    warnings.warn(message, IkedaRangeWarning, stacklevel=3)


def _check_on_out_of_range(on_out_of_range: str) -> None:
    if on_out_of_range not in ("warn", "raise", "ignore"):
        raise ValueError(
            f"on_out_of_range must be 'warn', 'raise' or 'ignore'; got {on_out_of_range!r}"
        )


def _ikeda(
    p: RollDampingParticulars,
    omega: float,
    phi: float,
    speed: float,
    bilge_keel: BilgeKeel | None,
    turbulent_friction: bool,
) -> IkedaRollDamping:
    L, B, d = p.lpp, p.beam, p.draught
    cb, cm = p.block_coefficient, p.midship_coefficient
    bd, ogd = B / d, p.og / d
    omega_hat = omega * math.sqrt(B / (2.0 * p.g))
    to_dim = p.rho * p.volume * B**2 * math.sqrt(2.0 * p.g / B)  # B = B̂ · to_dim
    phi_deg = math.degrees(phi)

    # friction (Kato; Ikeda's lever r_f; Himeno's turbulent term; Tamiya-Komura speed factor)
    r_f = d * ((0.887 + 0.145 * cb) * (1.7 + cb * bd) - 2.0 * ogd) / math.pi
    rn = 0.512 * (r_f * phi) ** 2 * omega / p.kinematic_viscosity
    c_f = 1.328 * rn**-0.5 + (0.014 * rn**-0.114 if turbulent_friction else 0.0)
    b_f = 4.0 / (3.0 * math.pi) * p.rho * p.friction_area * r_f**3 * phi * omega * c_f
    b_f *= 1.0 + 4.1 * speed / (omega * L)

    # eddy making (Kawahara et al. regression of Ikeda's C_R; Ikeda's speed reduction)
    f_e1 = (-0.0182 * cb + 0.0155) * (bd - 1.8) ** 3
    f_e2 = -79.414 * cb**4 + 215.695 * cb**3 - 215.883 * cb**2 + 93.894 * cb - 14.848
    a_e = f_e1 + f_e2
    b_e1 = (
        (3.98 * cb - 5.1525)
        * (-0.2 * bd + 1.6)
        * ogd
        * ((0.9717 * cb**2 - 1.55 * cb + 0.723) * ogd + 0.04567 * cb + 0.9408)
    )
    b_e2 = (0.25 * ogd + 0.95) * ogd - 219.2 * cb**3 + 443.7 * cb**2 - 283.3 * cb + 59.6
    b_e3 = -15.0 * cb * bd + 46.5 * cb + 11.2 * bd - 28.6
    c_r = a_e * math.exp(b_e1 + b_e2 * cm**b_e3)
    b_e = 4.0 * omega_hat * phi * c_r / (3.0 * math.pi * cb * bd**3) * to_dim
    if speed > 0.0:
        k2 = (0.04 * omega * L / speed) ** 2
        b_e *= k2 / (1.0 + k2)

    # hull lift (Ikeda, Himeno & Tanaka 1978)
    l_o, l_r = 0.3 * d, 0.5 * d
    k_n = 2.0 * math.pi * d / L + _lift_kappa(cm) * (4.1 * B / L - 0.045)
    og = p.og
    b_l = (
        0.5
        * p.rho
        * L
        * d
        * speed
        * k_n
        * l_o
        * l_r
        * (1.0 - 1.4 * og / l_r + 0.7 * og**2 / (l_o * l_r))
    )

    # bilge keels (Kawahara et al. regression)
    b_bk = 0.0
    if bilge_keel is not None:
        bb, lb = bilge_keel.breadth / B, bilge_keel.length / L
        f_bk1 = (-0.3651 * cb + 0.3907) * (bd - 2.83) ** 2 - 2.21 * cb + 2.632
        f_bk2 = 0.00255 * phi_deg**2 + 0.122 * phi_deg + 0.4794
        f_bk3 = (-0.8913 * bb**2 - 0.0733 * bb) * lb**2 + (
            5.2857 * bb**2 - 0.01185 * bb + 0.00189
        ) * lb
        a_bk = f_bk1 * f_bk2 * f_bk3
        b_bk1 = (
            5.0 * bb + 0.3 * bd - 0.2 * lb + 0.00125 * phi_deg**2 - 0.0425 * phi_deg - 1.86
        ) * ogd
        b_bk2 = -15.0 * bb + 1.2 * cb - 0.1 * bd - 0.0657 * ogd**2 + 0.0586 * ogd + 1.6164
        b_bk3 = 2.5 * ogd + 15.75
        b_bk = a_bk * math.exp(b_bk1 + b_bk2 * cm**b_bk3) * omega_hat * to_dim

    return IkedaRollDamping(
        friction=b_f,
        eddy=b_e,
        lift=b_l,
        bilge_keel=b_bk,
        omega=omega,
        roll_amplitude=phi,
        forward_speed=speed,
        particulars=p,
        out_of_range=_range_report(p, omega_hat, bilge_keel),
    )


def _validate_inputs(
    p: RollDampingParticulars,
    omega: float,
    roll_amplitude: float,
    forward_speed: float,
    bilge_keel: BilgeKeel | None,
) -> tuple[float, float, float]:
    w = _positive("omega", omega, "rad/s")
    phi = _positive("roll_amplitude", roll_amplitude, "rad")
    if phi >= math.pi / 2:
        raise ValueError(f"roll_amplitude must be below pi/2 [rad]; got {roll_amplitude!r}")
    u = _nonnegative("forward_speed", forward_speed, "m/s")
    if bilge_keel is not None:
        if not isinstance(bilge_keel, BilgeKeel):
            raise ValueError(
                f"bilge_keel must be a BilgeKeel or None; got {type(bilge_keel).__name__}"
            )
        half = 0.5 * p.lpp
        ends = (
            bilge_keel.x_centre - 0.5 * bilge_keel.length,
            bilge_keel.x_centre + 0.5 * bilge_keel.length,
        )
        if ends[0] < -half - 1e-9 or ends[1] > half + 1e-9:
            raise ValueError(
                f"bilge keel from x = {ends[0]:.4g} to {ends[1]:.4g} m extends beyond the hull "
                f"(-{half:.4g}..{half:.4g} m); expected it within Lpp"
            )
    return w, phi, u


def ikeda_roll_damping(
    ship: Hull | RollDampingParticulars,
    *,
    omega: float,
    roll_amplitude: float,
    forward_speed: float = 0.0,
    bilge_keel: BilgeKeel | None = None,
    turbulent_friction: bool = True,
    on_out_of_range: OnOutOfRange = "warn",
) -> IkedaRollDamping:
    """Viscous roll damping components by the simplified Ikeda method (module docstring).

    Parameters
    ----------
    ship : Hull or RollDampingParticulars
        The hull (particulars derived with :meth:`RollDampingParticulars.from_hull`) or its
        particulars.
    omega : float
        Roll frequency ω > 0 [rad/s] (usually the natural roll frequency).
    roll_amplitude : float
        Roll amplitude 0 < φa < π/2 [rad].
    forward_speed : float, optional
        Ship speed U ≥ 0 [m/s].
    bilge_keel : BilgeKeel, optional
        Bilge keels; None for a bare hull.
    turbulent_friction : bool, optional
        Add Himeno's turbulent term 0.014 R_n^{−0.114} to Kato's laminar C_f (full scale).
    on_out_of_range : {"warn", "raise", "ignore"}, optional
        What to do when a parameter is outside :data:`VALIDITY_RANGES`: warn
        (:class:`IkedaRangeWarning`), raise ValueError, or nothing. The violations are always
        listed in the result's ``out_of_range``.

    Returns
    -------
    IkedaRollDamping
        Equivalent-linear components [N·m·s/rad].

    Raises
    ------
    ValueError
        For non-physical inputs, a bilge keel longer than the hull, or (``on_out_of_range=
        "raise"``) parameters outside the regression ranges.
    """
    _check_on_out_of_range(on_out_of_range)
    p = _particulars(ship)
    w, phi, u = _validate_inputs(p, omega, roll_amplitude, forward_speed, bilge_keel)
    result = _ikeda(p, w, phi, u, bilge_keel, bool(turbulent_friction))
    _handle_range(result.out_of_range, on_out_of_range)
    return result


def linear_quadratic_from_equivalent(
    roll_amplitudes: ArrayLike, equivalent_damping: ArrayLike, omega: float
) -> RollDampingCoefficients:
    """Least-squares B1, B2 ≥ 0 of B_eq(φa) = B1 + (8/(3π)) ω φa B2 (eq. 2).

    Parameters
    ----------
    roll_amplitudes : array_like
        (n ≥ 2,) distinct roll amplitudes φa > 0 [rad].
    equivalent_damping : array_like
        (n,) equivalent linear damping at each amplitude [N·m·s/rad].
    omega : float
        Roll frequency [rad/s].

    Returns
    -------
    RollDampingCoefficients
        The fit; if the unconstrained fit has a negative coefficient it is refitted with that
        coefficient held at zero.
    """
    phi = np.asarray(roll_amplitudes, dtype=float).reshape(-1)
    b_eq = np.asarray(equivalent_damping, dtype=float).reshape(-1)
    w = _positive("omega", omega, "rad/s")
    if phi.shape != b_eq.shape:
        raise ValueError(
            f"roll_amplitudes {phi.shape} and equivalent_damping {b_eq.shape} differ in shape"
        )
    if len(np.unique(phi)) < 2 or np.any(~np.isfinite(phi)) or np.any(phi <= 0.0):
        raise ValueError(
            f"need at least two distinct positive finite roll amplitudes [rad]; got {phi}"
        )
    if np.any(~np.isfinite(b_eq)):
        raise ValueError(f"equivalent_damping must be finite; got {b_eq}")
    x = EIGHT_OVER_THREE_PI * w * phi
    design = np.column_stack([np.ones_like(x), x])
    (b1, b2), *_ = np.linalg.lstsq(design, b_eq, rcond=None)
    if b2 < 0.0:
        b1, b2 = max(float(np.mean(b_eq)), 0.0), 0.0
    elif b1 < 0.0:
        b1, b2 = 0.0, max(float(x @ b_eq / (x @ x)), 0.0)
    return RollDampingCoefficients(float(b1), float(b2))


def fit_linear_quadratic(
    ship: Hull | RollDampingParticulars,
    *,
    omega: float,
    roll_amplitudes: ArrayLike = DEFAULT_ROLL_AMPLITUDES,
    forward_speed: float = 0.0,
    bilge_keel: BilgeKeel | None = None,
    turbulent_friction: bool = True,
    on_out_of_range: OnOutOfRange = "warn",
) -> RollDampingCoefficients:
    """B1, B2 of eq. (1) from Ikeda's equivalent linear damping at several roll amplitudes.

    The total B_F + B_E + B_L + B_BK is evaluated at each amplitude and fitted with
    :func:`linear_quadratic_from_equivalent` (the split is described in the module docstring).

    Parameters
    ----------
    ship : Hull or RollDampingParticulars
        See :func:`ikeda_roll_damping`.
    omega : float
        Roll frequency [rad/s].
    roll_amplitudes : array_like, optional
        At least two distinct amplitudes [rad] (default 5°, 10°, 15°, 20°).
    forward_speed, bilge_keel, turbulent_friction, on_out_of_range
        See :func:`ikeda_roll_damping` (one warning at most for the whole fit).
    """
    _check_on_out_of_range(on_out_of_range)
    p = _particulars(ship)
    phis = np.asarray(roll_amplitudes, dtype=float).reshape(-1)
    if phis.size < 2:
        raise ValueError(f"need at least two roll amplitudes [rad]; got {roll_amplitudes!r}")
    results = []
    for phi in phis:
        w, ph, u = _validate_inputs(p, omega, phi, forward_speed, bilge_keel)
        results.append(_ikeda(p, w, ph, u, bilge_keel, bool(turbulent_friction)))
    report = tuple(dict.fromkeys(m for r in results for m in r.out_of_range))
    _handle_range(report, on_out_of_range)
    return linear_quadratic_from_equivalent(phis, [r.total for r in results], omega)


# ------------------------------------------------------------------------------ force model
class ViscousRollDamping(ForceModel):
    """Viscous roll damping force: (0, 0, 0, −(B1 p + B2 |p| p), 0, 0), p = ν[3].

    The coefficients hold for the speed and frequency they were estimated at; they act on the
    body roll rate and on roll only.

    Parameters
    ----------
    coefficients : RollDampingCoefficients
        B1 [N·m·s/rad], B2 [N·m·s²/rad²].
    name : str, optional
        Key in the simulator's force breakdown (default ``"viscous_roll"``).
    """

    def __init__(
        self, coefficients: RollDampingCoefficients, *, name: str = "viscous_roll"
    ) -> None:
        if not isinstance(coefficients, RollDampingCoefficients):
            raise ValueError(
                f"coefficients must be a RollDampingCoefficients; got {type(coefficients).__name__}"
            )
        if not isinstance(name, str) or not name:
            raise ValueError(f"name must be a non-empty string; got {name!r}")
        self.coefficients = coefficients
        self.name = name

    def __repr__(self) -> str:
        c = self.coefficients
        return f"ViscousRollDamping(b1={c.b1:.6g}, b2={c.b2:.6g}, name={self.name!r})"

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Force (6,) [N, N·m] with only the roll moment non-zero; no states."""
        p = float(ctx.nu[ROLL])
        force = np.zeros(6)
        force[ROLL] = -(self.coefficients.b1 * p + self.coefficients.b2 * abs(p) * p)
        return force, np.zeros(0)

    @classmethod
    def from_hull(
        cls,
        hull: Hull,
        *,
        omega: float | None = None,
        forward_speed: float = 0.0,
        bilge_keel: BilgeKeel | None = None,
        roll_amplitudes: ArrayLike = DEFAULT_ROLL_AMPLITUDES,
        turbulent_friction: bool = True,
        on_out_of_range: OnOutOfRange = "warn",
        kinematic_viscosity: float = KINEMATIC_VISCOSITY_SEAWATER,
    ) -> ViscousRollDamping:
        """Force model with B1, B2 fitted by :func:`fit_linear_quadratic` for a hull.

        Parameters
        ----------
        hull : Hull
            The hull at its design condition.
        omega : float, optional
            Roll frequency [rad/s]; default 2π/T with T the IMO IS Code roll period
            (:func:`imo_roll_period` with L_wl ≈ Lpp and the hull's GM). Better: the natural
            frequency from the BEM database
            (:func:`ship_gym.hydro.rao.natural_frequency` ``(db, "Roll")``).
        forward_speed, bilge_keel, roll_amplitudes, turbulent_friction, on_out_of_range
            See :func:`fit_linear_quadratic`.
        kinematic_viscosity : float, optional
            ν [m²/s].
        """
        if not isinstance(hull, Hull):
            raise ValueError(f"hull must be a Hull; got {type(hull).__name__}")
        particulars = RollDampingParticulars.from_hull(
            hull, kinematic_viscosity=kinematic_viscosity
        )
        if omega is None:
            p = hull.particulars
            period = imo_roll_period(p.beam, p.draught, p.lpp, hydrostatics(hull).gmt)
            omega = 2.0 * math.pi / period
        coefficients = fit_linear_quadratic(
            particulars,
            omega=omega,
            roll_amplitudes=roll_amplitudes,
            forward_speed=forward_speed,
            bilge_keel=bilge_keel,
            turbulent_friction=turbulent_friction,
            on_out_of_range=on_out_of_range,
        )
        return cls(coefficients)


__all__ = [
    "DEFAULT_ROLL_AMPLITUDES",
    "EIGHT_OVER_THREE_PI",
    "KINEMATIC_VISCOSITY_SEAWATER",
    "VALIDITY_RANGES",
    "BilgeKeel",
    "IkedaRangeWarning",
    "IkedaRollDamping",
    "RollDampingCoefficients",
    "RollDampingParticulars",
    "ViscousRollDamping",
    "critical_roll_damping",
    "dimensional_roll_damping",
    "fit_linear_quadratic",
    "ikeda_roll_damping",
    "imo_roll_period",
    "linear_quadratic_from_equivalent",
    "midship_section_area",
    "nondimensional_roll_damping",
]


# =============================================================================================
# row kernel of the compiled path (protocol: ship_gym.forces.base.RowPart)
# =============================================================================================
@nb.njit(cache=True, nogil=True, inline="always")
def viscous_roll_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: the roll moment −(B₁ p + B₂ |p| p) [N·m] (eq. 1), ``rec = (B₁, B₂)``."""
    p_roll = v[3]
    out[3] += -(rec[0] * p_roll + rec[1] * abs(p_roll) * p_roll)
