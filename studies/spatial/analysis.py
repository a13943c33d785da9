"""``flexfem analyze FILE --model beam`` on a spatial model file: the analysis of its beam
model (beam_model.py) in the continuum analysis' output format (studies/user_model/
analysis.py): the static solve, the 6x6 compliance and stiffness of the loaded body at its
centroid with its centre of compliance and the support-to-drive stiffness ratios, the modes
with their effective masses per direction, the beam stress, the large-deflection path,
linear buckling and the stroke limits. SI units.

A body is one rigid node: a body's "mean displacement" is its centroid's displacement (the
continuum's mean over its free faces, which move rigidly, is that of their centroid), a
force is the body's total force at its centroid. max_von_mises is the nominal beam stress:
a rectangle's |N|/A + |M_y| c_z / I_y + |M_z| c_y / I_z with its torsion shear, a wire's
|N|/A + |M| (d/2) / I with T (d/2) / J (no stress concentration at the roots).
"""
import numpy as np

from ...fem import compliance_matrix, solve_buckling, solve_modes, solve_nonlinear, solve_static
from ..user_model.outputs import (check_finite, check_loaded_supports, groups_of,
                                  single_force, stiffness)
from ..user_model.stroke import stroke_limits
from .beam_model import SpatialBeam, beam_model, supports_and_loads

#: What a spatial file's beam model does not give (the continuum's --model continuum does).
NOT_MODELLED = {"harmonic": "[analysis] harmonic is the continuum's (--model continuum)"}


def round_stress(beam: SpatialBeam, local_forces: np.ndarray, n_points: int = 5) -> np.ndarray:
    """(n_e, n_points) von Mises stress (Pa) at the outer fibre of the wires' round sections
    (NaN on other elements): sqrt(sigma^2 + 3 tau^2), sigma = |N|/A + |M| (d/2) / I, tau =
    |T| (d/2) / J, exact where both peak (the whole rim for torsion)."""
    model, xi = beam.model, np.linspace(0.0, 1.0, n_points)
    out = np.full((model.n_elements, n_points), np.nan)
    f = np.asarray(local_forces, float)
    for i, flexure in enumerate(beam.mechanism.flexures):
        if flexure.kind != "wire":
            continue
        e = beam.flexure_elements[i]
        s = model.sections[e[0]]
        c = flexure.diameter / 2
        torsion, my, mz = (-f[e, k:k + 1] * (1 - xi) + f[e, k + 3:k + 4] * xi for k in (1, 2, 3))
        sigma = np.abs(f[e, 0:1]) / s.A + np.hypot(my, mz) * c / s.Iy
        out[e] = np.sqrt(sigma ** 2 + 3 * (np.abs(torsion) * c / s.J) ** 2)
    return out


def peak_stress(beam: SpatialBeam, state) -> tuple:
    """(largest von Mises stress (Pa), where (3,) m on the centre line) of a Beam3DState:
    the rectangles' bound (Beam3DState.stresses) and the wires' :func:`round_stress`."""
    rect = state.stresses()
    vm = np.fmax(np.nan_to_num(rect["von_mises"], nan=-1.0),
                 np.nan_to_num(round_stress(beam, state.local_forces), nan=-1.0))
    e, k = np.unravel_index(int(np.argmax(vm)), vm.shape)
    a, b = beam.model.nodes[beam.model.elements[e]]
    xi = rect["xi"][k]
    return float(max(vm[e, k], 0.0)), a + xi * (b - a)


def compliance_at_centroid(beam: SpatialBeam, supports, body: str) -> dict:
    """The 6x6 compliance (m/N, rad/N, rad/(N m)) and stiffness of ``body`` at its centroid
    in global axes, its principal compliances and its centre of compliance (m)."""
    c = compliance_matrix(beam.model, supports, body)
    return {"group": body, "matrix": c.matrix.tolist(), "point_m": c.point.tolist(),
            "stiffness": c.stiffness.tolist(),
            "principal_compliances": c.principal()[0].tolist(),
            "centre_of_compliance_m": c.centre_of_compliance.tolist()}


