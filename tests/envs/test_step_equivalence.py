"""The compiled per-step bookkeeping of the ship tasks is the NumPy code it replaced, bit for bit.

``ShipTask.step`` fills its observations, statistics, history and comfort sample with small
numba kernels (``ship_task._step_kernel``, ``observations.write_state_columns``,
``_finish_observations_kernel``, ``_history_kernel``, ``comfort._comfort_kernel``…). The
reference here is the NumPy implementation they replaced (the reference tasks below: the former
``ShipTask.step``, observation and history code and the tasks' former hooks), run on the same
engine with the same seeds and actions: every observation, reward term, cost, flag, info value and
the rendering history must be the same to the last bit (NaN, −0.0 included). Coarse S175 mesh.
"""

import dataclasses
import math

import numpy as np
import pytest

from ship_gym.comfort.metrics import PassengerComfort
from ship_gym.control.actuators import FIN_SERVO, FOIL_SERVO
from ship_gym.envs.base import TaskEnv, TaskStep, TaskVectorEnv, validate_actions
from ship_gym.envs.capsize_avoidance import CapsizeAvoidanceTask
from ship_gym.envs.course_keeping import CourseKeepingTask
from ship_gym.envs.ride_control import RideControlTask
from ship_gym.envs.roll_stabilisation import RollStabilizationTask
from ship_gym.envs.ship_task import _TWO_PI, StepStatistics, _finish_observations_kernel, clip_into

from ._ship_env_checks import COARSE, COARSE_MESH


# =============================================================================================
# the reference: the NumPy step of the ship tasks
# =============================================================================================
class _ReferenceStep:
    """ShipTask.step, its observations and history as NumPy expressions."""

    def step(self, actions):
        sim = self.sim
        a = np.asarray(actions, dtype=np.float64).reshape(self.num_envs, -1)
        self._apply_actions(a)
        n = self.num_envs
        position_before = sim.eta[:, :2].copy()
        red = sim.advance(self.substeps, self.commands, danger_roll=self.dangerous_roll)
        max_abs, sum_sq, danger = red.max_abs_roll, red.sum_sq_roll, red.danger_steps
        diverged = sim.diverged.copy()
        capsized = (max_abs > self.capsize_angle) | diverged
        newly = capsized & ~self.capsized
        self.capsized |= capsized
        stats = StepStatistics(
            max_abs_roll=max_abs,
            mean_square_roll=sum_sq / self.substeps,
            danger_fraction=danger / self.substeps,
            capsized=self.capsized.copy(),
            diverged=diverged,
            newly_capsized=newly,
            position_before=position_before,
        )
        self.episode_steps += 1
        terms = self._reward_terms(stats)
        terms["capsize"] = -self.capsize_penalty * stats.newly_capsized
        self._record_history(np.arange(n))
        self._obs = self._noisy(self._clean_observations(), np.arange(n))
        info = {
            "capsized": stats.capsized.copy(),
            "diverged": diverged,
            "roll_deg": np.degrees(sim.eta[:, 3]),
            "max_roll_deg": np.degrees(max_abs),
            **self._task_info(stats),
        }
        return TaskStep(
            reward_terms=terms,
            cost=np.where(stats.newly_capsized, 1.0, stats.danger_fraction),
            terminated=stats.capsized.copy(),
            info=info,
        )

    def heading_term(self, weight, scale):
        return -weight * (self.heading_error() / scale) ** 2

    def _clean_observations(self, heading_error=None):
        sim = self.sim
        eta, nu = sim.eta, sim.nu
        beta = self.wave_direction - eta[:, 5]
        cols = [
            eta[:, 3],
            eta[:, 4],
            eta[:, 2] - self._z_eq,
            nu[:, 3],
            nu[:, 4],
            nu[:, 2],
            nu[:, 5],
            nu[:, 0],
            nu[:, 1],
            self.heading_error(),
            np.cos(beta),
            np.sin(beta),
        ]
        if self._rudder is not None:
            cols.append(self._rudder.angle)
        if "shaft_speed" in self.commands:
            cols.append(self.commands["shaft_speed"])
        out = np.empty((self.num_envs, len(self.observation_names)))
        out[:, : len(cols)] = np.column_stack(cols)
        extra = self._extra_observations()
        j = len(cols) + extra.shape[1]
        out[:, len(cols) : j] = extra
        if self.wave_preview_m.size:
            out[:, j:] = self._preview()
        self._reference_clean = out
        return out

    def _finish_observations(self, ids):  # the reset's: rows ids of the clean observations
        self._obs[ids] = self._noisy(self._reference_clean[ids], ids)

    def _noisy(self, obs, ids):
        if self.sensor_noise > 0.0:
            obs = obs.copy()
            for r, i in enumerate(ids):
                rng = self._rngs[int(i)]
                if rng is not None:
                    obs[r] += self._noise_std * rng.standard_normal(obs.shape[1])
        obs = np.nan_to_num(obs, nan=0.0, posinf=0.0, neginf=0.0)
        return np.clip(obs, self._obs_low, self._obs_high).astype(np.float32)

    def _record_history(self, ids):
        h = self._hist_t.shape[1]
        col = self.episode_steps[ids] % h
        eta = self.sim.eta[ids]
        self._hist_t[ids, col] = self.sim.t[ids]
        self._hist[ids, 0, col] = eta[:, 3]
        self._hist[ids, 1, col] = eta[:, 4]
        self._hist[ids, 2, col] = eta[:, 2] - self._z_eq
        self._hist[ids, 3, col] = eta[:, 5]


