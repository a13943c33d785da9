"""What each mode of a report's table is, from its effective masses: the direction the mass
moves in, or an internal mode (parts moving against each other, no net motion of the mass).

    describe_mode(fractions=[0.0007, 0.0], axes="xy")   # 'internal: ...'
    mode_table(freqs, effective_mass, total_mass, "xy", working=2, title="DBMA modes")
"""
from .format import number

INTERNAL = 0.01  # below 1 % of the mass in every direction: an internal mode


def describe_mode(fractions, axes: str = "xyz", working: bool = False,
                  working_name: str = "working mode") -> str:
    """One phrase: the working mode, the dominant effective-mass direction, or internal."""
    k = max(range(len(fractions)), key=lambda i: fractions[i])
    if working:
        return f"{working_name}: the mass moves along {axes[k]}"
    if fractions[k] < INTERNAL:
        return ("internal: parts move against each other, no net motion of the mass (under "
                "1 % in every direction)")
    return f"along {axes[k]} ({100 * fractions[k]:.0f} % of the mass)"


def _percent(fraction: float) -> str:
    return "< 0.01 %" if 100 * fraction < 0.01 else f"{100 * fraction:.2g} %"


def mode_table(frequencies, effective_mass, total_mass: float, axes: str, title: str,
               working: int | None = None, working_name: str = "working mode") -> dict:
    """A report key table: mode, frequency, effective-mass fraction per direction (%), what
    the mode is (``working``: its 1-based number)."""
    rows = []
    for k, (f, masses) in enumerate(zip(frequencies, effective_mass)):
        fractions = [m / total_mass for m in masses][:len(axes)]
        rows.append([k + 1, number(f, "Hz")] + [_percent(v) for v in fractions]
                    + [describe_mode(fractions, axes, k + 1 == working, working_name)])
    return {"title": title,
            "columns": ["mode", "frequency"] + [f"effective mass along {a}" for a in axes]
                       + ["what it is"],
            "rows": rows}
