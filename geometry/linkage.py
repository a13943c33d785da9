"""Planar rigid-body linkages: links with named points, revolute joints, a ground, driven inputs.

A linkage is drawn once, assembled, in its *reference pose*: every link lists its named points in
world coordinates (m) at that pose. The pose of moving link ``i`` is ``(x_i, y_i, theta_i)``, the
translation (m) and rotation (rad, counter-clockwise) of the link about its own centroid away from
the reference pose, so the reference pose is ``q = 0``. A revolute joint makes the same-named
point of two links coincide; the loop-closure equations (the joints, plus one equation per driven
input) are solved by Newton's method, and a range of inputs is traced by continuation from the
previous pose, halving the step where Newton fails, so the assembly branch is kept.
"""
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np


class AssemblyError(ValueError):
    """The linkage cannot be assembled (unreachable, or singular) at the given input value."""


@dataclass(frozen=True)
class Link:
    """A rigid body: named points (m, world coordinates at the reference pose) and the
    centre-line drawn through them (``outline``, see :attr:`polylines`)."""

    name: str
    points: Mapping[str, tuple]
    outline: tuple = ()

    def __post_init__(self):
        if not self.points:
            raise ValueError(f"link {self.name!r}: points is empty, needs at least 1 point")
        for key, xy in self.points.items():
            if len(xy) != 2 or not np.all(np.isfinite(xy)):
                raise ValueError(f"link {self.name!r}: point {key!r} = {xy} is not a finite (x, y)")
        for key in (k for line in self.polylines for k in line):
            if key not in self.points:
                raise ValueError(f"link {self.name!r}: outline point {key!r} is not among its points")

    @property
    def polylines(self) -> tuple:
        """Centre-line as polylines of point names: ``outline`` if given (one polyline, or a
        tuple of them for a branched link); else all points in order, closed if three or more."""
        if self.outline:
            return tuple(self.outline) if isinstance(self.outline[0], tuple) else (tuple(self.outline),)
        names = tuple(self.points)
        return (names + names[:1],) if len(names) > 2 else (names,)

    @property
    def segment_names(self) -> list:
        """Pairs of point names, one per centre-line segment."""
        return [pair for line in self.polylines for pair in zip(line[:-1], line[1:])]


@dataclass(frozen=True)
class Joint:
    """Revolute joint: point ``point`` of ``links[0]`` and the same-named point of ``links[1]``."""

    point: str
    links: tuple


@dataclass(frozen=True)
class CrankAngle:
    """Driven input: rotation (rad, counter-clockwise) of ``link`` away from its reference pose."""

    link: str


@dataclass(frozen=True)
class PointCoordinate:
    """Driven input: world coordinate (m) ``axis`` (0 = x, 1 = y) of point ``point`` of ``link``."""

    link: str
    point: str
    axis: int = 0


def gruebler_mobility(n_links: int, n_joints: int) -> int:
    """Gruebler-Kutzbach mobility of a planar linkage of revolute joints, 3(n - 1) - 2j.

    ``n_links`` counts the ground; a joint joining k links at one point counts k - 1 times.
    """
    return 3 * (n_links - 1) - 2 * n_joints


