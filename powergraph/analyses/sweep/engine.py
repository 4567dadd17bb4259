"""One chunk of variants through the virtual-power solve, vectorised (DESIGN §3).

The single solver's procedure, on arrays: speeds, loads, forces with ``f = 1``, each
variant's power directions (driver codes), factors, forces again — re-solving only the
variants whose directions changed — until they repeat. A variant whose directions cycle
(the single solver's ``SolveError``), that does not settle in ``MAX_PASSES``, or whose
speeds or loads are not determined is flagged by its status code, and its efficiency,
forces and losses are NaN: never a silently wrong number.

Elements whose efficiency is 1 have ``f = 1`` whatever their direction, so only the others
("moving" elements) iterate: a change in the direction of an ideal element changes no
factor, hence no force, and the single solver settles one pass later on the same numbers.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, Sequence

import numpy as np

from powergraph.analyses.sweep.layout import Layout
from powergraph.statics.directions import MAX_PASSES

#: Status codes of a variant (``SweepResult.status``), by value.
STATUS = ("ok", "cycle", "unsettled", "speeds", "loads")
OK, CYCLE, UNSETTLED, SPEEDS, LOADS = range(5)
#: Power below this fraction of the given port power passes "nothing" (as the single solver).
DIRECTION_TOLERANCE = 1e-11


class Backend(Protocol):
    """Solves a train's two linear systems for arrays of variants (speeds, forces); each
    returns the values and a mask (or bool) of the variants where the system is regular
    (False where it is singular: speeds or loads not determined)."""

    name: str

    def speeds(self, ratios: Sequence, given: Sequence) -> tuple[list, np.ndarray]: ...

    def forces(self, gains: Sequence, torques: Sequence) -> tuple[list, np.ndarray]: ...


@dataclass
class Chunk:
    """The varying values of ``n`` variants, as floats or arrays of length ``n``.

    ``magnitudes`` are the backend's ratio arguments per element: Willis' ratio ``i``, or
    ``z_b/z_a`` for a mesh whose ratio follows from swept teeth (the backend knows the
    sign). ``efficiencies`` per element, ``speeds`` per given speed, ``loads`` per load.
    """

    n: int
    magnitudes: list
    efficiencies: list
    speeds: list
    loads: list


@dataclass
class Views:
    """Where one chunk's results go (slices of the full result arrays)."""

    ratio: np.ndarray
    efficiency: np.ndarray
    input_power: np.ndarray
    output_power: np.ndarray
    total_loss: np.ndarray
    losses: np.ndarray        # (elements, n)
    codes: np.ndarray         # (elements, n) int8: +1 gear a drives, -1 gear b, 0 nothing
    self_locking: np.ndarray
    status: np.ndarray        # int8
    passes: np.ndarray
    ideal: np.ndarray | None = None   # (elements, n) int8: codes read from the ideal forces


def solve_chunk(layout: Layout, backend: Backend, chunk: Chunk, out: Views) -> None:
    """Solve every variant of ``chunk`` into ``out``."""
    with np.errstate(all="ignore"):
        out.status[:] = OK
        speeds, regular = backend.speeds(chunk.magnitudes, chunk.speeds)
        _flag(out.status, regular, SPEEDS)
        torques, power = _given_torques(layout, speeds, chunk.loads)
        _flag(out.status, np.isfinite(power), LOADS)
        rel = [speeds[a] if c == layout.frame else speeds[a] - speeds[c]
               for a, c in zip(layout.body_a, layout.body_c)]
        state = _State(layout, chunk, torques, rel, DIRECTION_TOLERANCE * power)
        forces, regular = backend.forces(chunk.magnitudes, torques)      # f = 1
        _flag(out.status, regular, LOADS)
        codes, _, masks = state.directions(forces)
        if out.ideal is not None:
            out.ideal[:] = 0
            for k, code in zip(state.moving, codes):
                out.ideal[k] = code
        if np.any(out.status) or not _settle_fast(backend, state, codes, masks, out):
            index = np.flatnonzero(out.status == OK)
            _iterate(backend, state, index, [_take(c, index) for c in codes], out)
        _outcome(layout, state, speeds, out)


def _flag(status: np.ndarray, regular, code: int) -> None:
    """Set ``code`` where not ``regular`` and no earlier failure is recorded."""
    if np.ndim(regular) == 0:
        if not regular:
            status[status == OK] = code
    elif not regular.all():
        status[~regular & (status == OK)] = code


