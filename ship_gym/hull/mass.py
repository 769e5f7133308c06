"""Rigid-body mass properties of a loading condition."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ship_gym.kinematics import skew


@dataclass(frozen=True, eq=False)
class MassProperties:
    """Mass, centre of gravity and inertia of a loaded ship.

    Parameters
    ----------
    mass : float
        Total mass [kg].
    cog : numpy.ndarray
        Centre of gravity G (3,) [m] in the body frame (z down from the design waterline).
    inertia : numpy.ndarray
        (3, 3) inertia tensor about G in body axes [kg·m²].
    """

    mass: float
    cog: np.ndarray
    inertia: np.ndarray

    def __post_init__(self) -> None:
        if not (np.isfinite(self.mass) and self.mass > 0.0):
            raise ValueError(f"mass must be a positive finite number [kg], got {self.mass!r}")
        cog = np.asarray(self.cog, dtype=float).reshape(-1)
        if cog.shape != (3,) or not np.all(np.isfinite(cog)):
            raise ValueError(f"cog must be 3 finite coordinates [m], got {self.cog!r}")
        inertia = np.asarray(self.inertia, dtype=float)
        if inertia.shape != (3, 3) or not np.allclose(inertia, inertia.T, rtol=1e-9, atol=0.0):
            raise ValueError("inertia must be a symmetric (3, 3) tensor [kg m^2]")
        if np.any(np.linalg.eigvalsh(inertia) <= 0.0):
            raise ValueError(
                f"inertia tensor must be positive definite, eigenvalues "
                f"{np.linalg.eigvalsh(inertia)} [kg m^2]"
            )
        for name, value in (("cog", cog), ("inertia", inertia)):
            value.flags.writeable = False
            object.__setattr__(self, name, value)
        object.__setattr__(self, "mass", float(self.mass))

    @classmethod
    def from_radii_of_gyration(
        cls, mass: float, cog: np.ndarray, radii: tuple[float, float, float]
    ) -> MassProperties:
        """Mass properties with a diagonal inertia tensor from radii of gyration.

        Parameters
        ----------
        mass : float
            Mass [kg].
        cog : numpy.ndarray
            Centre of gravity (3,) [m], body frame.
        radii : tuple of float
            Roll, pitch and yaw radii of gyration r44, r55, r66 about G [m].
        """
        r = np.asarray(radii, dtype=float)
        if r.shape != (3,) or np.any(r <= 0.0):
            raise ValueError(f"radii of gyration must be 3 positive lengths [m], got {radii!r}")
        return cls(mass, np.asarray(cog, dtype=float), np.diag(mass * r**2))

    @property
    def radii_of_gyration(self) -> np.ndarray:
        """Radii of gyration about G along the body axes [m]."""
        return np.sqrt(np.diag(self.inertia) / self.mass)

    def rigid_body_matrix(self, reference_point: np.ndarray | None = None) -> np.ndarray:
        """6×6 generalised mass matrix M_RB about a reference point (default: origin O).

        M_RB = [[m I, −m S(r_G)], [m S(r_G), I_G − m S(r_G)²]] with r_G the position of G relative
        to the reference point (Fossen 2011, eq. 3.44).
        """
        ref = np.zeros(3) if reference_point is None else np.asarray(reference_point, float)
        s = skew(self.cog - ref)
        m = self.mass
        out = np.zeros((6, 6))
        out[:3, :3] = m * np.eye(3)
        out[:3, 3:] = -m * s
        out[3:, :3] = m * s
        out[3:, 3:] = self.inertia - m * s @ s
        return out
