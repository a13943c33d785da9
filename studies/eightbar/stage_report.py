"""``reproduce()`` of the eight-bar stage section: compliance, support stiffness, modes and
buckling along the stroke, the beam model's beside the continuum's (:mod:`.stage`), with
figures, CSV tables and comparison rows."""
from pathlib import Path

from ...geometry.eightbar.flexure import EightBarFlexureParams
from ..engine.tables import write_rows
from ..report.comparison import Comparison, rows as comparison_rows
from ..report.figures import axis_label, legend_outside, pyplot, save
from ..mode_pairing import SPLIT
from .eightbar_modes3d import beam_modes
from .stage import BEAM_TOLERANCE, BUCKLING_CASES, ratio_key, stage_study

STROKE_COLUMNS = ["x_m", "y_m", "rotation_rad", "force_x_n", "k_x", "k_y", "support_ratio",
                  "k_theta", "parasitic_y", "parasitic_rotation", "f1_hz", "f2_hz", "f3_hz",
                  "mirrored"]
BUCKLING_COLUMNS = ["x_m", *[c for key in BUCKLING_CASES
                             for c in (key, f"beam_{key}", ratio_key(key))], "mirrored"]
CASE_LABELS = {"drive_critical_n": "drive F_x", "off_axis_plus_y_n": "off-axis +F_y",
               "off_axis_minus_y_n": "off-axis -F_y"}


def stroke_figure(out: dict, key: str, panels: int = 1) -> tuple:
    """A figure of ``panels`` side by side for the rows ``out[key]`` along the stroke: (fig,
    axes, rows, their stroke positions x in mm)."""
    rows = out[key]
    fig, axes = pyplot().subplots(1, panels, figsize=(10, 3.8) if panels == 2 else (6.5, 3.8))
    return fig, axes, rows, [r["x_m"] * 1e3 for r in rows]


def saved_against_stroke(fig, path: Path, caption: str, *panels) -> dict:
    """``fig`` saved as ``path`` with ``caption`` (the report's figure entry), each (axes, y
    label) of ``panels`` labelled as a plot against the stroke x (mm), the first's legend
    outside; two panels laid out tight."""
    for ax, ylabel in panels:
        ax.set_xlabel(axis_label("stroke x", "mm"))
        ax.set_ylabel(ylabel)
    legend_outside(panels[0][0])
    if len(panels) > 1:
        fig.tight_layout()
    return save(fig, path, caption)


def plot_stiffness(out: dict, path: Path) -> dict:
    """k_x, k_y, k_y / k_x and k_theta against the stroke."""
    fig, (ax, ax2), rows, x = stroke_figure(out, "stroke", panels=2)
    ax.semilogy(x, [r["k_x"] for r in rows], "o-", label="k_x (drive), N/m")
    ax.semilogy(x, [r["k_y"] for r in rows], "s-", label="k_y (support, motion held), N/m")
    ax.semilogy(x, [r["k_theta"] for r in rows], "^-", label="k_theta (rotation), N m/rad")
    ax2.plot(x, [r["support_ratio"] for r in rows], "o-")
    s = out["summary"]
    caption = (
        "The end-effector face's stiffness from its 3 x 3 tangent compliance about the "
        "large-deflection state at each stroke position: drive stiffness k_x, support stiffness "
        "across the motion k_y (motion held, rotation free) and rotational stiffness k_theta "
        f"(forces free); right, k_y / k_x, at least {s['support_ratio_min']:.3g} over the stroke.")
    return saved_against_stroke(fig, path, caption, (ax, "stiffness"),
                                (ax2, axis_label("support-stiffness ratio k_y / k_x", "-")))


def plot_frequencies(out: dict, path: Path) -> dict:
    """The first three prestressed natural frequencies against the stroke."""
    fig, ax, rows, x = stroke_figure(out, "stroke")
    for i, marker in zip((1, 2, 3), "os^"):
        ax.plot(x, [r[f"f{i}_hz"] for r in rows], marker + "-", label=f"mode {i}")
    caption = ("First three natural frequencies of the suspension, prestressed about the "
               "large-deflection state at each stroke position (end-effector free: the drive "
               "disconnected).")
    return saved_against_stroke(fig, path, caption, (ax, axis_label("natural frequency", "Hz")))


