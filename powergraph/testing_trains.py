"""Random valid gear trains from stage templates — for tests, benchmarks and users.

A train is a chain of stages joined shaft to shaft (``fixed`` links): fixed-axis pairs,
2K-H planetaries in their six arrangements, double- and stepped-planet 2K-H, K-H-V
(cycloid) stages, RV reducers, Wolfrom drives, Ravigneaux sets and closed differentials,
each usable either way round. A 2-DOF train puts a free 2K-H differential in the chain
with a third port of its own. Every stage knows its ratio in closed form, so the train's
ratio (1 DOF) or output speed (2 DOF) is known without a solve. Efficiencies are drawn
from 0.90–1.0; the load sits on the input, on the output, or the train is back-driven.

Examples
--------
>>> from powergraph.testing_trains import random_train
>>> train = random_train(7)
>>> train.model.name.startswith("random train 7")
True
>>> import powergraph as pg
>>> r = pg.solve(train.model)
>>> train.ratio is None or abs(r.ratio / train.ratio - 1) < 1e-9
True
"""
from __future__ import annotations

import random
from dataclasses import dataclass, field
from typing import Any, Callable

from powergraph.kinematics import backdriven
from powergraph.model import model_from_dict
from powergraph.model.spec import Model
from powergraph.records import record

FRAME = "0"


@dataclass
class Stage:
    """One stage: its components and links (ids prefixed), the shafts it joins, its ratio
    (speed of ``inp`` / speed of ``out``) and a name."""

    name: str
    components: dict[str, dict]
    links: list[dict]
    inp: str
    out: str
    ratio: float

    def reversed(self) -> "Stage":
        return Stage(self.name + " (reversed)", self.components, self.links, self.out,
                     self.inp, 1.0 / self.ratio)


@record
class Train:
    """A generated train: its model data and model, the stages, and what is known in
    closed form (``ratio`` for 1 DOF; ``speeds`` of the ports' components)."""

    seed: Any
    data: dict
    model: Model
    stages: tuple[str, ...]
    ratio: float | None
    speeds: dict[str, float] = field(default_factory=dict)
    dof: int = 1
    backdriven: bool = False


def _mesh(a: str, b: str, carrier: str | None, eta: float) -> dict:
    link = {"type": "mesh", "between": [a, b], "efficiency": eta}
    if carrier is not None:
        link["carrier"] = carrier
    return link


def _fixed(a: str, b: str) -> dict:
    return {"type": "fixed", "between": [a, b]}


def _pair(rng: random.Random, p: str, eta: Callable[[], float]) -> Stage:
    z1, z2 = rng.randint(12, 40), rng.randint(12, 80)
    comps = {f"{p}g1": {"teeth": z1}, f"{p}g2": {"teeth": z2}}
    return Stage("fixed-axis pair", comps, [_mesh(f"{p}g1", f"{p}g2", None, eta())],
                 f"{p}g1", f"{p}g2", -z2 / z1)


def _planetary(rng: random.Random, p: str, eta: Callable[[], float]) -> Stage:
    zs, zp = rng.randint(12, 40), rng.randint(12, 40)
    zr, k = zs + 2 * zp, (zs + 2 * zp) / zs
    comps = {f"{p}s": {"teeth": zs}, f"{p}p": {"teeth": zp, "count": 3},
             f"{p}r": {"teeth": zr, "internal": True}, f"{p}c": {}}
    links = [_mesh(f"{p}s", f"{p}p", f"{p}c", eta()), _mesh(f"{p}p", f"{p}r", f"{p}c", eta())]
    held, inp, out, ratio = rng.choice([("r", "s", "c", 1 + k), ("s", "r", "c", (1 + k) / k),
                                        ("c", "s", "r", -k)])
    links.append(_fixed(f"{p}{held}", FRAME))
    return Stage(f"2K-H {inp}->{out}, {held} held", comps, links, f"{p}{inp}", f"{p}{out}",
                 ratio)


