"""Vectorised control force models for :class:`~ship_gym.engine.batch.BatchSimulator`.

The single-ship control models (:mod:`ship_gym.forces.propeller`, :mod:`ship_gym.forces.resistance`,
:mod:`ship_gym.forces.manoeuvring`, :mod:`ship_gym.forces.rudder`, :mod:`ship_gym.forces.fins`
behind :class:`ship_gym.control.actuators.Actuated`, with the controllers of
:mod:`ship_gym.control.autopilot` and :mod:`ship_gym.control.stabilisers`) written with a leading
ship axis. Each class is built from a single-ship model by ``from_model`` (its parameters are read,
nothing is re-derived), evaluates all rows of a :class:`~ship_gym.engine.batch.BatchContext` in
one call, and keeps the internal states of the single-ship model as batch states with the same
layout (servo angle δ first, then the controller's states). Commands are (N,) arrays over all
ships or scalars (:meth:`BatchContext.rows`).

The arithmetic is the single-ship models', statement by statement (compiled loops over rows for
the lifting surfaces, the propeller and the cross-flow strips), so a batch agrees with the same
ships under :class:`~ship_gym.engine.batch.PerShipForceModel` or in single-ship
:class:`~ship_gym.engine.simulator.Simulator` runs to rounding (tested,
``tests/physics/test_batch_control.py``). The equations and their sources are in the modules of
the single-ship models; this module adds none.

==========================================  ==================================================
single-ship model                           batch model
==========================================  ==================================================
CalmWaterResistance                         :class:`BatchResistance` (R_T(|u|) per ship: the
                                            curve is a Python callable, ≈ 1.4 µs per ship)
Propeller                                   :class:`BatchPropeller` (publishes the (n,) thrust
                                            in ``ctx.shared["propeller_thrust"]``)
HullManoeuvring                             :class:`BatchHullManoeuvring`
Actuated(Rudder | RollFins | TFoil |        :class:`BatchActuatedSurfaces` (servo, optional
SternFlaps, controller)                     heading autopilot / fin / ride controller)
Rudder, RollFins, TFoil, SternFlaps         :class:`BatchActuatedSurfaces` without a servo
==========================================  ==================================================

Added resistance in waves (:class:`~ship_gym.forces.added_resistance.AddedResistance`) has no
batch version; :func:`ship_gym.engine.batch.build_batch_simulator` keeps it per ship.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import numba as nb
import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from ship_gym.control.actuators import (
    NO_CONTROLLER,
    Actuated,
    ActuatorStates,
    ServoSpec,
    actuator_angle_rows,
    actuator_commit_rows,
)
from ship_gym.conventions import SURGE
from ship_gym.engine.batch import BatchContext, BatchForceModel
from ship_gym.forces.base import ForceModel
from ship_gym.forces.fins import RollFins, SternFlaps, TFoil
from ship_gym.forces.lifting_surface import SurfaceGroup
from ship_gym.forces.manoeuvring import HullManoeuvring
from ship_gym.forces.propeller import SHAFT_SPEED_COMMAND, Propeller
from ship_gym.forces.resistance import CalmWaterResistance
from ship_gym.forces.rudder import Rudder

__all__ = [
    "BatchActuatedSurfaces",
    "BatchHullManoeuvring",
    "BatchPropeller",
    "BatchResistance",
    "batch_control_model",
    "trim_batch_shaft_speed",
]

_MIN_SPEED = 1e-9  # ship_gym.forces.lifting_surface._MIN_SPEED: no force below this speed [m/s]
_INFLOW_RUDDER = 0  # Rudder._inflow: wake, slipstream, flow straightening
_INFLOW_RIGID = 1  # _ControlSurfaces.inflow_velocities: rigid-body velocity, axial wake
_THRUST_NONE, _THRUST_GIVEN, _THRUST_COEFFICIENT = 0, 1, 2
# LiftingSurface attributes stacked over a group's surfaces, in the kernel's argument order
_SURFACE_KERNEL_FIELDS = (
    "position",
    "axis",
    "chord_direction",
    "leading_edge_motion",
    "area",
    "span",
    "rho",
    "lift_slope",
    "stall_angle",
    "stall_transition",
    "zero_lift_drag",
    "_k_induced",
    "normal_force_coefficient",
)


def _no_states(n: int) -> NDArray:
    return np.zeros((n, 0))


def _rows(ctx: BatchContext, value: Any, key: str) -> NDArray:
    """(n,) float rows of a command (array over all N ships or a scalar), checked finite."""
    if np.ndim(value) == 0:
        out = np.full(ctx.n, float(value))
    else:
        out = np.asarray(ctx.rows(np.asarray(value)), dtype=float)
        if out.shape != (ctx.n,):
            raise ValueError(
                f"commands[{key!r}] must be a scalar or an (N,) array over the ships; got shape "
                f"{np.shape(value)}"
            )
    if not np.all(np.isfinite(out)):
        raise ValueError(f"commands[{key!r}] must be finite; got {value!r}")
    return out


def _command_rows(ctx: BatchContext, key: str, default: float | None) -> NDArray | None:
    """Rows of ``ctx.commands[key]``; ``default`` (or None) when the key is absent."""
    value = ctx.commands.get(key, None)
    if value is None:
        return None if default is None else np.full(ctx.n, float(default))
    return _rows(ctx, value, key)


# =============================================================================================
# resistance, propeller, hull manoeuvring
# =============================================================================================
class BatchResistance(BatchForceModel):
    """Calm-water resistance X = −R_T(|u|) sign(u) for all ships (:class:`CalmWaterResistance`).

    R_T is the single-ship model's curve (a Holtrop–Mennen method or any callable), evaluated
    once per ship with a moving surge velocity (a Python call of ≈ 1.4 µs for Holtrop–Mennen:
    exact, and small beside the Froude–Krylov kernel at any N).
    """

    def __init__(
        self,
        curve: Callable[[float], float],
        *,
        name: str = "resistance",
        model: CalmWaterResistance | None = None,
    ) -> None:
        self._curve = curve
        self.name = name
        self.model = model

    @classmethod
    def from_model(cls, model: CalmWaterResistance) -> BatchResistance:
        """The batch version of a single-ship resistance model (same curve and name)."""
        return cls(model.curve, name=model.name, model=model)

    def kernel_parameters(self) -> NDArray:
        """The Holtrop–Mennen record of :func:`ship_gym.forces.resistance.holtrop_total`.

        Raises
        ------
        NotImplementedError
            For a resistance curve that is not Holtrop–Mennen.
        """
        if self.model is None:
            raise NotImplementedError(f"resistance {self.name!r} is a bare curve (numpy only)")
        return self.model.kernel_parameters()

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        force = np.zeros((ctx.n, 6))
        curve = self._curve
        for i, u in enumerate(ctx.nu[:, SURGE].tolist()):
            if u != 0.0:
                force[i, SURGE] = -math.copysign(float(curve(abs(u))), u)
        return force, _no_states(ctx.n)


@nb.njit(cache=True)
def _kt_kq(j, kt_c, kq_c, j0):  # pragma: no cover - compiled
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
        kt, kq = _kt_kq(va / (n * diameter), kt_c, kq_c, j0)
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


@nb.njit(cache=True, nogil=True)
def _propeller_rows(u, shaft, params, force, thrust_out):  # pragma: no cover - compiled
    """:func:`propeller_force` per row (params: the tuple of :attr:`BatchPropeller.params`)."""
    for i in range(u.shape[0]):
        thrust_out[i] = propeller_force(u[i], shaft[i], *params, force[i])


class BatchPropeller(BatchForceModel):
    """The :class:`Propeller` (eq. 2 of :mod:`ship_gym.forces.propeller`) for all ships.

    Reads the shaft speed n [rev/s] from ``ctx.commands["shaft_speed"]`` ((N,) or scalar; the
    model's default ``shaft_speed`` without it) and publishes the open-water thrust of the rows,
    (n,) [N], in ``ctx.shared["propeller_thrust"]`` for the rudder's slipstream.
    """

    def __init__(self, model: Propeller) -> None:
        ow = model.open_water
        self.propeller = model
        """The single-ship model (self-propulsion helpers, operating points)."""
        self.name = model.name
        self.default_shaft_speed = model.shaft_speed
        self._kt = np.array(ow.kt_coefficients, dtype=float)
        self._kq = np.array(ow.kq_coefficients, dtype=float)
        self._j0 = float(ow.j_zero_thrust)
        self._d = float(model.diameter)
        self._rho_d4 = float(model._rho_d4)
        self._one_minus_w = 1.0 - model.wake_fraction
        self._one_minus_t = 1.0 - model.thrust_deduction
        self._eta_r = float(model.relative_rotative_efficiency)
        self._astern = float(model.astern_thrust_factor)
        self._z_p = float(model.position[2])
        self._y_p = float(model.position[1])
        if not model.roll_reaction:
            self._roll_sign = 0.0
        else:
            self._roll_sign = -1.0 if model.handedness == "right" else 1.0
        self.params = (
            self._kt, self._kq, self._j0, self._d, self._rho_d4, self._one_minus_w,
            self._one_minus_t, self._eta_r, self._astern, self._z_p, self._y_p, self._roll_sign,
        )  # fmt: skip
        """The arguments of :func:`propeller_force` after (u, n)."""

    @classmethod
    def from_model(cls, model: Propeller) -> BatchPropeller:
        """The batch version of a single-ship propeller."""
        return cls(model)

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        n = _command_rows(ctx, SHAFT_SPEED_COMMAND, self.default_shaft_speed)
        if n is None:
            raise ValueError(
                f"no shaft speed: ctx.commands has no {SHAFT_SPEED_COMMAND!r} [rev/s] and the "
                "propeller has no default shaft_speed"
            )
        force = np.empty((ctx.n, 6))
        thrust = np.empty(ctx.n)
        _propeller_rows(np.ascontiguousarray(ctx.nu[:, SURGE]), n, self.params, force, thrust)
        ctx.shared["propeller_thrust"] = thrust
        return force, _no_states(ctx.n)


@nb.njit(cache=True, nogil=True)
def manoeuvring_force(nu, c_yv, c_yr, c_nv, c_nr, cda, x, crossflow, roll_lever, out):
    """HullManoeuvring.evaluate for one ship: eq. (1) + eq. (3), K = −z_H Y; writes out (6,)."""
    u, v, r = nu[0], nu[1], nu[5]
    au = abs(u)
    y = c_yv * au * v + c_yr * u * r
    n = c_nv * u * v + c_nr * au * r
    if crossflow:
        yc = 0.0
        nc = 0.0
        for k in range(x.shape[0]):
            vl = v + x[k] * r
            f = cda[k] * abs(vl) * vl
            yc += f
            nc += f * x[k]
        y += -yc
        n += -nc
    out[0] = 0.0
    out[1] = y
    out[2] = 0.0
    out[3] = -roll_lever * y
    out[4] = 0.0
    out[5] = n


@nb.njit(cache=True, nogil=True)
def _manoeuvring_rows(nu, params, force):  # pragma: no cover - compiled
    """:func:`manoeuvring_force` per row."""
    for i in range(nu.shape[0]):
        manoeuvring_force(nu[i], *params, force[i])


class BatchHullManoeuvring(BatchForceModel):
    """:class:`HullManoeuvring` (Clarke derivatives + cross-flow drag) for all ships.

    The strip sums of eq. (3) are accumulated in strip order (the single-ship model uses numpy's
    pairwise sum and a dot product: the two agree to rounding, not bit for bit).
    """

    def __init__(self, model: HullManoeuvring) -> None:
        self.name = model.name
        self._c = (model._c_yv, model._c_yr, model._c_nv, model._c_nr)
        self._cda = np.ascontiguousarray(model._cda, dtype=float)
        self._x = np.ascontiguousarray(model._x, dtype=float)
        self._crossflow = bool(model.crossflow)
        self._roll_lever = float(model.roll_lever)
        self.params = (*self._c, self._cda, self._x, self._crossflow, self._roll_lever)
        """The arguments of :func:`manoeuvring_force` after ν."""

    @classmethod
    def from_model(cls, model: HullManoeuvring) -> BatchHullManoeuvring:
        """The batch version of a single-ship manoeuvring model."""
        return cls(model)

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        force = np.empty((ctx.n, 6))
        _manoeuvring_rows(ctx.nu, self.params, force)
        return force, _no_states(ctx.n)


# =============================================================================================
# lifting surfaces behind a servo
# =============================================================================================
@nb.njit(cache=True)
def _coefficients(alpha, lift_slope, a_s, transition, cd0, k_induced, cn):  # pragma: no cover
    """LiftingSurface._coefficients: (C_L, C_D), eq. (3)–(6) of the lifting-surface module."""
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


@nb.njit(cache=True)
def _slipstream_speed(u_a, thrust, diameter, distance, rho, span):  # pragma: no cover
    """u_R of eq. (4) of the rudder module: rudder._slipstream (eq. 3) and the span fraction."""
    r0 = 0.5 * diameter
    u_inf = math.sqrt(u_a * u_a + 8.0 * thrust / (rho * math.pi * diameter * diameter))
    v_x = u_a + (u_inf - u_a) * 0.5 * (1.0 + distance / math.sqrt(distance**2 + r0 * r0))
    if v_x <= 0.0:
        v_x, r_x = 0.0, r0
    else:
        r_x = r0 * math.sqrt(0.5 * (u_a + u_inf) / v_x)
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
                    vx = _slipstream_speed(u_a, t_k, prop_d, prop_x, rho[k], span[k])
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
        alpha = (d - theta + math.pi) % (2.0 * math.pi) - math.pi
        cl, cd = _coefficients(
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


@nb.njit(cache=True, nogil=True)
def _surfaces_rows(
    nu, delta, inflow, wake, gamma_v, gamma_r, prop_d, prop_x, thrust_mode, thrust,
    pos, axis, chord, lead, area, span, rho, lift_slope, stall, transition, cd0, k_induced,
    cn, force,
):  # fmt: skip  # pragma: no cover - compiled
    """:func:`surface_group_force` per row (all surfaces of the group)."""
    for i in range(nu.shape[0]):
        surface_group_force(
            nu[i], delta[i], inflow, wake, gamma_v, gamma_r, prop_d, prop_x, thrust_mode,
            thrust[i], pos, axis, chord, lead, area, span, rho, lift_slope, stall, transition,
            cd0, k_induced, cn, 0, pos.shape[0], force[i],
        )  # fmt: skip


class BatchActuatedSurfaces(BatchForceModel):
    """A rudder, roll fins, T-foil or stern flaps behind a servo, for all ships.

    The batch version of ``Actuated(surface_group, servo, key, controller=…)``
    (:mod:`ship_gym.control.actuators`: the command sampled at each step start, the servo
    angle from the exact solution of its lag and rate limit), with the same kernels on rows:
    per-ship :class:`~ship_gym.control.actuators.ActuatorStates` (no ODE states); the command
    comes from the controller or from ``ctx.commands[command_key]`` ((N,) or scalar,
    missing → 0); fins, foil and flaps clip the angle again to their own ``max_angle``. With
    ``servo=None`` (a bare surface group) the angle is read from ``ctx.commands[key]``
    directly.

    Parameters
    ----------
    group : Rudder, RollFins, TFoil or SternFlaps
        The single-ship surface model (geometry, coefficients, inflow parameters).
    servo : ServoSpec or None
        Limits and lag of the servo.
    key : str
        Command key of the surface's angle (``"rudder"``, ``"fins"``, ``"t_foil"``,
        ``"flaps"``).
    command_key : str, optional
        Key of the open-loop commanded angle [rad] (default ``key + "_command"``).
    controller : HeadingAutopilot, FinController or RideController, optional
        Feedback law.
    """

    n_states = 0

    def __init__(
        self,
        group: SurfaceGroup,
        servo: ServoSpec | None,
        key: str,
        command_key: str | None = None,
        controller: Any = None,
    ) -> None:
        if isinstance(group, Rudder):
            self._inflow = _INFLOW_RUDDER
            self._wake = group.wake_fraction
            self._gamma = (group.drift_straightening, group.yaw_straightening)
            self._prop = (group.propeller_diameter, group.propeller_distance)
            self._rudder = group
            self._surface_limit = math.inf
        elif isinstance(group, RollFins | TFoil | SternFlaps):
            self._inflow = _INFLOW_RIGID
            self._wake = group.wake_fraction
            self._gamma = (1.0, 1.0)
            self._prop = (1.0, 0.0)
            self._rudder = None
            self._surface_limit = group.max_angle
        else:
            raise NotImplementedError(f"no batch version of surface group {type(group).__name__}")
        if servo is None and controller is not None:
            raise ValueError("a controller needs a servo (wrap the surfaces in Actuated)")
        self.group = group
        self.name = group.name
        self.servo = servo
        self.key = key
        self.command_key = command_key or f"{key}_command"
        self.controller = controller
        self.kind = NO_CONTROLLER if controller is None else int(controller.kind)
        self.gains = np.zeros(4) if controller is None else np.asarray(controller.gains(), float)
        self._geometry = tuple(
            np.array([getattr(sf, name) for sf in group.surfaces], dtype=float)
            for name in _SURFACE_KERNEL_FIELDS
        )
        self.states = ActuatorStates(1)

    @classmethod
    def from_model(cls, model: Actuated | SurfaceGroup) -> BatchActuatedSurfaces:
        """The batch version of an ``Actuated`` surface group (or of a bare surface group)."""
        if isinstance(model, Actuated):
            return cls(
                model.model,  # type: ignore[arg-type]
                model.servo,
                model.key,
                model.command_key,
                model.controller,
            )
        if isinstance(model, SurfaceGroup):
            key = {Rudder: "rudder"}.get(type(model)) or getattr(model, "command_key", "")
            return cls(model, None, key)
        raise NotImplementedError(f"no batch version of {type(model).__name__}")

    @property
    def angle(self) -> NDArray:
        """(N,) servo angles at the last accepted step [rad] (a view; zeros without a servo)."""
        return self.states.delta

    def bind(self, n_ships: int, n_comp: int) -> None:
        self.states = ActuatorStates(n_ships)

    def reset(self, ships: NDArray[np.int64], ctx: BatchContext) -> None:
        self.states.reset(ships, ctx.t, ctx.eta, ctx.nu)

    def reference(self, ctx: BatchContext) -> NDArray:
        """(n,) the law's reference of the rows: ψ_ref [rad] (autopilot; the heading at reset
        without a ``heading`` command) or the open-loop commanded angle [rad]."""
        if self.kind == 1:
            ref = _command_rows(ctx, self.controller.heading_key, None)
            return ctx.rows(self.states.initial_heading) if ref is None else ref
        if self.kind == NO_CONTROLLER:
            return _command_rows(ctx, self.command_key, 0.0)  # type: ignore[return-value]
        return np.zeros(ctx.n)

    def _kernel_args(self) -> tuple:
        st, sv = self.states, self.servo
        assert sv is not None
        return (
            self.kind, self.gains, sv.max_angle, sv.max_rate, sv.lag, st.delta, st.integral,
            st.t_step, st.eta_step, st.nu_step,
        )  # fmt: skip

    def _thrust(self, ctx: BatchContext) -> tuple[int, NDArray]:
        """Rudder._thrust's sources in its order: shared thrust, thrust command, C_Th."""
        shared = ctx.shared.get("propeller_thrust", None)
        if shared is not None:
            return _THRUST_GIVEN, np.asarray(shared, dtype=float)
        given = _command_rows(ctx, "propeller_thrust", None)
        if given is not None:
            return _THRUST_GIVEN, given
        assert self._rudder is not None
        c_th = _command_rows(ctx, "propeller_thrust_coefficient", self._rudder.thrust_coefficient)
        if c_th is None:
            return _THRUST_NONE, np.zeros(ctx.n)
        return _THRUST_COEFFICIENT, c_th

    def surface_force(self, ctx: BatchContext, angle: NDArray) -> NDArray:
        """(n, 6) force and moment about O of the surfaces at applied angles ``angle`` [rad]."""
        if self._inflow == _INFLOW_RUDDER:
            mode, thrust = self._thrust(ctx)
        else:
            mode, thrust = _THRUST_NONE, angle
            angle = np.minimum(np.maximum(angle, -self._surface_limit), self._surface_limit)
        force = np.empty((ctx.n, 6))
        _surfaces_rows(
            ctx.nu, np.ascontiguousarray(angle, dtype=float), self._inflow, self._wake,
            *self._gamma, *self._prop, mode, thrust, *self._geometry, force,
        )  # fmt: skip
        return force

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        if self.servo is None:
            angle = _command_rows(ctx, self.key, 0.0)
            return self.surface_force(ctx, angle), _no_states(ctx.n)  # type: ignore[arg-type]
        angle = np.empty(ctx.n)
        actuator_angle_rows(
            ctx.ships, np.ascontiguousarray(ctx.t, dtype=float), self.reference(ctx),
            *self._kernel_args(), angle,
        )  # fmt: skip
        return self.surface_force(ctx, angle), _no_states(ctx.n)

    def commit(self, ctx: BatchContext, states: NDArray) -> None:
        if self.servo is None:
            return
        actuator_commit_rows(
            ctx.ships, np.ascontiguousarray(ctx.t, dtype=float), ctx.eta, ctx.nu,
            self.reference(ctx), *self._kernel_args(),
        )  # fmt: skip


