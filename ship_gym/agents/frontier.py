"""The effort–performance frontier of a classical controller: its gains scaled up and down.

A tuned controller is one point of a trade-off: more gain buys a smaller task error (RMS roll,
heading error, vertical acceleration) with more actuator effort, up to saturation. Comparing a
learned policy with that one point says little when the two use different effort — a policy
that rolls 17 % less with 14 % more fin may or may not be better than the same fins driven
harder. The frontier answers it: the baseline's feedback gains
(:meth:`~ship_gym.agents.baselines.Baseline.gain_names`, e.g. k_φ and k_p of the fin law, K_p,
K_d and K_i of the PID) multiplied by factors c around 1 — a one-parameter family through the
tuned point, c = 1, which scales the loop gain and keeps the tuned shape of the law (the PID's
zeros, the ratio of roll-angle to roll-rate feedback) — each run on the same episodes as the
policies compared. :func:`metric_at_effort` reads the family's task metric at a given effort off
the non-dominated points (linear interpolation in effort), so a learned policy's metric can be
set against the classical one *at its own effort*.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ship_gym.agents.baselines import Baseline, make_baseline

__all__ = [
    "GAIN_FACTORS",
    "FrontierPoint",
    "baseline_frontier",
    "gain_scaled_baseline",
    "metric_at_effort",
]

GAIN_FACTORS: tuple[float, ...] = (0.25, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 4.0)
"""Default gain factors c of the frontier [-] (a factor √2 apart around the tuned c = 1)."""


@dataclass(frozen=True)
class FrontierPoint:
    """One controller of the family.

    Attributes
    ----------
    factor : float
        Gain factor c [-] (1: the tuned controller).
    effort : float
        Mean RMS action over the episodes [-].
    metric : float
        Mean task metric over the episodes [its unit].
    mean_return : float
        Mean episode return [-].
    """

    factor: float
    effort: float
    metric: float
    mean_return: float


def gain_scaled_baseline(
    name: str, env: Any, factor: float, *, env_id: str | None = None
) -> Baseline:
    """Baseline ``name`` for ``env`` (per-env default gains) with every ``k_*`` gain × ``factor``.

    Raises
    ------
    ValueError
        ``factor`` not a finite number > 0, or a baseline without gains (``zero``,
        ``imo-guidance``'s rule has no loop gain).
    """
    if not (isinstance(factor, int | float) and np.isfinite(factor) and factor > 0):
        raise ValueError(f"factor must be a finite number > 0, got {factor!r}")
    tuned = make_baseline(name, env, env_id=env_id)
    gains = {key: getattr(tuned, key) * float(factor) for key in tuned.gain_names()}
    if not gains:
        raise ValueError(f"baseline {name!r} has no k_* gains to scale")
    return make_baseline(name, env, env_id=env_id, **gains)


def baseline_frontier(
    env_id: str,
    name: str,
    metric: str,
    seeds: Sequence[int],
    env_kwargs: Mapping[str, Any] | None = None,
    *,
    factors: Sequence[float] = GAIN_FACTORS,
    progress: bool = False,
) -> list[FrontierPoint]:
    """Run the gain-scaled family of baseline ``name`` on one episode per seed.

    Parameters
    ----------
    env_id : str
        Registered id.
    name : str
        Baseline name (:data:`~ship_gym.agents.baselines.BASELINES`) with ``k_*`` gains.
    metric : str
        Task metric, a key of :func:`ship_gym.agents.evaluate.summarize`.
    seeds : sequence of int
        The episodes (those of the policies compared).
    env_kwargs : mapping, optional
        Environment keyword arguments.
    factors : sequence of float
        Gain factors c [-].
    progress : bool
        A progress bar over the factors.

    Returns
    -------
    list of FrontierPoint
        One per factor, in the order given.
    """
    from ship_gym.agents.evaluate import run_episodes, summarize

    if not factors:
        raise ValueError("factors must hold at least one gain factor")
    iterator: Any = factors
    if progress:
        from tqdm.auto import tqdm

        iterator = tqdm(factors, desc=f"{name} gain frontier", unit="gain", leave=False)
    points = []
    for c in iterator:

        def scaled(env: Any, c: float = float(c)) -> Baseline:
            return gain_scaled_baseline(name, env, c, env_id=env_id)

        stats = run_episodes(env_id, scaled, seeds, env_kwargs)
        summary = summarize(stats)
        points.append(
            FrontierPoint(
                factor=float(c),
                effort=summary["rms_action"],
                metric=summary[metric],
                mean_return=summary["mean_return"],
            )
        )
    return points


def metric_at_effort(points: Sequence[FrontierPoint], effort: float) -> float | None:
    """The best task metric (lower is better) the family reaches with no more than ``effort``:
    linear interpolation in effort between its non-dominated points (none of them has both less
    effort and a lower metric); beyond the last of them, its metric (more gain did not help).
    None outside the effort range the family was run over."""
    if not points:
        return None
    efforts = [p.effort for p in points]
    if not min(efforts) <= effort <= max(efforts):
        return None
    kept: list[FrontierPoint] = []
    for p in sorted(points, key=lambda p: (p.effort, p.metric)):
        if not kept or p.metric < kept[-1].metric:
            kept.append(p)
    return float(np.interp(effort, [p.effort for p in kept], [p.metric for p in kept]))
