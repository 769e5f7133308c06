"""The learned-vs-classical benchmark: train the shipped configs, evaluate on held-out seeds.

For each task (:data:`TASKS`) the benchmark

1. evaluates the task's classical baselines (:mod:`ship_gym.agents.baselines`) on the held-out
   seeds (``seed`` … ``seed + episodes − 1``, by default 10 000 onwards — never a training seed:
   a training run with seed k resets its n_envs episodes with seeds k … k + n_envs − 1 and
   draws the later ones from their generators; a held-out seed below that is refused);
2. trains the task's shipped configs (:mod:`ship_gym.agents.configs`) with ``n_seeds`` training
   seeds each (``ship-gym train`` runs under ``<out>/runs/<task>/<config>/seed<k>``; a finished
   run of the same config is reused, so an interrupted benchmark resumes) and evaluates every
   trained policy on the same held-out seeds; with ``configs`` only those are trained and
   evaluated, the task's other configs keep their rows from the earlier ``results.json`` of
   the same seeds and budget (``ship-gym benchmark --configs``: a config that changed is rerun
   without retraining the rest);
3. writes ``<out>/results.md`` (one table per task: task metric, effort = RMS action, capsize
   rate with its Wilson 95 % interval, return, safe-RL cost, wall time and steps/s of the
   training), ``<out>/results.json``, a learning-curve figure per task
   (``<out>/curves_<task>.png``: mean return of the last 100 training episodes against time
   steps, one line per seed, and beside it the deterministic policy's return on the validation
   seeds of a config with a ``[validation]`` table, :mod:`ship_gym.agents.validation`), and
   copies the best training seed of every config into
   ``<out>/policies/<task>/<config>/`` (``model.zip``, ``vecnormalize.npz``, ``config.toml``,
   ``residual.json`` of a residual policy, ``validation.csv``), so
   that ``ship-gym evaluate --policies model:<that folder>`` reproduces the table without
   training.

With a gain frontier (:attr:`BenchmarkTask.frontier`), the task's tuned baseline is also run with
its gains scaled up and down (:mod:`ship_gym.agents.frontier`) on the same held-out episodes, and
each learned policy is set against that family *at the policy's own effort* (column "vs baseline
at same effort"; ``<out>/frontier_<task>.png``: task metric against effort).

The target of issue #16 is read off each table: the learned policy's metric ≥ 20 % better than
the strongest baseline's (the baseline best on the metric), at equal or lower effort; the table
says whether it is met (``target``).
"""

from __future__ import annotations

import dataclasses
import json
import math
import shutil
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ship_gym.agents.frontier import FrontierPoint, baseline_frontier, metric_at_effort

__all__ = ["TASKS", "BenchmarkTask", "check_benchmark_arguments", "run_benchmark"]


@dataclass(frozen=True)
class BenchmarkTask:
    """One task of the benchmark.

    Attributes
    ----------
    env_id : str
        The environment.
    metric : str
        The task metric (a key of :func:`ship_gym.agents.evaluate.summarize`); lower is better.
    metric_label : str
        Its name and unit for the table.
    baselines : tuple of str
        Classical baselines (:data:`ship_gym.agents.baselines.BASELINES` names).
    configs : tuple of str
        Shipped training configs.
    timesteps : int or None
        Training budget per run of the published table (``docs/benchmarks/results.md``), so that
        ``ship-gym benchmark`` without ``--timesteps`` reproduces it; None: each config's own
        ``total_timesteps``.
    episodes : int
        Held-out episodes per policy of the published table.
    env_kwargs : dict
        Environment keyword arguments of every policy's episodes.
    frontier : str or None
        The baseline whose gain-scaled family (:mod:`ship_gym.agents.frontier`) is run on the
        held-out episodes, so that each learned policy is also compared with it at the
        policy's own effort; None for a task without a loop gain to scale.
    """

    env_id: str
    metric: str
    metric_label: str
    baselines: tuple[str, ...]
    configs: tuple[str, ...]
    timesteps: int | None = None
    episodes: int = 40
    env_kwargs: dict = field(default_factory=dict)
    frontier: str | None = None


