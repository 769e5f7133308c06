"""Capsize cells under a trained policy: the policy drives the environment it was trained in.

A campaign's ``controller = "policy:PATH"`` (:mod:`ship_gym.analysis.campaign`) names a run saved
by ``ship-gym train`` (its folder, or the ``model.zip`` in it, with the ``config.toml`` beside it
that names the environment and its arguments). Each cell is then an episode of that environment,
its seas and loading pinned to the cell's:

* the environment is built from the training ``[env] id`` and ``kwargs`` with the cell's ship
  (``ship``), loading (``kg_m``; a loading that sets anything but ``kg`` is refused), physics step
  (``physics_dt_s``), integrator, capsize angle (``capsize_angle_deg``), sea kind (``sea_kind``
  where the env has it), spreading (``wave_spreading_s``), components and ramp; its time limit is
  ``duration_s`` / the env's control step;
* each episode is reset with the cell's seed and ``options`` wave height, period (deep water,
  T = √(2πλ/g) for a regular wave given by λ), relative heading β and initial speed (the shaft
  at its calm-water self-propulsion rpm for that speed);
* the policy acts every control step (deterministic, with the ``VecNormalize`` statistics saved
  with it); the seeds of one task run as the episodes of one batched vector env.

The outcome record has the fields of :class:`~ship_gym.analysis.capsize_map.RunOutcome`: capsize
(the env's termination by |φ| past the capsize angle, or a diverged integration), its time, and
max |φ|, RMS φ after the ramp, max |θ|, max |ψ| from the initial (voyage) course, mean surge speed
after the ramp — sampled at the control steps (max |φ| over every physics step, from the env).

What differs from an autopilot cell, and must be kept in mind when the two are compared: the
model settings are the environment's (its mesh, wave-sum precision, control step and state-space
radiation), and the wave components of a seed are drawn by the environment (the same statistics,
not the same realisation as the autopilot cell of that seed).
"""

from __future__ import annotations

import hashlib
import inspect
import json
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "PolicyController",
    "check_policy_controller",
    "read_policy_controller",
    "run_policy_cells",
]

POLICY_PREFIX = "policy:"
"""How a campaign's ``controller`` names a trained policy (``"policy:runs/ppo_capsize"``)."""


@dataclass(frozen=True)
class PolicyController:
    """A trained policy saved by :func:`ship_gym.agents.train.train`, identified by content.

    Attributes
    ----------
    path : str
        Absolute path of its ``model.zip``.
    digest : str
        SHA-256 of ``model.zip``, its observation statistics (``vecnormalize.npz``, else a
        legacy ``vecnormalize.pkl``, if any) and the training env's id and kwargs: what a cell
        id hashes (not the path).
    env_id : str
        The environment it was trained in.
    env_kwargs : dict
        Its training kwargs.
    model_sha256 : str
        SHA-256 of ``model.zip`` alone: what every worker checks before loading the model
        (:func:`check_policy_controller` trusts it once, in the driver).
    """

    path: str
    digest: str
    env_id: str
    env_kwargs: dict
    model_sha256: str = ""


def check_policy_controller(controller: PolicyController, *, trusted: bool = False) -> None:
    """Refuse, before any cell runs, a policy this installation neither trained nor ships.

    Loading an SB3 model (and a legacy pickled ``vecnormalize.pkl``) runs code from the file
    (:mod:`ship_gym.envs.policy_trust`); ``trusted`` is the user's opt-in
    (``ship-gym campaign run --trust-policy``). The workers then load only a file whose
    SHA-256 is ``controller.model_sha256``.

    Raises
    ------
    UntrustedPolicyError
        A ValueError naming the file and the opt-in.
    """
    from ship_gym.envs.policy_trust import UntrustedPolicyError, check_policy_trust

    zip_path = Path(controller.path)
    check_policy_trust(zip_path.read_bytes(), zip_path, trusted=trusted)
    legacy = zip_path.parent / "vecnormalize.pkl"
    if not trusted and legacy.is_file() and not (zip_path.parent / "vecnormalize.npz").is_file():
        raise UntrustedPolicyError(
            f"{legacy}: observation statistics saved as a pickle (by an earlier version), which "
            "runs any code its author put in it when loaded; if you trust where it came from, "
            "pass --trust-policy to ship-gym campaign run; see docs/security.md"
        )


