"""ShipTask machinery: loading (G per ship), vanishing angle, wave field, preview, determinism,
and the checks every ship environment passes (parametrised over _ship_env_checks.SHIP_ENVS).

Coarse S175 mesh (24 sections) throughout; references are independent computations (a hull
built with the other KG, WaveField.elevation, a fresh interpreter, the single environment).
"""

import importlib
import inspect
import json
import subprocess
import sys

import gymnasium
import numpy as np
import pytest

from ship_gym.engine.batch import build_batch_simulator
from ship_gym.engine.ship import ShipSetup, wave_field_for
from ship_gym.envs.course_keeping import CourseKeepingEnv, CourseKeepingTask
from ship_gym.envs.docstrings import arguments_table
from ship_gym.envs.loading import loading_condition
from ship_gym.envs.registration import ENTRIES
from ship_gym.envs.seas import SeaSampler
from ship_gym.hull import load_hull, righting_arm
from ship_gym.waves.sea_state import IrregularSea

from ._ship_env_checks import (
    COARSE,
    RESET_INFO_KEYS,
    SHIP_ENVS,
    assert_bad_actions_raise,
    assert_checkers_pass_without_warnings,
    reward_terms,
    rollout,
    uniform_actions,
)

MESH = {"n_sections": 24, "n_below": 6, "n_above": 3, "n_deck": 2}


def test_vanishing_angle_of_a_raised_g_matches_the_gz_curve_of_that_loading():
    lc = loading_condition(ShipSetup(hull_overrides=MESH))
    delta = np.array([0.0, 0.3, -0.4])
    angles = np.degrees(lc.vanishing_angles(delta))
    assert angles[0] == pytest.approx(lc.vanishing_angle_deg, abs=1e-12)
    for d, angle in zip(delta[1:], angles[1:], strict=True):
        hull = load_hull("s175", **MESH, kg=9.55 + d)
        ref = righting_arm(hull, np.arange(0.0, 91.0, 5.0)).vanishing_angle_deg
        # GZ − ΔKG sin φ on a cubic spline of a 5° table vs the root of the exact curve at
        # free trim: interpolation error and the small trim coupling, well under 0.3°
        assert angle == pytest.approx(ref, abs=0.3)
    assert angles[1] < angles[0] < angles[2]  # a higher G loses range


def test_per_ship_centre_of_gravity_matches_a_hull_built_with_that_kg():
    # ship 1 of the batch gets G raised by 0.3 m; it must follow a batch built from a hull with
    # KG + 0.3 m (viscous roll damping off: its Ikeda estimate depends on KG by construction)
    base = {"speed": 0.0, "viscous_roll": False, "integrator": "holloway"}
    setup = ShipSetup(hull_overrides=MESH, **base)
    moved = ShipSetup(hull_overrides={**MESH, "kg": 9.85}, **base)
    batch = build_batch_simulator(setup, [None, None])
    ref = build_batch_simulator(moved, [None])
    cog = batch.centre_of_gravity[1] + np.array([0.0, 0.0, -0.3])
    batch.set_centre_of_gravity([1], cog)
    np.testing.assert_allclose(batch.centre_of_gravity[1], ref.hull.mass.cog, atol=1e-12)
    eta = batch.initial_eta.copy()
    eta[3] = 0.2  # heeled 11.5°
    batch.reset(eta=eta)
    ref.reset(eta=eta)
    for _ in range(300):
        batch.step()
        ref.step()
    # same equations to rounding (1e-9 relative, as the batch-vs-single tests)
    np.testing.assert_allclose(batch.eta[1], ref.eta[0], rtol=1e-9, atol=1e-10)
    # and the loading matters: ship 0 (nominal G) rolls with another period
    assert abs(batch.eta[0, 3] - batch.eta[1, 3]) > 1e-3


def test_batch_elevation_matches_the_wave_field():
    sea = IrregularSea(hs=4.0, tp=10.0, n_components=15, ramp_time=20.0)
    fields = [wave_field_for(sea, b, np.random.default_rng(s)) for s, b in ((1, 0.3), (2, 2.0))]
    batch = build_batch_simulator(ShipSetup(hull_overrides=MESH, speed=3.0), fields)
    for _ in range(50):  # t = 2.5 s: inside the ramp
        batch.step()
    x = np.array([[0.0, 50.0, -30.0], [10.0, 20.0, 30.0]])
    y = np.array([[0.0, 5.0, -7.0], [1.0, -2.0, 3.0]])
    got = batch.elevation(x, y)
    for s in range(2):
        want = fields[s].elevation(x[s], y[s], batch.t[s])
        np.testing.assert_allclose(got[s], want, rtol=1e-12, atol=1e-12)


