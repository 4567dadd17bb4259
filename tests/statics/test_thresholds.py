"""'Nothing passes' is decided on each element's own scale, never against an absolute power
floor: tiny efficiencies and long chains give the exact products.

Expected values are products of closed-form stage efficiencies (derivations below).
"""
from __future__ import annotations

import math

import pytest

import powergraph as pg
from powergraph.model import model_from_dict
from powergraph.testing import assert_conservation


def solve(model):
    result = pg.solve(model)
    assert_conservation(result)
    return result


def chain(n_gears: int, eta: float):
    """A fixed-axis chain of ``n_gears`` gears in series: every mesh passes what its driver
    feeds times η, so the efficiency is η^(n_gears - 1) exactly."""
    components = {0: {"role": "frame"}}
    components.update({f"g{j}": {"teeth": 20 + j % 3} for j in range(n_gears)})
    links = [{"type": "mesh", "between": [f"g{j}", f"g{j + 1}"], "efficiency": eta}
             for j in range(n_gears - 1)]
    return model_from_dict({"name": "chain", "components": components, "links": links,
                            "ports": [{"component": "g0", "role": "input", "speed": 1.0,
                                       "power": 1.0},
                                      {"component": f"g{n_gears - 1}", "role": "output"}]})


def test_three_meshes_at_one_in_a_million() -> None:
    result = solve(chain(4, 1e-6))
    assert result.efficiency == pytest.approx(1e-18, rel=1e-9, abs=0)
    assert [e.driver for e in result.meshes] == ["g0", "g1", "g2"]


def test_three_hundred_gears_at_090() -> None:
    result = solve(chain(300, 0.9))
    assert result.efficiency == pytest.approx(0.9 ** 299, rel=1e-9, abs=0)
    assert math.isclose(0.9 ** 299, 2.08e-14, rel_tol=1e-2)


def test_six_alternating_planetary_stages_at_001() -> None:
    """Ring held in every stage (k = z_r/z_s = 72/24 = 3, η0 = 0.01² per stage):
    sun -> carrier: the sun drives in the carrier's frame, efficiency (1 + η0 k)/(1 + k);
    carrier -> sun: the ring drives there; the sun receives η0 × what the ring feeds:
    -T_s k = -η0 T_r, T_c = -T_s - T_r, efficiency (1 + k) η0/(η0 + k).
    Stages alternate sun->carrier, carrier->sun, joined shaft to shaft."""
    eta, k = 0.01, 3.0
    eta0 = eta * eta
    components: dict = {0: {"role": "frame"}}
    links: list = []
    ends = []
    for j in range(6):
        p = f"t{j}"
        components.update({f"{p}s": {"teeth": 24}, f"{p}p": {"teeth": 24},
                           f"{p}r": {"teeth": 72, "internal": True}, f"{p}c": {}})
        links += [{"type": "mesh", "between": [f"{p}s", f"{p}p"], "carrier": f"{p}c",
                   "efficiency": eta},
                  {"type": "mesh", "between": [f"{p}p", f"{p}r"], "carrier": f"{p}c",
                   "efficiency": eta},
                  {"type": "fixed", "between": [f"{p}r", 0]}]
        ends.append((f"{p}s", f"{p}c") if j % 2 == 0 else (f"{p}c", f"{p}s"))
    for (_, out), (inp, _) in zip(ends, ends[1:]):
        links.append({"type": "fixed", "between": [out, inp]})
    model = model_from_dict({"name": "six stages", "components": components, "links": links,
                             "ports": [{"component": ends[0][0], "role": "input",
                                        "speed": 100.0, "power": 1000.0},
                                       {"component": ends[-1][1], "role": "output"}]})
    forward = (1 + eta0 * k) / (1 + k)
    backward = (1 + k) * eta0 / (eta0 + k)
    result = solve(model)
    assert result.lock is None
    assert result.efficiency == pytest.approx((forward * backward) ** 3, rel=1e-9, abs=0)
    assert result.ratio == pytest.approx(1.0, rel=1e-12)
