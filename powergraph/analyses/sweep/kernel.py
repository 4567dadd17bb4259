"""Numba kernels of the closed forms: a whole run of one direction pattern in one loop.

A :class:`~powergraph.analyses.sweep.backends.ClosedForm` evaluated with numpy makes a
pass over memory per operation (and the direction rule a dozen more per checked force
system). Its kernel is one loop over the variants, run on every core (numba's ``prange``:
its threads, and the loop vectorised, since numba tells the compiler that the arrays of a
parallel loop do not overlap). For each variant it does what :meth:`ClosedForm.evaluate`
does: read the swept values and check they are allowed (:func:`~powergraph.analyses.sweep.
paths.value_allowed`), form the ratio magnitudes from the teeth, compute the form's sympy
expressions (common subexpressions eliminated, printed as Python), check the pattern — the
speed system regular, the given torques' powers finite, then for each checked force
system: regular, its forces finite (one test: the bound of its scales below is), and the
driver codes the single solver's rule reads equal the expected ones — and, where all of
this holds, write every result of :class:`~powergraph.analyses.sweep.evaluate.Outputs` and
a ``valid`` flag. The other variants are left to the numpy path, which gives them exactly
today's answer.

The driver codes are read on a bound of the elements' own scales
(:func:`~powergraph.statics.directions.element_load`): a few operations per element
instead of the own scales' scatter over bodies. Where the bound names a driver (or the
relative speed is zero) its code is the own-scale rule's; a variant with a code the bound
cannot decide is left to the numpy path like one whose pattern fails.

The rules are not written again here: the direction rule, the zero relative speed and the
element's load are the numpy functions of :mod:`powergraph.statics.directions`, compiled
by numba on floats (their one selection, :func:`~powergraph.statics.directions.where`,
bound to a branch here); the flow efficiency and the allowed values are the per-point
forms of :mod:`powergraph.statics.ports` and :mod:`powergraph.analyses.sweep.paths`,
compiled as they are.

The generated source is written to a cache directory under a name that hashes it (and
the sources of those rules and numba's version), imported from there and compiled with
``cache=True``, so another process loads the machine code instead of compiling again
(:func:`cache_directory`; in memory when no directory is writable).
"""
from __future__ import annotations

import hashlib
import importlib.util
import math
import os
import sys
import threading
import time
import types
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numba
import numpy as np

from powergraph.analyses.sweep import paths as _paths
from powergraph.kinematics import elements as _elements
from powergraph.statics import directions as _directions
from powergraph.statics import ports as _ports
from powergraph.statics.directions import SCALE_BOUND, factor_of

if TYPE_CHECKING:  # pragma: no cover
    from powergraph.analyses.sweep.backends import ClosedForm
    from powergraph.analyses.sweep.layout import Layout
    from powergraph.analyses.sweep.evaluate import Outputs
    from powergraph.analyses.sweep.paths import Parameter

#: Environment variable naming the kernel cache directory ("" keeps kernels in memory).
CACHE_ENV = "POWERGRAPH_CACHE_DIR"
#: Array dtypes passed to a kernel as they are (others are converted to float64).
PASSED_DTYPES = (np.dtype(np.float64), np.dtype(np.int64))
#: One kernel runs at a time: each uses every core, and numba's own thread pool
#: (``workqueue``) must not be entered from two threads at once.
_RUNNING = threading.Lock()
#: The thread pool of the kernels' ``prange``: one that survives ``fork`` (TBB, else
#: numba's ``workqueue``): GNU OpenMP, numba's default where TBB is missing, aborts a
#: forked child that runs a kernel after its parent did. A choice made with
#: ``NUMBA_THREADING_LAYER`` is kept.
if "NUMBA_THREADING_LAYER" not in os.environ:
    numba.config.THREADING_LAYER = "forksafe"


def _jit(function: Callable) -> Callable:
    """``numba.njit`` of a rule, resolving its globals in this module: the
    functions it calls are their compiled forms here (numba caches a kernel only when
    every function it calls lives in an importable module)."""
    clone = types.FunctionType(function.__code__, globals(), function.__name__,
                               function.__defaults__, function.__closure__)
    clone.__qualname__ = clone.__name__ = f"jit_{function.__name__}"
    clone.__module__ = __name__
    clone.__doc__ = f"``{function.__module__}.{function.__name__}``, compiled by numba."
    return numba.njit(error_model="numpy", inline="never")(clone)


