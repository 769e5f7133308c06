"""``ship-gym hull``: particulars, hydrostatics, equilibrium and GZ curve of a library hull."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from ship_gym.cli.common import (
    CLIError,
    add_overrides_argument,
    add_ship_argument,
    bounded_float,
    parse_overrides,
    positive_float,
    prepare_output,
    write_json,
    write_or_rescue,
)


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``hull`` on the ``ship-gym`` parser."""
    p = sub.add_parser("hull", help="particulars, hydrostatics and GZ curve of a ship's hull")
    add_ship_argument(p, positional=True)
    add_overrides_argument(p, "builder overrides, e.g. kg=10.0 n_sections=80")
    p.add_argument(
        "--heel-max", type=bounded_float(0.0, 180.0, low_open=True), default=90.0,
        help="largest heel [deg], in (0, 180]",
    )  # fmt: skip
    p.add_argument("--heel-step", type=positive_float, default=5.0, help="heel step [deg], > 0")
    p.add_argument("--plot", default="out/gz.png", help="GZ plot (PNG); '' to skip")
    p.add_argument("--json", default=None, help="write the numbers to this JSON file")
    p.set_defaults(func=_cmd_hull)


def _check_loading(hull: object, hs: object, overrides: dict) -> None:
    """Refuse a loading condition without positive GM or with G outside the hull, naming
    ``kg`` when it was set with ``--set``."""
    import numpy as np

    kg = float(getattr(hull, "kg", np.nan))
    depth = float(getattr(getattr(hull, "particulars", None), "depth", np.inf))
    gmt = float(getattr(hs, "gmt", np.nan))
    name = "--set kg" if "kg" in overrides else "the loading condition"
    if not np.isfinite(kg) or kg < 0.0:
        raise CLIError(
            f"{name}: KG = {kg:g} m puts G below the keel; expected 0 <= KG (<= depth {depth:g} m)"
        )
    if kg > depth:
        raise CLIError(
            f"{name}: KG = {kg:g} m puts G above the deck (depth {depth:g} m); expected "
            "0 <= KG <= depth"
        )
    if not np.isfinite(gmt) or gmt <= 0.0:
        raise CLIError(
            f"{name}: KG = {kg:g} m gives GMt = {gmt:.3f} m <= 0 at the design waterline (the "
            f"ship is unstable upright); expected KG < KM = {kg + gmt:.3f} m"
        )


def _cmd_hull(args: argparse.Namespace) -> int:
    from ship_gym.ship import hull_of

    check_heel_arguments(args)
    prepare_output(args.plot, "--plot", suffixes=(".png", ".pdf", ".svg"))
    prepare_output(args.json, "--json")
    overrides = parse_overrides(args.set)
    hull = hull_of(args.hull, **overrides)
    payload = report_hull(
        hull, heel_max=args.heel_max, heel_step=args.heel_step, plot=args.plot, overrides=overrides
    )
    write_json(args.json, payload)
    return 0


def check_heel_arguments(args: argparse.Namespace) -> None:
    """Refuse a heel step larger than the largest heel (``--heel-step``, ``--heel-max``)."""
    if args.heel_step > args.heel_max:
        raise CLIError(
            f"--heel-step {args.heel_step:g} is larger than --heel-max {args.heel_max:g}; "
            "expected a step <= the largest heel"
        )


