"""Per-process caches of what a ship task builds once: the batch simulator of a setup
(deep-copied for each task instance) and the designed propeller of a hull.
"""

from __future__ import annotations

import copy
from functools import lru_cache
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ship_gym.engine.batch import BatchSimulator
    from ship_gym.engine.ship import ShipSetup


_PROTOTYPES: dict[tuple[str, int, int], BatchSimulator] = {}


def prototype_simulator(setup: ShipSetup, num_ships: int, n_components: int) -> BatchSimulator:
    """A fresh BatchSimulator of ``num_ships`` calm-water ships of ``setup`` (cached build).

    The first call for a (setup, N, component count) builds it
    (:func:`ship_gym.engine.batch.build_batch_simulator`: hull, database, state-space fit,
    Nomoto identification of the autopilot…, 0.2–1 s); later calls return a deep copy of the
    cached one (milliseconds).

    Parameters
    ----------
    setup : ShipSetup
        Ship, models and numerics.
    num_ships : int
        Batch size N.
    n_components : int
        Padded wave-component count (room for every sea given at reset).
    """
    from ship_gym.engine.batch import build_batch_simulator

    key = (repr(setup), int(num_ships), int(n_components))
    proto = _PROTOTYPES.get(key)
    if proto is None:
        proto = build_batch_simulator(
            setup, [None] * int(num_ships), max_components=int(n_components)
        )
        _PROTOTYPES[key] = proto
    return copy.deepcopy(proto)


@lru_cache(maxsize=16)
def designed_propeller(hull_name: str, overrides: tuple) -> Any:
    """The propeller designed for a ship and overrides (cached per process)."""
    from ship_gym.ship import load_ship

    return load_ship(hull_name, **dict(overrides)).propeller()
