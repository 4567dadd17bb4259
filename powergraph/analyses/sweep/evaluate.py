"""One chunk of variants through the virtual-power solve, vectorised.

:func:`evaluate_chunk` gives each variant to the first compiled closed form whose direction
pattern provably holds for it (:class:`~powergraph.analyses.sweep.backends.ClosedForm`),
and the rest to :func:`solve_chunk`: the single solver's procedure on arrays — speeds,
loads, forces with ``f = 1``, each variant's power directions (driver codes), factors,
forces again, re-solving only the variants whose directions changed, until they repeat
(docs/theory.md). A variant whose directions cycle (the single solver's ``SolveError``),
that does not settle in ``MAX_PASSES``, or whose speeds or loads are not determined is
flagged by its status code, and its efficiency, forces and losses are NaN: never a
silently wrong number.

Elements whose efficiency is 1 have ``f = 1`` whatever their direction, so only the others
("moving" elements) iterate: a change in the direction of an ideal element changes no
factor, hence no force, and the single solver settles one pass later on the same numbers.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Sequence

import numpy as np

from powergraph.analyses.sweep.result import CYCLE, LOADS, OK, SPEEDS, UNSETTLED
from powergraph.statics.directions import MAX_PASSES, factors_for, read_codes, relative_speed
from powergraph.statics.equilibrium import port_torque
from powergraph.statics.ports import flow_efficiency_of_roles

if TYPE_CHECKING:  # pragma: no cover
    from powergraph.analyses.sweep.layout import Layout

#: A pattern is worth a closed form when the general path settled this many variants on it.
LEARN_AT_LEAST = 1024


@dataclass
class Chunk:
    """The varying values of ``n`` variants, as floats or arrays of length ``n``.

    ``magnitudes`` are the backend's ratio arguments per element: Willis' ratio ``i``, or
    ``z_b/z_a`` for a mesh whose ratio follows from swept teeth (the layout knows the
    sign). ``efficiencies`` per element, ``speeds`` per given speed, ``loads`` per load.
    """

    n: int
    magnitudes: list
    efficiencies: list
    speeds: list
    loads: list

    def take(self, index: np.ndarray) -> "Chunk":
        """The variants ``index`` of this chunk."""
        pick = lambda values: [v if np.ndim(v) == 0 else v[index] for v in values]  # noqa: E731
        return Chunk(int(index.size), pick(self.magnitudes), pick(self.efficiencies),
                     pick(self.speeds), pick(self.loads))


@dataclass
class Outputs:
    """Result arrays of a run, or views of a chunk of them."""

    ratio: np.ndarray
    efficiency: np.ndarray    # as SweepResult.efficiency (flow efficiency; 0 where locked)
    input_power: np.ndarray
    output_power: np.ndarray
    total_loss: np.ndarray
    self_locking: np.ndarray
    status: np.ndarray        # int8, an index into STATUS
    passes: np.ndarray        # int8
    losses: np.ndarray        # (elements, n)
    codes: np.ndarray         # (elements, n) int8: +1 gear a drives, -1 gear b, 0 nothing
    ideal: np.ndarray | None = None   # (elements, n) int8: codes read from the ideal forces

    ROWS = ("ratio", "efficiency", "input_power", "output_power", "total_loss",
            "self_locking", "status", "passes")
    DTYPES = {"self_locking": bool, "status": np.int8, "passes": np.int8}

    @classmethod
    def empty(cls, n: int, n_el: int) -> "Outputs":
        """Fresh arrays for ``n`` variants of a train with ``n_el`` elements, not
        initialised (zeroing them would cost a pass over memory: whoever evaluates a
        variant writes every result of it)."""
        return cls(**{name: np.empty(n, dtype=cls.DTYPES.get(name, float))
                      for name in cls.ROWS},
                   losses=np.empty((n_el, n)), codes=np.empty((n_el, n), dtype=np.int8))

    def part(self, start: int, stop: int) -> "Outputs":
        """Views of the variants ``start:stop``."""
        cut = slice(start, stop)
        return Outputs(**{name: getattr(self, name)[cut] for name in self.ROWS},
                       losses=self.losses[:, cut], codes=self.codes[:, cut])

    def put(self, where, source: "Outputs", pick) -> None:
        """``self[where] = source[pick]`` for every result array."""
        for name in self.ROWS:
            getattr(self, name)[where] = getattr(source, name)[pick]
        self.losses[:, where] = source.losses[:, pick]
        self.codes[:, where] = source.codes[:, pick]


def evaluate_chunk(layout: "Layout", backend, chunk: Chunk, out: Outputs,
                   closed_forms: Sequence, moving: Sequence[int] | None) -> tuple | None:
    """Solve ``chunk`` into ``out``: the closed forms in the order given (each counts the
    variants it took in ``hits``), the general iteration for the rest. Return the
    pattern ``(ideal codes, settled codes)`` of the ``moving`` elements that the general
    iteration settled most variants on, when worth a closed form (``moving`` None: never).
    """
    rest = None    # the variants no closed form took (None: all of them)
    with np.errstate(all="ignore"):
        for form in closed_forms:
            part = chunk if rest is None else chunk.take(rest)
            views = out if rest is None else Outputs.empty(part.n, layout.n_elements)
            valid = form.evaluate(part, views)
            if valid is False:
                continue
            if valid is True and rest is None:
                form.hits += chunk.n
                return None
            taken = np.ones(part.n, bool) if valid is True else valid
            form.hits += int(np.count_nonzero(taken))
            if rest is None:
                rest = np.flatnonzero(~taken)
            else:
                out.put(rest[taken], views, taken)
                rest = rest[~taken]
            if rest.size == 0:
                return None
    views = out if rest is None else Outputs.empty(rest.size, layout.n_elements)
    if moving is not None:
        views = dataclasses.replace(views, ideal=np.empty_like(views.codes))
    solve_chunk(layout, backend, chunk if rest is None else chunk.take(rest), views)
    if rest is not None:
        out.put(rest, views, slice(None))
    return None if moving is None else dominant_pattern(views, moving)


def dominant_pattern(out: Outputs, moving: Sequence[int]) -> tuple | None:
    """The most common ``(ideal codes, settled codes)`` of the moving elements among the
    solved variants, when at least :data:`LEARN_AT_LEAST` variants share it."""
    solved = out.status == OK
    if not moving or out.ideal is None or np.count_nonzero(solved) < LEARN_AT_LEAST:
        return None
    key = np.zeros(int(np.count_nonzero(solved)), dtype=np.int64)
    rows = [out.ideal[k] for k in moving] + [out.codes[k] for k in moving]
    for row in rows:
        key = key * 3 + (row[solved].astype(np.int64) + 1)
    values, counts = np.unique(key, return_counts=True)
    best = int(np.argmax(counts))
    if counts[best] < LEARN_AT_LEAST:
        return None
    code, digits = int(values[best]), []
    for _ in rows:
        code, digit = divmod(code, 3)
        digits.append(digit - 1)
    digits.reverse()
    return tuple(digits[:len(moving)]), tuple(digits[len(moving):])


def solve_chunk(layout: "Layout", backend, chunk: Chunk, out: Outputs) -> None:
    """Solve every variant of ``chunk`` into ``out`` by the general iteration."""
    with np.errstate(all="ignore"):
        out.status[:] = OK
        speeds, regular = backend.speeds(chunk.magnitudes, chunk.speeds)
        _flag(out.status, regular, SPEEDS)
        torques, power = _given_torques(layout, speeds, chunk.loads)
        _flag(out.status, np.isfinite(power), LOADS)
        state = _State(layout, backend, chunk, torques, relative_speeds(layout, speeds))
        ideal = [1.0] * len(state.moving)
        forces, regular = state.solve(ideal)
        _flag(out.status, regular, LOADS)
        codes = state.directions(forces, ideal)
        if out.ideal is not None:
            out.ideal[:] = 0
            for k, code in zip(state.moving, codes):
                out.ideal[k] = code
        if np.any(out.status) or not _settle_fast(state, codes, out):
            index = np.flatnonzero(out.status == OK)
            _iterate(state, index, [_take(c, index) for c in codes], out)
        _outcome(layout, state, speeds, out)


def write_settled(layout: "Layout", chunk: Chunk, torques: list, rel: list, speeds: list,
                  forces: list, factors: list, moving: Sequence[int], out: Outputs,
                  passes: int, codes: np.ndarray | None = None) -> None:
    """Every result of ``chunk`` into ``out``, its variants settled on these ``forces``
    (each element's, then the reactions) with these ``factors`` of the ``moving``
    elements (a closed form's answer, written like the general iteration's); ``codes``,
    when given, are every element's driver codes read from these forces."""
    state = _State(layout, None, chunk, torques, rel)
    state.moving = list(moving)
    state.eta = [chunk.efficiencies[k] for k in moving]
    state.forces, state.factors = list(forces), list(factors)
    state.final_codes = codes
    out.status[:] = OK
    out.passes[:] = passes
    _outcome(layout, state, speeds, out)


def _flag(status: np.ndarray, regular, code: int) -> None:
    """Set ``code`` where not ``regular`` and no earlier failure is recorded."""
    if np.ndim(regular) == 0:
        if not regular:
            status[status == OK] = code
    elif not regular.all():
        status[~regular & (status == OK)] = code


def relative_speeds(layout: "Layout", speeds: list) -> list:
    """``w_a - w_c`` of every element, zero by the single solver's rule
    (:func:`powergraph.statics.directions.relative_speed`)."""
    return [relative_speed(speeds[a], speeds[b], speeds[c])
            for a, b, c in zip(layout.body_a, layout.body_b, layout.body_c)]


def _given_torques(layout: "Layout", speeds: list, loads: list) -> tuple[list, np.ndarray]:
    """External torque of each loaded port
    (:func:`powergraph.statics.equilibrium.port_torque`) and the largest given port power
    (NaN where a torque is unknown)."""
    torques, scale = [], 1e-300
    for load, value in zip(layout.loads, loads):
        w = speeds[load.body]
        torque = port_torque(value, load.kind, load.role, w)
        if load.kind != "torque" and not np.all(w):   # a power on a still port: unknown
            torque = np.where(w == 0, np.nan, torque)
        torques.append(torque)
        scale = np.maximum(scale, np.abs(torque * w))
    return torques, scale


def _take(value, keep):
    return value if np.ndim(value) == 0 else value[keep]


class _State:
    """The per-chunk arrays of the iteration (or of a subset of its variants), and the
    final forces and factors of the moving elements."""

    def __init__(self, layout: "Layout", backend, chunk: Chunk, torques: list,
                 rel: list) -> None:
        self.layout, self.backend = layout, backend
        self.magnitudes, self.torques, self.rel = list(chunk.magnitudes), torques, rel
        # elements whose factor depends on the direction (efficiency not identically 1)
        self.moving = [k for k, eta in enumerate(chunk.efficiencies)
                       if np.ndim(eta) or eta != 1.0]
        self.eta = [chunk.efficiencies[k] for k in self.moving]
        self.inverse = [1.0 / eta for eta in self.eta]
        self.forces: list = []      # final, per element, then the reactions
        self.factors: list = []     # final, per moving element
        self.final_codes = None     # every element's codes from the final forces, if known

    def solve(self, factors: list) -> tuple[list, np.ndarray]:
        """Forces and reactions with these factors of the moving elements."""
        every = [1.0] * self.layout.n_elements
        for k, factor in zip(self.moving, factors):
            every[k] = factor
        return self.backend.forces(self.magnitudes, every, self.torques)

    def directions(self, forces: list, factors: list) -> list:
        """Driver code of each moving element, for the forces of these factors."""
        codes = self.all_codes(forces, factors)
        return [codes[k] for k in self.moving]

    def all_codes(self, forces: list, factors: list) -> np.ndarray:
        """``(E, n)`` driver codes of every element by the single solver's rule
        (:func:`~powergraph.statics.directions.read_codes`: own scales)."""
        return element_codes(self.layout, self.magnitudes, self.torques, self.rel, forces,
                             dict(zip(self.moving, factors)))

    def factors_of(self, codes: list) -> list:
        """``f = η`` where gear a drives, ``1/η`` where gear b drives, 1 where neither."""
        return [factors_for(c, eta) for c, eta in zip(codes, self.eta)]

    def subset(self, keep: np.ndarray) -> "_State":
        """The same state restricted to the variants ``keep`` (indices or a mask)."""
        new = object.__new__(_State)
        new.__dict__.update(self.__dict__)
        for name in ("magnitudes", "torques", "rel", "eta", "inverse"):
            setattr(new, name, [_take(v, keep) for v in getattr(self, name)])
        return new


def element_codes(layout: "Layout", magnitudes: list, torques: list, rel: list,
                  forces: list, factors: dict) -> np.ndarray:
    """``(E, n)`` driver codes of every element of ``n`` variants (``(E,)`` when every
    value is a scalar): the single solver's rule on arrays
    (:func:`~powergraph.statics.directions.read_codes`).

    ``forces`` lists each element's force then the reaction of each body of
    ``layout.unknown``; ``factors`` maps element -> factor (1 for the others).
    """
    n_el = layout.n_elements
    values = [*forces, *rel, *torques, *magnitudes, *factors.values()]
    size = max([getattr(v, "size", 1) for v in values] + [1])

    def rows(items) -> np.ndarray:
        out = np.empty((len(items), size))
        for k, item in enumerate(items):
            out[k] = item
        return out

    lam = rows(forces[:n_el])
    factor = rows([factors.get(k, 1.0) for k in range(n_el)])
    ratios = rows([layout.signs[k] * magnitudes[k] for k in range(n_el)])
    load = np.zeros((layout.n_bodies, size))
    for spec, torque in zip(layout.loads, torques):
        load[spec.body] += np.abs(torque)
    for body, reaction in zip(layout.unknown, forces[n_el:]):
        load[body] += np.abs(reaction)
    codes = read_codes(np.array(layout.places, dtype=np.int64), ratios, lam, factor,
                       rows(rel), load, layout.frame)
    scalar = not any(np.ndim(v) for v in values)
    return codes[:, 0] if scalar else codes


def _settle_fast(state: _State, codes: list, out: Outputs) -> bool:
    """Every variant valid: one pass with the ideal directions' factors; True when every
    variant's directions repeat (then the chunk is solved)."""
    factors = state.factors_of(codes)
    forces, regular = state.solve(factors)
    following = state.directions(forces, factors)
    settled = bool(np.all(regular)) and all(bool(np.all((new == 0) | (old == new)))
                                            for old, new in zip(codes, following))
    if settled:
        state.forces, state.factors = forces, factors
        out.passes[:] = 1
    return settled


def _iterate(state: _State, index: np.ndarray, codes: list, out: Outputs) -> None:
    """General path: iterate the variants ``index`` (current driver ``codes``) until their
    directions repeat; re-solve only those still changing; flag cycles and failures."""
    n = out.status.size
    final_forces = np.full((state.layout.n_elements + len(state.layout.unknown), n), np.nan)
    final_factors = np.full((len(state.moving), n), np.nan)
    active, history = state.subset(index), []
    for passes in range(1, MAX_PASSES + 1):
        if index.size == 0:
            break
        factors = active.factors_of(codes)
        forces, regular = active.solve(factors)
        following = active.directions(forces, factors)
        regular = np.broadcast_to(regular, index.size)
        settled = regular & _agreeing(codes, following, index.size)
        cycling = regular & ~settled & _seen(following, history, index.size)
        where = index[settled]
        for k, force in enumerate(forces):
            final_forces[k, where] = _take(force, settled)
        for j, factor in enumerate(factors):
            final_factors[j, where] = _take(factor, settled)
        out.passes[where] = passes
        out.status[index[cycling]] = CYCLE
        out.status[index[~regular]] = LOADS
        keep = ~(settled | cycling | ~regular)
        history = [[_take(c, keep) for c in h] for h in history + [codes]]
        index, active = index[keep], active.subset(keep)
        codes = [_take(c, keep) for c in following]
    else:
        out.status[index] = UNSETTLED
    state.forces, state.factors = list(final_forces), list(final_factors)


def _agreeing(codes: list, following: list, size: int) -> np.ndarray:
    """Variants whose new directions agree with the assumed ones (an element found passing
    nothing agrees with any driver: :func:`powergraph.statics.directions.agrees`)."""
    agree = np.ones(size, dtype=bool)
    for old, new in zip(codes, following):
        agree &= np.broadcast_to((new == 0) | (old == new), size)
    return agree


def _same(codes: list, following: list, size: int) -> np.ndarray:
    same = np.ones(size, dtype=bool)
    for old, new in zip(codes, following):
        same &= np.broadcast_to(old == new, size)
    return same


def _seen(following: list, history: list[list], size: int) -> np.ndarray:
    """Variants whose new directions are ones they had before the current ones (a cycle)."""
    seen = np.zeros(size, dtype=bool)
    for earlier in history:
        seen |= _same(earlier, following, size)
    return seen


def _outcome(layout: "Layout", state: _State, speeds: list, out: Outputs) -> None:
    """Ratio, powers, efficiency, losses and driver codes into ``out``."""
    all_ok = not np.any(out.status)
    given = {load.body: torque for load, torque in zip(layout.loads, state.torques)}
    reaction = dict(zip(layout.unknown, state.forces[layout.n_elements:]))
    external = {b: given[b] if b in given else reaction[b]
                for b in set(layout.inputs + layout.outputs)}
    input_power = sum(external[b] * speeds[b] for b in layout.inputs)
    out.input_power[:] = input_power
    out.output_power[:] = sum(external[b] * speeds[b] for b in layout.outputs)
    np.negative(out.output_power, out=out.output_power)
    formal = out.output_power / out.input_power
    if not np.all(input_power):
        formal[out.input_power == 0] = np.nan
    _ratio(layout, speeds, out, all_ok)
    _losses_and_codes(layout, state, out)
    if not all_ok:
        bad = out.status != OK
        for array in (formal, out.input_power, out.output_power, out.total_loss):
            array[bad] = np.nan
        out.losses[:, bad] = np.nan
        out.codes[:, bad] = 0
        out.passes[bad] = 0
    np.less_equal(formal, 0.0, out=out.self_locking)
    out.efficiency[:] = flow_efficiency_of_roles(out.input_power, out.output_power)


def _losses_and_codes(layout: "Layout", state: _State, out: Outputs) -> None:
    """Loss ``λ (w_a - w_c)(f - 1)`` and driver code of every element (the codes read
    from the final forces, as the single solver reports them)."""
    moving = {k: j for j, k in enumerate(state.moving)}
    out.total_loss[:] = 0.0
    out.codes[:] = (state.all_codes(state.forces, state.factors)
                    if state.final_codes is None else state.final_codes)
    for k in range(layout.n_elements):
        j = moving.get(k)
        if j is None:
            out.losses[k] = 0.0
            continue
        np.multiply(state.forces[k] * state.rel[k], state.factors[j] - 1.0,
                    out=out.losses[k])
        out.total_loss += out.losses[k]


def _ratio(layout: "Layout", speeds: list, out: Outputs, all_ok: bool) -> None:
    if layout.ratio_bodies is None:
        out.ratio[:] = np.nan
        return
    w_in, w_out = (speeds[b] for b in layout.ratio_bodies)
    out.ratio[:] = w_in / w_out
    if not np.all(w_out):
        out.ratio[np.broadcast_to(w_out == 0, out.ratio.shape)] = np.inf
    if not all_ok:
        out.ratio[out.status == SPEEDS] = np.nan
