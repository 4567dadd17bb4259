"""SKF's four-component model of a rolling bearing's frictional moment (SKF, since 2004).

The SKF rolling bearings catalogue ("Friction" chapter) writes the total frictional moment as

    M = φ_ish·φ_rs·M_rr + M_sl + M_seal + M_drag

- rolling: ``M_rr = G_rr·(ν·n)^0.6``;
- sliding: ``M_sl = G_sl·μ_sl``, ``μ_sl = φ_bl·μ_bl + (1 − φ_bl)·μ_EHL``,
  ``φ_bl = exp(−2.6e-8·(n·ν)^1.4·d_m)``;
- inlet shear heating: ``φ_ish = 1 / (1 + 1.84e-9·(n·d_m)^1.28·ν^0.64)``;
- kinematic replenishment/starvation: ``φ_rs = exp(−K_rs·ν·n·(d + D)·sqrt(K_z/(2(D − d))))``;
- seals: ``M_seal = K_S1·d_s^β + K_S2``;
- drag in an oil bath (the 2005 catalogue's form): ``M_drag = V_M·K_ball·d_m^5·n²`` (ball
  bearings), ``10·V_M·K_roll·B·d_m^4·n²`` (roller bearings), with
  ``K_ball = i_rw·K_z·(d + D)/(D − d)·1e-12`` and ``K_roll = K_L·K_z·(d + D)/(D − d)·1e-12``.

The load terms (``d_m = (d + D)/2``):

- deep groove ball bearings: ``G_rr = R1·d_m^1.96·F_r^0.54`` and ``G_sl = S1·d_m^−0.26·F_r^(5/3)``
  without axial load; with ``F_a > 0``, ``G_rr = R1·d_m^1.96·(F_r + R2/sin α_F·F_a)^0.54``,
  ``G_sl = S1·d_m^−0.145·(F_r^5 + S2·d_m^1.5/sin α_F·F_a^4)^(1/3)``,
  ``α_F = 24.6·(F_a/C_0)^0.24`` degrees (``C_0`` the basic static load rating);
- cylindrical roller bearings: ``G_rr = R1·d_m^2.41·F_r^0.31``,
  ``G_sl = S1·d_m^0.9·F_a + S2·d_m·F_r``.

**Units.** The catalogue's formulas are dimensional: ``d, D, d_m`` in mm, ``n`` in r/min,
``ν`` in mm²/s, loads in N, moments in N·mm. The public functions here take SI (lengths in
m, speeds in rad/s — the magnitude is used —, kinematic viscosity in m²/s, loads in N) and
return N·m; the conversion happens once, at the boundary (``_catalogue_moment``).

Not modelled: the catalogue's other bearing types, the 2013+ catalogue's drag formula
(``0.4·V_M·…`` plus a second term in the oil level), the drag loss factor ``V_M`` itself
(read it from SKF's diagram against the oil level ``H/d_m``), seal-constant tables (give
the constants of the seal at hand), starting torque, mixed lubrication corrections beyond
``φ_bl``. docs/losses.md lists the sources of every constant and the ranges of validity.

Examples
--------
>>> m = skf_moment("62", bore=0.040, outside=0.080, radial_load=2000.0, axial_load=0.0,
...                speed=rad_s(1500.0), viscosity=20e-6)
>>> round(m.total * 1e3, 1), round(m.phi_ish, 4), round(m.phi_rs, 4)   # N·mm
(53.1, 0.9733, 0.979)

References
----------
SKF, *Rolling bearings*, catalogue 6000 EN (2005) and PUB BU/P1 10000 EN (2013), chapter
"Friction": "The SKF model for calculating the frictional moment". SKF General Catalogue
(2008), same chapter.
"""
from __future__ import annotations

import math

import numpy as np

from powergraph.errors import ModelError
from powergraph.records import record
from powergraph.units_si import RPM_PER_RAD_S, rad_s  # noqa: F401 (rad_s: the doctest)

__all__ = ["BearingSeries", "SERIES", "Seal", "OilBathDrag", "SKFMoment", "K_RS", "skf_moment",
           "inlet_shear_factor", "replenishment_factor", "sliding_weight"]

