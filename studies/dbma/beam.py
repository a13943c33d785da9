"""Beam-model analysis of the DBMA: the continuum study's outputs
(:mod:`flexfem.studies.dbma.analysis`) from the reduced beam model
(:func:`flexfem.geometry.dbma.beam.dbma_beam_model`), in milliseconds.

Same loadings as the continuum: equal and opposite forces on the pads, member 11 held
(R = output / elongation, k_in = F / elongation); output stiffness k_out: a force on the output
along y with the pads held along x (and their rotation: the continuum holds every pad node's
x); modes with the pads held along x, the working mode the one of largest effective mass along
y. The beam stress is |N|/A + |M|c/I: no stress concentration at the sharp hinge roots, where
the continuum's von Mises peak is singular (mesh-dependent); with filleted hinges the peak is
that nominal stress times the shoulder fillet's published K_t, with circular notches times the
neck's K_t from the notch's 2-D model (:mod:`.beam_stress`). SI units.
"""
import math

import numpy as np

from ...fem.beam import (Fixed, NodalLoad, solve_beam_displacements,
                         solve_beam_modes, solve_beam_static)
from ...geometry.beam_layout import ROOT_EXTENSION
from ...geometry.dbma.beam import dbma_beam_model, pads_held
from ...geometry.dbma.drawing import DBMALayout
from ...geometry.dbma.params import DBMAParams
from .analysis import dbma_material, params_from_dict
from .beam_stress import dbma_fillet_stress, dbma_notch_stress
from .figures import analytical_metrics


def beam_static(model, info, force: float, peak_stress=None) -> dict:
    """R_fem, R_fem_per_side, k_in (N/m), elongation and output displacement (m), max beam
    stress (Pa) under the actuator force pair ``force`` (N). ``peak_stress(model, state)``
    (optional, e.g. the fillets' K_t) returns {"peak_stress", ...}: max_von_mises is then
    its peak, the beam's own in "nominal_stress"."""
    a, b, top = info["input_a"], info["input_b"], info["output"]
    s = solve_beam_static(model, [Fixed(tuple(info["ground"]))],
                          [NodalLoad(a, fx=-force), NodalLoad(b, fx=force)])
    elongation = float(s.q[b, 0] - s.q[a, 0])
    u_out = float(s.q[top, 1])
    where = s.max_stress_location[2]
    out = {"force": force, "elongation": elongation, "output_displacement": u_out,
           "max_von_mises_location": [float(where[0]), float(where[1])],
           "R_fem": u_out / elongation, "R_fem_per_side": 2 * u_out / elongation,
           "k_in": force / elongation, "max_von_mises": s.max_stress}
    if peak_stress is not None:
        out.update(peak_stress(model, s), nominal_stress=s.max_stress)
        out["max_von_mises"] = out["peak_stress"]
    return out


def beam_output_stiffness(model, info, force: float = 100.0) -> float:
    """k_out = F / u_out (N/m): output pushed along y, pads held (actuator rigid)."""
    q = solve_beam_displacements(model, pads_held(info), [NodalLoad(info["output"], fy=force)])
    return force / float(q[info["output"], 1])


def beam_modal(model, info, n_modes: int = 6) -> dict:
    """frequencies_hz, effective_mass (n x 2, kg), working_mode (1-based), fn_working (Hz)."""
    modes = solve_beam_modes(model, pads_held(info), n=n_modes)
    k = int(np.argmax(modes.effective_mass[:, 1])) + 1
    return {"frequencies_hz": [float(f) for f in modes.frequencies_hz],
            "effective_mass": modes.effective_mass.tolist(), "working_mode": k,
            "fn_working": float(modes.frequencies_hz[k - 1])}


