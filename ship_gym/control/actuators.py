"""Actuator dynamics (servo): saturation, rate limit and first-order lag, sampled exactly.

A control surface (rudder, fins, T-foil) does not follow its command instantly. Its angle δ obeys

    δ̇ = clip((sat(δ_c) − δ) / T, −δ̇_max, +δ̇_max),

with sat(·) the angle limit ±δ_max, T the lag time constant (at least :data:`MIN_LAG`: a pure
rate-limited follower gets a small linear zone instead of a bang-bang switch) and δ̇_max the rate
limit.

**Sampled, exact.** The command δ_c (open-loop, or from a feedback law: autopilot, fin or ride
controller) is sampled at the start of every physics step from the state accepted at that
instant and held over the step (a digital controller running at the physics rate). With the
target held, the servo equation has a closed-form solution (:func:`servo_angle`): a ramp at
±δ̇_max while |target − δ| > δ̇_max T, then an exponential approach with time constant T. The
force models see δ(t) of that solution at every evaluation time of the step, and the angle is
advanced by it when the step is accepted. So the servo never overshoots its target, never moves
faster than δ̇_max, and settles to a constant command under every integrator and time step —
the servo is not an ODE state of the integrator (an explicit multistep update of the stiff lag,
Holloway's scheme at Δt ≈ T, made a constant +5° fin command cycle between 2.7° and 7.2°). A
controller's integral state is advanced at the same instants by forward Euler with its rate at
the step start (back-calculation anti-windup, :mod:`ship_gym.control.autopilot`).

The per-ship states (angle, integral, sampled time and state, initial heading) live in
:class:`ActuatorStates`, rows over ships; the compiled engine
(:mod:`ship_gym.engine.compiled`) updates the same arrays with the same kernels
(:func:`actuator_target`, :func:`servo_angle`).

Defaults: rudder ±35°, 2.32 °/s — IMO Resolution A.601(15)/SOLAS II-1 Reg. 29.3.2: the steering
gear must turn the rudder from 35° on one side to 30° on the other in at most 28 s, i.e.
65°/28 s ≈ 2.32 °/s; this is the slowest rate allowed (a usual merchant-ship value). Fins and foils
move faster (≈ 10–20 °/s for modern electro-hydraulic stabilisers).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, NamedTuple, Protocol, cast

import numba as nb
import numpy as np
from numpy.typing import NDArray

from ship_gym.control.autopilot import heading_autopilot_law
from ship_gym.control.stabilisers import fin_law, ride_law
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.forces.lifting_surface import surface_group_force
from ship_gym.typing import FloatArray

MIN_LAG = 0.05
"""Smallest servo lag T [s]: the linear zone of a pure rate-limited follower."""

NO_CONTROLLER = 0
"""Law index of an open-loop actuator (the command comes from ``commands``)."""


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
        First-order lag T [s] (0: pure rate-limited follower, lag :data:`MIN_LAG`).
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

    @property
    def lag(self) -> float:
        """The lag T used in the servo equation [s]: max(time_constant, :data:`MIN_LAG`)."""
        return max(self.time_constant, MIN_LAG)

    def angle_after(self, angle: float, command: float, elapsed: float) -> float:
        """δ [rad] ``elapsed`` seconds after ``angle`` with ``command`` held (exact solution)."""
        target = min(max(float(command), -self.max_angle), self.max_angle)
        return float(servo_angle(float(angle), target, float(elapsed), self.max_rate, self.lag))

    def applied(self, angle: np.ndarray | float) -> np.ndarray:
        """The angle the hydrodynamics sees: the state clipped to ±δ_max."""
        return np.clip(angle, -self.max_angle, self.max_angle)


RUDDER_SERVO = ServoSpec(max_angle=np.radians(35.0), max_rate=np.radians(65.0 / 28.0))
"""IMO minimum steering-gear rate (35° → −30° in 28 s) and ±35° limit."""

FIN_SERVO = ServoSpec(max_angle=np.radians(25.0), max_rate=np.radians(15.0), time_constant=0.1)
"""Typical roll-stabiliser fins: ±25°, 15 °/s."""

FOIL_SERVO = ServoSpec(max_angle=np.radians(15.0), max_rate=np.radians(20.0), time_constant=0.1)
"""Typical ride-control T-foil / flaps: ±15°, 20 °/s."""


# =============================================================================================
# kernels (shared by the single-ship model, the row engine and its compiled backend)
# =============================================================================================
@nb.njit(cache=True, nogil=True)
def servo_angle(delta0, target, elapsed, max_rate, lag):  # pragma: no cover - compiled
    """Exact solution of δ̇ = clip((target − δ)/T, ±δ̇_max) after ``elapsed`` seconds.

    A ramp at ±δ̇_max while |target − δ| > δ̇_max T, then target − e₁ exp(−t/T) with
    |e₁| ≤ δ̇_max T: monotone toward the target, never past it, never faster than δ̇_max.

    Parameters
    ----------
    delta0 : float
        Angle at the start [rad].
    target : float
        Saturated command, held [rad].
    elapsed : float
        Time since the start [s] (≥ 0).
    max_rate : float
        δ̇_max [rad/s].
    lag : float
        T [s] (> 0).
    """
    e = target - delta0
    band = max_rate * lag
    ae = abs(e)
    if ae > band:
        ramp = (ae - band) / max_rate
        if elapsed <= ramp:
            return delta0 + math.copysign(max_rate * elapsed, e)
        e = math.copysign(band, e)
        elapsed -= ramp
    return target - e * math.exp(-elapsed / lag)


@nb.njit(cache=True, nogil=True)
def control_law(kind, gains, eta, nu, integral, reference, limit):  # pragma: no cover
    """(δ_c [rad], d/dt integral) of feedback law ``kind`` at a sampled state.

    1: :func:`ship_gym.control.autopilot.heading_autopilot_law` (reference ψ_ref);
    2: :func:`ship_gym.control.stabilisers.fin_law`; 3: :func:`ship_gym.control.stabilisers.
    ride_law`; 0: open loop (δ_c = ``reference``, the commanded angle).
    """
    if kind == 1:
        return heading_autopilot_law(gains, eta, nu, integral, reference, limit)
    if kind == 2:
        return fin_law(gains, eta, nu, integral, limit)
    if kind == 3:
        return ride_law(gains, nu), 0.0
    return reference, 0.0


@nb.njit(cache=True, nogil=True)
def actuator_target(kind, gains, eta, nu, integral, reference, max_angle):  # pragma: no cover
    """(saturated target [rad], integral rate) of an actuator from its sampled inputs."""
    command, rate = control_law(kind, gains, eta, nu, integral, reference, max_angle)
    return min(max(command, -max_angle), max_angle), rate


@nb.njit(cache=True, nogil=True)
def actuator_angle_rows(
    ships, t, reference, kind, gains, max_angle, max_rate, lag, delta, integral, t_step,
    eta_step, nu_step, out,
):  # fmt: skip  # pragma: no cover - compiled
    """Angles δ(t) [rad] of rows r (ship ``ships[r]``) at times ``t[r]`` within their step."""
    for r in range(ships.shape[0]):
        s = ships[r]
        target, _ = actuator_target(
            kind, gains, eta_step[s], nu_step[s], integral[s], reference[r], max_angle
        )
        out[r] = servo_angle(delta[s], target, t[r] - t_step[s], max_rate, lag)


@nb.njit(cache=True, nogil=True)
def actuator_commit_rows(
    ships, t, eta, nu, reference, kind, gains, max_angle, max_rate, lag, delta, integral,
    t_step, eta_step, nu_step,
):  # fmt: skip  # pragma: no cover - compiled
    """Advance the actuators of rows r to their accepted state (t[r], η[r], ν[r]): angle by
    :func:`servo_angle`, integral by forward Euler, then sample the new state."""
    for r in range(ships.shape[0]):
        s = ships[r]
        target, rate = actuator_target(
            kind, gains, eta_step[s], nu_step[s], integral[s], reference[r], max_angle
        )
        elapsed = t[r] - t_step[s]
        delta[s] = servo_angle(delta[s], target, elapsed, max_rate, lag)
        integral[s] += elapsed * rate
        t_step[s] = t[r]
        for i in range(6):
            eta_step[s, i] = eta[r, i]
            nu_step[s, i] = nu[r, i]


class Controller(Protocol):
    """A feedback law producing an actuator command (sampled at the physics rate).

    Implemented by :class:`~ship_gym.control.autopilot.HeadingAutopilot`,
    :class:`~ship_gym.control.stabilisers.FinController` and
    :class:`~ship_gym.control.stabilisers.RideController`: ``kind`` selects the law in
    :func:`control_law`, ``gains()`` its four parameters.
    """

    kind: ClassVar[int]

    def gains(self) -> FloatArray:
        """The law's parameters (4,)."""
        ...


