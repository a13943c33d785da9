"""Where the beam model stops being trustworthy: one hinge between two blocks, beam model
against the 2-D plane-stress continuum, over the hinge's slenderness l/b (2 to 20).

The specimen is :func:`flexfem.geometry.hinge_profiles.mesh_hinge_specimen` (b = 0.5 mm,
w = 5 mm, blocks 10 mm tall and 5 mm long, P2 elements, 4 across the neck): the left block's
end clamped, a unit force on the right block's end, sideways (bending: the hinge's working
compliance) and along the hinge (axial: what carries the DBMA's output load). The beam model
is the hinge from its profile (:func:`flexfem.reduced.layout.profile_beam`, the blocks as
Timoshenko beams), with the common root extension (0.38 x root thickness, axial root
compliance for the block height) and a circular notch's 2-D correction
(:mod:`flexfem.reduced.hinge_patch`), as the mechanisms' models have them, and the bare beam
without either (plain beam theory of the profile). SI units.
"""
import math

import numpy as np

from ...fem import Fixed as FEFixed, Force, Material, Model, PlaneStress, solve_static
from ...fem.beam import (BeamModel, Fixed, NodalLoad, RigidLink, Section, beam_chain,
                         solve_beam_static)
from ...reduced.layout import ROOT_EXTENSION, profile_beam
from ...reduced.hinge_patch import notch_factors
from ...geometry.hinge_profiles import mesh_hinge_specimen, profile_thickness
from ..report.figures import axis_label, legend_outside, pyplot, save

STEEL = Material("steel", E=200e9, nu=0.3, rho=7800.0)
SPECIMEN = {"b": 0.5e-3, "w": 5e-3, "H": 10e-3, "block": 5e-3}
RATIOS = (2.0, 3.0, 5.0, 10.0, 20.0)
TRUST_LIMIT = 0.03  # the beam model is trusted where it is within 3 % of the continuum


def beam_specimen(profile: str, l: float, root_extension: float,
                  notch_correction: bool = True) -> tuple:
    """(sideways, axial) tip compliance (m/N) of the beam model of the specimen; a circular
    notch with its 2-D correction unless ``notch_correction`` is False."""
    b, w, H, Lb = (SPECIMEN[k] for k in ("b", "w", "H", "block"))
    fn = lambda s: float(profile_thickness(profile, l, b, 0.5e-3, s))
    factors = None
    if profile == "circular" and notch_correction:
        factors = notch_factors(profile, l, b, 0.5e-3, STEEL.nu)
    hinge = profile_beam((0.0, 0.0), (l, 0.0), fn, w, (), 40, root_extension, blocks=(H, H),
                         factors=factors)
    a, z = hinge.nodes[hinge.point_nodes[0]], hinge.nodes[hinge.point_nodes[1]]
    left = beam_chain([(-Lb, 0.0), tuple(a)], Section.rect(w, H), 4)
    right = beam_chain([tuple(z), (l + Lb, 0.0)], Section.rect(w, H), 4)
    mesh = left.join(hinge, tol=1e-12).join(right, tol=1e-12)
    model = BeamModel(mesh.nodes, mesh.elements, mesh.sections, STEEL, shear=True)
    tip, root = mesh.node_at((l + Lb, 0.0)), mesh.node_at((-Lb, 0.0))
    out = []
    for load in (NodalLoad(tip, fy=1.0), NodalLoad(tip, fx=1.0)):
        q = solve_beam_static(model, [Fixed(root)], [load]).q
        out.append(float(q[tip, 1] if load.fy else q[tip, 0]))
    return tuple(out)


