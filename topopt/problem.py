"""A topology optimisation problem as data: grid, material, supports, loads, springs,
objective, constraints, filter, interpolation, optimiser. Lengths in m, forces in N,
stiffnesses in N/m, moduli in Pa (top88's problems: E = 1, elements of size 1)."""
from dataclasses import dataclass, field
import hashlib

import numpy as np

from ..fem import checks
from ..fem.budget import check_grid
from .filters import KINDS as FILTERS
from .grid import Grid
from .interpolation import Interpolation
from .large_displacement import Nonlinear
from .projection import Projection
from .regions import Region
from .robust import Robust, radius_for

DOFS = ("x", "y")
RESPONSES = ("compliance", "volume", "displacement", "frequency", "stress")
OPTIMIZERS = ("oc", "mma")


@dataclass(frozen=True)
class Support:
    """DOFs ``fix`` ('x', 'y') held at zero on every node of ``where``."""

    where: Region
    fix: tuple = ("x", "y")


@dataclass(frozen=True)
class Load:
    """A force (fx, fy), N, shared equally by the nodes of ``where``, in load case ``case``
    (1, 2, ...: the loads of a case act together, each case is solved on its own)."""

    where: Region
    force: tuple
    case: int = 1


@dataclass(frozen=True)
class Spring:
    """A grounded spring of ``stiffness`` N/m along ``dof``, shared equally by the nodes of
    ``where``; its displacement is their mean (m). Named 'input' and 'output', the springs
    of a mechanism give ``u_in`` and ``u_out``."""

    name: str
    where: Region
    dof: str
    stiffness: float


@dataclass(frozen=True)
class Response:
    """'compliance' (sum over load cases of weights[k] f_k.u_k, J; ``weights`` default 1
    each), 'volume' (solid fraction), 'displacement' (the mean displacement of spring
    ``spring`` along its DOF in load case ``case``, m), 'frequency' (the lowest
    eigenfrequency, Hz; with ``modes`` > 1 that of an aggregate of the ``modes`` lowest
    eigenvalues, below the lowest and differentiable where it is repeated) or 'stress' (the p-norm, exponent ``pnorm``, of the elements'
    relaxed von Mises stresses rho^relaxation sigma_vm(solid) at their centres over all load
    cases, Pa). A 'displacement' with ``springs`` False is that of the structure without its
    springs (its own input stiffness: load over that displacement)."""

    kind: str
    spring: str = ""
    case: int = 1
    weights: tuple = ()
    pnorm: float = 8.0
    relaxation: float = 0.5
    modes: int = 1
    springs: bool = True


@dataclass(frozen=True)
class Constraint:
    """``response`` <= ``upper`` and/or >= ``lower`` (in the response's units)."""

    response: Response
    upper: float | None = None
    lower: float | None = None


@dataclass(frozen=True)
class Passive:
    """Elements whose centre lies in ``where`` held ``value`` 'solid' (1) or 'void' (0)."""

    where: Region
    value: str


@dataclass(frozen=True)
class Optimizer:
    """``kind`` 'oc' (optimality criteria, top88: compliance under a volume limit) or 'mma'
    (Svanberg's MMA as mmapy takes it: any objective and constraints); ``move``: largest
    density change per iteration; stops when the largest change is below ``tolerance`` or
    at ``max_iterations``."""

    kind: str = "oc"
    move: float = 0.2
    max_iterations: int = 200
    tolerance: float = 0.01


@dataclass(frozen=True)
class Problem:
    """Everything that defines a design problem; see docs/topopt.md."""

    grid: Grid
    objective: Response
    sense: str = "min"
    nu: float = 0.3
    thickness: float = 1.0
    mass_density: float = 1.0   # kg/m^3, for 'frequency'
    interpolation: Interpolation = field(default_factory=Interpolation)
    filter_kind: str = "sensitivity"
    radius: float = 1.5
    supports: tuple = ()
    loads: tuple = ()
    springs: tuple = ()
    constraints: tuple = ()
    passive: tuple = ()
    symmetry: tuple = ()
    optimizer: Optimizer = field(default_factory=Optimizer)
    initial: float | None = None
    projection: Projection | None = None
    nonlinear: Nonlinear | None = None
    robust: Robust | None = None

    def __post_init__(self):
        check_problem(self)

    def spring(self, name: str) -> Spring:
        for s in self.springs:
            if s.name == name:
                return s
        raise ValueError(f"spring = {name!r}: no spring of that name "
                         f"(springs: {[s.name for s in self.springs]})")

    @property
    def n_cases(self) -> int:
        """The number of load cases."""
        return max(load.case for load in self.loads)

    def case_loads(self, case: int = 1) -> tuple:
        """The loads of load case ``case``."""
        return tuple(load for load in self.loads if load.case == case)

    def load_groups(self, case: int | None = None) -> list:
        """[(group name, load)] of the loads of ``case`` (every case: None), each named
        'load<k>' by its place k in ``loads`` (the problem file's [[load]] k)."""
        return [(f"load{k}", ld) for k, ld in enumerate(self.loads)
                if case is None or ld.case == case]

    @property
    def volume_limit(self) -> float | None:
        """The upper bound of the volume constraint, if any."""
        return next((c.upper for c in self.constraints if c.response.kind == "volume"), None)

    def digest(self) -> str:
        """What the design depends on (the optimiser's limits excluded), for resuming."""
        limits = Optimizer(self.optimizer.kind, self.optimizer.move, 0, 0.0)
        text = repr((self.grid, self.objective, self.sense, self.nu, self.thickness,
                     self.mass_density, self.interpolation, self.filter_kind, self.radius,
                     self.supports, self.loads, self.springs, self.constraints, self.passive,
                     self.symmetry, limits, self.initial)
                    + ((self.projection,) if self.projection else ())
                    + ((self.nonlinear,) if self.nonlinear else ())
                    + ((self.robust,) if self.robust else ()))
        return hashlib.sha256(text.encode()).hexdigest()[:16]


