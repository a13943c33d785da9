"""Bad input gives an exception whose message says what to change, never garbage."""
import math

import numpy as np
import pytest
import skfem
from meshes import beam_2d, beam_3d
from flexfem.fem import (
    BodyForce,
    FEMesh,
    Fixed,
    Force,
    Gravity,
    Material,
    Model,
    PlaneStrain,
    PlaneStress,
    PointForce,
    Prescribed,
    SingularSystemError,
    Solid3D,
    Traction,
    UnderConstrainedError,
    facets_where,
    solve_modes,
    solve_static,
)
from flexfem.fem.mesh import corner_jacobians


@pytest.fixture(scope="module")
def beam(steel):
    return Model(beam_2d(1.0, 0.1, 0.05), steel, PlaneStress(0.01), order=2)


@pytest.fixture(scope="module")
def box(steel):
    return Model(beam_3d(1.0, 0.1, 0.1, 0.1), steel, Solid3D(), order=1)


def square_mesh(n=2, quads=False):
    """Unit square (m) of n x n cells."""
    x = np.linspace(0.0, 1.0, n + 1)
    return (skfem.MeshQuad if quads else skfem.MeshTri).init_tensor(x, x)


def with_edges(mesh):
    """FEMesh with boundary groups left (x = 0), right (x = max) and bottom (y = 0)."""
    return FEMesh(mesh, {"left": facets_where(mesh, lambda x: np.isclose(x[0], 0.0)),
                         "right": facets_where(mesh, lambda x: np.isclose(x[0], mesh.p[0].max())),
                         "bottom": facets_where(mesh, lambda x: np.isclose(x[1], 0.0))})


# --- parameters -------------------------------------------------------------------------------

@pytest.mark.parametrize("field, value, words", [
    ("E", 0.0, "E = 0.0"), ("E", -1e9, "> 0"), ("E", math.nan, "finite"), ("E", math.inf, "finite"),
    ("E", "200e9", "number"), ("nu", 0.5, "(-1, 0.5)"), ("nu", -1.0, "(-1, 0.5)"),
    ("nu", math.nan, "finite"), ("rho", 0.0, "rho"), ("rho", -7800.0, "> 0"),
    ("yield_strength", 0.0, "yield_strength"), ("yield_strength", math.nan, "yield_strength"),
])
def test_material_parameters_out_of_range(field, value, words):
    params = dict(E=200e9, nu=0.3, rho=7800.0, yield_strength=250e6)
    params[field] = value
    with pytest.raises(ValueError, match=r"'bad'.*" + field) as error:
        Material("bad", **params)
    assert words in str(error.value)


@pytest.mark.parametrize("formulation", [PlaneStress, PlaneStrain])
@pytest.mark.parametrize("thickness", [0.0, -0.01, math.nan, math.inf, "0.01"])
def test_thickness_must_be_positive_and_finite(formulation, thickness):
    with pytest.raises(ValueError, match=f"{formulation.__name__}: thickness .* finite number > 0"):
        formulation(thickness)


def test_model_rejects_wrong_order_and_formulation(beam, box, steel):
    with pytest.raises(ValueError, match="order = 3 must be 1 or 2"):
        Model(beam.mesh, steel, PlaneStress(0.01), order=3)
    with pytest.raises(ValueError, match="2-D mesh needs formulation=PlaneStress"):
        Model(beam.mesh, steel, Solid3D())
    with pytest.raises(ValueError, match="3-D mesh needs formulation=Solid3D"):
        Model(box.mesh, steel, PlaneStress(0.01))
    with pytest.raises(ValueError, match="solver = 'lu'; choose 'auto', 'direct' or 'amg'"):
        solve_static(beam, [Fixed("fixed")], [Force("tip", (0.0, 1.0))], solver="lu")
    with pytest.raises(ValueError, match="n = 0 must be a positive integer"):
        solve_modes(beam, 0, [Fixed("fixed")])


# --- meshes -----------------------------------------------------------------------------------

def test_empty_mesh():
    with pytest.raises(ValueError, match="no elements"):
        FEMesh(skfem.MeshTri(np.zeros((2, 3)), np.zeros((3, 0), dtype=int)))


def test_non_finite_coordinates():
    p = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, np.nan]])
    with pytest.raises(ValueError, match="1 vertices with non-finite coordinates"):
        FEMesh(skfem.MeshTri(p, np.array([[0], [1], [2]])))


@pytest.mark.parametrize("cells, p", [
    (skfem.MeshTri, [[0, 1, 2, 0], [0, 0, 0, 1]]),                      # three collinear vertices
    (skfem.MeshQuad, [[0, 1, 1, 1], [0, 0, 0, 1]]),                     # two coincident vertices
    (skfem.MeshTet, [[0, 1, 0, 1], [0, 0, 1, 1], [0, 0, 0, 0]]),        # four coplanar vertices
])
def test_degenerate_elements(cells, p):
    t = np.arange(len(p[0]) if cells is not skfem.MeshTri else 3).reshape(-1, 1)
    with pytest.raises(ValueError, match="1 degenerate .* element 0; remesh"):
        FEMesh(cells(np.array(p, dtype=float), t))


