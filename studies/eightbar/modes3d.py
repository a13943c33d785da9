"""The eight-bar suspension's modes in 3-D: the solid continuum (the 2-D drawing extruded
through its thickness, quadratic tetrahedra) beside the spatial beam model
(:func:`flexfem.geometry.eightbar.beam3d.eightbar_beam3d_model`), paired by shape.

    out = compare_modes(EightBarFlexureParams(), n_modes=10)
    out["rows"]  # family, k, beam_hz, continuum_hz, diff_pct, effective mass fractions

The part is symmetric about its mid-plane z = 0, so each mode is either in plane (u_x, u_y
even in z, u_z odd) or out of plane (u_x, u_y odd, u_z even): the share of a mode's vertex
motion in the out-of-plane parts sorts it (0 or 1 up to the mesh's asymmetry; the beam's are
exactly 0 or 1). Within each family the k-th continuum mode is paired with the k-th beam
mode; the effective mass fractions (x, y, z) of both are kept beside it to check the pairing.
Anchors clamped in both models. SI units; frequencies in Hz.
"""
import time

import numpy as np
import skfem
from scipy.spatial import cKDTree
from skfem.models.elasticity import linear_elasticity

from ...fem import Fixed, solve_modes
from ...fem.beam3d import Beam3DModel, rect_torsion_constant, solve_beam3d_modes
from ...fem.beam3d import Fixed as BeamFixed
from ...fem.beam3d.energy import strain_energy_share
from ...geometry.eightbar.beam3d import eightbar_beam3d_model
from ...geometry.eightbar.flexure import EightBarFlexureParams
from .analysis import build_model

SPLIT = 0.5  # out-of-plane share above which a mode is out of plane


def mirror_vertices(p: np.ndarray) -> np.ndarray:
    """Index of each vertex's mirror image about z = 0 (``p`` (3, n) m). Raises ValueError
    if the mesh is not mirror-symmetric (a vertex without its image within 1e-9 of the
    part's size)."""
    tree = cKDTree(p.T)
    mirrored = p.T * np.array([1.0, 1.0, -1.0])
    dist, index = tree.query(mirrored)
    size = np.ptp(p, axis=1).max()
    if dist.max() > 1e-9 * size:
        raise ValueError(f"the mesh is not symmetric about z = 0 (a vertex {dist.max():.3g} m "
                         "from its image); extrude the part symmetrically")
    return index


def out_of_plane_share(vertex_shapes, mirror: np.ndarray) -> np.ndarray:
    """Share (0-1) of each mode's vertex motion in the out-of-plane parts: u_x, u_y odd and
    u_z even in z. ``vertex_shapes``: (n_modes, n_vertices, 3)."""
    u = np.asarray(vertex_shapes)
    even, odd = (u + u[:, mirror]) / 2, (u - u[:, mirror]) / 2
    out = np.sum(odd[:, :, :2] ** 2, axis=(1, 2)) + np.sum(even[:, :, 2] ** 2, axis=1)
    inp = np.sum(even[:, :, :2] ** 2, axis=(1, 2)) + np.sum(odd[:, :, 2] ** 2, axis=1)
    return out / (out + inp)


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


def vlasov_factor(length: float, depth: float, width: float, nu: float) -> float:
    """Torsional stiffness of a rectangular depth x width (m, depth << width) bar of
    ``length`` (m) with warping restrained at both ends over its Saint-Venant one (Vlasov):
    1 / (1 - 2 tanh(lambda L / 2) / (lambda L)), lambda^2 = G J / (E Gamma), Gamma =
    width^3 depth^3 / 144."""
    lam = np.sqrt(rect_torsion_constant(depth, width) / (2 * (1 + nu))
                  / (width**3 * depth**3 / 144))
    x = lam * length
    return float(1 / (1 - 2 * np.tanh(x / 2) / x))


class _TorsionScaled(Beam3DModel):
    """A beam model whose elements' J are multiplied by ``factors`` (n_elements,)."""

    def __init__(self, base: Beam3DModel, factors):
        super().__init__(base.nodes, base.elements, base.sections, base.material,
                         rigid_links=base.rigid_links, point_masses=base.point_masses)
        self.j_factors = np.asarray(factors, dtype=float)

    def section_at(self, xi) -> dict:
        out = super().section_at(xi)
        out["J"] = out["J"] * self.j_factors[:, None]
        return out


def beam_modes(params: EightBarFlexureParams, n_modes: int = 10, warping: bool = False,
               links: str = "flexible") -> dict:
    """The spatial beam model's first ``n_modes`` (anchors clamped): {"f_hz",
    "mass_fraction", "out_of_plane_share" (of the nodes' translations), "total_mass_kg",
    "links_energy_share" (strain energy outside the flexures: links and anchors; 0 with
    rigid links)}. ``links``: "flexible" (link plates and anchors as beams) or "rigid"
    (:func:`~flexfem.geometry.eightbar.beam3d.eightbar_beam3d_model`). ``warping``: each
    flexure's J times its :func:`vlasov_factor` (the beam's Saint-Venant torsion leaves the
    roots' warping restraint out)."""
    model, info = eightbar_beam3d_model(params, links=links)
    if warping:
        factors = np.ones(len(model.elements))
        nu = model.material.nu
        for joint, (first, last) in info["flexures"].items():
            length, depth = params.flexure_size(joint)
            factors[first:last] = vlasov_factor(length, depth, params.thickness, nu)
        model = _TorsionScaled(model, factors)
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


def pair_modes(beam: dict, continuum: dict, split: float = SPLIT) -> list:
    """Rows pairing the k-th beam and continuum mode of each family ("in plane", "out of
    plane"), as far as both have one: {"family", "k", "beam_mode", "continuum_mode"
    (1-based), "beam_hz", "continuum_hz", "diff_pct" (beam over continuum - 1),
    "beam_mass_fraction", "continuum_mass_fraction" (x, y, z)}."""
    rows = []
    for family, out in (("in plane", False), ("out of plane", True)):
        b = [i for i, s in enumerate(beam["out_of_plane_share"]) if (s > split) == out]
        c = [i for i, s in enumerate(continuum["out_of_plane_share"]) if (s > split) == out]
        for k, (i, j) in enumerate(zip(b, c)):
            fb, fc = beam["f_hz"][i], continuum["f_hz"][j]
            rows.append({"family": family, "k": k + 1, "beam_mode": i + 1,
                         "continuum_mode": j + 1, "beam_hz": fb, "continuum_hz": fc,
                         "diff_pct": 100 * (fb / fc - 1),
                         "beam_mass_fraction": list(beam["mass_fraction"][i]),
                         "continuum_mass_fraction": list(continuum["mass_fraction"][j])})
    return rows


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
