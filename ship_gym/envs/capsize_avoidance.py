"""``ship_gym/CapsizeAvoidance-v3``: make way in steep following seas without capsizing.

Matusiak's capsize scenario (Matusiak 2003, "Importance of memory effect for capsizing
prediction": regular waves λ = 1.5 L, amplitude 4.5 m for L = 150 m, Fn 0.2–0.4, headings 0–45°
off following seas; the A-1 container ship capsized at Fn 0.4, 30°) on the S175, scaled with
length (amplitude 5.25 m, H ≈ 10.5 m, λ ≈ 262 m). The heading autopilot steers; the agent
changes its set-point and the engine telegraph, seeing the sea state as the officer of the watch
estimates it (wave period, λ/L, H/L) and the roll period of the loading — what the IMO guidance
to the master (MSC.1/Circ.1228) asks him to watch. On ``-v2`` (the forward-speed model of
issue #13), kept on course and speed (zero action) the ship capsized in about a third of the
default episodes (35 % [24 %, 48 %], Wilson 95 %, 60 episodes of 750 s, seeds 5000–5059; 16/60
on seeds 10000–10059). On ``-v3``, with the speed terms on the motion relative to the waves, it
capsizes in none of the 60 episodes of seeds 10000–10059 (0 % [0 %, 6.0 %]): those capsizes came
from the spurious moment, and at these defaults the task holds no dilemma between progress and
survival (issue #31 builds the heavy-weather task that does). The task
(:class:`CapsizeAvoidanceTask`) runs on :class:`ship_gym.envs.env_task.ShipEnvTask`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Literal

import numba
import numpy as np
from numpy.typing import NDArray

from ship_gym.conventions import GRAVITY
from ship_gym.envs._kernels import along_course_kernel, clip_array_bound, clip_scalar_bound
from ship_gym.envs.base import TaskEnv, TaskVectorEnv
from ship_gym.envs.docstrings import (
    FORWARD_SPEED_V3,
    VERSION_HISTORY,
    env_docstring,
    vector_env_docstring,
)
from ship_gym.envs.env_task import S175_MESH, ShipEnvTask, ship_kwargs, ship_particulars
from ship_gym.envs.observations import Observation
from ship_gym.envs.registration import max_episode_steps
from ship_gym.envs.seas import SeaSampler
from ship_gym.envs.ship_task import StepStatistics
from ship_gym.envs.validation import check_positive, check_range, check_real, check_weight
from ship_gym.numerics.angles import wrap_angle_scalar
from ship_gym.typing import ForwardSpeedModel, IntegratorName, Precision

__all__ = [
    "MAX_EPISODE_STEPS",
    "CapsizeAvoidanceEnv",
    "CapsizeAvoidanceTask",
    "CapsizeAvoidanceVectorEnv",
]

MAX_EPISODE_STEPS = max_episode_steps("CapsizeAvoidance")
"""Time limit in control steps, from the registration (750 s at the default control_dt;
Matusiak ran 720 s)."""

S175_LPP = 175.0  # [m]
DEFAULT_WAVE_HEIGHT_M = (10.0, 11.0)
"""H range [m] of the default episodes on the S175 (steepness ≈ 1/25 at λ = 1.5 L); another
ship's default is this range × Lpp/175."""


_TWO_PI = 2.0 * math.pi


@numba.njit(cache=True, nogil=True)
def _apply_actions_kernel(
    actions, heading_rate, course, max_deviation, lo, hi, telegraph_step, nominal, max_change,
    setpoint, heading_command, telegraph, shaft_speed,
):  # fmt: skip  # pragma: no cover - compiled
    """Per episode: ψ_ref ← course + clip(wrap(ψ_ref + a₀ · rate − course), ±max deviation);
    telegraph f ← clip(f + a₁ · step, lo, hi) (× the self-propulsion rpm); shaft speed ← f ·
    nominal clipped to ± ``max_change`` of the current one."""
    for i in range(actions.shape[0]):
        dev = wrap_angle_scalar(setpoint[i] + actions[i, 0] * heading_rate - course)
        dev = clip_scalar_bound(dev, -max_deviation, max_deviation)
        setpoint[i] = course + dev
        heading_command[i] = setpoint[i]
        telegraph[i] = clip_scalar_bound(telegraph[i] + actions[i, 1] * telegraph_step, lo, hi)
        n = shaft_speed[i]
        target = telegraph[i] * nominal
        shaft_speed[i] = clip_array_bound(target, n - max_change, n + max_change)


