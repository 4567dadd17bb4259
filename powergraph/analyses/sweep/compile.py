"""Compile a model once into an evaluator over arrays of its values.

Compiling resolves the PATHs (:mod:`~powergraph.analyses.sweep.paths`) and the train's
fixed structure (:class:`Layout`: which body each element's gear a, gear b and carrier is
on, which ports give a speed and which a load), then builds a backend
(:mod:`~powergraph.analyses.sweep.backends`: the speed and force systems solved
symbolically and compiled, or batched numeric solves) and the closed form of the model's
own direction pattern. Evaluating runs in chunks (:mod:`~powergraph.analyses.sweep.evaluate`):
each chunk's variants go to the closed forms whose direction pattern provably holds for
them, the rest through the general vectorised iteration — whose most common patterns get
closed forms of their own (at most :data:`MAX_CLOSED_FORMS`), so a sweep across a
direction change stays fast.
"""
from __future__ import annotations

import sys
import warnings
from contextlib import contextmanager
from typing import Any, Callable, Iterator, Mapping, Sequence

import numpy as np

from powergraph.analyses.sweep import backends
from powergraph.analyses.sweep.evaluate import Chunk, Outputs, evaluate_chunk
from powergraph.analyses.sweep.layout import Layout, base_values, layout_of
from powergraph.analyses.sweep.paths import (Parameter, broadcast_values, check_all,
                                             check_values, flat_values, parse_paths)
from powergraph.analyses.sweep.result import (CYCLE, LOADS, NO_FREEWHEEL_STATE,
                                             UNSETTLED, SweepResult, converged_of)
from powergraph.errors import ModelError, PowerGraphError, UsageError
from powergraph.kinematics import elements_of
from powergraph.model.spec import Model
from powergraph.statics import solve
from powergraph.statics.friction import loss_block_places
from powergraph.analyses.sweep.single import write_failed as _write_failed
from powergraph.analyses.sweep.per_point import with_values
from powergraph.analyses.sweep.single import write_single as _write_single

#: Variants evaluated at once: small enough to keep the work arrays in cache (measured
#: fastest on the RV benchmark among 8k, 12k, 16k, 24k, 32k and 64k).
CHUNK_SIZE = 1 << 14
#: A progress bar appears when a run lasts longer than this (s), unless quiet.
PROGRESS_DELAY = 1.0
BACKENDS = ("auto", "symbolic", "numeric")
#: Most direction patterns compiled to closed forms per evaluator.
MAX_CLOSED_FORMS = 4
#: Runs of at least this many variants go through the closed forms' numba kernels
#: (:mod:`~powergraph.analyses.sweep.kernel`) when numba imports; smaller ones, where a
#: kernel's compile (about a second, once per process without the disk cache) would not
#: pay, through numpy.
KERNEL_MIN_VARIANTS = 1 << 16


class KernelFallbackWarning(UserWarning):
    """A closed form's numba kernel did not compile or run: the sweep goes on with numpy
    (the same answers, slower). Not a RuntimeWarning, which the command line turns into
    an error about the numbers."""


