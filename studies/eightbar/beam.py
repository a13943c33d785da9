"""Beam-model analysis of the eight-bar flexure suspension: the continuum study's outputs
(:mod:`flexfem.studies.eightbar.analysis`) from the reduced beam model
(:func:`flexfem.geometry.eightbar.beam.eightbar_beam_model`), in milliseconds.

Same loadings as the continuum study: k_x with the end-effector's x prescribed (y and rotation
free), k_y with x held, y prescribed and the face's rotation held (the continuum prescribes
every node of the face), the first modes with the anchors clamped, the large-deflection path
with x prescribed from the middle to the end of the travel (the -x half is the mirror image,
as the continuum's ``both_halves=False``), the flexures' beam stress |N|/A + |M|c/I (the
continuum's von Mises peak includes the fillet's stress concentration, which beam theory has
not). SI units.
"""
from dataclasses import replace
import functools
import math

import numpy as np

from ...fem import material
from ...fem.beam import (Fixed, Prescribed, solve_beam_modes, solve_beam_nonlinear,
                         solve_beam_static)
from ...geometry.beam_layout import ROOT_EXTENSION
from ...geometry.eightbar.beam import eightbar_beam_model
from ...geometry.eightbar.flexure import EightBarFlexureParams, prbm_stiffness
from ...geometry.eightbar.rigid import trace_eightbar
from ...geometry.straight_line import straight_line_deviation
from .analysis import params_from_dict

# Newton tolerance (relative residual): the continuum study's own (analysis.NEWTON_TOL); the
# stroke's outputs (end force, path deviation, peak stress) agree with a 1e-9 solve to 3e-9,
# in 33 Newton iterations for the stroke's half instead of 48
NEWTON_TOL = 1e-5
# elements per flexure of the nonlinear stroke's model: its outputs agree with 24 to ~3e-5
# (force, stress) and it solves ~3x faster; the linear and modal solves keep 24 (above 800
# unknowns the modes use the sparse shift-invert solver, well conditioned here)
STROKE_ELEMENTS = 12


def _supports(info):
    return [Fixed(tuple(info["ground"]))]


def beam_linear(model, info, displacement: float) -> dict:
    """k_x, k_y (N/m) and the beam stress (Pa) with the end-effector moved ``displacement``
    (m) along x, linearly."""
    ee, ground = info["end_effector"], _supports(info)
    along = solve_beam_static(model, ground + [Prescribed(ee, "x", displacement)])
    across = solve_beam_static(model, ground + [Prescribed(ee, "x", 0.0),
                                                Prescribed(ee, "y", displacement),
                                                Prescribed(ee, "theta", 0.0)])
    return {"k_x": float(along.reactions[ee][0] / displacement),
            "k_y": float(across.reactions[ee][1] / displacement),
            "max_von_mises": along.max_stress, "state": along}


def beam_modes(model, info, n: int = 4) -> list:
    """[{"f_hz", "m_eff_x_kg", "m_eff_y_kg"}] of the first ``n`` modes, anchors clamped."""
    modes = solve_beam_modes(model, _supports(info), n=n)
    return [{"f_hz": float(f), "m_eff_x_kg": float(m[0]), "m_eff_y_kg": float(m[1])}
            for f, m in zip(modes.frequencies_hz, modes.effective_mass)]


def spatial_beam_modes(params: EightBarFlexureParams, n: int = 4,
                       root_extension: float = ROOT_EXTENSION) -> list:
    """beam_modes' rows from the spatial beam model (flexible links, the flexures' torsion
    with Vlasov's warping restraint; docs/beam.md), with "m_eff_z_kg", as the 3-D FEM's."""
    from .modes3d import beam_modes as spatial

    out = spatial(params, n, warping=True, root_extension=root_extension)
    mass = np.array(out["mass_fraction"]) * out["total_mass_kg"]
    return [{"f_hz": float(f), "m_eff_x_kg": float(m[0]), "m_eff_y_kg": float(m[1]),
             "m_eff_z_kg": float(m[2])} for f, m in zip(out["f_hz"], mass)]


