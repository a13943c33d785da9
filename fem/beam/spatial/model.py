"""Spatial beam models: sections, nodes and elements, rigid links, supports and loads.

    model = Beam3DModel(nodes, elements, Section.rect(2e-3, 10e-3), steel)

DOFs per node: (u_x, u_y, u_z) displacement (m) and (r_x, r_y, r_z) rotation (rad, about the
global axes; at large rotations the nodes carry rotation matrices, see nonlinear.py).
Each element's local axes: x along it (node 1 to node 2), z the component of its
``orientation`` vector normal to x (default global z; global x for an element along z),
y = z cross x. A planar model in the x-y plane then has local z = global z and bends in
plane about local z (Iz), as the planar model (fem/beam) does with its I.
"""
import math

import numpy as np

from ..model import BeamModelBase
from ..section import rect_depth, rect_torsion_constant
from ...materials import Material


def element_frames(nodes, elements, orientation=None) -> np.ndarray:
    """(n_e, 3, 3) local axes (columns x, y, z) of each element; ``orientation``: one
    vector or one per element (n_e, 3) towards which local z points (default global z,
    or global x for an element along global z)."""
    d = nodes[elements[:, 1]] - nodes[elements[:, 0]]
    ex = d / np.linalg.norm(d, axis=1)[:, None]
    if orientation is None:
        ref = np.tile([0.0, 0.0, 1.0], (len(ex), 1))
        along_z = np.abs(ex[:, 2]) > 1.0 - 1e-9
        ref[along_z] = [1.0, 0.0, 0.0]
    else:
        ref = np.broadcast_to(np.asarray(orientation, dtype=float), ex.shape)
    ez = ref - np.einsum("ei,ei->e", ref, ex)[:, None] * ex
    norm = np.linalg.norm(ez, axis=1)
    bad = ~(norm > 1e-9 * np.maximum(np.linalg.norm(ref, axis=1), 1e-300))
    if np.any(bad):
        raise ValueError(f"orientation: parallel to elements {np.flatnonzero(bad).tolist()} "
                         "(or zero); give a vector off their axis")
    ez = ez / norm[:, None]
    ey = np.cross(ez, ex)
    return np.stack([ex, ey, ez], axis=2)


class Beam3DModel(BeamModelBase):
    """A spatial beam model: co-rotational beams between nodes, 6 DOFs a node (u, v, w in
    m, rotations in rad), analysed by the same face and group supports and loads as the
    planar :class:`~flexfem.fem.beam.model.BeamModel` (forces (fx, fy, fz) N).

    Parameters
    ----------
    nodes : array_like, shape (n, 3)
        Node coordinates (m).
    elements, material, rigid_links, groups, shear
        As the planar :class:`~flexfem.fem.beam.model.BeamModel`'s.
    sections : Section or sequence of Section
        One for every element, or one per element; each needs ``Iy`` and ``J``
        (``Section.rect`` gives them).
    orientation : array_like, optional
        The reference for each element's local z axis, (3,) or (n_e, 3) (see
        :func:`element_frames`; None: global z, or global y for an element along z).
    point_masses : dict, optional
        {node: (mass kg, Jx, Jy, Jz kg m^2 about global axes through the node)}.

    Raises
    ------
    ValueError
        Nodes, elements, sections or links that do not fit together, naming which.
    """

    dim, PER_NODE, POINT_MASS = 3, 6, (4, "(m, Jx, Jy, Jz) >= 0")

    def __init__(self, nodes, elements, sections, material: Material, orientation=None,
                 rigid_links=(), point_masses=None, groups=None, shear: bool = False):
        d = self._setup(nodes, elements, sections, material, shear)
        if any(s.Iy is None or s.J is None for s in self.sections):
            raise ValueError("sections: a spatial model needs Iy and J on every Section")
        self.frames = element_frames(self.nodes, self.elements, orientation)
        self._links(rigid_links, point_masses)
        self._groups(groups)

    def section_table(self) -> dict:
        """Shear areas Ay, Az (m^2, inf where shear is off: no area, or the model without
        shear) as (n_e,) arrays, the stiffness factors (n_e, 4) and the mass factors (n_e,)."""
        shear = lambda name: np.array([math.inf if getattr(s, name) is None or not self.shear
                                       else getattr(s, name) for s in self.sections], dtype=float)
        return {"Ay": shear("Ay"), "Az": shear("Az"),
                "factors": np.array([s.factors for s in self.sections], dtype=float),
                "mass_factor": np.array([s.mass_factor for s in self.sections], dtype=float)}

    def section_at(self, xi) -> dict:
        """A, Iy, Iz, J, Ip (m^2, m^4) and the rectangles' depth_y, depth_z (m; NaN for a
        general section) of every element at fractions ``xi`` (k,) along it, each (n_e, k)."""
        xi = np.atleast_1d(np.asarray(xi, dtype=float))
        get = lambda name: np.array([math.nan if getattr(s, name) is None else getattr(s, name)
                                     for s in self.sections], dtype=float)
        out = {k: np.repeat(get(k)[:, None], len(xi), axis=1)
               for k in ("A", "Iy", "Iz", "J", "depth_y", "depth_z")}
        tapered = [e for e, s in enumerate(self.sections) if s.taper is not None]
        if tapered:
            t0, t1, tm, w = np.array([self.sections[e].taper for e in tapered]).T
            t = rect_depth(t0, t1, tm, xi)
            w = w[:, None]
            out["depth_y"][tapered] = t
            out["A"][tapered], out["Iy"][tapered] = t * w, t * w**3 / 12.0
            out["Iz"][tapered], out["J"][tapered] = w * t**3 / 12.0, rect_torsion_constant(t, w)
        out["Ip"] = out["Iy"] + out["Iz"]
        return out
