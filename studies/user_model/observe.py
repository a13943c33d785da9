"""Observations of groups and the [outputs] of a model file, from a solve of either model.

A group's displacement (ux, uy[, uz]) is its mean (the continuum: measure-weighted over the
face or subdomain, as ``mean_displacement``; the beam model: its point's). Its rotation is
the rigid rotation that fits its motion best by least squares, with the displacement's
weights: in 2-D rz = sum w (r x v) / sum w |r|^2 (r the points' offsets from the group's
centroid, v their displacements less the mean); in 3-D (rx, ry, rz) solves
[sum w (|r|^2 I - r r^T)] omega = sum w (r x v). Both are the linear (small-rotation) fits,
as a linear solve's displacements are; a large-deflection step's rotation is the best-fit
rotation of the deformed points (2-D: atan2 of sum w (r x r') over sum w (r . r'); 3-D:
Kabsch's SVD, as a rotation vector). On the beam model a group's rotation is its node's,
that of the rigid block it belongs to. A group whose points cannot fix a rotation (a single
point, a line in 3-D) gives nan for it. SI units (m, rad).
"""
import re

import numpy as np

from ...fem.beam.face import group as beam_group
from ...fem.beam.face import group as beam3d_group

_AXES = ("x", "y", "z")
_WORD = re.compile(r"\W")


def _points(model, u, group, basis=None):
    """(X (dim, n), U (dim, n), w (n,)) at the quadrature points of the group."""
    from ...fem.static_result import group_basis  # the continuum's: a beam run goes without
    basis = basis or group_basis(model, group)
    x = np.asarray(basis.global_coordinates())
    uh = np.asarray(basis.interpolate(u))
    w = np.asarray(basis.dx)
    dim = model.dim
    return x.reshape(dim, -1), uh.reshape(dim, -1), np.broadcast_to(w, x.shape[1:]).ravel()


def _fit(x, v, w, large: bool) -> list:
    """The rotation (rz in 2-D, [rx, ry, rz] in 3-D) of displacements v at points x."""
    c = x @ w / w.sum()
    t = v @ w / w.sum()
    r, d = x - c[:, None], v - t[:, None]
    scale = float(np.sqrt((w * (r * r).sum(axis=0)).sum() / w.sum()))
    if scale <= 0:
        return [float("nan")] * (1 if len(x) == 2 else 3)
    if len(x) == 2:
        if large:
            q = r + d
            return [float(np.arctan2((w * (r[0] * q[1] - r[1] * q[0])).sum(),
                                     (w * (r * q).sum(axis=0)).sum()))]
        return [float((w * (r[0] * d[1] - r[1] * d[0])).sum() / (w * (r * r).sum(axis=0)).sum())]
    if large:
        h = (r * w) @ (r + d).T
        a, _, bt = np.linalg.svd(h)
        s = np.diag([1.0, 1.0, np.sign(np.linalg.det(bt.T @ a.T))])
        rotation = bt.T @ s @ a.T
        from scipy.spatial.transform import Rotation

        return Rotation.from_matrix(rotation).as_rotvec().tolist()
    inertia = (w * (r * r).sum(axis=0)).sum() * np.eye(3) - (r * w) @ r.T
    b = (np.cross(r.T, d.T) * w[:, None]).sum(axis=0)
    if np.linalg.cond(inertia) > 1e10:
        return [float("nan")] * 3
    return np.linalg.solve(inertia, b).tolist()


def _components(mean, rotation, dim: int) -> dict:
    """{ux, uy[, uz], rz | rx, ry, rz}; a rotation the group cannot fix is None."""
    out = {f"u{a}": float(v) for a, v in zip(_AXES, mean)}
    names = ["rz"] if dim == 2 else [f"r{a}" for a in _AXES]
    out.update({n: float(v) if np.isfinite(v) else None for n, v in zip(names, rotation)})
    return out


def observe_continuum(model, u, groups, large: bool = False, bases=None) -> dict:
    """{group: {ux, uy[, uz], rz | rx, ry, rz}} of the continuum's displacement ``u``
    (``bases``: {group: its basis}, made once for many steps)."""
    out = {}
    for g in groups:
        x, v, w = _points(model, u, g, (bases or {}).get(g))
        out[g] = _components(v @ w / w.sum(), _fit(x, v, w, large), model.dim)
    return out


def observe_beam(result, groups) -> dict:
    """{group: {ux, uy, rz}} of a planar BeamResult, {group: {ux, uy, uz, rx, ry, rz}} of
    a spatial one (its group's node)."""
    out = {}
    for g in groups:
        mean = np.asarray(result.mean_displacement(g))
        out[g] = _components(mean, np.atleast_1d(result.rotation(g)), len(mean))
    return out


def observe(result, groups, large: bool = False) -> dict:
    """Observations of ``groups`` from a static result of either model (a continuum
    StaticResult, or the beam model's BeamResult)."""
    if hasattr(result, "state"):
        return observe_beam(result, groups)
    return observe_continuum(result.model, result.u, groups, large)


def observe_steps(path, groups) -> list:
    """Observations of ``groups`` at every step of a large-deflection solve (a continuum
    NonlinearResult or the beam model's BeamPath), step 0 (no load) included."""
    if hasattr(path, "step"):
        return [observe_beam(path.step(k), groups) for k in range(len(path.load_factors))]
    from ...fem.static_result import group_basis
    bases = {g: group_basis(path.model, g) for g in groups}
    return [observe_continuum(path.model, u, groups, True, bases) for u in path.u]


def lift(observations: dict) -> dict:
    """Planar observations as a solid's: uz, rx, ry = 0 (the planar model moves in its
    plane)."""
    return {g: {"ux": o["ux"], "uy": o["uy"], "uz": 0.0, "rx": 0.0, "ry": 0.0, "rz": o["rz"]}
            for g, o in observations.items()}


