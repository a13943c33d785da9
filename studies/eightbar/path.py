"""Rigid-body paths of the straight-line linkages and the symmetric eight-bar, beside the thesis.

Thesis: Y. Liu, Flexure Design for Eight-Bar Rectilinear Motion Mechanism, UC Irvine 2015
(data/eightbar_thesis.toml). Lengths in m, angles in rad.
"""
from dataclasses import replace
from pathlib import Path

import numpy as np

from ...data import load_toml
from ...geometry.eightbar.rigid import (
    EightBarParams,
    build_eightbar,
    overall_size,
    trace_eightbar,
)
from ...geometry.linkage import Trace, trace_from_reference
from ...geometry.linkage_clearance import overlapping_links_along
from ...geometry.straight_line import (
    CLASSIC_LINKAGES,
    straight_line_deviation,
    trace_straight_line,
)
from ...geometry.synthesis import (
    ThreeRChain,
    eightbar_constraint_synthesis,
    planar_transform,
    rr_dyad_synthesis,
    three_r_link_poses,
)
from ..engine.tables import write_rows
from ..report.comparison import Comparison, rows as comparison_rows
from ..report.figures import axis_label, plan_view, pyplot, save

MM = 1e-3


def thesis_targets() -> dict:
    """The thesis' design targets (Section 1.1, Ch. 5) in SI units (m, %)."""
    t = load_toml("eightbar_thesis.toml")["design_targets"]
    return {"width_m": t["overall_width_mm"] * MM, "height_m": t["overall_height_mm"] * MM,
            "travel_m": t["travel_mm"] * MM, "max_deviation_m": t["max_deviation_mm"] * MM,
            "max_deviation_pct": t["max_deviation_pct"], "y_max_m": t["y_max_mm"] * MM,
            "y_min_m": t["y_min_mm"] * MM}


def appendix_a_points() -> np.ndarray:
    """Table A.1's traced end-effector points (n, 2), m (x, y; z is constant)."""
    a = load_toml("eightbar_thesis.toml")["appendix_a"]
    return np.column_stack([a["x_mm"], a["y_mm"]]) * MM


def classic_linkage_deviations(n: int = 201) -> list:
    """Straightness of each Chapter 2 linkage over its input range: rows of dicts (m, %), with
    the pairs of links that overlap somewhere on the range when drawn as bars 1 % of the
    linkage's size wide (a single-layer layout needs none)."""
    rows = []
    for name, builder in CLASSIC_LINKAGES.items():
        mechanism = builder()
        _, dev = trace_straight_line(mechanism, n)
        tr = trace_from_reference(mechanism.linkage, *mechanism.input_range, 21)
        overlaps = overlapping_links_along(tr, 0.01 * mechanism.linkage.length_scale)
        rows.append({"linkage": name, "mobility": mechanism.linkage.mobility,
                     "travel_m": dev.travel_m, "max_deviation_m": dev.max_deviation_m,
                     "band_m": dev.band_m, "deviation_pct": dev.deviation_pct,
                     "overlapping_links": "; ".join("/".join(pair) for pair in overlaps)})
    return rows


def check_resolved(deviation_at, n: int, what: str):
    """The deviation ``deviation_at(n)`` if sampling the path at ``n`` points resolves it: the
    band from 2 n - 1 points (every point and the midpoints) within 1 % (or 1e-9 of the
    travel: an exact straight line's band is round-off); ValueError naming
    both otherwise (a coarse sampling misses the path's extremes: it under-reports)."""
    coarse = deviation_at(n)  # its own check of n first
    fine = deviation_at(2 * n - 1)
    if abs(coarse.band_m - fine.band_m) > 0.01 * fine.band_m + 1e-9 * fine.travel_m:
        raise ValueError(f"{what}: {n} points do not resolve the path: its deviation band is "
                         f"{coarse.band_m:.4g} m at {n} points but {fine.band_m:.4g} m at "
                         f"{2 * n - 1}; use more points (the default resolves it)")
    return coarse


