"""The oil temperature from a heat balance (the model's ``thermal:`` block; docs/losses.md).

The losses heat the oil and the housing gives the heat off: in the steady state

    total loss(T) = h · A · (T − T_ambient) + P_cooler,

where the loss depends on the temperature through the oil's viscosity (open wet clutches'
drag, the ISO/TR 14179-2 mesh friction, any law that takes the oil). The temperature is the
root of that balance between the ambient and the oil's limit, found by Brent's method
(:func:`scipy.optimize.brentq`) on whole solves at each trial temperature
(:func:`powergraph.model.lubricant.at_temperature`), so the answer is the solve's own at
the temperature found: the root is bracketed to 1e-12 K, so the balance closes to the
loss's own round-off times h·A.

Verdicts (:attr:`ThermalState.verdict`): ``ok``; ``at ambient`` when the cooler takes
away at least the losses at ambient (the oil does not warm up: the answer is at ambient);
``over the oil's limit`` when the losses at the oil's ``max_temperature`` still exceed what
the housing gives off there: no steady state below the limit, the answer shown is at the
limit, with a warning; ``does not settle`` when the iteration does not converge (a loss
that grows faster with the temperature than h·A: the answer shown is the last step's).

Examples
--------
>>> import powergraph as pg
>>> from powergraph.model import model_from_dict
>>> train = model_from_dict({"name": "sealed pair",
...     "lubricant": {"grade": "ISO VG 68", "temperature": "40 degC"},
...     "thermal": {"ambient": "20 degC", "heat_transfer": 10, "area": 0.1},
...     "components": {0: {"role": "frame"}, 1: {"teeth": 20}, 2: {"teeth": 40}},
...     "links": [{"type": "mesh", "between": [1, 2], "efficiency": 0.98}],
...     "ports": [{"component": 1, "role": "input", "speed": 100, "power": 100},
...               {"component": 2, "role": "output"}]})
>>> state = pg.solve(train).thermal        # 2 W lost = 10 * 0.1 * (T - 293.15)
>>> round(state.temperature - 273.15, 6), round(state.heat_dissipated, 9), state.verdict
(22.0, 2.0, 'ok')
"""
from __future__ import annotations

import dataclasses
from typing import Any, Callable, Mapping

from powergraph.errors import Caveat
from powergraph.model.lubricant import ZERO_C, at_temperature
from powergraph.model.spec import Model
from powergraph.records import record

#: The balance's closing tolerance, relative to the loss; the most solves it may take.
RTOL, MAX_STEPS = 1e-9, 100
VERDICTS = ("ok", "at ambient", "over the oil's limit", "does not settle")


@record
class ThermalState:
    """The settled heat balance: the oil ``temperature`` (K), the ``heat_dissipated`` there
    (W: the housing's plus the cooler's, equal to the total loss when ``verdict`` is
    ``ok``), the ``ambient`` (K) and the ``verdict`` (:data:`VERDICTS`)."""

    temperature: float
    heat_dissipated: float
    ambient: float
    verdict: str

    def to_dict(self) -> dict[str, Any]:
        return {"temperature": self.temperature, "heat_dissipated": self.heat_dissipated,
                "ambient": self.ambient, "verdict": self.verdict}

    def caveats(self) -> tuple[Caveat, ...]:
        """A warning unless the balance settled between the ambient and the limit."""
        if self.verdict == "over the oil's limit":
            return (Caveat(f"the losses still exceed the heat given off at the oil's limit "
                           f"({self.temperature - ZERO_C:g} degC): no steady temperature "
                           "below it; the answer shown is at the limit (add area, a cooler, "
                           "or a better-cooled housing)", "thermal", code="overheats"),)
        if self.verdict == "does not settle":
            return (Caveat("the heat balance does not settle: the losses change faster with "
                           "the oil temperature than the housing's h·A; the answer shown is "
                           f"at {self.temperature - ZERO_C:g} degC", "thermal",
                           code="thermal-unsettled"),)
        if self.verdict == "at ambient":
            return (Caveat("the cooler takes away at least the losses at ambient: the oil "
                           "stays at the ambient temperature", "thermal.cooler",
                           code="cooler-exceeds-losses"),)
        return ()


def solve_thermal(model: Model, speeds: Mapping[str, float] | None,
                  solve: Callable) -> Any:
    """``solve(model, speeds)`` at the oil temperature of ``model.thermal``'s balance;
    the result carries the :class:`ThermalState` in ``thermal``.

    The temperature is the fixed point of ``T = T_ambient + (loss(T) − P_cooler)/(h·A)``,
    iterated from the lubricant's own temperature: each step is a whole solve at the last
    temperature, and the iteration stops when the balance closes to :data:`RTOL` of the
    loss at the temperature of the answer. It contracts as long as the loss changes by
    less than h·A per kelvin (viscous losses fall as the oil warms); otherwise, or when
    it leaves the range between the ambient and the oil's limit, the verdict says so.
    """
    balance, oil = model.thermal, model.lubricant
    plain = dataclasses.replace(model, thermal=None)
    low, high = balance.ambient, max(oil.max_temperature, balance.ambient)
    temperature, verdict = min(max(oil.temperature, low), high), "does not settle"
    for _ in range(MAX_STEPS):
        result = solve(at_temperature(plain, temperature), speeds)
        residual = result.total_loss - balance.heat(temperature)
        if abs(residual) <= RTOL * max(result.total_loss, balance.heat(temperature), 1e-300):
            verdict = "ok"
            break
        following = low + (result.total_loss - balance.cooler) / (
            balance.heat_transfer * balance.area)
        if following <= low and temperature == low:
            verdict = "at ambient"
            break
        if following >= high and temperature == high:
            verdict = "over the oil's limit"
            break
        temperature = min(max(following, low), high)
    heat = result.total_loss if verdict == "ok" else balance.heat(temperature)
    return dataclasses.replace(result, thermal=ThermalState(
        float(temperature), float(heat), balance.ambient, verdict))
