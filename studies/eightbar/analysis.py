"""FEM of the eight-bar flexure suspension (eight-bar thesis, Chapter 5): stiffness, stress,
modes and the large-deflection path over the whole travel, beside the rigid-body linkage and
the pseudo-rigid-body model.

    from ..geometry.eightbar_flexure import EightBarFlexureParams
    out = analyze_eightbar(EightBarFlexureParams())
    out["k_x"], out["max_stress_location"], out["fem_deviation_pct"]

Drive: the "end_effector" face (bottom face of the end-effector bar). Linear stiffness along
the motion k_x: the face's x prescribed (y free), k_x = reaction / displacement (the force-
driven solve has the mechanism's near-zero mode in it and is too ill-conditioned for the direct
solver's residual check); across the motion k_y: y prescribed with x held (by the mirror
symmetry of the part, a y force moves the end-effector neither in x nor in rotation, so
holding x changes nothing). Large deflection: the face as a RigidFace, x prescribed, y and
rotation free, from the middle to each end of the travel.
"""
import math
from dataclasses import fields, replace
from typing import Literal

import numpy as np

from ...fem import (
    Fixed,
    Prescribed,
    RigidFace,
    material,
    solve_modes,
    solve_nonlinear,
    solve_static,
)
from ...geometry.eightbar.flexure import (
    EightBarFlexureParams,
    end_effector_point,
    prbm_peak_stress,
    prbm_stiffness,
)
from ...geometry.eightbar.rigid import EightBarParams, trace_eightbar
from ...geometry.straight_line import straight_line_deviation
from ..engine.validate import declare, require_finite
from .beam_model import beam_model, spatial_beam_modes
from .continuum_model import build_model, group_at_vertex  # noqa: F401 (public here too)
from .places import Places, continuum_places

# Newton tolerance (relative to the reaction): the residual of this part stagnates near 3e-6
# of the drive force -- round-off in the internal forces of the stiff links (E t ~ 4e8 N/m)
# against a mechanism reaction of ~1 N -- so the default 1e-8 cannot be reached.
NEWTON_TOL = 1e-5


def linear_analysis(model, displacement: float, places: Places | None = None) -> dict:
    """k_x, k_y (N/m), and the von Mises stress (Pa) with the end-effector moved by
    ``displacement`` (m) along x, linearly: its maximum, where and in which flexure
    (``places``, default the continuum's), and the quadrature-point maximum; the continuum or
    the beam model. Returns the static result as "result"."""
    places = places or continuum_places(model)
    probe = displacement
    fixed = Fixed("fixed")
    along = solve_static(model, [fixed, Prescribed("end_effector", x=probe)], [])
    across = solve_static(model, [fixed, Prescribed("end_effector", x=0.0, y=probe)], [])
    k_x = float(along.reactions["end_effector"][0] / probe)
    k_y = float(across.reactions["end_effector"][1] / probe)
    return {"k_x": k_x, "k_y": k_y, "max_von_mises": along.max_von_mises,
            "max_von_mises_element": along.max_von_mises_element,
            "max_stress_location": places.peak(along),
            "stress_displacement_m": probe, "result": along}


def stress_convergence(params: EightBarFlexureParams, size_factors=(1.0, 0.7, 0.5),
                       radii: tuple | None = None, displacement: float | None = None) -> list:
    """Max von Mises (Pa) of the linear solve with the end-effector moved ``displacement`` (m,
    default half the travel) along x, for each root fillet radius in ``radii`` (m, default
    sharp and ``params.root_fillet_radius``) and mesh ``size_factor``: [{"root_fillet_radius_m",
    "size_factor", "dofs", "root_size_m", "k_x", "max_von_mises_nodal_pa",
    "max_von_mises_element_pa", "x_m", "y_m", "flexure"}] (location of the nodal maximum).
    A sharp re-entrant corner is a singularity (stress ~ rho^-0.46 near it): its maximum grows
    as the mesh is refined; a filleted root's converges."""
    displacement = params.rigid.travel / 2 if displacement is None else float(displacement)
    radii = (0.0, params.root_fillet_radius) if radii is None else tuple(radii)
    rows = []
    for radius in radii:
        p = replace(params, root_fillet_radius=radius)
        for size_factor in size_factors:
            model, sizes = build_model(p, size_factor)
            res = solve_static(model, [Fixed("fixed"), Prescribed("end_effector", x=displacement)], [])
            vertex = int(np.argmax(res.von_mises_nodal))
            where = model.mesh.mesh.p[:, vertex]
            rows.append({"root_fillet_radius_m": float(radius), "size_factor": float(size_factor),
                         "dofs": int(model.n_dofs), "root_size_m": sizes.get("root_size"),
                         "k_x": float(res.reactions["end_effector"][0] / displacement),
                         "max_von_mises_nodal_pa": res.max_von_mises,
                         "max_von_mises_element_pa": res.max_von_mises_element,
                         "x_m": float(where[0]), "y_m": float(where[1]),
                         "flexure": group_at_vertex(model, vertex)})
    return rows


