"""The benchmark protocol: seed ranges that never mix, paired bootstrap and Wilson intervals.

A benchmark claim holds on unseen episodes only if the episodes it is measured on were never
used to choose anything (DESIGN §8). Every episode of a ship task is drawn from its reset seed
alone, so the protocol is a partition of the seeds:

==============  =====================  ===================================================
range           seeds                  used for
==============  =====================  ===================================================
training        0 … 4 999              training runs (a run with seed k resets its n_envs
                                       episodes with k … k + n_envs − 1) and the grids that
                                       tune the classical baselines
validation      5 000 … 6 999          choosing: checkpoints (the configs' ``[validation]``
                                       tables, 5 000 …), the shipped training seed of a
                                       config (:data:`SELECTION_SEEDS`), gains
burnt          7 000 … 19 999          used to choose in earlier rounds of the project (the
                                       shipped policies are the best of three training seeds
                                       *on* 10 000 …; the autopilot scan of issue #31 ran on
                                       7 000 … and 8 000 …): neither held out nor to be used
held-out        20 000 …               the benchmark's tables only (:data:`HELD_OUT_FIRST`,
                                       :data:`HELD_OUT_EPISODES` per task)
==============  =====================  ===================================================

:func:`check_disjoint` refuses ranges that overlap, :func:`check_held_out` held-out seeds
outside the held-out range, :func:`check_choice_seeds` seeds to choose on inside it.

Statistics: :func:`paired_bootstrap` resamples *episodes* (the same indices for both policies,
which ran the same seas) and gives a percentile interval of any statistic of the two policies'
per-episode values; :func:`relative_gain` is the statistic of the benchmark (how much lower the
candidate's mean is than the reference's), :func:`mean_ratio` its effort ratio.
:func:`wilson_interval` is the capsize rate's interval. :func:`verdict` judges a target on the
interval, not the point.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.analysis.capsize_statistics import wilson_interval

__all__ = [
    "BURNT_SEEDS",
    "HELD_OUT_EPISODES",
    "HELD_OUT_FIRST",
    "HELD_OUT_SEEDS",
    "SELECTION_SEEDS",
    "TRAINING_SEEDS",
    "TUNING_SEEDS",
    "VALIDATION_SEEDS",
    "Interval",
    "check_choice_seeds",
    "check_disjoint",
    "check_held_out",
    "mean_ratio",
    "paired_bootstrap",
    "relative_gain",
    "verdict",
    "wilson_interval",
]

TRAINING_SEEDS = range(0, 5_000)
"""Seeds of training runs and of the baselines' tuning grids."""
VALIDATION_SEEDS = range(5_000, 7_000)
"""Seeds on which checkpoints, training seeds and gains are chosen."""
BURNT_SEEDS = range(7_000, 20_000)
"""Seeds used to choose in earlier rounds (10 000 …: the shipped policies' training seed; 7 000 …,
8 000 …: the autopilot scan of issue #31): not held out any more, not to be used."""
HELD_OUT_FIRST = 20_000
"""First held-out seed (the benchmark's default ``--seed``)."""
HELD_OUT_SEEDS = range(HELD_OUT_FIRST, 2**31 - 1)
"""Seeds of the benchmark's tables only."""
HELD_OUT_EPISODES = 200
"""Held-out episodes per task and policy of the published tables."""
TUNING_SEEDS = range(0, 48)
"""The episodes of the baselines' tuning grids (``scripts/tune_baseline.py``)."""
SELECTION_SEEDS = range(6_000, 6_064)
"""The episodes on which ``ship-gym benchmark`` chooses the training seed it ships."""

_RANGES: Mapping[str, range] = {
    "training": TRAINING_SEEDS,
    "validation": VALIDATION_SEEDS,
    "burnt": BURNT_SEEDS,
    "held-out": HELD_OUT_SEEDS,
}


def _span(seeds: Iterable[int]) -> tuple[int, int]:
    values = [int(s) for s in seeds]
    return min(values), max(values)


def _text(seeds: Sequence[int] | range) -> str:
    low, high = _span(seeds)
    return f"{low} … {high}"


def check_disjoint(ranges: Mapping[str, Sequence[int] | range]) -> None:
    """Refuse seed sets that share a seed (ValueError naming both and the shared seeds)."""
    names = list(ranges)
    sets = {name: set(int(s) for s in ranges[name]) for name in names}
    for i, a in enumerate(names):
        for b in names[i + 1 :]:
            shared = sets[a] & sets[b]
            if shared:
                raise ValueError(
                    f"{a} seeds {_text(ranges[a])} and {b} seeds {_text(ranges[b])} overlap "
                    f"(seeds {_text(sorted(shared))}); expected disjoint ranges: an episode used "
                    "to train or choose is no longer held out"
                )