def beam_stroke(model, info, params: EightBarFlexureParams, travel: float,
                steps: int = 8, tol: float = NEWTON_TOL) -> dict:
    """Large deflection from the middle to +travel/2 (m), mirrored for the -x half: path
    deviation (the continuum's straight_line_deviation of the face centroid), peak stress,
    end force, rotation."""
    ee = info["end_effector"]
    res = solve_beam_nonlinear(model, _supports(info) + [Prescribed(ee, "x", travel / 2)],
                               steps=steps, tol=tol)
    path = res.path(ee)
    force = np.array([s.reactions[ee][0] for s in res.states])
    stress = np.array([s.max_stress for s in res.states])
    e0 = model.nodes[ee]  # the end_effector face's centroid (end_effector_point)
    half = np.column_stack([e0[0] + path[:, 0], e0[1] + path[:, 1]])
    mirror = np.column_stack([2 * e0[0] - half[:0:-1, 0], half[:0:-1, 1]])
    dev = straight_line_deviation(np.vstack([mirror, half]))
    rigid = _rigid_deviation(params.rigid, travel)
    peak = float(stress.max())
    rows = [{"x_m": float(u), "y_m": float(v), "rotation_rad": float(r), "force_x_n": float(f),
             "peak_von_mises_pa": float(sg)}
            for (u, v, r), f, sg in zip(path, force, stress)]
    rows = [{**r, "x_m": -r["x_m"], "rotation_rad": -r["rotation_rad"],
             "force_x_n": -r["force_x_n"]} for r in rows[:0:-1]] + rows
    where = res.states[int(stress.argmax())].max_stress_location[0]
    strength = material(params.material).yield_strength
    return {"fem_deviation_pct": dev.deviation_pct, "fem_deviation_m": dev.max_deviation_m,
            "fem_band_m": dev.band_m, "rigid_deviation_pct": rigid.deviation_pct,
            "rigid_deviation_m": rigid.max_deviation_m,
            "peak_von_mises_travel": peak, "safety_factor": strength / peak,
            "max_rotation_rad": float(np.abs(path[:, 2]).max()),
            "end_force_n": float(force[-1]), "first_step_k_x": float(force[1] / path[1, 0]),
            "newton_iterations": int(sum(res.iterations)), "result": res, "path": rows,
            "peak_von_mises_flexure": _flexure_of(info, where)}


@functools.lru_cache(maxsize=64)
def _rigid_deviation(rigid, travel: float):
    """The rigid-body linkage's straightness over ``travel`` (m), cached: a sweep of the
    flexure dimensions keeps the linkage."""
    return trace_eightbar(replace(rigid, travel=travel), n=101).deviation


def analyze_eightbar_beam(params: EightBarFlexureParams | None = None,
                          travel: float | None = None, steps: int = 8, n_modes: int = 4,
                          nonlinear: bool = True, n_per_flexure: int = 24,
                          root_extension: float = ROOT_EXTENSION, dim: int = 2) -> dict:
    """The continuum :func:`~flexfem.studies.eightbar.analysis.analyze_eightbar`'s keys from
    the beam model (the path's -x half mirrored). ``dim`` 3: the modes of the spatial beam
    model (:func:`spatial_beam_modes`: out-of-plane modes too); the rest is planar."""
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} must be 2 or 3")
    params = params or EightBarFlexureParams()
    travel = params.rigid.travel if travel is None else float(travel)
    if not (math.isfinite(travel) and 0 < travel < params.rigid.ground_spacing):
        raise ValueError(f"travel = {travel!r} m must be in (0, ground_spacing = "
                         f"{params.rigid.ground_spacing} m)")
    model, info = eightbar_beam_model(params, n_per_flexure, root_extension)
    lin = beam_linear(model, info, travel / 2)
    where = lin["state"].max_stress_location
    out = {"k_x": lin["k_x"], "k_y": lin["k_y"], "k_x_prbm": prbm_stiffness(params)["k_x"],
           "max_von_mises": lin["max_von_mises"], "travel_m": travel,
           "max_stress_location": {"x": float(where[2][0]), "y": float(where[2][1]),
                                   "flexure": _flexure_of(info, where[0])},
           "dofs": int(model.n_dofs), "model": "beam", "root_extension": root_extension,
           "dim": dim}
    if n_modes:
        out["modes"] = (beam_modes(model, info, n_modes) if dim == 2
                        else spatial_beam_modes(params, n_modes, root_extension))
    if nonlinear:
        coarse = eightbar_beam_model(params, min(n_per_flexure, STROKE_ELEMENTS), root_extension)
        nl = beam_stroke(*coarse, params, travel, steps)
        out.update({k: v for k, v in nl.items() if k != "result"})
    return out


def _flexure_of(info, element: int) -> str:
    for joint, (a, b) in info["flexures"].items():
        if a <= element < b:
            return f"flexure_{joint}"
    return "unknown"


def evaluate_beam(params: dict | None = None, nonlinear: bool = False, steps: int = 6,
                  n_per_flexure: int = 24, root_extension: float = ROOT_EXTENSION,
                  size_factor: float | None = None) -> dict:
    """Study metrics of the beam model, named as the continuum evaluate's: k_x, k_y,
    k_x_prbm, max_von_mises, f1_hz, dofs (and with ``nonlinear`` fem_deviation_pct,
    rigid_deviation_pct, peak_von_mises_travel, safety_factor, max_rotation_rad).
    The continuum-only option size_factor is accepted and ignored (a study can switch
    ``model`` without editing its options); any other option raises TypeError."""
    out = analyze_eightbar_beam(params_from_dict(params or {}), steps=steps, n_modes=1,
                                nonlinear=nonlinear, n_per_flexure=n_per_flexure,
                                root_extension=root_extension)
    metrics = {k: float(out[k]) for k in ("k_x", "k_y", "k_x_prbm", "max_von_mises", "dofs")}
    metrics["f1_hz"] = out["modes"][0]["f_hz"]
    if nonlinear:
        for k in ("fem_deviation_pct", "rigid_deviation_pct", "peak_von_mises_travel",
                  "safety_factor", "max_rotation_rad"):
            metrics[k] = float(out[k])
    return metrics
