"""Analyses built on the simulator stages: seed-paper reproductions, stability studies.

Sub-modules are imported explicitly (nothing heavy is loaded here), e.g.
``from ship_gym.analysis.holloway import stability_limits``.
"""