def _given_torques(layout: Layout, speeds: list, loads: list) -> tuple[list, np.ndarray]:
    """External torque of each loaded port (``P/w`` in, ``-P/w`` out) and the power scale
    (the largest given port power, as the single solver's direction tolerance)."""
    torques, scale = [], 1e-300
    for load, value in zip(layout.loads, loads):
        w = speeds[load.body]
        if load.kind == "torque":
            torque = value
        else:
            torque = value / w if load.role == "input" else -value / w
            if not np.all(w):   # a power on a still port: its torque is unknown
                torque = np.where(w == 0, np.nan, torque)
        torques.append(torque)
        scale = np.maximum(scale, np.abs(torque * w))
    return torques, scale


class _State:
    """The per-chunk arrays of the iteration, and their subsets."""

    def __init__(self, layout: Layout, chunk: Chunk, torques: list, rel: list,
                 tolerance) -> None:
        self.layout = layout
        self.n = chunk.n
        self.magnitudes = list(chunk.magnitudes)
        self.torques = torques
        self.rel = rel
        self.tolerance = tolerance
        self.negative_tolerance = -tolerance
        # elements whose factor depends on the direction (efficiency not identically 1)
        self.moving = [k for k, eta in enumerate(chunk.efficiencies)
                       if np.ndim(eta) or eta != 1.0]
        self.eta = [chunk.efficiencies[k] for k in self.moving]
        self.inverse = [1.0 / eta for eta in self.eta]
        self.forces: list = []      # final, per element
        self.factors: list = []     # final, per moving element
        self.products: list = []    # final λ (w_a - w_c), per moving element (or empty)
        self.codes: list = []       # final driver codes, per moving element (or empty)

    def directions(self, forces: list) -> tuple[list, list, list]:
        """Driver code of each moving element: +1 where gear a feeds power
        ``-λ (w_a - w_c)`` in, -1 where it takes it out, 0 where (almost) nothing passes;
        with ``λ (w_a - w_c)`` and the two masks."""
        codes, products, masks = [], [], []
        for k in self.moving:
            product = forces[k] * self.rel[k]
            a_drives = np.asarray(product < self.negative_tolerance)
            b_drives = np.asarray(product > self.tolerance)
            codes.append(a_drives.view(np.int8) - b_drives.view(np.int8))
            products.append(product)
            masks.append((a_drives, b_drives))
        return codes, products, masks

    def factors_from(self, masks: list) -> list:
        """``f = η`` where gear a drives, ``1/η`` where gear b drives, 1 where neither."""
        return [np.where(a_drives, eta, np.where(b_drives, inverse, 1.0))
                for (a_drives, b_drives), eta, inverse in zip(masks, self.eta, self.inverse)]

    def factors_of(self, codes: list) -> list:
        return self.factors_from([(c > 0, c < 0) for c in codes])

    def gains(self, factors: list) -> list:
        gains = list(self.magnitudes)
        for k, factor in zip(self.moving, factors):
            gains[k] = gains[k] * factor
        return gains

    def subset(self, keep: np.ndarray) -> "_State":
        """The same state restricted to the variants ``keep`` (indices or a mask)."""
        new = object.__new__(_State)
        new.__dict__.update(self.__dict__)
        for name in ("magnitudes", "torques", "rel", "eta", "inverse"):
            setattr(new, name, [_take(v, keep) for v in getattr(self, name)])
        new.tolerance = _take(self.tolerance, keep)
        new.negative_tolerance = _take(self.negative_tolerance, keep)
        new.n = int(np.count_nonzero(keep)) if keep.dtype == bool else keep.size
        return new


def _take(value, keep):
    return value if np.ndim(value) == 0 else value[keep]


def _settle_fast(backend: Backend, state: _State, codes: list, masks: list,
                 out: Views) -> bool:
    """Every variant valid: one pass with the ideal directions' factors; True when every
    variant's directions repeat (then the chunk is solved)."""
    factors = state.factors_from(masks)
    forces, regular = backend.forces(state.gains(factors), state.torques)
    following, products, _ = state.directions(forces)
    settled = np.all(regular)
    for old, new in zip(codes, following):
        settled = settled and bool(np.all(old == new))
    if settled:
        state.forces, state.factors = forces, factors
        state.products, state.codes = products, following
        out.passes[:] = 1
    return settled


