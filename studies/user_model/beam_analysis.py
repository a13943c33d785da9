"""What the beam model of a model file adds to its analysis (:func:`.analysis.analyze_model`
runs the same analysis on either model, :mod:`flexfem.fem.beam.face`).

A group is its [[rigid]] body's point (or its body, for bodies and flexures): a support holds
that body, a force is the group's total force applied there, the group's "mean displacement"
is that point's displacement (the continuum's mean over a face that moves rigidly).
max_von_mises is the beam stress |N|/A + |M| c / I (no stress concentration at the roots,
which the continuum has). Buckling is the continuum's only. ``--dim 3`` (bodies and flexures):
the modes of the spatial beam model (:mod:`.beam3d_modes`), and its statics where a force
pushes out of the plane (else the planar model's, the same in the plane). SI units.
"""
from .beam3d_modes import out_of_plane, planar_twin, spatial_modes, spatial_static

__all__ = ["check_beam_analyses", "lifted_outputs", "out_of_plane", "planar_twin",
           "spatial_modes", "spatial_static"]


def check_beam_analyses(spec) -> None:
    """ValueError naming the file for what the beam model does not do: a 3-D geometry file,
    two supports on one [[rigid]] body (the beam model holds a body once)."""
    if spec.dim != 2 and spec.mechanism is None:
        raise ValueError(f"{spec.source}: the declared beam model is planar; a 3-D geometry "
                         "file is the continuum's (--model continuum)")
    if out_of_plane(spec) and (spec.analysis.steps or spec.analysis.harmonic):
        raise ValueError(f"{spec.source}: [analysis] steps and harmonic of the beam model are "
                         "planar; with an out-of-plane force use --model continuum --dim 3")
    bodies = spec.beams.groups if spec.beams is not None else {}
    held = {}
    for s in spec.supports:
        body = bodies.get(s.group)
        if body is not None and held.setdefault(body, s.group) != s.group:
            raise ValueError(f"{s.source or spec.source}: [[supports]] {s.group!r} and "
                             f"{held[body]!r} are on the same [[rigid]] block (number "
                             f"{body + 1}); the beam model holds a block once")


def lifted_outputs(out: dict) -> dict:
    """The planar statics of a 3-D file as the solid's: dim 3, vectors with z = 0."""
    lifted = {"dim": 3}
    for key in ("mean_displacement", "reactions"):
        lifted[key] = {g: list(v) + [0.0] * (3 - len(v)) for g, v in out[key].items()}
    return lifted
