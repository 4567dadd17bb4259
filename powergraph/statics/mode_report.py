"""The text report of a train solved in one mode (docs/modes.md)."""
from __future__ import annotations


def mode_report(mode_result) -> str:
    """The power-flow report, then one line per shift element and the verdict."""
    lines = []
    if mode_result.result is not None:
        lines.append(mode_result.result.text_report().rstrip())
        lines.append("")
    head = f"mode {mode_result.mode}" if mode_result.mode is not None else "shift elements"
    lines.append(f"{head}: engages "
                 f"{', '.join(mode_result.engaged) or 'nothing'} — {mode_result.verdict}")
    if mode_result.inactive:
        lines.append("inactive ports: " + ", ".join(mode_result.inactive))
    if mode_result.idle:
        lines.append("idle (turning at no speed the train sets): "
                     + ", ".join(mode_result.idle))
    if mode_result.elements:
        lines.append(f"  {'element':<10} {'kind':<10} {'state':<12} {'torque N·m':>12} "
                     f"{'slip rad/s':>12} {'drag W':>10}")
        for e in mode_result.elements:
            torque = "indeterm." if e.engaged and e.torque is None else (
                "-" if e.torque is None else f"{e.torque:.6g}")
            slip = "idle" if e.slip_speed is None else f"{e.slip_speed:.6g}"
            lines.append(f"  {e.name:<10} {e.kind:<10} {e.state:<12} {torque:>12} "
                         f"{slip:>12} {e.drag_loss:>10.4g}")
    lines += [f"warning: {w}" for w in mode_result.warnings]
    return "\n".join(lines)
