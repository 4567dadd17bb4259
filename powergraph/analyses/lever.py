"""Lever diagrams of planetary sets (docs/modes.md): each set a vertical lever whose nodes
are its coaxial members, spaced so that the speeds along the lever are linear.

For a set with carrier ``c``, hold the carrier and turn a reference member at speed 1:
each coaxial member ``m`` then turns at ``p_m`` (the product of the Willis ratios along
the meshes from the reference); ``p_m`` is the node's position, the carrier at 0. For any
motion the speed of node ``m`` is ``w_c + p_m (w_ref - w_c)``: the speeds lie on a straight
line across the lever. A simple set (sun reference) has the sun at 1 and the ring at
``-z_s/z_r``: sun-carrier : carrier-ring = z_r : z_s.

Coaxial members of a carrier are the gears that take part in exactly one of its meshes
(suns and rings); its planets mesh twice or more (the steps of a stepped planet, fixed to
each other, counted together: a Wolfrom set's lever has its sun, both rings and the
carrier).

Examples
--------
>>> from powergraph.model import load_model
>>> levers = lever_diagram(load_model("models/simpson_first.yaml")).levers  # doctest: +SKIP
>>> [(n.component, round(n.position, 4)) for n in levers[0].nodes]           # doctest: +SKIP
[('s', 1.0), ('c1', 0.0), ('r1', -0.3333)]
"""
from __future__ import annotations

from collections import defaultdict
from dataclasses import field
from typing import Any, Mapping

from powergraph.errors import MethodNotApplicableError
from powergraph.format import format_number
from powergraph.kinematics.elements import willis_ratio
from powergraph.model.spec import Model
from powergraph.records import record


@record
class LeverNode:
    """One coaxial member on a lever: its position (carrier 0, reference 1), its body,
    its speed in the mode drawn (rad/s), and the shift elements acting on it."""

    component: str
    position: float
    body: str
    speed: float | None
    grounded: bool
    elements: tuple[str, ...]


@record
class Lever:
    """One planetary set: its carrier and its nodes sorted by position."""

    carrier: str
    nodes: tuple[LeverNode, ...]


@record
class LeverPort:
    """A port of the train: its name (its role when it has none), its role (``input``,
    ``output``, ``machine``), its component and body, and its speed in the mode drawn
    (rad/s; None without speeds). The lever nodes of its body are marked with it."""

    name: str
    role: str
    component: str
    body: str
    speed: float | None


@record
class LeverDiagram:
    """Every planetary set of a train as a lever, with the speeds of one mode, and the
    train's ports (which mark the nodes of their bodies)."""

    model: Model = field(repr=False, compare=False)
    mode: str | None
    levers: tuple[Lever, ...]
    ports: tuple[LeverPort, ...] = ()

    def ports_on(self, node: LeverNode) -> tuple[LeverPort, ...]:
        """The ports on ``node``'s body (an input on a shaft fixed to a carrier marks
        that carrier)."""
        return tuple(p for p in self.ports if p.body == node.body)

    @property
    def ports_off(self) -> tuple[LeverPort, ...]:
        """The ports on no lever node (wheels behind a final drive)."""
        bodies = {n.body for lever in self.levers for n in lever.nodes}
        return tuple(p for p in self.ports if p.body not in bodies)

    @property
    def title(self) -> str:
        """The train's name with the mode (once: a mode's model has it in its name)."""
        name = self.model.name
        return name if not self.mode or name.endswith(f"[{self.mode}]") else \
            f"{name} — mode {self.mode}"

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.model.name, "mode": self.mode,
                "levers": [{"carrier": lev.carrier,
                            "nodes": [{"component": n.component, "position": n.position,
                                       "body": n.body, "speed": n.speed,
                                       "grounded": n.grounded,
                                       "elements": list(n.elements)} for n in lev.nodes]}
                           for lev in self.levers],
                "ports": [{"name": p.name, "role": p.role, "component": p.component,
                           "body": p.body, "speed": p.speed} for p in self.ports]}

    def text_report(self) -> str:
        lines = [f"{self.title} — levers"]
        zero = 1e-9 * max((abs(n.speed) for lever in self.levers for n in lever.nodes
                           if n.speed is not None), default=0.0)  # round-off: no -0
        for lever in self.levers:
            lines.append(f"  carrier {lever.carrier}:")
            for n in lever.nodes:
                speed = "" if n.speed is None else f"  w = {format_number(n.speed, 6, zero)} rad/s"
                lines.append(f"    {n.component:<6} at {n.position:+.4f}{speed}"
                             + ("  (held)" if n.grounded else ""))
        return "\n".join(lines)

    def plot(self, ax: Any = None, **kwargs: Any):
        from powergraph.plot.lever import plot_levers

        return plot_levers(self, ax=ax, **kwargs)


