"""Stress concentration at a circular hole in a plate under tension (Kirsch 1898), on a quarter
model with symmetry supports."""
import numpy as np
import pytest
import skfem
from flexfem.fem import (
    Model,
    PlaneStress,
    Prescribed,
    Traction,
    gmsh_session,
    mesh_from_gmsh,
    solve_static,
)

A_HOLE = 0.005       # hole radius a (m)
HALF_WIDTH = 0.05    # plate width W = 0.1 m: W / d = 10
HALF_LENGTH = 0.1    # plate length 2 W: the loaded end is 2 widths from the hole
SIGMA = 1e6          # remote tension (Pa)


def quarter_plate_with_hole(a, half_width, half_length, size_at_hole, size_far):
    """Quarter of a plate [0, half_length] x [0, half_width] minus the hole of radius ``a`` at
    the origin (m); groups 'sym_x' (x = 0), 'sym_y' (y = 0), 'end' (x = half_length)."""
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        plate = occ.addRectangle(0, 0, 0, half_length, half_width)
        hole = occ.addDisk(0, 0, 0, a, a)
        (surface,), _ = occ.cut([(2, plate)], [(2, hole)])
        occ.synchronize()
        gmsh.model.addPhysicalGroup(2, [surface[1]], name="body")
        arc = []
        for _, tag in gmsh.model.getBoundary([surface], oriented=False):
            x, y, _ = occ.getCenterOfMass(1, tag)
            if np.isclose(x, 0.0):
                gmsh.model.addPhysicalGroup(1, [tag], name="sym_x")
            elif np.isclose(y, 0.0):
                gmsh.model.addPhysicalGroup(1, [tag], name="sym_y")
            elif np.isclose(x, half_length):
                gmsh.model.addPhysicalGroup(1, [tag], name="end")
            elif np.hypot(x, y) < a:
                arc.append(tag)
        field = gmsh.model.mesh.field
        distance = field.add("Distance")
        field.setNumbers(distance, "CurvesList", arc)
        threshold = field.add("Threshold")
        field.setNumber(threshold, "InField", distance)
        field.setNumber(threshold, "SizeMin", size_at_hole)
        field.setNumber(threshold, "SizeMax", size_far)
        field.setNumber(threshold, "DistMin", a / 2)
        field.setNumber(threshold, "DistMax", 4 * a)
        field.setAsBackgroundMesh(threshold)
        for option in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
            gmsh.option.setNumber(f"Mesh.{option}", 0)
        gmsh.model.mesh.generate(2)
        return mesh_from_gmsh(gmsh)


def stress_at(model, u, point):
    """Cauchy stress (Pa, 3 x 3) at ``point`` (m): the average, over the elements that touch it,
    of each element's own polynomial stress evaluated there (no smoothing or projection)."""
    mesh = model.mesh.mesh
    vertex = int(np.argmin(np.sum((mesh.p - np.reshape(point, (2, 1))) ** 2, axis=0)))
    elements = np.flatnonzero(np.any(mesh.t == vertex, axis=0))
    values = []
    for e in elements:
        local = mesh.mapping().invF(mesh.p[:, [vertex]][:, :, None], tind=np.array([e]))[:, 0, :]
        basis = skfem.Basis(mesh, model.basis.elem, elements=np.array([e]),
                            quadrature=(local, np.ones(1)))
        values.append(model.stress(u, basis)[:, :, 0, 0])
    return np.mean(values, axis=0)


def heywood_kt_gross(d_over_w):
    """Kt on the gross section of a finite-width strip with a central hole (Heywood's fit to
    Howland's solution): Kt_net = 2 + (1 - d/W)^3, Kt_gross = Kt_net / (1 - d/W)."""
    return (2 + (1 - d_over_w) ** 3) / (1 - d_over_w)


