"""What a solve with machines adds to its reports (docs/hybrid.md): the machines and
buses, the electrical path's share of the power reaching the outputs, and whether the
split is negative (power circulating through a bus)."""
from __future__ import annotations

from typing import Any

from powergraph.format import POWER_UNITS, aligned_table, format_column
from powergraph.statics.flow import BUS, Node, _reaches


def boundary_powers(result: "PowerFlowResult") -> list[float]:
    """The powers into the system at its boundary: every port's, except that the machines
    are inside and their batteries' powers into the buses count instead."""
    return ([p.power for p in result.ports if p.role != "machine"]
            + [b.battery_power for b in result.buses.values()])


def negative_split(result: "PowerFlowResult", tolerance: float = 1e-9) -> bool:
    """True when power circulates through a bus: a directed loop of the flow graph (in
    the ground frame) passes through a bus node, machine → bus → machine → train → ...
    (the negative split of a power-split hybrid)."""
    edges = result.flows()
    largest = max((e.power for e in edges), default=0.0)
    successors: dict[Node, set[Node]] = {}
    for edge in edges:
        if edge.power > tolerance * max(1.0, largest):
            successors.setdefault(edge.source_node, set()).add(edge.target_node)
    return any(_reaches(successors, target, bus)
               for bus in successors if bus.kind == BUS for target in successors[bus])


def electrical_share(result: "PowerFlowResult") -> float | None:
    """The electrical path's share of the power reaching the outputs: the mechanical
    power the motoring machines feed in over the power leaving at the output ports;
    negative in a negative split (the electrical path then carries power back). None
    without machines or without output power."""
    leaving = -sum(p.power for p in result.ports if p.role == "output" and p.power < 0)
    if not result.machines or leaving <= 0:
        return None
    motoring = sum(m.power for m in result.machines if m.power > 0)
    return (-motoring if negative_split(result) else motoring) / leaving


def machine_dict(result: "PowerFlowResult") -> dict[str, Any]:
    """The JSON keys of a solve with machines (none without)."""
    if not result.machines:
        return {}
    raw = result.model.raw_id
    return {"machines": [m.to_dict(raw) for m in result.machines],
            "buses": {name: bus.to_dict() for name, bus in result.buses.items()},
            "electrical_share": electrical_share(result),
            "negative_split": negative_split(result)}


def machine_lines(result: "PowerFlowResult") -> list[str]:
    """The text report's machine and bus section."""
    if not result.machines:
        return []
    columns = [format_column([getattr(m, key) for m in result.machines], POWER_UNITS)
               for key in ("power", "electrical_power", "loss")]
    rows = [["machine", "component", "bus", "state"]
            + [f"{what} [{unit}]" for what, (unit, _) in
               zip(("power", "electrical", "loss"), columns)]]
    rows += [[m.name, str(result.model.raw_id(m.component)), m.bus, m.state,
              *(texts[i] for _, texts in columns)] for i, m in enumerate(result.machines)]
    lines = ["", "machines (power into the train; electrical power drawn from the bus)"]
    lines += aligned_table(rows, {4, 5, 6})
    for name, bus in result.buses.items():
        given = "given" if bus.given else "free"
        lines.append(f"bus {name}: battery {bus.battery_power + 0.0:.6g} W into the bus "
                     f"({given})")
    share = electrical_share(result)
    if share is not None:
        lines.append(f"electrical path: {share:.1%} of the power reaching the outputs")
    if negative_split(result):
        lines.append("negative split: power circulates through the electrical path "
                     f"({result.circulating_power + 0.0:.6g} W)")
    return lines
