"""Numba kernels of the closed forms: a whole run of one direction pattern in one loop.

A :class:`~powergraph.analyses.sweep.backends.ClosedForm` evaluated with numpy makes a
pass over memory per operation (and the direction rule a dozen more per checked force
system). Its kernel does, per variant, in blocks of variants whose loops the compiler
vectorises, run on every core by threads (the kernel releases the GIL; numba's ``prange``
doubled the compile time), what :meth:`ClosedForm.evaluate` does: read the swept values, form the ratio
magnitudes from the teeth, compute the form's sympy expressions (common subexpressions
eliminated, printed as Python), check the pattern — the speed system regular, the given
torques' powers finite, then for each checked force system: regular, its forces finite,
and the driver codes read by the single solver's rule equal the expected ones — and, for
the variants it holds for, write every result of
:class:`~powergraph.analyses.sweep.evaluate.Outputs` and a ``valid`` flag. The others are
left to the numpy path, which gives them exactly today's answer.

The rules are not written again here: the direction rule, the zero relative speed, the
element's stencil and the flow efficiency are the plain-Python per-point forms of
:mod:`powergraph.statics.directions`, :mod:`powergraph.kinematics.elements` and
:mod:`powergraph.statics.ports`, compiled by numba as they are.

The generated source is written to a cache directory under a name that hashes it (and
the sources of those rules and numba's version), imported from there and compiled with
``cache=True``, so another process loads the machine code instead of compiling again
(:func:`cache_directory`; in memory when no directory is writable).
"""
from __future__ import annotations

import hashlib
import importlib.util
import os
import re
import sys
import time
import types
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numba
import numpy as np

from powergraph.kinematics import elements as _elements
from powergraph.statics import directions as _directions
from powergraph.statics import ports as _ports
from powergraph.statics.directions import FORCE_NOISE, SPEED_NOISE, factor_of  # noqa: F401

if TYPE_CHECKING:  # pragma: no cover
    from powergraph.analyses.sweep.backends import ClosedForm
    from powergraph.analyses.sweep.layout import Layout
    from powergraph.analyses.sweep.evaluate import Outputs

#: Variants per block: the loops over a block's variants are what the compiler vectorises,
#: and its scratch arrays stay in the cache.
BLOCK = 256
#: Threads that run a kernel's blocks (the cores this process may use).
THREADS = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else \
    (os.cpu_count() or 1)
#: A thread gets at least this many blocks (fewer variants run on the calling thread).
MIN_BLOCKS_PER_THREAD = 16
#: Environment variable naming the kernel cache directory ("" keeps kernels in memory).
CACHE_ENV = "POWERGRAPH_CACHE_DIR"
#: Array dtypes passed to a kernel as they are (others are converted to float64).
PASSED_DTYPES = (np.dtype(np.float64), np.dtype(np.int64))


def _jit(function: Callable) -> Callable:
    """``numba.njit`` of a plain-Python rule, resolving its globals in this module: the
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
nan_max = jit_nan_max = _jit(_directions.nan_max)
driver_code = jit_driver_code = _jit(_directions.driver_code)
element_stencil = jit_element_stencil = _jit(_elements.element_stencil)
jit_relative_speed_point = _jit(_directions.relative_speed_point)
jit_read_codes_loops = _jit(_directions.read_codes_loops)
jit_flow_efficiency_point = _jit(_ports.flow_efficiency_point)


def _rules_digest() -> str:
    """Hash of what a cached kernel compiled in: the rule modules, this generator and
    numba's version (a change to any gives new kernel files)."""
    digest = hashlib.sha256(numba.__version__.encode())
    for module in (_elements, _directions, _ports, sys.modules[__name__]):
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


