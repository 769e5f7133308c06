"""ship_gym/RollOneDOF-v0: the Edith Terkol single-DOF capsize task."""

from __future__ import annotations

import hashlib
import subprocess
import sys
import warnings
from pathlib import Path

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env as gym_check_env
from gymnasium.vector import AutoresetMode
from scipy.optimize import brentq

from ship_gym.envs.roll_one_dof import (
    MAX_EPISODE_STEPS,
    RollOneDOFEnv,
    RollOneDOFTask,
    RollOneDOFVectorEnv,
)
from ship_gym.roll.equation import RollEquation

ENV_ID = "ship_gym:ship_gym/RollOneDOF-v0"


def _digest(arrays: list[np.ndarray]) -> str:
    h = hashlib.sha256()
    for a in arrays:
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()


def _rollout(seed: int, steps: int = 300, **kwargs) -> list[np.ndarray]:
    env = RollOneDOFEnv(**kwargs)
    obs, _ = env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    out = [obs]
    for _ in range(steps):
        obs, r, term, _, _ = env.step(rng.uniform(-1, 1, 1).astype(np.float32))
        out += [obs, np.array([r])]
        if term:
            obs, _ = env.reset()
            out.append(obs)
    return out


def test_checkers_pass_without_warnings():
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        gym_check_env(RollOneDOFEnv(roll_noise_std=0.01), skip_render_check=True)
        sb3_check_env(RollOneDOFEnv(), warn=True)


def test_make_and_make_vec_by_id():
    env = gymnasium.make(ENV_ID)
    assert env.spec.max_episode_steps == MAX_EPISODE_STEPS
    obs, _ = env.reset(seed=0)
    assert obs.shape == (4,) and obs.dtype == np.float32
    vec = gymnasium.make_vec(ENV_ID, num_envs=3, vectorization_mode="vector_entry_point")
    obs, _ = vec.reset(seed=0)
    assert obs.shape == (3, 4)
    env.close()
    vec.close()


def test_seeded_determinism_two_instances_and_subprocess():
    kwargs = {"roll_noise_std": 0.005, "roll_rate_noise_std": 0.002}
    a = _rollout(7, **kwargs)
    b = _rollout(7, **kwargs)
    assert _digest(a) == _digest(b)
    assert _digest(_rollout(8, **kwargs)) != _digest(a)
    repo = str(Path(__file__).resolve().parents[2])  # the fresh interpreter imports this module
    code = (
        f"import sys; sys.path.insert(0, {repo!r}); "
        "from tests.envs.test_roll_one_dof import _rollout, _digest; "
        "print(_digest(_rollout(7, roll_noise_std=0.005, roll_rate_noise_std=0.002)))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    assert out.stdout.strip().splitlines()[-1] == _digest(a)


def test_reward_is_sum_of_terms():
    env = RollOneDOFEnv(forcing_amplitude=0.06)
    env.reset(seed=1)
    rng = np.random.default_rng(1)
    for _ in range(200):
        _, reward, term, _, info = env.step(rng.uniform(-1, 1, 1))
        terms = [info[f"reward_{k}"] for k in ("alive", "roll", "roll_rate", "effort", "capsize")]
        assert reward == pytest.approx(sum(terms), abs=1e-12)
        if term:
            assert info["reward_capsize"] == -100.0 and info["reward_alive"] == 0.0
            break
    else:
        pytest.fail("expected a capsize at F = 0.06 rad/s² under random actions")


def test_observations_stay_in_space_over_long_random_rollout():
    env = RollOneDOFEnv(forcing_amplitude=(0.0, 0.1), roll_noise_std=0.02, roll_rate_noise_std=0.02)
    obs, _ = env.reset(seed=3)
    rng = np.random.default_rng(3)
    n_capsized = 0
    for k in range(3000):
        assert env.observation_space.contains(obs)
        obs, _, term, _, _ = env.step(rng.uniform(-1.5, 1.5, 1))
        n_capsized += term
        if term or k % 300 == 299:
            obs, _ = env.reset()
    assert n_capsized > 0  # the rollout visited capsizes (the extreme states)


def test_capsize_terminates_and_state_is_held():
    env = RollOneDOFEnv(forcing_amplitude=0.2)
    env.reset(seed=0)
    for _ in range(100):
        _, _, term, _, info = env.step(np.zeros(1))
        if term:
            break
    assert term and info["capsized"]
    assert abs(np.radians(info["roll_deg"])) > env.unwrapped.task.capsize_angle
    assert info["cost"] == 1.0
    held = info["roll_deg"]
    # stepping a capsized ship must not raise; it stays where it capsized, no second penalty
    _, _, term2, _, info2 = env.step(np.ones(1))
    assert term2 and info2["roll_deg"] == held and info2["reward_capsize"] == 0.0


@pytest.mark.parametrize(
    "kwargs",
    [
        {"control_dt": 0.5, "physics_dt": 0.03},
        {"control_dt": 0.0},
        {"physics_dt": float("nan")},
        {"forcing_amplitude": (0.05, 0.01)},
        {"forcing_amplitude": -0.01},
        {"forcing_amplitude": "big"},
        {"initial_roll": (-1.0, 1.0)},
        {"capsize_angle": 4.0},
        {"dangerous_roll_angle": 2.0},
        {"effort_weight": -1.0},
        {"max_moment": float("inf")},
        {"roll_equation": "edith"},
    ],
)
def test_bad_kwargs_raise(kwargs):
    with pytest.raises(ValueError):
        RollOneDOFEnv(**kwargs)


@pytest.mark.parametrize("bad", [np.array([np.nan]), np.array([np.inf]), np.zeros(2)])
def test_bad_actions_raise(bad):
    env = RollOneDOFEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action"):
        env.step(bad)


def test_bad_reset_option_raises():
    env = RollOneDOFEnv()
    with pytest.raises(ValueError, match="reset options"):
        env.reset(seed=0, options={"wave_height": 3.0})
    with pytest.raises(ValueError, match="forcing_amplitude"):
        env.reset(seed=0, options={"forcing_amplitude": float("nan")})


@pytest.mark.parametrize("mode", [AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP])
def test_vector_sub_env_i_is_single_env_seeded_s_plus_i(mode):
    """Bit-identical, autoreset after capsize and truncation included, noise on."""
    n, steps, seed, limit = 4, 160, 20, 60
    kwargs = {"forcing_amplitude": (0.03, 0.07), "roll_noise_std": 0.01}
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, (steps, n, 1))
    vec = RollOneDOFVectorEnv(num_envs=n, max_episode_steps=limit, autoreset_mode=mode, **kwargs)
    obs, _ = vec.reset(seed=seed)
    vec_obs, vec_rew = [obs], []
    for t in range(steps):
        obs, rew, _, _, _ = vec.step(actions[t])
        vec_obs.append(obs)
        vec_rew.append(rew)
    n_done = 0
    for i in range(n):
        env = gymnasium.wrappers.TimeLimit(RollOneDOFEnv(**kwargs), max_episode_steps=limit)
        obs, _ = env.reset(seed=seed + i)
        np.testing.assert_array_equal(vec_obs[0][i], obs)
        pending = False
        for t in range(steps):
            if pending and mode == AutoresetMode.NEXT_STEP:
                obs, _ = env.reset()
                reward = 0.0
                pending = False
            else:
                obs, reward, term, trunc, _ = env.step(actions[t, i])
                if term or trunc:
                    n_done += 1
                    if mode == AutoresetMode.SAME_STEP:
                        obs, _ = env.reset()
                    else:
                        pending = True
            np.testing.assert_array_equal(vec_obs[t + 1][i], obs)
            assert vec_rew[t][i] == reward
    assert n_done >= n  # every sub-env ended at least one episode (truncation at 60 steps)


