#!/usr/bin/env python
"""Accuracy study of the environments' numerical settings (mesh, FK precision, integrator, dt).

The study — the combinations of mesh × FK precision × integrator × Δt, the metrics (GZ curve and
hydrostatics per mesh, calm-water roll decay, RMS heave/roll/pitch in a regular and an irregular
sea, their errors against the finest setting 9600/fast/rk4/0.025, single-ship and batch cost) and
the acceptance criteria — is :mod:`ship_gym.analysis.accuracy` (:func:`run_study`); this script
limits the threads, runs it, and writes the markdown tables, the figure and the JSON.

Threads: NUMBA_NUM_THREADS, OMP_NUM_THREADS, OPENBLAS_NUM_THREADS, MKL_NUM_THREADS = 1 before
numpy/numba are imported, and threadpoolctl limits BLAS to one thread: every number is
single-thread. A full run took 558 s on a 2-core machine shared with other work (load ≈ 3);
``--quick`` (≈ 45 s) is a smoke test with 120 s records, a 10° GZ grid and four combinations
(its figure goes to ``out/accuracy_quick.png``). ``--replot JSON`` redraws the tables and the
figure from a ``--json`` file. Results and recommendation: ``docs/accuracy/results.md``.

Usage::

    python scripts/accuracy_study.py [--quick] [--json PATH] [--output docs/accuracy/accuracy.png]
                                     [--replot JSON]
"""

from __future__ import annotations

import os

for _var in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

from ship_gym.analysis.accuracy import (  # noqa: E402
    CRITERIA,
    DOFS,
    FINER,
    FINER_MESH,
    MESHES,
    REF_MESH,
    SEED,
    UNITS,
    cheapest_passing,
    run_study,
)
from ship_gym.io_utils import from_json_value, to_json_value  # noqa: E402


# ------------------------------------------------------------------------------------ output
def _p(x: float, digits: int = 2) -> str:
    return "div." if not np.isfinite(x) else f"{100 * x:+.{digits}f}"


