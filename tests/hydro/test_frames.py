"""Change of frame between capytaine (x fwd, y port, z up) and ship_gym (x fwd, y stbd, z down)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

from ship_gym.conventions import BODY_FRAME, CAPYTAINE_DOF_SIGNS, DOF_NAMES
from ship_gym.hydro import frames


def _capytaine_like_dataset(rng: np.random.Generator) -> xr.Dataset:
    n_w, n_b = 3, 4
    a = rng.normal(size=(n_w, 6, 6))
    f = rng.normal(size=(n_w, n_b, 6)) + 1j * rng.normal(size=(n_w, n_b, 6))
    return xr.Dataset(
        {
            "added_mass": (("omega", "influenced_dof", "radiating_dof"), a),
            "excitation_force": (("omega", "wave_direction", "influenced_dof"), f),
            "center_of_mass": (("space_coordinate",), np.array([1.0, 2.0, 3.0])),
        },
        coords={
            "omega": [0.5, 1.0, 2.0],
            "wave_direction": [0.0, 0.5 * np.pi, np.pi, 1.25 * np.pi],
            "influenced_dof": list(DOF_NAMES),
            "radiating_dof": list(DOF_NAMES),
            "space_coordinate": ["x", "y", "z"],
            "rotation_center": ("space_coordinate", [0.5, -1.0, 2.0]),
        },
    )


def test_dof_signs_follow_the_rotation_about_x() -> None:
    np.testing.assert_array_equal(frames.dof_signs(DOF_NAMES), CAPYTAINE_DOF_SIGNS)
    np.testing.assert_array_equal(frames.dof_signs(["heave", "ROLL"]), [-1.0, 1.0])
    with pytest.raises(ValueError, match="'Bending'"):
        frames.dof_signs(["Heave", "Bending"])


def test_wave_direction_map_is_an_involution_onto_0_2pi() -> None:
    beta = np.linspace(-3 * np.pi, 3 * np.pi, 37)
    there = frames.wave_direction_to_capytaine(beta)
    back = frames.wave_direction_from_capytaine(there)
    assert np.all((there >= 0.0) & (there < 2 * np.pi))
    np.testing.assert_allclose(np.cos(back), np.cos(beta), atol=1e-12)
    np.testing.assert_allclose(np.sin(back), np.sin(beta), atol=1e-12)
    # head and following seas are the same in both frames; beam seas swap sides
    assert frames.wave_direction_from_capytaine(0.0) == 0.0
    assert frames.wave_direction_from_capytaine(np.pi) == pytest.approx(np.pi)
    assert frames.wave_direction_from_capytaine(0.5 * np.pi) == pytest.approx(1.5 * np.pi)


def test_heading_convention_against_capytaine_incident_wave() -> None:
    """Our β = 90° wave travels toward starboard in capytaine's own incident-wave formula.

    capytaine (airy_waves.py) gives the complex elevation η̂(p) with η(t) = Re(η̂ e^{-iωt}), crest
    at O at t = 0. A wave travelling toward starboard has its crest at y_ours = d at
    t = k d / ω, so η̂ at that point must be e^{+ikd}; at the port point, e^{-ikd}.
    """
    from capytaine.bem.airy_waves import airy_waves_free_surface_elevation

    g, omega = 9.81, 1.3
    k = omega**2 / g
    d = 0.7
    for beta_ours, direction in ((0.5 * np.pi, (0.0, 1.0)), (np.pi, (-1.0, 0.0)), (0.3, None)):
        if direction is None:
            direction = (np.cos(beta_ours), np.sin(beta_ours))
        pb = SimpleNamespace(
            wavenumber=k,
            water_depth=np.inf,
            encounter_wave_direction=frames.wave_direction_to_capytaine(beta_ours),
            wave_direction=frames.wave_direction_to_capytaine(beta_ours),
            g=g,
            omega=omega,
        )
        ahead = d * np.array([direction[0], direction[1], 0.0])  # our frame
        behind = -ahead
        pts_capy = frames.points_to_capytaine(np.array([ahead, behind]))
        eta = airy_waves_free_surface_elevation(pts_capy, pb)
        np.testing.assert_allclose(eta, [np.exp(1j * k * d), np.exp(-1j * k * d)], atol=1e-12)


def test_points_vectors_and_matrices() -> None:
    np.testing.assert_array_equal(frames.points_from_capytaine([1.0, 2.0, 3.0]), [1, -2, -3])
    v = np.arange(1.0, 7.0)
    np.testing.assert_array_equal(frames.vector_from_capytaine(v), v * CAPYTAINE_DOF_SIGNS)
    m = np.arange(36.0).reshape(6, 6)
    out = frames.matrix_from_capytaine(m)
    np.testing.assert_array_equal(out, m * np.outer(CAPYTAINE_DOF_SIGNS, CAPYTAINE_DOF_SIGNS))
    np.testing.assert_array_equal(frames.matrix_to_capytaine(out), m)
    # a positive heave stiffness stays positive; heave-pitch coupling keeps its sign (s3 s5 = 1)
    assert out[2, 2] == m[2, 2] and out[2, 4] == m[2, 4] and out[2, 3] == -m[2, 3]
    with pytest.raises(ValueError, match="length 3"):
        frames.points_from_capytaine(np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"\(6, 6\)"):
        frames.matrix_from_capytaine(np.zeros((3, 3)))


def test_dataset_conversion_and_round_trip() -> None:
    ds = _capytaine_like_dataset(np.random.default_rng(0))
    ours = frames.dataset_from_capytaine(ds)
    assert ours.attrs["frame"] == BODY_FRAME
    s = CAPYTAINE_DOF_SIGNS
    np.testing.assert_allclose(ours.added_mass.values, ds.added_mass.values * np.outer(s, s))
    # capytaine directions 0, π/2, π, 5π/4 → ours 0, 3π/2, π, 3π/4, sorted: 0, 3π/4, π, 3π/2
    np.testing.assert_allclose(ours.wave_direction.values, [0, 0.75 * np.pi, np.pi, 1.5 * np.pi])
    np.testing.assert_allclose(
        ours.excitation_force.sel(wave_direction=1.5 * np.pi).values,
        ds.excitation_force.sel(wave_direction=0.5 * np.pi).values * s,
    )
    np.testing.assert_allclose(ours.center_of_mass.values, [1.0, -2.0, -3.0])
    np.testing.assert_allclose(ours.rotation_center.values, [0.5, 1.0, -2.0])
    assert np.iscomplexobj(ours.excitation_force.values)  # no conjugation, still complex
    back = frames.dataset_to_capytaine(ours)
    xr.testing.assert_allclose(back.drop_attrs(), ds.sortby("wave_direction").drop_attrs())


def test_dataset_conversion_refuses_double_conversion_and_unknown_frames() -> None:
    ds = _capytaine_like_dataset(np.random.default_rng(1))
    ours = frames.dataset_from_capytaine(ds)
    with pytest.raises(ValueError, match="already in the ship_gym body frame"):
        frames.dataset_from_capytaine(ours)
    with pytest.raises(ValueError, match="expected the ship_gym body frame"):
        frames.dataset_to_capytaine(ds)
    bad = ds.assign_coords(influenced_dof=["Surge", "Sway", "Heave", "Roll", "Pitch", "Flex"])
    with pytest.raises(ValueError, match="'Flex'"):
        frames.dataset_from_capytaine(bad)
    with pytest.raises(ValueError, match=r"xarray\.Dataset"):
        frames.dataset_from_capytaine(ds.added_mass)  # type: ignore[arg-type]


def test_mirror_signs_are_the_reflection_in_y() -> None:
    # reflection y → -y: forces (x, -y, z), moments as pseudo-vectors (-x, y, -z)
    np.testing.assert_array_equal(frames.mirror_signs(), [1, -1, 1, -1, 1, -1])