def check_problem(p: Problem) -> None:
    """ValueError naming the first inconsistent key of ``p`` (a BudgetError for a grid
    that does not fit the machine: fem/budget.py)."""
    check_grid(p.grid.nelx, p.grid.nely, "domain.nelx x domain.nely")
    checks.in_range("material.nu", p.nu, (-1.0, 0.5), closed=False)
    checks.positive("domain.thickness", p.thickness)
    if p.sense not in ("min", "max"):
        raise ValueError(f"objective.sense = {p.sense!r}: choose 'min' or 'max'")
    names = [s.name for s in p.springs]
    if len(set(names)) != len(names):
        raise ValueError(f"spring names must differ: {names}")
    for s in p.springs:
        if s.dof not in DOFS:
            raise ValueError(f"spring {s.name!r}: dof = {s.dof!r}: choose 'x' or 'y'")
        checks.positive("stiffness", s.stiffness, owner=f"spring {s.name!r}")
    if not p.supports or not p.loads:
        raise ValueError("support, load: give at least one [[support]] and one [[load]]")
    for case in sorted({load.case for load in p.loads}):
        if not any(f != 0 for load in p.loads if load.case == case for f in load.force):
            raise ValueError(f"load case {case}: every [[load]] force is zero, so nothing "
                             "moves; give a force (N)")
    _check_cases(p)
    for r in [p.objective] + [c.response for c in p.constraints]:
        _check_response(p, r)
    for s in p.supports:
        if not s.fix or not set(s.fix) <= set(DOFS):
            raise ValueError(f"support.fix = {list(s.fix)!r}: give DOFs among 'x', 'y'")
    if p.robust is not None:
        _check_min_hinge(p)
    if p.filter_kind not in FILTERS:
        raise ValueError(f"filter.kind = {p.filter_kind!r}: choose one of {list(FILTERS)}")
    if p.filter_kind != "none" and not (isinstance(p.radius, (int, float)) and p.radius > 1):
        raise ValueError(f"filter.radius = {p.radius!r}: must be > 1 (elements)")
    if p.projection is not None and p.filter_kind == "sensitivity":
        raise ValueError("projection: needs filter.kind 'density', 'helmholtz' or 'none', "
                         "not 'sensitivity'")
    if p.objective.kind == "volume":
        raise ValueError("objective.kind = 'volume': optimise compliance, a displacement, "
                         "the frequency or the stress (the volume is a constraint)")
    for kind, sense in (("frequency", "max"), ("stress", "min")):
        if p.objective.kind == kind and p.sense != sense:
            raise ValueError(f"objective.kind = {kind!r}: its sense is {sense!r}")
    checks.positive("material.rho", p.mass_density)
    for c in p.constraints:
        if c.upper is None and c.lower is None:
            raise ValueError(f"constraint {c.response.kind!r}: give max or min")
    if p.symmetry and not set(p.symmetry) <= set(DOFS):
        raise ValueError(f"symmetry = {list(p.symmetry)!r}: give axes among 'x', 'y'")
    _check_optimizer(p)
    if p.nonlinear is not None:
        _check_nonlinear(p)
    if p.robust is not None:
        _check_robust(p)


def _check_robust(p: Problem) -> None:
    """The combinations the robust formulation takes: the hat (density) filter, whose
    radius the minimum size relation is for, a projection at 0.5 (its beta schedule), MMA,
    square elements, one bound per constraint (large displacements too: each design on its
    own equilibrium path)."""
    if p.filter_kind != "density":
        raise ValueError(f"robust: needs filter.kind 'density' (the hat filter its minimum "
                         f"size relation is for), not {p.filter_kind!r}")
    if p.projection is None or p.projection.eta != 0.5:
        raise ValueError("robust: needs a [projection] (its beta schedule) with eta = 0.5 "
                         "(the intermediate design's threshold)")
    if p.optimizer.kind != "mma":
        raise ValueError("robust: needs optimizer.kind 'mma'")
    for c in p.constraints:
        if c.response.kind != "volume" and c.upper is not None and c.lower is not None:
            raise ValueError(f"robust: constraint {c.response.kind!r}: give max or min, not "
                             "both (each bounds the worst of the three designs)")