def _double_planet(rng: random.Random, p: str, eta: Callable[[], float]) -> Stage:
    zs, za, zb = rng.randint(20, 40), rng.randint(12, 20), rng.randint(12, 20)
    zr = zs + 2 * za + 2 * zb + rng.choice([0, 2, 4])
    comps = {f"{p}s": {"teeth": zs}, f"{p}a": {"teeth": za, "count": 3},
             f"{p}b": {"teeth": zb, "count": 3}, f"{p}r": {"teeth": zr, "internal": True},
             f"{p}c": {}}
    links = [_mesh(f"{p}s", f"{p}a", f"{p}c", eta()), _mesh(f"{p}a", f"{p}b", f"{p}c", eta()),
             _mesh(f"{p}b", f"{p}r", f"{p}c", eta()), _fixed(f"{p}r", FRAME)]
    return Stage("double-planet 2K-H", comps, links, f"{p}s", f"{p}c", 1 - zr / zs)


def _stepped(rng: random.Random, p: str, eta: Callable[[], float]) -> Stage:
    zs, z1, z2 = rng.randint(14, 30), rng.randint(20, 40), rng.randint(12, 24)
    zr = zs + z1 + z2
    comps = {f"{p}s": {"teeth": zs}, f"{p}p1": {"teeth": z1}, f"{p}p2": {"teeth": z2},
             f"{p}r": {"teeth": zr, "internal": True}, f"{p}c": {}}
    links = [_mesh(f"{p}s", f"{p}p1", f"{p}c", eta()), _mesh(f"{p}p2", f"{p}r", f"{p}c", eta()),
             _fixed(f"{p}p1", f"{p}p2"), _fixed(f"{p}r", FRAME)]
    return Stage("stepped-planet 2K-H", comps, links, f"{p}s", f"{p}c",
                 1 + (z1 / zs) * (zr / z2))


def _khv(rng: random.Random, p: str, eta: Callable[[], float]) -> Stage:
    n = rng.randint(9, 59)
    comps = {f"{p}H": {}, f"{p}d": {"teeth": n}, f"{p}pins": {"teeth": n + 1, "internal": True},
             f"{p}o": {}}
    links = [_mesh(f"{p}d", f"{p}pins", f"{p}H", eta()), _fixed(f"{p}pins", FRAME),
             {"type": "coupling", "between": [f"{p}d", f"{p}o"]}]
    return Stage(f"K-H-V N={n}", comps, links, f"{p}H", f"{p}o", -float(n))


def _rv(rng: random.Random, p: str, eta: Callable[[], float]) -> Stage:
    z1, z2, n = rng.randint(10, 20), rng.randint(20, 50), rng.randint(19, 49)
    comps = {f"{p}1": {"teeth": z1}, f"{p}2": {"teeth": z2, "count": 2}, f"{p}3": {},
             f"{p}4": {"teeth": n}, f"{p}5": {"teeth": n + 1, "internal": True},
             f"{p}6": {}}
    links = [_mesh(f"{p}1", f"{p}2", f"{p}6", eta()), _mesh(f"{p}4", f"{p}5", f"{p}3", eta()),
             _fixed(f"{p}2", f"{p}3"), _fixed(f"{p}5", FRAME),
             {"type": "coupling", "between": [f"{p}4", f"{p}6"]}]
    return Stage("RV", comps, links, f"{p}1", f"{p}6", 1 + (z2 / z1) * (n + 1))


def _wolfrom(rng: random.Random, p: str, eta: Callable[[], float]) -> Stage:
    while True:
        zs, z1, z2 = rng.randint(12, 24), rng.randint(20, 36), rng.randint(18, 36)
        r1 = zs + 2 * z1
        r2 = r1 - z1 + z2
        w2 = 1 - (r1 * z2) / (z1 * r2)
        if abs(w2) > 0.02:
            break
    comps = {f"{p}s": {"teeth": zs}, f"{p}p1": {"teeth": z1}, f"{p}p2": {"teeth": z2},
             f"{p}r1": {"teeth": r1, "internal": True}, f"{p}r2": {"teeth": r2, "internal": True},
             f"{p}c": {}}
    links = [_mesh(f"{p}s", f"{p}p1", f"{p}c", eta()), _mesh(f"{p}p1", f"{p}r1", f"{p}c", eta()),
             _mesh(f"{p}p2", f"{p}r2", f"{p}c", eta()), _fixed(f"{p}p1", f"{p}p2"),
             _fixed(f"{p}r1", FRAME)]
    return Stage("Wolfrom", comps, links, f"{p}s", f"{p}r2", (1 + r1 / zs) / w2)


