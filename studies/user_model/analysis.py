"""Analysis of a user's model file: static solve (and natural frequencies, and a
large-deflection solve where asked), as a JSON-able dict and as flat metrics for sweeps."""
from pathlib import Path
import re
import tomllib
from typing import TYPE_CHECKING, Literal

import numpy as np

from ...fem import (Fixed, Force, Prescribed, Traction, compliance_matrix, solve_buckling,
                    solve_harmonic, solve_modes, solve_nonlinear, solve_static)
from ...geometry.user_model import ModelSpec, load_spec, mesh_geometry
from ...geometry.user_model.names import override_keys
from ...geometry.user_model.outputs_table import BUILT_IN, output_names
from ...geometry.user_model.spec import model_parameter_names
from ..engine.validate import declare
from ...reduced.model_file import beam_model
from ..spatial.analysis import analyze_spatial_beam
from .beam_analysis import (check_beam_analyses, lifted_outputs, out_of_plane, planar_twin,
                            spatial_modes, spatial_static)
from .observe import observation_metrics, observed, observed_path
from .outputs import check_finite, check_loaded_supports, groups_of as _groups, stiffness
from .corners import sharp_corner
from .stroke import stroke_limits
from .stroke_check import UNCHECKED, stroke_check

if TYPE_CHECKING:  # the continuum (scikit-fem): imported where one is built, never by the beam's
    from ...fem import Model

MODELS = ("continuum", "beam")

_AXES = ("x", "y", "z")
#: Units of the flat metrics of :func:`evaluate` (a model file's parameters are in its own
#: units, so they have none here).
UNITS = {"dofs": "-", "h": "m", "max_von_mises": "Pa", "mean_displacement_*": "m",
         "reaction_*": "N", "stiffness_*": "N/m"}


def formulation(spec: ModelSpec):
    """PlaneStress / PlaneStrain / Solid3D of the model file's [section]."""
    from ...fem import PlaneStrain, PlaneStress, Solid3D

    if spec.section.kind == "plane_stress":
        return PlaneStress(spec.section.thickness)
    if spec.section.kind == "plane_strain":
        return PlaneStrain(spec.section.thickness)
    return Solid3D()


def supports_and_loads(spec: ModelSpec) -> tuple[list, list]:
    """The fem supports (Fixed, Prescribed) and loads (Force, Traction) of the model file."""
    supports = [Fixed(s.group) if s.components is None else
                Prescribed(s.group, **{_AXES[i]: v for i, v in s.components.items()})
                for s in spec.supports]
    loads = [Force(load.group, load.vector) if load.kind == "force" else
             Traction(load.group, load.vector) for load in spec.loads]
    return supports, loads


def element_size(model: "Model") -> float:
    """Characteristic element size h (m): the mean edge length of the mesh."""
    mesh = model.mesh.mesh
    edges = mesh.facets if model.dim == 2 else mesh.edges
    return float(np.mean(np.linalg.norm(mesh.p[:, edges[0]] - mesh.p[:, edges[1]], axis=0)))


def build_model(spec: ModelSpec, size_factor: float = 1.0,
                max_dofs: int | None = None) -> "Model":
    """Mesh the geometry and make the Model (m, Pa); a mesh estimated above ``max_dofs``
    (None: half the available memory) is refused before meshing."""
    from ...fem import Model

    mesh = mesh_geometry(spec, size_factor, max_dofs)
    return Model(mesh, spec.material, formulation(spec), order=spec.mesh.order)


def _solver(spec: ModelSpec) -> str:
    """A model file's solver: "auto" is the direct one, whose memory the file's budget check
    already bounds. The iterative path (p-multigrid CG on quadratic elements, AMG-CG on
    linear ones) saves memory but on thin leaves no time against a factor that fits
    (docs/performance.md); it runs only when the file asks for it ([analysis] solver =
    "amg"), and then under its residual check."""
    return "direct" if spec.analysis.solver == "auto" else spec.analysis.solver


def _in_context(spec: ModelSpec, error: ValueError) -> ValueError:
    """The fem error itself, its message prefixed by the model file: its type and attributes
    kept (rebuilding it would fail for one whose constructor takes more than the message,
    such as NonConvergenceError, and hide the real cause behind a TypeError)."""
    text = str(error)
    if not text.startswith(spec.source):
        error.args = (f"{spec.source}: {text}",)
    return error


