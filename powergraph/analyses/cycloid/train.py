"""A cycloid stage's ratio fluctuation carried to the output of a whole train (docs/cycloid.md).

Derivation. In the stage analysis the pins (ring ``b``) are the reference, the crank ``c``
turns by ``θ`` and the disc by ``ψ(θ)``, so ``w_disc − w_ring = ρ(θ)·u`` with
``u = w_c − w_ring`` and ``ρ = dψ/dθ = −1/i_stage``. Ideally ``ρ = −1/z1``; write
``ρ = −1/z1 + ε(θ)``. Put into the mesh's Willis row ``(w_a − w_c) − i·(w_b − w_c) = s``
(``i`` = Willis' quotient): the ideal part cancels and what is left is a slip

    s = k·ε·u,   k = 1 if the disc is ``a``,  k = −i if the disc is ``b``.

With the other speeds given (the input held constant), every speed is affine in ``s``; two
solves of :func:`powergraph.kinematics.solve_speeds` (``s = 0`` and ``s = 1``) give
``u(s) = u0 + h·s``, ``w_in(s)``, ``w_out(s)``, and the consistent slip is exactly

    s = k·ε·u0 / (1 − k·ε·h).

So the train's instantaneous ratio ``w_in/w_out`` follows from the stage's ratio at each
crank angle without approximation. For the RV-40E (first stage 12/36) this gives
``i_train = 1 + (36/12)·(1 + i_stage) = 4 + 3·i_stage``: a stage deviation ``Δi`` (%)
appears at the output as ``(3·39/121)·Δi``.

Over one input revolution the crank turns ``u0/w_in`` revolutions relative to the ring; the
curve is sampled at crank angles ``θ = |u0/w_in|·φ_in`` (phase 0 at ``φ_in = 0``; the
reversed sense is the mirror image, same values). Each disc is analysed alone (``count``
is not used: identical discs at crank phases 2π/count apart see the same fluctuation when
``z2`` is a multiple of ``count``).
"""
from __future__ import annotations

import math

import numpy as np

from powergraph.analyses.cycloid.contact import contact_curve
from powergraph.analyses.cycloid.fluctuation import (CycloidFluctuation, read_only,
                                                     cycloid_fluctuation, deviation_percent)
from powergraph.analyses.cycloid.report import train_text
from powergraph.errors import ModelError, UsageError
from powergraph.kinematics import solve_speeds, willis_ratio
from powergraph.records import record
from powergraph.result import nothing_to_draw

#: Samples of the input angle per period of the stage's fluctuation (at least 360 in all).
SAMPLES_PER_PERIOD = 32


@record(eq=False)
class StageAtOutput:
    """One cycloid mesh's fluctuation, at the stage and at the train's output.

    Attributes
    ----------
    link : int
        Index of the mesh in ``links``.
    stage : CycloidFluctuation
        The stage on its own (ring fixed, crank in, disc out).
    crank_turns_per_input_turn : float
        ``u0/w_in``: crank revolutions relative to the ring per input revolution.
    input_angle, crank_angle : ndarray
        One input revolution (rad) and the stage's crank angle there (rad, mod 2π).
    stage_ratio, train_ratio : ndarray
        The stage's and the train's instantaneous ratios at those angles.
    train_ratio_nominal : float
    max_deviation_percent : float
        Exact largest ``|Δi|`` of the train (Eq. 11 applied to ``w_in/w_out``), from the
        stage's exact extreme ratios.
    """

    link: int
    disc: str
    ring: str
    carrier: str
    stage: CycloidFluctuation
    crank_turns_per_input_turn: float
    input_angle: np.ndarray
    crank_angle: np.ndarray
    stage_ratio: np.ndarray
    train_ratio: np.ndarray
    train_ratio_nominal: float
    max_deviation_percent: float

    @property
    def deviation_percent(self) -> np.ndarray:
        return deviation_percent(self.train_ratio, self.train_ratio_nominal)

    def to_dict(self) -> dict:
        stage = self.stage
        return {
            "link": self.link, "disc": self.disc, "ring": self.ring, "carrier": self.carrier,
            "module": stage.geometry.module, "teeth": stage.geometry.teeth,
            "shift": stage.geometry.shift, "rc": stage.geometry.rc,
            "profile_error": stage.profile_error,
            "stage_ratio_nominal": stage.ratio_nominal,
            "stage_max_deviation_percent": stage.max_deviation_percent,
            "stage_max_deviation_percent_2deg": stage.max_deviation_percent_2deg,
            "crank_turns_per_input_turn": self.crank_turns_per_input_turn,
            "ratio_nominal": self.train_ratio_nominal,
            "max_deviation_percent": self.max_deviation_percent,
            "input_angle_deg": np.degrees(self.input_angle).tolist(),
            "ratio": self.train_ratio.tolist(),
            "deviation_percent": self.deviation_percent.tolist(),
        }