def _check_nonlinear(p: Problem) -> None:
    if p.n_cases > 1:
        raise ValueError("nonlinear: one load case only (the large-displacement state is "
                         "that of load case 1)")
    for r in [p.objective] + [c.response for c in p.constraints]:
        if r.kind not in ("displacement", "compliance", "volume", "stress"):
            raise ValueError(f"nonlinear: {r.kind!r} is not available with large "
                             "displacements (displacement, compliance, stress and volume "
                             "are)")
        if not r.springs:
            raise ValueError("nonlinear: a displacement without the springs is not "
                             "available with large displacements")


def _check_cases(p: Problem) -> None:
    cases = {load.case for load in p.loads}
    for load in p.loads:
        if isinstance(load.case, bool) or not isinstance(load.case, int) or load.case < 1:
            raise ValueError(f"load.case = {load.case!r}: must be an integer >= 1")
    if cases != set(range(1, len(cases) + 1)):
        raise ValueError(f"load.case: the cases must be 1, 2, ... without a gap, not "
                         f"{sorted(cases)}")


def _check_response(p: Problem, r: Response) -> None:
    if r.kind not in RESPONSES:
        raise ValueError(f"kind = {r.kind!r}: choose one of {list(RESPONSES)}")
    if r.kind == "displacement":
        p.spring(r.spring)
    if not r.springs and r.kind != "displacement":
        raise ValueError(f"{r.kind}: springs = false applies to kind 'displacement' only")
    if not (isinstance(r.case, int) and 1 <= r.case <= p.n_cases):
        raise ValueError(f"{r.kind}: case = {r.case!r}: must be a load case, 1 to {p.n_cases}")
    if r.weights:
        if r.kind != "compliance":
            raise ValueError(f"{r.kind}: weights apply to kind 'compliance' only")
        ok = all(isinstance(w, (int, float)) and np.isfinite(w) and w >= 0 for w in r.weights)
        if len(r.weights) != p.n_cases or not ok or not any(r.weights):
            raise ValueError(f"compliance: weights = {list(r.weights)!r}: give one number "
                             f">= 0 per load case ({p.n_cases}), not all zero")
    if not (isinstance(r.pnorm, (int, float)) and 1 <= r.pnorm <= 64):
        raise ValueError(f"stress: pnorm = {r.pnorm!r}: must be in [1, 64]")
    if not (isinstance(r.relaxation, (int, float)) and 0 < r.relaxation <= 1):
        raise ValueError(f"stress: relaxation = {r.relaxation!r}: must be in (0, 1]")
    if isinstance(r.modes, bool) or not isinstance(r.modes, int) or not 1 <= r.modes <= 20:
        raise ValueError(f"frequency: modes = {r.modes!r}: must be an integer, 1 to 20")


def _check_optimizer(p: Problem) -> None:
    o = p.optimizer
    if o.kind not in OPTIMIZERS:
        raise ValueError(f"optimizer.kind = {o.kind!r}: choose one of {list(OPTIMIZERS)}")
    if not (isinstance(o.move, (int, float)) and 0 < o.move <= 1):
        raise ValueError(f"optimizer.move = {o.move!r}: must be in (0, 1]")
    if not isinstance(o.max_iterations, int) or o.max_iterations < 0:
        raise ValueError(f"optimizer.max_iterations = {o.max_iterations!r}: must be an "
                         "integer >= 0")
    checks.positive("optimizer.tolerance", o.tolerance)
    if o.kind == "oc":
        only_volume = [c.response.kind for c in p.constraints] == ["volume"]
        if p.objective.kind != "compliance" or p.sense != "min" or not only_volume:
            raise ValueError("optimizer.kind = 'oc' applies to minimum compliance under one "
                             "volume constraint; use 'mma'")
    vol = p.volume_limit
    if vol is not None and not 0 < vol <= 1:
        raise ValueError(f"volume max = {vol!r}: must be a fraction in (0, 1]")
    if p.initial is not None and not 0 < p.initial <= 1:
        raise ValueError(f"optimizer.initial = {p.initial!r}: must be in (0, 1]")


def _check_min_hinge(p: Problem) -> None:
    """robust.min_hinge against the grid and the filter's radius."""
    g = p.grid
    if abs(g.dx - g.dy) > 1e-9 * max(g.dx, g.dy):
        raise ValueError(f"robust: needs square elements (the filter's radius is in "
                         f"elements), not {g.dx:.4g} x {g.dy:.4g} m")
    if p.robust.min_size > 0:
        r = radius_for(p.robust.min_size, g.dx, p.robust.eta)
        if r <= 1.0:
            raise ValueError(f"robust.min_hinge = {p.robust.min_size!r} m: gives a filter "
                             f"radius of {r:.3g} elements, which must exceed 1: refine the "
                             "grid")
        if abs(r - p.radius) > 1e-9 * r:
            raise ValueError(f"filter.radius = {p.radius!r}: robust.min_hinge asks for "
                             f"{r!r} elements (robust.radius_for)")
