"""Reduced beam model of the driving linkage (thesis Ch. 6), generated from its parameters.

    model, info = driving_beam_model(DrivingParams(), EightBarFlexureParams())
    info["input"], info["ee_L"], info["ee_R"]   # master nodes on the faces' centres

Built from the same flexure layout as the continuum mesh
(:func:`flexfem.geometry.eightbar.driving.driving_layout`): every flexure (the lambdas', the
bars', the two suspensions') a beam, every link rigid with its mass
(:func:`flexfem.reduced.layout.layout_beam_model`); the shuttle's master node on its
"input" face, the end-effectors' on their "ee_L", "ee_R" faces, so that loads and supports
act where the continuum's faces are. Sharp roots: the continuum's mesh
(:func:`~flexfem.geometry.eightbar.driving.mesh_driving_flexure`) draws none of the
flexure's root fillets, so neither does this model (DRAWN_FILLET_RADIUS; with the fillets of
``flexure.root_fillet_radius`` = 0.3 mm it was 4.1 % stiffer than that continuum, without
them 0.03 %: docs/beam.md). Also the pseudo-rigid-body input stiffness
k_in = sum_j (E I / L)_j (dphi_j / ds)^2 of the same layout (N/m). All lengths in m.
"""
from dataclasses import replace

import numpy as np

from ..fem.materials import material as material_named
from .layout import ROOT_EXTENSION, layout_beam_model
from ..geometry.eightbar.driving import DrivingParams, driving_layout, trace_driving

FACES = {"input": "shuttle", "ee_L": "susL_end_effector", "ee_R": "susR_end_effector"}
# root fillet radius (m) of the driving linkage as drawn: mesh_driving_flexure calls
# flexure_drawing.mesh_layout without fillets (docs/eightbar.md, "Root fillets")
DRAWN_FILLET_RADIUS = 0.0


def driving_beam_model(params: DrivingParams, flexure, n_per_flexure: int = 24,
                       root_extension: float = ROOT_EXTENSION, shear: bool = True,
                       fillet_radius: float = DRAWN_FILLET_RADIUS) -> tuple:
    """(BeamModel, info) of the driving linkage's flexure part (with its shuttle) in the drawn
    pose; ``flexure`` an EightBarFlexureParams (flexure sizes, link width, out-of-plane
    thickness, material; its ``rigid`` and ``root_fillet_radius`` ignored, as the continuum's
    mesh ignores them); ``fillet_radius`` (m): the roots' fillets (default: as drawn). info:
    that of layout_beam_model plus "input", "ee_L", "ee_R" (master nodes on those faces'
    centres) and "layout" (the FlexureLayout). The model's groups are the continuum mesh's:
    "fixed" (the anchors' clamped nodes), "input", "ee_L" and "ee_R" (those faces' nodes,
    with their extents)."""
    layout = driving_layout(params, flexure, shuttle=True)
    anchors = {link: np.asarray(layout.edges[face], float).mean(axis=0)
               for face, link in FACES.items()}
    model, info = layout_beam_model(
        layout, material_named(flexure.material), flexure.thickness,
        fillet_radius=fillet_radius, n_per_flexure=n_per_flexure,
        root_extension=root_extension, anchors=anchors, shear=shear)
    model.add_group("fixed", info["ground"])
    for face, link in FACES.items():
        info[face] = info["masters"][link]
        edge = np.asarray(layout.edges[face], float)
        model.add_group(face, [info[face]], edge[-1] - edge[0])
    info["layout"] = layout
    return model, info


def driving_joint_rates(params: DrivingParams, n: int = 5, span: float = 1e-3) -> dict:
    """d(phi_j)/ds (rad/m) at the drawn pose: each joint's relative rotation per unit shuttle
    displacement s, by a central difference on the rigid trace (both halves driven by their
    coupler points; the shuttle does not turn, so the flexures at P_L, P_R turn with the
    couplers); and under "transmission" the right end-effector's d x / d s (-). ``span``:
    the fraction of input_travel differenced over."""
    small = replace(params, input_travel=span * params.input_travel)
    tr = trace_driving(small, n=n)
    linkage = tr.linkage
    theta = {name: tr.poses[:, 3 * i + 2] for i, name in enumerate(linkage.moving_links)}
    theta["ground"] = theta["shuttle"] = np.zeros(len(tr.s))
    k, h = len(tr.s) // 2, tr.s[len(tr.s) // 2 + 1] - tr.s[len(tr.s) // 2 - 1]
    pairs = {j.point: j.links for j in linkage.joints}
    pairs.update({f"lam{side}_P": (f"lam{side}_coupler", "shuttle") for side in "LR"})
    rates = {name: float((theta[a][k + 1] - theta[b][k + 1] - theta[a][k - 1] + theta[b][k - 1])
                         / h) for name, (a, b) in pairs.items()}
    rates["transmission"] = float((tr.dx_right[k + 1] - tr.dx_right[k - 1]) / h)
    return rates


def driving_prbm_stiffness(params: DrivingParams, flexure, layout=None) -> dict:
    """Pseudo-rigid-body stiffness at the shuttle along y, k_in = sum_j (E I / L)_j
    (dphi_j/ds)^2 (N/m), I = t w^3 / 12 with each flexure's drawn (L, w) (base joints O, C:
    the base flexure's), each joint's share, and the rigid linkage's transmission d x_R / d s
    (-). Neglects the links' compliance and the flexures' axial and transverse compliance.
    ``layout``: driving_layout(params, flexure) if already built."""
    E = material_named(flexure.material).E
    layout = layout or driving_layout(params, flexure, shuttle=True)
    sizes = {fj.name: (fj.length, fj.width) for fj in layout.joints}
    rates = driving_joint_rates(params)
    transmission = rates.pop("transmission")
    share = {}
    for joint, rate in rates.items():
        L, w = sizes[joint]
        share[joint] = E * flexure.thickness * w ** 3 / 12 / L * rate ** 2
    return {"k_in": float(sum(share.values())), "joints": share,
            "transmission": transmission}
