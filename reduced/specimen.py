"""A hinge specimen for checking the beam model against the continuum: one hinge (a leaf or a
notch) between two blocks, beam model against the 2-D plane-stress continuum, over the hinge's
slenderness l/b.

The specimen is :func:`flexfem.geometry.hinge_profiles.mesh_hinge_specimen` (b = 0.5 mm,
w = 5 mm, blocks 10 mm tall and 5 mm long, P2 elements, 4 across the neck): the left block's
end clamped, a unit force on the right block's end, sideways (bending: the hinge's working
compliance) and along the hinge (axial). The beam model is the hinge from its profile
(:func:`flexfem.reduced.layout.profile_beam`, the blocks as Timoshenko beams), with the common
root extension (0.38 x root thickness, axial root compliance for the block height) and a
circular notch's 2-D correction (:mod:`flexfem.reduced.hinge_patch`), as the mechanisms' models
have them, and the bare beam without either (plain beam theory of the profile).
:func:`leaf_between_blocks` is the leaf as the DBMA joins its hinges to its arms. SI units.
"""
import math

import numpy as np

from ..fem import Fixed as FEFixed, Force, Material, Model, PlaneStress, solve_static
from ..fem.beam import BeamModel, NodalLoad, RigidLink, Section, beam_chain, solve_beam_static
from ..fem.beam.supports import NodeFixed
from ..geometry.hinge_profiles import mesh_hinge_specimen, profile_thickness
from .hinge_patch import notch_factors
from .layout import ROOT_EXTENSION, profile_beam

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
        q = solve_beam_static(model, [NodeFixed(root)], [load]).q
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
