"""Statistics of capsize campaigns: binomial confidence intervals, seeds needed, survival, plots.

A cell of a campaign (:mod:`ship_gym.analysis.campaign`) is run for n seeds, k of which capsize;
its capsize probability is estimated by p̂ = k/n. The seeds are independent Bernoulli trials, so
the uncertainty of p̂ is that of a binomial proportion:

* :func:`wilson_interval` — the Wilson score interval (Wilson 1927): the set of p for which the
  score test does not reject at the given level. Good coverage even for small n and for k = 0 or
  k = n, where the Wald interval p̂ ± z √(p̂(1−p̂)/n) collapses to a point;
* :func:`clopper_pearson_interval` — the "exact" interval (Clopper & Pearson 1934) from the beta
  quantiles: coverage at least the nominal level for every p (conservative: wider).

:func:`seeds_for_half_width` turns a planning value of p into the number of seeds for which the
Wilson interval's half-width is at most a target (the convergence check of ``ship-gym campaign
report``). Times to capsize are *right-censored*: a run that did not capsize within its duration
T only says t_capsize > T; :func:`kaplan_meier` estimates the survival function S(t) = P(no capsize
by t) with that censoring, and :func:`plot_polar_capsize` draws the map with its intervals.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "CellSummary",
    "SurvivalCurve",
    "clopper_pearson_interval",
    "kaplan_meier",
    "plot_polar_capsize",
    "plot_survival",
    "seeds_for_half_width",
    "summarise_cells",
    "wilson_half_width",
    "wilson_interval",
]


def _z(confidence: float) -> float:
    """Two-sided standard-normal quantile z for a confidence level in (0, 1)."""
    from scipy.stats import norm

    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence!r}")
    return float(norm.ppf(0.5 + confidence / 2.0))


def _check_kn(k: int, n: int) -> None:
    if int(n) != n or n < 1:
        raise ValueError(f"n must be an integer >= 1 (the number of seeds), got {n!r}")
    if int(k) != k or not 0 <= k <= n:
        raise ValueError(f"k must be an integer in [0, n = {n}] (the capsizes), got {k!r}")


def wilson_interval(k: int, n: int, confidence: float = 0.95) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion.

    (p̂ + z²/2n ± z √(p̂(1−p̂)/n + z²/4n²)) / (1 + z²/n), p̂ = k/n.

    Parameters
    ----------
    k : int
        Successes (capsizes), 0 ≤ k ≤ n.
    n : int
        Trials (seeds), ≥ 1.
    confidence : float
        Two-sided confidence level in (0, 1), e.g. 0.95.

    Returns
    -------
    tuple of float
        (lower, upper), within [0, 1].
    """
    _check_kn(k, n)
    z = _z(confidence)
    p = k / n
    denom = 1.0 + z * z / n
    centre = (p + z * z / (2.0 * n)) / denom
    half = z * math.sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n)) / denom
    lo = 0.0 if k == 0 else max(0.0, centre - half)
    hi = 1.0 if k == n else min(1.0, centre + half)
    return lo, hi


def clopper_pearson_interval(k: int, n: int, confidence: float = 0.95) -> tuple[float, float]:
    """Clopper–Pearson ("exact") interval: beta quantiles B(α/2; k, n−k+1), B(1−α/2; k+1, n−k).

    Parameters
    ----------
    k : int
        Successes (capsizes), 0 ≤ k ≤ n.
    n : int
        Trials (seeds), ≥ 1.
    confidence : float
        Two-sided confidence level in (0, 1).

    Returns
    -------
    tuple of float
        (lower, upper); lower = 0 for k = 0, upper = 1 for k = n.
    """
    from scipy.stats import beta

    _check_kn(k, n)
    _z(confidence)  # validates the level
    alpha = 1.0 - confidence
    lo = 0.0 if k == 0 else float(beta.ppf(alpha / 2.0, k, n - k + 1))
    hi = 1.0 if k == n else float(beta.ppf(1.0 - alpha / 2.0, k + 1, n - k))
    return lo, hi


