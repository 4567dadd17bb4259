"""Result objects of the volume analysis (frozen, indexed by the model's component ids)."""
from __future__ import annotations

from typing import Any, Mapping

from powergraph.records import record
from powergraph.result import aligned_table, nothing_to_draw
from powergraph.display import Displayed

#: Unit of :func:`power_density`: kilowatt per litre (1 kW/L = 1 W/cm³ = 1e-3 W/mm³).
POWER_DENSITY_UNIT = "kW/L"


@record
class ComponentVolume:
    """Volume of one component (all ``count`` identical parts).

    Attributes
    ----------
    component : str
        The model's component id.
    name : str or None
        The component's name.
    shape : str
        Geometry shape (which formula): ``gear``, ``cycloid_disc``, ...
    equation : str
        The paper's equation number, e.g. ``"(3)"``.
    count : int
        Identical parts in parallel (the n and 2 of Eq. 8).
    unit_mm3 : float
        Volume of one part by the paper's formula, mm³.
    exact_unit_mm3 : float or None
        Volume of one part with the exact generated outline (gears: involute + trochoid;
        cycloid discs: offset epitrochoid) instead of the paper's circle; None otherwise.
    """

    component: str
    name: str | None
    shape: str
    equation: str
    count: int
    unit_mm3: float
    exact_unit_mm3: float | None = None

    @property
    def volume_mm3(self) -> float:
        """Paper's formula × count, mm³."""
        return self.unit_mm3 * self.count

    @property
    def exact_mm3(self) -> float | None:
        """Exact-outline volume × count, mm³ (None when not available)."""
        return None if self.exact_unit_mm3 is None else self.exact_unit_mm3 * self.count

    @property
    def profile_error(self) -> float | None:
        """(paper − exact) / exact: the error of the paper's circle approximation."""
        if self.exact_unit_mm3 is None:
            return None
        return (self.unit_mm3 - self.exact_unit_mm3) / self.exact_unit_mm3

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "shape": self.shape, "equation": self.equation,
                "count": self.count, "unit_volume_mm3": self.unit_mm3,
                "volume_mm3": self.volume_mm3, "exact_profile_mm3": self.exact_mm3,
                "profile_error": self.profile_error}


@record(repr=False)
class VolumeResult(Displayed):
    """Volumes of every component that has a ``geometry`` block, and the total (Eq. 8).

    Attributes
    ----------
    name : str
        The model's name.
    components : Mapping[str, ComponentVolume]
        By component id, in file order.
    """

    name: str
    components: Mapping[str, ComponentVolume]

    def _summary(self) -> str:
        return f"{self.name}: {len(self.components)} parts, {self.total_litres:.4g} L"

    def _records(self) -> list[dict[str, Any]]:
        """One row per component: count and volumes (mm³)."""
        return [{"component": cid, "name": c.name, "shape": c.shape, "count": c.count,
                 "volume_mm3": c.volume_mm3, "exact_mm3": c.exact_mm3}
                for cid, c in self.components.items()]


    @property
    def total_mm3(self) -> float:
        """Eq. (8): the sum of count × unit volume over the components, mm³."""
        return sum(c.volume_mm3 for c in self.components.values())

    @property
    def total_exact_profile_mm3(self) -> float:
        """The total with exact outlines where available (paper's formula elsewhere), mm³."""
        return sum(c.volume_mm3 if c.exact_mm3 is None else c.exact_mm3
                   for c in self.components.values())

    @property
    def total_litres(self) -> float:
        return self.total_mm3 * 1e-6

    def power_density(self, output_power_w: float) -> float:
        """Output power / total volume in kW/L (see :func:`power_density`)."""
        return power_density(output_power_w, self.total_mm3)

    def text_report(self) -> str:
        """Aligned text table: one row per component, then the total."""
        header = ("id", "name", "shape", "eq.", "count", "each mm³", "volume mm³",
                  "exact outline mm³", "circle error")
        rows = [header]
        for cid, part in self.components.items():
            rows.append((cid, part.name or "", part.shape, part.equation, str(part.count),
                         f"{part.unit_mm3:,.1f}", f"{part.volume_mm3:,.1f}",
                         "" if part.exact_mm3 is None else f"{part.exact_mm3:,.1f}",
                         "" if part.profile_error is None
                         else f"{100 * part.profile_error:+.3f} %"))
        rows.append(("", "total (Eq. 8)", "", "", "", "", f"{self.total_mm3:,.1f}",
                     f"{self.total_exact_profile_mm3:,.1f}", ""))
        lines = [f"{self.name}: volume by Pan & Wang (2019), lengths in mm"]
        lines += aligned_table(rows, {4, 5, 6, 7, 8}, rules_after=(0, len(rows) - 2))
        lines.append(f"total: {self.total_mm3:,.1f} mm³ = {self.total_litres:.4f} L")
        if any(part.exact_mm3 is not None for part in self.components.values()):
            lines.append("exact outline: gears and cycloid discs with their generated profile "
                         "(other parts as the paper);")
            lines.append("circle error: (paper − exact) / exact")
        return "\n".join(lines)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Nothing to draw: raises :class:`~powergraph.result.NothingToDrawError`."""
        raise nothing_to_draw(self, "plot pitch_circle_errors(...) for the volume error "
                                    "of the pitch-circle formula")

    def to_dict(self) -> dict[str, Any]:
        """``{components: {id: volume_mm3}, total_mm3, ...}`` plus per-part details."""
        return {"name": self.name,
                "components": {cid: c.volume_mm3 for cid, c in self.components.items()},
                "total_mm3": self.total_mm3,
                "total_exact_profile_mm3": self.total_exact_profile_mm3,
                "parts": {cid: c.to_dict() for cid, c in self.components.items()}}


def power_density(output_power_w: float, total_mm3: float) -> float:
    """Power density = output power / total volume, in kW/L.

    1 kW/L = 1 W/cm³ = 1e-3 W/mm³, so the value is ``output_power_w * 1000 / total_mm3``.

    Examples
    --------
    >>> power_density(2000.0, 1e6)          # 2 kW in one litre
    2.0
    """
    if total_mm3 <= 0:
        raise ValueError(f"total volume must be > 0 mm³, got {total_mm3!r}")
    return output_power_w * 1000.0 / total_mm3
