"""Common machinery of the 6-DOF ship tasks: N episodes of one ship in one BatchSimulator.

A :class:`ShipTask` is a :class:`ship_gym.envs.base.BatchedTask` whose N episodes are N ships of
one :class:`ship_gym.engine.batch.BatchSimulator` (one hull, one force-model setup, each ship
in its own sea). It does what every ship task needs, on arrays over the N episodes (no per-ship
Python loop in :meth:`ShipTask.step`):

* **build once, cheaply** — the simulator of a (setup, N, wave-component count) is built once
  per process and deep-copied for each task instance (:func:`prototype_simulator`), so making
  many environments (tests, vector envs) costs milliseconds after the first;
* **time steps** — ``control_dt`` must be an integer multiple k of the physics ``dt``
  (ValueError otherwise); one control step is k physics steps with the commands held;
* **per-episode sea** (:class:`SeaSampler`) — irregular (JONSWAP, Hs/Tp ranges) or regular
  (height/period ranges, random phase) at a random relative heading β, with Matusiak's start-up
  ramp (eq. 12, :func:`ship_gym.waves.wave_field.ramp_factor`) so episodes start calmly;
* **speed randomisation** — the initial surge speed and the shaft speed (the calm-water
  self-propulsion point of that speed) are per episode. The reference speed U of the radiation
  memory (ν − U), of the diffraction encounter frequency and of the autopilot gains is the build
  speed, shared by the batch: a rebuild per episode would cost ≈ 0.2–0.6 s, so the range should
  stay narrow around it (say ±15 %);
* **loading (GM) randomisation** — per-ship centre of gravity
  (:meth:`BatchSimulator.set_centre_of_gravity`): KG = KM − GM with KM of the upright hull. The
  nonlinear Froude–Krylov/hydrostatic force integrates the pressure over the hull panels, so the
  restoring moment (GZ curve) follows G exactly; the inertia about G, the Ikeda roll damping and
  the controller gains keep the values of the nominal loading;
* **capsize criterion** — |φ| > the angle of vanishing stability of the episode's loading (from
  the calm-water GZ curve at free sinkage and trim, :func:`ship_gym.hull.righting_arm`, shifted
  by ΔKG sin φ for a moved G), or a fixed angle given as a keyword argument; checked at every
  physics step. A ship whose integration diverges (BatchSimulator freezes it) is also
  terminated, as a capsize, with ``info["diverged"]``; stepping it again never raises;
* **Safe-RL cost** — one meaning in every ship environment: ``info["cost"]`` ∈ [0, 1] is the
  fraction of the control step spent violating the task's safety constraints, 1 in the step
  that capsizes; so an episode's summed cost is its time in violation [control steps]. The
  constraint of every ship task is |φ| ≤ the dangerous roll angle (the fraction of the physics
  steps above it); a task may add its own (RideControl: the running RMS vertical acceleration
  at the passenger point below its limit);
* **observations** — one table (:mod:`ship_gym.envs.observations`,
  :attr:`ShipTask.observation_entries`: name, unit, bounds, noise, getter per entry) gives the
  float32 values, the names with units (:attr:`ShipTask.observation_names`), clipped to the
  bounds of the space, optional Gaussian sensor noise (from the episode's generator) and
  optional wave preview (incident elevation at points ahead of O along the heading, or at any
  horizontal points of the body frame, from the wave field);
* **rendering** — :meth:`ShipTask.snapshot` (profile/section elevations from the wave field and a
  ring buffer of roll, pitch, heave and heading).

:class:`~ship_gym.envs.env_task.ShipEnvTask` builds a ShipTask of a ship (the S175 by default)
from the keyword arguments every ship environment shares
(:data:`~ship_gym.envs.docstrings.SHIP_ARGUMENTS`). Its subclasses
(:mod:`ship_gym.envs.course_keeping`, :mod:`ship_gym.envs.capsize_avoidance`,
:mod:`ship_gym.envs.roll_stabilisation`, :mod:`ship_gym.envs.ride_control`) define the actions →
commands mapping, the extra observations and the reward terms; their environment docstrings are
composed with :func:`~ship_gym.envs.docstrings.env_docstring` from the shared pieces written once
(the observation table of the common entries, the keyword table rows, the registered time limit).

Conventions (:mod:`ship_gym.conventions`): η = (x, y, z, φ, θ, ψ) of O in NED (z down), ν =
(u, v, w, p, q, r) in the body frame; the ship starts heading north (ψ = 0) and the waves travel
to χ = β (β = 0 following seas, π head seas).
"""

from __future__ import annotations

import abc
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

import numba
import numpy as np
from gymnasium import spaces
from numpy.typing import NDArray

from ship_gym.conventions import wrap_angle
from ship_gym.envs._kernels import clip_array_bound, clip_scalar_bound
from ship_gym.envs.base import BatchedTask, TaskStep
from ship_gym.envs.config import (
    DANGEROUS_ROLL_LIMITS,
    GM_LIMITS,
    SENSOR_NOISE_LIMITS,
    SPEED_LIMITS,
)
from ship_gym.envs.episodes import EpisodeSampler
from ship_gym.envs.loading import loading_condition
from ship_gym.envs.observations import (
    SENSOR_NOISE_STD as _SENSOR_NOISE_STD,
)
from ship_gym.envs.observations import (
    SHIP_OBSERVATIONS,
    Observation,
    observation_from_tuple,
    preview_observation,
    state_layout,
    write_state_columns,
)
from ship_gym.envs.prototypes import designed_propeller, prototype_simulator
from ship_gym.envs.seas import SeaSampler
from ship_gym.envs.validation import (
    check_options,
    check_range,
    check_real,
    check_weight,
    is_real,
)
from ship_gym.numerics.angles import wrap_angle_scalar

