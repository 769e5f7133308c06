r"""One model of a lifting surface (rudder, roll fin, T-foil, stern flap), shared by all of them.

A lifting surface is a low-aspect-ratio foil of planform area A, span s and mean chord c, turning
about a stock. Its hydrodynamic force is computed from the velocity of the surface through the
water (rigid-body velocity at its position, modified by the caller for wake, propeller slipstream
or flow straightening) and its deflection δ, and returned as a body-axis force and moment about
the body origin O (:mod:`ship_gym.conventions`: x forward, y starboard, z down).

Geometry and signs
------------------
``axis`` e_a is the unit vector about which the surface turns; a **positive deflection δ is a
right-handed rotation about e_a**. ``chord_direction`` e_c0 (default body x, made perpendicular
to e_a) points from the trailing edge to the leading edge at δ = 0; the zero-lift plane at
deflection δ is spanned by e_a and e_c(δ) = cos δ e_c0 + sin δ e_t0 with e_t0 = e_a × e_c0, the
direction in which the leading edge moves for δ > 0. A vertical rudder with e_a = −z (pointing
up, out of the page) seen from above, at δ > 0::

                       ^ x (forward)
                       |
          leading      |
          edge   o     |                 e_a  = −z (up, out of the page)
                  \    |                 e_c0 = +x
                   \   |                 e_t0 = e_a × e_c0 = −y: the leading edge
      lift <----    \  | δ               moves to PORT, the trailing edge to STARBOARD
      (to port)      \ |
                      \|                 +-----> y (starboard)
                       \
                       |\
                       | \  trailing edge
                       |
                       v  water flows aft past the rudder (the ship moves ahead: d = +x)

The flow leaves along the trailing edge to starboard, and the lift on the surface points to
port (e_a × d = −y for d = +x).

Let V be the velocity of the surface relative to the water at its reference point (body axes).
Only its part normal to the span counts (independence principle; the spanwise part makes no
lift), V⊥ = V − (V·e_a) e_a; the unit vector d = V⊥/|V⊥| points upstream (where the water comes
from). With θ_d = atan2(d·e_t0, d·e_c0) the direction of d in the section plane, the angle of
attack is

    α = δ − θ_d                                                               (1)

(wrapped to (−π, π]); straight-ahead motion (d = e_c0) gives α = δ. The force on the surface is

    F = q A [C_L(α) (e_a × d) − C_D(α) d],   q = ½ ρ |V⊥|²,   M_O = r × F,      (2)

r the position of its centre of pressure (taken at the given ``position``). Lift is normal to
the inflow and to the span, toward the side to which the leading edge turned; drag opposes the
surface's motion.

Lift and drag coefficients
--------------------------
Attached flow, |α| ≤ α_s (the stall angle):

    C_L = C_Lα α,     C_D = C_D0 + C_L² / (π e AR_e),                          (3)

with AR_e = k · s²/A the effective aspect ratio: k = 2 for a surface whose root closes on the hull
or a plate (reflection plane: rudder under the hull, fins on the bilge, flaps on the bottom),
k = 1 for a free foil (T-foil on a strut). The lift slope C_Lα [1/rad] is either

* Whicker & Fehlner (1958) (also Molland & Turnock 2007, §3.4), for low-aspect-ratio control
  surfaces, with a section lift-slope factor 0.9 and quarter-chord sweep Λ:

      C_Lα = 0.9 · 2π AR_e / (1.8 + cos Λ · √(AR_e²/cos⁴Λ + 4)),               (4)

* or Helmbold (1942), in the form with sweep of DATCOM (Diederich):

      C_Lα = 2π AR_e / (2 + √(AR_e² (1 + tan²Λ) + 4)).                         (5)

Both tend to the slender-wing value π AR_e/2 as AR_e → 0.

Post stall, the surface behaves as a flat plate with normal-force coefficient C_N (Hoerner 1965,
ch. 3: C_N ≈ 1.2 for rectangular plates of aspect ratio 1–5, 1.98 in 2-D):

    C_L = C_N sin α cos α,     C_D = C_D0 + C_N sin² α.                          (6)

Between α_s and α_s + Δα the coefficients go from their values at the stall (held constant,
C_L,max = C_Lα α_s) to (6) with the cosine weight σ = ½[1 − cos(π(|α| − α_s)/Δα)], so C_L is
continuous, peaks exactly at α_s (C_L,max must exceed C_N/2, the flat-plate maximum; checked) and
drops after it. C_L is odd and C_D even in α; both are π-periodic: with the flow from behind
(|α| > π/2) the trailing edge leads and the same curves are used with α − π (a simplification:
reversed-flow stall is in fact earlier and C_L,max lower).

Stall angle α_s: free-stream tests of all-movable rudders of aspect ratio 1–3 stall at ≈ 25–35°
(Whicker & Fehlner 1958; Molland & Turnock 2007, ch. 3); behind a propeller the stall is delayed
(≈ 35–45°). Defaults of the models: rudder 35°, roll fins 25°, T-foil and flaps 15°.

Not modelled: the nonlinear cross-flow lift of very low aspect ratios (Whicker & Fehlner's
C_Dc/AR α|α| term), the chordwise travel of the centre of pressure, the gap between root and hull
(k between 1 and 2), free-surface and cavitation effects, unsteady (Theodorsen/Wagner) lift.

References
----------
Whicker, L.F. & Fehlner, L.F. (1958). Free-stream characteristics of a family of low-aspect-ratio,
all-movable control surfaces for application to ship design. DTMB Report 933.
Helmbold, H.B. (1942). Der unverwundene Ellipsenflügel als tragende Wirbelfläche. Jahrbuch der
Deutschen Luftfahrtforschung, I 111–113.
Hoerner, S.F. (1965). Fluid-Dynamic Drag. Hoerner Fluid Dynamics.
Molland, A.F. & Turnock, S.R. (2007). Marine Rudders and Control Surfaces. Butterworth-Heinemann.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numba as nb
import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import RHO_SEAWATER
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.numerics.angles import wrap_angle_scalar

__all__ = [
    "LiftSlopeModel",
    "LiftingSurface",
    "SurfaceGroup",
    "SurfaceLoads",
    "lift_slope",
]

LiftSlopeModel = Literal["whicker_fehlner", "helmbold"]

_MIN_SPEED = 1e-9
"""Below this speed through the water [m/s] a surface makes no force."""


def _positive(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}; expected a positive number") from None
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name}={value!r}; expected a finite positive number")
    return v


def _vector3(name: str, value: ArrayLike) -> NDArray[np.float64]:
    try:
        v = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}; expected a (3,) vector of numbers") from None
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"{name}={value!r}; expected a finite (3,) vector")
    return v


def lift_slope(
    aspect_ratio: float | NDArray[np.float64],
    *,
    model: LiftSlopeModel = "whicker_fehlner",
    sweep: float = 0.0,
) -> float | NDArray[np.float64]:
    """Three-dimensional lift-curve slope C_Lα [1/rad] of a foil of (effective) aspect ratio.

    Parameters
    ----------
    aspect_ratio : float or numpy.ndarray
        Effective aspect ratio AR_e [-] (span²/area, doubled for a root on a reflection plane).
    model : {"whicker_fehlner", "helmbold"}
        Eq. (4) (Whicker & Fehlner 1958) or eq. (5) (Helmbold 1942) of the module docstring.
    sweep : float
        Quarter-chord sweep angle Λ [rad], |Λ| < π/2.

    Returns
    -------
    float or numpy.ndarray
        C_Lα [1/rad].
    """
    ar = np.asarray(aspect_ratio, dtype=float)
    if not np.all(np.isfinite(ar) & (ar > 0.0)):
        raise ValueError(f"aspect_ratio={aspect_ratio!r}; expected positive finite values")
    if not (math.isfinite(sweep) and abs(sweep) < 0.5 * math.pi):
        raise ValueError(f"sweep={sweep!r}; expected an angle in (−π/2, π/2) rad")
    cos_l = math.cos(sweep)
    if model == "whicker_fehlner":
        out = 0.9 * 2.0 * np.pi * ar / (1.8 + cos_l * np.sqrt(ar**2 / cos_l**4 + 4.0))
    elif model == "helmbold":
        out = 2.0 * np.pi * ar / (2.0 + np.sqrt(ar**2 * (1.0 + math.tan(sweep) ** 2) + 4.0))
    else:
        raise ValueError(f"model={model!r}; expected 'whicker_fehlner' or 'helmbold'")
    return float(out) if np.ndim(out) == 0 else out


@dataclass(frozen=True)
class SurfaceLoads:
    """Hydrodynamic loads of one lifting surface at one instant.

    Attributes
    ----------
    angle_of_attack : float
        α [rad], eq. (1) of :mod:`ship_gym.forces.lifting_surface`.
    speed : float
        |V⊥|, speed through the water normal to the span [m/s].
    lift_coefficient, drag_coefficient : float
        C_L(α), C_D(α) [-].
    lift, drag : float
        Magnitudes q A C_L (signed) and q A C_D [N].
    force : numpy.ndarray
        (6,) force [N] and moment about O [N·m], body axes.
    """

    angle_of_attack: float
    speed: float
    lift_coefficient: float
    drag_coefficient: float
    lift: float
    drag: float
    force: NDArray[np.float64]


class LiftingSurface:
    """A rudder, fin, foil or flap: lift and drag from angle of attack and inflow speed.

    Conventions, equations (1)–(6) and references are in the module docstring
    (:mod:`ship_gym.forces.lifting_surface`).

    Parameters
    ----------
    area : float
        Planform area A [m²] (of one surface).
    span : float
        Span s [m] (height of a rudder).
    position : array_like
        (3,) centre of pressure in the body frame [m], where the force acts.
    axis : array_like
        (3,) axis e_a of the stock (normalised here); δ > 0 is a right-handed rotation about it.
    chord_direction : array_like
        (3,) direction trailing → leading edge at δ = 0 [-] (default body x); the part normal to
        ``axis`` is used.
    chord : float, optional
        Mean chord [m] (default A/s); informative only (the model uses A and s).
    aspect_ratio_factor : float
        k in AR_e = k s²/A: 2 for a root closed by the hull or a plate, 1 for a free foil [-].
    lift_slope_model : {"whicker_fehlner", "helmbold"}
        Eq. (4) or (5).
    sweep : float
        Quarter-chord sweep Λ [rad].
    stall_angle : float
        α_s [rad], 0 < α_s, α_s + Δα < π/2.
    stall_transition : float
        Δα [rad] over which lift and drag go to the flat-plate values (6).
    zero_lift_drag : float
        C_D0 [-] (section profile drag).
    oswald_efficiency : float
        e [-] of the induced drag C_L²/(π e AR_e).
    normal_force_coefficient : float
        Flat-plate C_N [-] of eq. (6).
    rho : float
        Water density [kg/m³].
    """

    def __init__(
        self,
        area: float,
        span: float,
        position: ArrayLike,
        axis: ArrayLike,
        *,
        chord_direction: ArrayLike = (1.0, 0.0, 0.0),
        chord: float | None = None,
        aspect_ratio_factor: float = 1.0,
        lift_slope_model: LiftSlopeModel = "whicker_fehlner",
        sweep: float = 0.0,
        stall_angle: float = math.radians(25.0),
        stall_transition: float = math.radians(5.0),
        zero_lift_drag: float = 0.01,
        oswald_efficiency: float = 0.9,
        normal_force_coefficient: float = 1.2,
        rho: float = RHO_SEAWATER,
    ) -> None:
        self.area = _positive("area", area)
        self.span = _positive("span", span)
        self.chord = self.area / self.span if chord is None else _positive("chord", chord)
        self.position = _vector3("position", position)
        self.position.flags.writeable = False
        axis_v = _vector3("axis", axis)
        n = float(np.linalg.norm(axis_v))
        if n == 0.0:
            raise ValueError(f"axis={axis!r}; expected a non-zero (3,) vector")
        self.axis = axis_v / n
        c0 = _vector3("chord_direction", chord_direction)
        c0 = c0 - float(c0 @ self.axis) * self.axis
        nc = float(np.linalg.norm(c0))
        if nc < 1e-9:
            raise ValueError(
                f"chord_direction={chord_direction!r} is parallel to axis={axis!r}; expected a "
                "direction across the stock"
            )
        self.chord_direction = c0 / nc
        self.leading_edge_motion = np.cross(self.axis, self.chord_direction)
        for a in (self.axis, self.chord_direction, self.leading_edge_motion):
            a.flags.writeable = False
        self._axis = tuple(float(c) for c in self.axis)
        self._chord = tuple(float(c) for c in self.chord_direction)
        self._lead = tuple(float(c) for c in self.leading_edge_motion)
        self._pos = tuple(float(c) for c in self.position)
        self.aspect_ratio_factor = _positive("aspect_ratio_factor", aspect_ratio_factor)
        self.lift_slope_model: LiftSlopeModel = lift_slope_model
        self.sweep = float(sweep)
        self.lift_slope = float(
            lift_slope(self.effective_aspect_ratio, model=lift_slope_model, sweep=self.sweep)
        )
        self.stall_angle = _positive("stall_angle", stall_angle)
        self.stall_transition = _positive("stall_transition", stall_transition)
        if self.stall_angle + self.stall_transition >= 0.5 * math.pi:
            raise ValueError(
                f"stall_angle + stall_transition = {self.stall_angle + self.stall_transition!r} "
                "rad; expected less than π/2"
            )
        cd0 = float(zero_lift_drag)
        if not (math.isfinite(cd0) and cd0 >= 0.0):
            raise ValueError(f"zero_lift_drag={zero_lift_drag!r}; expected a number >= 0")
        self.zero_lift_drag = cd0
        self.oswald_efficiency = _positive("oswald_efficiency", oswald_efficiency)
        self.normal_force_coefficient = _positive(
            "normal_force_coefficient", normal_force_coefficient
        )
        self.rho = _positive("rho", rho)
        if self.max_lift_coefficient <= 0.5 * self.normal_force_coefficient:
            raise ValueError(
                f"stall_angle={stall_angle!r} rad gives C_L,max = {self.max_lift_coefficient:.3f}"
                f", not above the flat-plate maximum C_N/2 = "
                f"{0.5 * self.normal_force_coefficient:.3f}; expected a larger stall angle"
            )
        self._k_induced = 1.0 / (math.pi * self.oswald_efficiency * self.effective_aspect_ratio)

    # ------------------------------------------------------------------ geometry
    @property
    def aspect_ratio(self) -> float:
        """Geometric aspect ratio s²/A [-]."""
        return self.span**2 / self.area

    @property
    def effective_aspect_ratio(self) -> float:
        """AR_e = k s²/A [-]."""
        return self.aspect_ratio_factor * self.aspect_ratio

    @property
    def max_lift_coefficient(self) -> float:
        """C_L,max = C_Lα α_s [-] (reached at the stall angle)."""
        return self.lift_slope * self.stall_angle

    # ------------------------------------------------------------------ coefficients
    def lift_drag_coefficients(self, alpha: float) -> tuple[float, float]:
        """(C_L, C_D) at one angle of attack [rad] (scalar fast path of eq. 3–6,
        :func:`section_coefficients`)."""
        cl, cd = section_coefficients(
            float(alpha), self.lift_slope, self.stall_angle, self.stall_transition,
            self.zero_lift_drag, self._k_induced, self.normal_force_coefficient,
        )  # fmt: skip
        return float(cl), float(cd)

    @property
    def induced_drag_factor(self) -> float:
        """1/(π e AR_e) of the induced drag C_L²/(π e AR_e) [-]."""
        return self._k_induced

    def coefficients(
        self, alpha: float | ArrayLike
    ) -> tuple[float | NDArray[np.float64], float | NDArray[np.float64]]:
        """Lift and drag coefficients C_L(α), C_D(α) [-], eq. (3)–(6).

        Parameters
        ----------
        alpha : float or array_like
            Angle(s) of attack [rad].

        Returns
        -------
        (C_L, C_D) : floats or numpy.ndarray
            Same shape as ``alpha``.
        """
        arr = np.asarray(alpha, dtype=float)
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"alpha={alpha!r}; expected finite angles [rad]")
        if arr.ndim == 0:
            return self.lift_drag_coefficients(float(arr))
        flat = [self.lift_drag_coefficients(float(a)) for a in arr.ravel()]
        cl = np.array([f[0] for f in flat]).reshape(arr.shape)
        cd = np.array([f[1] for f in flat]).reshape(arr.shape)
        return cl, cd

    # ------------------------------------------------------------------ kinematics
    def rigid_body_velocity(self, nu: ArrayLike) -> NDArray[np.float64]:
        """Velocity of the surface's reference point through still water, v + ω × r [m/s].

        Parameters
        ----------
        nu : array_like
            (6,) body velocities (u, v, w, p, q, r) [m/s, rad/s].

        Returns
        -------
        numpy.ndarray
            (3,) (u + q z − r y, v + r x − p z, w + p y − q x) [m/s], body axes.
        """
        n = np.asarray(nu, dtype=float)
        if n.shape != (6,):
            raise ValueError(f"nu has shape {n.shape}; expected (6,)")
        x, y, z = self.position
        u, v, w, p, q, r = n
        return np.array([u + q * z - r * y, v + r * x - p * z, w + p * y - q * x])

    def _alpha_speed(
        self, vx: float, vy: float, vz: float, delta: float
    ) -> tuple[float, float, tuple[float, float, float]]:
        """α [rad], |V⊥| [m/s] and V⊥ for scalar velocity components (eq. 1)."""
        ax, ay, az = self._axis
        vs = vx * ax + vy * ay + vz * az
        px, py, pz = vx - vs * ax, vy - vs * ay, vz - vs * az
        speed = math.sqrt(px * px + py * py + pz * pz)
        if speed < _MIN_SPEED:
            return delta, 0.0, (px, py, pz)
        cx, cy, cz = self._chord
        tx, ty, tz = self._lead
        theta = math.atan2(px * tx + py * ty + pz * tz, px * cx + py * cy + pz * cz)
        alpha = wrap_angle_scalar(delta - theta)
        return alpha, speed, (px, py, pz)

    @staticmethod
    def _check_inputs(velocity: ArrayLike, deflection: float) -> tuple[float, float, float, float]:
        try:
            vx, vy, vz = (float(c) for c in np.asarray(velocity))
            delta = float(deflection)
        except (TypeError, ValueError):
            raise ValueError(
                f"velocity={velocity!r}, deflection={deflection!r}; expected a (3,) velocity "
                "[m/s] and an angle [rad]"
            ) from None
        if not (math.isfinite(vx) and math.isfinite(vy) and math.isfinite(vz)):
            raise ValueError(f"velocity={velocity!r}; expected a finite (3,) vector [m/s]")
        if not math.isfinite(delta):
            raise ValueError(f"deflection={deflection!r}; expected a finite angle [rad]")
        return vx, vy, vz, delta

    def angle_of_attack(self, velocity: ArrayLike, deflection: float) -> tuple[float, float]:
        """Angle of attack α [rad] (eq. 1) and speed |V⊥| [m/s] normal to the span.

        Parameters
        ----------
        velocity : array_like
            (3,) velocity of the surface relative to the water [m/s], body axes (the inflow is
            its negative).
        deflection : float
            δ [rad], right-handed about :attr:`axis`.
        """
        vx, vy, vz, delta = self._check_inputs(velocity, deflection)
        alpha, speed, _ = self._alpha_speed(vx, vy, vz, delta)
        return alpha, speed

    # ------------------------------------------------------------------ loads
    def loads(self, velocity: ArrayLike, deflection: float) -> SurfaceLoads:
        """Lift, drag and the body-axis force and moment about O, eq. (2).

        Parameters
        ----------
        velocity : array_like
            (3,) velocity of the surface relative to the water at its position [m/s], body axes:
            :meth:`rigid_body_velocity` possibly modified by the caller (wake fraction,
            slipstream, flow straightening).
        deflection : float
            δ [rad], right-handed about :attr:`axis`.

        Returns
        -------
        SurfaceLoads
        """
        vx, vy, vz, delta = self._check_inputs(velocity, deflection)
        alpha, speed, cl, cd, lift, drag, force = self.components(vx, vy, vz, delta)
        return SurfaceLoads(alpha, speed, cl, cd, lift, drag, np.array(force))

    def force(self, velocity: ArrayLike, deflection: float) -> NDArray[np.float64]:
        """(6,) body-axis force [N] and moment about O [N·m]; see :meth:`loads`."""
        return self.loads(velocity, deflection).force

    def components(
        self, vx: float, vy: float, vz: float, deflection: float
    ) -> tuple[float, float, float, float, float, float, tuple[float, ...]]:
        """Fast path of :meth:`loads` on plain floats, without input checks (for force models).

        Parameters
        ----------
        vx, vy, vz : float
            Velocity of the surface relative to the water [m/s], body axes (finite).
        deflection : float
            δ [rad] (finite).

        Returns
        -------
        tuple
            (α [rad], |V⊥| [m/s], C_L, C_D, lift [N], drag [N], (Fx, Fy, Fz, K, M, N) [N, N·m]).
        """
        alpha, speed, (px, py, pz) = self._alpha_speed(vx, vy, vz, deflection)
        cl, cd = self.lift_drag_coefficients(alpha)
        if speed < _MIN_SPEED:
            return alpha, 0.0, cl, cd, 0.0, 0.0, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        dx, dy, dz = px / speed, py / speed, pz / speed
        ax, ay, az = self._axis
        qa = 0.5 * self.rho * speed * speed * self.area
        lift, drag = qa * cl, qa * cd
        # F = L (e_a × d) − D d
        fx = lift * (ay * dz - az * dy) - drag * dx
        fy = lift * (az * dx - ax * dz) - drag * dy
        fz = lift * (ax * dy - ay * dx) - drag * dz
        x, y, z = self._pos
        force = (fx, fy, fz, y * fz - z * fy, z * fx - x * fz, x * fy - y * fx)
        return alpha, speed, cl, cd, lift, drag, force

    def rigid_body_components(
        self, u: float, v: float, w: float, p: float, q: float, r: float
    ) -> tuple[float, float, float]:
        """:meth:`rigid_body_velocity` on plain floats (v + ω × r) [m/s]."""
        x, y, z = self._pos
        return u + q * z - r * y, v + r * x - p * z, w + p * y - q * x

    def __repr__(self) -> str:
        return (
            f"LiftingSurface(area={self.area:.3g} m², span={self.span:.3g} m, "
            f"position={self.position.tolist()}, axis={self.axis.tolist()}, "
            f"AR_e={self.effective_aspect_ratio:.3g}, C_Lα={self.lift_slope:.3g}/rad, "
            f"stall={math.degrees(self.stall_angle):.3g}°)"
        )


class SurfaceGroup(ForceModel):
    """Force model of lifting surfaces deflected together by one angle (rudder(s), fins, foils).

    Subclasses provide :meth:`angle` (the applied deflection) and :meth:`inflow_velocities` (the
    water velocity relative to each surface); this class sums the surfaces' loads.
    """

    surfaces: list[LiftingSurface]

    def angle(self, ctx: ForceContext) -> float:
        """Applied deflection δ [rad]."""
        raise NotImplementedError

    def inflow_velocities(self, ctx: ForceContext) -> list[tuple[float, float, float]]:
        """Velocity (body axes) of each surface relative to the water [m/s]."""
        raise NotImplementedError

    def loads(self, ctx: ForceContext) -> list[SurfaceLoads]:
        """Per-surface loads at the current state and command."""
        delta = self.angle(ctx)
        return [
            s.loads(vel, delta)
            for s, vel in zip(self.surfaces, self.inflow_velocities(ctx), strict=True)
        ]

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Sum of the surfaces' forces and moments about O (body axes) [N, N·m]; no states."""
        delta = self.angle(ctx)
        total = [0.0] * 6
        for s, (vx, vy, vz) in zip(self.surfaces, self.inflow_velocities(ctx), strict=True):
            f = s.components(vx, vy, vz, delta)[6]
            total = [a + b for a, b in zip(total, f, strict=True)]
        return np.array(total), np.zeros(0)


