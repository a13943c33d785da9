"""A wide leaf's anticlastic (plate) stiffening: the bending stiffness of a bent strip
between the beam's E I (free anticlastic curvature) and the plate's E I / (1 - nu^2)
(anticlastic curvature suppressed), governed by Searle's parameter beta = w^2 / (R t)
(G. F. C. Searle, Experimental Elasticity, Cambridge 1908; D. G. Ashwell, "The anticlastic
curvature of rectangular beams and plates", J. Royal Aeronautical Society 54 (1950)
708-715).

A strip of width w and thickness t bent to a radius R along its length curls across its
width (anticlastic curvature nu / R) only where the membrane stresses of that curl are
small: the curl is a beam on an elastic foundation across the width, of wavenumber
lambda = (3 (1 - nu^2))^(1/4) / sqrt(R t). With eta = lambda w = (3 (1 - nu^2))^(1/4)
sqrt(beta) the effective stiffness is

    E I_eff / (E I) = (1 - nu^2 phi(eta)) / (1 - nu^2),
    phi(eta) = (2 / eta) (cosh eta - cos eta) / (sinh eta + sin eta),

1 at eta -> 0 (a narrow strip or a small curvature: the beam) and 1 / (1 - nu^2) at
eta -> infinity (the plate). tests/studies/spatial/test_plate_action.py checks it against
the strip's energy minimised numerically. The rule is the same for every leaf; at rest
(R infinite) it is the beam's E I. It leaves out the roots' clamping of the anticlastic
curl (a boundary layer about a width long at each root, stiffer there).
"""
import math

import numpy as np


def searle_parameter(width: float, thickness: float, curvature: float) -> float:
    """beta = w^2 |kappa| / t (-): ``width``, ``thickness`` (m), ``curvature`` 1/R (1/m)."""
    return width * width * abs(curvature) / thickness


def plate_factor(width: float, thickness: float, nu: float, curvature: float) -> float:
    """E I_eff / (E I) (-) of a leaf of ``width`` and ``thickness`` (m) bent to
    ``curvature`` (1/m) about its width, Poisson's ratio ``nu`` (see the module)."""
    if not (width > 0 and thickness > 0 and math.isfinite(curvature)):
        raise ValueError(f"plate_factor: width {width!r} and thickness {thickness!r} must be "
                         f"> 0 (m), curvature {curvature!r} finite (1/m)")
    if not -1.0 < nu < 0.5:
        raise ValueError(f"plate_factor: Poisson's ratio {nu!r} must be in (-1, 0.5)")
    eta = (3.0 * (1.0 - nu * nu)) ** 0.25 * math.sqrt(searle_parameter(width, thickness,
                                                                      curvature))
    if eta < 1e-3:
        phi = 1.0 - eta ** 4 / 180.0  # the series: the ratio below is 0/0 at eta = 0
    elif eta > 30.0:
        phi = 2.0 / eta  # cosh and sinh overflow beyond; their ratio is 1 to 1e-26
    else:
        phi = 2.0 / eta * (np.cosh(eta) - np.cos(eta)) / (np.sinh(eta) + np.sin(eta))
    return float((1.0 - nu * nu * phi) / (1.0 - nu * nu))