#: The rules, compiled, under the names they call each other by (the generated kernels
#: import the ``jit_`` names).
MAX_TEETH = _paths.MAX_TEETH
MAX_RATIO = _paths.MAX_RATIO
SPEED_NOISE, FORCE_NOISE = _directions.SPEED_NOISE, _directions.FORCE_NOISE
ROUND_OFF = _ports.ROUND_OFF


@numba.njit(error_model="numpy")
def where(condition, x, y):
    """:func:`powergraph.statics.directions.where` on floats: a branch (numba's
    ``np.where`` would make an array of a float)."""
    return x if condition else y


element_stencil = jit_element_stencil = _jit(_elements.element_stencil)
jit_driver_codes = _jit(_directions.driver_codes)
jit_element_load = _jit(_directions.element_load)
jit_relative_speed = _jit(_directions.relative_speed)
jit_flow_efficiency_point = _jit(_ports.flow_efficiency_point)
#: The allowed swept values, by kind (:func:`~powergraph.analyses.sweep.paths.value_allowed`).
ALLOWED = {"teeth": _jit(_paths.teeth_allowed), "efficiency": _jit(_paths.efficiency_allowed),
           "ratio": _jit(_paths.ratio_allowed)}
jit_port_value_allowed = _jit(_paths.port_value_allowed)


def _rules_digest() -> str:
    """Hash of what a cached kernel compiled in: the rule modules, this generator and
    numba's version (a change to any gives new kernel files)."""
    digest = hashlib.sha256(numba.__version__.encode())
    for module in (_elements, _directions, _ports, _paths, sys.modules[__name__]):
        digest.update(Path(module.__file__).read_bytes())
    return digest.hexdigest()


RULES_DIGEST = _rules_digest()


def input_lines(layout: "Layout", parameters: Sequence, base: Mapping,
                element: Mapping[int, int], speed_slot: Mapping, load_slot: Mapping,
                scalar: Sequence[bool]) -> list[str]:
    """Source lines setting, for variant ``j``, the closed form's arguments ``q{k}``
    (ratio magnitudes), ``e{k}`` (efficiencies), ``w{j}`` (given speeds) and ``p{j}``
    (loads) — what :meth:`CompiledSweep._chunk` does for a chunk. Swept value ``i`` is
    ``v{i}[j]``, or ``v{i}[0]`` where ``scalar[i]`` (one value for every variant); the
    others are constants.

    >>> from powergraph.model import load_model
    >>> from powergraph.analyses.sweep import compile_sweep
    >>> sweep = compile_sweep(load_model("models/rv40e_wang2021.yaml"), ["links.1.efficiency"])
    >>> input_lines(sweep.layout, sweep.parameters, sweep._base, sweep._element,
    ...             sweep._speed_slot, sweep._load_slot, [False])[3:5]
    ['e0 = 0.94', 'e1 = v0[j]']
    """
    value = lambda x: repr(float(x))   # noqa: E731  (exact: repr round-trips)
    magnitudes = [value(x) for x in base["ratios"]]
    etas = [value(x) for x in base["efficiencies"]]
    speeds, loads = [value(x) for x in base["speeds"]], [value(x) for x in base["loads"]]
    teeth = {cid: value(z) for cid, z in base["teeth"].items()}
    for i, param in enumerate(parameters):
        swept = f"v{i}[0]" if scalar[i] else f"v{i}[j]"
        if param.kind == "teeth":
            teeth[param.targets[0]] = swept
        elif param.kind in ("efficiency", "ratio"):
            target = etas if param.kind == "efficiency" else magnitudes
            for link in param.targets:
                target[element[link]] = swept
        elif param.kind == "speed":
            speeds[speed_slot[param.targets[0]]] = swept
        else:
            loads[load_slot[param.targets[0]]] = swept
    for k, gear_a, gear_b in layout.teeth_ratios:
        magnitudes[k] = f"{teeth[gear_b]} / {teeth[gear_a]}"
    return ([f"q{k} = {x}" for k, x in enumerate(magnitudes)]
            + [f"e{k} = {x}" for k, x in enumerate(etas)]
            + [f"w{k} = {x}" for k, x in enumerate(speeds)]
            + [f"p{k} = {x}" for k, x in enumerate(loads)])