def modal_analysis(model, n: int = 4) -> list:
    """First ``n`` modes: [{"f_hz", "m_eff_x_kg", "m_eff_y_kg"(, "m_eff_z_kg" in 3-D)}] with
    the base fixed."""
    # a shift just below zero: the default (1e-6 of the stiffness/mass scale) sits far above
    # this mechanism's few-Hz modes and Lanczos then needs tens of seconds
    modes = solve_modes(model, n=n, supports=[Fixed("fixed")], shift_hz=-1.0)
    return [{"f_hz": float(f), **{f"m_eff_{a}_kg": float(v) for a, v in zip("xyz", m)}}
            for f, m in zip(modes.frequencies_hz, modes.effective_mass)]


def _half_stroke(model, places: Places, end, steps):
    """One nonlinear solve from the middle to ``end`` (m): rows per converged step."""
    face = RigidFace("end_effector", x=end)
    result = solve_nonlinear(model, [Fixed("fixed")], [], steps=steps, tol=NEWTON_TOL,
                             rigid_faces=[face])
    rows = []
    for k, (motion, force) in enumerate(zip(result.face_motion, result.face_reactions)):
        element_max = result.stress_at_step(k)[1]
        element = int(np.argmax(element_max))
        peak = float(element_max[element])
        rows.append({"x_m": float(motion["end_effector"][0]), "y_m": float(motion["end_effector"][1]),
                     "rotation_rad": float(motion["end_effector"][2]),
                     "force_x_n": float(force["end_effector"][0]),
                     "force_y_n": float(force["end_effector"][1]),
                     "peak_von_mises_pa": peak, "peak_flexure": places.element(result, element)})
    return rows, result


def large_deflection(model, params: EightBarFlexureParams, travel: float, steps: int = 8,
                     both_halves: bool = True, places: Places | None = None) -> dict:
    """Displacement-controlled trace of the end-effector over ``travel`` (m), centred on the
    drawn pose. With ``both_halves=False`` only the +x half is solved and the -x half is its
    mirror image (the part is mirror-symmetric about x = 0: y(-s) = y(s), rotation(-s) =
    -rotation(s), force(-s) = -force(s)). Returns the path rows (sorted by x), the FEM and
    rigid-body straightness and the peak stress along the travel against yield. ``places``:
    default the continuum's."""
    places = places or continuum_places(model)
    rows_plus, last = _half_stroke(model, places, travel / 2, steps)
    iterations = sum(last.iterations)
    if both_halves:
        rows_minus, other = _half_stroke(model, places, -travel / 2, steps)
        iterations += sum(other.iterations)
    else:
        rows_minus = [{**r, "x_m": -r["x_m"], "rotation_rad": -r["rotation_rad"],
                       "force_x_n": -r["force_x_n"],
                       "peak_flexure": _mirror_name(r["peak_flexure"])} for r in rows_plus]
    rows = sorted(rows_minus[1:] + rows_plus, key=lambda r: r["x_m"])
    e0 = end_effector_point(params)
    points = np.array([[e0[0] + r["x_m"], e0[1] + r["y_m"]] for r in rows])
    fem = straight_line_deviation(points)
    rigid = trace_eightbar(replace(params.rigid, travel=travel), n=101).deviation
    peak = max(rows, key=lambda r: r["peak_von_mises_pa"])
    yield_strength = material(params.material).yield_strength
    return {"rows": rows, "fem_deviation_m": fem.max_deviation_m, "fem_band_m": fem.band_m,
            "fem_deviation_pct": fem.deviation_pct, "fem_travel_m": fem.travel_m,
            "rigid_deviation_m": rigid.max_deviation_m, "rigid_band_m": rigid.band_m,
            "rigid_deviation_pct": rigid.deviation_pct,
            "max_rotation_rad": float(max(abs(r["rotation_rad"]) for r in rows)),
            "peak_von_mises_travel": peak["peak_von_mises_pa"],
            "peak_von_mises_flexure": peak["peak_flexure"], "yield_strength": yield_strength,
            "safety_factor": yield_strength / peak["peak_von_mises_pa"],
            "first_step_k_x": rows_plus[1]["force_x_n"] / rows_plus[1]["x_m"],
            "end_force_n": rows_plus[-1]["force_x_n"], "newton_iterations": int(iterations),
            "final_result": last}


