"""Compiled, vectorised sweeps against single solves and closed forms.

Expected values come from ``powergraph.solve`` on the modified model (the validated single
solver: ``model.with_link``/``with_port``, or the model file rebuilt with new teeth by
``model_from_dict``), from the planetary closed forms (tests/data/reference_trains.yaml) and the model files'
descriptions, or from hand derivations — never from the sweep's own output.
"""
from __future__ import annotations

import copy
import importlib.util
import io
from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.sweep import STATUS, cartesian, compile_sweep, parse_set, sweep
from powergraph.errors import ModelError, StaticsError, UsageError
from powergraph.testing import assert_conservation
from powergraph.kinematics import backdriven
from powergraph.model import load_model, load_yaml_file, model_from_dict

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"
REL = 1e-12


def model(name: str):
    return load_model(MODELS / name)


def with_teeth(name: str, teeth: dict) -> object:
    """The model file rebuilt (and validated) with new tooth numbers. Geometry blocks (for
    the volume analysis; they check their own teeth) are dropped: power flow ignores them."""
    data = copy.deepcopy(load_yaml_file(MODELS / name))
    for raw_id, attrs in data["components"].items():
        if attrs:
            attrs.pop("geometry", None)
        if str(raw_id) in teeth:
            attrs["teeth"] = int(teeth[str(raw_id)])
    return model_from_dict(data)


def with_efficiencies(base, efficiencies: dict):
    for link, eta in efficiencies.items():
        base = base.with_link(link, efficiency=float(eta))
    return base


def driver_codes(result) -> list[int]:
    return [0 if e.driver is None else (1 if e.driver == e.a else -1) for e in result.elements]


def assert_matches_single(swept, j: int, single) -> None:
    """Variant ``j`` of a sweep equals a single solve (1e-12 relative, or absolute near 0)."""
    assert swept.converged.flat[j], STATUS[swept.status.flat[j]]
    scale = abs(single.input_power)
    assert swept.efficiency.flat[j] == pytest.approx(single.efficiency, rel=REL, abs=REL)
    assert swept.ratio.flat[j] == pytest.approx(single.ratio, rel=REL)
    assert swept.input_power.flat[j] == pytest.approx(single.input_power, rel=REL)
    assert swept.output_power.flat[j] == pytest.approx(single.output_power, rel=REL,
                                                       abs=REL * scale)
    assert swept.total_loss.flat[j] == pytest.approx(single.total_loss, rel=REL,
                                                     abs=REL * scale)
    for element in single.elements:
        assert swept.losses[element.link].flat[j] == pytest.approx(
            element.loss, rel=1e-11, abs=REL * scale)
    assert [int(swept.drivers[e.link].flat[j]) for e in single.elements] == \
        driver_codes(single)
    assert bool(swept.self_locking.flat[j]) == single.self_locking


# --- the RV-40E against its hand closed form ---------------------------------------------

def test_rv_values_of_the_hand_closed_form() -> None:
    # benchmarks/sweep_rv.py derives i = 1 + z2 z5/(z1 (z5 - z4)) = 121 and
    # eta = [1 + (z2/z1) eta1 z5/(z5 - z4 eta2)]/i: 0.287376 (0.94, 0.94), 0.873043
    # (eta2 = 0.998); L_12 = P (1 - 1/i)(1 - eta1) = 135.0744 W, L_45 = P (1 - eta) - L_12.
    r = sweep(model("rv40e_wang2021.yaml"), {"links.1.efficiency": [0.94, 0.998]})
    assert r.efficiency.tolist() == pytest.approx([0.287376, 0.873043], abs=5e-7)
    assert r.ratio.tolist() == pytest.approx([121.0, 121.0], rel=1e-13)
    assert r.losses[0].tolist() == pytest.approx([135.0744, 135.0744], abs=5e-5)
    assert r.losses[1].tolist() == pytest.approx([1482.583, 153.118], abs=5e-4)
    assert r.converged.all() and not r.self_locking.any()


