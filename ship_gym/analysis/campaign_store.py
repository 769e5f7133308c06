"""The results store of a capsize campaign: a folder of Parquet shards, one per finished task.

Layout::

    STORE/
        campaign.toml              copy of the campaign description last run into the store
        part-<task_id>.parquet     one shard per finished task (the seeds of one batch)

A shard is written whole to a temporary file in the same folder (``.part-….tmp``, flushed to
disk) and moved into place with ``os.replace`` (:func:`ship_gym.io_utils.atomic_write`): a shard
either exists completely or not at all, so a killed campaign loses at most the tasks that were
running. The shards share one schema (:data:`SCHEMA`): every cell's inputs (what its
``cell_id`` hashes, :mod:`ship_gym.analysis.campaign`), its outcome and its run cost. Reading
needs only pyarrow (no pandas): :func:`read_store` returns plain dicts.

pyarrow is an optional dependency (``pip install 'ship_gym[distributed]'``); without it the store
raises an ImportError saying so.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

__all__ = ["COLUMNS", "OUTPUT_COLUMNS", "read_store", "shard_path", "store_cell_ids", "write_shard"]

COLUMNS: tuple[tuple[str, str], ...] = (
    # identity
    ("cell_id", "string"),
    ("task_id", "string"),
    # inputs (what the cell id hashes, as readable columns)
    ("ship", "string"),
    ("ship_digest", "string"),
    ("loading", "string"),
    ("sea", "string"),
    ("sea_kind", "string"),
    ("sea_height_m", "float64"),
    ("sea_wavelength_m", "float64"),
    ("sea_period_s", "float64"),
    ("sea_gamma", "float64"),
    ("sea_spreading_s", "float64"),
    ("heading_deg", "float64"),
    ("speed_kind", "string"),
    ("speed_value", "float64"),
    ("seed", "int64"),
    ("duration_s", "float64"),
    ("dt_s", "float64"),
    ("integrator", "string"),
    ("radiation", "string"),
    ("controller", "string"),
    ("capsize_criterion", "string"),
    # outcome
    ("capsize_angle_deg", "float64"),
    ("capsized", "bool"),
    ("reason", "string"),
    ("time_to_capsize_s", "float64"),
    ("max_abs_roll_deg", "float64"),
    ("rms_roll_deg", "float64"),
    ("max_abs_pitch_deg", "float64"),
    ("max_heading_deviation_deg", "float64"),
    ("mean_speed_mps", "float64"),
    ("simulated_time_s", "float64"),
    ("speed_mps", "float64"),
    # run cost and provenance
    ("cpu_s", "float64"),
    ("wall_s", "float64"),
    ("engine", "string"),
    ("batch_size", "int64"),
    ("host", "string"),
    ("ship_gym_version", "string"),
)
"""Columns of every shard: (name, Arrow type). ``loading`` and ``sea`` are canonical JSON /
labels; ``time_to_capsize_s``, ``sea_wavelength_m``/``sea_period_s``, ``sea_gamma`` and
``sea_spreading_s`` (long-crested) may be null."""

COST_COLUMNS = ("cpu_s", "wall_s", "engine", "batch_size", "host", "ship_gym_version", "task_id")
"""Columns that describe how a cell was run, not what it gave (they differ between a serial and a
parallel run of the same campaign)."""

OUTPUT_COLUMNS = tuple(name for name, _ in COLUMNS if name not in COST_COLUMNS)
"""Every input and outcome column: bit-identical however the campaign was executed."""


def _pyarrow() -> Any:
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        raise ImportError(
            "the campaign results store needs pyarrow (Parquet); install it with "
            "pip install 'ship_gym[distributed]' (or pip install pyarrow)"
        ) from None
    return pa, pq


def _schema(pa: Any) -> Any:
    types = {
        "string": pa.string(),
        "float64": pa.float64(),
        "int64": pa.int64(),
        "bool": pa.bool_(),
    }
    return pa.schema([(name, types[kind]) for name, kind in COLUMNS])


def shard_path(store: str | Path, task_id: str) -> Path:
    """Path of the shard of a task: ``STORE/part-<task_id>.parquet``."""
    return Path(store) / f"part-{task_id}.parquet"


def write_shard(store: str | Path, task_id: str, records: Sequence[dict]) -> Path:
    """Write one task's records as a Parquet shard, atomically (temp file + ``os.replace``).

    Parameters
    ----------
    store : str or Path
        Store folder (created if missing).
    task_id : str
        The task's id (names the shard).
    records : sequence of dict
        One dict per cell with every column of :data:`COLUMNS`.

    Raises
    ------
    ValueError
        If a record lacks a column or has one not in the schema.
    """
    from ship_gym.io_utils import atomic_write

    pa, pq = _pyarrow()
    names = [name for name, _ in COLUMNS]
    for r in records:
        missing = [n for n in names if n not in r]
        extra = [k for k in r if k not in names]
        if missing or extra:
            raise ValueError(
                f"record of cell {r.get('cell_id')!r}: missing columns {missing}, unknown {extra}"
            )
    table = pa.Table.from_pylist([dict(r) for r in records], schema=_schema(pa))
    path = shard_path(store, task_id)
    return atomic_write(path, lambda p: pq.write_table(table, p))


def _shards(store: Path) -> list[Path]:
    return sorted(store.glob("part-*.parquet"))


def read_store(store: str | Path) -> list[dict]:
    """Every record of a store (one dict per cell, columns of :data:`COLUMNS`).

    A missing folder is an empty store. A cell found in two shards (a task re-run after its
    shard was written but before it was seen, which does not happen in one store, or shards
    copied in from elsewhere) is kept once: the first by shard name.

    Raises
    ------
    ValueError
        If a shard cannot be read as Parquet (names it).
    """
    pa, pq = _pyarrow()
    store = Path(store)
    if not store.is_dir():
        return []
    seen: set[str] = set()
    out: list[dict] = []
    for shard in _shards(store):
        try:
            table = pq.read_table(shard)
        except (OSError, pa.ArrowException) as exc:
            raise ValueError(
                f"{shard}: not a readable Parquet shard ({exc}); remove it to re-run its task"
            ) from None
        for row in table.to_pylist():
            for name, _ in COLUMNS:  # a column added since the shard was written: null
                row.setdefault(name, None)
            if row["cell_id"] not in seen:
                seen.add(row["cell_id"])
                out.append(row)
    return out


def store_cell_ids(store: str | Path) -> set[str]:
    """The cell ids already in a store (reads only that column)."""
    pa, pq = _pyarrow()
    store = Path(store)
    if not store.is_dir():
        return set()
    ids: set[str] = set()
    for shard in _shards(store):
        try:
            ids.update(pq.read_table(shard, columns=["cell_id"]).column(0).to_pylist())
        except (OSError, pa.ArrowException) as exc:
            raise ValueError(
                f"{shard}: not a readable Parquet shard ({exc}); remove it to re-run its task"
            ) from None
    return ids


def host_name() -> str:
    """This machine's name (the ``host`` column)."""
    return os.uname().nodename if hasattr(os, "uname") else "unknown"
