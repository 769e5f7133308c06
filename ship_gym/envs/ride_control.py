"""``ship_gym/RideControl-v0``: reduce the vertical accelerations of the S175 in head seas.

The task (:class:`RideControlTask`) runs on :class:`ship_gym.envs.ship_task.ShipTask` with the
comfort bookkeeping of :class:`ship_gym.envs.roll_stabilization.ComfortShipTask`; the Gymnasium
faces are :class:`RideControlEnv` and :class:`RideControlVectorEnv`.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from ship_gym.envs.base import TaskEnv, TaskStep, TaskVectorEnv
from ship_gym.envs.comfort import ComfortSample
from ship_gym.envs.roll_stabilization import ComfortShipTask, _check_point
from ship_gym.envs.ship_task import (
    S175_MESH,
    SeaSampler,
    StepStatistics,
    check_positive,
    check_weight,
    s175_setup,
)

__all__ = ["MAX_EPISODE_STEPS", "RideControlEnv", "RideControlTask", "RideControlVectorEnv"]

MAX_EPISODE_STEPS = 1000
"""Time limit in control steps (250 s at the default control_dt = 0.25 s)."""

FOIL_LIMIT_DEG = 15.0
"""T-foil angle limit of the servo [deg] (:data:`ship_gym.control.actuators.FOIL_SERVO`)."""


class RideControlTask(ComfortShipTask):
    """N ride-control episodes (see :class:`RideControlEnv` for the keyword arguments)."""

    def __init__(
        self,
        num_envs: int,
        *,
        froude_number: float = 0.3,
        speed_range_mps: tuple[float, float] | None = None,
        hs_range_m: tuple[float, float] = (2.0, 4.0),
        tp_range_s: tuple[float, float] = (7.0, 11.0),
        wave_heading_range_deg: tuple[float, float] = (150.0, 210.0),
        n_wave_components: int = 40,
        wave_spreading_s: float | None = None,
        wave_ramp_time_s: float = 20.0,
        kg_m: float | None = None,
        passenger_point_m: Sequence[float] = (50.0, 0.0, -10.0),
        physics_dt_s: float = 0.05,
        control_dt_s: float = 0.25,
        integrator: Literal["holloway", "rk4"] = "holloway",
        hull_mesh: Sequence[int] = S175_MESH,
        capsize_angle_deg: float | None = None,
        dangerous_roll_deg: float = 25.0,
        vertical_weight: float = 1.0,
        vertical_scale_mps2: float = 1.0,
        effort_weight: float = 0.05,
        capsize_penalty: float = 100.0,
        vertical_rms_limit_g: float = 0.05,
        comfort_time_constant_s: float = 30.0,
        sensor_noise: float = 0.0,
        wave_preview_m: Sequence[float] = (),
    ) -> None:
        self.vertical_weight = check_weight("vertical_weight", vertical_weight)
        self.vertical_scale = check_positive(
            "vertical_scale_mps2", vertical_scale_mps2, "m/s²", 50.0
        )
        self.effort_weight = check_weight("effort_weight", effort_weight)
        self.capsize_penalty = check_weight("capsize_penalty", capsize_penalty)
        limit_g = check_positive("vertical_rms_limit_g", vertical_rms_limit_g, "g", 2.0)
        tau = check_positive("comfort_time_constant_s", comfort_time_constant_s, "s", 3600.0)
        point = _check_point("passenger_point_m", passenger_point_m)
        self.foil_limit = math.radians(FOIL_LIMIT_DEG)
        self.action_names = (f"T-foil command (-1..1 = ±{FOIL_LIMIT_DEG:g} deg, + = nose up)",)
        setup = s175_setup(
            froude_number=froude_number,
            physics_dt=physics_dt_s,
            integrator=integrator,
            rudder="autopilot",
            hull_mesh=hull_mesh,
            kg=kg_m,
        )
        setup = dataclasses.replace(setup, t_foil="command")
        sea = SeaSampler(
            kind="irregular",
            height_range=hs_range_m,
            period_range=tp_range_s,
            heading_range_deg=wave_heading_range_deg,
            n_components=n_wave_components,
            spreading_s=wave_spreading_s,
            ramp_time=wave_ramp_time_s,
        )
        super().__init__(
            num_envs,
            passenger_point=point,
            actuators=(("t_foil_command", "t_foil", self.foil_limit),),
            comfort_time_constant_s=tau,
            setup=setup,
            sea=sea,
            control_dt=control_dt_s,
            speed_range=speed_range_mps,
            capsize_angle_deg=capsize_angle_deg,
            dangerous_roll_deg=dangerous_roll_deg,
            sensor_noise=sensor_noise,
            wave_preview_m=wave_preview_m,
            extra_observations=(
                ("T-foil angle [rad]", -math.pi / 2, math.pi / 2),
                ("vertical acceleration at the passenger [m/s^2]", -30.0, 30.0),
            ),
        )
        self.vertical_rms_limit = limit_g * float(self.sim.hull.g)

    # ------------------------------------------------------------------ hooks
    def _apply_actions(self, actions: NDArray) -> None:
        self._apply_surface_actions(actions)

    def _extra_observations(self) -> NDArray:
        return np.column_stack([self.actuator_angles()[:, 0], self.sample.vertical])

    def _comfort_reward_terms(
        self, stats: StepStatistics, sample: ComfortSample
    ) -> dict[str, NDArray]:
        effort = (self.actuator_angles()[:, 0] / self.foil_limit) ** 2
        return {
            "vertical": -self.vertical_weight
            * (sample.weighted_vertical / self.vertical_scale) ** 2,
            "effort": -self.effort_weight * effort,
            "capsize": -self.capsize_penalty * stats.newly_capsized,
        }

    def _task_info(self, stats: StepStatistics) -> dict[str, NDArray]:
        return {
            "t_foil_angle_deg": np.degrees(self.actuator_angles()[:, 0]),
            "weighted_vertical_acceleration_mps2": self.sample.weighted_vertical.copy(),
            **self._comfort_info(),
        }

    def step(self, actions: NDArray) -> TaskStep:
        """The ship-task step with the ride-control cost: 1 while the running RMS of the
        vertical acceleration at the passenger exceeds the limit, else the dangerous-roll
        fraction."""
        out = super().step(actions)
        excess = self.sample.vertical_rms > self.vertical_rms_limit
        return dataclasses.replace(out, cost=np.where(excess, 1.0, out.cost))


class RideControlEnv(TaskEnv):
    """Reduce the vertical accelerations of the S175 in head and bow seas with a bow T-foil.

    ## Description

    The hull is the ITTC S175 container ship at Fn = 0.3 (12.4 m/s, 24 kn), not a purpose-built
    fast monohull: its hydrodynamic database (radiation, diffraction) is validated and bundled,
    while a new hull would need its own BEM database; at Fn 0.3 in head seas the S175's pitch
    and heave accelerations at its bow quarter are those ride control addresses. Its motions are
    simulated in 6 DOF (:mod:`ship_gym.dynamics`): nonlinear Froude–Krylov and hydrostatic
    forces, radiation memory, diffraction, Ikeda roll damping, Holtrop resistance and a B-series
    propeller, hull manoeuvring forces, a rudder under the PID heading autopilot, and a 12.8 m²
    T-foil under the forefoot (x = 65 m, ±15°, 20 °/s, :class:`ship_gym.forces.fins.TFoil`).
    The agent commands the T-foil. No stern flaps: the S175's cruiser stern has no immersed
    transom to carry them. The reward penalises the ISO 2631-1 W_f-weighted vertical
    acceleration at a passenger point (whose squared sum over an episode is the motion sickness
    dose, :mod:`ship_gym.envs.comfort`) and actuator effort.

    ## Action Space

    ``Box(-1, 1, (1,), float32)``: T-foil angle command δ_c = a · 15°; positive turns the foil
    nose up: an upward force under the bow and a bow-up pitch moment. A classical ride
    controller commands δ ≈ k_w w − k_q q (heave-velocity and pitch-rate damping).

    ## Observation Space

    ``Box(float32)``; entries (``env.observation_names``), each clipped to its bound:

    | # | name | unit | bound |
    |---|---|---|---|
    | 0 | roll φ | rad | ±π |
    | 1 | pitch θ | rad | ±π/2 |
    | 2 | heave (from the calm-water equilibrium, down positive) | m | ±30 |
    | 3–5 | roll rate p, pitch rate q, heave velocity w (body) | rad/s, rad/s, m/s | 5, 5, 30 |
    | 6 | yaw rate r | rad/s | ±2 |
    | 7–8 | surge speed u, sway velocity v | m/s | ±30 |
    | 9 | heading error wrap(ψ_ref − ψ) | rad | ±π |
    | 10–11 | cos β, sin β of the mean relative wave heading β = χ − ψ | - | ±1 |
    | 12 | rudder angle (servo, autopilot) | rad | ±π/2 |
    | 13 | shaft speed | rev/s | ±20 |
    | 14 | T-foil angle (servo) | rad | ±π/2 |
    | 15 | earth-vertical acceleration at the passenger point (down positive) | m/s² | ±30 |
    | 16… | incident elevation at ``wave_preview_m`` ahead (if any) | m | ±30 |

    The accelerations at the passenger point use ν̇ from the backward difference of ν over the
    control step (:class:`ship_gym.envs.comfort.PassengerComfort`).

    ## Rewards

    r = Σ of the weighted terms, each in ``info["reward_<term>"]``:

    * ``vertical`` = −vertical_weight · (a_w/vertical_scale)², a_w the W_f-weighted (ISO
      2631-1:1997, Annex A) earth-vertical acceleration at the passenger point;
    * ``effort`` = −effort_weight · (δ_foil/15°)²;
    * ``capsize`` = −capsize_penalty in the step the ship capsizes.

    ``info["cost"]`` (Safe RL) is 1 while the running RMS (τ = ``comfort_time_constant_s``) of
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
    head seas the S175 does not come near it). Truncated by the time limit
    (``MAX_EPISODE_STEPS`` = 1000 control steps = 250 s).

    ## Arguments

    | kwarg | default | unit | meaning |
    |---|---|---|---|
    | froude_number | 0.3 | - | reference speed U = Fn √(g L) (12.4 m/s) |
    | speed_range_mps | None | m/s | initial speed range (self-propulsion rpm); keep near U |
    | hs_range_m | (2, 4) | m | significant wave height range |
    | tp_range_s | (7, 11) | s | peak period range |
    | wave_heading_range_deg | (150, 210) | deg | relative wave heading β (180 = head seas) |
    | n_wave_components | 40 | - | components of the irregular sea |
    | wave_spreading_s | None | - | cos-2s spreading exponent (None: long-crested) |
    | wave_ramp_time_s | 20 | s | start-up ramp of the waves |
    | kg_m | None | m | KG of the loading (None: 9.55 m) |
    | passenger_point_m | (50, 0, −10) | m | body-frame passenger position (z down) |
    | physics_dt_s | 0.05 | s | physics time step |
    | control_dt_s | 0.25 | s | control step (integer multiple of physics_dt_s) |
    | integrator | "holloway" | - | "holloway" (1 evaluation/step) or "rk4" |
    | hull_mesh | (60, 12, 6, 4) | - | S175 mesh (sections, panels below/above water, deck) |
    | capsize_angle_deg | None | deg | capsize roll angle (None: vanishing angle) |
    | dangerous_roll_deg | 25 | deg | roll angle of the roll part of the cost |
    | vertical_weight | 1.0 | - | weight of the weighted vertical acceleration |
    | vertical_scale_mps2 | 1.0 | m/s² | its scale |
    | effort_weight | 0.05 | - | weight of the foil effort |
    | capsize_penalty | 100 | - | penalty paid at capsize |
    | vertical_rms_limit_g | 0.05 | g | RMS vertical acceleration limit of the cost |
    | comfort_time_constant_s | 30 | s | time constant of the running acceleration RMS |
    | sensor_noise | 0 | - | multiplier of the sensor accuracies |
    | wave_preview_m | () | m | distances ahead of O of the elevation preview |

    ## Version History

    * v0: initial version.
    """

    task_class = RideControlTask


class RideControlVectorEnv(TaskVectorEnv):
    """N episodes of :class:`RideControlEnv` in one BatchSimulator (same arguments).

    Episode i reset with ``seed=s`` is the single environment reset with ``seed=s + i``.
    """

    task_class = RideControlTask
