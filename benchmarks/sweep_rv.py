"""RV-40E design sweep: compiled sweep vs a hand-derived closed form vs a loop of solves.

10^6 variants of models/rv40e_wang2021.yaml with z1, z2, z4, z5 = z4 + 1, η1 (mesh 1–2) and η2
(mesh 4–5) drawn at random (z1 in 10…20, z2 = round(z1·U(2, 4)), z4 in 25…60,
η in U(0.90, 1.0); input 1500 rpm, 2.27 kW) are evaluated by

(a) ``powergraph.analyses.sweep`` — the model compiled once (:func:`compile_sweep`);
(b) :func:`closed_form` below — the same virtual-power physics, derived by hand;
(b') the same closed form as numba kernels (one ``prange`` loop over the variants, both
     cores; skipped without numba): one writing every array the sweep returns, reported
     as ``compiled_vs_numba``, and one writing only the seven arrays of (b), reported as
     ``compiled_vs_numba_seven``;
(c) a Python loop of single solves (``powergraph.solve``) on ``--loop`` of them,
    extrapolated (each variant model is made by ``dataclasses.replace``, no validation,
    so the loop is as fast as it can be).

Times are wall-clock, best of ``--repeat`` runs after one warm-up run; (a) and (b) are
interleaved so both see the same machine load. ``compiled_vs_closed`` is the time ratio
(a)/(b); ``compiled_vs_loop`` the speed-up of (a) over (c); ``max_abs_diff`` the largest
difference between (a) and (b) over ratio and efficiency; ``peak_mb`` the peak of the
memory allocated during one evaluation of (a) (``tracemalloc``; inputs excluded);
``compile_s`` the one-off compile time (sympy derivation included); ``kernel_compile_s``
the time the sweep's numba kernel took to compile on its first run, or to load from the
kernel cache (``$POWERGRAPH_CACHE_DIR``, else ``~/.cache/powergraph/kernels``) when an
earlier process compiled it, and ``kernel_first_run_s`` that whole first run;
``*_first_s`` the warm-up runs after it, slower because fresh memory is page-faulted in.

Derivation of the closed form (docs/theory.md; ids as in the model file)
-----------------------------------------------------------------------
Bodies: 1 (input, speed ω1), 2/3 (planet gear on the crank), 4 (cycloid), 6/7 (output disk
and planet frame), 0/5 (housing and needle gear). Elements: mesh A = 1–2 in the frame of
carrier 7, Willis ratio i_A = -z2/z1; mesh B = 4–5 in the frame of the crank 3, i_B = +z5/z4
(5 is internal); coupling C = 4–6 (ratio 1, ideal).

Speeds. C: w4 = w6 = ω. B: (ω - w3) - i_B (0 - w3) = 0, so w3 = -ω z4/(z5 - z4).
A: (ω1 - ω) - i_A (w3 - ω) = 0, so ω1 = ω [1 + (z2/z1) z5/(z5 - z4)]:

    ratio  i = ω1/ω = 1 + z2 z5 / (z1 (z5 - z4))          (= 121 for 12, 36, 39, 40)

Torques. Mesh k applies λ_k to gear a, -g_k λ_k to gear b and (g_k - 1) λ_k to its
carrier, g_k = i_k f_k. Balance of body 1: T_in + λ_A = 0; of 2/3: -g_A λ_A +
(g_B - 1) λ_B = 0; of 4: λ_B + λ_C = 0; of 6/7: (g_A - 1) λ_A - λ_C + T_out = 0. Hence
λ_A = -T_in, λ_B = g_A λ_A / (g_B - 1), T_out = T_in [g_A g_B/(g_B - 1) - 1] and

    η = -T_out ω / (T_in ω1) = [1 + (z2/z1) f_A g_B/(g_B - 1)] / i.

Directions (who drives in the carrier's frame). Mesh A: gear 1 feeds
-λ_A (ω1 - ω) = P (1 - 1/i) > 0, so 1 drives: f_A = η1. Mesh B: gear 4 feeds
-λ_B (ω - w3) with ω - w3 = ω z5/(z5 - z4) > 0 and λ_B of the sign of (g_B - 1): with
f = 1, g_B = z5/z4 > 1, so 4 takes power out and the needle gear 5 drives: f_B = 1/η2,
g_B = z5/(z4 η2) > 1 — the same pattern, so it is self-consistent for every variant with
z5 > z4 (and P, ω1 > 0); ``valid`` checks it. With g_B/(g_B - 1) = z5/(z5 - z4 η2):

    η = [1 + (z2/z1) η1 z5 / (z5 - z4 η2)] / i             (0.287376 for η1 = η2 = 0.94)

Losses: L_A = P (1 - 1/i)(1 - η1) (the virtual power of A times 1 - η1); the total is
P (1 - η); L_B = P (1 - η) - L_A (the coupling is ideal). Self-locking: η <= 0.

Usage: python benchmarks/sweep_rv.py [--json] [--variants N] [--loop N] [--repeat N]
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import random
import resource
import sys
import time
import tracemalloc
from pathlib import Path
from types import MappingProxyType

import numpy as np

from powergraph.testing_trains import RV_PATHS, rv_variants

ROOT = Path(__file__).resolve().parents[1]
MODEL = ROOT / "models" / "rv40e_wang2021.yaml"
PATHS = RV_PATHS
POWER = 2270.0   # W, the model's input power


def variants(n: int, seed: int = 0) -> dict[str, np.ndarray]:
    """Random RV variants by PATH (teeth as integers)."""
    return rv_variants(n, seed)


def closed_form(z1, z2, z4, z5, eta1, eta2, power: float = POWER) -> dict[str, np.ndarray]:
    """The RV's ratio, efficiency, losses and flags by the hand derivation above."""
    k = z2 / z1
    ratio = 1.0 + k * z5 / (z5 - z4)
    efficiency = (1.0 + k * eta1 * z5 / (z5 - z4 * eta2)) / ratio
    loss_12 = power * (1.0 - 1.0 / ratio) * (1.0 - eta1)
    total_loss = power * (1.0 - efficiency)
    return {"ratio": ratio, "efficiency": efficiency, "loss_12": loss_12,
            "loss_45": total_loss - loss_12, "total_loss": total_loss,
            "self_locking": efficiency <= 0.0, "valid": z5 > z4}


