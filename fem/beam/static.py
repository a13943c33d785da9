"""Linear static analysis of a beam model: ``solve_beam_static(model, supports, loads)``."""
from dataclasses import dataclass, field

import numpy as np

from .assembly import BeamAssembler
from .supports import load_vector
from .element import bending_stress
from .linear import solve_linear
from .model import BeamModel


@dataclass(frozen=True, eq=False)
class BeamState:
    """One equilibrium state. q : (n_nodes, 3) DOFs (u m, v m, theta rad); reactions :
    {node: (F_x N, F_y N, M N m)} at supported nodes; axial_force : (n_e,) N (tension > 0);
    end_moments : (n_e, 2) bending moment (N m, sagging > 0) at each element's two ends;
    stress : (n_e,) largest |N/A| + |M| c / I (Pa) per element; stress_xi : where along
    each element (0..1)."""

    model: BeamModel
    q: np.ndarray
    reactions: dict
    axial_force: np.ndarray
    end_moments: np.ndarray
    stress: np.ndarray
    stress_xi: np.ndarray
    load_factor: float = 1.0
    info: dict = field(default_factory=dict)

    @property
    def displacement(self) -> np.ndarray:
        """(n_nodes, 2) displacement, m."""
        return self.q[:, :2]

    @property
    def rotation(self) -> np.ndarray:
        """(n_nodes,) rotation, rad (counter-clockwise)."""
        return self.q[:, 2]

    @property
    def max_stress(self) -> float:
        """Largest bending + axial stress |N/A| + |M| c / I in the model, Pa."""
        # fmax skips NaN (an element without a stress): np.nanmax's value, at less cost
        return float(np.fmax.reduce(self.stress)) if np.isfinite(self.stress).any() \
            else float("nan")

    @property
    def max_stress_location(self) -> tuple:
        """(element, xi along it 0..1, reference coordinates (2,) m) of max_stress."""
        nan = np.isnan(self.stress)
        if nan.all():
            raise ValueError("All-NaN slice encountered")  # np.nanargmax's error
        e = int(np.argmax(np.where(nan, -np.inf, self.stress)))  # np.nanargmax's, less cost
        a, b = self.model.nodes[self.model.elements[e]]
        xi = float(self.stress_xi[e])
        return e, xi, a + xi * (b - a)



def make_state(assembler: BeamAssembler, q, r, lam, info=None, fb=None, w=None) -> BeamState:
    """Package a converged state: reactions from the residual r = f_int - lam f_ext; basic
    element forces ``fb`` (n_e, 3) from the co-rotational element and the links' weights
    ``w`` (Space.weights) at q unless given."""
    model = assembler.model
    if fb is None:
        _, _, fb = assembler.elements(q, tangent=False)
    space = assembler.space
    held_nodes = dict.fromkeys((space.held // 3).tolist())  # ascending, once each
    rr = np.zeros(model.n_dofs)  # generalised residual of the independent DOFs
    rr[space.free], rr[space.held] = space.reduce(r, space.weights(q) if w is None else w)
    rr = rr.reshape(-1, 3)
    reactions = {int(k): rr[k].copy() for k in held_nodes}
    sigma, xi = bending_stress(model, fb)
    return BeamState(model=model, q=q.copy(), reactions=reactions, axial_force=fb[:, 0].copy(),
                     end_moments=np.column_stack([-fb[:, 1], fb[:, 2]]), stress=sigma,
                     stress_xi=xi, load_factor=float(lam), info=dict(info or {}))


def solve_beam_static(model: BeamModel, supports, loads=()) -> BeamState:
    """Linear (small-displacement) static solve: K z = f - K_p p for the loads (NodalLoad)
    and the supports' values (NodeFixed, NodePrescribed) at load factor 1. Forces and stresses are
    the linear element forces (no co-rotational update). The factor of K is cached on the
    model (fem/beam/linear.py): further load cases and supports of the model reuse it."""
    f_ext = load_vector(model, loads)
    q, system, own = solve_linear(model, supports, f_ext)
    # the reactions are the supports' own: the system's Space where it holds their DOFs
    asm = system.asm if own else BeamAssembler(model, supports, loads)
    r = system.ev.full_times(q) - f_ext
    q = q.reshape(-1, 3)
    fb = np.einsum("eij,ej->ei", asm.Kb, _natural(model, q))
    w = system.ev.w if own else asm.space.weights(np.zeros_like(q))  # at q = 0 both
    return make_state(asm, q, r, 1.0, {"n_unknowns": asm.space.n}, fb=fb, w=w)


def _natural(model: BeamModel, q) -> np.ndarray:
    """Linearised natural deformations (extension, theta1 - chord, theta2 - chord), (n_e, 3)."""
    e = model.elements
    c, s = np.cos(model.angles), np.sin(model.angles)
    du = q[e[:, 1], :2] - q[e[:, 0], :2]
    along = c * du[:, 0] + s * du[:, 1]
    chord = (-s * du[:, 0] + c * du[:, 1]) / model.lengths
    return np.column_stack([along, q[e[:, 0], 2] - chord, q[e[:, 1], 2] - chord])
