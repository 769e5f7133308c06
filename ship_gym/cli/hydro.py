"""``ship-gym hydro`` (build a BEM database) and ``ship-gym kernels`` (retardation diagnostics)."""

from __future__ import annotations

import argparse
import math
import os
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ship_gym.cli.common import (
    CLIError,
    add_overrides_argument,
    add_ship_argument,
    bounded_float,
    check_memory,
    min_count,
    n_jobs,
    parse_overrides,
    positive_float,
    prepare_output,
    prepare_output_dir,
    unique,
    write_json,
    write_or_rescue,
)


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register the hydrodynamic subcommands on the ``ship-gym`` parser."""
    p = sub.add_parser("hydro", help="compute a hydrodynamic database with capytaine (BEM)")
    add_ship_argument(p, positional=True)
    p.add_argument("--output", required=True, help="NetCDF file to write (atomically)")
    add_overrides_argument(p, "hull builder overrides (mesh resolution, loading)")
    p.add_argument(
        "--omega-max",
        type=positive_float,
        default=None,
        help="largest finite frequency [rad/s] (default: what the mesh resolves)",
    )
    p.add_argument(
        "--n-omega", type=min_count(10), default=40, help="number of finite frequencies (>= 10)"
    )
    p.add_argument(
        "--headings",
        type=bounded_float(-360.0, 360.0),
        nargs="*",
        default=None,
        help="wave headings [deg], ours: 0 following, 180 head seas",
    )
    p.add_argument("--n-jobs", type=n_jobs, default=1, help="parallel BEM jobs (joblib)")
    p.add_argument(
        "--checkpoint",
        default=None,
        help="folder keeping each solved frequency; a rerun with the same folder reuses them",
    )
    p.set_defaults(func=_cmd_hydro)

    k = sub.add_parser("kernels", help="retardation functions of a database, with diagnostics")
    k.add_argument("database", help="'s175' (bundled) or a NetCDF database")
    k.add_argument("--t-max", type=positive_float, default=60.0, help="kernel duration [s]")
    k.add_argument("--dt", type=positive_float, default=0.05, help="kernel time step [s]")
    k.add_argument("--method", default="filon", choices=["filon", "simpson", "trapezoid", "fft"])
    k.add_argument("--tail", default="asymptotic", choices=["none", "power", "asymptotic", "taper"])
    k.add_argument("--plot", default="out/kernels.png", help="figure of K, L and reconstructions")
    k.add_argument("--json", default=None, help="write diagnostics to this JSON file")
    k.set_defaults(func=_cmd_kernels)


def rejected_path(output: Path) -> Path:
    """Where a database that failed validation is kept: ``<output stem>.rejected.nc``."""
    return output.with_name(f"{output.stem}.rejected.nc")


def _cmd_hydro(args: argparse.Namespace) -> int:
    from ship_gym.hydro.bem import compute_hull_database
    from ship_gym.hydro.checks import DatabaseError, validate_database
    from ship_gym.hydro.database import save_database
    from ship_gym.ship import hull_of

    output = prepare_output(args.output, "--output", suffixes=(".nc",))
    assert output is not None
    checkpoint = prepare_output_dir(args.checkpoint, "--checkpoint")
    if not args.headings and args.headings is not None:
        raise CLIError("--headings: expected at least one heading [deg]")
    if args.headings is not None:
        unique([h % 360.0 for h in args.headings], "--headings", "headings (mod 360)")
    hull = hull_of(args.hull, **parse_overrides(args.set))
    headings = None if args.headings is None else np.radians(args.headings)
    start = time.perf_counter()
    ds = compute_hull_database(
        hull,
        n_omega=args.n_omega,
        omega_max=args.omega_max,
        wave_directions=headings,
        n_jobs=args.n_jobs,
        checkpoint=checkpoint,
    )
    elapsed = time.perf_counter() - start
    try:
        report = validate_database(ds)
    except DatabaseError as exc:
        # the BEM results are kept: a rejected database can be inspected (or validated with
        # other tolerances) instead of being computed again
        rejected = _save_or_rescue(ds, rejected_path(output), args.output, save_database)
        raise CLIError(
            f"{hull.name}: the computed database failed validation; it was saved to {rejected} "
            f"(not to {args.output!r}).\n{exc}"
        ) from None
    _save_or_rescue(ds, output, args.output, save_database)
    print(
        f"{hull.name}: {ds.attrs.get('n_panels')} panels, {ds.sizes['omega']} frequencies, "
        f"{ds.sizes['wave_direction']} headings in {elapsed:.1f} s → {args.output}"
    )
    for key, value in report.items():
        print(f"  {key}: {value}")
    return 0


def _save_or_rescue(ds: object, path: Path, shown: str, save: Callable[..., object]) -> Path:
    """Save ``ds`` at ``path``; if that fails, in the system temp directory (CLIError saying so)."""
    try:
        save(ds, path)
    except OSError as exc:
        rescue = Path(tempfile.gettempdir()) / f"ship-gym-{os.getpid()}-{path.name}"
        save(ds, rescue)
        raise CLIError(
            f"--output: could not write {str(path)!r} ({exc}) for --output {shown!r}; the "
            f"database was saved to {rescue}"
        ) from None
    return path


def _cmd_kernels(args: argparse.Namespace) -> int:
    from ship_gym.hydro.database import as_arrays, load_database
    from ship_gym.hydro.retardation import (
        compute_kernels,
        kernel_decay,
        plot_kernels,
        plot_reconstruction,
        reconstruction_error,
    )

    if args.dt >= args.t_max:
        raise CLIError(
            f"--dt {args.dt:g} must be smaller than --t-max {args.t_max:g}; expected dt < t_max"
        )
    plot = prepare_output(args.plot, "--plot", suffixes=(".png", ".pdf", ".svg"))
    prepare_output(args.json, "--json")
    if Path(args.database).is_dir():
        raise CLIError(f"database {args.database!r} is a directory; expected a NetCDF file")
    ds = load_database(args.database)
    arr = as_arrays(ds)
    if arr.added_mass_infinite is None:
        raise ValueError(
            f"{args.database} has no infinite-frequency added mass A(∞) (omega = inf entry); "
            "the kernels and their reconstruction need it"
        )
    # K(t) and L(t): one float64 per time step and DOF pair each (what fails first when t_max /
    # dt is huge); the kernels' own work arrays are of the same order
    steps = math.floor(args.t_max / args.dt) + 1
    n_pairs = int(np.prod(np.shape(arr.added_mass)[1:]))
    check_memory(
        2.0 * steps * n_pairs * 8.0,
        f"--t-max {args.t_max:g} with --dt {args.dt:g}: {steps:.3g} time steps of {n_pairs} DOF "
        "pairs",
        "a shorter --t-max or a larger --dt",
    )
    kernels = compute_kernels(
        arr.omega,
        arr.added_mass,
        arr.radiation_damping,
        arr.added_mass_infinite,
        t_max=args.t_max,
        dt=args.dt,
        method=args.method,
        tail=args.tail,
    )
    decay = kernel_decay(kernels.t, kernels.K)
    err = reconstruction_error(
        kernels.t,
        kernels.K,
        arr.omega,
        arr.added_mass,
        arr.radiation_damping,
        arr.added_mass_infinite,
    )
    print(
        f"kernels of {args.database}: t ∈ [0, {args.t_max}] s, dt {args.dt} s, "
        f"method {args.method}, tail {args.tail}"
    )
    print(
        f"  decay |K(t_end)|/max|K| worst pair: {np.nanmax(decay.ratio):.3g} "
        f"(all decayed below {decay.threshold}: {decay.all_decayed})"
    )
    print(f"  Ogilvie reconstruction, worst relative error over resolved ω: {err.max_error:.3g}")
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        pairs = (("Sway", "Sway"), ("Heave", "Heave"), ("Roll", "Roll"), ("Pitch", "Pitch"))
        fig, axes = plt.subplots(1 + len(pairs), 2, figsize=(11, 3.0 * (1 + len(pairs))))
        plot_kernels(kernels, pairs, axes=axes[0])
        for row, pair in zip(axes[1:], pairs, strict=True):
            plot_reconstruction(
                arr.omega,
                arr.added_mass,
                arr.radiation_damping,
                err.added_mass_reconstructed,
                err.damping_reconstructed,
                pair,
                omega_reconstructed=err.omega,
                axes=row,
            )
        fig.tight_layout()
        assert plot is not None
        write_or_rescue(plot, lambda f: fig.savefig(f, dpi=110, format=plot.suffix[1:]), "--plot")
        print(f"wrote {args.plot}")
    write_json(
        args.json,
        {
            "max_reconstruction_error": float(err.max_error),
            "max_decay_ratio": float(np.nanmax(decay.ratio)),
            "all_decayed": bool(decay.all_decayed),
        },
    )
    return 0
