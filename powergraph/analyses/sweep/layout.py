"""What a sweep keeps fixed: the train's structure as indices (:class:`Layout`), resolved
once from the model and the swept PATHs and validated on a probe solve, and the model's own
values of what varies (:func:`base_values`)."""
from __future__ import annotations

from typing import Callable, NamedTuple

from powergraph.analyses.sweep.paths import Parameter
from powergraph.kinematics import degrees_of_freedom, elements_of, solve_speeds
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.equilibrium import loads_of, solve_equilibrium


class Load(NamedTuple):
    """A port whose power or torque is given."""

    body: int
    port: int
    kind: str      # "power" or "torque" (the first input's default 1 W is a power)
    role: str      # "input" or "output"


@record
class Layout:
    """What a sweep keeps fixed: the train's structure, as indices into ``model.bodies``.

    What varies are the Willis ratios (from teeth or a mesh's ``ratio``), the
    efficiencies and the ports' speeds, powers and torques.
    """

    n_bodies: int
    links: tuple[int, ...]              # link index of each element
    kinds: tuple[str, ...]              # "mesh" / "coupling" per element
    body_a: tuple[int, ...]
    body_b: tuple[int, ...]
    body_c: tuple[int, ...]
    frame: int
    teeth_ratios: tuple[tuple[int, str, str], ...]   # (element, gear a, gear b): z_b/z_a
    signs: tuple[float, ...]            # Willis ratio = sign * magnitude, per element
    speed_ports: tuple[tuple[int, int | None], ...]   # (body, port index or None=default)
    loads: tuple[Load, ...]
    unknown: tuple[int, ...]            # bodies whose external torque is solved for
    inputs: tuple[int, ...]             # body of each input port
    outputs: tuple[int, ...]            # body of each output port
    ratio_bodies: tuple[int, int] | None   # (input, output) body for the ratio
    determinate: bool                   # load sharing fixed by statics at the base values

    @property
    def n_elements(self) -> int:
        return len(self.links)

    @property
    def places(self) -> tuple[tuple[int, int, int], ...]:
        """(body of gear a, of gear b, of the carrier) of each element."""
        return tuple(zip(self.body_a, self.body_b, self.body_c))

    @property
    def free_bodies(self) -> tuple[int, ...]:
        """Bodies whose speed is solved for."""
        known = {self.frame} | {body for body, _ in self.speed_ports}
        return tuple(j for j in range(self.n_bodies) if j not in known)

    @property
    def balance_bodies(self) -> tuple[int, ...]:
        """Bodies with no unknown external torque: their balance fixes the element forces."""
        return tuple(j for j in range(self.n_bodies) if j not in set(self.unknown))


def layout_of(model: Model, params: tuple[Parameter, ...]) -> Layout:
    """Resolve the structure of ``model`` with ``params`` swept (validated on a probe).

    The probe is the model with every swept port value set (to its value, or 1), solved
    once by the validated single solver: wrong DOF, speeds that do not fix the motion or
    loads that are not determined raise the single solver's own ModelError.
    """
    refuse_shared_ports(model, "the compiled sweep")
    probe = _probe(model, params)
    elements = elements_of(probe)
    loads = loads_of(probe, solve_speeds(probe))
    eq = solve_equilibrium(probe, elements, loads, [1.0] * len(elements))
    column = {body.id: j for j, body in enumerate(model.bodies)}
    body = lambda component: column[probe.body_of[component]]  # noqa: E731
    inputs = tuple(body(p.component) for p in probe.inputs)
    outputs = tuple(body(p.component) for p in probe.outputs)
    teeth, signs = _teeth_ratios(model, params, elements)
    return Layout(
        n_bodies=len(model.bodies), links=tuple(e.link for e in elements),
        kinds=tuple(e.kind for e in elements),
        body_a=tuple(column[e.body_a] for e in elements),
        body_b=tuple(column[e.body_b] for e in elements),
        body_c=tuple(column[e.body_c] for e in elements),
        frame=column[model.frame_body], teeth_ratios=teeth, signs=signs,
        speed_ports=_speed_ports(probe, body), loads=_loads(probe, body),
        unknown=tuple(column[b] for b in loads.unknown), inputs=inputs, outputs=outputs,
        ratio_bodies=(inputs[0], outputs[0]) if len(inputs) == len(outputs) == 1 else None,
        determinate=not eq.indeterminate)


