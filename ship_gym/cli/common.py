"""Helpers shared by the ``ship-gym`` command modules (:mod:`ship_gym.cli`).

The one ``--set KEY=VALUE …`` option (:func:`add_overrides_argument`, read back with
:func:`parse_overrides`) of every command that takes builder or env keyword arguments, and the
JSON writer of ``--json``. Kept free of heavy imports: every command module imports it at parse
time.
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

__all__ = ["add_overrides_argument", "parse_overrides", "write_json"]


def parse_overrides(items: Sequence[str]) -> dict[str, Any]:
    """``key=value`` pairs → keyword arguments (values parsed as JSON when possible, else str).

    Raises
    ------
    SystemExit
        An item without ``=``.
    """
    out: dict[str, Any] = {}
    for item in items:
        if "=" not in item:
            raise SystemExit(f"error: override {item!r} must look like key=value")
        key, value = item.split("=", 1)
        try:
            out[key] = json.loads(value)
        except json.JSONDecodeError:
            out[key] = value
    return out


def add_overrides_argument(parser: argparse.ArgumentParser, help: str) -> None:
    """Add the ``--set KEY=VALUE …`` option (read with :func:`parse_overrides`)."""
    parser.add_argument("--set", nargs="*", default=[], metavar="KEY=VALUE", help=help)


def write_json(path: str | Path | None, payload: Any) -> None:
    """Write ``payload`` as indented JSON atomically (NumPy scalars as floats) and say so;
    nothing when ``path`` is None or empty."""
    if not path:
        return
    from ship_gym.io_utils import atomic_write_text

    atomic_write_text(Path(path), json.dumps(payload, indent=2, default=float))
    print(f"wrote {path}")