def _ravigneaux(rng: random.Random, p: str, eta: Callable[[], float]) -> Stage:
    s1, s2, zp = rng.randint(20, 32), rng.randint(30, 40), rng.randint(14, 20)
    r = s2 + 2 * zp
    comps = {f"{p}s1": {"teeth": s1}, f"{p}s2": {"teeth": s2}, f"{p}p1": {"teeth": zp},
             f"{p}p2": {"teeth": zp}, f"{p}r": {"teeth": r, "internal": True}, f"{p}c": {}}
    links = [_mesh(f"{p}s1", f"{p}p1", f"{p}c", eta()), _mesh(f"{p}p1", f"{p}p2", f"{p}c", eta()),
             _mesh(f"{p}s2", f"{p}p2", f"{p}c", eta()), _mesh(f"{p}p2", f"{p}r", f"{p}c", eta())]
    gear, held, inp, ratio = rng.choice([
        ("first", "c", "s1", r / s1), ("second", "s2", "s1", r * (s1 + s2) / (s1 * (s2 + r))),
        ("reverse", "c", "s2", -r / s2)])
    links.append(_fixed(f"{p}{held}", FRAME))
    return Stage(f"Ravigneaux {gear}", comps, links, f"{p}{inp}", f"{p}r", ratio)


def _closed_differential(rng: random.Random, p: str, eta: Callable[[], float]) -> Stage:
    while True:
        zs, zp, g1, g2 = (rng.randint(18, 30), rng.randint(18, 30), rng.randint(20, 40),
                          rng.randint(40, 80))
        k = (zs + 2 * zp) / zs
        if abs(1 - k * g1 / g2) > 0.05:
            break
    comps = {f"{p}s": {"teeth": zs}, f"{p}p": {"teeth": zp, "count": 3},
             f"{p}r": {"teeth": zs + 2 * zp, "internal": True}, f"{p}c": {},
             f"{p}g1": {"teeth": g1}, f"{p}g2": {"teeth": g2}}
    links = [_mesh(f"{p}s", f"{p}p", f"{p}c", eta()), _mesh(f"{p}p", f"{p}r", f"{p}c", eta()),
             _mesh(f"{p}g1", f"{p}g2", None, eta()), _fixed(f"{p}s", f"{p}g1"),
             _fixed(f"{p}r", f"{p}g2")]
    # w_r = -(g1/g2) w_s and w_c = (w_s + k w_r)/(1 + k)
    return Stage("closed differential", comps, links, f"{p}s", f"{p}c",
                 (1 + k) / (1 - k * g1 / g2))


#: The 1-DOF stage templates, by name.
TEMPLATES: dict[str, Callable[[random.Random, str, Callable[[], float]], Stage]] = {
    "pair": _pair, "2K-H": _planetary, "double planet": _double_planet,
    "stepped planet": _stepped, "K-H-V": _khv, "RV": _rv, "Wolfrom": _wolfrom,
    "Ravigneaux": _ravigneaux, "closed differential": _closed_differential,
}


def _differential(rng: random.Random, p: str, eta: Callable[[], float]
                  ) -> tuple[Stage, str, Callable[[float, float], float]]:
    """A free 2K-H: (stage joining two of sun/ring/carrier, the third member, and the
    out-member speed as a function of the in-member and third-member speeds)."""
    zs, zp = rng.randint(12, 40), rng.randint(12, 40)
    k = (zs + 2 * zp) / zs
    comps = {f"{p}s": {"teeth": zs}, f"{p}p": {"teeth": zp, "count": 3},
             f"{p}r": {"teeth": zs + 2 * zp, "internal": True}, f"{p}c": {}}
    links = [_mesh(f"{p}s", f"{p}p", f"{p}c", eta()), _mesh(f"{p}p", f"{p}r", f"{p}c", eta())]
    inp, out, third = rng.sample(["s", "r", "c"], 3)

    def out_speed(w_in: float, w_third: float) -> float:
        # w_s + k w_r - (1 + k) w_c = 0 solved for the out member
        coef = {"s": 1.0, "r": k, "c": -(1.0 + k)}
        return -(coef[inp] * w_in + coef[third] * w_third) / coef[out]

    stage = Stage("2K-H differential", comps, links, f"{p}{inp}", f"{p}{out}", float("nan"))
    return stage, f"{p}{third}", out_speed


