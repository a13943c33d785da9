"""The DBMA as a servo-valve drive: output stiffness and parasitic motion, the frequency
response from actuator force to output displacement, its bandwidth beside the paper's, and
the hinges' buckling at the paper's 800 N.

    out = frf_study(dim=2, damping=0.02)
    out["resonance_hz"], out["bandwidth_minus3db_hz"], out["buckling"]["factor"]

The actuator in place. The paper's resonance (305-314 Hz) happens with its giant
magnetostrictive actuator between the pads; without it the pads are free and the working
mode falls near 110 Hz (docs/dbma.md). The actuator is modelled as a force source F in
parallel with its rod's axial stiffness k_a (data/dbma_paper.toml [actuator_assumed], not in
the paper): K + k_a w w^T, w the weights of the pads' mean x displacements with
w . u = elongation (m). Its mass is left out. The FRF is then output y per actuator force
(m/N); at 0 Hz it equals the static output / force of the same model.

Damping: the paper prints none. A modal damping ratio zeta (default 2 %, steel part bolted
at its mount; data [damping_assumed]) with its sensitivity 1 %, 2 %, 5 %.

Bandwidth. The paper's "response bandwidth up to 300 Hz" (Abstract, Conclusions) stands
beside its resonance 305-314 Hz: it reads as "usable up to the resonance". flexfem reports:
``resonance_hz`` (the peak of |H|), ``half_power_bandwidth_hz`` (width of that peak at
peak / sqrt 2, = 2 zeta f_n for one mode), ``bandwidth_minus3db_hz`` (the first frequency
above the resonance where |H| falls below |H(0)| / sqrt 2: the usual low-pass bandwidth) and
``flat_bandwidth_hz`` (the highest frequency below the resonance with |H| within 3 dB of
|H(0)|: the response is flat, i.e. a servo loop's usable band).
"""
import math

import numpy as np

from ...fem import compliance_matrix, solve_buckling, solve_harmonic, solve_modes, solve_static
from ...fem.springs import group_spring
from ...geometry.dbma.params import paper_design
from .analysis import (OUTPUT_AXIS, actuator_loads, build_model, modal_supports, published,
                       static_supports)

N_MODES = 12


def assumed() -> dict:
    """(actuator stiffness N/m, default damping ratio, sensitivity ratios) from the data."""
    data = published()
    return {"actuator_stiffness": float(data["actuator_assumed"]["stiffness_N_per_m"]),
            "damping": float(data["damping_assumed"]["ratio"]),
            "sensitivity": [float(z) for z in data["damping_assumed"]["sensitivity"]]}


def with_actuator(model, stiffness: float):
    """A copy of ``model`` whose stiffness has the actuator rod (``stiffness``, N/m) between
    the pads, acting on their mean x motion."""
    return model.with_stiffness(group_spring(model, "input_a", "input_b", stiffness, "x"))


def output_compliance(model) -> dict:
    """The output face's compliance (mount held, actuator in place): output stiffness along
    y (N/m, x and rotation free), lateral support stiffness (N/m, y held), parasitic lateral
    motion (m/m) and rotation (rad/m) per unit output motion, the matrix and its point."""
    c = compliance_matrix(model, static_supports(), "output")
    n = model.dim
    direction = np.eye(n)[OUTPUT_AXIS]
    k_out, k_lateral = c.support_stiffness(direction)
    across, rotation = c.parasitic(direction)
    if n == 3:
        across, rotation = float(np.linalg.norm(across)), float(np.linalg.norm(rotation))
    return {"k_out": k_out, "k_lateral": k_lateral, "parasitic_lateral": float(across),
            "parasitic_rotation": float(rotation), "matrix": c.matrix.tolist(),
            "point_m": c.point.tolist()}


def frequency_grid(f_n: float, zeta: float, f_max: float) -> np.ndarray:
    """0..f_max (Hz) on 401 points, plus 201 points within +-6 zeta f_n of ``f_n``."""
    near = f_n * (1.0 + np.linspace(-6.0, 6.0, 201) * max(zeta, 1e-3))
    return np.unique(np.concatenate([np.linspace(0.0, f_max, 401), near[near > 0]]))


def _first_below(f, a, level, start: int) -> float:
    """The first frequency at or after index ``start`` where ``a`` falls below ``level``
    (linear interpolation), nan if none."""
    below = np.flatnonzero(a[start:] < level)
    if len(below) == 0:
        return math.nan
    j = start + below[0]
    return float(f[j - 1] + (level - a[j - 1]) * (f[j] - f[j - 1]) / (a[j] - a[j - 1]))


def bandwidths(frf) -> dict:
    """resonance_hz, half_power_bandwidth_hz, bandwidth_minus3db_hz, flat_bandwidth_hz and
    the static response (m/N) of one FRF (see the module)."""
    f, a = frf.frequencies_hz, frf.amplitude
    peaks = frf.peaks()
    if len(peaks) == 0:
        raise ValueError("the FRF has no resonance in its frequency range")
    resonance = float(peaks[0])
    k = int(np.argmin(np.abs(f - resonance)))
    static = float(a[0])
    flat = np.flatnonzero(a[:k] > math.sqrt(2) * static)
    return {"static_m_per_n": float(frf.response[0].real), "resonance_hz": resonance,
            "peak_m_per_n": float(a[k]), "amplification_at_resonance": float(a[k] / static),
            "half_power_bandwidth_hz": frf.bandwidth(resonance),
            "bandwidth_minus3db_hz": _first_below(f, a, static / math.sqrt(2), k),
            "flat_bandwidth_hz": float(f[flat[0] - 1]) if len(flat) else resonance}


