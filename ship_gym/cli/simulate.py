"""``ship-gym simulate``: one time-domain run of a ship in waves, with series and a plot."""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ship_gym.cli.common import (
    CLIError,
    add_ship_argument,
    count,
    finite_float,
    irregular_sea,
    nonnegative_float,
    positive_float,
    prepare_output,
    seed,
    write_or_rescue,
)

if TYPE_CHECKING:
    from ship_gym.engine.simulator import SimulationResult


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``simulate`` on the ``ship-gym`` parser."""
    p = sub.add_parser("simulate", help="time-domain 6-DOF simulation in regular/irregular waves")
    add_ship_argument(p)
    p.add_argument(
        "--database",
        default="auto",
        help="'auto' (the ship's own), a bundled name or a NetCDF database",
    )
    p.add_argument("--speed", type=nonnegative_float, default=0.0, help="forward speed [m/s]")
    p.add_argument(
        "--heading-deg",
        type=finite_float,
        default=180.0,
        help="wave heading β [deg]: 0 following, 90 beam (from port), 180 head seas",
    )
    sea = p.add_mutually_exclusive_group()
    sea.add_argument(
        "--regular",
        type=positive_float,
        nargs=2,
        metavar=("H", "LAMBDA"),
        help="regular wave height [m] and length [m]",
    )
    sea.add_argument(
        "--irregular",
        type=positive_float,
        nargs=2,
        metavar=("HS", "TP"),
        help="JONSWAP significant height [m] and peak period [s]; Hs/λp <= 1/15 (Tp <= 8 s) "
        "… 1/25 (Tp >= 15 s), λp = g Tp²/2π (DNV-RP-C205 §3.5.5.4)",
    )
    p.add_argument("--components", type=count, default=50, help="irregular-sea components")
    p.add_argument("--seed", type=seed, default=0, help="seed of the irregular sea")
    p.add_argument("--duration", type=positive_float, default=300.0, help="simulated time [s]")
    p.add_argument("--dt", type=positive_float, default=0.05, help="physics time step [s]")
    p.add_argument(
        "--radiation",
        default="state_space",
        choices=["state_space", "convolution", "2a", "2b", "none"],
    )
    p.add_argument(
        "--integrator",
        default="holloway",
        choices=["rk4", "holloway"],
        help="holloway (1 force evaluation/step, default) or rk4 (4)",
    )
    p.add_argument(
        "--precision",
        default="float32",
        choices=["float32", "float64"],
        help="wave sums of the Froude–Krylov kernel (float32: ≈ 2e-7 relative, faster)",
    )
    p.add_argument("--no-diffraction", action="store_true")
    p.add_argument("--no-viscous", action="store_true")
    p.add_argument("--bilge-keels", action="store_true")
    p.add_argument("--hold", default="", help="comma-separated DOFs to hold, e.g. surge,sway,yaw")
    p.add_argument(
        "--steering",
        default="autopilot",
        choices=["autopilot", "none"],
        help="at speed with yaw free: the PID autopilot holds the initial heading with the rudder "
        "(propeller and hull manoeuvring forces on; default), or no rudder (hull manoeuvring "
        "forces only: the waves turn the ship)",
    )
    p.add_argument("--output", default="out/simulation.nc", help=".nc (NetCDF) or .csv")
    p.add_argument("--plot", default="out/simulation.png", help="motion plot; '' to skip")
    p.set_defaults(func=_cmd_simulate)


def _cmd_simulate(args: argparse.Namespace) -> int:
    from ship_gym.conventions import DOF_NAMES, dof_index
    from ship_gym.engine.ship import ShipSetup, build_simulator
    from ship_gym.waves.sea_state import IrregularSea, RegularWave

    if args.dt > 1.0:
        raise CLIError(f"--dt {args.dt:g} s is too coarse for the 6-DOF model; expected <= 1 s")
    if args.dt > args.duration:
        raise CLIError(f"--dt {args.dt:g} s is longer than --duration {args.duration:g} s")
    if args.irregular is not None:
        irregular_sea(args.irregular, "--irregular")
    try:
        held = [dof_index(d.strip()) for d in args.hold.split(",") if d.strip()]
    except (ValueError, KeyError, IndexError) as exc:
        raise CLIError(f"--hold {args.hold!r}: {exc}") from None
    out = prepare_output(args.output, "--output", suffixes=(".nc", ".csv"))
    if out is None:
        raise CLIError("--output: expected a .nc or .csv file path, got ''")
    plot = prepare_output(args.plot, "--plot", suffixes=(".png", ".pdf", ".svg"))
    free = tuple(i not in held for i in range(6))
    # at speed a free yaw needs the hull's lift (manoeuvring forces) and, to keep a course, a
    # rudder: the autopilot by default (ship_gym.hydro.forward_speed, "Two planes")
    steered = args.speed > 0.0 and free[5] and args.steering == "autopilot"
    setup = ShipSetup(
        hull=args.hull,
        database=args.database,
        speed=args.speed,
        radiation=args.radiation,
        diffraction=not args.no_diffraction,
        viscous_roll=not args.no_viscous,
        bilge_keels=args.bilge_keels,
        integrator=args.integrator,
        dt=args.dt,
        free_dofs=free,
        fk_method="fast32" if args.precision == "float32" else "fast",
        propulsion=steered,
        rudder="autopilot" if steered else "none",
    )
    sea: RegularWave | IrregularSea | None
    if args.regular is not None:
        sea = RegularWave(height=args.regular[0], wavelength=args.regular[1])
    elif args.irregular is not None:
        sea = IrregularSea(hs=args.irregular[0], tp=args.irregular[1], n_components=args.components)
    else:
        sea = None
    beta = np.radians(args.heading_deg)
    rng = np.random.default_rng(args.seed)
    sim = build_simulator(setup, sea, wave_heading=beta, rng=rng)
    engine = "compiled engine" if sim.engine.compiled else "engine, numpy path"
    eta0 = sim.eta
    sim.advance(1)  # compiles on the first run of a fresh install (numba cache)
    sim.reset(eta=eta0)
    start = time.perf_counter()
    result = sim.run(args.duration, record_every=max(1, round(0.1 / args.dt)), progress=True)
    wall = time.perf_counter() - start
    print(
        f"simulated {args.duration:.0f} s in {wall:.1f} s wall ({args.duration / wall:.1f}× "
        f"real time, {engine}); max |roll| {np.degrees(np.abs(result.eta[:, 3]).max()):.2f} deg, "
        f"max |pitch| {np.degrees(np.abs(result.eta[:, 4]).max()):.2f} deg"
    )
    if args.speed > 0.0 and free[5]:
        heading = np.degrees(result.eta[:, 5] - eta0[5])
        steering = "autopilot" if steered else "no rudder (hull manoeuvring forces only)"
        print(
            f"steering: {steering}; heading change {heading[-1]:+.1f} deg at the end, max "
            f"{np.abs(heading).max():.1f} deg; speed {result.nu[-1, 0]:.2f} m/s at the end"
        )
    ds = result.to_dataset()
    ds.attrs.update({k: str(v) for k, v in vars(args).items() if k != "func"})
    if out.suffix.lower() == ".csv":
        frame = {"t": result.t, "wave_elevation": result.elevation}
        for i, name in enumerate(DOF_NAMES):
            frame[f"eta_{name}"] = result.eta[:, i]
        for i, name in enumerate(DOF_NAMES):
            frame[f"nu_{name}"] = result.nu[:, i]
        header = ",".join(frame)
        table = np.column_stack(list(frame.values()))
        write_or_rescue(
            out,
            lambda p: np.savetxt(p, table, delimiter=",", header=header, comments=""),
            "--output",
        )
    else:
        from ship_gym.hydro.database import netcdf_engine

        write_or_rescue(out, lambda p: ds.to_netcdf(p, engine=netcdf_engine()), "--output")
    print(f"wrote {out}")
    if plot is not None:
        _plot(result, str(plot), f"{args.hull}, U = {args.speed} m/s, β = {args.heading_deg}°")
    return 0


def _plot(result: SimulationResult, path: str, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(10, 8))
    axes[0].plot(result.t, result.elevation, "k", lw=0.8)
    axes[0].set_ylabel("ζ at O [m]")
    axes[1].plot(result.t, result.eta[:, 2], lw=0.8)
    axes[1].set_ylabel("heave z [m]")
    for i, lab in ((3, "roll"), (4, "pitch"), (5, "yaw")):
        ax = axes[2] if i < 5 else axes[3]
        ax.plot(result.t, np.degrees(result.eta[:, i]), lw=0.8, label=lab)
    axes[2].set_ylabel("angle [deg]")
    axes[2].legend()
    axes[3].set_ylabel("yaw ψ [deg]")
    axes[3].set_xlabel("t [s]")
    axes[0].set_title(title)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    suffix = Path(path).suffix[1:].lower() or "png"
    write_or_rescue(Path(path), lambda f: fig.savefig(f, dpi=110, format=suffix), "--plot")
    print(f"wrote {path}")
