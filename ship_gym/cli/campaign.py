"""``ship-gym campaign run|report``: capsize-risk campaigns (:mod:`ship_gym.analysis.campaign`).

* ``campaign run FILE.toml``: run, resume or extend a campaign into its Parquet store (default
  ``<file stem>.campaign/`` next to the file), serially, on local worker processes or on Ray;
* ``campaign report FILE.toml|STORE``: per cell the capsize probability with its binomial
  confidence interval, the seeds needed for a target half-width, the Kaplan–Meier median time to
  capsize; optionally a polar plot and JSON (:mod:`ship_gym.analysis.capsize_statistics`).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ship_gym.cli.common import (
    CLIError,
    bounded_float,
    n_jobs,
    prepare_output,
    prepare_output_dir,
    write_json,
)

if TYPE_CHECKING:
    from ship_gym.analysis.campaign import CampaignSpec


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``campaign`` (with its ``run`` and ``report`` actions) on the parser."""
    p = sub.add_parser("campaign", help="capsize-risk campaigns from a TOML file: run, report")
    actions = p.add_subparsers(dest="action", required=True)
    r = actions.add_parser("run", help="run, resume or extend a campaign into its store")
    r.add_argument("file", metavar="FILE.toml", help="campaign description (TOML)")
    r.add_argument("--store", default=None, help="store folder (default: <FILE stem>.campaign/)")
    r.add_argument(
        "--executor",
        default="serial",
        choices=("serial", "processes", "ray"),
        help="where the tasks run: this process, local worker processes, or a Ray cluster",
    )
    r.add_argument("--workers", type=n_jobs, default=1, help="parallel workers")
    r.add_argument("--address", default=None, help="Ray cluster address (--executor ray)")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")
    r.add_argument(
        "--trust-policy",
        action="store_true",
        help="load a controller = 'policy:…' neither trained here nor shipped (loading a "
        "stable-baselines3 file runs code from it: only for files you trust; docs/security.md)",
    )
    r.set_defaults(func=cmd_campaign_run)

    q = actions.add_parser("report", help="capsize probabilities with confidence intervals")
    q.add_argument("source", metavar="FILE.toml|STORE", help="campaign file or store folder")
    q.add_argument("--store", default=None, help="store folder of FILE.toml (default as run)")
    q.add_argument("--plot", default="", help="polar capsize map with its CIs (PNG, PDF, SVG)")
    q.add_argument(
        "--survival",
        default="",
        help="Kaplan-Meier time-to-capsize curves of the cells that capsized (PNG, PDF, SVG)",
    )
    q.add_argument("--json", default=None, help="write the per-cell summary to this JSON file")
    q.add_argument(
        "--half-width",
        type=bounded_float(0.0, 0.5, low_open=True),
        default=0.1,
        help="target CI half-width for the seeds-needed column, in (0, 0.5]",
    )
    q.add_argument(
        "--confidence",
        type=bounded_float(0.5, 1.0, low_open=True),
        default=0.95,
        help="confidence level of the intervals, in (0.5, 1)",
    )
    q.add_argument(
        "--method", default="wilson", choices=("wilson", "clopper-pearson"), help="interval"
    )
    q.set_defaults(func=cmd_campaign_report)


def _default_store(file: Path) -> Path:
    return file.with_name(f"{file.stem}.campaign")


def _read(file: str) -> CampaignSpec:
    from ship_gym.analysis.campaign import CampaignError, read_campaign

    try:
        return read_campaign(file)
    except FileNotFoundError as exc:
        raise CLIError(f"FILE.toml: {exc}") from None
    except CampaignError as exc:
        raise CLIError(str(exc)) from None


