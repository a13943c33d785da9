"""The planar beam model is the spatial one restricted to the plane: for beams in the x-y
plane, the planar element's linear stiffness, its co-rotational internal forces and tangent
at a large-rotation state, and its consistent mass equal the spatial element's on the
in-plane DOFs (u_x, u_y, r_z) of its two nodes, to 1e-10 relative (round-off: measured
9e-13). A kinked chain at four angles, prismatic, linearly and quadratically tapered
sections, Euler-Bernoulli and Timoshenko."""
import numpy as np
import pytest

from flexfem.fem.beam import BeamModel, Section
from flexfem.fem.beam.assembly import element_mass
from flexfem.fem.beam.element import basic_stiffness, corotational
from flexfem.fem.beam.spatial import Beam3DModel, Section as SpatialSection
from flexfem.fem.beam.spatial.corotational import internal_forces
from flexfem.fem.beam.spatial.element import basic_stiffness as spatial_basic_stiffness
from flexfem.fem.beam.spatial.element import local_matrices, to_global
from flexfem.fem.beam.spatial.rotations import expm

IN_PLANE = np.array([0, 1, 5, 6, 7, 11])  # (u_x, u_y, r_z) of both nodes among 12
NODES = np.array([[0.0, 0.0], [0.02, 0.004], [0.035, 0.02], [0.03, 0.04], [0.01, 0.05]])
ELEMENTS = np.array([[0, 1], [1, 2], [2, 3], [3, 4]])
WIDTH = 5e-3  # m, out of the plane
THICKNESS = [(0.6e-3, None, None), (0.6e-3, 0.9e-3, None), (0.6e-3, 0.5e-3, 0.8e-3),
             (1e-3, None, None)]  # (t at node 1, at node 2, at the middle), m


def _models(steel, shear: bool):
    planar = [Section.rect(WIDTH, t0, thickness_end=t1, thickness_mid=tm)
              for t0, t1, tm in THICKNESS]
    spatial = [SpatialSection.rect(WIDTH, t0, thickness_end=t1, thickness_mid=tm)
               for t0, t1, tm in THICKNESS]
    nodes3 = np.column_stack([NODES, np.zeros(len(NODES))])
    return (BeamModel(NODES, ELEMENTS, planar, steel, shear=shear),
            Beam3DModel(nodes3, ELEMENTS, spatial, steel, shear=shear))


def _in_plane(a):
    return a[:, IN_PLANE[:, None], IN_PLANE[None, :]] if a.ndim == 3 else a[:, IN_PLANE]


def _relative(a, b) -> float:
    return float(np.abs(a - b).max() / np.abs(b).max())


def _states(steel, shear, q):
    """Planar and spatial (f, K) at the in-plane state q (n, 3): (u_x, u_y, theta)."""
    m2, m3 = _models(steel, shear)
    f2, K2, _ = corotational(m2, basic_stiffness(m2), q)
    x = np.column_stack([NODES + q[:, :2], np.zeros(len(NODES))])
    R = expm(np.column_stack([np.zeros((len(q), 2)), q[:, 2]]))
    f3, K3, _ = internal_forces(m3, spatial_basic_stiffness(m3), x, R)
    return (f2, K2), (f3, K3)


@pytest.mark.parametrize("shear", [False, True])
def test_the_linear_stiffness_is_the_spatial_one_in_plane(steel, shear):
    (_, K2), (_, K3) = _states(steel, shear, np.zeros((len(NODES), 3)))
    assert _relative(_in_plane(K3), K2) < 1e-10


@pytest.mark.parametrize("shear", [False, True])
def test_the_corotational_forces_and_tangent_are_the_spatial_ones_in_plane(steel, shear):
    """At nodal rotations up to 0.8 rad and displacements of up to a fifth of an element."""
    q = np.column_stack([[0.0, 1e-3, -2e-3, 3e-3, -1e-3], [0.0, -2e-3, 1e-3, 2e-3, 4e-3],
                         [0.3, -0.6, 0.8, 0.2, -0.5]])
    (f2, K2), (f3, K3) = _states(steel, shear, q)
    assert _relative(_in_plane(f3), f2) < 1e-10
    assert _relative(_in_plane(K3), K2) < 1e-10


@pytest.mark.parametrize("shear", [False, True])
def test_the_consistent_mass_is_the_spatial_one_in_plane(steel, shear):
    m2, m3 = _models(steel, shear)
    E = to_global(m3.frames)
    M3 = np.einsum("eij,ejk,elk->eil", E, local_matrices(m3)[1], E)
    assert _relative(_in_plane(M3), element_mass(m2)) < 1e-10
