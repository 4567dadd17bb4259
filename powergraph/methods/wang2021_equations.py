"""Eqs. (8)–(15) of Wang (2021) as plain formulas in β, α, P, η1 and η2.

``β = P/(P − V)`` (Eq. 8), ``α = (P + U)/(P − V)`` (Eq. 12), ``L1 = P(1 − η1)`` (Eq. 13),
``L2 = (P + U − L1)(1 − η2)`` (Eq. 14), ``η = (P − L1 − L2)/P`` (Eq. 15).
:func:`powergraph.methods.wang2021.paper_equations` fills β and α from a model's speeds.
"""
from __future__ import annotations

from powergraph.records import record


@record
class PaperEquations:
    """Eqs. (8)–(15) of Wang (2021) for given ratios, input power and mesh efficiencies.

    Examples
    --------
    >>> eq = PaperEquations(beta=39.0, alpha=40.0, input_power=2270.0, eta1=0.94, eta2=0.94)
    >>> round(eq.split_power, 4), round(eq.paper_virtual_power, 5), round(eq.efficiency, 6)
    (2211.7949, 58.20513, 0.882062)
    """

    beta: float
    alpha: float
    input_power: float
    eta1: float
    eta2: float

    @property
    def split_power(self) -> float:
        """V from ``β = P/(P − V)`` (Eqs. 8–9)."""
        return self.input_power * (1.0 - 1.0 / self.beta)

    @property
    def paper_virtual_power(self) -> float:
        """U from ``α = (P + U)/(P − V)`` (Eq. 12)."""
        return self.alpha * (self.input_power - self.split_power) - self.input_power

    @property
    def first_loss(self) -> float:
        """L1 = P(1 − η1) (Eq. 13)."""
        return self.input_power * (1.0 - self.eta1)

    @property
    def cycloid_power(self) -> float:
        """P + U − L1: the power Eq. (14) applies η2 to."""
        return self.input_power + self.paper_virtual_power - self.first_loss

    @property
    def cycloid_loss(self) -> float:
        """L2 = (P + U − L1)(1 − η2) (Eq. 14)."""
        return self.cycloid_power * (1.0 - self.eta2)

    @property
    def efficiency(self) -> float:
        """η = (P − L1 − L2)/P (Eq. 15)."""
        return 1.0 - (self.first_loss + self.cycloid_loss) / self.input_power

    def to_dict(self) -> dict[str, float]:
        return {"beta": self.beta, "alpha": self.alpha, "input_power": self.input_power,
                "eta1": self.eta1, "eta2": self.eta2, "split_power": self.split_power,
                "virtual_power": self.paper_virtual_power, "losses": [self.first_loss,
                                                                self.cycloid_loss],
                "efficiency": self.efficiency}
