"""The input of a rigid face: :class:`RigidFace`, the same class in 2-D and 3-D.

Coordinates, in order: 2-D (x, y, rotation) in (m, m, rad); 3-D (x, y, z, rotation_x,
rotation_y, rotation_z) in (m, m, m, rad, rad, rad), the rotation a rotation vector. Each is
prescribed (a number, scaled by the load factor) or free (None, loaded by the applied force
or moment component, zero by default).
"""
import math
from dataclasses import dataclass

import numpy as np

from .checks import finite_or_none, is_real




def _vector(value, name, sizes, what, allow_none=False):
    """A tuple of finite numbers (or None where ``allow_none``) of a length in ``sizes``."""
    try:
        items = tuple(value)
    except TypeError:
        raise ValueError(f"{name} = {value!r} must be {what}") from None
    if len(items) not in sizes:
        raise ValueError(f"{name} = {value!r} has {len(items)} components; it must be {what}")
    for item in items:
        if not ((allow_none and item is None) or (is_real(item) and math.isfinite(item))):
            raise ValueError(f"{name} = {value!r} must be {what}")
    return tuple(None if item is None else float(item) for item in items)


@dataclass(frozen=True)
class RigidFace:
    """Boundary group ``group`` held rigid, moving about its centroid.

    2-D: ``rotation`` (rad, counter-clockwise) and centroid translations ``x``, ``y`` (m)
    are prescribed at full load (scaled by the load factor) or None (free); a free
    coordinate carries the applied ``force`` (N, (Fx, Fy)) or ``moment`` (N m, about the
    current centroid). 3-D: also ``z`` (m); ``rotation`` is None (all free) or a rotation
    vector (theta_x, theta_y, theta_z) (rad) whose components may each be None (free);
    ``force`` = (Fx, Fy, Fz) (N), ``moment`` = (Mx, My, Mz) (N m, global axes, about the
    current centroid, dead). Loads default to zero; a face with only the defaults, or only
    x / y, fits both."""

    group: str
    rotation: object = None
    x: float | None = None
    y: float | None = None
    moment: object = 0.0
    force: tuple = (0.0, 0.0)
    z: float | None = None

    def __post_init__(self):
        name = f"RigidFace({self.group!r})"
        for coord in ("x", "y", "z"):
            object.__setattr__(self, coord, finite_or_none(f"{name}.{coord}", getattr(self, coord)))
        if self.rotation is not None and not is_real(self.rotation):
            rotation = _vector(self.rotation, f"{name}.rotation", (3,),
                               "a number (2-D) or 3 numbers or None (3-D rotation vector, rad)",
                               allow_none=True)
        else:
            rotation = finite_or_none(f"{name}.rotation", self.rotation)
        object.__setattr__(self, "rotation", rotation)
        if is_real(self.moment):
            moment = finite_or_none(f"{name}.moment", self.moment)
        else:
            moment = _vector(self.moment, f"{name}.moment", (3,),
                             "a number (2-D, N m) or 3 numbers (Mx, My, Mz) (3-D, N m)")
        object.__setattr__(self, "moment", moment)
        object.__setattr__(self, "force", _vector(self.force, f"{name}.force", (2, 3),
                                                  "2 (Fx, Fy) or 3 (Fx, Fy, Fz) finite numbers in N"))
        dims = self._dims()
        if len(set(dims.values())) > 1:
            raise ValueError(f"{name} mixes 2-D and 3-D input: " + ", ".join(
                f"{k} is {d}-D" for k, d in dims.items()))
        dim = self.dim or 2
        for coord, held, load in zip(self._names(dim), self.prescribed(dim), self.loads(dim)):
            if held and load != 0.0:
                raise ValueError(f"{name} prescribes {coord} and applies a load {load} on it; a "
                                 f"prescribed coordinate takes a reaction: leave {coord} free "
                                 "(None) to apply the load")

    def _dims(self) -> dict:
        """{field: the dimension its value implies} for the fields that imply one."""
        dims = {}
        if self.z is not None:
            dims["z"] = 3
        if self.rotation is not None:
            dims["rotation"] = 3 if isinstance(self.rotation, tuple) else 2
        if isinstance(self.moment, tuple):
            dims["moment"] = 3
        elif self.moment != 0.0:
            dims["moment"] = 2
        if len(self.force) == 3 or any(self.force):
            dims["force"] = len(self.force)
        return dims

    @property
    def dim(self) -> int | None:
        """2 or 3 where the input implies a dimension, None where it fits both."""
        dims = set(self._dims().values())
        return dims.pop() if dims else None

    def check_dim(self, dim: int) -> None:
        """ValueError naming the input that does not fit a ``dim``-D model."""
        wrong = {k: d for k, d in self._dims().items() if d != dim}
        if wrong:
            shapes = {2: "x, y, rotation (a number), moment (a number), force (Fx, Fy)",
                      3: "x, y, z, rotation (3 numbers or None), moment (Mx, My, Mz), force "
                         "(Fx, Fy, Fz)"}
            raise ValueError(f"RigidFace({self.group!r}) is on a {dim}-D model but its "
                             + ", ".join(f"{k} = {getattr(self, k)!r}" for k in wrong)
                             + f" {'is' if len(wrong) == 1 else 'are'} {5 - dim}-D input; a "
                             f"{dim}-D face takes {shapes[dim]}")

    @staticmethod
    def _names(dim) -> list:
        return (["x", "y", "rotation"] if dim == 2 else
                ["x", "y", "z", "rotation_x", "rotation_y", "rotation_z"])

    def _rotations(self, dim) -> list:
        if dim == 2:
            return [self.rotation]
        return list(self.rotation) if isinstance(self.rotation, tuple) else [None] * 3

    def _coordinates(self, dim) -> list:
        return [self.x, self.y] + ([self.z] if dim == 3 else []) + self._rotations(dim)

    def prescribed(self, dim=None) -> np.ndarray:
        """(3,) in 2-D, (6,) in 3-D bool: which coordinates are prescribed."""
        return np.array([v is not None for v in self._coordinates(dim or self.dim or 2)])

    def values(self, dim=None) -> np.ndarray:
        """Full-load values (m, rad) of the prescribed coordinates (0 where free)."""
        return np.array([v or 0.0 for v in self._coordinates(dim or self.dim or 2)], dtype=float)

    def loads(self, dim=None) -> np.ndarray:
        """Full-load generalised loads: (Fx, Fy, M) in 2-D, (F, M) (N, N m) in 3-D."""
        dim = dim or self.dim or 2
        force = np.zeros(dim)
        n = min(dim, len(self.force))
        force[:n] = self.force[:n]
        if dim == 2:
            return np.array([force[0], force[1], self.moment])
        moment = self.moment if isinstance(self.moment, tuple) else (0.0, 0.0, 0.0)
        return np.concatenate([force, moment])
