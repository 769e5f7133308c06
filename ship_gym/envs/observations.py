"""The observation table of the ship tasks: one row per entry drives everything about it.

An :class:`Observation` is one entry of a task's observation vector: its name, unit, bounds,
sensor-noise standard deviation, what it reads (a :class:`StateColumn` of the simulator state,
filled by one compiled kernel, or a getter function of the task) and a line of documentation.
From the table come

* the observation names (``"roll rate [rad/s]"``, :attr:`Observation.label`) and the bounds of
  the ``Box`` space, every entry clipped to them;
* the sensor noise (:attr:`Observation.noise_std` × ``sensor_noise``; :data:`SENSOR_NOISE_STD`);
* the values, written by :func:`write_state_columns` (the common entries) or by the getters;
* the docstring table of the environments (:func:`markdown_table`);
* the look-ups of the classical baselines (:func:`find_observation`: by the entry's
  :attr:`Observation.name` or one of its :attr:`Observation.aliases`, never a pattern on the
  label).

:data:`SHIP_OBSERVATIONS` holds the common entries of every ship task (the first 12–14 columns);
a task appends its own (``ShipTask(observations=...)``) and the wave preview follows.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numba
import numpy as np
from numpy.typing import NDArray

__all__ = [
    "PREVIEW_NOISE_STD",
    "SENSOR_NOISE_STD",
    "SHIP_OBSERVATIONS",
    "SIGNALS",
    "Observation",
    "StateColumn",
    "find_observation",
    "markdown_table",
    "observation_from_tuple",
    "preview_observation",
]


@dataclass(frozen=True)
class StateColumn:
    """Where a common entry is read: column ``column`` of the simulator's η or ν, or of the
    per-step signals (:data:`SIGNALS`), minus the calm-water heave equilibrium if
    ``from_equilibrium``.

    Attributes
    ----------
    array : {"eta", "nu", "signal"}
        η = (x, y, z, φ, θ, ψ) [m, rad], ν = (u, v, w, p, q, r) [m/s, rad/s] or the signals.
    column : int
        Column of the array.
    from_equilibrium : bool
        Subtract the calm-water heave z_eq [m] (the heave entry).
    """

    array: Literal["eta", "nu", "signal"]
    column: int
    from_equilibrium: bool = False


SIGNALS: tuple[str, ...] = (
    "heading error",
    "relative wave heading cos",
    "relative wave heading sin",
    "rudder angle",
    "shaft speed",
)
"""The per-step signals a :class:`StateColumn` of array ``"signal"`` reads, in column order:
wrap(ψ_ref − ψ) [rad], cos β and sin β of β = χ − ψ [-], the servo rudder angle [rad] and the
shaft speed [rev/s] (computed once per step by :class:`~ship_gym.envs.ship_task.ShipTask`)."""

Getter = Callable[[Any], Any]
"""A task entry's getter: the task (a :class:`~ship_gym.envs.ship_task.ShipTask` subclass) →
its (N,) values [unit of the entry]."""


@dataclass(frozen=True)
class Observation:
    """One observation entry (module docstring).

    Attributes
    ----------
    name : str
        What is observed, without the unit (``"roll rate"``): the key the baselines look up.
    unit : str
        Unit, as in the label ``"name [unit]"`` (``"rad/s"``, ``"-"``).
    low, high : float
        Bounds of the space [unit]; the value is clipped to them.
    noise_std : float
        Standard deviation of the sensor at ``sensor_noise=1`` [unit] (0: noise-free).
    getter : StateColumn or callable or None
        What the entry reads: a column of the state (the common entries, one compiled kernel),
        a function of the task returning the (N,) values, or None for an entry written by the
        task's ``_write_extra_observations`` hook (the tuples of ``extra_observations``).
    doc : str
        Its row in the docstring table (default: the name).
    bound : str
        The bounds as the docstring table writes them (default: from ``low`` and ``high``).
    aliases : tuple of str
        Other names a baseline may look it up by (``("p",)`` for the roll rate).
    requires : {"", "rudder", "propulsion"}
        A common entry present only with a rudder or with propulsion.
    """

    name: str
    unit: str
    low: float
    high: float
    noise_std: float = 0.0
    getter: StateColumn | Getter | None = None
    doc: str = ""
    bound: str = ""
    aliases: tuple[str, ...] = ()
    requires: Literal["", "rudder", "propulsion"] = ""

    @property
    def label(self) -> str:
        """``"name [unit]"``: the entry of ``observation_names``."""
        return f"{self.name} [{self.unit}]"

    def bound_text(self) -> str:
        """The bounds as written in the docstring table (``±5``, ``0 … 2``)."""
        if self.bound:
            return self.bound
        if self.low == -self.high:
            return f"±{self.high:.3g}"
        return f"{self.low:.3g} … {self.high:.3g}"

    def matches(self, keyword: str) -> bool:
        """Whether ``keyword`` (any case) is this entry's name or one of its aliases."""
        k = keyword.strip().lower()
        return k == self.name.lower() or k in (a.lower() for a in self.aliases)


