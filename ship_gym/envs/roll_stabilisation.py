"""``ship_gym/RollStabilization-v2``: reduce the roll of the S175 in beam and quartering seas.

The task (:class:`RollStabilizationTask`) runs on :class:`ship_gym.envs.env_task.ShipEnvTask` with
the comfort bookkeeping of :class:`ComfortShipTask` (accelerations at a passenger point,
:mod:`ship_gym.comfort.metrics`); the Gymnasium faces are :class:`RollStabilizationEnv` (one
episode) and :class:`RollStabilizationVectorEnv` (N episodes in one BatchSimulator). The
environment docstring (Gymnasium v5 template) lists every keyword argument with its unit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ship_gym.comfort.metrics import ComfortSample
from ship_gym.envs.base import TaskEnv, TaskVectorEnv
from ship_gym.envs.comfort import ComfortTracker
from ship_gym.envs.docstrings import (
    FORWARD_SPEED_V3,
    VERSION_HISTORY,
    env_docstring,
    vector_env_docstring,
)
from ship_gym.envs.env_task import (
    RUDDER_LIMIT_DEG,
    S175_MESH,
    ShipEnvTask,
    irregular_sea,
    point_scaled_from_s175,
    ship_kwargs,
)
from ship_gym.envs.observations import Observation
from ship_gym.envs.registration import max_episode_steps
from ship_gym.envs.ship_task import StepStatistics
from ship_gym.envs.validation import check_point, check_positive, check_weight
from ship_gym.typing import ForwardSpeedModel, IntegratorName, Precision

__all__ = [
    "MAX_EPISODE_STEPS",
    "ComfortShipTask",
    "RollStabilizationEnv",
    "RollStabilizationTask",
    "RollStabilizationVectorEnv",
]

MAX_EPISODE_STEPS = max_episode_steps("RollStabilization")
"""Time limit in control steps, from the registration (500 s at the default control_dt)."""

FIN_LIMIT_DEG = 25.0
"""Fin angle limit of the servo [deg] (:data:`ship_gym.control.actuators.FIN_SERVO`)."""
_FIN_LIMIT = math.radians(FIN_LIMIT_DEG)
S175_PASSENGER_POINT_M = (-50.0, 10.0, -15.0)
"""Default passenger position on the S175 [m] (aft, off the centreline, high in the
superstructure); on another ship scaled by
:func:`~ship_gym.envs.env_task.point_scaled_from_s175`."""


class ComfortShipTask(ShipEnvTask):
    """An :class:`ShipEnvTask` with actuated surfaces and comfort sampling at a passenger point.

    Parameters
    ----------
    num_envs : int
        N.
    passenger_point_m : array_like
        (3,) body-frame position of the passenger [m] (z down: negative above the waterline).
    actuators : sequence of (command key, force-model name, limit [rad])
        Commanded surfaces, in action order after any the subclass handles itself: action a
        gives the command a · limit; the servo state is observed.
    comfort_time_constant_s : float
        τ of the running RMS of the accelerations [s].
    **kwargs
        :class:`ShipEnvTask` arguments.
    """

    def __init__(
        self,
        num_envs: int,
        *,
        passenger_point_m: Sequence[float],
        actuators: Sequence[tuple[str, str, float]],
        comfort_time_constant_s: float,
        **kwargs: Any,
    ) -> None:
        tau = check_positive("comfort_time_constant_s", comfort_time_constant_s, "s", 3600.0)
        passenger_point = check_point("passenger_point_m", passenger_point_m)
        super().__init__(num_envs, **kwargs)
        n = self.num_envs
        self.passenger_point = passenger_point
        self.actuators = tuple(actuators)
        self._actuator_models = []
        for key, model_name, _ in self.actuators:
            try:
                self._actuator_models.append(self.sim.actuator_model(model_name))
            except ValueError:
                raise ValueError(f"the setup has no servo-driven {model_name!r}") from None
            self.commands[key] = np.zeros(n)
        self.comfort_tracker = ComfortTracker(
            n, self.control_dt, passenger_point, tau, g=float(self.sim.hull.g)
        )
        """The comfort component (:class:`ship_gym.envs.comfort.ComfortTracker`)."""
        self.comfort = self.comfort_tracker.meter

    @property
    def sample(self) -> ComfortSample:
        """The last control step's comfort sample (:attr:`ComfortTracker.sample`)."""
        return self.comfort_tracker.sample

    @sample.setter
    def sample(self, value: ComfortSample) -> None:
        self.comfort_tracker.sample = value

    def actuator_angles(self) -> NDArray:
        """(N, n_actuators) servo angles of the commanded surfaces [rad]."""
        return np.column_stack([m.angle for m in self._actuator_models])

    def _apply_surface_actions(self, actions: NDArray) -> None:
        for j, (key, _, limit) in enumerate(self.actuators):
            self.commands[key][:] = actions[:, j] * limit

    def _reset_task(self, i: int, rng: np.random.Generator) -> dict[str, float]:
        for key, _, _ in self.actuators:
            self.commands[key][i] = 0.0
        nu = np.zeros(6)
        nu[0] = self.initial_speed[i]  # ShipTask resets ν = (U_i, 0, …)
        self.comfort_tracker.reset([i], nu)
        return {}

    def _reward_terms(self, stats: StepStatistics) -> dict[str, NDArray]:
        sample = self.comfort_tracker.update(self.sim.eta, self.sim.nu)
        return self._comfort_reward_terms(stats, sample)

    def _comfort_reward_terms(
        self, stats: StepStatistics, sample: ComfortSample
    ) -> dict[str, NDArray]:
        raise NotImplementedError

    def _comfort_info(self) -> dict[str, NDArray]:
        return self.comfort_tracker.info()

    def _action_labels(self, i: int) -> dict[str, float]:
        out = super()._action_labels(i)
        angles = self.actuator_angles()[i]
        for (key, _, _), angle in zip(self.actuators, angles, strict=True):
            out[f"{key} [deg]"] = math.degrees(float(angle))
        return out