class _ReferenceTravel:
    """The former per-task servo-travel bookkeeping: the angle before the step, zeroed at reset."""

    def _reset_task(self, i, rng):
        if not hasattr(self, "_ref_before"):
            self._ref_before = np.zeros(self.num_envs)
        self._ref_before[i] = 0.0
        return super()._reset_task(i, rng)


class ReferenceCourseKeepingTask(_ReferenceTravel, _ReferenceStep, CourseKeepingTask):
    def _travel(self):
        return (self.rudder_angle() - self._ref_before) / (
            self._rudder.servo.max_rate * self.control_dt
        )

    def _apply_actions(self, actions):
        self._ref_before[:] = self.rudder_angle()
        cmd = self.commands["rudder_command"]
        if self.rudder_mode == "absolute":
            cmd[:] = actions[:, 0] * self.rudder_limit
        else:
            np.clip(
                cmd + actions[:, 0] * self.max_rudder_increment,
                -self.rudder_limit,
                self.rudder_limit,
                out=cmd,
            )

    def _extra_observations(self):
        psi = self.sim.eta[:, 5]
        return np.column_stack(
            [
                (psi + math.pi) % (2.0 * math.pi) - math.pi,
                (self.heading_setpoint + math.pi) % (2.0 * math.pi) - math.pi,
                self.commands["rudder_command"],
                self.heading_integral,
                self._travel(),
            ]
        )

    def _reward_terms(self, stats):
        delta = self.rudder_angle()
        decay = math.exp(-self.control_dt / self.integral_time)
        self.heading_integral[:] = (
            self.heading_integral * decay
            + self.integral_time * (1.0 - decay) * self.heading_error()
        )
        return {
            "heading": self.heading_term(self.heading_weight, self.heading_scale),
            "rudder": -self.rudder_weight * (delta / self.rudder_limit) ** 2,
            "rudder_rate": -self.rudder_rate_weight * self._travel() ** 2,
            "roll": self.roll_term(stats, self.roll_weight, self.roll_scale),
        }

    def _task_info(self, stats):
        return {"heading_error_deg": np.degrees(self.heading_error())}


class _ReferenceComfort(_ReferenceStep):
    def _reward_terms(self, stats):
        self.sample = self.comfort._update_numpy(self.sim.eta, self.sim.nu)
        return self._comfort_reward_terms(stats, self.sample)


class _ReferenceSurfaceTravel(_ReferenceTravel, _ReferenceComfort):
    """The former travel of a comfort task's one commanded surface (servo ``servo``)."""

    def _travel(self):
        return (self.actuator_angles()[:, 0] - self._ref_before) / (
            self.servo.max_rate * self.control_dt
        )

    def _apply_actions(self, actions):
        self._ref_before[:] = self.actuator_angles()[:, 0]
        super()._apply_actions(actions)


class ReferenceRollStabilizationTask(_ReferenceSurfaceTravel, RollStabilizationTask):
    servo = FIN_SERVO

    def _extra_observations(self):
        return np.column_stack(
            [
                self.actuator_angles()[:, 0],
                self.sample.lateral,
                self.commands["fins_command"],
                self._travel(),
            ]
        )

    def _comfort_reward_terms(self, stats, sample):
        p = self.sim.nu[:, 3]
        effort = (self.actuator_angles()[:, 0] / self.fin_limit) ** 2
        if self.rudder_roll_stabilization:
            effort = effort + (self.rudder_angle() / self.rudder_limit) ** 2
        terms = {
            "roll": self.roll_term(stats, self.roll_weight, self.roll_scale),
            "roll_rate": -self.roll_rate_weight * (p / self.roll_rate_scale) ** 2,
            "lateral": -self.lateral_weight * (sample.lateral / self.lateral_scale) ** 2,
            "effort": -self.effort_weight * effort,
            "fin_rate": -self.fin_rate_weight * self._travel() ** 2,
        }
        if self.rudder_roll_stabilization:
            terms["heading"] = self.heading_term(self.heading_weight, self.heading_scale)
        return terms

    def _task_info(self, stats):
        return {
            "fin_angle_deg": np.degrees(self.actuator_angles()[:, 0]),
            "heading_error_deg": np.degrees(self.heading_error()),
            **self._comfort_info(),
        }


