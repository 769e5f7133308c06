"""Numerics independent of ship physics.

* :mod:`ship_gym.numerics.fastmath` — numba polynomial approximations of cos, sin and 2^x
  (float64 and float32) used by the Froude–Krylov kernel;
* :mod:`ship_gym.numerics.integrators` — generic one-system ODE steppers (RK4,
  Adams–Bashforth–Moulton, Holloway's μ-Taylor scheme) for hand-written systems such as
  Holloway's oscillator (:mod:`ship_gym.analysis.holloway`); the ship engine's integrators work on
  rows of ships (:mod:`ship_gym.engine.batch`, :mod:`ship_gym.engine.compiled`).
"""
