"""A spatial stage's support stiffness along its stroke: the body driven by a prescribed
displacement (large deflection, flexfem.fem.solve_nonlinear) with and without a small probe
force along each support axis; the stiffness at each step is the probe force over the
difference of the two paths' displacements there. The same for a continuum Model and a
spatial beam model (the analysis face's groups). SI units (m, N)."""
import numpy as np

from ...fem import Force, Prescribed, solve_nonlinear

AXES = ("x", "y", "z")


def _path(model, supports, body, drive, stroke, force, steps):
    loads = [] if force is None else [Force(body, tuple(force))]
    held = list(supports) + [Prescribed(body, **{drive: stroke})]
    return solve_nonlinear(model, held, loads, steps=steps)


def support_along_stroke(model, supports, body: str, drive: str, stroke: float,
                         probes: dict, steps: int = 5) -> dict:
    """{"stroke_m": the drive's value at each step (m), "stiffness": {axis: [N/m per step]}}
    of ``body`` driven along ``drive`` ('x', 'y' or 'z') to ``stroke`` (m) in ``steps``
    under ``supports`` (Fixed of the held bodies), probed by ``probes`` {axis: force (N)}
    (small: its displacement well under the stroke). The steps after rest (the probe
    scales with the load factor, as the stroke does)."""
    if drive not in AXES or any(a not in AXES or a == drive for a in probes):
        raise ValueError(f"drive {drive!r} and probes {sorted(probes)} must be distinct axes "
                         "of x, y, z")
    base = _path(model, supports, body, drive, stroke, None, steps)
    lam = np.asarray(base.load_factors, float)
    out = {"stroke_m": (lam[1:] * stroke).tolist(), "stiffness": {}}
    for axis, force in probes.items():
        k = AXES.index(axis)
        vector = np.zeros(3)
        vector[k] = force
        probed = _path(model, supports, body, drive, stroke, vector, steps)
        if not np.allclose(probed.load_factors, lam):
            raise ValueError(f"support_along_stroke: the probe along {axis} took other steps "
                             f"({list(probed.load_factors)} against {lam.tolist()}); give "
                             "more steps")
        du = np.array([probed.mean_displacement(body, s)[k] - base.mean_displacement(body, s)[k]
                       for s in range(1, len(lam))])
        out["stiffness"][axis] = (lam[1:] * force / du).tolist()
    return out