class ReferenceRideControlTask(_ReferenceSurfaceTravel, RideControlTask):
    servo = FOIL_SERVO

    def _extra_observations(self):
        return np.column_stack(
            [
                self.actuator_angles()[:, 0],
                self.sample.vertical,
                self.commands["t_foil_command"],
                self._travel(),
            ]
        )

    def _comfort_reward_terms(self, stats, sample):
        effort = (self.actuator_angles()[:, 0] / self.foil_limit) ** 2
        return {
            "vertical": -self.vertical_weight
            * (sample.weighted_vertical / self.vertical_scale) ** 2,
            "effort": -self.effort_weight * effort,
            "foil_rate": -self.foil_rate_weight * self._travel() ** 2,
        }

    def _task_info(self, stats):
        return {
            "t_foil_angle_deg": np.degrees(self.actuator_angles()[:, 0]),
            "weighted_vertical_acceleration_mps2": self.sample.weighted_vertical.copy(),
            **self._comfort_info(),
        }

    def step(self, actions):
        out = super().step(actions)
        excess = self.sample.vertical_rms > self.vertical_rms_limit
        return dataclasses.replace(out, cost=np.where(excess, 1.0, out.cost))


def _wrap(angle):
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


class ReferenceCapsizeAvoidanceTask(_ReferenceStep, CapsizeAvoidanceTask):
    def _apply_actions(self, actions):
        dev = _wrap(self.heading_setpoint + actions[:, 0] * self.heading_rate - self.voyage_course)
        np.clip(dev, -self.max_course_deviation, self.max_course_deviation, out=dev)
        self.heading_setpoint[:] = self.voyage_course + dev
        self.commands["heading"][:] = self.heading_setpoint
        lo, hi = self.shaft_fraction_range
        np.clip(self.telegraph + actions[:, 1] * self.telegraph_step, lo, hi, out=self.telegraph)
        target = self.telegraph * self._nominal_shaft_speed
        step = self.shaft_rate * self._nominal_shaft_speed * self.control_dt
        n = self.commands["shaft_speed"]
        np.clip(target, n - step, n + step, out=n)

    def _extra_observations(self):
        return np.column_stack(
            [
                _wrap(self.sim.eta[:, 5] - self.voyage_course),
                _wrap(self.heading_setpoint - self.voyage_course),
                self.telegraph,
                self._wave_period,
                self._wavelength_ratio,
                self._height_ratio,
                self._roll_period,
            ]
        )

    def _task_info(self, stats):
        return {
            "heading_error_deg": np.degrees(self.heading_error()),
            "distance_along_voyage_m": self.sim.eta[:, 0] * math.cos(self.voyage_course)
            + self.sim.eta[:, 1] * math.sin(self.voyage_course),
        }


CASES = {
    # noise, preview, increment mode, loading and speed randomisation, capsizes (3°)
    "CourseKeeping": (
        CourseKeepingTask,
        ReferenceCourseKeepingTask,
        {
            **COARSE,
            "sensor_noise": 1.0,
            "wave_preview_m": (50.0, 100.0),
            "rudder_mode": "increment",
            "gm_range_m": (0.6, 1.4),
            "speed_range_mps": (9.5, 11.0),
            "capsize_angle_deg": 3.0,
        },
    ),
    "RollStabilization": (
        RollStabilizationTask,
        ReferenceRollStabilizationTask,
        {
            **COARSE,
            "rudder_roll_stabilization": True,
            "sensor_noise": 0.5,
            "dangerous_roll_deg": 1.0,
        },
    ),
    "RideControl": (
        RideControlTask,
        ReferenceRideControlTask,
        {**COARSE, "wave_preview_m": (30.0,), "vertical_rms_limit_g": 0.002},
    ),
    "CapsizeAvoidance": (
        CapsizeAvoidanceTask,
        ReferenceCapsizeAvoidanceTask,
        {
            "hull_mesh": COARSE_MESH,
            "sea_kind": "irregular",
            "n_wave_components": 20,
            "gm_range_m": (0.3, 0.6),
            "capsize_angle_deg": 4.0,
            "dangerous_roll_deg": 2.0,
            "sensor_noise": 1.0,
        },
    ),
}


