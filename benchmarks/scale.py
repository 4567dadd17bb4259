"""How the solve grows with the size of the train, checked against closed forms.

Two families, generated as YAML text, loaded with ``powergraph.model.loads_model`` and
solved with ``powergraph.statics.solve``:

- **chain**: a fixed-axis chain of N gears (gear i meshes gear i + 1, carrier = the
  frame, η 0.99; ``chain_text`` of benchmarks/large_model.py). Closed form: ratio
  (-1)^(N-1) z_N/z_1, efficiency 0.99^(N-1); and the power through mesh k is
  P·0.99^k (it is the carrier-frame power of a fixed-axis mesh), checked wherever it is
  representable (0.99^99999 ≈ 1e-437 underflows double precision).
- **series**: n identical 2K-H stages in series (z_s 20, z_p 30, z_r 80, ring fixed,
  both meshes η 0.98). One stage driven at the sun with the carrier as output has
  ratio 1 + k (k = z_r/z_s = 4) and efficiency η_f = (1 + η_sp η_pr k)/(1 + k). Up to
  400 stages every stage is driven that way (ratio 5^n, efficiency η_f^n); 5^1000
  (≈ 1e699) is not a double, so longer series alternate with stages driven at the
  carrier with the sun as output (ratio 1/(1 + k), efficiency
  η_b = (1 + k) η_sp η_pr/(η_sp η_pr + k)), joined carrier to carrier and sun to sun.

Each size prints the load time, the solve time, the total, the total over one RV-40E solve
(load and solve of models/rv40e_wang2021.yaml measured in the same run), and whether the result
matches its closed form to 1e-9 relative; each family its growth exponents (least squares
of log time over log size on its three largest sizes, for load and solve together and for
the solve alone; linear is 1).

Usage: python benchmarks/scale.py [--json] [--sizes 10 100 1000] [--series 10 100]
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

import numpy as np  # noqa: E402

from large_model import chain_text  # noqa: E402
from powergraph.model import load_model, loads_model  # noqa: E402
from powergraph.statics import solve  # noqa: E402

ETA_CHAIN, ETA_STAGE_MESH = 0.99, 0.98
Z_S, Z_P, Z_R = 20, 30, 80
ALL_FORWARD_UP_TO = 400
RTOL = 1e-9


def series_text(n: int) -> str:
    """``n`` 2K-H stages in series (see the module docstring)."""
    lines = ["name: series", f"description: {n} 2K-H stages in series", "components:",
             "  0: {role: frame}"]
    links = []
    ends = []
    alternate = n > ALL_FORWARD_UP_TO
    for k in range(n):
        lines += [f"  s{k}: {{teeth: {Z_S}}}", f"  p{k}: {{teeth: {Z_P}}}",
                  f"  r{k}: {{teeth: {Z_R}, internal: true}}", f"  c{k}: {{}}"]
        links += [f"  - {{type: mesh, between: [s{k}, p{k}], carrier: c{k}, "
                  f"efficiency: {ETA_STAGE_MESH}}}",
                  f"  - {{type: mesh, between: [p{k}, r{k}], carrier: c{k}, "
                  f"efficiency: {ETA_STAGE_MESH}}}",
                  f"  - {{type: fixed, between: [r{k}, 0]}}"]
        ends.append((f"s{k}", f"c{k}") if not alternate or k % 2 == 0 else (f"c{k}", f"s{k}"))
    for (_, out), (inp, _) in zip(ends, ends[1:]):
        links.append(f"  - {{type: fixed, between: [{out}, {inp}]}}")
    lines += ["links:"] + links
    lines += ["ports:", f"  - {{component: {ends[0][0]}, role: input, speed: 1000 rpm, "
              "power: 1 kW}", f"  - {{component: {ends[-1][1]}, role: output}}"]
    return "\n".join(lines) + "\n"


def series_closed_form(n: int) -> tuple[float, float]:
    """Ratio and efficiency of :func:`series_text` (derivations in the module docstring)."""
    k, eta0 = Z_R / Z_S, ETA_STAGE_MESH * ETA_STAGE_MESH
    forward = (1 + eta0 * k) / (1 + k)
    backward = (1 + k) * eta0 / (eta0 + k)
    if n <= ALL_FORWARD_UP_TO:
        return (1 + k) ** n, forward ** n
    pairs, odd = divmod(n, 2)
    return (1 + k) ** odd, (forward * backward) ** pairs * forward ** odd


def chain_check(n: int, result) -> bool:
    z_1, z_n = 20 + 1 % 7, 20 + n % 7
    ok = math.isclose(result.ratio, (-1) ** (n - 1) * z_n / z_1, rel_tol=RTOL)
    expected = ETA_CHAIN ** (n - 1)
    if expected > 1e-290:
        ok &= math.isclose(result.efficiency, expected, rel_tol=RTOL)
    power = np.array([m.carrier_frame_power for m in result.meshes])
    closed = result.input_power * ETA_CHAIN ** np.arange(len(power))
    shown = closed > 1e-290
    return bool(ok and np.allclose(power[shown], closed[shown], rtol=RTOL, atol=0))


def series_check(n: int, result) -> bool:
    ratio, efficiency = series_closed_form(n)
    return math.isclose(result.ratio, ratio, rel_tol=RTOL) and \
        math.isclose(result.efficiency, efficiency, rel_tol=RTOL)


def measure(text: str):
    start = time.perf_counter()
    model = loads_model(text)
    loaded = time.perf_counter()
    result = solve(model)
    return loaded - start, time.perf_counter() - loaded, result


def exponent(rows: list[dict], key: str) -> float | None:
    """Least-squares slope of log(time ``key``) over log(size), three largest sizes."""
    big = sorted(rows, key=lambda r: r["size"])[-3:]
    if len(big) < 2:
        return None
    x = np.log([r["size"] for r in big])
    y = np.log([max(r[key], 1e-6) for r in big])
    return float(np.polyfit(x, y, 1)[0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+",
                        default=[10, 100, 1_000, 10_000, 100_000], help="chain lengths")
    parser.add_argument("--series", type=int, nargs="+", default=[10, 100, 1_000, 2_000],
                        help="numbers of 2K-H stages")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()

    rv = ROOT / "models" / "rv40e_wang2021.yaml"
    solve(load_model(rv))  # one-time imports (scipy for the large trains) are not
    solve(loads_model(chain_text(500)))  # part of any size

    def rv_once() -> float:
        start = time.perf_counter()
        solve(load_model(rv))
        return time.perf_counter() - start

    baseline = min(rv_once() for _ in range(5))
    report: dict = {"rv40e_load_and_solve_s": baseline, "families": {}}
    for family, sizes, text, check in (("chain", args.sizes, chain_text, chain_check),
                                       ("series", args.series, series_text, series_check)):
        rows = []
        for n in sizes:
            load_s, solve_s, result = measure(text(n))
            rows.append({"size": n, "load_s": round(load_s, 4), "solve_s": round(solve_s, 4),
                         "total_s": round(load_s + solve_s, 4),
                         "x_rv40e": round((load_s + solve_s) / baseline, 1),
                         "closed_form_ok": check(n, result)})
            if not args.json:
                r = rows[-1]
                print(f"{family:6} {n:>7}: load {load_s:8.3f} s  solve {solve_s:8.3f} s  "
                      f"total {r['total_s']:8.3f} s  ({r['x_rv40e']:>9.1f} x RV-40E)  "
                      f"closed form {'ok' if r['closed_form_ok'] else 'MISMATCH'}",
                      flush=True)
        slope, solve_slope = exponent(rows, "total_s"), exponent(rows, "solve_s")
        report["families"][family] = {"rows": rows, "growth_exponent": slope,
                                      "solve_growth_exponent": solve_slope}
        if not args.json and slope is not None:
            print(f"{family}: growth exponent {slope:.2f} (load and solve), "
                  f"{solve_slope:.2f} (solve alone), three largest sizes")
    if args.json:
        print(json.dumps(report))
    else:
        print(f"RV-40E load and solve: {baseline * 1e3:.2f} ms")


if __name__ == "__main__":
    main()