def beam_modal3d(p: DBMAParams, layout: DBMALayout, n_modes: int,
                 root_extension: float = ROOT_EXTENSION) -> dict:
    """beam_modal's keys from the spatial beam model (in-plane and out-of-plane modes;
    effective_mass n x 3), the hinges' torsion with Vlasov's warping restraint where they
    are leaves ("torsion": "Vlasov" or "Saint-Venant")."""
    from ..modes3d import working_index
    from .modes3d import beam_modes3d

    leaf = layout.hinge_profile == "leaf"
    modes = beam_modes3d(p, layout, n_modes, warping=leaf, root_extension=root_extension)
    fraction = np.array(modes["mass_fraction"])
    k = working_index(modes) + 1
    note = ("out-of-plane modes from the spatial beam model: with Vlasov's warping restraint "
            "on leaf hinges the four lowest within about 3 % of the 3-D solid on the paper's "
            "design, the torsion modes above them up to about 5.5 % high; Saint-Venant torsion "
            "(notch and filleted hinges) reads 12-18 % low on the two lowest and 30-48 % above "
            "(docs/beam.md); decide with --model continuum")
    return {"frequencies_hz": modes["f_hz"],
            "effective_mass": (fraction * modes["total_mass_kg"]).tolist(), "working_mode": k,
            "fn_working": modes["f_hz"][k - 1], "torsion": "Vlasov" if leaf else "Saint-Venant",
            "validity_notes": [note]}


def analyze_dbma_beam(p: DBMAParams, layout: DBMALayout | None = None, force: float = 100.0,
                      n_modes: int = 6, root_extension: float = ROOT_EXTENSION,
                      dim: int = 2) -> dict:
    """Static, output stiffness and modal results of the beam model beside the analytical
    models (the keys of the continuum analyze_dbma where they mean the same). ``dim`` 3: the
    modes of the spatial beam model (:func:`beam_modal3d`: out-of-plane modes too, their
    accuracy in its note and docs/beam.md); the statics are in-plane either way."""
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} must be 2 or 3")
    layout = layout or DBMALayout()
    model, info = dbma_beam_model(p, layout, root_extension)
    peak = {"filleted": lambda m, s: dbma_fillet_stress(p, layout, m, s),
            "circular": lambda m, s: dbma_notch_stress(p, layout, m, info, s)
            }.get(layout.hinge_profile)
    out = {**analytical_metrics(p), **beam_static(model, info, force, peak),
           "k_out": beam_output_stiffness(model, info), "dofs": int(model.n_dofs),
           "model": "beam", "root_extension": root_extension}
    out["safety_factor"] = dbma_material(p).yield_strength / out["max_von_mises"]
    if n_modes:
        out.update(beam_modal(model, info, n_modes) if dim == 2 else
                   beam_modal3d(p, layout, n_modes, root_extension))
    return out


def evaluate_beam(params_dict: dict | None = None, modes: bool = False, force: float = 100.0,
                  root_extension: float = ROOT_EXTENSION, hinge_profile: str = "leaf",
                  dim: int | None = None, size_factor: float | None = None) -> dict:
    """Study metrics of the beam model, named as the continuum evaluate's: R_fem,
    R_fem_per_side, k_in, max_von_mises, dofs, the analytical metrics, k_out, and with
    ``modes`` fn_working and working_mode. The continuum-only options dim and size_factor
    are accepted and ignored (a study can switch ``model`` without editing its options); any
    other option raises TypeError."""
    p = params_from_dict(params_dict or {})
    layout = DBMALayout(hinge_profile=hinge_profile)
    out = analyze_dbma_beam(p, layout, force, 6 if modes else 0, root_extension)
    keep = [k for k, v in out.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    metrics = {k: float(out[k]) for k in keep if k not in ("force",)}
    if modes:
        metrics["working_mode"] = int(out["working_mode"])
    return metrics


def beam_estimates(p: DBMAParams, stroke: float) -> dict:
    """The optimiser's screening estimates from the beam model, keyed like
    :func:`flexfem.studies.dbma.optimize.analytical_estimates`: R_fem, k_out (N/m),
    fn_working (Hz), von_mises_at_stroke (Pa, the beam stress at the actuator stroke, m)."""
    model, info = dbma_beam_model(p)
    static = beam_static(model, info, 100.0)
    modal = beam_modal(model, info, 4)
    scale = stroke / static["elongation"]
    von_mises = static["max_von_mises"] * scale
    return {"R_fem": static["R_fem"], "k_out": beam_output_stiffness(model, info),
            "fn_working": modal["fn_working"],
            "von_mises_at_stroke": von_mises if math.isfinite(von_mises) else math.inf}
