"""WAMIT .1/.3/.hst import: scaling, time convention, heading and frame conversion."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from ship_gym.conventions import BODY_FRAME, DOF_NAMES
from ship_gym.hydro import frames
from ship_gym.hydro.wamit import read_wamit, read_wamit_1

RHO, G = 1025.0, 9.81
S = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])  # our DOF = S * WAMIT DOF (y, z flipped)
ROT = np.array([0, 0, 0, 1, 1, 1])


def known_database(seed: int = 0) -> xr.Dataset:
    """Symmetric A, B with zero/infinite limits, complex excitation, stiffness; our frame."""
    rng = np.random.default_rng(seed)
    w = np.array([0.3, 0.7, 1.1, 1.9])
    omega = np.concatenate([[0.0], w, [np.inf]])
    scale = np.sqrt(np.array([1e5, 2e5, 3e5, 4e6, 5e8, 6e8]))

    def sym(n: int) -> np.ndarray:
        x = rng.normal(size=(n, 6, 6))
        return (x + np.swapaxes(x, 1, 2)) * np.outer(scale, scale)

    a = sym(len(omega))
    b = np.abs(sym(len(omega)))
    b[0] = b[-1] = 0.0
    beta = np.deg2rad([0.0, 60.0, 90.0, 180.0, 300.0])
    f = rng.normal(size=(len(omega), len(beta), 6)) + 1j * rng.normal(size=(len(omega), 5, 6))
    f *= scale * 1e2
    f[0] = f[-1] = np.nan
    c = rng.normal(size=(6, 6)) * np.outer(scale, scale)
    dims3 = ("omega", "influenced_dof", "radiating_dof")
    return xr.Dataset(
        {
            "added_mass": (dims3, a),
            "radiation_damping": (dims3, b),
            "excitation_force": (("omega", "wave_direction", "influenced_dof"), f),
            "hydrostatic_stiffness": (("influenced_dof", "radiating_dof"), c),
        },
        coords={
            "omega": omega,
            "wave_direction": beta,
            "influenced_dof": list(DOF_NAMES),
            "radiating_dof": list(DOF_NAMES),
        },
    )


def write_wamit_files(ds: xr.Dataset, prefix: Path, ulen: float) -> None:
    """Independent writer following the WAMIT manual (used to test the reader)."""
    omega = ds.omega.values
    a, b = ds.added_mass.values, ds.radiation_damping.values
    lines1 = []
    for n, w in enumerate(omega):
        for i in range(6):
            for j in range(6):
                k = 3 + ROT[i] + ROT[j]
                a_nd = S[i] * S[j] * a[n, i, j] / (RHO * ulen**k)
                if w == 0.0:
                    lines1.append(f"{-1.0:14.6E}{i + 1:6d}{j + 1:6d}{a_nd:18.10E}\n")
                elif np.isinf(w):
                    lines1.append(f"{0.0:14.6E}{i + 1:6d}{j + 1:6d}{a_nd:18.10E}\n")
                else:
                    b_nd = S[i] * S[j] * b[n, i, j] / (RHO * w * ulen**k)
                    per = 2 * np.pi / w
                    lines1.append(f"{per:18.10E}{i + 1:6d}{j + 1:6d}{a_nd:18.10E}{b_nd:18.10E}\n")
    Path(f"{prefix}.1").write_text("".join(lines1))
    lines3 = ["  PER   BETA   I   Mod   Pha   Re   Im  (header line)\n"]
    for n, w in enumerate(omega):
        if not (np.isfinite(w) and w > 0):
            continue
        for m, beta in enumerate(ds.wave_direction.values):
            beta_w = np.rad2deg(np.mod(-beta, 2 * np.pi))  # WAMIT: from +x toward +y = port
            for i in range(6):
                x = np.conj(S[i] * ds.excitation_force.values[n, m, i])  # Re(X e^{+iωt})
                x_nd = x / (RHO * G * ulen ** (2 + ROT[i]))
                lines3.append(
                    f"{2 * np.pi / w:18.10E}{beta_w:18.10E}{i + 1:6d}{abs(x_nd):18.10E}"
                    f"{np.rad2deg(np.angle(x_nd)):14.6F}{x_nd.real:18.10E}{x_nd.imag:18.10E}\n"
                )
    Path(f"{prefix}.3").write_text("".join(lines3))
    c = ds.hydrostatic_stiffness.values
    lines_h = []
    for i in range(6):
        for j in range(6):
            c_nd = S[i] * S[j] * c[i, j] / (RHO * G * ulen ** (2 + ROT[i] + ROT[j]))
            lines_h.append(f"{i + 1:6d}{j + 1:6d}{c_nd:18.10E}\n")
    Path(f"{prefix}.hst").write_text("".join(lines_h))


def test_round_trip_through_wamit_files(tmp_path: Path) -> None:
    ds = known_database()
    write_wamit_files(ds, tmp_path / "ship", ulen=3.5)
    back = read_wamit(tmp_path / "ship", rho=RHO, g=G, ulen=3.5)
    assert back.attrs["frame"] == BODY_FRAME
    np.testing.assert_allclose(back.omega.values, ds.omega.values, rtol=1e-9)
    for name in ("added_mass", "radiation_damping", "hydrostatic_stiffness"):
        np.testing.assert_allclose(back[name].values, ds[name].values, rtol=1e-9)
    np.testing.assert_allclose(back.wave_direction.values, ds.wave_direction.values, atol=1e-9)
    np.testing.assert_allclose(
        back.excitation_force.values[1:-1], ds.excitation_force.values[1:-1], rtol=1e-9
    )
    assert np.all(np.isnan(back.excitation_force.values[[0, -1]]))
    np.testing.assert_allclose(back.period.values[[0, -1]], [np.inf, 0.0])


def test_agrees_with_capytaine_wamit_exporter(tmp_path: Path) -> None:
    """capytaine's own WAMIT export of a capytaine-frame dataset reads back as our conversion."""
    from capytaine.io.wamit import export_to_wamit

    ours = known_database(seed=4)
    ours.attrs["frame"] = BODY_FRAME
    capy = frames.dataset_to_capytaine(ours)
    with np.errstate(divide="ignore"):
        capy = capy.assign_coords(
            period=("omega", 2 * np.pi / capy.omega.values), rho=RHO, g=G, forward_speed=0.0
        )
    export_to_wamit(capy, str(tmp_path / "cpt"), exports=("1", "3", "hst"))
    back = read_wamit(tmp_path / "cpt", rho=RHO, g=G)
    for name in ("added_mass", "radiation_damping", "hydrostatic_stiffness"):
        np.testing.assert_allclose(back[name].values, ours[name].values, rtol=2e-6, atol=1e-3)
    np.testing.assert_allclose(back.wave_direction.values, ours.wave_direction.values, atol=1e-7)
    f_ref = ours.excitation_force.values[1:-1]
    np.testing.assert_allclose(
        back.excitation_force.values[1:-1], f_ref, rtol=2e-6, atol=1e-6 * np.abs(f_ref).max()
    )