if TYPE_CHECKING:
    from ship_gym.engine.batch import BatchSimulator
    from ship_gym.engine.ship import ShipSetup
    from ship_gym.envs.rendering import RenderSnapshot

_TWO_PI = 2.0 * math.pi

MAX_SUBSTEPS = 1000
"""Most physics steps in one control step (``control_dt_s`` ≤ 1000 ``physics_dt_s``): the
commands are held over a control step, and a longer one is no longer closed-loop control (and
one ``step()`` would run for minutes)."""

# SPEED_LIMITS, GM_LIMITS: the accepted initial speeds [m/s] and GM [m], from ShipConfig


# the observation table (ship_gym.envs.observations): names, units, bounds, noise, getters
SENSOR_NOISE_STD = _SENSOR_NOISE_STD
"""Standard deviation of each sensor at ``sensor_noise=1`` by observation name (typical marine
motion reference unit, gyro compass and log accuracy; from
:data:`~ship_gym.envs.observations.SHIP_OBSERVATIONS`); unlisted entries (commands, actuator
feedback, wave direction, preview) are noise-free except the preview, which takes 0.1 m."""


@dataclass
class StepStatistics:
    """Roll statistics of the physics steps of one control step (arrays over N episodes).

    Attributes
    ----------
    max_abs_roll : NDArray
        Largest |φ| [rad].
    mean_square_roll : NDArray
        Mean of φ² [rad²].
    danger_fraction : NDArray
        Fraction of the physics steps with |φ| above the dangerous roll angle [-].
    capsized : NDArray
        |φ| exceeded the capsize angle, or the ship diverged (bool).
    diverged : NDArray
        The integration diverged (bool).
    newly_capsized : NDArray
        Capsized in this control step (bool; the capsize penalty is paid once).
    position_before : NDArray
        (N, 2) north/east position of O at the start of the control step [m].
    """

    max_abs_roll: NDArray
    mean_square_roll: NDArray
    danger_fraction: NDArray
    capsized: NDArray
    diverged: NDArray
    newly_capsized: NDArray
    position_before: NDArray = field(default_factory=lambda: np.zeros((0, 2)))


# =============================================================================================
# per-step kernels (step bookkeeping, observations, rendering history): the NumPy expressions
# they replace, operation for operation (the same bits, tests/envs/test_step_equivalence.py);
# sines and cosines stay NumPy calls, whose implementation may differ from numba's
# =============================================================================================
_RAD2DEG = 180.0 / math.pi  # np.degrees multiplies by this


@numba.njit(cache=True, nogil=True)
def _step_kernel(
    max_abs, sum_sq, danger, sim_diverged, capsize_angle, capsized, substeps, episode_steps,
    heading_setpoint, eta,
    diverged, newly, capsized_now, mean_square, danger_fraction, heading_error, roll_deg,
    max_roll_deg, capsized_info, terminated, cost,
):  # fmt: skip  # pragma: no cover - compiled
    """The bookkeeping of :meth:`ShipTask.step` after the engine call, episode by episode.

    Updates ``capsized`` (the episodes' flags) and ``episode_steps`` in place; writes the
    :class:`StepStatistics` arrays, wrap(ψ_ref − ψ), the roll angles in degrees and copies of
    the capsize flags and of the danger fraction (the arrays the step returns). The operations
    of the NumPy expressions they replace, so the results are the same to the last bit.
    """
    for i in range(max_abs.shape[0]):
        d = sim_diverged[i]
        c = (max_abs[i] > capsize_angle[i]) or d
        diverged[i] = d
        newly[i] = c and not capsized[i]
        capsized[i] = capsized[i] or c
        capsized_now[i] = capsized[i]
        capsized_info[i] = capsized[i]
        terminated[i] = capsized[i]
        mean_square[i] = sum_sq[i] / substeps
        f = danger[i] / substeps
        danger_fraction[i] = f
        cost[i] = 1.0 if newly[i] else f
        episode_steps[i] += 1
        heading_error[i] = wrap_angle_scalar(heading_setpoint[i] - eta[i, 5])
        roll_deg[i] = eta[i, 3] * _RAD2DEG
        max_roll_deg[i] = max_abs[i] * _RAD2DEG


@numba.njit(cache=True, nogil=True)
def _finish_observations_kernel(
    clean, ids, noisy, noise_rows, draws, noise_std, low, high, out
):  # pragma: no cover - compiled
    """out[ids[r]] = float32(clip(nan_to_num(clean[ids[r]] + noise_std · draws[r]))).

    Bit for bit what ``np.clip(np.nan_to_num(x, nan=0, posinf=0, neginf=0), low, high)
    .astype(np.float32)`` gives (array bounds); the noise is added only to rows with
    ``noise_rows[r]``.
    """
    for r in range(ids.shape[0]):
        i = ids[r]
        add = noisy and noise_rows[r]
        for j in range(clean.shape[1]):
            v = clean[i, j]
            if add:
                v = v + noise_std[j] * draws[r, j]
            if not math.isfinite(v):
                v = 0.0
            out[i, j] = np.float32(clip_array_bound(v, low[j], high[j]))


