"""``components.ID.geometry`` (volume, Pan & Wang 2019): shapes, keys, units, checks."""
from __future__ import annotations

import dataclasses

import pytest

from powergraph.errors import ModelError
from powergraph.model import loads_model
from powergraph.model.block_geometry import (
    SHAPES,
    CrankshaftGeometry,
    CycloidDiscGeometry,
    GearGeometry,
    NeedleGearGeometry,
    PlanetFrame1Geometry,
    PlanetFrame2Geometry,
)
from powergraph.model.blocks import validate_geometry

PATH = "components.4.geometry"

VALID = {
    "gear": {"shape": "gear", "module": 1.5, "face_width": 12, "bore_radius": 0},
    "cycloid_disc": {"shape": "cycloid_disc", "width": 10, "pin_circle_radius": 64,
                     "pin_radius": 3, "eccentricity": 1.3, "crank_hole_radius": 17,
                     "crank_holes": 2, "pillar_radius": 9, "pillar_holes": 2,
                     "center_bore_radius": 15},
    "needle_gear": {"shape": "needle_gear", "width": 20, "pin_circle_radius": 64,
                    "pin_radius": 3, "shell_thickness": 10},
    "crankshaft": {"shape": "crankshaft", "shaft_radius": 10, "gear_seat_length": 12,
                   "bearing_width": 12, "journal_radius": 13, "journal_length": 10,
                   "journals": 2},
    "planet_frame_1": {"shape": "planet_frame_1", "bearing_seat_radius": 58,
                       "bearing_width": 14, "crank_bearing_radius": 18.5,
                       "crank_bearing_width": 12, "crank_bearings": 2},
    "planet_frame_2": {"shape": "planet_frame_2", "seal_radius": 50,
                       "bearing_seat_radius": 58, "bearing_width": 14,
                       "crank_bearing_radius": 18.5, "crank_bearing_width": 12,
                       "crank_bearings": 2, "pillar_radius": 9, "pillars": 2,
                       "pillar_length": 20, "sun": 1, "planet": "2"},
}
CLASSES = {"gear": GearGeometry, "cycloid_disc": CycloidDiscGeometry,
           "needle_gear": NeedleGearGeometry, "crankshaft": CrankshaftGeometry,
           "planet_frame_1": PlanetFrame1Geometry, "planet_frame_2": PlanetFrame2Geometry}


def with_(shape: str, **changes):
    raw = dict(VALID[shape])
    for key, value in changes.items():
        if value is None:
            raw.pop(key)
        else:
            raw[key] = value
    return raw


def error_of(raw, teeth=None) -> ModelError:
    with pytest.raises(ModelError) as info:
        validate_geometry(raw, PATH, teeth=teeth)
    return info.value


@pytest.mark.parametrize("shape", list(VALID))
def test_every_shape_validates_to_a_frozen_dataclass(shape) -> None:
    geometry = validate_geometry(VALID[shape], PATH)
    assert type(geometry) is CLASSES[shape] and SHAPES[shape] is CLASSES[shape]
    assert geometry.shape == shape
    with pytest.raises(dataclasses.FrozenInstanceError):
        geometry.width = 1.0  # type: ignore[misc]
    data = geometry.to_dict()
    assert data["shape"] == shape
    assert set(data) == set(VALID[shape])


def test_values_are_floats_counts_ints_and_refs_strings() -> None:
    frame = validate_geometry(VALID["planet_frame_2"], PATH)
    assert frame.seal_radius == 50.0 and isinstance(frame.seal_radius, float)
    assert frame.pillars == 2 and isinstance(frame.pillars, int)
    assert (frame.sun, frame.planet) == ("1", "2")


def test_lengths_accept_units() -> None:
    gear = validate_geometry(with_("gear", module="1.5 mm", face_width="1.2 cm",
                                   bore_radius="0.004 m"), PATH)
    assert gear.module == pytest.approx(1.5)
    assert gear.face_width == pytest.approx(12.0)
    assert gear.bore_radius == pytest.approx(4.0)


