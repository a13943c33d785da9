"""Report section "Balancing pivots: beam model beside beam theory and the continuum FEM":
the cross-spring pivots (K > 0 motors) and the compressed-leaf pivots (K < 0 motors), their
stiffness and stress over the rotation by the closed forms (beam theory n E w t^3 / (12 L);
the beam-column and elastica), the generated beam model and the 2-D FEM (plane stress).
"""
import time
from pathlib import Path

from ..engine.tables import write_rows
from ..report.figures import axis_label, legend_outside, pyplot, save
from ..report.three_way import (STRESS_TOL, Metric, beam_comparisons, key_table,
                                three_way_rows)
from .negative_pivot import compressed_leaf_elastica
from .negative_pivot_study import negative_pivot_designs, negative_pivot_fem_check
from .pivot_beam import compressed_leaf_beam_check, pivot_beam_check
from .pivot_fem import pivot_fem_check, positive_stiffness_pivots


def cross_metrics(label, pivot, steps, n_through) -> tuple:
    """([Metric], curves {model: (theta, moment)}, times) of one cross-spring pivot."""
    start = time.perf_counter()
    beam = pivot_beam_check(pivot, steps=steps)
    t_beam = time.perf_counter() - start
    start = time.perf_counter()
    fem = pivot_fem_check(pivot, steps=steps, elements_through_thickness=n_through)
    t_fem = time.perf_counter() - start
    k = fem["stiffness_beam_Nm_per_rad"]
    metrics = [
        Metric(f"{label}: stiffness, small angle", "N m/rad", k,
               beam["stiffness_linear_Nm_per_rad"], fem["stiffness_linear_Nm_per_rad"]),
        Metric(f"{label}: secant stiffness at theta_max", "N m/rad", k,
               beam["stiffness_secant_Nm_per_rad"], fem["stiffness_secant_Nm_per_rad"]),
        Metric(f"{label}: peak stress at theta_max", "Pa", fem["stress_beam_Pa"],
               beam["stress_fem_peak_Pa"], fem["stress_fem_peak_Pa"], STRESS_TOL)]
    curves = {"beam model": (beam["curve_theta_rad"], beam["curve_moment_Nm"]),
              "continuum FEM": (fem["curve_theta_rad"], fem["curve_moment_Nm"]),
              "beam theory": ([0.0, pivot.theta_max], [0.0, k * pivot.theta_max])}
    return metrics, curves, (t_beam, t_fem)


def compressed_metrics(label, pivot, fractions, steps) -> tuple:
    """([Metric], curves, times) of one compressed-leaf pivot."""
    start = time.perf_counter()
    beam = compressed_leaf_beam_check(pivot, fractions, steps)
    t_beam = time.perf_counter() - start
    start = time.perf_counter()
    fem = negative_pivot_fem_check(pivot, fractions, steps)
    t_fem = time.perf_counter() - start
    theta = fem["curve_theta_rad"]
    elastica = [compressed_leaf_elastica(pivot.material.E, pivot.I, pivot.L, pivot.P, t)
                for t in theta]
    metrics = [
        Metric(f"{label}: stiffness, small angle", "N m/rad", fem["stiffness_closed_Nm_per_rad"],
               beam["stiffness_fem_small_Nm_per_rad"], fem["stiffness_fem_small_Nm_per_rad"],
               note="closed form: the beam-column k L cot k L"),
        Metric(f"{label}: moment at theta_max", "N m", elastica[-1].moment,
               beam["curve_moment_fem_Nm"][-1], fem["curve_moment_fem_Nm"][-1],
               note="closed form: the elastica"),
        Metric(f"{label}: peak stress at theta_max", "Pa", fem["stress_elastica_Pa"],
               beam["stress_fem_peak_nodal_Pa"], fem["stress_fem_peak_nodal_Pa"], STRESS_TOL)]
    curves = {"beam model": ([0.0] + beam["curve_theta_rad"], [0.0] + beam["curve_moment_fem_Nm"]),
              "continuum FEM": ([0.0] + theta, [0.0] + fem["curve_moment_fem_Nm"]),
              "elastica": ([0.0] + theta, [0.0] + [e.moment for e in elastica])}
    return metrics, curves, (t_beam, t_fem)


def plot_curves(panels: dict, path) -> dict:
    """Moment against rotation, one panel per pivot, by the three models."""
    plt = pyplot()
    fig, axes = plt.subplots(1, len(panels), figsize=(4.2 * len(panels), 3.8), squeeze=False)
    styles = {"beam model": "-", "continuum FEM": "o", "beam theory": "k--", "elastica": "k--"}
    for ax, (label, curves) in zip(axes[0], panels.items()):
        for name, (theta, moment) in curves.items():
            ax.plot([t * 57.29578 for t in theta], moment, styles[name], label=name)
        ax.set_title(label, fontsize=9)
        ax.set_xlabel(axis_label("pivot rotation", "deg"))
        ax.set_ylabel(axis_label("hub moment", "N m"))
        ax.grid(True, alpha=0.3)
    legend_outside(axes[0][-1])
    fig.tight_layout()
    return save(fig, path, "Balancing pivots: hub moment against rotation by the beam model "
                "(line), the 2-D continuum FEM (points, plane stress) and the closed forms "
                "(dashed: beam theory for the cross-spring pivots, the elastica for the "
                "compressed leaves, whose stiffness is negative).")


def reproduce(out_dir, quick: bool = False) -> dict:
    """Three-way table of every pivot design (quick: the first compressed leaf only, its
    end rotation only, 2 elements through the leaf)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    steps, n_through = (4, 2) if quick else (8, 3)
    metrics, panels, times = [], {}, []
    for motor, reading, pivot in positive_stiffness_pivots():
        label = f"motor {motor} cross-spring"
        m, curves, t = cross_metrics(label, pivot, steps, n_through)
        metrics, panels[label] = metrics + m, curves
        times.append(t)
    designs = negative_pivot_designs()
    for row in designs[:1] if quick else designs:
        label = f"motor {row[0]} compressed leaf"
        m, curves, t = compressed_metrics(label, row[-1], (1.0,) if quick else (0.5, 1.0), 4)
        metrics, panels[label] = metrics + m, curves
        times.append(t)
    tables = [write_rows(out_dir / "balancing_beam_three_way.csv", three_way_rows(metrics)).name]
    figure = plot_curves(panels, out_dir / "balancing_beam_pivots.png")
    worst = max(abs(m.beam / m.continuum - 1) for m in metrics)
    beam_s, fem_s = sum(t[0] for t in times), sum(t[1] for t in times)
    paragraph = (
        "The balancing robot's pivots as beam models (reduced/pivot.py): the leaves of a "
        "cross-spring pivot crossing without touching, the hub rigid and free to translate; "
        "the compressed leaf under its dead preload. The 2-D model clamps the leaf end faces "
        "(rigid blocks), where beam theory is exact, so no root extension applies here. Over "
        f"{len(panels)} pivots the beam model is within {100 * worst:.2f} % of the continuum "
        f"(stiffness, moment, peak stress), in {beam_s:.2f} s against {fem_s:.1f} s.")
    return {"paragraph": paragraph, "comparisons": beam_comparisons(metrics),
            "figures": [figure], "tables": tables,
            "key_tables": [key_table(metrics, "Balancing pivots: closed form, beam, continuum")],
            "timing_s": {"beam": beam_s, "continuum": fem_s}}
