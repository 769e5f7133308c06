#!/usr/bin/env python
"""Reproduce Matusiak's memory-effect capsize table with the S175 (``ship_gym.analysis.matusiak``).

Runs his four (Fn, heading) pairs — (0.2, 0°), (0.2, 45°), (0.3, 30°), (0.4, 30°), heading 0°
following seas — in his regular wave scaled to the S175 (λ = 1.5 L = 262.5 m, A_w = 4.5 m ×
175/150 = 5.25 m, eq. 12 ramp T_f = 50 s, 720 s) with the memory model (case 1, state-space fit
of Cummins' kernel), the constant-coefficient cases 2a and 2b, and the direct convolution as the
case-1 reference at (0.3, 30°); for the design loading condition (KG = 9.55 m, GM ≈ 1.0 m) and
reduced-GM conditions (KG raised). Autopilot keeps the course, the propeller turns at the
calm-water self-propulsion rpm; RK4 at Δt = 0.1 s (Matusiak's step; ≤ 1e-6 relative error in
``scripts/convergence_study.py``).

Outputs (``--out``, default ``docs/matusiak``): ``results.csv`` (one row per run),
``outcomes.md`` (our capsize table next to his), ``time_histories_<condition>.png`` (roll,
pitch, yaw of every run), and the raw histories in ``--histories`` (default
``out/matusiak_histories.npz``). ``--json PATH`` writes the rows, wall time and the measured
parallel speed-up (Σ per-run CPU time / wall time).

Usage::

    python scripts/reproduce_matusiak.py [--kgs design 10.25] [--n-jobs 2]
                                         [--duration 720] [--dt 0.1] [--out docs/matusiak]
                                         [--json PATH] [--replot]
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import math
import time
from pathlib import Path

import numpy as np

from ship_gym.analysis import matusiak as mt

MODELS = ("state_space", "convolution", "2a", "2b")
MODEL_LABEL = {
    "state_space": "case 1 (memory, state space)",
    "convolution": "case 1 (memory, convolution)",
    "2a": "case 2a (const., roll at ω_φ)",
    "2b": "case 2b (const., all at ω_e)",
}


def _run(scenario: mt.Scenario) -> tuple[dict, dict]:
    from ship_gym.analysis.capsize_map import single_threaded_blas

    with single_threaded_blas():
        res = mt.run_scenario(scenario)
    series = {
        "t": res.t,
        "roll": res.roll,
        "pitch": res.pitch,
        "yaw": res.yaw,
        "rudder": res.rudder,
        "u": res.u,
    }
    return {"label": scenario.label, **res.row()}, series


def _kg(text: str) -> float | None:
    return None if text == "design" else float(text)


def _yes(flag: bool) -> str:
    return "capsize" if flag else "no capsize"


def outcomes_markdown(rows: list[dict]) -> str:
    """Our capsize outcomes per loading condition next to Matusiak's table."""
    out = io.StringIO()
    conditions = sorted({(r["kg_m"], r["gm_m"], r["capsize_angle_deg"]) for r in rows})
    for kg, gm, angle in conditions:
        out.write(
            f"\n**S175, KG = {kg:g} m, GM = {gm:.2f} m (capsize: |φ| > vanishing angle "
            f"{angle:.1f}°)**\n\n"
        )
        header = ["", *[f"Fn {r.froude:g}, {r.heading_deg:g}°" for r in mt.MATUSIAK_TABLE]]
        out.write("| " + " | ".join(header) + " |\n")
        out.write("|" + "---|" * len(header) + "\n")
        out.write(
            "| A-1 experiment (Matusiak) | "
            + " | ".join(_yes(r.experiment) for r in mt.MATUSIAK_TABLE)
            + " |\n"
        )
        out.write(
            "| A-1 case 1 (Matusiak) | "
            + " | ".join(_yes(r.case_1) for r in mt.MATUSIAK_TABLE)
            + " |\n"
        )
        out.write(
            "| A-1 case 2a & 2b (Matusiak) | "
            + " | ".join(_yes(r.case_2ab) for r in mt.MATUSIAK_TABLE)
            + " |\n"
        )
        for model in MODELS:
            cells = []
            for tr in mt.MATUSIAK_TABLE:
                match = [
                    r
                    for r in rows
                    if r["kg_m"] == kg
                    and r["radiation"] == model
                    and r["froude"] == tr.froude
                    and r["heading_deg"] == tr.heading_deg
                ]
                if not match:
                    cells.append("–")
                    continue
                r = match[0]
                if r["capsized"]:
                    cells.append(
                        f"**capsize** at {float(r['time_to_capsize_s']):.0f} s ({r['reason']})"
                    )
                else:
                    cells.append(f"no capsize (max φ {float(r['max_abs_roll_deg']):.1f}°)")
            if any(c != "–" for c in cells):
                out.write(f"| S175 {MODEL_LABEL[model]} | " + " | ".join(cells) + " |\n")
    return out.getvalue()