class RollStabilizationTask(ComfortShipTask):
    """N roll-stabilisation episodes (see :class:`RollStabilizationEnv` for the arguments)."""

    task_observations = (
        Observation("fin angle", "rad", -math.pi / 2, math.pi / 2, doc="fin angle (servo)",
                    bound="±π/2"),
        Observation("lateral specific force at the passenger", "m/s^2", -30.0, 30.0,
                    doc="lateral specific force f_y at the passenger point"),
        Observation("fin command", "rad", -_FIN_LIMIT, _FIN_LIMIT,
                    doc="fin command δ_c (the servo follows it at ≤ 15 °/s)"),
        Observation("fin travel over the last step", "rate limit x step", -1.0, 1.0,
                    doc="fin travel over the last control step Δδ/(δ̇_max Δt)"),
    )  # fmt: skip
    """The task's observation entries (written by :meth:`_write_extra_observations`)."""

    def __init__(
        self,
        num_envs: int,
        *,
        ship: str = "s175",
        froude_number: float = 0.25,
        speed_range_mps: tuple[float, float] | None = None,
        hs_range_m: tuple[float, float] = (2.0, 5.0),
        tp_range_s: tuple[float, float] = (9.0, 16.0),
        wave_heading_range_deg: tuple[float, float] = (30.0, 150.0),
        n_wave_components: int = 40,
        wave_spreading_s: float | None = None,
        wave_ramp_time_s: float = 30.0,
        gm_range_m: tuple[float, float] | None = None,
        kg_m: float | None = None,
        rudder_roll_stabilization: bool = False,
        passenger_point_m: Sequence[float] | None = None,
        physics_dt_s: float = 0.1,
        control_dt_s: float = 0.5,
        integrator: IntegratorName = "holloway",
        hull_mesh: Sequence[int] = S175_MESH,
        precision: Precision = "float32",
        forward_speed_model: ForwardSpeedModel = "relative_motion",
        wind_speed_mps: float = 0.0,
        wind_from_deg: float = 0.0,
        num_threads: int = 1,
        capsize_angle_deg: float | None = None,
        dangerous_roll_deg: float = 25.0,
        roll_weight: float = 1.0,
        roll_scale_deg: float = 5.0,
        roll_rate_weight: float = 0.2,
        roll_rate_scale_dps: float = 2.0,
        lateral_weight: float = 0.5,
        lateral_scale_mps2: float = 1.0,
        effort_weight: float = 0.2,
        fin_rate_weight: float = 0.2,
        heading_weight: float = 0.5,
        heading_scale_deg: float = 10.0,
        capsize_penalty: float = 100.0,
        comfort_time_constant_s: float = 60.0,
        sensor_noise: float = 0.0,
        wave_preview_m: Sequence[float] | Sequence[Sequence[float]] = (),
    ) -> None:
        args = dict(locals())  # the arguments, forwarded by name (ship_kwargs, irregular_sea)
        if not isinstance(rudder_roll_stabilization, bool):
            raise ValueError(
                f"rudder_roll_stabilization must be a bool, got {rudder_roll_stabilization!r}"
            )
        self.rudder_roll_stabilization = rudder_roll_stabilization
        self.roll_weight = check_weight("roll_weight", roll_weight)
        self.roll_scale = math.radians(check_positive("roll_scale_deg", roll_scale_deg, "deg", 90))
        self.roll_rate_weight = check_weight("roll_rate_weight", roll_rate_weight)
        self.roll_rate_scale = math.radians(
            check_positive("roll_rate_scale_dps", roll_rate_scale_dps, "deg/s", 90.0)
        )
        self.lateral_weight = check_weight("lateral_weight", lateral_weight)
        self.lateral_scale = check_positive("lateral_scale_mps2", lateral_scale_mps2, "m/s²", 50)
        self.effort_weight = check_weight("effort_weight", effort_weight)
        self.fin_rate_weight = check_weight("fin_rate_weight", fin_rate_weight)
        self.heading_weight = check_weight("heading_weight", heading_weight)
        self.heading_scale = math.radians(
            check_positive("heading_scale_deg", heading_scale_deg, "deg", 180.0)
        )
        fin_limit = math.radians(FIN_LIMIT_DEG)
        self.rudder_limit = math.radians(RUDDER_LIMIT_DEG)
        names = [f"fin command (-1..1 = ±{FIN_LIMIT_DEG:g} deg, + = starboard down)"]
        if rudder_roll_stabilization:
            names.append(f"rudder command (-1..1 = ±{RUDDER_LIMIT_DEG:g} deg, + = to starboard)")
        self.action_names = tuple(names)
        super().__init__(
            num_envs,
            passenger_point_m=(
                point_scaled_from_s175(ship, S175_PASSENGER_POINT_M)
                if passenger_point_m is None
                else passenger_point_m
            ),
            actuators=(("fins_command", "roll_fins", fin_limit),),
            comfort_time_constant_s=comfort_time_constant_s,
            rudder="command" if rudder_roll_stabilization else "autopilot",
            setup_changes={"fins": "command"},
            sea=irregular_sea(args),
            extra_observations=self.task_observations,
            **ship_kwargs(args),
        )
        self.fin_limit = fin_limit

    # ------------------------------------------------------------------ hooks
    def _apply_actions(self, actions: NDArray) -> None:
        self._apply_surface_actions(actions)
        if self.rudder_roll_stabilization:
            self.commands["rudder_command"][:] = actions[:, 1] * self.rudder_limit

    def _write_extra_observations(self, out: NDArray) -> None:
        out[:, 0] = self._actuator_models[0].angle
        out[:, 1] = self.sample.lateral
        out[:, 2] = self.commands["fins_command"]
        out[:, 3] = self.servo_travel("roll_fins")

    def _comfort_reward_terms(
        self, stats: StepStatistics, sample: ComfortSample
    ) -> dict[str, NDArray]:
        p = self.sim.nu[:, 3]
        effort = (self._actuator_models[0].angle / self.fin_limit) ** 2
        if self.rudder_roll_stabilization:
            effort = effort + (self._rudder.angle / self.rudder_limit) ** 2
        travel = self.servo_travel("roll_fins")
        terms = {
            "roll": self.roll_term(stats, self.roll_weight, self.roll_scale),
            "roll_rate": -self.roll_rate_weight * (p / self.roll_rate_scale) ** 2,
            "lateral": -self.lateral_weight * (sample.lateral / self.lateral_scale) ** 2,
            "effort": -self.effort_weight * effort,
            "fin_rate": -self.fin_rate_weight * travel**2,
        }
        if self.rudder_roll_stabilization:
            terms["heading"] = self.heading_term(self.heading_weight, self.heading_scale)
        return terms

    def _task_info(self, stats: StepStatistics) -> dict[str, NDArray]:
        return {
            "fin_angle_deg": np.degrees(self._actuator_models[0].angle),
            "heading_error_deg": np.degrees(self._current_heading_error()),
            **self._comfort_info(),
        }


