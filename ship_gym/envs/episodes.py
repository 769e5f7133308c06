"""The episode sampler of the ship tasks: what an episode's generator draws before it starts.

An :class:`EpisodeSampler` is one component holding everything drawn per episode — the sea
(:class:`~ship_gym.envs.seas.SeaSampler`), the initial speed, the loading (GM) and, from the
loading, the capsize angle — with the limits that check them. :meth:`EpisodeSampler.draw`
returns an :class:`EpisodeDraw` for a batch of episodes; the task applies it to its simulator.
The draws happen in one fixed order per episode (sea, speed, GM) and always happen, so a reset
option that fixes one of them does not shift the random stream of the rest.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ship_gym.envs.config import CAPSIZE_ANGLE_LIMITS, GM_LIMITS, SPEED_LIMITS
from ship_gym.envs.validation import check_range, check_real

if TYPE_CHECKING:
    from ship_gym.envs.loading import LoadingCondition
    from ship_gym.envs.seas import SeaSampler
    from ship_gym.waves.wave_field import WaveField


@dataclass(frozen=True)
class EpisodeDraw:
    """What :meth:`EpisodeSampler.draw` drew for k episodes.

    Attributes
    ----------
    wave_fields : list of WaveField
        The episodes' seas.
    infos : list of dict
        The sea's reset info of each episode (``wave_height_m``, ``wave_period_s``,
        ``wave_heading_deg``).
    speed : NDArray
        (k,) initial surge speed [m/s].
    gm : NDArray
        (k,) GM of the loading [m].
    delta_kg : NDArray
        (k,) rise of G from the nominal loading, GM_nominal − GM [m].
    capsize_angle : NDArray
        (k,) capsize roll angle [rad].
    """

    wave_fields: list[WaveField]
    infos: list[dict[str, float]]
    speed: NDArray
    gm: NDArray
    delta_kg: NDArray
    capsize_angle: NDArray


class EpisodeSampler:
    """Sea, speed, loading and capsize angle of the episodes (module docstring).

    Parameters
    ----------
    sea : SeaSampler
        The episodes' seas.
    loading : LoadingCondition
        The nominal loading (GM [m], GZ curve, vanishing angle).
    nominal_speed : float
        The reference speed [m/s], the initial speed without ``speed_range``.
    speed_range : tuple of float or None
        Initial speed range [m/s], uniform (None: ``nominal_speed``).
    gm_range : tuple of float or None
        GM range [m], uniform (None: the nominal loading).
    capsize_angle_deg : float or None
        Fixed capsize angle [deg] (None: the vanishing angle of each episode's loading).
    """

    def __init__(
        self,
        sea: SeaSampler,
        loading: LoadingCondition,
        nominal_speed: float,
        *,
        speed_range: tuple[float, float] | None = None,
        gm_range: tuple[float, float] | None = None,
        capsize_angle_deg: float | None = None,
    ) -> None:
        self.sea = sea
        self.loading = loading
        self.nominal_speed = float(nominal_speed)
        if speed_range is not None:
            low, high = SPEED_LIMITS
            speed_range = check_range(
                "speed_range_mps", speed_range, low=low, high=high, unit="m/s"
            )
        self.speed_range = speed_range
        if gm_range is not None:
            low, high = GM_LIMITS
            gm_range = check_range("gm_range_m", gm_range, low=low, high=high, unit="m")
        self.gm_range = gm_range
        if capsize_angle_deg is not None:
            capsize_angle_deg = check_real(
                "capsize_angle_deg",
                capsize_angle_deg,
                low=CAPSIZE_ANGLE_LIMITS[0],
                high=CAPSIZE_ANGLE_LIMITS[1],
                unit="deg",
                low_open=True,
                why=" or None",
            )
        self.capsize_angle_deg = capsize_angle_deg

    @property
    def nominal_capsize_angle(self) -> float:
        """Capsize angle of the nominal loading [rad]."""
        deg = self.capsize_angle_deg
        return math.radians(deg or self.loading.vanishing_angle_deg)

    def draw(self, rngs: Sequence[np.random.Generator], options: Mapping[str, Any]) -> EpisodeDraw:
        """Draw the episodes of ``rngs`` (one generator each), then apply the checked reset
        ``options`` (``wave_*`` keys through the sea sampler, ``initial_speed_mps``, ``gm_m``)."""
        sea_opts = self.sea.check_options(dict(options))
        fields, infos = [], []
        k = len(rngs)
        speeds, gms = np.empty(k), np.empty(k)
        for j, rng in enumerate(rngs):
            wave_field, info = self.sea.sample(rng, sea_opts)
            fields.append(wave_field)
            infos.append(info)
            # the draws always happen, so an option does not shift the random stream
            speed_range, gm_range = self.speed_range, self.gm_range
            speeds[j] = float(rng.uniform(*speed_range)) if speed_range else self.nominal_speed
            gms[j] = float(rng.uniform(*gm_range)) if gm_range else self.loading.gm
        if "initial_speed_mps" in options:
            speeds[:] = options["initial_speed_mps"]
        if "gm_m" in options:
            gms[:] = options["gm_m"]
        delta_kg = self.loading.gm - gms  # G raised by ΔKG = GM_nominal − GM
        if self.capsize_angle_deg is None:
            capsize = self.loading.vanishing_angles(delta_kg)
        else:
            capsize = np.full(k, math.radians(self.capsize_angle_deg))
        return EpisodeDraw(fields, infos, speeds, gms, delta_kg, capsize)
