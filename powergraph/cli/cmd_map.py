"""``powergraph map MODEL --torque A:B:N --speed C:D:N [--rated T] [-o FILE] [--json]
[--loss-map FILE]``: efficiency over output torque (N·m; negative: coasting, the output
driving the train) × input speed (rpm), and the same points as a transmission loss map
(input speed, input torque, torque loss), both quadrants as VECTO wants them.

A span that starts with a minus sign is written with ``=``, as argparse wants any value
that looks like an option: ``--torque=-400:400:9``."""
from __future__ import annotations

import argparse
import dataclasses
import math

import numpy as np

from powergraph.cli.cmd_modes import add_mode_option
from powergraph.cli.common import (add_oil_temperature, oil_temperature, check_figure_path, check_output_file,
                                   load, number_option, print_json, save_figure, say_wrote,
                                   whole_option, write_atomically)
from powergraph.errors import UsageError
from powergraph.model.schema_parts import MAX_SPEED, MAX_TORQUE


#: Output torques (N·m, either sign) and input speeds (rpm) taken: those a model file takes.
TORQUE_LIMIT = MAX_TORQUE
SPEED_LIMIT = MAX_SPEED * 60 / (2 * math.pi)
#: Most points along one axis.
MAX_POINTS = 500


def span_option(text: str, option: str, limit: float) -> np.ndarray:
    """``START:STOP:N`` (N evenly spaced values, ends included) or one value, each within
    ±``limit``; otherwise a :class:`~powergraph.errors.UsageError` naming ``option``.

    >>> span_option("100:400:4", "--torque", 1e9).tolist()
    [100.0, 200.0, 300.0, 400.0]
    """
    parts = text.split(":")
    if len(parts) not in (1, 3):
        raise UsageError(f"{option} {text}: expected START:STOP:N or one value")
    try:
        ends = [number_option(part, option, -limit, limit) for part in parts[:2]]
        count = whole_option(parts[2], option, 1, MAX_POINTS) if len(parts) == 3 else 1
    except UsageError as exc:
        raise UsageError(f"{exc.message} (in {option} {text}: START:STOP:N)") from None
    return np.linspace(ends[0], ends[-1], count)


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "map", help="efficiency over output torque × input speed",
        description="Efficiency map of a 1-DOF train with one input and one output: the "
                    "output drives a load torque at each input speed (torque > 0), or a "
                    "load drives the output (torque < 0: coasting; efficiency = power out "
                    "at the input / power in at the output; 0 when self-locking). Flat on "
                    "each side unless a mesh's friction depends on the load (friction: "
                    "{model: iso14179, ...}) or bearings carry friction or drag "
                    "(docs/losses.md). Write a negative span with '=': --torque=-400:400:9.")
    parser.add_argument("model", help="model file (YAML)")
    parser.add_argument("--torque", required=True, metavar="A:B:N",
                        help=f"output torques, N·m: > 0 driving a load, < 0 coasting (the "
                             f"output drives), 0 no load (up to {TORQUE_LIMIT:g} either way; "
                             f"N <= {MAX_POINTS}; a negative START as --torque=-A:B:N)")
    parser.add_argument("--speed", required=True, metavar="C:D:N",
                        help=f"input speeds, rpm (up to {SPEED_LIMIT:g} either way; N <= {MAX_POINTS})")
    parser.add_argument("--rated", default=None, metavar="T",
                        help="rated output torque, N·m (drawn as a line)")
    parser.add_argument("-o", "--output", metavar="FILE", help="write the map (PNG/SVG/PDF)")
    parser.add_argument("--json", action="store_true", help="print a JSON object")
    parser.add_argument("--loss-map", metavar="FILE",
                        help="write the points as a transmission loss map (.vtlm or .csv: "
                             "input speed, input torque, torque loss, as VECTO reads it; "
                             "give negative torques too for its drag side)")
    add_mode_option(parser, "map")
    add_oil_temperature(parser, span=True)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.analyses.efficiency_map import efficiency_map

    target = check_figure_path(args.output) if args.output else None
    loss_target = (check_output_file(args.loss_map, "--loss-map", (".vtlm", ".csv"))
                   if args.loss_map else None)
    torque = span_option(args.torque, "--torque", TORQUE_LIMIT)
    speed = span_option(args.speed, "--speed", SPEED_LIMIT)
    rated = (None if args.rated is None
             else number_option(args.rated, "--rated", 0, TORQUE_LIMIT, above=True))
    model = load(args.model)
    if args.oil_temperature is None:
        models = [(None, model)]
    else:
        from powergraph.model.lubricant import fixed_temperature

        celsius = span_option(args.oil_temperature, "--oil-temperature", 300.0)
        models = [(t, fixed_temperature(model, oil_temperature(repr(float(t)))))
                  for t in celsius]
        if loss_target is not None and len(models) > 1:
            raise UsageError("--loss-map: a loss map is for one oil temperature; give one "
                             "--oil-temperature")
    maps = [(t, efficiency_map(m, torque, speed, rated, mode=args.mode)) for t, m in models]
    maps = [(t, result if t is None else
             dataclasses.replace(result, name=f"{result.name}, oil at {t:g} degC"))
            for t, result in maps]
    if args.json:
        print_json(maps[0][1].to_dict() if args.oil_temperature is None else
                   {"oil_temperatures": [float(t) + 273.15 for t, _ in maps],
                    "maps": [result.to_dict() for _, result in maps]})
    else:
        print("\n\n".join(result.text_report() for _, result in maps))
    for t, result in maps:
        if target is not None:
            path = target if len(maps) == 1 else target.with_name(
                f"{target.stem}_{t:g}degC{target.suffix}")
            ax = result.plot()
            save_figure(ax.figure, path, dpi=150, bbox_inches="tight")
            say_wrote(path, data_on_stdout=args.json)
        if loss_target is not None:
            write_loss_map(loss_target, result, data_on_stdout=args.json)
    return 0


def write_loss_map(path, result, data_on_stdout: bool = False) -> None:
    """The map's points as a loss map file (:meth:`EfficiencyMap.loss_map`); the user is
    told how many points each side has, and how many were left out (no answer)."""
    from powergraph.analyses.efficiency_map_report import loss_map_text

    rows = result.loss_map()
    text = loss_map_text(result)
    lines = text.splitlines()

    def write(tmp: str) -> None:
        with open(tmp, "w", encoding="utf-8", newline="\n") as handle:
            handle.write(text)

    write_atomically(path, write)
    left_out = result.efficiency.size - len(rows["speed_rpm"])
    sides = np.sign(rows["output_torque"])
    counts = ", ".join(f"{np.count_nonzero(sides == s)} {name}"
                       for s, name in ((1, "driving"), (-1, "coasting"), (0, "no load"))
                       if np.any(sides == s))
    driven = np.count_nonzero((sides < 0) & (rows["input_torque"] > 0))
    say_wrote(path, f"({len(lines) - 1} points: {counts}" +
              (f"; {driven} coasting with a positive input torque: the input drives too, "
               "self-locking" if driven else "") +
              (f"; {left_out} left out: no solution)" if left_out else ")"),
              data_on_stdout=data_on_stdout)