class CompiledSweep:
    """A model compiled into an evaluator over arrays of the swept values.

    Parameters
    ----------
    model : Model
        The train (not changed).
    paths : sequence of str
        The model values to sweep (see :mod:`powergraph.analyses.sweep.paths`):
        ``components.<id>.teeth``, ``links.<i>.efficiency``, ``links.*.efficiency``,
        ``links.<i>.ratio``, ``ports.<i>.speed`` / ``power`` / ``torque``.
    backend : {"auto", "symbolic", "numeric"}
        ``symbolic`` solves the train's linear systems once with sympy and compiles the
        closed forms, per direction pattern (fast); ``numeric`` builds batched matrices
        and solves them with numpy. ``auto`` takes ``symbolic`` where it applies (square,
        determinate systems of up to 8 unknowns: every train in models/).

    Notes
    -----
    Results equal :func:`powergraph.solve` on each modified model (to rounding), power
    directions included: each variant settles on its own pattern. Variants the single
    solver rejects are flagged, never given a number: ``converged`` False, ``status``
    ``cycle`` (no consistent direction pattern), ``unsettled``, ``speeds`` or ``loads``
    (not determined), and NaN efficiency, powers and losses. Only power-flow values change:
    geometry blocks (volume analysis) are not re-checked against swept teeth.

    Examples
    --------
    >>> import numpy as np
    >>> from powergraph.model import load_model
    >>> rv = load_model("models/rv40e_wang2021.yaml")
    >>> evaluate = CompiledSweep(rv, ["links.1.efficiency"])
    >>> result = evaluate({"links.1.efficiency": np.array([0.94, 0.998])})
    >>> np.round(result.efficiency, 6).tolist()
    [0.287376, 0.873043]
    """

    def __init__(self, model: Model, paths: Sequence[str], backend: str = "auto",
                 mode: str | None = None) -> None:
        from powergraph.statics.case import TrainCase

        if isinstance(paths, str):
            paths = [paths]
        if backend not in BACKENDS:
            raise UsageError(f"backend must be one of {', '.join(BACKENDS)}, got {backend!r}")
        self.case = TrainCase.of(model, mode)
        self.source = model
        model = self.case.plain_model()    # the layout; freewheels as at the model's load
        refuse_loss_blocks(model, "the compiled sweep")
        self.model = model
        self.parameters: tuple[Parameter, ...] = parse_paths(model, paths)
        self._closed_forms: list = []
        self._kernels: dict = {}        # (start, codes) -> its numba Kernel (None: failed)
        if model.buses:     # the bus balance's iteration: every variant solved by its case
            self.links = tuple(e.link for e in elements_of(model))
            self.layout = self.backend = None
            return
        self.layout: Layout = layout_of(model, self.parameters)
        self.links = self.layout.links
        if backend == "symbolic" and not backends.applies(self.layout):
            raise UsageError("the symbolic backend needs square, statically determinate "
                             f"systems of at most {backends.MAX_SYMBOLIC} unknowns; "
                             "use backend='numeric'")
        use_symbolic = backend == "symbolic" or (backend == "auto"
                                                 and backends.applies(self.layout))
        self.backend = backends.symbolic_backend(self.layout) if use_symbolic \
            else backends.NumericBackend(self.layout)
        self._base = base_values(model, self.layout)
        self._element = {link: k for k, link in enumerate(self.layout.links)}
        self._moving = _moving(self.layout, self.parameters, self._base)
        if use_symbolic:
            pattern = _base_pattern(model, self._moving)
            if pattern is not None:
                self._add_closed_form(pattern, pattern)
        self._speed_slot = {port: j for j, (_, port) in enumerate(self.layout.speed_ports)}
        self._load_slot = {load.port: j for j, load in enumerate(self.layout.loads)}

    @property
    def paths(self) -> tuple[str, ...]:
        return tuple(p.path for p in self.parameters)

    def __call__(self, values: Mapping[str, Any], *, chunk_size: int = CHUNK_SIZE,
                 quiet: bool = False) -> SweepResult:
        """Evaluate every variant.

        Parameters
        ----------
        values : mapping PATH -> array_like
            One entry per compiled PATH; the arrays broadcast against each other and the
            result has their broadcast shape.
        chunk_size : int
            Variants evaluated at once (bounds the memory of the work arrays; the default
            keeps them in cache).
        quiet : bool
            Never show the progress bar (shown on stderr for runs over ~1 s otherwise).

        Returns
        -------
        SweepResult

        Raises
        ------
        UsageError
            Missing or unknown PATHs, arrays that do not broadcast.
        ModelError
            A value out of range (named by its PATH).
        """
        kernels = None
        arrays, shape = broadcast_values(self.parameters, values, check=False)
        n = int(np.prod(shape, dtype=np.int64))
        if self.case.decides_freewheels or self.layout is None:
            return self._per_point(arrays, shape, n, quiet)
        if n >= KERNEL_MIN_VARIANTS and self._closed_forms:
            kernels = kernel_module()
        if kernels is None:
            check_all(self.parameters, arrays)
        else:    # the kernels check the arrays' values; the values given once, here
            _check_scalars(self.parameters, arrays)
        flat = flat_values(arrays, shape)
        step = max(1, int(chunk_size))
        outputs = Outputs.empty(n, self.layout.n_elements)
        rest, converged = (None, None) if kernels is None else self._run_kernels(kernels, flat,
                                                                                 outputs)
        if kernels is not None and (rest is None or rest.size):
            check_all(self.parameters, arrays)    # a variant left may hold a value not allowed
        if rest is None:
            self._run_chunks(flat, outputs, step, quiet)
        elif rest.size:                       # the variants no kernel took
            part = Outputs.empty(rest.size, self.layout.n_elements)
            self._run_chunks({path: value[rest] if value.ndim else value
                              for path, value in flat.items()}, part, step, quiet)
            outputs.put(rest, part, slice(None))
            converged[rest] = converged_of(part.status)
        return SweepResult.of(self.model.name, arrays, shape, outputs, self.layout.links,
                              self.backend.name, converged)

    evaluate = __call__

    def _per_point(self, arrays: dict, shape: tuple, n: int, quiet: bool) -> SweepResult:
        """A mode whose freewheels are decided at each operating point, or a train with
        machines on buses: every variant is the case's own answer
        (:meth:`powergraph.statics.case.TrainCase.point`), so the sweep decides the
        freewheels and balances the buses exactly where ``solve --mode`` does."""
        check_all(self.parameters, arrays)
        flat = flat_values(arrays, shape)
        outputs = Outputs.empty(n, len(self.links))
        with _progress(n, 1, quiet) as update:
            for j in range(n):
                try:
                    point = self.case.point(with_values(self.source, self.parameters,
                                                        flat, j))
                except PowerGraphError:
                    point = None
                if point is not None and point.ok:
                    _write_single(outputs, j, point.result, self.links)
                else:                             # flagged: no number is made up
                    _write_failed(outputs, j, LOADS if point is None else NO_FREEWHEEL_STATE)
                update(1)
        return SweepResult.of(self.model.name, arrays, shape, outputs, self.links,
                              "single solves", converged_of(outputs.status))

    def _run_chunks(self, flat: dict, outputs: Outputs, step: int, quiet: bool) -> None:
        """Every variant of ``flat`` into ``outputs``, chunk by chunk, with numpy."""
        n = outputs.status.size
        with _progress(n, step, quiet) as update:
            for start in range(0, n, step):
                stop = min(n, start + step)
                chunk = self._chunk(flat, start, stop)
                part = outputs.part(start, stop)
                learned = evaluate_chunk(self.layout, self.backend, chunk, part,
                                         self._closed_forms,
                                         self._moving if self._learning else None)
                self._decide_undecided(flat, start, part)
                if learned is not None:
                    self._add_closed_form(*learned)
                self._closed_forms.sort(key=lambda form: -form.hits)
                update(stop - start)

    def _run_kernels(self, kernels, flat: dict,
                     outputs: Outputs) -> tuple[np.ndarray | None, np.ndarray | None]:
        """The closed forms' numba kernels over every variant, written straight into
        ``outputs`` (the first form's over all of them, each next one's over those left).

        Returns the indices of the variants none took, or None when a kernel does not
        compile or run (then numpy evaluates every variant); and where a kernel took the
        variant, the first kernel's ``valid`` array (a kernel's variant is ``ok``: this is
        ``converged`` but for the variants left, saving a pass over ``status``).
        """
        rest = taken = None          # the variants not taken yet (None: all)
        swept = [flat[param.path] for param in self.parameters]
        for form in list(self._closed_forms):
            key = (form.start, form.codes)
            try:
                if key not in self._kernels:
                    self._kernels[key] = kernels.Kernel(
                        form, lambda scalar: self._input_lines(kernels, scalar))
                if self._kernels[key] is None:
                    return None, None
                if rest is None:
                    taken, rejected = self._kernels[key](swept, outputs)
                    rest = np.flatnonzero(~taken) if rejected else np.empty(0, np.int64)
                    form.hits += outputs.status.size - rest.size
                    if rest.size == 0:
                        break
                    continue
                part = Outputs.empty(rest.size, self.layout.n_elements)
                valid, _ = self._kernels[key]([a[rest] if a.ndim else a for a in swept],
                                              part)
            except Exception as error:        # numba's typing or lowering errors
                warnings.warn(KernelFallbackWarning(
                    f"the sweep's numba kernel failed ({type(error).__name__}: {error}); "
                    "evaluating with numpy"), stacklevel=3)
                self._kernels[key] = None
                return None, None
            outputs.put(rest[valid], part, valid)
            taken[rest[valid]] = True
            form.hits += int(np.count_nonzero(valid))
            rest = rest[~valid]
            if rest.size == 0:
                break
        self._closed_forms.sort(key=lambda form: -form.hits)
        return rest, taken

    def _input_lines(self, kernels, scalar: tuple[bool, ...]) -> tuple[list, list]:
        return (kernels.input_lines(self.layout, self.parameters, self._base, self._element,
                                    self._speed_slot, self._load_slot, scalar),
                kernels.allowed_checks(self.parameters, scalar))

    @property
    def kernel_compile_s(self) -> float:
        """Seconds the numba kernels compiled (or loaded from the cache) so far."""
        return sum(k.compile_s for k in self._kernels.values() if k is not None)

    def variant(self, values: Mapping[str, Any], index: int = 0) -> Model:
        """The model of one variant: ``self.model`` with the swept values of variant
        ``index`` (of the flattened broadcast shape) written into its links and ports.

        Examples
        --------
        >>> from powergraph.model import load_model
        >>> rv = load_model("models/rv40e_wang2021.yaml")
        >>> CompiledSweep(rv, ["links.1.efficiency"]).variant(
        ...     {"links.1.efficiency": [0.9, 0.95]}, 1).links[1].efficiency
        0.95
        """
        arrays, shape = broadcast_values(self.parameters, values)
        return with_values(self.model, self.parameters, flat_values(arrays, shape), index)

    def _decide_undecided(self, flat: dict, start: int, out: Outputs) -> None:
        """Variants whose direction iteration cycles or does not settle go to the single
        solver, whose complementarity search and locking verdict decide them exactly as
        :func:`powergraph.solve` does (docs/locking.md)."""
        for j in np.flatnonzero((out.status == CYCLE) | (out.status == UNSETTLED)).tolist():
            try:
                result = solve(with_values(self.model, self.parameters, flat, start + j))
            except PowerGraphError:
                continue                       # left flagged: no number is made up
            _write_single(out, j, result, self.layout.links)

    @property
    def patterns(self) -> tuple[tuple[tuple[int, ...], tuple[int, ...]], ...]:
        """Direction patterns compiled to closed forms so far, as ``(ideal, settled)``
        driver codes of the elements whose efficiency is not 1 (+1 gear a drives, -1 gear
        b, 0 nothing): the codes read from the ideal forces, and the settled ones."""
        return tuple((form.start, form.codes) for form in self._closed_forms)

    @property
    def _learning(self) -> bool:
        return isinstance(self.backend, backends.SymbolicBackend) \
            and len(self._closed_forms) < MAX_CLOSED_FORMS

    def _add_closed_form(self, start: tuple[int, ...], codes: tuple[int, ...]) -> None:
        if self._learning and (start, codes) not in self.patterns:
            self._closed_forms.append(self.backend.closed_form(self._moving, codes, start))

    def _chunk(self, flat: dict, start: int, stop: int) -> Chunk:
        base = self._base
        magnitudes, etas = list(base["ratios"]), list(base["efficiencies"])
        speeds, loads = list(base["speeds"]), list(base["loads"])
        teeth = dict(base["teeth"])
        for param in self.parameters:
            value = flat[param.path]
            value = value[start:stop] if value.ndim else float(value)
            if param.kind == "teeth":
                teeth[param.targets[0]] = value
            elif param.kind in ("efficiency", "ratio"):
                target = etas if param.kind == "efficiency" else magnitudes
                for link in param.targets:
                    target[self._element[link]] = value
            elif param.kind == "speed":
                speeds[self._speed_slot[param.targets[0]]] = value
            else:
                loads[self._load_slot[param.targets[0]]] = value
        for k, gear_a, gear_b in self.layout.teeth_ratios:
            magnitudes[k] = teeth[gear_b] / teeth[gear_a]
        return Chunk(n=stop - start, magnitudes=magnitudes, efficiencies=etas,
                     speeds=speeds, loads=loads)


