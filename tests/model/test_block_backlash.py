"""A mesh's ``backlash:`` block and ``backlash_arcmin:`` (Li et al. 2012): format and checks."""
from __future__ import annotations

import copy
from types import MappingProxyType

import pytest

from powergraph.errors import ModelError
from powergraph.model import model_from_dict
from powergraph.model.block_backlash import BacklashBlock

PAIR_1 = {
    "module": 1, "pressure_angle": 20, "pin_diameter": 1.732,
    "standard_M": {"R": 42.434, "G": 42.436},
    "measured_M": {"R": [42.485, 42.481, 42.481, 42.480, 42.483, 42.479],
                   "G": [42.401, 42.398, 42.402, 42.404, 42.402, 42.404]},
    "runout": {"R": 0.022, "G": 0.015},
    "bearing_clearance": [0.005, 0.006],
}


def khv(mesh_extra: dict, ring: dict | None = None, gear: dict | None = None) -> dict:
    """A K-H-V stage whose ring-gear mesh carries ``mesh_extra``."""
    return {
        "name": "khv",
        "components": {0: {"role": "frame"}, "H": {},
                       "R": ring if ring is not None else {"teeth": 45, "internal": True},
                       "G": gear if gear is not None else {"teeth": 40}, "W": {}},
        "links": [dict({"type": "mesh", "between": ["R", "G"], "carrier": "H"}, **mesh_extra),
                  {"type": "fixed", "between": ["R", 0]},
                  {"type": "coupling", "between": ["G", "W"]}],
        "ports": [{"component": "H", "role": "input"}, {"component": "W", "role": "output"}],
    }


def block_with(**changes) -> dict:
    block = copy.deepcopy(PAIR_1)
    for key, value in changes.items():
        if value is KeyError:
            del block[key]
        else:
            block[key] = value
    return block


def error_of(data: dict) -> ModelError:
    with pytest.raises(ModelError) as info:
        model_from_dict(data)
    return info.value


def test_valid_block_is_frozen_and_typed() -> None:
    model = model_from_dict(khv({"backlash": PAIR_1}))
    block = model.links[0].blocks["backlash"]
    assert isinstance(block, BacklashBlock)
    assert (block.internal, block.external) == ("R", "G")
    assert block.measured_M["R"] == (42.485, 42.481, 42.481, 42.480, 42.483, 42.479)
    assert block.runout["G"] == 0.015 and block.bearing_clearance == (0.005, 0.006)
    assert block.assembly == "standard" and block.pressure_angle == 20.0
    assert isinstance(block.standard_M, MappingProxyType)
    with pytest.raises(Exception):
        block.module = 2  # frozen


def test_defaults_and_units() -> None:
    block = block_with(pressure_angle=KeyError, runout=KeyError, bearing_clearance=KeyError,
                       pin_diameter="1.732 mm")
    block["measured_M"] = {"R": "42.479 mm", "G": 42.404}
    parsed = model_from_dict(khv({"backlash": block})).links[0].blocks["backlash"]
    assert parsed.pressure_angle == 20.0
    assert dict(parsed.runout) == {"R": 0.0, "G": 0.0} and parsed.bearing_clearance == ()
    assert parsed.measured_M["R"] == (42.479,)
    assert parsed.pin_diameter == pytest.approx(1.732)


def test_integer_ids_compare_as_strings() -> None:
    data = khv({})
    data["components"] = {0: {"role": "frame"}, 1: {}, 5: {"teeth": 45, "internal": True},
                          4: {"teeth": 40}, 6: {}}
    data["links"] = [{"type": "mesh", "between": [5, 4], "carrier": 1,
                      "backlash": block_with(standard_M={5: 42.434, "4": 42.436},
                                             measured_M={5: [42.479], 4: [42.404]},
                                             runout={5: 0.022, 4: 0.015})},
                     {"type": "fixed", "between": [5, 0]},
                     {"type": "coupling", "between": [4, 6]}]
    data["ports"] = [{"component": 1, "role": "input"}, {"component": 6, "role": "output"}]
    block = model_from_dict(data).links[0].blocks["backlash"]
    assert block.internal == "5" and block.standard_M["4"] == 42.436


