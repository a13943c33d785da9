"""Exact-constraint analysis of a spatial mechanism: its degrees of freedom (twists) and its
over-constraints (redundant constraints), by a singular-value decomposition of the
constraint wrenches.

Each flexure is idealised by its stiff directions (Blanding, "Exact Constraint: Machine
Design Using Kinematic Principles", ASME Press 1999, ch. 3-4; Hopkins and Culpepper,
"Synthesis of multi-degree of freedom, parallel flexure system concepts via Freedom and
Constraint Topology (FACT)", Precision Engineering 34 (2010) 259-270):

- a wire: one constraint, a force along its axis (the line through its free span);
- a leaf: three constraints in its plane, a force along its length and a force along its
  width (both through the middle of its free span) and a moment about its normal.

The constraint wrenches act between the two bodies a flexure joins; the held bodies are
one ground. Rows of the constraint matrix C (one per wrench, (force, moment / L) with L
the mechanism's size) against the bodies' twists (velocity at the origin, L * angular
velocity): C t = 0 for every motion the idealised flexures allow, so the null space of C
gives the DOFs, and the left null space (C^T w = 0: wrenches in self-equilibrium) the
over-constraints, naming the flexures whose constraints take part. A singular value below
``RANK_TOLERANCE`` times the largest counts as zero.
"""
from dataclasses import dataclass

import numpy as np

from ...geometry.spatial.description import Plate, SpatialMechanism, flexure_label

#: A singular value below this fraction of the largest is zero (the mechanism's constraints
#: are exact numbers of its geometry: round-off is ~1e-15, a real constraint ~1e-3 and up).
RANK_TOLERANCE = 1e-8


@dataclass(frozen=True)
class ConstraintReport:
    """``singular_values`` of the constraint matrix (descending, dimensionless);
    ``dofs``: [(body, twist (6,): (v_x, v_y, v_z) at the origin (m/s per unit), (w_x, w_y,
    w_z) (rad/s per unit))] per free motion; ``over_constraints``: [[(flexure label, its
    constraint, weight)]] per redundant combination; ``constraints``: the labels of C's
    rows; ``threshold``: the singular value below which a direction counts as zero."""

    singular_values: np.ndarray
    dofs: list
    over_constraints: list
    constraints: list
    bodies: list
    threshold: float

    def summary(self) -> str:
        """The analysis as text: the singular values, the DOFs, the over-constraints."""
        lines = [f"constraints: {len(self.constraints)} on {len(self.bodies)} moving bodies "
                 f"({6 * len(self.bodies)} freedoms)",
                 "singular values: " + ", ".join(f"{s:.3g}" for s in self.singular_values)
                 + f" (zero below {self.threshold:.3g})",
                 f"degrees of freedom: {len(self.dofs)}"]
        for k, twist in enumerate(self.dofs, 1):
            lines.append(f"  DOF {k}: " + "; ".join(f"{body}: {describe_twist(t)}"
                                                     for body, t in twist))
        lines.append(f"over-constraints: {len(self.over_constraints)}"
                     + (" (over-constrained by "
                        f"{len(self.over_constraints)})" if self.over_constraints else
                        " (exactly constrained)"))
        for k, combo in enumerate(self.over_constraints, 1):
            lines.append(f"  redundant {k}: " + " with ".join(
                f"{label} ({what}, {w:+.2f})" for label, what, w in combo))
        return "\n".join(lines)


def describe_twist(twist) -> str:
    """A twist (v at the origin, w) in words: a translation along a direction, or a
    rotation about an axis through a point (m) with its pitch (m/rad)."""
    v, w = np.asarray(twist[:3], float), np.asarray(twist[3:], float)
    if np.linalg.norm(w) * 1e6 < np.linalg.norm(v) / (1 + np.linalg.norm(v)) * 1e-3 or \
            not np.linalg.norm(w) > 0:
        return f"translation along {_fmt(v / np.linalg.norm(v))}"
    axis, n2 = w / np.linalg.norm(w), float(w @ w)
    point, pitch = np.cross(w, v) / n2, float(w @ v) / n2
    return (f"rotation about {_fmt(axis)} through {_fmt(point)} m"
            + (f", pitch {pitch:.3g} m/rad" if abs(pitch) > 1e-9 else ""))


def _fmt(v) -> str:
    return "[" + ", ".join(f"{x:+.3f}" for x in v) + "]"


def flexure_wrenches(mechanism: SpatialMechanism, index: int) -> list:
    """[(what, force (3,), moment about the origin (3,))] of flexure ``index``: its ideal
    constraints (a unit force, or a moment of the mechanism's size in N m: as stiff as a
    unit force at that lever)."""
    f, span = mechanism.flexures[index], mechanism.span(index)
    centre, d = span.centre, span.d
    out = [("force along its axis", d, np.cross(centre, d))]
    if isinstance(f, Plate):
        w = np.asarray(f.width_along, float)
        w = w - (w @ d) * d
        w /= np.linalg.norm(w)
        out.append(("force along its width", w, np.cross(centre, w)))
        out.append(("moment about its normal", np.zeros(3), f.normal * mechanism.size))
    return out


def exact_constraint(mechanism: SpatialMechanism, held) -> ConstraintReport:
    """The DOFs and over-constraints of ``mechanism`` with the bodies named in ``held``
    as ground (see the module)."""
    ground = set(held)
    moving = [b.name for b in mechanism.bodies if b.name not in ground]
    if not moving:
        raise ValueError(f"{mechanism.source}: every body is held: nothing can move")
    column = {name: 6 * k for k, name in enumerate(moving)}
    scale = mechanism.size
    rows, labels = [], []
    for i, f in enumerate(mechanism.flexures):
        for what, force, moment in flexure_wrenches(mechanism, i):
            row = np.zeros(6 * len(moving))
            wrench = np.concatenate([force, moment / scale])
            for body, sign in ((f.between[1], 1.0), (f.between[0], -1.0)):
                if body in column:
                    row[column[body]:column[body] + 6] += sign * wrench
            rows.append(row)
            labels.append((flexure_label(f, i), what))
    C = np.array(rows)
    u, s, vt = np.linalg.svd(C)
    threshold = RANK_TOLERANCE * (s[0] if s.size else 1.0)
    rank = int(np.sum(s > threshold))
    dofs = []
    for t in vt[rank:]:
        twist = []
        for name in moving:
            part = t[column[name]:column[name] + 6]
            if np.linalg.norm(part) > 1e-9:
                twist.append((name, np.concatenate([part[:3], part[3:] / scale])))
        dofs.append(twist)
    over = []
    for w in u[:, rank:].T:
        w = w / np.max(np.abs(w))
        over.append([(labels[k][0], labels[k][1], float(w[k]))
                     for k in np.flatnonzero(np.abs(w) > 1e-6)])
    return ConstraintReport(s, dofs, over, labels, moving, float(threshold))
