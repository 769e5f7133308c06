"""``ship_gym/RideControl-v2``: reduce the vertical accelerations of the S175 in head seas.

The task (:class:`RideControlTask`) runs on :class:`ship_gym.envs.env_task.ShipEnvTask` with the
comfort bookkeeping of :class:`ship_gym.envs.roll_stabilisation.ComfortShipTask`; the Gymnasium
faces are :class:`RideControlEnv` and :class:`RideControlVectorEnv`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from ship_gym.comfort.metrics import ComfortSample
from ship_gym.envs.base import TaskEnv, TaskStep, TaskVectorEnv
from ship_gym.envs.docstrings import (
    FORWARD_SPEED_V3,
    VERSION_HISTORY,
    env_docstring,
    vector_env_docstring,
)
from ship_gym.envs.env_task import S175_MESH, irregular_sea, point_scaled_from_s175, ship_kwargs
from ship_gym.envs.observations import Observation
from ship_gym.envs.registration import max_episode_steps
from ship_gym.envs.roll_stabilisation import ComfortShipTask
from ship_gym.envs.ship_task import StepStatistics
from ship_gym.envs.validation import check_positive, check_weight
from ship_gym.typing import ForwardSpeedModel, IntegratorName, Precision

__all__ = ["MAX_EPISODE_STEPS", "RideControlEnv", "RideControlTask", "RideControlVectorEnv"]

MAX_EPISODE_STEPS = max_episode_steps("RideControl")
"""Time limit in control steps, from the registration (250 s at the default control_dt)."""

FOIL_LIMIT_DEG = 15.0
"""T-foil angle limit of the servo [deg] (:data:`ship_gym.control.actuators.FOIL_SERVO`)."""
_FOIL_LIMIT = math.radians(FOIL_LIMIT_DEG)
S175_PASSENGER_POINT_M = (50.0, 0.0, -10.0)
"""Default passenger position on the S175 [m] (forward, on the centreline, above the deck); on
another ship scaled by :func:`~ship_gym.envs.env_task.point_scaled_from_s175`."""


class RideControlTask(ComfortShipTask):
    """N ride-control episodes (see :class:`RideControlEnv` for the keyword arguments)."""

    task_observations = (
        Observation("T-foil angle", "rad", -math.pi / 2, math.pi / 2, doc="T-foil angle (servo)",
                    bound="±π/2"),
        Observation("vertical acceleration at the passenger", "m/s^2", -30.0, 30.0,
                    doc="earth-vertical acceleration at the passenger point (down positive)"),
        Observation("T-foil command", "rad", -_FOIL_LIMIT, _FOIL_LIMIT,
                    doc="T-foil command δ_c (the servo follows it at ≤ 20 °/s)"),
        Observation("T-foil travel over the last step", "rate limit x step", -1.0, 1.0,
                    doc="T-foil travel over the last control step Δδ/(δ̇_max Δt)"),
    )  # fmt: skip
    """The task's observation entries (written by :meth:`_write_extra_observations`)."""

    def __init__(
        self,
        num_envs: int,
        *,
        ship: str = "s175",
        froude_number: float = 0.3,
        speed_range_mps: tuple[float, float] | None = None,
        hs_range_m: tuple[float, float] = (2.0, 4.0),
        tp_range_s: tuple[float, float] = (7.0, 11.0),
        wave_heading_range_deg: tuple[float, float] = (150.0, 210.0),
        n_wave_components: int = 40,
        wave_spreading_s: float | None = None,
        wave_ramp_time_s: float = 20.0,
        kg_m: float | None = None,
        passenger_point_m: Sequence[float] | None = None,
        physics_dt_s: float = 0.05,
        control_dt_s: float = 0.25,
        integrator: IntegratorName = "holloway",
        hull_mesh: Sequence[int] = S175_MESH,
        precision: Precision = "float32",
        forward_speed_model: ForwardSpeedModel = "relative_motion",
        wind_speed_mps: float = 0.0,
        wind_from_deg: float = 0.0,
        num_threads: int = 1,
        capsize_angle_deg: float | None = None,
        dangerous_roll_deg: float = 25.0,
        vertical_weight: float = 1.0,
        vertical_scale_mps2: float = 1.0,
        effort_weight: float = 0.05,
        foil_rate_weight: float = 0.05,
        capsize_penalty: float = 100.0,
        vertical_rms_limit_g: float = 0.05,
        comfort_time_constant_s: float = 30.0,
        sensor_noise: float = 0.0,
        wave_preview_m: Sequence[float] | Sequence[Sequence[float]] = (),
    ) -> None:
        args = dict(locals())  # the arguments, forwarded by name (ship_kwargs, irregular_sea)
        self.vertical_weight = check_weight("vertical_weight", vertical_weight)
        self.vertical_scale = check_positive(
            "vertical_scale_mps2", vertical_scale_mps2, "m/s²", 50.0
        )
        self.effort_weight = check_weight("effort_weight", effort_weight)
        self.foil_rate_weight = check_weight("foil_rate_weight", foil_rate_weight)
        limit_g = check_positive("vertical_rms_limit_g", vertical_rms_limit_g, "g", 2.0)
        self.foil_limit = math.radians(FOIL_LIMIT_DEG)
        self.action_names = (f"T-foil command (-1..1 = ±{FOIL_LIMIT_DEG:g} deg, + = nose up)",)
        super().__init__(
            num_envs,
            passenger_point_m=(
                point_scaled_from_s175(ship, S175_PASSENGER_POINT_M)
                if passenger_point_m is None
                else passenger_point_m
            ),
            actuators=(("t_foil_command", "t_foil", self.foil_limit),),
            comfort_time_constant_s=comfort_time_constant_s,
            rudder="autopilot",
            setup_changes={"t_foil": "command"},
            sea=irregular_sea(args),
            extra_observations=self.task_observations,
            **ship_kwargs(args),
        )
        self.vertical_rms_limit = limit_g * float(self.sim.hull.g)

    # ------------------------------------------------------------------ hooks
    def _apply_actions(self, actions: NDArray) -> None:
        self._apply_surface_actions(actions)

    def _write_extra_observations(self, out: NDArray) -> None:
        out[:, 0] = self._actuator_models[0].angle
        out[:, 1] = self.sample.vertical
        out[:, 2] = self.commands["t_foil_command"]
        out[:, 3] = self.servo_travel("t_foil")

    def _comfort_reward_terms(
        self, stats: StepStatistics, sample: ComfortSample
    ) -> dict[str, NDArray]:
        effort = (self._actuator_models[0].angle / self.foil_limit) ** 2
        return {
            "vertical": -self.vertical_weight
            * (sample.weighted_vertical / self.vertical_scale) ** 2,
            "effort": -self.effort_weight * effort,
            "foil_rate": -self.foil_rate_weight * self.servo_travel("t_foil") ** 2,
        }

    def _task_info(self, stats: StepStatistics) -> dict[str, NDArray]:
        return {
            "t_foil_angle_deg": np.degrees(self._actuator_models[0].angle),
            "weighted_vertical_acceleration_mps2": self.sample.weighted_vertical.copy(),
            **self._comfort_info(),
        }

    def step(self, actions: NDArray) -> TaskStep:
        """The ship-task step with the ride-control cost: 1 while the running RMS of the
        vertical acceleration at the passenger exceeds the limit, else the dangerous-roll
        fraction."""
        out = super().step(actions)
        excess = self.sample.vertical_rms > self.vertical_rms_limit
        return TaskStep(out.reward_terms, np.where(excess, 1.0, out.cost), out.terminated, out.info)


