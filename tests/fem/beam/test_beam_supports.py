"""One Fixed, Prescribed and NodalLoad for the planar (3 DOFs a node) and the spatial (6)
beam model: the DOFs they name per model, and their one-line refusals."""
import numpy as np
import pytest

from flexfem.fem.beam import NodalLoad
from flexfem.fem.beam.supports import NodeFixed, NodePrescribed
from flexfem.fem.beam.spatial import NodalLoad as SpatialNodalLoad
from flexfem.fem.beam.supports import NodeFixed as SpatialFixed


def test_the_planar_and_the_spatial_names_are_one_class():
    assert (NodeFixed, NodalLoad) == (SpatialFixed, SpatialNodalLoad)


def test_fixed_holds_every_dof_of_the_node_of_either_model():
    assert [d for _, d, _ in NodeFixed(4).prescribed(3)] == [0, 1, 2]
    assert [d for _, d, _ in NodeFixed(4).prescribed(6)] == [0, 1, 2, 3, 4, 5]
    assert list(NodeFixed([1, 2], ("y", "rz")).prescribed(6)) == [(1, 1, 0.0), (1, 5, 0.0),
                                                              (2, 1, 0.0), (2, 5, 0.0)]
    assert list(NodePrescribed(3, "theta", 0.1).prescribed(3)) == [(3, 2, 0.1)]


def test_the_in_plane_moment_is_m_or_mz():
    assert np.array_equal(NodalLoad(0, 1.0, 2.0, m=3.0).vector(3), [1.0, 2.0, 3.0])
    assert np.array_equal(NodalLoad(0, 1.0, 2.0, mz=3.0).vector(6), [1, 2, 0, 0, 0, 3])
    assert np.array_equal(NodalLoad(0, 1.0, 2.0, m=3.0).vector(6), [1, 2, 0, 0, 0, 3])


@pytest.mark.parametrize("make, match", [
    (lambda: NodalLoad(0, fz=1.0).vector(3), "out of the plane"),
    (lambda: NodalLoad(0, m=1.0, mz=1.0), "m or as mz"),
    (lambda: NodalLoad(0, 1.0, 2.0, 3.0), "positional"),
    (lambda: list(NodeFixed(0, ("z",)).prescribed(3)), "dof"),
    (lambda: list(NodePrescribed(0, "theta", 0.0).prescribed(6)), "dof"),
])
def test_a_dof_or_component_the_model_lacks_is_refused(make, match):
    with pytest.raises((ValueError, TypeError), match=match):
        make()
