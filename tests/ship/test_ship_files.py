"""Ship files: reading and validation, loading defaults, appendage estimates, mesh symmetry and
the database-belongs-to-hull check."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from ship_gym.conventions import GRAVITY
from ship_gym.forces.fins import RollFins, TFoil
from ship_gym.forces.rudder import Rudder
from ship_gym.hull import equilibrium, hydrostatics, load_hull
from ship_gym.hull.mesh_io import read_mesh, write_mesh
from ship_gym.hydro import load_database
from ship_gym.hydro.bem import is_mirror_symmetric
from ship_gym.ship import (
    DatabaseMismatchError,
    ShipFileError,
    bundled_ships,
    check_database_matches,
    load_ship,
    read_ship,
)
from ship_gym.ship.appendages import fins_arguments, rudder_arguments, t_foil_arguments
from ship_gym.ship.model import mirror_symmetrised
from tests.ship.conftest import PATROL, SHIP_FILE


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "ship.toml"
    path.write_text(text)
    return path


# ---------------------------------------------------------------------------------- reading
@pytest.mark.parametrize(
    ("edit", "fragments"),
    [
        (("gm_m = 1.2", "gm_m = 1.2\nkg_m = 3.0"), ("kg_m or gm_m, not both",)),
        (("gm_m = 1.2", "gm_m = -1.0"), ("[loading] gm_m", "-1.0")),
        (("gm_m = 1.2", "gm = 1.2"), ("unknown [loading] key", "gm", "gm_m")),
        (('name = "patrol60"', 'name = "bad name!"'), ("name", "bad name!")),
        (('mesh = "patrol.stl"', 'mesh = "missing.stl"'), ("[hull] mesh", "missing.stl")),
        (('mesh = "patrol.stl"', 'mesh = "patrol.stl"\nlibrary = "s175"'), ("exactly one",)),
        (("n_omega = 10", "n_omega = 5"), ("n_omega", "5", "[10, 400]")),
        (("headings_deg = [0, 90, 180]", "headings_deg = [0, 360]"), ("repeated heading",)),
        (("service_froude = 0.3", "service_froude = 1.5"), ("service_froude", "1.5")),
        (("[speed]", "[speeds]"), ("unknown key", "speeds")),
        (("gm_m = 1.2", "gm_m = 1.2\n[rudder]\narea = 3.0"), ("[rudder]", "area_m2")),
    ],
)
def test_a_bad_field_is_named_as_written(patrol_ship: Path, edit, fragments):
    path = patrol_ship.parent / "bad.toml"
    path.write_text(SHIP_FILE.replace(*edit))
    with pytest.raises((ShipFileError, FileNotFoundError)) as info:
        read_ship(path)
    for fragment in fragments:
        assert fragment in str(info.value), (fragment, str(info.value))


def test_toml_syntax_errors_and_missing_tables_are_reported(tmp_path: Path):
    with pytest.raises(ShipFileError, match="not a valid TOML"):
        read_ship(_write(tmp_path, "name = \n"))
    with pytest.raises(ShipFileError, match=r"missing table \[hull\]"):
        read_ship(_write(tmp_path, 'name = "x"\n'))
    with pytest.raises(ShipFileError, match="cannot be given for a library hull"):
        read_ship(_write(tmp_path, 'name = "x"\n[hull]\nlibrary = "s175"\n[particulars]\n'
                                   "lpp_m = 100.0\n"))  # fmt: skip
    with pytest.raises(ShipFileError, match="needs \\[particulars\\] draught_m, depth_m"):
        header = "station,x_aft_of_midship_m,half_breadth_m,z_above_keel_m\n"
        (tmp_path / "o.csv").write_text(header)
        read_ship(_write(tmp_path, 'name = "x"\n[hull]\noffsets = "o.csv"\n'))


def test_a_mesh_hull_needs_the_height_of_g(patrol_ship: Path):
    path = patrol_ship.parent / "nokg.toml"
    path.write_text(SHIP_FILE.replace("gm_m = 1.2", "displacement_t = 900.0"))
    with pytest.raises(ShipFileError, match="needs kg_m or gm_m"):
        load_ship(path)
    path.write_text(SHIP_FILE.replace("gm_m = 1.2", "kg_m = 4.9"))
    with pytest.raises(ShipFileError, match=r"GM = .* <= 0"):
        load_ship(path)


def test_a_mesh_off_the_waterline_or_off_amidships_is_refused(patrol_ship: Path):
    shifted = patrol_ship.parent / "shifted.toml"
    shifted.write_text(SHIP_FILE.replace('mesh = "patrol.stl"', 'mesh = "patrol.stl"\n'
                                         "translate_m = [0.0, 0.0, 10.0]"))  # fmt: skip
    with pytest.raises(ShipFileError, match="design waterline z = 0 must cut it"):
        load_ship(shifted)
    shifted.write_text(SHIP_FILE.replace('mesh = "patrol.stl"', 'mesh = "patrol.stl"\n'
                                         "translate_m = [30.0, 0.0, 0.0]"))  # fmt: skip
    with pytest.raises(ShipFileError, match="translate_m = \\[-30"):
        load_ship(shifted)


# ------------------------------------------------------------------------- loading defaults
def test_loading_defaults_float_the_hull_level_at_its_design_draught(patrol_ship: Path):
    ship = load_ship(patrol_ship)
    hull = ship.hull
    p = hull.particulars
    # particulars measured on the mesh (triangulated, float32 STL: 1e-6 of the size)
    assert p.lpp == pytest.approx(PATROL["length"], rel=1e-6)
    assert p.beam == pytest.approx(PATROL["beam"], rel=1e-3)  # the widest station's offsets
    assert p.draught == pytest.approx(PATROL["draught"], rel=1e-6)
    assert p.depth == pytest.approx(PATROL["depth"], rel=1e-6)
    hs = hydrostatics(hull)
    # mass ρV at the design waterline, LCG at the LCB, KG from GM: no sinkage, no trim, GM given
    assert hull.mass.mass == pytest.approx(hull.rho * hs.volume, rel=1e-12)
    assert hs.gmt == pytest.approx(1.2, abs=1e-9)
    eq = equilibrium(hull)
    assert abs(eq.heave) < 1e-6 * p.draught and abs(eq.trim) < 1e-8
    # radii of gyration 0.35 B, 0.25 L, 0.25 L
    np.testing.assert_allclose(
        hull.mass.radii_of_gyration, [0.35 * p.beam, 0.25 * p.lpp, 0.25 * p.lpp], rtol=1e-12
    )


def test_overrides_replace_the_loading(patrol_ship: Path):
    base = load_ship(patrol_ship)
    heavier = load_ship(patrol_ship, displacement_t=1000.0, kg=2.5, radii_of_gyration=(3, 15, 15))
    assert heavier.hull.mass.mass == pytest.approx(1.0e6)
    assert heavier.hull.kg == pytest.approx(2.5)
    assert base.hull.mass.mass != heavier.hull.mass.mass
    with pytest.raises(ValueError, match="unknown override"):
        load_ship(patrol_ship, n_sections=30)


def test_a_bundled_library_ship_is_the_library_hull_with_the_force_model_defaults():
    assert {"s175", "box_barge", "hemisphere", "wigley"} <= set(bundled_ships())
    ship, hull = load_ship("s175"), load_hull("s175")
    np.testing.assert_array_equal(ship.hull.mesh.vertices, hull.mesh.vertices)
    np.testing.assert_array_equal(ship.hull.mass.inertia, hull.mass.inertia)
    assert ship.hull.mass.mass == hull.mass.mass
    assert load_ship("s175", kg=10.1).hull.kg == pytest.approx(10.1)
    assert ship.service_speed == pytest.approx(0.25 * math.sqrt(GRAVITY * 175.0), rel=1e-15)
    # the S175 file writes the models' documented S175 defaults
    for mine, default in ((ship.rudder(), Rudder()), (ship.fins(), RollFins()),
                          (ship.t_foil(), TFoil())):  # fmt: skip
        for a, b in zip(mine.surfaces, default.surfaces, strict=True):
            assert a.area == b.area and a.span == b.span
            np.testing.assert_array_equal(a.position, b.position)
    assert load_ship("box_barge").fins_arguments is None  # fitted = false


# ---------------------------------------------------------------------- appendage estimates
def test_the_estimates_give_the_s175_its_own_appendages():
    """The rules are calibrated on the S175's documented sizes: fed its particulars they must
    return them (rudder exactly by its L·T ratio; fins within 3 % from the heel-moment rule at
    22 kn, the speed of the S175 fins' design statement; T-foil within 0.1 % by similarity)."""
    hull = load_hull("s175")
    rudder, _ = rudder_arguments(hull, {}, None)
    assert rudder["area"] == pytest.approx(33.0376, rel=1e-4)
    assert rudder["x"] == -87.5 and rudder["z"] == pytest.approx(4.9, abs=0.01)
    fins, source = fins_arguments(hull, {}, speed=22 * 0.514444, gm=hydrostatics(hull).gmt,
                                  rho=hull.rho)  # fmt: skip
    assert fins["area"] == pytest.approx(10.0, rel=0.03)
    assert fins["y"] == pytest.approx(14.4, rel=0.01)
    assert set(source.values()) == {"estimated"}
    foil, _ = t_foil_arguments(hull, {})
    assert foil["area"] == pytest.approx(12.8, rel=1e-3)
    assert foil["x"] == pytest.approx(65.0, rel=2e-3)
    given, source = fins_arguments(hull, {"area_m2": 6.0}, speed=10.0, gm=1.0, rho=hull.rho)
    assert given["area"] == 6.0 and source["area"] == "given" and source["span"] == "estimated"


def test_fins_scale_with_the_righting_moment_they_must_balance(patrol_ship: Path):
    hull = load_ship(patrol_ship).hull
    slow, _ = fins_arguments(hull, {}, speed=7.0, gm=1.2, rho=hull.rho)
    fast, _ = fins_arguments(hull, {}, speed=9.0, gm=1.2, rho=hull.rho)
    # A_f ∝ 1/U² at a fixed arm; the arm grows with the span, so a little less than (9/7)²
    assert 1.5 < slow["area"] / fast["area"] < (9.0 / 7.0) ** 2
    # at 5 m/s the fins would be wider than 0.35 B: clipped, with their area
    clipped, _ = fins_arguments(hull, {}, speed=5.0, gm=1.2, rho=hull.rho)
    assert clipped["span"] == pytest.approx(0.35 * hull.particulars.beam)
    with pytest.raises(ValueError, match="GM"):
        fins_arguments(hull, {}, speed=5.0, gm=0.0, rho=hull.rho)


# ----------------------------------------------------------------------------- mesh symmetry
def test_a_triangulated_symmetric_hull_is_made_exactly_symmetric(tmp_path: Path):
    """An STL of a symmetric hull (triangles split along one diagonal, a transom across the
    centreline) becomes exactly mirror-symmetric, closed, with its volume kept to round-off."""
    from tests.ship.conftest import patrol_mesh

    write_mesh(patrol_mesh(), tmp_path / "p.stl", frame="z_up")
    raw = read_mesh(tmp_path / "p.stl")
    assert not is_mirror_symmetric(raw.vertices, raw.faces, 1)
    sym = mirror_symmetrised(raw)
    assert is_mirror_symmetric(sym.vertices, sym.faces, 1)
    sym.check(closed=True)
    assert sym.volume == pytest.approx(raw.volume, rel=1e-12)
    # an asymmetric hull is left as it is
    skew = read_mesh(tmp_path / "p.stl", translate=(0.0, 0.5, 0.0))
    assert mirror_symmetrised(skew) is skew


# --------------------------------------------------------------------- database membership
def test_a_database_of_another_hull_is_refused():
    s175_db = load_database("s175")
    with pytest.raises(DatabaseMismatchError, match="does not belong to hull 'box_barge'"):
        check_database_matches(load_hull("box_barge"), s175_db, "s175")
    # another mesh resolution or loading of the same hull is the same hull (< 1 % apart)
    check_database_matches(load_hull("s175", n_sections=50, n_below=10, kg=10.5), s175_db, "s175")


def test_the_simulator_refuses_a_foreign_database():
    from ship_gym.engine.ship import ShipSetup, build_simulator

    with pytest.raises(DatabaseMismatchError, match="box_barge"):
        build_simulator(ShipSetup(hull="box_barge", database="s175"))
