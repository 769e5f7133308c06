"""Vectorised control force models for :class:`~ship_gym.engine.batch.BatchSimulator`.

The single-ship control models (:mod:`ship_gym.forces.propeller`, :mod:`ship_gym.forces.resistance`,
:mod:`ship_gym.forces.manoeuvring`, :mod:`ship_gym.forces.rudder`, :mod:`ship_gym.forces.fins`
behind :class:`ship_gym.control.actuators.Actuated`, with the controllers of
:mod:`ship_gym.control.autopilot` and :mod:`ship_gym.control.stabilisers`) written with a leading
ship axis. Each class is built from a single-ship model by ``from_model`` (its
``kernel_parameters()`` are taken, nothing is re-derived), evaluates all rows of a
:class:`~ship_gym.forces.base.BatchContext` in one call with the row kernels that live beside
the physics (:func:`ship_gym.forces.propeller.propeller_force`,
:func:`ship_gym.forces.manoeuvring.manoeuvring_force`,
:func:`ship_gym.forces.lifting_surface.surface_group_force`, the servo and control-law kernels of
:mod:`ship_gym.control`) — the same kernels the compiled loop calls — and keeps the actuators'
sampled states per ship (:class:`~ship_gym.control.actuators.ActuatorStates`). Commands are (N,)
arrays over all ships or scalars (:meth:`BatchContext.rows`).

The single-ship propeller and manoeuvring models evaluate through the same kernels; the surface
groups' single-ship ``evaluate`` is still numpy per surface (same arithmetic), so a batch agrees
with the same ships under :class:`~ship_gym.engine.batch.PerShipForceModel` or in single-ship
:class:`~ship_gym.engine.simulator.Simulator` runs to rounding (tested,
``tests/engine/test_batch_control.py``). The equations and their sources are in the modules of
the single-ship models; this module adds none.

==========================================  ==================================================
single-ship model                           batch model
==========================================  ==================================================
CalmWaterResistance                         :class:`BatchResistance` (R_T(|u|) per ship: the
                                            curve; compiled: ``holtrop_total``)
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
from typing import Any, cast, overload

import numba as nb
import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from ship_gym.control.actuators import (
    NO_CONTROLLER,
    Actuated,
    ActuatedSurfacesRecord,
    ActuatorKernelArguments,
    ActuatorStates,
    ServoSpec,
    actuated_surfaces_end,
    actuated_surfaces_row,
    actuated_surfaces_start,
    actuator_angle_rows,
    actuator_commit_rows,
    actuator_kernel_arguments,
    law_parameters,
)
from ship_gym.conventions import SURGE
from ship_gym.forces.base import BatchContext, BatchForceModel, ForceModel, RowLayout, RowPart
from ship_gym.forces.fins import RollFins, SternFlaps, TFoil
from ship_gym.forces.lifting_surface import SurfaceGroup, surface_group_force
from ship_gym.forces.manoeuvring import (
    HullManoeuvring,
    ManoeuvringKernelParameters,
    manoeuvring_force,
    manoeuvring_row,
)
from ship_gym.forces.propeller import (
    SHAFT_SPEED_COMMAND,
    Propeller,
    PropellerKernelParameters,
    PropellerRecord,
    propeller_force,
    propeller_row,
)
from ship_gym.forces.resistance import CalmWaterResistance, resistance_row
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
_INFLOW_RUDDER = 0  # Rudder.inflow: wake, slipstream, flow straightening
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
    "induced_drag_factor",
    "normal_force_coefficient",
)

# the stacked kernel fields of a surface group, in _SURFACE_KERNEL_FIELDS order
SurfaceGeometry = tuple[
    NDArray, NDArray, NDArray, NDArray, NDArray, NDArray, NDArray, NDArray, NDArray, NDArray,
    NDArray, NDArray, NDArray,
]  # fmt: skip


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


@overload
def _command_rows(ctx: BatchContext, key: str, default: float) -> NDArray: ...
@overload
def _command_rows(ctx: BatchContext, key: str, default: float | None) -> NDArray | None: ...
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
    once per ship with a moving surge velocity (one Python call per ship: exact, and small beside
    the Froude–Krylov kernel at any N; measured: docs/benchmarks.md).
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

    def pack(self, layout: RowLayout) -> RowPart | None:
        holtrop = self.kernel_parameters()  # raises for a bare curve (numpy only)
        return RowPart(resistance_row, (np.ascontiguousarray(holtrop, dtype=float),))


@nb.njit(cache=True, nogil=True)
def _propeller_rows(
    u, shaft, params: PropellerKernelParameters, force, thrust_out
):  # pragma: no cover - compiled
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
        self.propeller = model
        """The single-ship model (self-propulsion helpers, operating points)."""
        self.name = model.name
        self.default_shaft_speed = model.shaft_speed
        self.params = model.kernel_parameters()
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

    def pack(self, layout: RowLayout) -> RowPart | None:
        kt, kq, *scalars = self.params
        c = np.ascontiguousarray
        record = PropellerRecord._make((
            c(kt, float), c(kq, float), *(float(x) for x in scalars),
            layout.column(SHAFT_SPEED_COMMAND, self.default_shaft_speed),
            layout.slot("propeller_thrust"),
        ))  # fmt: skip
        return RowPart(propeller_row, record)


@nb.njit(cache=True, nogil=True)
def _manoeuvring_rows(
    nu, params: ManoeuvringKernelParameters, force
):  # pragma: no cover - compiled
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
        self.params = model.kernel_parameters()
        """The arguments of :func:`manoeuvring_force` after ν."""

    @classmethod
    def from_model(cls, model: HullManoeuvring) -> BatchHullManoeuvring:
        """The batch version of a single-ship manoeuvring model."""
        return cls(model)

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        force = np.empty((ctx.n, 6))
        _manoeuvring_rows(ctx.nu, self.params, force)
        return force, _no_states(ctx.n)

    def pack(self, layout: RowLayout) -> RowPart | None:
        p = self.params
        c = np.ascontiguousarray
        record = (
            float(p[0]), float(p[1]), float(p[2]), float(p[3]), c(p[4], float), c(p[5], float),
            bool(p[6]), float(p[7]),
        )  # fmt: skip
        return RowPart(manoeuvring_row, record)


# =============================================================================================
# lifting surfaces behind a servo
# =============================================================================================
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

    Attributes
    ----------
    inflow, wake_fraction, straightening, propeller_geometry, surface_limit
        The inflow arguments of :func:`~ship_gym.forces.lifting_surface.surface_group_force`
        (rudder or rigid-body inflow, 1 − w, (γ_v, γ_r), (D_P [m], x_P [m])) and the surfaces'
        own angle limit [rad] (∞ for the rudder).
    rudder : Rudder or None
        The rudder (its thrust sources for the slipstream), None for fins, foil and flaps.
    geometry : tuple of numpy.ndarray
        The surfaces' stacked kernel fields (:data:`_SURFACE_KERNEL_FIELDS` order).
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
            self.inflow = _INFLOW_RUDDER
            self.wake_fraction = group.wake_fraction
            self.straightening = (group.drift_straightening, group.yaw_straightening)
            self.propeller_geometry = (group.propeller_diameter, group.propeller_distance)
            self.rudder: Rudder | None = group
            self.surface_limit = math.inf
        elif isinstance(group, RollFins | TFoil | SternFlaps):
            self.inflow = _INFLOW_RIGID
            self.wake_fraction = group.wake_fraction
            self.straightening = (1.0, 1.0)
            self.propeller_geometry = (1.0, 0.0)
            self.rudder = None
            self.surface_limit = group.max_angle
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
        self.kind, self.gains = law_parameters(controller)
        self.geometry = cast(
            SurfaceGeometry,  # one array per name of _SURFACE_KERNEL_FIELDS
            tuple(
                np.array([getattr(sf, name) for sf in group.surfaces], dtype=float)
                for name in _SURFACE_KERNEL_FIELDS
            ),
        )
        self.states = ActuatorStates(1)

    @classmethod
    def from_model(cls, model: Actuated | SurfaceGroup) -> BatchActuatedSurfaces:
        """The batch version of an ``Actuated`` surface group (or of a bare surface group)."""
        if isinstance(model, Actuated):
            if not isinstance(model.model, SurfaceGroup):
                raise NotImplementedError(
                    f"no batch version of surface group {type(model.model).__name__}"
                )
            return cls(
                model.model,
                model.servo,
                model.key,
                model.command_key,
                model.controller,
            )
        if isinstance(model, SurfaceGroup):
            key = "rudder" if type(model) is Rudder else getattr(model, "command_key", "")
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
            return _command_rows(ctx, self.command_key, 0.0)
        return np.zeros(ctx.n)

    def _kernel_args(self) -> ActuatorKernelArguments:
        assert self.servo is not None
        return actuator_kernel_arguments(self.kind, self.gains, self.servo, self.states)

    def _thrust(self, ctx: BatchContext) -> tuple[int, NDArray]:
        """Rudder._thrust's sources in its order: shared thrust, thrust command, C_Th."""
        shared = ctx.shared.get("propeller_thrust", None)
        if shared is not None:
            return _THRUST_GIVEN, np.asarray(shared, dtype=float)
        given = _command_rows(ctx, "propeller_thrust", None)
        if given is not None:
            return _THRUST_GIVEN, given
        assert self.rudder is not None
        c_th = _command_rows(ctx, "propeller_thrust_coefficient", self.rudder.thrust_coefficient)
        if c_th is None:
            return _THRUST_NONE, np.zeros(ctx.n)
        return _THRUST_COEFFICIENT, c_th

    def surface_force(self, ctx: BatchContext, angle: NDArray) -> NDArray:
        """(n, 6) force and moment about O of the surfaces at applied angles ``angle`` [rad]."""
        if self.inflow == _INFLOW_RUDDER:
            mode, thrust = self._thrust(ctx)
        else:
            mode, thrust = _THRUST_NONE, angle
            angle = np.minimum(np.maximum(angle, -self.surface_limit), self.surface_limit)
        force = np.empty((ctx.n, 6))
        _surfaces_rows(
            ctx.nu, np.ascontiguousarray(angle, dtype=float), self.inflow, self.wake_fraction,
            *self.straightening, *self.propeller_geometry, mode, thrust, *self.geometry, force,
        )  # fmt: skip
        return force

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        if self.servo is None:
            angle = _command_rows(ctx, self.key, 0.0)
            return self.surface_force(ctx, angle), _no_states(ctx.n)
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

    def pack(self, layout: RowLayout) -> RowPart | None:
        if self.servo is None:  # the angle as a command
            raise NotImplementedError(f"the bare surface group {self.name!r} is numpy only")
        has_propeller = "propeller_thrust" in layout.slots
        mode, c_th = _THRUST_NONE, 0.0
        if self.rudder is not None:
            if has_propeller:
                mode = _THRUST_GIVEN
            elif self.rudder.thrust_coefficient is not None:
                mode, c_th = _THRUST_COEFFICIENT, float(self.rudder.thrust_coefficient)
            if not has_propeller:
                # without a propeller the numpy path takes the slipstream from these commands;
                # the compiled kernel knows only the rudder's C_Th
                layout.numpy_only_commands |= {"propeller_thrust", "propeller_thrust_coefficient"}
        if self.kind == 1:
            # without a heading command: the heading at each ship's reset
            ref_col = layout.column(
                self.controller.heading_key, lambda: self.states.initial_heading
            )
        elif self.kind == NO_CONTROLLER:
            ref_col = layout.column(self.command_key, 0.0)
        else:
            ref_col = layout.column(f"{self.name}_unused", 0.0)
        n = layout.n_ships
        held = getattr(self, "_row_held", None)
        if held is None or held[0].shape != (n,):
            held = (np.zeros(n), np.zeros(n))  # the target and integral rate held over a step
            self._row_held = held
        st = self.states
        c = np.ascontiguousarray
        record = ActuatedSurfacesRecord._make((
            *(c(g, float) for g in self.geometry), int(self.inflow), float(self.wake_fraction),
            float(self.straightening[0]), float(self.straightening[1]),
            float(self.propeller_geometry[0]), float(self.propeller_geometry[1]), mode, c_th,
            layout.slot("propeller_thrust") if mode == _THRUST_GIVEN else 0,
            float(self.surface_limit), float(self.servo.max_angle), float(self.servo.max_rate),
            float(self.servo.lag), int(self.kind), c(self.gains, float), ref_col, st.delta,
            st.integral, st.t_step, st.eta_step, st.nu_step, *held,
        ))  # fmt: skip
        return RowPart(
            actuated_surfaces_row, record, 0, actuated_surfaces_start, actuated_surfaces_end
        )


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
            others = sum(
                (v[:, SURGE] for k, v in breakdown.items() if k != propeller.name),
                start=np.zeros(batch.n_ships),
            )
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
