"""The results store of a capsize campaign: a folder of Parquet shards, one per finished task.

Layout::

    STORE/
        campaign.toml              copy of the campaign description last run into the store
        part-<task_id>.parquet     one shard per finished task (the seeds of one batch)
        manifest.jsonl             what this store wrote: one JSON line per campaign run into it
                                   ({"campaign": digest, "name": …}) and per shard written
                                   ({"shard": file name, "sha256": …, "campaign": digest})

The manifest is how a store knows its own data: a shard it does not list (copied in from another
store) or whose SHA-256 differs from the one recorded (changed since) is ignored by every reader,
with a message naming the file, so its rows are neither counted in a report nor taken for cells
already run. A store written before the manifest existed has none: its shards are all read, and
the first shard written into it adopts them (lines with ``"adopted": true``). The campaign digest
is :func:`campaign_digest` of its cell ids.

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

import hashlib
import json
import os
import warnings
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

__all__ = [
    "COLUMNS",
    "MANIFEST",
    "OUTPUT_COLUMNS",
    "campaign_digest",
    "read_store",
    "record_campaign",
    "shard_path",
    "store_cell_ids",
    "write_shard",
]

MANIFEST = "manifest.jsonl"
"""File name of a store's manifest (module docstring)."""

REQUIRED_COLUMNS = (
    "cell_id",
    "ship",
    "loading",
    "sea",
    "heading_deg",
    "speed_kind",
    "speed_value",
    "seed",
    "capsized",
    "max_abs_roll_deg",
)
"""Columns no record of a shard may leave empty (a report groups and counts by them)."""

Report = Callable[[str], None]

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


def campaign_digest(cell_ids: Iterable[str]) -> str:
    """The digest a store's manifest knows a campaign by: SHA-256 of its sorted cell ids."""
    return hashlib.sha256("\n".join(sorted(cell_ids)).encode()).hexdigest()