def build(spec: ModelSpec, model: str = "continuum", size_factor: float = 1.0,
          max_dofs: int | None = None) -> tuple:
    """(model, h) of the model file: the continuum FEM (:func:`build_model`; h its mean edge
    length, m) or its beam model (:func:`~flexfem.reduced.model_file.beam_model`,
    with the file's groups; h the mean element length, m; size_factor unused)."""
    if model == "continuum":
        fe = build_model(spec, size_factor, max_dofs)
        return fe, element_size(fe)
    fe, _ = beam_model(spec)
    return fe, float(np.mean(fe.lengths))


def analyze_model(spec: ModelSpec, size_factor: float = 1.0, model: str = "continuum",
                  max_dofs: int | None = None, fields: dict | None = None) -> dict:
    """Solve the model file's problem. Returns (SI): dofs, solver, h (m), max_von_mises (Pa),
    max_von_mises_location (m), mean_displacement {group: vector (m)} of every support and
    load group, reactions {group: vector (N)} of every support, stiffness {group: {axis:
    N/m}} (single force load), frequencies_hz (when [analysis] modes), nonlinear (when
    [analysis] steps), compliance / buckling / harmonic (when asked; see :func:`_precision`).
    ``model="beam"``: the same analysis of the file's beam model (its declared [[beam]] or
    its bodies' and flexures'; with ``--dim 3`` the spatial beam model's modes, and its
    statics for a force out of the plane: :mod:`.beam_analysis`). ``max_dofs``: the continuum's mesh budget (None: half the
    available memory). ``fields``: a dict that receives the solved "model", its "static"
    result and its "modes" (pictures.py draws and writes them)."""
    if model not in MODELS:
        raise ValueError(f"{spec.source}: model = {model!r} must be one of {MODELS}")
    solid = None
    if model == "beam" and getattr(spec, "spatial", None) is not None:
        return analyze_spatial_beam(spec, fields)  # 3-D bodies: studies/spatial/analysis.py
    if model == "beam":
        check_beam_analyses(spec)
    check_loaded_supports(spec)
    if model == "beam" and spec.dim == 3:  # bodies and flexures: the lifted model's modes
        solid, spec = spec, planar_twin(spec)  # (statics: below)
    supports, loads = supports_and_loads(spec)
    spatial = solid is not None and out_of_plane(solid)
    try:
        fe, h = build(spec, model, size_factor, max_dofs)
        result = (spatial_static(solid, fe) if spatial else
                  solve_static(fe, supports, loads, solver=_solver(spec)))
    except ValueError as error:
        raise _in_context(spec, error) from None
    groups = _groups(spec)
    if fields is not None:
        fields.update(model=fe, static=result)
    mean = {g: result.mean_displacement(g).tolist() for g in groups}
    out = {
        "model": spec.source, "geometry": str(spec.geometry), "parameters": dict(spec.constants),
        "dim": spec.dim, "dofs": int(fe.n_dofs), "solver": result.solver,
        "h": h, "max_von_mises": result.max_von_mises,
        "max_von_mises_location": result.max_von_mises_location.tolist(),
        "mean_displacement": mean,
        "reactions": {g: np.asarray(r).tolist() for g, r in result.reactions.items()},
        "stiffness": stiffness(solid if spatial else spec, mean),
        "yield_strength": _strength(spec.material.yield_strength),
    }
    if out["yield_strength"] is None:
        out["not_available"] = {"yield_strength": "not given in [material]"}
    seen = observed(spec, result, groups, lifted=solid is not None)  # observe.py
    out["not_available"] = {**out.get("not_available", {}), **seen.pop("not_available", {})}
    out.update(seen)
    if spec.analysis.modes:
        try:
            modes = (spatial_modes(solid, fe, spec.analysis.modes) if solid is not None else
                     _kept(fields, "modes", solve_modes(fe, spec.analysis.modes, supports))
                     .frequencies_hz.tolist())
        except ValueError as error:
            raise _in_context(spec, error) from None
        out["frequencies_hz"] = modes
    if spec.analysis.steps:
        out["nonlinear"] = _nonlinear(spec, fe, supports, loads, groups, solid is not None)
    try:
        out.update(_precision(spec, fe, supports, loads))
    except ValueError as error:
        raise _in_context(spec, error) from None
    if solid is not None:
        out.update(lifted_outputs(out))
        spec = solid
    limits = _stroke(spec, out, fe, model, fields)
    out.update({**limits, "not_available": {**out.get("not_available", {}),
                                            **limits.get("not_available", {})}})
    if not out["not_available"]:
        del out["not_available"]
    return check_finite(out, spec.source)


