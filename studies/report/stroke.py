"""The stroke limits a mechanism's report section shows: how far it may move before its peak
stress reaches yield, and the amplitude it may cycle with for its material's fatigue life.
A linear flexure gives its stress per unit stroke (linear scaling, fem/fatigue.py); a
preloaded one (a compressed leaf) its peak stress at computed large-deflection states and the
preload's mean stress (:func:`curve_stroke_limits`).

    limits = stroke_limits(598e6 / 180e-6, material("structural_steel"), "actuator elongation",
                           "m", "peak von Mises at the hinge fillets, 800 N, linear scaling")
    stroke_table([limits], "Stroke limits")   # the section's printed key table
    stroke_sentence(limits)                   # one line for the design summary

Every value is in SI units (m, or rad for a rotation); a material without fatigue data
(silicon) has no fatigue-limited stroke, and the text says so instead of printing a number; a
limit beyond the last computed state is printed as "> (that state)".
"""
import math

import numpy as np

from ...fem.fatigue import (fatigue_stroke, fatigue_stroke_curve, yield_stroke,
                            yield_stroke_curve)
from .format import number


def _entry(material, stroke: str, unit: str, basis: str, safety_factor: float,
           mean_stroke: float) -> dict:
    return {"stroke": stroke, "unit": unit, "basis": basis, "material": material.name,
            "safety_factor": safety_factor, "mean_stroke": mean_stroke,
            "yield_strength": material.yield_strength,
            "fatigue_strength": material.fatigue_strength,
            "fatigue_cycles": material.fatigue_cycles,
            "fatigue_source": material.fatigue_source}


def stroke_limits(stress_per_stroke: float, material, stroke: str, unit: str, basis: str,
                  safety_factor: float = 1.0, mean_stroke: float = 0.0) -> dict:
    """{stroke, unit, stress_per_stroke (Pa per m or rad), basis, material, yield_strength,
    stroke_limit_yield, fatigue_strength, fatigue_cycles, fatigue_source, and
    stroke_limit_fatigue_goodman / _soderberg (amplitude about ``mean_stroke``; None without
    fatigue data)} of a stroke whose peak stress grows by ``stress_per_stroke``."""
    fatigue = {c: fatigue_stroke(stress_per_stroke, material, mean_stroke, c, safety_factor)
               for c in ("goodman", "soderberg")}
    return {**_entry(material, stroke, unit, basis, safety_factor, mean_stroke),
            "stress_per_stroke": stress_per_stroke,
            "stroke_limit_yield": yield_stroke(stress_per_stroke, material.yield_strength,
                                               safety_factor),
            "stroke_limit_fatigue_goodman": fatigue["goodman"],
            "stroke_limit_fatigue_soderberg": fatigue["soderberg"]}


def curve_stroke_limits(strokes, peak_stresses, material, stroke: str, unit: str, basis: str,
                        preload_stress: float = 0.0, safety_factor: float = 1.0,
                        mean_stroke: float = 0.0) -> dict:
    """The keys of :func:`stroke_limits` for a preloaded flexure whose peak von Mises (Pa) is
    known at computed states ``strokes`` (m or rad, > 0, increasing) with the preload's mean
    stress ``preload_stress`` (Pa, < 0 compressive) at its peak point (fem/fatigue.py:
    interpolated between the states, never beyond them); stress_per_stroke is None, the
    curve is kept (curve_strokes, curve_peak_stress_Pa) and stroke_limit_yield_reached /
    stroke_limit_fatigue_reached say whether a computed state reaches each limit (else the
    limit printed is a lower bound, the last state)."""
    at_yield, reached = yield_stroke_curve(strokes, peak_stresses, material.yield_strength,
                                           safety_factor, preload_stress)
    fatigue = {c: fatigue_stroke_curve(strokes, peak_stresses, material, preload_stress,
                                       mean_stroke, c, safety_factor)
               for c in ("goodman", "soderberg")}
    return {**_entry(material, stroke, unit, basis, safety_factor, mean_stroke),
            "stress_per_stroke": None, "preload_stress_Pa": float(preload_stress),
            "curve_strokes": [float(x) for x in strokes],
            "curve_peak_stress_Pa": [float(s) for s in peak_stresses],
            "stroke_limit_yield": at_yield, "stroke_limit_yield_reached": reached,
            "stroke_limit_fatigue_goodman": fatigue["goodman"][0],
            "stroke_limit_fatigue_soderberg": fatigue["soderberg"][0],
            "stroke_limit_fatigue_reached": all(f[1] for f in fatigue.values())}


def show(value, unit: str) -> str:
    """A stroke in the unit a designer reads it in (rotations in degrees)."""
    if unit == "rad" and isinstance(value, (int, float)):
        return number(math.degrees(value), "deg")
    return number(value, unit)