def refuse_shared_ports(model: Model, who: str) -> None:
    """A batched evaluator (the compiled sweep, the efficiency grid) works on one port per
    rigid body and on every port: a model with several ports on one body, or with ports
    its mode leaves inactive (docs/modes.md), is solved point by point instead
    (:class:`~powergraph.errors.UsageError` saying so)."""
    from powergraph.errors import UsageError
    from powergraph.model.graph import shared_port_bodies

    shared = shared_port_bodies(model)
    if shared:
        body, ports = next(iter(shared.items()))
        raise UsageError(f"{who} takes one port per rigid body; ports "
                         f"{', '.join(model.port_label(i) for i in ports)} share body "
                         f"{body!r}: solve the points one by one")
    if model.inactive:
        raise UsageError(f"{who} does not take ports a mode leaves inactive ("
                         f"{', '.join(model.port_label(i) for i in sorted(model.inactive))})"
                         ": solve the points one by one")


def _probe(model: Model, params: tuple[Parameter, ...]) -> Model:
    for param in params:
        if param.is_port:
            (index,) = param.targets
            if getattr(model.ports[index], param.kind) is None:
                model = model.with_port(index, **{param.kind: 1.0})
    return model


def _speed_ports(probe: Model, body: Callable) -> tuple[tuple[int, int | None], ...]:
    given = [(body(p.component), p.index) for p in probe.ports if p.speed is not None]
    if not given and degrees_of_freedom(probe) == 1:
        given = [(body(probe.inputs[0].component), None)]
    return tuple(given)


def _loads(probe: Model, body: Callable) -> tuple[Load, ...]:
    loaded = [p for p in probe.ports if p.power is not None or p.torque is not None]
    if not loaded:   # the first input feeds 1 W
        first = probe.inputs[0]
        return (Load(body(first.component), first.index, "power", "input"),)
    return tuple(Load(body(p.component), p.index,
                      "torque" if p.torque is not None else "power", p.role)
                 for p in loaded)


def _teeth_ratios(model: Model, params: tuple[Parameter, ...], elements) -> tuple:
    """Meshes whose ratio follows from a swept tooth number (and whose ratio is not
    swept), and the sign of every element's Willis ratio."""
    swept_teeth = {p.targets[0] for p in params if p.kind == "teeth"}
    swept_ratio = {t for p in params if p.kind == "ratio" for t in p.targets}
    out, signs = [], [1.0] * len(elements)
    for k, el in enumerate(elements):
        link = model.links[el.link]
        if el.kind != "mesh" or link.ratio is not None or link.index in swept_ratio:
            continue
        if swept_teeth & {el.a, el.b}:
            a, b = model.components[el.a], model.components[el.b]
            signs[k] = 1.0 if (a.internal or b.internal) else -1.0
            out.append((k, el.a, el.b))
    return tuple(out), tuple(signs)


def base_values(model: Model, layout: Layout) -> dict:
    """The model's own values of what a sweep may vary, in the layout's order."""
    elements = elements_of(model)
    ports = model.ports
    return {
        "ratios": tuple(e.ratio for e in elements),
        "efficiencies": tuple(e.efficiency for e in elements),
        "teeth": {c.id: float(c.teeth) for c in model.components.values() if c.teeth},
        "speeds": tuple(1.0 if port is None or ports[port].speed is None
                        else ports[port].speed for _, port in layout.speed_ports),
        "loads": tuple(_load_value(ports[load.port], load.kind) for load in layout.loads),
    }


def _load_value(port, kind: str) -> float:
    value = getattr(port, kind)
    return 1.0 if value is None else value