def lever_diagram(model: Model, speeds: Mapping[str, float] | None = None,
                  mode: str | None = None) -> LeverDiagram:
    """The levers of ``model``'s planetary sets (carriers other than the frame).

    Parameters
    ----------
    model : Model
        The train (in a mode, for the bodies and the grounded nodes of that mode).
    speeds : mapping, optional
        ``{component: rad/s}`` of the motion to show (a result's ``speeds``).
    mode : str, optional
        The mode's name, for titles.

    Raises
    ------
    MethodNotApplicableError
        A train without a planetary set (every mesh on fixed axes): it has no lever.
    """
    by_carrier: dict[str, list] = defaultdict(list)
    for link in model.meshes:
        if link.carrier != model.frame:
            by_carrier[link.carrier].append(link)
    if not by_carrier:
        raise MethodNotApplicableError("no planetary set (every mesh turns on fixed axes): "
                                       "a lever diagram draws the planetary sets' levers")
    acting = _elements_on(model)
    levers = []
    for carrier, meshes in by_carrier.items():
        positions = _positions(model, carrier, meshes)
        nodes = [LeverNode(component=m, position=p, body=model.body_of[m],
                           speed=None if speeds is None else speeds.get(m),
                           grounded=model.body_of[m] == model.frame_body,
                           elements=acting.get(m, ()))
                 for m, p in positions.items()]
        levers.append(Lever(carrier, tuple(sorted(nodes, key=lambda n: -n.position))))
    ports = tuple(LeverPort(name=str(p.name) if p.name else _role_name(p, model),
                            role=p.role, component=p.component, body=model.body_of[p.component],
                            speed=None if speeds is None else speeds.get(p.component))
                  for p in model.ports)
    return LeverDiagram(model=model, mode=mode, levers=tuple(levers), ports=ports)


def _role_name(port, model: Model) -> str:
    """An unnamed port is called by its role, with its component's id when the train has
    several ports of that role (as in the power-flow diagrams)."""
    several = sum(p.role == port.role for p in model.ports) > 1
    return f"{port.role} {model.raw_id(port.component)}" if several else port.role


def _positions(model: Model, carrier: str, meshes: list) -> dict[str, float]:
    """Carrier-held speeds of the coaxial members, the first one at 1, carrier at 0.

    Planets are the gears whose body meshes twice or more in the set: the steps of a
    stepped planet (fixed to each other) count as one planet, and turn together.
    """
    body = model.body_of
    uses: dict[str, int] = defaultdict(int)
    neighbours: dict[str, list] = defaultdict(list)
    for link in meshes:
        a, b = link.between
        i = willis_ratio(link, model)           # (w_a - w_c) = i (w_b - w_c)
        uses[body[a]] += 1
        uses[body[b]] += 1
        neighbours[a].append((b, 1.0 / i))
        neighbours[b].append((a, i))
    steps: dict[str, list[str]] = defaultdict(list)      # body -> its meshing gears
    for gear in neighbours:
        steps[body[gear]].append(gear)
    for gear in neighbours:
        if uses[body[gear]] > 1:                 # a planet's steps: one speed
            neighbours[gear] += [(other, 1.0) for other in steps[body[gear]] if other != gear]
    coaxial = [g for link in meshes for g in link.between if uses[body[g]] == 1]
    coaxial = list(dict.fromkeys(coaxial))
    if not coaxial:
        return {carrier: 0.0}
    speed = {coaxial[0]: 1.0}
    todo = [coaxial[0]]
    while todo:
        gear = todo.pop()
        for other, factor in neighbours[gear]:
            if other not in speed:
                speed[other] = speed[gear] * factor
                todo.append(other)
    out = {g: speed[g] for g in coaxial if g in speed}
    out[carrier] = 0.0
    return out


def _elements_on(model: Model) -> dict[str, tuple[str, ...]]:
    """Shift elements by the members they act on (engaged or not)."""
    acting: dict[str, list[str]] = defaultdict(list)
    for element in model.shift_elements:
        for member in element.between:
            if member != model.frame:
                acting[member].append(element.name)
    return {k: tuple(v) for k, v in acting.items()}
