"""Train stable-baselines3 agents as Ray tasks: the capsize campaigns' cluster, reused for RL.

:func:`train_on_ray` runs one :func:`ship_gym.agents.train.train` per (config, seed) pair, each
as a one-CPU Ray task (:class:`ship_gym.analysis.executors.RayExecutor`): a local cluster of
``workers`` CPUs by default, an existing one with ``address``. The configuration is read and
validated here, in the driver; the environment is created inside the worker (the task imports
ship_gym and builds the SB3 VecEnv there), so nothing but the small
:class:`~ship_gym.agents.train.TrainConfig` travels to the workers. Example, two seeds of the
shipped ``ppo_roll_one_dof`` config on a local two-CPU cluster::

    from ship_gym.agents.distributed import train_on_ray

    models = train_on_ray(["ppo_roll_one_dof"], [0, 1], workers=2, timesteps=50_000,
                          output_dir="runs/ray")
    # runs/ray/ppo_roll_one_dof/seed_0/model.zip, runs/ray/ppo_roll_one_dof/seed_1/model.zip

Each run directory holds what ``ship-gym train`` writes (``model.zip``, ``config.toml``,
``summary.json``, ``vecnormalize.npz`` when normalising; :mod:`ship_gym.agents.train`). Requires
the ``agents`` and ``distributed`` extras (``pip install 'ship_gym[agents,distributed]'``).
With a remote cluster, ``output_dir`` must be a path every node can write to (a shared
filesystem): the runs are saved where their tasks run.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from ship_gym.agents.train import TrainConfig, load_config

__all__ = ["plan_runs", "train_on_ray"]


def _run_name(config: str) -> str:
    """Directory name of a config: its file stem (``"ppo_roll_one_dof"``)."""
    return Path(config).name.removesuffix(".toml")


def plan_runs(
    configs: Sequence[str],
    seeds: Sequence[int],
    *,
    timesteps: int | None = None,
    n_envs: int | None = None,
    tensorboard: bool | None = None,
    output_dir: str | Path = "runs/ray",
) -> list[TrainConfig]:
    """The validated training configurations of every (config, seed) pair, config-major.

    Parameters
    ----------
    configs : sequence of str
        TOML files or names of shipped configs (:func:`ship_gym.agents.train.load_config`).
    seeds : sequence of int
        Training seeds; each config runs once per seed.
    timesteps : int, optional
        Environment steps per run (overrides ``training.total_timesteps``).
    n_envs : int, optional
        Parallel episodes per run (overrides ``env.n_envs``).
    tensorboard : bool, optional
        Override ``training.tensorboard``.
    output_dir : str or Path
        Root of the run directories ``<output_dir>/<config stem>/seed_<seed>`` (made absolute
        against the driver's working directory).

    Raises
    ------
    ValueError
        No configs or no seeds, a non-integer or repeated seed, two configs with the same stem,
        or an invalid config / override.
    FileNotFoundError
        A config that is neither a file nor a shipped name.
    """
    if isinstance(configs, str) or not configs:
        raise ValueError(f"configs must be a non-empty sequence of config names, got {configs!r}")
    if not seeds:
        raise ValueError(f"seeds must be a non-empty sequence of integers, got {seeds!r}")
    for seed in seeds:
        if isinstance(seed, bool) or not isinstance(seed, int):
            raise ValueError(f"seeds must be integers, got {seed!r} in {list(seeds)!r}")
    if len(set(seeds)) != len(seeds):
        raise ValueError(f"seeds must be distinct, got {list(seeds)!r}")
    names = [_run_name(c) for c in configs]
    if len(set(names)) != len(names):
        raise ValueError(f"configs must have distinct file names, got {list(configs)!r}")
    root = Path(output_dir).absolute()
    if root.exists() and not root.is_dir():
        raise ValueError(f"output_dir {str(output_dir)!r} is a file; expected a directory")
    plans: list[TrainConfig] = []
    for config, name in zip(configs, names, strict=True):
        for seed in seeds:
            plans.append(
                load_config(
                    config,
                    total_timesteps=timesteps,
                    seed=seed,
                    output_dir=str(root / name / f"seed_{seed}"),
                    n_envs=n_envs,
                    tensorboard=tensorboard,
                    progress_bar=False,  # no terminal in a worker
                )
            )
    return plans


def _train_task(config: TrainConfig) -> str:
    """Ray task: build the env and train in this worker; the saved model's path."""
    from ship_gym.agents.train import train

    return str(train(config) / "model.zip")


def train_on_ray(
    configs: Sequence[str],
    seeds: Sequence[int],
    *,
    address: str | None = None,
    workers: int = 2,
    timesteps: int | None = None,
    n_envs: int | None = None,
    tensorboard: bool | None = None,
    output_dir: str | Path = "runs/ray",
) -> list[Path]:
    """Train every (config, seed) pair as a Ray task; the saved models, in (config, seed) order.

    Parameters
    ----------
    configs : sequence of str
        TOML files or names of shipped configs, e.g. ``["ppo_roll_one_dof"]``.
    seeds : sequence of int
        Training seeds (distinct).
    address : str, optional
        Ray cluster to join (``"auto"``, ``"ray://host:10001"``). Default: reuse a Ray the
        caller initialised, else start a local cluster of ``workers`` CPUs (shut down at the
        end).
    workers : int
        CPUs of the local cluster (≥ 1); one run per CPU at a time.
    timesteps : int, optional
        Environment steps per run (overrides the configs' ``total_timesteps``).
    n_envs : int, optional
        Parallel episodes per run (overrides the configs' ``n_envs``).
    tensorboard : bool, optional
        Override the configs' ``tensorboard``.
    output_dir : str or Path
        Root of the run directories ``<output_dir>/<config stem>/seed_<seed>``.

    Returns
    -------
    list of Path
        ``model.zip`` of each run (load with the algorithm's ``load``, e.g. ``PPO.load``).

    Raises
    ------
    ImportError
        Ray is not installed (``pip install 'ship_gym[distributed]'``).
    ValueError, FileNotFoundError
        From :func:`plan_runs`, before any cluster is started.
    """
    from ship_gym.analysis.executors import RayExecutor

    plans = plan_runs(
        configs,
        seeds,
        timesteps=timesteps,
        n_envs=n_envs,
        tensorboard=tensorboard,
        output_dir=output_dir,
    )
    for plan in plans:
        Path(plan.output_dir).mkdir(parents=True, exist_ok=True)
    models: list[Path | None] = [None] * len(plans)
    with RayExecutor(workers, address=address) as executor:
        for index, model in executor.map_unordered(_train_task, plans):
            models[index] = Path(model)
    missing = [p.output_dir for p, m in zip(plans, models, strict=True) if m is None]
    if missing:  # pragma: no cover - map_unordered yields every item or raises
        raise RuntimeError(f"runs without a model: {missing}")
    return [m for m in models if m is not None]