@numba.njit(cache=True, nogil=True)
def _write_observations_kernel(
    psi, setpoint, course, telegraph, period, wavelength_ratio, height_ratio, roll_period, out,
):  # fmt: skip  # pragma: no cover - compiled
    """The task observations [wrap(ψ − course), wrap(ψ_ref − course), f, T_W, λ/L, H/L, T_R]."""
    for i in range(psi.shape[0]):
        out[i, 0] = wrap_angle_scalar(psi[i] - course)
        out[i, 1] = wrap_angle_scalar(setpoint[i] - course)
        out[i, 2] = telegraph[i]
        out[i, 3] = period[i]
        out[i, 4] = wavelength_ratio[i]
        out[i, 5] = height_ratio[i]
        out[i, 6] = roll_period[i]


class CapsizeAvoidanceTask(ShipEnvTask):
    """N capsize-avoidance episodes (see :class:`CapsizeAvoidanceEnv` for the arguments)."""

    task_observations = (
        Observation("heading from voyage course", "rad", -math.pi, math.pi,
                    doc="heading ψ from the voyage course (wrapped)", bound="±π"),
        Observation("heading set-point from voyage course", "rad", -math.pi, math.pi,
                    doc="heading set-point from the voyage course (wrapped)", bound="±π"),
        Observation("telegraph", "× self-propulsion rpm", 0.0, 2.0, doc="telegraph f"),
        Observation("wave period", "s", 0.0, 60.0,
                    doc="wave period T_W as observed (T of a regular wave, Tp of a spectrum)"),
        Observation("wavelength / ship length", "-", 0.0, 20.0,
                    doc="λ/L, λ = g T_W²/2π (deep water)"),
        Observation("wave height / ship length", "-", 0.0, 0.5,
                    doc="H/L (H of a regular wave, Hs of a spectrum)"),
        Observation("roll natural period", "s", 0.0, 100.0,
                    doc="roll natural period T_R of the episode's loading (T_R,nom √(GM_nom/GM))"),
    )  # fmt: skip
    """The task's observation entries (written by :meth:`_write_extra_observations`)."""

    def __init__(
        self,
        num_envs: int,
        *,
        ship: str = "s175",
        froude_number: float = 0.35,
        froude_range: tuple[float, float] | None = (0.25, 0.35),
        sea_kind: Literal["regular", "irregular"] = "regular",
        wave_height_range_m: tuple[float, float] | None = None,
        wavelength_ratio_range: tuple[float, float] = (1.4, 1.6),
        wave_heading_range_deg: tuple[float, float] = (-45.0, 45.0),
        n_wave_components: int = 40,
        wave_ramp_time_s: float = 50.0,
        gm_range_m: tuple[float, float] | None = None,
        kg_m: float | None = None,
        heading_rate_deg: float = 2.0,
        max_course_deviation_deg: float = 90.0,
        shaft_speed_range: tuple[float, float] = (0.3, 1.2),
        telegraph_step: float = 0.02,
        shaft_rate_per_s: float = 0.01,
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
        dangerous_roll_deg: float = 30.0,
        progress_weight: float = 1.0,
        danger_weight: float = 1.0,
        capsize_penalty: float = 100.0,
        sensor_noise: float = 0.0,
        wave_preview_m: Sequence[float] | Sequence[Sequence[float]] = (),
    ) -> None:
        args = dict(locals())  # the arguments, forwarded by name (ship_kwargs)
        check_real("froude_number", froude_number, low=0.05, high=0.5, unit="-")
        lpp = float(ship_particulars(ship).lpp)
        if wave_height_range_m is None:  # the S175's steep seas, scaled with the ship's length
            scale = lpp / S175_LPP
            low_h, high_h = DEFAULT_WAVE_HEIGHT_M
            wave_height_range_m = (low_h * scale, high_h * scale)
        if sea_kind not in ("regular", "irregular"):
            raise ValueError(f"sea_kind must be 'regular' or 'irregular', got {sea_kind!r}")
        ratio = check_range(
            "wavelength_ratio_range", wavelength_ratio_range, low=0.2, high=5.0, unit="λ/Lpp"
        )
        # deep water: T = √(2π λ / g) (the peak period of an irregular sea)
        periods = (
            math.sqrt(2.0 * math.pi * ratio[0] * lpp / GRAVITY),
            math.sqrt(2.0 * math.pi * ratio[1] * lpp / GRAVITY),
        )
        self.heading_rate = math.radians(
            check_positive("heading_rate_deg", heading_rate_deg, "deg", 45.0)
        )
        self.max_course_deviation = math.radians(
            check_positive("max_course_deviation_deg", max_course_deviation_deg, "deg", 180.0)
        )
        lo, hi = check_range(
            "shaft_speed_range", shaft_speed_range, low=0.0, high=2.0, unit="× self-propulsion rpm"
        )
        if hi <= lo:
            raise ValueError(f"shaft_speed_range must have min < max, got {shaft_speed_range!r}")
        self.shaft_fraction_range = (lo, hi)
        self.telegraph_step = check_positive("telegraph_step", telegraph_step, "-", 1.0)
        self.shaft_rate = check_positive("shaft_rate_per_s", shaft_rate_per_s, "1/s", 10.0)
        if froude_range is not None:
            froude_range = check_range("froude_range", froude_range, low=0.05, high=0.5, unit="-")
        self.progress_weight = check_weight("progress_weight", progress_weight)
        self.danger_weight = check_weight("danger_weight", danger_weight)
        self.action_names = (
            f"heading set-point change (-1..1 = ±{heading_rate_deg:g} deg per step)",
            f"telegraph change (-1..1 = ±{telegraph_step:g} × self-propulsion rpm at Fn "
            f"{froude_number:g} per step, within {lo:g}..{hi:g})",
        )
        sea = SeaSampler(
            kind=sea_kind,
            height_range=wave_height_range_m,
            period_range=periods,
            heading_range_deg=wave_heading_range_deg,
            n_components=n_wave_components,
            ramp_time=wave_ramp_time_s,
            keywords=(
                "wave_height_range_m",
                "wavelength_ratio_range (as periods [s])",
                "wave_heading_range_deg",
                "n_wave_components",
                "gamma",
                "wave_spreading_s",
                "wave_ramp_time_s",
            ),
        )
        speed_range: tuple[float, float] | None = None
        if froude_range is not None:
            low, high = froude_range
            speed_range = (
                low * math.sqrt(GRAVITY * lpp),
                high * math.sqrt(GRAVITY * lpp),
            )
        super().__init__(
            num_envs,
            rudder="autopilot",
            sea=sea,
            speed_range_mps=speed_range,
            extra_observations=self.task_observations,
            **ship_kwargs(args),
        )
        n = self.num_envs
        self.lpp = lpp
        self.telegraph = np.ones(n)  # [× self-propulsion rpm at froude_number]
        self.voyage_course = 0.0  # [rad], the initial heading (north)
        self._origin = np.zeros((n, 2))
        self._wave_period = np.zeros(n)
        self._wavelength_ratio = np.zeros(n)
        self._height_ratio = np.zeros(n)
        self._roll_period = np.zeros(n)
        self._nominal_roll_period = self.nominal_roll_period()

    # ------------------------------------------------------------------ hooks
    def _reset_task(self, i: int, rng: np.random.Generator) -> dict[str, float]:
        self.telegraph[i] = self.commands["shaft_speed"][i] / self._nominal_shaft_speed
        info = self._reset_infos[i]
        period = info["wave_period_s"]
        self._wave_period[i] = period
        self._wavelength_ratio[i] = GRAVITY * period**2 / _TWO_PI / self.lpp
        self._height_ratio[i] = info["wave_height_m"] / self.lpp
        # G moved vertically: C44 ∝ GM, the inertia nearly unchanged (the master's estimate)
        gm0 = self.loading.gm
        self._roll_period[i] = self._nominal_roll_period * math.sqrt(gm0 / self.gm[i])
        return {"roll_period_s": float(self._roll_period[i])}

    def _apply_actions(self, actions: NDArray) -> None:
        lo, hi = self.shaft_fraction_range
        _apply_actions_kernel(
            actions,
            self.heading_rate,
            self.voyage_course,
            self.max_course_deviation,
            lo,
            hi,
            self.telegraph_step,
            self._nominal_shaft_speed,
            self.shaft_rate * self._nominal_shaft_speed * self.control_dt,
            self.heading_setpoint,
            self.commands["heading"],
            self.telegraph,
            self.commands["shaft_speed"],
        )

    def _write_extra_observations(self, out: NDArray) -> None:
        _write_observations_kernel(
            self.sim.eta[:, 5],
            self.heading_setpoint,
            float(self.voyage_course),
            self.telegraph,
            self._wave_period,
            self._wavelength_ratio,
            self._height_ratio,
            self._roll_period,
            out,
        )

    def _along_course(self, origin: NDArray, weight: float, scale: float) -> NDArray:
        """weight · (distance of O from ``origin`` along the voyage course) / scale, (N,)."""
        out = np.empty(self.num_envs)
        c = self.voyage_course
        along_course_kernel(self.sim.eta, origin, math.cos(c), math.sin(c), weight, scale, out)
        return out

    def _reward_terms(self, stats: StepStatistics) -> dict[str, NDArray]:
        scale = self.setup.speed * self.control_dt
        return {
            "progress": self._along_course(stats.position_before, self.progress_weight, scale),
            "dangerous_roll": -self.danger_weight * stats.danger_fraction,
        }

    def _task_info(self, stats: StepStatistics) -> dict[str, NDArray]:
        return {
            "heading_error_deg": np.degrees(self._current_heading_error()),
            "distance_along_voyage_m": self._along_course(self._origin, 1.0, 1.0),
        }

    def _action_labels(self, i: int) -> dict[str, float]:
        out = super()._action_labels(i)
        out["heading set-point [deg]"] = math.degrees(float(self.heading_setpoint[i]))
        return out


