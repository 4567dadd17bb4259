"""Text view of a :class:`~powergraph.analyses.shift_placement.ShiftPlacement`.

Works on the placement it is given (its ``targets``, ``plans``, ``states``, ``model``):
it never imports :mod:`powergraph.analyses.shift_placement`, whose ``text_report()``
imports this module (the annotations name the types as text).
"""
from __future__ import annotations

from powergraph.format import aligned_table, format_number, format_ratio

#: Other plans listed below the best one, at most.
OTHERS = 5


def text_report(placement: "ShiftPlacement") -> str:
    """The best plan (its elements and gears), then the other plans in one line each."""
    targets = ", ".join(format_number(t, 4) for t in placement.targets)
    lines = [f"{placement.name} — shift elements for ratios {targets} (tolerance "
             f"{format_number(100 * placement.tolerance, 3)} %)",
             f"{len(placement.states)} gear states (one clutch from the input shaft with "
             "one brake, or two clutches); "
             f"{len(placement.plans)} plan(s), fewest elements first"]
    if not placement.plans:
        return "\n".join(lines + ["no plan gives every ratio with distinct gear states"])
    best = placement.plans[0]
    lines += ["", f"best plan: {best.size} shift elements, largest ratio error "
              f"{format_number(100 * best.error, 3)} %"]
    lines += aligned_table([["element", "kind", "joins"]]
                           + [[name, kind, _joins(placement, kind, member)]
                              for (kind, member), name in best.names.items()], set())
    lines.append("")
    rows = [["mode", "target", "ratio", "error %", "engaged"]]
    for (mode, engaged), target, gear in zip(best.modes.items(), best.targets, best.gears):
        rows.append([mode, format_ratio(target), format_ratio(gear.ratio),
                     format_number(100 * abs(gear.ratio - target) / abs(target), 3),
                     " + ".join(engaged)])
    lines += aligned_table(rows, {1, 2, 3})
    if len(placement.plans) > 1:
        lines += ["", "other plans"]
        lines += aligned_table([["elements", "error %", "shift elements"]]
                               + [[str(p.size), format_number(100 * p.error, 3),
                                   _summary(placement, p)]
                                  for p in placement.plans[1:1 + OTHERS]], {0, 1})
    return "\n".join(lines)


def _label(placement: "ShiftPlacement", member: str) -> str:
    component = placement.model.components[member]
    raw = str(placement.model.raw_id(member))
    return f"{raw} ({component.name})" if component.name else raw


def _joins(placement: "ShiftPlacement", kind: str, member: str) -> str:
    if kind == "clutch":
        return f"input shaft to {_label(placement, member)}"
    return f"holds {_label(placement, member)}"


def _summary(placement: "ShiftPlacement", plan: "ShiftPlan") -> str:
    return ", ".join(f"{name} {kind} {placement.model.raw_id(member)}"
                     for (kind, member), name in plan.names.items())
