"""The sweep's entry points: compile a model once (:func:`compile_sweep`), or compile and
evaluate in one call (:func:`sweep`), reusing the compiled form of the same model and PATHs
(:func:`compiled_for`)."""
from __future__ import annotations

from typing import Any, Mapping, Sequence

from powergraph.analyses.sweep.compile import CHUNK_SIZE, CompiledSweep
from powergraph.analyses.sweep.result import SweepResult
from powergraph.model.spec import Model


def compile_sweep(model: Model, paths: Sequence[str], backend: str = "auto",
                  mode: str | None = None) -> CompiledSweep:
    """Compile ``model`` once into an evaluator over arrays of the values at ``paths``.

    See :class:`CompiledSweep`.

    Examples
    --------
    >>> import numpy as np
    >>> from powergraph.model import load_model
    >>> evaluate = compile_sweep(load_model("models/rv40e_wang2021.yaml"),
    ...                          ["components.1.teeth", "links.*.efficiency"])
    >>> r = evaluate({"components.1.teeth": 12, "links.*.efficiency": [0.94, 0.99]})
    >>> np.round(r.ratio, 9).tolist(), np.round(r.efficiency, 6).tolist()
    ([121.0, 121.0], [0.287376, 0.714608])
    """
    return CompiledSweep(model, paths, backend, mode)


def sweep(model: Model, values: Mapping[str, Any], *, backend: str = "auto",
          chunk_size: int = CHUNK_SIZE, quiet: bool = False,
          mode: str | None = None) -> SweepResult:
    """Compile ``model`` for the PATHs of ``values`` and evaluate them (one call).

    Examples
    --------
    >>> import numpy as np
    >>> from powergraph.model import load_model
    >>> r = sweep(load_model("models/planetary_2kh_sun_to_carrier.yaml"),
    ...           {"components.ring.teeth": np.array([48, 72, 96])})
    >>> np.round(r.ratio, 12).tolist()
    [3.0, 4.0, 5.0]
    """
    return compiled_for(model, list(values), backend, mode)(values, chunk_size=chunk_size,
                                                             quiet=quiet)


#: Compiled sweeps kept per model (the last few PATH sets), so that calling
#: :func:`sweep` again on the same model and PATHs reuses its closed forms and kernels.
KEEP_COMPILED = 8


def compiled_for(model: Model, paths: Sequence[str], backend: str = "auto",
                 mode: str | None = None) -> CompiledSweep:
    """The :class:`CompiledSweep` of ``model`` for ``paths``, compiled on the first call
    and kept in the model's own store (``Model.derived``, which ``==`` ignores and a
    changed copy starts without) for the next ones.

    >>> from powergraph.model import load_model
    >>> rv = load_model("models/rv40e_wang2021.yaml")
    >>> compiled_for(rv, ["links.1.efficiency"]) is compiled_for(rv, ["links.1.efficiency"])
    True
    """
    kept = model.derived.setdefault("analyses.sweep.compiled", {})
    key = (tuple(paths), backend, mode)
    if key not in kept:
        if len(kept) >= KEEP_COMPILED:
            del kept[next(iter(kept))]
        kept[key] = CompiledSweep(model, paths, backend, mode)
    return kept[key]
