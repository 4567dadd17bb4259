"""The ``skf:`` block of a bearing and the ``churning:`` block of a gear (docs/losses.md):
the viscous laws of :mod:`powergraph.gears.skf_bearing` and :mod:`powergraph.gears.churning`
as loss laws of a model, their viscosity bound from the model's lubricant.

``{type: bearing, between: [shaft, housing], skf: {series: "62", bore: 40 mm, outside:
80 mm, lubrication: oil_bath}}``: SKF's four-component frictional moment (rolling with the
inlet-shear and replenishment factors, sliding) at the radial load the tooth forces put on
the carried member (as a ``friction:`` bearing's) and the relative speed.

``components.X.churning: {immersion: 20 mm, oil_volume: 1.5 L}``: the churning torque of a
gear dipping into the sump (Changenet & Velex 2007) at its speed against the housing;
its pitch radius and face width come from the gear's ``geometry`` (module · teeth / 2,
``face_width``) unless given in the block.

Examples
--------
>>> law = parse_skf({"series": "62", "bore": "40 mm", "outside": "80 mm"}, "links[3].skf")
>>> from powergraph.model.lubricant import Lubricant
>>> bound = law.at_oil(Lubricant(32e-6, 5.4e-6, 870.0, 313.15 + 40.0))
>>> round(bound.torque(2000.0, 157.08) * 1e3, 1) > 0      # N·mm at 1500 rpm, 2 kN
True
"""
from __future__ import annotations

import dataclasses
from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.model.units import parse_quantity
from powergraph.records import record

#: Tooth height of a standard gear as a multiple of its module (addendum 1 + dedendum 1.25).
TOOTH_HEIGHT = 2.25


@record
class SKFFriction:
    """A rolling bearing by SKF's model: ``series`` (a key of
    :data:`powergraph.gears.skf_bearing.SERIES`), ``bore`` and ``outside`` (m),
    ``lubrication`` (``oil_bath``, ``oil_jet``, ``grease``, ``oil_air``); ``viscosity``
    (m²/s) bound from the lubricant (:meth:`at_oil`)."""

    series: str
    bore: float
    outside: float
    lubrication: str = "oil_bath"
    viscosity: float | None = None

    takes_oil = True
    #: The block it is written in (for messages: ``links[3].skf``).
    block = "skf"
    #: Not proportional to the load (an efficiency map solves its points one by one).
    affine = False

    def at_oil(self, oil: Any) -> "SKFFriction":
        return dataclasses.replace(self, viscosity=oil.viscosity())

    def torque(self, radial_load: Any, relative_speed: Any = 0.0) -> Any:
        """The bearing's frictional moment (N·m) at ``radial_load`` (N) and
        ``relative_speed`` (rad/s)."""
        from powergraph.gears.skf_bearing import skf_moment

        return skf_moment(self.series, self.bore, self.outside, radial_load, 0.0,
                          relative_speed, self.viscosity, lubrication=self.lubrication).total

    @property
    def load_dependent(self) -> bool:
        return True


@record
class ChurningLaw:
    """A gear dipping into the sump: ``pitch_radius``, ``face_width``, ``immersion`` (m),
    ``oil_volume`` (m³), ``teeth`` and ``tooth_height`` (m) for the flanks' share of the
    wetted surface; ``viscosity`` (m²/s) and ``density`` (kg/m³) bound from the
    lubricant."""

    pitch_radius: float
    face_width: float
    immersion: float
    oil_volume: float
    teeth: int = 0
    tooth_height: float = 0.0
    viscosity: float | None = None
    density: float | None = None

    takes_oil = True

    def at_oil(self, oil: Any) -> "ChurningLaw":
        return dataclasses.replace(self, viscosity=oil.viscosity(), density=oil.density)

    def caveat(self, relative_speed: float, path: str) -> Any:
        """A warning when the gear runs between the paper's two fits (6000 < Re_c < 9000,
        interpolated here), None otherwise."""
        from powergraph.errors import Caveat
        from powergraph.gears.churning import RE_C_HIGH, RE_C_LOW

        critical = abs(relative_speed) * self.pitch_radius * self.immersion / self.viscosity
        if not RE_C_LOW < critical < RE_C_HIGH:
            return None
        return Caveat(f"the churning runs between Changenet & Velex's low- and high-speed fits "
                      f"(Re_c = {critical:.0f}, fitted below {RE_C_LOW:.0f} and above "
                      f"{RE_C_HIGH:.0f}): interpolated between them, which the paper does not "
                      "give (docs/losses.md)", path, code="churning-transition")

    def torque(self, relative_speed: Any) -> Any:
        """The churning torque (N·m) at the gear's speed against the housing (rad/s)."""
        from powergraph.gears.churning import churning_torque

        return churning_torque(self.pitch_radius, self.face_width, self.immersion,
                               self.oil_volume, relative_speed, self.viscosity, self.density,
                               teeth=self.teeth, tooth_height=self.tooth_height).torque


def parse_skf(raw: Mapping, path: str) -> SKFFriction:
    """Read a bearing's ``skf:`` block (schema-checked)."""
    from powergraph.gears.skf_bearing import K_RS, SERIES

    series = str(raw["series"])
    if series not in SERIES:
        raise ModelError(f"unknown series {series!r}: " + ", ".join(SERIES), f"{path}.series")
    bore, outside = (_length(raw[k], f"{path}.{k}") for k in ("bore", "outside"))
    if not outside > bore:
        raise ModelError(f"outside ({outside * 1000:g} mm) must be larger than the bore "
                         f"({bore * 1000:g} mm)", f"{path}.outside")
    lubrication = raw.get("lubrication", "oil_bath")
    if lubrication not in K_RS:
        raise ModelError(f"unknown lubrication {lubrication!r}: " + ", ".join(K_RS),
                         f"{path}.lubrication")
    return SKFFriction(series, bore, outside, lubrication)


def parse_churning(raw: Mapping, component: Any, path: str) -> ChurningLaw:
    """Read a component's ``churning:`` block; the pitch radius and face width from its
    gear geometry unless the block gives them."""
    geometry = component.geometry
    module = getattr(geometry, "module", None)
    if "pitch_radius" in raw:
        radius = _length(raw["pitch_radius"], f"{path}.pitch_radius")
    elif module is not None and component.teeth:
        radius = module * component.teeth / 2000.0
    else:
        raise ModelError("give pitch_radius, or the gear's teeth and geometry.module",
                         f"{path}.pitch_radius")
    if "face_width" in raw:
        width = _length(raw["face_width"], f"{path}.face_width")
    elif getattr(geometry, "face_width", None):
        width = geometry.face_width / 1000.0
    else:
        raise ModelError("give face_width, or the gear's geometry.face_width",
                         f"{path}.face_width")
    volume = parse_quantity(raw["oil_volume"], "volume", f"{path}.oil_volume")
    if not volume > 0.0:
        raise ModelError(f"must be > 0, got {volume:g} m^3", f"{path}.oil_volume")
    height = TOOTH_HEIGHT * module / 1000.0 if module is not None and component.teeth else 0.0
    return ChurningLaw(radius, width, _length(raw["immersion"], f"{path}.immersion"), volume,
                       (component.teeth or 0) if height else 0, height)


def _length(value: Any, path: str) -> float:
    """A length > 0 in m."""
    mm = parse_quantity(value, "length", path)
    if not mm > 0.0:
        raise ModelError(f"must be > 0 mm, got {mm:g}", path)
    return mm / 1000.0