TASKS: dict[str, BenchmarkTask] = {
    "CourseKeeping": BenchmarkTask(
        "ship_gym/CourseKeeping-v2",
        "rms_heading_error_deg",
        "RMS heading error [deg]",
        ("zero", "pid"),
        ("ppo_course_keeping", "ppo_residual_course_keeping"),
        None,  # each config's own budget: 500 k from scratch, 1 M for the residual
        frontier="pid",
    ),
    "RollStabilization": BenchmarkTask(
        "ship_gym/RollStabilization-v2",
        "rms_roll_deg",
        "RMS roll [deg]",
        ("zero", "fins"),
        ("ppo_roll_stabilization",),
        None,  # the config's 1 M: its validation return still rose steeply at 500 k
        frontier="fins",
    ),
    "RideControl": BenchmarkTask(
        "ship_gym/RideControl-v2",
        "rms_vertical_acceleration_mps2",
        "RMS vertical acceleration [m/s²]",
        ("zero", "ride"),
        ("sac_ride_control",),
        100_000,  # a third of the shipped 300 k: SAC runs at ≈ 150–200 steps/s
        frontier="ride",
    ),
    "CapsizeAvoidance": BenchmarkTask(
        "ship_gym/CapsizeAvoidance-v2",
        "capsize_rate",
        "capsize rate [-]",
        ("zero", "imo-guidance"),
        ("ppo_capsize_avoidance", "ppo_lagrangian_capsize_avoidance"),
        400_000,
        60,
    ),
    "RollOneDOF": BenchmarkTask(
        "ship_gym/RollOneDOF-v0",
        "capsize_rate",
        "capsize rate [-]",
        ("zero", "fins"),
        ("ppo_roll_one_dof",),
    ),
}
"""The benchmark's tasks by name."""


_RUN_ONLY = ("output_dir", "progress_bar", "tensorboard", "total_timesteps")
"""``[training]`` keys that do not change what a run learns (the budget is checked apart)."""


def _learning_setup(raw: dict) -> dict:
    """A config without the keys of :data:`_RUN_ONLY`."""
    setup = {k: v for k, v in raw.items() if k != "training"}
    setup["training"] = {k: v for k, v in raw.get("training", {}).items() if k not in _RUN_ONLY}
    return setup


def read_summary(run: Path) -> dict[str, Any]:
    """A run's ``summary.json`` (written by :func:`ship_gym.agents.train.train`).

    Raises
    ------
    ValueError
        A missing, damaged or foreign file, naming it and what is wrong.
    """
    path = run / "summary.json"
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise ValueError(f"{path}: not a readable run summary ({exc})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path}: holds a {type(data).__name__}; expected a JSON object")
    for key in ("num_timesteps", "wall_time_s"):
        value = data.get(key)
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ValueError(
                f"{path}: {key} = {value!r}; expected a number (the summary `ship-gym train` "
                "writes; delete the run folder to train it again)"
            )
    return data


def _run_is_complete(run: Path, config: Any) -> bool:
    """A finished training run of ``config`` (:class:`~ship_gym.agents.train.TrainConfig`) with ≥
    its ``total_timesteps``: the same env id and version, algorithm, hyperparameters, residual,
    safe and validation tables and seed (a run of an earlier config is not reused)."""
    from ship_gym.envs.saved_policies import read_run_config

    summary = run / "summary.json"
    if not (summary.is_file() and (run / "model.zip").is_file()):
        return False
    try:
        trained = read_run_config(run / "config.toml")
        return (
            _learning_setup(trained) == _learning_setup(dict(config.raw))
            and int(read_summary(run)["num_timesteps"]) >= config.total_timesteps
        )
    except (ValueError, KeyError, OSError):  # a damaged run is trained again
        return False


