"""The single solver's answer for one variant of a sweep, written into its outputs (a
variant the vectorised iteration hands over, or a mode's variant decided by its case)."""
from __future__ import annotations

import numpy as np

from powergraph.analyses.sweep.evaluate import Outputs
from powergraph.analyses.sweep.result import LOCKED, OK
from powergraph.statics.machine_report import boundary_powers
from powergraph.statics.ports import flow_efficiency_point


def write_single(out: Outputs, j: int, result: "PowerFlowResult",
                 links: tuple[int, ...]) -> None:
    """The single solver's answer for variant ``j`` of ``out`` (``links``: the elements'
    links, in the outputs' order). A train with machines on buses is measured at its
    boundary, as its solve measures it: the batteries in place of the machines
    (docs/hybrid.md)."""
    out.ratio[j] = np.nan if result.ratio is None else result.ratio
    if result.machines:
        crossing = boundary_powers(result)
        out.input_power[j] = sum(p for p in crossing if p > 0) + 0.0
        out.output_power[j] = sum(p for p in crossing if p < 0) + 0.0
        out.efficiency[j] = np.nan if result.efficiency is None else result.efficiency
    else:
        out.input_power[j], out.output_power[j] = result.input_power, result.output_power
        out.efficiency[j] = flow_efficiency_point(result.input_power, result.output_power)
    if result.lock is not None:
        out.efficiency[j] = 0.0
    out.total_loss[j] = result.total_loss
    out.self_locking[j] = result.self_locking
    out.status[j] = LOCKED if result.lock is not None else OK
    out.passes[j] = min(result.passes, 127)
    by_link = {flow.link: flow for flow in result.elements}
    for k, link in enumerate(links):
        flow = by_link[link]
        out.losses[k, j] = flow.loss
        out.codes[k, j] = 0 if flow.driver is None else (1 if flow.driver == flow.a else -1)


def write_failed(out: Outputs, j: int, status: int) -> None:
    """Variant ``j`` of ``out`` has no answer (``status`` says why): NaN powers."""
    for name in ("ratio", "efficiency", "input_power", "output_power", "total_loss"):
        getattr(out, name)[j] = np.nan
    out.self_locking[j], out.status[j], out.passes[j] = False, status, 0
    out.losses[:, j], out.codes[:, j] = np.nan, 0
