"""Length-scale control by the robust formulation (Wang, Lazarov, Sigmund 2011, "On
projection methods, convergence and robust formulations in topology optimization", Struct
Multidisc Optim 43:767-784, doi:10.1007/s00158-010-0602-y): one filtered field projected
three times, at the thresholds 1 - eta (eroded: the higher threshold leaves less solid),
0.5 (intermediate, the blueprint) and eta (dilated); the worst of the three designs is
optimised, so every solid member of the blueprint survives in the eroded design and every
void in the dilated one.

The minimum sizes this imposes on the blueprint are those of Qian & Sigmund (2013,
"Topological design of electromechanical actuators with robustness toward over- and
under-etching", CMAME 253:237-251, doi:10.1016/j.cma.2012.08.020) for the linear ("hat")
density filter of radius r: a 0/1 bar of the design field whose filtered peak is just the
eroded threshold eta_e has, at the 0.5 level, the width

    b_solid / r = 2 sqrt(eta_e - 1/2)          for 1/2 <= eta_e <= 3/4
    b_solid / r = 2 (1 - sqrt(1 - eta_e))       for 3/4 <= eta_e <= 1

and the void by symmetry with 1 - eta_d (tests/topopt/test_robust.py derives both branches
by quadrature). In 2-D top88's filter is a cone; across a straight member it acts as the
cone's projection onto a line, more peaked than the hat, and gives 0.943 r instead of r at
eta_e = 0.75. :func:`member_ratio` applies the papers' construction (the 0.5-level width of
the bar whose filtered peak is eta_e) to that profile, by quadrature, and :func:`radius_for`
uses it: the radius a minimum size asks for is that of the filter the grid applies."""
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

# the Kreisselmeier-Steinhauser aggregate of the three designs' objectives: at most
# ln(3) / KS_EXPONENT (5.5 %) of the intermediate design's |objective| above the worst
KS_EXPONENT = 20.0
# the dilated design's volume limit is re-derived from the intermediate one this often
VOLUME_UPDATE = 20
DESIGNS = ("eroded", "intermediate", "dilated")


def size_ratio(eta_e: float) -> float:
    """b / r: the blueprint's minimum solid size over the hat filter's radius, for the
    eroded threshold ``eta_e`` in [0.5, 1] (Qian & Sigmund 2013)."""
    if not 0.5 <= eta_e <= 1.0:
        raise ValueError(f"eroded threshold {eta_e!r}: must be in [0.5, 1]")
    if eta_e <= 0.75:
        return float(2.0 * np.sqrt(eta_e - 0.5))
    return float(2.0 * (1.0 - np.sqrt(1.0 - eta_e)))


def cone_across(s: float) -> float:
    """top88's cone 1 - |d| (radius 1) integrated along a straight member: its profile at
    the distance ``s`` (radii) across it."""
    s = abs(s)
    if s >= 1.0:
        return 0.0
    h = np.sqrt(1.0 - s * s)
    log = s * s * np.log((h + 1.0) / s) if s > 0 else 0.0
    return float(h - log)


def bar_width(eta_e: float, kernel=cone_across) -> float:
    """b / r: the 0.5-level width of the filtered 0/1 bar whose filtered peak is ``eta_e``
    (the papers' construction), for a filter of radius 1 whose profile across a member is
    ``kernel``, by quadrature and root finding."""
    from scipy.integrate import quad
    from scipy.optimize import brentq

    norm = quad(kernel, -1.0, 1.0, points=[0.0])[0]

    def filtered(t, a):    # the kernel centred at t over the bar [-a, a]
        return quad(lambda s: kernel(s - t), -a, a, points=[t], limit=200)[0] / norm

    a = brentq(lambda a: filtered(0.0, a) - eta_e, 1e-9, 1.0)
    return 2.0 * brentq(lambda t: filtered(t, a) - 0.5, 0.0, a + 1.0)


@lru_cache(maxsize=16)
def member_ratio(eta_e: float) -> float:
    """b / r of a straight member under the 2-D density filter (top88's cone): the
    minimum solid size over the radius for the eroded threshold ``eta_e`` in (0.5, 1)."""
    if not 0.5 < eta_e < 1.0:
        raise ValueError(f"eroded threshold {eta_e!r}: must be in (0.5, 1)")
    return bar_width(float(eta_e))


@dataclass(frozen=True)
class Robust:
    """The robust formulation with the dilated threshold ``eta`` (the eroded one 1 - eta,
    the intermediate 0.5); ``min_size`` (m): the minimum solid and void size asked for, from
    which the problem file derives the filter radius (0: none asked)."""

    eta: float = 0.25
    min_size: float = 0.0

    def __post_init__(self):
        if not (isinstance(self.eta, (int, float)) and 0.0 < self.eta < 0.5):
            raise ValueError(f"robust.eta = {self.eta!r}: must be in (0, 0.5) (the dilated "
                             "threshold; the eroded one is 1 - eta)")
        if not (isinstance(self.min_size, (int, float)) and self.min_size >= 0):
            raise ValueError(f"robust.min_hinge = {self.min_size!r}: must be a length >= 0 (m)")

    @property
    def thresholds(self) -> tuple:
        """(eroded, intermediate, dilated) thresholds."""
        return (1.0 - self.eta, 0.5, self.eta)

    def minimum_sizes(self, radius: float, element: float) -> dict:
        """The blueprint's minimum solid and void sizes (m) across straight members for the
        2-D density filter of ``radius`` elements of ``element`` m (:func:`member_ratio`;
        equal here: the thresholds are symmetric about 0.5)."""
        b = member_ratio(1.0 - self.eta) * radius * element
        return {"solid": b, "void": b}


def radius_for(min_size: float, element: float, eta: float) -> float:
    """The 2-D density filter's radius (elements) that gives the blueprint's straight
    members the minimum size ``min_size`` (m) with thresholds 1 - eta, 0.5, eta on elements
    of ``element`` m (:func:`member_ratio`)."""
    return min_size / (member_ratio(1.0 - eta) * element)


def aggregate(values, scale: float):
    """(KS, weights, d KS / d scale) of the worst (largest) of ``values``:
    KS = s / k ln sum exp(k v / s), s = ``scale`` > 0; max(v) <= KS <= max(v) + s ln(n) / k."""
    v = np.asarray(values, float)
    k = KS_EXPONENT / scale
    top = float(v.max())
    e = np.exp(k * (v - top))
    ks = top + float(np.log(e.sum())) / k
    weights = e / e.sum()
    return ks, weights, (ks - float(weights @ v)) / scale


def worst(values, grads, sign: float, reference: int = 1):
    """(value, gradient) of the KS aggregate of sign * values (the worst of designs to be
    minimised: sign 1 for the largest, -1 for the smallest), relative to |values[reference]|
    (the intermediate design's), returned in the units and sense of the values."""
    values, grads = np.asarray(values, float), np.asarray(grads, float)
    g = sign * values
    scale = abs(values[reference])
    if scale == 0.0:    # no reference: the plain maximum
        j = int(np.argmax(g))
        return float(values[j]), grads[j]
    ks, w, dscale = aggregate(g, scale)
    dg = w @ (sign * grads) + dscale * np.sign(values[reference]) * grads[reference]
    return sign * ks, sign * dg