def wilson_half_width(p: float, n: int, confidence: float = 0.95) -> float:
    """Half-width of the Wilson interval for an observed proportion ``p`` over ``n`` trials
    (the formula of :func:`wilson_interval` with p̂ = p, before clipping to [0, 1])."""
    z = _z(confidence)
    return z * math.sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n)) / (1.0 + z * z / n)


def seeds_for_half_width(p: float, half_width: float, confidence: float = 0.95) -> int:
    """Fewest seeds n for which the Wilson interval around p̂ = ``p`` has half-width ≤ target.

    The half-width decreases monotonically with n; the answer is found by bisection. For a
    cell, use its current p̂ (p̂ = 0 or 1 still needs seeds: the Wilson half-width is
    z²/(2(n + z²)) there); 0.5 is the worst case.

    Parameters
    ----------
    p : float
        Planning value of the capsize probability, in [0, 1].
    half_width : float
        Target half-width of the interval, in (0, 0.5].
    confidence : float
        Confidence level in (0, 1).
    """
    if not (math.isfinite(p) and 0.0 <= p <= 1.0):
        raise ValueError(f"p must lie in [0, 1], got {p!r}")
    if not (math.isfinite(half_width) and 0.0 < half_width <= 0.5):
        raise ValueError(f"half_width must lie in (0, 0.5], got {half_width!r}")
    lo, hi = 1, 2
    while wilson_half_width(p, hi, confidence) > half_width:
        lo, hi = hi, hi * 2
    while lo < hi:
        mid = (lo + hi) // 2
        if wilson_half_width(p, mid, confidence) > half_width:
            lo = mid + 1
        else:
            hi = mid
    return lo


@dataclass(frozen=True)
class SurvivalCurve:
    """Kaplan–Meier estimate of P(no capsize by t) from right-censored runs.

    Attributes
    ----------
    time : ndarray
        Distinct capsize times t_i [s], ascending (with t = 0 first).
    survival : ndarray
        Ŝ(t) just after each time [-] (1 at t = 0).
    at_risk : ndarray
        Runs still afloat and not censored just before t_i.
    events : ndarray
        Capsizes at t_i.
    lower, upper : ndarray
        Pointwise confidence band (Greenwood variance, clipped to [0, 1]).
    n : int
        Runs.
    """

    time: np.ndarray
    survival: np.ndarray
    at_risk: np.ndarray
    events: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    n: int

    def median(self) -> float:
        """Median time to capsize [s]: first t with Ŝ(t) ≤ 0.5 (NaN if Ŝ stays above)."""
        below = np.flatnonzero(self.survival <= 0.5)
        return float(self.time[below[0]]) if below.size else math.nan


def kaplan_meier(
    times: Sequence[float], capsized: Sequence[bool], confidence: float = 0.95
) -> SurvivalCurve:
    """Kaplan–Meier survival of the time to capsize, censored at the end of each run.

    Parameters
    ----------
    times : sequence of float
        Time to capsize [s] for a capsized run, the simulated duration [s] otherwise.
    capsized : sequence of bool
        Whether each run capsized (False: censored at its time).
    confidence : float
        Level of the pointwise Greenwood band.
    """
    t = np.asarray(times, dtype=float)
    e = np.asarray(capsized, dtype=bool)
    if t.shape != e.shape or t.ndim != 1 or t.size == 0:
        raise ValueError("times and capsized must be 1-D sequences of the same, non-zero length")
    z = _z(confidence)
    out_t, out_s, out_r, out_d, var = [0.0], [1.0], [t.size], [0], [0.0]
    s, greenwood = 1.0, 0.0
    for ti in np.unique(t[e]):
        at_risk = int(np.sum(t >= ti))
        d = int(np.sum((t == ti) & e))
        s *= 1.0 - d / at_risk
        if at_risk > d:
            greenwood += d / (at_risk * (at_risk - d))
        out_t.append(float(ti))
        out_s.append(s)
        out_r.append(at_risk)
        out_d.append(d)
        var.append(s * s * greenwood)
    surv = np.array(out_s)
    sd = np.sqrt(np.array(var))
    return SurvivalCurve(
        time=np.array(out_t),
        survival=surv,
        at_risk=np.array(out_r),
        events=np.array(out_d),
        lower=np.clip(surv - z * sd, 0.0, 1.0),
        upper=np.clip(surv + z * sd, 0.0, 1.0),
        n=int(t.size),
    )