@numba.njit(cache=True, nogil=True)
def _heading_observations_kernel(psi, setpoint, course, third, out):  # pragma: no cover - compiled
    """out[:, 0] = wrap(ψ − course), out[:, 1] = wrap(ψ_ref − course) (wrap(x) = (x + π) mod 2π
    − π, NumPy's remainder), out[:, 2] = third."""
    for i in range(psi.shape[0]):
        out[i, 0] = wrap_angle_scalar(psi[i] - course)
        out[i, 1] = wrap_angle_scalar(setpoint[i] - course)
        out[i, 2] = third[i]


def write_heading_observations(task: ShipTask, course: float, third: NDArray, out: NDArray) -> None:
    """The task observations ``[wrap(ψ − course), wrap(ψ_ref − course), third]`` into the
    (N, 3) ``out`` (course-keeping and capsize-avoidance observations; ψ − 0.0 is ψ exactly)."""
    _heading_observations_kernel(
        task.sim.eta[:, 5], task.heading_setpoint, float(course), third, out
    )


@numba.njit(cache=True, nogil=True)
def _clip_scalar_kernel(x, low, high, out):  # pragma: no cover - compiled
    for i in range(x.shape[0]):
        out[i] = clip_scalar_bound(x[i], low, high)


@numba.njit(cache=True, nogil=True)
def _clip_array_kernel(x, low, high, out):  # pragma: no cover - compiled
    for i in range(x.shape[0]):
        out[i] = clip_array_bound(x[i], low[i], high[i])


def clip_into(values: NDArray, low: float | NDArray, high: float | NDArray, out: NDArray) -> None:
    """``np.clip(values, low, high, out=out)`` for (N,) float64 arrays, bit for bit, without
    NumPy's per-call overhead; ``low`` and ``high`` both floats or both (N,) arrays."""
    if isinstance(low, float | int) and isinstance(high, float | int):
        _clip_scalar_kernel(values, float(low), float(high), out)
    else:
        _clip_array_kernel(values, low, high, out)


@numba.njit(cache=True, nogil=True)
def _history_kernel(ids, steps, t, eta, z_eq, hist_t, hist):  # pragma: no cover - compiled
    """One sample (t, φ, θ, heave, ψ) of episodes ``ids`` into the ring buffers, at column
    ``steps % h``."""
    h = hist_t.shape[1]
    for i in ids:
        col = steps[i] % h
        hist_t[i, col] = t[i]
        hist[i, 0, col] = eta[i, 3]
        hist[i, 1, col] = eta[i, 4]
        hist[i, 2, col] = eta[i, 2] - z_eq
        hist[i, 3, col] = eta[i, 5]


