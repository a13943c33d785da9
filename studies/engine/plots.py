"""The figure of a sweep: a metric against a parameter over the successful cases."""
import itertools
import math
from pathlib import Path

from ..report.figures import axis_label, legend_outside, pyplot
from .units import unit_of


def plot_metric(cases, metric: str, parameter: str, path, overlay=(), units=None) -> Path:
    """PNG of ``metric`` against ``parameter`` over the successful ``cases`` (CaseResult),
    one line per combination of the other varied parameters, ``overlay`` metrics (e.g. the
    analytical value) dashed or dotted in the same colour; designs that share no line with
    another (a space-filling sample) as grey points. Axis labels carry the units of
    ``units`` ({name: unit}, see :func:`.units.unit_of`)."""
    plt = pyplot()
    ok = [c for c in cases if c.ok and parameter in c.params and metric in c.metrics]
    if not ok:
        reasons = {c.metrics.get("not_available") for c in cases if c.ok} - {None, ""}
        why = f" (not available: {'; '.join(sorted(map(str, reasons)))})" if reasons else ""
        raise ValueError(f"no successful case has both parameter {parameter!r} and metric "
                         f"{metric!r}{why}")
    others = sorted({k for c in ok for k in c.params if k != parameter
                     and len({repr(d.params.get(k)) for d in ok}) > 1})
    groups = {}
    for case in ok:
        groups.setdefault(tuple(case.params.get(k) for k in others), []).append(case)
    lines = {k: v for k, v in groups.items() if len(v) > 1}
    scattered = [c for v in groups.values() if len(v) == 1 for c in v]
    styles = itertools.cycle(["--", ":", "-."])
    overlay_styles = {name: next(styles) for name in overlay}
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for (label_values, members), colour in zip(sorted(lines.items(), key=lambda g: repr(g[0])),
                                               itertools.cycle(plt.rcParams["axes.prop_cycle"].by_key()["color"])):
        members.sort(key=lambda c: c.params[parameter])
        x = [c.params[parameter] for c in members]
        label = ", ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                          for k, v in zip(others, label_values))
        ax.plot(x, [c.metrics[metric] for c in members], "o-", color=colour,
                label=f"{metric} {label}".strip())
        for name in overlay:
            ax.plot(x, [c.metrics.get(name, math.nan) for c in members], overlay_styles[name],
                    color=colour, label=f"{name} {label}".strip())
    if scattered:  # designs that share no line with another (e.g. a space-filling sample)
        ax.plot([c.params[parameter] for c in scattered], [c.metrics[metric] for c in scattered],
                "o", color="0.35", label=f"{metric}, other designs ({len(scattered)})")
    if len(lines) * (1 + len(overlay)) + bool(scattered) <= 12:
        legend_outside(ax)  # beside the axes: no curve hidden
    ax.set_xlabel(axis_label(parameter, unit_of(parameter, units)))
    ax.set_ylabel(axis_label(metric, unit_of(metric, units)))
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return Path(path)