@dataclass(frozen=True)
class CellSummary:
    """Capsize probability of one campaign cell over its seeds.

    Attributes
    ----------
    group : dict
        What defines the cell apart from the seed (ship, loading, sea, heading, speed…).
    n, k : int
        Seeds run and seeds that capsized.
    p_hat : float
        k/n [-].
    lower, upper : float
        Confidence interval of the capsize probability [-].
    method : str
        ``"wilson"`` or ``"clopper-pearson"``.
    seeds_needed : int or None
        Seeds for the target half-width at p̂ (None when no target was asked).
    median_time_to_capsize : float
        Kaplan–Meier median [s] (NaN when fewer than half capsize).
    max_abs_roll_deg : float
        Largest |φ| over the seeds [deg].
    survival : SurvivalCurve or None
        Kaplan–Meier curve of the time to capsize (:func:`plot_survival`).
    """

    group: dict
    n: int
    k: int
    p_hat: float
    lower: float
    upper: float
    method: str
    seeds_needed: int | None
    median_time_to_capsize: float
    max_abs_roll_deg: float
    survival: SurvivalCurve | None = None

    def to_dict(self) -> dict:
        """JSON-ready dict."""
        return {
            **self.group,
            "n": self.n,
            "k": self.k,
            "p_hat": self.p_hat,
            "lower": self.lower,
            "upper": self.upper,
            "method": self.method,
            "seeds_needed": self.seeds_needed,
            "median_time_to_capsize_s": self.median_time_to_capsize,
            "max_abs_roll_deg": self.max_abs_roll_deg,
        }


GROUP_KEYS = (
    "ship",
    "loading",
    "sea",
    "heading_deg",
    "speed_kind",
    "speed_value",
    "controller",
    "capsize_criterion",
    "duration_s",
    "dt_s",
    "integrator",
    "radiation",
)
"""Record columns that define a cell apart from its seed (:func:`summarise_cells`): a store with
runs of one sea under two controllers (or criteria, durations…) summarises them apart."""


def summarise_cells(
    records: Sequence[dict],
    *,
    confidence: float = 0.95,
    method: str = "wilson",
    half_width: float | None = None,
) -> list[CellSummary]:
    """Per cell (records sharing :data:`GROUP_KEYS`): p̂, its interval, seeds needed, survival.

    Parameters
    ----------
    records : sequence of dict
        Campaign records (:func:`ship_gym.analysis.campaign_store.read_store`).
    confidence : float
        Confidence level of the intervals.
    method : {"wilson", "clopper-pearson"}
        Interval.
    half_width : float, optional
        Target half-width for :func:`seeds_for_half_width`.
    """
    if method not in ("wilson", "clopper-pearson"):
        raise ValueError(f"method must be 'wilson' or 'clopper-pearson', got {method!r}")
    interval = wilson_interval if method == "wilson" else clopper_pearson_interval
    groups: dict[tuple, list[dict]] = {}
    for r in records:
        groups.setdefault(tuple(r[key] for key in GROUP_KEYS), []).append(r)
    out = []
    for key in sorted(groups, key=lambda g: tuple(str(x) if isinstance(x, str) else x for x in g)):
        rs = groups[key]
        n = len(rs)
        k = sum(bool(r["capsized"]) for r in rs)
        lo, hi = interval(k, n, confidence)
        curve = kaplan_meier(
            [r["time_to_capsize_s"] if r["capsized"] else r["simulated_time_s"] for r in rs],
            [bool(r["capsized"]) for r in rs],
            confidence,
        )
        out.append(
            CellSummary(
                group=dict(zip(GROUP_KEYS, key, strict=True)),
                n=n,
                k=k,
                p_hat=k / n,
                lower=lo,
                upper=hi,
                method=method,
                seeds_needed=(
                    None
                    if half_width is None
                    else seeds_for_half_width(k / n, half_width, confidence)
                ),
                median_time_to_capsize=curve.median(),
                max_abs_roll_deg=max(float(r["max_abs_roll_deg"]) for r in rs),
                survival=curve,
            )
        )
    return out