def _curve(run: Path) -> dict[str, list[float]]:
    """The run's learning curve (``progress.csv``: return, cost and the Lagrange multiplier of a
    ``[safe]`` run) and, when it has one, its deterministic validation curve
    (``validation.csv``: ``validation_timesteps``, ``validation_return``)."""
    import csv

    from ship_gym.agents.validation import VALIDATION_FILE

    keys = ("timesteps", "mean_return", "mean_cost", "lambda")
    curve: dict[str, list[float]] = {k: [] for k in keys}
    path = run / "progress.csv"
    if path.is_file():
        rows = list(csv.DictReader(path.open()))
        curve = {k: [float(r.get(k) or 0.0) for r in rows] for k in keys}
    path = run / VALIDATION_FILE
    if path.is_file():
        rows = list(csv.DictReader(path.open()))
        curve["validation_timesteps"] = [float(r["timesteps"]) for r in rows]
        curve["validation_return"] = [float(r["mean_return"]) for r in rows]
    return curve


def _row(label: str, metrics: dict, task: BenchmarkTask, training: dict | None) -> dict:
    from ship_gym.analysis.capsize_statistics import wilson_interval

    n = int(metrics["episodes"])
    k = round(metrics["capsize_rate"] * n)
    low, high = wilson_interval(k, n)
    row = {
        "policy": label,
        "metric": metrics[task.metric],
        "effort": metrics["rms_action"],
        "capsized": k,
        "episodes": n,
        "capsize_ci95": [low, high],
        "mean_return": metrics["mean_return"],
        "mean_cost": metrics["mean_cost"],
    }
    if training is not None:
        row.update(training)
    return row