def test_zero_and_infinite_period_rows(tmp_path: Path) -> None:
    path = tmp_path / "x.1"
    path.write_text(
        "  -1.0  3  3  2.0\n"  # PER = -1: infinite period, omega = 0
        "   0.0  3  3  0.5\n"  # PER = 0: zero period, omega = inf
        "   6.283185307179586  3  3  1.0  0.25\n"
    )
    omega, a, b = read_wamit_1(path, rho=1000.0, ulen=2.0)
    np.testing.assert_allclose(omega, [0.0, 1.0, np.inf])
    np.testing.assert_allclose(a[:, 2, 2], np.array([2.0, 1.0, 0.5]) * 1000.0 * 2.0**3)
    np.testing.assert_allclose(b[:, 2, 2], [0.0, 0.25 * 1000.0 * 1.0 * 8.0, 0.0])


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("  6.0  7  1  1.0  1.0\n", "mode index 7"),
        ("  6.0  1  1  1.0  1.0\n  oops here\n", "line 2"),
        ("  -2.0  1  1  1.0\n", "negative period"),
        ("  6.0  1  1  1.0\n", "without damping"),
        ("  6.0  1\n", "at least 4 columns"),
        ("just a header\n", "no numeric data"),
    ],
)
def test_malformed_files_are_rejected(tmp_path: Path, content: str, message: str) -> None:
    path = tmp_path / "bad.1"
    path.write_text(content)
    with pytest.raises(ValueError, match=message):
        read_wamit(file_1=path, rho=RHO, g=G)


def test_parameter_errors(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"missing\.1"):
        read_wamit(tmp_path / "missing", rho=RHO, g=G)
    with pytest.raises(ValueError, match="ulen"):
        read_wamit(tmp_path / "missing", rho=RHO, g=G, ulen=-1.0)
    with pytest.raises(ValueError, match="period_column"):
        read_wamit_1(tmp_path / "x.1", rho=RHO, period_column="hz")
    (tmp_path / "w.1").write_text("  1.5  1  1  1.0  1.0\n")
    ds = read_wamit(file_1=tmp_path / "w.1", rho=RHO, g=G, period_column="omega")
    assert ds.omega.values.tolist() == [1.5]
    assert ds.added_mass.values[0, 0, 0] == pytest.approx(RHO)
    (tmp_path / "z.1").write_text("  0.0  1  1  1.0\n")
    with pytest.raises(ValueError, match="must be > 0"):
        read_wamit(file_1=tmp_path / "z.1", rho=RHO, g=G, period_column="omega")
    with pytest.raises(ValueError, match=r"\(6, 6\)"):
        read_wamit(file_1=tmp_path / "w.1", rho=RHO, g=G, period_column="omega",
                   inertia_matrix=np.eye(3))  # fmt: skip