def _moving(layout: Layout, params: tuple[Parameter, ...], base: dict) -> tuple[int, ...]:
    """Elements whose factor depends on the direction: efficiency swept or not 1."""
    element = {link: k for k, link in enumerate(layout.links)}
    swept = {element[t] for p in params if p.kind == "efficiency" for t in p.targets}
    return tuple(k for k, eta in enumerate(base["efficiencies"]) if k in swept or eta != 1.0)


def _base_pattern(model: Model, moving: tuple[int, ...]) -> tuple[int, ...] | None:
    """Driver codes of the moving elements in a single solve of the model as given, when
    it settles on its ideal pattern (one pass)."""
    from powergraph.errors import PowerGraphError
    from powergraph.statics import solve

    try:
        result = solve(model)
    except PowerGraphError:
        return None
    if result.passes != 1:     # the ideal pattern differs: left to the learning
        return None
    codes = [0 if e.driver is None else (1 if e.driver == e.a else -1)
             for e in result.elements]
    return tuple(codes[k] for k in moving)


def _check_scalars(params: tuple[Parameter, ...], arrays: Mapping[str, np.ndarray]) -> None:
    """Check the values given once for every variant (the kernels check the arrays'); one
    out of range raises what checking every value in order raises."""
    try:
        for param in params:
            if arrays[param.path].ndim == 0:
                check_values(param, arrays[param.path])
    except ModelError:
        check_all(params, arrays)
        raise