def test_backlash_arcmin() -> None:
    model = model_from_dict(khv({"backlash_arcmin": 3}))
    assert model.links[0].blocks["backlash_arcmin"] == 3.0
    assert isinstance(model.links[0].blocks["backlash_arcmin"], float)


@pytest.mark.parametrize("value", [-1, "3 arcmin", True, None, [1]])
def test_backlash_arcmin_must_be_a_number_at_least_zero(value) -> None:
    assert error_of(khv({"backlash_arcmin": value})).path == "links[0].backlash_arcmin"


def test_not_both() -> None:
    err = error_of(khv({"backlash_arcmin": 1, "backlash": PAIR_1}))
    assert err.path == "links[0].backlash_arcmin" and "not both" in err.message


@pytest.mark.parametrize("changes,path", [
    ({"modulus": 1}, "links[0].backlash.modulus"),
    ({"module": KeyError}, "links[0].backlash.module"),
    ({"measured_M": KeyError}, "links[0].backlash.measured_M"),
    ({"module": 0}, "links[0].backlash.module"),
    ({"module": "one"}, "links[0].backlash.module"),
    ({"module": True}, "links[0].backlash.module"),
    ({"pressure_angle": 50}, "links[0].backlash.pressure_angle"),
    ({"pressure_angle": -20}, "links[0].backlash.pressure_angle"),
    ({"pin_diameter": float("nan")}, "links[0].backlash.pin_diameter"),
    ({"standard_M": {"R": 42.434}}, "links[0].backlash.standard_M.G"),
    ({"standard_M": {"R": 42.434, "G": 42.436, "X": 1}}, "links[0].backlash.standard_M.X"),
    ({"standard_M": [42.434, 42.436]}, "links[0].backlash.standard_M"),
    ({"measured_M": {"R": [], "G": [42.4]}}, "links[0].backlash.measured_M.R"),
    ({"measured_M": {"R": [42.48, "x"], "G": [42.4]}}, "links[0].backlash.measured_M.R[1]"),
    ({"measured_M": {"R": [42.48], "G": [-42.4]}}, "links[0].backlash.measured_M.G[0]"),
    ({"runout": {"R": -0.01, "G": 0.01}}, "links[0].backlash.runout.R"),
    ({"runout": {"R": 0.01, "H": 0.01}}, "links[0].backlash.runout.H"),
    ({"bearing_clearance": []}, "links[0].backlash.bearing_clearance"),
    ({"bearing_clearance": [0.005, -1]}, "links[0].backlash.bearing_clearance[1]"),
    ({"assembly": "tight"}, "links[0].backlash.assembly"),
])
def test_bad_block_names_its_place(changes: dict, path: str) -> None:
    assert error_of(khv({"backlash": block_with(**changes)})).path == path


def test_block_must_be_a_mapping() -> None:
    assert error_of(khv({"backlash": [1, 2]})).path == "links[0].backlash"


def test_impossible_over_pin_distance() -> None:
    # External gear z = 40, m = 1, α = 20°: base diameter 40 cos 20° = 37.588 mm; the pin
    # centres (M − d_p = 30 mm) would lie inside the base circle.
    block = block_with(measured_M={"R": [42.48], "G": [31.732]})
    err = error_of(khv({"backlash": block}))
    assert err.path == "links[0].backlash.measured_M.G[0]" and "base" in err.message


def test_pair_must_be_internal() -> None:
    err = error_of(khv({"backlash": PAIR_1}, ring={"teeth": 45}))
    assert err.path == "links[0].backlash" and "internal" in err.message


def test_gears_need_teeth() -> None:
    data = khv({"backlash": PAIR_1, "ratio": 0.9}, gear={})
    err = error_of(data)
    assert err.path == "links[0].backlash" and "teeth" in err.message


def test_internal_gear_must_be_larger() -> None:
    err = error_of(khv({"backlash": PAIR_1}, gear={"teeth": 50}))
    assert err.path == "links[0].backlash" and "more teeth" in err.message
