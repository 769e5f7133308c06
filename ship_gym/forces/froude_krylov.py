"""Nonlinear Froude–Krylov + hydrostatic force over the instantaneous wetted hull (stage 2).

The incident-wave and hydrostatic pressure (Wheeler-stretched in deep water, see
:mod:`ship_gym.waves`)

    p = ρ g (Z + Σⱼ Re[cⱼ(t) e^{−kⱼ d} e^{−i kⱼ (X cos χⱼ + Y sin χⱼ)}]),   d = Z + ζ(X, Y, t) ≥ 0,

is evaluated at the hull vertices in their instantaneous earth position (Z down, ζ up), and
integrated over the hull triangles below the incident-wave surface. Triangles crossing the surface
are cut where the submergence d changes sign (linear along each edge), not classified wet/dry by
centroid; the pressure vanishes on the cut. Pressure is taken linear over each (cut) triangle,
which integrates the hydrostatic part exactly; in calm water this is the same integral as
:func:`ship_gym.hull.hydrostatics.pressure_integral`, so the GZ curve is reproduced.

Two implementations, which the tests hold to 1e-6 relative agreement:

* ``method="fast"``: a numba kernel that evaluates the wave once per *vertex* (elevation and
  pressure share the per-component phasors), with branch-free polynomial sin/cos/exp that LLVM
  vectorises (:mod:`ship_gym.forces.fastmath`), and the time factor and the ship's horizontal
  position folded into one complex amplitude per component (no trig per component per step in
  Python). A batched variant loops over many ships in one call.
* ``method="reference"``: plain numpy (``np.cos``/``np.exp`` on the vertex × component matrix)
  with :func:`ship_gym.hull.mesh.clip_triangles` and
  :func:`ship_gym.hull.mesh.pressure_resultant`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numba as nb
import numpy as np

from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.forces.fastmath import exp_neg, sincos
from ship_gym.hull.hull import Hull
from ship_gym.hull.mesh import PanelMesh, clip_triangles, pressure_resultant
from ship_gym.waves.wave_field import WaveField

Method = Literal["fast", "reference"]


@dataclass(frozen=True, eq=False)
class HullPanels:
    """Triangulated hull geometry in the body frame, laid out for the kernels.

    Attributes
    ----------
    vertices : numpy.ndarray
        (n_vertices, 3) body-frame coordinates [m], C-contiguous float64.
    triangles : numpy.ndarray
        (n_triangles, 3) vertex indices (outward normals), int64.
    """

    vertices: np.ndarray
    triangles: np.ndarray

    @classmethod
    def from_mesh(cls, mesh: PanelMesh) -> HullPanels:
        """Triangulate a closed hull mesh (quads split along the diagonal (0, 2))."""
        mesh.check(closed=True)
        tri, _ = mesh.triangle_indices
        v = np.ascontiguousarray(mesh.vertices, dtype=np.float64)
        return cls(v, np.ascontiguousarray(tri, dtype=np.int64))


@dataclass(frozen=True, eq=False)
class WaveComponents:
    """Plain arrays of an incident wave for the kernels (one ship).

    Attributes
    ----------
    wavenumber : numpy.ndarray
        (n,) kⱼ [rad/m].
    cos_direction, sin_direction : numpy.ndarray
        (n,) cos χⱼ, sin χⱼ of the propagation directions (earth frame).
    """

    wavenumber: np.ndarray
    cos_direction: np.ndarray
    sin_direction: np.ndarray

    @classmethod
    def from_arrays(cls, wavenumber: np.ndarray, direction: np.ndarray) -> WaveComponents:
        """From kⱼ [rad/m] and χⱼ [rad]."""
        k = np.ascontiguousarray(wavenumber, dtype=np.float64)
        chi = np.asarray(direction, dtype=np.float64)
        if k.shape != chi.shape or k.ndim != 1:
            raise ValueError(
                f"wavenumber and direction must be 1-D of equal length, got {k.shape}, {chi.shape}"
            )
        return cls(k, np.ascontiguousarray(np.cos(chi)), np.ascontiguousarray(np.sin(chi)))

    def local_amplitudes(self, phasor: np.ndarray, x: float, y: float) -> np.ndarray:
        """Fold the ship's horizontal position into the complex amplitudes.

        cⱼ' = cⱼ(t) e^{−i kⱼ (x cos χⱼ + y sin χⱼ)}, so that the kernels see phases of the vertex
        positions *relative to O* only (small arguments, one complex exponential per component
        per step here instead of one per vertex and component there).

        Parameters
        ----------
        phasor : numpy.ndarray
            (n,) complex cⱼ(t) [m] with ζ = Re Σ cⱼ e^{−i kⱼ (X cos χⱼ + Y sin χⱼ)}.
        x, y : float
            Earth position of O [m].
        """
        s = self.wavenumber * (x * self.cos_direction + y * self.sin_direction)
        return np.asarray(phasor, dtype=np.complex128) * np.exp(-1j * s)


# ----------------------------------------------------------------------------- fast kernel
@nb.njit(fastmath={"contract", "nsz"}, cache=True)
def _fk_one_ship(
    vb: np.ndarray,
    tri: np.ndarray,
    rot: np.ndarray,
    z0: float,
    k: np.ndarray,
    cx: np.ndarray,
    sx: np.ndarray,
    cre: np.ndarray,
    cim: np.ndarray,
    rho_g: float,
    out: np.ndarray,
) -> None:  # pragma: no cover - compiled
    n_v = vb.shape[0]
    n_c = k.shape[0]
    rel = np.empty((n_v, 3))
    depth = np.empty(n_v)
    pres = np.empty(n_v)
    cbuf = np.empty(n_c)
    sbuf = np.empty(n_c)
    for v in range(n_v):
        bx, by, bz = vb[v, 0], vb[v, 1], vb[v, 2]
        rx = rot[0, 0] * bx + rot[0, 1] * by + rot[0, 2] * bz
        ry = rot[1, 0] * bx + rot[1, 1] * by + rot[1, 2] * bz
        rz = rot[2, 0] * bx + rot[2, 1] * by + rot[2, 2] * bz
        rel[v, 0] = rx
        rel[v, 1] = ry
        rel[v, 2] = rz
        zabs = z0 + rz
        _phasors(rx, ry, k, cx, sx, cbuf, sbuf)
        d = zabs + _dot2(cre, cbuf, cim, sbuf)
        depth[v] = d
        pres[v] = rho_g * (zabs + _decayed_dot2(k, d, cre, cbuf, cim, sbuf)) if d >= 0.0 else 0.0
    pa = np.empty((3, 3))
    pp = np.empty(3)
    for t in range(tri.shape[0]):
        i0, i1, i2 = tri[t, 0], tri[t, 1], tri[t, 2]
        d0, d1, d2 = depth[i0], depth[i1], depth[i2]
        w0, w1, w2 = d0 >= 0.0, d1 >= 0.0, d2 >= 0.0
        n_wet = int(w0) + int(w1) + int(w2)
        if n_wet == 0:
            continue
        # rotate so that the "odd" vertex (lone wet or lone dry) comes first
        if n_wet == 3 or (n_wet == 1 and w0) or (n_wet == 2 and not w0):
            a, b, c = i0, i1, i2
        elif (n_wet == 1 and w1) or (n_wet == 2 and not w1):
            a, b, c = i1, i2, i0
        else:
            a, b, c = i2, i0, i1
        if n_wet == 3:
            for q in range(3):
                pa[0, q] = rel[a, q]
                pa[1, q] = rel[b, q]
                pa[2, q] = rel[c, q]
            pp[0], pp[1], pp[2] = pres[a], pres[b], pres[c]
            _accumulate(pa, pp, out)
            continue
        da, db, dc = depth[a], depth[b], depth[c]
        sab = da / (da - db)
        sac = da / (da - dc)
        if n_wet == 1:
            for q in range(3):
                pa[0, q] = rel[a, q]
                pa[1, q] = rel[a, q] + sab * (rel[b, q] - rel[a, q])
                pa[2, q] = rel[a, q] + sac * (rel[c, q] - rel[a, q])
            pp[0], pp[1], pp[2] = pres[a], 0.0, 0.0
            _accumulate(pa, pp, out)
        else:
            for q in range(3):
                pa[0, q] = rel[a, q] + sab * (rel[b, q] - rel[a, q])
                pa[1, q] = rel[b, q]
                pa[2, q] = rel[c, q]
            pp[0], pp[1], pp[2] = 0.0, pres[b], pres[c]
            _accumulate(pa, pp, out)
            for q in range(3):
                pa[1, q] = rel[c, q]
                pa[2, q] = rel[a, q] + sac * (rel[c, q] - rel[a, q])
            pp[0], pp[1], pp[2] = 0.0, pres[c], 0.0
            _accumulate(pa, pp, out)
    return None


@nb.njit(fastmath={"contract", "nsz"}, cache=True)
def _phasors(
    rx: float,
    ry: float,
    k: np.ndarray,
    cx: np.ndarray,
    sx: np.ndarray,
    cbuf: np.ndarray,
    sbuf: np.ndarray,
) -> None:  # pragma: no cover - compiled
    """cos/sin of kⱼ (x cos χⱼ + y sin χⱼ) for all components (vectorised, no reduction)."""
    for j in range(k.shape[0]):
        s, c = sincos(k[j] * (rx * cx[j] + ry * sx[j]))
        cbuf[j] = c
        sbuf[j] = s


@nb.njit(fastmath={"contract", "nsz", "reassoc"}, cache=True)
def _dot2(a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray) -> float:  # pragma: no cover
    """Σ aⱼbⱼ + cⱼdⱼ = Re Σ (a + i c)(b − i d): the elevation (reassociated: vectorised sum)."""
    acc = 0.0
    for j in range(a.shape[0]):
        acc += a[j] * b[j] + c[j] * d[j]
    return acc


@nb.njit(fastmath={"contract", "nsz", "reassoc"}, cache=True)
def _decayed_dot2(
    k: np.ndarray, depth: float, a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray
) -> float:  # pragma: no cover - compiled
    """Σ e^{−kⱼ depth} (aⱼbⱼ + cⱼdⱼ): the Wheeler-stretched dynamic pressure head [m]."""
    acc = 0.0
    for j in range(k.shape[0]):
        acc += exp_neg(k[j] * depth) * (a[j] * b[j] + c[j] * d[j])
    return acc


@nb.njit(inline="always", fastmath={"contract", "nsz"}, cache=True)
def _accumulate(pa: np.ndarray, pp: np.ndarray, out: np.ndarray) -> None:  # pragma: no cover
    """Add −∫p n dS and −∫p r × n dS of one triangle (p linear) to out[0:3], out[3:6]."""
    e1x, e1y, e1z = pa[1, 0] - pa[0, 0], pa[1, 1] - pa[0, 1], pa[1, 2] - pa[0, 2]
    e2x, e2y, e2z = pa[2, 0] - pa[0, 0], pa[2, 1] - pa[0, 1], pa[2, 2] - pa[0, 2]
    nx = 0.5 * (e1y * e2z - e1z * e2y)
    ny = 0.5 * (e1z * e2x - e1x * e2z)
    nz = 0.5 * (e1x * e2y - e1y * e2x)
    psum = pp[0] + pp[1] + pp[2]
    pm = psum / 3.0
    out[0] -= pm * nx
    out[1] -= pm * ny
    out[2] -= pm * nz
    # ∫ p r dS / S = (Σ pᵢ rᵢ + Σpᵢ Σrᵢ) / 12
    qx = (
        pp[0] * pa[0, 0]
        + pp[1] * pa[1, 0]
        + pp[2] * pa[2, 0]
        + psum * (pa[0, 0] + pa[1, 0] + pa[2, 0])
    ) / 12.0
    qy = (
        pp[0] * pa[0, 1]
        + pp[1] * pa[1, 1]
        + pp[2] * pa[2, 1]
        + psum * (pa[0, 1] + pa[1, 1] + pa[2, 1])
    ) / 12.0
    qz = (
        pp[0] * pa[0, 2]
        + pp[1] * pa[1, 2]
        + pp[2] * pa[2, 2]
        + psum * (pa[0, 2] + pa[1, 2] + pa[2, 2])
    ) / 12.0
    out[3] -= qy * nz - qz * ny
    out[4] -= qz * nx - qx * nz
    out[5] -= qx * ny - qy * nx


@nb.njit(cache=True)
def _fk_batch(
    vb: np.ndarray,
    tri: np.ndarray,
    rot: np.ndarray,
    z0: np.ndarray,
    k: np.ndarray,
    cx: np.ndarray,
    sx: np.ndarray,
    cre: np.ndarray,
    cim: np.ndarray,
    rho_g: float,
    out: np.ndarray,
) -> None:  # pragma: no cover - compiled
    for s in range(rot.shape[0]):
        _fk_one_ship(vb, tri, rot[s], z0[s], k[s], cx[s], sx[s], cre[s], cim[s], rho_g, out[s])


# ----------------------------------------------------------------------------- public API
def froude_krylov_hydrostatic(
    panels: HullPanels,
    waves: WaveComponents,
    phasor: np.ndarray,
    position: np.ndarray,
    rotation: np.ndarray,
    *,
    rho: float,
    g: float,
    method: Method = "fast",
) -> np.ndarray:
    """Incident-wave + hydrostatic pressure force on the instantaneous wetted hull.

    Parameters
    ----------
    panels : HullPanels
        Triangulated closed hull (body frame).
    waves : WaveComponents
        Wavenumbers and directions of the incident components.
    phasor : numpy.ndarray
        (n,) complex amplitudes cⱼ(t) [m] (ramp included): ζ = Re Σ cⱼ e^{−i kⱼ(X cos χⱼ +
        Y sin χⱼ)}. Zeros give calm water.
    position : numpy.ndarray
        (3,) earth position of O [m] (NED, z down).
    rotation : numpy.ndarray
        (3, 3) body-to-earth rotation matrix.
    rho, g : float
        Water density [kg/m³] and gravity [m/s²].
    method : {"fast", "reference"}
        Numba kernel or numpy reference implementation.

    Returns
    -------
    numpy.ndarray
        (6,) force [N] and moment about O [N·m], in **earth** axes.
    """
    position = np.asarray(position, dtype=np.float64)
    rotation = np.ascontiguousarray(rotation, dtype=np.float64)
    amp = waves.local_amplitudes(phasor, position[0], position[1])
    if method == "fast":
        out = np.zeros(6)
        _fk_one_ship(
            panels.vertices,
            panels.triangles,
            rotation,
            float(position[2]),
            waves.wavenumber,
            waves.cos_direction,
            waves.sin_direction,
            np.ascontiguousarray(amp.real),
            np.ascontiguousarray(amp.imag),
            rho * g,
            out,
        )
        return out
    if method == "reference":
        return _reference(panels, waves, amp, position, rotation, rho, g)
    raise ValueError(f"method must be 'fast' or 'reference', got {method!r}")


def froude_krylov_hydrostatic_batch(
    panels: HullPanels,
    wavenumber: np.ndarray,
    cos_direction: np.ndarray,
    sin_direction: np.ndarray,
    local_amplitude: np.ndarray,
    depth_of_origin: np.ndarray,
    rotation: np.ndarray,
    *,
    rho: float,
    g: float,
) -> np.ndarray:
    """Batched fast kernel: many ships (same hull) in one call.

    Parameters
    ----------
    panels : HullPanels
        Shared hull geometry.
    wavenumber, cos_direction, sin_direction : numpy.ndarray
        (n_ships, n) wave arrays of each ship's sea.
    local_amplitude : numpy.ndarray
        (n_ships, n) complex amplitudes with each ship's horizontal position folded in
        (:meth:`WaveComponents.local_amplitudes`).
    depth_of_origin : numpy.ndarray
        (n_ships,) earth z of each ship's O [m].
    rotation : numpy.ndarray
        (n_ships, 3, 3) body-to-earth rotations.

    Returns
    -------
    numpy.ndarray
        (n_ships, 6) force and moment about O in earth axes.
    """
    n = rotation.shape[0]
    out = np.zeros((n, 6))
    amp = np.asarray(local_amplitude, dtype=np.complex128)
    _fk_batch(
        panels.vertices,
        panels.triangles,
        np.ascontiguousarray(rotation, dtype=np.float64),
        np.ascontiguousarray(depth_of_origin, dtype=np.float64),
        np.ascontiguousarray(wavenumber, dtype=np.float64),
        np.ascontiguousarray(cos_direction, dtype=np.float64),
        np.ascontiguousarray(sin_direction, dtype=np.float64),
        np.ascontiguousarray(amp.real),
        np.ascontiguousarray(amp.imag),
        rho * g,
        out,
    )
    return out


def _reference(
    panels: HullPanels,
    waves: WaveComponents,
    amp: np.ndarray,
    position: np.ndarray,
    rotation: np.ndarray,
    rho: float,
    g: float,
) -> np.ndarray:
    rel = panels.vertices @ rotation.T
    z = position[2] + rel[:, 2]
    phase = waves.wavenumber[None, :] * (
        rel[:, 0:1] * waves.cos_direction[None, :] + rel[:, 1:2] * waves.sin_direction[None, :]
    )
    spatial = np.cos(phase) * amp.real[None, :] + np.sin(phase) * amp.imag[None, :]
    depth = z + spatial.sum(axis=1)
    decay = np.exp(-np.outer(np.clip(depth, 0.0, None), waves.wavenumber))
    pressure = np.where(depth >= 0.0, rho * g * (z + (decay * spatial).sum(axis=1)), 0.0)
    idx = panels.triangles
    wet, _, _, p_wet = clip_triangles(rel[idx], depth[idx], pressure[idx])
    force, moment = pressure_resultant(wet, p_wet, np.zeros(3))
    return np.concatenate([force, moment])


class FroudeKrylovHydrostatics(ForceModel):
    """Force model: nonlinear incident-wave + hydrostatic pressure on the instantaneous hull.

    Parameters
    ----------
    hull : Hull
        Hull with its closed mesh (to the deck).
    wave_field : WaveField or None
        Incident waves (None: calm water, pure hydrostatics).
    method : {"fast", "reference"}
        Kernel implementation.

    Notes
    -----
    The force is returned in body axes about O: F_b = Rᵀ F_e, M_b = Rᵀ M_e.
    """

    name = "froude_krylov_hydrostatic"

    def __init__(self, hull: Hull, wave_field: WaveField | None = None, *, method: Method = "fast"):
        if method not in ("fast", "reference"):
            raise ValueError(f"method must be 'fast' or 'reference', got {method!r}")
        self.hull = hull
        self.method: Method = method
        self.panels = HullPanels.from_mesh(hull.mesh)
        self.wave_field = wave_field
        if wave_field is None or wave_field.n_components == 0:
            self.waves = WaveComponents.from_arrays(np.zeros(1), np.zeros(1))
        else:
            self.waves = WaveComponents.from_arrays(wave_field.wavenumber, wave_field.direction)
        self._calm = np.zeros(self.waves.wavenumber.shape, dtype=np.complex128)

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Body-axis force and moment about O (see :func:`froude_krylov_hydrostatic`)."""
        phasor = self._calm if ctx.wave_phasor is None else ctx.wave_phasor
        f = froude_krylov_hydrostatic(
            self.panels,
            self.waves,
            phasor,
            ctx.eta[:3],
            ctx.rotation,
            rho=self.hull.rho,
            g=self.hull.g,
            method=self.method,
        )
        rt = ctx.rotation.T
        return np.concatenate([rt @ f[:3], rt @ f[3:]]), _NO_STATES


_NO_STATES = np.zeros(0)
