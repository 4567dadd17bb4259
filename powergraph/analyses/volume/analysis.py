"""Volume of a model: each component's ``geometry`` block → Pan & Wang (2019)'s
formulas.

Functions over the model; the model is never changed.
"""
from __future__ import annotations

import math
from types import MappingProxyType

from powergraph.analyses.volume import formulas
from powergraph.analyses.volume.cycloid_profile import cycloid_disc_area
from powergraph.analyses.volume.involute import profile_area
from powergraph.analyses.volume.result import ComponentVolume, VolumeResult
from powergraph.errors import ModelError
from powergraph.model.block_geometry import (
    CrankshaftGeometry,
    CycloidDiscGeometry,
    GearGeometry,
    NeedleGearGeometry,
    PlanetFrame1Geometry,
    PlanetFrame2Geometry,
)
from powergraph.model.spec import Component, Model


def model_volume(model: Model) -> VolumeResult | None:
    """Volumes of a model, or None when no component has a ``geometry`` block.

    This is the entry point for ``compare``: ``model_volume(m).total_mm3``, and
    ``result.power_density(output_power_w)`` for the power density in kW/L.

    Parameters
    ----------
    model : Model

    Returns
    -------
    VolumeResult or None

    Raises
    ------
    ModelError
        A geometry block that cannot be built (path names the key).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> model_volume(load_model("models/rv40e_wang2021.yaml")).total_mm3 > 0   # doctest: +SKIP
    True
    """
    parts = {cid: component_volume(model, c) for cid, c in model.components.items()
             if c.geometry is not None}
    return VolumeResult(model.name, MappingProxyType(parts)) if parts else None


def volume(model: Model) -> VolumeResult:
    """Like :func:`model_volume`, but a model with no geometry at all is an error.

    Raises
    ------
    ModelError
        No component has a ``geometry`` block, or one cannot be built.

    Examples
    --------
    >>> from powergraph.model import loads_model
    >>> m = loads_model('''
    ... name: one gear
    ... components:
    ...   0: {role: frame}
    ...   1: {teeth: 20, geometry: {shape: gear, module: 1, face_width: 10, bore_radius: 0}}
    ...   2: {teeth: 40}
    ... links: [{type: mesh, between: [1, 2], carrier: 0}]
    ... ports: [{component: 1, role: input}, {component: 2, role: output}]
    ... ''')
    >>> round(volume(m).total_mm3 / math.pi, 9)       # π·10·(20²/4)
    1000.0
    """
    result = model_volume(model)
    if result is None:
        raise ModelError("no component has a geometry block, so there is no volume to "
                         "compute; add components.ID.geometry (shape: gear, cycloid_disc, "
                         "needle_gear, crankshaft, planet_frame_1 or planet_frame_2)",
                         "components")
    return result


def component_volume(model: Model, component: Component) -> ComponentVolume:
    """Volume of one component with a geometry block (see :func:`volume`)."""
    geometry = component.geometry
    path = f"components.{component.raw_id}.geometry"
    if type(geometry) not in _VOLUMES:
        raise ModelError("geometry block was not validated (build models with "
                         "powergraph.model.model_from_dict or load_model)", path)
    geometry.check_teeth(component.teeth, path)
    unit, exact = _VOLUMES[type(geometry)](model, component, geometry, path)
    if unit <= 0:
        raise ModelError(f"the holes and pockets are larger than the part: the formula of "
                         f"Eq. {geometry.equation} gives {unit:.6g} mm³", path)
    return ComponentVolume(component=component.id, name=component.name,
                           shape=geometry.shape, equation=geometry.equation,
                           count=component.count, unit_mm3=unit, exact_unit_mm3=exact)


def _gear(model: Model, component: Component, g: GearGeometry, path: str):
    if component.internal:
        raise ModelError("shape gear is the external gear of Eqs. (1)–(2); this component "
                         "is internal", f"{path}.shape")
    unit = formulas.gear_volume(g.module, component.teeth, g.face_width, g.bore_radius)
    try:
        outline = profile_area(g.module, component.teeth)
    except ValueError:           # pointed teeth: no exact outline for this tooth number
        return unit, None
    return unit, (outline - math.pi * g.bore_radius ** 2) * g.face_width


