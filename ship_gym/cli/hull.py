"""``ship-gym hull``: particulars, hydrostatics, equilibrium and GZ curve of a library hull."""

from __future__ import annotations

import argparse
from pathlib import Path

from ship_gym.cli.common import add_overrides_argument, parse_overrides, write_json


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``hull`` on the ``ship-gym`` parser."""
    p = sub.add_parser("hull", help="particulars, hydrostatics and GZ curve of a library hull")
    p.add_argument("hull", help="s175, box_barge, hemisphere or wigley")
    add_overrides_argument(p, "builder overrides, e.g. kg=10.0 n_sections=80")
    p.add_argument("--heel-max", type=float, default=90.0, help="largest heel [deg]")
    p.add_argument("--heel-step", type=float, default=5.0, help="heel step [deg]")
    p.add_argument("--plot", default="out/gz.png", help="GZ plot (PNG); '' to skip")
    p.add_argument("--json", default=None, help="write the numbers to this JSON file")
    p.set_defaults(func=_cmd_hull)


def _cmd_hull(args: argparse.Namespace) -> int:
    import numpy as np

    from ship_gym.hull import equilibrium, hydrostatics, load_hull, righting_arm

    hull = load_hull(args.hull, **parse_overrides(args.set))
    p = hull.particulars
    hs = hydrostatics(hull)
    eq = equilibrium(hull)
    hs_eq = hydrostatics(hull, heave=eq.heave, trim=eq.trim)
    heels = np.arange(0.0, args.heel_max + 1e-9, args.heel_step)
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
    print(
        f"  max GZ {curve.max_gz:.4f} m at {curve.angle_max_gz_deg:.1f} deg; angle of vanishing "
        f"stability {curve.vanishing_angle_deg:.2f} deg"
    )
    if args.plot:
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
        Path(args.plot).parent.mkdir(parents=True, exist_ok=True)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")
    write_json(
        args.json,
        {
            "hull": hull.name,
            "displacement_t": hs.displacement / 1e3,
            "kb_m": hs.kb,
            "gmt_m": hs.gmt,
            "gml_m": hs.gml,
            "heel_deg": curve.heel_deg.tolist(),
            "gz_m": curve.gz.tolist(),
            "vanishing_angle_deg": curve.vanishing_angle_deg,
        },
    )
    return 0