def test_wave_preview_is_the_elevation_ahead_along_the_heading():
    env = CourseKeepingEnv(**COARSE, wave_preview_m=(0.0, 80.0))
    env.reset(seed=2)
    for _ in range(30):
        obs, *_ = env.step(np.array([0.5], dtype=np.float32))
    sim = env.task.sim
    x, y, psi = sim.eta[0, 0], sim.eta[0, 1], sim.eta[0, 5]
    want = sim.elevation(
        np.array([[x, x + 80.0 * np.cos(psi)]]), np.array([[y, y + 80.0 * np.sin(psi)]])
    )[0]
    assert env.observation_names[-2:] == (
        "wave elevation 0 m ahead [m]",
        "wave elevation 80 m ahead [m]",
    )
    np.testing.assert_allclose(obs[-2:], want, rtol=1e-6, atol=1e-6)  # float32
    assert np.ptp(obs[-2:]) > 0.0


def test_wave_preview_at_body_points_rotates_with_the_heading():
    # (x forward, y to starboard) body-frame points: earth position O + R(ψ) (x, y), NED
    points = ((0.0, 0.0), (0.0, 40.0), (-30.0, -60.0))
    env = CourseKeepingEnv(**COARSE, wave_preview_m=points)
    env.reset(seed=2)
    for _ in range(60):  # turn away from north (≈ 0.3 rad), so that the rotation matters
        obs, *_ = env.step(np.array([1.0], dtype=np.float32))
    sim = env.task.sim
    x0, y0, psi = sim.eta[0, 0], sim.eta[0, 1], sim.eta[0, 5]
    assert abs(psi) > 0.15
    c, s = np.cos(psi), np.sin(psi)
    xs = np.array([[x0 + px * c - py * s for px, py in points]])
    ys = np.array([[y0 + px * s + py * c for px, py in points]])
    assert env.observation_names[-3:] == (
        "wave elevation at body point (0, 0) m [m]",
        "wave elevation at body point (0, 40) m [m]",
        "wave elevation at body point (-30, -60) m [m]",
    )
    np.testing.assert_allclose(obs[-3:], sim.elevation(xs, ys)[0], rtol=1e-6, atol=1e-6)
    with pytest.raises(ValueError, match=r"wave_preview_m must be .* \(x, y\) body-frame points"):
        CourseKeepingEnv(**COARSE, wave_preview_m=((0.0, 1.0, 2.0),))


def test_gm_randomisation_sets_loading_and_capsize_angle():
    env = CourseKeepingEnv(**COARSE, gm_range_m=(0.6, 1.4))
    _, info = env.reset(seed=4)
    lc = env.task.loading
    assert 0.6 <= info["gm_m"] <= 1.4
    raised = lc.gm - info["gm_m"]
    assert env.task.sim.centre_of_gravity[0, 2] == pytest.approx(
        env.task.sim.hull.mass.cog[2] - raised, abs=1e-12
    )
    assert info["capsize_angle_deg"] == pytest.approx(
        np.degrees(lc.vanishing_angles(np.array([raised]))[0]), abs=1e-9
    )


def test_sensor_noise_is_seeded_and_has_the_documented_size():
    kw = {**COARSE, "sensor_noise": 1.0}
    a, _ = CourseKeepingEnv(**kw).reset(seed=9)
    b, _ = CourseKeepingEnv(**kw).reset(seed=9)
    clean, _ = CourseKeepingEnv(**COARSE).reset(seed=9)
    np.testing.assert_array_equal(a, b)
    # roll noise σ = 0.2° at sensor_noise = 1: a draw beyond 6σ has probability 2e-9
    assert 0.0 < abs(a[0] - clean[0]) < np.radians(1.2)