def read_policy_controller(path: str | os.PathLike[str], *, field: str) -> PolicyController:
    """Check a trained policy (a run folder or its ``model.zip``) and identify it.

    Parameters
    ----------
    path : str or path-like
        The run folder or ``model.zip``.
    field : str
        How the user wrote it (for the error messages), e.g. ``"controller = 'policy:run'"``.

    Raises
    ------
    ValueError
        No model, no ``config.toml`` naming a ship environment, or an environment that cannot
        take a campaign cell (not a ship task).
    """
    from ship_gym.envs.registration import env_class_of
    from ship_gym.envs.saved_policies import RESIDUAL_FILE, read_run_config

    p = Path(path)
    zip_path = p / "model.zip" if p.is_dir() else p
    if not zip_path.is_file():
        raise ValueError(f"{field}: no saved model at {zip_path}; expected a `ship-gym train` run")
    if (zip_path.parent / RESIDUAL_FILE).is_file():
        raise ValueError(
            f"{field}: {zip_path.parent} is a residual policy (a correction of the classical "
            f"controller in {RESIDUAL_FILE}), which campaign cells cannot run yet; expected a "
            "policy trained without a [residual] table"
        )
    config_path = zip_path.parent / "config.toml"
    if not config_path.is_file():
        raise ValueError(
            f"{field}: {config_path} is missing; expected the config.toml that `ship-gym train` "
            "writes beside model.zip (it names the environment the policy drives)"
        )
    try:
        env = read_run_config(config_path).get("env", {})
    except ValueError as exc:
        raise ValueError(f"{field}: {exc}") from None
    env_id, kwargs = env.get("id"), dict(env.get("kwargs", {}))
    if not isinstance(env_id, str):
        raise ValueError(f"{field}: {config_path} has no [env] id")
    try:
        env_class_of(env_id)
    except ValueError as exc:
        raise ValueError(f"{field}: {config_path}: {exc}") from None
    if "ship" not in _task_parameters(env_id):
        raise ValueError(
            f"{field}: the policy drives {env_id!r}, which has no ship model; expected a policy "
            "trained on a ship environment (CourseKeeping, RollStabilization, RideControl, "
            "CapsizeAvoidance)"
        )
    digest = hashlib.sha256()
    model = zip_path.read_bytes()
    statistics = zip_path.parent / "vecnormalize.npz"
    if not statistics.is_file():
        statistics = zip_path.parent / "vecnormalize.pkl"
    for part in (model, statistics.read_bytes() if statistics.is_file() else b"-"):
        digest.update(part)
    digest.update(json.dumps({"id": env_id, "kwargs": kwargs}, sort_keys=True).encode())
    return PolicyController(
        str(zip_path.resolve()),
        digest.hexdigest(),
        env_id,
        kwargs,
        model_sha256=hashlib.sha256(model).hexdigest(),
    )


def _task_parameters(env_id: str) -> Mapping[str, inspect.Parameter]:
    """The keyword arguments of an environment's task (name → parameter, with its default)."""
    from ship_gym.envs.registration import env_class_of

    return inspect.signature(env_class_of(env_id).task_class.__init__).parameters