@pytest.mark.parametrize("backend", ["symbolic", "numeric"])
def test_2kh_closed_forms_over_ring_teeth_and_efficiencies(backend) -> None:
    # 2K-H closed form: sun -> carrier, ring fixed: ratio 1 + k, efficiency (1 + η0 k)/(1 + k)
    z_ring = np.array([48, 60, 72, 96, 120])[:, None]
    eta = np.array([0.9, 0.95, 0.98, 1.0])[None, :]
    r = sweep(model("planetary_2kh_sun_to_carrier.yaml"),
              {"components.ring.teeth": z_ring, "links.1.efficiency": eta}, backend=backend)
    k = z_ring / 24
    eta0 = 0.98 * eta
    assert r.shape == (5, 4)
    np.testing.assert_allclose(r.ratio, np.broadcast_to(1 + k, (5, 4)), rtol=REL)
    np.testing.assert_allclose(r.efficiency, (1 + eta0 * k) / (1 + k), rtol=REL)


def test_2kh_carrier_to_sun_and_internal_sign_from_teeth() -> None:
    # c -> s, ring fixed: ratio 1/(1 + k), efficiency (1 + k) η0 / (η0 + k); the ring is
    # internal, so its Willis ratio is +z_r/z_p: the sign comes from the model's flags.
    base = model("planetary_2kh_carrier_to_sun.yaml")
    z_sun = np.array([12, 18, 24, 30, 36])
    eta = np.array([0.93, 0.97, 0.99, 0.999, 1.0])
    sun = next(c for c in base.components.values() if c.name == "sun gear").id
    ring = next(c for c in base.components.values() if c.internal)
    r = sweep(base, {f"components.{sun}.teeth": z_sun, "links.*.efficiency": eta})
    k = ring.teeth / z_sun
    eta0 = eta * eta
    np.testing.assert_allclose(r.ratio, 1 / (1 + k), rtol=REL)
    np.testing.assert_allclose(r.efficiency, (1 + k) * eta0 / (eta0 + k), rtol=REL)


def test_planet_teeth_enter_an_external_and_an_internal_mesh() -> None:
    # The planet meshes the sun (external, -z_p/z_s) and the ring (internal, +z_r/z_p):
    # the train's ratio and efficiency do not depend on z_p (2K-H closed form) ...
    r = sweep(model("planetary_2kh_sun_to_carrier.yaml"),
              {"components.planet.teeth": np.arange(10, 40)})
    np.testing.assert_allclose(r.ratio, 4.0, rtol=REL)
    np.testing.assert_allclose(r.efficiency, (1 + 0.98 * 0.99 * 3) / 4, rtol=REL)
    # ... while in the Wolfrom drive the stepped planet's first step sets the ratio:
    # (1 + z_r1/z_s) / (1 - z_r1 z_p2 / (z_p1 z_r2)) (models/wolfrom_3k.yaml)
    z_p1 = np.array([28, 29, 31, 32])
    wolfrom = sweep(model("wolfrom_3k.yaml"), {"components.p1.teeth": z_p1})
    np.testing.assert_allclose(wolfrom.ratio, (1 + 72 / 12) / (1 - 72 * 27 / (z_p1 * 69)),
                               rtol=1e-11)
    for j, z in enumerate(z_p1):
        assert_matches_single(wolfrom, j, pg.solve(with_teeth("wolfrom_3k.yaml", {"p1": z})))


def test_tuplin_closed_form_forward_and_backdriven() -> None:
    # models/tuplin_256.yaml: efficiency 1/(256 - 255 η0); back-driven 256 - 255/η0 (< 0:
    # self-locking), η0 = η(r1) η(r2)
    eta = np.linspace(0.9, 1.0, 21)
    forward = sweep(model("tuplin_256.yaml"), {"links.*.efficiency": eta})
    np.testing.assert_allclose(forward.efficiency, 1 / (256 - 255 * eta**2), rtol=1e-11)
    np.testing.assert_allclose(forward.ratio, 256.0, rtol=1e-11)
    back = sweep(backdriven(model("tuplin_256.yaml")), {"links.*.efficiency": eta})
    formal = 256 - 255 / eta**2
    np.testing.assert_allclose(back.formal_efficiency, formal, rtol=1e-10, atol=1e-11)
    # from the flows: where it self-locks both ports take power in, so nothing leaves: 0
    np.testing.assert_allclose(back.efficiency, np.maximum(formal, 0.0), rtol=1e-10,
                               atol=1e-11)
    assert back.self_locking[:-1].all() and not back.self_locking[-1]


