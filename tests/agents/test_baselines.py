"""ship_gym.agents.baselines: name lookup, the control laws' arithmetic and signs, and that
they control."""

import math

import gymnasium
import numpy as np
import pytest

import ship_gym  # noqa: F401  (registers the ids)
from ship_gym.agents.baselines import (
    EnvLayout,
    PIDAutopilot,
    RideController,
    RollFinController,
    ZeroAction,
    find_name,
    make_baseline,
)

ROLL_ID = "ship_gym/RollOneDOF-v0"


def _layout(obs, act, dt=0.5):
    return EnvLayout(observation_names=tuple(obs), action_names=tuple(act), control_dt=dt)


def test_find_name_exact_partial_ambiguous_missing():
    names = ["roll [rad]", "roll rate [rad/s]", "heading error [rad]"]
    assert find_name(names, ["roll"], what="x") == 0  # exact base beats "roll rate"
    assert find_name(names, ["roll rate"], what="x") == 1
    assert find_name(names, ["error"], what="x") == 2  # whole-word partial match
    with pytest.raises(ValueError, match="ambiguous"):
        find_name(["fin port [rad]", "fin starboard [rad]"], ["fin"], what="x")
    with pytest.raises(ValueError, match=r"yaw rate.*roll rate \[rad/s\]"):
        find_name(names, ["yaw rate"], what="observation 'yaw rate'")
    assert find_name(names, ["yaw rate"], what="x", required=False) is None


def test_roll_fin_law_sign_and_degree_units():
    """a = −(k_φ φ + k_p p); observations in degrees are converted to radians first."""
    rad = RollFinController(
        layout=_layout(["roll [rad]", "roll rate [rad/s]"], ["fins (-1..1 = ±25 deg)"]),
        k_roll=1.5,
        k_rate=4.0,
    )
    deg = RollFinController(
        layout=_layout(["roll rate [deg/s]", "roll [deg]"], ["fins (-1..1 = ±25 deg)"]),
        k_roll=1.5,
        k_rate=4.0,
    )
    phi, p = 0.05, -0.02
    a_rad, _ = rad.predict(np.array([phi, p]))
    a_deg, _ = deg.predict(np.array([math.degrees(p), math.degrees(phi)]))
    expected = -(1.5 * phi + 4.0 * p)
    assert a_rad.shape == (1,)
    assert a_rad.dtype == np.float32
    assert a_rad[0] == pytest.approx(expected, rel=1e-6)  # float32 output
    assert a_deg[0] == pytest.approx(expected, rel=1e-6)
    # positive roll (starboard down), no rate → negative (port-down) fin moment; clipped to ±1
    big, _ = rad.predict(np.array([[2.0, 0.0], [-2.0, 0.0]]))
    np.testing.assert_array_equal(big[:, 0], [-1.0, 1.0])


def test_pid_autopilot_terms_integral_and_episode_start():
    layout = _layout(
        ["heading error [rad]", "yaw rate [rad/s]", "roll [rad]"],
        ["rudder (-1..1 = ±35 deg)", "shaft (-1..1)"],
        dt=2.0,
    )
    pid = PIDAutopilot(layout=layout, k_p=2.0, k_d=10.0, k_i=0.1)
    obs = np.array([[0.1, 0.01, 0.0], [-0.2, 0.0, 0.0]])
    a1, state = pid.predict(obs, episode_start=np.array([True, True]))
    # integral after one step: e·dt
    np.testing.assert_allclose(state[:, 0], [0.2, -0.4])
    np.testing.assert_allclose(
        a1[:, 0], [2.0 * 0.1 - 10.0 * 0.01 + 0.1 * 0.2, 2.0 * -0.2 + 0.1 * -0.4], rtol=1e-6
    )
    np.testing.assert_array_equal(a1[:, 1], [0.0, 0.0])  # the shaft is not driven
    _, state = pid.predict(obs, state=state, episode_start=np.array([False, True]))
    np.testing.assert_allclose(state[:, 0], [0.4, -0.4])  # episode 1 restarted its integral


def test_pid_without_yaw_rate_uses_the_error_difference():
    layout = _layout(["heading error [deg]"], ["rudder command (-1..1 = ±35 deg)"], dt=1.0)
    pid = PIDAutopilot(layout=layout, k_p=0.0, k_d=5.0, k_i=0.0)
    pid.predict(np.array([1.0]), episode_start=np.array([True]))
    a, _ = pid.predict(np.array([3.0]))
    # e went from 1° to 3° in 1 s: ė = 2°/s = −r → a = −k_d r = k_d ė
    assert a[0] == pytest.approx(5.0 * math.radians(2.0), rel=1e-6)


