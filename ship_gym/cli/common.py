"""Helpers shared by the ``ship-gym`` command modules (:mod:`ship_gym.cli`).

* the one ``--set KEY=VALUE …`` option (:func:`add_overrides_argument`, read back with
  :func:`parse_overrides`) of every command that takes builder or env keyword arguments;
* argparse ``type=`` validators (:func:`positive_float`, :func:`count`, …) whose errors argparse
  prints as ``argument --OPTION: …`` (usage error, exit 2), naming the option as typed and what
  was expected;
* :func:`prepare_output`, run by every command on each output path *before* its work: creates
  the parent folder and refuses a directory, a path under a file or an unwritable location,
  naming the option (:class:`CLIError`, exit 1);
* :func:`write_or_rescue`, which, when a late write fails anyway, saves what was computed in the
  system temp directory and says where;
* the JSON writer of ``--json``.

Kept free of heavy imports: every command module imports it at parse time.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

__all__ = [
    "MEMORY_LIMIT_BYTES",
    "CLIError",
    "add_overrides_argument",
    "check_memory",
    "count",
    "finite_float",
    "irregular_sea",
    "n_jobs",
    "nonnegative_float",
    "nonnegative_int",
    "override_item",
    "parse_overrides",
    "positive_float",
    "prepare_output",
    "prepare_output_dir",
    "seed",
    "write_json",
    "write_or_rescue",
]

GRAVITY = 9.80665


class CLIError(Exception):
    """A user error found by a command (bad value, bad path): message only, exit status 1."""


MEMORY_LIMIT_BYTES = 4 * 2**30
"""Largest memory [bytes] a command's arrays may be estimated to take before it allocates them."""


def check_memory(estimate_bytes: float, what: str, expected: str) -> None:
    """Refuse, before any allocation, work whose arrays are estimated past
    :data:`MEMORY_LIMIT_BYTES`.

    Parameters
    ----------
    estimate_bytes : float
        The estimated memory [bytes].
    what : str
        The options as the user typed them and what they size, e.g.
        ``"--t-max 1e+07 with --dt 0.05: 2e+08 time steps"``.
    expected : str
        What to change, e.g. ``"a shorter --t-max or a larger --dt"``.

    Raises
    ------
    CLIError
        Naming the options, the estimate and the limit [GiB].
    """
    if estimate_bytes > MEMORY_LIMIT_BYTES:
        raise CLIError(
            f"{what} would need ≈ {estimate_bytes / 2**30:.3g} GiB of memory; expected at most "
            f"{MEMORY_LIMIT_BYTES / 2**30:g} GiB: {expected}"
        )


