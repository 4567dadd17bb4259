"""Closed-form ratio and efficiency (``powergraph formula``, docs/formula.md).

Expected forms come from the textbook closed forms of the 2K-H arrangements and of the
K-H-V stage (Willis' relation with the basic efficiency in the carrier's frame, written
beside each test), the RV-40E's hand derivation (benchmarks/sweep_rv.py), and a
hand derivation written below (Wolfrom) -- never from the code's output. On trains the
formulas were not written for, they are checked against the numeric solver
(``powergraph.solve``) at the model's values and at random points inside their stated
validity domain.
"""
from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import powergraph as pg
from powergraph.errors import MethodNotApplicableError, UsageError
from powergraph.analyses.formula import derive_formulas, display, readable, sign_factors
from powergraph.kinematics import backdriven
from powergraph.model import load_model, model_from_dict
from powergraph.testing import assert_conservation

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"


def close(a: float, b: float, rtol: float = 1e-12) -> bool:
    return abs(a - b) <= rtol * max(abs(b), 1e-300)


def same(derived: sp.Expr, known: sp.Expr) -> bool:
    return sp.simplify(derived - known) == 0


def solved(model):
    result = pg.solve(model)
    assert_conservation(result)
    return result


# --- 2K-H closed forms, k = z_r/z_s, eta0 = eta(s-p)*eta(p-r) -------------------------------

TWO_K_H = [
    ("planetary_2kh_sun_to_carrier.yaml", lambda k, e: 1 + k, lambda k, e: (1 + e * k) / (1 + k)),
    ("planetary_2kh_carrier_to_sun.yaml", lambda k, e: 1 / (1 + k),
     lambda k, e: (1 + k) * e / (e + k)),
    ("planetary_2kh_ring_to_carrier.yaml", lambda k, e: 1 + 1 / k,
     lambda k, e: (k + e) / (k + 1)),
    ("planetary_2kh_carrier_to_ring.yaml", lambda k, e: k / (1 + k),
     lambda k, e: (k + 1) * e / (k * e + 1)),
    ("planetary_2kh_sun_to_ring.yaml", lambda k, e: -k, lambda k, e: e),
    ("planetary_2kh_ring_to_sun.yaml", lambda k, e: -1 / k, lambda k, e: e),
]


@pytest.mark.parametrize("name,ratio,efficiency", TWO_K_H, ids=[t[0][14:-5] for t in TWO_K_H])
def test_2kh_closed_forms(name, ratio, efficiency) -> None:
    model = load_model(MODELS / name)
    f = derive_formulas(model)
    k = f.symbols["z_ring"] / f.symbols["z_sun"]
    eta0 = f.symbols["eta_0"] * f.symbols["eta_1"]
    assert same(f.ratio, ratio(k, eta0))
    assert same(f.efficiency, efficiency(k, eta0))
    assert f.symbols["z_planet"] not in f.efficiency.free_symbols  # the planet cancels
    assert all(c.always for c in f.conditions)  # one pattern for every tooth number
    numeric = solved(model)
    at = f.evaluate()
    assert close(at["ratio"], numeric.ratio) and close(at["efficiency"], numeric.efficiency)


def test_khv_closed_form() -> None:
    """K-H-V closed form: ratio -N, efficiency eta0/(N + 1 - N eta0), N = z_p/(z_r - z_p)."""
    f = derive_formulas(load_model(MODELS / "khv_involute.yaml"))
    z_p, z_r, eta0 = f.symbols["z_p"], f.symbols["z_r"], f.symbols["eta_0"]
    n = z_p / (z_r - z_p)
    assert same(f.ratio, -n)
    assert same(f.efficiency, eta0 / (n + 1 - n * eta0))
    assert [(d.driver, str(d.factor)) for d in f.directions] == [("r", "1/eta_0")]
    assert f.evaluate()["efficiency"] == pytest.approx(0.99 / (9 - 8 * 0.99), rel=1e-12)


# --- RV-40E (Wang 2021, Table 1) ---------------------------------------------------------------