def _cycloid_disc(model: Model, component: Component, g: CycloidDiscGeometry, path: str):
    unit = formulas.cycloid_disc_volume(
        g.width, g.pin_circle_radius, g.pin_radius, g.eccentricity, g.crank_hole_radius,
        g.crank_holes, g.pillar_radius, g.pillar_holes, g.center_bore_radius)
    if component.teeth is None:
        return unit, None
    try:   # RV discs have one tooth fewer than pins: z_p = teeth + 1
        outline = cycloid_disc_area(g.pin_circle_radius, g.pin_radius, g.eccentricity,
                                    component.teeth + 1)
    except ValueError as exc:
        raise ModelError(str(exc), f"{path}.pin_radius") from None
    holes = math.pi * (g.pillar_holes * (g.pillar_radius + g.eccentricity) ** 2
                       + g.crank_holes * g.crank_hole_radius ** 2 + g.center_bore_radius ** 2)
    return unit, (outline - holes) * g.width


def _needle_gear(model: Model, component: Component, g: NeedleGearGeometry, path: str):
    return formulas.needle_gear_volume(g.width, g.pin_circle_radius, g.pin_radius,
                                       g.shell_thickness, component.teeth), None


def _crankshaft(model: Model, component: Component, g: CrankshaftGeometry, path: str):
    return formulas.crankshaft_volume(g.shaft_radius, g.gear_seat_length, g.bearing_width,
                                      g.journal_radius, g.journal_length, g.journals), None


def _planet_frame_1(model: Model, component: Component, g: PlanetFrame1Geometry, path: str):
    return formulas.planet_frame_1_volume(g.bearing_seat_radius, g.bearing_width,
                                          g.crank_bearing_radius, g.crank_bearing_width,
                                          g.crank_bearings), None


def _planet_frame_2(model: Model, component: Component, g: PlanetFrame2Geometry, path: str):
    sun = _gear_ref(model, g.sun, f"{path}.sun", needs_geometry=True)
    planet = _gear_ref(model, g.planet, f"{path}.planet", needs_geometry=False)
    if isinstance(planet.geometry, GearGeometry) and planet.geometry.module != sun.geometry.module:
        raise ModelError(f"sun {sun.raw_id} (module {sun.geometry.module:g}) and planet "
                         f"{planet.raw_id} (module {planet.geometry.module:g}) must have the "
                         "same module", f"{path}.planet")
    gear_width = sun.geometry.face_width
    if gear_width + g.crank_bearing_width - g.bearing_width <= 0:
        raise ModelError(f"B1 + B3 − B4 = {gear_width:g} + {g.crank_bearing_width:g} − "
                         f"{g.bearing_width:g} mm must be > 0 (B1: face width of sun "
                         f"{sun.raw_id})", f"{path}.bearing_width")
    return formulas.planet_frame_2_volume(
        g.seal_radius, g.bearing_seat_radius, g.bearing_width, g.crank_bearing_radius,
        g.crank_bearing_width, g.crank_bearings, g.pillar_radius, g.pillars, g.pillar_length,
        sun.geometry.module, sun.teeth, planet.teeth, planet.count, gear_width), None


def _gear_ref(model: Model, cid: str, path: str, needs_geometry: bool) -> Component:
    gear = model.components.get(cid)
    if gear is None:
        raise ModelError(f"unknown component {cid!r}", path)
    if gear.teeth is None:
        raise ModelError(f"component {cid!r} has no teeth", path)
    if needs_geometry and not isinstance(gear.geometry, GearGeometry):
        raise ModelError(f"component {cid!r} needs a gear geometry block (its module and "
                         "face width are the frame's m and B1)", path)
    return gear


_VOLUMES = {GearGeometry: _gear, CycloidDiscGeometry: _cycloid_disc,
            NeedleGearGeometry: _needle_gear, CrankshaftGeometry: _crankshaft,
            PlanetFrame1Geometry: _planet_frame_1, PlanetFrame2Geometry: _planet_frame_2}