def cmd_campaign_run(args: argparse.Namespace) -> int:
    """Run (or resume, or extend) a campaign and print what it did."""
    from ship_gym.analysis import campaign as cp

    spec = _read(args.file)
    store = Path(args.store) if args.store else _default_store(Path(args.file))
    if store.exists() and not store.is_dir():
        raise CLIError(f"--store: {str(store)!r} is a file; expected a folder")
    if args.executor == "serial" and args.workers != 1:
        raise CLIError(f"--workers {args.workers}: the serial executor has one worker")
    if args.address and args.executor != "ray":
        raise CLIError("--address is for --executor ray")
    try:
        from ship_gym.analysis.campaign_store import _pyarrow

        _pyarrow()
        if args.executor == "ray":
            import ray  # noqa: F401
    except ImportError as exc:
        raise CLIError(str(exc)) from None
    prepare_output_dir(store, "--store")
    n = len(cp.cells(spec))
    print(
        f"campaign {spec.name or args.file}: {n} cells ({len(spec.ships)} ships × "
        f"{len(spec.loadings)} loadings × {len(spec.seas)} seas × {len(spec.headings_deg)} "
        f"headings × {len(spec.speeds)} speeds × {spec.seeds} seeds) of {spec.duration_s:g} s "
        f"→ {store}"
    )
    try:
        result = cp.run_campaign(
            spec,
            store,
            executor=args.executor,
            workers=args.workers,
            address=args.address,
            progress=not args.no_progress,
            trust_policy=args.trust_policy,
        )
    except ImportError as exc:
        raise CLIError(str(exc)) from None
    print(
        f"ran {result.n_run} cells in {result.n_tasks} tasks ({n - result.n_run} already in "
        f"the store) in {result.wall_s:.1f} s wall"
    )
    return 0


def _fmt(x: float) -> str:
    return "     -" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:6.1f}"


def _stderr(message: str) -> None:
    print(f"ship-gym campaign: {message}", file=sys.stderr, flush=True)


def cmd_campaign_report(args: argparse.Namespace) -> int:
    """Print (and plot) the capsize probabilities of a campaign with their intervals."""
    from ship_gym.analysis import capsize_statistics as cs
    from ship_gym.analysis.campaign import campaign_records
    from ship_gym.analysis.campaign_store import read_store

    source = Path(args.source)
    prepare_output(args.plot, "--plot", suffixes=(".png", ".pdf", ".svg"))
    prepare_output(args.survival, "--survival", suffixes=(".png", ".pdf", ".svg"))
    prepare_output(args.json, "--json")
    try:
        if source.is_dir():
            if args.store:
                raise CLIError("--store is for a campaign FILE.toml, not a store folder")
            records, missing, title = read_store(source, report=_stderr), 0, str(source)
        else:
            spec = _read(args.source)
            store = Path(args.store) if args.store else _default_store(source)
            if not store.is_dir():
                raise CLIError(
                    f"no store {str(store)!r} for {args.source}; run "
                    f"`ship-gym campaign run {args.source}` first"
                )
            records, missing = campaign_records(spec, store, report=_stderr)
            title = spec.name or source.stem
    except (ImportError, ValueError) as exc:
        raise CLIError(str(exc)) from None
    if not records:
        raise CLIError(f"{args.source}: no finished cells to report")
    summary = cs.summarise_cells(
        records, confidence=args.confidence, method=args.method, half_width=args.half_width
    )
    pct = f"{100 * args.confidence:g}%"
    print(
        f"{title}: {len(records)} runs in {len(summary)} cells"
        + (f" ({missing} runs not finished)" if missing else "")
        + f"; {args.method} {pct} intervals; seeds for ±{args.half_width:g}"
    )
    print(
        " ship        loading            sea                           β [deg]  speed     n   k"
        f"    p̂    {pct} CI         seeds  t50 [s]"
    )
    for s in summary:
        g = s.group
        unit = "Fn" if g["speed_kind"] == "froude" else "m/s"
        print(
            f" {g['ship'][:11]:11s} {g['loading'][:18]:18s} {g['sea'][:29]:29s} "
            f"{g['heading_deg']:7.1f}  {g['speed_value']:5.2f} {unit:3s} {s.n:3d} {s.k:3d} "
            f"{s.p_hat:5.2f}  [{s.lower:.2f}, {s.upper:.2f}]  {s.seeds_needed:6d}  "
            f"{_fmt(s.median_time_to_capsize)}"
        )
    if args.plot:
        print(f"wrote {cs.plot_polar_capsize(summary, args.plot, title=title)}")
    if args.survival:
        print(f"wrote {cs.plot_survival(summary, args.survival, title=title)}")
    if args.json:
        write_json(
            args.json,
            {
                "source": str(source),
                "confidence": args.confidence,
                "method": args.method,
                "half_width": args.half_width,
                "missing_runs": missing,
                "cells": [s.to_dict() for s in summary],
            },
        )
    return 0
