"""Find the parts of an RV-type train (Wang 2021, Fig. 2) from the graph alone.

The paper's method needs one pattern, found here whatever the ids and the link order:

- one input port, one output port, one degree of freedom;
- **mesh A** (the first stage, the paper's 1–2): one gear is the input body (the central
  gear 1), the other is a *planet body* (planet gear/crank shaft 2/3), and its carrier is
  the *output body* (output disk/planet frame 6/7);
- **mesh B** (the cycloid–pin mesh, the paper's 4/4'–5): its carrier is the planet body
  (the crank's eccentric carries the cycloid), one gear is fixed to the frame (the needle
  gear 5) and the other (the cycloid 4) is a body of its own joined to the output body by a
  ``coupling`` (the equal-speed mechanism);
- no other mesh or coupling.

Anything else raises :class:`~powergraph.errors.MethodNotApplicableError` saying what the
method needs and what was found.

Examples
--------
>>> from powergraph.model import load_model
>>> roles = find_rv_roles(load_model("models/rv40e_wang2021.yaml"))     # doctest: +SKIP
>>> roles.input_gear, roles.planet_body, roles.cycloid, roles.output_body   # doctest: +SKIP
('1', '2/3', '4', '6/7')
"""
from __future__ import annotations


from powergraph.errors import MethodNotApplicableError
from powergraph.model.spec import Link, Model
from powergraph.records import record

NEEDS = ("the wang2021 method needs an RV-type train (Wang 2021, Fig. 2): one input port on "
         "a central gear meshing with a planet/crank body whose carrier is the output body; "
         "that planet/crank body the carrier of a second mesh between a cycloid gear, "
         "coupled to the output body, and a gear fixed to the frame; nothing else meshing "
         "or coupled")


@record
class RVRoles:
    """Which component plays which part of Wang's RV reducer (component ids as strings).

    ``first_mesh`` and ``cycloid_mesh`` are link indices (mesh A = 1–2, mesh B = 4–5);
    the ``*_body`` fields are body ids of the model ("2/3").
    """

    input_gear: str
    planet_gear: str
    planet_body: str
    cycloid: str
    pin_gear: str
    output_body: str
    output_component: str
    coupling: int
    first_mesh: int
    cycloid_mesh: int

    def to_dict(self, model: Model) -> dict:
        """Roles with component ids as written in the model file."""
        raw = model.raw_id
        return {"input_gear": raw(self.input_gear), "planet_gear": raw(self.planet_gear),
                "planet_body": self.planet_body, "cycloid": raw(self.cycloid),
                "pin_gear": raw(self.pin_gear), "output_body": self.output_body,
                "output": raw(self.output_component), "first_stage_mesh": self.first_mesh,
                "cycloid_mesh": self.cycloid_mesh, "coupling": self.coupling}


def _refuse(found: str) -> MethodNotApplicableError:
    return MethodNotApplicableError(f"{NEEDS}; {found}")


def _count(n: int, one: str, many: str) -> str:
    return f"{n} {one if n == 1 else many}"


def _check_ports(model: Model) -> None:
    n_in, n_out = len(model.inputs), len(model.outputs)
    if n_in != 1 or n_out != 1:
        raise _refuse(f"found {_count(n_in, 'input port', 'input ports')} and "
                      f"{_count(n_out, 'output port', 'output ports')} (it needs exactly one "
                      "of each)")


def _check_counts(model: Model) -> tuple[tuple[Link, ...], tuple[Link, ...]]:
    meshes = model.meshes
    couplings = tuple(link for link in model.links if link.type == "coupling")
    if len(meshes) != 2 or len(couplings) != 1:
        hint = ("; model parallel cycloid discs or cranks as one component with count: N"
                if len(meshes) > 2 else "")
        raise _refuse(f"found {_count(len(meshes), 'mesh', 'meshes')} and "
                      f"{_count(len(couplings), 'coupling', 'couplings')} (it needs 2 meshes "
                      f"and 1 coupling{hint})")
    return meshes, couplings