def test_ride_controller_law():
    ride = RideController(
        layout=_layout(
            ["heave velocity [m/s]", "pitch rate [rad/s]"], ["T-foil (-1..1 = ±15 deg)"]
        ),
        k_heave=2.0,
        k_pitch=3.0,
    )
    a, state = ride.predict(np.array([0.1, 0.05]))
    assert state is None
    assert a[0] == pytest.approx(2.0 * 0.1 - 3.0 * 0.05, rel=1e-6)


def test_missing_names_and_bad_gains_raise_clearly():
    env = gymnasium.make(ROLL_ID)
    with pytest.raises(ValueError, match="heading error"):
        make_baseline("pid", env)
    with pytest.raises(ValueError, match="foil"):
        make_baseline("ride", _EnvStub(["heave velocity [m/s]", "pitch rate [rad/s]"], ["fins"]))
    with pytest.raises(ValueError, match="unknown baseline"):
        make_baseline("lqr", env)
    with pytest.raises(ValueError, match="k_rate"):
        RollFinController.for_env(env, k_rate=-1.0)
    with pytest.raises(ValueError, match="shape"):
        make_baseline("zero", env).predict(np.zeros(3))


class _EnvStub:
    def __init__(self, obs, act):
        self.observation_names = tuple(obs)
        self.action_names = tuple(act)
        self.control_dt = 0.1


def test_for_env_reads_names_from_single_vector_and_sb3_envs():
    from ship_gym.envs.sb3 import make_sb3_vec_env

    single = gymnasium.make(ROLL_ID)
    vector = gymnasium.make_vec(ROLL_ID, num_envs=2, vectorization_mode="vector_entry_point")
    sb3 = make_sb3_vec_env(ROLL_ID, 2)
    layouts = [make_baseline("fins", e).layout for e in (single, vector, sb3)]
    assert layouts[0].observation_names == layouts[1].observation_names
    assert layouts[0].observation_names == layouts[2].observation_names
    assert layouts[0].env_id == ROLL_ID
    # per-env default gains for RollOneDOF
    assert make_baseline("fins", single).k_rate == 20.0
    assert isinstance(ZeroAction.for_env(single), ZeroAction)


def test_roll_fin_baseline_prevents_capsizes_on_roll_one_dof():
    """Same 12 seas: the passive ship capsizes in about half (F up to 0.05 rad/s² at 0.85 ωₙ,
    beyond the safe-basin erosion threshold), the PD roll-moment controller in none."""
    from ship_gym.agents.evaluate import run_episodes, summarize

    seeds = range(100, 112)
    zero = summarize(run_episodes(ROLL_ID, lambda env: make_baseline("zero", env), seeds))
    fins = summarize(run_episodes(ROLL_ID, lambda env: make_baseline("fins", env), seeds))
    assert zero["capsize_rate"] >= 0.25
    assert fins["capsize_rate"] == 0.0
    assert fins["rms_roll_deg"] < 0.5 * zero["rms_roll_deg"]


def test_baseline_works_with_sb3_evaluate_policy():
    from stable_baselines3.common.evaluation import evaluate_policy

    from ship_gym.envs.sb3 import make_sb3_vec_env

    venv = make_sb3_vec_env(ROLL_ID, 2, seed=0, max_episode_steps=40)
    mean, _ = evaluate_policy(make_baseline("fins", venv), venv, n_eval_episodes=2)
    # 40 steps upright: alive bonus 1 per step minus small roll/effort penalties
    assert 30.0 < mean <= 40.0


def test_ride_baseline_lowers_passenger_vertical_acceleration_on_ride_control():
    """The tuned T-foil baseline beats zero action on RideControl-v2: seeds 0–3, 40 s each.

    Same seas for both policies (per-episode seeds), so the comparison is deterministic. Measured
    (tuning run): RMS vertical acceleration at the passenger 0.302 vs 0.323 m/s² (−6.4 %), every
    episode lower; the bound (−3 % on the mean, each episode lower) leaves room for small changes
    of the ship model while still failing for the former defaults (k_heave 1, k_pitch 10: ≈ −1 %).
    """
    from ship_gym.agents.evaluate import run_episodes

    seeds, steps = [0, 1, 2, 3], 160
    runs = {
        name: run_episodes(
            "ship_gym/RideControl-v2",
            lambda env, name=name: make_baseline(name, env),
            seeds,
            max_steps=steps,
        )
        for name in ("zero", "ride")
    }
    zero = runs["zero"].rms_vertical_acceleration_mps2
    ride = runs["ride"].rms_vertical_acceleration_mps2
    assert np.all(np.isfinite(zero)) and np.all(zero > 0.05)
    assert np.all(ride < zero)
    assert ride.mean() < 0.97 * zero.mean()
    assert runs["ride"].returns.mean() > runs["zero"].returns.mean()


# --------------------------------------------------------------------- the IMO-guidance master
CAPSIZE_ID = "ship_gym/CapsizeAvoidance-v2"


