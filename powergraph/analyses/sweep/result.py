"""The result of a sweep: frozen arrays over the variants, with CSV and dict views."""
from __future__ import annotations

import io
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np

from powergraph.analyses.sweep.paths import shaped_views
from powergraph.format import csv_header
from powergraph.display import HTML_ROWS, Displayed, dataframe, html_table
from powergraph.records import record

#: Status codes of a variant (``SweepResult.status``), by value.
STATUS = ("ok", "cycle", "unsettled", "speeds", "loads", "locked", "no-freewheel-state")
OK, CYCLE, UNSETTLED, SPEEDS, LOADS, LOCKED, NO_FREEWHEEL_STATE = range(7)
#: Columns after the PATHs in the CSV; ``extra=True`` adds the rest.
CSV_COLUMNS = ("ratio", "efficiency")
EXTRA_COLUMNS = ("input_power", "output_power", "total_loss", "self_locking", "converged",
                 "status", "formal_efficiency")
#: Unit of each CSV column in its header (``efficiency [-]``); flags and statuses have none.
COLUMN_UNITS = {"ratio": "-", "efficiency": "-", "input_power": "W", "output_power": "W",
                "total_loss": "W", "teeth": "-", "speed": "rad/s", "power": "W",
                "torque": "N*m", "formal_efficiency": "-"}


