"""The compiled sweep and the tolerance analysis take constant efficiencies only: a model
with friction, pins, bearing or drag blocks is refused (its losses would silently vanish),
naming the first offending place; the CLI exits 2 with one line."""
from __future__ import annotations

import json
import re

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.sweep import compile_sweep, sweep
from powergraph.analyses.tolerance import tolerance_analysis
from powergraph.cli.main import main
from powergraph.errors import ModelError
from powergraph.model import model_from_dict

PAIR = {"name": "pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                                       2: {"teeth": 60}},
        "links": [{"type": "mesh", "between": [1, 2], "efficiency": 0.98}],
        "ports": [{"component": 1, "role": "input", "speed": 100.0, "power": 1000.0},
                  {"component": 2, "role": "output"}]}


def pair(**changes) -> dict:
    data = json.loads(json.dumps(PAIR))
    for key, value in changes.items():
        if key == "mesh":
            data["links"][0] = {"type": "mesh", "between": [1, 2], **value}
        elif key == "bearing":
            data["links"].append({"type": "bearing", "between": [2, 0], **value})
        else:
            data["components"]["2"]["drag"] = value
    return data


CASES = [
    (pair(mesh={"friction": {"mu": 0.05}, "geometry": {"module": 2}}), "links[0].friction"),
    (pair(mesh={"friction": {"model": "iso14179", "viscosity": 30, "roughness": 0.5},
                "geometry": {"module": 2, "face_width": 20}}), "links[0].friction"),
    (pair(bearing={"drag": {"no_load_torque": 0.3}}), "links[1].drag"),
    (pair(drag={"no_load_torque": 0.5}), "components.2.drag"),
]


@pytest.mark.parametrize("data, place", CASES)
def test_the_compiled_sweep_refuses_loss_blocks_naming_the_place(data, place) -> None:
    model = model_from_dict(data)
    with pytest.raises(ModelError, match="^" + re.escape(
            f"{place}: the compiled sweep takes constant efficiencies")):
        compile_sweep(model, ["ports.0.speed"])


def test_the_friction_rv_is_refused_at_its_first_block_and_its_pins() -> None:
    model = pg.load_model("models/rv40e.yaml")
    with pytest.raises(ModelError) as info:
        sweep(model, {"ports.0.speed": [100.0, 200.0]})
    assert info.value.path == "links[0].friction"
    # The cycloid mesh's losses come from its pins: block, named as such.
    without_first = model.with_link(0, efficiency=0.99, blocks={})
    with pytest.raises(ModelError) as info:
        compile_sweep(without_first, ["links.0.efficiency"])
    assert info.value.path == "links[1].pins"


def test_a_model_whose_blocks_were_replaced_by_efficiencies_is_swept() -> None:
    # The caller replaces the constant-μ mesh by its efficiency (as the map and the
    # load-dependent solve do): then the sweep equals the single solve.
    model = model_from_dict(pair(mesh={"friction": {"mu": 0.05}, "geometry": {"module": 2}}))
    eta = model.links[0].efficiency
    plain = model.with_link(0, efficiency=eta, blocks={})
    r = sweep(plain, {"ports.0.speed": np.array([100.0, 300.0])})
    assert r.efficiency.tolist() == pytest.approx([eta, eta], rel=1e-12)
    assert pg.solve(model).efficiency == pytest.approx(eta, rel=1e-12)


TOLERANCED = {"links.0.efficiency": {"distribution": "uniform", "min": 0.97, "max": 0.99}}


def test_the_tolerance_analysis_refuses_loss_blocks_when_it_computes_the_efficiency() -> None:
    model = model_from_dict({**pair(drag={"no_load_torque": 0.5}), "tolerances": TOLERANCED})
    with pytest.raises(ModelError, match=r"^components\.2\.drag: the tolerance analysis's "
                                         "efficiency takes constant efficiencies"):
        tolerance_analysis(model, samples=16, seed=1, sobol_samples=0)


def _status(argv: list[str]) -> int:
    try:
        return main(argv)
    except SystemExit as exc:
        return int(exc.code)


def test_cli_sweep_and_tolerance_exit_2_with_one_line(tmp_path, capsys) -> None:
    assert _status(["sweep", "models/rv40e.yaml", "--set",
                    "ports.0.speed=100:200:3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "links[0].friction: the compiled sweep takes constant " \
        "efficiencies" in err
    path = tmp_path / "dragged.yaml"
    path.write_text(json.dumps({**pair(bearing={"drag": {"no_load_torque": 0.3}}),
                                "tolerances": TOLERANCED}))
    assert _status(["tolerance", str(path), "--samples", "16"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "links[1].drag: the tolerance analysis's efficiency" in err
