"""The spatial beam model of bodies and flexures (``--model beam --dim 3``): the planar beam
model lifted out of the plane by the mechanism's depth (reduced/spatial.py), its bodies'
masses with their out-of-plane rotary inertias, for the modes out of the plane as well as in
it, and for the statics where a force pushes out of the plane (else the planar model's).
SI units."""
from dataclasses import replace

import numpy as np

from ...fem import Fixed, Force, solve_modes, solve_static
from ...geometry.polygon import moments as polygon_moments
from ...reduced.spatial import lifted_model
from ...geometry.user_model.tables import SectionSpec


def planar_twin(spec):
    """The 2-D spec of a 3-D spec of bodies and flexures: the plane-stress section of the
    mechanism's depth, the loads' and supports' in-plane components (a support holding z
    alone holds nothing in the plane)."""
    depth = spec.mechanism.depth
    loads = tuple(replace(load, vector=tuple(load.vector)[:2]) for load in spec.loads)
    supports = tuple(s if s.components is None else
                     replace(s, components={k: v for k, v in s.components.items() if k < 2})
                     for s in spec.supports if s.components is None or set(s.components) - {2})
    groups = {name: 1 for name, d in spec.groups.items() if d == 2} | {"solid": 2}
    return replace(spec, dim=2, section=SectionSpec("plane_stress", depth), loads=loads,
                   supports=supports, groups=groups)


def _box_inertias(body, rho: float, depth: float) -> tuple:
    """(mass, centroid (2,), (J_x, J_y, J_z) about it) of a body's boxes extruded by depth;
    with polygons, of the union of its boxes and polygons (its area moments: the same centroid
    as the planar model's mass node, reduced/model_file.py)."""
    if body.polygons:
        area, c, (xx, yy, _) = polygon_moments(body.blocks)
        m = rho * area * depth
        return m, c, (rho * depth * yy + m * depth * depth / 12,
                      rho * depth * xx + m * depth * depth / 12, rho * depth * (xx + yy))
    parts = []
    for (x0, y0), (x1, y1) in body.boxes:
        w, h = x1 - x0, y1 - y0
        parts.append((rho * w * h * depth, np.array([(x0 + x1) / 2, (y0 + y1) / 2]), w, h))
    m = sum(p[0] for p in parts)
    c = sum(p[0] * p[1] for p in parts) / m
    jx = sum(mi * ((h * h + depth * depth) / 12 + (ci[1] - c[1]) ** 2) for mi, ci, w, h in parts)
    jy = sum(mi * ((w * w + depth * depth) / 12 + (ci[0] - c[0]) ** 2) for mi, ci, w, h in parts)
    jz = sum(mi * ((w * w + h * h) / 12 + float((ci - c) @ (ci - c))) for mi, ci, w, h in parts)
    return m, c, (jx, jy, jz)


def spatial_model(spec, planar):
    """The lifted spatial model of ``planar`` (the BeamModel of a 3-D spec of bodies and
    flexures): its bodies' masses with their rotary inertias, the planar groups."""
    if any(s.components is not None for s in spec.supports):
        raise ValueError(f"{spec.source}: --model beam --dim 3 holds bodies whole; a support "
                         "with components (x = ..., y = ...) is the 2-D model's")
    mechanism, tol = spec.mechanism, 1e-9 * spec.mechanism.size
    masses = {}
    for node, _ in planar.point_masses.items():
        for body in mechanism.bodies:
            m, c, j = _box_inertias(body, spec.material.density, mechanism.depth)
            if np.linalg.norm(planar.nodes[node] - c) <= 10 * tol:
                masses[node] = (m, *j)
                break
        else:
            raise ValueError(f"{spec.source}: a body's mass node has no body (internal)")
    return lifted_model(planar, mechanism.depth, point_masses=masses)


def spatial_modes(spec, planar, n: int) -> list:
    """The ``n`` lowest frequencies (Hz) of the lifted model, held where the planar model's
    supports hold (every support holds its body whole: a partial support of a solid has no
    planar meaning here)."""
    supports = [Fixed(s.group) for s in spec.supports]
    return solve_modes(spatial_model(spec, planar), n, supports).frequencies_hz.tolist()


def out_of_plane(spec) -> bool:
    """True where a 3-D spec's loads push out of the plane (a nonzero F_z)."""
    return spec.dim == 3 and any(len(load.vector) == 3 and load.vector[2] != 0.0
                                 for load in spec.loads)


def spatial_static(spec, planar):
    """The linear static solve of the lifted model (:func:`spatial_model`) under the 3-D
    spec's supports and its forces with their out-of-plane components (the analysis face's
    Beam3DResult)."""
    supports = [Fixed(s.group) for s in spec.supports]
    loads = [Force(load.group, load.vector) for load in spec.loads]
    return solve_static(spatial_model(spec, planar), supports, loads)
