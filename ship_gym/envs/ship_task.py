"""Common machinery of the 6-DOF ship tasks: N episodes of the S175 in one BatchSimulator.

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
* **Safe-RL cost** — the fraction of the physics steps of a control step with |φ| above the
  dangerous roll angle (0 … 1);
* **observations** — float32, names with units (:attr:`ShipTask.observation_names`), clipped to
  the documented bounds of the space, optional Gaussian sensor noise (from the episode's
  generator) and optional wave preview (incident elevation at points ahead of O along the
  heading, from the wave field);
* **rendering** — :meth:`ShipTask.snapshot` (profile/section elevations from the wave field and a
  ring buffer of roll, pitch, heave and heading).

:class:`S175Task` builds a ShipTask of the S175 from the keyword arguments every ship
environment shares (:data:`SHIP_ARGUMENTS`). Its subclasses
(:mod:`ship_gym.envs.course_keeping`, :mod:`ship_gym.envs.capsize_avoidance`,
:mod:`ship_gym.envs.roll_stabilization`, :mod:`ship_gym.envs.ride_control`) define the actions →
commands mapping, the extra observations and the reward terms; their environment docstrings are
composed with :func:`env_docstring` from the shared pieces written once here (the observation
table of the common entries, the keyword table rows, the registered time limit).

Conventions (:mod:`ship_gym.conventions`): η = (x, y, z, φ, θ, ψ) of O in NED (z down), ν =
(u, v, w, p, q, r) in the body frame; the ship starts heading north (ψ = 0) and the waves travel
to χ = β (β = 0 following seas, π head seas).
"""

from __future__ import annotations

import abc
import copy
import dataclasses
import inspect
import math
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING, Any, Literal, TypeVar

import numba
import numpy as np
from gymnasium import spaces
from numpy.typing import NDArray

from ship_gym.conventions import GRAVITY
from ship_gym.envs._kernels import clip_array_bound, clip_scalar_bound
from ship_gym.envs.base import BatchedTask, TaskStep
from ship_gym.envs.registration import max_episode_steps
from ship_gym.typing import IntegratorName, Precision

if TYPE_CHECKING:
    from ship_gym.engine.batch import BatchSimulator
    from ship_gym.engine.ship import ShipSetup
    from ship_gym.envs.rendering import RenderSnapshot
    from ship_gym.waves.wave_field import WaveField

__all__ = [
    "RUDDER_LIMIT_DEG",
    "S175_MESH",
    "S175_MESH_FAST",
    "S175_MESH_FINE",
    "SENSOR_NOISE_STD",
    "SHIP_ARGUMENTS",
    "SHIP_KWARGS",
    "SHIP_OBSERVATION_TABLE",
    "LoadingCondition",
    "S175Task",
    "SeaSampler",
    "ShipTask",
    "StepStatistics",
    "check_point",
    "check_positive",
    "check_range",
    "check_weight",
    "clip_into",
    "env_docstring",
    "irregular_sea",
    "loading_condition",
    "prototype_simulator",
    "s175_setup",
    "ship_kwargs",
    "vector_env_docstring",
    "write_heading_observations",
]

S175_MESH: tuple[int, int, int, int] = (60, 12, 6, 4)
"""Default S175 mesh resolution (n_sections, n_below, n_above, n_deck): 2400 panels, the
library hull's. Against a 9600-panel mesh (``docs/accuracy/results.md``): GZ within 2.4 mm, roll
period −0.28 %, RMS roll +2.8 % in a stern-quartering sea near roll resonance."""

S175_MESH_FAST: tuple[int, int, int, int] = (50, 10, 4, 2)
"""The fastest mesh the accuracy study admits: 1500 panels, ≈ 1.6× faster than
:data:`S175_MESH`; GZ within 4.2 mm and roll period −0.43 %, but RMS roll +4.5 % near roll
resonance (``docs/accuracy/results.md``)."""

S175_MESH_FINE: tuple[int, int, int, int] = (90, 18, 9, 6)
"""5400 panels: RMS motions within 0.3 % of a 9600-panel mesh at ≈ 1.5× the cost of
:data:`S175_MESH` (``docs/accuracy/results.md``)."""

RUDDER_LIMIT_DEG = 35.0
"""Rudder angle limit of the servo [deg] (:data:`ship_gym.control.actuators.RUDDER_SERVO`)."""

_TWO_PI = 2.0 * math.pi


# =============================================================================================
# per-process caches
# =============================================================================================
_PROTOTYPES: dict[tuple[str, int, int], BatchSimulator] = {}


def prototype_simulator(setup: ShipSetup, num_ships: int, n_components: int) -> BatchSimulator:
    """A fresh BatchSimulator of ``num_ships`` calm-water ships of ``setup`` (cached build).

    The first call for a (setup, N, component count) builds it
    (:func:`ship_gym.engine.batch.build_batch_simulator`: hull, database, state-space fit,
    Nomoto identification of the autopilot…, 0.2–1 s); later calls return a deep copy of the
    cached one (milliseconds).

    Parameters
    ----------
    setup : ShipSetup
        Ship, models and numerics.
    num_ships : int
        Batch size N.
    n_components : int
        Padded wave-component count (room for every sea given at reset).
    """
    from ship_gym.engine.batch import build_batch_simulator

    key = (repr(setup), int(num_ships), int(n_components))
    proto = _PROTOTYPES.get(key)
    if proto is None:
        proto = build_batch_simulator(
            setup, [None] * int(num_ships), max_components=int(n_components)
        )
        _PROTOTYPES[key] = proto
    return copy.deepcopy(proto)