def _mirror_name(name: str) -> str:
    return name[:-1] + {"L": "R", "R": "L"}[name[-1]] if name[-2:] in ("_L", "_R") else name


MODELS = ("continuum", "beam")


def build(params: EightBarFlexureParams, model: str = "continuum", size_factor: float = 1.0,
          max_dofs: int | None = None, dim: int = 2, n_per_flexure: int = 24,
          root_extension: float | None = None, stroke: bool = False) -> tuple:
    """(model, Places, facts) of the suspension with the groups "fixed" and "end_effector"
    every analysis here names: the continuum FEM (:func:`build_model`; facts: h, mesh_sizes,
    n_elements) or the planar beam model (:func:`flexfem.studies.eightbar.beam.beam_model`;
    ``stroke``: its coarser model for the large-deflection path)."""
    if model == "continuum":
        fe, sizes = build_model(params, size_factor, max_dofs=max_dofs, dim=dim)
        return fe, continuum_places(fe), {"h": sizes["flexure_size"], "mesh_sizes": sizes,
                                          "n_elements": int(fe.mesh.mesh.t.shape[1])}
    if model == "beam":
        return beam_model(params, n_per_flexure, root_extension, stroke)
    raise ValueError(f"model = {model!r} must be one of {MODELS}")


def analyze_eightbar(params: EightBarFlexureParams | None = None, travel: float | None = None,
                     size_factor: float = 1.0, steps: int = 8, n_modes: int = 4,
                     both_halves: bool = True, nonlinear: bool = True,
                     max_dofs: int | None = None, dim: int = 2, *,
                     model: str = "continuum", n_per_flexure: int = 24,
                     root_extension: float | None = None) -> dict:
    """Linear stiffness and stress, modes, pseudo-rigid-body estimate and (``nonlinear``) the
    large-deflection trace over ``travel`` (m, default the rigid design's travel). SI units.
    The linear stress is at half the travel (the end of the stroke from the middle).
    ``model``: "continuum" (``dim=3``: the solid, linear and modal only) or "beam" (the same
    analyses on the reduced beam model; ``dim=3``: the spatial beam model's modes, out of
    plane too, the rest planar)."""
    params = params or EightBarFlexureParams()
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} must be 2 or 3")
    if dim == 3 and nonlinear and model == "continuum":
        raise ValueError("nonlinear=True needs dim=2: the 3-D model is linear and modal only")
    travel = params.rigid.travel if travel is None else float(travel)
    if not (math.isfinite(travel) and 0 < travel < params.rigid.ground_spacing):
        raise ValueError(f"travel = {travel!r} m must be in (0, ground_spacing = "
                         f"{params.rigid.ground_spacing} m)")
    replace(params.rigid, travel=travel)  # the linkage's own range, before meshing
    options = {"n_per_flexure": n_per_flexure, "root_extension": root_extension}
    fe, places, facts = build(params, model, size_factor, max_dofs, dim, **options)
    lin = linear_analysis(fe, travel / 2, places)
    prbm = prbm_stiffness(params)
    prbm_stress = prbm_peak_stress(params, travel / 2)
    out = {"k_x": lin["k_x"], "k_y": lin["k_y"], "k_x_prbm": prbm["k_x"],
           "k_x_prbm_joints": prbm["joints"], "max_von_mises": lin["max_von_mises"],
           "max_von_mises_element": lin["max_von_mises_element"],
           "max_stress_location": lin["max_stress_location"],
           "prbm_bending_stress": prbm_stress, "travel_m": travel,
           "dofs": int(fe.n_dofs), "linear_result": lin["result"], "model": model,
           "solver": lin["result"].solver, "dim": dim, **facts}
    if n_modes:
        if model == "beam" and dim == 3:
            out["modes"] = spatial_beam_modes(params, n_modes, facts["root_extension"])
        else:
            out["modes"] = modal_analysis(fe, n_modes)
    if nonlinear:
        stroke = (fe, places) if model == "continuum" else build(
            params, model, dim=2, stroke=True, **options)[:2]
        nl = large_deflection(stroke[0], params, travel, steps, both_halves, stroke[1])
        out.update({k: v for k, v in nl.items() if k != "rows"})
        out["path"] = nl["rows"]
    return out


