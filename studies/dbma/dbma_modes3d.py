"""The DBMA's modes in 3-D: the solid continuum (the 2-D drawing extruded through the plate
thickness d in layers of quadratic hexahedra) beside the spatial beam model
(:func:`flexfem.reduced.dbma.dbma_beam3d_model`), paired by shape.

    out = compare_modes3d(paper_design(), n_modes=10)
    out["rows"]                # family, k, beam_hz, continuum_hz, diff_pct, mass fractions
    out["saint_venant_rows"]   # the same without the hinges' warping restraint

Both held as the 2-D modal analysis: the mounting face clamped, the pads held along x by the
actuator (the beam: each pad-face node's x and its rotations about y and z, which a face held
along x cannot have). The modes are sorted into an in-plane and an out-of-plane family and
paired within each (:mod:`flexfem.studies.mode_pairing`). SI units; frequencies in Hz.
"""
import time

import numpy as np

from ...fem import solve_modes
from ...fem.beam.spatial import solve_beam3d_modes
from ...fem.beam.supports import NodeFixed, NodePrescribed
from ...reduced.layout import ROOT_EXTENSION
from ...reduced.dbma import dbma_beam3d_model
from ...geometry.dbma.drawing import DBMALayout
from ...geometry.dbma.params import DBMAParams, paper_design
from ...reduced.torsion import TorsionScaled, vlasov_factor
from ..mode_pairing import (SPLIT, mirror_vertices, out_of_plane_share, pair_modes)
from .analysis import build_model, modal_supports

PAD_DOFS = ("x", "ry", "rz")  # what the actuator holds on a pad face


def beam_modes3d(p: DBMAParams, layout: DBMALayout | None = None, n_modes: int = 10,
                 warping: bool = True, root_extension: float = ROOT_EXTENSION,
                 member_patch: bool = True) -> dict:
    """The spatial beam model's first ``n_modes``: {"f_hz", "mass_fraction" (n, 3),
    "out_of_plane_share" (of the nodes' translations), "total_mass_kg"}. ``warping``: each
    hinge's J times :func:`~flexfem.reduced.torsion.vlasov_factor` for its l x b x d strip
    (the arms and members it enters hold its ends against warping, which Saint-Venant
    torsion leaves out); leaf hinges only. The spatial model lifts the planar one with block
    input members; its in-plane and out-of-plane modes do not couple (a plate symmetric about
    its mid-plane), so with ``member_patch`` its in-plane family is the planar model's with
    the input members' 2-D patches (:func:`_planar_family`)."""
    layout = layout or DBMALayout()
    if warping and layout.hinge_profile != "leaf":
        raise ValueError(f"warping = True needs leaf hinges (a uniform strip); the layout's "
                         f"hinge_profile is {layout.hinge_profile!r}: pass warping=False")
    model, info = dbma_beam3d_model(p, layout, root_extension)
    if warping:
        factors = np.ones(model.n_elements)
        factors[info["hinge_elements"]] = vlasov_factor(p.l, p.b, p.d, p.nu)
        model = TorsionScaled(model, factors)
    supports = [NodeFixed(tuple(info["ground"]))] + [
        NodePrescribed(info[pad], dof, 0.0) for pad in ("input_a", "input_b") for dof in PAD_DOFS]
    modes = solve_beam3d_modes(model, supports, n=n_modes)
    u = modes.shapes[:, :, :3]
    share = np.sum(u[:, :, 2] ** 2, axis=1) / np.sum(u ** 2, axis=(1, 2))
    out = {"f_hz": modes.frequencies_hz.tolist(),
           "mass_fraction": modes.effective_mass_fraction.tolist(),
           "out_of_plane_share": share.tolist(), "total_mass_kg": float(modes.total_mass)}
    return _planar_family(out, p, layout, root_extension, n_modes) if member_patch else out


def _planar_family(out: dict, p, layout, root_extension, n_modes: int) -> dict:
    """``out`` with its in-plane modes replaced by the planar beam model's (member patches
    on), merged by frequency, the first ``n_modes`` kept."""
    from ...reduced.dbma import dbma_beam_model
    from .analysis import modal_response

    model, _ = dbma_beam_model(p, layout, root_extension)
    planar = modal_response(model, n_modes)[1]
    fraction = np.column_stack([planar.effective_mass / out["total_mass_kg"],
                                np.zeros(n_modes)])
    rows = [(f, m, 0.0) for f, m in zip(planar.frequencies_hz, fraction.tolist())]
    rows += [row for row in zip(out["f_hz"], out["mass_fraction"], out["out_of_plane_share"])
             if row[2] > SPLIT]
    rows = sorted(rows, key=lambda row: row[0])[:n_modes]
    return {**out, "f_hz": [float(r[0]) for r in rows], "mass_fraction": [r[1] for r in rows],
            "out_of_plane_share": [r[2] for r in rows]}


def continuum_modes3d(p: DBMAParams, layout: DBMALayout | None = None, n_modes: int = 10,
                      size_factor: float = 1.0, max_dofs: int | None = None) -> dict:
    """The solid's first ``n_modes``: {"f_hz", "mass_fraction" (n, 3), "out_of_plane_share",
    "total_mass_kg", "dofs", "solve_s" (wall-clock s, mesh included)}."""
    t0 = time.perf_counter()
    model = build_model(p, layout, 3, size_factor, max_dofs=max_dofs)
    modes = solve_modes(model, n=n_modes, supports=modal_supports())
    points = model.mesh.mesh.p
    mid = (points[2].min() + points[2].max()) / 2  # the plate spans 0 <= z <= d
    shapes = np.array([modes.vertex_shape(k) for k in range(n_modes)])
    share = out_of_plane_share(shapes, mirror_vertices(points - np.array([[0], [0], [mid]])))
    return {"f_hz": modes.frequencies_hz.tolist(),
            "mass_fraction": modes.effective_mass_fraction.tolist(),
            "out_of_plane_share": share.tolist(), "total_mass_kg": float(modes.total_mass),
            "dofs": int(model.n_dofs), "solve_s": time.perf_counter() - t0}


def compare_modes3d(p: DBMAParams | None = None, layout: DBMALayout | None = None,
                    n_modes: int = 10, size_factor: float = 1.0,
                    max_dofs: int | None = None) -> dict:
    """Beam and continuum modes side by side: {"rows" (see
    :func:`~flexfem.studies.mode_pairing.pair_modes`; the beam with the hinges' warping
    restraint where they are leaves, else Saint-Venant's), "saint_venant_rows" (without
    it), "beam", "saint_venant", "continuum"}."""
    p, layout = p or paper_design(), layout or DBMALayout()
    continuum = continuum_modes3d(p, layout, n_modes, size_factor, max_dofs)
    plain = beam_modes3d(p, layout, n_modes, warping=False)
    beam = beam_modes3d(p, layout, n_modes) if layout.hinge_profile == "leaf" else plain
    return {"rows": pair_modes(beam, continuum), "saint_venant_rows": pair_modes(plain, continuum),
            "beam": beam, "saint_venant": plain, "continuum": continuum}