_ARGUMENTS: dict[str, tuple[str, str]] = {
    # this environment's own rows and meanings (the shared ones: SHIP_ARGUMENTS)
    "froude_number": ("-", "reference speed U = Fn √(g L) (12.4 m/s)"),
    "wave_heading_range_deg": ("deg", "relative wave heading β (180 = head seas)"),
    "kg_m": ("m", "KG of the loading (None: 9.55 m)"),
    "dangerous_roll_deg": ("deg", "roll angle of the roll part of the cost"),
    "vertical_weight": ("-", "weight of the weighted vertical acceleration"),
    "vertical_scale_mps2": ("m/s²", "its scale"),
    "effort_weight": ("-", "weight of the foil effort"),
    "foil_rate_weight": ("-", "weight of the foil-travel (wear) term"),
    "vertical_rms_limit_g": ("g", "RMS vertical acceleration limit of the cost"),
}


@env_docstring(
    _ARGUMENTS,
    (
        *VERSION_HISTORY,
        "v2: the T-foil's travel costs (wear: −foil_rate_weight · (Δδ/(δ̇_max Δt))², 0.05 by "
        "default, equal to effort_weight); the foil command and its travel over the last step "
        "are observed (the servo lags the command: with the angle alone the task was not Markov "
        "in the actuator).",
        FORWARD_SPEED_V3,
    ),
)
class RideControlEnv(TaskEnv):
    """Reduce the vertical accelerations of the S175 in head and bow seas with a bow T-foil.

    ## Description

    The default ship is the ITTC S175 container ship at Fn = 0.3 (12.4 m/s, 24 kn), whose
    database and seakeeping are validated; at Fn 0.3 in head seas its pitch and heave
    accelerations at its bow quarter are those ride control addresses. A ship built for speed is
    bundled too: ``ship="dtmb5415"`` (the DTMB 5415 combatant, Lpp 142 m, tested at Fn 0.28 and
    0.41; its T-foil, fins and rudder estimated from its particulars,
    :mod:`ship_gym.ship.appendages`), and any ship file works (``ship="my_ship.toml"``). The
    motions are simulated in 6 DOF (:mod:`ship_gym.engine`): nonlinear Froude–Krylov and hydrostatic
    forces, radiation memory, diffraction, Ikeda roll damping, Holtrop resistance and a B-series
    propeller, hull manoeuvring forces, a rudder under the PID heading autopilot, and a 12.8 m²
    T-foil under the forefoot (S175: x = 65 m; ±15°, 20 °/s, :class:`ship_gym.forces.fins.TFoil`).
    The agent commands the T-foil. No stern flaps: the S175's cruiser stern has no immersed
    transom to carry them. The reward penalises the ISO 2631-1 W_f-weighted vertical
    acceleration at a passenger point (whose squared sum over an episode is the motion sickness
    dose, :mod:`ship_gym.comfort.metrics`), actuator effort and foil travel (wear).

    ## Action Space

    ``Box(-1, 1, (1,), float32)``: T-foil angle command δ_c = a · 15°; positive turns the foil
    nose up: an upward force under the bow and a bow-up pitch moment. A classical ride
    controller commands δ ≈ k_w w − k_q q (heave-velocity and pitch-rate damping).

    ## Observation Space

    ``Box(float32)``; entries (``env.observation_names``), each clipped to its bound:

    {ship_observations}

    The accelerations at the passenger point use ν̇ from the backward difference of ν over the
    control step (:class:`ship_gym.comfort.metrics.PassengerComfort`).

    ## Rewards

    r = Σ of the weighted terms, each in ``info["reward_<term>"]``:

    * ``vertical`` = −vertical_weight · (a_w/vertical_scale)², a_w the W_f-weighted (ISO
      2631-1:1997, Annex A) earth-vertical acceleration at the passenger point;
    * ``effort`` = −effort_weight · (δ_foil/15°)²;
    * ``foil_rate`` = −foil_rate_weight · (Δδ_foil/(δ̇_max Δt))², Δδ_foil the servo travel over
      the control step Δt and δ̇_max = 20 °/s its rate limit (1 = travelling at the limit the
      whole step: foil wear);
    * ``capsize`` = −capsize_penalty in the step the ship capsizes.

    ``info["cost"]`` (Safe RL, the fraction of the step in violation of the task's constraints,
    as in every ship env: :mod:`ship_gym.envs.ship_task`) is 1 in the step that capsizes and
    while the running RMS (τ = ``comfort_time_constant_s``) of
    the vertical acceleration at the passenger exceeds ``vertical_rms_limit_g`` · g (0.05 g is
    NORDFORSK's 1987 limit for passenger ships), otherwise the fraction of the physics steps
    with |φ| above ``dangerous_roll_deg``. Further info: ``t_foil_angle_deg``,
    ``weighted_vertical_acceleration_mps2``, ``vertical_acceleration_mps2``,
    ``lateral_acceleration_mps2``, their running RMS, ``msdv_z`` (ISO 2631-1 motion sickness
    dose value of the episode so far [m/s^1.5]) and ``msi_percent`` (MSDV_z/3, ISO Annex D).

    ## Starting State

    Free-floating equilibrium, heading north (ψ = 0, the autopilot's set-point) at the initial
    speed, foil at zero. Per episode, from the reset seed: Hs, Tp and the relative wave heading
    β, the wave components, optionally the speed. The waves ramp up over ``wave_ramp_time_s``.
    ``reset`` info: ``wave_height_m``, ``wave_period_s``, ``wave_heading_deg``,
    ``initial_speed_mps``, ``gm_m``, ``capsize_angle_deg``.

    ## Episode End

    Terminated when |φ| exceeds the capsize angle or the integration diverges (a safeguard: in
    head seas the S175 does not come near it). Truncated by the time limit:
    {time_limit}.
    """

    task_class = RideControlTask


class RideControlVectorEnv(TaskVectorEnv):
    __doc__ = vector_env_docstring(RideControlEnv)
    task_class = RideControlTask
