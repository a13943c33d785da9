"""``reproduce()`` of the DBMA dynamics section: output compliance, the FRF from actuator
force to output with its damping sensitivity, the bandwidth beside the paper's, and hinge
buckling at 800 N (:mod:`.dynamics`)."""
import math
from pathlib import Path

import numpy as np

from ..engine.tables import write_rows
from ..report.comparison import Comparison, rows as comparison_rows
from ..report.figures import axis_label, legend_outside, pyplot, save
from .dynamics import frf_study


def plot_frf(out: dict, curves: list, path: Path) -> dict:
    """|H| and phase of output / actuator force for each damping ratio."""
    plt = pyplot()
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    for c in curves:
        label = rf"$\zeta$ = {100 * c['damping']:.3g} %"
        ax.semilogy(c["frf_frequencies_hz"], np.array(c["amplitude_m_per_n"]) * 1e6, label=label)
        ax2.plot(c["frf_frequencies_hz"], np.degrees(c["phase_rad"]), label=label)
    p = out["paper"]
    for a in (ax, ax2):
        a.axvline(p["fn_measured_hz"], color="k", ls=":", lw=1, label=r"paper: measured $f_n$")
        a.axvline(p["bandwidth_hz"], color="gray", ls="--", lw=1, label="paper: bandwidth")
    ax.set_ylabel(r"$|H|$ = output / actuator force ($\mu$m/N)")
    ax2.set_ylabel(r"phase of $H$ (deg)")
    ax2.set_xlabel(axis_label("frequency", "Hz"))
    legend_outside(ax)
    return save(fig, path, (
        f"Output displacement per actuator force ({out['dim']}-D FEM, actuator rod "
        f"{out['actuator_stiffness']:.2g} N/m between the pads, modal damping as labelled): "
        f"resonance {out['resonance_hz']:.0f} Hz, -3 dB bandwidth "
        f"{out['bandwidth_minus3db_hz']:.0f} Hz at 2 %, beside the paper's measured natural "
        f"frequency {p['fn_measured_hz']:.4g} Hz and its 'response bandwidth up to "
        f"{p['bandwidth_hz']:.0f} Hz'."))


def comparisons(out: dict) -> list[Comparison]:
    """The dynamics beside the paper's numbers."""
    p, o, b = out["paper"], out["output"], out["buckling"]
    C = Comparison
    return [
        C("DBMA: FRF static limit (output / actuator force at 0 Hz)", out["static_m_per_n"],
          out["static_output_m_per_n"], "m/N", "the static solve of the same model",
          "derived", tolerance=1e-6, note="the modal FRF keeps the static correction"),
        C("DBMA: resonance of output / actuator force (actuator rod in place)",
          out["resonance_hz"], p["fn_measured_hz"], "Hz", "Section 5, Fig. 18 (measured)",
          tolerance=0.1, headline=True,
          note=f"the paper gives no actuator stiffness: an assumed {out['actuator_stiffness']:.2g}"
               " N/m rod holds only the pads' mean motion; pads held over their faces give "
               f"{out['working_frequency_pads_held_hz']:.0f} Hz (paper's FEM "
               f"{p['fn_fem_hz']:.5g} Hz)"),
        C("DBMA: -3 dB bandwidth (|H| below |H(0)|/sqrt 2 past the resonance)",
          out["bandwidth_minus3db_hz"], p["bandwidth_hz"], "Hz",
          "Abstract and Conclusions: 'response bandwidth up to 300 Hz'", tolerance=0.1,
          headline=True, note=f"modal damping {100 * out['damping']:.3g} % (assumed); flat "
          f"within 3 dB up to {out['flat_bandwidth_hz']:.0f} Hz"),
        C("DBMA: half-power width of the resonance", out["half_power_bandwidth_hz"],
          2 * out["damping"] * out["resonance_hz"], "Hz", "2 zeta f_n (one mode)", "derived",
          tolerance=0.05),
        C("DBMA: hinge buckling factor at the paper's 800 N", b["factor"], 1.0, "-",
          "Section 4, Fig. 14: 0-800 N", "derived", limit="lower",
          note=f"critical actuator force {b['critical_force_n'] / 1e3:.3g} kN (linear buckling, "
               "pads free)"),
        C("DBMA: output stiffness (mount held, actuator rod in place)", o["k_out"], o["k_out"],
          "N/m", "flexfem", "input", note=f"lateral {o['k_lateral']:.3g} N/m; parasitic "
          f"lateral {o['parasitic_lateral']:.2g} m/m, rotation {o['parasitic_rotation']:.2g} "
          "rad/m per unit output motion"),
    ]