def centroid(result, group) -> np.ndarray:
    """Where a group's observation refers to (m): the continuum's weighted centroid of its
    points (their mean displacement is the displacement there for a rigid motion), the beam
    model's node (the mean of its nodes)."""
    if hasattr(result, "state"):
        model = result.model
        face = (beam3d_group if model.nodes.shape[1] == 3 else beam_group)(model, group)
        return np.asarray(model.nodes)[list(face.nodes)].mean(axis=0)
    x, _, w = _points(result.model, np.zeros(result.model.n_dofs), group)
    return x @ w / w.sum()


def carried(observation: dict, frm, to, large: bool = False) -> dict:
    """The observation of a rigid body at ``frm`` carried to the point ``to`` (m): the same
    rotation, the displacement plus the rotation's motion of the offset (linear, or with
    ``large`` the finite rotation's)."""
    r = np.asarray(to, float) - np.asarray(frm, float)
    u = np.array([observation[f"u{a}"] for a in _AXES[:len(r)]])
    if len(r) == 2:
        t = observation["rz"] or 0.0
        turn = (np.array([[np.cos(t) - 1, -np.sin(t)], [np.sin(t), np.cos(t) - 1]]) @ r
                if large else t * np.array([-r[1], r[0]]))
    else:
        w = np.array([observation[f"r{a}"] or 0.0 for a in _AXES])
        if large:
            from scipy.spatial.transform import Rotation

            turn = Rotation.from_rotvec(w).apply(r) - r
        else:
            turn = np.cross(w, r)
    return {**observation, **{f"u{a}": float(v) for a, v in zip(_AXES, u + turn)}}


def with_points(spec, result, observations: dict, large: bool = False) -> dict:
    """``observations`` and those of the file's [points], each carried from its body."""
    if not spec.points:
        return observations
    centres = {body: centroid(result, body) for body, _ in spec.points.values()}
    return {**observations, **{  # a planar result of a 3-D file: the points in its plane
        name: carried(observations[body], centres[body], at[:len(centres[body])], large)
        for name, (body, at) in spec.points.items()}}


def output_values(spec, observations: dict) -> tuple[dict, dict]:
    """({output: value}, {output: why not}) of the model file's [outputs] from
    ``observations``: an output that cannot be evaluated (a division by zero: no load on the
    group it divides by) is None with the reason."""
    values, missing = {}, {}
    for o in spec.outputs:
        try:
            values[o.name] = o.value(observations, spec.constants)
        except ValueError as error:
            values[o.name], missing[f"outputs.{o.name}"] = None, str(error)
    return values, missing


def watched_groups(spec, groups) -> list:
    """The groups a model file's analysis observes: its support and load ``groups``, every
    body (bodies and flexures) and every group its [outputs] name."""
    bodies = [b.name for b in spec.mechanism.bodies] if spec.mechanism is not None else []
    points = set(spec.points)
    named = [g for o in spec.outputs for g in o.groups if g not in points]
    return list(dict.fromkeys([*groups, *bodies, *named]))


def observed(spec, result, groups, lifted: bool = False) -> dict:
    """{"observations": {group: {component: value}}, "outputs": {name: value}} of a static
    ``result`` (``lifted``: a planar result standing for a 3-D file), and "not_available"
    {"outputs.NAME": why} for an output that cannot be evaluated."""
    obs = with_points(spec, result, observe(result, watched_groups(spec, groups)))
    if lifted and obs and "uz" not in next(iter(obs.values())):
        obs = lift(obs)
    values, missing = output_values(spec, obs)
    out = {"observations": obs}
    if spec.outputs:
        out["outputs"] = values
    if missing:
        out["not_available"] = missing
    return out


def observed_path(spec, path, groups, lifted: bool = False) -> dict:
    """The large-deflection solve's observations at its final step, its outputs there
    ("outputs") and at every loaded step ("outputs_path": {name: [value per step]}, with
    "load_factors" of those steps)."""
    watched = watched_groups(spec, groups)
    steps = observe_steps(path, watched) if spec.outputs else [observe(_last(path), watched,
                                                                       large=True)]
    last = _last(path)
    steps = [with_points(spec, last, o, large=True) for o in steps]
    if lifted:
        steps = [lift(o) for o in steps]
    out = {"observations": steps[-1]}
    if spec.outputs:
        out["outputs"] = output_values(spec, steps[-1])[0]
        rows = [output_values(spec, o)[0] for o in steps[1:]]
        out["outputs_path"] = {o.name: [r[o.name] for r in rows] for o in spec.outputs}
        out["load_factors"] = [float(f) for f in path.load_factors[1:]]
    return out


class _Last:
    def __init__(self, model, u):
        self.model, self.u = model, u


def _last(path):
    """The final step of a large-deflection solve as a static result of either model."""
    return path.step(-1) if hasattr(path, "step") else _Last(path.model, path.u[-1])


def observation_metrics(result: dict) -> dict:
    """The flat metrics of the observations and outputs of an analyze_model dict: each output
    by its name (``R``; ``R_nonlinear`` at a large-deflection solve's final step),
    ``observed_<group>_<component>`` (m, rad; the group's characters other than letters,
    digits and _ as _). An output or observation that is not a finite number is left out."""
    out = {}
    for group, values in result.get("observations", {}).items():
        for component, value in values.items():
            if value is not None:
                out[f"observed_{_WORD.sub('_', group)}_{component}"] = float(value)
    for name, value in result.get("outputs", {}).items():
        if value is not None:
            out[name] = float(value)
    for name, value in result.get("nonlinear", {}).get("outputs", {}).items():
        if value is not None:
            out[f"{name}_nonlinear"] = float(value)
    return out
