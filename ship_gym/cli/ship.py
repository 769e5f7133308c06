"""``ship-gym ship list|check|build``: ship files, their estimates and their cached database."""

from __future__ import annotations

import argparse
from typing import Any

from ship_gym.cli.common import (
    CLIError,
    add_ship_argument,
    bounded_float,
    n_jobs,
    positive_float,
    prepare_output,
    prepare_output_dir,
    write_json,
)


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``ship`` (with its ``list``, ``check`` and ``build`` actions)."""
    p = sub.add_parser("ship", help="ship files: list, check (hydrostatics, estimates), build")
    actions = p.add_subparsers(dest="action", required=True)
    actions.add_parser("list", help="the bundled ships").set_defaults(func=_cmd_list)

    c = actions.add_parser(
        "check",
        help="read a ship file: particulars, loading, hydrostatics, equilibrium, GZ, resistance, "
        "propeller, manoeuvring and appendage estimates, database status",
    )
    add_ship_argument(c, positional=True)
    c.add_argument(
        "--heel-max", type=bounded_float(0.0, 180.0, low_open=True), default=90.0,
        help="largest heel of the GZ curve [deg], in (0, 180]",
    )  # fmt: skip
    c.add_argument("--heel-step", type=positive_float, default=5.0, help="heel step [deg]")
    c.add_argument("--plot", default="out/ship_gz.png", help="GZ plot (PNG); '' to skip")
    c.add_argument("--json", default=None, help="write the numbers to this JSON file")
    c.set_defaults(func=_cmd_check)

    b = actions.add_parser(
        "build", help="build the ship's BEM database (capytaine) into the cache, once"
    )
    add_ship_argument(b, positional=True)
    b.add_argument("--n-jobs", type=n_jobs, default=1, help="parallel BEM processes")
    b.add_argument("--force", action="store_true", help="rebuild a cached database")
    b.set_defaults(func=_cmd_build)


def _cmd_list(args: argparse.Namespace) -> int:
    from ship_gym.ship import bundled_ships, load_ship

    for name in bundled_ships():
        ship = load_ship(name)
        p = ship.hull.particulars
        print(
            f"{name:12s} Lpp {p.lpp:7.2f} m  B {p.beam:6.2f} m  T {p.draught:5.2f} m  "
            f"{ship.hull.mass.mass / 1e3:9.1f} t  {ship.description.description}"
        )
    return 0


def _cmd_check(args: argparse.Namespace) -> int:
    from ship_gym.cli.hull import check_heel_arguments, report_hull
    from ship_gym.ship import load_ship

    check_heel_arguments(args)
    prepare_output(args.plot, "--plot", suffixes=(".png", ".pdf", ".svg"))
    prepare_output(args.json, "--json")
    ship = load_ship(args.hull)
    desc = ship.description
    print(f"ship {ship.name}: {desc.description or '(no description)'}")
    if desc.source is not None:
        print(f"  file {desc.source}")
    print(f"  hull from {desc.hull.kind}: {_hull_source(ship)}")
    payload: dict[str, Any] = {"ship": ship.name}
    payload["hydrostatics"] = report_hull(
        ship.hull, heel_max=args.heel_max, heel_step=args.heel_step, plot=args.plot
    )
    payload["speed"] = _report_speed(ship)
    payload["appendages"] = _report_appendages(ship)
    payload["manoeuvring"] = _report_manoeuvring(ship)
    payload["database"] = _report_database(ship)
    write_json(args.json, payload)
    return 0


def _hull_source(ship: Any) -> str:
    g = ship.description.hull
    if g.kind == "library":
        return f"library hull {g.library!r} {dict(g.options) or ''}".rstrip()
    if g.kind == "offsets":
        return f"offsets {g.offsets} {dict(g.options) or ''}".rstrip()
    return f"mesh {g.mesh} (frame {g.frame}, scale {g.scale:g}, translate {list(g.translate)} m)"


def _report_speed(ship: Any) -> dict[str, Any]:
    """Service speed, calm-water resistance and the propeller designed for it."""
    import math

    hull = ship.hull
    u = ship.service_speed
    fn = u / math.sqrt(hull.g * hull.particulars.lpp)
    lo, hi = ship.speed_range
    print(
        f"  service speed {u:.3f} m/s ({u / 0.514444:.1f} kn, Fn {fn:.3f}); range {lo:g} … "
        f"{hi:g} m/s"
    )
    try:
        prop = ship.propeller()
    except ValueError as err:  # a form outside the regressions (a box barge: C_B = 1)
        print(
            f"  calm-water resistance and propeller: not estimated — {err} (Holtrop–Mennen and "
            "the B-series design are regressions for ship forms); what needs propulsion "
            "(manoeuvre, the ship environments) is not available for this form"
        )
        return {
            "service_speed_mps": u,
            "froude_number": fn,
            "resistance_N": None,
            "propeller": None,
            "not_estimated": str(err),
        }
    resistance = prop.resistance
    r_t = float(resistance.resistance(u)) if resistance is not None else float("nan")
    design = getattr(prop, "design", None)
    n = float(prop.shaft_speed_for(u))
    print(
        f"  calm-water resistance (Holtrop–Mennen) R_T {r_t / 1e3:.1f} kN, effective power "
        f"{r_t * u / 1e6:.2f} MW"
    )
    series = prop.open_water
    print(
        f"  propeller (B-series {series}): D {prop.diameter:.3f} m; self-propulsion "
        f"{60.0 * n:.1f} rpm at the service speed"
    )
    return {
        "service_speed_mps": u,
        "froude_number": fn,
        "resistance_N": r_t,
        "propeller": {
            "diameter_m": float(prop.diameter),
            "blades": int(series.z_blades),
            "blade_area_ratio": float(series.ae_a0),
            "pitch_ratio": float(series.p_d),
            "rpm": 60.0 * n,
            "design": str(design) if design is not None else None,
        },
    }


def _report_appendages(ship: Any) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for group, kwargs in (
        ("rudder", ship.rudder_arguments),
        ("fins", ship.fins_arguments),
        ("t_foil", ship.t_foil_arguments),
    ):
        if kwargs is None:
            print(f"  {group}: not fitted")
            out[group] = None
            continue
        items = []
        for key, value in kwargs.items():
            mark = "" if ship.provenance.get(f"{group}.{key}") == "given" else "*"
            items.append(f"{key} {_fmt(value)}{mark}")
        print(f"  {group}: " + ", ".join(items))
        out[group] = {k: _plain(v) for k, v in kwargs.items()}
    print("  (* estimated from the main particulars: ship_gym.ship.appendages)")
    out["provenance"] = dict(ship.provenance)
    return out


def _report_manoeuvring(ship: Any) -> dict[str, Any]:
    """Clarke's linear derivatives of the hull (non-dimensional, L and U)."""
    from ship_gym.forces.manoeuvring import HullManoeuvring

    d = HullManoeuvring.from_hull(ship.hull).derivatives
    values = {k: float(getattr(d, k)) for k in ("Y_v", "Y_r", "N_v", "N_r")}
    if values:
        print(
            "  manoeuvring (Clarke 1983, non-dimensional): "
            + ", ".join(f"{k} {v:+.4g}" for k, v in values.items())
        )
    return values