def test_rv_ratio_is_one_plus_z2_z5_over_z1() -> None:
    model = load_model(MODELS / "rv40e_wang2021.yaml")
    general = derive_formulas(model)
    z = {n: s for n, s in general.symbols.items()}
    # With any tooth difference: i = 1 + z2 z5 / (z1 (z5 - z4)); the RV's z5 - z4 = 1.
    assert same(general.ratio, 1 + z["z_2"] * z["z_5"] / (z["z_1"] * (z["z_5"] - z["z_4"])))
    one_tooth = derive_formulas(model, {"z_4": "z_5 - 1"})
    assert same(one_tooth.ratio, 1 + z["z_2"] * z["z_5"] / z["z_1"])
    assert "z_4" not in one_tooth.symbols
    assert one_tooth.to_dict()["ratio"] == "1 + z_2*z_5/z_1"  # the form a person writes
    assert one_tooth.evaluate()["ratio"] == pytest.approx(121.0, rel=1e-12)


def test_rv_efficiency_of_the_hand_closed_form() -> None:
    """eta = [1 + (z2/z1) eta1 z5/(z5 - z4 eta2)]/i (benchmarks/sweep_rv.py): 0.287376
    (0.94/0.94), 0.873043 (eta2 = 0.998); back-driven at eta2 = 0.998, 0.867490 (the
    86.75 % of the README's RV table), equal to the single solve."""
    model = load_model(MODELS / "rv40e_wang2021.yaml")
    f = derive_formulas(model)
    assert f.evaluate()["efficiency"] == pytest.approx(0.287376, abs=5e-7)
    assert f.evaluate(eta_1=0.998)["efficiency"] == pytest.approx(0.873043, abs=5e-7)
    back = derive_formulas(backdriven(model.with_link(1, efficiency=0.998)))
    assert back.evaluate()["efficiency"] == pytest.approx(0.867490, abs=5e-7)
    assert close(back.evaluate()["efficiency"], solved(back.model).efficiency)


def test_rv_virtual_power_condition_matches_solver() -> None:
    model = load_model(MODELS / "rv40e_wang2021.yaml")
    f = derive_formulas(model)
    numeric = solved(model)
    values = {f.symbols[n]: v for n, v in f.values.items()}
    for condition in f.conditions:
        if condition.kind == "power":
            flow = numeric.element(condition.link)
            expected = flow.carrier_frame_power / numeric.input_power
            assert close(float(condition.expression.subs(values)), expected, 1e-12)


def test_rv_derivation_gives_the_closed_form_ratio() -> None:
    """1 + z2 z5 / (z1 (z5 − z4)) = 1 + 36·40 / (12·1) = 121 (Wang 2021, Table 1)."""
    formulas = derive_formulas(load_model(MODELS / "rv40e_wang2021.yaml"))
    assert formulas.evaluate()["ratio"] == pytest.approx(121.0, rel=1e-12)


# --- Wolfrom: hand derivation ------------------------------------------------------------------

def test_wolfrom_known_closed_form() -> None:
    """Sun s in, ring r1 fixed, ring r2 out, stepped planet p1/p2, free carrier c.

    Kinematics: with r1 fixed, w_c = w_s/(1 + k1), k1 = z_r1/z_s; Willis on the two
    ring meshes gives w_r2 - w_c = u (w_r1 - w_c), u = z_r1 z_p2/(z_p1 z_r2), so
    w_r2 = w_c (1 - u) and i = (1 + k1)/(1 - u).
    Efficiency, for the pattern (carrier frame) s drives s-p1, p1 drives p1-r1, r2 drives
    p2-r2: the planet's power balance in the carrier frame,
    eta0*P_s + eta2*P_r2 = P_r1/eta1, with the external torques summing to zero
    (T_s = 1, T_c = 0, T_r1 = -1 - T_r2), gives T_r2 = -(1 + eta0 eta1 k1)/(1 - eta1 eta2 u)
    and eta = -T_r2 w_r2/w_s = (1 + eta0 eta1 k1)/(1 + k1) * (1 - u)/(1 - eta1 eta2 u):
    the 2K-H sun->carrier efficiency times that of the carrier->r2 stage.
    """
    model = load_model(MODELS / "wolfrom_3k.yaml")
    f = derive_formulas(model)
    s = f.symbols
    k1 = s["z_r1"] / s["z_s"]
    u = s["z_r1"] * s["z_p2"] / (s["z_p1"] * s["z_r2"])
    e0, e1, e2 = s["eta_0"], s["eta_1"], s["eta_2"]
    assert [(d.link, d.driver) for d in f.directions] == [(0, "s"), (1, "p1"), (2, "r2")]
    assert same(f.ratio, (1 + k1) / (1 - u))
    assert same(f.efficiency, (1 + e0 * e1 * k1) / (1 + k1) * (1 - u) / (1 - e1 * e2 * u))
    numeric = solved(model)
    assert close(f.evaluate()["ratio"], numeric.ratio)
    assert close(f.evaluate()["efficiency"], numeric.efficiency)