def cell_env_kwargs(
    controller: PolicyController,
    *,
    ship: str,
    loading: dict[str, float],
    sea: Any,
    dt_s: float,
    integrator: str,
    capsize_angle_deg: float,
) -> dict[str, Any]:
    """The env kwargs of a cell: the training kwargs with the cell's ship, loading and sea.

    Raises
    ------
    ValueError
        For what the env cannot represent (naming the campaign field): a loading setting other
        than ``kg``, a sea kind, γ or spreading the env does not draw.
    """
    accepted = _task_parameters(controller.env_id)
    kwargs = dict(controller.env_kwargs)
    unknown = sorted(set(loading) - {"kg"})
    if unknown:
        raise ValueError(
            f"loadings: {unknown[0]} = {loading[unknown[0]]!r}; a policy's environment takes "
            "the loading as kg only (its kg_m)"
        )
    kwargs.update(ship=ship, physics_dt_s=dt_s, integrator=integrator)
    kwargs["capsize_angle_deg"] = capsize_angle_deg
    if "kg" in loading:
        kwargs["kg_m"] = float(loading["kg"])
    kwargs.pop("gm_range_m", None)  # the cell's loading, not a random one
    if "froude_range" in accepted:
        kwargs["froude_range"] = None  # the cell's speed (reset option)
    if "speed_range_mps" in accepted:
        kwargs["speed_range_mps"] = None
    kwargs["wave_ramp_time_s"] = float(sea.ramp_time)
    name = controller.env_id
    if "sea_kind" in accepted:
        kwargs["sea_kind"] = sea.kind
    elif sea.kind == "regular":
        raise ValueError(f"seas: a regular wave; the policy's {name} draws irregular seas only")
    if sea.kind == "irregular":
        kwargs["n_wave_components"] = int(sea.n_components)
        if sea.gamma != 3.3:
            raise ValueError(f"seas: gamma = {sea.gamma!r}; the policy's {name} draws γ = 3.3 only")
        if sea.spreading_s is not None:
            if "wave_spreading_s" not in accepted:
                raise ValueError(
                    f"seas: spreading_s = {sea.spreading_s!r}; the policy's {name} draws "
                    "long-crested seas only"
                )
            kwargs["wave_spreading_s"] = float(sea.spreading_s)
    return kwargs


def _period(sea: Any) -> float:
    if sea.kind == "regular":
        return float(sea.to_sea().period)
    return float(sea.period)


