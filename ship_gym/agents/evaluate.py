"""Evaluate policies (baselines and saved SB3 models) on identical seas.

Every policy runs the same episodes: episode k is reset with ``seed + k`` (the env draws its sea,
loading and initial state from that seed only), so differences between policies are the
policies', not the weather's. The episodes run together in one batched vector env
(``gymnasium.make_vec(id, num_envs=episodes, vectorization_mode="vector_entry_point")``, whose env
k reset with seed s is the single env reset with seed s: :mod:`ship_gym.envs.base`); each env's
first episode is recorded, then it is ignored until all have ended.

Metrics per policy (mean over episodes):

* ``capsize_rate`` — fraction of episodes ending by capsize (``info["capsized"]``, else
  ``terminated``);
* ``rms_roll_deg`` — RMS roll over each episode [deg] (``info["roll_deg"]`` when the env gives
  it, else the ``"roll"`` observation), averaged over episodes;
* ``rms_heading_error_deg`` — RMS of the ``"heading error"`` observation [deg] (NaN without it);
* ``rms_vertical_acceleration_mps2`` — RMS earth-vertical acceleration at the passenger point
  [m/s²] (``info["vertical_acceleration_mps2"]`` when the env gives it, else the ``"vertical
  acceleration"`` observation; NaN without either): what ride control is judged by;
* ``rms_action`` — effort: RMS of the actions over steps and action entries [-];
* ``mean_return``, ``std_return``, ``mean_length`` [steps], ``mean_cost`` (Safe-RL cost per
  episode).

Results go to ``evaluation.csv`` (one row per policy), ``evaluation.json`` (also the
per-episode values) and ``evaluation.png`` (one bar chart per metric) in the output directory.
"""

from __future__ import annotations

import csv
import io
import json
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

import gymnasium
import numpy as np
from numpy.typing import NDArray

from ship_gym.agents.residual import load_agent_policy
from ship_gym.envs.saved_policies import ModelPolicy, load_policy

__all__ = [
    "METRICS",
    "EpisodeStats",
    "ModelPolicy",
    "Policy",
    "action_mean_square",
    "evaluate_policies",
    "load_agent_policy",
    "load_policy",
    "policy_labels",
    "run_episodes",
    "summarize",
    "write_results",
]

METRICS: tuple[str, ...] = (
    "capsize_rate",
    "rms_roll_deg",
    "rms_heading_error_deg",
    "rms_vertical_acceleration_mps2",
    "rms_action",
    "mean_return",
    "mean_length",
)
"""The metrics plotted (and first in the CSV), in order."""


@runtime_checkable
class Policy(Protocol):
    """Anything with SB3's ``predict`` signature (SB3 models, :mod:`ship_gym.agents.baselines`)."""

    def predict(
        self,
        observation: NDArray,
        state: Any = None,
        episode_start: NDArray | None = None,
        deterministic: bool = True,
    ) -> tuple[NDArray, Any]: ...


@dataclass(frozen=True)
class EpisodeStats:
    """Per-episode results of one policy (arrays over episodes, in seed order).

    Attributes
    ----------
    seeds : NDArray
        Reset seed of each episode.
    returns : NDArray
        Undiscounted return [-].
    lengths : NDArray
        Episode length [control steps].
    capsized : NDArray
        True when the episode ended by capsize.
    rms_roll_deg : NDArray
        RMS roll [deg] (NaN when the env shows no roll).
    rms_heading_error_deg : NDArray
        RMS heading error [deg] (NaN when the env has no heading-error observation).
    rms_action : NDArray
        RMS of all action entries over the episode [-].
    cost : NDArray
        Summed Safe-RL cost [-].
    rms_vertical_acceleration_mps2 : NDArray
        RMS vertical acceleration at the passenger point [m/s²] (NaN when the env shows none).
    voyage_progress : NDArray
        HeavyWeather's task metric at the episode's end, ``info["voyage_progress"]``: distance
        made good along the voyage course / the nominal voyage, 0 if capsized [-] (NaN when the
        env gives none).
    """

    seeds: NDArray
    returns: NDArray
    lengths: NDArray
    capsized: NDArray
    rms_roll_deg: NDArray
    rms_heading_error_deg: NDArray
    rms_action: NDArray
    cost: NDArray
    rms_vertical_acceleration_mps2: NDArray
    voyage_progress: NDArray | None = None