def leaf_between_blocks(t, l, w, H, Lb, material=STEEL) -> tuple:
    """(BeamModel, the near block's end node, the far block's end node, the leaf's element
    slice) of a leaf t x l, w wide, between two H x Lb blocks, joined as the DBMA's hinges to
    its arms: the blocks as beams, the leaf with its root extensions (into blocks H tall) tied
    to their ends by rigid offsets. Lengths in m."""
    leaf = profile_beam((0.0, 0.0), (l, 0.0), lambda s: np.full_like(s, t), w, (), 8,
                        blocks=(H, H), vectorized=True)
    near = beam_chain([(-Lb, 0.0), (0.0, 0.0)], Section.rect(w, H), 12)
    far = beam_chain([(l, 0.0), (l + Lb, 0.0)], Section.rect(w, H), 12)
    a, b = len(near.nodes), len(near.nodes) + len(leaf.nodes)
    links = [RigidLink(a - 1, (a + leaf.point_nodes[0],)),
             RigidLink(b, (a + leaf.point_nodes[1],))]
    model = BeamModel(np.vstack([near.nodes, leaf.nodes, far.nodes]),
                      np.vstack([near.elements, leaf.elements + a, far.elements + b]),
                      [*near.sections, *leaf.sections, *far.sections], material, shear=True,
                      rigid_links=links)
    first = len(near.elements)
    return model, 0, b + len(far.nodes) - 1, slice(first, first + len(leaf.elements))


def continuum_specimen(profile: str, l: float) -> tuple:
    """(sideways, axial) tip compliance (m/N) of the 2-D plane-stress specimen."""
    b, w, H, Lb = (SPECIMEN[k] for k in ("b", "w", "H", "block"))
    mesh = mesh_hinge_specimen(l, b, profile, block_height=H, block_length=Lb, hinge_elements=4)
    model = Model(mesh, STEEL, PlaneStress(w), order=2)
    side = solve_static(model, [FEFixed("fixed")], [Force("tip", (0.0, 1.0))])
    axial = solve_static(model, [FEFixed("fixed")], [Force("tip", (1.0, 0.0))])
    return (float(side.mean_displacement("tip")[1]), float(axial.mean_displacement("tip")[0]))


def slenderness_rows(ratios=RATIOS, profiles=("leaf", "circular")) -> list:
    """[{"profile", "l_over_b", "<load>_continuum_m_per_n", "<load>_beam_m_per_n",
    "<load>_beam_bare_m_per_n", "<load>_error", "<load>_error_bare"}] for the loads
    "bending" and "axial"; errors = beam / continuum - 1 (the stiffness error is about minus
    that)."""
    rows = []
    for profile in profiles:
        for ratio in ratios:
            l = ratio * SPECIMEN["b"]
            if profile == "circular" and SPECIMEN["b"] + l >= SPECIMEN["H"]:
                continue
            fe = continuum_specimen(profile, l)
            ext = beam_specimen(profile, l, ROOT_EXTENSION)
            bare = beam_specimen(profile, l, 0.0, notch_correction=False)
            row = {"profile": profile, "l_over_b": ratio}
            for k, load in enumerate(("bending", "axial")):
                row.update({f"{load}_continuum_m_per_n": fe[k], f"{load}_beam_m_per_n": ext[k],
                            f"{load}_beam_bare_m_per_n": bare[k],
                            f"{load}_error": ext[k] / fe[k] - 1,
                            f"{load}_error_bare": bare[k] / fe[k] - 1})
            rows.append(row)
    return rows


def trusted_from(rows: list, profile: str, load: str = "bending") -> float:
    """The smallest l/b from which on the beam model (root extension on) stays within
    TRUST_LIMIT of the continuum, nan if never."""
    mine = sorted((r for r in rows if r["profile"] == profile), key=lambda r: r["l_over_b"])
    ok = [abs(r[f"{load}_error"]) <= TRUST_LIMIT for r in mine]
    for k in range(len(mine)):
        if all(ok[k:]):
            return mine[k]["l_over_b"]
    return math.nan


def _notch_t_over_r(x):
    """t / R = 2 b / l of a right-circular notch (R = l / 2) at slenderness l / b."""
    return 2 / np.maximum(np.asarray(x, float), 1e-9)


