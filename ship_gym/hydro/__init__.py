"""Hydrodynamic database (second pipeline stage): BEM data, checks, retardation functions.

capytaine is imported only by :mod:`ship_gym.hydro.bem`, and only inside its functions; this
package's import loads neither capytaine nor the BEM adapter (``compute_database`` and
``compute_hull_database`` are resolved lazily).
"""

from typing import Any

from ship_gym.hydro import frames
from ship_gym.hydro.checks import DatabaseError, validate_database
from ship_gym.hydro.database import (
    HydroArrays,
    as_arrays,
    load_database,
    mirror_headings,
    open_database,
    save_database,
    split_frequencies,
    symmetrise,
)
from ship_gym.hydro.wamit import read_wamit

__all__ = [
    "DatabaseError",
    "HydroArrays",
    "as_arrays",
    "compute_database",
    "compute_hull_database",
    "frames",
    "load_database",
    "mirror_headings",
    "open_database",
    "read_wamit",
    "save_database",
    "split_frequencies",
    "symmetrise",
    "validate_database",
]


def __getattr__(name: str) -> Any:
    if name in ("compute_database", "compute_hull_database"):
        from ship_gym.hydro import bem

        return getattr(bem, name)
    raise AttributeError(f"module 'ship_gym.hydro' has no attribute {name!r}")
