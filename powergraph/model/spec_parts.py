"""The parts of a :class:`~powergraph.model.spec.Model`: components, links, shift elements,
ports, buses and rigid bodies (immutable records, no behaviour beyond their views).

They live apart from the model so that what builds them (the rigid bodies of
:mod:`powergraph.model.graph`, the shift elements of :mod:`powergraph.model.shift`) need
not import :mod:`powergraph.model.spec`, whose ``Model.in_mode`` calls those modules;
:mod:`powergraph.model.spec` re-exports every name here.

Examples
--------
>>> Component(id="1", raw_id=1, name="sun").label
'1 (sun)'
>>> Link(index=2, type="mesh", between=("1", "2"), raw_between=(1, 2)).path
'links[2]'
"""
from __future__ import annotations

from dataclasses import field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Mapping

from powergraph.records import record

if TYPE_CHECKING:  # pragma: no cover
    from powergraph.model.efficiency_table import EfficiencyTable

LINK_TYPES = ("mesh", "fixed", "coupling", "bearing", "seal")
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
    churning: Any = None  # dipped in the sump (block_spin.ChurningLaw; docs/losses.md)

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
class ModeSpec:
    """One entry of the modes table (docs/modes.md): the clutches and brakes it engages,
    the ports it leaves ``inactive`` (indices into ``Model.ports``: they carry nothing in
    the mode), and its operating point: ``ports`` ``{port index: {field: value}}`` with
    ``field`` ``speed``, ``power`` or ``torque`` (SI; None for ``free``: the mode drops
    the model's value) and ``buses`` ``{bus name: battery power}`` (W; None for
    ``free``). A mode written as a plain list engages its elements and changes nothing
    else.

    >>> ModeSpec(engaged=("C1",), inactive=(0,)).changes_point
    True
    """

    engaged: tuple[str, ...]
    inactive: tuple[int, ...] = ()
    ports: Mapping[int, Mapping[str, float | None]] = field(
        default_factory=lambda: MappingProxyType({}))
    buses: Mapping[str, float | None] = field(default_factory=lambda: MappingProxyType({}))

    @property
    def changes_point(self) -> bool:
        """The mode changes the model's ports or buses (not only its shift elements)."""
        return bool(self.inactive or self.ports or self.buses)


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
