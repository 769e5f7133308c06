"""Train a stable-baselines3 agent on a ship_gym environment from a TOML configuration.

Configuration (a TOML file, or the name of one shipped in :mod:`ship_gym.agents.configs`, e.g.
``ppo_roll_one_dof``; every key except ``env.id`` has a default)::

    [env]
    id = "ship_gym/RollOneDOF-v0"
    n_envs = 8                    # parallel episodes
    vectorization = "vector"      # "vector": our batched env via ship_gym.envs.sb3 (one call
                                  #   steps all episodes); "dummy": SB3 DummyVecEnv of single envs
    normalize = false             # wrap in SB3 VecNormalize (observations and rewards)
    [env.kwargs]                  # the environment's keyword arguments (physics, rewards)
    forcing_amplitude = [0.02, 0.05]

    [algorithm]
    name = "PPO"                  # PPO, SAC, TD3, A2C or DDPG
    policy = "MlpPolicy"
    [algorithm.hyperparameters]   # keyword arguments of the algorithm
    n_steps = 256
    [algorithm.policy_kwargs]     # e.g. net_arch = [64, 64]

    [training]
    total_timesteps = 200_000
    seed = 0
    output_dir = "runs/ppo_roll_one_dof"
    progress_bar = true           # SB3's tqdm + rich bar
    tensorboard = true            # logs under <output_dir>/tensorboard
    device = "cpu"
    torch_threads = 1             # optional: torch CPU threads (small MLPs: 1 is fastest and
                                  #   leaves the cores to the environment)

    [residual]                    # optional: learn a correction of a classical controller,
    baseline = "pid"              #   a = clip(a_pid + scale · a_learned)
    scale = 0.5                   #   (ship_gym.agents.residual; [residual.gains] overrides)

    [validation]                  # optional: deterministic evaluation during training
    every = 50_000                #   [time steps] on episodes of seeds first_seed … + episodes − 1
    episodes = 8                  #   (ship_gym.agents.validation); keep_best = true makes
    first_seed = 5000             #   model.zip the checkpoint of best validation return

    [safe]                        # optional: constrained RL (PPO-Lagrangian), one budget:
    cost_limit = 5.0              #   expected episode cost info["cost"] [control steps], or
                                  #   effort_limit = 0.25: RMS of the applied action [-],
                                  #   or = "fins": that baseline's effort (measured first)
    lagrangian_lr = 0.05          # multiplier step; also lambda_init = 0, lambda_max = 100

A relative ``output_dir`` (or ``--output``) is taken from the working directory, whether the config
is a file or a shipped name. The run directory receives ``model.zip``, ``config.toml`` (a copy of
the configuration actually used, with command-line overrides), ``vecnormalize.npz`` (the observation
statistics as plain arrays, read without pickle) when ``normalize`` is on, the tensorboard logs,
``progress.csv`` (the learning curve: after every rollout the time steps, wall time, mean return,
length and cost of the last 100 episodes, and λ) and ``summary.json`` (time steps, wall time,
steps/s, last mean episode return and cost, final λ), and ``residual.json`` (the baseline with all
its gains) for a residual run. With a ``[validation]`` table it also gets ``validation.csv`` (the
deterministic policy's evaluations) and, with ``keep_best``, ``model.zip`` (and
``vecnormalize.npz``) is the best evaluated checkpoint, ``final_model.zip``
(``final_vecnormalize.npz``) the last. With a ``[safe]`` table the reward is shaped by a Lagrange
multiplier on the cost or on the action's mean square (:mod:`ship_gym.agents.lagrangian`), and the
validation chooses among the checkpoints within the budget. All files are written atomically. The
SHA-256 of every model saved is recorded in this installation's trust folder
(:func:`ship_gym.envs.policy_trust.record_trusted_policy`), so that loading it needs no opt-in
(loading an SB3 model runs code from the file: ``docs/security.md``).
:func:`ship_gym.agents.residual.load_agent_policy` reads the directory back.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import time
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ship_gym.agents.configs import find_config
from ship_gym.agents.lagrangian import SAFE_KEYS, SafeConfig, safe_config
from ship_gym.agents.residual import ResidualConfig, residual_config
from ship_gym.agents.validation import (
    BEST,
    FINAL,
    VALIDATION_RUN_FILES,
    ValidationConfig,
    checkpoint_files,
    validation_config,
)

__all__ = ["TrainConfig", "load_config", "make_training_env", "train"]

from ship_gym.envs.saved_policies import ALGORITHMS

VECTORIZATIONS = ("vector", "dummy")

POLICIES = ("MlpPolicy",)
"""The SB3 policy classes a config may name: every ship_gym observation is a flat vector."""

MAX_TIMESTEPS = 10**10
"""Largest ``total_timesteps`` accepted (≈ 3 years of a 100 steps/s run)."""

# [algorithm.hyperparameters] checked at read time: (kind, low, low included, high, high incl.)
_HYPERPARAMETER_RANGES: dict[str, tuple[str, float, bool, float, bool]] = {
    "n_steps": ("int", 1, True, 10**8, True),
    "batch_size": ("int", 2, True, 10**8, True),
    "n_epochs": ("int", 1, True, 10**5, True),
    "buffer_size": ("int", 1, True, 10**9, True),
    "learning_starts": ("int", 0, True, 10**10, True),
    "gradient_steps": ("int", -1, True, 10**6, True),
    "policy_delay": ("int", 1, True, 10**6, True),
    "stats_window_size": ("int", 1, True, 10**6, True),
    "gamma": ("real", 0.0, False, 1.0, True),
    "gae_lambda": ("real", 0.0, True, 1.0, True),
    "tau": ("real", 0.0, False, 1.0, True),
    "learning_rate": ("real", 0.0, False, 10.0, True),
    "clip_range": ("real", 0.0, False, 10.0, True),
    "vf_coef": ("real", 0.0, True, 1e6, True),
    "max_grad_norm": ("real", 0.0, False, 1e12, True),
    "target_kl": ("real", 0.0, False, 1e6, True),
    "target_policy_noise": ("real", 0.0, True, 1e6, True),
    "target_noise_clip": ("real", 0.0, True, 1e6, True),
}


def _number_ok(value: Any, kind: str, bounds: tuple[float, bool, float, bool]) -> bool:
    """Whether a TOML value is an int (``kind == "int"``; not a bool) or a finite real in the
    interval ``bounds`` = (low, low included, high, high included)."""
    import math

    if isinstance(value, bool) or not isinstance(value, int | float):
        return False
    if kind == "int" and not isinstance(value, int):
        return False
    if not math.isfinite(value):
        return False
    low, low_in, high, high_in = bounds
    return (value > low or (low_in and value == low)) and (
        value < high or (high_in and value == high)
    )


def _interval(low: float, low_in: bool, high: float, high_in: bool) -> str:
    return f"{'[' if low_in else '('}{low:g}, {high:g}{']' if high_in else ')'}"


def check_hyperparameters(algorithm: str, hyperparameters: Mapping[str, Any], n_envs: int) -> None:
    """Check ``[algorithm.hyperparameters]`` before any work, naming the key.

    Known numeric keys must lie in their range (:data:`_HYPERPARAMETER_RANGES`, e.g.
    ``algorithm.hyperparameters.batch_size`` an integer ≥ 2, ``gamma`` in (0, 1]); PPO/A2C
    need ``n_steps × env.n_envs ≥ 2``; a key the algorithm does not take is refused (when
    stable-baselines3 is installed).

    Raises
    ------
    ValueError
        Naming ``algorithm.hyperparameters.<key>``, the value and what was expected.
    """
    for key, value in hyperparameters.items():
        rule = _HYPERPARAMETER_RANGES.get(key)
        if rule is None:
            continue
        kind, *bounds = rule
        if not _number_ok(value, kind, tuple(bounds)):  # type: ignore[arg-type]
            what = "an integer" if kind == "int" else "a number"
            raise ValueError(
                f"algorithm.hyperparameters.{key} = {value!r}; expected {what} in "
                f"{_interval(*bounds)}"  # type: ignore[arg-type]
            )
    ent_coef = hyperparameters.get("ent_coef")
    if ent_coef is not None and not (
        _number_ok(ent_coef, "real", (0.0, True, 1e6, True))
        or (isinstance(ent_coef, str) and ent_coef.startswith("auto"))
    ):
        raise ValueError(
            f"algorithm.hyperparameters.ent_coef = {ent_coef!r}; expected a number >= 0 (or "
            "'auto' for SAC)"
        )
    if algorithm.upper() in ("PPO", "A2C"):
        n_steps = hyperparameters.get("n_steps", 2048 if algorithm.upper() == "PPO" else 5)
        if n_steps * n_envs < 2:
            raise ValueError(
                f"algorithm.hyperparameters.n_steps = {n_steps!r} with env.n_envs = {n_envs}: "
                "a rollout of one step; expected n_steps × n_envs >= 2"
            )
    try:
        import inspect

        import stable_baselines3
    except ImportError:  # the agents extra is missing: train() says so
        return
    cls = getattr(stable_baselines3, algorithm.upper())
    accepted = set(inspect.signature(cls.__init__).parameters) - {
        "self",
        "policy",
        "env",
        "seed",
        "device",
        "verbose",
        "tensorboard_log",
        "policy_kwargs",
        "_init_setup_model",
    }
    unknown = sorted(set(hyperparameters) - accepted)
    if unknown:
        raise ValueError(
            f"algorithm.hyperparameters.{unknown[0]}: not a {algorithm.upper()} hyperparameter; "
            f"expected some of {sorted(accepted)}"
        )


@dataclass(frozen=True)
class TrainConfig:
    """A validated training configuration (see the module docstring for the TOML layout)."""

    env_id: str
    n_envs: int = 8
    vectorization: str = "vector"
    normalize: bool = False
    env_kwargs: Mapping[str, Any] = field(default_factory=dict)
    algorithm: str = "PPO"
    policy: str = "MlpPolicy"
    hyperparameters: Mapping[str, Any] = field(default_factory=dict)
    policy_kwargs: Mapping[str, Any] = field(default_factory=dict)
    total_timesteps: int = 100_000
    seed: int = 0
    output_dir: str = "runs/run"
    progress_bar: bool = True
    tensorboard: bool = True
    device: str = "cpu"
    torch_threads: int | None = None
    safe: SafeConfig | None = None
    residual: ResidualConfig | None = None
    validation: ValidationConfig | None = None
    raw: Mapping[str, Any] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.env_id, str) or not self.env_id:
            raise ValueError(f"env.id must be a registered env id, got {self.env_id!r}")
        if isinstance(self.n_envs, bool) or not isinstance(self.n_envs, int) or self.n_envs < 1:
            raise ValueError(f"env.n_envs must be a positive integer, got {self.n_envs!r}")
        if self.vectorization not in VECTORIZATIONS:
            raise ValueError(
                f"env.vectorization must be one of {VECTORIZATIONS}, got {self.vectorization!r}"
            )
        if self.algorithm.upper() not in ALGORITHMS:
            raise ValueError(f"algorithm.name must be one of {ALGORITHMS}, got {self.algorithm!r}")
        if self.policy not in POLICIES:
            raise ValueError(
                f"algorithm.policy = {self.policy!r}; expected one of {list(POLICIES)} (the "
                "observations are flat vectors: no image or dict policy)"
            )
        if (
            isinstance(self.total_timesteps, bool)
            or not isinstance(self.total_timesteps, int)
            or not 1 <= self.total_timesteps <= MAX_TIMESTEPS
        ):
            raise ValueError(
                f"training.total_timesteps = {self.total_timesteps!r}; expected an integer in "
                f"[1, {MAX_TIMESTEPS:.0e}]"
            )
        check_hyperparameters(self.algorithm, self.hyperparameters, self.n_envs)
        if not isinstance(self.seed, int):
            raise ValueError(f"training.seed must be an integer, got {self.seed!r}")
        if self.validation is not None:
            chosen_on = set(self.validation.seeds)
            first_episodes = range(self.seed, self.seed + self.n_envs)  # SB3's rule: seed + i
            if chosen_on & set(first_episodes):
                raise ValueError(
                    f"validation seeds {self.validation.seeds[0]} … {self.validation.seeds[-1]} "
                    f"overlap the training episodes' seeds {first_episodes[0]} … "
                    f"{first_episodes[-1]} (training.seed {self.seed}, env.n_envs "
                    f"{self.n_envs}); expected validation.first_seed apart from them"
                )
        if self.torch_threads is not None and (
            not isinstance(self.torch_threads, int) or self.torch_threads < 1
        ):
            raise ValueError(
                f"training.torch_threads must be a positive integer, got {self.torch_threads!r}"
            )


_KNOWN = {
    "env": {"id", "n_envs", "vectorization", "normalize", "kwargs"},
    "algorithm": {"name", "policy", "hyperparameters", "policy_kwargs"},
    "safe": set(SAFE_KEYS),
    "residual": {"baseline", "scale", "gains"},
    "validation": {"every", "episodes", "first_seed", "keep_best"},
    "training": {
        "total_timesteps",
        "seed",
        "output_dir",
        "progress_bar",
        "tensorboard",
        "device",
        "torch_threads",
    },
}


def config_from_mapping(data: Mapping[str, Any]) -> TrainConfig:
    """Validate a parsed TOML mapping into a :class:`TrainConfig` (unknown keys → ValueError)."""
    unknown_sections = set(data) - set(_KNOWN)
    if unknown_sections:
        raise ValueError(
            f"unknown config sections {sorted(unknown_sections)}; expected {sorted(_KNOWN)}"
        )
    for section, keys in _KNOWN.items():
        extra = set(data.get(section, {})) - keys
        if extra:
            raise ValueError(
                f"unknown keys {sorted(extra)} in [{section}]; expected {sorted(keys)}"
            )
    env = data.get("env", {})
    algo = data.get("algorithm", {})
    training = data.get("training", {})
    if "id" not in env:
        raise ValueError('the config needs [env] id = "ship_gym/<Name>-vN"')
    return TrainConfig(
        env_id=env["id"],
        n_envs=env.get("n_envs", 8),
        vectorization=env.get("vectorization", "vector"),
        normalize=bool(env.get("normalize", False)),
        env_kwargs=dict(env.get("kwargs", {})),
        algorithm=str(algo.get("name", "PPO")).upper(),
        policy=algo.get("policy", "MlpPolicy"),
        hyperparameters=dict(algo.get("hyperparameters", {})),
        policy_kwargs=dict(algo.get("policy_kwargs", {})),
        total_timesteps=_integral(training.get("total_timesteps", 100_000)),
        seed=training.get("seed", 0),
        output_dir=str(training.get("output_dir", "runs/run")),
        progress_bar=bool(training.get("progress_bar", True)),
        tensorboard=bool(training.get("tensorboard", True)),
        device=str(training.get("device", "cpu")),
        torch_threads=training.get("torch_threads"),
        safe=safe_config(data["safe"]) if "safe" in data else None,
        residual=residual_config(data["residual"]) if "residual" in data else None,
        validation=validation_config(data["validation"]) if "validation" in data else None,
        raw=copy.deepcopy(dict(data)),
    )


def _integral(value: Any) -> Any:
    """An integral float (TOML ``1e6``) as int; anything else as given (then checked)."""
    if isinstance(value, float) and value.is_integer() and abs(value) <= 2**63:
        return int(value)
    return value


def load_config(path: str | Path, **overrides: Any) -> TrainConfig:
    """Read a TOML config: a file, or the name of a shipped config (``"ppo_roll_one_dof"``;
    :func:`ship_gym.agents.configs.find_config`). ``overrides`` (``total_timesteps``, ``seed``,
    ``output_dir``, ``progress_bar``, ``n_envs``, ``device``) replace the file's values when not
    None."""
    p = find_config(path)
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{p}: invalid TOML: {exc}") from None
    places = {
        "total_timesteps": "training",
        "seed": "training",
        "output_dir": "training",
        "progress_bar": "training",
        "tensorboard": "training",
        "device": "training",
        "n_envs": "env",
    }
    for key, value in overrides.items():
        if key not in places:
            raise ValueError(f"cannot override {key!r}; allowed: {sorted(places)}")
        if value is not None:
            data.setdefault(places[key], {})[key] = value
    return config_from_mapping(data)


def make_training_env(config: TrainConfig) -> Any:
    """The SB3 VecEnv of a config: batched adapter or DummyVecEnv, VecMonitor, the action's
    effort recorder (an effort budget: below the residual, so it sees the total command), the
    residual wrapper (raw observations), cost shaping, VecNormalize."""
    from stable_baselines3.common.vec_env import VecNormalize

    from ship_gym.envs.sb3 import make_sb3_vec_env

    venv = make_sb3_vec_env(
        config.env_id,
        config.n_envs,
        seed=config.seed,
        vectorization=config.vectorization,
        env_kwargs=dict(config.env_kwargs),
    )
    if config.safe is not None and config.safe.constraint == "effort":
        from ship_gym.agents.lagrangian import record_action_effort

        venv = record_action_effort(venv, config.safe.rms_floor)
    if config.residual is not None:
        from ship_gym.agents.residual import residual_vec_env

        venv = residual_vec_env(venv, config.residual, config.env_id)
    if config.safe is not None:  # r − λc, between the monitor (true returns) and the normaliser
        from ship_gym.agents.lagrangian import make_cost_shaped

        venv = make_cost_shaped(venv, config.safe.lambda_init, config.safe.info_key)
    if config.normalize:
        # the reward normaliser discounts with the algorithm's gamma (SB3 default 0.99)
        venv = VecNormalize(venv, gamma=float(config.hyperparameters.get("gamma", 0.99)))
    return venv


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{k} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise ValueError(f"cannot write {value!r} to TOML")


def dump_toml(data: Mapping[str, Any]) -> str:
    """A small TOML writer for configs (tables of scalars, arrays and inline tables)."""
    lines: list[str] = []

    def table(prefix: str, mapping: Mapping[str, Any]) -> None:
        scalars = {k: v for k, v in mapping.items() if not isinstance(v, Mapping)}
        tables = {k: v for k, v in mapping.items() if isinstance(v, Mapping)}
        if prefix:
            lines.append(f"[{prefix}]")
        lines.extend(f"{k} = {_toml_value(v)}" for k, v in scalars.items())
        lines.append("")
        for k, v in tables.items():
            table(f"{prefix}.{k}" if prefix else k, v)

    table("", data)
    return "\n".join(lines).strip() + "\n"


def learning_curve_callback() -> Any:
    """An SB3 callback recording the learning curve after every rollout: time steps, wall time
    [s], and the mean return, length and cost of the last 100 finished episodes (SB3's episode
    buffer, true rewards from the monitor), λ of a cost-shaped run (else 0). ``csv()`` gives
    the table."""
    from stable_baselines3.common.callbacks import BaseCallback

    class _Curve(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.rows: list[dict[str, float]] = []
            self._t0 = time.perf_counter()
            self._costs: list[float] = []
            self._running: Any = None

        def _on_step(self) -> bool:
            import numpy as np

            infos, dones = self.locals.get("infos", []), self.locals.get("dones")
            if dones is None:
                return True
            if self._running is None:
                self._running = np.zeros(len(dones))
            self._running += [float(info.get("cost", 0.0)) for info in infos]
            for i in np.flatnonzero(dones):
                self._costs.append(float(self._running[i]))
                self._running[i] = 0.0
            self._costs = self._costs[-100:]
            return True

        def _on_rollout_end(self) -> None:
            episodes = list(self.model.ep_info_buffer or [])
            if not episodes:
                return
            from ship_gym.agents.lagrangian import find_cost_shaped

            try:
                lam = float(find_cost_shaped(self.training_env).multiplier)
            except ValueError:  # not a cost-shaped run
                lam = 0.0
            self.rows.append(
                {
                    "timesteps": float(self.num_timesteps),
                    "wall_s": time.perf_counter() - self._t0,
                    "mean_return": sum(e["r"] for e in episodes) / len(episodes),
                    "mean_length": sum(e["l"] for e in episodes) / len(episodes),
                    "mean_cost": sum(self._costs) / len(self._costs) if self._costs else 0.0,
                    "lambda": lam,
                }
            )

        def csv(self) -> str:
            from ship_gym.io_utils import csv_text

            keys = ("timesteps", "wall_s", "mean_return", "mean_length", "mean_cost", "lambda")
            return csv_text(keys, self.rows)

    return _Curve()


def train(config: TrainConfig) -> Path:
    """Train per ``config``; return the run directory (see the module docstring for its files)."""
    import stable_baselines3
    from stable_baselines3.common.vec_env import VecNormalize

    from ship_gym.envs.policy_trust import record_trusted_policy
    from ship_gym.envs.saved_policies import save_obs_normalizer
    from ship_gym.io_utils import atomic_write, atomic_write_text

    if config.torch_threads is not None:
        import torch

        torch.set_num_threads(config.torch_threads)
    out = Path(config.output_dir)
    out.mkdir(parents=True, exist_ok=True)
    # a summary marks a finished run (the benchmark reuses such runs): an earlier run's must not
    # stand beside this run's config while this one trains
    (out / "summary.json").unlink(missing_ok=True)
    stale_statistics = [f"{p}vecnormalize.{x}" for p in ("", BEST, FINAL) for x in ("npz", "pkl")]
    for stale in (*VALIDATION_RUN_FILES, *stale_statistics):
        # nor an earlier run's checkpoints, evaluations and observation statistics
        (out / stale).unlink(missing_ok=True)
    atomic_write_text(out / "config.toml", dump_toml(config.raw))
    validation_limit = None
    if config.safe is not None:  # a baseline's effort budget is measured before training
        from ship_gym.agents.lagrangian import CALIBRATION_EPISODES, resolve_effort_budget

        safe, validation_limit = resolve_effort_budget(
            config.safe,
            config.env_id,
            config.env_kwargs,
            range(config.seed, config.seed + CALIBRATION_EPISODES),
            config.validation.seeds if config.validation is not None else None,
            progress=config.progress_bar,
        )
        config = dataclasses.replace(config, safe=safe)
    venv = make_training_env(config)
    if config.residual is not None:
        from ship_gym.agents.residual import find_residual, save_residual

        wrapper = find_residual(venv)
        save_residual(out, wrapper.baseline, wrapper.scale)
    algo_class = getattr(stable_baselines3, config.algorithm)
    kwargs = dict(config.hyperparameters)
    if config.policy_kwargs:
        kwargs["policy_kwargs"] = dict(config.policy_kwargs)
    model = algo_class(
        config.policy,
        venv,
        seed=config.seed,
        device=config.device,
        verbose=0,
        tensorboard_log=str(out / "tensorboard") if config.tensorboard else None,
        **kwargs,
    )
    callbacks = []
    if config.safe is not None:  # first: the curve records the λ of this rollout's update
        from ship_gym.agents.lagrangian import lagrange_multiplier_callback

        callbacks.append(lagrange_multiplier_callback(config.safe))
    callbacks.append(curve := learning_curve_callback())
    validation: Any = None
    if config.validation is not None:
        from ship_gym.agents.validation import validation_callback

        validation = validation_callback(
            config.validation,
            config.env_id,
            config.env_kwargs,
            out,
            limit=validation_limit,
        )
        callbacks.append(validation)
    t0 = time.perf_counter()
    try:
        model.learn(
            total_timesteps=config.total_timesteps,
            progress_bar=config.progress_bar,
            tb_log_name=config.algorithm.lower(),
            callback=callbacks,
        )
    finally:
        wall = time.perf_counter() - t0
        selected = validation is not None and validation.keeps_best
        model_file, normalizer_file = checkpoint_files(FINAL if selected else "")
        atomic_write(out / model_file, lambda p: model.save(p))
        if isinstance(venv, VecNormalize):
            atomic_write(out / normalizer_file, lambda p: save_obs_normalizer(venv, p))
        if selected:  # the best checkpoint becomes the run's model
            for best, run in zip(checkpoint_files(BEST), checkpoint_files(""), strict=True):
                if (out / best).is_file():
                    (out / best).replace(out / run)
        for saved in {checkpoint_files("")[0], model_file}:  # this installation's own models
            if (out / saved).is_file():
                record_trusted_policy(out / saved)
        atomic_write_text(out / "progress.csv", curve.csv())
        episodes = list(model.ep_info_buffer or [])
        summary = {
            "env_id": config.env_id,
            "algorithm": config.algorithm,
            "num_timesteps": int(model.num_timesteps),
            "wall_time_s": wall,
            "steps_per_s": model.num_timesteps / wall if wall > 0 else None,
            "recent_episodes": len(episodes),
            "recent_mean_return": (
                float(sum(e["r"] for e in episodes) / len(episodes)) if episodes else None
            ),
            "recent_mean_length": (
                float(sum(e["l"] for e in episodes) / len(episodes)) if episodes else None
            ),
            "recent_mean_cost": curve.rows[-1]["mean_cost"] if curve.rows else None,
            "final_lambda": curve.rows[-1]["lambda"] if curve.rows else None,
        }
        if config.safe is not None and config.safe.constraint == "effort":
            summary["effort_budget"] = {
                "baseline": config.safe.effort_baseline,
                "training_rms_action": config.safe.effort_limit,
                "validation_rms_action": validation_limit[1] if validation_limit else None,
            }
        if validation is not None and validation.best is not None:
            chosen = validation.rows[validation.best]
            summary["validation"] = {
                "seeds": [validation.seeds[0], validation.seeds[-1]],
                "evaluations": len(validation.rows),
                "model": "best" if selected else "final",
                "best_timesteps": int(chosen["timesteps"]),
                "best_mean_return": chosen["mean_return"],
                "final_mean_return": validation.rows[-1]["mean_return"],
            }
        atomic_write_text(out / "summary.json", json.dumps(summary, indent=2))
        venv.close()
    return out