def law_parameters(controller: Controller | None) -> tuple[int, FloatArray]:
    """(law index of :func:`control_law`, its four gains) of a controller (None: open loop)."""
    if controller is None:
        return NO_CONTROLLER, np.zeros(4)
    return int(controller.kind), np.asarray(controller.gains(), dtype=float)


# (kind, gains, max_angle, max_rate, lag, delta, integral, t_step, eta_step, nu_step)
ActuatorKernelArguments = tuple[
    int, FloatArray, float, float, float, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray
]


def actuator_kernel_arguments(
    kind: int, gains: FloatArray, servo: ServoSpec, states: ActuatorStates
) -> ActuatorKernelArguments:
    """The arguments of :func:`actuator_angle_rows` / :func:`actuator_commit_rows` after the
    rows' inputs: law, gains, servo limits and lag, and the per-ship state arrays."""
    return (
        kind, gains, servo.max_angle, servo.max_rate, servo.lag, states.delta, states.integral,
        states.t_step, states.eta_step, states.nu_step,
    )  # fmt: skip


class _HeadingController(Controller, Protocol):
    """A controller of law 1 (:func:`heading_autopilot_law`): it reads ``commands[heading_key]``."""

    heading_key: str


class ActuatorStates:
    """Per-ship discrete states of one actuator (rows over ships).

    Attributes
    ----------
    delta : numpy.ndarray
        (n,) servo angle at the last accepted step [rad].
    integral : numpy.ndarray
        (n,) the controller's integral state [rad·s].
    t_step : numpy.ndarray
        (n,) time of the last accepted step [s].
    eta_step, nu_step : numpy.ndarray
        (n, 6) state sampled at that instant.
    initial_heading : numpy.ndarray
        (n,) heading at the last reset [rad] (the autopilot's default set-point).
    """

    def __init__(self, n: int) -> None:
        self.delta = np.zeros(n)
        self.integral = np.zeros(n)
        self.t_step = np.zeros(n)
        self.eta_step = np.zeros((n, 6))
        self.nu_step = np.zeros((n, 6))
        self.initial_heading = np.zeros(n)

    def reset(self, ships: np.ndarray, t: np.ndarray, eta: np.ndarray, nu: np.ndarray) -> None:
        """Angle and integral to zero; sample (t, η, ν) of the rows; remember the heading."""
        self.delta[ships] = 0.0
        self.integral[ships] = 0.0
        self.t_step[ships] = t
        self.eta_step[ships] = eta
        self.nu_step[ships] = nu
        self.initial_heading[ships] = eta[:, 5]


