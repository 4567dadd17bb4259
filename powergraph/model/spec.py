"""The validated, immutable gear-train model (file format: docs/format.md).

A :class:`Model` is built by :func:`powergraph.model.model_from_dict` or
:func:`powergraph.model.load_model`; every solver takes it and never changes it.
Component ids are compared as strings: ``Component.id`` is the string form and
``Component.raw_id`` the value as written in the file (an int stays an int in JSON lists).
"""
from __future__ import annotations

import dataclasses
from dataclasses import field
from functools import cached_property
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Mapping

from powergraph.records import record

if TYPE_CHECKING:  # pragma: no cover
    from powergraph.model.efficiency_table import EfficiencyTable

LINK_TYPES = ("mesh", "fixed", "coupling", "bearing")
#: Link types that are shift elements (docs/modes.md): resolved to ``fixed`` (engaged) or
#: ``bearing`` (open: no constraint, only its drag) in ``Model.links``.
SHIFT_TYPES = ("clutch", "brake", "freewheel")


@record
class Component:
    """One numbered part of the train (a gear, shaft, carrier, the housing...)."""

    id: str
    raw_id: int | str
    name: str | None = None
    role: str | None = None
    kind: str | None = None
    teeth: int | None = None
    internal: bool = False
    count: int = 1
    geometry: Any = None
    note: str | None = None
    drag: Any = None  # no-load drag against the frame (block_bearing.Drag; docs/losses.md)

    @property
    def is_frame(self) -> bool:
        return self.role == "frame"

    @property
    def label(self) -> str:
        """Short label for reports: the id, with the name if there is one."""
        return f"{self.raw_id} ({self.name})" if self.name else str(self.raw_id)


@record
class Link:
    """One edge of the graph: a mesh, a fixed joint, a coupling or a bearing.

    For a mesh, ``carrier`` is the member on which both gear axes are fixed and
    ``efficiency`` the basic (carrier-held) efficiency. ``ratio`` is Willis' quotient
    ``(w_a - w_c)/(w_b - w_c)`` when given; otherwise it follows from the teeth.
    ``blocks`` holds the optional analysis blocks (``backlash``, ``cycloid``, ...), already
    validated by their own schemas.
    """

    index: int
    type: str
    between: tuple[str, str]
    raw_between: tuple[int | str, int | str]
    carrier: str | None = None
    efficiency: float = 1.0
    ratio: float | None = None
    name: str | None = None
    blocks: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))

    @property
    def path(self) -> str:
        return f"links[{self.index}]"


@record
class ShiftElement:
    """A clutch, brake or freewheel (docs/modes.md), as written at ``links[index]``.

    ``engaged`` is its state when the model is solved without a mode; ``holds`` (freewheels
    only) is the sign of ``w_a - w_b`` it allows: ``positive`` lets ``a`` overrun ``b``
    forward and holds it against turning backward relative to ``b``. ``drag`` (a
    :class:`~powergraph.model.block_bearing.Drag`) acts in its slip speed while it is open.
    """

    index: int
    kind: str
    name: str
    between: tuple[str, str]
    raw_between: tuple[int | str, int | str]
    engaged: bool = False
    holds: str | None = None
    drag: Any = None

    @property
    def path(self) -> str:
        return f"links[{self.index}]"


@record
class Port:
    """Where power enters (``input``) or leaves (``output``) the train."""

    index: int
    component: str
    role: str
    speed: float | None = None
    power: float | None = None
    torque: float | None = None
    name: str | None = None
    #: A machine's efficiency (a number, or an EfficiencyTable over speed and torque), bus
    #: and the top of its speed range (rad/s, or None: ``role: machine``, docs/hybrid.md);
    #: else None.
    efficiency: float | EfficiencyTable | None = None
    bus: str | None = None
    max_speed: float | None = None

    @property
    def path(self) -> str:
        return f"ports[{self.index}]"

    @property
    def is_machine(self) -> bool:
        return self.role == "machine"


@record
class Bus:
    """An electrical bus joining machine ports; ``battery`` is the battery's power into
    the bus (W), None when free (docs/hybrid.md)."""

    name: str
    battery: float | None = None

    @property
    def path(self) -> str:
        return f"buses.{self.name}"


@record
class Body:
    """Components joined by ``fixed`` links: one rigid body with one speed."""

    id: str
    members: tuple[str, ...]
    is_frame: bool = False


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
        """True when a bearing has ``friction``/``drag`` or a component has ``drag``."""
        return any(c.drag is not None for c in self.components.values()) or any(
            link.type == "bearing" and link.blocks for link in self.links)

    @cached_property
    def has_load_dependent_losses(self) -> bool:
        """True when a mesh or bearing carries a ``friction:`` block, or a bearing or
        component a ``drag:`` block: losses that the solve iterates on."""
        return self.has_bearing_losses or any("friction" in link.blocks
                                              for link in self.links)

    @cached_property
    def inputs(self) -> tuple[Port, ...]:
        return tuple(p for p in self.ports if p.role == "input")

    @cached_property
    def outputs(self) -> tuple[Port, ...]:
        return tuple(p for p in self.ports if p.role == "output")

    @cached_property
    def machines(self) -> tuple[Port, ...]:
        """The ports with ``role: machine`` (electric machines on buses)."""
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
        from powergraph.model.validate import check_efficiency

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