class _SquaredSum:
    """Per-episode Σx² and sample count of one quantity, from ``info[info_key]`` when the env
    gives it, else from an observation (taken before the step, times ``factor``)."""

    def __init__(self, n: int, info_key: str, obs_index: int, factor: float) -> None:
        self.info_key = info_key
        self.obs_index = obs_index
        self.factor = factor
        self.total = np.zeros(n)
        self.count = np.zeros(n)

    def add(self, infos: Mapping[str, Any], obs_before: NDArray, active: NDArray) -> None:
        """Add one control step of the still-active episodes."""
        if self.info_key in infos:
            values = np.asarray(infos[self.info_key], float)
        elif self.obs_index >= 0:
            values = obs_before[:, self.obs_index] * self.factor
        else:
            return
        self.total += np.where(active, values**2, 0.0)
        self.count += active

    def rms(self) -> NDArray:
        """RMS per episode (NaN where nothing was measured)."""
        if self.obs_index < 0 and not self.count.any():
            return np.full(self.total.shape, np.nan)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.sqrt(self.total / self.count)


def _obs_index(names: Sequence[str], keyword: str) -> tuple[int, float]:
    """(index, factor to degrees) of an observation by name, (−1, nan) if absent."""
    from ship_gym.agents.baselines import find_name

    i = find_name(names, (keyword,), what=f"observation {keyword!r}", required=False)
    if i is None:
        return -1, math.nan
    return i, (1.0 if "[deg" in names[i] else 180.0 / math.pi)


def _vertical_acceleration_index(names: Sequence[str]) -> int:
    """Index of the passenger vertical-acceleration observation [m/s²], −1 if absent."""
    from ship_gym.agents.baselines import find_name

    i = find_name(
        names,
        ("vertical acceleration",),
        what="observation 'vertical acceleration'",
        required=False,
    )
    return -1 if i is None else i


def action_mean_square(actions: NDArray) -> NDArray:
    """(N,) mean over the action entries of clip(a, −1, 1)² [-] of (N, n_act) actions: the
    per-step effort whose RMS over an episode is ``rms_action`` (and which an effort budget of
    :mod:`ship_gym.agents.lagrangian` constrains in training)."""
    return np.mean(np.clip(actions, -1.0, 1.0) ** 2, axis=1)


