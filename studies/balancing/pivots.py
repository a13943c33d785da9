"""Flexure pivots as the torsion springs of Table IV, sized by beam theory.

A cross-spring (cross-strip) pivot of n_leaves identical leaves of length L, thickness t and
width w, with the leaves crossing at their midpoints and loaded by a pure moment, has to first
order the rotational stiffness of n leaves in pure bending (Wittrick, "The theory of
symmetrical crossed flexure pivots", Aust. J. Sci. Res. A1, 1948; Haringx, Appl. Sci. Res.
A1, 1949; the cross-axis flexural pivot of Howell, Compliant Mechanisms, Wiley 2001):

    K = n E I / L,  I = w t^3 / 12                          (N m/rad)

and each leaf, bent to a uniform curvature theta / L, carries the surface stress

    sigma = E (t / 2) theta / L = E t theta / (2 L)          (Pa)

Both hold for small axial load and moderate rotation (tens of degrees); the lead's FEM will
check them. A transmission of ratio N between motor and pivot (pivot angle = motor angle / N)
divides the rotation the leaves see by N and multiplies the stiffness they must have by N^2.
"""
from dataclasses import dataclass

import numpy as np

from ...fem import Material, checks


@dataclass(frozen=True)
class LeafPivot:
    """What a pivot of leaves has, however they are loaded: leaf length L, thickness t, width
    w (m), its material, transmission_ratio N (motor angle / pivot angle), theta_max (rad,
    largest pivot rotation), stiffness (N m/rad, at the pivot), max_stress (Pa) and
    safety_factor = yield / max_stress."""

    L: float
    t: float
    w: float
    material: Material
    transmission_ratio: float
    theta_max: float
    stiffness: float
    max_stress: float
    safety_factor: float

    @property
    def stiffness_at_motor(self) -> float:
        """Rotational stiffness seen by the motor, K / N^2 (N m/rad)."""
        return self.stiffness / self.transmission_ratio**2

    def row(self, **own) -> dict:
        """The pivot as a table row, ``own`` (its kind's columns) after its sizes."""
        return {"L_m": self.L, "t_m": self.t, "w_m": self.w, **own,
                "material": self.material.name, "transmission_ratio": self.transmission_ratio,
                "theta_max_rad": self.theta_max, "stiffness_Nm_per_rad": self.stiffness,
                "stiffness_at_motor_Nm_per_rad": self.stiffness_at_motor,
                "max_stress_Pa": self.max_stress, "safety_factor": self.safety_factor}


@dataclass(frozen=True)
class FlexurePivot(LeafPivot):
    """A cross-spring pivot of ``n_leaves`` leaves (a :class:`LeafPivot`)."""

    n_leaves: int

    def __post_init__(self):
        for attr in ("L", "t", "w", "transmission_ratio", "stiffness", "max_stress",
                     "safety_factor"):
            checks.positive(attr, getattr(self, attr), owner="FlexurePivot")
        if self.theta_max < 0.0:
            raise ValueError(f"theta_max = {self.theta_max} must be >= 0")
        if int(self.n_leaves) != self.n_leaves or self.n_leaves < 1:
            raise ValueError(f"n_leaves = {self.n_leaves} must be an integer >= 1")
        if self.t >= self.L:
            raise ValueError(f"t = {self.t} must be < L = {self.L} (a leaf, not a block)")

    def as_dict(self) -> dict:
        return self.row(n_leaves=self.n_leaves)


def leaf_bending_stress(E, t, theta, L):
    """Surface stress (Pa) of a leaf bent by a pure moment through theta (rad): E t theta/(2L)."""
    return E * t * np.abs(theta) / (2.0 * L)


def cross_spring_stiffness(E, w, t, L, n_leaves):
    """Rotational stiffness (N m/rad) of n leaves in pure bending: n E w t^3 / (12 L)."""
    return n_leaves * E * w * t**3 / (12.0 * L)


def pivot_stiffness_beam_theory(pivot: FlexurePivot) -> float:
    """Beam-theory stiffness (N m/rad) of the pivot's leaves, at the pivot (Wittrick 1948)."""
    return cross_spring_stiffness(pivot.material.E, pivot.w, pivot.t, pivot.L, pivot.n_leaves)