def plot_slenderness(rows: list, path, mechanism_rows: list | None = None) -> dict:
    """Beam / continuum - 1 of the hinge compliance against l/b (leaf and circular notch,
    bending and axial, the model as built and bare beam theory), the +-3 % band, and
    (``mechanism_rows``:
    [{"l_over_b", "<metric>_error"}]) the DBMA's own metrics."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.6))
    styles = {"leaf": "o", "circular": "s"}
    for profile in sorted({r["profile"] for r in rows}):
        mine = sorted((r for r in rows if r["profile"] == profile), key=lambda r: r["l_over_b"])
        x = [r["l_over_b"] for r in mine]
        for load, colour in (("bending", "tab:blue"), ("axial", "tab:orange")):
            ax.plot(x, [100 * r[f"{load}_error"] for r in mine], "-" + styles[profile],
                    color=colour, label=f"{profile}, {load}, as built")
            ax.plot(x, [100 * r[f"{load}_error_bare"] for r in mine], ":" + styles[profile],
                    color=colour, alpha=0.6, label=f"{profile}, {load}, bare beam theory")
    for metric, colour in (("R_fem", "tab:green"), ("k_out", "tab:red"), ("fn_working", "k")):
        mine = sorted(mechanism_rows or [], key=lambda r: r["l_over_b"])
        if mine:
            ax.plot([r["l_over_b"] for r in mine], [100 * r[f"{metric}_error"] for r in mine],
                    "-^", color=colour, label=f"DBMA {metric}")
    ax.axhspan(-100 * TRUST_LIMIT, 100 * TRUST_LIMIT, color="0.85", zorder=0)
    ax.set_xscale("log")
    ax.set_xticks([2, 3, 5, 10, 20], ["2", "3", "5", "10", "20"])
    ax.set_xticks([], minor=True)
    ax.set_xlabel(axis_label("hinge slenderness l / b", "-"))
    notch = ax.secondary_xaxis("top", functions=(_notch_t_over_r, _notch_t_over_r))
    notch.set_xticks([1, 2 / 3, 0.4, 0.2, 0.1], ["1", "0.67", "0.4", "0.2", "0.1"])
    notch.set_xticks([], minor=True)
    notch.set_xlabel(axis_label("circular notch: t / R = 2 b / l", "-"))
    ax.set_ylabel(axis_label("beam / continuum - 1", "%"))
    ax.set_ylim(-55, 15)
    ax.grid(True, alpha=0.3)
    legend_outside(ax)
    return save(fig, path, "Beam model against the 2-D continuum over the hinge slenderness: "
                "compliance error of one hinge between two blocks (bending and axial, leaf "
                "and circular notch) as the mechanisms' models build it (solid: the common "
                "root extension; a notch also corrected by its own 2-D model) and as bare beam "
                "theory (dotted), and the DBMA's own R, k_out and working frequency "
                "(triangles) where computed. Grey: the 3 % band. Top axis: the notch's t / R. "
                "Bare beam theory is too stiff by ~b / l (bending) and more axially: it leaves "
                "the band below l/b ~ 20. As built, a sharp-cornered leaf stays in it down to "
                "l/b ~ 2, a circular notch in bending at every l/b; axially the notch keeps "
                "part of its junction with blocks much taller than its ends (docs/beam_validation.md, "
                "\"Notch hinges: the 2-D patch\").")


def dbma_slenderness_rows(ratios=(2.0, 5.0, 10.0, 20.0), size_factor: float = 1.0) -> list:
    """The DBMA at hinge slenderness l/b (b varied, l = the paper's 4.41 mm): beam / 2-D
    continuum - 1 of R_fem, k_in, k_out and fn_working."""
    from dataclasses import replace

    from ...fem import solve_static as fe_static
    from ...geometry.dbma.params import paper_design
    from . import analysis as fem
    from .beam import analyze_dbma_beam

    rows = []
    for ratio in ratios:
        p = replace(paper_design(), b=paper_design().l / ratio)
        model = fem.build_model(p, None, 2, size_factor)
        static = fem.static_response(model, 100.0)
        probe = fe_static(model, fem.modal_supports(), [Force("output", (0.0, 100.0))])
        cont = {"R_fem": static["R_fem"], "k_in": static["k_in"],
                "k_out": 100.0 / float(probe.mean_displacement("output")[1]),
                "fn_working": fem.modal_response(model, 4)[0]["fn_working"]}
        beam = analyze_dbma_beam(p, n_modes=4)
        row = {"l_over_b": ratio, "b_m": p.b}
        for k, v in cont.items():
            row.update({f"{k}_continuum": v, f"{k}_beam": beam[k], f"{k}_error": beam[k] / v - 1})
        rows.append(row)
    return rows