def _number(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return value


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None


def finite_float(text: str) -> float:
    """A finite number (``nan``/``inf`` refused)."""
    return _number(text)


def positive_float(text: str) -> float:
    """A finite number > 0."""
    value = _number(text)
    if value <= 0.0:
        raise argparse.ArgumentTypeError(f"expected a number > 0, got {text!r}")
    return value


def nonnegative_float(text: str) -> float:
    """A finite number ≥ 0."""
    value = _number(text)
    if value < 0.0:
        raise argparse.ArgumentTypeError(f"expected a number >= 0, got {text!r}")
    return value


def bounded_float(low: float, high: float, *, low_open: bool = False) -> Callable[[str], float]:
    """A type function for a finite number in ``[low, high]`` (``(low, high]`` if ``low_open``)."""

    def check(text: str) -> float:
        value = _number(text)
        if value > high or value < low or (low_open and value == low):
            lo = "(" if low_open else "["
            raise argparse.ArgumentTypeError(
                f"expected a number in {lo}{low:g}, {high:g}], got {text!r}"
            )
        return value

    check.__name__ = "bounded_float"
    return check


def min_count(minimum: int, what: str = "an integer") -> Callable[[str], int]:
    """A type function for an integer ≥ ``minimum``; ``what`` names it in the error."""

    def check(text: str) -> int:
        value = _integer(text)
        if value < minimum:
            raise argparse.ArgumentTypeError(f"expected {what} >= {minimum}, got {text!r}")
        return value

    check.__name__ = "min_count"
    return check


count = min_count(1)
"""An integer ≥ 1."""
nonnegative_int = min_count(0)
"""An integer ≥ 0."""
seed = min_count(0, "a seed, an integer")
"""A random seed: an integer ≥ 0 (NumPy refuses negative seeds)."""
n_jobs = min_count(1, "a number of worker processes, an integer")
"""A number of worker processes: an integer ≥ 1."""


def existing_file(text: str) -> str:
    """A path to an existing regular file."""
    path = Path(text)
    if path.is_dir():
        raise argparse.ArgumentTypeError(f"{text!r} is a directory; expected a file")
    if not path.is_file():
        raise argparse.ArgumentTypeError(f"no such file {text!r}")
    if not os.access(path, os.R_OK):
        raise argparse.ArgumentTypeError(f"{text!r} is not readable")
    return text


def ship_name(text: str) -> str:
    """A ship: a bundled ship / library hull name or a ship file (``.toml``), read and checked
    at parse time so that a bad file is reported before any work."""
    from ship_gym.ship import load_ship

    try:
        load_ship(text)
    except (ValueError, OSError) as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return text


def add_ship_argument(parser: argparse.ArgumentParser, *, positional: bool = False) -> None:
    """Add the ship argument: ``--ship SHIP`` (alias ``--hull``, default the S175) or, with
    ``positional``, a required ``ship`` argument; either way stored as ``args.hull``."""
    help = (
        "ship: a bundled ship or library hull (s175, dtmb5415, box_barge, hemisphere, wigley) "
        "or a ship file (.toml; see `ship-gym ship check`)"
    )
    if positional:
        parser.add_argument("hull", metavar="SHIP", type=ship_name, help=help)
    else:
        parser.add_argument(
            "--ship", "--hull", dest="hull", default="s175", type=ship_name, metavar="SHIP",
            help=help,
        )  # fmt: skip


def override_item(text: str) -> str:
    """One ``key=value`` item of ``--set`` (checked at parse time)."""
    key = text.split("=", 1)[0]
    if "=" not in text or not key.strip():
        raise argparse.ArgumentTypeError(f"override {text!r} must look like key=value")
    return text


def unique(values: Sequence[float], option: str, what: str = "values") -> tuple[float, ...]:
    """``values`` as a tuple; duplicates refused (:class:`CLIError` naming ``option``)."""
    dup = sorted({v for i, v in enumerate(values) if v in values[:i]})
    if dup:
        raise CLIError(
            f"{option}: duplicate {what} {', '.join(f'{d:g}' for d in dup)}; "
            "expected each value once"
        )
    return tuple(values)


def check_irregular_sea(hs: float, tp: float, option: str) -> None:
    """Refuse a sea state that cannot exist (:func:`ship_gym.waves.sea_state.steepness_error`:
    Hs/λp above DNV-RP-C205's limit), naming ``option``."""
    from ship_gym.waves.sea_state import steepness_error

    if hs <= 0.0 or tp <= 0.0:
        raise CLIError(f"{option}: expected Hs > 0 [m] and Tp > 0 [s], got {hs:g} {tp:g}")
    error = steepness_error("irregular", hs, tp, "Hs", "Tp")
    if error is not None:
        raise CLIError(f"{option}: {error}; expected a lower Hs or a longer Tp")


def irregular_sea(values: Sequence[float], option: str = "--irregular") -> tuple[float, float]:
    """(Hs, Tp) checked by :func:`check_irregular_sea`."""
    hs, tp = float(values[0]), float(values[1])
    check_irregular_sea(hs, tp, option)
    return hs, tp


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
    parser.add_argument(
        "--set", nargs="*", default=[], metavar="KEY=VALUE", type=override_item, help=help
    )


def _probe_directory(directory: Path, option: str, shown: str) -> None:
    try:
        fd, probe = tempfile.mkstemp(prefix=".ship-gym-probe.", dir=directory)
    except OSError as exc:
        raise CLIError(
            f"{option}: cannot write to the folder of {shown!r} ({exc.strerror or exc}); "
            "expected a writable location"
        ) from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(probe)


def _make_directory(directory: Path, option: str, shown: str) -> None:
    if directory.exists() and not directory.is_dir():
        where = "" if str(directory) == shown else f" in {shown!r}"
        raise CLIError(f"{option}: {str(directory)!r}{where} is a file; expected a folder")
    for parent in directory.parents:
        if parent.exists() and not parent.is_dir():
            raise CLIError(f"{option}: {str(parent)!r} in {shown!r} is a file; expected a folder")
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CLIError(
            f"{option}: cannot create the folder {str(directory)!r} for {shown!r} "
            f"({exc.strerror or exc}); expected a writable location"
        ) from None


def prepare_output(
    path: str | Path | None, option: str, *, suffixes: Sequence[str] | None = None
) -> Path | None:
    """Check an output file path before any work; create its folder.

    Returns None for a None/empty path (output skipped). Raises :class:`CLIError`, naming
    ``option`` as typed (e.g. ``--output``), when the path is a directory, its folder cannot be
    created (a file in the way, permissions), the folder is not writable, an existing file is
    not writable, or (with ``suffixes``) the suffix is not one of them.
    """
    if path is None or str(path) == "":
        return None
    shown = str(path)
    p = Path(path)
    if shown.endswith(("/", os.sep)) or p.is_dir():
        raise CLIError(f"{option}: {shown!r} is a directory; expected a file path")
    if suffixes is not None and p.suffix.lower() not in suffixes:
        raise CLIError(
            f"{option}: {shown!r} has suffix {p.suffix or '(none)'!r}; expected one of "
            + ", ".join(suffixes)
        )
    directory = p.parent if str(p.parent) else Path(".")
    _make_directory(directory, option, shown)
    _probe_directory(directory, option, shown)
    if p.exists() and not os.access(p, os.W_OK):
        raise CLIError(f"{option}: {shown!r} exists and is not writable")
    return p


def prepare_output_dir(path: str | Path | None, option: str) -> Path | None:
    """Like :func:`prepare_output` for an output *folder*: created, must be writable."""
    if path is None or str(path) == "":
        return None
    p = Path(path)
    _make_directory(p, option, str(path))
    _probe_directory(p, option, str(path))
    return p


def write_or_rescue(path: str | Path, write: Callable[[Path], object], option: str) -> Path:
    """Write ``path`` atomically with ``write``; if that fails (a disk filled, a folder removed
    since the check), write the same content to the system temp directory and raise
    :class:`CLIError` saying where it is."""
    from ship_gym.io_utils import atomic_write

    path = Path(path)
    try:
        return atomic_write(path, write)
    except OSError as exc:
        rescue = Path(tempfile.gettempdir()) / f"ship-gym-{os.getpid()}-{path.name}"
        try:
            atomic_write(rescue, write)
        except Exception as exc2:
            raise CLIError(
                f"{option}: could not write {str(path)!r} ({exc}); saving to {rescue} "
                f"failed too ({exc2}): the result is lost"
            ) from None
        raise CLIError(
            f"{option}: could not write {str(path)!r} ({exc.strerror or exc}); the result was "
            f"saved to {rescue}"
        ) from None


def write_json(path: str | Path | None, payload: Any, option: str = "--json") -> None:
    """Write ``payload`` as indented JSON atomically (NumPy scalars as floats) and say so;
    nothing when ``path`` is None or empty. A failed write is rescued (:func:`write_or_rescue`)."""
    if not path:
        return
    text = json.dumps(payload, indent=2, default=float)
    write_or_rescue(Path(path), lambda p: p.write_text(text, encoding="utf-8"), option)
    print(f"wrote {path}")


def kill_worker_processes() -> None:
    """Terminate joblib/loky's reusable worker processes now (they otherwise idle for 300 s)."""
    import sys

    if "joblib" not in sys.modules:
        return
    with contextlib.suppress(Exception):
        from joblib.externals.loky import get_reusable_executor

        get_reusable_executor().shutdown(wait=False, kill_workers=True)


@contextlib.contextmanager
def workers_die_with_parent() -> Any:
    """Within the block, joblib's process workers (loky) die with this process: they get
    ``PR_SET_PDEATHSIG`` (Linux) and, if the block is left by an exception (SIGTERM turned into
    ``SystemExit`` by :func:`ship_gym.cli.main`, Ctrl-C), they are killed."""
    try:
        from joblib import parallel_config
    except ImportError:  # pragma: no cover - joblib is a dependency
        yield
        return
    from ship_gym.analysis.executors import die_with_parent

    try:
        with parallel_config(backend="loky", initializer=die_with_parent, initargs=(os.getpid(),)):
            yield
    except BaseException:
        kill_worker_processes()
        raise