# =============================================================================================
# row kernels (numba; the engine's numpy path and its compiled loop call these)
# =============================================================================================
@nb.njit(cache=True)
def section_coefficients(
    alpha, lift_slope, a_s, transition, cd0, k_induced, cn
):  # pragma: no cover
    """(C_L, C_D) at the angle of attack α [rad], eq. (3)–(6) of this module (what
    :meth:`LiftingSurface.lift_drag_coefficients` and the row kernels evaluate)."""
    a = alpha - math.pi * round(alpha / math.pi)
    s = 1.0 if a >= 0.0 else -1.0
    a = abs(a)
    if a <= a_s:
        cl = lift_slope * a
        return s * cl, cd0 + k_induced * cl * cl
    sin_a = math.sin(a)
    cl_plate = cn * sin_a * math.cos(a)
    cd_plate = cd0 + cn * sin_a * sin_a
    if a >= a_s + transition:
        return s * cl_plate, cd_plate
    sigma = 0.5 * (1.0 - math.cos(math.pi * (a - a_s) / transition))
    cl_max = lift_slope * a_s
    cd_max = cd0 + k_induced * cl_max * cl_max
    cl = (1.0 - sigma) * cl_max + sigma * cl_plate
    cd = (1.0 - sigma) * cd_max + sigma * cd_plate
    return s * cl, cd


