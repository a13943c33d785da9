"""Outputs shared by the continuum and the beam analyses of a model file."""
import numpy as np

_AXES = ("x", "y", "z")


def groups_of(spec) -> list[str]:
    """The support and load groups of the model file, in order, once each."""
    names = [s.group for s in spec.supports] + [load.group for load in spec.loads]
    return list(dict.fromkeys(names))


def stiffness(spec, mean_displacement: dict) -> dict:
    """{group: {axis: N/m}} where exactly one force load is applied: force / mean displacement
    of its group along the force (axis 'x'/'y'/'z' for an axis-aligned force, else 'along')."""
    forces = [load for load in spec.loads if load.kind == "force"]
    if len(forces) != 1 or len(spec.loads) != 1:
        return {}
    load = forces[0]
    f = np.array(load.vector)
    nonzero = np.flatnonzero(f)
    if len(nonzero) == 0:
        return {}
    u = np.asarray(mean_displacement[load.group])
    direction = f / np.linalg.norm(f)
    along = float(u @ direction)
    axis = _AXES[nonzero[0]] if len(nonzero) == 1 else "along"
    return {load.group: {axis: float(np.linalg.norm(f) / along) if along else float("inf")}}


