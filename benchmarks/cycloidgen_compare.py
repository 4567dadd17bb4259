"""The RV-40E's cycloid stage by powergraph's friction model and by the `cycloidgen` package.

cycloidgen (PyPI, version 8.0.0: a parametric cycloidal drive generator with engineering
analysis) computes the efficiency of a K-H-V cycloid drive — ring pins fixed, eccentric
input, output pins in holes — from the same equal-load pin forces, at absolute speeds.
This script runs the RV-40E's cycloid stage (39 lobes, 40 pins on R_p = 64 mm, r_p = 3 mm,
e = 1.3 mm, two discs) as such a drive in both and prints each loss beside the other;
docs/losses.md discusses the differences.

cycloidgen is not a dependency of powergraph (it pulls in CAD and GUI packages). Install
it in a virtual environment of your own to run this script::

    pip install cycloidgen==8.0.0
    python benchmarks/cycloidgen_compare.py [--mu 0.05] [--torque 200] [--rpm 1500]
"""
from __future__ import annotations

import argparse
import math
import sys

from powergraph.gears.cycloid_loss import (CrankBearing, OutputPins, PinContact, PinRing,
                                           cycloid_mesh_loss)

STAGE = PinRing(lobes=39, circle_radius=64.0, pin_radius=3.0, eccentricity=1.3)
OUTPUT_PINS, OUTPUT_CIRCLE = 8, 40.0          # mm: a W mechanism (the RV has cranks instead)
SHAFT_DIAMETER, BORE_DIAMETER = 20.0, 40.0    # mm: eccentric bearing (cycloidgen's fields)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mu", type=float, default=0.05, help="sliding coefficient (pins)")
    parser.add_argument("--torque", type=float, default=200.0, help="output torque, N*m")
    parser.add_argument("--rpm", type=float, default=1500.0, help="input speed, rpm")
    args = parser.parse_args(argv)
    try:
        from cycloidgen.analysis.efficiency import BEARING_MU, analyse_efficiency
        from cycloidgen.core.spec import DRY, GearSpec
    except ImportError:
        print("cycloidgen is not installed: pip install cycloidgen==8.0.0 (in your own "
              "environment; it is not a dependency of powergraph)", file=sys.stderr)
        return 1
    spec = GearSpec(pin_circle_radius=STAGE.circle_radius, pin_radius=STAGE.pin_radius,
                    eccentricity=STAGE.eccentricity, lobes=STAGE.lobes, disc_count=2,
                    output_pin_count=OUTPUT_PINS, output_pin_diameter=12.0,
                    output_bolt_circle_radius=OUTPUT_CIRCLE, friction_coefficient=args.mu,
                    lubricant=DRY, input_rpm=args.rpm, output_torque_Nm=args.torque,
                    center_bore_diameter=BORE_DIAMETER, input_shaft_diameter=SHAFT_DIAMETER)
    theirs = analyse_efficiency(spec)
    # powergraph: the same drive, the eccentric bearing as cycloidgen sizes it (BEARING_MU
    # on the mean of shaft and bore diameters), central crank.
    ours = cycloid_mesh_loss(STAGE, PinContact(args.mu), OutputPins(OUTPUT_PINS, OUTPUT_CIRCLE,
                                                                    args.mu),
                             CrankBearing(BEARING_MU, (SHAFT_DIAMETER + BORE_DIAMETER) / 4))
    n = STAGE.lobes
    omega_in = args.rpm * 2 * math.pi / 60
    p_out = args.torque * omega_in / n
    virtual = args.torque * omega_in * (n + 1) / n       # |T (ω_d − ω_c)|: crank-frame power
    rows = [("ring pins", args.mu * ours.pin_loss_factor * virtual, theirs.loss_ring_pins_W),
            ("output pins", args.mu * ours.output_loss_factor * virtual,
             theirs.loss_output_pins_W),
            ("eccentric + main bearings", BEARING_MU * ours.bearing_loss_factor * virtual,
             theirs.loss_bearings_W)]
    eta_c = ours.efficiency
    eta = eta_c / (1 + n * (1 - eta_c))                   # K-H-V, tests/statics/test_friction.py
    print(f"RV-40E cycloid stage as a K-H-V drive: {n} lobes, {args.torque:g} N*m out, "
          f"{args.rpm:g} rpm in, mu {args.mu:g}, output power {p_out:.2f} W")
    print(f"{'loss':<28}{'powergraph W':>14}{'cycloidgen W':>14}{'ratio':>8}")
    for name, mine, other in rows:
        ratio = mine / other if other else float("nan")
        print(f"{name:<28}{mine:>14.3f}{other:>14.3f}{ratio:>8.4f}")
    print(f"{'efficiency':<28}{100 * eta:>13.3f}%{100 * theirs.efficiency:>13.3f}%")
    print(f"(powergraph: basic efficiency {eta_c:.6f} in the crank frame, "
          f"η = η_c/(1 + N(1 − η_c)); cycloidgen: losses summed at absolute speeds)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
