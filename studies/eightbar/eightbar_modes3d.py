"""The eight-bar suspension's modes in 3-D: the solid continuum (the 2-D drawing extruded
through its thickness, quadratic tetrahedra) beside the spatial beam model
(:func:`flexfem.reduced.eightbar3d.eightbar_beam3d_model`), paired by shape.

    out = compare_modes(EightBarFlexureParams(), n_modes=10)
    out["rows"]  # family, k, beam_hz, continuum_hz, diff_pct, effective mass fractions

The modes are sorted into an in-plane and an out-of-plane family by their shapes and paired
within each (:mod:`flexfem.studies.mode_pairing`); the effective mass fractions (x, y, z) of both
are kept beside each pair to check the pairing.
Anchors clamped in both models. SI units; frequencies in Hz.
"""
import time

import numpy as np
import skfem
from skfem.models.elasticity import linear_elasticity

from ...fem import Fixed, solve_modes
from ...fem.beam.spatial import solve_beam3d_modes
from ...fem.beam.supports import NodeFixed as BeamFixed
from ...fem.beam.spatial.energy import strain_energy_share
from ...reduced.layout import ROOT_EXTENSION
from ...reduced.eightbar3d import eightbar_beam3d_model
from ...geometry.eightbar.flexure import EightBarFlexureParams
from ...reduced.torsion import TorsionScaled, vlasov_factor
from ..mode_pairing import mirror_vertices, out_of_plane_share, pair_modes
from .continuum_model import build_model


def energy_share(model, shapes: np.ndarray, subdomain: str) -> np.ndarray:
    """Share (0-1) of each mode's strain energy in the elements of ``subdomain``:
    phi.K_sub.phi / phi.K.phi (``shapes`` (n, n_dofs))."""
    basis = skfem.Basis(model.mesh.mesh, model.basis.elem, intorder=2 * (model.order - 1),
                        elements=model.mesh.subdomains[subdomain])
    K_sub = skfem.asm(linear_elasticity(*model.lame), basis)
    return np.array([(phi @ (K_sub @ phi)) / (phi @ (model.stiffness @ phi)) for phi in shapes])


def continuum_modes(params: EightBarFlexureParams, n_modes: int = 10, size_factor: float = 1.0,
                    layers: int | None = None, n_across: int = 3,
                    max_dofs: int | None = None) -> dict:
    """The solid's first ``n_modes`` (anchors clamped): {"f_hz", "mass_fraction" (n, 3),
    "out_of_plane_share", "links_energy_share" (strain energy outside the flexures), "dofs",
    "mesh_s", "solve_s" (wall-clock s), "sizes" (m)}."""
    t0 = time.perf_counter()
    model, sizes = build_model(params, size_factor, n_across, max_dofs, dim=3, layers=layers)
    t1 = time.perf_counter()
    # a shift just below zero, as the 2-D modal analysis (few-Hz modes)
    modes = solve_modes(model, n=n_modes, supports=[Fixed("fixed")], shift_hz=-1.0)
    t2 = time.perf_counter()
    shapes = np.array([modes.vertex_shape(k) for k in range(n_modes)])
    share = out_of_plane_share(shapes, mirror_vertices(model.mesh.mesh.p))
    # the energy outside the flexures: in the parts the beam model makes rigid
    rigid = 1 - energy_share(model, modes.shapes, "flexures")
    return {"f_hz": modes.frequencies_hz.tolist(), "links_energy_share": rigid.tolist(),
            "mass_fraction": modes.effective_mass_fraction.tolist(),
            "out_of_plane_share": share.tolist(), "dofs": int(model.n_dofs),
            "mesh_s": t1 - t0, "solve_s": t2 - t1, "sizes": sizes, "solver": modes.solver,
            "total_mass_kg": float(modes.total_mass)}


def beam_modes(params: EightBarFlexureParams, n_modes: int = 10, warping: bool = False,
               links: str = "flexible", root_extension: float = ROOT_EXTENSION) -> dict:
    """The spatial beam model's first ``n_modes`` (anchors clamped): {"f_hz",
    "mass_fraction", "out_of_plane_share" (of the nodes' translations), "total_mass_kg",
    "links_energy_share" (strain energy outside the flexures: links and anchors; 0 with
    rigid links)}. ``links``: "flexible" (link plates and anchors as beams) or "rigid"
    (:func:`~flexfem.reduced.eightbar3d.eightbar_beam3d_model`). ``warping``: each
    flexure's J times its :func:`vlasov_factor` (the beam's Saint-Venant torsion leaves the
    roots' warping restraint out)."""
    model, info = eightbar_beam3d_model(params, root_extension=root_extension, links=links)
    if warping:
        factors = np.ones(len(model.elements))
        nu = model.material.nu
        for joint, (first, last) in info["flexures"].items():
            length, depth = params.flexure_size(joint)
            factors[first:last] = vlasov_factor(length, depth, params.thickness, nu)
        model = TorsionScaled(model, factors)
    modes = solve_beam3d_modes(model, [BeamFixed(tuple(info["ground"]))], n=n_modes)
    u = modes.shapes[:, :, :3]
    share = np.sum(u[:, :, 2] ** 2, axis=1) / np.sum(u ** 2, axis=(1, 2))
    flexures = [e for a, b in info["flexures"].values() for e in range(a, b)]
    outside = np.setdiff1d(np.arange(model.n_elements), flexures)
    energy = (strain_energy_share(model, modes.shapes, outside) if len(outside)
              else np.zeros(n_modes))
    return {"f_hz": modes.frequencies_hz.tolist(),
            "mass_fraction": modes.effective_mass_fraction.tolist(),
            "out_of_plane_share": share.tolist(), "total_mass_kg": float(modes.total_mass),
            "links_energy_share": energy.tolist()}


def compare_modes(params: EightBarFlexureParams | None = None, n_modes: int = 10,
                  size_factor: float = 1.0, layers: int | None = None,
                  max_dofs: int | None = None) -> dict:
    """Beam and continuum modes of ``params`` (default design) side by side: {"rows" (see
    :func:`pair_modes`), "beam" (flexible links), "continuum", "rigid_rows", "rigid" (the
    beam model with rigid links)}."""
    params = params or EightBarFlexureParams()
    continuum = continuum_modes(params, n_modes, size_factor, layers, max_dofs=max_dofs)
    beam, rigid = beam_modes(params, n_modes), beam_modes(params, n_modes, links="rigid")
    return {"rows": pair_modes(beam, continuum), "beam": beam, "continuum": continuum,
            "rigid_rows": pair_modes(rigid, continuum), "rigid": rigid}
