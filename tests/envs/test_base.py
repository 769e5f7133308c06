"""The generic wrappers of ship_gym.envs.base on a small analytic task.

The task: N damped oscillators x'' = -ω² x - 2ζω x' + a·u driven by the action, exactly
discretised per control step (matrix exponential), with a random initial state; an episode
terminates when |x| exceeds a limit. It has no ship in it so that the wrapper semantics
(seeding, autoreset, infos, validation) are tested alone and fast.
"""

from __future__ import annotations

import subprocess
import sys
import warnings

import numpy as np
import pytest
from gymnasium import spaces
from gymnasium.utils.env_checker import check_env as gym_check_env
from gymnasium.vector import AutoresetMode
from scipy.linalg import expm

from ship_gym.envs.base import BatchedTask, TaskEnv, TaskStep, TaskVectorEnv
from ship_gym.envs.registration import ENTRIES, REGISTERED_IDS


class OscillatorTask(BatchedTask):
    def __init__(self, num_envs: int, limit: float = 1.0, control_dt: float = 0.1) -> None:
        super().__init__(num_envs)
        if not limit > 0.0:
            raise ValueError(f"limit must be > 0 [m], got {limit!r}")
        self.limit = float(limit)
        self.control_dt = float(control_dt)
        omega, zeta, gain = 2.0, 0.05, 3.0
        a = np.array([[0.0, 1.0], [-(omega**2), -2 * zeta * omega]])
        b = np.array([[0.0], [gain]])
        big = np.zeros((3, 3))
        big[:2, :2], big[:2, 2:] = a, b
        phi = expm(big * self.control_dt)
        self._ad, self._bd = phi[:2, :2], phi[:2, 2]
        self.state = np.zeros((num_envs, 2))
        self.observation_names = ("x [m]", "x rate [m/s]")
        self.action_names = ("force (-1..1)",)
        self.observation_space = spaces.Box(-10.0, 10.0, (2,), np.float32)
        self.action_space = spaces.Box(-1.0, 1.0, (1,), np.float32)

    def reset_episodes(self, ids, rngs, options):
        for i, rng in zip(ids, rngs, strict=True):
            self.state[i] = rng.uniform(-0.5, 0.5, 2)

    def step(self, actions):
        self.state = self.state @ self._ad.T + actions[:, :1] * self._bd
        x = self.state[:, 0]
        return TaskStep(
            reward_terms={"position": -(x**2), "effort": -0.1 * actions[:, 0] ** 2},
            cost=(np.abs(x) > 0.5 * self.limit).astype(float),
            terminated=np.abs(x) > self.limit,
            info={"x": x.copy()},
        )

    def observations(self):
        return self.state.astype(np.float32)

    def reset_info(self, ids):
        return {"x0": self.state[ids, 0].copy()}


class OscillatorEnv(TaskEnv):
    task_class = OscillatorTask


class OscillatorVectorEnv(TaskVectorEnv):
    task_class = OscillatorTask


def _rollout_single(seed: int, actions: np.ndarray) -> tuple[list, list, list]:
    env = OscillatorEnv(limit=0.4)
    obs, _ = env.reset(seed=seed)
    observations, rewards, dones = [obs], [], []
    for a in actions:
        obs, r, term, _trunc, _ = env.step(a)
        observations.append(obs)
        rewards.append(r)
        dones.append(term)
        if term:
            obs, _ = env.reset()
            observations.append(obs)
    return observations, rewards, dones


def test_checkers_pass_without_warnings():
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        gym_check_env(OscillatorEnv(), skip_render_check=True)
        sb3_check_env(OscillatorEnv(), warn=True)


def test_reward_is_sum_of_terms_and_info_layout():
    env = OscillatorEnv()
    env.reset(seed=3)
    _, reward, _, truncated, info = env.step(np.array([0.7], dtype=np.float32))
    assert reward == pytest.approx(info["reward_position"] + info["reward_effort"], abs=1e-15)
    assert set(info) >= {"cost", "x", "time"} and not truncated
    assert info["time"] == pytest.approx(0.1)


@pytest.mark.parametrize("bad", [np.array([np.nan]), np.array([np.inf]), np.zeros(3)])
def test_bad_actions_raise(bad):
    env = OscillatorEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action"):
        env.step(bad)


def test_out_of_range_actions_are_clipped():
    a, b = OscillatorEnv(), OscillatorEnv()
    a.reset(seed=1), b.reset(seed=1)
    np.testing.assert_array_equal(a.step(np.array([5.0]))[0], b.step(np.array([1.0]))[0])