def test_folded_quadrilateral():
    # vertices in "bow-tie" order: the bilinear map folds over, det J changes sign inside
    p = np.array([[0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]])
    with pytest.raises(ValueError, match="1 folded elements .* check the vertex order"):
        FEMesh(skfem.MeshQuad(p, np.array([[0], [1], [2], [3]])))


@pytest.mark.parametrize("quads", [False, True])
def test_inverted_elements_give_the_same_answer(steel, quads):
    """Decision: a mesh whose cells are all clockwise (inverted as a whole) is accepted; a
    cell turning against the rest is refused (test_mesh_validation). scikit-fem sorts simplex vertices
    and integrates with |det J|, and the gradients use the inverse map, so the vertex order
    of a cell that does not fold over does not change the result."""
    mesh = square_mesh(4, quads)
    flipped_t = mesh.t[::-1] if quads else mesh.t[[0, 2, 1]]
    flipped = type(mesh)(mesh.p, flipped_t)
    if quads:  # every cell now has the opposite orientation
        assert np.all(np.sign(corner_jacobians(flipped)) == -np.sign(corner_jacobians(mesh)))
    u = []
    for m in (mesh, flipped):
        model = Model(with_edges(m), steel, PlaneStress(0.01), order=2)
        u.append(solve_static(model, [Fixed("left")], [Force("right", (0.0, -1e3))]).mean_displacement("right"))
    # identical element matrices up to round-off in their summation order
    assert np.allclose(u[0], u[1], rtol=0, atol=1e-10 * np.abs(u[0]).max())


# --- groups and loads ----------------------------------------------------------------------------

def test_unknown_groups_list_the_existing_ones(beam):
    with pytest.raises(ValueError, match=r"no group 'root'; boundary groups: \['fixed', 'tip'\], subdomains: \['body'\]"):
        solve_static(beam, [Fixed("root")], [Force("tip", (0.0, 1.0))])
    with pytest.raises(ValueError, match=r"no boundary group 'end'; boundary groups: \['fixed', 'tip'\]"):
        solve_static(beam, [Fixed("fixed")], [Traction("end", (0.0, 1.0))])
    with pytest.raises(ValueError, match=r"no subdomain 'web'; subdomains: \['body'\]"):
        solve_static(beam, [Fixed("fixed")], [BodyForce((0.0, 1.0), group="web")])


def test_boundary_load_on_a_subdomain_says_so(beam):
    with pytest.raises(ValueError, match="'body' is a subdomain, not a boundary group.*BodyForce"):
        solve_static(beam, [Fixed("fixed")], [Force("body", (0.0, 1.0))])


def test_loads_and_supports_on_no_nodes(beam):
    empty = Model(beam.mesh.with_groups(boundaries={"nothing": np.array([], dtype=int)}),
                  beam.material, beam.formulation)
    with pytest.raises(ValueError, match="'nothing' has no facets: a load on it would act on no nodes"):
        solve_static(empty, [Fixed("fixed")], [Force("nothing", (0.0, 1.0))])
    with pytest.raises(ValueError, match="support on 'nothing' acts on no nodes"):
        solve_static(empty, [Fixed("fixed"), Fixed("nothing")], [Force("tip", (0.0, 1.0))])


def test_point_force_off_the_body(beam):
    # 0.5 m above a 0.1 m deep beam: no vertex there, the force would silently move
    with pytest.raises(ValueError, match=r"PointForce.point = \(0.5, 0.6\) m is 0.5 m from .* not on the body"):
        solve_static(beam, [Fixed("fixed")], [PointForce((0.5, 0.6), (0.0, 1.0))])
    # a point inside an element is fine: it goes to the nearest vertex
    result = solve_static(beam, [Fixed("fixed")], [PointForce((0.51, 0.052), (0.0, 1.0))])
    assert result.applied_force == pytest.approx([0.0, 1.0])


@pytest.mark.parametrize("load, words", [
    (Force("tip", (0.0, 1.0, 0.0)), "Force has 3 components; the model is 2-D: give 2"),
    (Traction("tip", (1.0,)), "Traction has 1 components; the model is 2-D: give 2"),
    (PointForce((1.0, 0.1), (0.0, 1.0, 0.0)), "PointForce.vector has 3 components"),
    (PointForce((1.0, 0.1, 0.0), (0.0, 1.0)), r"PointForce.point = .* has 3 coordinates; the model is 2-D: give 2"),
    (BodyForce((0.0, 1.0, 0.0)), "BodyForce has 3 components"),
    (Gravity((0.0, 0.0, -9.81)), "Gravity has 3 components"),
])
def test_wrong_vector_dimensions_2d(beam, load, words):
    with pytest.raises(ValueError, match=words):
        solve_static(beam, [Fixed("fixed")], [load])