# --- against single solves -------------------------------------------------------------

RV_TEETH = {"1": (10, 20), "2": (24, 60), "4": (25, 60)}


def rv_variants(n: int, seed: int) -> dict:
    rng = np.random.default_rng(seed)
    z4 = rng.integers(25, 61, n)
    return {"components.1.teeth": rng.integers(10, 21, n),
            "components.2.teeth": rng.integers(24, 61, n),
            "components.4.teeth": z4, "components.5.teeth": z4 + 1,
            "links.0.efficiency": rng.uniform(0.9, 1.0, n),
            "links.1.efficiency": rng.uniform(0.9, 1.0, n)}


@pytest.mark.parametrize("backend", ["auto", "numeric"])
def test_rv_teeth_and_efficiencies_equal_single_solves(backend) -> None:
    values = rv_variants(12, seed=1)
    swept = sweep(model("rv40e_wang2021.yaml"), values, backend=backend)
    for j in range(12):
        teeth = {path.split(".")[1]: values[path][j] for path in values if "teeth" in path}
        single = pg.solve(with_efficiencies(with_teeth("rv40e_wang2021.yaml", teeth),
                                            {0: values["links.0.efficiency"][j],
                                             1: values["links.1.efficiency"][j]}))
        assert_matches_single(swept, j, single)


@pytest.mark.parametrize("name", ["wolfrom_3k.yaml", "tuplin_256.yaml",
                                  "closed_differential.yaml",
                                  "planetary_2kh_ring_to_sun.yaml",
                                  "planetary_2kh_two_stages.yaml",
                                  "planetary_double_planet.yaml"])
@pytest.mark.parametrize("drive", ["forward", "back"])
def test_trains_equal_single_solves(name, drive) -> None:
    base = model(name) if drive == "forward" else backdriven(model(name))
    meshes = [link.index for link in base.meshes]
    gear = next(c for link in base.meshes for c in link.between)
    z0 = base.components[gear].teeth
    rng = np.random.default_rng(len(name))
    n = 10
    values = {f"links.{i}.efficiency": rng.uniform(0.6, 1.0, n) for i in meshes}
    values[f"components.{gear}.teeth"] = z0 + rng.integers(-2, 3, n)
    for backend in ("symbolic", "numeric"):
        swept = sweep(base, values, backend=backend)
        for j in range(n):
            variant = with_teeth(name, {gear: values[f"components.{gear}.teeth"][j]})
            if drive == "back":
                variant = backdriven(variant)
            variant = with_efficiencies(variant, {i: values[f"links.{i}.efficiency"][j]
                                                  for i in meshes})
            single = pg.solve(variant)
            if single.search is not None:  # the fixed-point iteration cycled
                assert STATUS[swept.status[j]] in ("cycle", "unsettled")
                continue
            assert_matches_single(swept, j, single)


def test_wolfrom_backdriven_direction_change_over_mesh_efficiency() -> None:
    # Back-driven, the Wolfrom drive self-locks below η ≈ 0.97: the sun–planet mesh changes
    # its driver inside the range, and the single solver needs one more pass there.
    back = backdriven(model("wolfrom_3k.yaml"))
    eta = np.linspace(0.90, 0.99, 91)
    swept = sweep(back, {"links.*.efficiency": eta})
    singles = [pg.solve(back.with_mesh_efficiency(float(e))) for e in eta]
    for j, single in enumerate(singles):
        assert_matches_single(swept, j, single)
    drivers = {single.elements[0].driver for single in singles}
    assert drivers == {"s", "p1"}                       # the change is inside the range
    assert swept.self_locking.any() and not swept.self_locking.all()