#: ``K_rs`` by lubrication method (catalogue): 3e-8 for a low-level oil bath (oil level at
#: most the centre of the lowest rolling element) and oil jet, 6e-8 for grease and oil-air.
K_RS = {"oil_bath": 3e-8, "oil_jet": 3e-8, "grease": 6e-8, "oil_air": 6e-8}

#: ``μ_EHL`` (full-film sliding coefficient) of ball bearings by lubricant (catalogue);
#: cylindrical roller bearings take 0.02 whatever the lubricant.
MU_EHL = {"mineral": 0.05, "synthetic": 0.04, "transmission_fluid": 0.1}
MU_EHL_CYLINDRICAL_ROLLER = 0.02


@record
class BearingSeries:
    """The geometry constants of one bearing series in SKF's model.

    ``kind`` is ``"deep_groove_ball"`` or ``"cylindrical_roller"``; ``R1, R2`` are the
    rolling, ``S1, S2`` the sliding constants (catalogue units, see the module docstring;
    ``R2`` is unused for cylindrical roller bearings); ``K_z`` the bearing-type constant of
    ``φ_rs`` and of the drag.
    """

    kind: str
    series: str
    R1: float
    R2: float
    S1: float
    S2: float
    K_z: float


def _dgbb(series: str, r1: float, s1: float, s2: float) -> BearingSeries:
    return BearingSeries("deep_groove_ball", series, r1, 1.7, s1, s2, 3.1)


def _crb(series: str, r1: float) -> BearingSeries:
    return BearingSeries("cylindrical_roller", series, r1, 0.0, 0.16, 0.0015, 5.1)


#: The series this module knows (docs/losses.md gives each row's source). Cylindrical
#: roller rows are for bearings with a cage (N, NU, NJ, NUP designs).
SERIES = {s.series: s for s in (
    _dgbb("60", 4.1e-7, 3.73e-3, 14.6), _dgbb("62", 3.9e-7, 3.23e-3, 36.5),
    _dgbb("63", 3.7e-7, 2.84e-3, 92.8), _dgbb("64", 3.6e-7, 2.43e-3, 198.0),
    _crb("NU 2", 1.09e-6), _crb("NU 3", 1.09e-6), _crb("NU 4", 1.00e-6))}


@record
class Seal:
    """A contact seal: ``M_seal = K_S1·d_s^β + K_S2`` (catalogue units: ``d_s`` in mm, the
    moment in N·mm, so ``K_S1`` and ``K_S2`` are the catalogue's numbers as printed);
    ``counterface_diameter`` ``d_s`` in m. ``count`` seals (2 for a ``-2RS`` bearing)."""

    K_S1: float
    beta: float
    K_S2: float
    counterface_diameter: float
    count: int = 1


@record
class OilBathDrag:
    """Drag of a bearing running in an oil bath (the 2005 catalogue's form).

    ``loss_factor`` ``V_M`` is read from SKF's diagram against the oil level ``H/d_m``;
    ``width`` ``B`` (m) and ``K_L`` are needed by roller bearings (``K_L`` 0.65 for
    cylindrical roller bearings); ``rows`` ``i_rw`` is the number of ball rows.
    """

    loss_factor: float
    width: float | None = None
    K_L: float = 0.65
    rows: int = 1


@record(eq=False)
class SKFMoment:
    """The frictional moment of a bearing and its components, N·m (floats, or arrays of the
    broadcast shape of the loads, speed and viscosity). ``rolling`` includes ``φ_ish·φ_rs``."""

    rolling: float | np.ndarray
    sliding: float | np.ndarray
    seal: float | np.ndarray
    drag: float | np.ndarray
    total: float | np.ndarray
    phi_ish: float | np.ndarray
    phi_rs: float | np.ndarray
    phi_bl: float | np.ndarray
    mu_sl: float | np.ndarray


def inlet_shear_factor(n, d_m, nu):
    """``φ_ish = 1/(1 + 1.84e-9·(n·d_m)^1.28·ν^0.64)``, catalogue units (r/min, mm, mm²/s).

    >>> inlet_shear_factor(0.0, 60.0, 20.0)
    1.0
    """
    return 1.0 / (1.0 + 1.84e-9 * (n * d_m) ** 1.28 * nu ** 0.64)