def numba_closed_form():
    """:func:`closed_form` as one numba loop over the variants on every core (``prange``),
    or None without numba: what a hand-written compiled kernel of the same seven outputs
    costs (it checks no direction: the derivation above proves the pattern for these
    values)."""
    try:
        import numba
    except ImportError:
        return None

    @numba.njit(parallel=True, cache=True)
    def kernel(z1, z2, z4, z5, eta1, eta2, power, ratio, efficiency, loss_12, loss_45,
               total_loss, self_locking, valid):
        for j in numba.prange(len(z1)):
            k = z2[j] / z1[j]
            ratio[j] = 1.0 + k * z5[j] / (z5[j] - z4[j])
            efficiency[j] = (1.0 + k * eta1[j] * z5[j] / (z5[j] - z4[j] * eta2[j])) / ratio[j]
            loss_12[j] = power * (1.0 - 1.0 / ratio[j]) * (1.0 - eta1[j])
            total_loss[j] = power * (1.0 - efficiency[j])
            loss_45[j] = total_loss[j] - loss_12[j]
            self_locking[j] = efficiency[j] <= 0.0
            valid[j] = z5[j] > z4[j]

    def run(z1, z2, z4, z5, eta1, eta2, power: float = POWER) -> dict[str, np.ndarray]:
        n = len(z1)
        out = {name: np.empty(n) for name in ("ratio", "efficiency", "loss_12", "loss_45",
                                               "total_loss")}
        flags = {name: np.empty(n, dtype=bool) for name in ("self_locking", "valid")}
        kernel(z1, z2, z4, z5, eta1, eta2, power, out["ratio"], out["efficiency"],
               out["loss_12"], out["loss_45"], out["total_loss"], flags["self_locking"],
               flags["valid"])
        return {**out, **flags}

    return run