def run_episodes(
    env_id: str,
    policy: Policy | Callable[[Any], Policy],
    seeds: Sequence[int],
    env_kwargs: Mapping[str, Any] | None = None,
    *,
    deterministic: bool = True,
    max_steps: int | None = None,
    progress: bool = False,
    label: str = "",
) -> EpisodeStats:
    """Run one episode per seed with ``policy`` (or a callable ``env -> policy``), batched.

    Parameters
    ----------
    env_id : str
        Registered id (``"ship_gym/RollOneDOF-v0"``; the ``"ship_gym:"`` prefix is optional).
    policy : Policy or callable
        An object with ``predict``, or a factory called with the vector env (baselines:
        ``lambda env: make_baseline("fins", env)``).
    seeds : sequence of int
        One episode per seed (episode k reset with ``seeds[k]``).
    env_kwargs : mapping, optional
        Environment keyword arguments (the same for every policy, for a fair comparison).
    deterministic : bool
        Passed to ``predict``.
    max_steps : int, optional
        Override of the registered time limit [control steps].
    progress : bool
        Show a tqdm bar over control steps.
    label : str
        Name on the progress bar.
    """
    from gymnasium.vector import AutoresetMode

    from ship_gym.envs.base import TaskVectorEnv

    seeds = [int(s) for s in seeds]
    if not seeds:
        raise ValueError("seeds must hold at least one seed")
    n = len(seeds)
    full_id = env_id if ":" in env_id else f"ship_gym:{env_id}"
    kwargs = dict(env_kwargs or {})
    if max_steps is not None:
        kwargs["max_episode_steps"] = int(max_steps)
    env = gymnasium.make_vec(
        full_id,
        num_envs=n,
        vectorization_mode="vector_entry_point",
        autoreset_mode=AutoresetMode.SAME_STEP,
        **kwargs,
    )
    try:
        if not isinstance(policy, Policy):  # a factory (Policy checks for ``predict``)
            policy = policy(env)
        if hasattr(policy, "reset"):
            policy.reset()
        task_env = env.unwrapped
        if not isinstance(task_env, TaskVectorEnv):
            raise ValueError(f"{env_id!r} is not a ship_gym environment (no TaskVectorEnv)")
        names = tuple(task_env.observation_names)
        i_roll, f_roll = _obs_index(names, "roll")
        i_head, f_head = _obs_index(names, "heading error")
        roll = _SquaredSum(n, "roll_deg", i_roll, f_roll)
        vertical = _SquaredSum(
            n, "vertical_acceleration_mps2", _vertical_acceleration_index(names), 1.0
        )
        limit = task_env.max_episode_steps
        n_act = int(np.prod(task_env.single_action_space.shape))

        obs, _ = env.reset(seed=seeds)  # type: ignore[arg-type]  # gymnasium types it int | None; TaskVectorEnv takes one per episode
        active = np.ones(n, dtype=bool)
        returns = np.zeros(n)
        lengths = np.zeros(n, dtype=np.int64)
        capsized = np.zeros(n, dtype=bool)
        cost = np.zeros(n)
        progress_end = np.full(n, np.nan)
        head_sq = np.zeros(n)
        act_sq = np.zeros(n)
        state = None
        episode_start = np.ones(n, dtype=bool)
        bar = None
        if progress:
            from tqdm.auto import tqdm

            bar = tqdm(total=limit, desc=f"evaluate {label}".strip(), unit="step", leave=False)
        while active.any():
            action, state = policy.predict(
                obs, state=state, episode_start=episode_start, deterministic=deterministic
            )
            action = np.asarray(action, dtype=np.float64).reshape(n, n_act)
            if i_head >= 0:
                head_sq += np.where(active, (obs[:, i_head] * f_head) ** 2, 0.0)
            obs_before = np.copy(obs)  # the env may refill its observation buffer
            obs, reward, terminated, truncated, infos = env.step(np.clip(action, -1.0, 1.0))
            episode_start = np.zeros(n, dtype=bool)
            returns += np.where(active, reward, 0.0)
            lengths += active
            act_sq += np.where(active, action_mean_square(action), 0.0)
            if "cost" in infos:
                cost += np.where(active, infos["cost"], 0.0)
            roll.add(infos, obs_before, active)
            vertical.add(infos, obs_before, active)
            done = (np.asarray(terminated) | np.asarray(truncated)) & active
            if done.any():
                if "voyage_progress" in infos:
                    progress_end = np.where(done, infos["voyage_progress"], progress_end)
                flag = infos.get("capsized", terminated)
                capsized |= done & np.asarray(flag, dtype=bool) & np.asarray(terminated, bool)
                active &= ~done
            if bar is not None:
                bar.update(1)
        if bar is not None:
            bar.close()
    finally:
        env.close()
    with np.errstate(invalid="ignore", divide="ignore"):
        return EpisodeStats(
            seeds=np.asarray(seeds),
            returns=returns,
            lengths=lengths,
            capsized=capsized,
            rms_roll_deg=roll.rms(),
            rms_heading_error_deg=(
                np.sqrt(head_sq / lengths) if i_head >= 0 else np.full(n, np.nan)
            ),
            rms_action=np.sqrt(act_sq / lengths),
            cost=cost,
            rms_vertical_acceleration_mps2=vertical.rms(),
            voyage_progress=progress_end,
        )


def summarize(stats: EpisodeStats) -> dict[str, float]:
    """The metrics of :data:`METRICS` (and a few more) from per-episode results."""

    def mean(a: NDArray) -> float:
        a = np.asarray(a, dtype=float)
        return float(np.mean(a)) if np.all(np.isfinite(a)) else math.nan

    return {
        "capsize_rate": float(np.mean(stats.capsized)),
        "rms_roll_deg": mean(stats.rms_roll_deg),
        "rms_heading_error_deg": mean(stats.rms_heading_error_deg),
        "rms_vertical_acceleration_mps2": mean(stats.rms_vertical_acceleration_mps2),
        "rms_action": mean(stats.rms_action),
        "mean_return": float(np.mean(stats.returns)),
        "mean_length": float(np.mean(stats.lengths)),
        "std_return": float(np.std(stats.returns)),
        "mean_cost": float(np.mean(stats.cost)),
        "episodes": float(len(stats.returns)),
        "voyage_progress": (
            math.nan if stats.voyage_progress is None else mean(stats.voyage_progress)
        ),
        # HeavyWeather's metric as a shortfall (lower is better, as the benchmark's metrics)
        "voyage_shortfall": (
            math.nan if stats.voyage_progress is None else 1.0 - mean(stats.voyage_progress)
        ),
    }