@pytest.mark.parametrize("raw, where, words", [
    ("not a mapping", PATH, "mapping"),
    ({"module": 1}, f"{PATH}.shape", "missing"),
    ({"shape": "spline"}, f"{PATH}.shape", "unknown shape"),
    ({"shape": 3}, f"{PATH}.shape", "unknown shape"),
    (with_("gear", teeth=12), f"{PATH}.teeth", "unknown field"),
    (with_("gear", bore_radius=None), f"{PATH}.bore_radius", "missing"),
    (with_("gear", module=-1.5), f"{PATH}.module", "> 0"),
    (with_("gear", module=0), f"{PATH}.module", "> 0"),
    (with_("gear", bore_radius=-1), f"{PATH}.bore_radius", ">= 0"),
    (with_("gear", face_width="12 N*m"), f"{PATH}.face_width", "not a length"),
    (with_("gear", face_width=True), f"{PATH}.face_width", "length"),
    (with_("crankshaft", journals=0), f"{PATH}.journals", "integer >= 1"),
    (with_("crankshaft", journals=2.0), f"{PATH}.journals", "integer"),
    (with_("crankshaft", journals=True), f"{PATH}.journals", "integer"),
    (with_("cycloid_disc", pillar_holes=-1), f"{PATH}.pillar_holes", "integer >= 0"),
    (with_("planet_frame_2", sun=[1]), f"{PATH}.sun", "component id"),
])
def test_bad_blocks_name_the_key(raw, where, words) -> None:
    error = error_of(raw)
    assert error.path == where
    assert words in error.message


def test_zero_pillar_holes_and_zero_bore_are_allowed() -> None:
    disc = validate_geometry(with_("cycloid_disc", pillar_holes=0, center_bore_radius=0),
                             PATH)
    assert disc.pillar_holes == 0 and disc.center_bore_radius == 0.0


@pytest.mark.parametrize("changes, key", [
    # root radius r_p − a − r_rp = 64 − 1.3 − 3 = 59.7: every hole must be smaller
    ({"center_bore_radius": 59.7}, "center_bore_radius"),
    ({"crank_hole_radius": 60}, "crank_hole_radius"),
    ({"pillar_radius": 58.5}, "pillar_radius"),          # 58.5 + a = 59.8
    ({"pin_circle_radius": 4}, "pin_circle_radius"),     # 4 − 1.3 − 3 < 0: no root circle
])
def test_cycloid_disc_impossible_dimensions(changes, key) -> None:
    assert error_of(with_("cycloid_disc", **changes)).path == f"{PATH}.{key}"


def test_cycloid_short_width_coefficient_needs_teeth() -> None:
    raw = with_("cycloid_disc", eccentricity=1.7)        # 1.7·40/64 = 1.0625 ≥ 1
    validate_geometry(raw, PATH)                          # no teeth: cannot tell
    assert error_of(raw, teeth=39).path == f"{PATH}.eccentricity"
    validate_geometry(with_("cycloid_disc", eccentricity=1.5), PATH, teeth=39)  # 0.9375


def test_needle_gear_impossible_dimensions() -> None:
    assert error_of(with_("needle_gear", pin_radius=64)).path == f"{PATH}.pin_radius"
    # 40 pins on r = 64 mm are 2·64·sin(π/40) = 10.05 mm apart: radius 5.1 overlaps
    assert error_of(with_("needle_gear", pin_radius=5.1), teeth=40).path == f"{PATH}.pin_radius"
    validate_geometry(with_("needle_gear", pin_radius=5.0), PATH, teeth=40)


def test_gear_bore_must_be_inside_the_root_circle() -> None:
    # z = 12, m = 1.5: root radius 1.5·12/2 − 1.25·1.5 = 7.125 mm
    validate_geometry(with_("gear", bore_radius=7.1), PATH, teeth=12)
    error = error_of(with_("gear", bore_radius=7.125), teeth=12)
    assert error.path == f"{PATH}.bore_radius" and "7.125" in error.message


def test_planet_frames_impossible_dimensions() -> None:
    error = error_of(with_("planet_frame_1", crank_bearing_radius=58))
    assert error.path == f"{PATH}.crank_bearing_radius"
    error = error_of(with_("planet_frame_1", crank_bearing_width=15))   # deeper than 14
    assert error.path == f"{PATH}.crank_bearing_width"
    error = error_of(with_("planet_frame_2", crank_bearing_radius=60))
    assert error.path == f"{PATH}.crank_bearing_radius"


RV_TEXT = """
name: t
components:
  0: {role: frame}
  1: {teeth: 12, geometry: GEOMETRY}
  2: {teeth: 36}
links: [{type: mesh, between: [1, 2], carrier: 0}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
"""


def test_model_loading_runs_the_schema_with_the_full_path() -> None:
    ok = loads_model(RV_TEXT.replace(
        "GEOMETRY", "{shape: gear, module: 1.5, face_width: 12 mm, bore_radius: 0}"))
    assert ok.components["1"].geometry.face_width == 12.0
    with pytest.raises(ModelError) as info:
        loads_model(RV_TEXT.replace("GEOMETRY", "{shape: gear, module: 1.5, face_width: 12}"))
    assert info.value.path == "components.1.geometry.bore_radius"
    assert str(info.value).startswith("components.1.geometry.bore_radius: missing")
