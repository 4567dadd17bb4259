"""Long and badly scaled trains: exact closed forms, dense and sparse paths agreeing.

The solver assembles its systems as triplets and solves them with dense numpy below
``powergraph.linalg.SPARSE_FROM`` unknowns and with scipy.sparse above;
``linalg.PATH`` forces one path. Expected values are closed forms derived here.
"""
from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

import powergraph as pg
from powergraph.errors import ModelError
from powergraph import linalg
from powergraph.model import loads_model, model_from_dict
from powergraph.testing import assert_conservation
from powergraph.testing_trains import gear_chain_text

ROOT = Path(__file__).resolve().parents[2]
MODELS = sorted((ROOT / "models").glob("*.yaml"))
UNSOLVABLE = yaml.safe_load((ROOT / "tests" / "data" / "unsolvable.yaml").read_text())


@pytest.fixture(params=["dense", "sparse"])
def path(request, monkeypatch):
    monkeypatch.setattr(linalg, "PATH", request.param)
    return request.param


def solve(model):
    result = pg.solve(model)
    assert_conservation(result)
    return result


def series(n: int, eta_sp: float, eta_pr: float, z_s: int = 20, z_p: int = 30,
           z_r: int = 80):
    """``n`` identical 2K-H stages, each driven at its sun, ring fixed, carrier out and
    joined to the next sun."""
    components: dict = {0: {"role": "frame"}}
    links: list = []
    for k in range(n):
        components.update({f"s{k}": {"teeth": z_s}, f"p{k}": {"teeth": z_p},
                           f"r{k}": {"teeth": z_r, "internal": True}, f"c{k}": {}})
        links += [{"type": "mesh", "between": [f"s{k}", f"p{k}"], "carrier": f"c{k}",
                   "efficiency": eta_sp},
                  {"type": "mesh", "between": [f"p{k}", f"r{k}"], "carrier": f"c{k}",
                   "efficiency": eta_pr},
                  {"type": "fixed", "between": [f"r{k}", 0]}]
        if k:
            links.append({"type": "fixed", "between": [f"c{k - 1}", f"s{k}"]})
    return model_from_dict({"name": "series", "components": components, "links": links,
                            "ports": [{"component": "s0", "role": "input", "speed": 100.0,
                                       "power": 1000.0},
                                      {"component": f"c{n - 1}", "role": "output"}]})


def test_twenty_2kh_stages_in_series_give_the_closed_form_product(path) -> None:
    """One stage, k = z_r/z_s = 4, ring held. Willis between sun and ring through the
    carrier: (w_s - w_c)/(0 - w_c) = -k, so w_s = (1 + k) w_c: ratio 1 + k = 5.
    In the carrier's frame the sun feeds P_s = T_s (w_s - w_c) = T_s k w_c > 0 and the ring
    takes out η_sp η_pr of it: -T_r (0 - w_c) = η_sp η_pr T_s k w_c, T_r = η_sp η_pr k T_s.
    Balance: T_c = -T_s - T_r = -T_s (1 + η_sp η_pr k). Efficiency
    -T_c w_c / (T_s w_s) = (1 + η_sp η_pr k)/(1 + k). Twenty stages: ratio 5^20 (about
    9.5e13, the torques span as much), efficiency the 20th power."""
    eta_sp, eta_pr, k = 0.98, 0.97, 4.0
    stage = (1 + eta_sp * eta_pr * k) / (1 + k)
    result = solve(series(20, eta_sp, eta_pr))
    assert result.ratio == pytest.approx(5.0 ** 20, rel=1e-9)
    assert result.efficiency == pytest.approx(stage ** 20, rel=1e-9, abs=0)
    assert result.load_sharing_assumed is False


@pytest.mark.parametrize("n", [16, 60])
def test_series_is_determined_whatever_its_length(n: int, path) -> None:
    """16 stages and more were once refused as 'loads not determined' (only bad scaling)."""
    stage = (1 + 0.98 * 0.98 * 4) / 5
    result = solve(series(n, 0.98, 0.98))
    assert result.ratio == pytest.approx(5.0 ** n, rel=1e-9)
    assert result.efficiency == pytest.approx(stage ** n, rel=1e-9, abs=0)


def chain_text(n: int, eta: float) -> str:
    return gear_chain_text(n, eta)


