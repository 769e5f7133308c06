"""Reinforcement-learning agents for ship_gym: classical baselines, SB3 training, evaluation."""
