"""Actuator dynamics (servo): saturation, rate limit and first-order lag, as part of the state.

A control surface (rudder, fins, T-foil) does not follow its command instantly. Its angle δ is a
state integrated with the ship (Matusiak integrates the rudder as a 13th ODE):

    δ̇ = clip((sat(δ_c) − δ) / T, −δ̇_max, +δ̇_max),

with sat(·) the angle limit ±δ_max, T the lag time constant and δ̇_max the rate limit. With T → 0
the servo is a pure rate-limited follower: δ̇ = δ̇_max · clip((sat(δ_c) − δ)/(δ̇_max T_min), −1, 1)
with a small internal T_min (a linear zone instead of a bang-bang switch, so explicit integrators
do not chatter).

Limits are honoured **exactly**: every slope the integrator sees is within ±δ̇_max and Runge–Kutta
and Adams weights of a step are positive, so |Δδ| ≤ δ̇_max Δt per step; the angle applied to the
hydrodynamic model is clipped to ±δ_max.

Defaults: rudder ±35°, 2.32 °/s — IMO Resolution A.601(15)/SOLAS II-1 Reg. 29.3.2: the steering
gear must turn the rudder from 35° on one side to 30° on the other in at most 28 s, i.e.
65°/28 s ≈ 2.32 °/s; this is the slowest rate allowed (a usual merchant-ship value). Fins and foils
move faster (≈ 10–20 °/s for modern electro-hydraulic stabilisers).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ship_gym.forces.base import ForceContext, ForceModel


@dataclass(frozen=True)
class ServoSpec:
    """Limits and lag of one actuator.

    Parameters
    ----------
    max_angle : float
        Saturation ±δ_max [rad].
    max_rate : float
        Rate limit ±δ̇_max [rad/s].
    time_constant : float
        First-order lag T [s] (0: pure rate-limited follower).
    """

    max_angle: float
    max_rate: float
    time_constant: float = 0.0

    def __post_init__(self) -> None:
        if not (np.isfinite(self.max_angle) and 0.0 < self.max_angle <= np.pi / 2):
            raise ValueError(f"max_angle must be in (0, π/2] rad, got {self.max_angle!r}")
        if not (np.isfinite(self.max_rate) and self.max_rate > 0.0):
            raise ValueError(f"max_rate must be a positive rate [rad/s], got {self.max_rate!r}")
        if not (np.isfinite(self.time_constant) and self.time_constant >= 0.0):
            raise ValueError(f"time_constant must be >= 0 [s], got {self.time_constant!r}")

    def rate(self, angle: np.ndarray | float, command: np.ndarray | float) -> np.ndarray:
        """δ̇ [rad/s] for the current angle and command (vectorised over ships)."""
        target = np.clip(command, -self.max_angle, self.max_angle)
        # a pure follower gets a linear zone of 0.05 s so that it does not chatter
        tau = max(self.time_constant, 0.05)
        return np.clip((target - np.asarray(angle)) / tau, -self.max_rate, self.max_rate)

    def applied(self, angle: np.ndarray | float) -> np.ndarray:
        """The angle the hydrodynamics sees: the state clipped to ±δ_max."""
        return np.clip(angle, -self.max_angle, self.max_angle)


RUDDER_SERVO = ServoSpec(max_angle=np.radians(35.0), max_rate=np.radians(65.0 / 28.0))
"""IMO minimum steering-gear rate (35° → −30° in 28 s) and ±35° limit."""

FIN_SERVO = ServoSpec(max_angle=np.radians(25.0), max_rate=np.radians(15.0), time_constant=0.1)
"""Typical roll-stabiliser fins: ±25°, 15 °/s."""

FOIL_SERVO = ServoSpec(max_angle=np.radians(15.0), max_rate=np.radians(20.0), time_constant=0.1)
"""Typical ride-control T-foil / flaps: ±15°, 20 °/s."""


class Controller(Protocol):
    """A feedback law producing an actuator command, with states integrated with the ship.

    Implemented by :class:`~ship_gym.control.autopilot.HeadingAutopilot`,
    :class:`~ship_gym.control.stabilisers.FinController` and
    :class:`~ship_gym.control.stabilisers.RideController`.
    """

    n_states: int

    def initial(self, ctx: ForceContext) -> dict:
        """Quantities remembered at reset (e.g. the initial heading)."""
        ...

    def command(self, ctx: ForceContext, states: np.ndarray, initial: dict) -> float:
        """Commanded angle [rad] before saturation."""
        ...

    def state_rates(
        self,
        ctx: ForceContext,
        states: np.ndarray,
        initial: dict,
        command: float,
        achievable: float,
    ) -> np.ndarray:
        """Derivatives of the controller states (``achievable`` = the saturated command)."""
        ...


class Actuated(ForceModel):
    """A force model whose control angle comes from a servo integrated with the ship.

    The wrapped model reads its angle from ``ctx.commands[key]``; this wrapper owns the servo
    state δ, takes the *command* from a feedback :class:`Controller` if one is given, else from
    ``ctx.commands[command_key]`` (default ``key + "_command"``; missing → 0), and hands the
    wrapped model a context in which ``commands[key]`` is the applied angle.

    Parameters
    ----------
    model : ForceModel
        The hydrodynamic model of the surface (rudder, fins, T-foil…), stateless.
    servo : ServoSpec
        Limits and lag.
    key : str
        Command key the wrapped model reads its angle from (``"rudder"``, ``"fins"``…).
    command_key : str, optional
        Key of an open-loop commanded angle [rad].
    controller : Controller, optional
        Feedback law (autopilot, fin or ride controller); its states follow the servo's.
    """

    def __init__(
        self,
        model: ForceModel,
        servo: ServoSpec,
        key: str,
        command_key: str | None = None,
        controller: Controller | None = None,
    ) -> None:
        if model.n_states:
            raise ValueError(
                f"the wrapped model {model.name!r} has states of its own; wrap a stateless model"
            )
        self.model = model
        self.servo = servo
        self.key = key
        self.command_key = command_key or f"{key}_command"
        self.name = model.name
        self.added_mass = model.added_mass
        self.controller = controller
        self.n_states = 1 + (0 if controller is None else int(controller.n_states))
        self._initial: dict = {}

    def reset(self, t0: float, ctx: ForceContext) -> None:
        """Let the controller remember what it needs (e.g. the initial heading)."""
        self._initial = {} if self.controller is None else self.controller.initial(ctx)
        self.model.reset(t0, ctx)

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Wrapped force at the applied angle; servo (and controller) state rates."""
        angle = float(states[0])
        applied = float(self.servo.applied(angle))
        if self.controller is None:
            command = float(ctx.commands.get(self.command_key, 0.0))
            extra = np.zeros(0)
        else:
            command = float(self.controller.command(ctx, states[1:], self._initial))
            achievable = float(np.clip(command, -self.servo.max_angle, self.servo.max_angle))
            extra = self.controller.state_rates(ctx, states[1:], self._initial, command, achievable)
        inner = ForceContext(
            t=ctx.t,
            eta=ctx.eta,
            nu=ctx.nu,
            rotation=ctx.rotation,
            forward_speed=ctx.forward_speed,
            wave_phasor=ctx.wave_phasor,
            acceleration_extrapolated=ctx.acceleration_extrapolated,
            commands={**ctx.commands, self.key: applied},
            shared=ctx.shared,
        )
        force, _ = self.model.evaluate(inner, np.zeros(0))
        rates = np.concatenate([[float(self.servo.rate(angle, command))], extra])
        return force, rates
