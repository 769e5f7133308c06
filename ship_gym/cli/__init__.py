"""``ship-gym`` command line: hulls, databases, simulation, manoeuvres, capsize studies, RL.

One module per command group, named after the commands the user types:

* :mod:`~ship_gym.cli.hull` — ``hull``;
* :mod:`~ship_gym.cli.hydro` — ``hydro``, ``kernels``;
* :mod:`~ship_gym.cli.simulate` — ``simulate``;
* :mod:`~ship_gym.cli.manoeuvre` — ``manoeuvre``;
* :mod:`~ship_gym.cli.capsize` — ``capsize-map``, ``parametric-roll``, ``dead-ship``;
* :mod:`~ship_gym.cli.safe_basin` — ``safe-basin``;
* :mod:`~ship_gym.cli.identify` — ``identify``;
* :mod:`~ship_gym.cli.agents` — ``train``, ``evaluate``;

and :mod:`~ship_gym.cli.common` for what they share (the ``--set KEY=VALUE`` overrides, JSON
output). Each module has ``add_commands(sub)``, which registers its commands on the subparsers.

Heavy modules (scipy solvers, capytaine, matplotlib, torch) are imported inside the commands so
that ``ship-gym --help`` stays instant.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

__all__ = ["build_parser", "main"]


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``ship-gym`` (one subparser per subcommand)."""
    from ship_gym.cli import (
        agents,
        capsize,
        hull,
        hydro,
        identify,
        manoeuvre,
        safe_basin,
        simulate,
    )

    parser = argparse.ArgumentParser(
        prog="ship-gym", description="Ship seakeeping models and Gymnasium environments."
    )
    sub = parser.add_subparsers(dest="command", required=True)
    for module in (hull, hydro, simulate, manoeuvre, capsize, safe_basin, identify, agents):
        module.add_commands(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``ship-gym`` console script.

    User errors (``ValueError``, ``FileNotFoundError``, ``RuntimeError``) print
    ``ship-gym COMMAND: error: …`` on stderr, without a traceback, and return 2.
    """
    args = build_parser().parse_args(argv)
    try:
        return int(args.func(args))
    except (ValueError, FileNotFoundError, RuntimeError) as exc:
        print(f"ship-gym {args.command}: error: {exc}", file=sys.stderr)
        return 2