def test_direction_change_in_a_large_sweep_uses_each_patterns_closed_form() -> None:
    back = backdriven(model("wolfrom_3k.yaml"))
    evaluate = compile_sweep(back, ["links.0.efficiency", "links.2.efficiency"])
    rng = np.random.default_rng(7)
    values = {"links.0.efficiency": rng.uniform(0.9, 1.0, 40_000),
              "links.2.efficiency": rng.uniform(0.9, 1.0, 40_000)}
    swept = evaluate(values, chunk_size=4096, quiet=True)
    assert len(evaluate.patterns) >= 2
    assert any(start != settled for start, settled in evaluate.patterns)   # two passes
    assert set(np.unique(swept.drivers[0])) == {-1, 1}
    assert set(np.unique(swept.passes)) == {1, 2}
    for j in rng.choice(40_000, 40, replace=False):
        single = pg.solve(with_efficiencies(back, {0: values["links.0.efficiency"][j],
                                                   2: values["links.2.efficiency"][j]}))
        assert_matches_single(swept, j, single)


def test_ports_speed_and_power() -> None:
    rv = model("rv40e_wang2021.yaml")
    speed = np.array([50.0, 157.07963267948966, 300.0])
    power = np.array([[100.0], [2270.0]])
    swept = sweep(rv, {"ports.0.speed": speed, "ports.0.power": power})
    assert swept.shape == (2, 3)
    for (a, b), _ in np.ndenumerate(swept.efficiency):
        single = pg.solve(rv.with_port(0, speed=float(speed[b]), power=float(power[a, 0])))
        assert_matches_single(swept, a * 3 + b, single)


def test_two_dof_differential_port_speeds() -> None:
    diff = model("bevel_differential.yaml")
    speed_ports = [p.index for p in diff.ports if p.speed is not None]
    values = {f"ports.{i}.speed": np.array([5.0, 20.0, -7.0]) * (k + 1)
              for k, i in enumerate(speed_ports)}
    swept = sweep(diff, values)
    assert np.isnan(swept.ratio).all()          # two outputs: no single ratio
    assert swept.converged.all()
    for j in range(3):
        variant = diff
        for i in speed_ports:
            variant = variant.with_port(i, speed=float(values[f"ports.{i}.speed"][j]))
        single = pg.solve(variant)
        assert swept.efficiency[j] == pytest.approx(single.efficiency, rel=REL, abs=REL)
        assert swept.output_power[j] == pytest.approx(single.output_power, rel=REL)


def test_chunks_do_not_change_the_numbers() -> None:
    values = rv_variants(1000, seed=3)
    evaluate = compile_sweep(model("rv40e_wang2021.yaml"), list(values))
    whole = evaluate(values, quiet=True)
    parts = evaluate(values, chunk_size=7, quiet=True)
    np.testing.assert_array_equal(whole.efficiency, parts.efficiency)
    np.testing.assert_array_equal(whole.drivers[1], parts.drivers[1])


# --- flagged, never wrong ---------------------------------------------------------------

@pytest.mark.parametrize("backend", ["symbolic", "numeric"])
def test_direction_cycles_get_the_single_solvers_verdict(backend) -> None:
    # Back-driven RV with a very lossy cycloid mesh: no consistent direction pattern; the
    # single solver searches and gives the locking verdict (docs/locking.md). The sweep
    # hands such a variant to the same search: the same verdict (status "locked",
    # efficiency 0, self-locking), never NaN where the single solver answers.
    back = backdriven(model("rv40e_wang2021.yaml"))
    eta = np.array([0.1, 0.2, 0.5, 0.9])
    swept = sweep(back, {"links.1.efficiency": eta}, backend=backend)
    searched = 0
    for j, e in enumerate(eta):
        single = pg.solve(back.with_link(1, efficiency=float(e)))
        assert_conservation(single)
        assert_matches_single(swept, j, single)
        if single.search is not None:
            searched += 1
            assert single.lock is not None and single.lock.meshes
            assert STATUS[swept.status[j]] == "locked" and swept.self_locking[j]
            assert swept.efficiency[j] == 0.0
        else:
            assert STATUS[swept.status[j]] == "ok"
    assert searched >= 1                                 # the grid does contain a cycle


