"""``ship-gym`` command line: hulls, databases, simulation, manoeuvres, capsize studies, RL.

One module per command group, named after the commands the user types:

* :mod:`~ship_gym.cli.hull` — ``hull``;
* :mod:`~ship_gym.cli.hydro` — ``hydro``, ``kernels``;
* :mod:`~ship_gym.cli.simulate` — ``simulate``;
* :mod:`~ship_gym.cli.manoeuvre` — ``manoeuvre``;
* :mod:`~ship_gym.cli.capsize` — ``capsize-map``, ``parametric-roll``, ``dead-ship``;
* :mod:`~ship_gym.cli.campaign` — ``campaign`` (``run``, ``report``);
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
import signal
import sys
import threading
from collections.abc import Sequence
from typing import Any

__all__ = ["build_parser", "main"]


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``ship-gym`` (one subparser per subcommand)."""
    from ship_gym.cli import (
        agents,
        campaign,
        capsize,
        hull,
        hydro,
        identify,
        manoeuvre,
        safe_basin,
        ship,
        simulate,
    )

    parser = argparse.ArgumentParser(
        prog="ship-gym", description="Ship seakeeping models and Gymnasium environments."
    )
    parser.add_argument("--debug", action="store_true", help="show the full traceback of an error")
    sub = parser.add_subparsers(dest="command", required=True)
    for module in (
        ship,
        hull,
        hydro,
        simulate,
        manoeuvre,
        capsize,
        campaign,
        safe_basin,
        identify,
        agents,
    ):
        module.add_commands(sub)
    for command in sub.choices.values():  # also ``ship-gym CMD … --debug``
        command.add_argument(
            "--debug",
            action="store_true",
            default=argparse.SUPPRESS,
            help="show the full traceback of an error",
        )
    return parser


def _user_error_types() -> tuple[type[BaseException], ...]:
    from ship_gym.cli.common import CLIError

    types: list[type[BaseException]] = [
        CLIError,
        ValueError,
        OSError,
        LookupError,
        TypeError,
        ArithmeticError,
        RuntimeError,
    ]
    gym = sys.modules.get("gymnasium.error")
    if gym is not None:
        types.append(gym.Error)
    return tuple(types)


def _message(exc: BaseException) -> str:
    text = str(exc)
    if isinstance(exc, KeyError) and exc.args:
        text = f"unknown key {exc.args[0]!r}"
    if isinstance(exc, OSError) and exc.filename is not None and str(exc.filename) not in text:
        text = f"{text}: {exc.filename}"
    return text or type(exc).__name__


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``ship-gym`` console script; returns the exit status.

    * usage errors (argparse: a bad option value, a missing argument) print argparse's message
      and return 2;
    * user and runtime errors (a bad value found by a command, a missing or unwritable file, an
      unknown env id…) print ``ship-gym COMMAND: error: …`` on stderr and return 1;
    * anything else is a bug: a one-line message asking to rerun with ``--debug`` (exit 1).

    ``--debug`` (before or after the command) re-raises instead, with the traceback.
    """
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help (0) or a usage error (2)
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 2)
    debug = bool(getattr(args, "debug", False))
    previous = _install_sigterm_handler()
    try:
        return _run(args)
    except KeyboardInterrupt:
        if debug:
            raise
        print(f"ship-gym {args.command}: interrupted", file=sys.stderr)
        return 130
    except SystemExit as exc:  # a command's own exit (e.g. parse_overrides)
        if debug:
            raise
        if isinstance(exc.code, str):
            msg = exc.code.removeprefix("error: ")
            print(f"ship-gym {args.command}: error: {msg}", file=sys.stderr)
            return 2
        if isinstance(exc.code, int) and exc.code > 128:
            print(f"ship-gym {args.command}: terminated by a signal", file=sys.stderr)
        return 0 if exc.code is None else int(exc.code)
    except Exception as exc:
        if debug:
            raise
        if isinstance(exc, _user_error_types()):
            print(f"ship-gym {args.command}: error: {_message(exc)}", file=sys.stderr)
        else:
            print(
                f"ship-gym {args.command}: internal error (a bug, please report it): "
                f"{type(exc).__name__}: {exc}; rerun with --debug for the traceback",
                file=sys.stderr,
            )
        return 1
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _terminated(signum: int, frame: object) -> None:
    raise SystemExit(128 + signum)


def _install_sigterm_handler() -> Any:
    """SIGTERM → ``SystemExit(143)`` so that ``finally`` blocks run (temporary files removed,
    worker processes killed); returns the previous handler (None outside the main thread)."""
    if threading.current_thread() is not threading.main_thread():
        return None
    return signal.signal(signal.SIGTERM, _terminated)


def _run(args: argparse.Namespace) -> int:
    if int(getattr(args, "n_jobs", 1) or 1) == 1:
        return int(args.func(args))
    from ship_gym.cli.common import workers_die_with_parent

    with workers_die_with_parent():
        return int(args.func(args))