def params_from_dict(values: dict) -> EightBarFlexureParams:
    """EightBarFlexureParams from a flat dict: its own fields and EightBarParams' fields
    (unknown keys raise ValueError)."""
    own = {f.name for f in fields(EightBarFlexureParams)} - {"rigid"}
    rigid_names = {f.name for f in fields(EightBarParams)}
    unknown = set(values) - own - rigid_names
    if unknown:
        raise ValueError(f"unknown eight-bar parameter(s) {sorted(unknown)}; known: "
                         f"{sorted(own | rigid_names)}")
    base = EightBarFlexureParams()
    rigid = replace(base.rigid, **{k: v for k, v in values.items() if k in rigid_names})
    return replace(base, rigid=rigid, **{k: v for k, v in values.items() if k in own})


def parameter_names() -> list[str]:
    """The names :func:`params_from_dict` takes: EightBarFlexureParams' and EightBarParams'."""
    return sorted(({f.name for f in fields(EightBarFlexureParams)} - {"rigid"})
                  | {f.name for f in fields(EightBarParams)})


@declare(parameters=parameter_names, positive=("k_x", "k_y", "f1_hz", "h", "dofs"))
def evaluate(params: dict | None = None, size_factor: float = 1.0, nonlinear: bool = False,
             steps: int = 6, max_dofs: int | None = None, *,
             model: Literal["continuum", "beam"] = "continuum", n_per_flexure: int = 24,
             root_extension: float | None = None) -> dict:
    """Study-registry entry: flat float metrics of the design ``params`` (a flat dict, see
    :func:`params_from_dict`) from the continuum FEM or the beam model (``model``; a study
    selects it with ``options = { model = "beam" }``): k_x, k_y, k_x_prbm, max_von_mises,
    max_von_mises_element, f1_hz, dofs (and the continuum's h, flexure element size, m). The
    nonlinear trace (fem_deviation_pct, peak stress) only with ``nonlinear=True``.
    ``size_factor``, ``max_dofs``: the continuum's; ``n_per_flexure``, ``root_extension``:
    the beam's; each model ignores the other's."""
    out = analyze_eightbar(params_from_dict(params or {}), size_factor=size_factor, steps=steps,
                           n_modes=1, both_halves=False, nonlinear=nonlinear, max_dofs=max_dofs,
                           model=model, n_per_flexure=n_per_flexure,
                           root_extension=root_extension)
    keys = ("k_x", "k_y", "k_x_prbm", "max_von_mises", "max_von_mises_element", "dofs")
    metrics = {k: float(out[k]) for k in keys + (("h",) if model == "continuum" else ())}
    metrics["f1_hz"] = out["modes"][0]["f_hz"]
    if nonlinear:
        for k in ("fem_deviation_pct", "rigid_deviation_pct", "peak_von_mises_travel",
                  "safety_factor", "max_rotation_rad"):
            metrics[k] = float(out[k])
    return require_finite(metrics, "eight-bar")


def summary_row(out: dict) -> dict:
    """The CLI keys of an analysis: k_x, k_y, max_von_mises, max_stress_location,
    fem_deviation_pct, rigid_deviation_pct and a few more (SI)."""
    keys = ("k_x", "k_y", "k_x_prbm", "max_von_mises", "max_stress_location", "travel_m",
            "fem_deviation_pct", "fem_deviation_m", "fem_band_m", "rigid_deviation_pct",
            "rigid_deviation_m", "peak_von_mises_travel", "peak_von_mises_flexure",
            "safety_factor", "max_rotation_rad", "end_force_n", "dofs", "solver", "dim")
    row = require_finite({k: out[k] for k in keys if k in out}, "eight-bar")
    if "modes" in out:
        row["modes"] = out["modes"]
    return row