def policy_labels(specs: Sequence[str]) -> list[str]:
    """One unique label per policy spec.

    Baselines keep their name; ``model:PATH`` is labelled by its run folder (``model:RUN`` for
    ``RUN/model.zip`` or the folder ``RUN``, ``model:NAME.zip`` for another file name), or by
    the path as typed where two models would share a label (every ``train`` run writes
    ``model.zip``). The same spec twice raises ``ValueError``.
    """
    specs = [s.strip() for s in specs]
    dup = sorted({s for i, s in enumerate(specs) if s in specs[:i]})
    if dup:
        raise ValueError(f"--policies: {', '.join(dup)} given more than once; expected each once")

    def short(spec: str) -> str:
        if not spec.startswith("model:"):
            return spec
        path = Path(spec[len("model:") :])
        if path.name == "model.zip" and path.parent.name:
            return f"model:{path.parent.name}"
        return f"model:{path.name or path}"

    labels = [short(s) for s in specs]
    return [
        spec if labels.count(label) > 1 else label
        for spec, label in zip(specs, labels, strict=True)
    ]


def _policy_factory(spec: str, device: str = "cpu", *, trusted: bool = False) -> tuple[str, Any]:
    """``"zero"``, ``"pid"``, ``"fins"``, ``"ride"`` or ``"model:PATH"`` → (label, factory)
    (``trusted``: the opt-in to load a model neither trained here nor shipped)."""
    from ship_gym.agents.baselines import BASELINES, make_baseline

    spec = spec.strip()
    if spec.startswith("model:"):
        path = spec[len("model:") :]
        policy = load_agent_policy(path, device=device, trusted=trusted)
        return policy_labels([spec])[0], policy
    if spec in BASELINES:
        return spec, lambda env, name=spec: make_baseline(name, env)
    raise ValueError(f"unknown policy {spec!r}: expected one of {sorted(BASELINES)} or model:PATH")


def _shared_env_kwargs(
    env_id: str,
    labels: Sequence[str],
    policies: Sequence[Any],
    env_kwargs: dict[str, Any],
    use_training_env: bool,
    report: Any,
) -> dict[str, Any]:
    """The one set of env keyword arguments every policy of an evaluation runs with.

    Saved models carry the settings they were trained with (``training_env``); with
    ``use_training_env`` those settings, updated by ``env_kwargs``, apply to *every* policy,
    baselines included, so that no table compares policies on different ships or seas (a model
    trained on another ship beside baselines on the default one). Models trained with different
    settings cannot share a table: ValueError naming them.
    """
    trained: dict[str, dict[str, Any]] = {}
    for label, policy in zip(labels, policies, strict=True):
        training_env = getattr(policy, "training_env", None) or {}
        trained_id = training_env.get("id")
        if trained_id and trained_id != env_id and report is not None:
            report(f"warning: {label} was trained on {trained_id}, evaluated on {env_id}")
        if training_env:
            trained[label] = dict(training_env.get("kwargs") or {})
    if not use_training_env:
        for label, settings in trained.items():
            if settings and report is not None:
                report(f"{label}: ignoring the env settings it was trained with {settings}")
        return env_kwargs
    distinct = {json.dumps(v, sort_keys=True, default=str) for v in trained.values()}
    if len(distinct) > 1:
        listing = "; ".join(f"{k}: {v}" for k, v in trained.items())
        raise ValueError(
            "the models were trained with different env settings and cannot share one table "
            f"({listing}); evaluate them separately, or pass the settings to compare on with "
            "--set and --no-training-env"
        )
    settings = next(iter(trained.values()), {})
    if not settings:
        return env_kwargs
    merged = {**settings, **env_kwargs}
    if report is not None:
        overridden = sorted(set(settings) & set(env_kwargs))
        report(
            f"every policy runs with the env settings the model(s) were trained with {settings}"
            + (f" (overridden by --set: {overridden})" if overridden else "")
        )
    return merged