def test_wrong_vector_dimensions_3d(box):
    with pytest.raises(ValueError, match="Gravity has 2 components; the model is 3-D: give 3"):
        solve_static(box, [Fixed("fixed")], [Gravity()])  # the default is 2-D
    with pytest.raises(ValueError, match="prescribes z in a 2-D model"):
        solve_static(Model(beam_2d(1.0, 0.1, 0.1), box.material, PlaneStress(0.01)),
                     [Prescribed("fixed", z=0.0)], [])


@pytest.mark.parametrize("make, words", [
    (lambda: Force("tip", 1.0), "must be a sequence of 2 .* or 3 .* numbers"),
    (lambda: Force("tip", (np.nan, 0.0)), "must be finite"),
    (lambda: Traction("tip", (np.inf, 0.0)), "must be finite"),
    (lambda: PointForce((0.0, np.nan), (1.0, 0.0)), "PointForce.point .* must be finite"),
    (lambda: Gravity(("down", 0.0)), "Gravity.acceleration .* sequence"),
    (lambda: Prescribed("fixed"), "prescribes no component; give x, y or z"),
    (lambda: Prescribed("fixed", x=np.nan), "must be a finite number"),
    (lambda: Prescribed("fixed", y="0"), "must be a finite number .* or a function"),
])
def test_malformed_loads_and_supports(make, words):
    with pytest.raises(ValueError, match=words):
        make()


def test_prescribed_function_returning_bad_values(beam):
    with pytest.raises(ValueError, match=r"Prescribed\('fixed'\).x: the function returns a non-finite value at"):
        with np.errstate(invalid="ignore"):
            solve_static(beam, [Prescribed("fixed", x=lambda p: np.log(p[1] - 0.05), y=0.0)], [])
    with pytest.raises(ValueError, match="must return one number per point"):
        solve_static(beam, [Prescribed("fixed", x=lambda p: p, y=0.0)], [])


# --- singular systems ----------------------------------------------------------------------------

def test_no_supports(beam):
    with pytest.raises(UnderConstrainedError, match="no supports: all 3 rigid-body modes are free"):
        solve_static(beam, [], [Force("tip", (0.0, 1.0))])


def test_supports_that_leave_a_translation_free(box):
    with pytest.raises(UnderConstrainedError, match="leave 1 of 6 rigid-body modes free"):
        solve_static(box, [Prescribed("fixed", x=0.0, y=0.0)], [Force("tip", (0.0, 1.0, 0.0))])


def test_supports_that_leave_a_rotation_free(steel):
    # rollers: u_x = 0 along the bottom edge, u_y = 0 along the left edge. Both translations are
    # held, but the rotation about the corner (u = theta (-y, x)) vanishes on both: free
    model = Model(with_edges(square_mesh(4)), steel, PlaneStress(0.01))
    supports = [Prescribed("bottom", x=0.0), Prescribed("left", y=0.0)]
    with pytest.raises(UnderConstrainedError, match="leave 1 of 3 rigid-body modes free"):
        solve_static(model, supports, [Force("right", (1.0, 0.0))])
    # an UnderConstrainedError is a SingularSystemError is a ValueError (CLI exit code 2)
    assert issubclass(UnderConstrainedError, SingularSystemError)
    assert issubclass(SingularSystemError, ValueError)


@pytest.mark.parametrize("solver", ["direct", "amg"])
def test_part_connected_to_nothing(steel, solver):
    # two unit squares 1 m apart in one mesh; only the left one is held
    p = np.array([[0, 1, 1, 0, 2, 3, 3, 2], [0, 0, 1, 1, 0, 0, 1, 1]], dtype=float)
    t = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]).T
    model = Model(with_edges(skfem.MeshTri(p, t)), steel, PlaneStress(0.01))
    with pytest.raises(UnderConstrainedError, match=r"2 disconnected parts and part 2 \(centred near \[2.5, 0.5\] m\) "
                                                    "has 3 of 3 rigid-body modes free"):
        solve_static(model, [Fixed("left")], [Force("right", (0.0, 1.0))], solver=solver)
    # held on both parts, it solves
    result = solve_static(model, [Fixed("left"), Fixed("right")], [Gravity((0.0, -9.81))], solver=solver)
    assert np.all(np.isfinite(result.u))


def test_small_and_graded_meshes_are_not_degenerate(steel):
    # a MEMS-sized square (1 um) with one cell column 1000x narrower than the rest: the
    # degeneracy test is relative to each element's own size, not to the mesh's
    x = np.array([0.0, 1e-9, 0.5e-6, 1e-6])
    mesh = skfem.MeshTri.init_tensor(x, np.array([0.0, 0.5e-6, 1e-6]))
    model = Model(with_edges(mesh), steel, PlaneStress(1e-6), order=1)
    result = solve_static(model, [Fixed("left")], [Force("right", (1e-6, 0.0))])
    assert result.mean_displacement("right")[0] > 0
