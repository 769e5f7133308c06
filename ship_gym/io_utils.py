"""Small file helpers shared by every writer: atomic replacement so a failure loses nothing."""

from __future__ import annotations

import contextlib
import math
import os
import stat
import tempfile
from collections.abc import Callable
from pathlib import Path


def atomic_write(
    path: str | Path, write: Callable[[Path], object], *, make_parents: bool = True
) -> Path:
    """Write a file through ``write(tmp_path)`` then atomically move it to ``path``.

    The temporary file lives in the target directory (same file system, so ``os.replace`` is
    atomic) and is flushed to disk before the move; if ``write`` raises, it is removed and an
    existing ``path`` is left untouched. The result keeps the permissions of the file it
    replaces, or gets 0644 when new (not ``mkstemp``'s private 0600).

    Parameters
    ----------
    path : str or Path
        Destination file.
    write : callable
        Writes the complete file to the path it is given.
    make_parents : bool
        Create missing parent directories (otherwise a missing directory raises
        ``FileNotFoundError``).
    """
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    if make_parents:
        directory.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=directory)
    os.close(fd)
    tmp_path = Path(tmp)
    try:
        write(tmp_path)
        with open(tmp_path, "rb+") as fh:
            os.fsync(fh.fileno())
        try:
            mode = stat.S_IMODE(path.stat().st_mode)
        except FileNotFoundError:
            mode = 0o644
        os.chmod(tmp_path, mode)
        os.replace(tmp_path, path)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp_path.unlink()
        raise
    return path


def atomic_write_text(path: str | Path, text: str) -> Path:
    """Atomically write a text file (UTF-8)."""
    return atomic_write(path, lambda p: p.write_text(text, encoding="utf-8"))


def to_json_value(x: object) -> object:
    """``x`` with NumPy arrays and scalars turned into lists and Python numbers, tuples into
    lists and non-finite floats into None (JSON has no NaN), recursively through dicts/lists."""
    import numpy as np

    if isinstance(x, dict):
        return {k: to_json_value(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [to_json_value(v) for v in x]
    if isinstance(x, np.ndarray):
        return to_json_value(x.tolist())
    if isinstance(x, np.floating | np.integer | np.bool_):
        return to_json_value(x.item())
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def from_json_value(x: object) -> object:
    """The inverse of :func:`to_json_value` for numbers: None back to NaN, recursively."""
    if isinstance(x, dict):
        return {k: from_json_value(v) for k, v in x.items()}
    if isinstance(x, list):
        return [from_json_value(v) for v in x]
    return math.nan if x is None else x