def _env_classes(task_class):
    single = type(f"{task_class.__name__}Env", (TaskEnv,), {"task_class": task_class})
    vector = type(f"{task_class.__name__}VectorEnv", (TaskVectorEnv,), {"task_class": task_class})
    return single, vector


def assert_identical(a, b, where=""):
    """Equal to the last bit: same types, dtypes, shapes and bytes (NaN and −0.0 included)."""
    assert type(a) is type(b), f"{where}: {type(a)} vs {type(b)}"
    if isinstance(a, dict):
        assert list(a) == list(b), f"{where}: keys {list(a)} vs {list(b)}"
        for key in a:
            assert_identical(a[key], b[key], f"{where}[{key!r}]")
    elif isinstance(a, tuple | list):
        assert len(a) == len(b), where
        for k, (x, y) in enumerate(zip(a, b, strict=True)):
            assert_identical(x, y, f"{where}[{k}]")
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape, f"{where}: {a!r} vs {b!r}"
        if a.dtype == object:
            for k, (x, y) in enumerate(zip(a, b, strict=True)):
                assert_identical(x, y, f"{where}[{k}]")
        else:
            assert a.tobytes() == b.tobytes(), f"{where}: {a!r} vs {b!r}"
    elif isinstance(a, float):
        assert np.float64(a).tobytes() == np.float64(b).tobytes(), f"{where}: {a!r} vs {b!r}"
    else:
        assert a == b, f"{where}: {a!r} vs {b!r}"


def _assert_same_task_state(fast, reference):
    assert_identical(fast._hist_t, reference._hist_t, "history time")
    assert_identical(fast._hist, reference._hist, "history")
    assert_identical(fast.observations(), reference.observations(), "observations")
    if hasattr(fast, "comfort"):
        for name in ("weighting", "dose", "lateral_rms", "vertical_rms"):
            assert_identical(
                vars(getattr(fast.comfort, name)), vars(getattr(reference.comfort, name))
            )
        assert_identical(fast.comfort._nu_prev, reference.comfort._nu_prev)


@pytest.mark.parametrize("case", list(CASES))
def test_single_env_steps_are_the_numpy_reference_bit_for_bit(case):
    task_class, reference_class, kwargs = CASES[case]
    fast, reference = (_env_classes(c)[0](**kwargs) for c in (task_class, reference_class))
    rng = np.random.default_rng(3)
    actions = 1.3 * rng.uniform(-1.0, 1.0, (70, *fast.action_space.shape))  # some clipped
    assert_identical(fast.reset(seed=11), reference.reset(seed=11), "reset")
    for k, a in enumerate(actions):
        out = fast.step(a.astype(np.float32))
        assert_identical(out, reference.step(a.astype(np.float32)), f"step {k}")
        if out[2] or k % 25 == 24:  # capsized, or a new episode anyway
            assert_identical(fast.reset(), reference.reset(), f"reset after {k}")
    _assert_same_task_state(fast.task, reference.task)


@pytest.mark.parametrize("case", list(CASES))
def test_vector_env_steps_are_the_numpy_reference_bit_for_bit(case):
    task_class, reference_class, kwargs = CASES[case]
    fast, reference = (
        _env_classes(c)[1](num_envs=3, max_episode_steps=23, **kwargs)
        for c in (task_class, reference_class)
    )
    rng = np.random.default_rng(4)
    actions = 1.3 * rng.uniform(-1.0, 1.0, (60, *fast.action_space.shape))
    assert_identical(fast.reset(seed=5), reference.reset(seed=5), "reset")
    for k, a in enumerate(actions):
        if k == 30:  # a partial reset
            mask = {"reset_mask": np.array([False, True, False])}
            assert_identical(fast.reset(options=mask), reference.reset(options=mask), "partial")
        out = fast.step(a.astype(np.float32))
        assert_identical(out, reference.step(a.astype(np.float32)), f"step {k}")
    _assert_same_task_state(fast.task, reference.task)