def _perp(v):
    """Rotate vectors (..., 2) by +90 degrees."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


@dataclass(frozen=True)
class Linkage:
    """Links (one named ``ground``), revolute joints and driven inputs; see the module docstring."""

    links: tuple
    joints: tuple
    inputs: tuple
    ground: str = "ground"
    _index: dict = field(init=False, repr=False, compare=False)
    _centroids: np.ndarray = field(init=False, repr=False, compare=False)
    _sides: list = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        names = [link.name for link in self.links]
        if len(set(names)) != len(names):
            raise ValueError(f"links: names {names} are not unique")
        if self.ground not in names:
            raise ValueError(f"links: no ground link named {self.ground!r} among {names}")
        moving = [n for n in names if n != self.ground]
        object.__setattr__(self, "_index", {n: i for i, n in enumerate(moving)})
        by_name = {link.name: link for link in self.links}
        for joint in self.joints:
            a, b = joint.links
            for n in (a, b):
                if n not in by_name or joint.point not in by_name[n].points:
                    raise ValueError(f"joint {joint.point!r}: link {n!r} has no point {joint.point!r}")
            gap = np.hypot(*np.subtract(by_name[a].points[joint.point], by_name[b].points[joint.point]))
            scale = max(1.0, max(abs(c) for xy in by_name[a].points.values() for c in xy))
            if gap > 1e-9 * scale:
                raise ValueError(f"joint {joint.point!r}: the points of {a!r} and {b!r} are {gap:.3g} m "
                                 "apart in the reference pose, must coincide")
        for driven in self.inputs:
            if driven.link not in self._index:
                raise ValueError(f"input {driven}: {driven.link!r} is not a moving link")
        centroids = np.array([np.mean(np.array(list(by_name[n].points.values()), float), axis=0)
                              for n in moving]).reshape(-1, 2)
        object.__setattr__(self, "_centroids", centroids)
        # every joint row: (link index, point relative to centroid) on both sides; -1 = ground
        sides = []
        for k in (0, 1):
            idx = np.array([self._index.get(j.links[k], -1) for j in self.joints], int)
            ref = np.array([by_name[j.links[k]].points[j.point] for j in self.joints], float).reshape(-1, 2)
            if len(moving):
                ref = ref - np.where(idx[:, None] >= 0, centroids[np.maximum(idx, 0)], 0.0)
            rel = ref
            sides.append((idx, rel))
        object.__setattr__(self, "_sides", sides)

    # -- geometry of a pose ------------------------------------------------------------------
    def link(self, name: str) -> Link:
        return next(link for link in self.links if link.name == name)

    @property
    def moving_links(self) -> tuple:
        return tuple(self._index)

    @property
    def mobility(self) -> int:
        """Gruebler's count for this linkage (see :func:`gruebler_mobility`)."""
        return gruebler_mobility(len(self.links), len(self.joints))

    @property
    def length_scale(self) -> float:
        """Largest distance (m) of a point from the origin, for tolerances."""
        return max(np.hypot(*xy) for link in self.links for xy in link.points.values()) or 1.0

    def _centroid(self, name):
        return self._centroids[self._index[name]]

    def point_position(self, q, link: str, point: str) -> np.ndarray:
        """World position (m) of ``point`` of ``link`` in pose ``q`` (shape (3m,) or (n, 3m))."""
        q = np.asarray(q, float)
        ref = np.asarray(self.link(link).points[point], float)
        if link == self.ground:
            return np.broadcast_to(ref, q.shape[:-1] + (2,)).copy()
        i = 3 * self._index[link]
        x, y, t = q[..., i], q[..., i + 1], q[..., i + 2]
        c = self._centroid(link)
        r = ref - c
        cos, sin = np.cos(t), np.sin(t)
        return np.stack([c[0] + x + cos * r[0] - sin * r[1], c[1] + y + sin * r[0] + cos * r[1]], axis=-1)

    def link_transform(self, q, link: str) -> np.ndarray:
        """Homogeneous transform (3x3, m) taking the link's reference-pose points to pose q."""
        if link == self.ground:
            return np.eye(3)
        x, y, t = np.asarray(q, float)[3 * self._index[link]:3 * self._index[link] + 3]
        c = self._centroid(link)
        rot = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
        return np.block([[rot, (c + (x, y) - rot @ c)[:, None]], [np.zeros((1, 2)), np.ones((1, 1))]])

    def _point_jacobian(self, q, link, point):
        """d(world position)/dq of one point: a (2, 3m) array."""
        jac = np.zeros((2, q.size))
        if link == self.ground:
            return jac
        i = 3 * self._index[link]
        rotated = self.point_position(q, link, point) - self._centroid(link) - q[i:i + 2]
        jac[:, i:i + 2] = np.eye(2)
        jac[:, i + 2] = _perp(rotated)
        return jac

    # -- loop closure --------------------------------------------------------------------------
    def _joint_world(self, q, side):
        """World positions (nj, 2) of the joints' points on links[side], and their rotated
        offsets from the link centroids (zero rows for the ground)."""
        idx, rel = self._sides[side]
        moving = idx >= 0
        pose = q.reshape(-1, 3)[np.maximum(idx, 0)] if q.size else np.zeros((len(idx), 3))
        cos, sin = np.cos(pose[:, 2]), np.sin(pose[:, 2])
        rotated = np.stack([cos * rel[:, 0] - sin * rel[:, 1], sin * rel[:, 0] + cos * rel[:, 1]], axis=1)
        base = self._centroids[np.maximum(idx, 0)] + pose[:, :2] if q.size else 0.0
        world = np.where(moving[:, None], base + rotated, rel)
        return world, np.where(moving[:, None], rotated, 0.0)

    def residual(self, q, values) -> np.ndarray:
        """Loop-closure residual: joint gaps (m), then input errors (rad or m)."""
        q = np.asarray(q, float)
        gaps = self._joint_world(q, 0)[0] - self._joint_world(q, 1)[0]
        return np.concatenate([gaps.ravel(), self.input_values(q) - np.atleast_1d(values)])

    def jacobian(self, q) -> np.ndarray:
        """d(residual)/dq, analytic."""
        q = np.asarray(q, float)
        nj = len(self.joints)
        jac = np.zeros((2 * nj + len(self.inputs), q.size))
        rows = np.arange(nj)
        for side, sign in ((0, 1.0), (1, -1.0)):
            idx = self._sides[side][0]
            rotated = self._joint_world(q, side)[1]
            m, r = idx >= 0, rows[idx >= 0]
            col = 3 * idx[m]
            jac[2 * r, col] += sign
            jac[2 * r + 1, col + 1] += sign
            jac[2 * r, col + 2] += -sign * rotated[m, 1]
            jac[2 * r + 1, col + 2] += sign * rotated[m, 0]
        for k, driven in enumerate(self.inputs):
            if isinstance(driven, CrankAngle):
                jac[2 * nj + k, 3 * self._index[driven.link] + 2] = 1.0
            else:
                jac[2 * nj + k] = self._point_jacobian(q, driven.link, driven.point)[driven.axis]
        return jac

    def input_values(self, q) -> np.ndarray:
        """The driven inputs' values (rad or m) in pose ``q``."""
        q = np.asarray(q, float)
        return np.array([q[3 * self._index[d.link] + 2] if isinstance(d, CrankAngle)
                         else self.point_position(q, d.link, d.point)[d.axis] for d in self.inputs])


