"""The Chapter 6 driving linkage (eight-bar thesis): rigid-body trace and a flexure FEM showing
the two eight-bar suspensions' end-effectors moving in opposite straight lines.

    out = driving_study("out/driving", quick=True)

FEM: plane stress, P2 triangles, base anchors "fixed", the shuttle's top face "input" driven
along y (x free). Linear: the end-effector faces' mean displacements per unit input. Nonlinear
(default, not quick): the input face as a RigidFace (y prescribed, x and rotation free) and the
end-effector faces as free RigidFaces whose motion is read at each step, over +-half the
rigid trace's stroke.

Where the nonlinear path deviation comes from (docs/eightbar_driving.md, tests/geometry/
test_driving_linkage.py): it is the suspension's own elastic bow, y ~ c2 x^2 (deviation ~
stroke^2), which the suspension alone, x prescribed with no y force and no moment, shows over the
same stroke (:func:`suspension_alone_path`); the bar adds about 8 % (its end flexures
resist Q's rise x^2 / 2r and push the end-effector across its motion) and tilts the path by
the lever flexure's shear (:func:`flexfem.geometry.eightbar.driving.lever_shear_rate`, odd: a
tilt, not a deviation); the lambdas' misfit takes no share (the part without its shuttle,
each half driven by its own coupler point, traces the same path). The default suspensions
therefore have their coupler lengthened (geometry/driving_linkage.py,
FLEXURE_COMPENSATED_COUPLER_LENGTH) so that the flexure path, not the rigid one, runs straight;
``DrivingParams(suspension=EightBarParams())`` gives the Chapter 5 design.
"""
from dataclasses import replace
from pathlib import Path

from matplotlib.tri import Triangulation
import numpy as np

from ...fem import (
    Fixed,
    Model,
    PlaneStress,
    Prescribed,
    RigidFace,
    material,
    solve_nonlinear,
    solve_static,
)
from ...geometry.eightbar.driving import (
    FLEXURE_COMPENSATED_COUPLER_LENGTH,
    DrivingParams,
    build_driving_linkage,
    half_mobility,
    lever_shear_rate,
    mesh_driving_flexure,
    trace_driving,
    transmission_ratio,
)
from ...geometry.eightbar.flexure import EightBarFlexureParams
from ...geometry.straight_line import straight_line_deviation
from ..engine.tables import write_rows
from ..report.comparison import Comparison, rows as comparison_rows
from ..report.figures import axis_label, plan_view, pyplot, save
from .analysis import NEWTON_TOL as TOL
from .analysis import build_model as build_suspension

NEWTON_TOL = 1e-5   # as studies/eightbar_fem.py: the stiff links' round-off floor


def build_model(params: DrivingParams, flexure: EightBarFlexureParams, size_factor: float = 2.0,
                shuttle: bool = True):
    """(Model (plane stress, P2), mesh sizes) of the driving linkage's flexure part; without
    ``shuttle``, the two halves apart, with input faces "input_L", "input_R" at the coupler
    points (see :func:`flexfem.geometry.eightbar.driving.driving_layout`)."""
    mesh, sizes = mesh_driving_flexure(params, flexure, size_factor=size_factor, shuttle=shuttle)
    return Model(mesh, material(flexure.material), PlaneStress(flexure.thickness), order=2), sizes


def linear_drive(model, displacement: float) -> dict:
    """Input face moved ``displacement`` (m) along y, x free, on the continuum or the beam
    model: the end-effector faces' mean displacements (m: the continuum's area average, the
    motion of a rigid face's centroid), their x ratio (left / right), their cross-motion
    (|uy| / |ux|) and the input force (N)."""
    res = solve_static(model, [Fixed("fixed"), Prescribed("input", y=displacement)], [])
    u_l, u_r = res.mean_displacement("ee_L"), res.mean_displacement("ee_R")
    return {"input_m": displacement, "ux_left_m": float(u_l[0]), "uy_left_m": float(u_l[1]),
            "ux_right_m": float(u_r[0]), "uy_right_m": float(u_r[1]),
            "ratio_left_right": float(u_l[0] / u_r[0]),
            "transmission": float(u_r[0] / displacement),
            "cross_motion_right": float(abs(u_r[1] / u_r[0])),
            "input_force_n": float(res.reactions["input"][1]),
            "stiffness_n_per_m": float(res.reactions["input"][1] / displacement),
            "max_von_mises_pa": float(res.max_von_mises), "result": res}


