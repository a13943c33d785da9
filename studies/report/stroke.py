"""The stroke limits a mechanism's report section shows: how far it may move before its peak
stress reaches yield, and the amplitude it may cycle with for its material's fatigue life,
from the stress per unit stroke its analysis reports (linear scaling, fem/fatigue.py).

    limits = stroke_limits(598e6 / 180e-6, material("structural_steel"), "actuator elongation",
                           "m", "peak von Mises at the hinge fillets, 800 N, linear scaling")
    stroke_table([limits], "Stroke limits")   # the section's printed key table
    stroke_sentence(limits)                   # one line for the design summary

Every value is in SI units (m, or rad for a rotation); a material without fatigue data
(silicon) has no fatigue-limited stroke, and the text says so instead of printing a number.
"""
import math

from ...fem.fatigue import fatigue_stroke, yield_stroke
from .format import number


def stroke_limits(stress_per_stroke: float, material, stroke: str, unit: str, basis: str,
                  safety_factor: float = 1.0, mean_stroke: float = 0.0) -> dict:
    """{stroke, unit, stress_per_stroke (Pa per m or rad), basis, material, yield_strength,
    stroke_limit_yield, fatigue_strength, fatigue_cycles, fatigue_source, and
    stroke_limit_fatigue_goodman / _soderberg (amplitude about ``mean_stroke``; None without
    fatigue data)} of a stroke whose peak stress grows by ``stress_per_stroke``."""
    fatigue = {c: fatigue_stroke(stress_per_stroke, material, mean_stroke, c, safety_factor)
               for c in ("goodman", "soderberg")}
    return {"stroke": stroke, "unit": unit, "stress_per_stroke": stress_per_stroke,
            "basis": basis, "material": material.name, "safety_factor": safety_factor,
            "mean_stroke": mean_stroke, "yield_strength": material.yield_strength,
            "stroke_limit_yield": yield_stroke(stress_per_stroke, material.yield_strength,
                                               safety_factor),
            "fatigue_strength": material.fatigue_strength,
            "fatigue_cycles": material.fatigue_cycles,
            "fatigue_source": material.fatigue_source,
            "stroke_limit_fatigue_goodman": fatigue["goodman"],
            "stroke_limit_fatigue_soderberg": fatigue["soderberg"]}


def show(value, unit: str) -> str:
    """A stroke in the unit a designer reads it in (rotations in degrees)."""
    if unit == "rad" and isinstance(value, (int, float)):
        return number(math.degrees(value), "deg")
    return number(value, unit)


def _per_stroke(limits: dict) -> str:
    if limits["unit"] == "rad":
        return f"{number(limits['stress_per_stroke'] * math.pi / 180, 'Pa')} per deg"
    per_mm = limits["stress_per_stroke"] * 1e-3
    if per_mm >= 1e9:
        return f"{number(per_mm * 1e-3, 'Pa')} per um"
    return f"{number(per_mm, 'Pa')} per mm"


def _fatigue(limits: dict) -> str:
    if limits["stroke_limit_fatigue_goodman"] is None:
        return "no fatigue data for this material"
    amplitude = show(limits["stroke_limit_fatigue_goodman"], limits["unit"])
    cycles = f"{limits['fatigue_cycles']:.0e}".replace("e+0", "e").replace("e+", "e")
    return f"±{amplitude} for {cycles} cycles"


def stroke_table(limits: list, title: str = "Stroke limits (linear scaling)") -> dict:
    """The section's key table: one row per stroke, strings formatted for reading."""
    rows = []
    for s in limits:
        soderberg = s["stroke_limit_fatigue_soderberg"]
        differs = soderberg is not None and soderberg != s["stroke_limit_fatigue_goodman"]
        rows.append([s["stroke"], _per_stroke(s), show(s["stroke_limit_yield"], s["unit"]),
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
    return "Fatigue data: " + "; ".join(
        f"{name}: {source or 'none (no endurance limit for this material)'}"
        for name, source in seen.items())


def stroke_sentence(limits: list) -> str:
    """'Stroke limits (yield; fatigue, Goodman, fully reversed): actuator elongation 59.1 um;
    ±47.3 um for 1e6 cycles (structural_steel)', one line for the design summary; the
    section's table gives the stress basis and the fatigue data's source."""
    parts = [f"{s['stroke']} {show(s['stroke_limit_yield'], s['unit'])}; {_fatigue(s)} "
             f"({s['material']})" for s in limits]
    return ("Stroke limits (before yield; fatigue amplitude, Goodman, fully reversed; stress "
            "basis and fatigue data in the audit): " + " | ".join(parts) + ".")


def fatigue_stress(limits: dict):
    """The stress amplitude (Pa) the fatigue-limited stroke reaches (Goodman), or None."""
    amplitude = limits["stroke_limit_fatigue_goodman"]
    return None if amplitude is None else limits["stress_per_stroke"] * amplitude


def plot_stroke_limits(limits: list, path, caption: str | None = None) -> dict:
    """Peak stress against stroke for each stroke of ``limits`` (one panel each, at most
    three; linear scaling: stress = stress_per_stroke x stroke) up to 1.25 times the
    yield-limited stroke, with the yield strength and the fatigue-limited stress amplitude
    (Goodman) drawn across and their strokes marked. Returns the figure entry."""
    from .figures import axis_label, pyplot, save

    plt = pyplot()
    shown = limits[:3]
    fig, axes = plt.subplots(1, len(shown), figsize=(4.2 * len(shown), 3.0), squeeze=False)
    for ax, s in zip(axes[0], shown):
        scale, unit = (180 / math.pi, "deg") if s["unit"] == "rad" else (1e6, "um")
        if s["unit"] == "m" and s["stroke_limit_yield"] > 2e-3:
            scale, unit = 1e3, "mm"
        top = 1.25 * s["stroke_limit_yield"]
        ax.plot([0, top * scale], [0, s["stress_per_stroke"] * top / 1e6], "-",
                label="peak stress (linear)")
        ax.axhline(s["yield_strength"] / 1e6, color="tab:red", lw=1,
                   label=f"yield {s['yield_strength'] / 1e6:.0f} MPa")
        ax.axvline(s["stroke_limit_yield"] * scale, color="tab:red", ls=":", lw=1)
        stress = fatigue_stress(s)
        if stress is not None:
            cycles = f"{s['fatigue_cycles']:.0e}".replace("e+0", "e").replace("e+", "e")
            ax.axhline(stress / 1e6, color="tab:green", lw=1,
                       label=f"fatigue amplitude {stress / 1e6:.0f} MPa ({cycles} cycles)")
            ax.axvline(s["stroke_limit_fatigue_goodman"] * scale, color="tab:green", ls=":",
                       lw=1)
        ax.set_xlabel(axis_label(s["stroke"], unit), fontsize=8)
        ax.set_ylabel(axis_label("peak von Mises", "MPa"), fontsize=8)
        ax.set_xlim(0, top * scale)
        ax.set_ylim(0, None)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6.5, loc="upper left")
    fig.tight_layout()
    return save(fig, path, caption or (
        "Stroke limits: the peak stress grows with the stroke (linear scaling of the "
        "section's solve) until it reaches the yield strength (red) or, cycled fully "
        "reversed, the fatigue-limited amplitude (Goodman, green); dotted: the strokes "
        "where each is reached (" + "; ".join(f"{s['stroke']}: {s['basis']}"
                                              for s in shown) + ")."))