def _stroke(spec: ModelSpec, out: dict, fe, model: str, fields: dict | None = None) -> dict:
    """The stroke limits (stroke.py) of the analysis ``out`` of ``fe``: for the continuum,
    the sharp re-entrant corner of its mesh at its peak (corners.py), and the beam model's
    nominal stress to stand in for a singular peak."""
    nominal, corner = None, None
    if model == "continuum":
        corner = (sharp_corner(fe.mesh.mesh, out["max_von_mises_location"]) if fe.dim == 2
                  else "unchecked")
        if spec.beams is not None:
            nominal = lambda: analyze_model(spec, model="beam")  # noqa: E731
    limits = stroke_limits(spec, out, nominal, corner)
    if not limits.get("stroke_limit_yield") and not limits.get("stroke_limit_fatigue"):
        return limits
    if not spec.analysis.stroke_check:
        return {**limits, "stroke_limit_basis": UNCHECKED}
    if fe.dim != 2 or spec.dim != 2:
        return {**limits, "stroke_limit_basis": "linear (the large-deflection check is planar "
                "only)"}
    if model == "continuum" and limits["stroke_stress_basis"].startswith("nominal beam"):
        fe = build(spec, "beam")[0]  # the path of the model whose stress sized the limits
    checked = stroke_check(spec, {**limits, "groups": list(out["mean_displacement"])}, fe,
                           supports_and_loads(spec)[0], kept=fields)
    return {**limits, **checked}


def _kept(fields: dict | None, name: str, value):
    """``value``, also kept as ``fields[name]`` where the caller asked for the fields."""
    if fields is not None:
        fields[name] = value
    return value


def _strength(value: float) -> float | None:
    """A material strength as output: None where the material gives none (inf)."""
    return float(value) if np.isfinite(value) else None


def _precision(spec, model, supports, loads) -> dict:
    """[analysis] compliance, buckling and harmonic: {"compliance": {group, matrix, point_m,
    stiffness, principal_compliances, centre_of_compliance_m}, "buckling": {load_factors},
    "harmonic": {group, component, damping, resonances_hz, static, frequencies_hz,
    amplitude, phase_rad}} (SI; those asked for)."""
    a, out = spec.analysis, {}
    if a.compliance:
        c = compliance_matrix(model, supports, a.compliance)
        out["compliance"] = {"group": a.compliance, "matrix": c.matrix.tolist(),
                             "point_m": c.point.tolist(), "stiffness": c.stiffness.tolist(),
                             "principal_compliances": c.principal()[0].tolist(),
                             "centre_of_compliance_m": c.centre_of_compliance.tolist()}
    if a.buckling:
        b = solve_buckling(model, supports, loads, n=a.buckling)
        out["buckling"] = {"load_factors": b.load_factors.tolist()}
    if a.harmonic:
        h = a.harmonic
        freqs = np.linspace(0.0, h.f_max, h.points)
        frf = solve_harmonic(model, supports, loads, freqs, damping=h.damping,
                             n_modes=h.n_modes).frf(h.group, h.component)
        out["harmonic"] = {"group": h.group, "component": h.component, "damping": h.damping,
                           "resonances_hz": frf.peaks().tolist(),
                           "static": float(frf.response[0].real),
                           "frequencies_hz": freqs.tolist(), "amplitude": frf.amplitude.tolist(),
                           "phase_rad": frf.phase.tolist()}
    return out


def _nonlinear(spec, model, supports, loads, groups, lifted: bool = False) -> dict:
    """Large-deflection solve at full load: mean displacements (m), reactions (N), von Mises
    (Pa), observations and outputs (and the outputs at every step: observe.py)."""
    try:
        large = solve_nonlinear(model, supports, loads, steps=spec.analysis.steps)
    except ValueError as error:
        raise _in_context(spec, error) from None
    return {"steps": len(large.load_factors) - 1,
            "mean_displacement": {g: large.mean_displacement(g).tolist() for g in groups},
            "reactions": {g: np.asarray(r).tolist() for g, r in large.reactions[-1].items()},
            "max_von_mises": large.max_von_mises,
            **observed_path(spec, large, groups, lifted)}


