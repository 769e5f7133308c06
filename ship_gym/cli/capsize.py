"""``ship-gym capsize-map``, ``parametric-roll`` and ``dead-ship``: capsize-risk evaluation.

* ``capsize-map``: heading × Froude number (× sea state × seeds) sweep under the heading
  autopilot, resumable JSON-lines results, polar plot (:mod:`ship_gym.analysis.capsize_map`).
* ``parametric-roll``: Mathieu-type susceptibility check in head/following regular waves and,
  optionally, the simulator's answer (:mod:`ship_gym.analysis.intact_stability`).
* ``dead-ship``: no propulsion, beam irregular seas; roll statistics and capsize probability over
  seeds (:mod:`ship_gym.analysis.intact_stability`).

All three run on the engine: ``--engine auto`` (default) batches the seeds of a cell into one
engine call, ``--engine simulator`` runs one ship at a time.
"""

from __future__ import annotations

import argparse

from ship_gym.cli.common import (
    CLIError,
    add_overrides_argument,
    add_ship_argument,
    bounded_float,
    check_irregular_sea,
    count,
    n_jobs,
    parse_overrides,
    positive_float,
    prepare_output,
    unique,
    write_json,
)

ENGINE_HELP = (
    "how the engine runs the study: 'auto'/'engine' (default) the seeds of a cell as the ships "
    "of one batch, 'simulator' one ship at a time (both agree to rounding)"
)