# =============================================================================================
# the common task
# =============================================================================================
class ShipTask(BatchedTask, abc.ABC):
    """N episodes of the S175 in waves, stepped together (module docstring).

    Subclasses call ``super().__init__`` with the setup and options below, then implement
    :meth:`_apply_actions`, :meth:`_reward_terms`, and optionally :meth:`_extra_observations`
    or :meth:`_write_extra_observations` (with :attr:`extra_observations`), :meth:`_reset_task`,
    :meth:`_task_info`, :meth:`_action_labels`. The step computes the heading error once, after
    the engine call; the hooks read it with :meth:`_current_heading_error`.

    Parameters
    ----------
    num_envs : int
        Number of episodes N.
    setup : ShipSetup
        Hull, models, integrator and physics dt (``setup.speed`` is the reference speed).
    sea : SeaSampler
        Per-episode sea.
    control_dt : float
        Control step [s], an integer multiple of ``setup.dt``.
    speed_range : tuple of float or None
        Initial speed range [m/s] (None: ``setup.speed``).
    gm_range : tuple of float or None
        GM range [m] of the episodes' loading (None: the nominal loading).
    capsize_angle_deg : float or None
        Fixed capsize roll angle [deg] (None: the vanishing angle of each episode's loading).
    dangerous_roll_deg : float
        Roll angle above which the cost accrues [deg].
    sensor_noise : float
        Multiplier of :data:`SENSOR_NOISE_STD` [-] (0: exact observations).
    wave_preview_m : sequence of float, or of (x, y) pairs
        Where the incident elevation is observed [m]: distances ahead of O along the heading,
        or (x forward, y to starboard) points of the horizontal body frame, which can look
        abeam and up-wave in beam seas (empty: no preview).
    history_length : int
        Samples of the rendering history (one per control step).
    extra_observations : sequence of Observation or of (name, low, high)
        The subclass's observation entries (appended after the common ones of
        :data:`~ship_gym.envs.observations.SHIP_OBSERVATIONS`): an
        :class:`~ship_gym.envs.observations.Observation` with a getter (a function of the task
        returning the (N,) values), or without one, or a ``("name [unit]", low, high)`` tuple,
        written by :meth:`_write_extra_observations`.
    capsize_penalty : float
        Reward ``capsize`` = −capsize_penalty in the control step the ship capsizes [-], the last
        of the reward terms (after the subclass's :meth:`_reward_terms`).
    """

    setup: ShipSetup
    sim: BatchSimulator
    num_threads: int = 1
    """numba threads over the ships in the compiled loop (set by :class:`ShipEnvTask`)."""
    observations_bounded = True  # observations() is a float32 copy, clipped to the bounds
    task_observations: ClassVar[tuple[Observation, ...]] = ()
    """The task's own observation entries, after the common ones (a subclass passes them as
    ``extra_observations``; :func:`~ship_gym.envs.docstrings.env_docstring` writes their rows
    of the environment's observation table from them)."""

    def __init__(
        self,
        num_envs: int,
        *,
        setup: ShipSetup,
        sea: SeaSampler,
        control_dt: float,
        speed_range: tuple[float, float] | None = None,
        gm_range: tuple[float, float] | None = None,
        capsize_angle_deg: float | None = None,
        dangerous_roll_deg: float = 30.0,
        sensor_noise: float = 0.0,
        wave_preview_m: Sequence[float] | Sequence[Sequence[float]] = (),
        history_length: int = 240,
        extra_observations: Sequence[tuple[str, float, float] | Observation] = (),
        capsize_penalty: float = 0.0,
    ) -> None:
        super().__init__(num_envs)
        n = self.num_envs
        self.setup = setup
        self.sea = sea
        self.capsize_penalty = check_weight("capsize_penalty", capsize_penalty)
        # --- time steps
        dt = float(setup.dt)
        if not (is_real(control_dt) and math.isfinite(control_dt) and control_dt > 0.0):
            raise ValueError(
                f"control_dt_s must be a positive finite time step [s] (an integer multiple of "
                f"physics_dt_s = {dt!r} s), got {control_dt!r}"
            )
        control_dt = float(control_dt)
        if control_dt > MAX_SUBSTEPS * dt:
            raise ValueError(
                f"control_dt_s = {control_dt!r} s is more than {MAX_SUBSTEPS} physics steps of "
                f"physics_dt_s = {dt!r} s: at most {MAX_SUBSTEPS * dt:g} s per control step (one "
                f"step would run {control_dt / dt:.3g} physics steps with the commands held)"
            )
        k = round(control_dt / dt)
        if k < 1 or abs(k * dt - control_dt) > 1e-9 * max(1.0, control_dt):
            raise ValueError(
                f"control_dt_s = {control_dt!r} s must be a positive integer multiple of "
                f"physics_dt_s = {dt!r} s"
            )
        self.substeps = int(k)
        self.control_dt = float(k * dt)
        # --- options
        lc = loading_condition(setup)
        self.loading = lc
        if speed_range is not None and not setup.propulsion:
            low, high = SPEED_LIMITS
            check_range("speed_range_mps", speed_range, low=low, high=high, unit="m/s")
            raise ValueError("speed_range_mps needs a setup with propulsion (a shaft speed)")
        self.episodes = EpisodeSampler(
            sea,
            lc,
            float(setup.speed),
            speed_range=speed_range,
            gm_range=gm_range,
            capsize_angle_deg=capsize_angle_deg,
        )
        """The episode sampler: sea, speed, loading (GM) and capsize angle of each episode."""
        self.speed_range = self.episodes.speed_range
        self.gm_range = self.episodes.gm_range
        self.capsize_angle_deg = self.episodes.capsize_angle_deg
        dangerous_roll_deg = check_real(
            "dangerous_roll_deg",
            dangerous_roll_deg,
            low=DANGEROUS_ROLL_LIMITS[0],
            high=DANGEROUS_ROLL_LIMITS[1],
            unit="deg",
            low_open=True,
            high_open=True,
        )
        self.dangerous_roll = math.radians(dangerous_roll_deg)
        low, high = SENSOR_NOISE_LIMITS
        self.sensor_noise = check_real("sensor_noise", sensor_noise, low=low, high=high, unit="-")
        try:
            if isinstance(wave_preview_m, str | bytes):
                raise TypeError
            preview = np.asarray(wave_preview_m, dtype=float)
            if preview.ndim > 2 or (preview.ndim == 2 and preview.shape[1] != 2):
                raise ValueError
        except (TypeError, ValueError):
            raise ValueError(
                "wave_preview_m must be a sequence of distances ahead [m] or of (x, y) "
                f"body-frame points [m], got {wave_preview_m!r}"
            ) from None
        if not np.all(np.isfinite(preview)) or np.any(np.abs(preview) > 5000.0):
            raise ValueError(
                f"wave_preview_m must be finite distances within ±5 km, got {preview.tolist()}"
            )
        self.wave_preview_m = preview
        ahead = preview.ndim < 2
        # (k, 2) body-frame points of the preview: (d, 0) for a distance d ahead
        self._preview_xy = (
            np.column_stack([preview.reshape(-1), np.zeros(preview.size)]) if ahead else preview
        )
        if (
            isinstance(history_length, bool)
            or not isinstance(history_length, int | np.integer)
            or (history_length < 2)
        ):
            raise ValueError(f"history_length must be an integer >= 2, got {history_length!r}")
        # --- simulator (cached build, deep copy)
        self.sim = prototype_simulator(setup, n, sea.max_components)
        self._z_eq = float(self.sim.initial_eta[2])
        self._propeller = self._find_propeller()
        self._nominal_shaft_speed = (
            float(self._propeller.shaft_speed_for(setup.speed)) if self._propeller else 0.0
        )
        self._rudder = self._actuator("rudder")
        # every servo-driven surface (rudder, fins, T-foil): its travel over the control step
        # as a fraction of the most its servo can travel in one (computed once per step)
        self._servo_names = self.sim.actuator_names()
        self._servos = tuple(self.sim.actuator_model(name) for name in self._servo_names)
        self._servo_angles_before = np.zeros((n, len(self._servos)))
        rates = [servo.servo.max_rate for servo in self._servos]
        self._servo_max_travel = np.array(rates) * self.control_dt
        self._servo_travel = np.zeros((n, len(self._servos)))
        self.commands: dict[str, NDArray] = {}
        if setup.propulsion:
            self.commands["shaft_speed"] = np.full(n, self._nominal_shaft_speed)
        if setup.rudder == "command":
            self.commands["rudder_command"] = np.zeros(n)
        if setup.rudder == "autopilot":
            self.commands["heading"] = np.zeros(n)
        # --- observation layout: the table's common entries, the task's, the preview
        present = {"": True, "rudder": self._rudder is not None, "propulsion": setup.propulsion}
        common = [e for e in SHIP_OBSERVATIONS if present[e.requires]]
        extra = [observation_from_tuple(e) for e in extra_observations]
        preview_entries = [preview_observation(x, y, ahead) for x, y in self._preview_xy]
        entries = (*common, *extra, *preview_entries)
        self.observation_entries: tuple[Observation, ...] = entries
        """The observation table of the task: one :class:`Observation` per entry, in order."""
        self.observation_names = tuple(e.label for e in entries)
        names = self.observation_names
        self._n_base = len(common)
        self._n_extra = len(extra)
        self._state_layout = state_layout(common)
        self._extra_getters = tuple(
            (j, e.getter) for j, e in enumerate(extra) if callable(e.getter)
        )
        self._signals = np.zeros((n, 5))  # ship_gym.envs.observations.SIGNALS
        self._obs_low = np.asarray([e.low for e in entries], dtype=np.float32)
        self._obs_high = np.asarray([e.high for e in entries], dtype=np.float32)
        self.observation_space = spaces.Box(self._obs_low, self._obs_high, dtype=np.float32)
        self._noise_std = self.sensor_noise * np.asarray([e.noise_std for e in entries])
        # --- per-episode state
        self.heading_setpoint = np.zeros(n)  # ψ_ref [rad]
        self.wave_direction = np.zeros(n)  # mean χ of the episode's sea [rad]
        self.capsize_angle = np.full(n, self.episodes.nominal_capsize_angle)
        self.initial_speed = np.full(n, float(setup.speed))
        self.initial_roll = np.zeros(n)
        """Roll angle [rad] and rate [rad/s] each ship started its episode with."""
        self.initial_roll_rate = np.zeros(n)
        self.gm = np.full(n, lc.gm)
        self.episode_steps = np.zeros(n, dtype=np.int64)
        self.capsized = np.zeros(n, dtype=bool)
        self._cog_moved = np.zeros(n, dtype=bool)  # G moved by a gm_m reset option
        self._task_options: dict[str, Any] = {}
        self._rngs: list[np.random.Generator | None] = [None] * n
        self._reset_infos: list[dict[str, float]] = [{} for _ in range(n)]
        self._obs = np.zeros((n, len(names)), dtype=np.float32)
        # per-step work buffers: the clean (float64) observations, the bounds as float64 (what
        # np.clip of float64 observations compares with), the noise draws
        self._obs_clean = np.zeros((n, len(names)))
        j = self._n_base + self._n_extra
        self._obs_extra = self._obs_clean[:, self._n_base : j]  # views of the buffer
        self._obs_preview = self._obs_clean[:, j:]
        self._obs_low64 = self._obs_low.astype(np.float64)
        self._obs_high64 = self._obs_high.astype(np.float64)
        self._noise_draws = np.zeros((n, len(names)))
        self._noise_rows = np.zeros(n, dtype=bool)
        self._all_ids = np.arange(n, dtype=np.int64)
        self._custom_extra = type(self)._extra_observations is not ShipTask._extra_observations
        self._step_heading_error: NDArray | None = None
        self._last_stats: StepStatistics | None = None
        h = int(history_length)
        self._hist_t = np.full((n, h), np.nan)
        self._hist = np.full((n, 4, h), np.nan)  # roll, pitch, heave, heading
        self.action_space = spaces.Box(-1.0, 1.0, (len(self.action_names),), dtype=np.float32)

    # ------------------------------------------------------------------ simulator helpers
    def _find_propeller(self) -> Any:
        """The setup's propeller (same design as the simulator's; cached per hull)."""
        if not self.setup.propulsion:
            return None
        return designed_propeller(self.setup.hull, tuple(sorted(self.setup.hull_overrides.items())))

    def _actuator(self, name: str) -> Any:
        """The servo-driven force model ``name`` of the simulator, or None."""
        try:
            return self.sim.actuator_model(name)
        except ValueError:
            return None

    def servo_travel(self, name: str) -> NDArray:
        """(N,) travel of the servo-driven force model ``name`` (``"rudder"``, ``"roll_fins"``,
        ``"t_foil"``…) over the last control step, as a fraction of the most its servo can
        travel in one, Δδ/(δ̇_max Δt) [-] in [−1, 1]; 0 after a reset. A read-only view."""
        try:
            j = self._servo_names.index(name)
        except ValueError:
            raise ValueError(
                f"no servo-driven force model {name!r}; the setup's are {list(self._servo_names)}"
            ) from None
        view = self._servo_travel[:, j]
        view.flags.writeable = False
        return view

    def rudder_angle(self) -> NDArray:
        """(N,) servo rudder angle δ [rad] (zeros without a rudder)."""
        if self._rudder is None:
            return np.zeros(self.num_envs)
        return self._rudder.angle.copy()

    def shaft_speed_for(self, speed: NDArray) -> NDArray:
        """Calm-water self-propulsion shaft speed [rev/s] at speeds [m/s] (propeller model)."""
        return np.array([self._propeller.shaft_speed_for(float(u)) for u in np.atleast_1d(speed)])

    # ------------------------------------------------------------------ subclass hooks
    @abc.abstractmethod
    def _apply_actions(self, actions: NDArray) -> None:
        """Turn (N, n_act) actions in [-1, 1] into :attr:`commands` (arrays over N)."""

    @abc.abstractmethod
    def _reward_terms(self, stats: StepStatistics) -> dict[str, NDArray]:
        """Weighted reward terms (N,) of the control step just taken (without ``capsize``,
        which :meth:`step` appends)."""

    def _extra_observations(self) -> NDArray:
        """(N, n_extra) task observations (in the order of ``extra_observations``).

        A subclass overrides this or, cheaper, :meth:`_write_extra_observations`."""
        out = np.zeros((self.num_envs, self._n_extra))
        self._write_extra_observations(out)
        return out

    def _write_extra_observations(self, out: NDArray) -> None:
        """Write the (N, n_extra) task observations into ``out`` (float64, in the order of
        ``extra_observations``; a view of the observation buffer, so no array is built)."""

    def _reset_task(self, i: int, rng: np.random.Generator) -> dict[str, float]:
        """Draw the task's own initial conditions of episode ``i`` (after the sea, speed and
        loading); return its reset info."""
        return {}

    def _task_info(self, stats: StepStatistics) -> dict[str, NDArray]:
        """Extra per-episode step info (N,)."""
        return {}

    def _action_labels(self, i: int) -> dict[str, float]:
        """Current physical commands of episode ``i`` for rendering (label with unit → value)."""
        out: dict[str, float] = {}
        if self._rudder is not None:
            out["rudder [deg]"] = math.degrees(float(self._rudder.angle[i]))
        if "shaft_speed" in self.commands:
            out["shaft [rpm]"] = 60.0 * float(self.commands["shaft_speed"][i])
        return out

    # ------------------------------------------------------------------ reset
    def reset_episodes(
        self,
        ids: NDArray[np.int64],
        rngs: Sequence[np.random.Generator],
        options: Mapping[str, Any] | None,
    ) -> None:
        ids = np.asarray(ids, dtype=np.int64).reshape(-1)
        if len(rngs) != ids.size:
            raise ValueError(f"need one generator per episode id: {len(rngs)} for {ids.size}")
        if ids.size == 0:
            return
        opts = self._check_reset_options(options)
        drawn = self.episodes.draw(rngs, opts)
        fields, infos, speeds = drawn.wave_fields, drawn.infos, drawn.speed
        gms, delta_kg, capsize_angles = drawn.gm, drawn.delta_kg, drawn.capsize_angle
        if "roll_deg" in opts and np.any(abs(math.radians(opts["roll_deg"])) >= capsize_angles):
            raise ValueError(
                f"options['roll_deg'] = {opts['roll_deg']!r} deg must be inside the capsize angle "
                f"of the episode's loading, |roll| < {math.degrees(capsize_angles.min()):.2f} deg"
            )
        for k, ship in enumerate(ids.tolist()):
            self.wave_direction[ship] = math.radians(infos[k]["wave_heading_deg"])
            self._rngs[ship] = rngs[k]
            self._reset_infos[ship] = infos[k]
        if self.gm_range is not None or "gm_m" in opts or self._cog_moved[ids].any():
            cog = np.tile(np.asarray(self.sim.hull.mass.cog, float), (ids.size, 1))
            cog[:, 2] -= delta_kg
            self.sim.set_centre_of_gravity(ids, cog)
            self._cog_moved[ids] = self.gm_range is not None or "gm_m" in opts
        self.gm[ids] = gms
        self.capsize_angle[ids] = capsize_angles
        # speed and shaft speed
        self.initial_speed[ids] = speeds
        nu = np.zeros((ids.size, 6))
        nu[:, 0] = speeds
        eta = None
        if "roll_deg" in opts:
            eta = np.tile(self.sim.initial_eta, (ids.size, 1))
            eta[:, 3] = math.radians(opts["roll_deg"])
        if "roll_rate_dps" in opts:
            nu[:, 3] = math.radians(opts["roll_rate_dps"])
        if "shaft_speed" in self.commands:
            if self.speed_range is None and "initial_speed_mps" not in opts:
                self.commands["shaft_speed"][ids] = self._nominal_shaft_speed
            else:
                self.commands["shaft_speed"][ids] = self.shaft_speed_for(speeds)
        if "rudder_command" in self.commands:
            self.commands["rudder_command"][ids] = 0.0
        self.heading_setpoint[ids] = 0.0
        self._servo_travel[ids] = 0.0
        self._task_options = opts
        for i, rng in zip(ids, rngs, strict=True):
            self._reset_infos[int(i)].update(self._reset_task(int(i), rng))
        if "heading" in self.commands:
            self.commands["heading"][ids] = self.heading_setpoint[ids]
        self.sim.commands = {**self.sim.commands, **self.commands}
        self.sim.reset(ids, eta=eta, nu=nu, wave_fields=fields)
        self.initial_roll[ids] = self.sim.eta[ids, 3]
        self.initial_roll_rate[ids] = self.sim.nu[ids, 3]
        self.episode_steps[ids] = 0
        self.capsized[ids] = False
        self._hist_t[ids] = np.nan
        self._hist[ids] = np.nan
        self._step_heading_error = None
        self._record_history(ids)
        self._clean_observations()
        self._finish_observations(ids)

    RESET_OPTIONS: tuple[str, ...] = (
        "wave_height_m",
        "wave_period_s",
        "wave_heading_deg",
        "initial_speed_mps",
        "gm_m",
        "roll_deg",
        "roll_rate_dps",
    )
    """The keys of ``reset(options=...)`` every ship task accepts (:data:`RESET_OPTIONS_DOC`);
    a subclass adds its own in :attr:`task_reset_options`."""

    task_reset_options: tuple[str, ...] = ()
    """The subclass's own reset options (validated by :meth:`_check_task_option`, read by its
    :meth:`_reset_task` from ``self._task_options``)."""

    def _check_reset_options(self, options: Mapping[str, Any] | None) -> dict[str, Any]:
        """``reset(options=...)`` validated with the constructor's limits (module docstring
        :data:`RESET_OPTIONS_DOC`): unknown keys, non-numbers and out-of-range values raise."""
        accepted = self.RESET_OPTIONS + self.task_reset_options
        opts = check_options(options, accepted)
        out: dict[str, Any] = {}
        for key, value in opts.items():
            name = f"options[{key!r}]"
            if key in ("wave_height_m", "wave_period_s", "wave_heading_deg"):
                out[key] = value  # SeaSampler.check_options
            elif key == "initial_speed_mps":
                if "shaft_speed" not in self.commands:
                    raise ValueError(f"{name} needs a ship with propulsion (a shaft speed)")
                out[key] = check_real(
                    name, value, low=SPEED_LIMITS[0], high=SPEED_LIMITS[1], unit="m/s"
                )
            elif key == "gm_m":
                out[key] = check_real(name, value, low=GM_LIMITS[0], high=GM_LIMITS[1], unit="m")
            elif key == "roll_deg":
                out[key] = check_real(
                    name, value, low=-90.0, high=90.0, unit="deg", low_open=True, high_open=True
                )
            elif key == "roll_rate_dps":
                out[key] = check_real(name, value, low=-30.0, high=30.0, unit="deg/s")
            else:
                out[key] = self._check_task_option(key, value)
        return out

    def _check_task_option(self, key: str, value: Any) -> Any:
        """A subclass's own reset option ``key`` validated (ValueError naming it)."""
        raise ValueError(f"unknown reset option {key!r}")  # pragma: no cover - no such key

    def reset_info(self, ids: NDArray[np.int64]) -> Mapping[str, NDArray]:
        ids = np.asarray(ids, dtype=np.int64).reshape(-1)
        out: dict[str, NDArray] = {}
        keys = self._reset_infos[int(ids[0])].keys() if ids.size else ()
        for key in keys:
            out[key] = np.array([self._reset_infos[int(i)][key] for i in ids], dtype=float)
        out["initial_speed_mps"] = self.initial_speed[ids].copy()
        out["roll_deg"] = np.degrees(self.initial_roll[ids])
        out["roll_rate_dps"] = np.degrees(self.initial_roll_rate[ids])
        out["gm_m"] = self.gm[ids].copy()
        out["capsize_angle_deg"] = np.degrees(self.capsize_angle[ids])
        return out

    # ------------------------------------------------------------------ step
    def step(self, actions: NDArray) -> TaskStep:
        sim = self.sim
        n = self.num_envs
        a = np.asarray(actions, dtype=np.float64).reshape(n, -1)
        self._step_heading_error = None
        before = self._servo_angles_before
        for j, servo in enumerate(self._servos):
            before[:, j] = servo.angle
        self._apply_actions(a)
        position_before = sim.eta[:, :2].copy()
        # the control step's physics substeps in one engine call (compiled when possible)
        if self.num_threads > 1:
            numba.set_num_threads(min(self.num_threads, numba.config.NUMBA_NUM_THREADS))  # type: ignore[attr-defined]  # numba.config sets it through globals()
        red = sim.advance(self.substeps, self.commands, danger_roll=self.dangerous_roll)
        max_abs = red.max_abs_roll
        for j, servo in enumerate(self._servos):
            self._servo_travel[:, j] = (servo.angle - before[:, j]) / self._servo_max_travel[j]
        # capsize flags, roll statistics, wrap(ψ_ref − ψ) (once per step: the observation, the
        # reward terms and the info use it) and the returned copies, in one compiled pass
        empty, flag = np.empty, np.bool_
        diverged, newly, capsized = empty(n, flag), empty(n, flag), empty(n, flag)
        capsized_info, terminated = empty(n, flag), empty(n, flag)
        mean_square, danger_fraction, cost = empty(n), empty(n), empty(n)
        heading_error, roll_deg, max_roll_deg = empty(n), empty(n), empty(n)
        _step_kernel(
            max_abs, red.sum_sq_roll, red.danger_steps, sim.diverged, self.capsize_angle,
            self.capsized, self.substeps, self.episode_steps, self.heading_setpoint, sim.eta,
            diverged, newly, capsized, mean_square, danger_fraction, heading_error, roll_deg,
            max_roll_deg, capsized_info, terminated, cost,
        )  # fmt: skip
        stats = StepStatistics(
            max_abs_roll=max_abs,
            mean_square_roll=mean_square,
            danger_fraction=danger_fraction,
            capsized=capsized,
            diverged=diverged,
            newly_capsized=newly,
            position_before=position_before,
        )
        self._last_stats = stats
        self._step_heading_error = heading_error
        terms = self._reward_terms(stats)
        terms["capsize"] = -self.capsize_penalty * newly
        self._record_history(self._all_ids)
        self._clean_observations(heading_error)
        self._finish_observations(self._all_ids)
        info = {
            "capsized": capsized_info,
            "diverged": diverged,
            "roll_deg": roll_deg,
            "max_roll_deg": max_roll_deg,
            **self._task_info(stats),
        }
        return TaskStep(reward_terms=terms, cost=cost, terminated=terminated, info=info)

    # ------------------------------------------------------------------ observations
    def heading_error(self) -> NDArray:
        """(N,) wrap(ψ_ref − ψ) [rad] in [−π, π)."""
        return wrap_angle(self.heading_setpoint - self.sim.eta[:, 5])

    def _current_heading_error(self) -> NDArray:
        """:meth:`heading_error` after the engine call of the step being taken (computed once
        per step; a fresh computation outside a step)."""
        he = self._step_heading_error
        return self.heading_error() if he is None else he

    def _preview(self) -> NDArray:
        eta = self.sim.eta
        px, py = self._preview_xy[None, :, 0], self._preview_xy[None, :, 1]
        cos, sin = np.cos(eta[:, 5:6]), np.sin(eta[:, 5:6])
        x = eta[:, 0:1] + (px * cos - py * sin)
        y = eta[:, 1:2] + (px * sin + py * cos)
        return self.sim.elevation(x, y)

    def _clean_observations(self, heading_error: NDArray | None = None) -> NDArray:
        """Fill and return the (N, n_obs) float64 buffer of the noise-free observations."""
        sim = self.sim
        eta = sim.eta
        out = self._obs_clean
        beta = self.wave_direction - eta[:, 5]
        if heading_error is None:
            heading_error = self.heading_error()
        signals = self._signals
        signals[:, 0] = heading_error
        signals[:, 1] = np.cos(beta)
        signals[:, 2] = np.sin(beta)
        if self._rudder is not None:
            signals[:, 3] = self._rudder.angle
        if "shaft_speed" in self.commands:
            signals[:, 4] = self.commands["shaft_speed"]
        write_state_columns(eta, sim.nu, signals, self._z_eq, *self._state_layout, out)
        if self._custom_extra:
            self._obs_extra[:] = self._extra_observations()
        elif self._n_extra:
            self._write_extra_observations(self._obs_extra)
            for j, getter in self._extra_getters:
                self._obs_extra[:, j] = getter(self)
        if len(self._preview_xy):
            self._obs_preview[:] = self._preview()
        return out

    def _finish_observations(self, ids: NDArray[np.int64]) -> None:
        """Rows ``ids`` of :attr:`_obs`: the clean observations plus the episodes' sensor noise,
        non-finite entries zeroed, clipped to the bounds, as float32."""
        rows = self._noise_rows
        if self.sensor_noise > 0.0:
            draws = self._noise_draws
            width = draws.shape[1]
            for r, i in enumerate(ids.tolist()):
                rng = self._rngs[i]
                rows[r] = rng is not None
                if rng is not None:
                    draws[r] = rng.standard_normal(width)
        _finish_observations_kernel(
            self._obs_clean,
            ids,
            self.sensor_noise > 0.0,
            rows,
            self._noise_draws,
            self._noise_std,
            self._obs_low64,
            self._obs_high64,
            self._obs,
        )

    def observations(self) -> NDArray:
        return self._obs.copy()

    # ------------------------------------------------------------------ rendering
    def _record_history(self, ids: NDArray[np.int64]) -> None:
        _history_kernel(
            np.asarray(ids, dtype=np.int64),
            self.episode_steps,
            self.sim.t,
            self.sim.eta,
            self._z_eq,
            self._hist_t,
            self._hist,
        )

    def snapshot(self, i: int) -> RenderSnapshot:
        from ship_gym.envs.rendering import RenderSnapshot

        sim = self.sim
        hull = sim.hull.particulars
        eta = sim.eta[i].copy()
        profile_x = np.linspace(-0.6 * hull.lpp, 0.6 * hull.lpp, 61)
        section_y = np.linspace(-1.5 * hull.beam, 1.5 * hull.beam, 31)
        c, s = math.cos(eta[5]), math.sin(eta[5])
        px = np.concatenate([profile_x, np.zeros_like(section_y)])
        py = np.concatenate([np.zeros_like(profile_x), section_y])
        xs = eta[0] + c * px - s * py
        ys = eta[1] + s * px + c * py
        x_all = np.tile(xs, (self.num_envs, 1))
        y_all = np.tile(ys, (self.num_envs, 1))
        elevation = sim.elevation(x_all, y_all)[i]
        order = np.argsort(self._hist_t[i])
        order = order[np.isfinite(self._hist_t[i, order])]
        hist = self._hist[i][:, order]
        info = self._reset_infos[i]
        title = (
            f"{type(self).__name__}  H={info.get('wave_height_m', 0.0):.1f} m "
            f"T={info.get('wave_period_s', 0.0):.1f} s β={info.get('wave_heading_deg', 0.0):.0f}°"
        )
        return RenderSnapshot(
            time=float(sim.t[i]),
            eta=eta,
            length=float(hull.lpp),
            beam=float(hull.beam),
            draught=float(hull.draught),
            depth=float(hull.depth),
            profile_x=profile_x,
            profile_elevation=elevation[: profile_x.size],
            section_y=section_y,
            section_elevation=elevation[profile_x.size :],
            history_time=self._hist_t[i, order],
            history={
                "roll [deg]": np.degrees(hist[0]),
                "pitch [deg]": np.degrees(hist[1]),
                "heave [m]": hist[2],
                "heading [deg]": np.degrees(hist[3]),
            },
            actions=self._action_labels(i),
            title=title,
            roll_limit=float(self.capsize_angle[i]),
        )