def numba_sweep_outputs():
    """The hand derivation as a numba kernel writing every array the sweep returns, or None
    without numba: ratio, efficiency, input and output power, total loss, a loss and a
    driver code per link (the coupling's loss 0 by derivation), self-locking, status and
    passes (constants by derivation), and the validity flag (standing for ``converged``);
    fresh arrays written once each, in the loop (zeroing them first with ``np.zeros``
    would cost a pass over memory)."""
    try:
        import numba
    except ImportError:
        return None

    @numba.njit(parallel=True, cache=True)
    def kernel(z1, z2, z4, z5, eta1, eta2, power, ratio, efficiency, input_power,
               output_power, total_loss, losses, drivers, self_locking, status, passes,
               valid):
        for j in numba.prange(len(z1)):
            k = z2[j] / z1[j]
            i = 1.0 + k * z5[j] / (z5[j] - z4[j])
            eta = (1.0 + k * eta1[j] * z5[j] / (z5[j] - z4[j] * eta2[j])) / i
            loss_12 = power * (1.0 - 1.0 / i) * (1.0 - eta1[j])
            total = power * (1.0 - eta)
            ratio[j], efficiency[j], total_loss[j] = i, eta, total
            input_power[j], output_power[j] = power, power * eta
            losses[0, j], losses[1, j], losses[2, j] = loss_12, total - loss_12, 0.0
            drivers[0, j], drivers[1, j], drivers[2, j] = 1, -1, 1
            self_locking[j] = eta <= 0.0
            status[j], passes[j] = 0, 1
            valid[j] = z5[j] > z4[j]

    def run(z1, z2, z4, z5, eta1, eta2, power: float = POWER) -> dict[str, np.ndarray]:
        n = len(z1)
        out = {name: np.empty(n) for name in ("ratio", "efficiency", "input_power",
                                               "output_power", "total_loss")}
        out.update(losses=np.empty((3, n)), drivers=np.empty((3, n), dtype=np.int8),
                   self_locking=np.empty(n, dtype=bool), status=np.empty(n, dtype=np.int8),
                   passes=np.empty(n, dtype=np.int8), valid=np.empty(n, dtype=bool))
        kernel(z1, z2, z4, z5, eta1, eta2, power, out["ratio"], out["efficiency"],
               out["input_power"], out["output_power"], out["total_loss"], out["losses"],
               out["drivers"], out["self_locking"], out["status"], out["passes"],
               out["valid"])
        return out

    return run


def loop(model, values: dict[str, np.ndarray], count: int) -> tuple[float, np.ndarray]:
    """Seconds for ``count`` single solves, and their (ratio, efficiency) rows."""
    import powergraph as pg

    rows = np.empty((count, 2))
    start = time.perf_counter()
    for j in range(count):
        components = dict(model.components)
        for path in PATHS[:4]:
            cid = path.split(".")[1]
            components[cid] = dataclasses.replace(components[cid],
                                                  teeth=int(values[path][j]))
        variant = dataclasses.replace(model, components=MappingProxyType(components))
        variant = variant.with_link(0, efficiency=float(values[PATHS[4]][j]))
        variant = variant.with_link(1, efficiency=float(values[PATHS[5]][j]))
        result = pg.solve(variant)
        rows[j] = result.ratio, result.efficiency
    return time.perf_counter() - start, rows


def best_times(runs: dict, repeat: int) -> tuple[dict[str, float], dict[str, float]]:
    """Best wall time of each callable, interleaved, after one warm-up run each; and the
    warm-up (first) times, which include the page faults of fresh memory. Each round runs
    the callables in a fresh shuffled order (seeded), so that none is always timed after
    the same one (a run finds the caches and the allocator as the one before left them)."""
    times = {name: [] for name in runs}
    first = {}
    for name, run in runs.items():
        start = time.perf_counter()
        run()
        first[name] = time.perf_counter() - start
    order, shuffle = list(runs), random.Random(0).shuffle
    for _ in range(repeat):
        shuffle(order)
        for name in order:
            start = time.perf_counter()
            runs[name]()
            times[name].append(time.perf_counter() - start)
    return {name: min(t) for name, t in times.items()}, first


def peak_megabytes(run) -> float:
    """Peak memory traced while ``run()`` evaluates (numpy reports to tracemalloc)."""
    tracemalloc.start()
    try:
        run()
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return peak / 2**20