@record(repr=False)
class SweepResult(Displayed):
    """Ratio, efficiency, losses and flags of every variant of a sweep.

    Every array has the broadcast shape of the swept values (``shape``).

    Attributes
    ----------
    name : str
        The model's name.
    parameters : Mapping[str, ndarray]
        The swept values, by PATH, in the order given.
    ratio : ndarray
        Input speed / output speed (NaN without one input and one output, or where the
        speeds are not determined).
    efficiency : ndarray
        Power leaving at the ports / power entering at the ports, by the virtual-power
        method, as ``solve`` reports it (:attr:`PowerFlowResult.efficiency`): 0 where the
        train self-locks, below 1 when it runs back-driven; NaN where not converged or no
        power passes. Read from the declared input and output powers, so with several
        ports of one role it assumes they all pass power the same way.
    input_power, output_power, total_loss : ndarray
        W.
    losses : Mapping[int, ndarray]
        Loss of each mesh and coupling, W, by link index.
    drivers : Mapping[int, ndarray]
        Who drives each element in its carrier's frame: +1 gear a, -1 gear b, 0 nothing.
    self_locking : ndarray of bool
        ``formal_efficiency <= 0``: the input cannot drive the output (False where not
        converged).
    converged : ndarray of bool
        The variant was solved (``ok`` or ``locked``): its directions are decided and its
        speeds and loads are determined. Where False, ``status`` says why and the powers are NaN.
    status : ndarray of int8
        Index into :data:`~powergraph.analyses.sweep.STATUS`: ``ok``, ``locked`` (the
        single solver's locking verdict: the train stays at rest, efficiency 0),
        ``cycle`` and ``unsettled`` (only where even the single solver's complementarity
        search finds no answer), ``speeds`` (Willis rows singular), ``loads`` (loads not
        determined), ``no-freewheel-state`` (a mode's freewheels have no consistent
        state at this variant, or several).
    passes : ndarray
        Passes of the direction iteration.
    backend : str
        ``symbolic`` (compiled closed forms) or ``numeric`` (batched linear solves).
    """

    name: str
    parameters: Mapping[str, np.ndarray]
    ratio: np.ndarray
    efficiency: np.ndarray
    input_power: np.ndarray
    output_power: np.ndarray
    total_loss: np.ndarray
    losses: Mapping[int, np.ndarray]
    drivers: Mapping[int, np.ndarray]
    self_locking: np.ndarray
    converged: np.ndarray
    status: np.ndarray
    passes: np.ndarray
    backend: str

    def _summary(self) -> str:
        return self.text_report()

    def _records(self) -> list[dict[str, Any]]:
        """The first rows, for the HTML table (all of them: :meth:`to_dataframe`)."""
        columns = self.columns(extra=True)
        return [{k: v[i].item() for k, v in columns.items()}
                for i in range(min(self.size, HTML_ROWS + 1))]

    def _repr_html_(self) -> str:
        return html_table(self._records(), f"SweepResult: {self._summary()}"
                          + (f" (first {HTML_ROWS} shown)" if self.size > HTML_ROWS else ""))

    def to_dataframe(self) -> Any:
        """One row per variant: each PATH, ratio, efficiency, powers and losses (W), flags
        and status (pandas is optional)."""
        columns = self.columns(extra=True)
        columns["status"] = np.array([STATUS[s] for s in columns["status"].tolist()])
        return dataframe(columns)


    @classmethod
    def of(cls, name: str, arrays: Mapping[str, np.ndarray], shape: tuple[int, ...],
           outputs: Any, links: tuple[int, ...], backend: str,
           converged: np.ndarray | None = None) -> "SweepResult":
        """The result of a run from its swept ``arrays`` and its flat ``outputs``
        (:class:`~powergraph.analyses.sweep.evaluate.Outputs`, whose ``efficiency`` is
        already the flow efficiency reported here), shaped to ``shape``; ``converged``
        is :func:`converged_of` the outputs' status, computed here when not given."""
        shaped = lambda a: a.reshape(shape)  # noqa: E731
        by_link = lambda rows: MappingProxyType(  # noqa: E731
            {link: shaped(rows[k]) for k, link in enumerate(links)})
        return cls(name=name, parameters=shaped_views(arrays, shape),
                   ratio=shaped(outputs.ratio),
                   efficiency=shaped(outputs.efficiency),   # flow efficiency, 0 if locked
                   input_power=shaped(outputs.input_power),
                   output_power=shaped(outputs.output_power),
                   total_loss=shaped(outputs.total_loss), losses=by_link(outputs.losses),
                   drivers=by_link(outputs.codes), self_locking=shaped(outputs.self_locking),
                   converged=shaped(converged_of(outputs.status)
                                    if converged is None else converged),
                   status=shaped(outputs.status),
                   passes=shaped(outputs.passes), backend=backend)

    @property
    def formal_efficiency(self) -> np.ndarray:
        """Output power / input power by the declared roles (``PowerFlowResult.
        formal_efficiency``): negative where the train self-locks, the papers' figure."""
        with np.errstate(divide="ignore", invalid="ignore"):
            formal = np.where(self.input_power != 0, self.output_power / self.input_power,
                              np.nan)
        return np.where(self.status == LOCKED, 0.0, formal)

    @property
    def shape(self) -> tuple[int, ...]:
        return self.efficiency.shape

    @property
    def size(self) -> int:
        return int(self.efficiency.size)

    def __len__(self) -> int:
        return self.size

    @property
    def paths(self) -> tuple[str, ...]:
        return tuple(self.parameters)

    def status_counts(self) -> dict[str, int]:
        """How many variants have each status (only the statuses that occur)."""
        counts = np.bincount(self.status.ravel(), minlength=len(STATUS))
        return {name: int(c) for name, c in zip(STATUS, counts) if c}

    def curves(self, x: str | None = None) -> tuple[str, dict[str, np.ndarray]]:
        """Group the variants into curves over one PATH, for plotting.

        Parameters
        ----------
        x : str, optional
            The PATH along the curves (default: the first swept PATH).

        Returns
        -------
        (x, {label: flat indices sorted by x})
            One curve per combination of the other PATHs' values; the label names them
            (``""`` when ``x`` is the only PATH).

        Examples
        --------
        >>> from powergraph.model import load_model
        >>> from powergraph.analyses.sweep import sweep
        >>> r = sweep(load_model("models/rv40e_wang2021.yaml"), {"links.0.efficiency": [[0.9], [1.0]],
        ...                                            "links.1.efficiency": [0.99, 1.0]})
        >>> path, curves = r.curves()
        >>> path, sorted(curves)
        ('links.0.efficiency', ['links.1.efficiency = 0.99', 'links.1.efficiency = 1'])
        """
        x = self.paths[0] if x is None else x
        if x not in self.parameters:
            from powergraph.errors import UsageError

            raise UsageError(f"{x!r} is not a swept PATH ({', '.join(self.paths)})")
        others = [p for p in self.paths if p != x]
        xs = np.ravel(self.parameters[x])
        if not others:
            return x, {"": np.argsort(xs, kind="stable")}
        keys = np.stack([np.ravel(self.parameters[p]) for p in others], axis=1)
        unique, inverse = np.unique(keys, axis=0, return_inverse=True)
        curves = {}
        for g, values in enumerate(unique):
            members = np.flatnonzero(np.ravel(inverse) == g)
            label = ", ".join(f"{p} = {v:g}" for p, v in zip(others, values))
            curves[label] = members[np.argsort(xs[members], kind="stable")]
        return x, curves

    def columns(self, extra: bool = False) -> dict[str, np.ndarray]:
        """Flat columns: each PATH, then ratio and efficiency (and more with ``extra``)."""
        out = {path: np.ravel(values) for path, values in self.parameters.items()}
        names = CSV_COLUMNS + (EXTRA_COLUMNS if extra else ())
        for name in names:
            out[name] = np.ravel(getattr(self, name))
        if extra:
            for link, loss in self.losses.items():
                out[f"loss_link_{link}"] = np.ravel(loss)
        return out

    def to_csv(self, path: Any = None, extra: bool = False) -> str | None:
        """Write the CSV (PATHs, ``ratio``, ``efficiency``; ``extra`` adds powers, losses
        and flags) to ``path`` (a file name or an open text file); return it when None.

        Each header carries its unit (``links.1.efficiency [-]``, ``ports.0.speed
        [rad/s]``, ``output_power [W]``); NaN is written as ``nan``; ``status`` as its name.
        """
        columns = self.columns(extra)
        if path is None:
            buffer = io.StringIO()
            _write_csv(buffer, columns)
            return buffer.getvalue()
        if hasattr(path, "write"):
            _write_csv(path, columns)
            return None
        with open(path, "w", newline="", encoding="utf-8") as handle:
            _write_csv(handle, columns)
        return None

    def text_report(self) -> str:
        """One line: variants, self-locking (of which locked at rest) and unsolved counts."""
        counts = self.status_counts()
        unsolved = {k: v for k, v in counts.items() if k not in ("ok", "locked")}
        text = (f"{self.name}: {self.size:,} variants, "
                f"{int(self.self_locking.sum()):,} self-locking")
        if counts.get("locked"):
            text += f" ({counts['locked']:,} locked at rest)"
        if unsolved:
            text += ", not solved: " + ", ".join(f"{v:,} {k}" for k, v in unsolved.items())
        return text

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Efficiency (%) against the first swept path, one curve per value of the others
        (delegates, lazily, to :func:`powergraph.plot.sweep.curve_plot`)."""
        from powergraph.plot.sweep import curve_plot

        x_path, curves = self.curves()
        x, eta = self.parameters[x_path].ravel(), 100 * self.efficiency.ravel()
        kwargs.setdefault("xlabel", x_path)
        kwargs.setdefault("title", f"{self.name}: sweep by the virtual-power method")
        kwargs.setdefault("zero_line", "self-locking below 0")
        return curve_plot({label: (x[i], eta[i]) for label, i in curves.items()},
                          ylabel="efficiency [%]", ax=ax, **kwargs)

    def to_dict(self) -> dict[str, Any]:
        """Plain lists (JSON-ready except NaN): parameters, results, flags, losses."""
        flat = lambda a: np.ravel(a).tolist()  # noqa: E731
        return {"name": self.name, "backend": self.backend, "shape": list(self.shape),
                "parameters": {p: flat(v) for p, v in self.parameters.items()},
                "ratio": flat(self.ratio), "efficiency": flat(self.efficiency),
                "formal_efficiency": flat(self.formal_efficiency),
                "input_power": flat(self.input_power), "output_power": flat(self.output_power),
                "total_loss": flat(self.total_loss),
                "losses": {str(k): flat(v) for k, v in self.losses.items()},
                "drivers": {str(k): flat(v) for k, v in self.drivers.items()},
                "self_locking": flat(self.self_locking), "converged": flat(self.converged),
                "status": [STATUS[s] for s in np.ravel(self.status)],
                "passes": flat(self.passes)}


#: Rows formatted at once when writing CSV (bounds the memory of the text).
CSV_BLOCK = 1 << 16


def _write_csv(handle, columns: Mapping[str, np.ndarray]) -> None:
    """Header, then the rows, formatted and written block by block."""
    names = list(columns)
    handle.write(",".join(_quoted(csv_header(name, column_unit(name))) for name in names)
                 + "\n")
    size = len(next(iter(columns.values()))) if columns else 0
    for start in range(0, size, CSV_BLOCK):
        cells = [_cells(name, columns[name][start:start + CSV_BLOCK]) for name in names]
        handle.write("\n".join(map(",".join, zip(*cells))) + "\n")


def column_unit(name: str) -> str | None:
    """The SI unit of a CSV column (a PATH's by its last part; ``-`` for a pure number).

    >>> column_unit("ports.0.speed"), column_unit("links[1].efficiency"), column_unit("status")
    ('rad/s', '-', None)
    """
    if name.startswith("loss_link_"):
        return "W"
    field = name.replace("]", "").replace("[", ".").rsplit(".", 1)[-1]
    return COLUMN_UNITS.get(field)


def _quoted(name: str) -> str:
    if any(c in name for c in ',"\n'):
        return '"' + name.replace('"', '""') + '"'
    return name


def _cells(name: str, values: np.ndarray) -> list[str]:
    """Text of one column: floats as ``repr`` (round-trip exact, ``nan``), teeth as
    integers, flags as ``true``/``false``, statuses by name."""
    if name == "status":
        return [STATUS[s] for s in values.tolist()]
    if values.dtype == bool:
        return ["true" if v else "false" for v in values.tolist()]
    if name.replace("]", "").endswith(".teeth"):
        return list(map(str, values.astype(np.int64).tolist()))
    return list(map(repr, values.astype(float).tolist()))


def converged_of(status: np.ndarray) -> np.ndarray:
    """Where a variant has an answer (``ok`` or ``locked``): one pass and one new array
    when nothing locked (a run's usual case), for a million variants or more."""
    converged = status == OK
    if status.size and status.max() >= LOCKED:
        converged |= status == LOCKED
    return converged