def test_cycles_inside_a_large_sweep() -> None:
    back = backdriven(model("rv40e_wang2021.yaml"))
    rng = np.random.default_rng(11)
    n = 1000
    values = {"links.0.efficiency": rng.uniform(0.05, 1.0, n),
              "links.1.efficiency": rng.uniform(0.05, 1.0, n)}
    swept = sweep(back, values, chunk_size=1024)
    assert swept.converged.all()                         # every variant answered
    assert 0 < np.count_nonzero(swept.status == STATUS.index("locked")) < n
    searched = 0
    for j in rng.choice(n, 30, replace=False):
        variant = with_efficiencies(back, {0: values["links.0.efficiency"][j],
                                           1: values["links.1.efficiency"][j]})
        single = pg.solve(variant)
        assert_conservation(single)
        searched += single.search is not None
        assert_matches_single(swept, j, single)
    assert searched > 0


@pytest.mark.parametrize("backend", ["symbolic", "numeric"])
def test_singular_speeds_are_flagged(backend) -> None:
    # sun -> carrier with the sun–planet Willis ratio forced to 1/3 = 1/i(p-r): w_c (1 -
    # i1 i2) = w_s has no solution; the single solver rejects it.
    base = model("planetary_2kh_sun_to_carrier.yaml")
    with pytest.raises(pg.ModelError):
        pg.solve(base.with_link(0, ratio=1 / 3))
    swept = sweep(base, {"links.0.ratio": [-1.0, 1 / 3]}, backend=backend)
    assert swept.converged.tolist() == [True, False]
    assert STATUS[swept.status[1]] == "speeds"
    assert np.isnan(swept.ratio[1]) and np.isnan(swept.efficiency[1])
    single = pg.solve(base.with_link(0, ratio=-1.0))
    assert_matches_single(swept, 0, single)


@pytest.mark.parametrize("backend", ["symbolic", "numeric"])
def test_power_on_a_still_port_is_flagged(backend) -> None:
    rv = model("rv40e_wang2021.yaml")
    with pytest.raises(StaticsError):
        pg.solve(rv.with_port(0, speed=0.0))
    swept = sweep(rv, {"ports.0.speed": [0.0, 10.0]}, backend=backend)
    assert [STATUS[s] for s in swept.status] == ["loads", "ok"]
    assert np.isnan(swept.efficiency[0]) and swept.efficiency[1] > 0


# --- paths and values -------------------------------------------------------------------

@pytest.mark.parametrize("path, error, words", [
    ("gears.1.teeth", UsageError, "must start with"),
    ("components.9.teeth", ModelError, "unknown component '9'"),
    ("components.1.name", ModelError, "cannot be swept"),
    ("components.7.teeth", ModelError, "has no teeth"),
    ("links.2.efficiency", ModelError, "fixed link"),
    ("links.5.ratio", ModelError, "only a mesh has a ratio"),
    ("links.12.efficiency", ModelError, "no link 12"),
    ("links.x.efficiency", UsageError, "whole number"),
    ("links.0.between", ModelError, "cannot be swept"),
    ("ports.0.torque", ModelError, "gives power"),
    ("ports.3.speed", ModelError, "no port 3"),
])
def test_bad_paths_name_the_path(path, error, words) -> None:
    with pytest.raises(error, match=words) as info:
        compile_sweep(model("rv40e_wang2021.yaml"), [path])
    assert path in str(info.value) or error is UsageError


def test_teeth_of_a_gear_whose_meshes_give_ratios_change_nothing() -> None:
    with pytest.raises(ModelError, match="changes nothing"):
        compile_sweep(model("rv40e_wang2021.yaml"), ["links.0.ratio", "components.1.teeth"])


@pytest.mark.parametrize("path, values, words", [
    ("components.1.teeth", [12, 12.5], "whole numbers"),
    ("components.1.teeth", [0, 12], "whole numbers >= 1"),
    ("links.1.efficiency", [0.9, 1.1], r"\(0, 1\]"),
    ("links.1.efficiency", [0.0], r"\(0, 1\]"),
    ("links.1.efficiency", [float("nan")], r"\(0, 1\]"),
    ("links.0.ratio", [0.0, -3.0], "non-zero"),
    ("ports.0.speed", [float("inf")], "finite"),
    ("links.1.efficiency", ["high"], "numbers"),
])
def test_bad_values_name_the_path(path, values, words) -> None:
    with pytest.raises(ModelError, match=words) as info:
        sweep(model("rv40e_wang2021.yaml"), {path: values})
    assert info.value.path == path


