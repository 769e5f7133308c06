"""The polar-guidance master: its roll response against the frequency-domain solver, its risk
formula, and its decisions in seas where the answer is known."""

import math

import numpy as np
import pytest

from ship_gym.agents.roll_risk import (
    RollResponse,
    _unit_jonswap,
    roll_exceedance_probability,
)
from ship_gym.conventions import GRAVITY


@pytest.fixture(scope="module")
def response() -> RollResponse:
    return RollResponse.of_ship("s175")


@pytest.mark.parametrize("beta_deg, speed", [(60.0, 4.0), (90.0, 0.0), (150.0, 4.0)])
def test_roll_moments_match_the_solvers_one_dof_roll(response, beta_deg, speed):
    """Eq. (2) summed with the solver's complex roll RAO (free roll only, same C₄₄, I₄₄ and
    viscous damping): the kernel's tables (15° headings, 48 frequencies, bilinear in |F₄|²)
    agree within 4 % in m₀ and m₂ — the difference of interpolating |F₄|² instead of F₄."""
    from ship_gym.engine.ship import ShipSetup, database_of
    from ship_gym.hydro.rao import response_amplitude_operator

    db = database_of(ShipSetup(hull="s175", database="auto"))
    # long waves and moderate speed: every encounter frequency inside the database's range,
    # which the solver refuses to leave (the kernel holds A₄₄, B₄₄ at its ends)
    hs, tp, s, t_r, zeta = 6.0, 16.0, 8.0, 20.0, 0.05
    beta = math.radians(beta_deg)
    m0, m2 = response.spectral_moments(
        hs=hs, tp=tp, spreading_s=s, beta=beta, speed=speed, roll_period=t_r, damping_ratio=zeta
    )
    # the same sums with the solver
    w_r = 2 * math.pi / t_r
    inertia = response.inertia + float(response.added_inertia(np.array(w_r)))
    c44 = inertia * w_r**2
    stiffness = np.zeros((6, 6))
    stiffness[3, 3] = c44
    mass = np.zeros((6, 6))
    mass[3, 3] = response.inertia
    damping = np.zeros((6, 6))
    damping[3, 3] = 2 * zeta * math.sqrt(inertia * c44)
    x, energy = _unit_jonswap(3.3)
    w = 2 * math.pi / tp * x
    theta = (np.arange(12) + 0.5) * (2 * math.pi / 12) - math.pi
    spread = np.abs(np.cos(0.5 * theta)) ** (2 * s)
    spread /= spread.sum()
    ref0 = ref2 = 0.0
    for th, d in zip(theta, spread, strict=True):
        b = abs((beta + th + math.pi) % (2 * math.pi) - math.pi)  # |ξ₄(−β)| = |ξ₄(β)|
        xi = response_amplitude_operator(
            db, omega=w, heading=b, forward_speed=speed, free_dofs=("Roll",),
            hull_hydrostatic_stiffness=stiffness, mass_matrix=mass, extra_damping=damping,
            speed_terms="none",
        )  # fmt: skip
        w_e = np.abs(w - w**2 * speed * math.cos(b) / GRAVITY)
        r = np.abs(xi[:, 3]) ** 2 * hs**2 * energy * d
        ref0 += r.sum()
        ref2 += (r * w_e**2).sum()
    assert m0 == pytest.approx(ref0, rel=0.04)
    assert m2 == pytest.approx(ref2, rel=0.04)
    # and the JONSWAP energy of the band is nearly all of Hs²/16 (0.6 … 2.5 ωp)
    assert energy.sum() == pytest.approx(1 / 16, rel=0.05)


def test_exceedance_probability_limits():
    """Eq. (3): P → 0 as φ_c/σ grows, → 1 over a long exposure, and P = 1 − e^{−T/T_z · e^{−1/2}}
    at φ_c = σ (with T_z = 2π √(m₀/m₂))."""
    m0, m2 = np.array(0.01), np.array(0.01 * 0.3**2)  # σ = 0.1 rad, T_z = 2π/0.3 s
    tz = 2 * math.pi / 0.3
    assert roll_exceedance_probability(m0, m2, 0.1, 100.0) == pytest.approx(
        1 - math.exp(-100.0 / tz * math.exp(-0.5))
    )
    assert roll_exceedance_probability(m0, m2, 1.0, 3600.0) < 1e-15
    assert roll_exceedance_probability(m0, m2, 0.2, 1e7) == pytest.approx(1.0)


def _master_and_obs(gains=None, **sea):
    import gymnasium as gym

    import ship_gym  # noqa: F401
    from ship_gym.agents.baselines import make_baseline

    env = gym.make_vec(
        "ship_gym/HeavyWeather-v0", num_envs=1, vectorization_mode="vector_entry_point",
        hull_mesh=(24, 6, 3, 2), n_wave_components=20, **sea,
    )  # fmt: skip
    obs, _ = env.reset(seed=0)
    master = make_baseline("polar", env, **(gains or {}))
    return env, master, obs, env.unwrapped.observation_names


def test_polar_master_keeps_course_and_speed_in_a_gentle_sea():
    env, master, obs, _ = _master_and_obs(
        height_ratio_range=(0.02, 0.02), gm_range_m=(1.0, 1.0), wave_heading_range_deg=(150, 150)
    )
    action, _ = master.predict(obs)
    assert action[0, 0] == pytest.approx(0.0, abs=1e-6)  # on the voyage course
    assert action[0, 1] > 0.0  # full ahead (telegraph above the service rpm)
    env.close()


def test_polar_master_avoids_resonant_quartering_sea_roll():
    """Stern-quartering seas (β = 45°, λp = 1.7 L, Hs = 0.045 L) with a loading whose roll period
    (GM 0.8 m: T_R ≈ 20 s) meets the encounter period at service speed: the linear roll response
    alone (σ_φ ≈ 17° at ζ_v 0.05) makes keeping course and speed dangerous; the master turns or
    slows."""
    env, master, obs, _ = _master_and_obs(
        {"damping_ratio": 0.06, "risk_limit": 0.03},
        height_ratio_range=(0.045, 0.045),
        wavelength_ratio_range=(1.7, 1.7),
        wave_heading_range_deg=(45, 45),
        gm_range_m=(0.8, 0.8),
    )
    action, _ = master.predict(obs)
    assert abs(action[0, 0]) * 135.0 > 10.0 or action[0, 1] < 0.0
    env.close()
