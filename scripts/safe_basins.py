"""Safe basins and their erosion: Edith Terkol (McCue & Campbell eq. 1/2) and the S175 roll slice.

Writes into ``--out`` (default docs/safe_basins/):

* ``edith_terkol_integrity.png`` / ``.csv`` — integrity (safe area / unforced safe area) versus
  forcing amplitude F = 0 … 0.1 rad/s² at ωₑ = 0.85 ωₙ, with basins showing the erosion;
* ``edith_terkol_F0.0195.png`` / ``.csv`` — the basin at McCue & Campbell's F = 0.0195, with the
  unforced undamped separatrix;
* ``mccue_campbell_fit.png`` — the basin of the eq. 2 model fitted from ⟨−0.4, −0.35⟩
  (b_u1 = 0.0098, b_u3 = 0.0388, c_u1 = 0.5147, c_u3 = −0.7052, F_u = 0.0220) next to eq. 1's
  (their figure 8), and the fraction of cells on which they agree;
* ``s175_integrity.png`` / ``.csv`` and ``s175_H*.csv`` — the S175 with only roll free in the
  6-DOF simulator, regular beam waves of period 18 s, integrity versus wave height (``--quick``
  uses a coarser grid and fewer heights).

``--json PATH`` writes every number (with the CPU time of each stage, ``time.process_time``).
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from ship_gym.analysis import safe_basin as sb
from ship_gym.io_utils import atomic_write_text
from ship_gym.roll.equation import RollEquation


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--out", default="docs/safe_basins", help="output folder")
    p.add_argument("--json", default=None, help="write the numbers here")
    p.add_argument("--grid", type=int, default=101, help="Edith Terkol grid points per axis")
    p.add_argument("--duration", type=float, default=200.0, help="Edith Terkol run time [s]")
    p.add_argument("--s175-grid", type=int, default=21, help="S175 grid points per axis")
    p.add_argument("--s175-duration", type=float, default=120.0, help="S175 run time [s]")
    p.add_argument(
        "--s175-heights", type=float, nargs="*", default=[0.0, 4.0, 8.0, 11.0, 14.0],
        help="S175 wave heights [m] ('--s175-heights' alone skips the S175)",
    )  # fmt: skip
    p.add_argument("--quick", action="store_true", help="coarse grids (a smoke run)")
    p.add_argument("--no-progress", action="store_true")
    args = p.parse_args()
    if args.quick:
        args.grid, args.duration, args.s175_grid, args.s175_duration = 31, 100.0, 5, 40.0
        args.s175_heights = args.s175_heights[:2]
    out = Path(args.out)
    progress = not args.no_progress
    results: dict = {}

    # ---------------------------------------------------------------- Edith Terkol
    et = RollEquation.edith_terkol()
    grid = {
        "roll_range": (-1.0, 1.0),
        "roll_rate_range": (-0.6, 0.6),
        "n_roll": args.grid,
        "n_rate": args.grid,
        "duration": args.duration,
        "dt": 0.05,
        "model": "edith-terkol",
    }
    t0 = time.process_time()
    amps = np.round(np.linspace(0.0, 0.1, 21), 6)
    curve = sb.integrity_curve(et, amps, progress=progress, **grid)
    cpu_curve = time.process_time() - t0
    sb.write_integrity_csv(curve, out / "edith_terkol_integrity.csv")
    sb.plot_integrity(curve, out / "edith_terkol_integrity.png", separatrix_of=et)
    n_traj = args.grid**2 * (len(amps) + 1)
    steps = round(args.duration / 0.05)
    results["edith_terkol"] = {
        "grid": args.grid,
        "duration_s": args.duration,
        "dt_s": 0.05,
        "vanishing_angle_rad": et.vanishing_angle(),
        "unforced_safe_fraction": curve.reference_safe_fraction,
        "forcing_amplitude_rad_s2": curve.forcing.tolist(),
        "integrity": curve.integrity.tolist(),
        "cpu_s": cpu_curve,
        "cpu_ns_per_trajectory_step": 1e9 * cpu_curve / (n_traj * steps),
    }
    print(
        f"Edith Terkol: unforced safe fraction {curve.reference_safe_fraction:.4f} of the "
        f"{args.grid}² grid; {cpu_curve:.1f} s CPU for {len(amps) + 1} basins "
        f"({results['edith_terkol']['cpu_ns_per_trajectory_step']:.1f} ns per trajectory-step)"
    )
    for f, g in zip(curve.forcing, curve.integrity, strict=True):
        print(f"  F = {f:.3f} rad/s^2: integrity {g:.4f}")

    # McCue & Campbell's forcing, and their eq. 2 fit from ⟨−0.4, −0.35⟩ (figure 8)
    unforced = sb.safe_basin(et, **grid)
    eq1 = RollEquation.edith_terkol(forcing_amplitude=0.0195)
    b1 = sb.safe_basin(eq1, **grid)
    sb.write_basin(b1, out / "edith_terkol_F0.0195.csv")
    sb.plot_basin(b1, out / "edith_terkol_F0.0195.png", separatrix_of=et, reference=unforced)
    fit = RollEquation.mccue_campbell(0.0098, 0.0388, 0.5147, -0.7052, 0.0220)
    b2 = sb.safe_basin(fit, **{**grid, "model": "mccue-campbell-eq2-fit"})
    agree = float(np.mean(b1.capsized == b2.capsized))
    _plot_comparison(b1, b2, out / "mccue_campbell_fit.png")
    results["mccue_campbell"] = {
        "eq1_F0.0195_safe_fraction": b1.safe_fraction,
        "eq1_F0.0195_integrity": b1.integrity(unforced),
        "eq2_fit_safe_fraction": b2.safe_fraction,
        "eq2_fit_vanishing_angle_rad": fit.vanishing_angle(),
        "cells_agreeing": agree,
    }
    print(
        f"F = 0.0195: integrity {b1.integrity(unforced):.4f}; eq. 2 fit basin agrees with eq. 1 "
        f"on {agree:.1%} of the cells (safe fractions {b1.safe_fraction:.4f} vs "
        f"{b2.safe_fraction:.4f})"
    )

    # ---------------------------------------------------------------- S175 roll-only slice
    if args.s175_heights:
        t0 = time.process_time()
        kw = {
            "n_roll": args.s175_grid,
            "n_rate": args.s175_grid,
            "duration": args.s175_duration,
            "dt": 0.1,
            "wave_period": 18.0,
        }
        s_curve = sb.s175_integrity_curve(args.s175_heights, progress=progress, **kw)
        cpu_s175 = time.process_time() - t0
        sb.write_integrity_csv(s_curve, out / "s175_integrity.csv")
        sb.plot_integrity(s_curve, out / "s175_integrity.png", n_panels=4)
        for h, b in zip(s_curve.forcing, s_curve.basins, strict=True):
            sb.write_basin(b, out / f"s175_H{h:g}.csv")
        n_ship_steps = args.s175_grid**2 * round(args.s175_duration / 0.1) * len(s_curve.basins)
        results["s175"] = {
            "grid": args.s175_grid,
            "duration_s": args.s175_duration,
            "dt_s": 0.1,
            "wave_period_s": 18.0,
            "wave_heading_deg": 90.0,
            "capsize_angle_rad": s_curve.basins[0].capsize_angle,
            "calm_safe_fraction": s_curve.reference_safe_fraction,
            "wave_height_m": s_curve.forcing.tolist(),
            "integrity": s_curve.integrity.tolist(),
            "cpu_s": cpu_s175,
            "cpu_us_per_ship_step": 1e6 * cpu_s175 / n_ship_steps,
        }
        print(
            f"S175 roll only ({args.s175_grid}² ships per batch, {args.s175_duration:g} s, "
            f"T = 18 s beam seas): calm safe fraction {s_curve.reference_safe_fraction:.4f}; "
            f"{cpu_s175:.0f} s CPU ({results['s175']['cpu_us_per_ship_step']:.0f} µs per "
            "ship-step)"
        )
        for h, g in zip(s_curve.forcing, s_curve.integrity, strict=True):
            print(f"  H = {h:g} m: integrity {g:.4f}")

    if args.json:
        atomic_write_text(Path(args.json), json.dumps(results, indent=2, default=float))
        print(f"wrote {args.json}")
    return 0


def _plot_comparison(b1: sb.SafeBasin, b2: sb.SafeBasin, path: Path) -> None:
    """Eq. 1 and the eq. 2 fit side by side, and the cells where they disagree (their fig. 8)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.2), dpi=110, sharey=True)
    ext = (b1.roll[0], b1.roll[-1], b1.roll_rate[0], b1.roll_rate[-1])
    for ax, b, title in (
        (axes[0], b1, "eq. 1 (Edith Terkol), F = 0.0195"),
        (axes[1], b2, "eq. 2 fit from ⟨−0.4, −0.35⟩, F_u = 0.022"),
    ):
        ax.imshow(b.safe, origin="lower", extent=ext, aspect="auto", cmap="Greys_r")
        ax.set_title(f"{title}\nsafe fraction {b.safe_fraction:.3f}", fontsize=9)
        ax.set_xlabel("φ₀ [rad]")
    diff = b1.capsized != b2.capsized
    axes[2].imshow(b1.safe, origin="lower", extent=ext, aspect="auto", cmap="Greys_r", alpha=0.4)
    yy, xx = np.nonzero(diff)
    axes[2].plot(b1.roll[xx], b1.roll_rate[yy], "r.", ms=2)
    axes[2].set_title(f"disagreement (red): {diff.mean():.1%} of the cells", fontsize=9)
    axes[2].set_xlabel("φ₀ [rad]")
    axes[0].set_ylabel("φ̇₀ [rad/s]")
    fig.tight_layout()
    sb._save(fig, path)


if __name__ == "__main__":
    raise SystemExit(main())