def check_benchmark_arguments(
    tasks: Sequence[str],
    *,
    n_seeds: int,
    timesteps: int | None,
    episodes: int | None,
    seed: int,
    configs: Sequence[str] | None = None,
) -> None:
    """Refuse bad benchmark arguments before any work (ValueError naming the argument): unknown
    tasks, configs that belong to none of them, non-positive counts, held-out seeds that overlap
    a training run's seeds or the validation seeds its checkpoint is chosen on."""
    from ship_gym.agents.train import load_config

    unknown = [t for t in tasks if t not in TASKS]
    if unknown or not tasks:
        raise ValueError(
            f"tasks: {'unknown task ' + repr(unknown[0]) if unknown else 'none given'}; "
            f"expected some of {sorted(TASKS)}"
        )
    if configs is not None:
        offered = [c for t in tasks for c in TASKS[t].configs]
        stray = [c for c in configs if c not in offered]
        if stray or not configs:
            raise ValueError(
                f"configs: {repr(stray[0]) + ' is no config of ' if stray else 'none given for '}"
                f"{', '.join(tasks)}; expected some of {offered}"
            )
    for name, value in (("n_seeds", n_seeds), ("episodes", 1 if episodes is None else episodes)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise ValueError(f"{name} must be a positive integer, got {value!r}")
    if timesteps is not None and (not isinstance(timesteps, int) or timesteps < 1):
        raise ValueError(f"timesteps must be a positive integer or None, got {timesteps!r}")
    for name in tasks:
        n_episodes = episodes if episodes is not None else TASKS[name].episodes
        held_out = range(seed, seed + n_episodes)
        for config_name in TASKS[name].configs:
            config = load_config(config_name)
            top = n_seeds - 1 + config.n_envs - 1
            if seed <= top:  # the training env of seed k resets with k … k + n_envs − 1
                raise ValueError(
                    f"held-out seed {seed} overlaps the training seeds 0 … {top} of "
                    f"{config_name}; expected a seed > {top}"
                )
            chosen_on = config.validation.seeds if config.validation is not None else range(0)
            if set(held_out) & set(chosen_on):  # the checkpoint is chosen on these episodes
                raise ValueError(
                    f"held-out seeds {held_out[0]} … {held_out[-1]} (seed {seed}) overlap the "
                    f"validation seeds {chosen_on[0]} … {chosen_on[-1]} of {config_name}; "
                    "expected held-out seeds apart from them"
                )


def run_benchmark(
    tasks: Sequence[str],
    out_dir: str | Path,
    *,
    n_seeds: int = 3,
    timesteps: int | None = None,
    episodes: int | None = None,
    seed: int = 10_000,
    configs: Sequence[str] | None = None,
    progress: bool = True,
    report: Callable[[str], None] = print,
) -> dict[str, Any]:
    """Run the benchmark (module docstring) and write its files; return the results.

    Parameters
    ----------
    tasks : sequence of str
        Names of :data:`TASKS`.
    out_dir : str or Path
        Output folder.
    n_seeds : int
        Training seeds per config (0 … n_seeds − 1).
    timesteps : int, optional
        Training budget per run, for every task (default: each task's
        :attr:`BenchmarkTask.timesteps`, else its configs' ``total_timesteps``).
    episodes : int, optional
        Held-out evaluation episodes per policy, for every task (default: each task's
        :attr:`BenchmarkTask.episodes`).
    seed : int
        First held-out seed.
    configs : sequence of str, optional
        Train and evaluate only these of the tasks' configs; the rows and learning curves of
        a task's other configs are kept from ``results.json`` in ``out_dir``, which must hold
        that task run with the same held-out seeds, episodes, training seeds and budget (the
        table says which rows are kept, and from when). None: all configs.
    progress : bool
        Progress bars.
    report : callable
        Where progress messages go.

    Raises
    ------
    ValueError
        Unknown task or config, non-positive counts, held-out seeds that overlap training
        seeds, or configs to keep without matching earlier results — all before any work.
    """
    from ship_gym.agents.evaluate import evaluate_policies
    from ship_gym.agents.train import load_config, train

    check_benchmark_arguments(tasks, n_seeds=n_seeds, timesteps=timesteps, episodes=episodes,
                              seed=seed, configs=configs)  # fmt: skip
    out = Path(out_dir)
    results: dict[str, Any] = {"tasks": {}}
    previous = out / "results.json"
    if previous.is_file():  # other tasks' results stay (a task is re-run as a whole)
        try:
            earlier = json.loads(previous.read_text(encoding="utf-8"))
            if not isinstance(earlier, dict) or not isinstance(earlier.get("tasks", {}), dict):
                raise ValueError("not a results table")
            results["tasks"] = dict(earlier.get("tasks", {}))
        except (ValueError, UnicodeDecodeError):
            report(f"{previous}: unreadable, rewritten")
    kept = _kept_configs(tasks, configs, results["tasks"], previous, n_seeds=n_seeds,
                         timesteps=timesteps, episodes=episodes, seed=seed)  # fmt: skip
    out.mkdir(parents=True, exist_ok=True)
    for name in tasks:
        task = TASKS[name]
        budget = timesteps if timesteps is not None else task.timesteps
        n_episodes = episodes if episodes is not None else task.episodes
        earlier = results["tasks"].get(name, {})
        kept_from: dict[str, str] = {}
        rows: list[dict] = []
        curves: dict[str, list[dict]] = {}
        base = evaluate_policies(
            task.env_id, list(task.baselines), n_episodes, seed, task.env_kwargs, progress=progress
        )
        for label, metrics in base["policies"].items():
            rows.append(_row(label, metrics, task, None))
        frontier: list[FrontierPoint] = []
        if task.frontier is not None:
            held_out = list(range(seed, seed + n_episodes))
            frontier = baseline_frontier(task.env_id, task.frontier, task.metric, held_out,
                                         task.env_kwargs, progress=progress)  # fmt: skip
        for config_name in task.configs:
            if config_name in kept[name]:
                report(f"{name}/{config_name}: keeping the rows of the earlier run")
                rows += [_learned_row(r) for r in earlier["rows"] if r.get("config") == config_name]
                curves[config_name] = earlier.get("curves", {}).get(config_name, [])
                kept_from[config_name] = earlier.get("kept", {}).get(config_name, earlier["date"])
                continue
            curves[config_name] = []
            best: tuple[float, Path] | None = None
            for k in range(n_seeds):
                run = out / "runs" / name / config_name / f"seed{k}"
                config = load_config(
                    config_name,
                    seed=k,
                    output_dir=str(run),
                    total_timesteps=budget,
                    progress_bar=progress,
                    tensorboard=False,
                )
                if _run_is_complete(run, config):
                    report(f"{name}/{config_name}/seed{k}: reusing the finished run")
                else:
                    report(f"{name}/{config_name}/seed{k}: training {config.total_timesteps} steps")
                    train(config)
                summary = read_summary(run)
                ev = evaluate_policies(
                    task.env_id, [f"model:{run}"], n_episodes, seed, progress=progress
                )
                metrics = next(iter(ev["policies"].values()))
                training = {
                    "config": config_name,
                    "training_seed": k,
                    "timesteps": summary["num_timesteps"],
                    "wall_s": summary["wall_time_s"],
                    "steps_per_s": summary.get("steps_per_s"),
                }
                chosen = summary.get("validation", {})
                if chosen.get("model") == "best":
                    training["model_timesteps"] = chosen["best_timesteps"]
                rows.append(_row(f"{config_name} seed {k}", metrics, task, training))
                curves[config_name].append(_curve(run))
                score = float(metrics[task.metric])
                if best is None or score < best[0] or (math.isnan(best[0]) and score == score):
                    best = (score, run)
            if best is not None:
                _ship_policy(best[1], out / "policies" / name / config_name)
        results["tasks"][name] = _verdict(task, rows, frontier)
        results["tasks"][name].update(
            curves=curves,
            seed=seed,
            episodes=n_episodes,
            n_seeds=n_seeds,
            timesteps=budget,
            date=time.strftime("%Y-%m-%d"),
            kept=kept_from,
        )
        _plot_curves(name, task, curves, out / f"curves_{name}.png")
        if frontier:
            _plot_frontier(name, task, results["tasks"][name], out / f"frontier_{name}.png")
    from ship_gym.io_utils import atomic_write_text

    atomic_write_text(out / "results.json", json.dumps(results, indent=2, default=float))
    atomic_write_text(out / "results.md", results_markdown(results))
    return results


VERDICT_KEYS = ("gain_vs_strongest", "target", "frontier_metric", "gain_at_effort")
"""The fields of a learned row that :func:`_verdict` derives (recomputed for a kept row)."""


def _learned_row(row: Mapping[str, Any]) -> dict[str, Any]:
    """A learned row of an earlier run as measured, without the verdict derived from it."""
    return {k: v for k, v in row.items() if k not in VERDICT_KEYS}


def _kept_configs(
    tasks: Sequence[str],
    configs: Sequence[str] | None,
    earlier: Mapping[str, Any],
    previous: Path,
    *,
    n_seeds: int,
    timesteps: int | None,
    episodes: int | None,
    seed: int,
) -> dict[str, tuple[str, ...]]:
    """Per task, the configs whose rows are kept from the earlier results (none without
    ``configs``); ValueError where those results are missing or were run otherwise."""
    kept: dict[str, tuple[str, ...]] = {}
    for name in tasks:
        task = TASKS[name]
        keep = tuple(c for c in task.configs if configs is not None and c not in configs)
        kept[name] = keep
        if not keep:
            continue
        wanted = {
            "seed": seed,
            "episodes": episodes if episodes is not None else task.episodes,
            "n_seeds": n_seeds,
            "timesteps": timesteps if timesteps is not None else task.timesteps,
        }
        found = earlier.get(name)
        if found is None:
            differs = "no results of the task"
        else:
            changed = [f"{k} {found.get(k)!r} (now {v!r})" for k, v in wanted.items()
                       if found.get(k) != v]  # fmt: skip
            differs = ", ".join(changed)
        rows = found["rows"] if found is not None else []
        missing = [c for c in keep if not any(r.get("config") == c for r in rows)]
        if differs or missing:
            why = differs or f"no rows of {', '.join(missing)}"
            raise ValueError(
                f"configs {list(configs or [])}: keeping {', '.join(keep)} of {name} needs its "
                f"earlier run in {previous} with the same held-out seeds, episodes, training "
                f"seeds and budget; found {why}. Expected all of {name}'s configs, or that run"
            )
    return kept


def _ship_policy(run: Path, to: Path) -> None:
    to.mkdir(parents=True, exist_ok=True)
    from ship_gym.agents.residual import RESIDUAL_FILE
    from ship_gym.agents.validation import VALIDATION_FILE

    kept = ("model.zip", "vecnormalize.npz", "config.toml", "summary.json")
    for name in (*kept, RESIDUAL_FILE, VALIDATION_FILE):
        if (run / name).is_file():
            shutil.copy2(run / name, to / name)


def _verdict(
    task: BenchmarkTask, rows: list[dict], frontier: Sequence[FrontierPoint] = ()
) -> dict[str, Any]:
    """The rows, the strongest baseline and, per learned row, whether the target is met and,
    with a gain frontier, the gain against the baseline family at the row's own effort."""
    baselines = [r for r in rows if "config" not in r and r["policy"] != "zero"]
    strongest = min(baselines, key=lambda r: r["metric"]) if baselines else None
    for r in rows:
        if "config" not in r or strongest is None:
            continue
        ref = strongest["metric"]
        # a baseline at 0 (no capsize) cannot be beaten by 20 %: no gain, target not met
        gain = (ref - r["metric"]) / ref if ref > 0 else None
        r["gain_vs_strongest"] = gain
        r["target"] = bool(gain is not None and gain >= 0.2 and r["effort"] <= strongest["effort"])
        if frontier:
            at_effort = metric_at_effort(frontier, r["effort"])
            r["frontier_metric"] = at_effort
            r["gain_at_effort"] = (
                (at_effort - r["metric"]) / at_effort if at_effort is not None and at_effort > 0
                else None
            )  # fmt: skip
    return {
        "env_id": task.env_id,
        "metric": task.metric,
        "metric_label": task.metric_label,
        "strongest_baseline": strongest["policy"] if strongest else None,
        "rows": rows,
        "frontier_baseline": task.frontier if frontier else None,
        "frontier": [dataclasses.asdict(p) for p in frontier],
    }


def results_markdown(results: dict[str, Any]) -> str:
    """The tables of ``results.md``."""
    lines = [
        "# Learned vs classical controllers",
        "",
        "Every policy runs the same held-out episodes (seeds far from the training seeds). "
        "Effort = RMS action [-]; capsize rate with its Wilson 95 % interval; cost = the Safe-RL "
        "cost per episode (time in violation [control steps]); target = ≥ 20 % better than the "
        "strongest baseline on the task metric at equal or lower effort. Written by "
        "`ship-gym benchmark` (rerun it to reproduce; `ship-gym evaluate --policies "
        "model:docs/benchmarks/policies/<task>/<config>` evaluates a shipped policy).",
        "",
        "The classical baselines are designed from the ship's own linear model and tuned on "
        "training seeds by a script: the fin stabiliser, the heading autopilot and the ride "
        "controller by `scripts/tune_baseline.py RollStabilization|CourseKeeping|RideControl` "
        "(grids in `<task>_baseline_tuning.csv`, choice and held-out check in "
        "`<task>_baseline.json`), the CapsizeAvoidance master by "
        "`scripts/tune_capsize_master.py` (`capsize_master.json`). A `ppo_residual_*` config "
        "learns a correction of its task's tuned baseline, a = clip(a_baseline + scale · "
        "a_learned) (`ship_gym.agents.residual`). A config with a `[validation]` table keeps "
        "the checkpoint of best deterministic return on its validation seeds (from 5000 in "
        "the shipped configs), apart "
        'from the held-out ones (`ship_gym.agents.validation`; "model at" in the training-'
        "steps column). A config with a `[safe]` `effort_limit` trains with its actuator "
        "effort constrained (PPO-Lagrangian, `ship_gym.agents.lagrangian`; "
        '`effort_limit = "fins"` or `"pid"`: the tuned baseline\'s own effort; with '
        '`effort_measure = "episode_rms"` on the mean episode RMS action, this table\'s '
        "effort column, else on the mean square over all steps), and its validation keeps the "
        "best checkpoint within the baseline's effort on the validation episodes; the held-out "
        "seas may still ask a few per cent more or less of the policy than of the baseline.",
        "",
    ]
    for name, task in results["tasks"].items():
        first = task["seed"]
        budget = task["timesteps"] or "each config's total_timesteps"
        lines += [
            f"## {name} (`{task['env_id']}`)",
            "",
            f"Held-out seeds {first} … {first + task['episodes'] - 1}; training seeds 0 … "
            f"{task['n_seeds'] - 1}, budget {budget}; run {task['date']}"
            + "".join(f", {c} kept from the run of {d}" for c, d in task.get("kept", {}).items())
            + ". Task metric: "
            f"{task['metric_label']} (lower is better); strongest baseline: "
            f"{task['strongest_baseline']}.",
            "",
            f"| policy | {task['metric_label']} | effort | capsize [95 % CI] | return | cost | "
            "training steps | training wall [s] | steps/s | vs strongest | target | "
            "vs baseline at same effort |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|",
        ]
        for r in task["rows"]:
            low, high = r["capsize_ci95"]
            wall = f"{r['wall_s']:.0f}" if "wall_s" in r else "–"
            rate = f"{r['steps_per_s']:.0f}" if r.get("steps_per_s") else "–"
            steps = f"{r['timesteps'] / 1000:.0f} k" if r.get("timesteps") else "–"
            if r.get("model_timesteps"):
                steps += f" (model at {r['model_timesteps'] / 1000:.0f} k)"
            if r.get("gain_vs_strongest") is not None:
                gain = f"{100 * r['gain_vs_strongest']:+.0f} %"
            else:
                gain = "baseline at 0" if "gain_vs_strongest" in r else "–"
            target = ("met" if r["target"] else "not met") if "target" in r else "–"
            if r.get("gain_at_effort") is not None:
                matched = f"{100 * r['gain_at_effort']:+.0f} % (vs {r['frontier_metric']:.4g})"
            else:
                matched = "outside the gain range" if "gain_at_effort" in r else "–"
            lines.append(
                f"| {r['policy']} | {r['metric']:.4g} | {r['effort']:.3f} | "
                f"{r['capsized']}/{r['episodes']} [{low:.2f}, {high:.2f}] | "
                f"{r['mean_return']:.0f} | {r['mean_cost']:.2f} | {steps} | {wall} | {rate} | "
                f"{gain} | {target} | {matched} |"
            )
        lines += ["", f"![learning curves](curves_{name}.png)", ""]
        if task.get("frontier"):
            factors = ", ".join(f"{p['factor']:g}" for p in task["frontier"])
            lines += [
                f"*vs baseline at same effort*: against {task['frontier_baseline']} with its "
                f"gains scaled by {factors} (`ship_gym.agents.frontier`), on the same held-out "
                "episodes, read at the policy's own effort.",
                "",
                f"![effort frontier](frontier_{name}.png)",
                "",
            ]
    return "\n".join(lines)


def _plot_curves(name: str, task: BenchmarkTask, curves: dict[str, list[dict]], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ship_gym.io_utils import atomic_write

    validated = any("validation_return" in c for runs in curves.values() for c in runs)
    constrained = any(max(c.get("lambda") or [0.0]) > 0 for runs in curves.values() for c in runs)
    panels = 1 + validated + constrained
    fig, axes = plt.subplots(1, panels, figsize=(6.0 * panels if panels > 1 else 7.0, 4.2),
                             squeeze=False)  # fmt: skip
    colours = [plt.get_cmap("tab10")(i) for i in range(10)]
    for c, (config, runs) in enumerate(curves.items()):
        for k, curve in enumerate(runs):
            axes[0, 0].plot(curve["timesteps"], curve["mean_return"], color=colours[c % 10],
                            alpha=0.85, lw=1.2, label=config if k == 0 else None)  # fmt: skip
            if validated and "validation_return" in curve:
                axes[0, 1].plot(curve["validation_timesteps"], curve["validation_return"],
                                color=colours[c % 10], alpha=0.85, lw=1.2, marker=".",
                                label=config if k == 0 else None)  # fmt: skip
            if constrained and max(curve.get("lambda") or [0.0]) > 0:
                axes[0, -1].plot(curve["timesteps"], curve["lambda"], color=colours[c % 10],
                                 alpha=0.85, lw=1.0, label=config if k == 0 else None)  # fmt: skip
    axes[0, 0].set_ylabel("mean return of the last 100 training episodes [-]")
    axes[0, 0].set_title(f"{name}: stochastic training policy, one line per training seed",
                         fontsize=9)  # fmt: skip
    if validated:
        axes[0, 1].set_ylabel("mean return on the validation episodes [-]")
        axes[0, 1].set_title("deterministic policy on the validation seeds (model.zip: the best "
                             "point)", fontsize=9)  # fmt: skip
    if constrained:
        axes[0, -1].set_ylabel("Lagrange multiplier λ [reward / constraint unit]")
        axes[0, -1].set_title("[safe] runs: the constraint's price (0: within the budget)",
                              fontsize=9)  # fmt: skip
    for ax in axes[0]:
        ax.set_xlabel("training time steps [-]")
        ax.grid(alpha=0.3)
        if curves:
            ax.legend(fontsize=8)
    fig.tight_layout()
    atomic_write(path, lambda p: fig.savefig(p, dpi=110, format="png"))
    plt.close(fig)


def _plot_frontier(name: str, task: BenchmarkTask, result: dict[str, Any], path: Path) -> None:
    """Task metric against effort: the baseline's gain family, the baselines, the policies."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ship_gym.io_utils import atomic_write

    fig, ax = plt.subplots(figsize=(7.0, 4.6))
    points = result["frontier"]
    ax.plot([p["effort"] for p in points], [p["metric"] for p in points], "-o", color="0.45",
            ms=4, label=f"{result['frontier_baseline']}, gains x c")  # fmt: skip
    for p in points:
        ax.annotate(f"c={p['factor']:g}", (p["effort"], p["metric"]), fontsize=7,
                    textcoords="offset points", xytext=(3, 3), color="0.35")  # fmt: skip
    colours = [plt.get_cmap("tab10")(i) for i in range(10)]
    configs: list[str] = []
    for r in result["rows"]:
        if "config" in r:
            first = r["config"] not in configs
            if first:
                configs.append(r["config"])
            c = configs.index(r["config"])
            ax.plot(r["effort"], r["metric"], "D", color=colours[c % 10], ms=6,
                    label=r["config"] if first else None)  # fmt: skip
        elif r["policy"] != "zero":
            ax.plot(r["effort"], r["metric"], "s", color="k", ms=7, label=f"{r['policy']} (tuned)")
    ax.set_xlabel("effort: RMS action [-]")
    ax.set_ylabel(task.metric_label)
    ax.set_title(f"{name} ({task.env_id}): held-out episodes; lower left is better", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    atomic_write(path, lambda p: fig.savefig(p, dpi=110, format="png"))
    plt.close(fig)