@pytest.mark.slow  # 5,000 gears: the conservation check draws three large flow graphs
def test_five_thousand_gear_chain_is_exact() -> None:
    """Fixed-axis pairs: w_(i+1) = -w_i z_i/z_(i+1), so the ratio w_1/w_N is
    (-1)^(N-1) z_N/z_1; every mesh passes η of what its driver feeds: η^(N-1)."""
    n = 5000
    result = solve(loads_model(chain_text(n, 0.99)))
    z_1, z_n = 20 + 1 % 7, 20 + n % 7
    assert result.ratio == pytest.approx((-1) ** (n - 1) * z_n / z_1, rel=1e-9)
    assert result.efficiency == pytest.approx(0.99 ** (n - 1), rel=1e-9, abs=0)
    for k, mesh in enumerate(result.meshes):
        assert mesh.carrier_frame_power == pytest.approx(100 * 0.99 ** k, rel=1e-9, abs=0)


def test_a_chain_in_the_sparse_path_is_exact() -> None:
    """The same closed forms, 400 gears (sparse by size), η 0.5: 0.5^399 ≈ 1e-120."""
    n = 400
    assert linalg.use_sparse(n)
    result = solve(loads_model(chain_text(n, 0.5)))
    assert result.ratio == pytest.approx((-1) ** (n - 1) * (20 + n % 7) / 21, rel=1e-9)
    assert result.efficiency == pytest.approx(0.5 ** (n - 1), rel=1e-9, abs=0)


def _relative_gap(a: float, b: float, scale: float) -> float:
    return abs(a - b) / max(abs(a), abs(b), 1e-300 + 1e-12 * scale)


@pytest.mark.parametrize("model_path", MODELS, ids=lambda p: p.stem)
def test_dense_and_sparse_paths_agree(model_path: Path, monkeypatch) -> None:
    """Every library model: speeds, external torques and losses to 1e-9 relative."""
    model = pg.load_model(model_path)
    results = {}
    for which in ("dense", "sparse"):
        monkeypatch.setattr(linalg, "PATH", which)
        results[which] = solve(model)
    dense, sparse = results["dense"], results["sparse"]
    speed_scale = max(abs(w) for w in dense.kinematics.body_speeds.values())
    for body, w in dense.kinematics.body_speeds.items():
        assert _relative_gap(w, sparse.kinematics.body_speeds[body], speed_scale) < 1e-9
    torque_scale = max(abs(t) for t in dense.external_torques.values())
    for body, t in dense.external_torques.items():
        assert _relative_gap(t, sparse.external_torques[body], torque_scale) < 1e-9
    loss_scale = max(abs(dense.input_power), 1e-300)
    for d, s in zip(dense.elements, sparse.elements):
        assert _relative_gap(d.loss, s.loss, loss_scale) < 1e-9
        assert d.driver == s.driver
    assert dense.load_sharing_assumed == sparse.load_sharing_assumed


@pytest.mark.parametrize("case", UNSOLVABLE, ids=lambda c: c["id"])
def test_undetermined_trains_are_still_refused(case: dict, path) -> None:
    """Genuinely undetermined or contradictory trains keep their messages on both paths
    (a 2-DOF differential given one speed, loads missing, a locked mesh loop...)."""
    with pytest.raises(ModelError, match=case["match"]):
        pg.solve(loads_model(case["text"]))


def test_solve_does_not_import_scipy() -> None:
    """A small train takes the dense path: `powergraph solve` never loads scipy."""
    code = ("import sys; from powergraph.cli.main import main; "
            "main(['solve', 'models/rv40e_wang2021.yaml', '--json']); "
            "print(sorted(m for m in ('scipy', 'networkx', 'sympy', 'pint', 'matplotlib') "
            "if m in sys.modules), file=sys.stderr)")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT)
    assert proc.returncode == 0
    assert proc.stderr.strip().splitlines()[-1] == "[]"


def test_the_last_torque_of_a_long_chain_is_accurate_relative_to_itself(path) -> None:
    """200 gears at η 0.1: the output torque is 0.1^199 of the input's (times the tooth
    ratio), a range no unscaled solve keeps; the output power is P·0.1^199."""
    result = solve(loads_model(chain_text(200, 0.1)))
    assert result.output_power == pytest.approx(100 * 0.1 ** 199, rel=1e-9, abs=0)
    assert math.isfinite(result.efficiency)