def allowed_checks(parameters: Sequence["Parameter"], scalar: Sequence[bool]) -> list[str]:
    """Source of the checks that variant ``j``'s swept values are allowed (the arrays'
    values: the caller checks values given once for every variant itself)."""
    checks = []
    for i, param in enumerate(parameters):
        if scalar[i]:
            continue
        if param.kind in ALLOWED:
            checks.append(f"{param.kind}_allowed(v{i}[j])")
        else:
            checks.append(f"port_value_allowed(v{i}[j], {_number(_paths.port_limit(param.kind))})")
    return checks


def _number(x: float) -> str:
    return repr(float(x)) if math.isfinite(x) else ("math.inf" if x > 0 else "-math.inf")


def expression_lines(form: "ClosedForm") -> list[str]:
    """``o{i} = ...``: the closed form's expressions as Python on floats, after common
    subexpression elimination (as its numpy function)."""
    import sympy as sp

    replacements, reduced = sp.cse(list(form.expressions), sp.numbered_symbols("x_"))
    return ([f"{symbol} = {_python(e)}" for symbol, e in replacements]
            + [f"o{i} = {_python(e)}" for i, e in enumerate(reduced)])


def _python(expression) -> str:
    """A sympy expression (or a number) as Python on floats; numbers as exact floats."""
    import sympy as sp
    from sympy.printing.pycode import PythonCodePrinter

    expression = sp.sympify(expression)
    if expression.is_Number:
        return repr(float(expression))
    return PythonCodePrinter({"standard": "python3"}).doprint(expression)


def kernel_source(form: "ClosedForm", n_swept: int, inputs: list[str], allowed: list[str],
                  cache: bool) -> str:
    """The Python source of the kernel of ``form`` (``inputs``: :func:`input_lines`,
    ``allowed``: :func:`allowed_checks`).

    One loop over the variants, branch-free so that the compiler vectorises it: the
    inputs, the expressions, then per checked force system its factors, the bound of its
    own scales and the driver codes read on it; ``valid`` where every check holds and
    every code is decided, and every result written (the caller overwrites the others).
    The kernel returns how many variants are not valid.
    """
    import sympy as sp

    lay = form.layout
    n_el, n_b = lay.n_elements, lay.n_bodies
    speed = [f"o{2 + b}" for b in range(n_b)]
    torque = [f"o{2 + n_b + i}" for i in range(len(lay.loads))]
    body = inputs + expression_lines(form)
    body += [f"r{k} = {lay.signs[k]!r} * q{k}" for k in range(n_el)]
    body += [f"rel{k} = relative_speed({speed[a]}, {speed[b]}, {speed[c]})"
             for k, (a, b, c) in enumerate(lay.places)]
    checks = ["(o0 > o1)"] + [f"math.isfinite({t} * {speed[load.body]})"
                              for load, t in zip(lay.loads, torque)] + allowed
    at = 2 + n_b + len(lay.loads)
    forces: list[str] = []
    for p, (pattern, expected) in enumerate(form.checked):
        forces = [f"o{at + 2 + i}" for i in range(n_el + len(lay.unknown))]
        # u{p} sums every force's magnitude (times a stencil whose gear-a entry is 1):
        # finite only where every force is (an overflow only rejects the variant)
        checks += [f"(o{at} > o{at + 1})", f"math.isfinite(u{p})"]
        at += 2 + len(forces)
        factors = {k: _python(factor_of(code, sp.Symbol(f"e{k}")))
                   for k, code in zip(form.moving, pattern)}
        body += [f"f{p}_{k} = {factors.get(k, '1.0')}" for k in range(n_el)]
        loads = ([f"abs({t})" for t in torque] + [f"abs({f})" for f in forces[n_el:]]
                 + [f"element_load(r{k}, f{p}_{k}, {forces[k]})" for k in range(n_el)])
        body.append(f"u{p} = {SCALE_BOUND!r} * ({' + '.join(['0.0'] + loads)})")
        body += [f"d{p}_{k} = driver_codes({forces[k]}, rel{k}, u{p})" for k in range(n_el)]
        checks += [f"(d{p}_{k} == {code})" if code else
                   f"((rel{k} == 0.0) | ({forces[k]} == 0.0))"    # proves "nothing passes"
                   for k, code in zip(form.moving, expected)]
    last = len(form.checked) - 1
    checks += [f"((d{last}_{k} != 0) | (rel{k} == 0.0))"          # the reported codes decided
               for k in range(n_el) if k not in form.moving]
    body.append(f"good = {' & '.join(checks)}")
    body += ["valid[j] = good", "rejected += 0 if good else 1"]
    body += _write_lines(lay, form, speed, torque, forces, last)
    arguments = "".join(f"v{i}, " for i in range(n_swept))
    return (HEADER.format(digest=RULES_DIGEST, cache=cache, arguments=arguments)
            + "".join(" " * 8 + line + "\n" for line in body) + "    return rejected\n")


