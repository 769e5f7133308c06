"""Build the bundled hydrodynamic database of a library hull (ship_gym/data/<hull>/).

The file is ``ship_gym/data/<hull>/<hull>_hydro.nc``.

For any hull of :data:`ship_gym.hull.library.HULLS` (``s175`` rebuilds the S175 file, whose
attributes still name its former script ``build_s175_database.py``). The grid of the bundled
databases: 40 finite frequencies up to the highest frequency the default
mesh resolves, plus ω = 0 and ω = ∞, and headings 0°–180° every 15° (the rest of the circle
follows from port/starboard symmetry, :func:`ship_gym.hydro.mirror_headings`). Provenance goes
into the file's attributes (capytaine version, mesh, grid, loading condition, build time, this
script).

Usage::

    python scripts/build_hull_database.py HULL [--output PATH] [--n-omega 40]
        [--heading-step 15] [--json PATH]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from ship_gym.hull import hydrostatics, load_hull
from ship_gym.hull.library import HULLS
from ship_gym.hydro import compute_hull_database, save_database, validate_database
from ship_gym.hydro.database import bundled_database_path
from ship_gym.io_utils import atomic_write_text


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("hull", choices=sorted(HULLS), help="library hull name")
    parser.add_argument("--output", default=None, help="default: the bundled file")
    parser.add_argument("--n-omega", type=int, default=40)
    parser.add_argument("--heading-step", type=float, default=15.0, help="[deg]")
    parser.add_argument("--json", default=None, help="write timing and checks here")
    args = parser.parse_args(argv)

    name = args.hull
    hull = load_hull(name)
    output = Path(args.output) if args.output else bundled_database_path(name)
    headings = np.radians(np.arange(0.0, 180.0 + 1e-9, args.heading_step))
    start = time.perf_counter()
    ds = compute_hull_database(
        hull,
        n_omega=args.n_omega,
        wave_directions=headings,
        hydrostatic_stiffness=hydrostatics(hull).stiffness,
    )
    elapsed = time.perf_counter() - start
    ds.attrs["built_by"] = f"scripts/build_hull_database.py {name}"
    ds.attrs["build_seconds"] = float(elapsed)
    ds.attrs["hull_builder"] = f"ship_gym.hull.load_hull({name!r}) (default resolution)"
    ds.attrs["hydrostatic_stiffness_source"] = (
        "ship_gym.hull.hydrostatics (pressure integration on the closed hull mesh)"
    )
    report = validate_database(ds)
    output.parent.mkdir(parents=True, exist_ok=True)
    save_database(ds, output)
    print(
        f"{name} database: {ds.sizes['omega']} frequencies (incl. 0 and inf), "
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
