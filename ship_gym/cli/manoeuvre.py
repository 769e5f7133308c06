"""``ship-gym manoeuvre``: IMO manoeuvring trials (turning circle, zig-zags) in calm water.

Runs the trials of :mod:`ship_gym.analysis.manoeuvres` on the 6-DOF simulator at the test speed
(default: the ship's service speed, from its ship file), prints the metrics and the MSC.137(76)
pass/fail table — a trial that heels the ship beyond its angle of vanishing stability is
reported as a capsize, and its criteria as not met — and optionally writes the numbers
(``--json``) and a figure (``--plot``).
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from ship_gym.cli.common import (
    CLIError,
    add_ship_argument,
    bounded_float,
    nonnegative_float,
    positive_float,
    prepare_output,
    write_json,
    write_or_rescue,
)

if TYPE_CHECKING:
    from ship_gym.analysis.manoeuvres import TurningCircleResult, ZigzagResult
    from ship_gym.engine.ship import ShipSetup

TESTS = ("turning", "zigzag10", "zigzag20", "all")


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``manoeuvre`` on the ``ship-gym`` parser."""
    p = sub.add_parser(
        "manoeuvre",
        help="IMO manoeuvring trials: 35° turning circle, 10/10 and 20/20 zig-zags (calm water)",
    )
    p.add_argument("--test", default="all", choices=TESTS, help="which trial(s) to run")
    add_ship_argument(p)
    p.add_argument(
        "--speed",
        type=positive_float,
        default=None,
        help="test speed [m/s] (default: the ship's service speed)",
    )
    p.add_argument("--dt", type=positive_float, default=0.1, help="physics time step [s]")
    p.add_argument(
        "--rudder-deg",
        type=bounded_float(0.0, 45.0, low_open=True),
        default=35.0,
        help="turning-circle rudder angle [deg], in (0, 45]",
    )
    p.add_argument("--port", action="store_true", help="first rudder order to port")
    p.add_argument("--settle", type=nonnegative_float, default=60.0, help="straight run before [s]")
    p.add_argument("--json", default=None, help="write the numbers to this JSON file")
    p.add_argument("--plot", default="out/manoeuvre.png", help="figure (PNG); '' to skip")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.set_defaults(func=_cmd_manoeuvre)


def _cmd_manoeuvre(args: argparse.Namespace) -> int:
    from ship_gym.analysis import manoeuvres as man
    from ship_gym.ship import hull_of

    if args.dt > 1.0:
        raise CLIError(f"--dt {args.dt:g} s is too coarse for the 6-DOF model; expected <= 1 s")
    prepare_output(args.json, "--json")
    prepare_output(args.plot, "--plot", suffixes=(".png", ".pdf", ".svg"))
    setup = man.trial_setup(args.hull, args.speed, dt=args.dt)
    length = hull_of(args.hull).particulars.lpp
    side = -1.0 if args.port else 1.0
    progress = not args.no_progress
    want = set(TESTS[:3]) if args.test == "all" else {args.test}
    turning = z10 = z20 = None
    print(
        f"{args.hull}: L = {length:.1f} m, test speed U = {setup.speed:.3f} m/s, "
        f"L/V = {length / setup.speed:.2f} s, dt = {setup.dt} s, 6 DOF free, calm water"
    )
    if "turning" in want:
        turning = man.turning_circle(
            setup, side * args.rudder_deg, settle=args.settle, progress=progress
        )
        _report_capsize(f"turning circle δ = {turning.rudder_order_deg:+g}°", turning, setup)
        m = turning.metrics
        print(
            f"turning circle δ = {turning.rudder_order_deg:+g}°: advance "
            f"{turning.advance_over_L:.3f} L ({m.advance:.0f} m), transfer "
            f"{turning.transfer_over_L:.3f} L, tactical diameter "
            f"{turning.tactical_diameter_over_L:.3f} L ({m.tactical_diameter:.0f} m), steady "
            f"diameter {turning.steady_diameter_over_L:.2f} L, speed "
            f"{turning.steady_speed:.2f} m/s ({turning.steady_speed / turning.approach_speed:.0%})"
            f", heel {turning.steady_roll_deg:+.1f}° [{turning.wall_time:.0f} s wall]"
        )
    for key in ("zigzag10", "zigzag20"):
        if key not in want:
            continue
        angle = 10.0 if key == "zigzag10" else 20.0
        res = man.zigzag(setup, side * angle, settle=args.settle, progress=progress)
        _report_capsize(f"{angle:g}°/{angle:g}° zig-zag", res, setup)
        shoots = ", ".join(f"{o:.2f}°" for o in res.metrics.overshoots_deg)
        print(
            f"{angle:g}°/{angle:g}° zig-zag: overshoots {shoots}; initial turning "
            f"{res.initial_turning_over_L:.3f} L [{res.wall_time:.0f} s wall]"
        )
        if key == "zigzag10":
            z10 = res
        else:
            z20 = res
    rows = man.imo_criteria([r for r in (turning, z10, z20) if r is not None], length, setup.speed)
    print(man.format_criteria(rows))
    if args.json:
        write_json(args.json, man.report(length, setup.speed, turning, z10, z20))
    if args.plot:
        _plot([r for r in (turning, z10, z20) if r is not None], args.plot)
    return 0


def _report_capsize(
    trial: str, result: TurningCircleResult | ZigzagResult, setup: ShipSetup
) -> None:
    """Say so, first, when a trial capsized the ship (its metrics are of the run until then)."""
    import math

    from ship_gym.analysis import manoeuvres as man

    if result.capsized:
        angle = math.degrees(man.capsize_angle(setup))
        print(
            f"{trial}: CAPSIZED {result.capsize_time:.0f} s after the first rudder order (heel "
            f"beyond the angle of vanishing stability, {angle:.1f}°); the trial stopped there "
            "and the metrics below are of the run until then"
        )


def _plot(results: list, path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ship_gym.analysis import manoeuvres as man

    fig, axes = plt.subplots(1, len(results), figsize=(6.0 * len(results), 5.5), squeeze=False)
    for ax, res in zip(axes[0], results, strict=True):
        if isinstance(res, man.TurningCircleResult):
            man.plot_turning_circle(ax, res)
        else:
            man.plot_zigzag(ax, res)
    fig.tight_layout()
    suffix = Path(path).suffix[1:].lower() or "png"
    write_or_rescue(Path(path), lambda f: fig.savefig(f, dpi=110, format=suffix), "--plot")
    plt.close(fig)
    print(f"wrote {path}")