@dataclass(frozen=True)
class LoadingCondition:
    """Stability of the nominal loading condition of a hull (calm water, free sinkage and trim).

    Attributes
    ----------
    kg : float
        Height of G above the keel [m].
    gm : float
        Transverse metacentric height GM of the upright floating hull [m].
    heel_deg : numpy.ndarray
        Heel angles of the GZ table [deg] (0 … 90).
    gz : numpy.ndarray
        Righting arms there [m].
    vanishing_angle_deg : float
        Angle of vanishing stability [deg] (90 if GZ stays positive up to 90°).
    draught, heave : float
        Design draught [m] and the equilibrium sinkage of O [m] (z down).
    """

    kg: float
    gm: float
    heel_deg: NDArray
    gz: NDArray
    vanishing_angle_deg: float
    draught: float
    heave: float

    def vanishing_angles(self, delta_kg: NDArray) -> NDArray:
        """Angle of vanishing stability [rad] after raising G by ``delta_kg`` [m].

        GZ(φ) − ΔKG sin φ on the cubic interpolant of the GZ table (exact for a vertical shift
        of G at the same free sinkage and trim); the first down-crossing, 90° if none.
        """
        from scipy.interpolate import CubicSpline

        d = np.atleast_1d(np.asarray(delta_kg, float))
        out = np.full(d.shape, math.radians(self.vanishing_angle_deg))
        moved = d != 0.0
        if moved.any():
            fine = np.linspace(0.0, 90.0, 1801)
            gz = CubicSpline(self.heel_deg, self.gz)(fine)[None, :] - d[moved, None] * np.sin(
                np.radians(fine)
            )
            for r, row in zip(np.flatnonzero(moved), gz, strict=True):
                pos = np.flatnonzero(row[1:] > 0.0)
                start = int(pos[0]) + 1 if pos.size else 1  # first positive GZ after 0°
                down = np.flatnonzero((row[start:-1] > 0.0) & (row[start + 1 :] <= 0.0))
                if down.size == 0:
                    out[r] = math.pi / 2 if pos.size else math.radians(fine[1])
                    continue
                i = start + int(down[0])
                x = fine[i] + (fine[i + 1] - fine[i]) * row[i] / (row[i] - row[i + 1])
                out[r] = math.radians(x)
        return out


@lru_cache(maxsize=16)
def _loading_condition(hull_name: str, overrides: tuple) -> LoadingCondition:
    from ship_gym.hull import equilibrium, hydrostatics, load_hull, righting_arm

    hull = load_hull(hull_name, **dict(overrides))
    eq = equilibrium(hull)
    hs = hydrostatics(hull, eq.heave, 0.0, eq.trim)
    heels = np.arange(0.0, 90.0 + 1e-9, 5.0)
    curve = righting_arm(hull, heels)
    vanishing = curve.vanishing_angle_deg
    if not math.isfinite(vanishing):
        vanishing = 90.0
    return LoadingCondition(
        kg=float(hull.kg),
        gm=float(hs.gmt),
        heel_deg=curve.heel_deg,
        gz=curve.gz,
        vanishing_angle_deg=float(min(vanishing, 90.0)),
        draught=float(hull.particulars.draught),
        heave=float(eq.heave),
    )


@lru_cache(maxsize=16)
def _propeller(hull_name: str, overrides: tuple) -> Any:
    from ship_gym.forces.propeller import design_propeller_for
    from ship_gym.hull import load_hull

    return design_propeller_for(load_hull(hull_name, **dict(overrides)))


def loading_condition(setup: ShipSetup) -> LoadingCondition:
    """GZ table, GM and vanishing angle of the setup's hull and loading (cached per process)."""
    return _loading_condition(setup.hull, tuple(sorted(setup.hull_overrides.items())))


# =============================================================================================
# sea sampling
# =============================================================================================
def check_range(name: str, value: Any, *, low: float, high: float, unit: str) -> tuple:
    """A (min, max) pair of floats with low ≤ min ≤ max ≤ high, else ValueError."""
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a (min, max) pair [{unit}], got {value!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and low <= lo <= hi <= high):
        raise ValueError(
            f"{name} must satisfy {low} <= min <= max <= {high} [{unit}], got {value!r}"
        )
    return lo, hi