# =============================================================================================
# conversion and trim
# =============================================================================================
def batch_control_model(model: ForceModel) -> BatchForceModel:
    """The batch version of a single-ship control model (see the module's table).

    Raises
    ------
    NotImplementedError
        For a model without a batch version (e.g. added resistance in waves).
    """
    if isinstance(model, CalmWaterResistance):
        return BatchResistance.from_model(model)
    if isinstance(model, Propeller):
        return BatchPropeller.from_model(model)
    if isinstance(model, HullManoeuvring):
        return BatchHullManoeuvring.from_model(model)
    if isinstance(model, Actuated) and isinstance(model.model, SurfaceGroup):
        return BatchActuatedSurfaces.from_model(model)
    if isinstance(model, Rudder | RollFins | TFoil | SternFlaps):
        return BatchActuatedSurfaces.from_model(model)
    raise NotImplementedError(
        f"no batch version of control model {type(model).__name__!r} ({model.name!r})"
    )


def trim_batch_shaft_speed(
    batch: Any, propeller: Propeller, speed: float, iterations: int = 4
) -> NDArray:
    """Per-ship shaft speeds [rev/s] that make ``speed`` a steady straight run (and set them).

    :func:`ship_gym.engine.ship.trim_shaft_speed` for every ship of a
    :class:`~ship_gym.engine.batch.BatchSimulator` at its current state (call it right after
    construction): the surge force of everything but the propeller at ν = (U, 0, …, 0) is
    balanced by (1 − t) T(n, (1 − w) U) (Brent on n), a few fixed-point iterations for the
    rudder's slipstream drag. Returns the (N,) shaft speeds, also put in
    ``batch.commands["shaft_speed"]``.

    Parameters
    ----------
    batch : BatchSimulator
        The ships (their states are restored afterwards).
    propeller : Propeller
        The single-ship propeller (its :meth:`Propeller.operating_point`).
    speed : float
        U [m/s].
    iterations : int
        Fixed-point iterations.
    """
    saved = batch.nu.copy()
    nu = np.zeros_like(saved)
    nu[:, SURGE] = float(speed)
    batch.nu = nu
    n = np.broadcast_to(
        np.asarray(batch.commands.get(SHAFT_SPEED_COMMAND, propeller.shaft_speed_for(speed))),
        (batch.n_ships,),
    ).astype(float)
    try:
        for _ in range(iterations):
            batch.commands = {**batch.commands, SHAFT_SPEED_COMMAND: n.copy()}
            breakdown: Mapping[str, NDArray] = batch.force_breakdown()
            others = sum(v[:, SURGE] for k, v in breakdown.items() if k != propeller.name)
            for s in range(batch.n_ships):

                def net(nn: float, other: float = float(others[s])) -> float:
                    return propeller.operating_point(speed, nn).surge_force + other

                hi = 2.0 * n[s] + 0.1
                while net(hi) < 0.0:
                    hi *= 2.0
                n[s] = float(brentq(net, 0.0, hi, xtol=1e-12))
    finally:
        batch.nu = saved
    batch.commands = {**batch.commands, SHAFT_SPEED_COMMAND: n.copy()}
    return n