@record
class TrainFluctuation:
    """The fluctuation of every cycloid mesh of a train, carried to its output."""

    input: str
    output: str
    ratio_nominal: float
    stages: tuple[StageAtOutput, ...]

    def text_report(self) -> str:
        """The readable report (what the command line prints)."""
        return train_text(self)

    def plot(self, ax=None, **kwargs):
        """Nothing to draw: raises :class:`~powergraph.result.NothingToDrawError`."""
        raise nothing_to_draw(self, "plot each stage's cycloid_fluctuation result")

    def to_dict(self) -> dict:
        """Plain data for ``solve --json`` (key ``cycloid_fluctuation``)."""
        return {"input": self.input, "output": self.output,
                "ratio_nominal": self.ratio_nominal,
                "stages": [stage.to_dict() for stage in self.stages]}


def train_fluctuation(model, speeds=None) -> TrainFluctuation:
    """Carry each ``cycloid`` mesh's ratio fluctuation to the train's output.

    Parameters
    ----------
    model : Model
        A one-input, one-output train; meshes with a ``cycloid`` block are analysed.
    speeds : mapping, optional
        ``{component: rad/s}`` held constant (default: the ports' speeds, as in ``solve``).

    Returns
    -------
    TrainFluctuation
        ``stages`` is empty when no mesh carries a ``cycloid`` block.

    Raises
    ------
    ModelError
        For a train without exactly one input and one output, or an impossible stage
        (``links[i].cycloid: profile undercut ...``).

    Examples
    --------
    A K-H-V cycloid stage (crank in, disc out): the output sees the stage's fluctuation.

    >>> from powergraph.model import loads_model
    >>> model = loads_model('''
    ... name: K-H-V
    ... components: {0: {role: frame}, H: {}, d: {teeth: 39},
    ...              pins: {teeth: 40, internal: true}, out: {}}
    ... links:
    ...   - {type: mesh, between: [d, pins], carrier: H,
    ...      cycloid: {module: 3.2, profile_error: 0.01}}
    ...   - {type: fixed, between: [pins, 0]}
    ...   - {type: coupling, between: [d, out]}
    ... ports: [{component: H, role: input}, {component: out, role: output}]
    ... ''')
    >>> result = train_fluctuation(model)
    >>> round(result.ratio_nominal, 9)
    -39.0
    >>> stage = result.stages[0]
    >>> round(stage.max_deviation_percent / stage.stage.max_deviation_percent, 9)
    1.0
    """
    nominal = solve_speeds(model, speeds)
    if nominal.input_component is None or nominal.output_component is None:
        raise ModelError("the cycloid fluctuation at the output needs exactly one input "
                         "and one output port", "ports")
    if not math.isfinite(nominal.ratio) or nominal.ratio == 0:
        raise ModelError("the output does not turn (or the input stands still): the "
                         "train's ratio is not finite, so its fluctuation at the output is "
                         "not defined", "ports")
    stages = tuple(_stage_at_output(model, link, nominal)
                   for link in model.meshes if "cycloid" in link.blocks)
    return TrainFluctuation(nominal.input_component, nominal.output_component,
                            float(nominal.ratio), stages)


def _stage_at_output(model, link, nominal) -> StageAtOutput:
    block = link.blocks["cycloid"]
    try:
        stage = cycloid_fluctuation(block.module, block.teeth, block.profile_error,
                                    block.shift, block.rc)
    except UsageError as exc:
        raise ModelError(exc.message, f"{link.path}.cycloid") from None
    slipped = solve_speeds(model, dict(nominal.given), slips={link.index: 1.0})
    base = _watched_speeds(nominal, link, block)
    u0, in0, out0 = base
    h, g_in, g_out = _watched_speeds(slipped, link, block) - base
    k = 1.0 if link.between[0] == block.disc else -willis_ratio(link, model)

    def train_ratio(stage_ratio):
        eps = 1.0 / block.teeth - 1.0 / np.asarray(stage_ratio)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = k * eps * u0 / (1.0 - k * eps * h)
            ratio = (in0 + g_in * s) / (out0 + g_out * s)
        if not np.all(np.isfinite(ratio)):
            raise ModelError("within the stage's ratio fluctuation the output (or the "
                             "stage's own crank) stands still: the train's ratio is not "
                             "defined there, so neither is its fluctuation at the output",
                             f"{link.path}.cycloid")
        return ratio

    turns = u0 / in0
    count = max(360, SAMPLES_PER_PERIOD * math.ceil(abs(turns) * stage.geometry.pins))
    input_angle = np.arange(count) * (2.0 * np.pi / count)
    crank = (abs(turns) * input_angle) % (2.0 * np.pi)
    stage_ratio = -1.0 / contact_curve(stage.geometry, stage.profile_error, crank)[2]
    sides = np.concatenate([stage.ratio, stage.ratio_before, stage.ratio_after])
    extremes = train_ratio(np.array([sides.min(), sides.max()]))
    nominal_ratio = in0 / out0
    peak = np.max(np.abs(deviation_percent(extremes, nominal_ratio)))
    return StageAtOutput(link.index, block.disc, block.ring, link.carrier, stage,
                         float(turns), read_only(input_angle), read_only(crank),
                         read_only(stage_ratio), read_only(train_ratio(stage_ratio)),
                         float(nominal_ratio), float(peak))


def _watched_speeds(kinematics, link, block) -> np.ndarray:
    """Crank speed relative to the ring, input speed, output speed."""
    return np.array([kinematics.speed(link.carrier) - kinematics.speed(block.ring),
                     kinematics.speed(kinematics.input_component),
                     kinematics.speed(kinematics.output_component)])