_ARGUMENTS: dict[str, tuple[str, str]] = {
    # this environment's own rows and meanings (the shared ones: SHIP_ARGUMENTS)
    "froude_number": ("-", "reference speed (radiation, diffraction, autopilot, telegraph)"),
    "froude_range": ("-", "initial Froude number range (None: froude_number)"),
    "sea_kind": ("-", '"regular" or "irregular" (JONSWAP, Hs, Tp from λ)'),
    "wave_height_range_m": ("m", "H (regular) or Hs (irregular)"),
    "wavelength_ratio_range": ("-", "λ/Lpp (peak wavelength if irregular)"),
    "wave_heading_range_deg": ("deg", "relative heading β (0 following seas)"),
    "n_wave_components": ("-", "components of an irregular sea"),
    "heading_rate_deg": ("deg", "set-point change per step at a = ±1"),
    "max_course_deviation_deg": ("deg", "largest set-point deviation from the course"),
    "shaft_speed_range": ("-", "telegraph range, × self-propulsion rpm"),
    "telegraph_step": ("-", "telegraph change per step at a = ±1, × self-propulsion rpm"),
    "shaft_rate_per_s": ("1/s", "shaft acceleration, × self-propulsion rpm per s"),
    "dangerous_roll_deg": ("deg", "roll angle of the cost and the danger term"),
    "progress_weight": ("-", "weight of the progress term"),
    "danger_weight": ("-", "weight of the dangerous-roll term"),
}