@nb.njit(cache=True, nogil=True)
def slipstream_axial(u_a, thrust, diameter, distance, rho):  # pragma: no cover - compiled
    """(V_x [m/s], R_x [m]) of an actuator-disk slipstream at ``distance`` behind the disk,
    eq. (3) of :mod:`ship_gym.forces.rudder` (Söding 1982), without input checks."""
    r0 = 0.5 * diameter
    u_inf = math.sqrt(u_a * u_a + 8.0 * thrust / (rho * math.pi * diameter * diameter))
    v_x = u_a + (u_inf - u_a) * 0.5 * (1.0 + distance / math.sqrt(distance**2 + r0 * r0))
    if v_x <= 0.0:
        return 0.0, r0
    return v_x, r0 * math.sqrt(0.5 * (u_a + u_inf) / v_x)


@nb.njit(cache=True, nogil=True)
def slipstream_speed(u_a, thrust, diameter, distance, rho, span):  # pragma: no cover
    """u_R of eq. (4) of the rudder module: :func:`slipstream_axial` and the span fraction."""
    v_x, r_x = slipstream_axial(u_a, thrust, diameter, distance, rho)
    fraction = min(1.0, 2.0 * r_x / span)
    return math.sqrt(fraction * v_x * v_x + (1.0 - fraction) * u_a * u_a)


