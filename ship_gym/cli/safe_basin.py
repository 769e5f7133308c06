"""``ship-gym safe-basin``: McCue & Campbell safe basins of roll motion.

A grid of initial roll / roll rate is integrated for ``--duration`` seconds and every cell whose
roll exceeds the vanishing angle is marked capsized (:mod:`ship_gym.analysis.safe_basin`):

* ``--model edith-terkol``: the 1-DOF Edith Terkol (McCue & Campbell eq. 1), forcing amplitude
  ``--forcing`` F [rad/s²] at ωₑ = 0.85 · 0.62 rad/s; ``--integrity F1 F2 …`` adds the integrity
  curve (safe area relative to the unforced basin) over those amplitudes;
* ``--model s175``: the S175 with only roll free in the 6-DOF simulator (one batch of grid² ships),
  in calm water or regular beam waves of ``--wave-height`` [m] and ``--wave-period`` [s].

Outputs: a summary on stdout; ``--json`` (numbers), ``--csv`` (the basin, long format; a ``.nc``
suffix writes NetCDF), ``--plot`` (PNG) — all written atomically.
"""

from __future__ import annotations

import argparse
from typing import Any

from ship_gym.cli.common import (
    CLIError,
    add_ship_argument,
    bounded_float,
    check_memory,
    finite_float,
    min_count,
    nonnegative_float,
    positive_float,
    prepare_output,
    write_json,
)

