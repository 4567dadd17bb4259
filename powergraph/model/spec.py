"""The validated, immutable gear-train model (file format: docs/format.md).

A :class:`Model` is built by :func:`powergraph.model.model_from_dict` or
:func:`powergraph.model.load_model`; every solver takes it and never changes it.
Component ids are compared as strings: ``Component.id`` is the string form and
``Component.raw_id`` the value as written in the file (an int stays an int in JSON lists).
Its parts (:class:`Component`, :class:`Link`, :class:`ShiftElement`, :class:`Port`,
:class:`Bus`, :class:`Body`) are defined in :mod:`powergraph.model.spec_parts` and
importable from here.
"""
from __future__ import annotations

import dataclasses
from dataclasses import field
from functools import cached_property
from types import MappingProxyType
from typing import Any, Mapping

from powergraph.model.spec_parts import (LINK_TYPES, SHIFT_TYPES, Body, Bus, Component, Link,
                                         ModeSpec, Port, ShiftElement)
from powergraph.records import record

__all__ = ["LINK_TYPES", "SHIFT_TYPES", "Body", "Bus", "Component", "Link", "Model", "ModeSpec",
           "Port", "ShiftElement"]


@record
class Model:
    """A validated gear train. Immutable: solvers return new objects, never edit it."""

    name: str
    components: Mapping[str, Component]
    links: tuple[Link, ...]
    ports: tuple[Port, ...]
    bodies: tuple[Body, ...]
    body_of: Mapping[str, str]
    description: str | None = None
    source: str | None = None
    tolerances: Any = None  # top-level ``tolerances:`` (powergraph.model.block_tolerances)
    #: Caveats found while reading the model (powergraph.errors.Caveat): a speed without a
    #: unit, a planetary set that cannot be assembled... The model is still valid.
    warnings: tuple = field(default=(), compare=False)
    #: Clutches, brakes and freewheels (ShiftElement), in file order; ``links`` holds each
    #: one resolved to its current state (``fixed`` engaged, ``bearing`` open).
    shift_elements: tuple = ()
    #: ``{mode name: engaged shift-element names}`` (docs/modes.md); empty without modes.
    modes: Mapping[str, tuple[str, ...]] = field(default_factory=lambda: MappingProxyType({}))
    #: The mode this model was resolved in (powergraph.model.modes.resolve), else None.
    mode: str | None = None
    #: True when its shift elements' states were set for one operating point
    #: (powergraph.model.modes.resolve); False for a loaded model in its default state
    #: (the first mode, freewheels as loaded), whose solve says so in a warning.
    resolved: bool = field(default=False, compare=False)
    #: ``{name: Bus}`` electrical buses of the machine ports; empty without machines.
    buses: Mapping[str, "Bus"] = field(default_factory=lambda: MappingProxyType({}))
    #: The oil (powergraph.model.lubricant.Lubricant), None without a ``lubricant:`` block.
    lubricant: Any = None
    #: The heat balance (powergraph.model.lubricant.Thermal), None without ``thermal:``.
    thermal: Any = None
    #: ``{mode name: ModeSpec}``: each mode's engaged elements, inactive ports and
    #: operating point (docs/modes.md); empty without modes.
    mode_specs: Mapping[str, ModeSpec] = field(default_factory=lambda: MappingProxyType({}))
    #: Indices of the ports the mode this model is in leaves inactive: they stay in
    #: ``ports`` (their places do not move) carrying nothing (torque 0, no speed), and
    #: are left out of ``inputs``, ``outputs`` (docs/modes.md).
    inactive: frozenset = frozenset()
    #: Components the mode leaves idle: joined to no active port and not to the frame
    #: (a declutched engine shaft). They turn at no speed the train sets: the solve
    #: holds them in the frame's body, with no load, and reports their speed as None.
    idle: frozenset = frozenset()
    #: The mode whose operating point (ports, buses, inactive ports) this model is at
    #: (powergraph.model.modes.at_mode_point), else None.
    point_of: str | None = field(default=None, compare=False)

    # Derived views are computed once per model (cached_property writes the instance's
    # __dict__, which a frozen dataclass allows), so loops over a large model stay linear.
    @cached_property
    def derived(self) -> dict:
        """A store for what later layers compute once per model and reuse on every solve
        (its elements, the structure of its linear systems): keyed by the computing
        module's name; not part of the model's value (ignored by ``==``, and a
        ``dataclasses.replace`` copy starts empty)."""
        return {}

    @cached_property
    def frame(self) -> str:
        """Id of the frame component."""
        return next(c.id for c in self.components.values() if c.is_frame)

    @cached_property
    def frame_body(self) -> str:
        return self.body_of[self.frame]

    @cached_property
    def meshes(self) -> tuple[Link, ...]:
        return tuple(link for link in self.links if link.type == "mesh")

    @cached_property
    def has_bearing_losses(self) -> bool:
        """True when a bearing has ``friction``/``drag``, a component has ``drag``, or a
        seal joins two members."""
        return any(c.drag is not None or c.churning is not None
                   for c in self.components.values()) or any(
            link.type in ("bearing", "seal") and link.blocks for link in self.links)

    @cached_property
    def has_load_dependent_losses(self) -> bool:
        """True when a mesh or bearing carries a ``friction:`` block, or a bearing or
        component a ``drag:`` block: losses that the solve iterates on."""
        return self.has_bearing_losses or any("friction" in link.blocks
                                              for link in self.links)

    @cached_property
    def inputs(self) -> tuple[Port, ...]:
        """The active input ports (an inactive one, docs/modes.md, is left out)."""
        return tuple(p for p in self.ports if p.role == "input" and p.index not in self.inactive)

    @cached_property
    def outputs(self) -> tuple[Port, ...]:
        """The active output ports."""
        return tuple(p for p in self.ports if p.role == "output"
                     and p.index not in self.inactive)

    def port_label(self, index: int) -> str:
        """``ports[2] (MG1)``, or ``ports[0] (component 1)`` for a port without a name."""
        port = self.ports[index]
        return (f"{port.path} ({port.name})" if port.name else
                f"{port.path} (component {self.raw_id(port.component)})")

    @cached_property
    def machines(self) -> tuple[Port, ...]:
        """The ports with ``role: machine`` (electric machines on buses), inactive ones
        too: a solve reports each machine, an inactive one as ``inactive``."""
        return tuple(p for p in self.ports if p.role == "machine")

    @cached_property
    def _bodies_by_id(self) -> Mapping[str, Body]:
        return MappingProxyType({b.id: b for b in self.bodies})

    def body(self, body_id: str) -> Body:
        return self._bodies_by_id[body_id]

    def raw_id(self, component: str) -> int | str:
        return self.components[component].raw_id

    def shift_element(self, name: str) -> "ShiftElement":
        """The shift element called ``name`` (KeyError when there is none)."""
        return {e.name: e for e in self.shift_elements}[name]

    def in_mode(self, name: str) -> "Model":
        """This train in mode ``name``: its engaged elements rigid, the others open
        (:func:`powergraph.model.modes.resolve`; freewheels open)."""
        from powergraph.model.modes import resolve

        return resolve(self, name)

    def with_mesh_efficiency(self, efficiency: float) -> "Model":
        """A copy in which every mesh has basic efficiency ``efficiency``.

        Examples
        --------
        >>> from powergraph.model import load_model
        >>> m = load_model("models/rv40e_wang2021.yaml").with_mesh_efficiency(0.99)  # doctest: +SKIP
        """
        from powergraph.model.conform import check_efficiency

        efficiency = check_efficiency(efficiency, "--mesh-efficiency")
        links = tuple(dataclasses.replace(link, efficiency=efficiency)
                      if link.type == "mesh" else link for link in self.links)
        return dataclasses.replace(self, links=links)

    def with_link(self, index: int, **changes: Any) -> "Model":
        """A copy with ``links[index]`` changed (e.g. ``efficiency=0.998``)."""
        links = list(self.links)
        links[index] = dataclasses.replace(links[index], **changes)
        return dataclasses.replace(self, links=tuple(links))

    def with_port(self, index: int, **changes: Any) -> "Model":
        """A copy with ``ports[index]`` changed (e.g. ``role="output"``)."""
        ports = list(self.ports)
        ports[index] = dataclasses.replace(ports[index], **changes)
        return dataclasses.replace(self, ports=tuple(ports))

    def with_bus(self, name: str, **changes: Any) -> "Model":
        """A copy with bus ``name`` changed (e.g. ``battery=-5000.0``)."""
        buses = dict(self.buses)
        buses[name] = dataclasses.replace(buses[name], **changes)
        return dataclasses.replace(self, buses=MappingProxyType(buses))
