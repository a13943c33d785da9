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

from .rigid_face import RigidFace

_LOAD_FIELDS = ("group", "force", "moment")


def split_preloads(preloads, rigid_faces) -> tuple[list, dict]:
    """(nodal loads, {face group: RigidFace carrying the face preload}) of ``preloads``;
    ValueError naming a face preload that prescribes a coordinate, names no face of
    ``rigid_faces``, is given twice or loads a coordinate that face prescribes."""
    faces = {f.group: f for f in rigid_faces}
    nodal, face_loads = [], {}
    for load in preloads:
        if not isinstance(load, RigidFace):
            nodal.append(load)
            continue
        name = f"preload RigidFace({load.group!r})"
        if np.any(load.prescribed()):
            raise ValueError(f"{name} prescribes a coordinate; a preload carries force and "
                             "moment only: leave its x, y and rotation None")
        if load.group not in faces:
            raise ValueError(f"{name} names no face of rigid_faces "
                             f"({', '.join(map(repr, faces)) or 'none'}); list the face there")
        if load.group in face_loads:
            raise ValueError(f"{name} is given twice; add its loads into one")
        clash = faces[load.group].prescribed() & (load.loads() != 0.0)
        if np.any(clash):
            raise ValueError(f"{name} loads a coordinate that rigid face prescribes; a "
                             "prescribed coordinate takes a reaction, not a load")
        face_loads[load.group] = load
    return nodal, face_loads


def _zero(value):
    """0.0, or a tuple of zeros as long as ``value``."""
    return tuple(0.0 for _ in value) if isinstance(value, (tuple, list, np.ndarray)) else 0.0


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

    def applied(self, load_factor: float, *where) -> np.ndarray:
        """Generalised loads on the free face coordinates (N): scaled plus preloads."""
        return self._space.applied(load_factor, *where) + self._preload.applied(1.0, *where)