def test_sea_sampler_ranges_and_breaking_check():
    sampler = SeaSampler(
        kind="regular", height_range=(2.0, 3.0), period_range=(8.0, 9.0), heading_range_deg=(10, 20)
    )
    field, info = sampler.sample(np.random.default_rng(0))
    assert 2.0 <= info["wave_height_m"] <= 3.0 and 10.0 <= info["wave_heading_deg"] <= 20.0
    assert field.n_components == 1
    assert field.amplitude[0] == pytest.approx(info["wave_height_m"] / 2)
    with pytest.raises(ValueError):
        SeaSampler(kind="regular", height_range=(10.0, 20.0), period_range=(5.0, 6.0))


def test_smoke_snapshot_renders():

    env = CourseKeepingEnv(**COARSE, render_mode="rgb_array")
    env.reset(seed=0)
    for _ in range(3):
        env.step(np.zeros(1, dtype=np.float32))
    snap = env.task.snapshot(0)
    assert snap.history_time.shape == (4,) and np.all(np.isfinite(snap.profile_elevation))
    frame = env.render()
    assert frame.ndim == 3 and frame.dtype == np.uint8


_SCRIPT = """
import json, numpy as np
from ship_gym.envs.course_keeping import CourseKeepingEnv
env = CourseKeepingEnv(hull_mesh=(24, 6, 3, 2), n_wave_components=20)
obs, _ = env.reset(seed=123)
for a in np.random.default_rng(5).uniform(-1, 1, (6, 1)):
    obs, r, *_ = env.step(a)
print(json.dumps([obs.tolist(), r]))
"""


def test_seeded_rollout_identical_in_a_fresh_interpreter():
    # the capsize-avoidance env shares this machinery (its seeding is tested in-process)
    res = subprocess.run(
        [sys.executable, "-c", _SCRIPT], capture_output=True, text=True, check=True, timeout=600
    )
    other_obs, other_reward = json.loads(res.stdout.strip().splitlines()[-1])
    env = CourseKeepingEnv(**COARSE)
    obs, _ = env.reset(seed=123)
    for a in np.random.default_rng(5).uniform(-1, 1, (6, 1)):
        obs, r, *_ = env.step(a)
    assert obs.tolist() == other_obs  # bit for bit
    assert r == other_reward


# =============================================================================================
# what every ship environment must do
# =============================================================================================
@pytest.mark.parametrize("case", list(SHIP_ENVS))
def test_gymnasium_and_sb3_checkers_pass_without_warnings(case):
    assert_checkers_pass_without_warnings(SHIP_ENVS[case].env)


@pytest.mark.parametrize("case", list(SHIP_ENVS))
def test_seeded_rollouts_repeat_and_the_reward_is_the_sum_of_its_terms(case):
    env_case = SHIP_ENVS[case]
    env = env_case.env()
    actions = uniform_actions(env, 12, seed=0)
    a = rollout(env, 5, actions)
    b = rollout(env_case.env(), 5, actions)  # another instance, same seed: bit for bit
    np.testing.assert_array_equal(a.observations, b.observations)
    np.testing.assert_array_equal(a.rewards, b.rewards)
    assert not a.ended  # no default sea capsizes the S175 within 6 s
    assert RESET_INFO_KEYS <= a.reset_info.keys()
    assert all(env.observation_space.contains(o) for o in a.observations)
    assert len(env.observation_names) == env.observation_space.shape[0]
    for reward, info in zip(a.rewards, a.infos, strict=True):
        terms = reward_terms(info)
        assert tuple(terms) == env_case.reward_terms
        # summed in the same order as TaskStep.reward: equal to rounding of the float sum
        assert reward == pytest.approx(sum(terms.values()), rel=1e-12, abs=1e-15)
        assert 0.0 <= info["cost"] <= 1.0
        assert not info["capsized"] and not info["diverged"]
    # another seed, another sea (and set-point)
    other = rollout(env, 6, actions[:2])
    assert not np.array_equal(other.observations, a.observations[:3])


@pytest.mark.parametrize("n", [2, 5])
@pytest.mark.parametrize("case", list(SHIP_ENVS))
def test_vector_env_episode_i_is_the_single_env_seeded_s_plus_i(case, n):
    # the compiled engine shares no reduction between ships: bit for bit for every N (v0 on
    # the numpy path differed by 1e-14 in rewards and drifted 0.014 in CapsizeAvoidance)
    env_case = SHIP_ENVS[case]
    seed, steps = 10, 12
    vec = env_case.vector_env(n)
    actions = uniform_actions(vec, steps, seed=1)
    obs_v, info_v = vec.reset(seed=seed)
    steps_v = [vec.step(a) for a in actions]
    for i in range(n):
        single = rollout(env_case.env(), seed + i, actions[:, i])
        np.testing.assert_array_equal(obs_v[i], single.observations[0])
        for key in RESET_INFO_KEYS:
            assert info_v[key][i] == single.reset_info[key]
        for k, (obs, reward, *_rest) in enumerate(steps_v):
            if k >= len(single.rewards):
                break  # the single episode ended (the vector env autoresets)
            np.testing.assert_array_equal(obs[i], single.observations[k + 1])
            assert reward[i] == single.rewards[k]