# --- trains the formulas were not written for --------------------------------------------------

def _frame() -> dict:
    return {0: {"role": "frame"}}


def _mesh(a, b, carrier=0, eta=0.98) -> dict:
    return {"type": "mesh", "between": [a, b], "carrier": carrier, "efficiency": eta}


STEPPED = {  # sun in, stepped planet p1/p2, ring fixed, carrier out
    "name": "stepped planet", "components": {**_frame(), "s": {"teeth": 20},
        "p1": {"teeth": 40}, "p2": {"teeth": 20}, "r": {"teeth": 80, "internal": True},
        "c": {}},
    "links": [_mesh("s", "p1", "c", 0.985), _mesh("p2", "r", "c", 0.99),
              {"type": "fixed", "between": ["p1", "p2"]}, {"type": "fixed", "between": ["r", 0]}],
    "ports": [{"component": "s", "role": "input", "speed": 100, "power": 500},
              {"component": "c", "role": "output"}]}

DOUBLE_PLANET = {  # ring in, sun fixed, carrier out; planets a-b in series
    "name": "double planet", "components": {**_frame(), "s": {"teeth": 36}, "a": {"teeth": 14},
        "b": {"teeth": 16}, "r": {"teeth": 90, "internal": True}, "c": {}},
    "links": [_mesh("s", "a", "c", 0.98), _mesh("a", "b", "c", 0.985), _mesh("b", "r", "c", 0.99),
              {"type": "fixed", "between": ["s", 0]}],
    "ports": [{"component": "r", "role": "input", "speed": 50, "power": 1000},
              {"component": "c", "role": "output"}]}

CLOSED_DIFFERENTIAL = {  # sun and pinion on the input shaft, pinion drives the ring's rim
    "name": "closed differential", "components": {**_frame(), "s": {"teeth": 20},
        "p": {"teeth": 25}, "r": {"teeth": 70, "internal": True}, "c": {},
        "g1": {"teeth": 28}, "g2": {"teeth": 70}},
    "links": [_mesh("s", "p", "c", 0.97), _mesh("p", "r", "c", 0.98), _mesh("g1", "g2", 0, 0.99),
              {"type": "fixed", "between": ["s", "g1"]},
              {"type": "fixed", "between": ["r", "g2"]}],
    "ports": [{"component": "s", "role": "input", "speed": 150, "power": 2000},
              {"component": "c", "role": "output"}]}

SERIES = {  # fixed-axis pair, then 2K-H ring in / sun fixed / carrier out
    "name": "pair then planetary", "components": {**_frame(), "g1": {"teeth": 17},
        "g2": {"teeth": 51}, "s": {"teeth": 30}, "p": {"teeth": 21},
        "r": {"teeth": 72, "internal": True}, "c": {}},
    "links": [_mesh("g1", "g2", 0, 0.985), _mesh("s", "p", "c", 0.975), _mesh("p", "r", "c", 0.99),
              {"type": "fixed", "between": ["g2", "r"]}, {"type": "fixed", "between": ["s", 0]}],
    "ports": [{"component": "g1", "role": "input", "speed": 300, "power": 750},
              {"component": "c", "role": "output"}]}

RAVIGNEAUX = {  # small sun in, large sun fixed, ring out (a second gear)
    "name": "Ravigneaux", "components": {**_frame(), "s1": {"teeth": 26}, "s2": {"teeth": 34},
        "ps": {"teeth": 16}, "pl": {"teeth": 20}, "r": {"teeth": 74, "internal": True}, "c": {}},
    "links": [_mesh("s1", "ps", "c", 0.98), _mesh("ps", "pl", "c", 0.975),
              _mesh("s2", "pl", "c", 0.985), _mesh("pl", "r", "c", 0.99),
              {"type": "fixed", "between": ["s2", 0]}],
    "ports": [{"component": "s1", "role": "input", "speed": 200, "power": 3000},
              {"component": "r", "role": "output"}]}