def report_hull(
    hull: Any,
    *,
    heel_max: float = 90.0,
    heel_step: float = 5.0,
    plot: str | None = None,
    overrides: dict | None = None,
) -> dict[str, Any]:
    """Print a hull's particulars, hydrostatics, equilibrium and GZ curve, plot the GZ curve
    (``plot``: a prepared path or None/'' to skip); returns the numbers (the ``--json`` payload).
    """
    import numpy as np

    from ship_gym.hull import equilibrium, hydrostatics, righting_arm

    p = hull.particulars
    hs = hydrostatics(hull)
    _check_loading(hull, hs, overrides or {})
    eq = equilibrium(hull)
    hs_eq = hydrostatics(hull, heave=eq.heave, trim=eq.trim)
    heels = np.arange(0.0, heel_max + 1e-9, heel_step)
    curve = righting_arm(hull, heels)
    print(
        f"hull {hull.name}: {hull.mesh.n_faces} panels to the deck, "
        f"{hull.immersed_mesh.n_faces} immersed"
    )
    print(f"  Lpp {p.lpp:.3f} m  B {p.beam:.3f} m  T {p.draught:.3f} m  D {p.depth:.3f} m")
    print(
        f"  mass {hull.mass.mass / 1e3:.1f} t  G = {np.round(hull.mass.cog, 3)} m (body frame)"
        f"  KG {hull.kg:.3f} m  radii {np.round(hull.mass.radii_of_gyration, 3)} m"
    )
    print("  design waterline (even keel):")
    print(
        f"    displacement {hs.displacement / 1e3:.1f} t  volume {hs.volume:.1f} m^3  "
        f"KB {hs.kb:.3f} m  BMt {hs.bmt:.3f} m  GMt {hs.gmt:.3f} m  GMl {hs.gml:.1f} m  "
        f"Awp {hs.waterplane_area:.1f} m^2  LCF {hs.centre_of_flotation[0]:.3f} m"
    )
    print(
        f"  free-floating equilibrium: sinkage {eq.heave:+.4f} m  trim "
        f"{np.degrees(eq.trim):+.4f} deg  GMt {hs_eq.gmt:.3f} m"
    )
    if p.reference:
        print(f"  reference: {p.reference}")
    print("  heel [deg]   GZ [m]")
    for h, gz in zip(curve.heel_deg, curve.gz, strict=True):
        print(f"  {h:9.1f}  {gz:8.4f}")
    vanishing = curve.vanishing_angle_deg
    top = float(np.max(curve.heel_deg))
    print(
        f"  max GZ {curve.max_gz:.4f} m at {curve.angle_max_gz_deg:.1f} deg; angle of vanishing "
        + (
            f"stability {vanishing:.2f} deg"
            if np.isfinite(vanishing)
            else f"stability not reached up to {top:g} deg (GZ > 0 there, within rounding)"
        )
    )
    if plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 4))
        ax.plot(curve.heel_deg, curve.gz, "o-", ms=3, label="GZ (free sinkage and trim)")
        ax.plot(
            curve.heel_deg, hs_eq.gmt * np.sin(np.radians(curve.heel_deg)), "--", label="GM sin φ"
        )
        ax.axhline(0.0, color="k", lw=0.5)
        if np.isfinite(curve.vanishing_angle_deg):
            ax.axvline(
                curve.vanishing_angle_deg,
                color="r",
                lw=0.8,
                label=f"vanishing {curve.vanishing_angle_deg:.1f}°",
            )
        ax.set(xlabel="heel φ [deg]", ylabel="GZ [m]", title=f"{hull.name} righting arm")
        ax.set_ylim(min(-0.5, curve.gz.min() * 1.1), max(curve.gz.max() * 1.3, 0.5))
        ax.legend()
        ax.grid(alpha=0.3)
        fig.tight_layout()
        target = Path(plot)
        write_or_rescue(
            target, lambda f: fig.savefig(f, dpi=120, format=target.suffix[1:]), "--plot"
        )
        plt.close(fig)
        print(f"wrote {plot}")
    return {
        "hull": hull.name,
        "displacement_t": hs.displacement / 1e3,
        "kb_m": hs.kb,
        "gmt_m": hs.gmt,
        "gml_m": hs.gml,
        "heel_deg": curve.heel_deg.tolist(),
        "gz_m": curve.gz.tolist(),
        "vanishing_angle_deg": curve.vanishing_angle_deg,
        "sinkage_m": float(eq.heave),
        "trim_deg": float(np.degrees(eq.trim)),
    }