_PI = math.pi
SHIP_OBSERVATIONS: tuple[Observation, ...] = (
    Observation("roll", "rad", -_PI, _PI, math.radians(0.2), StateColumn("eta", 3),
                "roll φ", "±π", ("roll angle", "phi")),
    Observation("pitch", "rad", -_PI / 2, _PI / 2, math.radians(0.2), StateColumn("eta", 4),
                "pitch θ", "±π/2", ("pitch angle", "theta")),
    Observation("heave", "m", -30.0, 30.0, 0.05, StateColumn("eta", 2, from_equilibrium=True),
                "heave (from the calm-water equilibrium, down positive)"),
    Observation("roll rate", "rad/s", -5.0, 5.0, math.radians(0.1), StateColumn("nu", 3),
                "roll rate p (body)", aliases=("roll velocity", "p")),
    Observation("pitch rate", "rad/s", -5.0, 5.0, math.radians(0.1), StateColumn("nu", 4),
                "pitch rate q (body)", aliases=("pitch velocity", "q")),
    Observation("heave velocity", "m/s", -30.0, 30.0, 0.02, StateColumn("nu", 2),
                "heave velocity w (body)", aliases=("heave rate", "w")),
    Observation("yaw rate", "rad/s", -2.0, 2.0, math.radians(0.05), StateColumn("nu", 5),
                "yaw rate r", aliases=("r",)),
    Observation("surge speed", "m/s", -30.0, 30.0, 0.05, StateColumn("nu", 0),
                "surge speed u", aliases=("u",)),
    Observation("sway velocity", "m/s", -30.0, 30.0, 0.05, StateColumn("nu", 1),
                "sway velocity v", aliases=("v",)),
    Observation("heading error", "rad", -_PI, _PI, math.radians(0.5), StateColumn("signal", 0),
                "heading error wrap(ψ_ref − ψ)", "±π", ("course error",)),
    Observation("relative wave heading cos", "-", -1.0, 1.0, 0.0, StateColumn("signal", 1),
                "cos β of the mean relative wave heading β = χ − ψ"),
    Observation("relative wave heading sin", "-", -1.0, 1.0, 0.0, StateColumn("signal", 2),
                "sin β of the mean relative wave heading β = χ − ψ"),
    Observation("rudder angle", "rad", -_PI / 2, _PI / 2, 0.0, StateColumn("signal", 3),
                "rudder angle (servo)", "±π/2", requires="rudder"),
    Observation("shaft speed", "rev/s", -20.0, 20.0, 0.0, StateColumn("signal", 4),
                "shaft speed", requires="propulsion"),
)  # fmt: skip
"""The common entries of every ship task, in column order (the rudder angle with a rudder, the
shaft speed with propulsion). Noise: a typical marine motion reference unit, gyro compass and
log; commands, actuator feedback and the wave direction are noise-free."""