def trace_classic(name: str, n: int = 201) -> dict:
    """Straightness of one classic linkage (watt, roberts, chebyshev, peaucellier,
    modified_peaucellier): travel_m, max_deviation_m, band_m, deviation_pct. ValueError
    where ``n`` points do not resolve the path (:func:`check_resolved`)."""
    if name not in CLASSIC_LINKAGES:
        raise ValueError(f"linkage = {name!r}, must be one of {sorted(CLASSIC_LINKAGES)}")
    dev = check_resolved(lambda k: trace_straight_line(CLASSIC_LINKAGES[name](), k)[1], n,
                         f"linkage trace {name}")
    return {"linkage": name, "travel_m": dev.travel_m, "max_deviation_m": dev.max_deviation_m,
            "band_m": dev.band_m, "deviation_pct": dev.deviation_pct}


def eightbar_path_summary(params: EightBarParams = None, n: int = 251,
                          overlap_width: float = 2e-3) -> dict:
    """Rigid-body straightness, size, rotation and link overlaps of the eight-bar (m, rad, %).

    ``band_m`` (max minus min distance across the line) is the quantity the thesis calls its
    0.027 mm deviation; ``max_deviation_m`` is the largest distance from the line.
    """
    params = EightBarParams() if params is None else params
    tr = trace_eightbar(params, n)
    width, height = overall_size(params, tr)
    linkage = build_eightbar(params)
    overlaps = overlapping_links_along(Trace(linkage, tr.displacements[:, None], tr.poses[::5]),
                                       overlap_width)
    return {"travel_m": tr.deviation.travel_m, "max_deviation_m": tr.deviation.max_deviation_m,
            "band_m": tr.deviation.band_m, "deviation_pct": tr.deviation.deviation_pct,
            "band_pct": 100 * tr.deviation.band_m / tr.deviation.travel_m,
            "max_rotation_rad": float(np.max(np.abs(tr.rotation))), "width_m": width,
            "height_m": height, "mobility": linkage.mobility, "overlapping_links": overlaps,
            "overlap_width_m": overlap_width}


def _link_frames(linkage, poses, link):
    """3x3 transforms of a link along poses (the reference pose is the identity)."""
    return np.array([linkage.link_transform(q, link) for q in poses])


def synthesis_check(params: EightBarParams = None) -> dict:
    """Recover known joints by five-position synthesis: the Roberts four-bar's two dyads
    (Eqs. 3.20-3.28), and the eight-bar's left rocker as an RR constraint between the ground and
    the left coupler of the 3R chain O_L-A_L-P_L (Eqs. 4.1-4.6). Largest pivot errors, m."""
    params = EightBarParams() if params is None else params
    roberts = CLASSIC_LINKAGES["roberts"]()
    lk = roberts.linkage
    tr = trace_from_reference(lk, -0.25, 0.25, 5)
    tasks = _link_frames(lk, tr.poses, "coupler")
    dyads = rr_dyad_synthesis(tasks)
    known = [(lk.link("ground").points[g], lk.point_position(tr.poses[0], "coupler", w))
             for g, w in (("O", "A"), ("C", "B"))]
    four_bar_error = max(min(np.hypot(*np.subtract(d.g1, g)) + np.hypot(*np.subtract(d.w1, w))
                             for d in dyads) for g, w in known)

    eb = trace_eightbar(replace(params, travel=0.8 * params.travel), n=5)
    linkage = build_eightbar(params)
    pts = {n: linkage.point_position(eb.poses[0], "crank_L" if n.startswith("O") else
                                     "coupler_L" if n[0] in "ABM" else "end_effector", n)
           for n in ("O_L", "A_L", "B_L", "P_L", "E")}
    ee_tasks = _link_frames(linkage, eb.poses, "end_effector")
    chain = _left_chain(pts, ee_tasks[0])
    found = eightbar_constraint_synthesis(chain, chain, ee_tasks, [(("ground",), ("a", 2))])
    c_l = linkage.link("ground").points["C_L"]
    rocker_error = min(np.hypot(*np.subtract(s.g1, c_l)) + np.hypot(*np.subtract(s.w1, pts["B_L"]))
                       for s in found[(("ground",), ("a", 2))])
    return {"four_bar_dyads_found": len(dyads), "four_bar_pivot_error_m": float(four_bar_error),
            "eightbar_constraints_found": len(found[(("ground",), ("a", 2))]),
            "eightbar_rocker_error_m": float(rocker_error)}


