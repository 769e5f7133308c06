"""Rebuild the bundled S175 hydrodynamic database ``ship_gym/data/s175/s175_hydro.nc``.

Provenance goes into the file's attributes (capytaine version, mesh, grid, loading condition,
build time, this script). The default grid is what ``ship_gym.hydro.load_database("s175")``
ships with: 40 finite frequencies up to the highest frequency the default S175 mesh resolves,
plus ω = 0 and ω = ∞, and headings 0°–180° every 15° (our convention; the rest of the circle
follows from port/starboard symmetry, :func:`ship_gym.hydro.mirror_headings`).

Usage::

    python scripts/build_s175_database.py [--output PATH] [--n-omega 40] [--heading-step 15]
        [--json PATH]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from ship_gym.hull import hydrostatics, load_hull
from ship_gym.hydro import compute_hull_database, save_database, validate_database
from ship_gym.hydro.database import bundled_database_path
from ship_gym.io_utils import atomic_write_text


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=None, help="default: the bundled file")
    parser.add_argument("--n-omega", type=int, default=40)
    parser.add_argument("--heading-step", type=float, default=15.0, help="[deg]")
    parser.add_argument("--json", default=None, help="write timing and checks here")
    args = parser.parse_args(argv)

    hull = load_hull("s175")
    output = Path(args.output) if args.output else bundled_database_path("s175")
    headings = np.radians(np.arange(0.0, 180.0 + 1e-9, args.heading_step))
    start = time.perf_counter()
    ds = compute_hull_database(
        hull,
        n_omega=args.n_omega,
        wave_directions=headings,
        hydrostatic_stiffness=hydrostatics(hull).stiffness,
    )
    elapsed = time.perf_counter() - start
    ds.attrs["built_by"] = "scripts/build_s175_database.py"
    ds.attrs["build_seconds"] = float(elapsed)
    ds.attrs["hull_builder"] = "ship_gym.hull.load_hull('s175') (default resolution)"
    ds.attrs["hydrostatic_stiffness_source"] = (
        "ship_gym.hull.hydrostatics (pressure integration on the closed hull mesh)"
    )
    report = validate_database(ds)
    save_database(ds, output)
    print(
        f"S175 database: {ds.sizes['omega']} frequencies (incl. 0 and inf), "
        f"{ds.sizes['wave_direction']} headings, {ds.attrs['n_panels']} panels; "
        f"BEM time {elapsed:.1f} s → {output} ({output.stat().st_size / 1e3:.0f} kB)"
    )
    for key, value in report.items():
        print(f"  {key}: {value}")
    if args.json:
        atomic_write_text(
            args.json,
            json.dumps(
                {"build_seconds": elapsed, "n_panels": int(ds.attrs["n_panels"]), "report": report},
                indent=2,
                default=str,
            ),
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
