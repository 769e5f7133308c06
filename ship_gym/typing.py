"""Type aliases used across the package, defined once.

``FloatArray`` is a float64 NumPy array; ``IntegratorName`` names the time-stepping schemes
of the engine; ``Precision`` the floating-point width of the Froude–Krylov wave sums.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import NDArray

__all__ = ["FloatArray", "ForwardSpeedModel", "IntegratorName", "Precision"]

FloatArray = NDArray[np.float64]
"""A float64 array (shape given where it is used)."""

IntegratorName = Literal["rk4", "holloway"]
"""The schemes of the engine (:class:`ship_gym.engine.batch.BatchSimulator`, its compiled
backend, the single-ship view and the environments): RK4 (4 force evaluations per step) or
Holloway's μ-Taylor scheme (1, after a 2-step RK4 start-up)."""

Precision = Literal["float64", "float32"]
"""Precision of the Froude–Krylov wave sums (float32: ≈ 2e-7 relative)."""

ForwardSpeedModel = Literal["relative_motion", "radiation_only"]
"""The environments' forward-speed model (:mod:`ship_gym.hydro.forward_speed`): the speed terms
on the motion relative to the incident flow (radiated and scattered momentum, high-passed;
the ``-v3`` ids), or on the radiated momentum only (the model of issue #13; the ``-v2`` ids)."""
