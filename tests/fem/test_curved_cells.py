"""Quadratic tetrahedra curved onto a round surface (fem/curved.py) against the circle: the
rod's volume and second moment, its cantilever deflection against Timoshenko's, and the
straight-sided mesh beside it (a polygonal section, 5 % soft in bending)."""
import numpy as np
import pytest
import skfem

from flexfem.fem import FEMesh, Fixed, Force, Model, Solid3D, solve_static
from flexfem.fem.abaqus import abaqus_mesh
from flexfem.fem.curved import curved_onto_cylinders, facet_edges, lateral_facets
from meshes import rod_3d

L, R, P = 10.0, 0.5, 1.0
AXIS = ((0.0, 0.0, 0.0), (L, 0.0, 0.0), R)


@pytest.fixture(scope="module")
def rods():
    straight = rod_3d(L, R, 16)
    return straight, curved_onto_cylinders(straight, [AXIS])


def _integrals(mesh, steel):
    basis = Model(mesh, steel, Solid3D(), order=2).basis
    y = basis.mapping.F(basis.X)[1]              # (n_elements, n_points)
    return float(np.sum(basis.dx)), float(np.sum(y ** 2 * basis.dx))


def test_the_curved_section_is_the_circles_the_straight_one_a_polygons(rods, steel):
    area, inertia = np.pi * R ** 2, np.pi * R ** 4 / 4
    (v_straight, i_straight), (v_curved, i_curved) = (_integrals(m, steel) for m in rods)
    assert v_curved == pytest.approx(area * L, rel=2e-4)
    assert i_curved == pytest.approx(inertia * L, rel=1e-3)
    assert v_straight < 0.99 * area * L        # a polygon of some 16-20 sides: 0.975-0.984
    assert i_straight < 0.97 * inertia * L     # 0.950-0.967


def test_a_curved_rods_cantilever_is_timoshenkos(rods, steel):
    nu, G = steel.nu, steel.E / (2 * (1 + steel.nu))
    kappa = 6 * (1 + nu) / (7 + 6 * nu)                        # Cowper's, a circle
    area, inertia = np.pi * R ** 2, np.pi * R ** 4 / 4
    expected = P * L ** 3 / (3 * steel.E * inertia) + P * L / (kappa * G * area)
    tips = [-solve_static(Model(m, steel, Solid3D()), [Fixed("fixed")],
                          [Force("tip", (0.0, -P, 0.0))]).mean_displacement("tip")[1]
            for m in rods]
    assert tips[1] == pytest.approx(expected, rel=0.01)
    assert tips[0] > 1.03 * expected                           # the polygon's section


def test_only_the_surfaces_edges_move_and_the_export_keeps_them(rods):
    """The edges of the lateral surface's triangles move onto the circle; interior chords
    and the end caps' chords between two points of the rim (they cross the rod or its
    flat end) and every other edge keep their midpoints."""
    straight, curved = rods
    mesh = straight.mesh
    midpoints = (mesh.p[:, mesh.edges[0]] + mesh.p[:, mesh.edges[1]]) / 2
    ends = mesh.p[:, mesh.edges]                                  # (3, 2, n_edges)
    on_surface = np.all(np.abs(np.hypot(ends[1], ends[2]) - R) < 1e-6 * R, axis=0)
    moved = np.isin(np.arange(mesh.edges.shape[1]),
                    facet_edges(mesh, lateral_facets(mesh, *AXIS)))
    assert np.array_equal(curved.edge_nodes[:, ~moved], midpoints[:, ~moved])
    assert np.allclose(np.hypot(*curved.edge_nodes[1:, moved]), R, rtol=1e-9)
    rim = on_surface & np.all(np.isclose(ends[0], 0.0) | np.isclose(ends[0], L), axis=0)
    assert np.all(moved[rim])                                     # the end circles' edges
    points = abaqus_mesh(curved, order=2).points[mesh.p.shape[1]:]
    assert np.allclose(np.sort(np.hypot(points[:, 1], points[:, 2])[moved]), R, rtol=1e-9)
    assert curved_onto_cylinders(straight, [((0, 5, 5), (L, 5, 5), R)]) is straight


def _one_tetrahedron(corners):
    return FEMesh(skfem.MeshTet(np.array(corners, float).T, np.array([[0, 1, 2, 3]]).T))


def _on_circle(x, degrees):
    a = np.radians(degrees)
    return [x, R * np.cos(a), R * np.sin(a)]


def test_a_cap_whose_corners_lie_on_the_rim_stays_flat():
    """A boundary triangle across the rod's end with its three corners on the rim: a flat
    face, its chords kept straight; a triangle of the side surface is curved."""
    cap = _one_tetrahedron([_on_circle(0, 0), _on_circle(0, 120), _on_circle(0, 240), [1, 0, 0]])
    assert curved_onto_cylinders(cap, [AXIS]) is cap
    side = _one_tetrahedron([_on_circle(0, 0), _on_circle(0, 30), _on_circle(0.3, 15),
                             [0.1, 0, 0]])
    curved = curved_onto_cylinders(side, [AXIS])
    radius = np.hypot(*curved.edge_nodes[1:])
    assert np.sum(np.isclose(radius, R, rtol=1e-12)) == 3       # the side triangle's edges
