"""Modes as operating states in the file (docs/modes.md, docs/format.md): the mapping form
of a mode, its errors naming the YAML place, and the order in which a variant's, a
mode's and the model's values apply."""
from __future__ import annotations

import copy
from pathlib import Path

import pytest
import yaml

from powergraph.errors import ModelError
from powergraph.model import load_model, model_from_dict
from powergraph.model.mode_specs import at_mode_point
from powergraph.model.modes import resolve
from powergraph.statics.case import TrainCase
from powergraph.testing import assert_conservation

VOLT = Path(__file__).resolve().parents[2] / "models" / "volt_gen1.yaml"
DATA = yaml.safe_load(VOLT.read_text())
RPM = 3.141592653589793 / 30


def with_mode(entry) -> dict:
    data = copy.deepcopy(DATA)
    data["modes"]["EV1"] = entry
    return data


def test_a_mode_as_a_list_and_as_a_mapping() -> None:
    model = load_model(VOLT)
    assert model.modes["series"] == ("C1", "C3")
    spec = model.mode_specs["one-motor EV"]
    assert spec.engaged == ("C1",) and spec.inactive == (0, 1)
    assert dict(spec.ports[3]) == {"power": 20e3} and dict(spec.buses) == {"dc": None}
    listed = model_from_dict(with_mode(["C1"]))
    assert listed.mode_specs["EV1"].engaged == ("C1",)
    assert not listed.mode_specs["EV1"].changes_point


@pytest.mark.parametrize("entry, message", [
    ({"engage": ["C1"], "inactive": ["engin"]},
     "modes.EV1.inactive[0]: unknown port 'engin' (the model's ports: engine, MG-A, MG-B, "
     "wheels)"),
    ({"engage": ["C1"], "inactiv": ["engine"]},
     "modes.EV1.inactiv: unknown field (allowed: buses, engage, inactive, ports)"),
    ({"engage": ["C1"], "inactive": ["engine", "E"]},
     "modes.EV1.inactive[1]: ports[0] (engine) is listed twice"),
    ({"engage": ["C1"], "inactive": ["engine"], "ports": {"engine": {"power": 3}}},
     "modes.EV1.ports.engine: ports[0] (engine) is inactive in this mode "
     "(modes.EV1.inactive): it takes no speed, power or torque"),
    ({"engage": ["C1"], "ports": {"wheel": {"power": 3}}},
     "modes.EV1.ports.wheel: unknown port 'wheel'"),
    ({"engage": ["C1"], "ports": {"wheels": {"power": 3, "torque": 1}}},
     "modes.EV1.ports.wheels: give at most one of power and torque"),
    ({"engage": ["C1"], "ports": {"wheels": {"pwr": 3}}},
     "modes.EV1.ports.wheels.pwr: unknown field (allowed: power, speed, torque)"),
    ({"engage": ["C1"], "ports": {"wheels": {"power": "fast"}}},
     "modes.EV1.ports.wheels.power: cannot read 'fast' as a power"),
    ({"engage": ["C1"], "ports": {"wheels": {"speed": 1e7}}},
     "modes.EV1.ports.wheels.speed: speed must be within ±1e+06 rad/s"),
    ({"engage": ["C1"], "buses": {"ac": {"battery": "free"}}},
     "modes.EV1.buses.ac: unknown bus 'ac' (the model's buses: dc)"),
    ({"engage": ["C1"], "buses": {"dc": {}}}, "modes.EV1.buses.dc.battery: missing"),
    ({"engage": ["C9"]}, "modes.EV1.engage[0]: unknown shift element 'C9'"),
    ("C1", "modes.EV1: EV1 must be a list of shift-element names, or a mapping"),
])
def test_mistakes_name_their_place(entry, message: str) -> None:
    with pytest.raises(ModelError) as error:
        model_from_dict(with_mode(entry))
    assert str(error.value).startswith(message)


def test_off_as_a_key_is_refused_with_a_hint() -> None:
    data = yaml.safe_load(VOLT.read_text().replace("  series:", "  off:"))
    with pytest.raises(ModelError, match="modes.False: a mode name read as the boolean"):
        model_from_dict(data)


def test_the_mode_point_replaces_the_model_values() -> None:
    model = load_model(VOLT)
    ev = at_mode_point(model, "one-motor EV")
    assert ev.inactive == {0, 1} and ev.point_of == "one-motor EV"
    engine, mg_a, _, wheels = ev.ports
    assert (engine.speed, engine.power, engine.torque) == (None, None, 0.0)
    assert mg_a.torque == 0.0 and wheels.power == 20e3 and wheels.speed == 800 * RPM
    assert ev.buses["dc"].battery is None
    assert [p.name for p in ev.inputs] == [] and [p.name for p in ev.outputs] == ["wheels"]
    assert at_mode_point(ev, "one-motor EV") is ev                 # applied once
    assert model.ports[3].power is None and model.buses["dc"].battery == 0.0


def test_a_variant_s_own_values_come_before_the_mode_s() -> None:
    """A duty cycle's row (a variant of the model) that gives the wheels' power keeps it;
    the mode sets what the variant leaves as the model has it (here the battery)."""
    model = load_model(VOLT)
    row = model.with_port(3, power=10e3)
    at = at_mode_point(row, "one-motor EV", loaded=model)
    assert at.ports[3].power == 10e3 and at.buses["dc"].battery is None
    p = TrainCase.of(model, "one-motor EV").point(row)
    assert_conservation(p.result)
    wheels = next(port for port in p.result.ports if port.name == "wheels")
    assert -wheels.power == pytest.approx(10e3, rel=1e-12)
    own = TrainCase.of(model, "one-motor EV").point()
    assert -next(port for port in own.result.ports
                 if port.name == "wheels").power == pytest.approx(20e3, rel=1e-12)


def test_free_drops_a_value_of_the_model() -> None:
    data = with_mode({"engage": ["C2", "C3"], "ports": {"engine": {"speed": "free"},
                                                         "MG-A": {"speed": "2000 rpm"}}})
    model = model_from_dict(data)
    at = at_mode_point(model, "EV1")
    assert at.ports[0].speed is None and at.ports[1].speed == pytest.approx(2000 * RPM)
    assert at.ports[0].power == 30e3                     # the load stays the model's


def test_resolve_holds_idle_members_in_the_frame_body() -> None:
    model = load_model(VOLT)
    ev = resolve(model, "one-motor EV")
    frame = next(b for b in ev.bodies if b.is_frame)
    assert ev.idle == {"A", "E"} and {"A", "E"} <= set(frame.members)
    assert frame.id == "case/R"            # C1 holds the ring; the idle ones add no name
    assert ev.body_of["A"] == ev.body_of["E"] == frame.id
    assert resolve(model, "series").idle == frozenset()
    assert resolve(model, "two-motor EV").idle == {"E"}


def test_a_variant_cannot_give_an_inactive_port_a_value() -> None:
    model = load_model(VOLT)
    row = model.with_port(0, speed=100.0, power=None)
    with pytest.raises(ModelError, match=r"modes\.one-motor EV\.inactive: ports\[0\] "
                                         r"\(engine\) is inactive in mode 'one-motor EV': "
                                         r"it takes no speed \(given 100"):
        TrainCase.of(model, "one-motor EV").point(row)
    cleared = model.with_port(0, speed=None, power=None)     # a column left empty: no value
    assert TrainCase.of(model, "one-motor EV").point(cleared).verdict == "ok"
