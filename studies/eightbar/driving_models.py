"""The driving linkage (thesis Ch. 6) by either model, with the same outputs: the continuum FEM
(:mod:`flexfem.studies.eightbar.driving`) or the reduced beam model
(:func:`flexfem.geometry.eightbar.driving_beam.driving_beam_model`).

    out = analyze_driving(model="beam")      # or model="continuum"
    out["stiffness_n_per_m"], out["transmission"], out["modes"][0]["f_hz"]

Loading as the continuum's :func:`~flexfem.studies.eightbar.driving.linear_drive`: the anchors
clamped, the shuttle's top face "input" moved along y with its x free and its rotation held
(the continuum prescribes y on every node of the level face); the end-effector faces' motion
per unit input (m/m), the input force per metre (N/m) and the peak stress (Pa: the continuum's
von Mises includes the fillets' stress concentration, the beam's |N|/A + |M|c/I has not).
Modes with the anchors clamped. SI units.
"""
from dataclasses import fields, replace
import functools
import math

from ...fem import Fixed as FixedFace
from ...fem import solve_modes
from ...fem.beam import Fixed, Prescribed, solve_beam_modes, solve_beam_static
from ...geometry.beam_layout import ROOT_EXTENSION
from ...geometry.eightbar.driving import DrivingParams
from ...geometry.eightbar.driving_beam import driving_beam_model, driving_prbm_stiffness
from ...geometry.eightbar.flexure import EightBarFlexureParams
from ..engine.choice import ModelChoice
from .driving import build_model, linear_drive

PROBE = 1e-6  # m, the linear input displacement (results are per metre)
MODELS = ("continuum", "beam")
_DRIVING = tuple(f.name for f in fields(DrivingParams) if f.name != "suspension")
_FLEXURE = tuple(f.name for f in fields(EightBarFlexureParams) if f.name != "rigid")


@functools.lru_cache(maxsize=1)
def default_flexure() -> EightBarFlexureParams:
    """The default flexure sizes, built once (their checks take ~1 s: the contact check)."""
    return EightBarFlexureParams()


def designs_from_dict(values: dict | None) -> tuple:
    """(DrivingParams, EightBarFlexureParams) of the defaults with ``values`` ({field: value}
    of either dataclass, m) changed; ValueError naming an unknown field."""
    values = dict(values or {})
    unknown = sorted(set(values) - set(_DRIVING) - set(_FLEXURE))
    if unknown:
        raise ValueError(f"unknown driving-linkage parameter(s) {unknown}; known: "
                         f"{sorted(_DRIVING + _FLEXURE)}")
    params = replace(DrivingParams(), **{k: v for k, v in values.items() if k in _DRIVING})
    changed = {k: v for k, v in values.items() if k in _FLEXURE}
    flexure = replace(default_flexure(), **changed) if changed else default_flexure()
    return params, flexure


def _drive_keys(u_l, u_r, force, stress) -> dict:
    """The linear drive's outputs per PROBE input: motions (m), ratios (-), force (N)."""
    return {"input_m": PROBE, "ux_left_m": float(u_l[0]), "uy_left_m": float(u_l[1]),
            "ux_right_m": float(u_r[0]), "uy_right_m": float(u_r[1]),
            "ratio_left_right": float(u_l[0] / u_r[0]), "transmission": float(u_r[0] / PROBE),
            "cross_motion_right": float(abs(u_r[1] / u_r[0])), "input_force_n": float(force),
            "stiffness_n_per_m": float(force / PROBE), "max_von_mises_pa": float(stress)}


def _references(params: DrivingParams, flexure, layout=None) -> dict:
    """The closed forms beside both models: PRBM input stiffness (N/m), rigid transmission."""
    prbm = driving_prbm_stiffness(params, flexure, layout)
    return {"k_in_prbm": prbm["k_in"], "rigid_transmission": prbm["transmission"]}


def analyze_driving_beam(params: DrivingParams | None = None, flexure=None, n_modes: int = 3,
                         n_per_flexure: int = 24,
                         root_extension: float = ROOT_EXTENSION) -> dict:
    """Linear drive and ``n_modes`` modes of the beam model: the keys of
    :func:`analyze_driving_continuum` (model "beam")."""
    params, flexure = params or DrivingParams(), flexure or default_flexure()
    model, info = driving_beam_model(params, flexure, n_per_flexure, root_extension)
    ground, inp = [Fixed(tuple(info["ground"]))], info["input"]
    state = solve_beam_static(model, ground + [Prescribed(inp, "y", PROBE),
                                               Prescribed(inp, "theta", 0.0)])
    out = _drive_keys(state.q[info["ee_L"], :2], state.q[info["ee_R"], :2],
                      state.reactions[inp][1], state.max_stress)
    if n_modes:
        modes = solve_beam_modes(model, ground, n=n_modes)
        out["modes"] = [{"f_hz": float(f)} for f in modes.frequencies_hz]
    return {**out, **_references(params, flexure, info["layout"]), "dofs": int(model.n_dofs),
            "model": "beam", "root_extension": root_extension}