def evaluate_policies(
    env_id: str,
    policies: Sequence[str],
    episodes: int,
    seed: int,
    env_kwargs: Mapping[str, Any] | None = None,
    *,
    max_steps: int | None = None,
    progress: bool = True,
    device: str = "cpu",
    use_training_env: bool = True,
    report: Any = None,
    trusted: bool = False,
) -> dict[str, Any]:
    """Evaluate each policy on episodes seeded ``seed … seed + episodes − 1``.

    Every policy runs with the same env keyword arguments (:func:`_shared_env_kwargs`): by
    default (``use_training_env``) those a saved model was trained with (``[env] kwargs`` of its
    run's ``config.toml``), updated by ``env_kwargs`` — baselines included, so that a model
    trained on another ship is compared on that ship; models trained with different settings
    are refused. ``report(message)`` (e.g. ``print``) is told which settings were applied. Each
    policy gets a unique label (:func:`policy_labels`).

    A saved model is loaded only when trained by this installation, shipped with the package,
    or ``trusted`` (the caller's opt-in: loading an SB3 model runs code from the file;
    :mod:`ship_gym.envs.policy_trust`); else
    :class:`~ship_gym.envs.policy_trust.UntrustedPolicyError` (a ValueError) is raised before
    any policy runs.

    Returns
    -------
    dict
        ``{"env_id", "seeds", "env_kwargs", "policies": {label: {metric: value, ...,
        "episodes": {per-episode lists}}}, "wall_time_s": {label: s}}``.
    """
    if isinstance(episodes, bool) or not isinstance(episodes, int) or episodes < 1:
        raise ValueError(f"episodes must be a positive integer, got {episodes!r}")
    if not policies:
        raise ValueError("give at least one policy (zero, pid, fins, ride or model:PATH)")
    seeds = list(range(int(seed), int(seed) + episodes))
    out: dict[str, Any] = {
        "env_id": env_id,
        "seeds": seeds,
        "env_kwargs": dict(env_kwargs or {}),
        "max_steps": max_steps,
        "policies": {},
        "wall_time_s": {},
        "policy_env_kwargs": {},
    }
    labels = policy_labels(policies)
    factories = [_policy_factory(spec, device=device, trusted=trusted)[1] for spec in policies]
    kwargs = _shared_env_kwargs(
        env_id, labels, factories, dict(env_kwargs or {}), use_training_env, report
    )
    for label, policy in zip(labels, factories, strict=True):
        out["policy_env_kwargs"][label] = kwargs
        t0 = time.perf_counter()
        stats = run_episodes(
            env_id,
            policy,
            seeds,
            kwargs,
            max_steps=max_steps,
            progress=progress,
            label=label,
        )
        out["wall_time_s"][label] = time.perf_counter() - t0
        metrics: dict[str, Any] = summarize(stats)
        metrics["per_episode"] = {
            k: np.asarray(v).tolist() for k, v in asdict(stats).items() if k != "seeds"
        }
        if stats.voyage_progress is not None and "voyage_progress" in metrics["per_episode"]:
            metrics["per_episode"]["voyage_shortfall"] = (
                1.0 - np.asarray(stats.voyage_progress, float)
            ).tolist()
        out["policies"][label] = metrics
    return out


def write_results(results: Mapping[str, Any], out_dir: str | Path, *, plot: bool = True) -> Path:
    """Write ``evaluation.csv``, ``evaluation.json`` and (``plot``) ``evaluation.png``."""
    from ship_gym.io_utils import atomic_write, atomic_write_text

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    columns = [*METRICS, "std_return", "mean_cost", "episodes"]
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(["policy", *columns])
    for label, m in results["policies"].items():
        writer.writerow([label, *(f"{m[c]:.6g}" for c in columns)])
    atomic_write_text(out / "evaluation.csv", buffer.getvalue())
    atomic_write_text(out / "evaluation.json", json.dumps(results, indent=2, default=_json_default))
    if plot:
        import matplotlib

        matplotlib.use("Agg")
        from matplotlib.figure import Figure

        labels = list(results["policies"])
        fig = Figure(figsize=(3.0 * len(METRICS) / 2, 6.0))
        axes = fig.subplots(2, math.ceil(len(METRICS) / 2)).ravel()
        colours = [f"C{i}" for i in range(len(labels))]
        for ax, metric in zip(axes, METRICS, strict=False):
            values = [results["policies"][k][metric] for k in labels]
            ax.bar(range(len(labels)), np.nan_to_num(values), color=colours)
            if not np.any(np.isfinite(values)):
                ax.text(0.5, 0.5, "not measured\nin this env", ha="center", transform=ax.transAxes)
            ax.set_xticks(range(len(labels)), labels, rotation=30, ha="right", fontsize=7)
            ax.set_title(metric, fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(axis="y", alpha=0.3)
        for ax in axes[len(METRICS) :]:
            ax.set_visible(False)
        fig.suptitle(
            f"{results['env_id']}: {len(results['seeds'])} episodes, seeds "
            f"{results['seeds'][0]}…{results['seeds'][-1]} (same seas for every policy)",
            fontsize=9,
        )
        fig.tight_layout()
        atomic_write(out / "evaluation.png", lambda p: fig.savefig(p, dpi=110, format="png"))
    return out


def _json_default(value: Any) -> Any:
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return str(value)