def replenishment_factor(n, nu, d, D, K_z, K_rs):
    """``φ_rs = exp(−K_rs·ν·n·(d + D)·sqrt(K_z/(2(D − d))))``, catalogue units.

    >>> float(replenishment_factor(0.0, 20.0, 40.0, 80.0, 3.1, 3e-8))
    1.0
    """
    return np.exp(-K_rs * nu * n * (d + D) * math.sqrt(K_z / (2.0 * (D - d))))


def sliding_weight(n, nu, d_m):
    """``φ_bl = exp(−2.6e-8·(n·ν)^1.4·d_m)``, catalogue units: 1 at rest (boundary
    lubrication), → 0 at full film.

    >>> float(sliding_weight(0.0, 20.0, 60.0))
    1.0
    """
    return np.exp(-2.6e-8 * (n * nu) ** 1.4 * d_m)


def _load_terms(s: BearingSeries, d_m: float, Fr, Fa, C0):
    """``G_rr`` and ``G_sl`` (catalogue units) of the series at the loads."""
    if s.kind == "cylindrical_roller":
        return s.R1 * d_m ** 2.41 * Fr ** 0.31, s.S1 * d_m ** 0.9 * Fa + s.S2 * d_m * Fr
    axial = Fa > 0.0
    if np.any(axial) and C0 is None:
        raise ModelError("a deep groove ball bearing with an axial load needs its basic static "
                         "load rating (static_load_rating, N) for the contact angle α_F")
    if C0 is not None and not (math.isfinite(C0) and C0 > 0.0):
        raise ModelError(f"static_load_rating must be a finite number > 0 (N), got {C0!r}")
    ratio = np.where(axial, Fa, 1.0) / (C0 if C0 is not None else 1.0)
    sin_af = np.sin(np.radians(24.6 * ratio ** 0.24))
    g_rr = np.where(axial, s.R1 * d_m ** 1.96 * (Fr + s.R2 / sin_af * Fa) ** 0.54,
                    s.R1 * d_m ** 1.96 * Fr ** 0.54)
    g_sl = np.where(axial, s.S1 * d_m ** -0.145 * (Fr ** 5 + s.S2 * d_m ** 1.5 / sin_af * Fa ** 4)
                    ** (1.0 / 3.0), s.S1 * d_m ** -0.26 * Fr ** (5.0 / 3.0))
    return g_rr, g_sl


def _catalogue_moment(s: BearingSeries, d: float, D: float, Fr, Fa, n, nu, K_rs: float,
                      C0, mu_bl: float, mu_ehl: float):
    """Rolling (with φ_ish·φ_rs) and sliding moments, N·mm, in catalogue units (mm, N,
    r/min, mm²/s), and the factors."""
    d_m = 0.5 * (d + D)
    g_rr, g_sl = _load_terms(s, d_m, Fr, Fa, C0)
    phi_ish = inlet_shear_factor(n, d_m, nu)
    phi_rs = replenishment_factor(n, nu, d, D, s.K_z, K_rs)
    phi_bl = sliding_weight(n, nu, d_m)
    mu_sl = phi_bl * mu_bl + (1.0 - phi_bl) * mu_ehl
    return phi_ish * phi_rs * g_rr * (nu * n) ** 0.6, g_sl * mu_sl, phi_ish, phi_rs, phi_bl, mu_sl


def _drag_nmm(s: BearingSeries, d: float, D: float, n, drag: OilBathDrag):
    """``M_drag``, N·mm, catalogue units (d, D mm; n r/min)."""
    d_m = 0.5 * (d + D)
    shape = s.K_z * (d + D) / (D - d) * 1e-12
    if s.kind == "deep_groove_ball":
        return drag.loss_factor * drag.rows * shape * d_m ** 5 * n ** 2
    if drag.width is None or not drag.width > 0:
        raise ModelError("the drag of a roller bearing needs its width B (m), got "
                         f"{drag.width!r}")
    return 10.0 * drag.loss_factor * drag.K_L * shape * (drag.width * 1e3) * d_m ** 4 * n ** 2


def _series(series: str | BearingSeries) -> BearingSeries:
    if isinstance(series, BearingSeries):
        return series
    try:
        return SERIES[series]
    except KeyError:
        raise ModelError(f"unknown bearing series {series!r}; known: "
                         f"{', '.join(sorted(SERIES))} (or pass a BearingSeries)") from None


def _out(x):
    return float(x) if np.ndim(x) == 0 else x


