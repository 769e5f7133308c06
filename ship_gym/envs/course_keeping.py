"""``ship_gym/CourseKeeping-v2``: steer the S175 on a heading in irregular seas with its rudder.

The task (:class:`CourseKeepingTask`) runs on :class:`ship_gym.envs.env_task.ShipEnvTask`; the
Gymnasium faces are :class:`CourseKeepingEnv` (one episode) and :class:`CourseKeepingVectorEnv`
(N episodes in one BatchSimulator). The environment docstring (Gymnasium v5 template) lists
every keyword argument with its unit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from ship_gym.envs.base import TaskEnv, TaskVectorEnv
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
    ship_kwargs,
)
from ship_gym.envs.observations import Observation
from ship_gym.envs.registration import max_episode_steps
from ship_gym.envs.ship_task import StepStatistics, clip_into, write_heading_observations
from ship_gym.envs.validation import check_positive, check_real, check_weight
from ship_gym.typing import ForwardSpeedModel, IntegratorName, Precision

__all__ = ["MAX_EPISODE_STEPS", "CourseKeepingEnv", "CourseKeepingTask", "CourseKeepingVectorEnv"]

_RUDDER_LIMIT = math.radians(RUDDER_LIMIT_DEG)

MAX_EPISODE_STEPS = max_episode_steps("CourseKeeping")
"""Time limit in control steps, from the registration (500 s at the default control_dt)."""


class CourseKeepingTask(ShipEnvTask):
    """N course-keeping episodes (see :class:`CourseKeepingEnv` for the keyword arguments)."""

    task_observations = (
        Observation("heading", "rad", -math.pi, math.pi, doc="heading ψ (wrapped)", bound="±π"),
        Observation("heading set-point", "rad", -math.pi, math.pi,
                    doc="heading set-point ψ_ref (wrapped)", bound="±π"),
        Observation("rudder command", "rad", -_RUDDER_LIMIT, _RUDDER_LIMIT),
        Observation("heading error integral", "rad s", -10.0 * math.pi, 10.0 * math.pi,
                    doc="heading-error integral I, İ = e − I/τ (τ = ``heading_integral_time_s``)",
                    bound="±10π"),
        Observation("rudder travel over the last step", "rate limit x step", -1.0, 1.0,
                    doc="rudder travel over the last control step Δδ/(δ̇_max Δt)"),
    )  # fmt: skip
    """The task's observation entries (written by :meth:`_write_extra_observations`)."""

    def __init__(
        self,
        num_envs: int,
        *,
        ship: str = "s175",
        froude_number: float = 0.25,
        speed_range_mps: tuple[float, float] | None = None,
        hs_range_m: tuple[float, float] = (3.0, 5.0),
        tp_range_s: tuple[float, float] = (9.0, 12.0),
        wave_heading_range_deg: tuple[float, float] = (0.0, 360.0),
        n_wave_components: int = 40,
        wave_spreading_s: float | None = None,
        wave_ramp_time_s: float = 30.0,
        gm_range_m: tuple[float, float] | None = None,
        kg_m: float | None = None,
        initial_heading_error_deg: float = 10.0,
        rudder_mode: Literal["absolute", "increment"] = "absolute",
        max_rudder_increment_deg: float = 5.0,
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
        heading_weight: float = 1.0,
        heading_scale_deg: float = 10.0,
        rudder_weight: float = 0.1,
        rudder_rate_weight: float = 0.1,
        heading_integral_time_s: float = 100.0,
        roll_weight: float = 0.1,
        roll_scale_deg: float = 10.0,
        capsize_penalty: float = 100.0,
        sensor_noise: float = 0.0,
        wave_preview_m: Sequence[float] | Sequence[Sequence[float]] = (),
    ) -> None:
        args = dict(locals())  # the arguments, forwarded by name (ship_kwargs, irregular_sea)
        if rudder_mode not in ("absolute", "increment"):
            raise ValueError(f"rudder_mode must be 'absolute' or 'increment', got {rudder_mode!r}")
        self.rudder_mode = rudder_mode
        self.max_rudder_increment = math.radians(
            check_positive("max_rudder_increment_deg", max_rudder_increment_deg, "deg", 70.0)
        )
        self.initial_heading_error = math.radians(
            check_real(
                "initial_heading_error_deg",
                initial_heading_error_deg,
                low=0.0,
                high=180.0,
                unit="deg",
            )
        )
        self.heading_weight = check_weight("heading_weight", heading_weight)
        self.heading_scale = math.radians(
            check_positive("heading_scale_deg", heading_scale_deg, "deg", 180.0)
        )
        self.rudder_weight = check_weight("rudder_weight", rudder_weight)
        self.rudder_rate_weight = check_weight("rudder_rate_weight", rudder_rate_weight)
        self.integral_time = check_positive(
            "heading_integral_time_s", heading_integral_time_s, "s", 3600.0
        )
        self.roll_weight = check_weight("roll_weight", roll_weight)
        self.roll_scale = math.radians(
            check_positive("roll_scale_deg", roll_scale_deg, "deg", 90.0)
        )
        self.rudder_limit = math.radians(RUDDER_LIMIT_DEG)
        if rudder_mode == "absolute":
            self.action_names = (f"rudder command (-1..1 = ±{RUDDER_LIMIT_DEG:g} deg)",)
        else:
            self.action_names = (
                f"rudder command increment (-1..1 = ±{max_rudder_increment_deg:g} deg per step)",
            )
        super().__init__(
            num_envs,
            rudder="command",
            sea=irregular_sea(args),
            extra_observations=self.task_observations,
            **ship_kwargs(args),
        )
        n = self.num_envs
        self.heading_integral = np.zeros(n)
        self._integral_decay = math.exp(-self.control_dt / self.integral_time)

    # ------------------------------------------------------------------ hooks
    task_reset_options = ("heading_setpoint_deg",)

    def _check_task_option(self, key: str, value: Any) -> Any:
        return check_real(f"options[{key!r}]", value, low=-180.0, high=180.0, unit="deg")

    def _reset_task(self, i: int, rng: np.random.Generator) -> dict[str, float]:
        e = float(rng.uniform(-self.initial_heading_error, self.initial_heading_error))
        if "heading_setpoint_deg" in self._task_options:
            e = math.radians(self._task_options["heading_setpoint_deg"])
        self.heading_setpoint[i] = e  # the ship starts heading north (ψ = 0)
        self.heading_integral[i] = 0.0
        return {"heading_setpoint_deg": math.degrees(e)}

    def _apply_actions(self, actions: NDArray) -> None:
        cmd = self.commands["rudder_command"]
        if self.rudder_mode == "absolute":
            cmd[:] = actions[:, 0] * self.rudder_limit
        else:
            step = cmd + actions[:, 0] * self.max_rudder_increment
            clip_into(step, -self.rudder_limit, self.rudder_limit, cmd)

    def _write_extra_observations(self, out: NDArray) -> None:
        # wrap(ψ), wrap(ψ_ref), the rudder command
        write_heading_observations(self, 0.0, self.commands["rudder_command"], out)
        out[:, 3] = self.heading_integral
        out[:, 4] = self.servo_travel("rudder")

    def _reward_terms(self, stats: StepStatistics) -> dict[str, NDArray]:
        delta = self._rudder.angle  # the servo angle (read only)
        # the leaky integral of the error after the step (exact for e held over the step):
        # I ← I e^(−Δt/τ) + τ (1 − e^(−Δt/τ)) e
        e = self._current_heading_error()
        decay = self._integral_decay
        self.heading_integral[:] = (
            self.heading_integral * decay + self.integral_time * (1.0 - decay) * e
        )
        return {
            "heading": self.heading_term(self.heading_weight, self.heading_scale),
            "rudder": -self.rudder_weight * (delta / self.rudder_limit) ** 2,
            "rudder_rate": -self.rudder_rate_weight * self.servo_travel("rudder") ** 2,
            "roll": self.roll_term(stats, self.roll_weight, self.roll_scale),
        }

    def _task_info(self, stats: StepStatistics) -> dict[str, NDArray]:
        return {"heading_error_deg": np.degrees(self._current_heading_error())}


