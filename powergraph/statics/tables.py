"""A solve's tables as rows and as pandas DataFrames: meshes, ports, flows, speeds.

:func:`records` gives plain rows (one dict each, the component's name beside its id, SI
units named in the column names); :func:`to_dataframe` the same as a
:class:`pandas.DataFrame` (pandas is optional: a :class:`~powergraph.errors.UsageError`
says so when it is missing). ``PowerFlowResult.to_dataframe(what)`` is this function.

Examples
--------
>>> import powergraph as pg
>>> result = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))
>>> [round(row["virtual_power_w"]) for row in records(result, "meshes")]
[2251, 24710]
>>> round(to_dataframe(result, "speeds").loc[1, "rpm"], 6)          # doctest: +SKIP
1500.0
"""
from __future__ import annotations

import math
from typing import Any

from powergraph.display import dataframe
from powergraph.errors import UsageError

#: The tables a solve offers, and the column each is indexed by in a DataFrame.
TABLES = {"meshes": "link", "ports": "port", "flows": None, "speeds": "component"}
RPM = 60.0 / (2.0 * math.pi)


def records(result: "PowerFlowResult", what: str = "meshes",
            frame: str | None = None) -> list[dict[str, Any]]:
    """The rows of one table of ``result``.

    Parameters
    ----------
    what : ``"meshes"``, ``"ports"``, ``"flows"`` or ``"speeds"``
        meshes: link, the gears and carrier (ids and names), basic efficiency, driver,
        virtual power (the power in the carrier's frame) and loss, W; ports: role, component,
        speed (rad/s, rpm), torque (N·m), power (W, positive in); flows: the arrows of the
        power-flow graph (W); speeds: every component's speed (rad/s, rpm).
    frame : component id, optional
        For ``flows``: the body the powers are seen from (default the housing).
    """
    if what not in TABLES:
        raise UsageError(f"to_dataframe: what must be one of {', '.join(TABLES)}, "
                         f"got {what!r}")
    if what == "meshes":
        return _meshes(result)
    if what == "ports":
        return _ports(result)
    if what == "flows":
        return [{"from": f.source, "to": f.target, "power_w": f.power}
                for f in result.flows(frame)]
    return [{"component": result.model.raw_id(cid), "name": _name(result, cid), "rad_s": w,
             "rpm": w * RPM}
            for cid, w in result.speeds.items()]


def to_dataframe(result: "PowerFlowResult", what: str = "meshes",
                 frame: str | None = None) -> Any:
    """:func:`records` as a :class:`pandas.DataFrame`, indexed by link, port or component
    (flows: by row)."""
    rows = records(result, what, frame)
    return dataframe(rows, index=TABLES[what])


def _name(result: "PowerFlowResult", cid: str) -> str:
    return result.model.components[cid].name or ""


def _meshes(result: "PowerFlowResult") -> list[dict[str, Any]]:
    raw = result.model.raw_id
    return [{"link": e.link, "a": raw(e.a), "a_name": _name(result, e.a), "b": raw(e.b),
             "b_name": _name(result, e.b), "carrier": raw(e.carrier),
             "carrier_name": _name(result, e.carrier), "efficiency": e.efficiency,
             "driver": None if e.driver is None else raw(e.driver),
             "virtual_power_w": e.carrier_frame_power, "loss_w": e.loss}
            for e in result.meshes]


def _ports(result: "PowerFlowResult") -> list[dict[str, Any]]:
    rows = []
    for port in result.model.ports:
        w = result.kinematics.speed(port.component)
        rows.append({"port": port.index, "role": port.role,
                     "component": result.model.raw_id(port.component),
                     "name": port.name or _name(result, port.component), "rad_s": w,
                     "rpm": w * RPM, "torque_nm": result.torques.get(port.component),
                     "power_w": result.port_power(port.component)})
    return rows