GIVEN_RATIO_LOSSY_COUPLING = {  # bevel pair by ratio, then K-H-V with a lossy W mechanism
    "name": "bevel + K-H-V", "components": {**_frame(), "b1": {}, "b2": {},
        "g": {"teeth": 50}, "R": {"teeth": 53, "internal": True}, "w": {}},
    "links": [{"type": "mesh", "between": ["b1", "b2"], "ratio": -2.5, "efficiency": 0.97},
              _mesh("g", "R", "b2", 0.995), {"type": "fixed", "between": ["R", 0]},
              {"type": "coupling", "between": ["g", "w"], "efficiency": 0.985}],
    "ports": [{"component": "b1", "role": "input", "speed": 100, "power": 100},
              {"component": "w", "role": "output"}]}

UNSEEN = {"stepped": STEPPED, "double_planet": DOUBLE_PLANET,
          "closed_differential": CLOSED_DIFFERENTIAL, "series": SERIES,
          "ravigneaux": RAVIGNEAUX, "given_ratio_lossy_coupling": GIVEN_RATIO_LOSSY_COUPLING}


def _with_values(data: dict, f, values: dict) -> dict:
    """The model dict with teeth / efficiencies / given ratios set from symbol values."""
    data = copy.deepcopy(data)
    keys = {str(k): k for k in data["components"]}
    for name, value in values.items():
        info = f.info[name]
        if info.kind == "teeth":
            data["components"][keys[info.component]]["teeth"] = int(value)
        elif info.kind == "efficiency":
            data["links"][info.link]["efficiency"] = float(value)
        else:
            data["links"][info.link]["ratio"] = float(value)
    return data


def _random_inside(f, rng, tries: int = 500) -> dict:
    for _ in range(tries):
        values = {}
        for name, info in f.info.items():
            if info.kind == "teeth":
                values[name] = float(max(5, info.value + rng.integers(-6, 7)))
            elif info.kind == "efficiency":
                values[name] = float(rng.uniform(0.85, 0.999))
            else:
                values[name] = info.value * float(rng.uniform(0.7, 1.4))
        if f.holds(**values):
            return values
    raise AssertionError("no random point inside the validity domain")


@pytest.mark.parametrize("key", list(UNSEEN))
def test_unseen_train_matches_solver(key) -> None:
    data = UNSEEN[key]
    model = model_from_dict(data)
    f = derive_formulas(model)
    numeric = solved(model)
    at = f.evaluate()
    assert close(at["ratio"], numeric.ratio), (at, numeric.ratio)
    assert close(at["efficiency"], numeric.efficiency), (at, numeric.efficiency)
    assert f.holds()
    rng = np.random.default_rng(sum(map(ord, key)))
    for _ in range(5):
        values = _random_inside(f, rng)
        other = solved(model_from_dict(_with_values(data, f, values)))
        at = f.evaluate(**values)
        assert close(at["ratio"], other.ratio), (values, at, other.ratio)
        assert close(at["efficiency"], other.efficiency), (values, at, other.efficiency)
        drivers = {e.link: e.driver for e in other.elements}
        assert all(drivers[d.link] == d.driver for d in f.directions)


def test_given_ratio_and_lossy_coupling_symbols() -> None:
    f = derive_formulas(model_from_dict(GIVEN_RATIO_LOSSY_COUPLING))
    assert {n: i.kind for n, i in f.info.items()} == {
        "i_0": "ratio", "eta_0": "efficiency", "z_g": "teeth", "z_R": "teeth",
        "eta_1": "efficiency", "eta_3": "efficiency"}
    # Hand derivation: bevel stage i_0 with eta_0 (b1 drives); K-H-V stage of ratio -N,
    # N = z_g/(z_R - z_g), efficiency eta_1/(N + 1 - N eta_1) (K-H-V closed form); the lossy
    # coupling passes eta_3 of the power. Stages in series multiply.
    s = f.symbols
    n = s["z_g"] / (s["z_R"] - s["z_g"])
    assert same(f.ratio, s["i_0"] * -n)
    assert same(f.efficiency, s["eta_0"] * s["eta_1"] / (n + 1 - n * s["eta_1"]) * s["eta_3"])


def test_outside_the_domain_the_pattern_changes() -> None:
    """Double planet, ring in / sun fixed: valid while z_r > z_s. Swap them: the solver's
    directions change, and ``holds`` says the formula no longer applies."""
    f = derive_formulas(model_from_dict(DOUBLE_PLANET))
    assert not all(c.always for c in f.conditions)
    swapped = {"z_s": 90.0, "z_r": 36.0}
    assert not f.holds(**swapped)
    other = solved(model_from_dict(_with_values(DOUBLE_PLANET, f, swapped)))
    drivers = {e.link: e.driver for e in other.elements}
    assert any(drivers[d.link] != d.driver for d in f.directions)
    assert not close(f.evaluate(**swapped)["efficiency"], other.efficiency, 1e-6)


