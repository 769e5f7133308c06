"""Per-episode sea states of the ship tasks (:class:`SeaSampler`): irregular (JONSWAP) or regular
seas at a random relative heading, with Matusiak's start-up ramp.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from ship_gym.envs.validation import check_range, check_real
from ship_gym.waves.sea_state import steepness_error

if TYPE_CHECKING:
    from ship_gym.waves.wave_field import WaveField

_TWO_PI = 2.0 * math.pi

HEIGHT_LIMITS = (0.0, 30.0)
"""Accepted wave heights H or Hs [m]."""
PERIOD_LIMITS = (1.0, 40.0)
"""Accepted wave periods T or Tp [s]."""
HEADING_LIMITS = (-360.0, 720.0)
"""Accepted relative wave headings [deg]."""


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
    keywords : tuple of str
        The environment keyword arguments these fields came from, named in the errors (height
        range, period range, heading range, components, γ, spreading, ramp time).
    """

    kind: Literal["irregular", "regular"] = "irregular"
    height_range: tuple[float, float] = (3.0, 5.0)
    period_range: tuple[float, float] = (9.0, 12.0)
    heading_range_deg: tuple[float, float] = (0.0, 360.0)
    n_components: int = 40
    gamma: float = 3.3
    spreading_s: float | None = None
    ramp_time: float = 30.0
    keywords: tuple[str, ...] = field(
        default=(
            "height_range",
            "period_range",
            "heading_range_deg",
            "n_components",
            "gamma",
            "spreading_s",
            "ramp_time",
        ),
        compare=False,
    )

    def __post_init__(self) -> None:
        kh, kt, kb, kn, kg, ks, kr = self.keywords
        if self.kind not in ("irregular", "regular"):
            raise ValueError(f"sea kind must be 'irregular' or 'regular', got {self.kind!r}")
        h = check_range(
            kh, self.height_range, low=HEIGHT_LIMITS[0], high=HEIGHT_LIMITS[1], unit="m"
        )
        t = check_range(
            kt, self.period_range, low=PERIOD_LIMITS[0], high=PERIOD_LIMITS[1], unit="s"
        )
        b = check_range(
            kb, self.heading_range_deg, low=HEADING_LIMITS[0], high=HEADING_LIMITS[1], unit="deg"
        )
        object.__setattr__(self, "height_range", h)
        object.__setattr__(self, "period_range", t)
        object.__setattr__(self, "heading_range_deg", b)
        n = self.n_components
        if isinstance(n, bool) or not isinstance(n, int | np.integer) or not 1 <= n <= 1000:
            raise ValueError(f"{kn} must be an integer in 1…1000, got {n!r}")
        check_real(kg, self.gamma, low=1.0, high=20.0, unit="-", why=" (JONSWAP γ)")
        if self.spreading_s is not None:
            check_real(ks, self.spreading_s, low=0.0, high=1000.0, unit="-", why=" or None")
        check_real(kr, self.ramp_time, low=0.0, high=3600.0, unit="s")
        # the steepest corner of the ranges (largest height at the shortest period) is drawn
        error = steepness_error(self.kind, h[1], t[0], f"max of {kh}", f"min of {kt}")
        if error is not None:
            raise ValueError(error)

    @property
    def max_components(self) -> int:
        """Components of the largest sea drawn (the batch's padded count)."""
        return 1 if self.kind == "regular" else int(self.n_components)

    def check_options(self, options: dict[str, Any]) -> dict[str, float]:
        """The sea entries ``wave_height_m``, ``wave_period_s``, ``wave_heading_deg`` of
        ``reset(options=...)`` validated as the constructor validates the ranges (limits and
        steepness: a given height is checked against the given period, else against the
        shortest period of the range), as floats."""
        out: dict[str, float] = {}
        what = "H" if self.kind == "regular" else "Hs"
        if "wave_height_m" in options:
            out["wave_height_m"] = check_real(
                "options['wave_height_m']",
                options["wave_height_m"],
                low=HEIGHT_LIMITS[0],
                high=HEIGHT_LIMITS[1],
                unit="m",
                why=f" ({what} of this {self.kind} sea)",
            )
        if "wave_period_s" in options:
            out["wave_period_s"] = check_real(
                "options['wave_period_s']",
                options["wave_period_s"],
                low=PERIOD_LIMITS[0],
                high=PERIOD_LIMITS[1],
                unit="s",
                why=" (T)" if self.kind == "regular" else " (Tp)",
            )
        if "wave_heading_deg" in options:
            out["wave_heading_deg"] = check_real(
                "options['wave_heading_deg']",
                options["wave_heading_deg"],
                low=HEADING_LIMITS[0],
                high=HEADING_LIMITS[1],
                unit="deg",
            )
        if out:
            height = out.get("wave_height_m", self.height_range[1])
            if "wave_period_s" in out:
                period, pname = out["wave_period_s"], "options['wave_period_s']"
            else:
                period, pname = self.period_range[0], f"min of {self.keywords[1]}"
            hname = (
                "options['wave_height_m']"
                if "wave_height_m" in out
                else f"max of {self.keywords[0]}"
            )
            if "wave_height_m" in out or "wave_period_s" in out:
                error = steepness_error(self.kind, height, period, hname, pname)
                if error is not None:
                    raise ValueError(error)
        return out

    def sample(
        self, rng: np.random.Generator, fixed: dict[str, float] | None = None
    ) -> tuple[WaveField, dict[str, float]]:
        """One episode's wave field and its parameters (``wave_height_m``, ``wave_period_s``,
        ``wave_heading_deg``); ``fixed`` (from :meth:`check_options`) replaces drawn ones (the
        draws still happen, so the components and what follows are those of the same seed)."""
        from ship_gym.engine.ship import wave_field_for
        from ship_gym.waves.sea_state import IrregularSea, RegularWave

        height = float(rng.uniform(*self.height_range))
        period = float(rng.uniform(*self.period_range))
        heading_deg = float(rng.uniform(*self.heading_range_deg))
        if fixed:
            height = fixed.get("wave_height_m", height)
            period = fixed.get("wave_period_s", period)
            heading_deg = fixed.get("wave_heading_deg", heading_deg)
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