def frf(model, zeta: float, f_n: float, f_max: float) -> dict:
    """The FRF (output y per actuator force) with modal damping ``zeta``: bandwidths and the
    sampled amplitude (m/N) and phase (rad)."""
    freqs = frequency_grid(f_n, zeta, f_max)
    result = solve_harmonic(model, static_supports(), actuator_loads(1.0, model.dim), freqs,
                            damping=zeta, n_modes=N_MODES)
    response = result.frf("output", OUTPUT_AXIS)
    return {"damping": zeta, **bandwidths(response),
            "frf_frequencies_hz": response.frequencies_hz.tolist(),
            "amplitude_m_per_n": response.amplitude.tolist(), "phase_rad": response.phase.tolist()}


def hinge_buckling(model, force: float) -> dict:
    """Linear buckling of the hinges under the actuator force ``force`` (N) on free pads (the
    paper's static load case, Fig. 14): the lowest factor and critical actuator force."""
    b = solve_buckling(model, static_supports(), actuator_loads(force, model.dim), n=1)
    return {"force_n": force, "factor": float(b.load_factors[0]),
            "critical_force_n": float(force * b.load_factors[0])}


def working_frequency(model, supports=None) -> tuple[float, list]:
    """(frequency (Hz) of the mode with the largest effective mass along y, first modes);
    ``supports`` default the mount held, pads free (the actuator's rod in the model)."""
    modes = solve_modes(model, 6, supports or static_supports())
    k = int(np.argmax(modes.effective_mass[:, OUTPUT_AXIS]))
    return float(modes.frequencies_hz[k]), [float(f) for f in modes.frequencies_hz]


def actuator_sweep(bare, stiffnesses=(1e7, 4e7, 1.6e8, 6.4e8, 2.56e9)) -> list:
    """The working frequency (Hz) with the actuator rod's stiffness (N/m) at each of
    ``stiffnesses``: [{"actuator_stiffness", "working_frequency_hz"}]."""
    return [{"actuator_stiffness": float(k),
             "working_frequency_hz": working_frequency(with_actuator(bare, k))[0]}
            for k in stiffnesses]


def frf_study(damping: float | None = None, dim: int = 2, size_factor: float = 1.0,
              sensitivity: bool = True, buckling: bool = True, params=None,
              sweep: bool = False) -> dict:
    """The dynamics study (see the module), SI units; ``damping`` default the data's 2 %.
    Keys: dim, dofs, damping, actuator_stiffness (N/m), working_frequency_hz (actuator rod in
    place), working_frequency_pads_held_hz (pads held along x: a rigid actuator, the bound),
    modal_frequencies_hz (first six), output {k_out, k_lateral, parasitic_lateral,
    parasitic_rotation, matrix, point_m}, static_output_m_per_n, the FRF's bandwidths
    (:func:`bandwidths`) and samples (frf_frequencies_hz, amplitude_m_per_n, phase_rad), paper {fn_fem_hz, fn_measured_hz, bandwidth_hz},
    sensitivity (bandwidths and samples per damping ratio), buckling (:func:`hinge_buckling`)
    and, with ``sweep``, actuator_sweep (:func:`actuator_sweep`)."""
    data, a = published(), assumed()
    zeta = a["damping"] if damping is None else float(damping)
    if not (math.isfinite(zeta) and 0 < zeta < 1):
        raise ValueError(f"damping = {damping!r} must be a modal damping ratio in (0, 1)")
    bare = build_model(params or paper_design(), dim=dim, size_factor=size_factor)
    model = with_actuator(bare, a["actuator_stiffness"])
    f_n, freqs = working_frequency(model)
    f_max = 2.0 * float(data["frequency"]["sweep_max_Hz"])
    static = solve_static(model, static_supports(), actuator_loads(1.0, dim))
    main = frf(model, zeta, f_n, f_max)
    out = {"dim": dim, "dofs": int(model.n_dofs), "damping": zeta,
           "actuator_stiffness": a["actuator_stiffness"], "working_frequency_hz": f_n,
           "working_frequency_pads_held_hz": working_frequency(bare, modal_supports())[0],
           "modal_frequencies_hz": freqs, "output": output_compliance(model),
           "static_output_m_per_n": float(static.mean_displacement("output")[OUTPUT_AXIS]),
           **{k: v for k, v in main.items() if k != "damping"},
           "paper": {"fn_fem_hz": float(data["frequency"]["fn_fem_Hz"]),
                     "fn_measured_hz": float(data["frequency"]["fn_measured_Hz"]),
                     "bandwidth_hz": float(data["frequency"]["bandwidth_Hz"])}}
    if sensitivity:
        out["sensitivity"] = [main if z == zeta else frf(model, z, f_n, f_max)
                              for z in a["sensitivity"]]
    if buckling:
        out["buckling"] = hinge_buckling(bare, float(data["loading"]["force_max_N"]))
    if sweep:
        out["actuator_sweep"] = actuator_sweep(bare)
    return out