def _limit(limits: dict, key: str, sign: str = "") -> str:
    """A limit ('±' with ``sign``), '> x' where no computed state reaches it."""
    text = sign + show(limits[key], limits["unit"])
    reached = limits.get(("stroke_limit_yield" if key == "stroke_limit_yield"
                          else "stroke_limit_fatigue") + "_reached", True)
    return text if reached else f"> {text} (last computed state)"


def _per_stroke(limits: dict) -> str:
    if limits["stress_per_stroke"] is None:
        return (f"nonlinear (computed states); preload's mean "
                f"{number(limits['preload_stress_Pa'], 'Pa')}")
    if limits["unit"] == "rad":
        return f"{number(limits['stress_per_stroke'] * math.pi / 180, 'Pa')} per deg"
    per_mm = limits["stress_per_stroke"] * 1e-3
    if per_mm >= 1e9:
        return f"{number(per_mm * 1e-3, 'Pa')} per um"
    return f"{number(per_mm, 'Pa')} per mm"


def _cycles(limits: dict) -> str:
    return f"{limits['fatigue_cycles']:.0e}".replace("e+0", "e").replace("e+", "e")


def _fatigue(limits: dict) -> str:
    if limits["stroke_limit_fatigue_goodman"] is None:
        return "no fatigue data for this material"
    return f"{_limit(limits, 'stroke_limit_fatigue_goodman', '±')} for {_cycles(limits)} cycles"


def stroke_table(limits: list, title: str = "Stroke limits (linear scaling)") -> dict:
    """The section's key table: one row per stroke, strings formatted for reading."""
    rows = []
    for s in limits:
        soderberg = s["stroke_limit_fatigue_soderberg"]
        differs = soderberg is not None and soderberg != s["stroke_limit_fatigue_goodman"]
        rows.append([s["stroke"], _per_stroke(s), _limit(s, "stroke_limit_yield"),
                     _fatigue(s) + (f" (Soderberg ±{show(soderberg, s['unit'])})"
                                    if differs else ""),
                     s["basis"]])
    return {"title": title,
            "columns": ["stroke", "peak stress per unit stroke",
                        "before yield (safety factor 1)",
                        "fatigue-limited amplitude (Goodman, fully reversed)", "stress basis"],
            "rows": rows}


def fatigue_note(limits: list) -> str:
    """Where the fatigue and strength data of the table come from (data/materials.toml)."""
    seen = {s["material"]: s["fatigue_source"] for s in limits}
    compressive = any(s.get("preload_stress_Pa", 0.0) < 0 for s in limits)
    return "Fatigue data: " + "; ".join(
        f"{name}: {source or 'none (no endurance limit for this material)'}"
        for name, source in seen.items()) + (
        ". A compressive mean (a preload) allows sigma_a = Se / n if the first cycle does not "
        "yield, sigma_a + |sigma_m| <= Sy / n (Budynas and Nisbett, Shigley's Mechanical "
        "Engineering Design, 9th ed., Section 6-12)" if compressive else "")


def stroke_sentence(limits: list) -> str:
    """'Stroke limits (yield; fatigue, Goodman, fully reversed): actuator elongation 59.1 um;
    ±47.3 um for 1e6 cycles (structural_steel)', one line for the design summary; the
    section's table gives the stress basis and the fatigue data's source."""
    parts = [f"{s['stroke']} {_limit(s, 'stroke_limit_yield')}; {_fatigue(s)} "
             f"({s['material']})" for s in limits]
    return ("Stroke limits (before yield; fatigue amplitude, Goodman, fully reversed; stress "
            "basis and fatigue data in the audit): " + " | ".join(parts) + ".")


def peak_stress(limits: dict, stroke: float) -> float:
    """The peak stress (Pa) at ``stroke`` (m or rad): linear, or the computed states'
    curve interpolated (from the preload's stress at 0)."""
    if limits["stress_per_stroke"] is not None:
        return limits["stress_per_stroke"] * stroke
    x = [0.0] + limits["curve_strokes"]
    S = [abs(limits["preload_stress_Pa"])] + limits["curve_peak_stress_Pa"]
    return float(np.interp(stroke, x, S))


def fatigue_stress(limits: dict):
    """The peak stress (Pa) the fatigue-limited stroke reaches (Goodman), or None."""
    amplitude = limits["stroke_limit_fatigue_goodman"]
    return None if amplitude is None else peak_stress(limits, amplitude)


COLORS = ("tab:blue", "tab:orange", "tab:purple", "tab:brown", "tab:gray", "tab:olive",
          "tab:cyan", "tab:pink")


def _scale(s: dict) -> tuple[float, str]:
    if s["unit"] == "rad":
        return 180 / math.pi, "deg"
    return (1e3, "mm") if s["stroke_limit_yield"] > 2e-3 else (1e6, "um")