def _chain(rng: random.Random, count: int, start: int, eta: Callable[[], float],
           names: list[str]) -> list[Stage]:
    stages = []
    for j in range(count):
        name = rng.choice(names)
        stage = TEMPLATES[name](rng, f"s{start + j}", eta)
        stages.append(stage.reversed() if rng.random() < 0.3 else stage)
    return stages


def gear_chain_text(n: int, efficiency: float | None = None,
                    input_port: str = "speed: 10, power: 100") -> str:
    """A model file of ``n`` gears on fixed axes in a row: gear ``i`` (``20 + i % 7``
    teeth) meshes gear ``i + 1`` on the frame, gear 1 is the input (its port's fields
    ``input_port``), gear ``n`` the output; every mesh of ``efficiency`` (None: the
    format's default). The long and the threshold chains of the tests and benchmarks:
    the ratio is ``(-1)^(n-1) z_n/z_1`` and the efficiency ``η^(n-1)``.

    >>> import powergraph as pg
    >>> from powergraph.model import loads_model
    >>> round(pg.solve(loads_model(gear_chain_text(4, 0.5))).efficiency, 12)
    0.125
    """
    mesh = "" if efficiency is None else f", efficiency: {efficiency!r}"
    port = f", {input_port}" if input_port else ""
    lines = ["name: chain", "components:", "  0: {role: frame}"]
    lines += [f"  {i}: {{teeth: {20 + i % 7}}}" for i in range(1, n + 1)]
    lines += ["links:"] + [f"  - {{type: mesh, between: [{i}, {i + 1}]{mesh}}}"
                           for i in range(1, n)]
    lines += ["ports:", f"  - {{component: 1, role: input{port}}}",
              f"  - {{component: {n}, role: output}}"]
    return "\n".join(lines) + "\n"


#: The PATHs :func:`rv_variants` sweeps in models/rv40e_wang2021.yaml.
RV_PATHS = ("components.1.teeth", "components.2.teeth", "components.4.teeth",
            "components.5.teeth", "links.0.efficiency", "links.1.efficiency")


def rv_variants(n: int, seed: int = 0) -> dict:
    """``n`` random RV-40E variants by PATH (:data:`RV_PATHS`): z1 in 10…20, z2 =
    round(z1·U(2, 4)), z4 in 25…60, z5 = z4 + 1 (teeth as integers), η1 and η2 in
    U(0.90, 1.0) — the sweep benchmark's and the kernel tests' design space.

    >>> v = rv_variants(3)
    >>> bool((v["components.5.teeth"] == v["components.4.teeth"] + 1).all())
    True
    """
    import numpy as np

    rng = np.random.default_rng(seed)
    z1 = rng.integers(10, 21, n)
    z2 = np.round(z1 * rng.uniform(2.0, 4.0, n)).astype(np.int64)
    z4 = rng.integers(25, 61, n)
    return dict(zip(RV_PATHS, (z1, z2, z4, z4 + 1, rng.uniform(0.90, 1.0, n),
                               rng.uniform(0.90, 1.0, n))))