def _master(**gains):
    env = gymnasium.make(CAPSIZE_ID)
    return make_baseline("imo-guidance", env, **gains), env


def test_master_zones_are_those_of_the_guidance():
    """MSC.1/Circ.1228 §4.2 by hand, L = 175 m (1.8 √L kn = 12.25 m/s), T_W = 13 s (c = 20.30
    m/s, λ/L = 1.507), H/L = 0.06; weights 1 each, no margin, no beam zone."""
    master, env = _master(
        resonance_band=0.2, zone_margin=0.0, beam_limit_deg=90.0, zone_weights=(1, 1, 1, 1, 1)
    )
    env.close()

    def zones(u, beta_deg, t_r):
        a = np.atleast_1d
        out = master.dangerous_zones(
            a(u), a(math.radians(beta_deg)), a(13.0), a(1.507), a(0.06), a(t_r), a(175.0)
        )
        return float(out[0])

    # following seas at 13 m/s: surf-riding (13 > 12.25) and T_E = 13/(1 − 13/20.30) = 36.1 s
    # = 2.78 T_W: successive high waves; T_E/T_R = 2 (T_R 18 s): no resonance
    assert zones(13.0, 0.0, 18.0) == 2.0
    # at 12 m/s: no surf-riding; T_E = 31.8 s = 2.45 T_W still in the high-wave band
    assert zones(12.0, 0.0, 18.0) == 1.0
    # quartering 50°: outside 135° < α < 225°, no surf-riding even at 13 m/s; T_E =
    # 13/(1 − 8.36/20.30) = 22.1 s = 1.70 T_W (< 1.8), T_E/T_R = 1.23 (band 0.2): safe
    assert zones(13.0, 50.0, 18.0) == 0.0
    # head seas at 5 m/s: T_E = 13/(1 + 5/20.30) = 10.43 s; T_R = 20.9 s → parametric
    assert zones(5.0, 180.0, 20.9) == 1.0
    # … and T_R = 10.4 s → synchronous
    assert zones(5.0, 180.0, 10.4) == 1.0
    # beam zone (beam_limit 20°): steep waves 30° off the stern count, 10° do not
    master_beam, env = _master(beam_limit_deg=20.0, zone_weights=(0, 0, 0, 0, 1))  # band irrelevant
    env.close()
    beta = np.radians([10.0, 30.0, 150.0, 170.0])  # 170°, 150° are 10°, 30° off the bow
    n = beta.size
    values = master_beam.dangerous_zones(
        np.full(n, 8.0), beta, np.full(n, 13.0), np.full(n, 1.507), np.full(n, 0.06),
        np.full(n, 18.0), np.full(n, 175.0),
    )  # fmt: skip
    assert values.tolist() == [0.0, 1.0, 1.0, 0.0]


def test_master_slows_down_out_of_the_surf_riding_zone():
    """Dead following steep seas at Fn 0.33 (13.6 m/s > 12.25): the master's plan is safe and
    slower; zero action keeps the telegraph. With the zone margin of 0.2 (the tuned master has
    none and may plan at the limit itself, within the noise of its speed estimate)."""
    master, env = _master(zone_margin=0.2)
    names = env.unwrapped.observation_names
    obs, _ = env.reset(seed=0, options={"wave_heading_deg": 0.0, "initial_speed_mps": 13.6,
                                         "wave_height_m": 10.5, "wave_period_s": 13.0})  # fmt: skip
    f0 = obs[names.index("telegraph [× self-propulsion rpm]")]
    for _ in range(20):
        action, _ = master.predict(obs)
        obs, *_ = env.step(action)
    _, plan_f, per_telegraph = master._memory[0]
    assert plan_f < f0 - 0.1  # slower
    speed = per_telegraph * plan_f
    assert speed * math.cos(0.0) < 12.25  # out of the surf-riding speed
    assert obs[names.index("telegraph [× self-propulsion rpm]")] < f0
    env.close()


def test_master_capsizes_less_than_keeping_course_and_speed():
    """Held-out seeds 10 000–10 011 of CapsizeAvoidance-v2 (the tuning used seeds 0–39):
    measured 0/12 capsizes under the master against 2/12 kept on course and speed."""
    from ship_gym.agents.evaluate import run_episodes

    seeds = list(range(10_000, 10_012))
    runs = {
        name: run_episodes(CAPSIZE_ID, lambda env, name=name: make_baseline(name, env), seeds)
        for name in ("zero", "imo-guidance")
    }
    assert runs["zero"].capsized.sum() >= 2
    assert runs["imo-guidance"].capsized.sum() == 0
    assert runs["imo-guidance"].cost.mean() < runs["zero"].cost.mean()


