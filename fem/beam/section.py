"""The beam cross-section, one for the planar and the spatial model, and the rectangle's
torsion and taper formulas.

    Section.rect(10e-3, 0.5e-3)                       # width (out of plane) x thickness, m
    Section.rect(10e-3, 0.5e-3, 0.8e-3)               # tapered linearly along the element
    Section(A=1e-6, Iz=2e-13, depth_y=1e-3)            # general; a planar model needs no Iy, J

Local axes: x along the element, y in a planar mechanism's plane, z out of it (the planar
model bends about z: Iz, shear area Ay).
"""
from dataclasses import dataclass, replace
from functools import cached_property
import math

import numpy as np

from ..checks import positive

KAPPA = 5.0 / 6.0  # a rectangle's shear coefficient (shear area kappa A)


def rect_torsion_constant(a, b):
    """Saint-Venant torsion constant J (m^4) of a x b rectangles (arrays broadcast): the
    series solution for rectangular bars (Timoshenko & Goodier, Theory of Elasticity, 3rd
    ed., 1970), 20 odd terms."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    a, b = np.maximum(a, b), np.minimum(a, b)
    n = np.arange(1, 40, 2).reshape((-1,) + (1,) * a.ndim)
    series = np.sum(np.tanh(n * np.pi * a / (2 * b)) / n**5, axis=0)
    J = a * b**3 / 3.0 * (1.0 - 192.0 / np.pi**5 * (b / a) * series)
    return float(J) if J.ndim == 0 else J


def rect_torsion_shear(a, b):
    """Largest shear stress per unit torque (1/m^3) of a x b rectangles under Saint-Venant
    torsion, at the middle of the long sides: tau_max = G theta' t (1 - 8 / pi^2 sum_{n odd}
    1 / (n^2 cosh(n pi a / (2 t)))), t the short side, theta' = T / (G J) (Timoshenko &
    Goodier, Theory of Elasticity, 3rd ed., 1970, Sec. 109), 20 odd terms."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    a, t = np.maximum(a, b), np.minimum(a, b)
    n = np.arange(1, 40, 2).reshape((-1,) + (1,) * a.ndim)
    series = np.sum(1.0 / (n**2 * np.cosh(np.minimum(n * np.pi * a / (2 * t), 700.0))), axis=0)
    return t * (1.0 - 8.0 / np.pi**2 * series) / rect_torsion_constant(a, t)


def rect_depth(t0, t1, tm, xi):
    """Depth (m) at fractions xi (k,) of elements with end depths t0, t1 (n_e,) and mid
    depth tm (n_e,; NaN: linear taper): (n_e, k); quadratic through tm."""
    x = np.asarray(xi, dtype=float)[None, :]
    t0, t1, tm = t0[:, None], t1[:, None], tm[:, None]
    quadratic = t0 * (1 - x) * (1 - 2 * x) + 4 * tm * x * (1 - x) + t1 * x * (2 * x - 1)
    return np.where(np.isfinite(tm), quadratic, t0 + (t1 - t0) * x)


def mid_depth(t0: float, t1: float, tm: float) -> float:
    """The depth (m) half-way along a taper (t0, t1, tm) (tm NaN: linear), as rect_depth."""
    return tm if math.isfinite(tm) else t0 + (t1 - t0) * 0.5