_ARGUMENTS: dict[str, tuple[str, str]] = {
    # this environment's own rows and meanings (the shared ones: SHIP_ARGUMENTS)
    "tp_range_s": ("s", "peak period range (roll resonance near 18 s)"),
    "wave_heading_range_deg": ("deg", "relative wave heading β (90 = beam seas)"),
    "rudder_roll_stabilization": ("-", "the rudder is a second action (no autopilot)"),
    "roll_rate_weight": ("-", "weight of the roll-rate term"),
    "roll_rate_scale_dps": ("deg/s", "roll-rate scale"),
    "lateral_weight": ("-", "weight of the lateral-force term"),
    "lateral_scale_mps2": ("m/s²", "lateral specific force scale"),
    "heading_weight": ("-", "weight of the heading term (rudder roll stabilisation)"),
    "fin_rate_weight": ("-", "weight of the fin-travel (wear) term"),
}


@env_docstring(
    _ARGUMENTS,
    (
        *VERSION_HISTORY,
        "v2: the fins cost what a real stabiliser's do — a fin-travel (wear) term "
        "−fin_rate_weight · (Δδ/(δ̇_max Δt))², 0.2 by default, and effort_weight 0.2 (v1: "
        "0.05, under which PPO held the fins at their limit on 67 % of the steps); the fin "
        "command and the fin travel over the last step are observed (the servo lags the "
        "command: with the angle alone the task was not Markov in the actuator).",
        FORWARD_SPEED_V3,
    ),
)
class RollStabilizationEnv(TaskEnv):
    """Reduce the roll of the S175 container ship in beam and quartering seas with roll fins.

    ## Description

    The ITTC S175 container ship (Lpp 175 m, B 25.4 m, T 9.5 m, GM ≈ 1.0 m, roll natural period
    ≈ 18 s) sails at its service speed (Fn = 0.25, 10.36 m/s) in long-crested JONSWAP seas
    from the beam and quarters. Its motions are simulated in 6 DOF (:mod:`ship_gym.engine`):
    nonlinear Froude–Krylov and hydrostatic forces on the instantaneous wetted hull, radiation
    memory, linear diffraction, Ikeda roll damping, Holtrop resistance and a B-series propeller,
    hull manoeuvring forces, a rudder, and a pair of 10 m² roll fins amidships behind their servo
    (±25°, 15 °/s, :class:`ship_gym.forces.fins.RollFins`). The agent commands the fins (and,
    with ``rudder_roll_stabilization=True``, the rudder, then also keeping the course); without
    it the PID heading autopilot holds the course. The reward penalises roll, roll rate and the
    lateral specific force at a passenger point (the lateral force estimator of Graham 1990,
    :mod:`ship_gym.comfort.metrics`), actuator effort and fin travel (wear: a stabiliser that
    chatters at its rate limit wears its seals and bearings). Every term is normalised by a
    scale, so its weight is its cost at the scale. A capsize ends the episode.

    ## Action Space

    ``Box(-1, 1, (1,), float32)``: fin angle command δ_c = a · 25° (positive gives a
    starboard-down roll moment, so a stabiliser commands δ ≈ −k_φ φ − k_p p). With
    ``rudder_roll_stabilization=True``, ``Box(-1, 1, (2,))``: [fins, rudder δ_R = a · 35°
    (positive turns the ship to starboard and heels it to starboard at first)].

    ## Observation Space

    ``Box(float32)``; entries (``env.observation_names``), each clipped to its bound:

    {ship_observations}

    The accelerations at the passenger point use ν̇ from the backward difference of ν over the
    control step (:class:`ship_gym.comfort.metrics.PassengerComfort`).

    ## Rewards

    r = Σ of the weighted terms, each in ``info["reward_<term>"]``:

    * ``roll`` = −roll_weight · mean(φ²)/roll_scale² over the physics steps of the control step;
    * ``roll_rate`` = −roll_rate_weight · (p/roll_rate_scale)²;
    * ``lateral`` = −lateral_weight · (f_y/lateral_scale)², f_y the lateral specific force at
      the passenger point (eq. 2 of :mod:`ship_gym.comfort.metrics`);
    * ``effort`` = −effort_weight · [(δ_fin/25°)² (+ (δ_R/35°)² with the rudder)];
    * ``fin_rate`` = −fin_rate_weight · (Δδ_fin/(δ̇_max Δt))², Δδ_fin the servo travel over the
      control step Δt and δ̇_max = 15 °/s its rate limit (1 = travelling at the limit the whole
      step: fin wear);
    * ``heading`` (only with ``rudder_roll_stabilization``) = −heading_weight ·
      (e/heading_scale)²;
    * ``capsize`` = −capsize_penalty in the step the ship capsizes.

    ``info["cost"]`` (Safe RL, one meaning in every ship env: :mod:`ship_gym.envs.ship_task`) is
    the fraction of the step's physics steps with |φ| above ``dangerous_roll_deg``, 1 in the
    step that capsizes. Further info: ``fin_angle_deg``, ``heading_error_deg``,
    ``lateral_acceleration_mps2``, ``vertical_acceleration_mps2`` (earth-vertical at the
    passenger), their running RMS (τ = ``comfort_time_constant_s``), ``msdv_z`` (ISO 2631-1
    motion sickness dose value of the episode so far [m/s^1.5]) and ``msi_percent`` (MSDV_z/3).

    ## Starting State

    Free-floating equilibrium, heading north (ψ = 0, the set-point) at the initial speed, fins
    and rudder amidships. Per episode, from the reset seed: Hs, Tp and the relative wave heading
    β (uniform in the ranges), the wave components, optionally the speed and the GM. The waves
    ramp up over ``wave_ramp_time_s``. ``reset`` info: ``wave_height_m``, ``wave_period_s``,
    ``wave_heading_deg``, ``initial_speed_mps``, ``gm_m``, ``capsize_angle_deg``.

    ## Episode End

    Terminated when |φ| exceeds the capsize angle at any physics step (default: the angle of
    vanishing stability of the episode's loading; ``capsize_angle_deg`` overrides it) or when
    the integration diverges (``info["diverged"]``). Truncated by the time limit:
    {time_limit}.
    """

    task_class = RollStabilizationTask


class RollStabilizationVectorEnv(TaskVectorEnv):
    __doc__ = vector_env_docstring(RollStabilizationEnv)
    task_class = RollStabilizationTask
