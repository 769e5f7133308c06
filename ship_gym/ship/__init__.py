"""Ships: description files, hull and loading, appendage estimates and the cached BEM database.

``load_ship("s175")`` or ``load_ship("path/to/ship.toml")`` gives a :class:`Ship` (hull with its
loading condition, appendages, service speed, database); ``ship-gym ship check|build FILE`` are
the command-line side. The file format is documented in :mod:`ship_gym.ship.description`.
"""

from ship_gym.ship.description import (
    SCHEMA_VERSION,
    ShipDescription,
    ShipFileError,
    bundled_ship_path,
    bundled_ships,
    is_ship_file,
    read_ship,
)
from ship_gym.ship.model import (
    LOADING_OVERRIDES,
    DatabaseMismatchError,
    Ship,
    build_hull,
    check_database_matches,
    hull_of,
    load_ship,
)

__all__ = [
    "LOADING_OVERRIDES",
    "SCHEMA_VERSION",
    "DatabaseMismatchError",
    "Ship",
    "ShipDescription",
    "ShipFileError",
    "build_hull",
    "bundled_ship_path",
    "bundled_ships",
    "check_database_matches",
    "hull_of",
    "is_ship_file",
    "load_ship",
    "read_ship",
]