def _iterate(backend: Backend, state: _State, index: np.ndarray, codes: list,
             out: Views) -> None:
    """General path: iterate the variants ``index`` (current driver ``codes``) until their
    directions repeat; re-solve only those still changing; flag cycles and failures."""
    n_el, n_moving = state.layout.n_elements, len(state.moving)
    final_forces = np.full((n_el, state.n), np.nan)
    final_factors = np.full((n_moving, state.n), np.nan)
    active, history = state.subset(index), []
    for passes in range(1, MAX_PASSES + 1):
        if index.size == 0:
            break
        factors = active.factors_of(codes)
        forces, regular = backend.forces(active.gains(factors), active.torques)
        following, _, _ = active.directions(forces)
        regular = np.broadcast_to(regular, index.size)
        settled = regular & _same(codes, following, index.size)
        cycling = regular & ~settled & _seen(following, history, index.size)
        where = index[settled]
        for k in range(n_el):
            final_forces[k, where] = _take(forces[k], settled)
        for j in range(n_moving):
            final_factors[j, where] = _take(factors[j], settled)
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


def _outcome(layout: Layout, state: _State, speeds: list, out: Views) -> None:
    """Ratio, powers, efficiency, losses and driver codes into ``out``."""
    all_ok = not np.any(out.status)
    external = _external_torques(layout, state)
    input_power = sum(external[b] * speeds[b] for b in layout.inputs)
    out.input_power[:] = input_power
    out.output_power[:] = sum(external[b] * speeds[b] for b in layout.outputs)
    np.negative(out.output_power, out=out.output_power)
    np.divide(out.output_power, out.input_power, out=out.efficiency)
    if not np.all(input_power):
        out.efficiency[out.input_power == 0] = np.nan
    _ratio(layout, speeds, out, all_ok)
    _losses_and_codes(layout, state, out)
    if not all_ok:
        bad = out.status != OK
        for array in (out.efficiency, out.input_power, out.output_power, out.total_loss):
            array[bad] = np.nan
        out.losses[:, bad] = np.nan
        out.codes[:, bad] = 0
        out.passes[bad] = 0
    np.less_equal(out.efficiency, 0.0, out=out.self_locking)


def _losses_and_codes(layout: Layout, state: _State, out: Views) -> None:
    """Loss ``-λ (w_a - w_c)(1 - f)`` and driver code of every element."""
    moving = {k: j for j, k in enumerate(state.moving)}
    out.total_loss[:] = 0.0
    for k in range(layout.n_elements):
        j = moving.get(k)
        if j is not None and state.codes:
            product = state.products[j]
            out.codes[k] = state.codes[j]
        else:
            product = state.forces[k] * state.rel[k]
            np.subtract(np.asarray(product < state.negative_tolerance).view(np.int8),
                        np.asarray(product > state.tolerance).view(np.int8), out=out.codes[k])
        if j is None:
            out.losses[k] = 0.0
            continue
        np.multiply(product, state.factors[j] - 1.0, out=out.losses[k])
        out.total_loss += out.losses[k]


def _ratio(layout: Layout, speeds: list, out: Views, all_ok: bool) -> None:
    if layout.ratio_bodies is None:
        out.ratio[:] = np.nan
        return
    w_in, w_out = (speeds[b] for b in layout.ratio_bodies)
    out.ratio[:] = w_in / w_out
    if not np.all(w_out):
        out.ratio[np.broadcast_to(w_out == 0, out.ratio.shape)] = np.inf
    if not all_ok:
        out.ratio[out.status == SPEEDS] = np.nan


def _external_torques(layout: Layout, state: _State) -> dict:
    """External torque of every port body: given, or from that body's balance."""
    given = {load.body: torque for load, torque in zip(layout.loads, state.torques)}
    factor = dict(zip(state.moving, state.factors))
    out = {}
    for body in set(layout.inputs + layout.outputs):
        if body in given:
            out[body] = given[body]
            continue
        total = 0.0
        for k in range(layout.n_elements):
            on_a, on_b, on_c = (layout.body_a[k] == body, layout.body_b[k] == body,
                                layout.body_c[k] == body)
            if not (on_a or on_b or on_c):
                continue
            gain = layout.signs[k] * state.magnitudes[k] * factor.get(k, 1.0)
            coef = (1.0 if on_a else 0.0) + (gain - 1.0 if on_c else 0.0) \
                - (gain if on_b else 0.0)
            total = total + coef * state.forces[k]
        out[body] = -total
    return out