@env_docstring(
    _ARGUMENTS,
    (
        *VERSION_HISTORY,
        "v2: a dilemma by default — initial Fn 0.25–0.35 (v1: 0.3–0.4), where kept on course and "
        "speed the S175 capsizes in 35 % [24 %, 48 %] of the episodes (v1's defaults, Fn "
        "0.3–0.4 with an absolute telegraph whose zero meant 0.75 × rpm, mixed the two); the "
        "telegraph action is a change per step (zero action = keep course and speed); the sea "
        "state as observed (T_W, λ/L, H/L) and the loading's roll period T_R are observed, "
        "the telegraph as a fraction of the self-propulsion rpm.",
        FORWARD_SPEED_V3,
    ),
)
class CapsizeAvoidanceEnv(TaskEnv):
    """Make way along a voyage course in steep following seas without capsizing the S175.

    ## Description

    Matusiak's capsize scenario (Matusiak 2003: regular waves of length 1.5 L and amplitude
    4.5 m for L = 150 m, Froude numbers 0.2–0.4, headings 0–45° off following seas; the model
    capsized at Fn 0.4, 30°) on the ITTC S175 container ship, scaled with length: λ ≈ 1.5 ×
    175 m, H ≈ 10.5 m (steepness ≈ 1/25), Fn 0.25–0.35. The 6-DOF model (nonlinear
    Froude–Krylov and hydrostatics on the wetted hull, radiation memory, diffraction, Ikeda roll
    damping, resistance, propeller, manoeuvring forces) is steered by a PID heading autopilot
    (tuned on the Nomoto model identified for the hull) acting on a rudder behind its servo. The
    agent changes the autopilot's heading set-point and the engine telegraph; it is rewarded for
    progress along the voyage course (north, the initial heading) and penalised for dangerous
    roll and for capsizing. Kept on course and speed (the zero action) the ship capsizes in
    about a third of the default episodes, mostly in stern-quartering seas; slowing down, or
    turning towards following seas or away from the waves, lowers the risk of pure loss of
    stability on the crest, broaching and resonant rolling at a cost in progress — the
    dangerous zones the IMO guidance to the master (MSC.1/Circ.1228) describes
    (:class:`ship_gym.agents.baselines.IMOGuidanceMaster` follows it).

    ## Action Space

    ``Box(-1, 1, (2,), float32)``:

    * ``a[0]`` — heading set-point change ψ_ref += a · ``heading_rate_deg`` per control step,
      with |ψ_ref − voyage course| ≤ ``max_course_deviation_deg``;
    * ``a[1]`` — telegraph change f += a · ``telegraph_step`` per control step, f within
      ``shaft_speed_range``, f the target shaft speed as a fraction of the calm-water
      self-propulsion shaft speed at ``froude_number``; the shaft speed follows at ≤
      ``shaft_rate_per_s`` × that shaft speed per second. The episode starts with f at the
      self-propulsion rpm of its initial speed.

    ## Observation Space

    ``Box(float32)``; entries (``env.observation_names``), each clipped to its bound:

    {ship_observations}

    ## Rewards

    Σ of the weighted terms (``info["reward_<term>"]``):

    * ``progress`` = progress_weight · Δs / (U_ref Δt_c), Δs the distance made good along the
      voyage course in the control step (1 per step at the reference speed on course);
    * ``dangerous_roll`` = −danger_weight × the fraction of the physics steps with |φ| above
      ``dangerous_roll_deg``;
    * ``capsize`` = −capsize_penalty in the step the ship capsizes.

    ``info["cost"]`` (Safe RL, :mod:`ship_gym.envs.ship_task`) is the fraction of the step's
    physics steps with |φ| above ``dangerous_roll_deg``, 1 in the step that capsizes.

    ## Starting State

    Free-floating equilibrium heading north (the voyage course) at a speed uniform in
    ``froude_range`` (shaft and telegraph at its self-propulsion rpm), autopilot set-point on
    the course. Per episode, from the reset seed: wave height, wavelength (period) and relative
    heading β (uniform in the ranges), the phase (regular) or components (irregular),
    optionally the loading's GM. The waves ramp up over ``wave_ramp_time_s`` (Matusiak eq. 12,
    T_f = 50 s).

    ## Episode End

    Terminated on capsize: |φ| above the angle of vanishing stability of the episode's loading
    (66.2° for the nominal S175; ``capsize_angle_deg`` overrides) at any physics step, or a
    diverged integration (``info["diverged"]``). Truncated by the time limit:
    {time_limit}.
    """

    task_class = CapsizeAvoidanceTask


class CapsizeAvoidanceVectorEnv(TaskVectorEnv):
    __doc__ = vector_env_docstring(CapsizeAvoidanceEnv)
    task_class = CapsizeAvoidanceTask