def plot_histories(rows: list[dict], series: dict[str, dict], out_dir: Path) -> list[Path]:
    """One figure per loading condition: rows = (Fn, heading) pairs, columns = models."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = []
    for kg in sorted({r["kg_m"] for r in rows}):
        sub = [r for r in rows if r["kg_m"] == kg]
        models = [m for m in MODELS if any(r["radiation"] == m for r in sub)]
        fig, axes = plt.subplots(
            len(mt.MATUSIAK_TABLE),
            len(models),
            figsize=(4.2 * len(models), 2.6 * len(mt.MATUSIAK_TABLE)),
            sharex=True,
            squeeze=False,
        )
        for i, tr in enumerate(mt.MATUSIAK_TABLE):
            for j, model in enumerate(models):
                ax = axes[i, j]
                match = [
                    r
                    for r in sub
                    if r["radiation"] == model
                    and r["froude"] == tr.froude
                    and r["heading_deg"] == tr.heading_deg
                ]
                if not match:
                    ax.set_axis_off()
                    continue
                r = match[0]
                s = series[r["label"]]
                ax.plot(s["t"], np.degrees(s["roll"]), lw=0.8, label="roll φ")
                ax.plot(s["t"], np.degrees(s["pitch"]), lw=0.8, label="pitch θ")
                ax.plot(s["t"], np.degrees(s["yaw"]), lw=0.8, label="yaw ψ")
                verdict = (
                    f"CAPSIZE {float(r['time_to_capsize_s']):.0f} s"
                    if r["capsized"]
                    else f"max φ {float(r['max_abs_roll_deg']):.1f}°"
                )
                ax.set_title(
                    f"Fn {tr.froude:g}, {tr.heading_deg:g}° — {MODEL_LABEL[model]}\n{verdict}",
                    fontsize=8,
                )
                ax.grid(alpha=0.3)
                if j == 0:
                    ax.set_ylabel("[deg]")
                if i == len(mt.MATUSIAK_TABLE) - 1:
                    ax.set_xlabel("t [s]")
        axes[0, 0].legend(fontsize=7, loc="upper left")
        gm = sub[0]["gm_m"]
        fig.suptitle(
            f"S175 in Matusiak's wave scaled to L = 175 m (H = 10.5 m, λ = 262.5 m), "
            f"KG = {kg:g} m, GM = {gm:.2f} m",
            fontsize=10,
        )
        fig.tight_layout()
        path = out_dir / f"time_histories_kg{kg:g}.png"
        from ship_gym.io_utils import atomic_write

        atomic_write(path, lambda p, fig=fig: fig.savefig(p, dpi=90, format="png"))
        plt.close(fig)
        paths.append(path)
    return paths


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--kgs", nargs="+", default=["design", "10.25"])
    parser.add_argument("--models", nargs="+", default=["state_space", "2a", "2b"])
    parser.add_argument("--no-convolution", action="store_true", help="skip the reference run")
    parser.add_argument("--n-jobs", type=int, default=2)
    parser.add_argument("--duration", type=float, default=mt.DURATION)
    parser.add_argument("--dt", type=float, default=0.1)
    parser.add_argument("--out", default="docs/matusiak")
    parser.add_argument("--histories", default="out/matusiak_histories.npz")
    parser.add_argument("--json", default=None)
    parser.add_argument("--replot", action="store_true", help="redraw from saved CSV + npz")
    args = parser.parse_args()
    out_dir = Path(args.out)
    from ship_gym.io_utils import atomic_write, atomic_write_text

    if args.replot:
        with open(out_dir / "results.csv", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))
        for r in rows:
            for key in ("froude", "heading_deg", "kg_m", "gm_m", "capsize_angle_deg"):
                r[key] = float(r[key])
            r["capsized"] = r["capsized"] == "True"
        data = np.load(args.histories)
        series = {
            r["label"]: {k: data[f"{r['label']}/{k}"] for k in ("t", "roll", "pitch", "yaw")}
            for r in rows
        }
        wall = math.nan
    else:
        scenarios = mt.study_scenarios(
            tuple(_kg(k) for k in args.kgs),
            tuple(args.models),
            convolution_reference=None if args.no_convolution else (0.3, 30.0),
            duration=args.duration,
            dt=args.dt,
        )
        print(f"{len(scenarios)} runs of {args.duration:g} s, dt {args.dt} s, n_jobs {args.n_jobs}")
        t0 = time.perf_counter()
        from joblib import Parallel, delayed
        from tqdm import tqdm

        results = list(
            tqdm(
                Parallel(n_jobs=args.n_jobs, return_as="generator")(
                    delayed(_run)(s) for s in scenarios
                ),
                total=len(scenarios),
                desc="Matusiak runs",
            )
        )
        wall = time.perf_counter() - t0
        rows = [r for r, _ in results]
        series = {r["label"]: s for r, s in results}
        buf = io.StringIO()
        writer = csv.DictWriter(buf, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
        atomic_write_text(out_dir / "results.csv", buf.getvalue())
        flat = {f"{lab}/{k}": v for lab, s in series.items() for k, v in s.items()}
        atomic_write(Path(args.histories), lambda p: np.savez_compressed(open(p, "wb"), **flat))
        cpu = sum(float(r["cpu_s"]) for r in rows)
        print(
            f"wall {wall:.0f} s for {len(rows)} runs; Σ per-run CPU {cpu:.0f} s → effective "
            f"parallel speed-up {cpu / wall:.2f} on {args.n_jobs} jobs"
        )
    table = outcomes_markdown(rows)
    atomic_write_text(
        out_dir / "outcomes.md",
        "# Matusiak study: capsize outcomes (generated by scripts/reproduce_matusiak.py)\n" + table,
    )
    print(table)
    for p in plot_histories(rows, series, out_dir):
        print(f"wrote {p}")
    if args.json:
        cpu = sum(float(r["cpu_s"]) for r in rows) if not args.replot else math.nan
        atomic_write_text(
            Path(args.json),
            json.dumps(
                {"rows": rows, "wall_s": wall, "cpu_s": cpu, "n_jobs": args.n_jobs},
                indent=2,
                default=float,
            ),
        )
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