def plot_buckling(out: dict, path: Path) -> dict:
    """The critical added loads along the stroke, continuum and beam model; their ratio."""
    fig, (ax, ax2), rows, x = stroke_figure(out, "stroke_buckling", panels=2)
    for (key, label), colour in zip(CASE_LABELS.items(), ("C0", "C1", "C2")):
        ax.plot(x, [r[key] for r in rows], "o-", color=colour, label=f"{label}, continuum")
        ax.plot(x, [r[f"beam_{key}"] for r in rows], "s--", color=colour,
                label=f"{label}, beam model")
        ax2.plot(x, [r[ratio_key(key)] for r in rows], "o-", color=colour, label=label)
    for bound in (1 - BEAM_TOLERANCE, 1 + BEAM_TOLERANCE):
        ax2.axhline(bound, color="0.5", lw=0.8, ls=":")
    b = out["buckling"]
    caption = (
        "Buckling along the stroke: the critical force added on the released end-effector "
        "face about the large-deflection state at each position (incremental linearised "
        "buckling), the drive force in the stroke's sense and a force across the stroke in "
        "each sense; continuum (solid) and the beam model about its own path (dashed). Right, "
        f"beam / continuum, at worst {b['beam_buckling_worst_ratio']:.3f} (dotted: "
        f"+-{100 * BEAM_TOLERANCE:.0f} %).")
    return saved_against_stroke(fig, path, caption,
                                (ax, axis_label("critical added force", "N")),
                                (ax2, axis_label("beam model / continuum", "-")))


def beam_rows(out: dict) -> list[Comparison]:
    """Per load case, the beam model's critical load at the position where it is furthest
    from the continuum's (kind 'derived', judged within BEAM_TOLERANCE)."""
    rows = out["stroke_buckling"]
    out_rows = []
    for key, label in CASE_LABELS.items():
        worst = max(rows, key=lambda r: abs(r[ratio_key(key)] - 1.0))
        out_rows.append(Comparison(
            f"stage: critical {label} along the stroke (beam model)", worst[f"beam_{key}"],
            worst[key], "N", "continuum FEM (2-D, same design), same stroke position",
            "derived", tolerance=BEAM_TOLERANCE,
            note=f"worst of {len(rows)} positions, at x = {worst['x_m'] * 1e3:.3g} mm; each "
                 "model about its own large-deflection path"))
    return out_rows


def comparisons(out: dict, k_x_linear: float) -> list[Comparison]:
    """The stage's numbers as report rows: the linear k_x check, and the stroke extremes."""
    s, b, lin = out["summary"], out["buckling"], out["linear"]
    C = Comparison
    return [
        C("stage: drive stiffness k_x from the compliance matrix (drawn pose)", lin["k_x"],
          k_x_linear, "N/m", "the face driven along x (analysis.linear_analysis)", "derived",
          tolerance=1e-3, note="two routes to the same linear stiffness"),
        C("stage: least support-stiffness ratio k_y / k_x over the stroke",
          s["support_ratio_min"], lin["support_ratio"], "-",
          "the drawn pose (linear compliance)", "derived", tolerance=0.2,
          note=f"k_y >= {s['k_y_min']:.4g} N/m at every position: the suspension stays stiff "
               "across the motion over the whole stroke (within 20 % of the drawn pose's ratio)"),
        C("stage: least rotational stiffness over the stroke", s["k_theta_min"],
          lin["k_theta"], "N m/rad", "the drawn pose (linear)", "derived",
          note="how far the stiffness against a payload's moment falls along the stroke"),
        C("stage: buckling factor of the flexures under the drive force", b["drive_factor"],
          1.0, "-", "the end-of-stroke drive force", "derived", limit="lower",
          note=f"critical drive force {b['drive_critical_n']:.4g} N (linear buckling, force on "
               f"the free end-effector face) over {b['drive_force_n']:.3g} N; support "
               f"stiffness k_y >= {s['k_y_min']:.4g} N/m over the stroke", headline=True),
        C("stage: least buckling factor under the drive force along the stroke",
          b["drive_factor_min"], 1.0, "-", "the end-of-stroke drive force", "derived",
          limit="lower", note=f"least critical added drive force {b['drive_critical_min_n']:.4g}"
                              " N about the large-deflection states"),
        C("stage: least critical off-axis load along the stroke", b["off_axis_critical_min_n"],
          b["drive_force_n"], "N", "the end-of-stroke drive force", "derived",
          limit="lower", note=b["off_axis_load"]),
    ] + beam_rows(out)


