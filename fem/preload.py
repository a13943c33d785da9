"""Preloads of a nonlinear solve: loads applied first and then held constant while the scaled
loads are stepped or continued (``solve_nonlinear(..., preloads=[...])``).

The solve has two stages. Preload: the preloads are stepped 0 -> 1 by load control, with the
scaled loads, prescribed displacements and prescribed face coordinates at 0. Then the
preloads stay at their full value while the scaled loads and prescribed motions follow the
load factor 0 -> 1, by load or by arc-length control. A preload is any load that
``solve_nonlinear`` takes (Force, Traction, PointForce, BodyForce, Gravity: fixed direction;
Pressure: follower if so marked) or a RigidFace naming a face of ``rigid_faces``: its force
(N) and moment (N m) then act on that face's free coordinates (the preload's own x, y and
rotation are left None).
"""
import dataclasses

import numpy as np
import scipy.sparse as sp

from .rigid_face import RigidFace

_LOAD_FIELDS = ("group", "force", "moment")


def split_preloads(preloads, rigid_faces, dim: int) -> tuple[list, dict]:
    """(nodal loads, {face group: RigidFace carrying the face preload}) of ``preloads`` on a
    ``dim``-D model; ValueError naming a face preload that prescribes a coordinate, names no
    face of ``rigid_faces``, is given twice, loads a coordinate that face prescribes, or (3-D)
    puts a moment on a face that prescribes part of its rotation."""
    faces = {f.group: f for f in rigid_faces}
    nodal, face_loads = [], {}
    for load in preloads:
        if not isinstance(load, RigidFace):
            nodal.append(load)
            continue
        name = f"preload RigidFace({load.group!r})"
        if np.any(load.prescribed(dim)):
            raise ValueError(f"{name} prescribes a coordinate; a preload carries force and "
                             "moment only: leave its x, y and rotation None")
        if load.group not in faces:
            raise ValueError(f"{name} names no face of rigid_faces "
                             f"({', '.join(map(repr, faces)) or 'none'}); list the face there")
        if load.group in face_loads:
            raise ValueError(f"{name} is given twice; add its loads into one")
        held = faces[load.group].prescribed(dim)
        if np.any(held & (load.loads(dim) != 0.0)):
            raise ValueError(f"{name} loads a coordinate that rigid face prescribes; a "
                             "prescribed coordinate takes a reaction, not a load")
        if dim == 3 and np.any(held[3:]) and np.any(load.loads(dim)[3:] != 0.0):
            # the preload's moment would be taken at the preload stage's rotation (the
            # prescribed components at 0), not at the scaled one
            raise ValueError(f"{name} puts a moment on a 3-D face that prescribes part of its "
                             "rotation; apply that moment as a scaled load instead")
        face_loads[load.group] = load
    return nodal, face_loads


def _zero(value):
    """0.0, or a tuple as long as ``value`` with 0.0 where it holds a number (None stays)."""
    if isinstance(value, (tuple, list, np.ndarray)):
        return tuple(None if v is None else 0.0 for v in value)
    return 0.0


def preload_faces(rigid_faces, face_loads: dict) -> list:
    """The rigid faces of the preload stage: each prescribed coordinate held at 0 (the scaled
    motions have not started), each free one carrying the face preload (or nothing)."""
    out = []
    for face in rigid_faces:
        load = face_loads.get(face.group)
        held = {f.name: _zero(getattr(face, f.name)) for f in dataclasses.fields(face)
                if f.name not in _LOAD_FIELDS and getattr(face, f.name) is not None}
        out.append(dataclasses.replace(
            face, **held, force=load.force if load else _zero(face.force),
            moment=load.moment if load else _zero(face.moment)))
    return out


class PreloadedSpace:
    """A reduced space (:class:`.rigid_face.ReducedSpace`) whose applied face loads carry the
    face preloads, those of ``preload`` (the preload stage's space) at full value, beside the
    scaled ones."""

    def __init__(self, space, preload):
        self._space, self._preload = space, preload

    def __getattr__(self, name):
        return getattr(self._space, name)

    @property
    def symmetric(self) -> bool:
        """False when the scaled or the preloaded face loads make the tangent non-symmetric."""
        return self._space.symmetric and self._preload.symmetric

    def applied(self, load_factor: float, z=None) -> np.ndarray:
        """Generalised loads on the free face coordinates (N): scaled plus preloads."""
        return self._space.applied(load_factor, z) + self._preload.applied(1.0, z)

    def geometric_matrix(self, z, load_factor, r) -> sp.csr_matrix:
        """The scaled space's geometric and load stiffness (N/m) plus the load stiffness of
        the face preloads (3-D dead moments; zero in 2-D)."""
        return (self._space.geometric_matrix(z, load_factor, r)
                + self._preload.geometric_matrix(z, 1.0, np.zeros_like(r)))
