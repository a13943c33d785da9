"""A model file's problem solved with its declared beam model (``[[beam]]``, ``[[rigid]]``):
``analyze_beam_model(spec) -> dict`` with the keys of the continuum's
:func:`flexfem.studies.user_model.analysis.analyze_model`, in milliseconds.

Supports and loads act on the node each group names in its [[rigid]] body: a support holds
that body (all of x, y and rotation; a prescribed component only that component), a force is
the group's total force applied at that point, the group's "mean displacement" is that point's
displacement (the continuum's mean over a face that moves rigidly). max_von_mises is the beam
stress |N|/A + |M| c / I (no stress concentration at the roots, which the continuum has).
Buckling and harmonic analyses are the continuum's only. SI units.
"""
import numpy as np

from ...fem.beam import (Fixed, NodalLoad, Prescribed, compliance, solve_beam_modes,
                         solve_beam_nonlinear, solve_beam_static)
from ...fem.compliance import Compliance
from ...geometry.user_model.beam_model import beam_model
from .beam3d_modes import planar_twin, spatial_modes
from .outputs import groups_of, stiffness

_AXES = ("x", "y")


def beam_supports_and_loads(spec, info) -> tuple[list, list]:
    """The beam model's supports (Fixed, Prescribed) and loads (NodalLoad) of the model
    file; ValueError naming the file for a traction load (give the face's total force)."""
    groups, supports, loads, held = info["groups"], [], [], {}
    for s in spec.supports:
        body = info["bodies"][s.group]
        if held.setdefault(body, s.group) != s.group:
            raise ValueError(f"{s.source or spec.source}: [[supports]] {s.group!r} and "
                             f"{held[body]!r} are on the same [[rigid]] block (number "
                             f"{body + 1}); the beam model holds a block once")
        node = groups[s.group]
        if s.components is None:
            supports.append(Fixed((node,)))
        else:
            supports += [Prescribed(node, _AXES[i], v) for i, v in s.components.items()]
    for load in spec.loads:
        if load.kind != "force":
            raise ValueError(f"{load.source or spec.source}: [[loads]] {load.kind} on "
                             f"{load.group!r}: the beam model takes forces (N, the face's "
                             "total); give force = [...]")
        loads.append(NodalLoad(groups[load.group], *load.vector))
    return supports, loads


def _unsupported(spec) -> None:
    if spec.dim != 2 and spec.mechanism is None:
        raise ValueError(f"{spec.source}: the declared beam model is planar; a 3-D geometry "
                         "file is the continuum's (--model continuum)")
    a = spec.analysis
    asked = [k for k, v in (("buckling", a.buckling), ("harmonic", a.harmonic)) if v]
    if asked:
        raise ValueError(f"{spec.source}: [analysis] {', '.join(asked)}: the beam model does "
                         "not compute it; use the continuum model (--model continuum)")


def _mean(state, info, groups) -> dict:
    return {g: state.q[info["groups"][g], :2].tolist() for g in groups}


def _reactions(spec, state, info) -> dict:
    out = {}
    for s in spec.supports:
        node = info["groups"][s.group]
        out[s.group] = [float(v) for v in state.reactions.get(node, np.zeros(3))[:2]]
    return out


def analyze_beam_model(spec) -> dict:
    """The continuum analyze_model's keys from the declared beam model (solver "beam", h the
    mean element length, m)."""
    _unsupported(spec)
    solid = spec if spec.dim == 3 else None
    if solid is not None:  # bodies and flexures: the planar statics, the lifted model's modes
        spec = planar_twin(spec)
    try:
        model, info = beam_model(spec)
        supports, loads = beam_supports_and_loads(spec, info)
        state = solve_beam_static(model, supports, loads)
    except ValueError as error:
        raise type(error)(str(error) if str(error).startswith(spec.source)
                          else f"{spec.source}: {error}") from None
    groups = groups_of(spec)
    mean = _mean(state, info, groups)
    e, xi, where = state.max_stress_location
    out = {
        "model": spec.source, "geometry": str(spec.geometry), "parameters": dict(spec.constants),
        "dim": spec.dim, "dofs": int(model.n_dofs), "solver": "beam",
        "h": float(np.mean(model.lengths)), "max_von_mises": state.max_stress,
        "max_von_mises_location": [float(v) for v in where],
        "mean_displacement": mean, "reactions": _reactions(spec, state, info),
        "stiffness": stiffness(spec, mean), "yield_strength": spec.material.yield_strength,
    }
    if solid is not None:  # the solid's groups have three components
        out["dim"] = 3
        for key in ("mean_displacement", "reactions"):
            out[key] = {g: list(v) + [0.0] for g, v in out[key].items()}
    if spec.analysis.modes and solid is not None:
        out["frequencies_hz"] = spatial_modes(solid, model, info, spec.analysis.modes)
    elif spec.analysis.modes:
        modes = solve_beam_modes(model, supports, n=spec.analysis.modes)
        out["frequencies_hz"] = modes.frequencies_hz.tolist()
    if spec.analysis.steps:
        large = solve_beam_nonlinear(model, supports, loads, steps=spec.analysis.steps)
        out["nonlinear"] = {"steps": len(large.load_factors) - 1,
                            "mean_displacement": _mean(large.final, info, groups),
                            "reactions": _reactions(spec, large.final, info),
                            "max_von_mises": large.final.max_stress}
    if spec.analysis.compliance:
        out["compliance"] = _compliance(spec, model, info, supports)
    return out


def _compliance(spec, model, info, supports) -> dict:
    """The [analysis] compliance group's 3x3 compliance at its point, as the continuum's."""
    node = info["groups"][spec.analysis.compliance]
    c = Compliance(spec.analysis.compliance, compliance(model, supports, node),
                   model.nodes[node].copy(), np.eye(2))
    return {"group": c.face, "matrix": c.matrix.tolist(), "point_m": c.point.tolist(),
            "stiffness": c.stiffness.tolist(),
            "principal_compliances": c.principal()[0].tolist(),
            "centre_of_compliance_m": c.centre_of_compliance.tolist()}