def kernel_source(form: "ClosedForm", n_swept: int, inputs: list[str],
                  cache: bool) -> str:
    """The Python source of the kernel of ``form`` (``inputs``: :func:`input_lines`).

    Each block of variants goes through three steps, each vectorised by the compiler:
    a loop over its variants computing the inputs, the expressions, the checks that need
    no direction and, per checked force system, the forces, factors and loads; the rule
    reading the driver codes of each checked system on the whole block; a loop comparing
    them with the expected ones and writing the results. Every result is written;
    ``valid`` tells where the pattern holds (the caller overwrites the others).
    """
    import sympy as sp

    lay = form.layout
    n_el, n_b = lay.n_elements, lay.n_bodies
    speed = [f"o{2 + b}" for b in range(n_b)]
    torque = [f"o{2 + n_b + i}" for i in range(len(lay.loads))]
    first = inputs + expression_lines(form)
    first += [f"ratios[{k}, i] = {lay.signs[k]!r} * q{k}" for k in range(n_el)]
    first += [f"rel[{k}, i] = relative_speed_point({speed[a]}, {speed[b]}, {speed[c]})"
              for k, (a, b, c) in enumerate(lay.places)]
    checks = ["o0 > o1"] + [f"math.isfinite({t} * {speed[load.body]})"
                            for load, t in zip(lay.loads, torque)]
    rules, same = [], []
    at = 2 + n_b + len(lay.loads)
    forces: list[str] = []
    for p, (pattern, expected) in enumerate(form.checked):
        forces = [f"o{at + 2 + i}" for i in range(n_el + len(lay.unknown))]
        checks += [f"o{at} > o{at + 1}"] + [f"math.isfinite({f})" for f in forces]
        at += 2 + len(forces)
        first += [f"lam[{p}, {k}, i] = {forces[k]}" for k in range(n_el)]
        first += [f"fac[{p}, {k}, i] = {_python(factor_of(code, sp.Symbol(f'e{k}')))}"
                  for k, code in zip(form.moving, pattern)]     # the others stay 1
        for body in range(n_b):
            terms = [f"abs({t})" for load, t in zip(lay.loads, torque) if load.body == body]
            terms += [f"abs({forces[n_el + j]})" for j, b in enumerate(lay.unknown)
                      if b == body]
            first.append(f"load[{p}, {body}, i] = {' + '.join(['0.0'] + terms)}")
        rules.append(f"read_codes_loops(bodies, ratios, lam[{p}], fac[{p}], rel, load[{p}], "
                     f"{lay.frame}, read[{p}])")
        same += [f"(read[{p}, {k}, i] == {code})" for k, code in zip(form.moving, expected)]
    first.append(f"ok[i] = {' and '.join(f'({c})' for c in checks)}")
    last = len(form.checked) - 1
    stored = lambda name: re.sub(r"\bo(\d+)\b", r"o[\1, i]", name)  # noqa: E731
    write = _write_lines(lay, form, [stored(x) for x in speed], [stored(x) for x in torque],
                         [stored(x) for x in forces], last)
    needed = sorted({int(x) for x in re.findall(r"o\[(\d+), i\]", "\n".join(write))})
    first += [f"o[{i}, i] = o{i}" for i in needed]
    write = [f"valid[j] = {' and '.join(['ok[i]'] + same)}"] + write
    return _assemble(form, n_swept, len(form.expressions), [first, *rules, write], cache)


def _assemble(form: "ClosedForm", n_swept: int, n_out: int, loops: list,
              cache: bool) -> str:
    """The module text: the header, then each loop over the block's variants (a list of
    lines) or call (a string) in the block's body."""
    lay = form.layout
    text = HEADER.format(digest=RULES_DIGEST, cache=cache, block=BLOCK,
                         arguments="".join(f"v{i}, " for i in range(n_swept)),
                         n_el=lay.n_elements, n_b=lay.n_bodies, n_out=n_out,
                         n_checked=len(form.checked))
    pad = " " * 8
    for loop in loops:
        if isinstance(loop, str):
            text += pad + loop + "\n"
            continue
        text += pad + "for i in range(m):\n" + pad + "    j = start + i\n"
        text += "".join(pad + "    " + line + "\n" for line in loop)
    return text


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
    lines.append("total = 0.0")
    for k in range(lay.n_elements):
        if k in form.moving:
            lines += [f"loss = lam[{last}, {k}, i] * rel[{k}, i] * (fac[{last}, {k}, i] - 1.0)",
                      f"losses[{k}, j] = loss", "total = total + loss"]
        else:
            lines.append(f"losses[{k}, j] = 0.0")
    lines += [f"codes[{k}, j] = read[{last}, {k}, i]" for k in range(lay.n_elements)]
    return lines + ["total_loss[j] = total", "status[j] = 0", f"passes[j] = {form.passes}"]


