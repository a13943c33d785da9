"""The driving linkage's large-deflection path by either model: the shuttle driven along y
over +-``input_travel`` / 4 through the drawn pose (the continuum study's stroke,
:func:`flexfem.studies.eightbar.driving._nonlinear_study`), its x and rotation free; the
right end-effector's path, its straight-line deviation and the input force.

    out = driving_path(model="beam")       # ~1 s; model="continuum": minutes
    out["deviation_m"], out["end_force_n"]
"""
from dataclasses import replace

import numpy as np

from ...fem.beam import solve_beam_nonlinear
from ...fem.beam.supports import NodeFixed, NodePrescribed
from ...reduced.layout import ROOT_EXTENSION
from ...geometry.eightbar.driving import DrivingParams, trace_driving
from ...reduced.driving import driving_beam_model
from ...geometry.straight_line import straight_line_deviation
from .driving import NEWTON_TOL, build_model, nonlinear_drive
from .driving_models import MODELS, default_flexure


def beam_drive(model, info, end: float, steps: int = 4) -> list:
    """The beam model's rows of :func:`~flexfem.studies.eightbar.driving.nonlinear_drive`:
    per step the end-effectors' motion (m, rad) and the input force (N), input y from 0 to
    ``end`` (m), its x and rotation free."""
    inp = info["input"]
    res = solve_beam_nonlinear(model, [NodeFixed(tuple(info["ground"])),
                                       NodePrescribed(inp, "y", end)], steps=steps, tol=NEWTON_TOL)
    rows = []
    for state in res.states:
        ql, qr = state.q[info["ee_L"]], state.q[info["ee_R"]]
        rows.append({"input_m": float(state.q[inp, 1]),
                     "x_left_m": float(ql[0]), "y_left_m": float(ql[1]),
                     "rot_left_rad": float(ql[2]),
                     "x_right_m": float(qr[0]), "y_right_m": float(qr[1]),
                     "rot_right_rad": float(qr[2]),
                     "input_force_n": float(state.reactions[inp][1])})
    return rows


def driving_path(params: DrivingParams | None = None, flexure=None, model: str = "beam",
                 steps: int = 4, size_factor: float = 1.5,
                 root_extension: float = ROOT_EXTENSION) -> dict:
    """Path over +-input_travel / 4 (m) of input, ``steps`` each way: {"rows", "stroke_m"
    (right end-effector's x range), "deviation_m", "deviation_pct" (its straight-line
    deviation), "end_force_n" (input force at +input_travel / 4), "rigid_deviation_m" (the
    rigid linkage over the same input stroke), "model"}."""
    if model not in MODELS:
        raise ValueError(f"model = {model!r} must be one of {MODELS}")
    params, flexure = params or DrivingParams(), flexure or default_flexure()
    half = params.input_travel / 4
    if model == "beam":
        built = driving_beam_model(params, flexure, root_extension=root_extension)
        drive = lambda end: beam_drive(*built, end, steps)  # noqa: E731
    else:
        continuum = build_model(params, flexure, size_factor=size_factor)[0]
        drive = lambda end: nonlinear_drive(continuum, end, steps)  # noqa: E731
    rows = drive(-half)[::-1] + drive(half)[1:]
    right = np.array([[r["x_right_m"], r["y_right_m"]] for r in rows])
    dev = straight_line_deviation(right)
    rigid = trace_driving(replace(params, input_travel=2 * half), n=2 * steps + 1)
    return {"rows": rows, "stroke_m": float(np.ptp(right[:, 0])),
            "deviation_m": dev.max_deviation_m, "deviation_pct": dev.deviation_pct,
            "end_force_n": rows[-1]["input_force_n"],
            "rigid_deviation_m": rigid.deviation_right.max_deviation_m, "model": model}