def _write_lines(lay: "Layout", form: "ClosedForm", speed: list, torque: list,
                 forces: list, last: int) -> list[str]:
    """The results of variant ``j`` on the last checked forces (``_outcome`` of
    evaluate.py)."""
    given = {load.body: t for load, t in zip(lay.loads, torque)}
    reaction = dict(zip(lay.unknown, forces[lay.n_elements:]))
    external = lambda b: given[b] if b in given else reaction[b]   # noqa: E731
    power = lambda bodies: " + ".join(["0.0"] + [f"{external(b)} * {speed[b]}"  # noqa: E731
                                                 for b in bodies])
    lines = [f"p_in = {power(lay.inputs)}", f"p_out = -({power(lay.outputs)})",
             "input_power[j] = p_in", "output_power[j] = p_out",
             "formal = p_out / p_in if p_in != 0.0 else np.nan",
             "self_locking[j] = formal <= 0.0",
             "efficiency[j] = flow_efficiency_point(p_in, p_out)"]
    if lay.ratio_bodies is None:
        lines.append("ratio[j] = np.nan")
    else:
        w_in, w_out = (speed[b] for b in lay.ratio_bodies)
        lines.append(f"ratio[j] = np.inf if {w_out} == 0.0 else {w_in} / {w_out}")
    total = ["0.0"]
    for k in range(lay.n_elements):
        if k in form.moving:
            lines.append(f"loss{k} = {forces[k]} * rel{k} * (f{last}_{k} - 1.0)")
            total.append(f"loss{k}")
        lines.append(f"losses[{k}, j] = {'loss' + str(k) if k in form.moving else '0.0'}")
    lines += [f"codes[{k}, j] = d{last}_{k}" for k in range(lay.n_elements)]
    return lines + [f"total_loss[j] = {' + '.join(total)}", "status[j] = 0",
                    f"passes[j] = {form.passes}"]


HEADER = '''"""A sweep kernel generated by powergraph.analyses.sweep.kernel (rules {digest})."""
import math

import numba
import numpy as np

from powergraph.analyses.sweep.kernel import (
    ALLOWED, jit_driver_codes as driver_codes, jit_element_load as element_load,
    jit_flow_efficiency_point as flow_efficiency_point,
    jit_port_value_allowed as port_value_allowed,
    jit_relative_speed as relative_speed)

efficiency_allowed, ratio_allowed, teeth_allowed = (
    ALLOWED["efficiency"], ALLOWED["ratio"], ALLOWED["teeth"])


@numba.njit(cache={cache}, error_model="numpy", nogil=True, parallel=True)
def kernel({arguments}valid, ratio, efficiency, input_power, output_power, total_loss,
           self_locking, status, passes, losses, codes):
    rejected = 0
    for j in numba.prange(valid.shape[0]):
'''