def analyze_driving_continuum(params: DrivingParams | None = None, flexure=None,
                              n_modes: int = 3, size_factor: float = 1.5) -> dict:
    """Linear drive (:func:`~flexfem.studies.eightbar.driving.linear_drive`) and ``n_modes``
    modes of the 2-D FEM (P2, mesh ``size_factor``): input stiffness (N/m), transmission
    d x_R / d s and left/right ratio (-), end-effector motions per PROBE (m), peak von Mises
    (Pa), modes [{"f_hz"}], closed forms (k_in_prbm N/m, rigid_transmission), dofs."""
    params, flexure = params or DrivingParams(), flexure or default_flexure()
    model, _ = build_model(params, flexure, size_factor=size_factor)
    lin = linear_drive(model, PROBE)
    u_l = (lin["ux_left_m"], lin["uy_left_m"])
    u_r = (lin["ux_right_m"], lin["uy_right_m"])
    out = _drive_keys(u_l, u_r, lin["input_force_n"], lin["max_von_mises_pa"])
    if n_modes:
        # shift-invert about -1 Hz: the mechanism's modes (~10 Hz) lie far below the
        # default shift's scale (the stiff links' K/M), where Lanczos converges slowly
        modes = solve_modes(model, n_modes, [FixedFace("fixed")], shift_hz=-1.0)
        out["modes"] = [{"f_hz": float(f)} for f in modes.frequencies_hz]
    return {**out, **_references(params, flexure), "dofs": int(model.n_dofs),
            "model": "continuum", "size_factor": size_factor}


def analyze_driving(params: DrivingParams | None = None, flexure=None, model: str = "continuum",
                    n_modes: int = 3, **options) -> dict:
    """:func:`analyze_driving_continuum` or :func:`analyze_driving_beam` by ``model``."""
    if model not in MODELS:
        raise ValueError(f"model = {model!r} must be one of {MODELS}")
    run = analyze_driving_beam if model == "beam" else analyze_driving_continuum
    return run(params, flexure, n_modes=n_modes, **options)


METRICS = ("stiffness_n_per_m", "transmission", "ratio_left_right", "cross_motion_right",
           "max_von_mises_pa", "k_in_prbm", "rigid_transmission", "dofs")


def _metrics(out: dict) -> dict:
    metrics = {k: float(out[k]) for k in METRICS}
    metrics["f1_hz"] = out["modes"][0]["f_hz"]
    return metrics


def evaluate_continuum(params: dict | None = None, size_factor: float = 1.5) -> dict:
    """Study metrics of the continuum FEM: METRICS and f1_hz (SI)."""
    if not (isinstance(size_factor, (int, float)) and math.isfinite(size_factor)
            and size_factor > 0):
        raise ValueError(f"size_factor = {size_factor!r} must be a number > 0")
    return _metrics(analyze_driving_continuum(*designs_from_dict(params), n_modes=1,
                                              size_factor=float(size_factor)))


def evaluate_beam(params: dict | None = None, n_per_flexure: int = 24,
                  root_extension: float = ROOT_EXTENSION, size_factor: float | None = None) -> dict:
    """Study metrics of the beam model, named as :func:`evaluate_continuum`'s; the
    continuum-only size_factor is accepted and ignored (a study switches ``model`` without
    editing its options)."""
    return _metrics(analyze_driving_beam(*designs_from_dict(params), n_modes=1,
                                         n_per_flexure=n_per_flexure,
                                         root_extension=root_extension))


evaluate = ModelChoice("continuum", continuum=evaluate_continuum, beam=evaluate_beam)

#: Units of the study's parameters (DrivingParams and the flexure sizes: lengths) and metrics,
#: for plot axes.
UNITS = {**dict.fromkeys(_DRIVING + tuple(n for n in _FLEXURE if n != "material"), "m"),
         "stiffness_n_per_m": "N/m", "k_in_prbm": "N/m", "transmission": "-",
         "rigid_transmission": "-", "ratio_left_right": "-", "cross_motion_right": "-",
         "max_von_mises_pa": "Pa", "dofs": "-"}