@pytest.fixture(scope="module")
def plate_result(steel):
    mesh = quarter_plate_with_hole(A_HOLE, HALF_WIDTH, HALF_LENGTH, A_HOLE / 12, HALF_WIDTH / 6)
    model = Model(mesh, steel, PlaneStress(thickness=0.001), order=2)
    supports = [Prescribed("sym_x", x=0.0), Prescribed("sym_y", y=0.0)]
    return solve_static(model, supports, [Traction("end", (SIGMA, 0.0))])


def test_kirsch_stress_concentration(plate_result):
    model, u = plate_result.model, plate_result.u
    sig_top = stress_at(model, u, (0.0, A_HOLE))
    kt = sig_top[0, 0] / SIGMA
    expected = heywood_kt_gross(2 * A_HOLE / (2 * HALF_WIDTH))  # 3.03 for d/W = 0.1
    # Heywood's fit is within 1 % of Howland for d/W <= 0.5; the length 2 W adds an end effect
    # decaying like exp(-pi x / W) (< 0.1 %); P2 with h = a/12 at the hole and a 12-segment
    # polygonal quarter circle: stress error ~ (h/a)^2 ~ 1 %. Allow 2 %.
    assert kt == pytest.approx(expected, rel=0.02)
    # The infinite-plate value 3 (Kirsch) is 1 % below the finite-width one
    assert kt > 3.0 * 0.99
    # the hole edge is traction free: sigma_yy = tau_xy = 0 there, to the same error
    assert abs(sig_top[1, 1]) < 0.03 * SIGMA and abs(sig_top[0, 1]) < 0.03 * SIGMA


def test_stress_at_agrees_with_the_per_element_average_at_the_hole(plate_result):
    """``StaticResult.stress_at`` (one containing element, P2's own field) against the
    average over the elements touching the hole's top vertex: they differ by the jump of
    the discontinuous P1 stress between elements, O(h^2) ~ 1 % at h = a/12; allow 3 %."""
    sig = plate_result.stress_at([(0.0, A_HOLE)], full=True)[0]
    assert sig[0, 0] == pytest.approx(stress_at(plate_result.model, plate_result.u,
                                                 (0.0, A_HOLE))[0, 0], rel=0.03)
    assert sig[0, 0] / SIGMA == pytest.approx(heywood_kt_gross(0.1), rel=0.03)
    # the nodal (L2-projected) field at that vertex too
    vertex = int(np.argmin(np.hypot(*(plate_result.model.mesh.mesh.p - [[0.0], [A_HOLE]]))))
    assert plate_result.nodal_stress[vertex, 0, 0] / SIGMA == pytest.approx(3.03, rel=0.03)


def test_kirsch_compression_at_the_side_and_ligament_decay(plate_result):
    model, u = plate_result.model, plate_result.u
    # Kirsch: sigma_yy = -sigma at (a, 0). We know no closed-form finite-width correction for
    # this point; the side walls at W/2 = 10 a push the magnitude up (measured +2.9 % on a mesh
    # twice as fine, see docs/verification.md), discretisation ~1 %: allow 5 %, one-sided
    # (the finite width cannot lower the magnitude below the infinite-plate value by more than
    # the discretisation error)
    sig_side = stress_at(model, u, (A_HOLE, 0.0))[1, 1] / SIGMA
    assert -1.05 < sig_side < -0.99
    # the recovered nodal maximum sits on the hole at its top
    where = plate_result.max_von_mises_location
    assert np.hypot(*where) == pytest.approx(A_HOLE, rel=1e-6)
    assert where[1] > 0.9 * A_HOLE


def test_quarter_model_reactions_balance_the_traction(plate_result):
    # the symmetry plane x = 0 carries the whole end load (sigma * net ligament * thickness)
    applied = SIGMA * HALF_WIDTH * 0.001
    assert plate_result.applied_force[0] == pytest.approx(applied, rel=1e-12)
    assert plate_result.reactions["sym_x"][0] == pytest.approx(-applied, rel=1e-9)
    assert abs(plate_result.reactions["sym_y"][1]) < 1e-9 * applied
