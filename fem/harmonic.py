"""Steady-state harmonic response: ``solve_harmonic(model, supports, loads, frequencies_hz)``.

The loads act as f cos(omega t) (real amplitudes, N); the response is u(omega) e^{i omega t}
with complex u (m). Modal superposition over the lowest modes with a residual-flexibility
(static correction) term, exact at 0 Hz:

    u = sum_r phi_r (phi_r . f) / (omega_r^2 - omega^2 + 2 i zeta_r omega_r omega)
        + (K^-1 f - sum_r phi_r (phi_r . f) / omega_r^2),

or the direct complex solve (K - omega^2 M + i omega C) u = f with Rayleigh damping
C = alpha M + beta K (zeta_r = alpha / (2 omega_r) + beta omega_r / 2 in the modal method).
"""
from dataclasses import dataclass, field

import numpy as np
import skfem

from . import linsolve
from .factor import factor
from .frequency_response import FRF, Rayleigh, check_frequencies, damping_ratios
from .boundary import component_indices, constrained_dofs, group_dofs, load_vector
from .modal import Modes, solve_modes
from .model import Model
from .solved import Solved
from .static_result import check_supports, group_basis


@dataclass(frozen=True, eq=False)
class HarmonicResult(Solved):
    """The steady-state harmonic response (:func:`flexfem.fem.solve_harmonic`): ``model``
    (:class:`~.solved.Solved`) and

    Attributes
    ----------
    frequencies_hz : ndarray
        (n,) the excitation frequencies (Hz).
    u : ndarray
        (n, n_dofs) complex displacement amplitudes (m per the loads' amplitudes).
    method : str
        'modal' or 'direct'.
    modes : Modes or None
        The modes used (modal method).
    info : dict
        The solver's own figures.
    """

    frequencies_hz: np.ndarray
    u: np.ndarray
    method: str
    modes: Modes | None = None
    info: dict = field(default_factory=dict)

    def mean_displacement(self, group: str) -> np.ndarray:
        """(n, dim) complex mean displacement amplitude (m) of a group per frequency (the
        average of :func:`.static.mean_field`, applied as one linear functional)."""
        return self.u @ mean_weights(self.model, group).T

    def frf(self, group: str, component) -> FRF:
        """Response of ``group``'s mean displacement along ``component`` (0/'x', 1/'y',
        2/'z') to the applied loads."""
        axes = {"x": 0, "y": 1, "z": 2}
        i = axes.get(component, component)
        if i not in range(self.model.dim):
            raise ValueError(f"component = {component!r} must be one of "
                             f"{list(axes)[:self.model.dim]} or 0..{self.model.dim - 1}")
        return FRF(self.frequencies_hz, self.mean_displacement(group)[:, i])


def mean_weights(model: Model, group: str) -> np.ndarray:
    """(dim, n_dofs) weights w with w @ u the measure-averaged displacement (m) of a
    boundary group or subdomain."""
    group_dofs(model, group)  # validates the name
    basis = group_basis(model, group)
    total = skfem.LinearForm(lambda v, w: sum(v[i] for i in range(model.dim))).assemble(basis)
    weights = np.zeros((model.dim, model.n_dofs))
    for i, idx in enumerate(component_indices(model)):
        weights[i, idx] = total[idx]
    return weights / np.sum(basis.dx)


def _static(model, I, f) -> np.ndarray:
    K = model.stiffness[I][:, I].tocsr()
    return linsolve.solve_and_check(K, f[I], kind="spd", what="static correction")


def solve_harmonic(model: Model, supports, loads, frequencies_hz, damping=0.0,
                   method: str = "modal", n_modes: int = 20) -> HarmonicResult:
    """Steady-state response (m, complex) to the loads (amplitudes, N) at ``frequencies_hz``.

    supports : Fixed/Prescribed, held at zero. damping : a modal damping ratio (-), one per
    mode, or Rayleigh(alpha, beta). method : 'modal' (``n_modes`` modes plus the static
    correction, exact at 0 Hz) or 'direct' (one complex factorization per frequency; Rayleigh
    or zero damping only). An undamped response at a natural frequency is infinite."""
    f_hz = check_frequencies(frequencies_hz)
    if method not in ("modal", "direct"):
        raise ValueError(f"method = {method!r}; choose 'modal' or 'direct'")
    D, _, _ = constrained_dofs(model, supports)
    check_supports(model, D)
    I = np.setdiff1d(np.arange(model.n_dofs), D)
    f = load_vector(model, loads)
    omega = 2 * np.pi * f_hz
    u = np.zeros((len(f_hz), model.n_dofs), dtype=complex)
    if method == "direct":
        if not isinstance(damping, Rayleigh) and np.any(np.asarray(damping) != 0):
            raise ValueError(f"damping = {damping!r}: method='direct' takes Rayleigh(alpha, "
                             "beta) or 0; modal damping ratios need method='modal'")
        r = damping if isinstance(damping, Rayleigh) else Rayleigh()
        K, M = model.stiffness[I][:, I], model.mass[I][:, I]
        for k, w in enumerate(omega):
            A = (K - w ** 2 * M + 1j * w * (r.alpha * M + r.beta * K)).tocsc()
            with factor(A, "general", "superlu") as F:
                u[k, I] = F.solve(f[I].astype(complex))
        return HarmonicResult(model, f_hz, u, "direct", info={"n_dofs": model.n_dofs})
    if not (isinstance(n_modes, int) and 1 <= n_modes < len(I)):
        raise ValueError(f"n_modes = {n_modes!r} must be an integer in [1, {len(I) - 1}]")
    modes = solve_modes(model, n_modes, supports)
    w_r = 2 * np.pi * modes.frequencies_hz
    zeta = damping_ratios(damping, w_r)
    p = modes.shapes @ f  # modal forces, N m/sqrt(kg)
    static = np.zeros(model.n_dofs)
    static[I] = _static(model, I, f)
    residual = static - modes.shapes.T @ (p / w_r ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        h = 1.0 / (w_r[None, :] ** 2 - omega[:, None] ** 2 + 2j * zeta * w_r * omega[:, None])
    u[:] = (h * p) @ modes.shapes + residual
    return HarmonicResult(model, f_hz, u, "modal", modes,
                          info={"n_modes": n_modes, "damping_ratios": zeta})
