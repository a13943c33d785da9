"""Outputs shared by the continuum and the beam analyses of a model file."""
import numpy as np

_AXES = ("x", "y", "z")


def groups_of(spec) -> list[str]:
    """The support and load groups of the model file, in order, once each."""
    names = [s.group for s in spec.supports] + [load.group for load in spec.loads]
    return list(dict.fromkeys(names))


def single_force(spec):
    """The model's one load if it is a non-zero force and every support holds still, else
    None. Only then is a group's motion the force's alone: a prescribed support displacement
    moves the group too, so force over displacement would be no stiffness."""
    forces = [load for load in spec.loads if load.kind == "force"]
    if len(forces) != 1 or len(spec.loads) != 1 or not np.any(forces[0].vector):
        return None
    if any(s.components and any(v != 0 for v in s.components.values()) for s in spec.supports):
        return None
    return forces[0]


def stiffness(spec, mean_displacement: dict) -> dict:
    """{group: {axis: N/m}} for the :func:`single_force`: force / mean displacement of its
    group along the force (axis 'x'/'y'/'z' for an axis-aligned force, else 'along')."""
    load = single_force(spec)
    if load is None:
        return {}
    f = np.array(load.vector)
    nonzero = np.flatnonzero(f)
    u = np.asarray(mean_displacement[load.group])
    direction = f / np.linalg.norm(f)
    along = float(u @ direction)
    axis = _AXES[nonzero[0]] if len(nonzero) == 1 else "along"
    return {load.group: {axis: float(np.linalg.norm(f) / along) if along else float("inf")}}




def check_finite(result: dict, source: str) -> dict:
    """``result`` unchanged if every number in it is finite; else ValueError naming the first
    quantity that is not (an overflow of extreme inputs: a 1e300 N load, a 1e-300 m
    thickness), so that nothing non-finite is printed or stored as a result."""
    def walk(value, key):
        if isinstance(value, dict):
            for k, v in value.items():
                walk(v, f"{key}.{k}" if key else str(k))
        elif isinstance(value, (list, tuple)):
            for i, v in enumerate(value):
                walk(v, f"{key}[{i}]")
        elif isinstance(value, (float, np.floating)) and not np.isfinite(value):
            raise ValueError(f"{source}: {key} = {value}: the inputs are beyond what double "
                             "precision can solve (check the loads, sizes and material for "
                             "extreme values and units: lengths in m, forces in N, moduli in "
                             "Pa)")
    walk(result, "")
    return result