@dataclass(frozen=True)
class Section:
    """Cross-section of one element: area ``A`` (m^2), second moments ``Iy`` = int z^2 dA
    and ``Iz`` = int y^2 dA (m^4, about local y and z; the planar model bends with Iz),
    torsion constant ``J`` (m^4; Iy and J may be None for a planar model), shear areas
    ``Ay``, ``Az`` (m^2; None: no shear deformation in that direction; used where the
    model has ``shear``), the outer-fibre depths ``depth_y``, ``depth_z`` (m, fibres at
    +-depth / 2; None: no stress reported), ``taper`` (a rectangle's (depth_y at node 1,
    at node 2, at mid or NaN, depth_z); A, Iy, Iz, J are those at node 1). ``factors``
    (bending, shear, axial, bending_y) multiply E Iz, G Ay, E A and E Iy in the stiffness
    only (a notch's 2-D correction, a root's axial compliance), not the mass or the
    stress; ``mass_factor`` multiplies the mass (0: a root extension inside a body)."""

    A: float
    Iy: float | None = None
    Iz: float | None = None
    J: float | None = None
    Ay: float | None = None
    Az: float | None = None
    taper: tuple | None = None
    depth_y: float | None = None
    depth_z: float | None = None
    factors: tuple = (1.0, 1.0, 1.0, 1.0)
    mass_factor: float = 1.0

    def __post_init__(self):
        positive("A", self.A)
        positive("Iz", self.Iz)
        for name in ("Iy", "J", "Ay", "Az", "depth_y", "depth_z"):
            positive(name, getattr(self, name), allow_none=True)
        if len(self.factors) != 4 or not all(f > 0 for f in self.factors):
            raise ValueError(f"Section: factors = {self.factors!r} must be four positive "
                             "numbers (bending, shear, axial, bending_y)")
        if not (isinstance(self.mass_factor, (int, float)) and 0 <= self.mass_factor < math.inf):
            raise ValueError(f"mass_factor = {self.mass_factor!r} must be a finite number >= 0")

    @classmethod
    def rect(cls, width: float, thickness: float, thickness_end: float | None = None,
             thickness_mid: float | None = None):
        """A rectangular section, optionally tapered along the element.

        Parameters
        ----------
        width : float
            The side along local z (m): out of a planar mechanism's plane.
        thickness : float
            The side along local y (m): in the plane, at the first node.
        thickness_end : float, optional
            The thickness at the second node (m): a linear taper.
        thickness_mid : float, optional
            The thickness at mid-length (m): a quadratic taper through it.

        Returns
        -------
        Section
            A, Iy, Iz, J (Saint-Venant's, of the rectangle) at the first node; shear areas
            5/6 of the mid-length section; depth_y = thickness, depth_z = width.
        """
        b, h = positive("thickness", thickness), positive("width", width)
        end = positive("thickness_end", thickness_end, allow_none=True)
        mid = positive("thickness_mid", thickness_mid, allow_none=True)
        taper = None
        if end is not None or mid is not None:
            end = b if end is None else end
            taper = (b, end, math.nan if mid is None else mid, h)
        k = KAPPA * (b if taper is None else mid_depth(*taper[:3])) * h
        return cls(A=b * h, Iy=b * h**3 / 12.0, Iz=h * b**3 / 12.0,
                   J=float(rect_torsion_constant(b, h)), Ay=k, Az=k, taper=taper,
                   depth_y=b, depth_z=h)

    @property
    def Ip(self) -> float:
        """Polar second moment Iy + Iz (m^4): the section's torsional inertia per rho."""
        return self.Iy + self.Iz

    def with_factors(self, bending=1.0, shear=1.0, axial=1.0, bending_y=1.0) -> "Section":
        """This section with its stiffness factors multiplied by these."""
        f = self.factors
        return replace(self, factors=(f[0] * bending, f[1] * shear, f[2] * axial,
                                       f[3] * bending_y))

    @cached_property
    def planar_row(self) -> tuple:
        """The planar model's row (PLANAR_COLUMNS): (tapered, w, t0, t1, A, Iz, c, kappa,
        t_mid, bending, axial, mass), kappa the shear area Ay over the mid-length area times
        the shear factor (inf: no shear area), NaN for what does not apply."""
        nan, f = math.nan, self.factors
        if self.taper is not None:
            t0, t1, tm, w = self.taper
            kappa = math.inf if self.Ay is None else f[1] * (self.Ay / (w * mid_depth(t0, t1, tm)))
            return (1.0, w, t0, t1, nan, nan, nan, kappa, tm, f[0], f[2], self.mass_factor)
        kappa = math.inf if self.Ay is None else f[1] * (self.Ay / self.A)
        c = nan if self.depth_y is None else self.depth_y / 2.0
        return (0.0, nan, nan, nan, self.A, self.Iz, c, kappa, nan, f[0], f[2],
                self.mass_factor)


PLANAR_COLUMNS = 12
BENDING_FACTOR, AXIAL_FACTOR, MASS_FACTOR = 9, 10, 11  # their columns in planar_row


def rect_sections(width: float, t0, t1, tm) -> list:
    """[Section.rect(width, t0[i], t1[i], tm[i])] for thickness arrays (m) already checked
    finite and > 0, built at once (one torsion series for all): the same numbers."""
    width = positive("width", width)
    t0, t1, tm = (np.asarray(a, dtype=float) for a in (t0, t1, tm))
    J = np.atleast_1d(rect_torsion_constant(t0, width))
    mid = np.where(np.isfinite(tm), tm, t0 + (t1 - t0) * 0.5)
    out = []
    for a, b, c, j, m in zip(t0.tolist(), t1.tolist(), tm.tolist(), J.tolist(), mid.tolist()):
        sec = object.__new__(Section)  # a frozen dataclass: its fields set as __init__ would
        k = KAPPA * m * width
        sec.__dict__.update(A=a * width, Iy=a * width**3 / 12.0, Iz=width * a**3 / 12.0, J=j,
                            Ay=k, Az=k, taper=(a, b, c, width), depth_y=a, depth_z=width,
                            factors=(1.0, 1.0, 1.0, 1.0), mass_factor=1.0)
        out.append(sec)
    return out
