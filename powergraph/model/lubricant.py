"""The model's ``lubricant:`` and ``thermal:`` blocks (docs/losses.md).

``lubricant: {viscosity_40: 32 cSt, viscosity_100: 5.4 cSt, density: 870 kg/m^3,
temperature: 80 degC}`` — or ``{grade: ISO VG 220, temperature: 80 degC}`` — gives the oil's
kinematic viscosity at any temperature by the Walther equation of ASTM D341,

    log10(log10(ν + 0.7)) = A − B·log10(T)      (ν in mm²/s, T in K),

through the two points (40 °C, ν40) and (100 °C, ν100). Every viscous law (the ISO/TR
14179-2 mesh friction without its own ``viscosity``, an open wet clutch's drag) takes the
viscosity at the oil's temperature from it: the model's laws are bound to that viscosity
when the model is read, and again at any other temperature by :func:`at_temperature` (the
heat balance, :mod:`powergraph.statics.thermal`). The density is taken as constant.

``thermal: {ambient: 20 degC, heat_transfer: 18 W/(m^2*K), area: 0.3 m^2, cooler: 0 W}``
asks for the oil temperature at which the losses equal the heat the housing gives off,
``h·A·(T − T_ambient)``, plus what a cooler takes away.

Examples
--------
>>> oil = parse_lubricant({"viscosity_40": "32 cSt", "viscosity_100": "5.4 cSt",
...                        "density": "870 kg/m^3", "temperature": "80 degC"}, "lubricant")
>>> round(oil.viscosity() * 1e6, 2)          # cSt at 80 °C
8.53
>>> round(parse_lubricant({"grade": "ISO VG 220"}, "lubricant").viscosity(313.15) * 1e6, 6)
220.0

References
----------
ASTM D341-20, Standard practice for viscosity–temperature equations and charts for liquid
petroleum or hydrocarbon products (the Walther equation, constant 0.7 for ν ≥ 2 mm²/s).
ISO 3448:1992, Industrial liquid lubricants — ISO viscosity classification (the grades'
mid-point viscosities at 40 °C).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any, Mapping

import numpy as np

from powergraph.errors import ModelError
from powergraph.model.units import parse_quantity, parse_temperature
from powergraph.records import record

#: 0 °C in kelvin; the Walther equation's two reference temperatures (K).
ZERO_C = 273.15
T40, T100 = ZERO_C + 40.0, ZERO_C + 100.0
#: ISO VG grades: (ν40 mm²/s, ν100 mm²/s, density kg/m³). ν40 is the grade's mid-point
#: (ISO 3448); ν100 and the density are typical of a mineral gear oil of viscosity index
#: about 95–100 (rounded from makers' data sheets); give ``viscosity_100`` and ``density``
#: to use an oil's own values.
GRADES = {32: (32.0, 5.4, 870.0), 46: (46.0, 6.8, 875.0), 68: (68.0, 8.7, 880.0),
          100: (100.0, 11.2, 885.0), 150: (150.0, 14.7, 890.0), 220: (220.0, 19.0, 895.0),
          320: (320.0, 24.1, 900.0), 460: (460.0, 30.8, 900.0), 680: (680.0, 39.2, 905.0)}
#: The oil's temperature limit (K) unless ``max_temperature`` is given: 150 °C, about where
#: a mineral gear oil's oxidation life becomes too short to run at.
DEFAULT_LIMIT = ZERO_C + 150.0
#: Temperatures read at all (K): from -60 °C to 300 °C; outside, a number is a mistake
#: (``temperature: 80`` meant as °C is 80 K).
READ_RANGE = (ZERO_C - 60.0, ZERO_C + 300.0)


@record
class Lubricant:
    """The oil: ``viscosity_40``, ``viscosity_100`` (m²/s), ``density`` (kg/m³),
    ``temperature`` (K, where the model runs unless a heat balance sets it),
    ``max_temperature`` (K, its limit) and ``grade`` (as written, or None)."""

    viscosity_40: float
    viscosity_100: float
    density: float
    temperature: float
    max_temperature: float = DEFAULT_LIMIT
    grade: str | None = None

    def viscosity(self, temperature: Any = None) -> Any:
        """Kinematic viscosity (m²/s) at ``temperature`` (K; the oil's own by default),
        by the Walther equation through the 40 °C and 100 °C points. Arrays too.

        >>> oil = Lubricant(32e-6, 5.4e-6, 870.0, 353.15)
        >>> round(oil.viscosity(T40) * 1e6, 9), round(oil.viscosity(T100) * 1e6, 9)
        (32.0, 5.4)
        """
        t = self.temperature if temperature is None else temperature
        w40, w100 = (math.log10(math.log10(v * 1e6 + 0.7))
                     for v in (self.viscosity_40, self.viscosity_100))
        slope = (w40 - w100) / (math.log10(T100) - math.log10(T40))
        walther = w40 - slope * (np.log10(t) - math.log10(T40))
        nu = (10.0 ** (10.0 ** walther) - 0.7) * 1e-6
        return float(nu) if np.ndim(nu) == 0 else nu

    def dynamic_viscosity(self, temperature: Any = None) -> Any:
        """Dynamic viscosity μ = ν·ρ (Pa·s) at ``temperature`` (K)."""
        return self.viscosity(temperature) * self.density

    def to_dict(self) -> dict[str, float]:
        """``{temperature, viscosity, density}`` in SI (K, m²/s, kg/m³): ``solve --json``."""
        return {"temperature": self.temperature, "viscosity": self.viscosity(),
                "density": self.density}


@record
class Thermal:
    """A heat balance: ``ambient`` (K), ``heat_transfer`` h (W/(m²·K)), ``area`` A (m²),
    ``cooler`` (W taken away by a cooler, 0 without)."""

    ambient: float
    heat_transfer: float
    area: float
    cooler: float = 0.0

    def heat(self, temperature: Any) -> Any:
        """The heat given off at oil ``temperature`` (K): h·A·(T − T_ambient) + cooler."""
        return self.heat_transfer * self.area * (temperature - self.ambient) + self.cooler


def parse_lubricant(raw: Mapping, path: str) -> Lubricant:
    """Read a ``lubricant:`` block (already checked against the schema)."""
    grade = raw.get("grade")
    nu40 = nu100 = density = None
    if grade is not None:
        nu40, nu100, density = (x * f for x, f in zip(_grade(grade, f"{path}.grade"),
                                                      (1e-6, 1e-6, 1.0)))
        if "viscosity_40" in raw:
            raise ModelError("give grade or viscosity_40, not both", f"{path}.viscosity_40")
    elif "viscosity_40" not in raw or "viscosity_100" not in raw:
        raise ModelError("give grade, or viscosity_40 and viscosity_100", path)
    if "viscosity_40" in raw:
        nu40 = _positive(raw["viscosity_40"], "kinematic viscosity", f"{path}.viscosity_40")
    if "viscosity_100" in raw:
        nu100 = _positive(raw["viscosity_100"], "kinematic viscosity", f"{path}.viscosity_100")
    if not 2e-6 <= nu100 < nu40:
        raise ModelError(f"viscosity_100 must be at least 2 cSt (the Walther equation's range) "
                         f"and below viscosity_40 ({nu40 * 1e6:g} cSt), got "
                         f"{nu100 * 1e6:g} cSt", f"{path}.viscosity_100")
    if "density" in raw:
        density = _positive(raw["density"], "density", f"{path}.density")
    elif density is None:
        raise ModelError("give the oil's density (e.g. 870 kg/m^3)", path)
    if not 500.0 <= density <= 2000.0:
        raise ModelError(f"an oil's density lies between 500 and 2000 kg/m^3, got {density:g}",
                         f"{path}.density")
    limit = _temperature(raw.get("max_temperature", DEFAULT_LIMIT), f"{path}.max_temperature")
    temperature = _temperature(raw.get("temperature", T40), f"{path}.temperature")
    if temperature > limit:
        raise ModelError(f"{temperature - ZERO_C:g} degC is above the oil's limit "
                         f"(max_temperature {limit - ZERO_C:g} degC)", f"{path}.temperature")
    return Lubricant(nu40, nu100, density, temperature, limit,
                     None if grade is None else str(grade))


def parse_thermal(raw: Mapping, path: str) -> Thermal:
    """Read a ``thermal:`` block (already checked against the schema)."""
    cooler = parse_quantity(raw.get("cooler", 0.0), "power", f"{path}.cooler")
    if cooler < 0.0:
        raise ModelError(f"a cooler takes heat away: give its power >= 0, got {cooler:g} W",
                         f"{path}.cooler")
    return Thermal(ambient=_temperature(raw["ambient"], f"{path}.ambient"),
                   heat_transfer=_positive(raw["heat_transfer"], "heat transfer coefficient",
                                           f"{path}.heat_transfer"),
                   area=_positive(raw["area"], "area", f"{path}.area"), cooler=cooler)


def needs_oil(law: Any) -> bool:
    """True for a law that takes the oil's viscosity (``takes_oil``; bound by its
    ``at_oil(lubricant)``)."""
    return bool(getattr(law, "takes_oil", False))


def at_temperature(model: Any, temperature: float) -> Any:
    """``model`` with its oil at ``temperature`` (K) and every viscous law bound to the
    viscosity there (the laws of its links, shift elements and components)."""
    oil = dataclasses.replace(model.lubricant, temperature=float(temperature))
    return bind_oil(dataclasses.replace(model, lubricant=oil))


def fixed_temperature(model: Any, temperature: float, where: str = "--oil-temperature") -> Any:
    """``model`` at oil ``temperature`` (K) without its heat balance: a catalogue's
    "efficiency at 40 °C". Refused (naming ``where``) for a model without a lubricant, or
    a temperature outside the oil's range.

    >>> from powergraph.model import load_model
    >>> cold = fixed_temperature(load_model("models/rv40e.yaml"), ZERO_C + 40)
    >>> cold.thermal is None, round(cold.lubricant.viscosity(), 9)
    (True, 0.00032)
    """
    from powergraph.errors import UsageError

    if model.lubricant is None:
        raise UsageError(f"{where}: the model has no lubricant: block (docs/losses.md)")
    low = READ_RANGE[0]
    if not low <= temperature <= model.lubricant.max_temperature:
        raise UsageError(f"{where}: {temperature - ZERO_C:g} degC is outside the oil's range "
                         f"({low - ZERO_C:g} to {model.lubricant.max_temperature - ZERO_C:g} "
                         "degC, its max_temperature)")
    return at_temperature(dataclasses.replace(model, thermal=None), temperature)


def bind_oil(model: Any) -> Any:
    """``model`` with every law that takes the oil's viscosity bound to its lubricant at
    the lubricant's temperature; a model without a ``lubricant:`` block and such a law is
    refused, naming the law's place."""
    oil = model.lubricant

    def bound(law: Any, path: str) -> Any:
        if not needs_oil(law):
            return law
        if oil is None:
            raise ModelError("this law takes the oil's viscosity: give the model a "
                             "lubricant: block (docs/losses.md)", path)
        return law.at_oil(oil)

    links = tuple(dataclasses.replace(link, blocks=type(link.blocks)(
        {k: bound(v, f"{link.path}.{k}") for k, v in link.blocks.items()}))
        if any(map(needs_oil, link.blocks.values())) else link for link in model.links)
    shifts = tuple(dataclasses.replace(e, drag=bound(e.drag, f"links[{e.index}].drag"))
                   if needs_oil(e.drag) else e for e in model.shift_elements)
    components = {cid: dataclasses.replace(
        c, drag=bound(c.drag, f"components.{c.raw_id}.drag"),
        churning=bound(c.churning, f"components.{c.raw_id}.churning"))
        if needs_oil(c.drag) or needs_oil(c.churning) else c
        for cid, c in model.components.items()}
    if links == model.links and shifts == model.shift_elements and all(
            components[cid] is c for cid, c in model.components.items()):
        return model
    return dataclasses.replace(model, links=links, shift_elements=shifts,
                               components=type(model.components)(components))


def _grade(raw: Any, path: str) -> tuple[float, float, float]:
    text = str(raw).upper().replace("ISO", "").replace("VG", "").strip()
    try:
        number = int(text)
    except ValueError:
        number = None
    if number not in GRADES:
        raise ModelError(f"unknown grade {raw!r}: ISO VG " + ", ".join(map(str, GRADES)),
                         path)
    return GRADES[number]


def _positive(raw: Any, kind: str, path: str) -> float:
    value = parse_quantity(raw, kind, path)
    if not value > 0.0:
        raise ModelError(f"must be > 0, got {value:g}", path)
    return value


def _temperature(raw: Any, path: str) -> float:
    kelvin = parse_temperature(raw, path)
    low, high = READ_RANGE
    if not low <= kelvin <= high:
        raise ModelError(f"{kelvin:g} K ({kelvin - ZERO_C:g} degC) is not a temperature a "
                         "gearbox runs at; write the unit (e.g. 80 degC)", path)
    return kelvin
