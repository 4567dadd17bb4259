"""Conservation checks for any solved train — for the test-suite and for users.

After a solve these must hold whatever the topology:

- power in = power out + mesh losses + bearing losses (``assert_power_balance``), in the
  ground frame and seen from every body (losses are frame-invariant);
- every bearing or body drag opposes its relative rotation: torque ``M >= 0`` applied as
  ``-M·sign(Δω)`` / ``+M·sign(Δω)`` to its two bodies, loss ``M·|Δω|``
  (``assert_bearing_law``);
- every node of the flow graph balances (``assert_flow_balance``);
- every Willis row, coupling and the frame's zero speed (``assert_kinematics``);
- every body is in torque equilibrium, bearing torques included (``assert_equilibrium``);
- every loss is >= 0, and each mesh passes power from its driver with its basic
  efficiency in its carrier's frame, or passes nothing with its factor inside
  ``[η, 1/η]`` (it sticks) (``assert_mesh_law``);
- a locked train (``result.lock``) is at rest: every speed and power is zero, every mesh
  sticks, and the loads are held in equilibrium (``assert_locked``).

:func:`consistent_patterns` is a deliberately plain, independent search over every
driver pattern, for checking the solver's verdicts on small trains (docs/locking.md).

Examples
--------
>>> import powergraph as pg
>>> from powergraph.testing import assert_conservation
>>> assert_conservation(pg.solve(pg.load_model("models/rv40e_wang2021.yaml")))   # doctest: +SKIP
"""
from __future__ import annotations

from powergraph.statics.loss_sources import losses
from powergraph.statics.flow import BATTERY, GENERATOR, GROUND, LOSS, MOTOR
from powergraph.statics.result import PowerFlowResult

RTOL = 1e-9


def _close(a: float, b: float, scale: float, rtol: float, what: str) -> None:
    if abs(a - b) > rtol * max(scale, 1e-300):
        raise AssertionError(f"{what}: {a!r} != {b!r} (difference {a - b:.3e}, "
                             f"allowed {rtol * scale:.3e})")


def _scale(result: PowerFlowResult) -> float:
    return max(abs(result.input_power), abs(result.output_power), result.total_loss, 1e-12)


def assert_power_balance(result: PowerFlowResult, rtol: float = RTOL) -> None:
    """Power in = power out + losses; the total loss is the elements' plus the bearings';
    no element loses a negative power."""
    battery = sum(b.battery_power for b in getattr(result, "buses", {}).values())
    _close(result.input_power + battery, result.output_power + result.total_loss,
           _scale(result), rtol, "power in (+ batteries) vs power out + losses")
    _close(result.total_loss, sum(loss for _, loss in losses(result)), _scale(result), rtol,
           "total loss vs the sum of the loss sources' (meshes, bearings, drags, machines)")
    _assert_machines(result, rtol)
    for element in result.elements:
        if element.loss < -rtol * _scale(result):
            raise AssertionError(f"links[{element.link}] has a negative loss {element.loss}")


def _assert_machines(result: PowerFlowResult, rtol: float) -> None:
    """Each machine draws P/η motoring and P·η generating (loss >= 0); each bus's battery
    power equals what its machines draw."""
    scale = _scale(result)
    drawn: dict[str, float] = {}
    for m in getattr(result, "machines", ()):
        expected = m.power / m.efficiency if m.power > 0 else m.power * m.efficiency
        _close(m.electrical_power, expected, scale, rtol, f"{m.name}: electrical power")
        if m.loss < -rtol * scale:
            raise AssertionError(f"{m.name} has a negative loss {m.loss}")
        drawn[m.bus] = drawn.get(m.bus, 0.0) + m.electrical_power
    for name, bus in getattr(result, "buses", {}).items():
        _close(bus.battery_power, drawn.get(name, 0.0), scale, rtol, f"balance of bus {name}")


def assert_flow_balance(result: PowerFlowResult, frame: str | None = None,
                        rtol: float = RTOL) -> None:
    """In the flow graph seen from ``frame``, every body and element node balances, and
    motor + ground = generator + loss."""
    graph = result.flow_graph(frame)
    scale = _scale(result) + sum(abs(e.carrier_frame_power) for e in result.elements)
    sources = (MOTOR, GENERATOR, LOSS, GROUND, BATTERY)
    for node in graph.nodes:
        if node.kind in sources:
            continue
        inflow = sum(d["power"] for _, _, d in graph.in_edges(node, data=True))
        outflow = sum(d["power"] for _, _, d in graph.out_edges(node, data=True))
        # seen from a fast body, a node's arrows can exceed the train's powers by far (a
        # 5^20 reducer's housing torque times the input speed): its own round-off then
        # sets the tolerance, never below the train's scale
        _close(inflow, outflow, max(scale, inflow + outflow), rtol,
               f"flow balance at {node!r} (frame {frame})")
    edges = list(graph.edges(data="power"))
    fed = sum(p for u, _, p in edges if u.kind in (MOTOR, GROUND, BATTERY)) \
        - sum(p for _, v, p in edges if v.kind in (MOTOR, GROUND, BATTERY))
    taken = sum(p for _, v, p in edges if v.kind in (GENERATOR, LOSS)) \
        - sum(p for u, _, p in edges if u.kind in (GENERATOR, LOSS))
    moved = sum(p for u, v, p in edges if u.kind in sources or v.kind in sources)
    _close(fed, taken, max(scale, moved), rtol, f"sources vs sinks (frame {frame})")


