"""ship_gym.envs.sb3: a Gymnasium vector env (SAME_STEP autoreset) as a stable-baselines3 VecEnv.

Most tests use a tiny analytic task (a damped oscillator pushed by the action) so that they run in
milliseconds and do not depend on the ship physics; the last ones run the real RollOneDOF-v0.
"""

from collections.abc import Mapping, Sequence
from typing import Any

import gymnasium
import numpy as np
import pytest
from gymnasium import spaces
from gymnasium.vector import AutoresetMode
from gymnasium.wrappers import TimeLimit
from stable_baselines3.common.vec_env import DummyVecEnv, VecMonitor, VecNormalize

from ship_gym.envs.base import BatchedTask, TaskEnv, TaskStep, TaskVectorEnv
from ship_gym.envs.sb3 import SB3VecEnv, make_sb3_vec_env, vector_infos_to_list

MAX_STEPS = 15


class OscillatorTask(BatchedTask):
    """x'' = -x - 0.1 x' + u (explicit Euler, dt 0.2 s); capsize when |x| > 2; reward -x²."""

    def __init__(self, num_envs: int, push: float = 1.0) -> None:
        super().__init__(num_envs)
        self.observation_space = spaces.Box(-10.0, 10.0, (2,), np.float32)
        self.action_space = spaces.Box(-1.0, 1.0, (1,), np.float32)
        self.observation_names = ("x [m]", "v [m/s]")
        self.action_names = ("force (-1..1 = ±push N)",)
        self.control_dt = 0.2
        self.push = push
        self.state = np.zeros((num_envs, 2))

    def reset_episodes(self, ids, rngs: Sequence[np.random.Generator], options) -> None:
        for i, rng in zip(ids, rngs, strict=True):
            self.state[i] = [rng.uniform(-1.0, 1.0), rng.uniform(-3.0, 3.0)]

    def step(self, actions) -> TaskStep:
        x, v = self.state[:, 0].copy(), self.state[:, 1].copy()
        acc = -x - 0.1 * v + self.push * actions[:, 0]
        self.state[:, 0] = x + self.control_dt * v
        self.state[:, 1] = v + self.control_dt * acc
        x = self.state[:, 0]
        return TaskStep(
            reward_terms={"position": -(x**2)},
            cost=np.abs(x),
            terminated=np.abs(x) > 2.0,
            info={"x": x.copy()},
        )

    def observations(self):
        return np.clip(self.state, -10.0, 10.0).astype(np.float32)

    def reset_info(self, ids) -> Mapping[str, Any]:
        return {"x0": self.state[ids, 0].copy()}


class OscillatorEnv(TaskEnv):
    task_class = OscillatorTask


class OscillatorVectorEnv(TaskVectorEnv):
    task_class = OscillatorTask

    def episodes_times(self, factor: float) -> float:
        """A method for env_method: factor × number of episodes."""
        return factor * self.num_envs


def _adapter(n: int, **kwargs: Any):
    return SB3VecEnv(
        OscillatorVectorEnv(
            n, max_episode_steps=MAX_STEPS, autoreset_mode=AutoresetMode.SAME_STEP, **kwargs
        )
    )


def _dummy(n: int) -> DummyVecEnv:
    return DummyVecEnv([lambda: TimeLimit(OscillatorEnv(), MAX_STEPS) for _ in range(n)])