def test_values_must_match_the_compiled_paths_and_broadcast() -> None:
    evaluate = compile_sweep(model("rv40e_wang2021.yaml"), ["links.0.efficiency",
                                                   "links.1.efficiency"])
    with pytest.raises(UsageError, match="missing links.1.efficiency"):
        evaluate({"links.0.efficiency": [0.9]})
    with pytest.raises(UsageError, match="do not broadcast"):
        evaluate({"links.0.efficiency": [0.9, 0.95], "links.1.efficiency": [0.9, 0.9, 0.9]})
    with pytest.raises(UsageError, match="same model value"):
        compile_sweep(model("rv40e_wang2021.yaml"), ["links.*.efficiency", "links.1.efficiency"])


def test_parse_set_ranges_lists_units_and_whole_teeth() -> None:
    rv = model("rv40e_wang2021.yaml")
    assert parse_set(rv, "links.1.efficiency=0.9:1.0:3")[1].tolist() == \
        pytest.approx([0.9, 0.95, 1.0])
    assert parse_set(rv, "components.5.teeth=38:42:5")[1].tolist() == [38, 39, 40, 41, 42]
    assert parse_set(rv, "ports.0.speed=0:60rpm:2")[1].tolist() == pytest.approx([0, 2 * np.pi])
    with pytest.raises(ModelError, match="whole numbers.*39.5"):
        parse_set(rv, "components.5.teeth=38:41:3")
    for text in ("links.1.efficiency", "links.1.efficiency=0.9:1", "=1", "links.1.efficiency=a",
                 "links.1.efficiency=0.9:1:x", "links.1.efficiency=0.9:1:0"):
        with pytest.raises(UsageError):
            parse_set(rv, text)


# --- results ----------------------------------------------------------------------------

def test_grid_csv_dict_and_curves() -> None:
    rv = model("rv40e_wang2021.yaml")
    grid = cartesian({"links.1.efficiency": np.array([0.9, 0.95, 1.0]),
                      "components.1.teeth": np.array([10, 12])})
    swept = sweep(rv, grid)
    assert swept.shape == (3, 2)
    lines = swept.to_csv().splitlines()
    assert lines[0] == ("links.1.efficiency [-],components.1.teeth [-],ratio [-],"
                        "efficiency [-]")
    assert lines[1].split(",")[:2] == ["0.9", "10"] and lines[2].split(",")[:2] == ["0.9", "12"]
    rows = np.loadtxt(io.StringIO(swept.to_csv()), delimiter=",", skiprows=1)
    # ratio 1 + z2 z5 / (z1 (z5 - z4)) = 1 + 36·40/z1
    np.testing.assert_allclose(rows[:, 2], 1 + 36 * 40 / rows[:, 1], rtol=REL)
    extra = swept.to_csv(extra=True).splitlines()[0].split(",")
    assert extra[4:] == ["input_power [W]", "output_power [W]", "total_loss [W]",
                         "self_locking", "converged", "status", "formal_efficiency [-]",
                         "loss_link_0 [W]",
                         "loss_link_1 [W]", "loss_link_5 [W]"]
    data = swept.to_dict()
    assert data["shape"] == [3, 2] and data["status"] == ["ok"] * 6
    x, curves = swept.curves()
    assert x == "links.1.efficiency" and len(curves) == 2
    np.testing.assert_array_equal(swept.parameters[x].ravel()[curves["components.1.teeth = 10"]],
                                  [0.9, 0.95, 1.0])


def test_progress_bar_unless_quiet(monkeypatch, capsys) -> None:
    from powergraph.analyses.sweep import compile as compiled

    monkeypatch.setattr(compiled, "PROGRESS_DELAY", 0.0)
    values = {"links.1.efficiency": np.linspace(0.9, 1.0, 3000)}
    sweep(model("rv40e_wang2021.yaml"), values, chunk_size=1000)
    assert "sweep" in capsys.readouterr().err
    sweep(model("rv40e_wang2021.yaml"), values, chunk_size=1000, quiet=True)
    assert capsys.readouterr().err == ""