def _newton(linkage, q0, values, tol, max_iter, max_correction):
    """Newton (least-squares steps) from q0; returns the pose or None when it fails or would
    move farther than ``max_correction`` (scaled) from the start, which means a branch jump."""
    scale = linkage.length_scale
    weights = np.tile([1.0 / scale, 1.0 / scale, 1.0], q0.size // 3)
    q = q0.copy()
    for _ in range(max_iter):
        r = linkage.residual(q, values)
        if np.max(np.abs(r[:2 * len(linkage.joints)])) < tol * scale and np.max(
                np.abs(r[2 * len(linkage.joints):]), initial=0.0) < tol * max(1.0, np.max(np.abs(values))):
            return q
        step = np.linalg.lstsq(linkage.jacobian(q), -r, rcond=None)[0]
        q = q + step
        if not np.all(np.isfinite(q)) or np.max(np.abs((q - q0) * weights)) > max_correction:
            return None
    return None


def assemble(linkage: Linkage, values, guess=None, *, tol=1e-12, max_iter=30) -> np.ndarray:
    """Pose q solving the loop closure at input ``values`` (rad or m), by Newton from ``guess``
    (the reference pose by default). Raises :class:`AssemblyError` naming the input value."""
    q0 = np.zeros(3 * len(linkage.moving_links)) if guess is None else np.asarray(guess, float)
    q = _newton(linkage, q0, np.atleast_1d(values).astype(float), tol, max_iter, np.inf)
    if q is None:
        raise AssemblyError(f"cannot assemble the linkage at input {np.atleast_1d(values).tolist()}: "
                            "Newton did not converge (unreachable input?)")
    _check_regular(linkage, q, values)
    return q


def _check_regular(linkage, q, values, rcond=1e-9):
    s = np.linalg.svd(linkage.jacobian(q), compute_uv=False)
    n = q.size
    if s.size < n or s[n - 1] < rcond * s[0]:
        raise AssemblyError(f"singular configuration at input {np.atleast_1d(values).tolist()}: "
                            f"loop-closure Jacobian rank-deficient (sigma_min/sigma_max = "
                            f"{(s[n - 1] if s.size >= n else 0.0) / s[0]:.2e})")


@dataclass(frozen=True)
class Trace:
    """Poses along a traced input range: ``inputs`` (n, k) in rad or m, ``poses`` (n, 3m)."""

    linkage: Linkage
    inputs: np.ndarray
    poses: np.ndarray

    def path(self, link: str, point: str) -> np.ndarray:
        """World positions (n, 2), in m, of a point along the trace."""
        return self.linkage.point_position(self.poses, link, point)


def trace(linkage: Linkage, values, q0=None, *, max_halvings=14, max_correction=0.05,
          tol=1e-12) -> Trace:
    """Trace the linkage over the input sequence ``values`` ((n,) or (n, k), rad or m).

    The first pose is assembled from ``q0`` (default: the reference pose); each next pose by
    Newton from a linear predictor of the previous two. Where Newton fails or would jump more
    than ``max_correction`` (length-scaled, rad) the step is halved (and doubled again after a
    success); below 2**-max_halvings of the step, :class:`AssemblyError` names the input value
    (unreachable or singular).
    """
    values = np.asarray(values, float)
    values = values[:, None] if values.ndim == 1 else values
    poses = [assemble(linkage, values[0], q0, tol=tol)]
    for k in range(1, len(values)):
        start, stop = values[k - 1], values[k]
        q_prev = poses[-1]
        q_prevprev, v_prev = (poses[-2], values[k - 2]) if k > 1 else (None, None)
        done, fraction = 0.0, 1.0
        q_here = q_prev
        while done < 1.0:
            frac = min(fraction, 1.0 - done)
            target = start + (done + frac) * (stop - start)
            guess = q_here
            span = start - v_prev if q_prevprev is not None else 0.0
            if np.any(span != 0):  # linear predictor along the last step, signed
                ratio = np.dot(target - (start + done * (stop - start)), span) / np.dot(span, span)
                guess = q_here + (q_prev - q_prevprev) * ratio
            q_new = _newton(linkage, guess, target, tol, 30, max_correction)
            if q_new is None:
                fraction = frac / 2
                if fraction < 0.5**max_halvings:
                    raise AssemblyError(f"cannot assemble the linkage at input {target.tolist()} "
                                        f"(tracing from {start.tolist()} to {stop.tolist()}): "
                                        "unreachable or singular configuration")
                continue
            _check_regular(linkage, q_new, target)
            q_here, done = q_new, done + frac
            fraction = min(1.0, 2 * frac)   # grow the step again after a success
        poses.append(q_here)
    return Trace(linkage, values, np.array(poses))


def trace_from_reference(linkage: Linkage, start: float, stop: float, n: int) -> Trace:
    """Trace a one-input linkage at n inputs from ``start`` to ``stop`` (rad or m), stepping
    outward from the reference input value (between them) so the drawn branch is kept."""
    if n < 3:
        raise ValueError(f"n = {n}, must be >= 3")
    reference = float(linkage.input_values(np.zeros(3 * len(linkage.moving_links)))[0])
    values = np.linspace(start, stop, n)
    if not min(start, stop) <= reference <= max(start, stop):
        return _drop_first(trace(linkage, np.r_[reference, values]))
    k = int(np.argmin(np.abs(values - reference)))
    up = trace(linkage, np.r_[reference, values[k:]])
    down = trace(linkage, np.r_[reference, values[:k][::-1]])
    poses = np.concatenate([down.poses[1:][::-1], up.poses[1:]])
    return Trace(linkage, values[:, None], poses)


def _drop_first(t: Trace) -> Trace:
    return Trace(t.linkage, t.inputs[1:], t.poses[1:])
