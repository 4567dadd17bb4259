"""Every consistent set of power directions: the mesh friction law as a complementarity
problem (docs/locking.md).

Each lossy element either passes power from gear a (factor ``η``, gear a's carrier-frame
power ``-λ (w_a - w_c) >= 0``), or from gear b (``1/η``, that power ``<= 0``); an element
whose relative speed is zero sticks, with any factor in ``[η, 1/η]``. Writing the
element's force as a sum of nonnegative amounts along its allowed "rays" (one per driver;
two per sign for a sticking element) makes the torque balance linear; the friction law is
then the complementarity of the two groups of rays (one of them is zero).

Two searches find the solutions:

- **exhaustive** (:func:`enumerate_patterns`): every driver pattern of up to
  ``EXHAUSTIVE_LIMIT`` moving lossy elements, all torque balances solved in one batch;
- **branch and bound** (:func:`branch_and_bound`) for larger trains, trains with sticking
  lossy elements or statically indeterminate load sharing: linear programs
  (``scipy.optimize.linprog``) over the rays, branching on an element whose two groups
  are both used, the least total loss first.

Candidates are confirmed by the caller with the project's own torque balance.
"""
from __future__ import annotations

import itertools

import numpy as np

from powergraph.kinematics import Element
from powergraph.kinematics.system import TrainSystem, system_of
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.directions import factors_for
from powergraph.statics.equilibrium import Loads

#: Trains with at most this many moving lossy elements are searched exhaustively.
EXHAUSTIVE_LIMIT = 12
#: Linear programs the branch and bound may solve before it gives up.
MAX_LPS = 4000


@record
class Statics:
    """The torque balance in a form the searches share: body rows, load columns."""

    elements: tuple[Element, ...]
    rel: np.ndarray
    row: dict[str, int]
    rhs: np.ndarray            # minus the given external torques, normalised to max 1
    top: float                 # the normalising torque (N·m)
    ideal: frozenset[int]      # elements treated as lossless (ideal or asked so)
    system: TrainSystem        # where the elements' and unknown torques' columns go

    @property
    def n_unknown(self) -> int:
        """Unknown external torques (ports, frame reaction)."""
        return len(self.system.unknown)

    @property
    def unknown_rows(self) -> tuple[int, ...]:
        return tuple(self.system.unknown.tolist())

    @property
    def lossy(self) -> tuple[int, ...]:
        """Moving elements with losses: the ones with a driver to choose."""
        return tuple(k for k, e in enumerate(self.elements)
                     if k not in self.ideal and e.efficiency < 1.0 and self.rel[k] != 0.0)

    @property
    def sticking(self) -> tuple[int, ...]:
        """Lossy elements at zero relative speed: factor anywhere in ``[η, 1/η]``."""
        return tuple(k for k, e in enumerate(self.elements)
                     if k not in self.ideal and e.efficiency < 1.0 and self.rel[k] == 0.0)

    def column(self, k: int, factor) -> np.ndarray:
        """Torques of element ``k`` on every body per unit force (any factor shape)."""
        return self.system.element_column(k, self.elements[k].ratio, factor)


def statics_of(model: Model, elements: tuple[Element, ...], loads: Loads, rel: np.ndarray,
               ideal: frozenset[int] = frozenset()) -> Statics:
    """Collect the torque balance of ``model`` for the searches."""
    row = {body.id: r for r, body in enumerate(model.bodies)}
    rhs = np.zeros(len(row))
    for body, torque in loads.given.items():
        rhs[row[body]] -= torque
    top = float(np.max(np.abs(rhs))) or 1.0
    return Statics(elements=elements, rel=rel, row=row, rhs=rhs / top, top=top, ideal=ideal,
                   system=system_of(list(row), elements, loads.unknown))


def enumerate_patterns(st: Statics) -> list[tuple[int, ...]] | None:
    """Driver codes (+1/-1 for each of ``st.lossy``) of every pattern whose torque balance
    passes power the assumed way, screened loosely (the caller confirms each).

    None when the torque balance is not square and regular (indeterminate sharing) or
    there are sticking lossy elements: then :func:`branch_and_bound` decides.
    """
    lossy = st.lossy
    n_el, n_b = len(st.elements), len(st.row)
    if st.sticking or n_el + st.n_unknown != n_b:
        return None
    codes = np.array(list(itertools.product((1, -1), repeat=len(lossy))), dtype=float)
    codes = codes.reshape(len(codes), len(lossy))
    factors = np.ones((n_el, len(codes)))
    for k in lossy:
        factors[k] = factors_for(codes[:, lossy.index(k)], st.elements[k].efficiency)
    matrix = st.system.balance([[e.ratio] for e in st.elements], factors)
    try:
        solution = np.linalg.solve(matrix, np.broadcast_to(st.rhs, (len(codes), n_b))[..., None])
    except np.linalg.LinAlgError:
        return None
    forces = solution[:, :n_el, 0]
    if not np.all(np.isfinite(forces)):
        return None
    lossy_forces = forces[:, list(lossy)]
    power = -lossy_forces * st.rel[list(lossy)]
    slack = 1e-8 * np.abs(lossy_forces * st.rel[list(lossy)]).max(axis=1, initial=0.0)
    ok = np.all(codes * power >= -slack[:, None], axis=1)
    return [tuple(int(c) for c in codes[i]) for i in np.flatnonzero(ok)]


