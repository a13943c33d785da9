"""The vectorised stiffness and mass assembly of fem/model.py equals scikit-fem's weak-form
assembly, and has the physics a stiffness and a mass matrix must have."""
import numpy as np
import pytest
import skfem
from flexfem.fem import FEMesh, Model, PlaneStrain, PlaneStress, Solid3D
from flexfem.fem.static import rigid_body_dof_modes
from skfem.helpers import ddot, dot, sym_grad, trace


def _distorted(mesh, amount):
    """Move the interior vertices by up to ``amount`` x the cell size (deterministic), so that
    quadrilaterals and hexahedra are not parallelograms and simplices not all alike."""
    rng = np.random.default_rng(0)
    interior = np.setdiff1d(np.arange(mesh.p.shape[1]), mesh.boundary_nodes())
    p = mesh.p.copy()
    h = 1.0 / round(len(mesh.p[0]) ** (1 / mesh.dim()))
    p[:, interior] += amount * h * rng.uniform(-1, 1, (mesh.dim(), len(interior)))
    return type(mesh)(p, mesh.t)


MESHES = {
    "tri": lambda: _distorted(skfem.MeshTri().refined(3), 0.2),
    "quad": lambda: _distorted(skfem.MeshQuad().refined(3), 0.2),
    "tet": lambda: _distorted(skfem.MeshTet().refined(2), 0.1),
    "hex": lambda: _distorted(skfem.MeshHex().refined(2), 0.1),
}
FORMULATIONS = {2: [PlaneStress(0.01), PlaneStrain()], 3: [Solid3D()]}


def _skfem_matrices(model):
    """K and M from skfem's BilinearForm, on the model's own quadrature rules."""
    lam, mu = model.lame
    t, rho = model.thickness, model.material.rho

    @skfem.BilinearForm
    def stiffness(u, v, w):
        return t * (2 * mu * ddot(sym_grad(u), sym_grad(v)) + lam * trace(sym_grad(u)) * trace(sym_grad(v)))

    @skfem.BilinearForm
    def mass(u, v, w):
        return rho * t * dot(u, v)

    return stiffness.assemble(model.stiffness_basis), mass.assemble(model.basis)


def _cases():
    for name, build in MESHES.items():
        dim = 2 if name in ("tri", "quad") else 3
        for formulation in FORMULATIONS[dim]:
            for order in (1, 2):
                yield pytest.param(name, formulation, order,
                                   id=f"{name}-{type(formulation).__name__}-P{order}")


@pytest.mark.parametrize("name, formulation, order", list(_cases()))
def test_assembly_equals_skfem_weak_form(steel, name, formulation, order):
    model = Model(FEMesh(MESHES[name]()), steel, formulation, order=order)
    K0, M0 = _skfem_matrices(model)
    # the same sums of the same products in another order: round-off only, ~1e-16 x the
    # largest entry per added term (at most a few dozen elements share a DOF)
    for new, ref in ((model.stiffness, K0), (model.mass, M0)):
        assert new.shape == ref.shape == (model.n_dofs, model.n_dofs)
        assert abs(new - ref).max() <= 1e-12 * abs(ref).max()


@pytest.mark.parametrize("name", list(MESHES))
def test_rigid_body_modes_cost_no_energy_and_mass_adds_up(steel, name):
    msh = MESHES[name]()
    dim = msh.dim()
    model = Model(FEMesh(msh), steel, FORMULATIONS[dim][0], order=2)
    K, M = model.stiffness, model.mass
    modes = rigid_body_dof_modes(model)
    # K r = 0 for a rigid motion, to round-off relative to K's scale (|K| |r|)
    assert np.abs(K @ modes).max() <= 1e-10 * abs(K).max() * np.abs(modes).max()
    # K is symmetric positive semi-definite: a random field has positive energy
    assert abs(K - K.T).max() <= 1e-14 * abs(K).max()
    u = np.random.default_rng(1).standard_normal(model.n_dofs)
    assert u @ (K @ u) > 0
    # a unit translation carries the whole mass: rho t (area) in 2-D, rho (volume) in 3-D,
    # the unit square or cube (the distortion keeps the boundary)
    translation = modes[:, 0]
    assert np.isclose(translation @ (M @ translation), steel.rho * model.thickness, rtol=1e-12)
    assert abs(M - M.T).max() <= 1e-14 * abs(M).max()

