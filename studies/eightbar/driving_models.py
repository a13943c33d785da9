"""The driving linkage (thesis Ch. 6) by either model, with one analysis: the continuum FEM
(:func:`flexfem.studies.eightbar.driving.build_model`) or the reduced beam model
(:func:`flexfem.reduced.driving.driving_beam_model`), both with the groups
"fixed", "input", "ee_L" and "ee_R".

    out = analyze_driving(model="beam")      # or model="continuum"
    out["stiffness_n_per_m"], out["transmission"], out["modes"][0]["f_hz"]

Loading: :func:`~flexfem.studies.eightbar.driving.linear_drive`, the anchors clamped, the
shuttle's top face "input" moved along y with its x free (its rotation held: every point of
the level face moves alike); the end-effector faces' mean motion per unit input (m/m), the
input force per metre (N/m) and the peak stress (Pa: the continuum's von Mises includes the
fillets' stress concentration, the beam's |N|/A + |M|c/I has not). Modes with the anchors
clamped. SI units.
"""
from dataclasses import fields, replace
import functools
import math
from typing import Literal

from ...fem import Fixed, solve_modes
from ...reduced.layout import ROOT_EXTENSION
from ...geometry.eightbar.driving import DrivingParams
from ...reduced.driving import driving_beam_model, driving_prbm_stiffness
from ...geometry.eightbar.flexure import EightBarFlexureParams
from ..engine.validate import declare
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


def _references(params: DrivingParams, flexure, layout=None) -> dict:
    """The closed forms beside both models: PRBM input stiffness (N/m), rigid transmission."""
    prbm = driving_prbm_stiffness(params, flexure, layout)
    return {"k_in_prbm": prbm["k_in"], "rigid_transmission": prbm["transmission"]}


def build(params: DrivingParams, flexure, model: str = "continuum", size_factor: float = 1.5,
          n_per_flexure: int = 24, root_extension: float = ROOT_EXTENSION) -> tuple:
    """(model, facts) of the driving linkage: the 2-D FEM (P2, mesh ``size_factor``) or the
    beam model (``n_per_flexure`` elements a flexure, ``root_extension``), each with the
    groups the analysis names; facts: what the output records of the model."""
    if model == "continuum":
        if not (isinstance(size_factor, (int, float)) and math.isfinite(size_factor)
                and size_factor > 0):
            raise ValueError(f"size_factor = {size_factor!r} must be a number > 0")
        fe, _ = build_model(params, flexure, size_factor=float(size_factor))
        return fe, {"size_factor": size_factor, "layout": None}
    if model == "beam":
        fe, info = driving_beam_model(params, flexure, n_per_flexure, root_extension)
        return fe, {"root_extension": root_extension, "layout": info["layout"]}
    raise ValueError(f"model = {model!r} must be one of {MODELS}")


def analyze_driving(params: DrivingParams | None = None, flexure=None, model: str = "continuum",
                    n_modes: int = 3, **options) -> dict:
    """Linear drive (:func:`~flexfem.studies.eightbar.driving.linear_drive`, per PROBE) and
    ``n_modes`` modes of the continuum or the beam model (``options``: :func:`build`'s):
    input stiffness (N/m), transmission d x_R / d s and left/right ratio (-), end-effector
    motions per PROBE (m), peak von Mises (Pa), modes [{"f_hz"}], closed forms (k_in_prbm
    N/m, rigid_transmission), dofs."""
    params, flexure = params or DrivingParams(), flexure or default_flexure()
    fe, facts = build(params, flexure, model, **options)
    out = {k: v for k, v in linear_drive(fe, PROBE).items() if k != "result"}
    if n_modes:
        # shift-invert about -1 Hz: the mechanism's modes (~10 Hz) lie far below the
        # default shift's scale (the stiff links' K/M), where Lanczos converges slowly
        modes = solve_modes(fe, n_modes, [Fixed("fixed")], shift_hz=-1.0)
        out["modes"] = [{"f_hz": float(f)} for f in modes.frequencies_hz]
    layout = facts.pop("layout")
    return {**out, **_references(params, flexure, layout), "dofs": int(fe.n_dofs),
            "model": model, **facts}


def analyze_driving_beam(params: DrivingParams | None = None, flexure=None, n_modes: int = 3,
                         **options) -> dict:
    """:func:`analyze_driving` of the beam model."""
    return analyze_driving(params, flexure, "beam", n_modes, **options)


def analyze_driving_continuum(params: DrivingParams | None = None, flexure=None,
                              n_modes: int = 3, **options) -> dict:
    """:func:`analyze_driving` of the continuum FEM."""
    return analyze_driving(params, flexure, "continuum", n_modes, **options)


METRICS = ("stiffness_n_per_m", "transmission", "ratio_left_right", "cross_motion_right",
           "max_von_mises_pa", "k_in_prbm", "rigid_transmission", "dofs")


def _metrics(out: dict) -> dict:
    metrics = {k: float(out[k]) for k in METRICS}
    metrics["f1_hz"] = out["modes"][0]["f_hz"]
    return metrics


@declare(parameters=_DRIVING + _FLEXURE, positive=("stiffness_n_per_m", "f1_hz", "dofs"))
def evaluate(params: dict | None = None, *, model: Literal["continuum", "beam"] = "continuum",
             size_factor: float = 1.5, n_per_flexure: int = 24,
             root_extension: float = ROOT_EXTENSION) -> dict:
    """Study metrics, METRICS and f1_hz (SI), of the continuum FEM or the beam model
    (``model``); ``size_factor`` is the continuum's, ``n_per_flexure`` and
    ``root_extension`` the beam's; each model ignores the other's."""
    options = ({"size_factor": size_factor} if model == "continuum" else
               {"n_per_flexure": n_per_flexure, "root_extension": root_extension})
    return _metrics(analyze_driving(*designs_from_dict(params), model, 1, **options))


#: Units of the study's parameters (DrivingParams and the flexure sizes: lengths) and metrics,
#: for plot axes.
UNITS = {**dict.fromkeys(_DRIVING + tuple(n for n in _FLEXURE if n != "material"), "m"),
         "stiffness_n_per_m": "N/m", "k_in_prbm": "N/m", "transmission": "-",
         "rigid_transmission": "-", "ratio_left_right": "-", "cross_motion_right": "-",
         "max_von_mises_pa": "Pa", "dofs": "-"}
