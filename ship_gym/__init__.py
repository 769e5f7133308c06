"""ship_gym — Gymnasium environments for ship seakeeping on a two-stage 6-DOF ship model."""

__version__ = "0.1.0"