def nonlinear_drive(model: Model, end: float, steps: int = 6) -> list:
    """Input face driven from 0 to ``end`` (m) along y with large deflection (x and rotation
    free): rows per step of the end-effector faces' centroid motion (m, rad) and the input
    force (N). A model without the shuttle has its two input faces driven alike (input force:
    their sum)."""
    inputs = ["input"] if "input" in model.mesh.boundaries else ["input_L", "input_R"]
    faces = [RigidFace(name, y=end) for name in inputs] + [RigidFace("ee_L"), RigidFace("ee_R")]
    res = solve_nonlinear(model, [Fixed("fixed")], [], steps=steps, tol=NEWTON_TOL, rigid_faces=faces)
    rows = []
    for motion, force in zip(res.face_motion, res.face_reactions):
        rows.append({"input_m": float(motion[inputs[0]][1]),
                     "x_left_m": float(motion["ee_L"][0]), "y_left_m": float(motion["ee_L"][1]),
                     "rot_left_rad": float(motion["ee_L"][2]),
                     "x_right_m": float(motion["ee_R"][0]), "y_right_m": float(motion["ee_R"][1]),
                     "rot_right_rad": float(motion["ee_R"][2]),
                     "input_force_n": float(sum(force[name][1] for name in inputs))})
    return rows