def _report_database(ship: Any) -> dict[str, Any]:
    from pathlib import Path

    source = ship.database_source()
    given = ship.description.hydrodynamics.database is not None
    exists = given or Path(source).is_file()
    state = "given" if given else "cached" if exists else "not built yet (ship-gym ship build)"
    print(f"  hydrodynamic database: {source} ({state})")
    return {"source": source, "state": state}


def _fmt(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    if isinstance(value, tuple):
        return "(" + ", ".join(_fmt(v) for v in value) + ")"
    return str(value)


def _plain(value: Any) -> Any:
    return list(value) if isinstance(value, tuple) else value


def _cmd_build(args: argparse.Namespace) -> int:
    import time

    from ship_gym.hydro.checks import validate_database
    from ship_gym.hydro.database import load_database
    from ship_gym.ship import load_ship
    from ship_gym.ship.database_cache import build_database, cache_dir, cache_path

    ship = load_ship(args.hull)
    if ship.description.hydrodynamics.database is not None:
        raise CLIError(
            f"ship {ship.name!r} names its database ([hydrodynamics] database = "
            f"{ship.description.hydrodynamics.database!r}); remove that line to build one "
            "from the hull"
        )
    prepare_output_dir(cache_dir() / "databases", "the cache folder ($SHIP_GYM_CACHE)")
    path = cache_path(ship.hull, ship.description)
    if path.is_file() and not args.force:
        print(f"{ship.name}: database already built: {path}")
        return 0
    start = time.perf_counter()
    path = build_database(
        ship.hull, ship.description, progress=True, n_jobs=args.n_jobs, force=args.force
    )
    elapsed = time.perf_counter() - start
    ds = load_database(path)
    report = validate_database(ds)
    print(
        f"{ship.name}: {ds.attrs.get('n_panels')} panels, {ds.sizes['omega']} frequencies, "
        f"{ds.sizes['wave_direction']} headings in {elapsed:.1f} s → {path}"
    )
    for key, value in report.items():
        print(f"  {key}: {value}")
    return 0