def test_master_refuses_bad_parameters():
    env = gymnasium.make(CAPSIZE_ID)
    with pytest.raises(ValueError, match=r"resonance_band must lie in \[0, 1\)"):
        make_baseline("imo-guidance", env, resonance_band=1.5)
    with pytest.raises(ValueError, match="beam_limit_deg must lie in"):
        make_baseline("imo-guidance", env, beam_limit_deg=0.0)
    with pytest.raises(ValueError, match="zone_weights must be 5 weights"):
        make_baseline("imo-guidance", env, zone_weights=(1.0, 2.0))
    env.close()
    roll = gymnasium.make(ROLL_ID)
    with pytest.raises(ValueError, match="observation 'relative wave heading cos'"):
        make_baseline("imo-guidance", roll)
    roll.close()


def _tuned(task: str) -> dict[str, float]:
    """The point ``scripts/tune_baseline.py <task>`` chose (docs/benchmarks/<task>_baseline.json),
    which it found inside its grid."""
    import json
    from pathlib import Path

    path = Path(__file__).parents[2] / "docs" / "benchmarks" / f"{task}_baseline.json"
    record = json.loads(path.read_text(encoding="utf-8"))
    assert record["optimum_inside"], record["optimum_position"]
    return record["chosen"]


def test_roll_stabilization_fins_are_the_tuned_design_of_the_ships_own_model():
    # DEFAULT_GAINS for RollStabilization are scripts/tune_baseline.py's choice (its json:
    # ζ_add 1.5, c_add 0.8) of the design fin_stabiliser makes from the S175's linear roll model,
    # in action units (δ/25°); rounded to 4 digits, checked to 1 % (a changed model or fin would
    # move them more)
    from ship_gym.engine.ship import fin_stabiliser
    from ship_gym.envs.roll_stabilisation import FIN_LIMIT_DEG

    env = gymnasium.make("ship_gym/RollStabilization-v2")  # the per-env gains follow the id
    design = fin_stabiliser(env.unwrapped.task.setup, **_tuned("RollStabilization"))
    fins = make_baseline("fins", env)
    limit = math.radians(FIN_LIMIT_DEG)
    assert fins.k_rate == pytest.approx(design.k_rate / limit, rel=0.01)
    assert fins.k_roll == pytest.approx(design.k_roll / limit, rel=0.01)


def test_ride_control_foil_gains_are_the_tuned_design_of_the_ships_own_model():
    # DEFAULT_GAINS for RideControl: ride_controller at the tuning script's choice (its json:
    # ζ_3 0, ζ_5 0.02) in action units (δ/15°), rounded to 4 digits: 0.1 %
    from ship_gym.engine.ship import ride_controller
    from ship_gym.envs.ride_control import FOIL_LIMIT_DEG

    env = gymnasium.make("ship_gym/RideControl-v2")
    design = ride_controller(env.unwrapped.task.setup, **_tuned("RideControl"))
    ride = make_baseline("ride", env)
    limit = math.radians(FOIL_LIMIT_DEG)
    assert ride.k_heave == 0.0
    assert ride.k_pitch == pytest.approx(design.k_pitch / limit, rel=1e-3)


def test_course_keeping_pid_is_the_tuned_autopilot_of_the_ships_own_nomoto_model():
    # DEFAULT_GAINS for CourseKeeping: heading_autopilot at the tuning script's choice (its
    # json: ω_n 0.08 rad/s, ζ 0.2) in action units (δ/35°), rounded to 4 digits: 0.1 %
    from ship_gym.engine.ship import heading_autopilot
    from ship_gym.envs.env_task import RUDDER_LIMIT_DEG

    env = gymnasium.make("ship_gym/CourseKeeping-v2")
    design = heading_autopilot(env.unwrapped.task.setup, **_tuned("CourseKeeping"))
    pid = make_baseline("pid", env)
    limit = math.radians(RUDDER_LIMIT_DEG)
    assert pid.k_p == pytest.approx(design.kp / limit, rel=1e-3)
    assert pid.k_d == pytest.approx(design.kd / limit, rel=1e-3)
    assert pid.k_i == pytest.approx(design.ki / limit, rel=1e-3)


def test_capsize_master_settings_are_the_tuning_scripts_choice():
    # DEFAULT_GAINS for CapsizeAvoidance: scripts/tune_baseline.py CapsizeAvoidance's choice
    # (docs/benchmarks/capsize_master.json), found inside its grid or on a physical bound
    import json
    from pathlib import Path

    path = Path(__file__).parents[2] / "docs" / "benchmarks" / "capsize_master.json"
    record = json.loads(path.read_text(encoding="utf-8"))
    assert record["optimum_inside"], record["optimum_position"]
    env = gymnasium.make("ship_gym/CapsizeAvoidance-v2")
    master = make_baseline("imo-guidance", env)
    for key, value in record["chosen"].items():
        assert getattr(master, key) == pytest.approx(value), key
    env.close()
