"""Vlasov's warping restraint on the torsion of a spatial beam model's leaves: a rectangular
leaf clamped in blocks at both ends cannot warp there, and is stiffer in torsion than
Saint-Venant's G J (docs/beam.md, "The spatial beam")."""
import numpy as np

from ..fem.beam.spatial import Beam3DModel, rect_torsion_constant


def vlasov_factor(length: float, depth: float, width: float, nu: float) -> float:
    """Torsional stiffness of a rectangular depth x width (m, depth << width) bar of
    ``length`` (m) with warping restrained at both ends over its Saint-Venant one (Vlasov):
    1 / (1 - 2 tanh(lambda L / 2) / (lambda L)), lambda^2 = G J / (E Gamma), Gamma =
    width^3 depth^3 / 144."""
    lam = np.sqrt(rect_torsion_constant(depth, width) / (2 * (1 + nu))
                  / (width**3 * depth**3 / 144))
    x = lam * length
    return float(1 / (1 - 2 * np.tanh(x / 2) / x))


class TorsionScaled(Beam3DModel):
    """A beam model whose elements' J are multiplied by ``factors`` (n_elements,)."""

    def __init__(self, base: Beam3DModel, factors):
        super().__init__(base.nodes, base.elements, base.sections, base.material,
                         rigid_links=base.rigid_links, point_masses=base.point_masses,
                         groups=base.groups, shear=base.shear)
        self.j_factors = np.asarray(factors, dtype=float)

    def section_at(self, xi) -> dict:
        out = super().section_at(xi)
        out["J"] = out["J"] * self.j_factors[:, None]
        return out