SENSOR_NOISE_STD: dict[str, float] = {
    o.label: o.noise_std for o in SHIP_OBSERVATIONS if o.noise_std
}
"""Standard deviation of each sensor at ``sensor_noise=1`` by label (from :data:`SHIP_OBSERVATIONS`;
unlisted entries are noise-free except the preview, :data:`PREVIEW_NOISE_STD`)."""

PREVIEW_NOISE_STD = 0.1
"""Wave-radar elevation accuracy at ``sensor_noise=1`` [m]."""


def preview_observation(x: float, y: float, ahead: bool) -> Observation:
    """The entry of the incident elevation at body-frame point (x, y) [m] (``ahead``: a
    distance x ahead of O), ±30 m, noise :data:`PREVIEW_NOISE_STD`."""
    name = (
        f"wave elevation {x:g} m ahead"
        if ahead
        else f"wave elevation at body point ({x:g}, {y:g}) m"
    )
    return Observation(name, "m", -30.0, 30.0, PREVIEW_NOISE_STD, None, "incident elevation")


def observation_from_tuple(entry: tuple[str, float, float] | Observation) -> Observation:
    """An :class:`Observation` from an ``extra_observations`` tuple ``("name [unit]", low,
    high)`` (noise-free, written by the task's ``_write_extra_observations``); an Observation
    is returned as it is."""
    if isinstance(entry, Observation):
        return entry
    label, low, high = entry
    name, sep, rest = label.partition(" [")
    if not sep or not rest.endswith("]"):
        raise ValueError(f"observation name {label!r} must end with its unit in brackets")
    return Observation(name, rest[:-1], float(low), float(high))


def find_observation(entries: Sequence[Observation], keywords: Iterable[str]) -> int | None:
    """Index of the entry whose name or alias is the first of ``keywords`` that any entry has
    (tried in order); None if none has one. Several entries with it → ValueError."""
    for keyword in keywords:
        hits = [i for i, e in enumerate(entries) if e.matches(keyword)]
        if len(hits) == 1:
            return hits[0]
        if len(hits) > 1:
            raise ValueError(
                f"observation {keyword!r} is ambiguous among {[entries[i].label for i in hits]}"
            )
    return None


def markdown_table(entries: Sequence[Observation], first: int = 0, header: bool = True) -> str:
    """Markdown rows ``| # | name | unit | bound |`` of ``entries`` numbered from ``first``."""
    lines = ["| # | name | unit | bound |", "|---|---|---|---|"] if header else []
    for k, e in enumerate(entries):
        lines.append(f"| {first + k} | {e.doc or e.name} | {e.unit} | {e.bound_text()} |")
    return "\n".join(lines)


def state_layout(entries: Sequence[Observation]) -> tuple[NDArray, NDArray, NDArray]:
    """(kinds, columns, subtract-equilibrium flags) of the :class:`StateColumn` entries, the
    arguments of :func:`write_state_columns` (kind 0 η, 1 ν, 2 the signals)."""
    kinds, columns, eq = [], [], []
    for e in entries:
        g = e.getter
        if not isinstance(g, StateColumn):
            raise ValueError(f"{e.label} is not read from the state")
        kinds.append(("eta", "nu", "signal").index(g.array))
        columns.append(g.column)
        eq.append(g.from_equilibrium)
    return (
        np.asarray(kinds, dtype=np.int64),
        np.asarray(columns, dtype=np.int64),
        np.asarray(eq, dtype=np.bool_),
    )


@numba.njit(cache=True, nogil=True)
def write_state_columns(
    eta, nu, signals, z_eq, kinds, columns, from_equilibrium, out
):  # pragma: no cover - compiled
    """out[i, j] = the state column j (:func:`state_layout`) of episode i: η[i, c], ν[i, c] or
    signals[i, c], minus z_eq where ``from_equilibrium[j]`` (a copy otherwise: the same bits)."""
    for i in range(eta.shape[0]):
        for j in range(kinds.shape[0]):
            k = kinds[j]
            c = columns[j]
            if k == 0:
                v = eta[i, c]
            elif k == 1:
                v = nu[i, c]
            else:
                v = signals[i, c]
            if from_equilibrium[j]:
                v = v - z_eq
            out[i, j] = v
