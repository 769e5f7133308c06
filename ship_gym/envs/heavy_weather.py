"""``ship_gym/HeavyWeather-v0``: the master's course and speed through heavy weather.

The flagship decision task (issue #31). A voyage along a course (north) through a short-crested
irregular sea drawn per episode from a wide range — JONSWAP, peak wavelength λp = 0.6 … 2 L,
Hs/L = 0.02 … 0.07 below the breaking limit of DNV-RP-C205 (Hs/λp ≤ 1/15 … 1/25), cos-2s
spreading s = 2 … 50 (wind sea to swell), every relative heading — with the loading's GM drawn
per episode down to low-GM conditions. The dangers are those the IMO guidance to the master
(MSC.1/Circ.1228) names: parametric roll in head and following seas near T_E ≈ T_R/2,
synchronous roll near T_E ≈ T_R, surf-riding and broaching in steep following/quartering seas,
successive high waves, large beam-sea roll. The master (the agent) sets the autopilot's course
set-point and the engine telegraph and sees what a bridge has: his ship's motions and their
recent statistics, the sea as a wave radar estimates it (Hs, Tp, λp/L, Hs/L, mean direction),
the roll period of his loading, speed, heading off the voyage course. He is paid for progress
along the voyage course and charged a capsize penalty that makes a capsize never worth its
progress; ``info["cost"]`` (dangerous roll, capsize) serves constrained RL.

Task metric (:func:`voyage_progress`): the mean over episodes of the distance made good along
the voyage course as a fraction of the nominal voyage (U_ref × the episode's duration), a
capsized episode counting 0, judged at a capsize rate no worse than the best classical master's.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ship_gym.conventions import GRAVITY, wrap_angle
from ship_gym.envs._kernels import along_course_kernel
from ship_gym.envs.base import TaskEnv, TaskVectorEnv
from ship_gym.envs.docstrings import env_docstring, vector_env_docstring
from ship_gym.envs.env_task import S175_MESH, ShipEnvTask, ship_kwargs, ship_particulars
from ship_gym.envs.registration import max_episode_steps
from ship_gym.envs.seas import HEADING_LIMITS, HEIGHT_LIMITS, PERIOD_LIMITS, SeaSampler
from ship_gym.envs.ship_task import StepStatistics
from ship_gym.envs.validation import check_positive, check_range, check_real, check_weight
from ship_gym.typing import ForwardSpeedModel, IntegratorName, Precision
from ship_gym.waves.sea_state import irregular_steepness_limit

__all__ = [
    "MAX_EPISODE_STEPS",
    "HeavyWeatherEnv",
    "HeavyWeatherSea",
    "HeavyWeatherTask",
    "HeavyWeatherVectorEnv",
    "telegraph_of_action",
    "voyage_progress",
]

MAX_EPISODE_STEPS = max_episode_steps("HeavyWeather")
"""Time limit in control steps, from the registration (1800 s, half an hour of a watch, at
the default control step of 5 s)."""

_TWO_PI = 2.0 * math.pi
_MAX_DRAWS = 1000  # rejection sampling of the admissible (λp/L, Hs/L) region


@dataclass(frozen=True)
class HeavyWeatherSea(SeaSampler):
    """The sea of a heavy-weather episode: JONSWAP, short-crested, drawn in ship-length units.

    Draws, in this order: λp/L and Hs/L uniform over the admissible part of their ranges (pairs
    steeper than DNV-RP-C205's Hs/λp limit at that Tp are redrawn, so the density is uniform
    over the physical region), the relative mean heading β uniform, the spreading exponent s
    log-uniform, then the wave components
    (:meth:`ship_gym.waves.wave_field.WaveField.from_sea_state`). The reset info names Hs as
    ``wave_height_m`` and Tp as ``wave_period_s`` (the ship tasks' keys), and adds
    ``wave_spreading_s``.

    Parameters
    ----------
    lpp : float
        Ship length L [m] the ratios refer to.
    wavelength_ratio_range : tuple of float
        Peak wavelength λp/L = g Tp²/(2π L) [-].
    height_ratio_range : tuple of float
        Hs/L [-].
    spreading_range : tuple of float
        Cos-2s spreading exponent s [-] (log-uniform; small: short-crested wind sea).
    """

    lpp: float = 175.0
    wavelength_ratio_range: tuple[float, float] = (0.6, 2.0)
    height_ratio_range: tuple[float, float] = (0.02, 0.07)
    spreading_range: tuple[float, float] = (2.0, 50.0)
    keywords: tuple[str, ...] = field(
        default=(
            "height_ratio_range",
            "wavelength_ratio_range",
            "wave_heading_range_deg",
            "n_wave_components",
            "gamma",
            "spreading_range",
            "wave_ramp_time_s",
        ),
        compare=False,
    )

    def __post_init__(self) -> None:
        kh, kl, kb, kn, kg, ks, kr = self.keywords
        lpp = check_real("lpp", self.lpp, low=1.0, high=1000.0, unit="m")
        lam = check_range(kl, self.wavelength_ratio_range, low=0.1, high=10.0, unit="λp/L")
        hr = check_range(kh, self.height_ratio_range, low=0.0, high=0.2, unit="Hs/L")
        spread = check_range(ks, self.spreading_range, low=0.5, high=1000.0, unit="-")
        b = check_range(
            kb, self.heading_range_deg, low=HEADING_LIMITS[0], high=HEADING_LIMITS[1], unit="deg"
        )
        periods = tuple(math.sqrt(_TWO_PI * r * lpp / GRAVITY) for r in lam)
        if not (PERIOD_LIMITS[0] <= periods[0] and periods[1] <= PERIOD_LIMITS[1]):
            raise ValueError(
                f"{kl} = {self.wavelength_ratio_range!r} gives Tp {periods[0]:.2f} … "
                f"{periods[1]:.2f} s on a {lpp:g} m ship; expected within {PERIOD_LIMITS} s"
            )
        if hr[1] * lpp > HEIGHT_LIMITS[1]:
            raise ValueError(
                f"max of {kh} = {hr[1]!r} gives Hs = {hr[1] * lpp:.1f} m on a {lpp:g} m ship; "
                f"expected Hs <= {HEIGHT_LIMITS[1]:g} m"
            )
        # some pair of the ranges must be a physical sea: the gentlest height at the longest λ
        if hr[0] > irregular_steepness_limit(periods[1]) * lam[1]:
            raise ValueError(
                f"{kh} = {self.height_ratio_range!r} is steeper than any physical sea at "
                f"{kl} = {self.wavelength_ratio_range!r} (DNV-RP-C205 Hs/λp limit)"
            )
        n = self.n_components
        if isinstance(n, bool) or not isinstance(n, int | np.integer) or not 1 <= n <= 1000:
            raise ValueError(f"{kn} must be an integer in 1…1000, got {n!r}")
        check_real(kg, self.gamma, low=1.0, high=20.0, unit="-", why=" (JONSWAP γ)")
        check_real(kr, self.ramp_time, low=0.0, high=3600.0, unit="s")
        object.__setattr__(self, "lpp", lpp)
        object.__setattr__(self, "wavelength_ratio_range", lam)
        object.__setattr__(self, "height_ratio_range", hr)
        object.__setattr__(self, "spreading_range", spread)
        object.__setattr__(self, "heading_range_deg", b)
        object.__setattr__(self, "height_range", (hr[0] * lpp, hr[1] * lpp))
        object.__setattr__(self, "period_range", periods)
        object.__setattr__(self, "kind", "irregular")

    @property
    def max_components(self) -> int:
        return int(self.n_components)

    def sample(
        self, rng: np.random.Generator, fixed: dict[str, float] | None = None
    ) -> tuple[Any, dict[str, float]]:
        """One episode's wave field and its parameters (class docstring); ``fixed`` (from
        :meth:`check_options`) replaces drawn ones after the draws."""
        from ship_gym.engine.ship import wave_field_for
        from ship_gym.waves.sea_state import IrregularSea

        lpp = self.lpp
        for _ in range(_MAX_DRAWS):
            ratio = float(rng.uniform(*self.wavelength_ratio_range))
            height_ratio = float(rng.uniform(*self.height_ratio_range))
            period = math.sqrt(_TWO_PI * ratio * lpp / GRAVITY)
            if height_ratio <= irregular_steepness_limit(period) * ratio:
                break
        else:  # pragma: no cover - the constructor guarantees an admissible corner
            height_ratio = irregular_steepness_limit(period) * ratio
        height = height_ratio * lpp
        heading_deg = float(rng.uniform(*self.heading_range_deg))
        lo, hi = self.spreading_range
        spreading = float(math.exp(rng.uniform(math.log(lo), math.log(hi))))
        if fixed:
            height = fixed.get("wave_height_m", height)
            period = fixed.get("wave_period_s", period)
            heading_deg = fixed.get("wave_heading_deg", heading_deg)
        sea = IrregularSea(
            hs=height,
            tp=period,
            gamma=self.gamma,
            spreading_s=spreading,
            n_components=int(self.n_components),
            ramp_time=self.ramp_time,
        )
        wave_field = wave_field_for(sea, math.radians(heading_deg), rng)
        info = {
            "wave_height_m": height,
            "wave_period_s": period,
            "wave_heading_deg": (heading_deg + 180.0) % 360.0 - 180.0,
            "wave_spreading_s": spreading,
        }
        return wave_field, info


def telegraph_of_action(action: NDArray, low: float, high: float) -> NDArray:
    """Telegraph f [× self-propulsion rpm] of the telegraph action a ∈ [−1, 1]: piecewise linear
    through (−1, ``low``), (0, 1), (1, ``high``) — the zero action keeps the service rpm."""
    a = np.clip(action, -1.0, 1.0)
    return np.where(a < 0.0, 1.0 + a * (1.0 - low), 1.0 + a * (high - 1.0))


def action_of_telegraph(telegraph: NDArray, low: float, high: float) -> NDArray:
    """The inverse of :func:`telegraph_of_action` (f clipped to [``low``, ``high``])."""
    f = np.clip(telegraph, low, high)
    return np.where(f < 1.0, (f - 1.0) / (1.0 - low), (f - 1.0) / (high - 1.0))


def voyage_progress(distance_m: NDArray, capsized: NDArray, nominal_m: float) -> NDArray:
    """The task metric of each episode: distance made good along the voyage course as a fraction
    of the nominal voyage ``nominal_m`` [m] (U_ref × the episode's duration); 0 if it capsized."""
    return np.where(np.asarray(capsized, bool), 0.0, np.asarray(distance_m, float) / nominal_m)


class HeavyWeatherTask(ShipEnvTask):
    """N heavy-weather episodes (see :class:`HeavyWeatherEnv` for the arguments)."""

    def __init__(
        self,
        num_envs: int,
        *,
        ship: str = "s175",
        froude_number: float = 0.25,
        froude_range: tuple[float, float] | None = (0.22, 0.28),
        wavelength_ratio_range: tuple[float, float] = (0.6, 2.0),
        height_ratio_range: tuple[float, float] = (0.02, 0.07),
        wave_heading_range_deg: tuple[float, float] = (-180.0, 180.0),
        spreading_range: tuple[float, float] = (2.0, 50.0),
        n_wave_components: int = 40,
        wave_ramp_time_s: float = 60.0,
        gm_range_m: tuple[float, float] | None = (0.3, 1.5),
        kg_m: float | None = None,
        max_course_deviation_deg: float = 135.0,
        shaft_speed_range: tuple[float, float] = (0.3, 1.2),
        shaft_rate_per_s: float = 0.01,
        roll_statistics_time_s: float = 300.0,
        physics_dt_s: float = 0.1,
        control_dt_s: float = 5.0,
        integrator: IntegratorName = "holloway",
        hull_mesh: Sequence[int] = S175_MESH,
        precision: Precision = "float32",
        forward_speed_model: ForwardSpeedModel = "relative_motion",
        num_threads: int = 1,
        capsize_angle_deg: float | None = None,
        dangerous_roll_deg: float = 25.0,
        progress_weight: float = 1.0,
        danger_weight: float = 1.0,
        capsize_penalty: float = 600.0,
        sensor_noise: float = 0.0,
        wave_preview_m: Sequence[float] | Sequence[Sequence[float]] = (),
    ) -> None:
        args = dict(locals())  # the shared arguments, forwarded by name (ship_kwargs)
        check_real("froude_number", froude_number, low=0.05, high=0.5, unit="-")
        lpp = float(ship_particulars(ship).lpp)
        self.max_course_deviation = math.radians(
            check_positive("max_course_deviation_deg", max_course_deviation_deg, "deg", 180.0)
        )
        lo, hi = check_range(
            "shaft_speed_range", shaft_speed_range, low=0.0, high=2.0, unit="× self-propulsion rpm"
        )
        if not lo < 1.0 < hi:
            raise ValueError(
                f"shaft_speed_range must hold the service rpm 1 strictly inside (min < 1 < max), "
                f"got {shaft_speed_range!r}"
            )
        self.shaft_fraction_range = (lo, hi)
        self.shaft_rate = check_positive("shaft_rate_per_s", shaft_rate_per_s, "1/s", 10.0)
        self.statistics_time = check_positive(
            "roll_statistics_time_s", roll_statistics_time_s, "s", 3600.0
        )
        self.progress_weight = check_weight("progress_weight", progress_weight)
        self.danger_weight = check_weight("danger_weight", danger_weight)
        speed_range: tuple[float, float] | None = None
        if froude_range is not None:
            low, high = check_range("froude_range", froude_range, low=0.05, high=0.5, unit="-")
            root = math.sqrt(GRAVITY * lpp)
            speed_range = (low * root, high * root)
        dev = math.degrees(self.max_course_deviation)
        self.action_names = (
            f"course set-point (-1..1 = ±{dev:g} deg from the voyage course)",
            f"telegraph set-point (-1..0..1 = {lo:g}..1..{hi:g} × self-propulsion rpm at Fn "
            f"{froude_number:g})",
        )
        sea = HeavyWeatherSea(
            lpp=lpp,
            wavelength_ratio_range=wavelength_ratio_range,
            height_ratio_range=height_ratio_range,
            heading_range_deg=wave_heading_range_deg,
            spreading_range=spreading_range,
            n_components=n_wave_components,
            ramp_time=wave_ramp_time_s,
        )  # its default keywords are this task's argument names
        super().__init__(
            num_envs,
            rudder="autopilot",
            sea=sea,
            speed_range_mps=speed_range,
            extra_observations=(
                ("heading from voyage course [rad]", -math.pi, math.pi),
                ("heading set-point from voyage course [rad]", -math.pi, math.pi),
                ("telegraph [× self-propulsion rpm]", 0.0, 2.0),
                ("significant wave height [m]", 0.0, 30.0),
                ("wave period [s]", 0.0, 60.0),
                ("wavelength / ship length [-]", 0.0, 20.0),
                ("wave height / ship length [-]", 0.0, 0.5),
                ("wave spreading exponent [-]", 0.0, 1000.0),
                ("roll natural period [s]", 0.0, 100.0),
                ("RMS roll, recent [rad]", 0.0, math.pi),
                ("max roll, recent [rad]", 0.0, math.pi),
                ("RMS pitch, recent [rad]", 0.0, math.pi / 2),
                ("speed made good along the course [m/s]", -30.0, 30.0),
            ),
            **ship_kwargs(args),
        )
        n = self.num_envs
        self.lpp = lpp
        self.voyage_course = 0.0  # [rad], the initial heading (north)
        self.telegraph = np.ones(n)  # [× self-propulsion rpm at froude_number]
        self.nominal_voyage_m = self.setup.speed * self.control_dt * MAX_EPISODE_STEPS
        self._sea_rows = np.zeros((n, 5))  # Hs, Tp, λp/L, Hs/L, s
        self._roll_period = np.zeros(n)
        self._ms_roll = np.zeros(n)  # running mean φ² [rad²]
        self._peak_roll = np.zeros(n)  # decaying peak |φ| [rad]
        self._ms_pitch = np.zeros(n)  # running mean θ² [rad²] (sampled per control step)
        self._speed_made_good = np.zeros(n)  # running mean [m/s]
        self._distance = np.zeros(n)  # along the voyage course [m]
        self._nominal_roll_period = self.nominal_roll_period()

    # ------------------------------------------------------------------ hooks
    def _reset_task(self, i: int, rng: np.random.Generator) -> dict[str, float]:
        self.telegraph[i] = self.commands["shaft_speed"][i] / self._nominal_shaft_speed
        info = self._reset_infos[i]
        hs, tp = info["wave_height_m"], info["wave_period_s"]
        self._sea_rows[i] = (
            hs,
            tp,
            GRAVITY * tp**2 / _TWO_PI / self.lpp,
            hs / self.lpp,
            info["wave_spreading_s"],
        )
        # G moved vertically: C44 ∝ GM, the inertia nearly unchanged (the master's estimate)
        self._roll_period[i] = self._nominal_roll_period * math.sqrt(self.loading.gm / self.gm[i])
        self._ms_roll[i] = 0.0
        self._peak_roll[i] = 0.0
        self._ms_pitch[i] = 0.0
        self._speed_made_good[i] = self.initial_speed[i]
        self._distance[i] = 0.0
        return {"roll_period_s": float(self._roll_period[i])}

    def _apply_actions(self, actions: NDArray) -> None:
        lo, hi = self.shaft_fraction_range
        a = np.clip(actions, -1.0, 1.0)
        setpoint = self.voyage_course + a[:, 0] * self.max_course_deviation
        self.heading_setpoint[:] = setpoint
        self.commands["heading"][:] = setpoint
        self.telegraph[:] = telegraph_of_action(a[:, 1], lo, hi)
        nominal = self._nominal_shaft_speed
        n = self.commands["shaft_speed"]
        max_change = self.shaft_rate * nominal * self.control_dt
        n[:] = np.clip(self.telegraph * nominal, n - max_change, n + max_change)

    def _write_extra_observations(self, out: NDArray) -> None:
        psi = self.sim.eta[:, 5]
        c = self.voyage_course
        out[:, 0] = wrap_angle(psi - c)
        out[:, 1] = wrap_angle(self.heading_setpoint - c)
        out[:, 2] = self.telegraph
        out[:, 3:8] = self._sea_rows
        out[:, 8] = self._roll_period
        out[:, 9] = np.sqrt(self._ms_roll)
        out[:, 10] = self._peak_roll
        out[:, 11] = np.sqrt(self._ms_pitch)
        out[:, 12] = self._speed_made_good

    def _reward_terms(self, stats: StepStatistics) -> dict[str, NDArray]:
        c = self.voyage_course
        eta = self.sim.eta
        step = np.empty(self.num_envs)  # distance made good along the course [m]
        along_course_kernel(eta, stats.position_before, math.cos(c), math.sin(c), 1.0, 1.0, step)
        alive = ~stats.capsized | stats.newly_capsized
        self._distance += np.where(alive, step, 0.0)
        # the bridge's running statistics (time constant roll_statistics_time_s)
        dt = self.control_dt
        alpha = min(1.0, dt / self.statistics_time)
        self._ms_roll += alpha * (stats.mean_square_roll - self._ms_roll)
        self._peak_roll = np.maximum(stats.max_abs_roll, self._peak_roll * (1.0 - alpha))
        self._ms_pitch += alpha * (eta[:, 4] ** 2 - self._ms_pitch)
        self._speed_made_good += alpha * (step / dt - self._speed_made_good)
        scale = self.setup.speed * dt
        return {
            "progress": self.progress_weight * step / scale,
            "dangerous_roll": -self.danger_weight * stats.danger_fraction,
        }

    def _task_info(self, stats: StepStatistics) -> dict[str, NDArray]:
        return {
            "distance_along_voyage_m": self._distance.copy(),
            "voyage_progress": voyage_progress(
                self._distance, stats.capsized, self.nominal_voyage_m
            ),
        }

    def _action_labels(self, i: int) -> dict[str, float]:
        out = super()._action_labels(i)
        out["course set-point [deg]"] = math.degrees(float(self.heading_setpoint[i]))
        out["telegraph [-]"] = float(self.telegraph[i])
        return out


_ARGUMENTS: dict[str, tuple[str, str]] = {
    # this environment's own rows and meanings (the shared ones: SHIP_ARGUMENTS)
    "froude_number": ("-", "service speed: reference of radiation, autopilot, telegraph 1"),
    "froude_range": ("-", "initial Froude number range (None: froude_number)"),
    "wavelength_ratio_range": ("-", "peak wavelength λp/Lpp"),
    "height_ratio_range": ("-", "Hs/Lpp (pairs steeper than DNV-RP-C205's limit redrawn)"),
    "wave_heading_range_deg": ("deg", "relative mean heading β (0 following seas)"),
    "spreading_range": ("-", "cos-2s spreading exponent s (log-uniform)"),
    "n_wave_components": ("-", "components of the irregular sea"),
    "gm_range_m": ("m", "GM range of the loading (per episode; None: nominal)"),
    "max_course_deviation_deg": ("deg", "largest course set-point off the voyage course"),
    "shaft_speed_range": ("-", "telegraph range, × self-propulsion rpm (1 inside)"),
    "shaft_rate_per_s": ("1/s", "shaft acceleration, × self-propulsion rpm per s"),
    "roll_statistics_time_s": ("s", "time constant of the recent motion statistics"),
    "dangerous_roll_deg": ("deg", "roll angle of the cost and the danger term"),
    "progress_weight": ("-", "weight of the progress term"),
    "danger_weight": ("-", "weight of the dangerous-roll term"),
    "capsize_penalty": ("-", "penalty at capsize (> the most progress of an episode)"),
}


@env_docstring(_ARGUMENTS, ("v0: initial version (issue #31).",))
class HeavyWeatherEnv(TaskEnv):
    """Take the ship along her voyage course through heavy weather without capsizing her.

    ## Description

    The master's decision in heavy weather. The ship (the ITTC S175 container ship by default,
    any ship by ``ship=``) is bound north along her voyage course in a short-crested irregular
    sea drawn per episode: JONSWAP (γ 3.3), peak wavelength 0.6–2 L, Hs 0.02–0.07 L below the
    breaking limit, cos-2s spreading 2–50, any mean direction; her loading's GM is drawn from
    0.3–1.5 m (S175 nominal 1.0 m), so some episodes are low-GM conditions prone to parametric
    and synchronous roll. The 6-DOF model (nonlinear Froude–Krylov and hydrostatics on the
    wetted hull, radiation memory, diffraction at speed, Ikeda roll damping, resistance,
    propeller, manoeuvring forces) is steered by a PID heading autopilot acting on a rudder
    behind its servo. The agent sets the course set-point and the telegraph every control step
    (5 s). Keeping course and speed capsizes the ship in some seas and loadings; slowing down or
    altering course avoids the dangerous zones at a cost in progress.

    ## Action Space

    ``Box(-1, 1, (2,), float32)``:

    * ``a[0]`` — course set-point ψ_ref = voyage course + a · ``max_course_deviation_deg``
      (the autopilot turns the ship to it);
    * ``a[1]`` — telegraph f, piecewise linear through (−1, min), (0, 1), (1, max) of
      ``shaft_speed_range`` (× the calm-water self-propulsion rpm at ``froude_number``); the
      shaft follows at ≤ ``shaft_rate_per_s`` of that rpm per second.

    The zero action keeps the voyage course and the service rpm.

    ## Observation Space

    ``Box(float32)``; entries (``env.observation_names``), each clipped to its bound:

    {ship_observations}
    | 14 | heading ψ from the voyage course (wrapped) | rad | ±π |
    | 15 | course set-point from the voyage course (wrapped) | rad | ±π |
    | 16 | telegraph f | × self-propulsion rpm | 0 … 2 |
    | 17 | significant wave height Hs (wave radar) | m | 0 … 30 |
    | 18 | peak period Tp (wave radar) | s | 0 … 60 |
    | 19 | λp/L, λp = g Tp²/2π | - | 0 … 20 |
    | 20 | Hs/L | - | 0 … 0.5 |
    | 21 | spreading exponent s (wave radar) | - | 0 … 1000 |
    | 22 | roll natural period T_R of the loading (T_R,nom √(GM_nom/GM)) | s | 0 … 100 |
    | 23 | recent RMS roll (running mean of φ², ``roll_statistics_time_s``) | rad | 0 … π |
    | 24 | recent max roll (decaying peak of the roll angle) | rad | 0 … π |
    | 25 | recent RMS pitch (running mean of θ² sampled per control step) | rad | 0 … π/2 |
    | 26 | speed made good along the voyage course (running mean) | m/s | ±30 |
    | 27… | incident elevation at the ``wave_preview_m`` points (if any) | m | ±30 |

    ## Rewards

    Σ of the weighted terms (``info["reward_<term>"]``):

    * ``progress`` = progress_weight · Δs / (U_ref Δt_c), Δs the distance made good along the
      voyage course in the control step (1 per step at the service speed on course);
    * ``dangerous_roll`` = −danger_weight × the fraction of the physics steps with |φ| above
      ``dangerous_roll_deg``;
    * ``capsize`` = −capsize_penalty in the step the ship capsizes (600 by default: more than
      the progress of a whole episode at the highest telegraph, so a capsize is never worth
      its progress).

    ``info["cost"]`` is the fraction of the step's physics steps with |φ| above
    ``dangerous_roll_deg``, 1 in the step that capsizes. ``info["voyage_progress"]`` is the
    task metric so far (distance along the voyage / the nominal voyage, 0 once capsized).

    ## Starting State

    Free-floating equilibrium heading north (the voyage course) at a speed uniform in
    ``froude_range`` (shaft at its self-propulsion rpm), autopilot set-point on the course.
    Per episode, from the reset seed: λp/L, Hs/L, β, s, the wave components and the loading's
    GM. The waves ramp up over ``wave_ramp_time_s`` (Matusiak eq. 12).

    ## Episode End

    Terminated on capsize: |φ| above the angle of vanishing stability of the episode's loading
    (``capsize_angle_deg`` overrides) at any physics step, or a diverged integration
    (``info["diverged"]``). Truncated by the time limit: {time_limit}.
    """

    task_class = HeavyWeatherTask


class HeavyWeatherVectorEnv(TaskVectorEnv):
    __doc__ = vector_env_docstring(HeavyWeatherEnv)
    task_class = HeavyWeatherTask