def _actions(n_steps: int, n: int, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(-1.0, 1.0, (n_steps, n, 1)).astype(np.float32)


def test_reset_and_step_shapes_dtypes_and_infos():
    n = 5
    venv = _adapter(n)
    assert venv.num_envs == n
    assert venv.observation_space == spaces.Box(-10.0, 10.0, (2,), np.float32)
    assert venv.action_space.shape == (1,)
    venv.seed(3)
    obs = venv.reset()
    assert obs.shape == (n, 2)
    assert obs.dtype == np.float32
    assert [set(info) for info in venv.reset_infos] == [{"x0", "time"}] * n
    obs, rewards, dones, infos = venv.step(np.zeros((n, 1), np.float32))
    assert obs.shape == (n, 2)
    assert rewards.shape == (n,)
    assert rewards.dtype == np.float32
    assert dones.shape == (n,)
    assert dones.dtype == np.bool_
    assert isinstance(infos, list)
    assert len(infos) == n
    for info in infos:
        assert {"reward_position", "cost", "x", "time", "TimeLimit.truncated"} <= set(info)
        assert isinstance(info["x"], float)
        # the reward is the sum of the (one) weighted term
        assert info["reward_position"] == pytest.approx(-(info["x"] ** 2))


def test_terminal_observation_and_time_limit_flag():
    """Capsizes (|x| > 2) and time limits both happen in 40 steps of 8 episodes; every ended
    episode carries its last observation, the returned obs is already the next episode's first."""
    n = 8
    venv = _adapter(n)
    venv.seed(0)
    venv.reset()
    seen_terminated = seen_truncated = 0
    for actions in _actions(40, n, seed=1):
        obs, _, dones, infos = venv.step(actions)
        for i in np.flatnonzero(dones):
            terminal = infos[i]["terminal_observation"]
            assert terminal.shape == (2,)
            assert terminal.dtype == np.float32
            if infos[i]["TimeLimit.truncated"]:
                seen_truncated += 1
                assert abs(terminal[0]) <= 2.0
            else:
                seen_terminated += 1
                assert abs(terminal[0]) > 2.0
            # reset in the same step: the new first observation has |x0| <= 1
            assert abs(obs[i, 0]) <= 1.0
        for i in np.flatnonzero(~dones):
            assert "terminal_observation" not in infos[i]
            assert infos[i]["TimeLimit.truncated"] is False
    assert seen_terminated > 0
    assert seen_truncated > 0


def test_adapter_reproduces_dummy_vec_env_of_single_envs_bit_for_bit():
    """Same seed → episode i of the batched adapter == env i of SB3's DummyVecEnv (seed + i),
    across automatic resets (several episodes each), to the last bit."""
    n = 4
    ours, ref = _adapter(n), _dummy(n)
    ours.seed(11)
    ref.seed(11)
    np.testing.assert_array_equal(ours.reset(), ref.reset())
    n_done = 0
    for actions in _actions(50, n, seed=2):
        o1, r1, d1, i1 = ours.step(actions)
        o2, r2, d2, i2 = ref.step(actions)
        np.testing.assert_array_equal(o1, o2)
        np.testing.assert_array_equal(r1, r2)
        np.testing.assert_array_equal(d1, d2)
        for a, b in zip(i1, i2, strict=True):
            assert a["TimeLimit.truncated"] == b["TimeLimit.truncated"]
            assert a["x"] == b["x"]
            if "terminal_observation" in b:
                np.testing.assert_array_equal(a["terminal_observation"], b["terminal_observation"])
                n_done += 1
            else:
                assert "terminal_observation" not in a
    assert n_done >= n  # the comparison went through automatic resets


def test_seed_is_applied_at_next_reset_only():
    venv = _adapter(3)
    venv.seed(5)
    first = venv.reset()
    again = venv.reset()  # no new seed: generators continue, other episodes
    assert not np.array_equal(first, again)
    assert venv.seed(5) == [5, 6, 7]
    np.testing.assert_array_equal(venv.reset(), first)


def test_get_set_attr_env_method_and_wrappers():
    venv = _adapter(3)
    assert venv.get_attr("observation_space") == [venv.observation_space] * 3
    assert venv.get_attr("observation_names", indices=[0, 2]) == [("x [m]", "v [m/s]")] * 2
    assert venv.get_attr("render_mode") == [None] * 3
    assert venv.has_attr("control_dt")
    assert not venv.has_attr("no_such_attribute")
    venv.set_attr("custom_flag", 42)
    assert venv.get_attr("custom_flag") == [42] * 3
    with pytest.raises(ValueError, match="shared"):
        venv.set_attr("custom_flag", 1, indices=[0])
    with pytest.raises(ValueError, match="out of range"):
        venv.get_attr("render_mode", indices=[3])
    assert venv.env_method("episodes_times", 2.0, indices=[1, 2]) == [6.0, 6.0]
    assert venv.env_is_wrapped(TimeLimit) == [False] * 3
    # SB3 wrappers stack on it
    wrapped = VecNormalize(VecMonitor(venv))
    wrapped.seed(0)
    assert wrapped.reset().shape == (3, 2)
    wrapped.step(np.zeros((3, 1), np.float32))


def test_next_step_autoreset_is_refused():
    with pytest.raises(ValueError, match="SAME_STEP"):
        SB3VecEnv(OscillatorVectorEnv(2, max_episode_steps=MAX_STEPS))


def test_vector_infos_to_list_respects_masks():
    infos = {"a": np.array([1.0, 2.0]), "_a": np.array([True, False]), "final_obs": None}
    assert vector_infos_to_list(infos, 2) == [{"a": 1.0}, {}]


def test_smoke_ppo_learn_on_adapter():
    from stable_baselines3 import PPO

    venv = VecMonitor(_adapter(4))
    venv.seed(0)
    model = PPO("MlpPolicy", venv, n_steps=32, batch_size=64, n_epochs=1, seed=0, device="cpu")
    model.learn(total_timesteps=256)
    assert model.num_timesteps >= 256


# ---------------------------------------------------------------------------- a real env

ROLL_ID = "ship_gym/RollOneDOF-v0"


def _require_roll_env() -> None:
    pytest.importorskip("ship_gym.envs.roll_one_dof", reason="RollOneDOF-v0 not written yet")


def test_make_sb3_vec_env_matches_dummy_on_roll_one_dof():
    """Our batched RollOneDOF through the adapter == SB3 DummyVecEnv of gymnasium.make envs."""
    _require_roll_env()
    n = 3
    ours = make_sb3_vec_env(ROLL_ID, n, seed=21, monitor=False)
    ref = make_sb3_vec_env(ROLL_ID, n, seed=21, monitor=False, vectorization="dummy")
    np.testing.assert_array_equal(ours.reset(), ref.reset())
    for actions in _actions(30, n, seed=4):
        o1, r1, d1, _ = ours.step(actions)
        o2, r2, d2, _ = ref.step(actions)
        np.testing.assert_array_equal(o1, o2)
        np.testing.assert_array_equal(r1, r2)
        np.testing.assert_array_equal(d1, d2)
    ours.close()
    ref.close()


def test_make_sb3_vec_env_bad_arguments():
    with pytest.raises(ValueError, match="n_envs"):
        make_sb3_vec_env(ROLL_ID, 0)
    with pytest.raises(ValueError, match="vectorization"):
        make_sb3_vec_env(ROLL_ID, 1, vectorization="subproc")
    assert isinstance(gymnasium.spec(ROLL_ID), gymnasium.envs.registration.EnvSpec)


def test_rgb_array_render_tiles_the_episodes():
    _require_roll_env()
    venv = make_sb3_vec_env(ROLL_ID, 2, seed=0, monitor=False, render_mode="rgb_array")
    venv.reset()
    venv.step(np.zeros((2, 1), np.float32))
    images = venv.get_images()
    assert [im.shape for im in images] == [(480, 640, 3)] * 2
    # SB3 tiles N images on a near-square grid, ceil(√N) rows: 2 images → 2 rows × 1 column
    assert venv.render().shape == (960, 640, 3)
    assert venv.render_mode == "rgb_array"
