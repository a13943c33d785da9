"""Sharp re-entrant corners of a planar mesh's outline, found from the mesh itself: where a
peak stress sits at one, it is singular (it grows without bound as the mesh is refined) and
no limit may be sized by it, whatever the flexure was declared to be.

The interior angle of the outline at a boundary vertex is the sum of the angles of its
triangles there (180 deg on a straight edge, 270 deg at a square re-entrant corner, 225 deg
at a 45-degree chamfer, 270 deg at each corner of two leaves fused where they cross). A
corner is sharp where the turn of the outline is concentrated at one vertex: its interior
angle is above :data:`SHARP` and its neighbours along the outline turn by less than half as
much. A fillet meshed finely spreads its turn over several vertices (a leaf's fillets are
meshed at an eighth of their radius: about 7 deg each), so it is not one. 3-D meshes are not
checked (None).
"""
import numpy as np

#: The interior angle (deg) above which a vertex whose turn is its own is a sharp corner.
SHARP = 200.0


def interior_angles(mesh) -> np.ndarray:
    """(n_vertices,) the sum of the triangle angles (deg) at each vertex of a MeshTri:
    360 inside, the outline's interior angle on the boundary."""
    p, t = mesh.p, mesh.t[:3]
    total = np.zeros(p.shape[1])
    for i in range(3):
        a, b, c = t[i], t[(i + 1) % 3], t[(i + 2) % 3]
        u, v = p[:, b] - p[:, a], p[:, c] - p[:, a]
        angle = np.arctan2(np.abs(u[0] * v[1] - u[1] * v[0]), np.einsum("ij,ij->j", u, v))
        total += np.bincount(a, np.degrees(angle), minlength=p.shape[1])
    return total


def _outline(mesh) -> dict:
    """{boundary vertex: [its neighbours along the outline]}."""
    edges = mesh.facets[:, mesh.boundary_facets()]
    out: dict = {}
    for a, b in edges.T:
        out.setdefault(int(a), []).append(int(b))
        out.setdefault(int(b), []).append(int(a))
    return out


def sharp_corner(mesh, point, reach: float = 3.0) -> dict | None:
    """The sharp re-entrant corner of ``mesh`` (a 2-D skfem mesh) within ``reach`` outline
    edges of ``point`` (m): {"point": [x, y] (m), "angle_deg": its interior angle}, the
    nearest if several; None where there is none (or the mesh is not planar)."""
    if mesh.p.shape[0] != 2:
        return None
    outline = _outline(mesh)
    vertices = np.fromiter(outline, int)
    here = np.asarray(point, float)[:2]
    distance = np.linalg.norm(mesh.p[:, vertices].T - here, axis=1)
    nearest = int(vertices[np.argmin(distance)])
    edge = np.mean([np.linalg.norm(mesh.p[:, nearest] - mesh.p[:, n])
                    for n in outline[nearest]])
    angles = interior_angles(mesh)
    best = None
    for v in vertices[distance <= distance.min() + reach * edge]:
        excess = angles[v] - 180.0
        if angles[v] <= SHARP or any(abs(angles[n] - 180.0) >= 0.5 * excess
                                     for n in outline[int(v)]):
            continue
        gap = float(np.linalg.norm(mesh.p[:, v] - here))
        if best is None or gap < best[0]:
            best = gap, {"point": mesh.p[:, v].tolist(), "angle_deg": float(angles[v])}
    return None if best is None else best[1]