# --- evaluation, lambdify, output --------------------------------------------------------------

def test_lambdify_vectorised() -> None:
    model = load_model(MODELS / "rv40e_wang2021.yaml")
    f = derive_formulas(model)
    fn = f.lambdify()
    eta = np.linspace(0.9, 0.999, 7)
    z5 = np.array([[30.0], [40.0], [50.0]])
    out = fn(eta_1=eta, z_5=z5, z_4=z5 - 1)
    assert out["efficiency"].shape == (3, 7) and out["valid"].all()
    for i, j in [(0, 0), (1, 6), (2, 3)]:
        point = f.evaluate(eta_1=eta[j], z_5=z5[i, 0], z_4=z5[i, 0] - 1)
        assert out["efficiency"][i, j] == pytest.approx(point["efficiency"], rel=1e-14)
        assert out["ratio"][i, j] == pytest.approx(1 + 36 * z5[i, 0] / 12, rel=1e-14)
    constant = derive_formulas(load_model(MODELS / "planetary_2kh_sun_to_ring.yaml")).lambdify()
    out = constant(z_ring=np.array([60.0, 72.0, 84.0]))
    assert out["efficiency"].shape == (3,)
    assert out["efficiency"] == pytest.approx([0.98 * 0.99] * 3)
    with pytest.raises(UsageError, match="z_9"):
        fn(z_9=1.0)


def test_to_dict_round_trip() -> None:
    f = derive_formulas(load_model(MODELS / "closed_differential.yaml"))
    data = f.to_dict()
    assert {"ratio", "efficiency", "latex", "directions", "conditions", "symbols"} <= set(data)
    ratio, efficiency = sp.sympify(data["ratio"]), sp.sympify(data["efficiency"])
    assert sp.cancel(ratio - f.ratio) == 0 and sp.cancel(efficiency - f.efficiency) == 0
    used = {str(s) for s in ratio.free_symbols | efficiency.free_symbols}
    assert used < set(data["symbols"])  # every symbol of the model; the planet's z_p cancels
    assert "z_p" not in used
    assert data["directions"][2] == {"link": 2, "kind": "mesh", "between": ["g1", "g2"],
                                     "carrier": 0, "driver": "g1", "factor": "eta_2"}
    assert r"\frac" in data["latex"]["efficiency"]


def test_relations_are_checked() -> None:
    model = load_model(MODELS / "rv40e_wang2021.yaml")
    with pytest.raises(UsageError, match="does not hold"):
        derive_formulas(model, {"z_4": "z_5 - 2"})
    with pytest.raises(UsageError, match="unknown symbol"):
        derive_formulas(model, {"z_9": "1"})
    with pytest.raises(UsageError, match="unknown symbol"):
        derive_formulas(model, {"z_4": "z_9 - 1"})


def test_not_applicable() -> None:
    data = copy.deepcopy(STEPPED)
    data["ports"].append({"component": "p1", "role": "output"})
    with pytest.raises(MethodNotApplicableError, match="one input and one output"):
        derive_formulas(model_from_dict(data))


def test_readable_and_sign_helpers() -> None:
    z1, z2, z4, z5, e = sp.symbols("z_1 z_2 z_4 z_5 eta_1")
    assert display(readable((z1 + z2 * z5) / z1)) == "1 + z_2*z_5/z_1"
    sign, factors = sign_factors(e * (z4 - z5) / (z1 + z2), [z1, z2, z4, z5, e],
                                 {z4: 39, z5: 40})
    assert sign == -1 and factors == [z5 - z4]


# --- the shared symbolic systems (formula/systems.py, also the sweep's symbolic backend) ---