def test_zero_action_follows_roll_equation():
    # Same RK4 kernel; the env folds the episode time into the forcing phase, so the two differ
    # only by the rounding of ωₑt + ε (≈ 1e-16 relative, amplified by the 500-step rollout):
    # tolerance 1e-10 rad.
    options = {
        "forcing_amplitude": 0.03,
        "forcing_phase": 0.7,
        "initial_roll": 0.2,
        "initial_roll_rate": -0.05,
    }
    env = RollOneDOFEnv(observe_forcing_phase=False)
    obs, _ = env.reset(seed=0, options=options)
    rolls = [obs[0]]
    for _ in range(400):
        obs, _, term, _, info = env.step(np.zeros(1))
        assert not term
        rolls.append(np.radians(info["roll_deg"]))
    eq = RollEquation.edith_terkol(forcing_amplitude=0.03, forcing_phase=0.7)
    tr = eq.integrate(0.2, -0.05, t_end=200.0, dt=0.05, record_every=10)
    np.testing.assert_allclose(np.array(rolls[1:]), tr.phi[1:], atol=1e-10, rtol=0)
    assert np.max(np.abs(tr.phi)) > 0.1  # a real motion was compared


def test_constant_moment_gives_static_heel():
    # F = 0, a = +1 held: the damped roll settles at the heel where the restoring equals the
    # moment, restoring(φ) = max_moment (root by brentq). The damping is light (b₁/2ωₙ ≈ 0.0035):
    # after 2000 s the oscillation about the heel is ≈ 0.075·e^(−b₁·1000) ≈ 1e-3 rad, and the
    # mean over the last 20 s (≈ 2 periods) cuts it to < 3e-4 rad. Tolerance 1e-3 rad.
    env = RollOneDOFEnv(forcing_amplitude=0.0, initial_roll=0.0, initial_roll_rate=0.0)
    env.reset(seed=0)
    rolls = []
    for _ in range(4000):
        _, _, _, _, info = env.step(np.ones(1))
        rolls.append(np.radians(info["roll_deg"]))
    eq = RollEquation.edith_terkol()
    heel = brentq(lambda x: eq.restoring(x) - 0.03, 0.0, 0.5)
    assert np.mean(rolls[-40:]) == pytest.approx(heel, abs=1e-3)
    assert heel > 0.05


def test_damping_controller_reduces_capsizes():
    # A roll-rate feedback (extra damping) must keep more ships upright than no control at
    # F = 0.045 rad/s² (zero action capsizes nearly every episode within 200 s).
    n = 64
    counts = {}
    for name in ("none", "damping"):
        vec = RollOneDOFVectorEnv(num_envs=n, forcing_amplitude=0.045)
        obs, _ = vec.reset(seed=5)
        capsized = np.zeros(n, dtype=bool)
        for _ in range(400):
            act = np.zeros((n, 1)) if name == "none" else np.clip(-obs[:, 1:2] / 0.05, -1, 1)
            obs, _, term, _, _ = vec.step(act)
            capsized |= term
        counts[name] = capsized.sum()
    assert counts["none"] > 0.9 * n
    assert counts["damping"] < 0.1 * n


def test_smoke_render_rgb_array():
    env = RollOneDOFEnv(render_mode="rgb_array")
    env.reset(seed=0)
    for _ in range(3):
        env.step(np.array([0.5]))
    frame = env.render()
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[2] == 3
    snap = env.task.snapshot(0)
    assert snap.history_time.shape == (4,) and snap.roll_limit == env.task.capsize_angle


def test_task_num_envs_validation():
    with pytest.raises(ValueError):
        RollOneDOFTask(num_envs=0)