def kernel_module():
    """:mod:`powergraph.analyses.sweep.kernel`, or None when numba does not import."""
    try:
        import numba  # noqa: F401

        from powergraph.analyses.sweep import kernel
    except ImportError:
        return None
    return kernel


@contextmanager
def _progress(n: int, chunk_size: int, quiet: bool) -> Iterator[Callable[[int], Any]]:
    """``update(count)`` of a tqdm bar on stderr for long runs (delayed, so short runs
    print nothing)."""
    if quiet or n <= chunk_size:
        yield lambda count: None
        return
    from tqdm import tqdm

    with tqdm(total=n, unit="variant", unit_scale=True, file=sys.stderr,
              delay=PROGRESS_DELAY, desc="sweep", leave=False) as bar:
        yield bar.update


def refuse_loss_blocks(model: Model, what: str) -> None:
    """Refuse a model whose losses are not constant efficiencies: a mesh's ``friction:``
    or ``pins:``, a bearing's ``friction:``/``drag:``, a component's ``drag:`` (evaluated
    on plain efficiencies they would silently vanish). A caller that has replaced them by
    efficiencies passes a model without them.

    >>> from powergraph.model import load_model
    >>> m = load_model("models/rv40e.yaml")
    >>> refuse_loss_blocks(m, "the compiled sweep")   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    powergraph.errors.ModelError: links[0].friction: the compiled sweep takes constant ...
    """
    places = loss_block_places(model)
    if places:
        raise ModelError(f"{what} takes constant efficiencies; replace this block by an "
                         f"efficiency, or use powergraph solve / map", places[0])