def _sha256_file(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _append_manifest(store: Path, entries: Sequence[dict]) -> None:
    """Append lines to the manifest (one writer: the campaign driver), flushed to disk."""
    with open(store / MANIFEST, "a", encoding="utf-8") as fh:
        for entry in entries:
            fh.write(json.dumps(entry, sort_keys=True) + "\n")
        fh.flush()
        os.fsync(fh.fileno())


def _adopt_legacy_shards(store: Path) -> None:
    """A store without a manifest (an earlier version's): record its shards as they are."""
    if (store / MANIFEST).exists():
        return
    entries = [
        {"shard": shard.name, "sha256": _sha256_file(shard), "adopted": True}
        for shard in _shards(store)
    ]
    _append_manifest(store, entries)


def record_campaign(store: str | Path, digest: str, name: str = "") -> None:
    """Record in the store's manifest that a campaign (:func:`campaign_digest`) runs into it
    (creating the store; an earlier version's shards are adopted first)."""
    store = Path(store)
    store.mkdir(parents=True, exist_ok=True)
    _adopt_legacy_shards(store)
    _append_manifest(store, [{"campaign": digest, "name": name}])


def _manifest_shards(store: Path) -> dict[str, str] | None:
    """Shard name → recorded SHA-256 (the last line for a name wins); None without manifest."""
    path = store / MANIFEST
    if not path.is_file():
        return None
    known: dict[str, str] = {}
    for line in path.read_text(encoding="utf-8", errors="replace").splitlines():
        try:
            entry = json.loads(line)
        except json.JSONDecodeError:
            continue  # a line torn by a kill: its shard counts as unknown (and is re-run)
        if isinstance(entry, dict) and isinstance(entry.get("shard"), str):
            known[entry["shard"]] = str(entry.get("sha256", ""))
    return known


def _own_shards(store: Path, report: Report | None) -> list[tuple[Path, bytes]]:
    """The store's own shards (name, content): foreign or changed ones are left out, each with
    a message naming it."""
    known = _manifest_shards(store)
    tell = report if report is not None else _warn
    out = []
    for shard in _shards(store):
        data = shard.read_bytes()
        if known is not None:
            if shard.name not in known:
                tell(
                    f"{shard}: not in the store's {MANIFEST} (a shard of another campaign or "
                    "store copied in?); ignored"
                )
                continue
            digest = hashlib.sha256(data).hexdigest()
            if digest != known[shard.name]:
                tell(
                    f"{shard}: its SHA-256 {digest[:16]}… differs from the one {MANIFEST} "
                    "recorded when the store wrote it (changed since); ignored, remove it to "
                    "re-run its task"
                )
                continue
        out.append((shard, data))
    return out


def _warn(message: str) -> None:
    warnings.warn(message, stacklevel=3)


def write_shard(
    store: str | Path, task_id: str, records: Sequence[dict], *, campaign: str = ""
) -> Path:
    """Write one task's records as a Parquet shard, atomically (temp file + ``os.replace``).

    Parameters
    ----------
    store : str or Path
        Store folder (created if missing).
    task_id : str
        The task's id (names the shard).
    records : sequence of dict
        One dict per cell with every column of :data:`COLUMNS`.
    campaign : str
        The campaign's digest (:func:`campaign_digest`), recorded in the manifest with the
        shard's SHA-256.

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
    Path(store).mkdir(parents=True, exist_ok=True)
    _adopt_legacy_shards(Path(store))
    atomic_write(path, lambda p: pq.write_table(table, p))
    entry = {"shard": path.name, "sha256": _sha256_file(path), "campaign": campaign}
    _append_manifest(Path(store), [entry])
    return path


def _shards(store: Path) -> list[Path]:
    return sorted(store.glob("part-*.parquet"))


def _read_shard(shard: Path, data: bytes, columns: Sequence[str] | None = None) -> Any:
    pa, pq = _pyarrow()
    try:
        return pq.read_table(pa.BufferReader(data), columns=columns)
    except (OSError, pa.ArrowException) as exc:
        raise ValueError(
            f"{shard}: not a readable Parquet shard ({exc}); remove it to re-run its task"
        ) from None


def read_store(store: str | Path, *, report: Report | None = None) -> list[dict]:
    """Every record of a store (one dict per cell, columns of :data:`COLUMNS`).

    A missing folder is an empty store. Shards the manifest does not know, or that changed
    since the store wrote them, are ignored, each named to ``report`` (default: a warning). A
    cell found in two shards is kept once: the first by shard name.

    Raises
    ------
    ValueError
        If a shard cannot be read as Parquet, or leaves a :data:`REQUIRED_COLUMNS` entry empty
        (names it).
    """
    _pyarrow()  # a missing pyarrow is said first, whatever the folder
    store = Path(store)
    if not store.is_dir():
        return []
    seen: set[str] = set()
    out: list[dict] = []
    for shard, data in _own_shards(store, report):
        table = _read_shard(shard, data)
        for row in table.to_pylist():
            for name, _ in COLUMNS:  # a column added since the shard was written: null
                row.setdefault(name, None)
            empty = [name for name in REQUIRED_COLUMNS if row[name] is None]
            if empty:
                raise ValueError(
                    f"{shard}: a record (cell {row['cell_id']!r}) has no {', '.join(empty)}; "
                    "expected a shard written by `ship-gym campaign run` (remove it to re-run "
                    "its task)"
                )
            if row["cell_id"] not in seen:
                seen.add(row["cell_id"])
                out.append(row)
    return out


def store_cell_ids(store: str | Path, *, report: Report | None = None) -> set[str]:
    """The cell ids already in a store (its own shards: :func:`read_store`)."""
    _pyarrow()
    store = Path(store)
    if not store.is_dir():
        return set()
    ids: set[str] = set()
    for shard, data in _own_shards(store, report):
        ids.update(_read_shard(shard, data, ["cell_id"]).column(0).to_pylist())
    return ids


def host_name() -> str:
    """This machine's name (the ``host`` column)."""
    return os.uname().nodename if hasattr(os, "uname") else "unknown"