class Actuated(ForceModel):
    """A force model whose control angle comes from a servo (module docstring: sampled, exact).

    The wrapped model reads its angle from ``ctx.commands[key]``; this wrapper owns the servo
    (:class:`ActuatorStates` of one ship), takes the *command* from a feedback
    :class:`Controller` if one is given, else from ``ctx.commands[command_key]`` (default
    ``key + "_command"``; missing → 0), and hands the wrapped model a context in which
    ``commands[key]`` is the servo angle at the evaluation time.

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
        Feedback law (autopilot, fin or ride controller).
    """

    n_states = 0

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
        self.kind, self.gains = law_parameters(controller)
        self.states = ActuatorStates(1)
        self._ship = np.zeros(1, dtype=np.int64)

    @property
    def angle(self) -> float:
        """Servo angle at the last accepted step [rad]."""
        return float(self.states.delta[0])

    def reference(self, commands: dict) -> float:
        """The law's reference: ψ_ref (autopilot: the command, or the heading at reset), or
        the open-loop commanded angle [rad]."""
        if self.kind == 1:
            # law 1 is the heading autopilot's, which names its set-point command
            key = cast(_HeadingController, self.controller).heading_key
            return float(commands.get(key, self.states.initial_heading[0]))
        if self.kind == NO_CONTROLLER:
            return float(commands.get(self.command_key, 0.0))
        return 0.0

    def _kernel_args(self) -> ActuatorKernelArguments:
        return actuator_kernel_arguments(self.kind, self.gains, self.servo, self.states)

    def reset(self, t0: float, ctx: ForceContext) -> None:
        """Servo at rest at zero angle; the controller samples the initial state."""
        self.states.reset(self._ship, np.array([t0]), ctx.eta[None, :], ctx.nu[None, :])
        self.model.reset(t0, ctx)

    def current_angle(self, ctx: ForceContext) -> float:
        """δ [rad] at the context's time (within the current step)."""
        out = np.empty(1)
        ref = np.array([self.reference(ctx.commands)])
        actuator_angle_rows(self._ship, np.array([ctx.t]), ref, *self._kernel_args(), out)
        return float(out[0])

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Wrapped force at the servo angle of the evaluation time (no ODE states)."""
        inner = ForceContext(
            t=ctx.t,
            eta=ctx.eta,
            nu=ctx.nu,
            rotation=ctx.rotation,
            forward_speed=ctx.forward_speed,
            wave_phasor=ctx.wave_phasor,
            commands={**ctx.commands, self.key: self.current_angle(ctx)},
            shared=ctx.shared,
        )
        force, _ = self.model.evaluate(inner, np.zeros(0))
        return force, np.zeros(0)

    def commit(self, ctx: ForceContext, states: np.ndarray) -> None:
        """Advance the servo and the controller to the accepted step's end."""
        ref = np.array([self.reference(ctx.commands)])
        actuator_commit_rows(
            self._ship, np.array([ctx.t]), ctx.eta[None, :], ctx.nu[None, :], ref,
            *self._kernel_args(),
        )  # fmt: skip