def plane_modes(n_modes: int = 6) -> dict:
    """The lowest out-of-plane and in-plane natural frequencies (Hz) of the default design's
    spatial beam model, flexure torsion with Vlasov's warping restraint (within 1 % of the 3-D
    continuum's out-of-plane mode, docs/beam.md); rigid links, so that its drive mode is the
    planar beam model's of the section (flexible links: 0.1 % lower, both modes); ~1 s."""
    modes = beam_modes(EightBarFlexureParams(), n_modes=n_modes, warping=True, links="rigid")
    pairs = list(zip(modes["f_hz"], modes["out_of_plane_share"]))
    return {"out_of_plane_hz": min(f for f, s in pairs if s > SPLIT),
            "in_plane_hz": min(f for f, s in pairs if s <= SPLIT)}


def paragraph(out: dict) -> str:
    s, b = out["summary"], out["buckling"]
    return (
        "The suspension judged as a precision stage: the end-effector face's 3 x 3 compliance "
        "at the drawn pose and, tangent about the large-deflection state, at "
        f"{len(out['stroke'])} positions over the {out['travel_m'] * 1e3:.3g} mm stroke. It "
        f"stays stiff across the motion everywhere: k_y >= {s['k_y_min']:.4g} N/m against a "
        f"drive stiffness of {s['k_x_min']:.3g}-{s['k_x_max']:.3g} N/m, k_y / k_x >= "
        f"{s['support_ratio_min']:.3g}; its rotational stiffness falls to "
        f"{s['k_theta_min']:.3g} N m/rad at the ends, and a push along x turns the face by up "
        f"to {s['parasitic_rotation_max']:.3g} rad/m. The first in-plane mode (the drive mode) stays at "
        f"{s['f1_hz_min']:.3g}-{s['f1_hz_max']:.3g} Hz along the stroke. The flexures buckle "
        f"under a drive force {b['drive_factor']:.3g} times the end-of-stroke drive at the "
        f"drawn pose ({b['drive_factor_min']:.3g} times at worst along the stroke, about the "
        f"large-deflection state), and under {b['off_axis_critical_min_n']:.3g} N across the "
        f"stroke at worst. The beam model, about its own large-deflection path, gives these "
        f"critical loads within {100 * abs(b['beam_buckling_worst_ratio'] - 1):.1f} % of the "
        f"continuum's at each of the {len(out['stroke_buckling'])} positions.")


def plane_sentence(planes: dict) -> str:
    """The paragraph's sentence on the out-of-plane mode (:func:`plane_modes`)."""
    return (f" Out of the plane the suspension is softer: the spatial beam model's first mode "
            f"({planes['out_of_plane_hz']:.3g} Hz, the flexures twisting) lies below the drive "
            f"mode ({planes['in_plane_hz']:.3g} Hz); the 3-D continuum of the same design "
            "(flexfem eightbar analyze --dim 3) confirms the order.")


def reproduce(out_dir, quick: bool = False) -> dict:
    """Run :func:`.stage.stage_study` and write its figures and tables; the section summary."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    out = stage_study(quick=quick)
    planes = plane_modes()
    k_x_linear = out["linear_analysis"]["k_x"]
    figures = [plot_stiffness(out, out_dir / "eightbar_stage_stiffness.png"),
               plot_frequencies(out, out_dir / "eightbar_stage_modes.png"),
               plot_buckling(out, out_dir / "eightbar_stage_buckling.png")]
    write_rows(out_dir / "eightbar_stage_stroke.csv", out["stroke"], STROKE_COLUMNS)
    write_rows(out_dir / "eightbar_stage_buckling.csv", out["stroke_buckling"],
               BUCKLING_COLUMNS)
    return {"paragraph": paragraph(out) + plane_sentence(planes), "figures": figures,
            # the out-of-plane mode is told in the paragraph, not as a row: its only reference
            # would be flexfem's own drive mode, and a row compares with a source
            "comparisons": comparison_rows(comparisons(out, k_x_linear)),
            "tables": ["eightbar_stage_stroke.csv", "eightbar_stage_buckling.csv"],
            "summary": out["summary"], "linear": out["linear"], "buckling": out["buckling"],
            "dofs": out["dofs"]}