def path_shape(points) -> dict:
    """Fit y = y0 + a x + c2 x^2 (+ c3 x^3 + c4 x^4 with 7 points or more) to a path (n, 2), m,
    x measured from the middle point: {"tilt_rad": atan(a), "c2_per_m": c2, "c4_per_m3": c4
    (nan if not fitted)}. An even path's deviation from its best line is the c2 x^2 bow."""
    pts = np.asarray(points, float)
    x = pts[:, 0] - pts[len(pts) // 2, 0]
    coef = np.polynomial.polynomial.polyfit(x, pts[:, 1], 4 if len(pts) >= 7 else 2)
    return {"tilt_rad": float(np.arctan(coef[1])), "c2_per_m": float(coef[2]),
            "c4_per_m3": float(coef[4]) if len(coef) > 4 else float("nan")}


def suspension_model(flexure: EightBarFlexureParams, size_factor: float = 2.0) -> Model:
    """The eight-bar suspension alone, same flexures and mesh rules as the driving linkage's
    (:func:`flexfem.studies.eightbar.analysis.build_model`; its face "end_effector")."""

    return build_suspension(flexure, size_factor=size_factor)[0]


def suspension_alone_path(model: Model, x_end: float, steps: int = 4,
                          both_halves: bool = True) -> np.ndarray:
    """The suspension alone (:func:`suspension_model`), its end-effector face's x prescribed
    from -``x_end`` to ``x_end`` (m) through the middle, y and rotation free (no y force, no
    moment): (2 steps + 1, 3) centroid motion (m, m, rad), sorted by x. With ``both_halves``
    False the -x half is the +x half's mirror image (the part is mirror-symmetric: y even,
    x and rotation odd)."""

    halves = []
    for end in ((-x_end, x_end) if both_halves else (x_end,)):
        res = solve_nonlinear(model, [Fixed("fixed")], [], steps=steps, tol=TOL,
                              rigid_faces=[RigidFace("end_effector", x=end)])
        halves.append(np.array([m["end_effector"] for m in res.face_motion]))
    if not both_halves:
        halves.insert(0, halves[0] * np.array([-1.0, 1.0, -1.0]))
    return np.concatenate([halves[0][::-1], halves[1][1:]])


def k_y_alone(model: Model) -> float:
    """Linear stiffness (N/m) of the suspension alone (:func:`suspension_model`) across its
    motion (y, x held)."""
    probe = 1e-6
    res = solve_static(model, [Fixed("fixed"), Prescribed("end_effector", x=0.0, y=probe)], [])
    return float(res.reactions["end_effector"][1] / probe)


def _draw_rigid(path: Path, tr, params: DrivingParams) -> dict:
    plt = pyplot()
    linkage = tr.linkage
    fig, ax = plt.subplots(figsize=(11, 4))
    for k, colour in zip((0, len(tr.s) // 2, len(tr.s) - 1), ("tab:blue", "k", "tab:red")):
        for link in linkage.links:
            if link.name == "ground":
                continue
            for a, b in link.segment_names:
                p = linkage.point_position(tr.poses[k], link.name, a)
                q = linkage.point_position(tr.poses[k], link.name, b)
                ax.plot([p[0] * 1e3, q[0] * 1e3], [p[1] * 1e3, q[1] * 1e3], color=colour, lw=1,
                        alpha=1.0 if k == len(tr.s) // 2 else 0.6)
        for side in ("L", "R"):
            pl = linkage.point_position(tr.poses[k], f"lam{side}_coupler", f"lam{side}_P")
            ax.plot(*(pl * 1e3), "o", color=colour, ms=3)
        ax.plot([], [], color=colour, label=f"shuttle s = {tr.s[k] * 1e3:+.1f} mm")
    ground = linkage.link("ground").points
    gx = np.array(list(ground.values()))
    ax.plot(gx[:, 0] * 1e3, gx[:, 1] * 1e3, "k^", ms=5, label="ground pivots")
    for pts in (tr.ee_left, tr.ee_right):
        ax.plot(pts[:, 0] * 1e3, pts[:, 1] * 1e3, "g-", lw=2)
    plan_view(ax)
    fig.tight_layout()
    return save(fig, path, "The driving linkage of Chapter 6 as a rigid linkage: two Chebyshev "
                "lambdas drive the two eight-bar suspensions in opposite directions, at both ends "
                "and the middle of the shuttle's stroke, with the end effectors' paths (green).")


def _draw_fem(path: Path, model: Model, lin: dict, scale: float) -> dict:
    plt = pyplot()
    p, t = model.mesh.mesh.p, model.mesh.mesh.t
    u = lin["result"].displacement
    mag = np.hypot(u[:, 0], u[:, 1])
    fig, ax = plt.subplots(figsize=(11, 4))
    ax.triplot(Triangulation(p[0] * 1e3, p[1] * 1e3, t.T), color="0.85", lw=0.2)
    tri = Triangulation((p[0] + scale * u[:, 0]) * 1e3, (p[1] + scale * u[:, 1]) * 1e3, t.T)
    cs = ax.tripcolor(tri, mag * 1e6, shading="gouraud", cmap="viridis")
    fig.colorbar(cs, ax=ax, label="|u| (um) per input")
    ax.set_aspect("equal")
    ax.set_title(f"Linear FEM, input {lin['input_m'] * 1e6:.0f} um along y (drawn x{scale:.0f}): "
                 f"ee_L/ee_R = {lin['ratio_left_right']:.6f}")
    ax.set_xlabel(axis_label("x", "mm"))
    ax.set_ylabel(axis_label("y", "mm"))
    fig.tight_layout()
    return save(fig, path, "The driving linkage's flexure part by linear FEM: displacement "
                "magnitude per unit input on the deformed shape (magnified); the two end "
                "effectors move in opposite directions.")


def driving_study(out_dir, quick: bool = False, params: DrivingParams | None = None,
                  flexure: EightBarFlexureParams | None = None) -> dict:
    """Rigid trace, linear FEM and (not ``quick``) a nonlinear drive over half the stroke each
    way; writes driving_rigid.png, driving_fem.png, driving_rigid.csv, driving_fem.csv
    (and driving_fem_nonlinear.csv). Returns {"comparisons", "tables", "figures", "notes",
    "summary"}; SI units."""
    params = params or DrivingParams()
    flexure = flexure or EightBarFlexureParams()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    tr = trace_driving(params, n=31 if quick else 121)
    tables = [write_rows(out / "driving_rigid.csv", _rigid_rows(tr)).name]
    figures = [_draw_rigid(out / "driving_rigid.png", tr, params)]
    size_factor = 3.0 if quick else 1.5
    model, _ = build_model(params, flexure, size_factor=size_factor)
    lin = linear_drive(model, 1e-6)
    umax = float(np.max(np.hypot(*lin["result"].displacement.T)))
    figures.append(_draw_fem(out / "driving_fem.png", model, lin, scale=8e-3 / umax))
    fem_row = {k: v for k, v in lin.items() if k != "result"}
    summary = {**_rigid_summary(params, tr), "dofs": int(model.n_dofs), **fem_row}
    extra_notes = []
    if not quick:
        table, nonlinear = _nonlinear_study(out, model, params, flexure, size_factor)
        tables.append(table)
        summary.update(nonlinear)
        extra_notes.append(_nonlinear_note(summary))
    tables.append(write_rows(out / "driving_fem.csv", [fem_row]).name)
    return {"comparisons": _comparisons(lin, summary["rigid_transmission"]), "tables": tables,
            "figures": figures, "notes": _notes(params, summary) + extra_notes, "summary": summary}


def _rigid_rows(tr) -> list:
    """The rigid trace as rows: shuttle input s, end-effector positions, misfit (m)."""
    return [{"s_m": float(s), "x_left_m": float(l[0]), "y_left_m": float(l[1]),
             "x_right_m": float(r[0]), "y_right_m": float(r[1]), "misfit_m": float(m)}
            for s, l, r, m in zip(tr.s, tr.ee_left, tr.ee_right, tr.misfit)]


def _rigid_summary(params: DrivingParams, tr) -> dict:
    """Gruebler counts, transmission (-), strokes, deviations and misfit (m, %) of the rigid trace."""
    return {"gruebler_whole": build_driving_linkage(params).mobility,
            "gruebler_half": half_mobility(params),
            "rigid_transmission": transmission_ratio(tr),
            "rigid_stroke_right_m": float(np.ptp(tr.dx_right)),
            "rigid_antisymmetry_m": float(np.max(np.abs(tr.dx_left + tr.dx_right))),
            "rigid_deviation_right_m": tr.deviation_right.max_deviation_m,
            "rigid_deviation_right_pct": tr.deviation_right.deviation_pct,
            "rigid_deviation_left_pct": tr.deviation_left.deviation_pct,
            "coupler_deviation_m": tr.coupler_deviation.max_deviation_m,
            "max_misfit_m": float(np.max(np.abs(tr.misfit))),
            "input_travel_m": params.input_travel}


def _nonlinear_study(out: Path, model: Model, params: DrivingParams, flexure, size_factor) -> tuple:
    """Nonlinear drive over +-input_travel / 4 (m), written to driving_fem_nonlinear.csv, beside
    the suspension alone over the same x stroke: (table name, summary entries, SI)."""
    half = params.input_travel / 4
    rows = nonlinear_drive(model, -half, 4)[::-1] + nonlinear_drive(model, half, 4)[1:]
    table = write_rows(out / "driving_fem_nonlinear.csv", rows).name
    left = np.array([[r["x_left_m"], r["y_left_m"]] for r in rows])
    right = np.array([[r["x_right_m"], r["y_right_m"]] for r in rows])
    dl, dr = straight_line_deviation(left), straight_line_deviation(right)
    # the suspension alone (x prescribed, no y force, no moment) over the same x stroke,
    # sampled alike (9 points): what the driven deviation is measured against
    alone_model = suspension_model(replace(flexure, rigid=replace(
        params.suspension, travel=flexure.rigid.travel)), size_factor)
    alone = suspension_alone_path(alone_model, float(np.max(np.abs(right[:, 0]))), 4)
    da, shape, shape_alone = (straight_line_deviation(alone[:, :2]), path_shape(right),
                              path_shape(alone[:, :2]))
    return table, {"fem_nl_stroke_right_m": float(np.ptp(right[:, 0])),
                   "fem_nl_ratio_end": rows[-1]["x_left_m"] / rows[-1]["x_right_m"],
                   "fem_nl_deviation_right_m": dr.max_deviation_m,
                   "fem_nl_deviation_right_pct": dr.deviation_pct,
                   "fem_nl_deviation_left_pct": dl.deviation_pct,
                   "fem_nl_max_rotation_rad": float(max(abs(r["rot_right_rad"]) for r in rows)),
                   "fem_nl_tilt_right_rad": shape["tilt_rad"],
                   "fem_nl_c2_right_per_m": shape["c2_per_m"],
                   "lever_tilt_prbm_rad": float(np.arctan(lever_shear_rate(params, flexure)
                                                          / k_y_alone(alone_model))),
                   "alone_deviation_m": da.max_deviation_m,
                   "alone_deviation_pct": da.deviation_pct,
                   "alone_c2_per_m": shape_alone["c2_per_m"]}


def _nonlinear_note(summary: dict) -> str:
    """The nonlinear path's deviation beside the suspension alone's, and its tilt."""
    return (f"Nonlinear path deviation {summary['fem_nl_deviation_right_pct']:.3f} % "
            f"({summary['fem_nl_deviation_right_m'] * 1e6:.1f} um over "
            f"{summary['fem_nl_stroke_right_m'] * 1e3:.1f} mm, c2 "
            f"{summary['fem_nl_c2_right_per_m']:.3f} /m); the suspension alone (no load across its "
            f"motion) over the same stroke: {summary['alone_deviation_pct']:.4f} % (c2 "
            f"{summary['alone_c2_per_m']:.3f} /m), the difference being the bar's shear. Path tilt "
            f"{summary['fem_nl_tilt_right_rad'] * 1e3:.2f} mrad (lever flexure's shear / k_y: "
            f"{summary['lever_tilt_prbm_rad'] * 1e3:.2f} mrad), removed by the best-line fit.")


def _comparisons(lin: dict, ratio: float) -> list[dict]:
    """The report's rows: the linear FEM's left/right ratio and transmission (-). The thesis
    states only "opposite directions" (Ch. 6, Fig. 6.3): the mirror symmetry's -1 and the
    rigid linkage's transmission are flexfem's own references (kind 'derived')."""
    return comparison_rows([
        # the mesh is not exactly mirror-symmetric: 1 % bounds its asymmetry
        Comparison("driving linkage: end-effector x ratio left/right (linear FEM)",
                   lin["ratio_left_right"], -1.0, "-", "mirror symmetry (Ch. 6, Fig. 6.3)",
                   "derived", 0.01, "thesis: 'opposite directions', no number"),
        # the flexures' elastic compliance lowers the rigid transmission a little
        Comparison("driving linkage: transmission d x_R / d s, linear FEM", lin["transmission"],
                   ratio, "-", "flexfem's rigid linkage", "derived", 0.05,
                   "the thesis gives no dimensions"),
    ])


def _notes(params: DrivingParams, summary: dict) -> list:
    """The study's notes: our arrangement, the Gruebler counts and misfit, the coupler length."""
    return [
        "Arrangement and dimensions are ours: the thesis prints none for Chapter 6 and its figures "
        "are not in the text.",
        f"Gruebler count of the whole mechanism {summary['gruebler_whole']}, of one half "
        f"{summary['gruebler_half']}; the symmetric rigid motion holds only to the lambdas' "
        f"straight-line deviation (misfit |P_R P_L| - 2e up to {summary['max_misfit_m'] * 1e6:.1f} um), "
        "which the flexures take up (without the shuttle, each half driven by its own coupler "
        "point, the end-effector path is the same: tested).",
        f"Suspension coupler length {params.suspension.coupler_length * 1e3:.1f} mm (Chapter 5 "
        f"design: 50 mm; {FLEXURE_COMPENSATED_COUPLER_LENGTH * 1e3:.1f} mm cancels the flexures' "
        f"elastic bow): rigid-body path deviation {summary['rigid_deviation_right_pct']:.4f} %.",
    ]