@dataclass(frozen=True)
class SeaSampler:
    """How the sea of an episode is drawn from its generator.

    Draws, in this order: height, period, relative heading, then (regular) the phase or
    (irregular) the components (:meth:`ship_gym.waves.wave_field.WaveField.from_sea_state`).

    Parameters
    ----------
    kind : {"irregular", "regular"}
        JONSWAP irregular sea or a regular wave.
    height_range : tuple of float
        Significant height Hs (irregular) or wave height H (regular) [m], uniform.
    period_range : tuple of float
        Peak period Tp (irregular) or period T (regular) [s], uniform.
    heading_range_deg : tuple of float
        Relative wave heading β [deg] (0 following seas, 180 head seas), uniform.
    n_components : int
        Wave components of an irregular sea.
    gamma : float
        JONSWAP peak enhancement γ [-].
    spreading_s : float or None
        Cos-2s spreading exponent (None: long-crested).
    ramp_time : float
        Start-up ramp T_f [s] (Matusiak eq. 12).
    """

    kind: Literal["irregular", "regular"] = "irregular"
    height_range: tuple[float, float] = (3.0, 5.0)
    period_range: tuple[float, float] = (9.0, 12.0)
    heading_range_deg: tuple[float, float] = (0.0, 360.0)
    n_components: int = 40
    gamma: float = 3.3
    spreading_s: float | None = None
    ramp_time: float = 30.0

    def __post_init__(self) -> None:
        if self.kind not in ("irregular", "regular"):
            raise ValueError(f"sea kind must be 'irregular' or 'regular', got {self.kind!r}")
        h = check_range("wave height range", self.height_range, low=0.0, high=30.0, unit="m")
        t = check_range("wave period range", self.period_range, low=1.0, high=40.0, unit="s")
        b = check_range(
            "wave heading range", self.heading_range_deg, low=-360.0, high=720.0, unit="deg"
        )
        object.__setattr__(self, "height_range", h)
        object.__setattr__(self, "period_range", t)
        object.__setattr__(self, "heading_range_deg", b)
        n = self.n_components
        if isinstance(n, bool) or not isinstance(n, int | np.integer) or not 1 <= n <= 1000:
            raise ValueError(f"n_components must be an integer in 1…1000, got {n!r}")
        if not (math.isfinite(self.gamma) and self.gamma >= 1.0):
            raise ValueError(f"JONSWAP gamma must be >= 1, got {self.gamma!r}")
        if self.spreading_s is not None and not (
            math.isfinite(self.spreading_s) and self.spreading_s >= 0.0
        ):
            raise ValueError(f"spreading_s must be None or >= 0, got {self.spreading_s!r}")
        if not (math.isfinite(self.ramp_time) and self.ramp_time >= 0.0):
            raise ValueError(f"wave ramp time must be >= 0 [s], got {self.ramp_time!r}")
        if self.kind == "regular":
            from ship_gym.waves.sea_state import MAX_STEEPNESS

            shortest = GRAVITY * t[0] ** 2 / _TWO_PI
            if h[1] / shortest > MAX_STEEPNESS:
                raise ValueError(
                    f"regular waves up to H = {h[1]} m at T = {t[0]} s (λ = {shortest:.1f} m) "
                    f"exceed the breaking steepness H/λ = {MAX_STEEPNESS:.3f}"
                )

    @property
    def max_components(self) -> int:
        """Components of the largest sea drawn (the batch's padded count)."""
        return 1 if self.kind == "regular" else int(self.n_components)

    def sample(self, rng: np.random.Generator) -> tuple[WaveField, dict[str, float]]:
        """One episode's wave field and its parameters (``wave_height_m``, ``wave_period_s``,
        ``wave_heading_deg``)."""
        from ship_gym.engine.ship import wave_field_for
        from ship_gym.waves.sea_state import IrregularSea, RegularWave

        height = float(rng.uniform(*self.height_range))
        period = float(rng.uniform(*self.period_range))
        heading_deg = float(rng.uniform(*self.heading_range_deg))
        beta = math.radians(heading_deg)
        if self.kind == "regular":
            phase = float(rng.uniform(0.0, _TWO_PI))
            sea: Any = RegularWave(
                height=height, period=period, phase=phase, ramp_time=self.ramp_time
            )
        else:
            sea = IrregularSea(
                hs=height,
                tp=period,
                gamma=self.gamma,
                spreading_s=self.spreading_s,
                n_components=int(self.n_components),
                ramp_time=self.ramp_time,
            )
        wave_field = wave_field_for(sea, beta, rng)
        info = {
            "wave_height_m": height,
            "wave_period_s": period,
            "wave_heading_deg": (heading_deg + 180.0) % 360.0 - 180.0,
        }
        return wave_field, info


# =============================================================================================
# sensor noise and observation bounds
# =============================================================================================
SENSOR_NOISE_STD: dict[str, float] = {
    "roll [rad]": math.radians(0.2),
    "pitch [rad]": math.radians(0.2),
    "heave [m]": 0.05,
    "roll rate [rad/s]": math.radians(0.1),
    "pitch rate [rad/s]": math.radians(0.1),
    "heave velocity [m/s]": 0.02,
    "yaw rate [rad/s]": math.radians(0.05),
    "surge speed [m/s]": 0.05,
    "sway velocity [m/s]": 0.05,
    "heading error [rad]": math.radians(0.5),
}
"""Standard deviation of each sensor at ``sensor_noise=1`` (typical marine motion reference
unit, gyro compass and log accuracy); unlisted entries (commands, actuator feedback, wave
direction, preview) are noise-free except the preview, which takes 0.1 m."""

_PREVIEW_NOISE_STD = 0.1  # [m] wave-radar elevation accuracy at sensor_noise = 1

_BASE_OBSERVATIONS: tuple[tuple[str, float], ...] = (
    # name, bound (symmetric) — every entry is clipped to ±bound
    ("roll [rad]", math.pi),
    ("pitch [rad]", math.pi / 2),
    ("heave [m]", 30.0),
    ("roll rate [rad/s]", 5.0),
    ("pitch rate [rad/s]", 5.0),
    ("heave velocity [m/s]", 30.0),
    ("yaw rate [rad/s]", 2.0),
    ("surge speed [m/s]", 30.0),
    ("sway velocity [m/s]", 30.0),
    ("heading error [rad]", math.pi),
    ("relative wave heading cos [-]", 1.0),
    ("relative wave heading sin [-]", 1.0),
)


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
_EMPTY = np.zeros(0)
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
        cost[i] = f
        episode_steps[i] += 1
        heading_error[i] = (heading_setpoint[i] - eta[i, 5] + math.pi) % _TWO_PI - math.pi
        roll_deg[i] = eta[i, 3] * _RAD2DEG
        max_roll_deg[i] = max_abs[i] * _RAD2DEG


