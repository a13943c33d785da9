"""The suspensions' coupler length that cancels the flexures' elastic bow in the driving
linkage (Chapter 6): the flexure suspension's large-deflection path bows, y ~ c2 x^2, where its
rigid-body linkage runs straight; lengthening the coupler pre-bows the rigid path the other
way. Two FEM evaluations of the driven path and the secant through them give c2 = 0."""
import numpy as np

from ...geometry.eightbar.driving import DrivingParams
from ...geometry.eightbar.flexure import EightBarFlexureParams
from ...geometry.eightbar.rigid import EightBarParams
from .driving import build_model, nonlinear_drive, path_shape

STROKE = 3e-3       # m, input stroke either side of the drawn pose
ROUNDING = 1e-4     # m: the coupler length is a design dimension, kept to 0.1 mm


def driven_bow(coupler_length: float, size_factor: float = 3.0, steps: int = 4) -> float:
    """c2 (1/m) of the right end effector's large-deflection path when the driving linkage
    drives suspensions of coupler length ``coupler_length`` (m) over +-STROKE."""
    params = DrivingParams(suspension=EightBarParams(coupler_length=coupler_length))
    model, _ = build_model(params, EightBarFlexureParams(), size_factor=size_factor)
    rows = nonlinear_drive(model, -STROKE, steps)[::-1] + nonlinear_drive(model, STROKE, steps)[1:]
    path = np.array([[r["x_right_m"], r["y_right_m"]] for r in rows])
    return path_shape(path[np.argsort(path[:, 0])])["c2_per_m"]


def compensated_coupler_length(lengths=(50e-3, 54.9e-3), size_factor: float = 3.0,
                               steps: int = 4) -> float:
    """Coupler length (m, rounded to 0.1 mm) at which the driven path's bow c2 vanishes:
    the secant through c2 at the two ``lengths`` (m; the Chapter 5 design's 50 mm and a
    longer one), each by nonlinear FEM on a coarse mesh (``size_factor``)."""
    (h0, h1) = lengths
    c0, c1 = (driven_bow(h, size_factor, steps) for h in (h0, h1))
    if c0 == c1:
        raise ValueError(f"the bow does not change between coupler lengths {h0} and {h1} m")
    root = h1 - c1 * (h1 - h0) / (c1 - c0)
    return round(root / ROUNDING) * ROUNDING
