"""Monte Carlo over the toleranced values, yields, and Sobol sensitivities.

Sampling: every toleranced value is drawn independently through its quantile function
from ``numpy.random.default_rng(seed)`` (PCG64), in chunks of :data:`CHUNK` units, each
chunk evaluated by one vectorised call. Sensitivities: first-order and total Sobol indices
with SALib (Saltelli's scheme on a scrambled Sobol sequence, Jansen's total-effect
estimator; ``sobol_samples``·(D + 2) extra evaluations for D toleranced values), in the
same uniform-then-quantile coordinates, so the indices are those of the distributions.
"""
from __future__ import annotations

import sys
from typing import Any, Sequence

import numpy as np

from powergraph.analyses.tolerance.evaluate import ToleranceEvaluator
from powergraph.analyses.tolerance.result import ToleranceResult
from powergraph.analyses.tolerance.stats import Spec, Yield, parse_spec, summary
from powergraph.errors import UsageError
from powergraph.model.spec import Model

#: Units evaluated per vectorised call (bounds the memory of the work arrays).
CHUNK = 1 << 17
#: Base sample size N of the Sobol design (N·(D + 2) evaluations).
SOBOL_SAMPLES = 1 << 12


def tolerance_analysis(model, samples: int = 100_000, seed: int | None = None,
                       specs: Sequence[str | Spec] = (), sobol_samples: int = SOBOL_SAMPLES,
                       progress: bool | None = None,
                       evaluator: ToleranceEvaluator | None = None) -> ToleranceResult:
    """Sample the model's tolerances and report outputs, yields and sensitivities.

    Parameters
    ----------
    model : Model
        A model with a ``tolerances:`` block.
    samples : int
        Monte Carlo units.
    seed : int, optional
        Seed of the generator (default: fresh entropy, reported in the result).
    specs : sequence of str or Spec
        Specifications (``"lost_motion<=1arcmin"``) whose yields to report.
    sobol_samples : int
        Base size N of the Sobol design (a power of 2); 0 skips the sensitivities.
    progress : bool, optional
        Show a tqdm bar on stderr (default: only on a terminal, for runs of several chunks).
    evaluator : ToleranceEvaluator, optional
        A prepared evaluator (to reuse its tables and compiled sweep).

    Returns
    -------
    ToleranceResult

    Examples
    --------
    >>> from powergraph.model import loads_model
    >>> m = loads_model('''
    ... name: pair
    ... components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 60}}
    ... links: [{type: mesh, between: [1, 2], backlash_arcmin: 6.0}]
    ... ports: [{component: 1, role: input}, {component: 2, role: output}]
    ... tolerances: {links.0.backlash_arcmin: {distribution: uniform, min: 0, max: 6}}
    ... ''')
    >>> r = tolerance_analysis(m, samples=10_000, seed=1, specs=["lost_motion<=1arcmin"],
    ...                        sobol_samples=0)
    >>> round(r.outputs["lost_motion_arcmin"]["max"], 2), round(r.yields[0].fraction, 1)
    (2.0, 0.5)
    """
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 2:
        raise UsageError(f"samples must be a whole number >= 2, got {samples!r}")
    if sobol_samples and (sobol_samples < 2 or sobol_samples & (sobol_samples - 1)):
        raise UsageError(f"sobol_samples must be a power of 2 (or 0), got {sobol_samples!r}")
    specs = tuple(s if isinstance(s, Spec) else parse_spec(s) for s in specs)
    evaluate = evaluator if evaluator is not None else ToleranceEvaluator(model)
    for spec in specs:
        if spec.output not in evaluate.outputs:
            raise UsageError(f"--spec {spec.text!r}: the model has no {spec.output} (its "
                             f"outputs: {', '.join(evaluate.outputs)})")
    if seed is None:
        seed = int(np.random.SeedSequence().entropy % (1 << 63))
    values = _monte_carlo(evaluate, int(samples), seed, progress)
    yields = tuple(Yield(s, int(np.count_nonzero(s.met(values[s.output]))), int(samples))
                   for s in specs)
    sensitivity = _sobol(evaluate, sobol_samples, seed) if sobol_samples else {}
    tables = {link: {"errors": t.errors.tolist(), "values": t.values.tolist(),
                     "interpolation_error_bound": t.error_bound}
              for link, t in evaluate.tables.items() if len(t.errors) > 1}
    return ToleranceResult(
        name=model.name, samples=int(samples), seed=seed,
        tolerances=evaluate.tolerances, values=values,
        outputs={k: summary(v) for k, v in values.items()}, yields=yields,
        sensitivity=sensitivity, sobol_samples=int(sobol_samples),
        fluctuation_tables=tables, labels=path_labels(model, evaluate.tolerances))