def _left_chain(pts, task1):
    """The 3R chain ground - crank_L - coupler_L - end-effector of the eight-bar (Eq. 4.1)."""
    a1 = np.hypot(*(pts["A_L"] - pts["O_L"]))
    a2 = np.hypot(*(pts["P_L"] - pts["A_L"]))
    base = planar_transform(0.0, *pts["O_L"])
    tool = np.linalg.inv(planar_transform(0.0, *pts["P_L"])) @ task1
    for elbow in (1, -1):
        chain = ThreeRChain(base, a1, a2, tool, elbow)
        if np.allclose(three_r_link_poses(chain, [task1])[1, 0][:2, 2], pts["A_L"], atol=1e-9):
            return chain
    raise ValueError("no elbow branch of the 3R chain reproduces the drawn pose")


def plot_path_vs_appendix_a(tr, out: Path) -> dict:
    """PNG: our end-effector's deviation across its line beside Table A.1's (shapes compare)."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6))
    for ax, pts, label in ((axes[0], tr.points, "flexfem eight-bar (this design)"),
                           (axes[1], appendix_a_points(), "thesis Table A.1")):
        dev = straight_line_deviation(pts)
        centred = pts - np.array(dev.centroid)
        normal = np.array([-dev.direction[1], dev.direction[0]])
        along = centred @ np.array(dev.direction)
        sign = np.sign(dev.direction[0]) or 1.0
        ax.plot(sign * along * 1e3, centred @ normal * 1e6, ".-", ms=2, lw=0.8)
        ax.set_title(f"{label}\nband {dev.band_m * 1e6:.1f} um over {dev.travel_m * 1e3:.1f} mm")
        ax.set_xlabel(axis_label("along the line", "mm"))
        ax.set_ylabel(axis_label("across the line", "um"))
        ax.grid(alpha=0.3)
    fig.tight_layout()
    return save(fig, out, "Straight-line path of the rigid eight-bar: the end-effector's "
                "deviation across its best-fit line, flexfem's design (left) beside the "
                "thesis' traced path (Table A.1, right).")


def plot_eightbar(params: EightBarParams, tr, out: Path) -> dict:
    """PNG: the eight-bar's links at both ends and the middle of its travel, and the path."""
    plt = pyplot()
    linkage = build_eightbar(params)
    fig, ax = plt.subplots(figsize=(7, 5.5))
    for q, style in ((tr.poses[0], ":"), (tr.poses[-1], "--"), (tr.poses[len(tr.poses) // 2], "-")):
        for link in linkage.links:
            if link.name == linkage.ground:
                continue
            for a, b in link.segment_names:
                p, r = linkage.point_position(q, link.name, a), linkage.point_position(q, link.name, b)
                ax.plot([p[0] * 1e3, r[0] * 1e3], [p[1] * 1e3, r[1] * 1e3], style, color="C0", lw=1.5)
    base = np.array(list(linkage.link("ground").points.values()))
    ax.plot(base[:, 0] * 1e3, base[:, 1] * 1e3, "k^", ms=8, label="ground pivots")
    ax.plot(tr.points[:, 0] * 1e3, tr.points[:, 1] * 1e3, "C3-", lw=2, label="end-effector path")
    plan_view(ax)
    fig.tight_layout()
    return save(fig, out, "The symmetric eight-bar as a rigid linkage at the middle (solid), "
                "start (dotted) and end (dashed) of its travel, with its ground pivots and the "
                "end-effector's path.")


PARAGRAPH = ("The symmetric eight-bar of the thesis is built as a rigid planar linkage (Ch. 5), "
             "with the classic straight-line linkages (Ch. 2) and five-position synthesis "
             "(Ch. 3-4) beside it, and traced over the thesis' travel. Its end effector keeps "
             "to a straight line within the thesis' 0.1 % bound; the link dimensions are "
             "flexfem's own synthesis, so the size of the deviation band, not only its bound, "
             "differs from the thesis' own design.")


def comparisons(summary: dict, thesis, table_band: float, targets: dict) -> list[Comparison]:
    """The rigid eight-bar and the thesis' Table A.1 beside the thesis' numbers (SI units)."""
    C = Comparison
    return [
        C("eight-bar travel", summary["travel_m"], targets["travel_m"], "m", "Ch. 5", "input",
          note="the trace is run over the thesis' travel: an input, not a result"),
        C("eight-bar path deviation (band, % of travel)", summary["band_pct"],
          targets["max_deviation_pct"], "% of travel", "Ch. 5 design bound", limit="upper",
          note="band = max - min across the best-fit line", headline=True),
        C("eight-bar path deviation band", summary["band_m"], targets["max_deviation_m"], "m",
          "Appendix A", note="flexfem's own link dimensions: not the thesis' design, not judged"),
        C("Table A.1 band about its best-fit line, recomputed", thesis.band_m,
          targets["max_deviation_m"], "m", "Appendix A",
          note="total-least-squares line through Table A.1 vs the thesis' max - min Y"),
        C("Table A.1 max - min Y, recomputed", table_band, targets["max_deviation_m"], "m",
          "Appendix A", tolerance=0.02,
          note="check of the transcribed table against the text's 0.027 mm"),
        C("Table A.1 travel, recomputed", thesis.travel_m, targets["travel_m"], "m", "Appendix A",
          note="Table A.1 spans 33.76 mm; the text says 33.1 mm between task positions 1 and 5"),
        # the thesis gives the overall size as 'approximately': 10 % is that word's room
        C("eight-bar overall width", summary["width_m"], targets["width_m"], "m", "Ch. 5",
          tolerance=0.10, note="centre-line box over the travel; the height agrees too "
          "(audit)", headline=True),
        C("eight-bar overall height", summary["height_m"], targets["height_m"], "m", "Ch. 5",
          tolerance=0.10, note="centre-line box over the travel"),
    ]


def reproduce(out_dir: Path, quick: bool = False) -> dict:
    """Tables and figures of the rigid-body part of the eight-bar thesis, into ``out_dir``."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 41 if quick else 201
    classic = classic_linkage_deviations(n)
    write_rows(out_dir / "straight_line_linkages.csv", classic)

    targets = thesis_targets()
    params = replace(EightBarParams(), travel=targets["travel_m"])
    tr = trace_eightbar(params, 51 if quick else 251)
    summary = eightbar_path_summary(params, 51 if quick else 251)
    thesis = straight_line_deviation(appendix_a_points())
    table_band = float(np.ptp(appendix_a_points()[:, 1]))
    write_rows(out_dir / "eightbar_path.csv",
               [{"displacement_m": float(s), "x_m": float(x), "y_m": float(y), "rotation_rad": float(r)}
                for s, (x, y), r in zip(tr.displacements, tr.points, tr.rotation)])
    figures = [plot_path_vs_appendix_a(tr, out_dir / "eightbar_path_vs_appendix_a.png"),
               plot_eightbar(params, tr, out_dir / "eightbar_linkage.png")]
    synthesis = synthesis_check()
    rows = comparison_rows(comparisons(summary, thesis, table_band, targets))
    return {"paragraph": PARAGRAPH, "comparisons": rows, "figures": figures,
            "tables": ["straight_line_linkages.csv", "eightbar_path.csv"],
            "straight_line_linkages": classic, "eightbar": summary, "synthesis": synthesis,
            "params": {k: getattr(params, k) for k in params.__dataclass_fields__}}