def _draw(ax, s: dict, scale: float, top: float, color: str, label: str) -> None:
    """One stroke's peak stress (MPa) to ``top`` (its curve only to its last state), with its
    yield (x) and fatigue-limited (diamond) strokes marked."""
    if s["stress_per_stroke"] is None:
        x = np.array([0.0] + [v for v in s["curve_strokes"] if v < top]
                     + [min(top, s["curve_strokes"][-1])])
        ax.plot(x * scale, [peak_stress(s, v) / 1e6 for v in x], "-", color=color, label=label)
        ax.plot(np.array(s["curve_strokes"]) * scale, np.array(s["curve_peak_stress_Pa"]) / 1e6,
                "o", color=color, ms=3, mfc="none")
    else:
        ax.plot([0, top * scale], [0, s["stress_per_stroke"] * top / 1e6], "-", color=color,
                label=label)
    marks = [(s["stroke_limit_yield"], "x", "tab:red")]
    if s["stroke_limit_fatigue_goodman"] is not None:
        marks.append((s["stroke_limit_fatigue_goodman"], "D", "tab:green"))
    for at, marker, edge in marks:
        if at <= top:
            ax.plot(at * scale, peak_stress(s, at) / 1e6, marker, color=edge, ms=6, mew=1.5,
                    mfc="none")


def _panel(ax, shown: list) -> None:
    """The strokes ``shown`` (one unit) on one axes: curves, yield and fatigue stresses."""
    from .figures import axis_label

    scale, unit = _scale(shown[0])
    top = 1.25 * max(s["stroke_limit_yield"] for s in shown)
    for s, color in zip(shown, COLORS):  # neither red nor green: the marks' colours
        _draw(ax, s, scale, top, color, "peak stress" if len(shown) == 1 else s["stroke"])
    for strength in sorted({s["yield_strength"] for s in shown}):
        ax.axhline(strength / 1e6, color="tab:red", lw=1, label=f"yield {strength / 1e6:.0f} MPa")
    stresses = {round(fatigue_stress(s) / 1e6) for s in shown if fatigue_stress(s) is not None}
    if len(stresses) == 1:
        s = next(s for s in shown if fatigue_stress(s) is not None)
        ax.axhline(fatigue_stress(s) / 1e6, color="tab:green", lw=1,
                   label=f"fatigue-limited peak {stresses.pop():.0f} MPa ({_cycles(s)} cycles)")
    ax.plot([], [], "x", color="tab:red", mew=1.5, label="yield-limited stroke")
    if any(s["stroke_limit_fatigue_goodman"] is not None for s in shown):
        ax.plot([], [], "D", color="tab:green", mfc="none", mew=1.5,
                label="fatigue-limited amplitude")
    name = (shown[0]["stroke"] if len(shown) == 1 else
            "rotation" if shown[0]["unit"] == "rad" else "stroke")
    ax.set_xlabel(axis_label(name, unit), fontsize=8)
    ax.set_ylabel(axis_label("peak von Mises", "MPa"), fontsize=8)
    ax.set_xlim(0, top * scale)
    ax.set_ylim(0, 1.3 * max(s["yield_strength"] for s in shown) / 1e6)
    ax.tick_params(labelsize=7)
    ax.grid(alpha=0.3)
    if len(shown) == 1:
        ax.legend(fontsize=6, loc="upper left")
    else:
        ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)


def plot_stroke_limits(limits: list, path, caption: str | None = None,
                       together: bool = False) -> dict:
    """Peak stress against stroke for each stroke of ``limits`` (one panel each, at most
    three; ``together``: all on one panel, which needs one unit) up to 1.25 times the largest
    yield-limited stroke: linear scaling (a line), or the computed states (circles, a curve
    never drawn beyond them); the yield strength and the peak stress at the fatigue-limited
    amplitude drawn across, the yield-limited (x) and fatigue-limited (diamond) strokes
    marked. Returns the figure entry."""
    from .figures import pyplot, save

    plt = pyplot()
    if together and (len({s["unit"] for s in limits}) > 1 or len(limits) > len(COLORS)):
        raise ValueError(f"strokes drawn together must share one unit, at most {len(COLORS)}")
    panels = [limits] if together else [[s] for s in limits[:3]]
    size = (6.4, 2.8) if together else (4.2 * len(panels), 3.0)
    fig, axes = plt.subplots(1, len(panels), figsize=size, squeeze=False)
    for ax, shown in zip(axes[0], panels):
        _panel(ax, shown)
    fig.tight_layout()
    shown = [s for p in panels for s in p]
    return save(fig, path, caption or (
        "Stroke limits: the peak stress grows with the stroke until it reaches the yield "
        "strength (red, x) or, cycled about the working position, the stress of the "
        "fatigue-limited amplitude (Goodman; green, diamond) (" + "; ".join(
            f"{s['stroke']}: {s['basis']}" for s in shown) + ")."))