_ARGUMENTS: dict[str, tuple[str, str]] = {
    # the rows of this environment's own keyword arguments (the shared ones: SHIP_ARGUMENTS)
    "initial_heading_error_deg": ("deg", "set-point range at reset"),
    "rudder_mode": ("-", '"absolute" angle or "increment" per step'),
    "max_rudder_increment_deg": ("deg", "increment at a = ±1 (increment mode)"),
    "rudder_weight": ("-", "weight of the rudder term"),
    "rudder_rate_weight": ("-", "weight of the rudder-travel (steering gear wear) term"),
    "heading_integral_time_s": ("s", "time constant τ of the observed heading-error integral"),
}


@env_docstring(
    _ARGUMENTS,
    (
        *VERSION_HISTORY,
        "v2: the steering gear's travel costs (−rudder_rate_weight · (Δδ/(δ̇_max Δt))², 0.1 by "
        "default: v1's PPO flipped the rudder's sign on 37 % of the steps); a leaky integral of "
        "the heading error (τ = 100 s) and the rudder travel over the last step are observed "
        "(v1's PPO kept a steady error of ≈ 0.9° that an integral removes, and the servo lags "
        "its command by up to 15 s at 2.32 °/s).",
        FORWARD_SPEED_V3,
    ),
)
class CourseKeepingEnv(TaskEnv):
    """Keep the S175 container ship on a heading in irregular seas with its rudder.

    ## Description

    The ITTC S175 container ship (Lpp 175 m, B 25.4 m, T 9.5 m, GM ≈ 1.0 m) sails at its service
    speed (Fn = 0.25, 10.36 m/s) in long-crested JONSWAP seas from a random direction. Its motions
    are simulated in 6 DOF (:mod:`ship_gym.engine.batch`): nonlinear Froude–Krylov and
    hydrostatic forces on the instantaneous wetted hull, radiation memory (state-space fit of
    the Cummins kernel), linear diffraction, Ikeda viscous roll damping, Holtrop resistance and
    a B-series propeller at the self-propulsion rpm, hull manoeuvring forces, and a rudder
    behind an IMO-minimum steering gear (±35°, 2.32 °/s). The agent commands the rudder to hold
    the heading set-point while keeping rudder effort, steering-gear travel (wear) and roll low.
    Every reward term is normalised by a scale, so its weight is its cost at the scale. A
    capsize ends the episode.

    ## Action Space

    ``Box(-1, 1, (1,), float32)``: with ``rudder_mode="absolute"`` the rudder angle command
    δ_c = a · 35° (positive turns the ship to starboard); with ``"increment"`` the command
    changes by a · ``max_rudder_increment_deg`` per control step (clipped at ±35°). The servo
    follows the command at ≤ 2.32 °/s.

    ## Observation Space

    ``Box(float32)``; entries (``env.observation_names``), each clipped to its bound:

    {ship_observations}

    ``sensor_noise`` adds Gaussian noise of ``sensor_noise`` × the accuracies of
    :data:`ship_gym.envs.ship_task.SENSOR_NOISE_STD` (0.1 m on the preview).

    ## Rewards

    r = Σ of the weighted terms, each in ``info["reward_<term>"]``:

    * ``heading`` = −heading_weight · (e/heading_scale)², e the wrapped heading error;
    * ``rudder`` = −rudder_weight · (δ/35°)², δ the servo rudder angle;
    * ``rudder_rate`` = −rudder_rate_weight · (Δδ/(δ̇_max Δt))², Δδ the servo travel over the
      control step Δt, δ̇_max = 2.32 °/s (1 = moving at the steering gear's limit the whole
      step);
    * ``roll`` = −roll_weight · mean(φ²)/roll_scale² over the physics steps of the control step;
    * ``capsize`` = −capsize_penalty in the step the ship capsizes.

    ``info["cost"]`` (Safe RL, one meaning in every ship env: :mod:`ship_gym.envs.ship_task`) is
    the fraction of the step's physics steps with |φ| above ``dangerous_roll_deg``, 1 in the
    step that capsizes.

    ## Starting State

    Free-floating equilibrium, heading north (ψ = 0) at the initial speed; heading set-point
    uniform in ±``initial_heading_error_deg``. Per episode, from the reset seed: Hs, Tp and the
    relative wave heading β (uniform in the ranges), the wave components (random phases and
    jittered frequencies), optionally the speed and the GM of the loading. The waves ramp up over
    ``wave_ramp_time_s`` (Matusiak 2003, eq. 12). ``reset`` info: ``wave_height_m`` (Hs),
    ``wave_period_s`` (Tp), ``wave_heading_deg`` (β), ``heading_setpoint_deg``,
    ``initial_speed_mps``, ``gm_m``, ``capsize_angle_deg``.

    ## Episode End

    Terminated when |φ| exceeds the capsize angle at any physics step (default: the angle of
    vanishing stability of the episode's loading from its GZ curve, 66.2° for the nominal S175;
    ``capsize_angle_deg`` overrides it) or when the integration diverges (``info["diverged"]``).
    Truncated by the time limit: {time_limit}.
    """

    task_class = CourseKeepingTask


class CourseKeepingVectorEnv(TaskVectorEnv):
    __doc__ = vector_env_docstring(CourseKeepingEnv)
    task_class = CourseKeepingTask
