"""HeavyWeather-v0's benchmark table: the learned master against the classical ones on held-out
episodes, with intervals.

Runs every policy on the same held-out episodes (seeds 20 000 … 20 199 by default: the
held-out range of :mod:`ship_gym.agents.protocol`, used to choose nothing — the masters were
tuned on training seeds 1000 …, the policy's checkpoint chosen on validation seeds 5000 …) and
writes ``docs/benchmarks/heavy_weather.md`` / ``.json`` (the table) and
``heavy_weather.png`` (mean progress against capsize rate, with their intervals).

Task metric: mean voyage progress (distance made good along the voyage course / the nominal
voyage, 0 for a capsized episode). The strongest classical master is the one of most progress
among those whose capsize rate is lowest-bounded (Wilson upper bound no higher than the best
master's); the learned master's gain over it is the paired-bootstrap 95 % interval of the ratio
of mean progress − 1, its capsize rate judged on its Wilson interval.

    python scripts/heavy_weather_benchmark.py \
        --model docs/benchmarks/policies/HeavyWeather/ppo_heavy_weather
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path
from typing import Any

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from ship_gym.agents.evaluate import evaluate_policies
from ship_gym.agents.protocol import (
    HELD_OUT_EPISODES,
    HELD_OUT_FIRST,
    check_held_out,
    mean_ratio,
    paired_bootstrap,
)
from ship_gym.analysis.capsize_statistics import wilson_interval

ROOT = Path(__file__).resolve().parents[1]
ENV_ID = "ship_gym/HeavyWeather-v0"
MASTERS = ("keep", "imo-guidance", "polar")
TARGET = 0.15  # the issue's: ≥ 15 % more mean progress than the strongest classical master


def progress_gain(reference: np.ndarray, candidate: np.ndarray) -> np.ndarray:
    """mean(candidate)/mean(reference) − 1 along the last axis (higher progress is better)."""
    return mean_ratio(reference, candidate) - 1.0


def table(results: dict[str, Any]) -> dict[str, Any]:
    """Per policy: mean progress with its bootstrap interval, capsize rate with Wilson's; the
    strongest master; the gain of every other policy over it (paired)."""
    rows: dict[str, Any] = {}
    for label, res in results["policies"].items():
        per = res["per_episode"]
        progress = np.asarray(per["voyage_progress"], float)
        capsized = np.asarray(per["capsized"], bool)
        n, k = progress.size, int(capsized.sum())
        mean_ci = paired_bootstrap(progress, progress, lambda r, c: np.mean(c, axis=-1))
        rows[label] = {
            "progress": mean_ci.as_list(),
            "capsizes": [k, n],
            "capsize_rate": [k / n, *wilson_interval(k, n)],
            "mean_return": float(np.mean(per["returns"])),
            "mean_cost": float(np.mean(per["cost"])),
            "rms_action": float(np.mean(per["rms_action"])),
        }
    masters = [m for m in MASTERS if m in rows]
    if not masters:
        raise ValueError("no classical master in the results: run them too (--policies)")
    safest = min(rows[m]["capsize_rate"][2] for m in masters)
    eligible = [m for m in masters if rows[m]["capsize_rate"][2] <= safest + 1e-12]
    strongest = max(eligible, key=lambda m: rows[m]["progress"][0])
    ref = np.asarray(results["policies"][strongest]["per_episode"]["voyage_progress"], float)
    for label, row in rows.items():
        if label == strongest:
            continue
        cand = np.asarray(results["policies"][label]["per_episode"]["voyage_progress"], float)
        gain = paired_bootstrap(ref, cand, progress_gain)
        row["gain_vs_strongest"] = gain.as_list()
        row["capsize_no_worse"] = row["capsize_rate"][2] <= rows[strongest]["capsize_rate"][2]
        row["target_met"] = bool(gain.low >= TARGET and row["capsize_no_worse"])
    return {"strongest_master": strongest, "rows": rows, "target": TARGET}


def markdown(summary: dict[str, Any], seeds: list[int]) -> str:
    lines = [
        f"# HeavyWeather-v0: held-out seeds {seeds[0]} … {seeds[-1]} ({len(seeds)} episodes)",
        "",
        "Mean voyage progress (distance made good along the voyage / nominal voyage, 0 if "
        "capsized) with its bootstrap 95 % interval; capsize rate with its Wilson 95 % interval; "
        f"gain = paired-bootstrap 95 % interval of the progress ratio − 1 against the strongest "
        f"classical master (**{summary['strongest_master']}**). Target: gain ≥ "
        f"{TARGET:.0%} on the interval's lower end, at a capsize rate whose Wilson upper bound "
        "is no higher than the master's.",
        "",
        "| policy | mean progress [95 %] | capsizes | capsize rate [Wilson 95 %] | gain vs "
        "strongest [95 %] | mean return | target |",
        "|---|---|---|---|---|---|---|",
    ]
    for label, row in summary["rows"].items():
        p, lo, hi = row["progress"]
        k, n = row["capsizes"]
        c, clo, chi = row["capsize_rate"]
        if "gain_vs_strongest" in row:
            g, glo, ghi = row["gain_vs_strongest"]
            gain = f"{g:+.1%} [{glo:+.1%}, {ghi:+.1%}]"
            target = "met" if row["target_met"] else "not met"
        else:
            gain, target = "(reference)", ""
        lines.append(
            f"| {label} | {p:.3f} [{lo:.3f}, {hi:.3f}] | {k}/{n} | {c:.1%} [{clo:.1%}, "
            f"{chi:.1%}] | {gain} | {row['mean_return']:.1f} | {target} |"
        )
    return "\n".join(lines) + "\n"


def figure(summary: dict[str, Any], path: Path) -> None:
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for label, row in summary["rows"].items():
        p, lo, hi = row["progress"]
        c, clo, chi = row["capsize_rate"]
        ax.errorbar(
            100 * c, p, xerr=[[100 * (c - clo)], [100 * (chi - c)]], yerr=[[p - lo], [hi - p]],
            fmt="o", capsize=4, label=label,
        )  # fmt: skip
    ax.set_xlabel("capsize rate [%] (Wilson 95 %)")
    ax.set_ylabel("mean voyage progress [-] (bootstrap 95 %)")
    ax.set_title("HeavyWeather-v0, held-out episodes")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--model", type=Path, default=None, help="a trained policy folder")
    parser.add_argument(
        "--policies",
        default=",".join(MASTERS),
        help="masters to run now (the others' episodes are kept from an earlier run of the "
        "same seeds in the output JSON)",
    )
    parser.add_argument("--episodes", type=int, default=HELD_OUT_EPISODES)
    parser.add_argument("--seed", type=int, default=HELD_OUT_FIRST)
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "benchmarks")
    args = parser.parse_args()
    seeds = list(range(args.seed, args.seed + args.episodes))
    check_held_out(seeds)
    policies = [p for p in args.policies.split(",") if p] + (
        [f"model:{args.model}"] if args.model else []
    )
    path = args.out / "heavy_weather.json"
    results = evaluate_policies(ENV_ID, policies, args.episodes, args.seed, report=print)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "heavy_weather_last_run.json").write_text(json.dumps(results) + "\n")
    if path.exists():  # keep the other policies' episodes of the same seeds
        earlier = json.loads(path.read_text())
        if earlier.get("seeds") == [seeds[0], seeds[-1]]:
            kept = {
                k: v for k, v in earlier["results"]["policies"].items()
                if k not in results["policies"]
            }  # fmt: skip
            results["policies"] = {**kept, **results["policies"]}
    order = [*MASTERS, *sorted(k for k in results["policies"] if k not in MASTERS)]
    results["policies"] = {k: results["policies"][k] for k in order if k in results["policies"]}
    summary = table(results)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "heavy_weather.json").write_text(
        json.dumps({"seeds": [seeds[0], seeds[-1]], **summary, "results": results}, indent=1) + "\n"
    )
    (args.out / "heavy_weather.md").write_text(markdown(summary, seeds))
    figure(summary, args.out / "heavy_weather.png")
    print(markdown(summary, seeds))


if __name__ == "__main__":
    main()
