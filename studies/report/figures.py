"""The one figure helper of the reports: a headless pyplot, axis labels with units, and a
saved figure that carries its caption into the report."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the headless backend)

DPI = 110


def pyplot():
    """matplotlib.pyplot on the headless Agg backend."""
    return plt


def axis_label(name: str, unit: str | None = None) -> str:
    """An axis label, 'name (unit)', or just the name for a dimensionless quantity."""
    return f"{name} ({unit})" if unit and unit != "-" else name


def legend_outside(ax, **options) -> None:
    """A legend beside the axes, so that it never hides a curve."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
              fontsize="small", **options)


def label(ax, x: tuple, y: tuple, legend_size=None) -> None:
    """Axis labels from (name, unit) pairs ``x`` and ``y``, a light grid and a legend inside
    the axes in ``legend_size`` points (None: no grid or legend)."""
    ax.set_xlabel(axis_label(*x))
    ax.set_ylabel(axis_label(*y))
    if legend_size is not None:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=legend_size)


def plan_view(ax) -> None:
    """A drawing in its plane: equal axes in mm, the legend beside them."""
    ax.set_aspect("equal")
    label(ax, ("x", "mm"), ("y", "mm"))
    legend_outside(ax)


def save(fig, path, caption: str) -> dict:
    """Save ``fig`` as ``path`` (PNG), close it and return the report's figure entry
    {"file": name, "caption": caption}."""
    if not caption or not caption.strip():
        raise ValueError(f"figure {Path(path).name}: a caption is required")
    fig.savefig(path, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return {"file": Path(path).name, "caption": caption.strip()}


def entry(name: str, caption: str) -> dict:
    """The report's entry of a file written elsewhere (e.g. a VTU field for ParaView)."""
    return {"file": name, "caption": caption}
