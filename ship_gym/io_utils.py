"""Small file helpers shared by every writer: atomic replacement so a failure loses nothing."""

from __future__ import annotations

import contextlib
import math
import os
import stat
import tempfile
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path

#: When this module was imported: temporary files older than this were not made by this process.
_PROCESS_START = time.time()
#: A temporary file without a pid in its name (older versions) is removed once this old [s].
_LEGACY_TEMP_AGE_S = 3600.0


def _pid_alive(pid: int) -> bool:
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # someone else's live process
        return True
    except OSError:
        return False
    return True


def clean_stale_temps(path: str | Path) -> list[Path]:
    """Remove the leftover temporary files of :func:`atomic_write` for ``path``.

    A write killed by SIGKILL (or SIGTERM without cleanup) leaves ``.NAME.PID.XXXX.tmp`` beside
    ``NAME``. Such a file is removed when it is older than this process's start and its pid is
    not a live process (``.NAME.XXXX.tmp`` files of older versions, without a pid: when older
    than an hour). Returns the removed paths; errors are ignored.
    """
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    prefix = f".{path.name}."
    removed: list[Path] = []
    try:
        candidates = [c for c in directory.iterdir() if c.name.startswith(prefix)]
    except OSError:
        return removed
    now = time.time()
    for candidate in candidates:
        name = candidate.name
        if not name.endswith(".tmp"):
            continue
        try:
            mtime = candidate.lstat().st_mtime
        except OSError:
            continue
        if mtime >= _PROCESS_START:
            continue
        middle = name[len(prefix) : -len(".tmp")].split(".")
        if len(middle) == 2 and middle[0].isdigit():
            if _pid_alive(int(middle[0])):
                continue
        elif now - mtime < _LEGACY_TEMP_AGE_S:
            continue
        with contextlib.suppress(OSError):
            candidate.unlink()
            removed.append(candidate)
    return removed


def atomic_write(
    path: str | Path, write: Callable[[Path], object], *, make_parents: bool = True
) -> Path:
    """Write a file through ``write(tmp_path)`` then atomically move it to ``path``.

    The temporary file ``.NAME.PID.XXXX.tmp`` lives in the target directory (same file system,
    so ``os.replace`` is atomic; the pid lets a later run remove the leftovers of a killed one,
    :func:`clean_stale_temps`, which runs first) and is flushed to disk before the move; if
    ``write`` raises, it is removed and an existing ``path`` is left untouched. The result keeps
    the permissions of the file it replaces, or gets 0644 when new (not ``mkstemp``'s private
    0600).

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
    clean_stale_temps(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.{os.getpid()}.", suffix=".tmp", dir=directory)
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


def csv_text(columns: Sequence[str], rows: Iterable[Mapping[str, float]]) -> str:
    """A CSV table of numeric rows: a header of ``columns``, then each row's values in that
    order (10 significant digits)."""
    lines = [",".join(columns)]
    lines += [",".join(f"{row[k]:.10g}" for k in columns) for row in rows]
    return "\n".join(lines) + "\n"


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
