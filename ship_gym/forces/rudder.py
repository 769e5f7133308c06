"""Spade rudder(s) at the stern: lift and drag in the hull wake and the propeller slipstream.

The rudder is a :class:`~ship_gym.forces.lifting_surface.LiftingSurface` turning about a vertical
stock. Its angle δ [rad] is read from ``ctx.commands["rudder"]`` (the steering-gear dynamics —
saturation, rate limit — are :class:`ship_gym.control.actuators.Actuated`'s business).

Sign of the rudder angle
------------------------
**A positive rudder angle turns the ship to starboard** (positive yaw rate r, bow to starboard):
δ > 0 moves the trailing edge to starboard (stock axis e_a = −z, see the drawing in
:mod:`ship_gym.forces.lifting_surface`). At forward speed the lift on the rudder then points to
**port** (Y < 0), and because the rudder is aft (x_R < 0) the yaw moment N = x_R Y is positive:
the stern is pushed to port and the bow swings to starboard. The rudder's centre of pressure lies
below O (z_R > 0, z down), so the same force gives the roll moment

    K = y F_z − z F_y = −z_R Y > 0,

i.e. **starboard side down**: the rudder heels the ship *into* the turn it starts (the well-known
initial inward heel; the outward heel of the steady turn comes later from the centrifugal force
on G against the hull's lateral force). This is the moment that rudder-roll stabilisation uses.

Inflow (Söding 1982; MMG, Yasukawa & Yoshimura 2015)
----------------------------------------------------
Rigid-body velocity of the rudder's centre of pressure (x_R, y_R, z_R): u + q z_R − r y_R
(axial), v + r x_R − p z_R (lateral). The velocity the rudder sees is

    u_A = (1 − w_R)(u + q z_R − r y_R)                   hull wake at the rudder,      (1)
    v_R = γ_v v + γ_r x_R r − p z_R                      flow straightening,            (2)

with w_R the rudder wake fraction and γ_v, γ_r the flow-straightening factors of the hull and
propeller for drift and yaw rate (the roll-rate part is kept whole). The angle of attack is then
α = δ + atan(v_R/u_R) (eq. 1 of the lifting-surface module for this axis), the MMG form.

Propeller slipstream (actuator disk; Söding 1982, Brix 1993 §1.2): with the thrust T [N] of the
propeller ahead of the rudder (diameter D, radius R₀ = D/2, rudder x_PR behind the disk), the
far-slipstream velocity is u_∞ = √(u_A² + 8T/(ρπD²)) (= u_A √(1 + C_Th), C_Th = 8K_T/(πJ²)); on
the axis at x_PR it is

    V_x = u_A + (u_∞ − u_A) · ½ (1 + x_PR/√(x_PR² + R₀²)),                       (3)

and the slipstream radius there is R_x = R₀ √((u_A + u_∞)/2 / V_x) (continuity). The fraction
f = min(1, 2R_x/s) of the rudder span s lies in the slipstream, and the axial speed used is the
one with the same dynamic pressure,

    u_R = √(f V_x² + (1 − f) u_A²).                                                  (4)

The thrust comes, in that order, from ``ctx.shared["propeller_thrust"]`` (published by a
:class:`~ship_gym.forces.propeller.Propeller` evaluated before the rudder), from
``ctx.commands["propeller_thrust"]`` [N] (thrust of the
propeller ahead of *each* rudder), from ``ctx.commands["propeller_thrust_coefficient"]`` (C_Th),
or from the constructor's ``thrust_coefficient``. **With none of them the rudder sees the hull
wake only** (eq. 1), which under-predicts the rudder force of a self-propelled ship (C_Th ≈ 1–2
at service speed gives +70–130 % dynamic pressure at the S175 rudder). No slipstream is applied
astern (u_A ≤ 0) or with negative thrust. Not modelled: Söding's turbulent-mixing correction of
the slipstream and his lift reduction for a slipstream narrower than the chord, the propeller
swirl, the rudder's induced lateral force on the hull (MMG's a_H — see below).

Lift slope and hull interaction
-------------------------------
The hull above the rudder acts as a reflection plane (``aspect_ratio_factor = 2``): the S175
rudder (geometric AR 1.82, effective 3.64) gets C_Lα = 3.46/rad from Whicker & Fehlner. The MMG
model of the same ship (Son & Nomoto 1982) uses Fujii's normal-force slope 6.13Λ/(Λ + 2.25) =
2.74/rad with the geometric Λ = 1.82 and multiplies the lateral force by 1 + a_H = 1.237 for the
force the rudder induces on the hull: 3.39/rad in all, close to the doubled-aspect-ratio slope
used here, which therefore stands in for a_H (the moment arm of that hull force, x_H = −0.48L, is
not distinguished from x_R = −0.5L).

S175 defaults (Son & Nomoto 1982, the S175 container ship in their MMG-type model)
-----------------------------------------------------------------------------------
* Area A_R = 33.04 m² = 1.99 % of L·T at T = 9.5 m (2.2 % at their d = 8.5 m): the upper end of
  the usual 1.6–2 % of L·T for fast, directionally weakly stable container ships, and above the
  classification minimum A_R = (L T/100)[1 + 25 (B/L)²] = 1.53 % of L·T (DNV rules).
* Aspect ratio 1.82 → span s = 7.76 m, mean chord 4.26 m.
* Centre of pressure at the aft perpendicular, x_R = −Lpp/2 = −87.5 m, at mid-span z_R = 4.9 m:
  root at z = 1.02 m, 0.24 m under the hull (the S175's keel line at the AP is 0.78 m below the
  waterline), tip at z = 8.78 m, 0.72 m above the base line.
* Wake w_R = 0.25 from their ε = (1 − w_R)/(1 − w_P) = 0.921 with w_P = 0.184.
* Flow straightening γ_v = 0.088, γ_r = 0.312 from their v_R' = 0.088 v' − 0.156 r' (r' = rL/U,
  x_R = −0.5L).
* Propeller D = 6.533 m, disk 3.5 m ahead of the rudder's centre of pressure.
* Stall 35°: free-stream stall of AR 1–3 rudders is 25–35°, delayed behind a propeller; 35° is
  also the usual hard-over angle (:data:`ship_gym.control.actuators.RUDDER_SERVO`).

References
----------
Söding, H. (1982). Prediction of ship steering capabilities. Schiffstechnik 29, 3–29.
Brix, J. (ed.) (1993). Manoeuvring Technical Manual. Seehafen Verlag.
Son, K.H. & Nomoto, K. (1981/1982). On the coupled motion of steering and rolling of a high-speed
container ship. J. Soc. Naval Arch. Japan 150 (1981); Naval Arch. & Ocean Eng. 20 (1982) 73–83.
Yasukawa, H. & Yoshimura, Y. (2015). Introduction of MMG standard method for ship manoeuvring
predictions. J. Mar. Sci. Technol. 20, 37–52.
Molland, A.F. & Turnock, S.R. (2007). Marine Rudders and Control Surfaces.
Fossen, T.I. (2011). Handbook of Marine Craft Hydrodynamics and Motion Control, ch. 9.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from ship_gym.conventions import RHO_SEAWATER
from ship_gym.forces.base import ForceContext
from ship_gym.forces.lifting_surface import (
    LiftingSurface,
    LiftSlopeModel,
    SurfaceGroup,
    slipstream_axial,
)

__all__ = ["Rudder", "slipstream_velocity"]

S175_RUDDER_AREA = 33.0376
"""Rudder area of the S175 [m²] (Son & Nomoto 1982)."""

S175_RUDDER_ASPECT_RATIO = 1.8219
"""Geometric aspect ratio of the S175 rudder [-] (Son & Nomoto 1982)."""


def _finite(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}; expected a finite number") from None
    if not math.isfinite(v):
        raise ValueError(f"{name}={value!r}; expected a finite number")
    return v


def _velocities(ctx: ForceContext) -> tuple[float, float, float, float, float, float]:
    """(u, v, w, p, q, r) of ``ctx.nu`` as floats, checked finite."""
    try:
        vals = tuple(float(c) for c in ctx.nu)
    except (TypeError, ValueError):
        vals = ()
    if len(vals) != 6 or not all(map(math.isfinite, vals)):
        raise ValueError(f"ctx.nu={ctx.nu!r}; expected a finite (6,) velocity vector")
    return vals


def _slipstream(
    u_a: float, thrust: float, diameter: float, distance: float, rho: float
) -> tuple[float, float]:
    """Eq. (3) without input checks (see :func:`slipstream_velocity`): the kernel
    :func:`ship_gym.forces.lifting_surface.slipstream_axial`."""
    v_x, r_x = slipstream_axial(
        float(u_a), float(thrust), float(diameter), float(distance), float(rho)
    )
    return float(v_x), float(r_x)


def slipstream_velocity(
    inflow: float,
    thrust: float,
    diameter: float,
    distance: float,
    rho: float = RHO_SEAWATER,
) -> tuple[float, float]:
    """Axial velocity and radius of an actuator-disk slipstream at a distance behind the disk.

    Eq. (3) of :mod:`ship_gym.forces.rudder` (Söding 1982): u_∞ = √(u_A² + 8T/(ρπD²)),
    V_x = u_A + (u_∞ − u_A) ½ (1 + x/√(x² + R₀²)), R_x = R₀ √((u_A + u_∞)/(2 V_x)).

    Parameters
    ----------
    inflow : float
        Propeller advance speed u_A ≥ 0 [m/s].
    thrust : float
        Thrust T ≥ 0 [N].
    diameter : float
        Propeller diameter D [m].
    distance : float
        Distance x ≥ 0 behind the disk [m].
    rho : float
        Water density [kg/m³].

    Returns
    -------
    (V_x, R_x) : tuple of float
        Axial velocity on the slipstream axis [m/s] and slipstream radius [m] at x.
    """
    u_a = _finite("inflow", inflow)
    t = _finite("thrust", thrust)
    d = _finite("diameter", diameter)
    x = _finite("distance", distance)
    if u_a < 0.0 or t < 0.0 or d <= 0.0 or x < 0.0 or rho <= 0.0:
        raise ValueError(
            f"inflow={inflow!r}, thrust={thrust!r}, diameter={diameter!r}, "
            f"distance={distance!r}, rho={rho!r}; expected u_A >= 0, T >= 0, D > 0, x >= 0, "
            "rho > 0"
        )
    return _slipstream(u_a, t, d, x, rho)


class Rudder(SurfaceGroup):
    """Spade rudder(s) at the stern (force model ``"rudder"``); S175 defaults.

    Reads δ [rad] from ``ctx.commands["rudder"]`` (missing → 0; positive turns the ship to
    starboard) and optionally the propeller thrust (``"propeller_thrust"`` [N] or
    ``"propeller_thrust_coefficient"`` [-]). Equations, signs, defaults and their sources are in
    the module docstring (:mod:`ship_gym.forces.rudder`).

    Parameters
    ----------
    area : float
        Area of one rudder [m²].
    aspect_ratio : float
        Geometric aspect ratio s²/A of one rudder [-].
    x : float
        Longitudinal position of the centre of pressure [m] (negative aft of amidships).
    z : float
        Depth of the centre of pressure below the waterline [m] (z down).
    lateral_positions : sequence of float
        y of each rudder [m]: ``(0.0,)`` for one centreline rudder, ``(-a, a)`` for twin
        rudders (each behind its own propeller).
    wake_fraction : float
        w_R [-] of eq. (1), in [0, 1).
    drift_straightening, yaw_straightening : float
        γ_v, γ_r [-] of eq. (2).
    propeller_diameter : float
        D [m] of the propeller ahead of each rudder.
    propeller_distance : float
        x_PR [m], disk to the rudder's centre of pressure.
    thrust_coefficient : float, optional
        C_Th = T/(½ρ u_A² πD²/4) used when the commands carry no thrust; None: wake only.
    aspect_ratio_factor : float
        k of AR_e = k AR (2: the hull closes the root).
    stall_angle : float
        α_s [rad].
    lift_slope_model : {"whicker_fehlner", "helmbold"}
        Lift-slope formula.
    zero_lift_drag : float
        C_D0 [-].
    rho : float
        Water density [kg/m³].
    """

    name = "rudder"

    def __init__(
        self,
        *,
        area: float = S175_RUDDER_AREA,
        aspect_ratio: float = S175_RUDDER_ASPECT_RATIO,
        x: float = -87.5,
        z: float = 4.9,
        lateral_positions: Sequence[float] = (0.0,),
        wake_fraction: float = 0.25,
        drift_straightening: float = 0.088,
        yaw_straightening: float = 0.312,
        propeller_diameter: float = 6.533,
        propeller_distance: float = 3.5,
        thrust_coefficient: float | None = None,
        aspect_ratio_factor: float = 2.0,
        stall_angle: float = math.radians(35.0),
        lift_slope_model: LiftSlopeModel = "whicker_fehlner",
        zero_lift_drag: float = 0.01,
        rho: float = RHO_SEAWATER,
    ) -> None:
        area = _finite("area", area)
        aspect_ratio = _finite("aspect_ratio", aspect_ratio)
        if area <= 0.0 or aspect_ratio <= 0.0:
            raise ValueError(
                f"area={area!r}, aspect_ratio={aspect_ratio!r}; expected positive values"
            )
        span = math.sqrt(aspect_ratio * area)
        ys = [_finite("lateral_positions", y) for y in lateral_positions]
        if not ys:
            raise ValueError("lateral_positions is empty; expected at least one rudder position")
        self.wake_fraction = _finite("wake_fraction", wake_fraction)
        if not 0.0 <= self.wake_fraction < 1.0:
            raise ValueError(f"wake_fraction={wake_fraction!r}; expected a value in [0, 1)")
        self.drift_straightening = _finite("drift_straightening", drift_straightening)
        self.yaw_straightening = _finite("yaw_straightening", yaw_straightening)
        for nm, val in (
            ("drift_straightening", self.drift_straightening),
            ("yaw_straightening", self.yaw_straightening),
        ):
            if val < 0.0:
                raise ValueError(f"{nm}={val!r}; expected a factor >= 0")
        self.propeller_diameter = _finite("propeller_diameter", propeller_diameter)
        self.propeller_distance = _finite("propeller_distance", propeller_distance)
        if self.propeller_diameter <= 0.0 or self.propeller_distance < 0.0:
            raise ValueError(
                f"propeller_diameter={propeller_diameter!r}, propeller_distance="
                f"{propeller_distance!r}; expected D > 0 and a distance >= 0 [m]"
            )
        if thrust_coefficient is not None:
            thrust_coefficient = _finite("thrust_coefficient", thrust_coefficient)
            if thrust_coefficient < 0.0:
                raise ValueError(
                    f"thrust_coefficient={thrust_coefficient!r}; expected C_Th >= 0 or None"
                )
        self.thrust_coefficient = thrust_coefficient
        self.rho = _finite("rho", rho)
        self.surfaces = [
            LiftingSurface(
                area,
                span,
                (_finite("x", x), y, _finite("z", z)),
                (0.0, 0.0, -1.0),
                aspect_ratio_factor=aspect_ratio_factor,
                lift_slope_model=lift_slope_model,
                stall_angle=stall_angle,
                zero_lift_drag=zero_lift_drag,
                rho=rho,
            )
            for y in ys
        ]
        self._positions = [tuple(float(c) for c in sf.position) for sf in self.surfaces]

    # ------------------------------------------------------------------ helpers
    @property
    def surface(self) -> LiftingSurface:
        """The first (or only) rudder's lifting surface."""
        return self.surfaces[0]

    def _thrust(self, ctx: ForceContext, u_a: float) -> float:
        """Thrust of the propeller ahead of each rudder [N] (0: wake only)."""
        cmd = ctx.commands
        if "propeller_thrust" in ctx.shared:  # published by a Propeller evaluated before
            return _finite('shared["propeller_thrust"]', ctx.shared["propeller_thrust"])
        if "propeller_thrust" in cmd:
            return _finite('commands["propeller_thrust"]', cmd["propeller_thrust"])
        c_th = cmd.get("propeller_thrust_coefficient", self.thrust_coefficient)
        if c_th is None:
            return 0.0
        c_th = _finite('commands["propeller_thrust_coefficient"]', c_th)
        d = self.propeller_diameter
        return c_th * 0.5 * self.rho * u_a * u_a * math.pi * d * d / 4.0

    def inflow(self, ctx: ForceContext) -> list[NDArray[np.float64]]:
        """Velocity of each rudder relative to the water, eq. (1)–(4) [m/s], body axes.

        Parameters
        ----------
        ctx : ForceContext
            Uses ``nu`` and the thrust commands.

        Returns
        -------
        list of numpy.ndarray
            (3,) (u_R, v_R, w) per rudder; the angle of attack is δ + atan(v_R/u_R).
        """
        return [np.array(vel) for vel in self._inflow(ctx)]

    def _inflow(self, ctx: ForceContext) -> list[tuple[float, float, float]]:
        u, v, w, p, q, r = _velocities(ctx)
        out = []
        for s, (x_r, y_r, z_r) in zip(self.surfaces, self._positions, strict=True):
            u_a = (1.0 - self.wake_fraction) * (u + q * z_r - r * y_r)
            u_r = u_a
            if u_a >= 0.0:
                thrust = self._thrust(ctx, u_a)
                if thrust > 0.0:
                    v_x, r_x = _slipstream(
                        u_a, thrust, self.propeller_diameter, self.propeller_distance, self.rho
                    )
                    f = min(1.0, 2.0 * r_x / s.span)
                    u_r = math.sqrt(f * v_x * v_x + (1.0 - f) * u_a * u_a)
            v_r = self.drift_straightening * v + self.yaw_straightening * x_r * r - p * z_r
            w_r = w + p * y_r - q * x_r
            out.append((u_r, v_r, w_r))
        return out

    def rudder_angle(self, ctx: ForceContext) -> float:
        """δ [rad] from ``ctx.commands["rudder"]`` (0 if absent)."""
        return _finite('commands["rudder"]', ctx.commands.get("rudder", 0.0))

    def angle(self, ctx: ForceContext) -> float:
        """The applied deflection (:meth:`rudder_angle`) for :class:`SurfaceGroup`."""
        return self.rudder_angle(ctx)

    def inflow_velocities(self, ctx: ForceContext) -> list[tuple[float, float, float]]:
        """Rudder inflow, eq. (1)–(4), for :class:`SurfaceGroup` [m/s]."""
        return self._inflow(ctx)

    def __repr__(self) -> str:
        s = self.surface
        return (
            f"Rudder(n={len(self.surfaces)}, area={s.area:.4g} m², span={s.span:.3g} m, "
            f"x={s.position[0]:.4g} m, z={s.position[2]:.3g} m, C_Lα={s.lift_slope:.3g}/rad, "
            f"stall={math.degrees(s.stall_angle):.3g}°)"
        )
