"""Deterministic evaluation during training on validation seeds, and the choice of checkpoint.

The learning curve of :mod:`ship_gym.agents.train` (``progress.csv``) averages the returns of the
*stochastic* training policy; for the tasks whose reward charges actuator rate (fin, T-foil and
rudder wear), the exploration noise alone costs a large part of the return, so that curve says
little of the deterministic policy a user deploys (RollStabilization-v2: −351 at the end of
training against −131 held out). A ``[validation]`` table in a training config evaluates the
deterministic policy every ``every`` time steps on a fixed set of episodes (one per seed
``first_seed … first_seed + episodes − 1``, the same episodes each time, with
:func:`ship_gym.agents.evaluate.run_episodes`, the evaluation of ``ship-gym evaluate``) and,
with ``keep_best``, makes the run's ``model.zip`` the evaluated checkpoint of highest mean
validation return — the early-stopping rule of model selection, on seeds apart from both the
training episodes and the benchmark's held-out ones, so that the held-out result stays an
unbiased estimate. The last checkpoint is kept as ``final_model.zip``.

A run with a ``[safe]`` table selects among the evaluations within its budget — mean episode cost
≤ ``cost_limit``, or RMS action ≤ ``effort_limit`` (the constrained problem's feasible set on
the validation seeds; the evaluation nearest to it when none is).

The run folder gets ``validation.csv``: time steps, wall time [s], mean and standard deviation of
the return, mean cost, capsize rate, effort (RMS action) and the task's RMS metrics of every
evaluation.
"""

from __future__ import annotations

import copy
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = [
    "BEST",
    "FINAL",
    "VALIDATION_FILE",
    "VALIDATION_RUN_FILES",
    "ValidationConfig",
    "best_evaluation",
    "checkpoint_files",
    "validation_callback",
    "validation_config",
]

VALIDATION_FILE = "validation.csv"
"""Name of the evaluations table in a run folder."""

BEST = "best_"
"""File-name prefix of the best checkpoint while training runs."""
FINAL = "final_"
"""File-name prefix of the last checkpoint when the best one is kept as the run's model."""


def checkpoint_files(prefix: str) -> tuple[str, str]:
    """The model and observation-statistics file names of a checkpoint with ``prefix`` (""
    for the run's own ``model.zip``, ``vecnormalize.npz``; the loader pairs them the same way:
    :func:`ship_gym.envs.saved_policies.load_policy`)."""
    return f"{prefix}model.zip", f"{prefix}vecnormalize.npz"


VALIDATION_RUN_FILES = (*checkpoint_files(BEST), *checkpoint_files(FINAL), VALIDATION_FILE)
"""The files a validated run adds to its folder (removed when a new run starts there)."""

_COLUMNS = (
    "timesteps",
    "wall_s",
    "mean_return",
    "std_return",
    "mean_cost",
    "capsize_rate",
    "rms_action",
    "rms_roll_deg",
    "rms_heading_error_deg",
    "rms_vertical_acceleration_mps2",
)


@dataclass(frozen=True)
class ValidationConfig:
    """The ``[validation]`` table of a training config.

    Attributes
    ----------
    every : int
        Training time steps between evaluations [-] (also one at the end of training).
    episodes : int
        Validation episodes per evaluation [-].
    first_seed : int
        Seed of the first validation episode; episodes use ``first_seed … first_seed +
        episodes − 1``.
    keep_best : bool
        The run's ``model.zip`` is the checkpoint of best validation return (else the last).
    """

    every: int = 50_000
    episodes: int = 8
    first_seed: int = 5_000
    keep_best: bool = True

    @property
    def seeds(self) -> range:
        """The validation seeds."""
        return range(self.first_seed, self.first_seed + self.episodes)


def validation_config(table: Mapping[str, Any]) -> ValidationConfig:
    """Validate a ``[validation]`` table (errors name the key as written and its value)."""
    known = {"every", "episodes", "first_seed", "keep_best"}
    extra = set(table) - known
    if extra:
        raise ValueError(f"unknown keys {sorted(extra)} in [validation]; expected {sorted(known)}")
    for key, low in (("every", 1), ("episodes", 1), ("first_seed", 0)):
        value = table.get(key, getattr(ValidationConfig, key))
        if not isinstance(value, int) or isinstance(value, bool) or value < low:
            raise ValueError(f"validation.{key} must be an integer >= {low}, got {value!r}")
    keep_best = table.get("keep_best", True)
    if not isinstance(keep_best, bool):
        raise ValueError(f"validation.keep_best must be true or false, got {keep_best!r}")
    return ValidationConfig(
        every=table.get("every", ValidationConfig.every),
        episodes=table.get("episodes", ValidationConfig.episodes),
        first_seed=table.get("first_seed", ValidationConfig.first_seed),
        keep_best=keep_best,
    )


