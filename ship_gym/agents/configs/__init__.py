"""Training configurations shipped with ship_gym (package data), one per registered env id.

``ship-gym train NAME`` (or :func:`ship_gym.agents.train.load_config`) takes the name of one of
these — ``ppo_roll_one_dof``, with or without ``.toml`` — from any working directory, or a path
to a TOML file of the same layout (:mod:`ship_gym.agents.train`). Relative paths inside a config
(``training.output_dir``) are taken from the working directory, never from the package.
"""

from __future__ import annotations

from importlib.resources import files
from importlib.resources.abc import Traversable
from pathlib import Path

__all__ = ["find_config", "shipped_config", "shipped_config_names"]

_SUFFIX = ".toml"


def _directory() -> Traversable:
    return files(__name__)


def shipped_config_names() -> list[str]:
    """Names of the shipped configs (file stems, sorted), e.g. ``"ppo_roll_one_dof"``."""
    return sorted(
        entry.name.removesuffix(_SUFFIX)
        for entry in _directory().iterdir()
        if entry.is_file() and entry.name.endswith(_SUFFIX)
    )


def shipped_config(name: str) -> Traversable:
    """The shipped config ``name`` (stem, ``.toml`` optional); FileNotFoundError if none."""
    stem = name.removesuffix(_SUFFIX)
    if stem in shipped_config_names():
        return _directory() / f"{stem}{_SUFFIX}"
    raise FileNotFoundError(
        f"no shipped config {name!r}; shipped: {', '.join(shipped_config_names())}"
    )


def find_config(config: str | Path) -> Path | Traversable:
    """A config file: ``config`` itself when it is an existing file (relative to the working
    directory), else, when it is a bare name (no directory part), the shipped config of that name.

    Raises
    ------
    FileNotFoundError
        Neither a file nor a shipped config; the message lists the shipped names.
    """
    path = Path(config)
    if path.is_file():
        return path
    if path.parent == Path(".") and path.name.removesuffix(_SUFFIX) in shipped_config_names():
        return shipped_config(path.name)
    raise FileNotFoundError(
        f"no config file {path} (nor a shipped config of that name; shipped: "
        f"{', '.join(shipped_config_names())})"
    )