def plot_polar_capsize(
    summaries: Sequence[CellSummary], path: str | Path, *, title: str = ""
) -> Path:
    """Polar capsize map with its confidence intervals, one panel per (ship, loading, sea).

    Heading β around (0° following at the top, clockwise; 180° head seas), speed radially (one
    ring per speed). Each cell is drawn as three concentric bands: the inner band coloured by the
    lower confidence bound, the middle by p̂ and the outer by the upper bound, so a cell whose
    bands differ strongly is not yet converged; the label is p̂ with the interval.

    Parameters
    ----------
    summaries : sequence of CellSummary
        :func:`summarise_cells` output.
    path : str or Path
        Image file (PNG, PDF or SVG), written atomically.
    title : str
        Figure title.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LinearSegmentedColormap

    if not summaries:
        raise ValueError("nothing to plot: no finished cells")
    panels: dict[tuple, list[CellSummary]] = {}
    for s in summaries:
        g = s.group
        panels.setdefault((g["ship"], g["loading"], g["sea"], g["controller"]), []).append(s)
    n = len(panels)
    fig, axes = plt.subplots(
        1, n, figsize=(5.2 * n + 0.8, 5.6), subplot_kw={"projection": "polar"}, squeeze=False
    )
    cmap = LinearSegmentedColormap.from_list("capsize", ["#2c7bb6", "#ffffbf", "#d7191c"])
    for ax, (panel, cells) in zip(axes[0], panels.items(), strict=True):
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ax.set_rlabel_position(250)
        heads = np.radians(sorted({c.group["heading_deg"] for c in cells}))
        speeds = sorted({c.group["speed_value"] for c in cells})
        kind = cells[0].group["speed_kind"]
        dh = float(np.min(np.diff(heads))) if len(heads) > 1 else math.radians(30.0)
        dv = float(np.min(np.diff(speeds))) if len(speeds) > 1 else 0.5 * speeds[0]
        for c in cells:
            th, v = math.radians(c.group["heading_deg"]), c.group["speed_value"]
            base = v - dv / 2
            for band, value in enumerate((c.lower, c.p_hat, c.upper)):
                ax.bar(
                    th,
                    dv / 3.0,
                    width=0.92 * dh,
                    bottom=base + band * dv / 3.0,
                    color=cmap(value),
                    edgecolor="k",
                    lw=0.3,
                )
            ax.text(
                th,
                v,
                f"{c.p_hat:.2f}\n[{c.lower:.2f}, {c.upper:.2f}]",
                ha="center",
                va="center",
                fontsize=6,
            )
        ax.set_rlim(0.0, max(speeds) + dv / 2)
        ship, loading, sea, controller = panel
        unit = "Fn [-]" if kind == "froude" else "U [m/s]"
        ax.set_title(f"{ship} {loading} {_controller_label(controller)}\n{sea}", fontsize=8)
        ax.set_xlabel(
            f"{unit} (radius), β [deg] (angle: 0° following, 180° head)\n"
            "bands inside → out: CI lower, p̂, CI upper",
            fontsize=7,
        )
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0.0, 1.0))
    conf = summaries[0].method
    fig.colorbar(sm, ax=axes[0].tolist(), label=f"capsize probability ({conf} CI)", shrink=0.8)
    if title:
        fig.suptitle(title, fontsize=10)
    return _save_figure(fig, path)


def _save_figure(fig: Any, path: str | Path) -> Path:
    """Write a figure atomically in the format of its suffix (PNG by default) and close it."""
    import matplotlib.pyplot as plt

    from ship_gym.io_utils import atomic_write

    path = Path(path)
    fmt = path.suffix.lower().lstrip(".") or "png"
    atomic_write(path, lambda p: fig.savefig(p, dpi=110, format=fmt))
    plt.close(fig)
    return path


def _controller_label(controller: str) -> str:
    """``"autopilot"``, ``"none"`` or ``"policy <run folder>"`` (short, for plot titles)."""
    if controller.startswith("policy:"):
        return f"policy {Path(controller[len('policy:') :]).parent.name}"
    return controller


def plot_survival(
    summaries: Sequence[CellSummary],
    path: str | Path,
    *,
    title: str = "",
    max_curves: int = 12,
) -> Path:
    """Kaplan–Meier curves P(no capsize by t) of the cells that capsized, with their bands.

    One step curve per cell with at least one capsize (the ``max_curves`` with the most
    capsizes; the others are counted in the legend), its pointwise Greenwood band shaded and
    the censoring times (runs that survived to their end) marked ``|``. Cells without capsize
    have Ŝ = 1 throughout and are left out.

    Parameters
    ----------
    summaries : sequence of CellSummary
        :func:`summarise_cells` output.
    path : str or Path
        Image file (PNG, PDF or SVG), written atomically.
    title : str
        Figure title.
    max_curves : int
        Most curves drawn.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if not summaries:
        raise ValueError("nothing to plot: no finished cells")
    hit = sorted((s for s in summaries if s.k > 0), key=lambda s: (-s.p_hat, -s.k))
    shown, hidden = hit[:max_curves], len(hit) - min(len(hit), max_curves)
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    colours = plt.cm.tab10(np.linspace(0.0, 1.0, 10))
    t_end = max(float(s.group["duration_s"]) for s in summaries)
    one_loading = len({(s.group["ship"], s.group["loading"]) for s in shown}) <= 1
    for i, s in enumerate(shown):
        curve = s.survival
        assert curve is not None  # summarise_cells sets it
        g, colour = s.group, colours[i % 10]
        unit = "Fn" if g["speed_kind"] == "froude" else "m/s"
        t = np.append(curve.time, t_end)
        label = (
            f"β {g['heading_deg']:g}°, {g['speed_value']:g} {unit}, {g['sea']}"
            f"{'' if one_loading else ', ' + str(g['ship']) + ' ' + str(g['loading'])}"
            f" (k/n {s.k}/{s.n})"
        )
        ax.step(t, np.append(curve.survival, curve.survival[-1]), where="post", color=colour,
                label=label)  # fmt: skip
        ax.fill_between(t, np.append(curve.lower, curve.lower[-1]),
                        np.append(curve.upper, curve.upper[-1]), step="post", color=colour,
                        alpha=0.15, lw=0)  # fmt: skip
        survivors = s.n - s.k
        if survivors:
            ax.plot([float(g["duration_s"])], [curve.survival[-1]], "|", color=colour, ms=12)
    if not shown:
        ax.text(0.5, 0.5, "no capsize in any cell", transform=ax.transAxes, ha="center")
    ax.set_xlim(0.0, t_end)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("P(no capsize by t) [-] (Kaplan–Meier)")
    ax.grid(alpha=0.3)
    extra = f"; {hidden} more cells with capsizes not drawn" if hidden else ""
    n_safe = len(summaries) - len(hit)
    ax.set_title(
        (title + "\n" if title else "")
        + "shaded: pointwise Greenwood band at the report's confidence; "
        + f"{n_safe} cells without capsize{extra}",
        fontsize=9,
    )
    if shown:
        ax.legend(fontsize=6.5, loc="lower left")
    fig.tight_layout()
    return _save_figure(fig, path)
