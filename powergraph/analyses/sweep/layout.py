"""What a sweep keeps fixed: the train's structure, resolved once to index arrays.

Bodies, which body each element's gear a, gear b and carrier is on, which ports give a
speed and which a load, the frame: none of these change across variants. What varies are
the Willis ratios (from teeth or a mesh's ``ratio``), the efficiencies and the ports'
speeds, powers and torques (DESIGN §2–3).
"""
from __future__ import annotations

from dataclasses import dataclass

from powergraph.analyses.sweep.paths import Parameter
from powergraph.kinematics import degrees_of_freedom, elements_of, solve_speeds
from powergraph.model.spec import Model
from powergraph.statics.equilibrium import loads_of, solve_equilibrium


@dataclass(frozen=True)
class TeethRatio:
    """Willis ratio of mesh ``element`` from teeth: ``sign * z[b] / z[a]``."""

    element: int
    gear_a: str
    gear_b: str
    sign: float


@dataclass(frozen=True)
class Load:
    """A port whose power or torque is given: its body, port index, kind and role."""

    body: int
    port: int
    kind: str      # "power" or "torque" (the first input's default 1 W is a power)
    role: str      # "input" or "output"


@dataclass(frozen=True)
class Layout:
    """The fixed structure of a swept train (indices into ``model.bodies``)."""

    model: Model
    params: tuple[Parameter, ...]
    links: tuple[int, ...]              # link index of each element
    kinds: tuple[str, ...]              # "mesh" / "coupling" per element
    body_a: tuple[int, ...]
    body_b: tuple[int, ...]
    body_c: tuple[int, ...]
    frame: int
    teeth_ratios: tuple[TeethRatio, ...]
    signs: tuple[float, ...]            # Willis ratio = sign * magnitude, per element
    speed_ports: tuple[tuple[int, int | None], ...]   # (body, port index or None=default)
    loads: tuple[Load, ...]
    unknown: tuple[int, ...]            # bodies whose external torque is solved for
    inputs: tuple[int, ...]             # body of each input port
    outputs: tuple[int, ...]            # body of each output port
    ratio_bodies: tuple[int, int] | None   # (input, output) body for the ratio
    determinate: bool                   # load sharing fixed by statics at the base values

    @property
    def n_bodies(self) -> int:
        return len(self.model.bodies)

    @property
    def n_elements(self) -> int:
        return len(self.links)

    @property
    def known_speed_bodies(self) -> tuple[int, ...]:
        return (self.frame,) + tuple(body for body, _ in self.speed_ports)

    @property
    def free_bodies(self) -> tuple[int, ...]:
        """Bodies whose speed is solved for."""
        known = set(self.known_speed_bodies)
        return tuple(j for j in range(self.n_bodies) if j not in known)

    @property
    def balance_bodies(self) -> tuple[int, ...]:
        """Bodies with no unknown external torque: their balance fixes the element forces."""
        unknown = set(self.unknown)
        return tuple(j for j in range(self.n_bodies) if j not in unknown)


def layout_of(model: Model, params: tuple[Parameter, ...]) -> Layout:
    """Resolve the structure of ``model`` with ``params`` swept (validated on a probe).

    The probe is the model with every swept port value set (to its value, or 1), solved
    once by the validated single solver: wrong DOF, speeds that do not fix the motion or
    loads that are not determined raise the single solver's own ModelError.
    """
    probe = _probe(model, params)
    kin = solve_speeds(probe)
    elements = elements_of(probe)
    loads = loads_of(probe, kin)
    eq = solve_equilibrium(probe, elements, loads, [1.0] * len(elements))
    column = {body.id: j for j, body in enumerate(model.bodies)}
    speed_ports = _speed_ports(probe, column)
    load_list = _loads(probe, column)
    inputs, outputs = probe.inputs, probe.outputs
    ratio_bodies = (column[probe.body_of[inputs[0].component]],
                    column[probe.body_of[outputs[0].component]]) \
        if len(inputs) == 1 and len(outputs) == 1 else None
    teeth = _teeth_ratios(model, params, elements)
    signs = [1.0] * len(elements)
    for tr in teeth:
        signs[tr.element] = tr.sign
    return Layout(
        model=model, params=params, links=tuple(e.link for e in elements),
        kinds=tuple(e.kind for e in elements),
        body_a=tuple(column[e.body_a] for e in elements),
        body_b=tuple(column[e.body_b] for e in elements),
        body_c=tuple(column[e.body_c] for e in elements),
        frame=column[model.frame_body], teeth_ratios=teeth,
        signs=tuple(signs),
        speed_ports=speed_ports, loads=load_list,
        unknown=tuple(column[b] for b in loads.unknown),
        inputs=tuple(column[probe.body_of[p.component]] for p in inputs),
        outputs=tuple(column[probe.body_of[p.component]] for p in outputs),
        ratio_bodies=ratio_bodies, determinate=not eq.indeterminate)


def _probe(model: Model, params: tuple[Parameter, ...]) -> Model:
    for param in params:
        if param.is_port:
            (index,) = param.targets
            if getattr(model.ports[index], param.kind) is None:
                model = model.with_port(index, **{param.kind: 1.0})
    return model


def _speed_ports(probe: Model, column: dict) -> tuple[tuple[int, int | None], ...]:
    given = [(column[probe.body_of[p.component]], p.index) for p in probe.ports
             if p.speed is not None]
    if not given and degrees_of_freedom(probe) == 1:
        given = [(column[probe.body_of[probe.inputs[0].component]], None)]
    return tuple(given)


def _loads(probe: Model, column: dict) -> tuple[Load, ...]:
    loaded = [p for p in probe.ports if p.power is not None or p.torque is not None]
    if not loaded:   # the first input feeds 1 W
        first = probe.inputs[0]
        return (Load(column[probe.body_of[first.component]], first.index, "power", "input"),)
    return tuple(Load(column[probe.body_of[p.component]], p.index,
                      "torque" if p.torque is not None else "power", p.role)
                 for p in loaded)


def _teeth_ratios(model: Model, params: tuple[Parameter, ...],
                  elements) -> tuple[TeethRatio, ...]:
    """Meshes whose ratio follows from a swept tooth number (and whose ratio is not swept)."""
    swept_teeth = {p.targets[0] for p in params if p.kind == "teeth"}
    swept_ratio = {t for p in params if p.kind == "ratio" for t in p.targets}
    out = []
    for k, el in enumerate(elements):
        link = model.links[el.link]
        if el.kind != "mesh" or link.ratio is not None or link.index in swept_ratio:
            continue
        if swept_teeth & {el.a, el.b}:
            a, b = model.components[el.a], model.components[el.b]
            sign = 1.0 if (a.internal or b.internal) else -1.0
            out.append(TeethRatio(k, el.a, el.b, sign))
    return tuple(out)

