"""Reinforcement-learning agents for ship_gym: classical baselines, SB3 training, evaluation.

* :mod:`ship_gym.agents.baselines` — classical controllers (zero, PID autopilot, fin and ride
  controllers) with SB3's ``predict`` signature: plain numpy;
* :mod:`ship_gym.agents.train` — stable-baselines3 training from a TOML config (``ship-gym
  train``); the shipped configs are in :mod:`ship_gym.agents.configs`;
* :mod:`ship_gym.agents.evaluate` — baselines and saved models on the same seeded seas
  (``ship-gym evaluate``).

stable-baselines3 and torch (the ``agents`` extra) are imported only inside the functions that
train or load a model: importing any of these modules loads neither.
"""
