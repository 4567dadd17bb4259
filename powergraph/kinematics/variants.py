"""Derived operating cases of a model (the model itself is never changed)."""
from __future__ import annotations

import dataclasses

from powergraph.errors import ModelError
from powergraph.kinematics.speeds import solve_speeds
from powergraph.model.spec import Model


def backdriven(model: Model, power: float | None = None) -> Model:
    """The same train driven from its output: the output port becomes the input.

    The motion keeps its direction (the new input turns at the speed it had), and the new
    input feeds the power (or the torque) the old input fed, so forward and back-driven
    efficiencies compare at the same power. Only one-input, one-output trains.

    When the input is given only a speed, the power fed in is ``power`` — pass the forward
    solve's input power, so that load-dependent losses (friction laws, drag) are met at
    the same power — or 1 W when ``power`` is None (or not positive).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> back = backdriven(load_model("models/rv40e_wang2021.yaml"))      # doctest: +SKIP
    >>> [(p.component, p.role) for p in back.ports]              # doctest: +SKIP
    [('1', 'output'), ('6', 'input')]
    """
    if len(model.inputs) != 1 or len(model.outputs) != 1:
        raise ModelError("back-driving needs exactly one input and one output port", "ports")
    kin = solve_speeds(model)
    source, sink = model.inputs[0], model.outputs[0]
    if source.power is not None:
        power = source.power
    elif source.torque is not None:
        power = source.torque * kin.speed(source.component)
    else:
        power = float(power) if power is not None and power > 0 else 1.0
    load = {"power": power, "torque": None}
    ports = []
    for port in model.ports:
        if port is sink:
            ports.append(dataclasses.replace(port, role="input",
                                             speed=kin.speed(port.component), **load))
        elif port is source:
            ports.append(dataclasses.replace(port, role="output", speed=None, power=None,
                                             torque=None))
        else:
            ports.append(port)
    return dataclasses.replace(model, ports=tuple(ports), name=f"{model.name} (back-driven)")