@numba.njit(cache=True, nogil=True)
def _base_observations_kernel(
    eta, nu, z_eq, heading_error, cos_beta, sin_beta, rudder, shaft, out
):  # pragma: no cover - compiled
    """Columns 0–13 of the clean observations (``_BASE_OBSERVATIONS``, the rudder angle if
    ``rudder`` is not empty, the shaft speed if ``shaft`` is not empty) into ``out``."""
    for i in range(eta.shape[0]):
        out[i, 0] = eta[i, 3]
        out[i, 1] = eta[i, 4]
        out[i, 2] = eta[i, 2] - z_eq
        out[i, 3] = nu[i, 3]
        out[i, 4] = nu[i, 4]
        out[i, 5] = nu[i, 2]
        out[i, 6] = nu[i, 5]
        out[i, 7] = nu[i, 0]
        out[i, 8] = nu[i, 1]
        out[i, 9] = heading_error[i]
        out[i, 10] = cos_beta[i]
        out[i, 11] = sin_beta[i]
        j = 12
        if rudder.shape[0] > 0:
            out[i, j] = rudder[i]
            j += 1
        if shaft.shape[0] > 0:
            out[i, j] = shaft[i]


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
        out[i, 0] = (psi[i] - course + math.pi) % _TWO_PI - math.pi
        out[i, 1] = (setpoint[i] - course + math.pi) % _TWO_PI - math.pi
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
    wave_preview_m : sequence of float
        Distances ahead of O along the heading where the incident elevation is observed [m]
        (empty: no preview).
    history_length : int
        Samples of the rendering history (one per control step).
    extra_observations : sequence of (name, low, high)
        The subclass's observation entries (appended after the common ones).
    capsize_penalty : float
        Reward ``capsize`` = −capsize_penalty in the control step the ship capsizes [-], the last
        of the reward terms (after the subclass's :meth:`_reward_terms`).
    """

    setup: ShipSetup
    sim: BatchSimulator
    num_threads: int = 1
    """numba threads over the ships in the compiled loop (set by :class:`S175Task`)."""
    observations_bounded = True  # observations() is a float32 copy, clipped to the bounds

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
        wave_preview_m: Sequence[float] = (),
        history_length: int = 240,
        extra_observations: Sequence[tuple[str, float, float]] = (),
        capsize_penalty: float = 0.0,
    ) -> None:
        super().__init__(num_envs)
        n = self.num_envs
        self.setup = setup
        self.sea = sea
        self.capsize_penalty = check_weight("capsize_penalty", capsize_penalty)
        # --- time steps
        dt = float(setup.dt)
        if not (isinstance(control_dt, int | float) and math.isfinite(control_dt)):
            raise ValueError(f"control_dt must be a finite time step [s], got {control_dt!r}")
        k = round(control_dt / dt)
        if k < 1 or abs(k * dt - control_dt) > 1e-9 * max(1.0, control_dt):
            raise ValueError(
                f"control_dt = {control_dt!r} s must be a positive integer multiple of the "
                f"physics dt = {dt!r} s"
            )
        self.substeps = int(k)
        self.control_dt = float(k * dt)
        # --- options
        lc = loading_condition(setup)
        self.loading = lc
        if speed_range is not None:
            speed_range = check_range("speed_range", speed_range, low=0.1, high=30.0, unit="m/s")
            if not setup.propulsion:
                raise ValueError("speed_range needs a setup with propulsion (a shaft speed)")
        self.speed_range = speed_range
        if gm_range is not None:
            gm_range = check_range("gm_range", gm_range, low=0.05, high=10.0, unit="m")
        self.gm_range = gm_range
        if capsize_angle_deg is not None and not (
            isinstance(capsize_angle_deg, int | float) and 0.0 < capsize_angle_deg <= 180.0
        ):
            raise ValueError(
                f"capsize_angle_deg must be in (0, 180] [deg] or None, got {capsize_angle_deg!r}"
            )
        self.capsize_angle_deg = capsize_angle_deg
        if not (isinstance(dangerous_roll_deg, int | float) and 0.0 < dangerous_roll_deg < 90.0):
            raise ValueError(
                f"dangerous_roll_deg must be in (0, 90) [deg], got {dangerous_roll_deg!r}"
            )
        self.dangerous_roll = math.radians(dangerous_roll_deg)
        if not (isinstance(sensor_noise, int | float) and 0.0 <= sensor_noise <= 100.0):
            raise ValueError(f"sensor_noise must be in [0, 100] [-], got {sensor_noise!r}")
        self.sensor_noise = float(sensor_noise)
        try:
            preview = np.asarray(wave_preview_m, dtype=float).reshape(-1)
        except (TypeError, ValueError):
            raise ValueError(
                f"wave_preview_m must be a sequence of distances [m], got {wave_preview_m!r}"
            ) from None
        if not np.all(np.isfinite(preview)) or np.any(np.abs(preview) > 5000.0):
            raise ValueError(f"wave_preview_m must be finite distances within ±5 km, got {preview}")
        self.wave_preview_m = preview
        if (
            isinstance(history_length, bool)
            or not isinstance(history_length, int)
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
        self.commands: dict[str, NDArray] = {}
        if setup.propulsion:
            self.commands["shaft_speed"] = np.full(n, self._nominal_shaft_speed)
        if setup.rudder == "command":
            self.commands["rudder_command"] = np.zeros(n)
        if setup.rudder == "autopilot":
            self.commands["heading"] = np.zeros(n)
        # --- observation layout
        names = [name for name, _ in _BASE_OBSERVATIONS]
        bounds = [b for _, b in _BASE_OBSERVATIONS]
        low = [-b for b in bounds]
        if self._rudder is not None:
            names.append("rudder angle [rad]")
            low.append(-math.pi / 2)
            bounds.append(math.pi / 2)
        if setup.propulsion:
            names.append("shaft speed [rev/s]")
            low.append(-20.0)
            bounds.append(20.0)
        self._n_base = len(names)
        self._n_extra = len(extra_observations)
        for name, lo, hi in extra_observations:
            names.append(name)
            low.append(float(lo))
            bounds.append(float(hi))
        for d in preview:
            names.append(f"wave elevation {d:g} m ahead [m]")
            low.append(-30.0)
            bounds.append(30.0)
        self.observation_names = tuple(names)
        self._obs_low = np.asarray(low, dtype=np.float32)
        self._obs_high = np.asarray(bounds, dtype=np.float32)
        self.observation_space = spaces.Box(self._obs_low, self._obs_high, dtype=np.float32)
        noise = [SENSOR_NOISE_STD.get(name, 0.0) for name in names]
        noise[len(names) - preview.size :] = [_PREVIEW_NOISE_STD] * preview.size
        self._noise_std = self.sensor_noise * np.asarray(noise)
        # --- per-episode state
        self.heading_setpoint = np.zeros(n)  # ψ_ref [rad]
        self.wave_direction = np.zeros(n)  # mean χ of the episode's sea [rad]
        self.capsize_angle = np.full(n, math.radians(capsize_angle_deg or lc.vanishing_angle_deg))
        self.initial_speed = np.full(n, float(setup.speed))
        self.gm = np.full(n, lc.gm)
        self.episode_steps = np.zeros(n, dtype=np.int64)
        self.capsized = np.zeros(n, dtype=bool)
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
        return _propeller(self.setup.hull, tuple(sorted(self.setup.hull_overrides.items())))

    def _actuator(self, name: str) -> Any:
        """The servo-driven force model ``name`` of the simulator, or None."""
        try:
            return self.sim.actuator_model(name)
        except ValueError:
            return None

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
        lc = self.loading
        fields = []
        speeds = np.empty(ids.size)
        gms = np.empty(ids.size)
        for k, (i, rng) in enumerate(zip(ids, rngs, strict=True)):
            wave_field, info = self.sea.sample(rng)
            fields.append(wave_field)
            speeds[k] = (
                float(rng.uniform(*self.speed_range)) if self.speed_range else self.setup.speed
            )
            gms[k] = float(rng.uniform(*self.gm_range)) if self.gm_range else lc.gm
            self.wave_direction[i] = math.radians(info["wave_heading_deg"])
            self._rngs[int(i)] = rng
            self._reset_infos[int(i)] = info
        # loading: G raised by ΔKG = GM_nominal − GM
        delta_kg = lc.gm - gms
        if self.gm_range is not None:
            cog = np.tile(np.asarray(self.sim.hull.mass.cog, float), (ids.size, 1))
            cog[:, 2] -= delta_kg
            self.sim.set_centre_of_gravity(ids, cog)
        self.gm[ids] = gms
        if self.capsize_angle_deg is None:
            self.capsize_angle[ids] = lc.vanishing_angles(delta_kg)
        else:
            self.capsize_angle[ids] = math.radians(self.capsize_angle_deg)
        # speed and shaft speed
        self.initial_speed[ids] = speeds
        nu = np.zeros((ids.size, 6))
        nu[:, 0] = speeds
        if "shaft_speed" in self.commands:
            if self.speed_range is None:
                self.commands["shaft_speed"][ids] = self._nominal_shaft_speed
            else:
                self.commands["shaft_speed"][ids] = self.shaft_speed_for(speeds)
        if "rudder_command" in self.commands:
            self.commands["rudder_command"][ids] = 0.0
        self.heading_setpoint[ids] = 0.0
        for i, rng in zip(ids, rngs, strict=True):
            self._reset_infos[int(i)].update(self._reset_task(int(i), rng))
        if "heading" in self.commands:
            self.commands["heading"][ids] = self.heading_setpoint[ids]
        self.sim.commands = {**self.sim.commands, **self.commands}
        self.sim.reset(ids, nu=nu, wave_fields=fields)
        self.episode_steps[ids] = 0
        self.capsized[ids] = False
        self._hist_t[ids] = np.nan
        self._hist[ids] = np.nan
        self._step_heading_error = None
        self._record_history(ids)
        self._clean_observations()
        self._finish_observations(ids)

    def reset_info(self, ids: NDArray[np.int64]) -> Mapping[str, NDArray]:
        ids = np.asarray(ids, dtype=np.int64).reshape(-1)
        out: dict[str, NDArray] = {}
        keys = self._reset_infos[int(ids[0])].keys() if ids.size else ()
        for key in keys:
            out[key] = np.array([self._reset_infos[int(i)][key] for i in ids], dtype=float)
        out["initial_speed_mps"] = self.initial_speed[ids].copy()
        out["gm_m"] = self.gm[ids].copy()
        out["capsize_angle_deg"] = np.degrees(self.capsize_angle[ids])
        return out

    # ------------------------------------------------------------------ step
    def step(self, actions: NDArray) -> TaskStep:
        sim = self.sim
        n = self.num_envs
        a = np.asarray(actions, dtype=np.float64).reshape(n, -1)
        self._step_heading_error = None
        self._apply_actions(a)
        position_before = sim.eta[:, :2].copy()
        # the control step's physics substeps in one engine call (compiled when possible)
        if self.num_threads > 1:
            numba.set_num_threads(min(self.num_threads, numba.config.NUMBA_NUM_THREADS))
        red = sim.advance(self.substeps, self.commands, danger_roll=self.dangerous_roll)
        max_abs = red.max_abs_roll
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
        return (self.heading_setpoint - self.sim.eta[:, 5] + math.pi) % _TWO_PI - math.pi

    def _current_heading_error(self) -> NDArray:
        """:meth:`heading_error` after the engine call of the step being taken (computed once
        per step; a fresh computation outside a step)."""
        he = self._step_heading_error
        return self.heading_error() if he is None else he

    def _preview(self) -> NDArray:
        eta = self.sim.eta
        d = self.wave_preview_m[None, :]
        x = eta[:, 0:1] + d * np.cos(eta[:, 5:6])
        y = eta[:, 1:2] + d * np.sin(eta[:, 5:6])
        return self.sim.elevation(x, y)

    def _clean_observations(self, heading_error: NDArray | None = None) -> NDArray:
        """Fill and return the (N, n_obs) float64 buffer of the noise-free observations."""
        sim = self.sim
        eta = sim.eta
        out = self._obs_clean
        beta = self.wave_direction - eta[:, 5]
        if heading_error is None:
            heading_error = self.heading_error()
        rudder = self._rudder.angle if self._rudder is not None else _EMPTY
        shaft = self.commands.get("shaft_speed", _EMPTY)
        _base_observations_kernel(
            eta, sim.nu, self._z_eq, heading_error, np.cos(beta), np.sin(beta), rudder, shaft, out
        )
        if self._custom_extra:
            self._obs_extra[:] = self._extra_observations()
        elif self._n_extra:
            self._write_extra_observations(self._obs_extra)
        if self.wave_preview_m.size:
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


# =============================================================================================
# shared keyword validation of the S175 tasks
# =============================================================================================
def s175_setup(
    *,
    froude_number: float,
    physics_dt: float,
    integrator: str,
    rudder: Literal["command", "autopilot"],
    hull_mesh: Sequence[int],
    kg: float | None,
    precision: Precision = "float32",
) -> ShipSetup:
    """The S175 setup of the ship tasks: state-space radiation memory, diffraction, Ikeda roll
    damping, propulsion (Holtrop resistance + B-series propeller), manoeuvring forces and a
    rudder behind its servo (commanded, or under the heading autopilot).

    Parameters
    ----------
    froude_number : float
        Reference Froude number Fn = U/√(g Lpp) [-] (0.05 … 0.5).
    physics_dt : float
        Physics time step [s] (0.01 … 0.5).
    integrator : {"holloway", "rk4"}
        Holloway's μ-Taylor scheme (1 force evaluation per step) or RK4 (4).
    rudder : {"command", "autopilot"}
        Rudder following ``"rudder_command"`` or the PID heading autopilot (``"heading"``).
    hull_mesh : sequence of 4 int
        S175 mesh (n_sections, n_below, n_above, n_deck); :data:`S175_MESH` is the default.
    kg : float or None
        KG of the loading [m] (None: 9.55 m, the ITTC condition, GM ≈ 1.0 m).
    precision : {"float32", "float64"}
        Wave sums of the Froude–Krylov kernel (``fk_method`` "fast32" or "fast").
    """
    from ship_gym.engine.ship import ShipSetup

    if not (isinstance(froude_number, int | float) and 0.05 <= froude_number <= 0.5):
        raise ValueError(f"froude_number must be in [0.05, 0.5] [-], got {froude_number!r}")
    if not (isinstance(physics_dt, int | float) and 0.01 <= physics_dt <= 0.5):
        raise ValueError(f"physics_dt must be in [0.01, 0.5] [s], got {physics_dt!r}")
    if integrator not in ("holloway", "rk4"):
        raise ValueError(f"integrator must be 'holloway' or 'rk4', got {integrator!r}")
    if precision not in ("float32", "float64"):
        raise ValueError(f"precision must be 'float32' or 'float64', got {precision!r}")
    mesh = tuple(hull_mesh) if isinstance(hull_mesh, Sequence) else ()
    if len(mesh) != 4 or not all(
        isinstance(v, int | np.integer) and not isinstance(v, bool) and v >= 2 for v in mesh
    ):
        raise ValueError(
            f"hull_mesh must be 4 integers >= 2 (n_sections, n_below, n_above, n_deck), "
            f"got {hull_mesh!r}"
        )
    overrides: dict[str, Any] = {}
    if mesh != S175_MESH:  # the library hull's own mesh
        overrides.update(
            n_sections=int(mesh[0]),
            n_below=int(mesh[1]),
            n_above=int(mesh[2]),
            n_deck=int(mesh[3]),
        )
    if kg is not None:
        if not (isinstance(kg, int | float) and 5.0 <= kg <= 12.0):
            raise ValueError(f"kg must be in [5, 12] [m] (S175 depth 15.4 m), got {kg!r}")
        overrides["kg"] = float(kg)
    speed = float(froude_number) * math.sqrt(GRAVITY * 175.0)
    return ShipSetup(
        hull="s175",
        hull_overrides=overrides,
        database="s175",
        speed=speed,
        radiation="state_space",
        diffraction=True,
        viscous_roll=True,
        integrator=integrator,  # type: ignore[arg-type]
        dt=float(physics_dt),
        propulsion=True,
        manoeuvring=True,
        rudder=rudder,
        fk_method="fast32" if precision == "float32" else "fast",
    )


def check_weight(name: str, value: Any) -> float:
    """A reward weight ≥ 0 (finite), else ValueError."""
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float)
        or not (math.isfinite(value) and value >= 0.0)
    ):
        raise ValueError(f"{name} must be a finite weight >= 0, got {value!r}")
    return float(value)


def check_positive(name: str, value: Any, unit: str, high: float = math.inf) -> float:
    """A positive finite number ≤ ``high``, else ValueError."""
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float)
        or not (math.isfinite(value) and 0.0 < value <= high)
    ):
        raise ValueError(f"{name} must be in (0, {high}] [{unit}], got {value!r}")
    return float(value)


def check_point(name: str, value: Any) -> NDArray:
    """A finite body-frame point (x, y, z) within ±200 m [m], else ValueError."""
    try:
        point = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(
            f"{name} must be a body-frame point (x, y, z) [m], got {value!r}"
        ) from None
    if point.shape != (3,) or not np.all(np.isfinite(point)) or np.any(np.abs(point) > 200.0):
        raise ValueError(f"{name} must be a finite (x, y, z) within ±200 m [m], got {value!r}")
    return point


# =============================================================================================
# the S175 task built from the environments' shared keyword arguments
# =============================================================================================
SHIP_KWARGS: tuple[str, ...] = (
    "froude_number",
    "speed_range_mps",
    "gm_range_m",
    "kg_m",
    "physics_dt_s",
    "control_dt_s",
    "integrator",
    "hull_mesh",
    "precision",
    "num_threads",
    "capsize_angle_deg",
    "dangerous_roll_deg",
    "capsize_penalty",
    "sensor_noise",
    "wave_preview_m",
)
"""The environment keyword arguments :class:`S175Task` takes as they are (:func:`ship_kwargs`)."""


def ship_kwargs(values: Mapping[str, Any]) -> dict[str, Any]:
    """The :data:`SHIP_KWARGS` among an environment task's arguments (its ``locals()``).

    Every ship environment task declares its keyword arguments explicitly (typed, with units,
    with its own defaults) and forwards the shared ones to :class:`S175Task` by name with this.
    """
    return {key: values[key] for key in SHIP_KWARGS if key in values}


def irregular_sea(values: Mapping[str, Any]) -> SeaSampler:
    """The JONSWAP :class:`SeaSampler` of an environment task's irregular-sea arguments
    ``hs_range_m``, ``tp_range_s``, ``wave_heading_range_deg``, ``n_wave_components``,
    ``wave_spreading_s`` and ``wave_ramp_time_s`` (in ``values``, its ``locals()``)."""
    return SeaSampler(
        kind="irregular",
        height_range=values["hs_range_m"],
        period_range=values["tp_range_s"],
        heading_range_deg=values["wave_heading_range_deg"],
        n_components=values["n_wave_components"],
        spreading_s=values["wave_spreading_s"],
        ramp_time=values["wave_ramp_time_s"],
    )


class S175Task(ShipTask, abc.ABC):
    """A :class:`ShipTask` of the S175 (:func:`s175_setup`) from the shared environment
    keyword arguments (:data:`SHIP_ARGUMENTS` for their meaning and units).

    Parameters
    ----------
    num_envs : int
        Number of episodes N.
    rudder : {"command", "autopilot"}
        Rudder following ``"rudder_command"`` or the PID heading autopilot.
    sea : SeaSampler
        Per-episode sea.
    froude_number, physics_dt_s, integrator, hull_mesh, kg_m, precision
        :func:`s175_setup` arguments (Fn [-], dt [s], scheme, mesh, KG [m], wave sums).
    num_threads : int
        numba threads over the ships in the compiled loop (1: serial).
    control_dt_s : float
        Control step [s], an integer multiple of ``physics_dt_s``.
    speed_range_mps : tuple of float or None
        Initial speed range [m/s] (None: the reference speed).
    gm_range_m : tuple of float or None
        GM range [m] of the episodes' loading (None: nominal).
    capsize_angle_deg, dangerous_roll_deg, capsize_penalty, sensor_noise, wave_preview_m
        :class:`ShipTask` arguments.
    setup_changes : mapping, optional
        :class:`ship_gym.engine.ship.ShipSetup` fields replaced after :func:`s175_setup`
        (e.g. ``{"fins": "command"}``).
    extra_observations : sequence of (name, low, high)
        The subclass's observation entries.
    """

    def __init__(
        self,
        num_envs: int,
        *,
        rudder: Literal["command", "autopilot"],
        sea: SeaSampler,
        froude_number: float,
        physics_dt_s: float,
        control_dt_s: float,
        integrator: IntegratorName,
        hull_mesh: Sequence[int],
        capsize_angle_deg: float | None,
        dangerous_roll_deg: float,
        precision: Precision = "float32",
        num_threads: int = 1,
        capsize_penalty: float,
        sensor_noise: float,
        wave_preview_m: Sequence[float],
        kg_m: float | None = None,
        speed_range_mps: tuple[float, float] | None = None,
        gm_range_m: tuple[float, float] | None = None,
        setup_changes: Mapping[str, Any] | None = None,
        extra_observations: Sequence[tuple[str, float, float]] = (),
    ) -> None:
        setup = s175_setup(
            froude_number=froude_number,
            physics_dt=physics_dt_s,
            integrator=integrator,
            rudder=rudder,
            hull_mesh=hull_mesh,
            kg=kg_m,
            precision=precision,
        )
        if not (
            isinstance(num_threads, int) and not isinstance(num_threads, bool) and num_threads >= 1
        ):
            raise ValueError(f"num_threads must be an integer >= 1, got {num_threads!r}")
        self.num_threads = num_threads
        if setup_changes:
            setup = dataclasses.replace(setup, **setup_changes)
        super().__init__(
            num_envs,
            setup=setup,
            sea=sea,
            control_dt=control_dt_s,
            speed_range=speed_range_mps,
            gm_range=gm_range_m,
            capsize_angle_deg=capsize_angle_deg,
            dangerous_roll_deg=dangerous_roll_deg,
            sensor_noise=sensor_noise,
            wave_preview_m=wave_preview_m,
            extra_observations=extra_observations,
            capsize_penalty=capsize_penalty,
        )
        self.sim.parallel = num_threads > 1

    # ------------------------------------------------------------------ shared reward terms
    def roll_term(self, stats: StepStatistics, weight: float, scale: float) -> NDArray:
        """−weight · mean(φ²)/scale² over the physics steps of the control step (scale [rad])."""
        return -weight * stats.mean_square_roll / scale**2

    def heading_term(self, weight: float, scale: float) -> NDArray:
        """−weight · (e/scale)², e the wrapped heading error (scale [rad])."""
        return -weight * (self._current_heading_error() / scale) ** 2


# =============================================================================================
# the environments' docstrings: shared pieces, written once
# =============================================================================================
SHIP_OBSERVATION_TABLE = """\
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
| 12 | rudder angle (servo) | rad | ±π/2 |
| 13 | shaft speed | rev/s | ±20 |"""
"""Markdown rows of the common observation entries 0–13 of every S175 task (the names and
bounds of ``_BASE_OBSERVATIONS``, the rudder angle and the shaft speed)."""

SHIP_ARGUMENTS: dict[str, tuple[str, str]] = {
    # name: (unit, meaning); an environment may give its own meaning for any of them
    "froude_number": ("-", "reference speed U = Fn √(g L) (radiation, diffraction, propeller)"),
    "speed_range_mps": ("m/s", "initial speed range (self-propulsion rpm); keep near U"),
    "hs_range_m": ("m", "significant wave height range"),
    "tp_range_s": ("s", "peak period range"),
    "wave_heading_range_deg": ("deg", "relative wave heading β (0 following, 180 head seas)"),
    "n_wave_components": ("-", "components of the irregular sea"),
    "wave_spreading_s": ("-", "cos-2s spreading exponent (None: long-crested)"),
    "wave_ramp_time_s": ("s", "start-up ramp of the waves (Matusiak 2003, eq. 12)"),
    "gm_range_m": ("m", "GM range of the loading (per episode; None: nominal)"),
    "kg_m": ("m", "KG of the nominal loading (None: 9.55 m)"),
    "passenger_point_m": ("m", "body-frame passenger position (z down)"),
    "physics_dt_s": ("s", "physics time step"),
    "control_dt_s": ("s", "control step (integer multiple of physics_dt_s)"),
    "integrator": ("-", '"holloway" (1 force evaluation/step) or "rk4" (4)'),
    "hull_mesh": ("-", "S175 mesh (sections, panels below/above water, deck)"),
    "precision": ("-", '"float32" or "float64" wave sums of the Froude–Krylov kernel'),
    "num_threads": ("-", "numba threads over the batch's ships (1: serial)"),
    "capsize_angle_deg": ("deg", "capsize roll angle (None: vanishing angle of the loading)"),
    "dangerous_roll_deg": ("deg", "roll angle of the Safe-RL cost"),
    "heading_weight": ("-", "weight of the heading term"),
    "heading_scale_deg": ("deg", "heading error scale"),
    "roll_weight": ("-", "weight of the roll term"),
    "roll_scale_deg": ("deg", "roll scale"),
    "effort_weight": ("-", "weight of the actuator effort term"),
    "capsize_penalty": ("-", "penalty paid at capsize"),
    "comfort_time_constant_s": ("s", "time constant of the running acceleration RMS"),
    "sensor_noise": ("-", "multiplier of the sensor accuracies (SENSOR_NOISE_STD)"),
    "wave_preview_m": ("m", "distances ahead of O of the elevation preview"),
}
"""Unit and meaning of the keyword arguments shared by the ship environments (the rows of the
``## Arguments`` tables; :func:`env_docstring` takes each default from the task's signature)."""


def _format_default(value: Any) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float):
        return f"{value:g}" if value != 0.0 else "0"
    if isinstance(value, tuple):
        return "(" + ", ".join(_format_default(v) for v in value) + ")"
    return repr(value)


def _task_parameters(task_class: type) -> list[inspect.Parameter]:
    """The keyword arguments of ``task_class.__init__`` after ``num_envs``."""
    params = list(inspect.signature(task_class.__init__).parameters.values())
    return [p for p in params[1:] if p.name != "num_envs"]


def arguments_table(task_class: type, rows: Mapping[str, tuple[str, str]]) -> str:
    """The ``## Arguments`` markdown table of a task: every keyword argument of its
    ``__init__`` in signature order, its default, and (unit, meaning) from ``rows`` or else
    :data:`SHIP_ARGUMENTS`.

    Raises
    ------
    ValueError
        A keyword argument without a documented unit and meaning.
    """
    known = {**SHIP_ARGUMENTS, **rows}
    lines = ["| kwarg | default | unit | meaning |", "|---|---|---|---|"]
    for p in _task_parameters(task_class):
        if p.name not in known:
            raise ValueError(f"{task_class.__name__} keyword {p.name!r} has no documented unit")
        unit, meaning = known[p.name]
        lines.append(f"| {p.name} | {_format_default(p.default)} | {unit} | {meaning} |")
    return "\n".join(lines)


def _time_limit(name: str, task_class: type) -> str:
    steps = max_episode_steps(name)
    defaults = {p.name: p.default for p in _task_parameters(task_class)}
    dt = defaults.get("control_dt_s", defaults.get("control_dt"))
    return f"``MAX_EPISODE_STEPS`` = {steps} control steps = {steps * dt:g} s at the default step"


def _fill(doc: str, marker: str, text: str) -> str:
    """Replace ``{marker}`` in ``doc``, indenting the lines of ``text`` like the marker."""
    found = re.search(rf"^([ \t]*)(.*?)\{{{marker}\}}", doc, re.MULTILINE)
    if found is None:
        raise ValueError(f"docstring has no {{{marker}}} marker")
    indent = found.group(1)
    return doc.replace(f"{{{marker}}}", text.replace("\n", "\n" + indent), 1)


_EnvType = TypeVar("_EnvType", bound=type)


def env_docstring(
    arguments: Mapping[str, tuple[str, str]] | None = None,
    version_history: Sequence[str] = (
        "v0: initial version.",
        "v1: one compiled engine call per control step; servos sampled at each physics step "
        "and advanced by the exact solution of their lag and rate limit (v0 integrated them as "
        "ODE states: under Holloway's scheme a constant command cycled); float32 wave sums by "
        "default (docs/accuracy/results.md: ≤ 3e-5 % on every motion statistic).",
    ),
) -> Callable[[_EnvType], _EnvType]:
    """Class decorator completing a ship environment's Gymnasium v5 docstring.

    The class docstring holds the sections Description … Episode End; this fills the markers
    ``{ship_observations}`` (:data:`SHIP_OBSERVATION_TABLE`) and ``{time_limit}`` (the
    registered ``MAX_EPISODE_STEPS`` of ``<Name>Env`` and its duration at the default control
    step) where it has them, and appends ``## Arguments`` (:func:`arguments_table` of the
    class's ``task_class``, with the environment's own ``arguments`` rows, name → (unit,
    meaning)) and ``## Version History``.
    """

    def decorate(cls: _EnvType) -> _EnvType:
        task_class = cls.task_class  # type: ignore[attr-defined]
        name = cls.__name__.removesuffix("Env")
        doc = (cls.__doc__ or "").rstrip()
        if "{ship_observations}" in doc:
            doc = _fill(doc, "ship_observations", SHIP_OBSERVATION_TABLE)
        if "{time_limit}" in doc:
            doc = _fill(doc, "time_limit", _time_limit(name, task_class))
        sections = [
            "## Arguments",
            arguments_table(task_class, arguments or {}),
            "## Version History",
            "\n".join(f"* {line}" for line in version_history),
        ]
        cls.__doc__ = doc + "".join(_indent(f"\n\n{part}") for part in sections) + "\n    "
        return cls

    return decorate


def _indent(text: str, indent: str = "    ") -> str:
    """Indent the lines of a docstring fragment like a class docstring's body."""
    return "\n".join(indent + line if line else line for line in text.split("\n"))


def vector_env_docstring(env_class: type) -> str:
    """The docstring of the vector face of ``env_class`` (N episodes, seeds s + i)."""
    return (
        f"N episodes of :class:`{env_class.__name__}` in one BatchSimulator (same keyword "
        "arguments).\n\n"
        "    Episode i reset with ``seed=s`` is the single environment reset with "
        "``seed=s + i``.\n    "
    )