def size_flexure_pivot(K, theta_range_rad, material: Material, safety_factor=2.0,
                       n_leaves=2, transmission_ratio=1.0, max_width=0.1,
                       lengths=None, thickness_step=1e-5) -> FlexurePivot:
    """Size a cross-spring pivot of motor-side stiffness K over a motor rotation range.

    K: required stiffness at the motor (N m/rad, > 0); theta_range_rad: (low, high) motor
    rotation (rad) from the pivot's unstressed angle over the workspace; transmission_ratio N:
    pivot angle = motor angle / N. For each candidate leaf length L (m, shortest first) the
    thickness is the largest multiple of thickness_step (m) keeping E t theta / (2 L) below
    yield / safety_factor, and the width follows from n E w t^3 / (12 L) = N^2 K. The first L
    whose width stays <= max_width (m) and >= t is returned. Raises ValueError when K <= 0
    (a plain flexure has positive stiffness) or when no length fits.
    """
    if not K > 0.0:
        raise ValueError(f"K = {K} N m/rad must be > 0: a plain flexure pivot cannot supply a "
                         "negative stiffness")
    theta_max = pivot_rotation(theta_range_rad, transmission_ratio, safety_factor)
    k_pivot = K * transmission_ratio**2
    allowable = material.yield_strength / safety_factor
    if lengths is None:
        lengths = np.arange(0.02, 0.3001, 0.005)
    for L in lengths:
        t = 2.0 * L * allowable / (material.E * theta_max)
        t = np.floor(t / thickness_step) * thickness_step
        if t <= 0.0:
            continue
        w = 12.0 * k_pivot * L / (n_leaves * material.E * t**3)
        if t <= w <= max_width:
            stress = leaf_bending_stress(material.E, t, theta_max, L)
            return FlexurePivot(L=float(L), t=float(t), w=float(w), n_leaves=n_leaves,
                                material=material, transmission_ratio=float(transmission_ratio),
                                theta_max=theta_max, stiffness=float(k_pivot),
                                max_stress=float(stress),
                                safety_factor=float(material.yield_strength / stress))
    raise no_leaf_fits("cross-spring pivot", lengths, max_width, K, theta_max,
                       f"{material.name}, safety factor {safety_factor}, N = {transmission_ratio}")


def pivot_rotation(theta_range_rad, transmission_ratio, safety_factor) -> float:
    """The largest pivot rotation theta_max (rad): max |theta_range_rad| (motor, rad) / N,
    once safety_factor >= 1 and the transmission ratio N > 0 are checked."""
    if not safety_factor >= 1.0:
        raise ValueError(f"safety_factor = {safety_factor} must be >= 1")
    checks.positive("transmission_ratio", transmission_ratio)
    theta_max = float(np.max(np.abs(theta_range_rad))) / transmission_ratio
    if not theta_max > 0.0:
        raise ValueError(f"theta_range_rad = {theta_range_rad} must not be all zero")
    return theta_max


def no_leaf_fits(what: str, lengths, max_width, K, theta_max, given: str) -> ValueError:
    """The refusal of a pivot search: no ``what`` over ``lengths`` (m) within ``max_width``
    (m) gives K (N m/rad) over theta_max (rad); ``given``: the material and factors."""
    return ValueError(f"no {what} with L in [{lengths[0]:.3f}, {lengths[-1]:.3f}] m and width "
                      f"<= max_width = {max_width} m gives K = {K} N m/rad over theta_max = "
                      f"{theta_max:.3f} rad ({given})")


def negative_stiffness_preload(K, lever_arm):
    """Compressive force (N) of a constant-force spring whose line of action passes through
    the motor axis at the neutral angle, at lever_arm (m) on the arm, giving K < 0 (N m/rad).

    For small rotation phi the force F at radius r pushing towards the axis produces the
    destabilising torque F r sin(phi) ~ F r phi, i.e. a stiffness -F r; F = -K / r.
    """
    if not K < 0.0:
        raise ValueError(f"K = {K} N m/rad must be < 0 for a negative-stiffness element")
    if not lever_arm > 0.0:
        raise ValueError(f"lever_arm = {lever_arm} m must be > 0")
    return -K / lever_arm