# =============================================================================================
# the kernels against the NumPy functions they stand for
# =============================================================================================
def _awkward(rng, n):
    """Values with NaN, ±inf, ±0 and entries beyond ±1 and on the bounds."""
    x = rng.uniform(-2.0, 2.0, n)
    special = [np.nan, np.inf, -np.inf, 0.0, -0.0, 1.0, -1.0]
    x[rng.integers(0, n, n // 4)] = rng.choice(special, n // 4)
    x[::7] = -0.0
    x[3::11] = 0.0
    return x


def test_finish_kernel_is_clip_of_nan_to_num_as_float32():
    rng = np.random.default_rng(0)
    n_rows, width = 9, 8
    clean = _awkward(rng, n_rows * width).reshape(n_rows, width)
    draws = _awkward(rng, n_rows * width).reshape(n_rows, width)
    low = np.array([-1.0, 0.0, -0.5, -np.pi, 0.0, -30.0, -1.0, -0.0], np.float32)
    high = np.array([1.0, 20.0, 0.5, np.pi, 0.0, 30.0, 0.0, 1.0], np.float32)
    std = np.abs(rng.standard_normal(width))
    ids = np.array([0, 2, 3, 5, 8])
    rows = np.array([True, False, True, True, False])
    for noisy in (False, True):
        x = clean[ids].copy()
        if noisy:
            x[rows] += std * draws[: ids.size][rows]
        expected = np.clip(np.nan_to_num(x, nan=0.0, posinf=0.0, neginf=0.0), low, high)
        out = np.full((n_rows, width), 7.0, np.float32)
        _finish_observations_kernel(
            clean, ids, noisy, rows, draws, std, low.astype(float), high.astype(float), out
        )
        assert_identical(out[ids], expected.astype(np.float32))
        assert np.all(np.delete(out, ids, axis=0) == 7.0)


def test_clip_into_is_np_clip():
    rng = np.random.default_rng(1)
    x = _awkward(rng, 400)
    for low, high in ((-1.0, 1.0), (0.0, 1.0), (-1.0, -0.0), (-0.0, 0.0)):
        out = np.empty_like(x)
        clip_into(x, low, high, out)
        assert_identical(out, np.clip(x, low, high))
    low, high = _awkward(rng, 400), _awkward(rng, 400)
    low, high = np.minimum(low, high), np.maximum(low, high)
    out = x.copy()
    clip_into(out, low, high, out)  # in place
    assert_identical(out, np.clip(x, low, high))


def test_validate_actions_clips_like_np_clip():
    rng = np.random.default_rng(2)
    x = rng.uniform(-3.0, 3.0, 60)
    x[::5] = -0.0
    x[1::5] = rng.choice([-1.0, 1.0], 12)
    out = validate_actions(x.astype(np.float32).reshape(30, 2), (30, 2))
    assert_identical(out, np.clip(x.astype(np.float32).astype(float).reshape(30, 2), -1.0, 1.0))
    assert not np.shares_memory(validate_actions(out, (30, 2)), out)


def test_wrap_kernel_matches_numpy_remainder():
    from ship_gym.envs.ship_task import _heading_observations_kernel

    rng = np.random.default_rng(5)
    psi = np.concatenate([rng.standard_normal(500) * s for s in (1e-6, 1.0, 10.0, 1e4)])
    psi[::13] = np.pi * rng.integers(-4, 5, psi[::13].size)
    psi[::17] = -0.0
    setpoint = psi[::-1].copy()
    out = np.empty((psi.size, 3))
    for course in (0.0, 0.7):
        _heading_observations_kernel(psi, setpoint, course, psi, out)
        assert_identical(out[:, 0], (psi - course + math.pi) % _TWO_PI - math.pi)
        assert_identical(out[:, 1], (setpoint - course + math.pi) % _TWO_PI - math.pi)


def test_comfort_kernel_is_the_numpy_update():
    rng = np.random.default_rng(6)
    n, dt = 5, 0.25
    fast, reference = (
        PassengerComfort(n, dt, (40.0, -8.0, -12.0), rms_time_constant=20.0) for _ in range(2)
    )
    nu0 = rng.standard_normal((n, 6))
    for comfort in (fast, reference):
        comfort.reset(np.arange(n), nu0)
    for k in range(40):
        eta = rng.standard_normal((n, 6)) * [100.0, 100.0, 2.0, 0.3, 0.1, 3.0]
        nu = rng.standard_normal((n, 6)) * [10.0, 1.0, 1.0, 0.1, 0.05, 0.02]
        if k == 20:
            for comfort in (fast, reference):
                comfort.reset([1, 3], nu[[1, 3]] * 0.5)
        a, b = fast.update(eta, nu), reference._update_numpy(eta, nu)
        for name in ("lateral", "vertical", "weighted_vertical", "lateral_rms", "vertical_rms"):
            assert_identical(getattr(a, name), np.ascontiguousarray(getattr(b, name)), name)
        assert_identical(a.msdv, b.msdv)
    assert_identical(fast.weighting.state, reference.weighting.state)
    assert_identical(fast.dose.dose_squared, reference.dose.dose_squared)