def _first_mesh(model: Model, meshes: tuple[Link, ...], input_body: str,
                output_body: str) -> tuple[Link, str]:
    """Mesh A: input body on one side, carrier on the output body. Returns (link, planet)."""
    body = model.body_of
    for link in meshes:
        sides = [body[c] for c in link.between]
        if input_body in sides and body[link.carrier] == output_body:
            planet = link.between[1 - sides.index(input_body)]
            if body[planet] in (input_body, output_body, model.frame_body):
                raise _refuse(f"{link.path}: the gear meshing with the input, "
                              f"{model.raw_id(planet)!r}, must be a planet/crank body of "
                              "its own (not the input, the output or the frame)")
            return link, planet
    raise _refuse(f"no mesh has the input component {model.raw_id(_port(model, 'input'))!r} "
                  f"as a gear and the output body {output_body!r} as its carrier")


def _port(model: Model, role: str) -> str:
    return (model.inputs if role == "input" else model.outputs)[0].component


def _cycloid_mesh(model: Model, mesh: Link, planet_body: str,
                  output_body: str) -> tuple[str, str]:
    """Mesh B: carried by the planet body, one gear fixed. Returns (cycloid, pin gear)."""
    body, frame = model.body_of, model.frame_body
    if body[mesh.carrier] != planet_body:
        raise _refuse(f"the second mesh, {mesh.path} between "
                      f"{[model.raw_id(c) for c in mesh.between]}, has carrier "
                      f"{model.raw_id(mesh.carrier)!r}, not the planet/crank body "
                      f"{planet_body!r}")
    fixed = [c for c in mesh.between if body[c] == frame]
    if len(fixed) != 1:
        raise _refuse(f"{mesh.path}: exactly one gear of the cycloid mesh must be fixed to "
                      f"the frame; found {len(fixed)}")
    cycloid = mesh.between[1 - mesh.between.index(fixed[0])]
    if body[cycloid] in (output_body, planet_body):
        raise _refuse(f"{mesh.path}: the cycloid gear {model.raw_id(cycloid)!r} must be a "
                      "body of its own, joined to the output body by a coupling")
    return cycloid, fixed[0]


def _check_coupling(model: Model, coupling: Link, cycloid: str, output_body: str) -> None:
    sides = {model.body_of[c] for c in coupling.between}
    if sides != {model.body_of[cycloid], output_body}:
        raise _refuse(f"the coupling {coupling.path} joins "
                      f"{[model.raw_id(c) for c in coupling.between]}, not the cycloid gear "
                      f"{model.raw_id(cycloid)!r} and the output body {output_body!r}")


def _check_dof(model: Model) -> None:
    from powergraph.kinematics import degrees_of_freedom

    dof = degrees_of_freedom(model)
    if dof != 1:
        raise _refuse(f"the train has {dof} degrees of freedom (it needs 1)")


def find_rv_roles(model: Model) -> RVRoles:
    """Identify the RV reducer's parts in ``model`` from its graph.

    Parameters
    ----------
    model : Model
        Any validated model; it is not changed.

    Returns
    -------
    RVRoles

    Raises
    ------
    MethodNotApplicableError
        When the train is not of the RV pattern; the message says what the method needs
        and what was found.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> roles = find_rv_roles(load_model("models/rv40e_wang2021.yaml"))     # doctest: +SKIP
    >>> roles.first_mesh, roles.cycloid_mesh, roles.pin_gear       # doctest: +SKIP
    (0, 1, '5')
    """
    _check_ports(model)
    meshes, (coupling,) = _check_counts(model)
    input_body = model.body_of[_port(model, "input")]
    output_body = model.body_of[_port(model, "output")]
    if len({input_body, output_body, model.frame_body}) != 3:
        raise _refuse("the input, the output and the frame are not three different bodies")
    first, planet = _first_mesh(model, meshes, input_body, output_body)
    planet_body = model.body_of[planet]
    second = meshes[1] if meshes[0] is first else meshes[0]
    cycloid, pin = _cycloid_mesh(model, second, planet_body, output_body)
    _check_coupling(model, coupling, cycloid, output_body)
    _check_dof(model)
    return RVRoles(input_gear=_port(model, "input"), planet_gear=planet,
                   planet_body=planet_body, cycloid=cycloid, pin_gear=pin,
                   output_body=output_body, output_component=_port(model, "output"),
                   coupling=coupling.index, first_mesh=first.index,
                   cycloid_mesh=second.index)
