"""Per-episode sea states of the ship tasks (:class:`SeaSampler`): irregular (JONSWAP) or regular
seas at a random relative heading, with Matusiak's start-up ramp.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

from ship_gym.conventions import GRAVITY
from ship_gym.envs.validation import check_range

if TYPE_CHECKING:
    from ship_gym.waves.wave_field import WaveField

_TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class SeaSampler:
    """How the sea of an episode is drawn from its generator.

    Draws, in this order: height, period, relative heading, then (regular) the phase or
    (irregular) the components (:meth:`ship_gym.waves.wave_field.WaveField.from_sea_state`).

    Parameters
    ----------
    kind : {"irregular", "regular"}
        JONSWAP irregular sea or a regular wave.
    height_range : tuple of float
        Significant height Hs (irregular) or wave height H (regular) [m], uniform.
    period_range : tuple of float
        Peak period Tp (irregular) or period T (regular) [s], uniform.
    heading_range_deg : tuple of float
        Relative wave heading β [deg] (0 following seas, 180 head seas), uniform.
    n_components : int
        Wave components of an irregular sea.
    gamma : float
        JONSWAP peak enhancement γ [-].
    spreading_s : float or None
        Cos-2s spreading exponent (None: long-crested).
    ramp_time : float
        Start-up ramp T_f [s] (Matusiak eq. 12).
    """

    kind: Literal["irregular", "regular"] = "irregular"
    height_range: tuple[float, float] = (3.0, 5.0)
    period_range: tuple[float, float] = (9.0, 12.0)
    heading_range_deg: tuple[float, float] = (0.0, 360.0)
    n_components: int = 40
    gamma: float = 3.3
    spreading_s: float | None = None
    ramp_time: float = 30.0

    def __post_init__(self) -> None:
        if self.kind not in ("irregular", "regular"):
            raise ValueError(f"sea kind must be 'irregular' or 'regular', got {self.kind!r}")
        h = check_range("wave height range", self.height_range, low=0.0, high=30.0, unit="m")
        t = check_range("wave period range", self.period_range, low=1.0, high=40.0, unit="s")
        b = check_range(
            "wave heading range", self.heading_range_deg, low=-360.0, high=720.0, unit="deg"
        )
        object.__setattr__(self, "height_range", h)
        object.__setattr__(self, "period_range", t)
        object.__setattr__(self, "heading_range_deg", b)
        n = self.n_components
        if isinstance(n, bool) or not isinstance(n, int | np.integer) or not 1 <= n <= 1000:
            raise ValueError(f"n_components must be an integer in 1…1000, got {n!r}")
        if not (math.isfinite(self.gamma) and self.gamma >= 1.0):
            raise ValueError(f"JONSWAP gamma must be >= 1, got {self.gamma!r}")
        if self.spreading_s is not None and not (
            math.isfinite(self.spreading_s) and self.spreading_s >= 0.0
        ):
            raise ValueError(f"spreading_s must be None or >= 0, got {self.spreading_s!r}")
        if not (math.isfinite(self.ramp_time) and self.ramp_time >= 0.0):
            raise ValueError(f"wave ramp time must be >= 0 [s], got {self.ramp_time!r}")
        if self.kind == "regular":
            from ship_gym.waves.sea_state import MAX_STEEPNESS

            shortest = GRAVITY * t[0] ** 2 / _TWO_PI
            if h[1] / shortest > MAX_STEEPNESS:
                raise ValueError(
                    f"regular waves up to H = {h[1]} m at T = {t[0]} s (λ = {shortest:.1f} m) "
                    f"exceed the breaking steepness H/λ = {MAX_STEEPNESS:.3f}"
                )

    @property
    def max_components(self) -> int:
        """Components of the largest sea drawn (the batch's padded count)."""
        return 1 if self.kind == "regular" else int(self.n_components)

    def sample(self, rng: np.random.Generator) -> tuple[WaveField, dict[str, float]]:
        """One episode's wave field and its parameters (``wave_height_m``, ``wave_period_s``,
        ``wave_heading_deg``)."""
        from ship_gym.engine.ship import wave_field_for
        from ship_gym.waves.sea_state import IrregularSea, RegularWave

        height = float(rng.uniform(*self.height_range))
        period = float(rng.uniform(*self.period_range))
        heading_deg = float(rng.uniform(*self.heading_range_deg))
        beta = math.radians(heading_deg)
        if self.kind == "regular":
            phase = float(rng.uniform(0.0, _TWO_PI))
            sea: RegularWave | IrregularSea = RegularWave(
                height=height, period=period, phase=phase, ramp_time=self.ramp_time
            )
        else:
            sea = IrregularSea(
                hs=height,
                tp=period,
                gamma=self.gamma,
                spreading_s=self.spreading_s,
                n_components=int(self.n_components),
                ramp_time=self.ramp_time,
            )
        wave_field = wave_field_for(sea, beta, rng)
        info = {
            "wave_height_m": height,
            "wave_period_s": period,
            "wave_heading_deg": (heading_deg + 180.0) % 360.0 - 180.0,
        }
        return wave_field, info
