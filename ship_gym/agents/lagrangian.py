"""Constrained RL by a Lagrange multiplier (PPO-Lagrangian, any SB3 algorithm): a Safe-RL cost
budget or an actuator-effort budget.

The problem: maximise the expected return J_r(π) subject to one constraint J(π) ≤ d, either

* the **cost** constraint (``[safe] cost_limit = d``): J_c(π) = E[Σ_t c_t] the expected episode
  cost, c_t = ``info["cost"]`` of the ship envs (the fraction of the control step spent
  violating the task's safety constraints, 1 in the step that capsizes:
  :mod:`ship_gym.envs.ship_task`), so J_c is the expected time in violation [control steps]
  and d a budget of it; or
* the **effort** constraint (``[safe] effort_limit = e``): J_e(π) = E[c_t] the mean square of
  the applied action per step, c_t = mean over the action entries of clip(a_t, −1, 1)² (for a
  residual policy the total command, baseline plus correction: :func:`record_action_effort`),
  with d = e², e the allowed RMS action [-]. This is the benchmark's effort rule ("at equal or
  lower actuator effort", :mod:`ship_gym.agents.benchmark`) as a constraint: the policy learns
  the most it can do with a baseline's effort instead of being compared with it afterwards.
  As the episode RMS is the square root of the episode mean square, E[RMS] ≤ √E[c] = e
  (Jensen), so the constraint also bounds the benchmark's mean RMS action.
  ``effort_limit = "fins"`` (a baseline's name, :data:`ship_gym.agents.baselines.BASELINES`)
  makes the budget that classical controller's own effort (its per-env default gains, the
  benchmark's tuned baseline): e² is its mean square action over :data:`CALIBRATION_EPISODES`
  episodes of the training distribution, measured before training
  (:func:`resolve_effort_budget`), and the validation compares each checkpoint with the
  baseline's RMS action on the validation episodes themselves. That is the fair form of "at
  equal or lower effort": the effort of any controller depends on the seas drawn (the fins of
  RollStabilization-v2 use 0.25–0.32 RMS on different sets of 16–64 episodes), the ratio of two
  controllers' efforts on the same episodes much less (0.96 on the 16 validation and 1.07 on
  the 40 held-out episodes for one PPO checkpoint against the fins) — but enough that a policy
  held at the baseline's effort on one set of episodes may exceed it by a few per cent on
  another.

Which mean of the effort (``effort_measure``). The default, ``"mean_square"``, constrains the
mean square over all steps, so heavy seas weigh most; the benchmark compares the *mean over
episodes of each episode's RMS action* (:func:`ship_gym.agents.evaluate.summarize`), which weighs
every sea alike. The two rank controllers differently when they spend differently across seas,
and the seas differ much: on RollStabilization-v2 the fins' per-episode mean square has a
coefficient of variation of 1.2 over 512 episodes. A policy held to the fins' mean square spent
17–52 % more than the fins in the calmer half of the 40 held-out seas and 1–8 % less in the
heavier half: 0.97–1.06× their pooled RMS but 1.02–1.16× their mean RMS, the benchmark's
column. ``effort_measure = "episode_rms"`` constrains that column instead: J_e(π) =
E_episodes[RMS_ep], with the per-step cost c_t = a_t² / max(ρ_t, ρ_min), ρ_t the episode's
running RMS action up to step t (:func:`record_action_effort`), whose episode mean is
MS_ep / RMS_ep = RMS_ep when ρ_t has settled — a step of calm seas is priced higher per unit a²
than one of heavy seas, as the episode's RMS is. ρ_min = e / 2 bounds the price early in an
episode and in the calmest seas. The budget of a baseline is then its mean episode RMS on the
calibration episodes, and the multiplier's violation is (Ĵ_e / e)² − 1 (relative in mean-square
units, as for the default measure).

Its Lagrangian relaxation, max_π min_{λ≥0} J_r − λ (J − d), is solved by the two-time-scale
scheme of the Safety Gym baselines (Ray, Achiam & Amodei 2019, "Benchmarking Safe Exploration in
Deep Reinforcement Learning", §5; Stooke, Achiam & Abbeel 2020 for the multiplier update):

* the policy is trained by the unconstrained algorithm on the shaped reward r_t − λ c_t
  (:func:`make_cost_shaped`; the advantage of r − λc is A_r − λA_c, so one critic of the shaped
  reward replaces the separate cost critic of the original — exact for the returns, approximate
  for a learned value function);
* after every rollout, λ follows the constraint's violation Δ by a PID controller
  (:func:`lagrange_multiplier_callback`, :func:`update_multiplier`; Stooke, Achiam & Abbeel
  2020, "Responsive Safety in Reinforcement Learning by PID Lagrangian Methods", Alg. 2):

  - the violation: cost, Δ = Ĵ_c − d, Ĵ_c the mean cost of the episodes completed since the
    last update (λ waits while none has); effort, Δ = Ĵ_e / e² − 1, Ĵ_e the mean of c_t over
    the rollout's steps less the exploration noise's share of it (below). The effort's
    violation is relative, so the gains mean the same for any budget; λ is an extra price of
    the mean-square action in reward units per step, comparable with the envs' own
    ``effort_weight``;
  - the integral I ← clip(I + K_i Δ, 0, λ_max), K_i = ``lagrangian_lr`` (I starts at
    ``lambda_init``): projected gradient ascent on the dual, the classical update;
  - the smoothed violation Δ̄ ← α Δ̄ + (1 − α) Δ, α = ``lagrangian_smoothing`` (a rollout
    of 8 × 256 steps of 1000-step episodes sees only 8 seas, so one rollout's Δ is noisy);
  - λ = clip(I + K_p Δ̄ + K_d max(Δ̄ − Δ̄_prev, 0), 0, λ_max), K_p = ``lagrangian_kp``,
    K_d = ``lagrangian_kd``.

  With K_p = K_d = 0 (the defaults) this is the integral update alone, λ = I. The integral
  winds up: a policy that learns the price with a lag overshoots the budget, I grows past
  its equilibrium while it does, and it comes down only at K_i times the underspend
  afterwards (the residual CourseKeeping run of seed 1 kept λ ≈ 0.7 while it spent 0.78–0.91
  of its budget). The proportional term prices an excess at once, so the integral needs less
  gain and accumulates less; it releases the price as soon as the excess ends. The derivative
  acts on rising violation only (it damps an overshoot, never pushes λ below the integral's
  and proportional's price).

The exploration noise. A stochastic policy's applied action is its mean plus noise, so the
rollout's mean square exceeds the deterministic policy's (the one evaluated and deployed) by the
noise variance: ≈ s² σ² for a diagonal Gaussian of standard deviations σ whose correction is
scaled by s (s = 1, or the residual ``scale``). For the PPO/A2C Gaussian policies (state-
independent σ = exp(log_std)) the callback subtracts s² · mean(σ²) from the rollout's mean
square: exact to first order, slightly optimistic where the action clips (the clipped noise is
smaller); other policies (SAC's squashed Gaussian, gSDE) are charged their noise, which makes
the constraint conservative. For ``effort_measure = "episode_rms"`` the rollout's mean of
a²/ρ_t estimates the noisy policy's episode RMS, √(ρ² + s²σ²) for a deterministic RMS ρ, so the
estimate is √(max(mean² − s² mean(σ²), 0)). For a deterministic baseline that mean of a²/ρ_t
reads 1.4 % (the PID on CourseKeeping-v2) to 5.5 % (the fins on RollStabilization-v2) above
the true mean episode RMS over 32 episodes — the running RMS lags the wave ramp at an
episode's start — so this budget is held a few per cent conservatively. The training run's
validation (:mod:`ship_gym.agents.validation`) then checks the deterministic policy's RMS
action against e on its own seeds.

The callback logs ``safe/lambda`` and ``safe/episode_cost`` with ``safe/cost_limit``, or
``safe/effort`` (the estimated deterministic RMS action) with ``safe/effort_limit``, to SB3's
logger (tensorboard). :func:`ship_gym.agents.train.train` uses both when the config has a
``[safe]`` table (``cost_limit`` or ``effort_limit``, ``lagrangian_lr``, ``lagrangian_kp``,
``lagrangian_kd``, ``lagrangian_smoothing``, ``lambda_init``, ``lambda_max``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "CALIBRATION_EPISODES",
    "EFFORT_INFO_KEY",
    "EFFORT_MEASURES",
    "EPISODE_RMS_INFO_KEY",
    "SAFE_KEYS",
    "MultiplierState",
    "SafeConfig",
    "lagrange_multiplier_callback",
    "make_cost_shaped",
    "record_action_effort",
    "resolve_effort_budget",
    "safe_config",
    "update_multiplier",
]

EFFORT_INFO_KEY = "action_mean_square"
"""Step-info key of the applied action's mean square over its entries [-]
(:func:`record_action_effort`)."""

EPISODE_RMS_INFO_KEY = "action_rms_share"
"""Step-info key of the step's share of its episode's RMS action, a² / max(ρ_t, ρ_min) [-]
(``effort_measure = "episode_rms"``, :func:`record_action_effort`)."""

EFFORT_MEASURES = ("mean_square", "episode_rms")
"""The means of the effort a budget can constrain (module docstring)."""

CALIBRATION_EPISODES = 64
"""Episodes of the baseline measuring the training budget of ``effort_limit = "<baseline>"``."""

SAFE_KEYS = (
    "cost_limit",
    "effort_limit",
    "effort_measure",
    "lagrangian_lr",
    "lagrangian_kp",
    "lagrangian_kd",
    "lagrangian_smoothing",
    "lambda_init",
    "lambda_max",
)
"""The keys of a ``[safe]`` table."""


@dataclass(frozen=True)
class SafeConfig:
    """The ``[safe]`` table of a training config: one constraint, ``cost_limit`` or
    ``effort_limit``, and the multiplier's update.

    Attributes
    ----------
    cost_limit : float or None
        Budget d of the expected episode cost [control steps in violation] (≥ 0).
    effort_limit : float or None
        Allowed RMS of the applied action e [-] (0 < e ≤ 1; the action space is [−1, 1]).
    effort_baseline : str or None
        The baseline whose effort is the budget (``effort_limit = "fins"`` in TOML);
        :func:`resolve_effort_budget` then sets ``effort_limit`` from its measured effort.
    effort_measure : {"mean_square", "episode_rms"}
        The mean of the effort constrained (module docstring): e² bounds the mean square over
        all steps, or e the mean over episodes of the episode's RMS action.
    lagrangian_lr : float
        Integral gain K_i of the multiplier's update, its step per rollout and unit violation
        [reward / cost unit per cost unit for a cost budget; reward per unit relative violation
        for an effort budget] (> 0).
    lagrangian_kp : float
        Proportional gain K_p [units of K_i] (≥ 0; 0: the integral update alone).
    lagrangian_kd : float
        Derivative gain K_d on rising violation [units of K_i] (≥ 0).
    lagrangian_smoothing : float
        α of the exponential moving average of the violation the P and D terms see [-]
        (0 ≤ α < 1; 0: this rollout's violation).
    lambda_init : float
        Initial λ [reward / cost unit] (≥ 0).
    lambda_max : float
        Upper bound of λ [reward / cost unit] (keeps the shaped reward bounded).
    """

    cost_limit: float | None = None
    effort_limit: float | None = None
    effort_baseline: str | None = None
    effort_measure: str = "mean_square"
    lagrangian_lr: float = 0.05
    lagrangian_kp: float = 0.0
    lagrangian_kd: float = 0.0
    lagrangian_smoothing: float = 0.0
    lambda_init: float = 0.0
    lambda_max: float = 100.0

    def __post_init__(self) -> None:
        effort = self.effort_limit is not None or self.effort_baseline is not None
        if (self.cost_limit is None) == (not effort):
            raise ValueError(
                f"[safe] needs exactly one of cost_limit (an episode-cost budget, >= 0) and "
                f"effort_limit (an RMS action in (0, 1], or a baseline's name); got cost_limit "
                f"= {self.cost_limit!r}, effort_limit = "
                f"{self.effort_baseline or self.effort_limit!r}"
            )
        if self.effort_measure not in EFFORT_MEASURES or (
            self.cost_limit is not None and self.effort_measure != "mean_square"
        ):
            raise ValueError(
                f"[safe] effort_measure = {self.effort_measure!r}; expected one of "
                f"{list(EFFORT_MEASURES)}, with effort_limit"
            )

    @property
    def constraint(self) -> str:
        """``"cost"`` or ``"effort"``."""
        return "cost" if self.cost_limit is not None else "effort"

    @property
    def info_key(self) -> str:
        """The step-info key of the constrained per-step quantity c_t."""
        if self.cost_limit is not None:
            return "cost"
        return EPISODE_RMS_INFO_KEY if self.effort_measure == "episode_rms" else EFFORT_INFO_KEY

    @property
    def rms_floor(self) -> float | None:
        """ρ_min of ``effort_measure = "episode_rms"`` [-] (e / 2; None for other budgets)."""
        if self.effort_measure != "episode_rms":
            return None
        if self.effort_limit is None:
            raise ValueError(f"the effort budget of {self.effort_baseline!r} is not measured yet")
        return 0.5 * self.effort_limit

    @property
    def validation_limit(self) -> tuple[str, float]:
        """The constraint on an evaluation: (column of :mod:`ship_gym.agents.validation`'s
        table, its limit) — the mean episode cost, or the RMS action (a baseline's budget is
        measured on the validation episodes instead: :func:`resolve_effort_budget`)."""
        if self.cost_limit is not None:
            return "mean_cost", self.cost_limit
        if self.effort_limit is None:
            raise ValueError(f"the effort budget of {self.effort_baseline!r} is not measured yet")
        return "rms_action", self.effort_limit


def safe_config(table: Mapping[str, Any]) -> SafeConfig:
    """Validate a ``[safe]`` table (errors name the key as written and its value)."""
    unknown = sorted(set(table) - set(SAFE_KEYS))
    if unknown:
        raise ValueError(f"unknown keys {unknown} in [safe]; expected {sorted(SAFE_KEYS)}")
    out: dict[str, Any] = {}  # SafeConfig refuses none or both of cost_limit and effort_limit
    baseline = table.get("effort_limit")
    if isinstance(baseline, str):
        from ship_gym.agents.baselines import BASELINES

        choices = sorted(set(BASELINES) - {"zero"})
        if baseline not in choices:
            raise ValueError(
                f"[safe] effort_limit = {baseline!r}; expected an RMS action in (0, 1] or the "
                f"name of a baseline, one of {choices}"
            )
        out["effort_baseline"] = baseline
        table = {k: v for k, v in table.items() if k != "effort_limit"}
    if "effort_measure" in table:
        out["effort_measure"] = table["effort_measure"]  # SafeConfig checks it
        table = {k: v for k, v in table.items() if k != "effort_measure"}
    for key, low, low_allowed, high, high_allowed in (
        ("cost_limit", 0.0, True, math.inf, True),
        ("effort_limit", 0.0, False, 1.0, True),
        ("lagrangian_lr", 0.0, False, math.inf, True),
        ("lagrangian_kp", 0.0, True, math.inf, True),
        ("lagrangian_kd", 0.0, True, math.inf, True),
        ("lagrangian_smoothing", 0.0, True, 1.0, False),
        ("lambda_init", 0.0, True, math.inf, True),
        ("lambda_max", 0.0, False, math.inf, True),
    ):
        if key not in table:
            continue
        value = table[key]
        ok = isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)
        if (
            not ok
            or value < low
            or (value == low and not low_allowed)
            or value > high
            or (value == high and not high_allowed)
        ):
            what = f"{'>=' if low_allowed else '>'} {low:g}"
            if high < math.inf:
                what += f" and {'<=' if high_allowed else '<'} {high:g}"
            raise ValueError(f"[safe] {key} = {value!r}; expected a number {what}")
        out[key] = float(value)
    config = SafeConfig(**out)
    if config.lambda_init > config.lambda_max:
        raise ValueError(
            f"[safe] lambda_init = {config.lambda_init!r} exceeds lambda_max = "
            f"{config.lambda_max!r}"
        )
    return config


def resolve_effort_budget(
    safe: SafeConfig,
    env_id: str,
    env_kwargs: Mapping[str, Any],
    training_seeds: Sequence[int],
    validation_seeds: Sequence[int] | None,
    *,
    progress: bool = False,
) -> tuple[SafeConfig, tuple[str, float] | None]:
    """The numbers of a budget before training: (``safe`` with ``effort_limit`` set, the
    validation's limit (column, value), None without validation).

    For ``effort_limit = "<baseline>"`` the baseline (per-env default gains) runs on one episode
    per training seed: e = √(mean square action over all their steps), the quantity the
    multiplier constrains (with ``effort_measure = "episode_rms"`` its mean episode RMS
    action); with validation it also runs on the validation seeds, whose limit is
    its mean RMS action there (the column the validation compares). Other budgets pass through.
    """
    if safe.effort_baseline is None or safe.effort_limit is not None:
        return safe, (safe.validation_limit if validation_seeds is not None else None)
    from dataclasses import replace

    from ship_gym.agents.baselines import make_baseline
    from ship_gym.agents.evaluate import run_episodes, summarize

    name = safe.effort_baseline

    def baseline(env: Any) -> Any:
        return make_baseline(name, env)

    calibration = run_episodes(
        env_id, baseline, list(training_seeds), dict(env_kwargs), progress=progress,
        label=f"{name} effort budget",
    )  # fmt: skip
    if safe.effort_measure == "episode_rms":
        effort = float(summarize(calibration)["rms_action"])
    else:
        weights = calibration.lengths / np.sum(calibration.lengths)
        effort = float(np.sqrt(np.sum(weights * calibration.rms_action**2)))
    if not effort > 0.0:
        raise ValueError(
            f"[safe] effort_limit = {name!r}: the baseline used no effort on {env_id} "
            f"(seeds {training_seeds[0]} … {training_seeds[-1]}); expected a positive budget"
        )
    resolved = replace(safe, effort_limit=min(effort, 1.0))
    if validation_seeds is None:
        return resolved, None
    on_validation = run_episodes(
        env_id, baseline, list(validation_seeds), dict(env_kwargs), progress=progress,
        label=f"{name} validation effort",
    )  # fmt: skip
    return resolved, ("rms_action", float(summarize(on_validation)["rms_action"]))


def record_action_effort(venv: Any, rms_floor: float | None = None) -> Any:
    """``venv`` (an SB3 VecEnv) whose step infos carry :data:`EFFORT_INFO_KEY`: the mean over
    the action entries of clip(a, −1, 1)², a the action the wrapped env receives; with
    ``rms_floor`` = ρ_min [-] also :data:`EPISODE_RMS_INFO_KEY`, a² / max(ρ_t, ρ_min), ρ_t the
    RMS of a over the episode's steps so far, this one included (module docstring).

    Placed below a residual wrapper it sees the total command (baseline plus correction), the
    action whose effort the benchmark measures (:func:`ship_gym.agents.evaluate.run_episodes`).
    """
    from stable_baselines3.common.vec_env import VecEnvWrapper

    from ship_gym.agents.evaluate import action_mean_square

    class ActionEffortVecEnv(VecEnvWrapper):
        def __init__(self, inner: Any) -> None:
            super().__init__(inner)
            self._mean_square: NDArray = np.zeros(inner.num_envs)
            self._episode_sum = np.zeros(inner.num_envs)  # Σ a² of each running episode
            self._episode_steps = np.zeros(inner.num_envs)

        def reset(self) -> Any:
            self._episode_sum[:] = 0.0
            self._episode_steps[:] = 0.0
            return self.venv.reset()

        def step_async(self, actions: NDArray) -> None:
            a = np.asarray(actions, dtype=float).reshape(self.num_envs, -1)
            self._mean_square = action_mean_square(a)
            self.venv.step_async(actions)

        def step_wait(self) -> Any:
            obs, reward, done, infos = self.venv.step_wait()
            for info, value in zip(infos, self._mean_square, strict=True):
                info[EFFORT_INFO_KEY] = float(value)
            if rms_floor is not None:  # the episode-RMS share (only its budget needs it)
                self._episode_sum += self._mean_square
                self._episode_steps += 1.0
                running = np.sqrt(self._episode_sum / self._episode_steps)
                shares = self._mean_square / np.maximum(running, rms_floor)
                for info, share in zip(infos, shares, strict=True):
                    info[EPISODE_RMS_INFO_KEY] = float(share)
                ended = np.asarray(done, dtype=bool)  # the next step starts a new episode
                self._episode_sum[ended] = 0.0
                self._episode_steps[ended] = 0.0
            return obs, reward, done, infos

    return ActionEffortVecEnv(venv)


def make_cost_shaped(venv: Any, lambda_init: float, info_key: str = "cost") -> Any:
    """``venv`` (an SB3 VecEnv whose infos carry ``info_key``, the constrained per-step quantity
    c_t) with reward r − λ c (``CostShapedVecEnv``, built on first use so that SB3 is imported
    only then)."""
    from stable_baselines3.common.vec_env import VecEnvWrapper

    class CostShapedVecEnv(VecEnvWrapper):
        """Reward r − λ c per step; tracks Σ c of every episode (``episode_costs``) and of the
        steps since the last multiplier update (``step_cost_sum`` over ``step_count``).

        ``multiplier`` is λ (set by :func:`lagrange_multiplier_callback`); ``episode_costs``
        collects Σ c of the episodes that end, until the callback takes them.
        """

        def __init__(self, inner: Any, multiplier: float) -> None:
            super().__init__(inner)
            self.multiplier = float(multiplier)
            self.info_key = info_key
            self.episode_costs: list[float] = []
            self.step_cost_sum = 0.0
            self.step_count = 0
            self._running = np.zeros(inner.num_envs)

        def reset(self) -> Any:
            self._running[:] = 0.0
            return self.venv.reset()

        def step_wait(self) -> Any:
            obs, reward, done, infos = self.venv.step_wait()
            cost = np.array([float(info.get(self.info_key, 0.0)) for info in infos])
            self._running += cost
            self.step_cost_sum += float(cost.sum())
            self.step_count += cost.size
            for i in np.flatnonzero(done):
                self.episode_costs.append(float(self._running[i]))
                self._running[i] = 0.0
            return obs, reward - self.multiplier * cost, done, infos

    return CostShapedVecEnv(venv, lambda_init)


def find_cost_shaped(venv: Any) -> Any:
    """The cost-shaping wrapper inside a VecEnv stack (ValueError if none).

    Looked up by the wrapper's *own* attributes: SB3's wrappers forward unknown attribute reads
    to the env they wrap, so ``hasattr`` on an outer wrapper (VecNormalize) would find the
    inner one's ``multiplier`` and a write would land on the outer one, silently unused.
    """
    env = venv
    while env is not None:
        own = vars(env)
        if "episode_costs" in own and "multiplier" in own:
            return env
        env = own.get("venv")
    raise ValueError("no cost-shaping wrapper in the VecEnv stack (make_cost_shaped)")


def exploration_variance(model: Any) -> float:
    """The exploration noise's share of the applied action's mean square [-]: s² · mean(σ²)
    for a PPO/A2C diagonal-Gaussian policy of state-independent σ = exp(log_std), s the
    residual ``scale`` of a residual run (1 otherwise); 0 for other policies (module
    docstring)."""
    policy = getattr(model, "policy", None)
    log_std = getattr(policy, "log_std", None)
    if log_std is None or getattr(policy, "use_sde", False):
        return 0.0
    from ship_gym.agents.residual import find_residual

    try:
        scale = float(find_residual(model.get_env()).scale)
    except ValueError:  # not a residual run
        scale = 1.0
    variance = np.exp(2.0 * np.asarray(log_std.detach().cpu().numpy(), dtype=float))
    return scale**2 * float(np.mean(variance))


@dataclass(frozen=True)
class MultiplierState:
    """The PID multiplier's memory between updates (:func:`update_multiplier`).

    Attributes
    ----------
    integral : float
        I, the integral term in multiplier units [reward / cost unit] (0 ≤ I ≤ λ_max).
    smoothed : float or None
        Δ̄, the smoothed violation of the last update (None before the first).
    """

    integral: float
    smoothed: float | None = None


def update_multiplier(
    config: SafeConfig, state: MultiplierState, violation: float
) -> tuple[MultiplierState, float]:
    """One PID update of the multiplier (module docstring): (the new state, λ).

    ``violation`` is this rollout's Δ (Ĵ_c − d for a cost budget [control steps], Ĵ_e / e² − 1
    for an effort budget [-]).
    """
    c = config
    integral = min(max(state.integral + c.lagrangian_lr * violation, 0.0), c.lambda_max)
    if state.smoothed is None:
        smoothed, rise = violation, 0.0
    else:
        alpha = c.lagrangian_smoothing
        smoothed = alpha * state.smoothed + (1.0 - alpha) * violation
        rise = max(smoothed - state.smoothed, 0.0)
    lam = integral + c.lagrangian_kp * smoothed + c.lagrangian_kd * rise
    return MultiplierState(integral, smoothed), float(min(max(lam, 0.0), c.lambda_max))


def lagrange_multiplier_callback(config: SafeConfig) -> Any:
    """An SB3 callback updating λ after every rollout (module docstring); built on first use so
    that SB3 is imported only then. ``history`` holds (time steps, λ, Ĵ) per update, Ĵ the mean
    episode cost [control steps] or the estimated deterministic RMS action [-]."""
    from stable_baselines3.common.callbacks import BaseCallback

    class _Callback(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.config = config
            self.history: list[tuple[int, float, float]] = []
            self.state: MultiplierState | None = None  # I starts at the wrapper's λ

        def _on_step(self) -> bool:
            return True

        def _on_rollout_end(self) -> None:
            shaped = find_cost_shaped(self.training_env)
            costs, shaped.episode_costs = shaped.episode_costs, []
            total, count = shaped.step_cost_sum, shaped.step_count
            shaped.step_cost_sum, shaped.step_count = 0.0, 0
            c = self.config
            if c.cost_limit is not None:
                if not costs:  # no episode ended in this rollout: λ waits
                    return
                measured = float(np.mean(costs))
                violation = measured - c.cost_limit
                self.logger.record("safe/episode_cost", measured)
                self.logger.record("safe/cost_limit", c.cost_limit)
            else:
                assert c.effort_limit is not None
                if count == 0:
                    return
                noise = exploration_variance(self.model)
                if c.effort_measure == "episode_rms":  # Σ a²/ρ over an episode ≈ its noisy RMS
                    measured = math.sqrt(max((total / count) ** 2 - noise, 0.0))
                else:
                    measured = math.sqrt(max(total / count - noise, 0.0))
                violation = (measured / c.effort_limit) ** 2 - 1.0
                self.logger.record("safe/effort", measured)
                self.logger.record("safe/effort_limit", c.effort_limit)
            state = self.state or MultiplierState(integral=shaped.multiplier)
            self.state, shaped.multiplier = update_multiplier(c, state, violation)
            self.logger.record("safe/lambda_integral", self.state.integral)
            self.history.append((int(self.num_timesteps), shaped.multiplier, measured))
            self.logger.record("safe/lambda", shaped.multiplier)

    return _Callback()
