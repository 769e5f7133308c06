"""``ship-gym train``, ``evaluate`` and ``benchmark``: reinforcement learning on the ship_gym envs.

``train CONFIG`` trains a stable-baselines3 agent from a TOML configuration: a path, or the name
of a config shipped in :mod:`ship_gym.agents` (``ppo_roll_one_dof``, …; see
:mod:`ship_gym.agents.train`). ``evaluate`` runs classical baselines and saved models on the same
seeded seas and writes a table, JSON and a bar chart (:mod:`ship_gym.agents.evaluate`).
``benchmark`` trains the shipped configs with several seeds and compares them with the tasks'
strongest classical baselines on held-out seeds (:mod:`ship_gym.agents.benchmark`).
stable-baselines3 and torch are imported inside the commands, so ``ship-gym --help`` stays
instant; they need the ``agents`` extra (``pip install -e .[agents]``).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import Any

from ship_gym.agents.configs import shipped_config_names
from ship_gym.cli.common import (
    CLIError,
    add_overrides_argument,
    count,
    parse_overrides,
    prepare_output,
    prepare_output_dir,
    seed,
)


def _check_env_id(env_id: str, option: str = "--env") -> None:
    """Refuse an unregistered env id before any work (gymnasium's NameNotFound…)."""
    import gymnasium  # the ids are registered: importing ship_gym.cli imported ship_gym

    try:
        gymnasium.spec(env_id)
    except gymnasium.error.Error as exc:
        known = sorted(k for k in gymnasium.registry if k.startswith("ship_gym/"))
        raise CLIError(
            f"{option} {env_id!r}: {str(exc).rstrip('.')}; expected a registered id, e.g. "
            + ", ".join(known)
        ) from None


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``train`` and ``evaluate`` on the ``ship-gym`` parser."""
    p = sub.add_parser("train", help="train an SB3 agent (PPO, SAC…) from a TOML config")
    p.add_argument(
        "config",
        help="TOML configuration: a path, or the name of a shipped config ("
        + ", ".join(shipped_config_names())
        + "); relative paths inside it (output_dir) are from the working directory",
    )
    p.add_argument("--timesteps", type=count, default=None, help="override total_timesteps")
    p.add_argument("--seed", type=seed, default=None, help="override the seed")
    p.add_argument("--output", default=None, help="override the run directory")
    p.add_argument("--n-envs", type=count, default=None, help="override the number of episodes")
    p.add_argument("--device", default=None, help="torch device (cpu, cuda)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_train)

    p = sub.add_parser(
        "evaluate", help="compare baselines and trained models on the same seeded seas"
    )
    p.add_argument("--env", required=True, help="env id, e.g. ship_gym/RollOneDOF-v0")
    p.add_argument(
        "--policies",
        default="zero",
        help="comma-separated: zero, pid, fins, ride, imo-guidance (CapsizeAvoidance, "
        "HeavyWeather), keep, polar (HeavyWeather), model:RUN_DIR_OR_ZIP (default: zero)",
    )
    p.add_argument("--episodes", type=count, default=20, help="episodes per policy")
    p.add_argument("--seed", type=seed, default=0, help="episode k is reset with seed + k")
    p.add_argument("--max-steps", type=count, default=None, help="override the time limit")
    add_overrides_argument(p, "env keyword arguments (JSON values), e.g. forcing_amplitude=0.04")
    p.add_argument("--out", default="out/evaluation", help="directory for CSV, JSON and PNG")
    p.add_argument("--no-plot", action="store_true", help="skip the bar chart")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.add_argument("--json", default=None, help="also write the results JSON to this path")
    p.add_argument(
        "--no-training-env",
        action="store_true",
        help="run saved models with --set only, not the env settings they were trained with "
        "(by default a model's training [env] kwargs are applied, then --set)",
    )
    p.add_argument(
        "--trust-policy",
        action="store_true",
        help="load model:PATH files neither trained here nor shipped (loading a "
        "stable-baselines3 file runs code from it: only for files you trust; docs/security.md)",
    )
    p.set_defaults(func=_cmd_evaluate)

    from ship_gym.agents.benchmark import TASKS
    from ship_gym.agents.protocol import HELD_OUT_EPISODES, HELD_OUT_FIRST

    p = sub.add_parser(
        "benchmark",
        help="train the shipped configs (several seeds) and compare them with the strongest "
        "classical baselines on held-out seeds",
    )
    p.add_argument(
        "--tasks",
        default="CourseKeeping,RollStabilization,RideControl,CapsizeAvoidance",
        help="comma-separated, of " + ", ".join(TASKS),
    )
    p.add_argument("--seeds", type=count, default=3, help="training seeds per config")
    p.add_argument(
        "--timesteps",
        type=count,
        default=None,
        help="training budget per run (default: the published table's per task)",
    )
    p.add_argument(
        "--episodes",
        type=count,
        default=None,
        help=f"held-out episodes per policy (default: the published table's, {HELD_OUT_EPISODES})",
    )
    p.add_argument(
        "--seed",
        type=seed,
        default=HELD_OUT_FIRST,
        help=f"first held-out seed (default {HELD_OUT_FIRST}; lower seeds were used to train or "
        "to choose and are refused)",
    )
    p.add_argument(
        "--shipped",
        action="store_true",
        help="evaluate the shipped policies in --out/policies instead of training (how the "
        "published table is made)",
    )
    p.add_argument(
        "--configs",
        default=None,
        help="comma-separated shipped configs to train and evaluate; the tasks' other configs "
        "keep their rows from the earlier results.json in --out (default: all)",
    )
    p.add_argument("--out", default="docs/benchmarks", help="output folder")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.set_defaults(func=_cmd_benchmark)


def _cmd_benchmark(args: argparse.Namespace) -> int:
    from ship_gym.agents.benchmark import TASKS, check_benchmark_arguments, run_benchmark

    tasks = [t.strip() for t in args.tasks.split(",") if t.strip()]
    unknown = [t for t in tasks if t not in TASKS]
    if not tasks or unknown:
        raise CLIError(
            f"--tasks {args.tasks!r}: {'unknown ' + repr(unknown[0]) if unknown else 'empty'}; "
            f"expected comma-separated names of {', '.join(TASKS)}"
        )
    configs = None
    if args.configs is not None:
        configs = [c.strip() for c in args.configs.split(",") if c.strip()]
    try:
        check_benchmark_arguments(
            tasks, n_seeds=args.seeds, timesteps=args.timesteps, episodes=args.episodes,
            seed=args.seed, configs=configs,
        )  # fmt: skip
    except ValueError as exc:
        text = str(exc)
        if text.startswith("configs:"):
            raise CLIError(f"--configs {args.configs!r}:{text.removeprefix('configs:')}") from None
        raise CLIError(f"--seed {args.seed}: {text}" if "held-out" in text else text) from None
    prepare_output_dir(args.out, "--out")
    try:
        run_benchmark(
            tasks,
            args.out,
            n_seeds=args.seeds,
            timesteps=args.timesteps,
            episodes=args.episodes,
            seed=args.seed,
            configs=configs,
            shipped=args.shipped,
            progress=not args.no_progress,
        )
    except ValueError as exc:
        raise CLIError(str(exc)) from None
    print(f"wrote {Path(args.out) / 'results.md'}")
    return 0


def _cmd_train(args: argparse.Namespace) -> int:
    from ship_gym.agents.train import load_config, train

    config = load_config(
        args.config,
        total_timesteps=args.timesteps,
        seed=args.seed,
        output_dir=args.output,
        n_envs=args.n_envs,
        device=args.device,
        progress_bar=False if args.no_progress else None,
    )
    _check_env_id(config.env_id, f"{args.config}: [env] id")
    if Path(config.output_dir).exists() and not Path(config.output_dir).is_dir():
        raise CLIError(
            f"{'--output' if args.output else 'output_dir'}: {config.output_dir!r} is a file; "
            "expected a run directory"
        )
    prepare_output_dir(config.output_dir, "--output" if args.output else "output_dir")
    print(
        f"training {config.algorithm} on {config.env_id}: {config.n_envs} episodes "
        f"({config.vectorization}), {config.total_timesteps} steps, seed {config.seed} → "
        f"{config.output_dir}"
    )
    out = train(config)
    summary = json.loads((out / "summary.json").read_text())
    mean = summary["recent_mean_return"]
    print(
        f"done: {summary['num_timesteps']} steps in {summary['wall_time_s']:.0f} s "
        f"({summary['steps_per_s']:.0f} steps/s); recent mean return "
        f"{'n/a' if mean is None else f'{mean:.2f}'}; model {out / 'model.zip'}"
    )
    return 0


def _cmd_evaluate(args: argparse.Namespace) -> int:
    from ship_gym.agents.evaluate import METRICS, evaluate_policies, policy_labels, write_results
    from ship_gym.io_utils import atomic_write_text

    _check_env_id(args.env)
    policies = [p.strip() for p in args.policies.split(",") if p.strip()]
    if not policies:
        raise CLIError(
            "--policies: expected at least one of zero, pid, fins, ride, imo-guidance, keep, "
            "polar, model:PATH"
        )
    try:
        policy_labels(policies)
    except ValueError as exc:
        raise CLIError(str(exc)) from None
    from ship_gym.agents.baselines import BASELINES

    for spec in policies:
        if spec.startswith("model:"):
            path = Path(spec[len("model:") :])
            zip_path = path / "model.zip" if path.is_dir() else path
            if not zip_path.is_file():
                raise CLIError(f"--policies {spec}: no saved model at {zip_path}")
        elif spec not in BASELINES:
            raise CLIError(
                f"--policies: unknown policy {spec!r}; expected one of "
                + ", ".join(sorted(BASELINES))
                + " or model:PATH"
            )
    overrides = parse_overrides(args.set)
    prepare_output_dir(args.out, "--out")
    prepare_output(args.json, "--json")
    results = evaluate_policies(
        args.env,
        policies,
        args.episodes,
        args.seed,
        overrides,
        max_steps=args.max_steps,
        progress=not args.no_progress,
        use_training_env=not args.no_training_env,
        report=print,
        trusted=args.trust_policy,
    )
    out = write_results(results, args.out, plot=not args.no_plot)
    width = max(len(k) for k in results["policies"]) + 2
    settings: dict[str, Any] = next(iter(results["policy_env_kwargs"].values()), {})
    print(
        f"{args.env}: {args.episodes} episodes, seeds {args.seed}…{args.seed + args.episodes - 1}"
        f"; every row with {settings or 'the env defaults'}"
    )
    column = max(len(k) for k in METRICS) + 2
    print("policy".ljust(width) + "".join(k.rjust(column) for k in METRICS))
    for label, m in results["policies"].items():
        cells = "".join(
            ("n/a" if math.isnan(m[k]) else f"{m[k]:.4g}").rjust(column) for k in METRICS
        )
        print(label.ljust(width) + cells)
    print(
        f"wrote {out / 'evaluation.csv'}, evaluation.json"
        + ("" if args.no_plot else ", evaluation.png")
    )
    if args.json:
        atomic_write_text(Path(args.json), (out / "evaluation.json").read_text())
        print(f"wrote {args.json}")
    return 0