def measure(n: int, n_loop: int, repeat: int, seed: int) -> dict:
    from powergraph.model import load_model
    from powergraph.analyses.sweep import compile_sweep

    model = load_model(MODEL)
    values = variants(n, seed)
    start = time.perf_counter()
    evaluate = compile_sweep(model, list(PATHS))
    compile_s = time.perf_counter() - start
    start = time.perf_counter()
    evaluate(values, quiet=True)       # the first run: the numba kernel compiles (or loads)
    kernel_first_s = time.perf_counter() - start
    kernel_compile_s = evaluate.kernel_compile_s
    args = [values[p] for p in PATHS]
    runs = {"compiled": lambda: evaluate(values, quiet=True),
            "closed": lambda: closed_form(*args)}
    kernel, kernel_all = numba_closed_form(), numba_sweep_outputs()
    if kernel is not None:
        runs["numba_seven"] = lambda: kernel(*args)
        runs["numba"] = lambda: kernel_all(*args)
    times, first = best_times(runs, repeat)
    swept, hand = evaluate(values, quiet=True), closed_form(*args)
    numba_row = {}
    if kernel is not None:
        seven, every = kernel(*args), kernel_all(*args)
        every = {"loss_12": every["losses"][0], "loss_45": every["losses"][1], **every}
        numba_row = {
            "numba_per_s": round(n / times["numba"]),
            "compiled_vs_numba": round(times["compiled"] / times["numba"], 3),
            "compiled_vs_numba_seven": round(times["compiled"] / times["numba_seven"], 3),
            "numba_s": round(times["numba"], 4), "numba_first_s": round(first["numba"], 4),
            "numba_seven_s": round(times["numba_seven"], 4),
            "numba_max_abs_diff": float(max(
                np.max(np.abs(hands[key] - hand[key])) for hands in (seven, every) for key in
                ("ratio", "efficiency", "loss_12", "loss_45", "total_loss")))}
    if not (np.all(hand["valid"]) and np.all(swept.converged)):
        raise SystemExit("a variant left the closed form's direction pattern")
    diff = max(np.max(np.abs(swept.formal_efficiency - hand["efficiency"])),
               np.max(np.abs(swept.ratio - hand["ratio"])))
    loop_s, rows = loop(model, values, n_loop)
    loop_diff = max(np.max(np.abs(rows[:, 0] - swept.ratio[:n_loop])),
                    np.max(np.abs(rows[:, 1] - swept.efficiency[:n_loop])))
    peak = peak_megabytes(lambda: evaluate(values, quiet=True))
    compiled_per_s, loop_per_s = n / times["compiled"], n_loop / loop_s
    return {"variants": n, "compiled_per_s": round(compiled_per_s),
            "closed_form_per_s": round(n / times["closed"]), "loop_per_s": round(loop_per_s),
            "compiled_vs_closed": round(times["compiled"] / times["closed"], 3),
            **numba_row,
            "compiled_vs_loop": round(compiled_per_s / loop_per_s, 1),
            "max_abs_diff": float(diff), "peak_mb": round(peak, 1),
            "compile_s": round(compile_s, 3), "kernel_compile_s": round(kernel_compile_s, 3),
            "kernel_first_run_s": round(kernel_first_s, 3),
            "compiled_s": round(times["compiled"], 4),
            "closed_form_s": round(times["closed"], 4),
            "compiled_first_s": round(first["compiled"], 4),
            "closed_form_first_s": round(first["closed"], 4), "loop_variants": n_loop,
            "loop_max_abs_diff": float(loop_diff),
            "max_rss_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", action="store_true", help="print one JSON line")
    parser.add_argument("--variants", type=int, default=10**6)
    parser.add_argument("--loop", type=int, default=1000, help="single solves timed")
    parser.add_argument("--repeat", type=int, default=40)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    row = measure(args.variants, args.loop, args.repeat, args.seed)
    if args.json:
        print(json.dumps(row))
        return
    width = max(map(len, row))
    for key, value in row.items():
        print(f"{key:<{width}}  {value}")


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    main()
