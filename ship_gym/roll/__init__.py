"""The single-degree-of-freedom nonlinear roll model (McCue & Campbell eq. 1 and 2;
:mod:`ship_gym.roll.equation`), used by the RollOneDOF environment, the safe basins and the
identification study.
"""

from ship_gym.roll.equation import (
    EDITH_TERKOL_NATURAL_FREQUENCY,
    MomentFn,
    RollEquation,
    RollTrajectory,
)

__all__ = ["EDITH_TERKOL_NATURAL_FREQUENCY", "MomentFn", "RollEquation", "RollTrajectory"]