def paragraph(out: dict) -> str:
    o, b = out["output"], out["buckling"]
    s = {round(100 * r["damping"]): r for r in out.get("sensitivity", [])}
    spread = ", ".join(f"{k} %: {r['bandwidth_minus3db_hz']:.0f} Hz" for k, r in s.items())
    return (
        "The amplifier as a servo-valve drive. The paper's resonance happens with its "
        "magnetostrictive actuator between the pads, so the actuator is modelled as its rod's "
        f"axial stiffness ({out['actuator_stiffness']:.2g} N/m, assumed) in parallel with its "
        f"force. The output then moves {out['static_output_m_per_n'] * 1e6:.3g} um per N of "
        f"actuator force at low frequency and resonates at {out['resonance_hz']:.0f} Hz (pads "
        f"held: {out['working_frequency_pads_held_hz']:.0f} Hz); the response falls 3 dB "
        f"below its static value at {out['bandwidth_minus3db_hz']:.0f} Hz with 2 % modal "
        f"damping ({spread}). Its output stiffness is {o['k_out']:.3g} N/m and the output "
        f"turns by {o['parasitic_rotation']:.2g} rad per m of stroke; the hinges buckle at "
        f"{b['factor']:.3g} times the paper's 800 N.")


def reproduce(out_dir, quick: bool = False) -> dict:
    """Run :func:`.dynamics.frf_study` (2-D; quick: mesh size factor 2) and write the FRF
    figure and tables; the section summary."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    out = frf_study(dim=2, size_factor=2.0 if quick else 1.0, sweep=not quick)
    figures = [plot_frf(out, out["sensitivity"], out_dir / "dbma_frf.png")]
    write_rows(out_dir / "dbma_frf.csv",
               [{"frequency_hz": f, "amplitude_m_per_n": a, "phase_rad": ph} for f, a, ph in
                zip(out["frf_frequencies_hz"], out["amplitude_m_per_n"], out["phase_rad"])])
    damping_rows = [{k: v for k, v in r.items() if not isinstance(v, list)}
                    for r in out["sensitivity"]]
    write_rows(out_dir / "dbma_frf_damping.csv", damping_rows)
    summary = {k: v for k, v in out.items() if not isinstance(v, list)}
    summary["sensitivity"] = damping_rows
    tables = ["dbma_frf.csv", "dbma_frf_damping.csv"]
    notes = []
    if "actuator_sweep" in out:
        write_rows(out_dir / "dbma_actuator_sweep.csv", out["actuator_sweep"])
        tables.append("dbma_actuator_sweep.csv")
        summary["actuator_sweep"] = out["actuator_sweep"]
        notes.append(sweep_note(out))
    return {"paragraph": paragraph(out), "figures": figures,
            "comparisons": comparison_rows(comparisons(out)),
            "tables": tables, "notes": notes, "dynamics": summary}


def sweep_note(out: dict) -> str:
    """The actuator stiffness the paper's measured resonance asks for (log interpolation)."""
    rows, target = out["actuator_sweep"], out["paper"]["fn_measured_hz"]
    f = [r["working_frequency_hz"] for r in rows]
    k = [math.log10(r["actuator_stiffness"]) for r in rows]
    text = ", ".join(f"{r['actuator_stiffness']:.2g} N/m: {r['working_frequency_hz']:.0f} Hz"
                     for r in rows)
    if f[0] <= target <= f[-1]:
        need = 10 ** float(np.interp(target, f, k))
        return (f"Working frequency against the actuator rod's stiffness ({text}): the paper's "
                f"measured {target:.4g} Hz asks for about {need:.2g} N/m.")
    return (f"Working frequency against the actuator rod's stiffness ({text}): no rod "
            f"stiffness reaches the paper's measured {target:.4g} Hz; a rigid rod, which "
            "holds only the pads' mean elongation, tends to about "
            f"{f[-1]:.0f} Hz, while the pads held along x over their faces (their tilt held "
            f"too) give {out['working_frequency_pads_held_hz']:.0f} Hz: the paper's resonance "
            "asks the actuator's end caps to hold the pads' tilt as well.")