@nb.njit(cache=True, nogil=True)
def surface_group_force(
    nu, d, inflow, wake, gamma_v, gamma_r, prop_d, prop_x, thrust_mode, thrust,
    pos, axis, chord, lead, area, span, rho, lift_slope, stall, transition, cd0, k_induced,
    cn, k0, k1, out,
):  # fmt: skip  # pragma: no cover - compiled
    """SurfaceGroup.evaluate for one ship: Σ over surfaces k0 ≤ k < k1 of
    LiftingSurface.components at the applied angle ``d`` [rad]; writes out (6,).

    Inflow: ``_INFLOW_RUDDER`` — Rudder._inflow (eq. 1–4 of the rudder module: wake, actuator-
    disk slipstream of the thrust, flow straightening); ``_INFLOW_RIGID`` — the rigid-body
    velocity v + ω × r with the axial part scaled by 1 − w (fins, foil, flaps). ``thrust``:
    the propeller thrust [N] (mode 1) or C_Th (mode 2).
    """
    u, v, w, p, q, r = nu[0], nu[1], nu[2], nu[3], nu[4], nu[5]
    f0 = f1 = f2 = f3 = f4 = f5 = 0.0
    for k in range(k0, k1):
        x_s, y_s, z_s = pos[k, 0], pos[k, 1], pos[k, 2]
        if inflow == 0:
            u_a = (1.0 - wake) * (u + q * z_s - r * y_s)
            vx = u_a
            if u_a >= 0.0:
                if thrust_mode == 1:
                    t_k = thrust
                elif thrust_mode == 2:
                    t_k = thrust * 0.5 * rho[k] * u_a * u_a * math.pi * prop_d * prop_d / 4.0
                else:
                    t_k = 0.0
                if t_k > 0.0:
                    vx = slipstream_speed(u_a, t_k, prop_d, prop_x, rho[k], span[k])
            vy = gamma_v * v + gamma_r * x_s * r - p * z_s
            vz = w + p * y_s - q * x_s
        else:
            vx = (1.0 - wake) * (u + q * z_s - r * y_s)
            vy = v + r * x_s - p * z_s
            vz = w + p * y_s - q * x_s
        # LiftingSurface._alpha_speed
        ax, ay, az = axis[k, 0], axis[k, 1], axis[k, 2]
        vs = vx * ax + vy * ay + vz * az
        px, py, pz = vx - vs * ax, vy - vs * ay, vz - vs * az
        speed = math.sqrt(px * px + py * py + pz * pz)
        if speed < 1e-9:
            continue  # components(): zero force (0.0 added)
        theta = math.atan2(
            px * lead[k, 0] + py * lead[k, 1] + pz * lead[k, 2],
            px * chord[k, 0] + py * chord[k, 1] + pz * chord[k, 2],
        )
        alpha = wrap_angle_scalar(d - theta)
        cl, cd = section_coefficients(
            alpha, lift_slope[k], stall[k], transition[k], cd0[k], k_induced[k], cn[k]
        )
        dx, dy, dz = px / speed, py / speed, pz / speed
        qa = 0.5 * rho[k] * speed * speed * area[k]
        lift, drag = qa * cl, qa * cd
        fx = lift * (ay * dz - az * dy) - drag * dx
        fy = lift * (az * dx - ax * dz) - drag * dy
        fz = lift * (ax * dy - ay * dx) - drag * dz
        f0 += fx
        f1 += fy
        f2 += fz
        f3 += y_s * fz - z_s * fy
        f4 += z_s * fx - x_s * fz
        f5 += x_s * fy - y_s * fx
    out[0] = f0
    out[1] = f1
    out[2] = f2
    out[3] = f3
    out[4] = f4
    out[5] = f5