MODELS = ("edith-terkol", "six-dof", "s175")
"""``six-dof``: the roll-only slice of the 6-DOF model of ``--ship``; ``s175`` is the same with
the S175 (the default ship)."""


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``safe-basin`` on the ``ship-gym`` parser."""
    p = sub.add_parser(
        "safe-basin",
        help="safe basin of roll motion (McCue & Campbell): Edith Terkol 1-DOF or S175 roll-only",
    )
    p.add_argument("--model", default="edith-terkol", choices=MODELS)
    add_ship_argument(p)
    p.add_argument(
        "--forcing", type=nonnegative_float, default=0.0195,
        help="edith-terkol forcing amplitude F [rad/s^2] (McCue & Campbell: 0.0195)",
    )  # fmt: skip
    p.add_argument(
        "--integrity", type=nonnegative_float, nargs="*", default=None, metavar="F",
        help="edith-terkol: also the integrity curve over these amplitudes [rad/s^2]",
    )  # fmt: skip
    p.add_argument(
        "--wave-height", type=nonnegative_float, default=0.0, help="s175: wave height H [m]"
    )
    p.add_argument("--wave-period", type=positive_float, default=18.0, help="s175: wave period [s]")
    p.add_argument(
        "--wave-heading-deg", type=finite_float, default=90.0, help="s175: relative heading β [deg]"
    )
    p.add_argument(
        "--grid", type=min_count(2), default=None,
        help="grid points per axis (default 101 edith-terkol, 21 s175)",
    )  # fmt: skip
    p.add_argument(
        "--duration", type=positive_float, default=None,
        help="integration time [s] (default 200 edith-terkol, 120 s175)",
    )  # fmt: skip
    p.add_argument(
        "--dt",
        type=positive_float,
        default=None,
        help="time step [s] (default 0.05 / 0.1 for s175)",
    )
    p.add_argument(
        "--roll-max", type=bounded_float(0.0, 3.2, low_open=True), default=None,
        help="grid half-width in roll [rad], in (0, 3.2]",
    )  # fmt: skip
    p.add_argument(
        "--rate-max", type=positive_float, default=None, help="grid half-width in roll rate [rad/s]"
    )
    p.add_argument("--json", default=None, help="write the numbers to this JSON file")
    p.add_argument("--csv", default=None, help="write the basin (CSV; .nc suffix: NetCDF)")
    p.add_argument("--plot", default=None, help="write a PNG of the basin (and integrity curve)")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.set_defaults(func=_cmd_safe_basin)


_BYTES_PER_CELL = {
    True: 12 * 8.0,  # Edith–Terkol: roll and rate, the RK4 stages and a work array, float64
    False: 4096.0,  # a ship of the batched 6-DOF engine (measured ≈ 3 kB per ship, S175)
}
"""Memory per grid cell [bytes] (key: the model is the 1-DOF Edith–Terkol equation)."""


def _cmd_safe_basin(args: argparse.Namespace) -> int:
    from ship_gym.analysis import safe_basin as sb
    from ship_gym.roll.equation import RollEquation

    if args.dt is not None and args.duration is not None and args.dt > args.duration:
        raise CLIError(f"--dt {args.dt:g} s is longer than --duration {args.duration:g} s")
    if args.integrity is not None and args.model != "edith-terkol":
        raise CLIError("--integrity is for --model edith-terkol only")
    if args.integrity is not None and not args.integrity:
        raise CLIError("--integrity: expected at least one forcing amplitude F [rad/s^2]")
    prepare_output(args.json, "--json")
    prepare_output(args.csv, "--csv", suffixes=(".csv", ".nc"))
    prepare_output(args.plot, "--plot", suffixes=(".png", ".pdf", ".svg"))
    progress = not args.no_progress
    separatrix = None
    curve = None
    n_grid = args.grid if args.grid is not None else (101 if args.model == "edith-terkol" else 21)
    check_memory(
        float(n_grid) ** 2 * _BYTES_PER_CELL[args.model == "edith-terkol"],
        f"--grid {n_grid}: {float(n_grid) ** 2:.3g} initial conditions integrated together",
        "a smaller --grid",
    )
    if args.model == "edith-terkol":
        n = 101 if args.grid is None else args.grid
        roll_max = 1.0 if args.roll_max is None else args.roll_max
        rate_max = 0.6 if args.rate_max is None else args.rate_max
        kwargs: dict[str, Any] = {
            "roll_range": (-roll_max, roll_max),
            "roll_rate_range": (-rate_max, rate_max),
            "n_roll": n,
            "n_rate": n,
            "duration": 200.0 if args.duration is None else args.duration,
            "dt": 0.05 if args.dt is None else args.dt,
            "model": "edith-terkol",
        }
        eq = RollEquation.edith_terkol(forcing_amplitude=args.forcing)
        separatrix = eq
        basin = sb.safe_basin(eq, progress=progress, **kwargs)
        reference = sb.safe_basin(RollEquation.edith_terkol(), **kwargs)
        if args.integrity:
            curve = sb.integrity_curve(eq, args.integrity, progress=progress, **kwargs)
    else:
        n = 21 if args.grid is None else args.grid
        rate_max = 0.5 if args.rate_max is None else args.rate_max
        kwargs = {
            "roll_range": None if args.roll_max is None else (-args.roll_max, args.roll_max),
            "roll_rate_range": (-rate_max, rate_max),
            "n_roll": n,
            "n_rate": n,
            "duration": 120.0 if args.duration is None else args.duration,
            "dt": 0.1 if args.dt is None else args.dt,
            "wave_period": args.wave_period,
            "wave_heading_deg": args.wave_heading_deg,
            "hull": "s175" if args.model == "s175" else args.hull,
        }
        basin = sb.s175_safe_basin(wave_height=args.wave_height, progress=progress, **kwargs)
        reference = (
            basin
            if args.wave_height == 0.0
            else sb.s175_safe_basin(wave_height=0.0, progress=progress, **kwargs)
        )
    integrity = basin.integrity(reference)
    print(
        f"{basin.model}: {basin.roll.size}×{basin.roll_rate.size} grid, {basin.duration:g} s, "
        f"capsize angle {basin.capsize_angle:.4f} rad; safe fraction {basin.safe_fraction:.4f}, "
        f"safe area {basin.safe_area:.4f} rad²/s, integrity (vs unforced) {integrity:.4f}"
    )
    if curve is not None:
        for f, g in zip(curve.forcing, curve.integrity, strict=True):
            print(f"  F = {f:.4g} rad/s^2: integrity {g:.4f}")
    if args.json:
        payload = {
            "model": basin.model,
            "parameters": dict(basin.parameters),
            "grid": [int(basin.roll_rate.size), int(basin.roll.size)],
            "duration_s": basin.duration,
            "capsize_angle_rad": basin.capsize_angle,
            "safe_fraction": basin.safe_fraction,
            "safe_area_rad2_s": basin.safe_area,
            "unforced_safe_fraction": reference.safe_fraction,
            "integrity": integrity,
        }
        if curve is not None:
            payload["integrity_curve"] = {
                "forcing_amplitude_rad_s2": curve.forcing.tolist(),
                "integrity": curve.integrity.tolist(),
                "safe_fraction": curve.safe_fraction.tolist(),
            }
        write_json(args.json, payload)
    if args.csv:
        print(f"wrote {sb.write_basin(basin, args.csv)}")
    if args.plot:
        if curve is not None:
            print(f"wrote {sb.plot_integrity(curve, args.plot, separatrix_of=separatrix)}")
        else:
            png = sb.plot_basin(basin, args.plot, separatrix_of=separatrix, reference=reference)
            print(f"wrote {png}")
    return 0