def best_evaluation(
    rows: Sequence[Mapping[str, float]], limit: tuple[str, float] | None = None
) -> int:
    """Index of the best evaluation: highest mean return; with ``limit`` = (column, value),
    e.g. ``("mean_cost", 2.0)`` or ``("rms_action", 0.25)``, among those whose column is ≤ the
    value (the one of the lowest column when none is). Ties go to the earliest."""
    if not rows:
        raise ValueError("no evaluations to choose from")
    candidates = list(range(len(rows)))
    if limit is not None:
        column, value = limit
        if column not in rows[0]:
            raise ValueError(
                f"no column {column!r} in the evaluations; expected one of {sorted(rows[0])}"
            )
        feasible = [i for i in candidates if rows[i][column] <= value]
        if not feasible:
            return min(candidates, key=lambda i: rows[i][column])
        candidates = feasible
    return max(candidates, key=lambda i: rows[i]["mean_return"])


def _current_policy(model: Any, training_env: Any) -> Any:
    """The policy being trained as ``ship-gym evaluate`` would load it: its observation
    normaliser's present statistics, composed with a copy of its residual baseline (the
    training wrapper keeps its own controller memory)."""
    from stable_baselines3.common.vec_env import VecNormalize

    from ship_gym.agents.residual import ResidualPolicy, find_residual
    from ship_gym.envs.saved_policies import ModelPolicy

    normalizer = training_env if isinstance(training_env, VecNormalize) else None
    learned = ModelPolicy(model=model, obs_normalizer=normalizer)
    try:
        wrapper = find_residual(training_env)
    except ValueError:
        return learned
    return ResidualPolicy(learned, copy.deepcopy(wrapper.baseline), wrapper.scale)


def validation_callback(
    config: ValidationConfig,
    env_id: str,
    env_kwargs: Mapping[str, Any],
    out_dir: str | Path,
    *,
    limit: tuple[str, float] | None = None,
) -> Any:
    """An SB3 callback evaluating the deterministic policy on the validation seeds (module
    docstring), at the first rollout start after every ``config.every`` steps (after the update
    of the steps collected) and at the end of training. It saves the best checkpoint as
    ``best_model.zip`` (and ``best_vecnormalize.npz``) and the table ``validation.csv`` in
    ``out_dir`` as it goes; ``rows`` holds the evaluations, ``best`` the index of the best,
    ``keeps_best`` whether the run's model is to be that checkpoint, ``seeds`` the validation
    seeds, ``csv()`` the table. ``limit`` (column, value) is a ``[safe]`` run's budget on an
    evaluation (:attr:`ship_gym.agents.lagrangian.SafeConfig.validation_limit`; see
    :func:`best_evaluation`)."""
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.vec_env import VecNormalize

    from ship_gym.agents.evaluate import run_episodes, summarize
    from ship_gym.envs.saved_policies import save_obs_normalizer
    from ship_gym.io_utils import atomic_write, atomic_write_text, csv_text

    out = Path(out_dir)

    class _Validation(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.rows: list[dict[str, float]] = []
            self.best: int | None = None
            self.seeds = config.seeds
            self._next = config.every
            self._t0 = time.perf_counter()

        @property
        def keeps_best(self) -> bool:
            return config.keep_best and self.best is not None

        def _on_step(self) -> bool:
            return True

        def _on_rollout_start(self) -> None:
            # between rollouts: the policy has been updated with every step collected so far
            if self.num_timesteps >= self._next:
                while self._next <= self.num_timesteps:
                    self._next += config.every
                self.evaluate()

        def _on_training_end(self) -> None:
            if not self.rows or self.rows[-1]["timesteps"] < self.num_timesteps:
                self.evaluate()

        def evaluate(self) -> None:
            policy = _current_policy(self.model, self.training_env)
            stats = run_episodes(env_id, policy, list(config.seeds), dict(env_kwargs))
            metrics = summarize(stats)
            row = {"timesteps": float(self.num_timesteps), "wall_s": time.perf_counter() - self._t0}
            row.update({k: float(metrics[k]) for k in _COLUMNS[2:]})
            self.rows.append(row)
            self.logger.record("validation/mean_return", row["mean_return"])
            self.logger.record("validation/rms_action", row["rms_action"])
            best = best_evaluation(self.rows, limit)
            if best == len(self.rows) - 1 and best != self.best:
                model_file, normalizer_file = checkpoint_files(BEST)
                atomic_write(out / model_file, lambda p: self.model.save(p))
                env = self.training_env
                if isinstance(env, VecNormalize):
                    atomic_write(out / normalizer_file, lambda p: save_obs_normalizer(env, p))
            self.best = best
            atomic_write_text(out / VALIDATION_FILE, self.csv())  # readable while training

        def csv(self) -> str:
            return csv_text(_COLUMNS, self.rows)

    return _Validation()