def assert_kinematics(result: PowerFlowResult, rtol: float = RTOL) -> None:
    """Every Willis relation, every coupling and the frame's zero speed hold."""
    kin, model = result.kinematics, result.model
    scale = max(abs(w) for w in kin.body_speeds.values()) or 1.0
    _close(kin.body_speeds[model.frame_body], 0.0, scale, rtol, "frame speed")
    for element in result.elements:
        w_a, w_b, w_c = (kin.speed(x) for x in (element.a, element.b, element.carrier))
        _close(w_a - w_c, element.ratio * (w_b - w_c), scale, rtol,
               f"Willis relation of links[{element.link}]")
    for link in model.links:
        if link.type in ("coupling", "fixed"):
            _close(kin.speed(link.between[0]), kin.speed(link.between[1]), scale, rtol,
                   f"equal speeds of links[{link.index}] ({link.type})")


def assert_equilibrium(result: PowerFlowResult, rtol: float = RTOL) -> None:
    """Element torques plus the external torque on every body sum to zero."""
    totals = {body.id: result.external_torques.get(body.id, 0.0) for body in result.model.bodies}
    for element in result.elements:
        for body, torque in element.torques.items():
            totals[body] += torque
    for bearing in getattr(result, "bearings", ()):
        for body, torque in bearing.torques.items():
            totals[body] += torque
    scale = max([abs(t) for t in result.external_torques.values()] + [1e-12])
    for body, total in totals.items():
        _close(total, 0.0, scale, rtol, f"torque balance of body {body!r}")


def assert_mesh_law(result: PowerFlowResult, rtol: float = RTOL) -> None:
    """In its carrier's frame each element passes power from its driver to the other gear
    with its basic efficiency: out = η · in, in >= 0 (Chen & Angeles' virtual power)."""
    kin, model = result.kinematics, result.model
    scale = _scale(result) + sum(e.carrier_frame_power for e in result.elements)
    for e in result.elements:
        body_a, body_b = model.body_of[e.a], model.body_of[e.b]
        w_c = kin.speed(e.carrier)
        t_a = -e.force                        # torque gear a applies to the mesh
        fed_a = t_a * (kin.body_speeds[body_a] - w_c)
        fed_b = e.ratio * e.factor * e.force * (kin.body_speeds[body_b] - w_c)
        if e.driver is None:
            _close(fed_a, 0.0, scale, rtol, f"links[{e.link}] passes power but has no driver")
            low, high = min(e.efficiency, 1.0 / e.efficiency), max(e.efficiency, 1.0 / e.efficiency)
            if not low * (1 - rtol) <= e.factor <= high * (1 + rtol):
                raise AssertionError(f"links[{e.link}] sticks with factor {e.factor!r} "
                                     f"outside [η, 1/η] = [{low!r}, {high!r}]")
            continue
        fed_in, fed_out = (fed_a, -fed_b) if e.driver == e.a else (fed_b, -fed_a)
        if fed_in < -rtol * scale:
            raise AssertionError(f"links[{e.link}]: the driver {e.driver!r} takes power out")
        _close(fed_out, e.efficiency * fed_in, scale, rtol,
               f"links[{e.link}] carrier-frame output vs efficiency x input")
        _close(e.carrier_frame_power, fed_in, scale, rtol, f"links[{e.link}] virtual power")


def assert_bearing_law(result: PowerFlowResult, rtol: float = RTOL) -> None:
    """Each bearing or drag: its bodies' relative speed as the kinematics give it, a torque
    ``M >= 0`` (zero without relative motion) opposing it, and the loss ``M·|Δω| >= 0``."""
    speeds, model = result.kinematics.body_speeds, result.model
    for b in getattr(result, "bearings", ()):
        w_1, w_2 = (speeds[model.body_of[c]] for c in b.between)
        scale = max(abs(w_1), abs(w_2), 1e-300)
        _close(b.relative_speed, w_1 - w_2, scale, max(rtol, 1e-12), f"{b.node} relative speed")
        if b.torque < 0 or b.loss < 0 or (b.relative_speed == 0 and b.torque != 0):
            raise AssertionError(f"{b.node}: torque {b.torque!r} and loss {b.loss!r} must be "
                                 ">= 0, and 0 without relative motion")
        _close(b.loss, b.torque * abs(b.relative_speed), max(b.loss, 1e-300), rtol,
               f"{b.node} loss vs M·|Δω|")
        on_1 = b.torques[model.body_of[b.between[0]]] if b.bodies[0] != b.bodies[1] else 0.0
        if on_1 * b.relative_speed > 0:
            raise AssertionError(f"{b.node}: the torque on the carried body drives it")


