"""What a leaf's roots do to its beam, as general rules for every leaf of a spatial
mechanism (studies/spatial/beam_model.py); the beam elements themselves end rigidly at the
bodies' faces.

- **Torsion with restrained warping.** A leaf twisted between two bodies cannot warp at its
  roots: near each root the twist bends the strip's two halves across its width (the
  secondary warping of a thin rectangle, warping constant Gamma = w^3 t^3 / 144: W. D.
  Pilkey, *Analysis and Design of Elastic Beams*, Wiley 2002, table of warping constants;
  V. Z. Vlasov, *Thin-Walled Elastic Beams*, 1961). Non-uniform torsion of a bar of length
  L restrained at both ends under an end torque T (Timoshenko and Gere, *Theory of Elastic
  Stability*, 2nd ed. 1961, ch. 5) twists by phi = T / (G J) (L - (2 / lambda) tanh(lambda
  L / 2)), lambda = sqrt(G J / (E Gamma)): the leaf's G J is multiplied by
  1 / (1 - 2 tanh(lambda L / 2) / (lambda L)) (:func:`warping_factor`). For the
  Saint-Venant J = w t^3 / 3 (1 - 0.63 t / w) lambda is about 4.2 / w: the factor is 1.19
  for the examples' w / L = 1/3, 1.005 for a leaf 100 times longer than wide.
- **The roots' axial compliance.** An axial force spreads from the leaf into the body over a
  few thicknesses: each root adds alpha(H / t) / (E w) of axial compliance, H the body's
  depth along the leaf beyond the root (:func:`block_depth`) and alpha the planar beam
  model's plane-stress fit (reduced/layout.axial_root_compliance: 0.38 t / H + 0.67 ln(H /
  t) - 0.45 (1 - t / H), docs/beam.md); the leaf's E A is multiplied by
  (L / t) / (L / t + alpha_1 + alpha_2) (:func:`axial_factor`). Its bending root
  compliance (the planar model's root extension, 0.38 t per root) is left out: a leaf as
  wide as the examples' (w = 10 t) meshed as a solid is not softened by it (the
  planar/spatial consistency test, docs/spatial.md: the blocks' clamping of the leaf's
  anticlastic curl stiffens its roots by as much).
Wires get neither (a round root's spreading is three-dimensional: not fitted here).
SI units.
"""
import math

import numpy as np

from ...reduced.layout import axial_root_compliance


def warping_factor(width: float, thickness: float, length: float, nu: float,
                   J: float) -> float:
    """G J_eff / (G J) (-) of a leaf of ``width``, ``thickness`` and free ``length`` (m),
    Poisson's ratio ``nu``, Saint-Venant constant ``J`` (m^4), its warping restrained at
    both roots (see the module)."""
    gamma = width ** 3 * thickness ** 3 / 144.0
    x = math.sqrt(J / (2.0 * (1.0 + nu) * gamma)) * length  # lambda L, G / E = 1 / (2 (1 + nu))
    return 1.0 / (1.0 - 2.0 * math.tanh(x / 2.0) / x)


def block_depth(mechanism, index: int, end: int) -> float:
    """H (m): how deep the body at end ``end`` (0: from, 1: to) of flexure ``index`` is
    along the flexure's axis, from its free span's end on (bisection, to 1e-9 of the
    mechanism's size; at most the mechanism's size)."""
    f, span = mechanism.flexures[index], mechanism.span(index)
    body = mechanism.body(f.between[end])
    root = span.a if end == 0 else span.b
    e = span.d if end == 1 else -span.d
    lo, hi, tol = 0.0, mechanism.size, mechanism.tol
    if body.contains(root + hi * e, tol):
        return hi
    while hi - lo > tol:
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if body.contains(root + mid * e, tol) else (lo, mid)
    return lo


def axial_factor(thickness: float, length: float, depths) -> float:
    """E A_eff / (E A) (-) of a leaf of ``thickness`` and free ``length`` (m) whose roots
    enter bodies ``depths`` = (H_1, H_2) (m) deep (see the module)."""
    slender = length / thickness
    return slender / (slender + sum(axial_root_compliance(h, thickness) for h in depths))