def check_held_out(seeds: Sequence[int] | range, **used: Sequence[int] | range) -> None:
    """Refuse held-out seeds outside :data:`HELD_OUT_SEEDS` or sharing a seed with ``used``
    (name → seeds: a run's training episodes, its validation seeds)."""
    if len(seeds) == 0:
        raise ValueError("held-out seeds: none given")
    low, high = _span(seeds)
    if low < HELD_OUT_SEEDS.start or high >= HELD_OUT_SEEDS.stop:
        where = next(
            (name for name, r in _RANGES.items() if name != "held-out" and low in r), "outside"
        )
        raise ValueError(
            f"held-out seeds {low} … {high} start in the {where} range "
            f"({_text(_RANGES[where]) if where in _RANGES else 'no range'}); expected seeds "
            f"≥ {HELD_OUT_FIRST} (seeds below were used to train or to choose)"
        )
    check_disjoint({"held-out": seeds, **used})


def check_choice_seeds(seeds: Sequence[int] | range, what: str) -> None:
    """Refuse seeds to tune or choose on (``what`` names them) that reach into the held-out or
    burnt ranges."""
    if len(seeds) == 0:
        raise ValueError(f"{what}: no seeds given")
    values = [int(s) for s in seeds]
    burnt = [s for s in values if s in BURNT_SEEDS]
    held_out = [s for s in values if s >= HELD_OUT_FIRST]
    for name, shared, span in (
        ("burnt", burnt, _text(BURNT_SEEDS)),
        ("held-out", held_out, f"{HELD_OUT_FIRST} …"),
    ):
        if shared:
            raise ValueError(
                f"{what} seeds {_text(values)} reach into the {name} range {span}; expected "
                f"training ({_text(TRAINING_SEEDS)}) or validation ({_text(VALIDATION_SEEDS)}) "
                "seeds"
            )


@dataclass(frozen=True)
class Interval:
    """A point estimate with its two-sided interval.

    Attributes
    ----------
    point : float
        The statistic on the episodes as drawn.
    low, high : float
        The interval's bounds.
    """

    point: float
    low: float
    high: float

    def as_list(self) -> list[float]:
        """``[point, low, high]`` (for JSON)."""
        return [self.point, self.low, self.high]


def relative_gain(reference: NDArray, candidate: NDArray) -> NDArray:
    """(mean_ref − mean_cand) / mean_ref along the last axis: how much lower the candidate is
    (lower is better; +0.2 = 20 % lower)."""
    ref = np.mean(reference, axis=-1)
    return (ref - np.mean(candidate, axis=-1)) / ref


def mean_ratio(reference: NDArray, candidate: NDArray) -> NDArray:
    """mean_cand / mean_ref along the last axis (an effort ratio)."""
    return np.mean(candidate, axis=-1) / np.mean(reference, axis=-1)


def paired_bootstrap(
    reference: ArrayLike,
    candidate: ArrayLike,
    statistic: Callable[[NDArray, NDArray], NDArray] = relative_gain,
    *,
    confidence: float = 0.95,
    resamples: int = 10_000,
    seed: int = 0,
) -> Interval:
    """Percentile interval of ``statistic`` by the paired bootstrap over episodes.

    Each resample draws n episode indices with replacement and evaluates ``statistic`` on both
    policies' values *at the same indices* (they ran the same seas, so the seas' variation
    cancels in the comparison; an unpaired bootstrap would add it back).

    Parameters
    ----------
    reference, candidate : array_like
        (n,) per-episode values of the two policies on the same episodes, in the same order.
    statistic : callable
        (…, n), (…, n) → (…) — vectorised over leading axes (:func:`relative_gain`,
        :func:`mean_ratio`).
    confidence : float
        Two-sided level in (0, 1).
    resamples : int
        Bootstrap resamples.
    seed : int
        Seed of the resampling (the interval is reproducible).

    Raises
    ------
    ValueError
        Arrays of different or zero length, non-finite values, a bad level or resample count.
    """
    ref = np.asarray(reference, dtype=float)
    cand = np.asarray(candidate, dtype=float)
    if ref.ndim != 1 or ref.shape != cand.shape or ref.size == 0:
        raise ValueError(
            f"reference and candidate must be (n,) arrays of the same episodes, got shapes "
            f"{ref.shape} and {cand.shape}"
        )
    if not (np.all(np.isfinite(ref)) and np.all(np.isfinite(cand))):
        raise ValueError("reference and candidate must be finite per-episode values")
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence!r}")
    if isinstance(resamples, bool) or not isinstance(resamples, int) or resamples < 1:
        raise ValueError(f"resamples must be a positive integer, got {resamples!r}")
    rng = np.random.default_rng(seed)
    index = rng.integers(0, ref.size, size=(resamples, ref.size))
    with np.errstate(divide="ignore", invalid="ignore"):
        values = np.asarray(statistic(ref[index], cand[index]), dtype=float)
        point = float(statistic(ref, cand))
    tail = 100.0 * (1.0 - confidence) / 2.0
    low, high = np.nanpercentile(values, [tail, 100.0 - tail])
    return Interval(point, float(low), float(high))


def verdict(interval: Interval, target: float) -> str:
    """A target judged on the interval: ``"met"`` (the whole interval ≥ target), ``"not met"``
    (the whole interval < target) or ``"undecided"`` (it straddles the target: more episodes
    or a larger margin needed)."""
    if interval.low >= target:
        return "met"
    if interval.high < target:
        return "not met"
    return "undecided"