def assert_locked(result: PowerFlowResult, rtol: float = RTOL) -> None:
    """A locked result is at rest: zero speeds, zero powers and losses, efficiency 0, no
    mesh with a driver, and a reason naming links of the model."""
    lock = result.lock
    if lock is None:
        return
    if any(w != 0.0 for w in result.kinematics.body_speeds.values()):
        raise AssertionError("a locked train must be at rest (all speeds 0)")
    if result.input_power or result.output_power or result.total_loss or result.efficiency:
        raise AssertionError("a locked train at rest passes no power")
    if not result.self_locking:
        raise AssertionError("a locked train must report self_locking")
    for e in result.elements:
        if e.driver is not None or e.carrier_frame_power or e.loss:
            raise AssertionError(f"links[{e.link}] of a locked train must stick")
    links = {link.index for link in result.model.links}
    if not lock.reasons or not set(lock.meshes) <= links:
        raise AssertionError("a lock must give a reason and name links of the model")


def consistent_patterns(model, speeds=None, tolerance: float = 1e-9) -> list[dict[int, int]]:
    """Every self-consistent driver pattern, by plain enumeration (2^m torque balances for
    m moving lossy elements; keep m small): ``[{link index: +1 (a drives) / -1}]``,
    one per distinct solution (elements passing no power are left out of the dicts, so
    patterns differing only there count once).

    Independent of the solver's search: it only shares the kinematics and the torque
    balance. A pattern is consistent when every lossy element passes power the assumed
    way, to ``tolerance`` times the largest carrier-frame power of the pattern.

    Examples
    --------
    >>> import powergraph as pg
    >>> consistent_patterns(pg.load_model("models/cycloid_khv.yaml"))   # doctest: +SKIP
    [{0: -1}]
    """
    import itertools

    import numpy as np

    from powergraph.kinematics import elements_of, solve_speeds
    from powergraph.statics.equilibrium import loads_of, solve_equilibrium

    kin = solve_speeds(model, speeds)
    elements = elements_of(model)
    loads = loads_of(model, kin)
    rel = np.array([kin.body_speeds[e.body_a] - kin.body_speeds[e.body_c] for e in elements])
    top = max(abs(w) for w in kin.body_speeds.values())
    lossy = [k for k, e in enumerate(elements) if e.efficiency < 1 and abs(rel[k]) > 1e-12 * top]
    found: dict[tuple, dict[int, int]] = {}
    for codes in itertools.product((1, -1), repeat=len(lossy)):
        factors = np.ones(len(elements))
        for k, code in zip(lossy, codes):
            eta = elements[k].efficiency
            factors[k] = eta if code > 0 else 1.0 / eta
        forces = solve_equilibrium(model, elements, loads, factors).forces
        power = -forces * rel
        scale = max(float(np.max(np.abs(power))), 1e-300)
        if all(code * power[k] >= -tolerance * scale for k, code in zip(lossy, codes)):
            passing = {elements[k].link: code for k, code in zip(lossy, codes)
                       if abs(power[k]) > tolerance * scale}
            found.setdefault(tuple(sorted(passing.items())), passing)
    return list(found.values())


def assert_conservation(result: PowerFlowResult, rtol: float = RTOL) -> None:
    """All of the above, with the flow balance checked in the ground frame and in the frame
    of every body (for trains of more than ``EVERY_FRAME_UP_TO`` bodies, through the
    slowest and the fastest body, which bound all the others: see
    :func:`_extreme_bodies`); a locked result is also checked to be at rest
    (``assert_locked``)."""
    assert_locked(result, rtol)
    assert_kinematics(result, rtol)
    assert_equilibrium(result, rtol)
    assert_power_balance(result, rtol)
    assert_mesh_law(result, rtol)
    assert_bearing_law(result, rtol)
    assert_flow_balance(result, None, rtol)
    bodies = result.model.bodies
    for body in bodies if len(bodies) <= EVERY_FRAME_UP_TO else _extreme_bodies(result):
        assert_flow_balance(result, body.members[0], rtol)


#: Trains with at most this many bodies have their flow balance checked from every body.
EVERY_FRAME_UP_TO = 40


def _extreme_bodies(result: PowerFlowResult) -> list:
    """The bodies of least and greatest speed: checking the flow balance seen from them
    checks it seen from every body.

    Seen from a body turning at ``w_F`` every arrow's power is ``-T (w - w_F)``, so each
    node's imbalance and the sources-minus-sinks difference are affine in ``w_F``; the
    largest magnitude of an affine function over the speeds of all bodies is reached at the
    least or the greatest speed, and ``w_F = 0`` (the ground frame) lies between them. The
    balances are oriented (an arrow flips with its power's sign) but each flip leaves the
    signed sum unchanged. So an imbalance seen from any body is at most the larger of the
    two seen from these (the tolerance, relative to each node's own throughput, is not
    covered by this argument: hence every frame is checked on trains of ordinary size).
    """
    speeds = result.kinematics.body_speeds
    bodies = result.model.bodies
    if not bodies:
        return []
    slowest = min(bodies, key=lambda b: speeds[b.id])
    fastest = max(bodies, key=lambda b: speeds[b.id])
    return [slowest] if slowest is fastest else [slowest, fastest]
