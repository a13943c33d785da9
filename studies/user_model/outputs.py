"""Outputs shared by the continuum and the beam analyses of a model file."""
import math

import numpy as np

_AXES = ("x", "y", "z")


def groups_of(spec) -> list[str]:
    """The support and load groups of the model file, in order, once each."""
    names = [s.group for s in spec.supports] + [load.group for load in spec.loads]
    return list(dict.fromkeys(names))


def check_loaded_supports(spec) -> None:
    """ValueError naming the group that is both supported and loaded along a held axis (a
    fully held group along any): its support takes the load at once, nothing else carries it,
    and its "stiffness" would be a force over no motion."""
    held = {}
    for s in spec.supports:
        held.setdefault(s.group, set()).update(range(3) if s.components is None else
                                                s.components)
    for load in spec.loads:
        axes = [_AXES[k] for k in sorted(held.get(load.group, ()))
                if k < len(load.vector) and load.vector[k] != 0]
        if axes:
            raise ValueError(f"{load.source or spec.source}: group {load.group!r} is both "
                             f"supported and loaded (along {', '.join(axes)}): its support "
                             "takes the load and nothing moves; load another group, or leave "
                             "that axis of its [[supports]] free")


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
    path = _non_finite(result)
    if path is not None:
        key = "".join(f"[{k}]" if index else f".{k}" if i else str(k)
                      for i, (k, index) in enumerate(path))
        raise ValueError(f"{source}: {key} = {_at(result, path)}: the inputs are beyond what "
                         "double precision can solve (check the loads, sizes and material for "
                         "extreme values and units: lengths in m, forces in N, moduli in Pa)")
    return result


def _non_finite(value):
    """The keys [(key, whether a list index)] down to the first non-finite float in
    ``value`` ([] for ``value`` itself), None where there is none."""
    if isinstance(value, (float, np.floating)):
        return None if np.isfinite(value) else []
    if isinstance(value, dict):
        items, index = value.items(), False
    elif isinstance(value, (list, tuple)):
        try:  # a list of numbers at once (most of a result); else item by item
            if all(map(math.isfinite, value)):
                return None
        except (TypeError, OverflowError):  # not all numbers, or an int beyond a float
            pass
        items, index = enumerate(value), True
    else:
        return None
    for k, v in items:
        path = _non_finite(v)
        if path is not None:
            return [(k, index)] + path
    return None


def _at(result, path):
    for k, _ in path:
        result = result[k]
    return result
