"""The load-dependent fixed point on a whole grid at once equals the single solves."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses import efficiency_grid
from powergraph.analyses.efficiency_grid import at_point, solve_grid
from powergraph.analyses.efficiency_map import efficiency_map
from powergraph.cli.main import main
from powergraph.model import model_from_dict
from powergraph.testing import assert_conservation

RV = "models/rv40e.yaml"


def friction_rv():
    """The friction RV-40E with its oil at 60 °C (its heat balance set aside: with it each
    point settles its own temperature and is solved alone, the next test but one)."""
    from powergraph.model.lubricant import fixed_temperature

    return fixed_temperature(pg.load_model(RV), 273.15 + 60)

ISO_PAIR = {"name": "iso pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                                               2: {"teeth": 40}},
            "links": [{"type": "mesh", "between": [1, 2],
                       "friction": {"model": "iso14179", "viscosity": 30, "roughness": 0.5},
                       "geometry": {"module": 2, "face_width": 20}}],
            "ports": [{"component": 1, "role": "input", "speed": 100.0},
                      {"component": 2, "role": "output", "torque": 50.0}]}


def _single(model, rpm: float, torque: float):
    """The single solve at one point (the RV's ratio is +121: the output turns with the
    input, so the load torque on it has the opposite sign of the input speed)."""
    result = pg.solve(at_point(model, rpm * math.pi / 30, torque, 1.0))
    assert_conservation(result)
    return result


def test_the_friction_rv_grid_equals_its_single_solves() -> None:
    # ISO/TR 14179-2 on the first stage, pins and crank bearings on the cycloid mesh,
    # crank-support friction and the drags: every point is its own fixed point. Both
    # senses of rotation (two direction patterns, each from its own reference solve).
    model = friction_rv()
    speeds = np.array([-1815.0, 100.0, 700.0, 1815.0, 3000.0])
    torques = np.array([20.0, 150.0, 412.0, 800.0])
    rpm, torque = (a.ravel() for a in np.meshgrid(speeds, torques, indexing="ij"))
    grid = solve_grid(model, rpm, torque)
    assert grid.single_solves == 0 and not grid.unconverged.any()
    for p in range(rpm.size):
        single = _single(model, rpm[p], torque[p])
        assert grid.efficiency[p] == pytest.approx(single.efficiency, rel=1e-9)
        assert grid.input_power[p] == pytest.approx(single.input_power, rel=1e-9)


def test_the_map_of_the_friction_rv_is_the_grid_of_single_solves() -> None:
    model = friction_rv()
    emap = efficiency_map(model, [50.0, 412.0, 800.0], [300.0, 1815.0])
    assert emap.load_dependent and emap.unconverged == () and emap.single_solves == 0
    for i, rpm in enumerate(emap.speeds_rpm):
        for j, torque in enumerate(emap.torques):
            assert emap.efficiency[i, j] == pytest.approx(
                _single(model, rpm, torque).efficiency, rel=1e-9)
    # Drag weighs most at light load, the ISO law's μ ∝ F^0.2 little: the map rises with
    # torque over this range (and stays a plausible RV efficiency at the rated point).
    assert np.all(np.diff(emap.efficiency, axis=1) > 0)
    assert 0.80 < emap.efficiency[1, 1] < 0.95


def test_with_its_heat_balance_each_point_is_its_single_solve() -> None:
    """The RV-40E as written (a heat balance): every point of the grid is solved alone and
    settles its own oil temperature, as `solve` of that point does."""
    model = pg.load_model(RV)
    rpm, torque = np.array([300.0, 1815.0]), np.array([412.0, 100.0])
    grid = solve_grid(model, rpm, torque)
    assert grid.single_solves == 2
    for p in range(2):
        single = _single(model, rpm[p], torque[p])
        assert single.thermal.verdict == "ok"
        assert grid.efficiency[p] == pytest.approx(single.efficiency, rel=1e-12)


def test_points_whose_pattern_disagrees_are_solved_one_by_one(monkeypatch) -> None:
    # Pretend every point's forces disagree with the assumed pattern: all points then
    # come from single solves, with the same values.
    model = model_from_dict(ISO_PAIR)
    rpm = np.array([500.0, 500.0, 3000.0])
    torque = np.array([20.0, 200.0, 20.0])
    batched = solve_grid(model, rpm, torque)
    assert batched.single_solves == 0
    monkeypatch.setattr(efficiency_grid._Grid, "_pattern",
                        lambda self, m, r, x, f, mask: -np.tile(self.codes, (x.shape[0], 1)))
    alone = solve_grid(model, rpm, torque)
    assert alone.single_solves == 3
    assert np.allclose(alone.efficiency, batched.efficiency, rtol=1e-12, atol=0)


def _diverging() -> dict:
    # The output gear 2's shaft bearing with c = mu·d/(2·r_w2) = 0.9·100/(2·40) = 1.125 > 1:
    # its teeth carry T + M, so M = c·(T + M) has no stable fixed point and the passes
    # cannot converge (a SolveError when solved alone).
    data = json.loads(json.dumps(ISO_PAIR))
    data["links"].append({"type": "bearing", "between": [2, 0],
                          "friction": {"mu": 0.9, "bore": 100}})
    return data


def test_points_that_do_not_converge_are_reported() -> None:
    model = model_from_dict(_diverging())
    with pytest.raises(pg.SolveError, match="did not converge"):
        pg.solve(model)
    emap = efficiency_map(model, [20.0, 200.0], [500.0])
    assert emap.unconverged == ((500.0, 20.0), (500.0, 200.0))
    assert np.isnan(emap.efficiency).all()
    assert emap.to_dict()["efficiency"] == [[None, None]]
    assert emap.to_dict()["unconverged"] == [[500.0, 20.0], [500.0, 200.0]]
    assert "2 point(s) did not converge" in emap.text_report()


def test_cli_reports_points_that_do_not_converge(tmp_path, capsys) -> None:
    path = tmp_path / "diverging.yaml"
    path.write_text(json.dumps(_diverging()))
    assert main(["map", str(path), "--torque", "20:200:2", "--speed", "500"]) == 0
    assert "did not converge" in capsys.readouterr().out