def test_the_sweep_does_not_change_the_model() -> None:
    rv = model("rv40e_wang2021.yaml")
    before = (rv.links, rv.components, rv.ports)
    sweep(rv, {"links.*.efficiency": [0.9], "components.1.teeth": [15]})
    assert (rv.links, rv.components, rv.ports) == before


# --- the benchmark's hand-derived closed form --------------------------------------------

def benchmark():
    spec = importlib.util.spec_from_file_location("sweep_rv", ROOT / "benchmarks" /
                                                  "sweep_rv.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_benchmark_closed_form_equals_single_solves() -> None:
    bench = benchmark()
    values = bench.variants(8, seed=5)
    hand = bench.closed_form(*(values[p] for p in bench.PATHS))
    assert hand["valid"].all()
    for j in range(8):
        teeth = {p.split(".")[1]: values[p][j] for p in bench.PATHS[:4]}
        single = pg.solve(with_efficiencies(with_teeth("rv40e_wang2021.yaml", teeth),
                                            {0: values[bench.PATHS[4]][j],
                                             1: values[bench.PATHS[5]][j]}))
        assert hand["ratio"][j] == pytest.approx(single.ratio, rel=REL)
        assert hand["efficiency"][j] == pytest.approx(single.efficiency, rel=REL)
        assert hand["loss_12"][j] == pytest.approx(single.element(0).loss, rel=1e-11)
        assert hand["loss_45"][j] == pytest.approx(single.element(1).loss, rel=1e-10)
        assert [e.driver for e in single.meshes] == ["1", "5"]   # the derived pattern
    # Wang (2021), Table 1: z = 12, 36, 39, 40 and η1 = η2 = 0.94
    assert bench.closed_form(12, 36, 39, 40, 0.94, 0.94)["efficiency"] == \
        pytest.approx(0.287376, abs=5e-7)


@pytest.mark.parametrize("kind", ["teeth", "efficiency", "ratio", "speed", "power", "torque"])
def test_check_values_refuses_exactly_what_value_allowed_refuses(kind) -> None:
    """check_values (reductions: the numpy path's fast check) and value_allowed (the
    per-value rule the kernels compile) agree on single values of every sort, at and
    around each limit."""
    from powergraph.analyses.sweep.paths import Parameter, check_values, value_allowed
    from powergraph.model.schema_parts import (MAX_POWER, MAX_RATIO, MAX_SPEED, MAX_TEETH,
                                               MAX_TORQUE)

    limit = {"teeth": MAX_TEETH, "ratio": MAX_RATIO, "speed": MAX_SPEED, "power": MAX_POWER,
             "torque": MAX_TORQUE, "efficiency": 1.0}[kind]
    candidates = [0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 12.0, 12.5, 1e-300, limit,
                  np.nextafter(limit, np.inf), -limit, np.inf, -np.inf, np.nan]
    param = Parameter(path=f"x.{kind}", kind=kind, targets=("x",))
    for value in candidates:
        try:
            check_values(param, np.array([value]))
            refused = False
        except ModelError:
            refused = True
        assert refused == (not bool(value_allowed(kind, value))), (kind, value)


def test_sweep_reuses_the_compiled_form_of_the_same_model_and_paths() -> None:
    """``sweep(model, values)`` compiles once per model and PATH set (issue 35: it re-derived
    the closed forms on every call); a changed copy of the model compiles anew, and the
    answers are those of a fresh compile."""
    import dataclasses

    from powergraph.analyses.sweep.compile import CompiledSweep
    from powergraph.analyses.sweep.entry import compiled_for

    model = load_model(ROOT / "models" / "rv40e_wang2021.yaml")
    values = {"links.1.efficiency": np.linspace(0.9, 0.99, 7)}
    first = compiled_for(model, list(values))
    assert compiled_for(model, list(values)) is first
    assert compiled_for(dataclasses.replace(model), list(values)) is not first
    again = sweep(model, values, quiet=True)
    fresh = CompiledSweep(model, list(values))(values, quiet=True)
    assert np.array_equal(again.efficiency, fresh.efficiency)
    assert np.array_equal(again.ratio, fresh.ratio)
