"""What a powergraph FMU does at each step (the slave :mod:`powergraph.exchange.fmu`
builds calls it; no pythonfmu here, so it is tested and imported without it).

The FMU's inputs are the loads and speeds the model gives at its ports, each named
``PORT.speed`` (rad/s), ``PORT.power`` (W) or ``PORT.torque`` (N·m) with PORT the
port's name or its component id, in the model's own sign conventions
(docs/format.md, Ports), starting at the model's own values. Its outputs are every
port's ``PORT.speed``, ``PORT.torque`` (on the train) and ``PORT.power`` (into the
train), as ``solve --json`` gives them, named ``PORT.speed_out``, ``PORT.torque_out``,
``PORT.power_out`` (an FMU's variable names are unique, and an input's name is taken),
and ``efficiency`` (NaN when no power passes) and ``total_loss`` (W).

Examples
--------
>>> stepper = TrainStepper("models/planetary_2kh_two_stages.yaml")
>>> stepper.inputs
('s1.speed', 's1.power')
>>> stepper.values["s1.power"] = 4000.0
>>> stepper.step()
>>> round(stepper.values["total_loss"], 6) == round(4000 * (1 - 0.946599836), 6)
True
"""
from __future__ import annotations

import math

from powergraph.model import load_model
from powergraph.statics import solve

#: The quantities a port may give, as model fields and variable suffixes.
QUANTITIES = ("speed", "power", "torque")


class TrainStepper:
    """A model, its input values and the outputs of the last :meth:`step`."""

    def __init__(self, path: str) -> None:
        self.model = load_model(path)
        self.keys = [str(p.name) if p.name else str(self.model.raw_id(p.component))
                     for p in self.model.ports]
        self.inputs = tuple(f"{key}.{q}" for key, port in zip(self.keys, self.model.ports)
                            for q in QUANTITIES if getattr(port, q) is not None)
        self.outputs = tuple(f"{key}.{q}_out" for key in self.keys
                             for q in ("speed", "torque", "power")) + ("efficiency",
                                                                      "total_loss")
        self.values: dict[str, float] = {
            f"{key}.{q}": float(getattr(port, q))
            for key, port in zip(self.keys, self.model.ports)
            for q in QUANTITIES if getattr(port, q) is not None}
        self.step()

    def step(self) -> None:
        """Solve at the current inputs and set the outputs."""
        model = self.model
        for index, (key, port) in enumerate(zip(self.keys, model.ports)):
            changes = {q: self.values[f"{key}.{q}"] for q in QUANTITIES
                       if getattr(port, q) is not None}
            model = model.with_port(index, **changes)
        result = solve(model)
        for key, flow in zip(self.keys, result.ports):
            self.values.update({f"{key}.speed_out": flow.speed,
                                f"{key}.torque_out": flow.torque,
                                f"{key}.power_out": flow.power})
        self.values["efficiency"] = math.nan if result.efficiency is None \
            else result.efficiency
        self.values["total_loss"] = result.total_loss