def random_train(seed: Any, stages: tuple[int, int] = (1, 3), dof: int | None = None,
                 drive: str | None = None, eta: tuple[float, float] = (0.90, 1.0),
                 templates: list[str] | None = None) -> Train:
    """A random valid train (same ``seed``, same train).

    Parameters
    ----------
    seed
        Seed of the random generator (any hashable).
    stages : (min, max)
        Number of 1-DOF stages in the chain.
    dof : 1 or 2, optional
        Degrees of freedom (random when None; 2 inserts a free differential).
    drive : "forward", "load on output" or "back-driven", optional
        Where the load is given (1 DOF); random when None.
    eta : (low, high)
        Range of the mesh efficiencies.
    templates : list of str, optional
        Names from :data:`TEMPLATES` to draw from (all by default).
    """
    rng = random.Random(str(seed))
    names = templates or list(TEMPLATES)
    dof = dof or rng.choice([1, 1, 1, 2])

    def draw_eta() -> float:
        return round(rng.uniform(*eta), 6)

    chain = _chain(rng, rng.randint(*stages), 0, draw_eta, names)
    w_in = round(rng.uniform(10.0, 300.0), 3)
    power = round(rng.uniform(10.0, 5000.0), 3)
    data: dict = {"name": f"random train {seed}", "components": {FRAME: {"role": "frame"}},
                  "links": [], "ports": []}
    speeds: dict[str, float] = {}
    if dof == 1:
        ratio = 1.0
        for stage in chain:
            ratio *= stage.ratio
        _join(data, chain)
        drive = drive or rng.choice(["forward", "load on output", "back-driven"])
        inp, out = chain[0].inp, chain[-1].out
        on_output = drive == "load on output"
        data["ports"] = [{"component": inp, "role": "input", "speed": w_in,
                          **({} if on_output else {"power": power})},
                         {"component": out, "role": "output",
                          **({"power": power} if on_output else {})}]
        speeds = {inp: w_in, out: w_in / ratio}
        model = model_from_dict(data)
        if drive == "back-driven":  # the old output drives: the ratio inverts
            model, ratio = backdriven(model), 1.0 / ratio
        return Train(seed, data, model, tuple(s.name for s in chain), ratio, speeds, 1,
                     drive == "back-driven")
    diff, third, out_speed = _differential(rng, f"s{len(chain)}", draw_eta)
    after = _chain(rng, rng.randint(0, 1), len(chain) + 1, draw_eta, names)
    _join(data, chain + [diff] + after)
    before_ratio = 1.0
    for stage in chain:
        before_ratio *= stage.ratio
    w_member = w_in / before_ratio
    w_third = round(w_member * rng.choice([-1, 1]) * rng.uniform(0.2, 2.0), 6)
    w_out = out_speed(w_member, w_third)
    for stage in after:
        w_out /= stage.ratio
    inp, out = chain[0].inp, (after[-1].out if after else diff.out)
    third_role = rng.choice(["input", "output"])
    loaded = rng.choice(["in", "third"])
    data["ports"] = [
        {"component": inp, "role": "input", "speed": w_in,
         **({"power": power} if loaded == "in" else {})},
        {"component": third, "role": third_role, "speed": w_third,
         **({"power": power} if loaded == "third" else {})},
        {"component": out, "role": "output"}]
    speeds = {inp: w_in, third: w_third, out: w_out}
    return Train(seed, data, model_from_dict(data),
                 tuple(s.name for s in chain + [diff] + after), None, speeds, 2, False)


def _join(data: dict, chain: list[Stage]) -> None:
    for j, stage in enumerate(chain):
        data["components"].update(stage.components)
        data["links"].extend(stage.links)
        if j:
            data["links"].append(_fixed(chain[j - 1].out, stage.inp))


def with_ids(data: dict, new: dict) -> dict:
    """Model data with the components ``new`` maps (old id -> new id) renamed wherever
    they are named, the others kept; the file order is kept, so link and port indices too.

    >>> with_ids({"components": {1: {}, 2: {}}, "links": [{"between": [1, 2]}],
    ...           "ports": [{"component": 2}]}, {2: "out"})["links"]
    [{'between': [1, 'out']}]
    """
    get = lambda c: new.get(c, c)  # noqa: E731
    links = [dict(link, between=[get(b) for b in link["between"]],
                  **({"carrier": get(link["carrier"])} if "carrier" in link else {}))
             for link in data["links"]]
    ports = [dict(port, component=get(port["component"])) for port in data["ports"]]
    return dict(data, components={get(c): v for c, v in data["components"].items()},
                links=links, ports=ports)


def renamed(data: dict, seed: Any) -> tuple[dict, dict[str, str]]:
    """The same train with every component renamed and components, links and ports
    shuffled: ``(data, {old id: new id})``."""
    rng = random.Random(str(seed))
    ids = list(data["components"])
    fresh = [f"x{n}" for n in rng.sample(range(10 * len(ids)), len(ids))]
    new = dict(zip(ids, fresh))
    out = with_ids(data, new)
    comps = list(out["components"].items())
    rng.shuffle(comps)
    links, ports = list(out["links"]), list(out["ports"])
    rng.shuffle(links)
    rng.shuffle(ports)
    return dict(out, components=dict(comps), links=links, ports=ports), new


def train_strategy(**kwargs: Any):
    """A hypothesis strategy of :class:`Train` (hypothesis is imported here, lazily:
    it is a test dependency only). Keyword arguments go to :func:`random_train`."""
    from hypothesis import strategies as st

    return st.integers(min_value=0, max_value=2**32 - 1).map(
        lambda seed: random_train(seed, **kwargs))