def test_train_systems_of_a_2kh_by_hand() -> None:
    """Sun s (input: speed 1, torque 1), planets p on carrier c (output), ring fixed on the
    frame f. Willis in c: s-p, i0 = -z_p/z_s; p-ring, i1 = z_r/z_p. By hand: the planet's
    balance gives λ1 = i0 f0 λ0 with λ0 = -1 (the sun's), w_c = z_s/(z_s + z_r), and the
    carrier's reaction -(1 + η0 η1 z_r/z_s): efficiency (1 + η0 η1 k)/(1 + k), k = z_r/z_s."""
    from powergraph.analyses.formula.systems import solve_linear, train_systems

    z_s, z_p, z_r, e0, e1 = sp.symbols("z_s z_p z_r eta_0 eta_1", positive=True)
    systems = train_systems(["f", "s", "p", "c"], [("s", "p", "c"), ("p", "f", "c")],
                            [-z_p / z_s, z_r / z_p], [e0, e1], {"f": 0, "s": 1}, {"s": 1},
                            ["c", "f"])
    assert systems.free == ("p", "c") and systems.balanced == ("s", "p")
    _, (w_p, w_c) = solve_linear(systems.speed_matrix, systems.speed_rhs)
    assert same(w_c, z_s / (z_s + z_r))
    assert same(w_p, w_c - z_s / z_p * (1 - w_c))   # s-p Willis row, written out
    _, forces = solve_linear(systems.force_matrix, systems.force_rhs)
    assert forces[0] == -1 and same(forces[1], z_p * e0 / z_s)
    t_c = systems.reactions["c"].xreplace(dict(zip(systems.forces, forces)))
    assert same(t_c, -(1 + e0 * e1 * z_r / z_s))
    k = z_r / z_s
    assert same(-t_c * w_c, (1 + e0 * e1 * k) / (1 + k))


def test_stencil_is_element_stencil_exact() -> None:
    from powergraph.analyses.formula.systems import stencil
    from powergraph.kinematics.elements import element_stencil

    i, f = sp.symbols("i f")
    assert stencil(i, f) == (1, -i * f, i * f - 1)
    assert all(not c.atoms(sp.Float) for c in stencil(i, f))
    # the same numbers as the float stencil
    assert [float(c.subs({i: -2.5, f: 0.98})) for c in stencil(i, f)] == pytest.approx(
        element_stencil(-2.5, 0.98), rel=1e-15)


def test_conditions_are_plain_json_even_when_the_sign_comes_from_sympy() -> None:
    # Found by the hostile-input benchmark: a merge key turned the closed differential's
    # link 3 into a mesh s-g1 on the carrier; `formula --json` ended in "Object of type
    # BooleanTrue is not JSON serializable" (a condition's sign was a sympy Integer).
    import json

    from powergraph.model.yaml_loader import load_yaml_file

    data = load_yaml_file(MODELS / "closed_differential.yaml")
    data["links"][3] = {"type": "mesh", "between": ["s", "g1"], "carrier": "c"}
    data = json.loads(json.dumps(derive_formulas(model_from_dict(data)).to_dict()))
    assert all(type(c["always"]) is bool for c in data["conditions"])
    assert any(c["always"] for c in data["conditions"])


@pytest.mark.parametrize("name", sorted(p.name for p in (ROOT / "models").glob(
    "planetary_2kh_*.yaml") if "two_stages" not in p.name))
def test_a_back_driven_load_gives_solves_efficiency_not_its_reciprocal(name: str) -> None:
    """Issue 35: with the input giving power out (power -1 kW) the formula said 100.75 %
    where solve says 99.255 %. Both now say power leaving over power entering, <= 1;
    and the closed form is the reciprocal of the formal one (declared output / input)."""
    model = load_model(ROOT / "models" / name)
    given = model.inputs[0]
    back = model.with_port(given.index, power=-1000.0, torque=None)
    solved = pg.solve(back)
    f = derive_formulas(back)
    assert f.evaluate()["efficiency"] == pytest.approx(solved.efficiency, rel=1e-12)
    assert f.numeric["efficiency"] == pytest.approx(solved.efficiency, rel=1e-12)
    assert solved.efficiency < 1.0
    assert f.evaluate()["efficiency"] == pytest.approx(1 / solved.formal_efficiency, rel=1e-12)


def test_a_train_with_modes_needs_a_mode() -> None:
    """Issue 35: formula silently gave the first mode's closed form; now it refuses, as
    solve does, and ``--mode`` gives each gear's (the Simpson set: 1 + 1/k = 4/3 in 2nd,
    -k = -3 in reverse, k = z_r/z_s = 3)."""
    from powergraph.errors import UsageError

    model = load_model(ROOT / "models" / "simpson_3speed.yaml")
    with pytest.raises(UsageError, match="the model has modes 1, 2, 3, R"):
        derive_formulas(model)
    assert float(derive_formulas(model, mode="2").evaluate()["ratio"]) == pytest.approx(4 / 3)
    assert float(derive_formulas(model, mode="R").evaluate()["ratio"]) == pytest.approx(-3)
