"""The engine: one simulation engine for N ≥ 1 ships (stage 6).

* :mod:`ship_gym.engine.ship` — :class:`~ship_gym.engine.ship.ShipSetup` (which hull, database,
  force models and numerics) and the builders of its force models;
* :mod:`ship_gym.engine.rigid_body` — rigid-body terms, kinematics and the left-hand side;
* :mod:`ship_gym.engine.batch` — :class:`~ship_gym.engine.batch.BatchSimulator`, the engine:
  N ships stepped together by RK4 or Holloway's scheme, on its numpy path or its compiled
  backend (:mod:`ship_gym.engine.compiled`: K steps of all ships in one numba call);
* :mod:`ship_gym.engine.simulator` — :class:`~ship_gym.engine.simulator.Simulator`, the engine
  seen as one ship (scalar time, (6,) states, an exception on divergence);
* :mod:`ship_gym.engine.results` — the recorded series and the divergence error;
* :mod:`ship_gym.engine.linearisation` — Nomoto and linear models identified from the forces.

Generic ODE steppers for hand-written systems are in :mod:`ship_gym.numerics.integrators`.
"""