def run_policy_cells(
    controller: PolicyController,
    *,
    ship: str,
    loading: dict[str, float],
    sea: Any,
    heading_deg: float,
    speed_mps: float,
    seeds: list[int],
    duration_s: float,
    dt_s: float,
    integrator: str,
    capsize_angle_deg: float,
    trusted: bool = False,
) -> list[dict]:
    """Run the seeds of one cell group under the policy; one outcome dict per seed.

    The model is loaded only if its SHA-256 is still ``controller.model_sha256`` (the file the
    driver checked, :func:`check_policy_controller`).

    Parameters
    ----------
    controller : PolicyController
        The policy (:func:`read_policy_controller`).
    ship : str
        Ship name or file.
    loading : dict
        Loading overrides (``{"kg": …}`` [m] or empty).
    sea : SeaSpec
        The sea (:class:`~ship_gym.analysis.capsize_map.SeaSpec`).
    heading_deg : float
        Relative wave heading β [deg].
    speed_mps : float
        Initial speed [m/s].
    seeds : list of int
        One episode per seed.
    duration_s, dt_s : float
        Run length and physics step [s].
    integrator : str
        ``"holloway"`` or ``"rk4"``.
    capsize_angle_deg : float
        |φ| counted as capsize [deg].
    trusted : bool
        The user's opt-in (``--trust-policy``): also allows a legacy pickled
        ``vecnormalize.pkl``.

    Returns
    -------
    list of dict
        The :class:`~ship_gym.analysis.capsize_map.RunOutcome` fields and ``speed``, ``cpu_s``,
        ``engine`` (``"env:<id>"``), ``batch_size``.
    """
    import time

    import gymnasium

    from ship_gym.envs.saved_policies import load_policy

    t0 = time.process_time()
    kwargs = cell_env_kwargs(
        controller,
        ship=ship,
        loading=loading,
        sea=sea,
        dt_s=dt_s,
        integrator=integrator,
        capsize_angle_deg=capsize_angle_deg,
    )
    policy = load_policy(
        controller.path, trusted=trusted, expected_sha256=controller.model_sha256 or None
    )
    n = len(seeds)
    control_dt = float(
        kwargs.get("control_dt_s", _task_parameters(controller.env_id)["control_dt_s"].default)
    )
    steps = max(1, round(duration_s / control_dt))
    # Gymnasium's default NEXT_STEP autoreset: the step that ends an episode leaves its final
    # state in the simulator and its final info in ``infos`` (ended episodes are then ignored)
    env = gymnasium.make_vec(
        controller.env_id, num_envs=n, vectorization_mode="vector_entry_point",
        max_episode_steps=steps, **kwargs,
    )  # fmt: skip
    options = {
        "wave_height_m": float(sea.height),
        "wave_period_s": _period(sea),
        "wave_heading_deg": float(heading_deg),
        "initial_speed_mps": float(speed_mps),
    }
    try:
        task = env.unwrapped.task  # type: ignore[attr-defined]  # a TaskVectorEnv
        # one seed per episode (TaskVectorEnv; gymnasium types it int | None)
        obs, _ = env.reset(seed=[int(s) for s in seeds], options=options)  # type: ignore[arg-type]
        active = np.ones(n, dtype=bool)
        capsized = np.zeros(n, dtype=bool)
        diverged = np.zeros(n, dtype=bool)
        t_capsize = np.full(n, np.nan)
        sim_time = np.zeros(n)
        max_roll = np.zeros(n)
        max_pitch = np.zeros(n)
        max_heading = np.zeros(n)
        roll_sq, speed_sum, after = np.zeros(n), np.zeros(n), np.zeros(n)
        state, start = None, np.ones(n, dtype=bool)
        while active.any():
            action, state = policy.predict(obs, state=state, episode_start=start)
            start = np.zeros(n, dtype=bool)
            obs, _, terminated, truncated, infos = env.step(np.clip(action, -1.0, 1.0))
            eta, nu = task.sim.eta, task.sim.nu
            t = np.asarray(infos["time"], dtype=float)
            pitch = np.degrees(np.abs(eta[:, 4]))
            heading = np.degrees(np.abs((eta[:, 5] + math.pi) % (2 * math.pi) - math.pi))
            max_roll = np.where(active, np.maximum(max_roll, infos["max_roll_deg"]), max_roll)
            max_pitch = np.where(active, np.maximum(max_pitch, pitch), max_pitch)
            max_heading = np.where(active, np.maximum(max_heading, heading), max_heading)
            ended = (np.asarray(terminated) | np.asarray(truncated)) & active
            counted = active & (t > sea.ramp_time)
            roll_sq += np.where(counted, np.asarray(infos["roll_deg"]) ** 2, 0.0)
            speed_sum += np.where(counted, nu[:, 0], 0.0)
            after += counted
            sim_time = np.where(active, t, sim_time)
            if ended.any():
                cap = ended & np.asarray(terminated, bool)
                capsized |= cap & np.asarray(infos["capsized"], bool)
                diverged |= cap & np.asarray(infos["diverged"], bool)
                t_capsize = np.where(cap, t, t_capsize)
                active &= ~ended
    finally:
        env.close()
    cpu = (time.process_time() - t0) / n
    out = []
    for i in range(n):
        hit = bool(capsized[i] or diverged[i])
        out.append(
            {
                "capsized": hit,
                "reason": "diverged" if diverged[i] else ("roll" if capsized[i] else "none"),
                "time_to_capsize": float(t_capsize[i]) if hit else None,
                "max_abs_roll_deg": float(max_roll[i]),
                "rms_roll_deg": float(math.sqrt(roll_sq[i] / after[i])) if after[i] else math.nan,
                "max_abs_pitch_deg": float(max_pitch[i]),
                "max_heading_deviation_deg": float(max_heading[i]),
                "mean_speed": float(speed_sum[i] / after[i]) if after[i] else math.nan,
                "simulated_time": float(sim_time[i]),
                "speed": float(speed_mps),
                "cpu_s": cpu,
                "engine": f"env:{controller.env_id}",
                "batch_size": n,
            }
        )
    return out
