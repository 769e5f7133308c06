"""What a run returns: the recorded series, the divergence error and the step count of a duration.

Shared by the engine (:class:`ship_gym.engine.batch.BatchSimulator`) and its one-ship view
(:class:`ship_gym.engine.simulator.Simulator`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ship_gym.conventions import DOF_NAMES

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["SimulationDiverged", "SimulationResult", "steps_in"]


class SimulationDiverged(RuntimeError):
    """The state became non-finite or absurd; the simulator keeps its last valid state."""

    result: SimulationResult | None = None
    """The series recorded up to the divergence, when raised by a recording run."""


@dataclass
class SimulationResult:
    """Time series of a run.

    Attributes
    ----------
    t : numpy.ndarray
        (n,) times [s].
    eta : numpy.ndarray
        (n, 6) positions [m] and Euler angles [rad].
    nu : numpy.ndarray
        (n, 6) body velocities [m/s, rad/s].
    elevation : numpy.ndarray
        (n,) incident-wave elevation at O's horizontal position [m] (0 in calm water).
    forces : dict
        Per-force body-axis generalised forces (n, 6) at the recorded states (if recorded).
    """

    t: np.ndarray
    eta: np.ndarray
    nu: np.ndarray
    elevation: np.ndarray
    forces: dict[str, np.ndarray] = field(default_factory=dict)

    def to_dataset(self) -> xr.Dataset:
        """The series as an ``xarray.Dataset`` (dims ``time``, ``dof``)."""
        import xarray as xr

        data = {
            "eta": (("time", "dof"), self.eta),
            "nu": (("time", "dof"), self.nu),
            "wave_elevation": (("time",), self.elevation),
        }
        for name, f in self.forces.items():
            data[f"force_{name}"] = (("time", "dof"), f)
        ds = xr.Dataset(data, coords={"time": self.t, "dof": list(DOF_NAMES)})
        ds["eta"].attrs["units"] = "m (x, y, z) and rad (roll, pitch, yaw)"
        ds["nu"].attrs["units"] = "m/s (u, v, w) and rad/s (p, q, r)"
        return ds


def steps_in(duration: float, dt: float) -> int:
    """Number of steps of ``dt`` [s] in ``duration`` [s] (ValueError unless a positive
    multiple, to 1e-9 relative)."""
    n = round(duration / dt)
    if n < 1 or abs(n * dt - duration) > 1e-9 * max(1.0, duration):
        raise ValueError(f"duration {duration} s must be a positive multiple of dt = {dt} s")
    return n