@pytest.mark.parametrize(
    "case", ["CourseKeeping", "CapsizeAvoidance", "RollStabilization-rudder", "RideControl"]
)
def test_nan_inf_and_wrong_shape_actions_raise_value_error(case):
    assert_bad_actions_raise(SHIP_ENVS[case].env())


@pytest.mark.parametrize("entry", ENTRIES, ids=[e.name for e in ENTRIES])
def test_module_time_limit_is_the_registered_one(entry):
    module = importlib.import_module(f"ship_gym.envs.{entry.module}")
    assert module.MAX_EPISODE_STEPS == gymnasium.spec(entry.id).max_episode_steps
    assert "``MAX_EPISODE_STEPS``" in (getattr(module, f"{entry.name}Env").__doc__ or "")


@pytest.mark.parametrize("env_class", sorted({c.env_class for c in SHIP_ENVS.values()}, key=str))
def test_env_docstring_has_every_section_and_every_keyword_argument(env_class):
    doc = env_class.__doc__
    sections = [line.strip() for line in doc.splitlines() if line.strip().startswith("## ")]
    assert sections == [
        "## Description", "## Action Space", "## Observation Space", "## Rewards",
        "## Starting State", "## Episode End", "## Arguments", "## Version History",
    ]  # fmt: skip
    assert "{" not in doc  # every marker filled
    assert "| 13 | shaft speed | rev/s | ±20 |" in doc  # the common observation rows
    for name in inspect.signature(env_class.task_class.__init__).parameters:
        if name not in ("self", "num_envs"):
            assert f"    | {name} | " in doc


def test_arguments_table_takes_the_defaults_from_the_signature():
    own = {
        "initial_heading_error_deg": ("deg", "set-point range"),
        "rudder_mode": ("-", "mode"),
        "max_rudder_increment_deg": ("deg", "increment"),
        "rudder_rate_weight": ("-", "weight"),
        "heading_integral_time_s": ("s", "τ"),
    }
    with pytest.raises(ValueError, match="rudder_weight"):
        arguments_table(CourseKeepingTask, own)  # an undocumented keyword argument
    table = arguments_table(CourseKeepingTask, {**own, "rudder_weight": ("-", "weight")})
    assert table.splitlines()[2].startswith('| ship | "s175" | - | bundled ship name or ship file')
    assert (
        "| froude_number | 0.25 | - | reference speed U = Fn √(g L) (radiation, diffraction, "
        "propeller) |"
    ) in table
    assert "| hs_range_m | (3, 5) | m | significant wave height range |" in table
    assert '| rudder_mode | "absolute" | - | mode |' in table
    assert "| hull_mesh | (60, 12, 6, 4) | - |" in table
    assert "| speed_range_mps | None | m/s |" in table


def test_numerical_settings_are_checked_and_float32_follows_float64():
    # bad values name the argument; float32 wave sums stay within the float32 kernel's
    # ≈ 2e-7 relative force error over 20 control steps (bar 1e-4 of the roll excursion)
    with pytest.raises(ValueError, match="precision"):
        CourseKeepingEnv(precision="half")
    with pytest.raises(ValueError, match="num_threads"):
        CourseKeepingEnv(num_threads=0)
    rolls = {}
    for precision in ("float32", "float64"):
        env = CourseKeepingEnv(precision=precision, hs_range_m=(4.0, 4.0))
        env.reset(seed=3)
        rolls[precision] = [
            env.step(np.array([0.2], dtype=np.float32))[4]["roll_deg"] for _ in range(20)
        ]
    a, b = np.array(rolls["float32"]), np.array(rolls["float64"])
    assert np.any(a != b)  # not the same computation
    assert np.abs(a - b).max() < 1e-4 * max(np.abs(b).max(), 1.0)
