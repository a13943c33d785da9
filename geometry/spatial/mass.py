"""A spatial body's volume, centroid and second moments, from its boxes, cylinders and
prisms (geometry/spatial/description.py): what the continuum's mesh estimate and the beam
model's rigid nodes take. The parts are summed: where two parts of one body overlap, the
overlap counts twice (an upper bound of the volume). SI units (m, kg)."""
from dataclasses import dataclass

import numpy as np

from ..polygon import moments as polygon_moments
from .description import AXES


@dataclass(frozen=True)
class MassProperties:
    """``volume`` (m^3), ``centroid`` (3,) (m) and ``second_moments`` (3, 3): int (x_i - c_i)
    (x_j - c_j) dV about the centroid (m^5); times a density they are the body's mass and
    inertia (:meth:`mass`, :meth:`inertia`)."""

    volume: float
    centroid: np.ndarray
    second_moments: np.ndarray

    def mass(self, rho: float) -> float:
        """The mass (kg) at density ``rho`` (kg/m^3)."""
        return rho * self.volume

    def inertia(self, rho: float) -> np.ndarray:
        """The inertia tensor (3, 3) about the centroid (kg m^2) at density ``rho``."""
        s = rho * self.second_moments
        return np.trace(s) * np.eye(3) - s


def _box(lo, hi) -> tuple:
    side = np.abs(np.subtract(hi, lo))
    v = float(np.prod(side))
    return v, (np.asarray(lo, float) + np.asarray(hi, float)) / 2, np.diag(v * side ** 2 / 12)


def _cylinder(c) -> tuple:
    axis = np.subtract(c.end, c.start)
    length = float(np.linalg.norm(axis))
    e = axis / length
    r = c.diameter / 2
    v = np.pi * r * r * length
    s = v * length ** 2 / 12 * np.outer(e, e) + v * r * r / 4 * (np.eye(3) - np.outer(e, e))
    return v, (np.asarray(c.start, float) + np.asarray(c.end, float)) / 2, s


def _prism(p) -> tuple:
    k = AXES[p.axis]
    iu, iv = (k + 1) % 3, (k + 2) % 3
    area, (cu, cv), (suu, svv, suv) = polygon_moments([tuple(map(tuple, p.polygon))])
    h = abs(p.span[1] - p.span[0])
    centre = np.zeros(3)
    centre[iu], centre[iv], centre[k] = cu, cv, (p.span[0] + p.span[1]) / 2
    s = np.zeros((3, 3))
    s[iu, iu], s[iv, iv], s[k, k] = h * suu, h * svv, area * h ** 3 / 12
    s[iu, iv] = s[iv, iu] = h * suv
    return area * h, centre, s


def mass_properties(body) -> MassProperties:
    """The :class:`MassProperties` of a SolidBody: its parts' volumes, centroids and second
    moments combined (parallel axes), turned by its pose."""
    parts = [_box(lo, hi) for lo, hi in body.boxes]
    parts += [_cylinder(c) for c in body.cylinders] + [_prism(p) for p in body.prisms]
    volume = sum(v for v, _, _ in parts)
    centroid = sum(v * c for v, c, _ in parts) / volume
    s = sum(si + v * np.outer(c - centroid, c - centroid) for v, c, si in parts)
    if body.pose is not None:  # the parts turned: the centroid moves, the moments rotate
        R = body.pose.matrix
        centroid, s = body.pose.to_world(centroid), R @ s @ R.T
    return MassProperties(float(volume), centroid, s)


def flexure_volume(mechanism, index: int) -> float:
    """The volume (m^3) of flexure ``index`` outside its bodies: its section (a wire's
    pi d^2 / 4, a leaf's w t) times its free span (exact where the bodies' faces it crosses
    are perpendicular to it and its section lies inside them there)."""
    f = mechanism.flexures[index]
    section = (np.pi * f.diameter ** 2 / 4 if hasattr(f, "diameter")
               else f.width * f.thickness)
    return float(section * mechanism.span(index).length)


def mechanism_volume(mechanism) -> float:
    """The description's volume (m^3): its bodies' (:func:`mass_properties`) and its
    flexures' free spans (:func:`flexure_volume`); what the fused solid's STEP
    (geometry/spatial/export.py) holds."""
    return (sum(mass_properties(b).volume for b in mechanism.bodies)
            + sum(flexure_volume(mechanism, i) for i in range(len(mechanism.flexures))))