def markdown_tables(res: dict) -> str:
    lines: list[str] = []
    h = res["hydrostatics"]
    lines += [
        "### Hydrostatics (vs the 9600-face mesh)",
        "",
        "| mesh | faces | displacement at T [t] | Δ [%] | sinkage [mm] | Δ [mm] | GMt [m] "
        "| ΔGMt [mm] | max abs ΔGZ 0–70° [mm] | vanishing [deg] | Δ [deg] |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name, m in h["meshes"].items():
        v = m["vs_reference"]
        lines.append(
            f"| {name} {tuple(m['mesh'])} | {m['faces']} | {m['displacement_design_t']:.1f} | "
            f"{_p(v['displacement_rel'], 3)} | {1e3 * m['sinkage_m']:.1f} | "
            f"{v['sinkage_mm']:+.1f} | {m['gmt_m']:.4f} | {v['gmt_mm']:+.1f} | "
            f"{v['gz_max_abs_mm']:.1f} | {m['vanishing_angle_deg']:.2f} | "
            f"{v['vanishing_angle_deg']:+.2f} |"
        )
    heels = h["heels_deg"]
    show = [i for i, a in enumerate(heels) if a % 10 == 0 and a > 0]
    lines += [
        "",
        "ΔGZ [mm] against the 9600-face mesh:",
        "",
        "| mesh | " + " | ".join(f"{heels[i]:g}°" for i in show) + " |",
        "|---|" + "---|" * len(show),
    ]
    for name, m in h["meshes"].items():
        dz = m["vs_reference"]["gz_mm"]
        lines.append(f"| {name} | " + " | ".join(f"{dz[i]:+.1f}" for i in show) + " |")
    ref_gz = h["meshes"][REF_MESH]["gz_m"]
    lines.append("| GZ 9600 [m] | " + " | ".join(f"{ref_gz[i]:.4f}" for i in show) + " |")

    lines += [
        "",
        "### Roll decay, calm water, φ0 = 10°, Fn 0.25",
        "",
        "| combination | role | T [s] | ΔT [%] | φ after 3 cycles [deg] | Δ [%] | Δ [deg] |",
        "|---|---|---|---|---|---|---|",
    ]
    for label, d in res["decay"]["runs"].items():
        role = ", ".join(res["roles"].get(label, []))
        lines.append(
            f"| {label} | {role} | {d['period_s']:.3f} | {_p(d['period_rel'])} | "
            f"{d['amplitude_3_cycles_deg']:.3f} | {_p(d['amplitude_rel'])} | "
            f"{d['amplitude_diff_deg']:+.4f} |"
        )

    for case, w in res["waves"].items():
        ref = w["runs"][res["reference"]]["statistics"]
        lines += [
            "",
            f"### {case}: {w['description']}, {w['duration_s']:g} s, statistics from "
            f"t = {w['statistics_from_s']:g} s",
            "",
            "Reference: "
            + ", ".join(
                f"{k} RMS {ref[k]['rms']:.4f} {UNITS[k]}, amplitude {ref[k]['amplitude']:.4f} "
                f"{UNITS[k]}"
                for k in DOFS
            ),
            "",
            "| combination | RMS heave [%] | RMS roll [%] | RMS pitch [%] | ampl. heave [%] "
            "| ampl. roll [%] | ampl. pitch [%] | series heave [%] | series roll [%] "
            "| series pitch [%] |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        for label, r in w["runs"].items():
            if label == res["reference"]:
                continue
            e = r["errors"]
            lines.append(
                f"| {label} | "
                + " | ".join(_p(e[k]["rms_rel"]) for k in DOFS)
                + " | "
                + " | ".join(_p(e[k]["amplitude_rel"]) for k in DOFS)
                + " | "
                + " | ".join(f"{100 * e[k]['series_rel']:.2f}" for k in DOFS)
                + " |"
            )

    if res.get("seed_check"):
        labels = list(next(iter(res["seed_check"].values()))["errors"])
        seeds = [str(SEED), *res["seed_check"]]
        lines += [
            "",
            "### Irregular sea, other realisations (seeds): roll RMS error [%] (max abs of heave "
            "and pitch in brackets)",
            "",
            "| combination | " + " | ".join(f"seed {k}" for k in seeds) + " |",
            "|---|" + "---|" * len(seeds),
        ]
        irr = res["waves"]["irregular"]
        refs = [irr["runs"][res["reference"]]["statistics"]] + [
            v["reference"] for v in res["seed_check"].values()
        ]
        lines.append(
            "| reference roll RMS [deg] | "
            + " | ".join(f"{r['roll']['rms']:.2f}" for r in refs)
            + " |"
        )
        for label in labels:
            errs = [irr["runs"][label]["errors"]] + [
                v["errors"][label] for v in res["seed_check"].values()
            ]
            cells = [
                f"{_p(e['roll']['rms_rel'])} "
                f"({100 * max(abs(e['heave']['rms_rel']), abs(e['pitch']['rms_rel'])):.2f})"
                for e in errs
            ]
            lines.append(f"| {label} | " + " | ".join(cells) + " |")

    lines += [
        "",
        "### Cost (one ship, BatchSimulator N = 1, irregular sea after the ramp; fastest of 3)",
        "",
        "| combination | eval/s | wall [ms per sim. s] | CPU [ms per sim. s] | real-time × (CPU) "
        f"| CPU / current | batch of {res['batch_cost_ships']}: CPU [ms per ship-sim. s] "
        "| batch CPU / current |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for label, v in res["cost"].items():
        b = v.get("batch")
        batch = (
            f"{1e3 * b['cpu_s_per_ship_simulated_s']:.2f} | {b['cpu_ratio_to_current']:.2f}"
            if b
            else "– | –"
        )
        lines.append(
            f"| {label} | {v['evaluations_per_simulated_s']:.0f} | "
            f"{1e3 * v['wall_s_per_simulated_s']:.2f} | {1e3 * v['cpu_s_per_simulated_s']:.2f} | "
            f"{v['realtime_factor_cpu']:.0f} | {v['cpu_ratio_to_current']:.2f} | {batch} |"
        )

    lines += [
        "",
        "### Summary against the criteria",
        "",
        "| combination | role | max abs ΔGZ [mm] | ΔT roll [%] | Δφ 3 cycles [%] "
        "| max abs RMS err. [%] | incl. regular roll [%] | max series err. [%] "
        "| CPU / current | batch CPU / current | meets (RMS ≤ 2 % / 3 %) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for label, s in res["summary"].items():
        role = ", ".join(res["roles"].get(label, []))
        lines.append(
            f"| {label} | {role} | {s['gz_max_abs_mm']:.1f} | {_p(s['roll_period_rel'])} | "
            f"{_p(s['roll_amplitude_3_cycles_rel'])} | {100 * s['rms_max']:.2f} | "
            f"{100 * s['rms_max_all']:.2f} | {100 * s['series_max']:.2f} | "
            f"{s['cpu_ratio_to_current']:.2f} | "
            + ("–" if not np.isfinite(s["batch_cpu_ratio_to_current"])
               else f"{s['batch_cpu_ratio_to_current']:.2f}")
            + f" | {'yes' if s['passes_2pct'] else 'no'} / {'yes' if s['passes_3pct'] else 'no'} |"
        )  # fmt: skip
    lines.append("")
    for limit in ("rms_strict", "rms_loose"):
        best = cheapest_passing(res["summary"], CRITERIA[limit])
        lines.append(
            f"Cheapest combination (single-ship CPU) with |ΔT roll| ≤ 1 %, max |Δ RMS| ≤ "
            f"{100 * CRITERIA[limit]:g} %, max |ΔGZ| ≤ 5 mm: {best or 'none'}"
        )
    return "\n".join(lines)


def plot(res: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    fig, axes = plt.subplots(2, 3, figsize=(17, 9.5))
    (ax_gz, ax_cost, ax_sens), (ax_decay, ax_ddecay, ax_dirr) = axes
    h = res["hydrostatics"]
    heels = np.array(h["heels_deg"])
    for name, m in h["meshes"].items():
        if name == REF_MESH:
            continue
        ax_gz.plot(heels, m["vs_reference"]["gz_mm"], marker="o", ms=3, label=f"{m['faces']} faces")
    ax_gz.axhline(0.0, color="k", lw=0.6)
    for y in (-5.0, 5.0):
        ax_gz.axhline(y, color="grey", ls=":", lw=0.8)
    ax_gz.set_xlabel("heel angle φ [deg]")
    ax_gz.set_ylabel("GZ − GZ(9600 faces) [mm]")
    ax_gz.set_title("(a) righting-arm error of the mesh (calm water, free sinkage and trim)",
                    fontsize=9)  # fmt: skip
    ax_gz.grid(True, alpha=0.3)
    ax_gz.legend(fontsize=8)

    # (b) error against cost: colour = mesh, marker = integrator, filled = float32 wave sums
    colours = dict(zip(MESHES, plt.rcParams["axes.prop_cycle"].by_key()["color"], strict=False))
    floor = 1e-3  # [%]: errors below are drawn on this line
    named = {res["current"]: "current", res["candidate"]: "candidate",
             res["recommended"]: "recommended"}  # fmt: skip
    for label, s in res["summary"].items():
        if label == res["reference"]:
            continue
        mesh, precision, integrator, _ = label.split("/")
        err = 100 * max(abs(s["roll_period_rel"]), s["rms_max"])
        cpu = res["cost"][label]["cpu_s_per_simulated_s"] * 1e3
        ax_cost.loglog(
            cpu, max(err, floor), "o" if integrator == "holloway" else "s", ms=7,
            color=colours[mesh], mfc=colours[mesh] if precision == "fast32" else "none",
        )  # fmt: skip
        if label in named:
            text = f"{named.get(label, '')} {label}".strip()
            ax_cost.annotate(text, (cpu, max(err, floor)), fontsize=6.5, xytext=(4, 3),
                             textcoords="offset points")  # fmt: skip
    for mesh, colour in colours.items():
        if mesh == FINER_MESH:
            continue
        ax_cost.plot([], [], "o", color=colour, label=f"{mesh} faces")
    ax_cost.plot([], [], "o", color="k", mfc="none", label="holloway, float64 (open)")
    ax_cost.plot([], [], "s", color="k", label="rk4 (square), float32 (filled)")
    for y, ls in ((1.0, ":"), (2.0, "--")):
        ax_cost.axhline(y, color="grey", ls=ls, lw=0.8)
    for axis in (ax_cost.xaxis, ax_cost.yaxis):
        axis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax_cost.set_xlabel("CPU time per simulated second, one ship [ms/s]")
    ax_cost.set_ylabel("max(|ΔT roll|, max |Δ RMS motion|) vs reference [%]")
    ax_cost.set_title(
        "(b) error against cost (reference 9600/fast/rk4/0.025; errors < 0.001 % drawn at 0.001 %)",
        fontsize=9,
    )
    ax_cost.grid(True, which="both", alpha=0.3)
    ax_cost.legend(fontsize=7, loc="center right")

    # (c) sensitivity of the resonant roll RMS to the roll period
    irr = res["waves"]["irregular"]["runs"]
    for label, s in res["summary"].items():
        if label == res["reference"]:
            continue
        mesh = label.split("/")[0]
        ax_sens.plot(100 * s["roll_period_rel"], 100 * irr[label]["errors"]["roll"]["rms_rel"],
                      "o", color=colours[mesh])  # fmt: skip
    fine = res["decay"]["runs"].get(FINER.label)
    if fine is not None and FINER.label in irr:
        ax_sens.plot(100 * fine["period_rel"], 100 * irr[FINER.label]["errors"]["roll"]["rms_rel"],
                     "o", color=colours[FINER_MESH])  # fmt: skip
    for mesh, colour in colours.items():
        if mesh != REF_MESH:
            ax_sens.plot([], [], "o", color=colour, label=f"{mesh} faces")
    ax_sens.axhline(0.0, color="k", lw=0.6)
    ax_sens.axvline(0.0, color="k", lw=0.6)
    ax_sens.set_xlabel("roll period error ΔT / T, calm-water decay [%]")
    ax_sens.set_ylabel("roll RMS error, irregular quartering sea [%]")
    ax_sens.set_title("(c) near-resonant roll amplifies the period error", fontsize=9)
    ax_sens.grid(True, alpha=0.3)
    ax_sens.legend(fontsize=7)

    decay = res["decay"]["runs"]
    ref = decay[res["reference"]]
    ax_decay.plot(ref["t"], ref["roll_deg"], "k-", lw=1.0, label=res["reference"])
    ax_decay.set_xlabel("time t [s]")
    ax_decay.set_ylabel("roll angle φ [deg]")
    ax_decay.set_title("(d) roll decay in calm water, Fn 0.25, φ0 = 10° (reference)", fontsize=9)
    ax_decay.grid(True, alpha=0.3)
    ax_decay.legend(fontsize=8)
    styles = ("b-", "r-", "g-", "m-")
    for label, style in zip(res["plotted"], styles, strict=False):
        if label not in decay:
            continue
        d = decay[label]
        diff = np.array(d["roll_deg"]) - np.array(ref["roll_deg"])
        ax_ddecay.plot(d["t"], diff, style, lw=0.9, label=label)
    ax_ddecay.set_xlabel("time t [s]")
    ax_ddecay.set_ylabel("φ − φ_ref [deg]")
    ax_ddecay.set_title("(e) roll decay: difference to the reference", fontsize=9)
    ax_ddecay.grid(True, alpha=0.3)
    ax_ddecay.legend(fontsize=8)

    rec = res["records"]["irregular"]
    ref_rec = rec[res["reference"]]
    for label, style in zip(res["plotted"], styles, strict=False):
        if label in rec:
            diff = np.array(rec[label]["roll_deg"]) - np.array(ref_rec["roll_deg"])
            ax_dirr.plot(rec[label]["t"], diff, style, lw=0.7, label=label)
    rms_ref = res["waves"]["irregular"]["runs"][res["reference"]]["statistics"]["roll"]["rms"]
    ax_dirr.set_xlabel("time t [s]")
    ax_dirr.set_ylabel("φ − φ_ref [deg]")
    ax_dirr.set_title(
        f"(f) roll in the irregular sea (Hs 4 m, β 60°) minus the reference (RMS {rms_ref:.1f}°)",
        fontsize=9,
    )
    ax_dirr.grid(True, alpha=0.3)
    ax_dirr.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="≈ 1 min smoke run")
    parser.add_argument("--json", type=Path, default=None, help="write the numbers here")
    parser.add_argument(
        "--output",
        type=Path,
        default=None,
        help="figure (default docs/accuracy/accuracy.png; with --quick out/accuracy_quick.png, "
        "so that a smoke run never overwrites the documented figure)",
    )
    parser.add_argument(
        "--replot", type=Path, default=None, help="redo tables and figure from a --json file"
    )
    args = parser.parse_args(argv)
    if args.output is None:
        args.output = Path("out/accuracy_quick.png" if args.quick else "docs/accuracy/accuracy.png")
    if args.replot is not None:
        res = from_json_value(json.loads(args.replot.read_text()))
        print(markdown_tables(res))
        plot(res, args.output)
        print(f"figure: {args.output}")
        return 0
    with threadpool_limits(limits=1):
        res = run_study(args.quick, log=print)
    print()
    print(markdown_tables(res))
    print(
        f"\ntotal {res['elapsed_s']:.0f} s; load average {res['load_average'][0]:.2f}; "
        f"environments' S175_MESH at run time: {res['env_default_mesh_at_run_time']}"
    )
    plot(res, args.output)
    print(f"figure: {args.output}")
    if args.json is not None:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(to_json_value(res), indent=1) + "\n")
        print(f"numbers: {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
