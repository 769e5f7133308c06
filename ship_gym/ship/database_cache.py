"""The BEM database of a ship, built once and cached by a content hash.

A ship whose file names no database gets one computed with capytaine from its hull
(:func:`ship_gym.hydro.bem.compute_hull_database`), validated, and stored under
``<cache>/databases/<name>-<key>.nc``. The key is the SHA-256 of everything the radiation and
diffraction solution depends on: the immersed mesh at the design waterline (vertices and
faces), ρ, g, the frequency grid, the wave headings, the lid and symmetry settings, the versions
of capytaine and of the database format. The loading condition is *not* in the key: radiation
and diffraction are properties of the wetted surface, and every force the engine takes from a
database is one of them (hydrostatics and inertia come from the hull itself), so the loadings
of one hull share its database; the stored ``hydrostatic_stiffness`` and ``inertia_matrix``
are those of the loading the database was first built for.

The cache folder is ``$SHIP_GYM_CACHE`` if set, else ``$XDG_CACHE_HOME/ship_gym``, else
``~/.cache/ship_gym``. Builds are safe against concurrency: a build holds an exclusive file
lock on its key (:mod:`filelock`), so two processes asking for one database build it once (the
second waits and reads the first's file), and the database file appears atomically. A build
keeps every solved frequency under ``<cache>/partial/<key>/`` until the database is written, so
a killed build resumes where it stopped; a database that fails validation is kept as
``…rejected.nc`` beside the cache entry and reported.
"""

from __future__ import annotations

import hashlib
import inspect
import os
import shutil
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from ship_gym.hull.hull import Hull
    from ship_gym.ship.description import ShipDescription

__all__ = ["build_database", "cache_dir", "cache_path", "cached_database", "database_key",
           "frequency_grid"]  # fmt: skip

LOCK_TIMEOUT_S = 6 * 3600.0
"""Longest wait [s] for another process's build of the same database."""


def cache_dir() -> Path:
    """The cache folder (module docstring)."""
    env = os.environ.get("SHIP_GYM_CACHE")
    if env:
        return Path(env).expanduser()
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg).expanduser() if xdg else Path.home() / ".cache"
    return base / "ship_gym"


def frequency_grid(hull: Hull, desc: ShipDescription) -> np.ndarray:
    """The finite frequencies [rad/s] of the ship's BEM grid (``[hydrodynamics]`` settings)."""
    from ship_gym.hydro.bem import default_omega_grid

    spec = desc.hydrodynamics
    return default_omega_grid(
        hull.immersed_mesh, n_omega=spec.n_omega, omega_max=spec.omega_max_rad_s, g=hull.g
    )


def database_key(hull: Hull, desc: ShipDescription) -> str:
    """SHA-256 (hex) of what the ship's BEM solution depends on (module docstring)."""
    import capytaine

    from ship_gym.hydro.database import FORMAT_VERSION

    mesh = hull.immersed_mesh
    h = hashlib.sha256()
    h.update(np.ascontiguousarray(np.round(mesh.vertices, 9), dtype="<f8").tobytes())
    h.update(np.ascontiguousarray(mesh.faces, dtype="<i8").tobytes())
    h.update(np.array([hull.rho, hull.g], dtype="<f8").tobytes())
    h.update(np.ascontiguousarray(frequency_grid(hull, desc), dtype="<f8").tobytes())
    h.update(np.array(desc.hydrodynamics.headings_deg, dtype="<f8").tobytes())
    h.update(f"lid=True;symmetry=auto;capytaine={capytaine.__version__};"
             f"format={FORMAT_VERSION}".encode())  # fmt: skip
    return h.hexdigest()


def cache_path(hull: Hull, desc: ShipDescription) -> Path:
    """Where the ship's database is (or will be) cached."""
    return cache_dir() / "databases" / f"{desc.name}-{database_key(hull, desc)[:20]}.nc"


def cached_database(
    hull: Hull, desc: ShipDescription, *, build: bool = True, progress: bool = True,
    n_jobs: int = 1,
) -> Path:  # fmt: skip
    """Path of the ship's cached database, built first if it is not there.

    Parameters
    ----------
    hull : Hull
        The ship's hull (its immersed mesh at the design waterline is solved).
    desc : ShipDescription
        The ship (name, ``[hydrodynamics]`` settings).
    build : bool
        Build a missing database; else raise :class:`FileNotFoundError`.
    progress : bool
        Progress bar over the frequencies.
    n_jobs : int
        Parallel BEM processes.
    """
    path = cache_path(hull, desc)
    if path.is_file():
        return path
    if not build:
        raise FileNotFoundError(
            f"ship {desc.name!r} has no database yet (expected {str(path)!r}); build it with "
            f"`ship-gym ship build {desc.source or desc.name}`"
        )
    return build_database(hull, desc, progress=progress, n_jobs=n_jobs)


def build_database(
    hull: Hull, desc: ShipDescription, *, progress: bool = True, n_jobs: int = 1,
    force: bool = False,
) -> Path:  # fmt: skip
    """Build, validate and cache the ship's database under an exclusive lock; its path.

    Another process's build of the same key is waited for (and its file used). ``force``
    rebuilds an existing entry. A database that fails validation is written to
    ``<entry>.rejected.nc`` and :class:`ship_gym.hydro.checks.DatabaseError` raised naming it.
    """
    from filelock import FileLock

    from ship_gym.hydro.bem import compute_hull_database
    from ship_gym.hydro.checks import DatabaseError, validate_database
    from ship_gym.hydro.database import save_database, symmetrise

    path = cache_path(hull, desc)
    path.parent.mkdir(parents=True, exist_ok=True)
    key = database_key(hull, desc)
    with FileLock(str(path) + ".lock", timeout=LOCK_TIMEOUT_S):
        if path.is_file() and not force:
            return path  # built by another process while this one waited
        partial = cache_dir() / "partial" / key
        kwargs: dict[str, Any] = {"progress": progress, "n_jobs": n_jobs, "name": desc.name}
        if "checkpoint" in inspect.signature(compute_hull_database).parameters:
            partial.mkdir(parents=True, exist_ok=True)
            kwargs["checkpoint"] = partial
        ds = compute_hull_database(
            hull,
            omega=frequency_grid(hull, desc),
            wave_directions=np.radians(desc.hydrodynamics.headings_deg),
            **kwargs,
        )
        ds.attrs["ship"] = desc.name
        ds.attrs["ship_file"] = str(desc.source or "")
        ds.attrs["cache_key"] = key
        try:
            ds = symmetrise(ds)
        except ValueError:  # not port/starboard symmetric: stored as solved
            pass
        try:
            validate_database(ds)
        except DatabaseError as exc:
            rejected = path.with_suffix(".rejected.nc")
            save_database(ds, rejected)
            raise DatabaseError(
                f"the database of ship {desc.name!r} failed validation; it was kept as "
                f"{str(rejected)!r}. {exc}"
            ) from None
        save_database(ds, path)
        shutil.rmtree(partial, ignore_errors=True)
    return path