@record
class LPSolution:
    """A complementary solution of the rays' linear program."""

    codes: dict[int, int]        # driver code per lossy moving element
    factors: dict[int, float]    # factor per sticking element
    loss: float                  # in units of the normalised loads


def branch_and_bound(st: Statics, first: bool = False) -> tuple[list[LPSolution], bool]:
    """Least-loss complementary solutions by branch and bound over linear programs.

    Returns the solutions met (the least-loss one first) and whether the search finished
    (False when it stopped at ``MAX_LPS`` linear programs). With ``first`` it stops at
    the first solution (an existence test).
    """
    from scipy.optimize import linprog

    cols, cost, owner = _rays(st)
    n_b, n_rays = len(st.row), len(cols)
    a_eq = np.zeros((n_b, n_rays + st.n_unknown))
    a_eq[:, :n_rays] = np.array(cols).T if cols else np.zeros((n_b, 0))
    for j, r in enumerate(st.unknown_rows):
        a_eq[r, n_rays + j] = 1.0
    c = np.concatenate([cost, np.zeros(st.n_unknown)])
    free = [(None, None) if owner[i][1] == 0 else (0.0, None) for i in range(n_rays)]
    groups = {k for k, g in owner if g != 0}
    found: list[LPSolution] = []
    stack: list[dict[int, int]] = [{}]
    best, lps = np.inf, 0
    while stack:
        if lps >= MAX_LPS:
            return sorted(found, key=lambda s: s.loss), False
        fixed = stack.pop()
        bounds = free + [(None, None)] * st.n_unknown
        for i, (k, g) in enumerate(owner):
            if k in fixed and g != 0 and g != fixed[k]:
                bounds[i] = (0.0, 0.0)
        lps += 1
        res = linprog(c, A_eq=a_eq, b_eq=st.rhs, bounds=bounds, method="highs")
        if res.status != 0 or res.fun >= best * (1 + 1e-9) + 1e-12:
            continue
        x = res.x
        size = {(k, g): 0.0 for k in groups for g in (1, -1)}
        for i, (k, g) in enumerate(owner):
            if g != 0:
                size[k, g] += abs(x[i])
        both = [(min(size[k, 1], size[k, -1]), k) for k in groups if k not in fixed
                and min(size[k, 1], size[k, -1]) > 1e-9 * max(size[k, 1], size[k, -1], 1e-3)]
        if not both:
            found.append(_solution(st, x, owner, size, float(res.fun)))
            if first:
                return found, True
            best = min(best, float(res.fun))
            continue
        _, k = max(both)
        stack.append({**fixed, k: -1})
        stack.append({**fixed, k: 1})
    return sorted(found, key=lambda s: s.loss), True


def _rays(st: Statics) -> tuple[list[np.ndarray], list[float], list[tuple[int, int]]]:
    """Columns, loss per unit and (element, group) of every ray; group 0 is a free force."""
    cols: list[np.ndarray] = []
    cost: list[float] = []
    owner: list[tuple[int, int]] = []
    lossy, sticking = set(st.lossy), set(st.sticking)
    for k, e in enumerate(st.elements):
        eta = e.efficiency
        if k in lossy:
            s, r = -np.sign(st.rel[k]), abs(st.rel[k])
            cols += [s * st.column(k, eta), -s * st.column(k, 1.0 / eta)]
            cost += [r * (1.0 - eta), r * (1.0 / eta - 1.0)]
            owner += [(k, 1), (k, -1)]
        elif k in sticking:
            for sign in (1, -1):
                cols += [sign * st.column(k, eta), sign * st.column(k, 1.0 / eta)]
                cost += [0.0, 0.0]
                owner += [(k, sign), (k, sign)]
        else:
            cols.append(st.column(k, 1.0))
            cost.append(0.0)
            owner.append((k, 0))
    return cols, cost, owner


def _solution(st: Statics, x: np.ndarray, owner: list[tuple[int, int]],
              size: dict[tuple[int, int], float], loss: float) -> LPSolution:
    codes: dict[int, int] = {}
    for k in st.lossy:
        plus, minus = size[k, 1], size[k, -1]
        codes[k] = 1 if plus >= minus else -1  # no force: either driver
    factors: dict[int, float] = {}
    for k in st.sticking:
        eta = st.elements[k].efficiency
        i = [j for j, (kk, _) in enumerate(owner) if kk == k]  # +η, +1/η, -η, -1/η
        force = x[i[0]] + x[i[1]] - x[i[2]] - x[i[3]]
        scaled = eta * x[i[0]] + x[i[1]] / eta - eta * x[i[2]] - x[i[3]] / eta
        f = scaled / force if abs(force) > 1e-12 else 1.0
        factors[k] = float(min(max(f, eta), 1.0 / eta))
    return LPSolution(codes=codes, factors=factors, loss=loss)
