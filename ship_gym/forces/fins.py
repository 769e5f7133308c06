"""Roll-stabiliser fins, a bow T-foil and stern flaps: controlled lifting surfaces for ride control.

Every surface is a :class:`~ship_gym.forces.lifting_surface.LiftingSurface` (lift slope from the
effective aspect ratio, stall, flat-plate post-stall; see that module) moving with the hull: the
velocity it sees is the rigid-body velocity of its centre of pressure, v + ω × r, so roll, heave
and pitch rates change its angle of attack (a fin at rest gives roll damping at speed). The
commanded angle is clipped to ±``max_angle``; rate limits and lag belong to the servo
(:class:`ship_gym.control.actuators.Actuated` with ``FIN_SERVO`` / ``FOIL_SERVO``), which hands
these models the applied angle. Wave orbital velocities at the surfaces are not included.

Sign conventions (body frame x forward, y starboard, z down; positive roll = starboard down,
positive pitch = bow up)
--------------------------------------------------------------------------------------------
:class:`RollFins` (``ctx.commands["fins"]`` [rad]) — **a positive command gives a positive roll
moment K > 0 (starboard side down)**: the starboard fin turns nose-down (stock axis −y) and lifts
downward, the port fin turns nose-up (stock axis +y) and lifts upward. With horizontal fins at
(x_f, ±y_f, z_f) the pair gives a pure roll moment (the lifts cancel in heave and pitch, the drags
in yaw; the drags leave a small pitch moment z_f F_x):

    K = 2 y_f · ½ρ U_f² A_f C_L(δ),                                                  (1)

U_f the speed at the fins. A stabiliser therefore commands δ = −k_φ φ − k_p p (+ …).

    view from aft, looking forward, δ > 0:

        port fin: lift up (F_z < 0)                starboard fin: lift down (F_z > 0)
               ^                                                |
               |                                                v
        =======o=======[          hull section          ]=======o=======
            y = −y_f                                        y = +y_f

    K = Σ (y F_z − z F_y) = 2 y_f L > 0: starboard side down.

:class:`TFoil` (``ctx.commands["t_foil"]`` [rad]) — a horizontal foil on a strut under the bow,
stock axis +y: **a positive command turns it nose-up and gives an upward force (F_z < 0) and a
bow-up pitch moment (M = −x_T F_z > 0)**.

:class:`SternFlaps` (``ctx.commands["flaps"]`` [rad]) — a pair of trailing-edge flaps on the
transom bottom, moved together; **a positive command turns the trailing edges down: upward force
at the stern (F_z < 0) and a bow-down pitch moment (M < 0)**. Modelled as a lifting surface of
the flap's own area on the hull bottom (reflection plane, k = 2); the pressure the flap raises on
the hull bottom ahead of it (which dominates real flaps and interceptors, Savitsky & Brown 1976)
is not included, so the lift is a lower bound.

S175 defaults (illustrative sizes; the S175 has none of these appendages)
------------------------------------------------------------------------
* Roll fins: two fins of 10 m² (span 4.0 m, chord 2.5 m, geometric AR 1.6, effective 3.2,
  C_Lα = 3.25/rad, stall 25°, limit ±25°) at the turn of the bilge amidships: root on the hull at
  z = 7.5 m (2 m above the base line, half-breadth 12.4 m), centre of pressure at mid-span
  y_f = ±14.4 m. At 22 kn and δ = 20° (C_L = 1.13) the pair gives K ≈ 2.1e7 N·m, the righting
  moment of ≈ 5° of heel (Δ g GM = 2.4e8 N·m/rad).
* T-foil: 12.8 m² (span 8 m, chord 1.6 m, AR 5, free foil, C_Lα = 3.94/rad, stall 15°, limit
  ±15°) on a 1.5 m strut under the forefoot, x_T = 65 m, z_T = 11.0 m. The strut's own side force
  and drag are not modelled.
* Stern flaps: no default geometry (the S175's cruiser stern has no immersed transom).

References
----------
Whicker & Fehlner (1958), Hoerner (1965), Molland & Turnock (2007): see
:mod:`ship_gym.forces.lifting_surface`.
Perez, T. (2005). Ship Motion Control: Course Keeping and Roll Stabilisation Using Rudder and
Fins. Springer, ch. 4 and 11.
Fossen, T.I. (2011). Handbook of Marine Craft Hydrodynamics and Motion Control, §9.5.
Savitsky, D. & Brown, P.W. (1976). Procedures for hydrodynamic evaluation of planing hulls in
smooth and rough water. Marine Technology 13(4), 381–400.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import partial

from ship_gym.conventions import RHO_SEAWATER
from ship_gym.forces.base import ForceContext
from ship_gym.forces.lifting_surface import LiftingSurface, LiftSlopeModel, SurfaceGroup

__all__ = ["RollFins", "SternFlaps", "TFoil"]


def _finite(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}; expected a finite number") from None
    if not math.isfinite(v):
        raise ValueError(f"{name}={value!r}; expected a finite number")
    return v


class _ControlSurfaces(SurfaceGroup):
    """Lifting surfaces moved by one command; shared machinery of fins, T-foil and flaps."""

    command_key: str = ""

    def __init__(
        self,
        surfaces: Sequence[LiftingSurface],
        *,
        max_angle: float,
        wake_fraction: float,
    ) -> None:
        self.surfaces = list(surfaces)
        self.max_angle = _finite("max_angle", max_angle)
        if not 0.0 < self.max_angle <= 0.5 * math.pi:
            raise ValueError(f"max_angle={max_angle!r}; expected an angle in (0, π/2] rad")
        self.wake_fraction = _finite("wake_fraction", wake_fraction)
        if not 0.0 <= self.wake_fraction < 1.0:
            raise ValueError(f"wake_fraction={wake_fraction!r}; expected a value in [0, 1)")

    def angle(self, ctx: ForceContext) -> float:
        """Applied angle [rad]: the command clipped to ±max_angle (missing command → 0)."""
        key = self.command_key
        cmd = _finite(f"commands[{key!r}]", ctx.commands.get(key, 0.0))
        return min(max(cmd, -self.max_angle), self.max_angle)

    def inflow_velocities(self, ctx: ForceContext) -> list[tuple[float, float, float]]:
        try:
            nu = tuple(float(c) for c in ctx.nu)
        except (TypeError, ValueError):
            nu = ()
        if len(nu) != 6 or not all(map(math.isfinite, nu)):
            raise ValueError(f"ctx.nu={ctx.nu!r}; expected a finite (6,) velocity vector")
        k = 1.0 - self.wake_fraction
        out = []
        for s in self.surfaces:
            vx, vy, vz = s.rigid_body_components(*nu)
            out.append((k * vx, vy, vz))
        return out


class RollFins(_ControlSurfaces):
    """A pair of antisymmetric roll-stabiliser fins (force model ``"roll_fins"``).

    Positive ``ctx.commands["fins"]`` [rad] → positive roll moment (starboard down); see the
    module docstring (:mod:`ship_gym.forces.fins`) for signs and the S175 defaults.

    Parameters
    ----------
    area : float
        Area of one fin [m²].
    span : float
        Span of one fin [m].
    x : float
        Longitudinal position of the fins [m].
    y : float
        Lateral distance of each fin's centre of pressure from the centreline, y_f > 0 [m].
    z : float
        Depth of the fins below the waterline [m].
    max_angle : float
        Angle limit [rad].
    stall_angle : float
        α_s [rad].
    aspect_ratio_factor : float
        k of AR_e (2: root on the hull).
    wake_fraction : float
        Axial wake at the fins [-].
    lift_slope_model : {"whicker_fehlner", "helmbold"}
        Lift-slope formula.
    zero_lift_drag : float
        C_D0 [-].
    rho : float
        Water density [kg/m³].
    """

    name = "roll_fins"
    command_key = "fins"

    def __init__(
        self,
        *,
        area: float = 10.0,
        span: float = 4.0,
        x: float = 0.0,
        y: float = 14.4,
        z: float = 7.5,
        max_angle: float = math.radians(25.0),
        stall_angle: float = math.radians(25.0),
        aspect_ratio_factor: float = 2.0,
        wake_fraction: float = 0.0,
        lift_slope_model: LiftSlopeModel = "whicker_fehlner",
        zero_lift_drag: float = 0.01,
        rho: float = RHO_SEAWATER,
    ) -> None:
        y_f = _finite("y", y)
        if y_f <= 0.0:
            raise ValueError(f"y={y!r}; expected the (positive) lateral distance of each fin [m]")
        fin = partial(
            LiftingSurface,
            aspect_ratio_factor=aspect_ratio_factor,
            lift_slope_model=lift_slope_model,
            stall_angle=stall_angle,
            zero_lift_drag=zero_lift_drag,
            rho=rho,
        )
        starboard = fin(area, span, (x, y_f, z), (0.0, -1.0, 0.0))
        port = fin(area, span, (x, -y_f, z), (0.0, 1.0, 0.0))
        super().__init__([starboard, port], max_angle=max_angle, wake_fraction=wake_fraction)

    @property
    def arm(self) -> float:
        """Lateral distance y_f of each fin from the centreline [m] (roll arm of eq. 1)."""
        return float(self.surfaces[0].position[1])


class TFoil(_ControlSurfaces):
    """A horizontal T-foil under the bow (force model ``"t_foil"``), for heave/pitch control.

    Positive ``ctx.commands["t_foil"]`` [rad] → nose-up, upward force, bow-up pitch moment; see
    :mod:`ship_gym.forces.fins` for the S175 defaults.

    Parameters
    ----------
    area : float
        Foil area [m²].
    span : float
        Foil span [m].
    x : float
        Longitudinal position [m] (forward of amidships > 0).
    z : float
        Depth below the waterline [m].
    max_angle : float
        Angle limit [rad].
    stall_angle : float
        α_s [rad].
    aspect_ratio_factor : float
        k of AR_e (1: free foil on a strut).
    wake_fraction : float
        Axial wake at the foil [-].
    lift_slope_model : {"whicker_fehlner", "helmbold"}
        Lift-slope formula.
    zero_lift_drag : float
        C_D0 [-].
    rho : float
        Water density [kg/m³].
    """

    name = "t_foil"
    command_key = "t_foil"

    def __init__(
        self,
        *,
        area: float = 12.8,
        span: float = 8.0,
        x: float = 65.0,
        z: float = 11.0,
        max_angle: float = math.radians(15.0),
        stall_angle: float = math.radians(15.0),
        aspect_ratio_factor: float = 1.0,
        wake_fraction: float = 0.0,
        lift_slope_model: LiftSlopeModel = "whicker_fehlner",
        zero_lift_drag: float = 0.01,
        rho: float = RHO_SEAWATER,
    ) -> None:
        foil = LiftingSurface(
            area,
            span,
            (x, 0.0, z),
            (0.0, 1.0, 0.0),
            aspect_ratio_factor=aspect_ratio_factor,
            lift_slope_model=lift_slope_model,
            stall_angle=stall_angle,
            zero_lift_drag=zero_lift_drag,
            rho=rho,
        )
        super().__init__([foil], max_angle=max_angle, wake_fraction=wake_fraction)


class SternFlaps(_ControlSurfaces):
    """Transom stern flaps moved together (force model ``"stern_flaps"``), for trim/pitch control.

    Positive ``ctx.commands["flaps"]`` [rad] → trailing edges down, upward force at the stern,
    bow-down pitch moment. The geometry has no default (see :mod:`ship_gym.forces.fins`).

    Parameters
    ----------
    span : float
        Span of one flap [m].
    chord : float
        Chord of the flaps [m].
    x : float
        Longitudinal position of the flaps' centre of pressure [m] (at the transom, < 0).
    z : float
        Depth of the flaps below the waterline [m] (> 0: the transom must be immersed).
    lateral_positions : sequence of float
        y of each flap's centre [m], e.g. ``(-3.0, 3.0)``.
    max_angle : float
        Angle limit [rad].
    stall_angle : float
        α_s [rad].
    aspect_ratio_factor : float
        k of AR_e (2: on the hull bottom).
    wake_fraction : float
        Axial wake at the transom [-].
    zero_lift_drag : float
        C_D0 [-].
    rho : float
        Water density [kg/m³].
    """

    name = "stern_flaps"
    command_key = "flaps"

    def __init__(
        self,
        *,
        span: float,
        chord: float,
        x: float,
        z: float,
        lateral_positions: Sequence[float] = (0.0,),
        max_angle: float = math.radians(15.0),
        stall_angle: float = math.radians(15.0),
        aspect_ratio_factor: float = 2.0,
        wake_fraction: float = 0.0,
        zero_lift_drag: float = 0.01,
        rho: float = RHO_SEAWATER,
    ) -> None:
        if _finite("z", z) <= 0.0:
            raise ValueError(f"z={z!r}; expected a depth below the waterline > 0 [m]")
        span = _finite("span", span)
        chord = _finite("chord", chord)
        if span <= 0.0 or chord <= 0.0:
            raise ValueError(f"span={span!r}, chord={chord!r}; expected positive lengths [m]")
        ys = [_finite("lateral_positions", y) for y in lateral_positions]
        if not ys:
            raise ValueError("lateral_positions is empty; expected at least one flap position")
        flaps = [
            LiftingSurface(
                span * chord,
                span,
                (x, y, z),
                (0.0, 1.0, 0.0),
                chord=chord,
                aspect_ratio_factor=aspect_ratio_factor,
                stall_angle=stall_angle,
                zero_lift_drag=zero_lift_drag,
                rho=rho,
            )
            for y in ys
        ]
        super().__init__(flaps, max_angle=max_angle, wake_fraction=wake_fraction)