def cache_directory() -> Path | None:
    """Where kernels are kept between processes: ``$POWERGRAPH_CACHE_DIR`` (empty: none),
    else ``$XDG_CACHE_HOME/powergraph/kernels`` (``~/.cache`` without it); None when it
    cannot be created or written."""
    chosen = os.environ.get(CACHE_ENV)
    if chosen == "":
        return None
    if chosen is None:
        root = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
        chosen = str(Path(root) / "powergraph" / "kernels")
    path = Path(chosen)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return path if os.access(path, os.W_OK | os.X_OK) else None


def _load(source_of: Callable[[bool], str]) -> Callable:
    """The kernel function of the generated source: imported from the cache directory
    (numba's own cache beside it), or executed in memory when there is none; either way
    once per process (the module, or the function, is kept)."""
    directory = cache_directory()
    if directory is not None:
        source = source_of(True)
        name = "powergraph_kernel_" + hashlib.sha256(source.encode()).hexdigest()[:24]
        path = directory / f"{name}.py"
        try:
            if not path.exists():
                temporary = directory / f".{name}.{os.getpid()}.tmp"
                temporary.write_text(source, encoding="utf-8")
                os.replace(temporary, path)
            module = sys.modules.get(name)
            if module is None:
                spec = importlib.util.spec_from_file_location(name, path)
                module = importlib.util.module_from_spec(spec)
                spec.loader.exec_module(module)
                sys.modules[name] = module
            return module.kernel
        except (OSError, ImportError, SyntaxError):
            pass                              # fall back to memory
    source = source_of(False)
    key = hashlib.sha256(source.encode()).hexdigest()
    kernel = _IN_MEMORY.get(key)
    if kernel is None:                        # compiled once per process, like a file's
        namespace: dict[str, Any] = {}
        exec(compile(source, "<powergraph sweep kernel>", "exec"), namespace)
        kernel = _IN_MEMORY[key] = namespace["kernel"]
    return kernel


#: The kernels kept in memory (no cache directory), by the hash of their source.
_IN_MEMORY: dict[str, Callable] = {}


class Kernel:
    """The compiled kernel of one closed form of a :class:`CompiledSweep`.

    Calling it evaluates every variant: it writes results into ``outputs`` and returns
    ``valid``, where the form's pattern holds (the results elsewhere are to be
    overwritten), and how many variants are not valid. ``compile_s`` is the time its
    compiles (or loads from the cache) took.

    Parameters
    ----------
    form : ClosedForm
    inputs : callable
        ``inputs(scalar)``: :func:`input_lines` and :func:`allowed_checks` for these swept
        values given as scalars (a kernel is compiled per such mask: indexing a constant
        stride would keep the compiler from vectorising).
    """

    def __init__(self, form: "ClosedForm",
                 inputs: Callable[[tuple], tuple[list[str], list[str]]]) -> None:
        self.form, self._inputs = form, inputs
        self._functions: dict[tuple, Callable] = {}
        self.compile_s = 0.0

    def __call__(self, swept: Sequence[np.ndarray],
                 outputs: "Outputs") -> tuple[np.ndarray, int]:
        arguments = []
        for array in swept:
            array = np.asarray(array)
            if array.dtype not in PASSED_DTYPES:
                array = array.astype(np.float64)
            arguments.append(np.ascontiguousarray(array.reshape(-1)))
        scalar = tuple(np.ndim(a) == 0 for a in swept)
        function = self._functions.get(scalar)
        if function is None:                  # generate, compile on one variant, timed
            begin = time.perf_counter()
            lines, allowed = self._inputs(scalar)
            function = _load(lambda cache: kernel_source(self.form, len(scalar), lines,
                                                         allowed, cache))
            self._run(function, [a[:1] for a in arguments],
                      type(outputs).empty(1, self.form.layout.n_elements))
            self._functions[scalar] = function
            self.compile_s += time.perf_counter() - begin
        return self._run(function, arguments, outputs)

    @staticmethod
    def _run(function: Callable, arguments: list, out: "Outputs") -> tuple[np.ndarray, int]:
        valid = np.empty(out.status.size, dtype=bool)
        with _RUNNING:
            rejected = function(*arguments, valid, out.ratio, out.efficiency,
                                out.input_power, out.output_power, out.total_loss,
                                out.self_locking, out.status, out.passes, out.losses,
                                out.codes)
        return valid, int(rejected)