def path_labels(model: Model, tolerances: Any) -> dict[str, str]:
    """What each toleranced PATH is, in the model's names: ``mesh cycloid gear-needle
    gear`` for ``links.1.backlash_arcmin``."""
    labels = {}
    for entry in tolerances.entries:
        parts = []
        for index in entry.target.links:
            link = model.links[index]
            names = [model.components[c].name or str(raw)
                     for c, raw in zip(link.between, link.raw_between)]
            parts.append(f"{link.type} {'-'.join(names)}")
        labels[entry.target.path] = ", ".join(parts)
    return labels


def _columns(evaluate: ToleranceEvaluator, u: np.ndarray) -> dict[str, np.ndarray]:
    return {t.path: t.distribution.ppf(row) for t, row in zip(evaluate.tolerances.entries, u)}


def _monte_carlo(evaluate: ToleranceEvaluator, n: int, seed: int,
                 progress: bool | None) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(seed)
    count = len(evaluate.tolerances.entries)
    values = {name: np.empty(n) for name in evaluate.outputs}
    if progress is None:
        progress = n > 4 * CHUNK and sys.stderr.isatty()
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=n, unit="unit", file=sys.stderr, leave=False)
    try:
        for start in range(0, n, CHUNK):
            stop = min(n, start + CHUNK)
            out = evaluate(_columns(evaluate, rng.random((count, stop - start))))
            for name, array in out.items():
                values[name][start:stop] = array
            if bar is not None:
                bar.update(stop - start)
    finally:
        if bar is not None:
            bar.close()
    for array in values.values():
        array.setflags(write=False)
    return values


def _sobol(evaluate: ToleranceEvaluator, base: int, seed: int) -> dict[str, dict]:
    """``{output: {PATH: {first, total, first_conf, total_conf}}}`` by SALib."""
    from SALib.analyze import sobol as sobol_analyze
    from SALib.sample import sobol as sobol_sample

    paths = [t.path for t in evaluate.tolerances.entries]
    problem = {"num_vars": len(paths), "names": paths, "bounds": [[0.0, 1.0]] * len(paths)}
    u = sobol_sample.sample(problem, base, calc_second_order=False, scramble=True, seed=seed)
    outputs: dict[str, np.ndarray] = {name: np.empty(len(u)) for name in evaluate.outputs}
    for start in range(0, len(u), CHUNK):
        block = u[start:start + CHUNK].T
        for name, array in evaluate(_columns(evaluate, block)).items():
            outputs[name][start:start + CHUNK] = array
    indices = {}
    for name, y in outputs.items():
        if not np.all(np.isfinite(y)) or np.ptp(y) <= 1e-12 * max(1.0, np.max(np.abs(y))):
            continue   # constant (nothing toleranced reaches it) or not computable
        s = sobol_analyze.analyze(problem, y, calc_second_order=False, seed=seed)
        indices[name] = {p: {"first": float(s["S1"][i]), "total": float(s["ST"][i]),
                             "first_conf": float(s["S1_conf"][i]),
                             "total_conf": float(s["ST_conf"][i])}
                         for i, p in enumerate(paths)}
    return indices