def test_vector_env_episode_i_is_single_env_with_seed_plus_i():
    """Autoreset included: each vector episode follows the single env (bit-identical)."""
    n, steps, seed = 4, 120, 10
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, (steps, n, 1))
    vec = OscillatorVectorEnv(num_envs=n, limit=0.4, autoreset_mode=AutoresetMode.SAME_STEP)
    obs, _ = vec.reset(seed=seed)
    vec_obs = [obs]
    for t in range(steps):
        obs, _, _, _, info = vec.step(actions[t])
        vec_obs.append((obs, info))
    n_done = 0
    for i in range(n):
        single, _, dones = _rollout_single(seed + i, actions[:, i])
        n_done += sum(dones)
        k = 1
        np.testing.assert_array_equal(vec_obs[0][i], single[0])
        for t in range(steps):
            obs_t, info_t = vec_obs[t + 1]
            if dones[t]:  # SAME_STEP: final obs in info, obs is the reset one
                np.testing.assert_array_equal(info_t["final_obs"][i], single[k])
                np.testing.assert_array_equal(obs_t[i], single[k + 1])
                k += 2
            else:
                np.testing.assert_array_equal(obs_t[i], single[k])
                k += 1
    assert n_done >= 2, "the limit was chosen so that episodes terminate (autoreset exercised)"


def test_next_step_autoreset_semantics():
    vec = OscillatorVectorEnv(num_envs=3, limit=0.3, max_episode_steps=50)
    vec.reset(seed=2)
    done_prev = np.zeros(3, bool)
    saw_reset = False
    for _ in range(200):
        obs, reward, term, trunc, info = vec.step(np.ones((3, 1)))
        if done_prev.any():
            saw_reset = True
            assert np.all(reward[done_prev] == 0.0)
            assert not term[done_prev].any() and not trunc[done_prev].any()
            assert not info["_cost"][done_prev].any()  # infos of the ignored step are masked
            # the returned observation is a fresh initial state (inside the reset box)
            assert np.all(np.abs(obs[done_prev]) <= 0.5)
        done_prev = term | trunc
    assert saw_reset


def test_truncation_by_step_counter():
    vec = OscillatorVectorEnv(num_envs=2, limit=100.0, max_episode_steps=5)
    vec.reset(seed=0)
    for k in range(1, 6):
        _, _, term, trunc, _ = vec.step(np.zeros((2, 1)))
        assert not term.any()
        assert trunc.all() == (k == 5)


def test_partial_reset_mask_and_bad_seed():
    vec = OscillatorVectorEnv(num_envs=3)
    _obs0, _ = vec.reset(seed=5)
    vec.step(np.zeros((3, 1)))
    before = vec.task.state.copy()
    _obs, info = vec.reset(options={"reset_mask": np.array([False, True, False])})
    np.testing.assert_array_equal(vec.task.state[[0, 2]], before[[0, 2]])
    assert info["_x0"].tolist() == [False, True, False]
    with pytest.raises(ValueError, match="seed"):
        vec.reset(seed=[1, 2])


def test_bad_constructor_arguments():
    with pytest.raises(ValueError, match="autoreset_mode"):
        OscillatorVectorEnv(num_envs=2, autoreset_mode="sometimes")
    with pytest.raises(ValueError, match="num_envs"):
        OscillatorVectorEnv(num_envs=0)
    with pytest.raises(ValueError, match="render_mode"):
        OscillatorEnv(render_mode="ascii")
    with pytest.raises(ValueError, match="limit"):
        OscillatorEnv(limit=-1.0)


def test_registration_in_a_fresh_interpreter():
    """``import ship_gym`` (what the ``ship_gym:`` prefix of make does) registers every id
    without importing any environment module."""
    code = (
        "import gymnasium, sys, ship_gym; "
        "spec = gymnasium.spec('ship_gym/RollOneDOF-v0'); "
        "ids = [i for i in gymnasium.registry if i.startswith('ship_gym/')]; "
        "print(len(ids), spec.max_episode_steps, 'ship_gym.envs.roll_one_dof' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    n, steps, env_loaded = out.stdout.split()
    assert int(n) == len(REGISTERED_IDS) and env_loaded == "False"
    assert int(steps) == next(e for e in ENTRIES if e.name == "RollOneDOF").max_episode_steps
