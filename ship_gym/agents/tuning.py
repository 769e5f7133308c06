"""Grid tuning of a classical baseline until its optimum lies inside the grid.

A baseline tuned on a grid whose best point lies on the grid's edge is not tuned: the optimum may
lie beyond (issue #31: the CourseKeeping autopilot's grid optimum sat on ζ = 0.7, its smallest
damping, and ζ = 0.3 was far better). :func:`tune_grid` evaluates every point of a grid, and
while the best point lies on an edge of an axis that may go further, it widens that axis by one
step (the step of the two outermost values, clipped to the axis's physical bounds), says so, and
evaluates the new points; it stops when the optimum is inside (or on a physical bound: a gain
cannot go below 0) or after ``max_widenings`` widenings (then the result says the optimum is
still on the edge).

The criterion (:func:`default_score`) counts capsizes first — a controller that capsizes on
the tuning episodes loses to any that does not, whatever its return (a capsized episode ends
early and may so collect *less* negative reward) — then the mean return, the env's own trade-off
of the task error against the actuator's effort and wear.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

__all__ = [
    "Axis",
    "TuningResult",
    "default_score",
    "one_standard_error_choice",
    "tune_grid",
]


@dataclass(frozen=True)
class Axis:
    """One tuned parameter.

    Attributes
    ----------
    name : str
        Parameter name (a key of the points given to the evaluation).
    values : tuple of float
        Its grid values, at least 3, strictly increasing.
    lower, upper : float
        Physical bounds (inclusive): the grid is never widened past them, and an optimum on
        a bound counts as found.
    """

    name: str
    values: tuple[float, ...]
    lower: float = -math.inf
    upper: float = math.inf

    def __post_init__(self) -> None:
        v = tuple(float(x) for x in self.values)
        if len(v) < 3 or any(b <= a for a, b in itertools.pairwise(v)):
            raise ValueError(
                f"axis {self.name}: values must be ≥ 3 strictly increasing numbers (an optimum "
                f"can only lie inside a grid of three), got {self.values!r}"
            )
        if not self.lower <= v[0] or not v[-1] <= self.upper:
            raise ValueError(
                f"axis {self.name}: values {v} leave the bounds [{self.lower}, {self.upper}]"
            )
        object.__setattr__(self, "values", v)


@dataclass
class TuningResult:
    """What :func:`tune_grid` found.

    Attributes
    ----------
    rows : list of dict
        Every evaluated point (its parameters and the evaluation's results), in order.
    best : dict
        The chosen row.
    axes : dict
        The final grid per axis.
    position : dict
        Per axis, where the optimum lies: ``"inside"``, ``"on the lower bound"``, ``"on the
        upper bound"`` (a physical limit) or ``"on the edge"`` (widening stopped).
    widenings : list of str
        The messages of each widening.
    """

    rows: list[dict[str, Any]]
    best: dict[str, Any]
    axes: dict[str, tuple[float, ...]]
    position: dict[str, str]
    widenings: list[str] = field(default_factory=list)

    @property
    def inside(self) -> bool:
        """The optimum lies inside the grid or on a physical bound along every axis."""
        return all(p != "on the edge" for p in self.position.values())


def default_score(row: Mapping[str, Any]) -> tuple[float, float]:
    """Larger is better: fewest capsizes (``capsized``), then highest ``mean_return``."""
    return (-float(row["capsized"]), float(row["mean_return"]))


def one_standard_error_choice(
    metric: str, returns: str = "returns"
) -> Callable[[Sequence[Mapping[str, Any]]], Mapping[str, Any]]:
    """A ``choose`` for :func:`tune_grid`: among the points the tuning episodes cannot tell
    apart from the best by :func:`default_score` — as many capsizes, and a mean return below
    the best's by less than one standard error of their paired per-episode difference (rows
    hold the per-episode returns under ``returns``) — the one lowest on the task ``metric``
    (on equal metrics, e.g. a capsize rate of 0, the best return).

    The return of a regulation task is often flat across a ridge of gains (the CourseKeeping
    autopilot: within 0.3 of −59.5 from ζ 0.05, no derivative action, to ζ 0.2), and the best
    return on a few dozen episodes is then chosen by noise; this rule (Breiman's one-standard-
    error rule, with the task metric as the tie-break) gives the strongest baseline on the
    metric among the equally good ones."""

    def choose(rows: Sequence[Mapping[str, Any]]) -> Mapping[str, Any]:
        import numpy as np

        top = max(rows, key=default_score)
        best = np.asarray(top[returns], dtype=float)

        def near(row: Mapping[str, Any]) -> bool:
            if row["capsized"] != top["capsized"] or returns not in row:
                return False
            difference = best - np.asarray(row[returns], dtype=float)
            error = difference.std(ddof=1) / np.sqrt(difference.size)
            return bool(difference.mean() <= error)

        return min(
            (r for r in rows if near(r)),
            key=lambda r: (float(r[metric]), -float(r["mean_return"])),
        )

    return choose


def _key(point: Mapping[str, float], names: Sequence[str]) -> tuple[float, ...]:
    return tuple(round(float(point[n]), 12) for n in names)


def tune_grid(
    axes: Sequence[Axis],
    evaluate: Callable[[dict[str, float]], Mapping[str, Any]],
    *,
    score: Callable[[Mapping[str, Any]], Any] = default_score,
    choose: Callable[[Sequence[Mapping[str, Any]]], Mapping[str, Any]] | None = None,
    max_widenings: int = 4,
    report: Callable[[str], None] = print,
) -> TuningResult:
    """Evaluate the grid, widening it until the best point is inside (module docstring).

    Parameters
    ----------
    axes : sequence of Axis
        The tuned parameters.
    evaluate : callable
        point (name → value) → results (with what ``score`` reads); called once per point.
    score : callable
        Row → a comparable value, larger is better (:func:`default_score`).
    choose : callable, optional
        The grid's rows → the chosen one (default: the best by ``score``;
        :func:`one_standard_error_choice`).
    max_widenings : int
        Widening rounds at most.
    report : callable
        Where the widening messages go.
    """
    names = [a.name for a in axes]
    grid: dict[str, list[float]] = {a.name: list(a.values) for a in axes}
    bounds = {a.name: (a.lower, a.upper) for a in axes}
    done: dict[tuple[float, ...], dict[str, Any]] = {}
    rows: list[dict[str, Any]] = []
    widenings: list[str] = []
    rounds = 0
    while True:
        for combination in itertools.product(*(grid[n] for n in names)):
            point = dict(zip(names, combination, strict=True))
            key = _key(point, names)
            if key not in done:
                row = {**point, **evaluate(dict(point))}
                done[key] = row
                rows.append(row)
        in_grid = [done[_key(dict(zip(names, v, strict=True)), names)]
                   for v in itertools.product(*(grid[n] for n in names))]  # fmt: skip
        best = dict(choose(in_grid)) if choose is not None else max(in_grid, key=score)
        position: dict[str, str] = {}
        wider: dict[str, list[float]] = {}
        for n in names:
            axis, (lower, upper) = grid[n], bounds[n]
            v = best[n]
            if axis[0] < v < axis[-1]:
                position[n] = "inside"
                continue
            at_top = v == axis[-1]
            bound = upper if at_top else lower
            if v == bound:
                position[n] = f"on the {'upper' if at_top else 'lower'} bound"
                continue
            position[n] = "on the edge"
            step = axis[-1] - axis[-2] if at_top else axis[1] - axis[0]
            new = round(min(upper, v + step) if at_top else max(lower, v - step), 10)
            wider[n] = [*axis, new] if at_top else [new, *axis]
        if not wider or rounds >= max_widenings:
            break
        rounds += 1
        for n, widened in wider.items():
            message = (
                f"optimum {n} = {best[n]:g} on the edge of the grid {grid[n]}: widening to "
                f"{widened}"
            )
            report(message)
            widenings.append(message)
            grid[n] = widened
    return TuningResult(rows, best, {n: tuple(grid[n]) for n in names}, position, widenings)