def support_to_drive(compliance: dict, direction) -> dict:
    """{axis: k_axis / k_drive} (-): the translational stiffness along x, y and z (the
    others free, 1 / C_ii) over the stiffness along the drive ``direction`` (1 / (d^T C d))."""
    c = np.asarray(compliance["matrix"])[:3, :3]
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    k_drive = 1.0 / float(d @ c @ d)
    return {axis: float(1.0 / c[i, i] / k_drive) for i, axis in enumerate("xyz")}


def modes(beam: SpatialBeam, supports, n: int) -> dict:
    """The ``n`` lowest frequencies (Hz) and their effective masses (n, 3) (kg) along x, y,
    z."""
    result = solve_modes(beam.model, n, supports)
    return {"frequencies_hz": result.frequencies_hz.tolist(),
            "effective_mass_kg": np.asarray(result.effective_mass).tolist(),
            "total_mass_kg": float(result.total_mass)}


def _nonlinear(beam, supports, loads, groups, steps: int) -> dict:
    path = solve_nonlinear(beam.model, supports, loads, steps=steps)
    return {"steps": len(path.load_factors) - 1,
            "mean_displacement": {g: path.mean_displacement(g).tolist() for g in groups},
            "reactions": {g: np.asarray(r).tolist() for g, r in path.reactions[-1].items()}}


def _static(spec, beam, supports, loads) -> dict:
    result = solve_static(beam.model, supports, loads)
    groups = groups_of(spec)
    mean = {g: result.mean_displacement(g).tolist() for g in groups}
    vm, where = peak_stress(beam, result.state)
    strength = spec.material.yield_strength
    return {"model": spec.source, "geometry": str(spec.geometry),
            "parameters": dict(spec.constants), "dim": 3, "dofs": int(beam.model.n_dofs),
            "solver": "beam", "h": float(np.mean(beam.model.lengths)),
            "max_von_mises": vm, "max_von_mises_location": where.tolist(),
            "mean_displacement": mean,
            "reactions": {g: np.asarray(r).tolist() for g, r in result.reactions.items()},
            "stiffness": {} if spec.spatial.moments else stiffness(spec, mean),
            "yield_strength": float(strength) if np.isfinite(strength) else None}


def analyze_spatial_beam(spec, fields: dict | None = None) -> dict:
    """The analysis dict of a spatial model file's beam model (the module; keys as
    analyze_model's, with "compliance" of the loaded body at its centroid, its
    "support_to_drive" ratios and the modes' "effective_mass_kg"). ``fields`` is left empty:
    the field files and pictures of ``--out`` are the continuum's."""
    check_loaded_supports(spec)
    a = spec.analysis
    for key, why in NOT_MODELLED.items():
        if getattr(a, key):
            raise ValueError(f"{spec.source}: --model beam: {why}")
    try:
        beam = beam_model(spec.spatial, spec.material)
        supports, loads = supports_and_loads(spec, beam)
        out = _static(spec, beam, supports, loads)
        load = single_force(spec)
        body = a.compliance or (load.group if load is not None else None)
        if body is not None:
            out["compliance"] = compliance_at_centroid(beam, supports, body)
        if load is not None and out.get("compliance", {}).get("group") == load.group:
            out["support_to_drive"] = support_to_drive(out["compliance"], load.vector)
        if a.modes:
            found = modes(beam, supports, a.modes)
            out["frequencies_hz"] = found.pop("frequencies_hz")
            out["modes"] = found
        if a.steps:
            out["nonlinear"] = _nonlinear(beam, supports, loads, groups_of(spec), a.steps)
        if a.buckling:
            out["buckling"] = {"load_factors": solve_buckling(
                beam.model, supports, loads, n=a.buckling).load_factors.tolist()}
    except ValueError as error:
        text = str(error)
        raise ValueError(text if text.startswith(spec.source) else
                         f"{spec.source}: {text}") from None
    limits = {} if spec.spatial.moments else stroke_limits(spec, out)  # a force's alone
    out.update({k: v for k, v in limits.items() if k != "not_available"})
    missing = {**({"yield_strength": "not given in [material]"}
                  if out["yield_strength"] is None else {}), **limits.get("not_available", {})}
    if missing:
        out["not_available"] = missing
    return check_finite(out, spec.source)