# =============================================================================================
# row kernels of the compiled path (protocol: ship_gym.forces.base.RowPart)
# =============================================================================================
class ActuatedSurfacesRecord(NamedTuple):
    """One surface group behind its servo and control law, for the compiled path.

    Geometry of the group's surfaces (``pos`` … ``cn``: the arguments of
    :func:`ship_gym.forces.lifting_surface.surface_group_force`), its inflow model (``inflow``,
    ``wake``, ``gamma_v``, ``gamma_r``, ``prop_d``, ``prop_x``, ``thrust_mode``: 0 none, 1 the
    propeller thrust in ``shared[thrust_slot]``, 2 the constant C_Th ``c_th``), the servo
    (``surface_limit``, ``max_angle`` [rad], ``max_rate`` [rad/s], ``lag`` [s]), the law
    (``kind``, ``gains``, the reference command's column ``ref_col``) and the per-ship actuator
    states (N,) / (N, 6) shared with the numpy path, with the held target and integral rate.
    """

    pos: NDArray
    axis: NDArray
    chord: NDArray
    lead: NDArray
    area: NDArray
    span: NDArray
    rho: NDArray
    lift_slope: NDArray
    stall: NDArray
    transition: NDArray
    cd0: NDArray
    k_induced: NDArray
    cn: NDArray
    inflow: int
    wake: float
    gamma_v: float
    gamma_r: float
    prop_d: float
    prop_x: float
    thrust_mode: int
    c_th: float
    thrust_slot: int
    surface_limit: float
    max_angle: float
    max_rate: float
    lag: float
    kind: int
    gains: NDArray
    ref_col: int
    delta: NDArray
    integral: NDArray
    t_step: NDArray
    eta_step: NDArray
    nu_step: NDArray
    target: NDArray
    rate: NDArray


@nb.njit(cache=True, nogil=True, inline="always")
def actuated_surfaces_start(s, t, q, v, cmd, rec):  # pragma: no cover - compiled
    """Step start: the law's saturated target and integral rate, sampled and held."""
    rec.target[s], rec.rate[s] = actuator_target(
        rec.kind, rec.gains, q, v, rec.integral[s], cmd[s, rec.ref_col], rec.max_angle
    )


@nb.njit(cache=True, nogil=True, inline="always")
def actuated_surfaces_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: the servo's angle at t (:func:`servo_angle`, clipped to the surfaces'
    own limit) and the group's force (:func:`surface_group_force`) added to ``out``."""
    angle = servo_angle(rec.delta[s], rec.target[s], t - rec.t_step[s], rec.max_rate, rec.lag)
    lim = rec.surface_limit
    angle = min(max(angle, -lim), lim)
    mode = rec.thrust_mode
    th = ctx.shared[rec.thrust_slot] if mode == 1 else rec.c_th
    work = ctx.work
    surface_group_force(
        v, angle, rec.inflow, rec.wake, rec.gamma_v, rec.gamma_r, rec.prop_d, rec.prop_x, mode,
        th, rec.pos, rec.axis, rec.chord, rec.lead, rec.area, rec.span, rec.rho,
        rec.lift_slope, rec.stall, rec.transition, rec.cd0, rec.k_induced, rec.cn, 0,
        rec.pos.shape[0], work,
    )  # fmt: skip
    for i in range(6):
        out[i] += work[i]


@nb.njit(cache=True, nogil=True, inline="always")
def actuated_surfaces_end(s, t, q, v, rec):  # pragma: no cover - compiled
    """Accepted step ending at t: the servo's angle, the integral and the sampled state
    (``actuator_commit_rows``)."""
    elapsed = t - rec.t_step[s]
    rec.delta[s] = servo_angle(rec.delta[s], rec.target[s], elapsed, rec.max_rate, rec.lag)
    rec.integral[s] += elapsed * rec.rate[s]
    rec.t_step[s] = t
    for i in range(6):
        rec.eta_step[s, i] = q[i]
        rec.nu_step[s, i] = v[i]
