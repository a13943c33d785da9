"""The continuum's large-deflection tangent (fem/assembly.py's batched
tangent_stiffness_upper): the derivative of the internal force at a strained, rotated state
(central differences), skfem's generic assembly of the same form, and the linear stiffness
at rest, in 2-D and 3-D."""
import sys
from pathlib import Path

import numpy as np
import pytest
import skfem
from skfem.helpers import grad

from flexfem.fem import Model, PlaneStress, Solid3D, material
from flexfem.fem.hyperelastic import Assembler, tangent_modulus

sys.path.insert(0, str(Path(__file__).parent))
from meshes import beam_2d, beam_3d  # noqa: E402


@skfem.BilinearForm
def _reference_tangent(du, v, w):
    return np.einsum("ij...,ijkl...,kl...->...", grad(v), np.asarray(w.A), grad(du))


def _state(model):
    """A turned and strained state: a rotation of 0.3 rad about z plus a random field (DOF
    k is component k % dim of its node)."""
    x = model.basis.doflocs  # (dim, n_dofs): where each DOF sits
    c, s = np.cos(0.3), np.sin(0.3)
    turned = np.array(x, float)
    turned[0], turned[1] = c * x[0] - s * x[1], s * x[0] + c * x[1]
    k = np.arange(model.n_dofs)
    return (turned - x)[k % model.dim, k] + 1e-5 * np.random.default_rng(3).standard_normal(k.size)


@pytest.mark.parametrize("dim, order", [(2, 2), (3, 1), (3, 2)])
def test_the_tangent_is_the_internal_forces_derivative(dim, order):
    mesh = beam_2d(0.1, 0.01, 0.004) if dim == 2 else beam_3d(0.1, 0.01, 0.01, 0.004)
    model = Model(mesh, material("structural_steel"), PlaneStress(0.002) if dim == 2 else
                  Solid3D(), order=order)
    asm = Assembler(model)
    u = _state(model)
    K = asm.tangent(*asm.state(u))
    du = np.random.default_rng(4).standard_normal(model.n_dofs)
    h = 1e-7
    difference = (asm.internal_force(*asm.state(u + h * du))
                  - asm.internal_force(*asm.state(u - h * du))) / (2 * h)
    assert np.linalg.norm(K @ du - difference) <= 1e-6 * np.linalg.norm(difference)
    reference = _reference_tangent.assemble(
        asm.basis, A=asm.t * tangent_modulus(*asm.state(u), asm.lam, asm.mu))
    assert abs(K - reference).max() <= 1e-12 * abs(reference).max()
    rest = asm.tangent(*asm.state(np.zeros(model.n_dofs)))
    assert abs(rest - model.stiffness).max() <= 1e-12 * abs(model.stiffness).max()