HEADER = '''"""A sweep kernel generated by powergraph.analyses.sweep.kernel (rules {digest})."""
import math

import numba
import numpy as np

from powergraph.analyses.sweep.kernel import (
    jit_flow_efficiency_point as flow_efficiency_point,
    jit_read_codes_loops as read_codes_loops,
    jit_relative_speed_point as relative_speed_point)


@numba.njit(cache={cache}, error_model="numpy", nogil=True)
def kernel(first, last, {arguments}bodies, valid, ratio, efficiency, input_power,
           output_power, total_loss, self_locking, status, passes, losses, codes):
    n = valid.shape[0]
    o = np.zeros(({n_out}, {block}))
    ratios = np.ones(({n_el}, {block}))
    rel = np.zeros(({n_el}, {block}))
    lam = np.zeros(({n_checked}, {n_el}, {block}))
    fac = np.ones(({n_checked}, {n_el}, {block}))
    load = np.zeros(({n_checked}, {n_b}, {block}))
    read = np.zeros(({n_checked}, {n_el}, {block}), dtype=np.int8)
    ok = np.zeros({block}, dtype=np.bool_)
    for block in range(first, last):
        start = block * {block}
        m = min({block}, n - start)
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
    (numba's own cache beside it), or executed in memory when there is none."""
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
    namespace: dict[str, Any] = {}
    exec(compile(source_of(False), "<powergraph sweep kernel>", "exec"), namespace)
    return namespace["kernel"]


class Kernel:
    """The compiled kernel of one closed form of a :class:`CompiledSweep`.

    Calling it evaluates every variant: it writes results into ``outputs`` and returns
    ``valid``, where the form's pattern holds (the results elsewhere are to be
    overwritten). ``compile_s`` is the time its compiles (or loads from the cache) took.

    Parameters
    ----------
    form : ClosedForm
    inputs : callable
        ``inputs(scalar)``: :func:`input_lines` for these swept values given as scalars
        (a kernel is compiled per such mask: indexing a constant stride would keep the
        compiler from vectorising).
    """

    def __init__(self, form: "ClosedForm", inputs: Callable[[tuple], list[str]]) -> None:
        self.form, self._inputs = form, inputs
        self._functions: dict[tuple, Callable] = {}
        self._bodies = np.array(form.layout.places, dtype=np.int64).reshape(-1, 3)
        self.compile_s = 0.0

    def __call__(self, swept: Sequence[np.ndarray], outputs: "Outputs") -> np.ndarray:
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
            lines = self._inputs(scalar)
            function = _load(lambda cache: kernel_source(self.form, len(scalar), lines, cache))
            self._run(function, [a[:1] for a in arguments],
                      type(outputs).empty(1, self.form.layout.n_elements))
            self._functions[scalar] = function
            self.compile_s += time.perf_counter() - begin
        return self._run(function, arguments, outputs)

    def _run(self, function: Callable, arguments: list, out: "Outputs") -> np.ndarray:
        """Run the blocks of variants on every core (the kernel releases the GIL)."""
        n = out.status.size
        valid = np.empty(n, dtype=bool)
        blocks = -(-n // BLOCK)
        rest = [self._bodies, valid, out.ratio, out.efficiency, out.input_power,
                out.output_power, out.total_loss, out.self_locking, out.status, out.passes,
                out.losses, out.codes]
        workers = min(THREADS, blocks // MIN_BLOCKS_PER_THREAD)
        if workers <= 1:
            function(0, blocks, *arguments, *rest)
            return valid
        cuts = [blocks * t // workers for t in range(workers + 1)]
        list(_pool().map(lambda t: function(cuts[t], cuts[t + 1], *arguments, *rest),
                         range(workers)))
        return valid


_POOL: list = []


def _pool() -> ThreadPoolExecutor:
    """The threads that run the kernels' blocks (made on first use)."""
    if not _POOL:
        _POOL.append(ThreadPoolExecutor(THREADS, thread_name_prefix="powergraph-kernel"))
    return _POOL[0]