def skf_moment(series: str | BearingSeries, bore: float, outside: float, radial_load,
               axial_load, speed, viscosity, *, lubrication: str = "oil_bath",
               static_load_rating: float | None = None, mu_bl: float = 0.15,
               lubricant: str = "mineral", mu_ehl: float | None = None,
               seal: Seal | None = None, drag: OilBathDrag | None = None) -> SKFMoment:
    """Frictional moment of a rolling bearing by SKF's four-component model, N·m.

    Parameters
    ----------
    series : str or BearingSeries
        A key of :data:`SERIES` (``"62"``, ``"NU 2"``, …) or the constants of another series.
    bore, outside : float
        ``d`` and ``D``, m.
    radial_load, axial_load : float or array
        ``F_r``, ``F_a``, N (magnitudes; broadcast with ``speed`` and ``viscosity``).
    speed : float or array
        Speed of the rotating ring relative to the other, rad/s (magnitude).
    viscosity : float or array
        Kinematic viscosity of the oil (or the grease's base oil) at its working
        temperature, m²/s (20 mm²/s = 20e-6 m²/s).
    lubrication : str
        A key of :data:`K_RS`: ``"oil_bath"`` (low level), ``"oil_jet"``, ``"grease"``,
        ``"oil_air"``.
    static_load_rating : float, optional
        ``C_0``, N: needed by a deep groove ball bearing with an axial load.
    mu_bl : float
        Boundary-lubrication sliding coefficient (catalogue: "generally ≈ 0.15").
    lubricant, mu_ehl
        ``μ_EHL``: by default 0.02 for cylindrical roller bearings, else from
        :data:`MU_EHL` by ``lubricant``.
    seal : Seal, optional
    drag : OilBathDrag, optional
        Without it ``M_drag`` is 0 (grease, oil-air, oil jet, or a drag not modelled).

    Examples
    --------
    >>> m = skf_moment("NU 2", 0.040, 0.080, radial_load=np.array([2000.0, 8000.0]),
    ...                axial_load=0.0, speed=rad_s(1500.0), viscosity=20e-6)
    >>> (m.total * 1e3).round(1).tolist()        # N·mm
    [106.9, 176.4]
    """
    s = _series(series)
    if lubrication not in K_RS:
        raise ModelError(f"unknown lubrication {lubrication!r}; known: {', '.join(K_RS)}")
    if not (math.isfinite(bore) and math.isfinite(outside) and 0.0 < bore < outside):
        raise ModelError(f"need 0 < bore < outside diameter, got {bore!r} and {outside!r}")
    if mu_ehl is None:
        if s.kind == "cylindrical_roller":
            mu_ehl = MU_EHL_CYLINDRICAL_ROLLER
        elif lubricant in MU_EHL:
            mu_ehl = MU_EHL[lubricant]
        else:
            raise ModelError(f"unknown lubricant {lubricant!r}; known: {', '.join(MU_EHL)}")
    d, D = bore * 1e3, outside * 1e3                                  # mm
    Fr, Fa, n, nu = np.broadcast_arrays(np.abs(np.asarray(radial_load, float)),
                                        np.abs(np.asarray(axial_load, float)),
                                        np.abs(np.asarray(speed, float)) * RPM_PER_RAD_S,
                                        np.asarray(viscosity, float) * 1e6)   # r/min, mm²/s
    if np.any(nu <= 0.0) or not np.all(np.isfinite(nu)):
        raise ModelError("viscosity must be finite and > 0 (m²/s)")
    rolling, sliding, phi_ish, phi_rs, phi_bl, mu_sl = _catalogue_moment(
        s, d, D, Fr, Fa, n, nu, K_RS[lubrication], static_load_rating, mu_bl, mu_ehl)
    seal_nmm = np.zeros_like(n)
    if seal is not None:
        ds = seal.counterface_diameter * 1e3
        seal_nmm = seal_nmm + seal.count * (seal.K_S1 * ds ** seal.beta + seal.K_S2)
    drag_nmm = np.zeros_like(n) if drag is None else _drag_nmm(s, d, D, n, drag)
    parts = [x * 1e-3 for x in (rolling, sliding, seal_nmm, drag_nmm)]       # N·m
    return SKFMoment(*map(_out, parts), _out(sum(parts)), *map(_out, (phi_ish, phi_rs, phi_bl,
                                                                      mu_sl)))