def _key(name: str) -> str:
    return re.sub(r"\W", "_", name)


def flat_metrics(result: dict) -> dict[str, float]:
    """The analyze_model dict as flat float metrics (see :func:`evaluate`)."""
    out = {"dofs": float(result["dofs"]), "h": result["h"],
           "max_von_mises": result["max_von_mises"]}
    for what, table in (("mean_displacement", result["mean_displacement"]),
                        ("reaction", result["reactions"])):
        for group, vector in table.items():
            for axis, value in zip(_AXES, vector):
                out[f"{what}_{_key(group)}_{axis}"] = float(value)
    for group, by_axis in result["stiffness"].items():
        for axis, value in by_axis.items():
            out[f"stiffness_{_key(group)}_{axis}"] = value
    for k, f in enumerate(result.get("frequencies_hz", []), start=1):
        out[f"f{k}_hz"] = float(f)
    for k, f in enumerate(result.get("buckling", {}).get("load_factors", []), start=1):
        out[f"buckling_factor_{k}"] = float(f)
    if "compliance" in result:
        for i, row in enumerate(result["compliance"]["matrix"]):
            out[f"compliance_{i}{i}"] = float(row[i])
    for key in ("stroke_limit_yield", "stroke_limit_fatigue"):
        if result.get(key) is not None:
            out[key] = float(result[key])
    missing = {k: v for k, v in result.get("not_available", {}).items()
               if k.startswith(("stroke", "outputs."))}
    if missing:  # a study's table says why a stroke metric is absent (a string, not a number)
        out["not_available"] = "; ".join(f"{k}: {v}" for k, v in missing.items())
    if result.get("harmonic", {}).get("resonances_hz"):
        out["harmonic_resonance_hz"] = float(result["harmonic"]["resonances_hz"][0])
    out.update(observation_metrics(result))
    return out


def _names(file=None, allow_code=False, **_) -> list[str] | None:
    """The [parameters] names of the model file a study binds (spec.model_parameter_names)."""
    return model_parameter_names(file, allow_code) if file is not None else None


def _metrics(file=None, **_) -> list[str] | None:
    """The metrics the model file's evaluate may return: the built-in names and patterns,
    its [outputs] (and NAME_nonlinear); None where the file cannot be read (its own error
    then comes from evaluate)."""
    try:
        raw = tomllib.loads(Path(file).read_text()) if file is not None else None
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return None
    if raw is None:
        return None
    names = output_names(raw)
    return [*BUILT_IN, *names, *(f"{n}_nonlinear" for n in names)]


@declare(parameters=_names, options=lambda **_: override_keys(), metrics=_metrics,
         positive=("stiffness_*", "f*_hz", "compliance_*", "h", "dofs"))
def evaluate(params: dict | None = None, *, model: Literal["continuum", "beam"] = "continuum",
             file: str | None = None, size_factor: float = 1.0, allow_code: bool = False,
             max_dofs: int | None = None, **options) -> dict[str, float]:
    """Metrics of the model file ``file`` with ``params`` overriding its [parameters]
    (SI) and ``options`` its other tables ('material.E': 210e9, 'analysis.modes': 3, ...),
    by the continuum FEM or (``model="beam"``) its declared beam model. Keys: dofs, h (m),
    max_von_mises (Pa), mean_displacement_<group>_<axis> (m), reaction_<group>_<axis> (N),
    stiffness_<group>_<axis> (N/m, single force load), f1_hz, f2_hz, ... (Hz),
    stroke_limit_yield and stroke_limit_fatigue (m, studies/user_model/stroke.py). A path given
    as ``model`` (``evaluate(model="guide.toml")``) is the file, analysed by the continuum.
    ``allow_code``: the file's .geo may run code (geometry/user_model/geo_guard.py);
    ``max_dofs``: the continuum's mesh budget (None: half the available memory)."""
    if file is None and model not in MODELS:
        file, model = model, "continuum"
    if file is None:
        raise ValueError("evaluate: file = \"MODEL.toml\" (the model file) is required")
    unknown = [k for k in options if "." not in k]
    if unknown:
        raise ValueError(f"evaluate: unknown option(s) {unknown}; give parameters in params and "
                         "other model-file keys as 'table.key' (e.g. 'material.E')")
    spec = load_spec(file, {**(params or {}), **options}, allow_code=allow_code)
    return flat_metrics(analyze_model(spec, size_factor, model, max_dofs))