def _add_engine_argument(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--engine", default="auto", choices=("auto", "engine", "simulator"), help=ENGINE_HELP
    )


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``capsize-map``, ``parametric-roll`` and ``dead-ship`` on the parser."""
    p = sub.add_parser(
        "capsize-map",
        help="capsize map: heading x Froude number (x sea state x seeds) under the autopilot",
    )
    add_ship_argument(p)
    add_overrides_argument(
        p, "loading condition / hull overrides, e.g. kg=10.1 (raises G: lower GM)"
    )
    p.add_argument(
        "--headings",
        type=bounded_float(-360.0, 360.0),
        nargs="+",
        default=[0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0],
        help="relative wave headings β [deg] (0 following, 180 head seas)",
    )
    p.add_argument(
        "--froude",
        type=bounded_float(0.0, 1.0),
        nargs="+",
        default=[0.1, 0.2, 0.3],
        help="Froude numbers, in [0, 1]",
    )
    p.add_argument(
        "--sea",
        nargs="+",
        default=["regular:10.5:262.5"],
        help="sea states: 'regular:H:lambda' [m] or 'jonswap:Hs:Tp' [m, s]",
    )
    p.add_argument("--seeds", type=count, default=1, help="seeds per cell (0..n-1)")
    p.add_argument(
        "--duration", type=positive_float, default=720.0, help="simulated time per run [s]"
    )
    p.add_argument("--dt", type=positive_float, default=0.1, help="physics time step [s]")
    p.add_argument("--integrator", default="rk4", choices=("rk4", "holloway"))
    p.add_argument(
        "--radiation",
        default="state_space",
        choices=("state_space", "convolution", "2a", "2b", "none"),
    )
    p.add_argument(
        "--capsize-angle",
        type=bounded_float(0.0, 180.0, low_open=True),
        default=None,
        help="|roll| counted as capsize [deg] (default: vanishing angle of the GZ curve)",
    )
    p.add_argument(
        "--initial-heel-deg",
        type=bounded_float(0.0, 30.0),
        default=0.0,
        help="each seed starts heeled by a heel drawn in ± this [deg], so that an instability "
        "grows from a stated disturbance, not from round-off (default 0: upright)",
    )
    p.add_argument("--n-jobs", type=n_jobs, default=1, help="parallel worker processes")
    p.add_argument(
        "--results", default="out/capsize_map.jsonl", help="JSON-lines results (resumable)"
    )
    p.add_argument("--plot", default="out/capsize_map.png", help="polar plot (PNG); '' to skip")
    p.add_argument("--json", default=None, help="write the per-cell summary to this JSON file")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    _add_engine_argument(p)
    p.set_defaults(func=cmd_capsize_map)

    q = sub.add_parser(
        "parametric-roll",
        help="parametric-roll susceptibility (Mathieu check; --simulate for the 6-DOF answer)",
    )
    add_ship_argument(q)
    add_overrides_argument(q, "hull overrides")
    q.add_argument("--wavelength-ratio", type=positive_float, default=1.0, help="λ/L [-]")
    q.add_argument(
        "--steepness",
        type=bounded_float(0.0, 1.0 / 7.0, low_open=True),
        default=1.0 / 30.0,
        help="H/λ [-], in (0, 1/7] (the breaking limit)",
    )
    q.add_argument(
        "--heading",
        type=bounded_float(-360.0, 360.0),
        default=180.0,
        help="β [deg]: 180 head seas, 0 following",
    )
    q.add_argument(
        "--froude",
        type=bounded_float(0.0, 1.0),
        default=None,
        help="Froude number (default: the one giving ω_e = 2 ω_φ, if any)",
    )
    q.add_argument("--simulate", action="store_true", help="also run the simulator")
    q.add_argument("--duration", type=positive_float, default=600.0, help="simulated time [s]")
    q.add_argument("--dt", type=positive_float, default=0.1, help="physics time step [s]")
    q.add_argument("--json", default=None, help="write the numbers to this JSON file")
    q.add_argument("--plot", default="", help="roll time history (PNG) with --simulate")
    _add_engine_argument(q)
    q.set_defaults(func=cmd_parametric_roll)

    d = sub.add_parser(
        "dead-ship", help="dead ship (no propulsion) in beam irregular seas: roll statistics"
    )
    add_ship_argument(d)
    add_overrides_argument(d, "hull overrides")
    d.add_argument("--hs", type=positive_float, default=7.0, help="significant wave height [m]")
    d.add_argument("--tp", type=positive_float, default=15.0, help="peak period [s]")
    d.add_argument("--seeds", type=count, default=4, help="number of seeds")
    d.add_argument(
        "--duration", type=positive_float, default=600.0, help="simulated time per seed [s]"
    )
    d.add_argument("--dt", type=positive_float, default=0.1, help="physics time step [s]")
    d.add_argument("--n-jobs", type=n_jobs, default=1, help="parallel worker processes")
    d.add_argument(
        "--hold-yaw",
        action="store_true",
        help="keep the ship beam-on (IMO dead-ship assumption); by default yaw is free and the "
        "unpowered ship turns away from beam seas",
    )
    d.add_argument("--json", default=None, help="write the numbers to this JSON file")
    _add_engine_argument(d)
    d.set_defaults(func=cmd_dead_ship)


def _check_times(args: argparse.Namespace) -> None:
    if args.dt > 1.0:
        raise CLIError(f"--dt {args.dt:g} s is too coarse for the 6-DOF model; expected <= 1 s")
    if args.dt > args.duration:
        raise CLIError(f"--dt {args.dt:g} s is longer than --duration {args.duration:g} s")


def cmd_capsize_map(args: argparse.Namespace) -> int:
    """Run (or resume) a capsize map and print its summary."""
    from ship_gym.analysis import capsize_map as cm

    _check_times(args)
    unique([h % 360.0 for h in args.headings], "--headings", "headings [deg] (mod 360)")
    headings = tuple(args.headings)
    froude = unique(args.froude, "--froude", "Froude numbers")
    seas = []
    for text in args.sea:
        try:
            spec = cm.SeaSpec.parse(text)
        except ValueError as exc:
            raise CLIError(f"--sea: {exc}") from None
        if spec.kind == "irregular" and spec.period is not None:
            check_irregular_sea(spec.height, spec.period, f"--sea {text}")
        seas.append(spec)
    dup = sorted({args.sea[i] for i, sp in enumerate(seas) if sp in seas[:i]})
    if dup:
        raise CLIError(f"--sea: duplicate sea states {', '.join(dup)}; expected each one once")
    prepare_output(args.results, "--results")
    prepare_output(args.plot, "--plot", suffixes=(".png", ".pdf", ".svg"))
    prepare_output(args.json, "--json")
    config = cm.CapsizeMapConfig(
        hull=args.hull,
        hull_overrides=parse_overrides(args.set),
        headings_deg=headings,
        froude_numbers=froude,
        seas=tuple(seas),
        seeds=tuple(range(int(args.seeds))),
        duration=args.duration,
        dt=args.dt,
        integrator=args.integrator,
        radiation=args.radiation,
        capsize_angle_deg=args.capsize_angle,
        initial_heel_deg=args.initial_heel_deg,
    )
    n_cells = len(config.cells())
    print(
        f"capsize map {args.hull} {config.hull_overrides or '(design loading)'}: {n_cells} runs "
        f"of {config.duration:g} s, dt {config.dt} s, {config.integrator}, radiation "
        f"{config.radiation}, n_jobs {args.n_jobs} → {args.results}"
    )
    result = cm.run_capsize_map(
        config,
        args.results,
        n_jobs=args.n_jobs,
        progress=not args.no_progress,
        engine=getattr(args, "engine", "auto"),
    )
    print(
        f"capsize angle {result.capsize_angle_deg:.1f}°; ran {result.n_run} cells "
        f"({n_cells - result.n_run} resumed) in {result.wall_s:.1f} s wall"
    )
    summary = result.summary()
    print(" sea  β [deg]   Fn    P(capsize)  max|φ| [deg]  RMS φ [deg]  t_capsize [s]")
    for row in summary:
        print(
            f" {row['sea']:3d}  {row['heading_deg']:7.1f}  {row['froude']:5.2f}  "
            f"{row['capsize_probability']:10.2f}  {row['max_abs_roll_deg']:12.1f}  "
            f"{row['rms_roll_deg']:11.2f}  {row['mean_time_to_capsize']:13.1f}"
        )
    if args.plot:
        print(f"wrote {cm.plot_capsize_map(result, args.plot)}")
    if args.json:
        payload = {
            "config": config.to_dict(),
            "capsize_angle_deg": result.capsize_angle_deg,
            "wall_s": result.wall_s,
            "summary": summary,
        }
        write_json(args.json, payload)
    return 0


def cmd_parametric_roll(args: argparse.Namespace) -> int:
    """Mathieu susceptibility check (and optionally the simulator)."""
    from ship_gym.analysis import intact_stability as ist

    _check_times(args)
    prepare_output(args.json, "--json")
    prepare_output(args.plot, "--plot", suffixes=(".png", ".pdf", ".svg"))
    check = ist.parametric_roll_check(
        args.hull,
        parse_overrides(args.set),
        wavelength_ratio=args.wavelength_ratio,
        steepness=args.steepness,
        heading_deg=args.heading,
        froude=args.froude,
    )
    print(ist.format_check(check))
    payload: dict = {"check": ist.check_to_dict(check)}
    if args.simulate:
        sim = ist.simulate_parametric_roll(
            check, duration=args.duration, dt=args.dt, engine=getattr(args, "engine", "auto")
        )
        print(
            f"simulator: max |φ| {sim.max_abs_roll_deg:.2f}° from an initial "
            f"{sim.initial_heel_deg:g}° heel; late amplitude / initial heel "
            f"{sim.growth_ratio:.2f} → {'GROWS' if sim.grows else 'decays'}"
        )
        payload["simulation"] = ist.simulation_to_dict(sim)
        if args.plot:
            print(f"wrote {ist.plot_parametric_roll(check, sim, args.plot)}")
    write_json(args.json, payload)
    return 0


def cmd_dead_ship(args: argparse.Namespace) -> int:
    """Dead-ship condition: roll statistics and capsize probability over seeds."""
    from ship_gym.analysis import intact_stability as ist

    _check_times(args)
    check_irregular_sea(args.hs, args.tp, "--hs/--tp")
    prepare_output(args.json, "--json")
    res = ist.dead_ship(
        args.hull,
        parse_overrides(args.set),
        hs=args.hs,
        tp=args.tp,
        seeds=tuple(range(int(args.seeds))),
        duration=args.duration,
        dt=args.dt,
        n_jobs=args.n_jobs,
        hold_yaw=args.hold_yaw,
        engine=getattr(args, "engine", "auto"),
    )
    print(ist.format_dead_ship(res))
    if args.json:
        write_json(args.json, ist.dead_ship_to_dict(res))
    return 0
