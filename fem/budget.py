"""Resource budgets, checked before a mesh is made or a system is solved.

An analysis whose mesh would not fit the machine should be refused in seconds, with the
estimate and the way to raise the limit, not die of memory after minutes. The budget is a
number of unknowns (DOFs); by default what half the memory available now (MemAvailable)
affords at BYTES_PER_DOF, which covers the sparse direct factorisation (its fill-in) and the
modal solve of flexfem's quadratic elements (:func:`memory_bytes`). 2-D: measured peaks of
the DBMA analysis are about 2.8 kB per DOF (106k DOFs), the constant keeps a factor ~2 of
margin. 3-D: the peaks of ``flexfem analyze --dim 3`` of the bodies-and-flexures examples
(50k-144k DOFs, the interpreter's import subtracted) are 60 MiB plus 4.3-8.8 kB a DOF
(docs/performance.md); above GROWTH_FROM DOFs the bytes a DOF grow as the factor's fill-in,
~N^(1/3) (the 3-D cantilever: 6.5 kB a DOF at 95k DOFs, 9.8 kB at 351k).
"""
import contextlib
import contextvars
import math
import os

BYTES_PER_DOF = {2: 5_000, 3: 5_500}
#: Bytes of an analysis beyond the interpreter's import, whatever its size (MKL's libraries,
#: PARDISO's workspace, gmsh's model).
BASE_BYTES = {2: 0, 3: 64 * 2**20}
#: DOFs above which the bytes a DOF grow as (dofs / GROWTH_FROM) ** GROWTH.
GROWTH_FROM = {2: math.inf, 3: 150_000}
GROWTH = {2: 0.0, 3: 1 / 3}
#: Elements of a size h: a triangle's area (x h^2), tetrahedra in a cube of side h.
TRIANGLE = math.sqrt(3) / 4
TETRAHEDRA_PER_CUBE = 8.5  # regular tetrahedra of edge h: h^3 / (6 sqrt 2) each
#: Nodes per element of large unstructured meshes, by (dim, order).
NODES_PER_ELEMENT = {(2, 1): 0.5, (2, 2): 2.05, (3, 1): 0.18, (3, 2): 1.4}
#: Nodes a boundary element side adds (an edge in 2-D, a triangle in 3-D): Euler's formula.
#: 2-D: V = (T + B) / 2 + 1 and E = (3 T + B) / 2 for T triangles and B boundary edges, so
#: P1 nodes T / 2 + B / 2 and P2 nodes (V + E) 2 T + B. 3-D: E = V + T + B / 2 - 1 with B
#: boundary triangles; a boundary vertex (B / 2 of them) sits in half a bulk vertex's
#: tetrahedra, so V = 0.18 T + B / 4 and P2 nodes (V + E) 1.36 T + B.
BOUNDARY_NODES = {(2, 1): 0.5, (2, 2): 1.0, (3, 1): 0.25, (3, 2): 1.0}
FALLBACK_MEMORY = 4 * 2**30  # when the available memory cannot be read
#: Most eigenpairs a model file may ask for (modes, buckling factors, a harmonic's modal
#: basis): a flexure is designed on its first few; the Lanczos solve keeps k vectors of the
#: model's size and its time grows ~k^2 (4000 modes of a small guide ran past 120 s).
MAX_MODES = 200
#: Most frequencies of a harmonic response: the response is stored at every frequency for
#: every DOF (16 bytes each, complex), 10,000 x 100,000 DOFs = 16 GB; an FRF is read at
#: hundreds of points.
MAX_FREQUENCY_POINTS = 10_000
#: Bytes per DOF of a topology optimisation's structured grid (bilinear quads, a direct
#: solve of a banded stiffness: measured ~1.5 kB a DOF on top88-sized grids; margin ~2).
TOPOPT_BYTES_PER_DOF = 3_000


_ESTIMATING = contextvars.ContextVar("flexfem_budget_estimating", default=False)


class Estimated(Exception):
    """Raised by :func:`check_budget` inside :func:`estimate_only` instead of going on to
    mesh: ``estimate`` ({"elements", "nodes", "dofs"}), ``limit`` (DOFs), ``source`` (where
    the limit comes from), ``what`` was estimated and its ``dim``. Not a ValueError: no analysis wraps it
    as a failure of the design; picklable (a bounded child process sends it back)."""

    def __init__(self, estimate: dict, limit: int, source: str, what: str, dim: int = 2):
        super().__init__(estimate, limit, source, what, dim)
        self.estimate, self.limit, self.source, self.what = estimate, limit, source, what
        self.dim = dim

    @property
    def memory_gib(self) -> float:
        return memory_bytes(self.estimate["dofs"], self.dim) / 2**30

    @property
    def fits(self) -> bool:
        return self.estimate["dofs"] <= self.limit


@contextlib.contextmanager
def estimate_only():
    """Inside this context the first :func:`check_budget` of an analysis raises
    :class:`Estimated` with its estimate (its mesh is never made): a study checks every level
    against the budget before it meshes any (studies/engine/convergence.py)."""
    token = _ESTIMATING.set(True)
    try:
        yield
    finally:
        _ESTIMATING.reset(token)


class BudgetError(ValueError):
    """A model above its resource budget. ``environmental``: the machine, not the design,
    decides it (a study records the case as an "error", computed again by the next run)."""

    environmental = True


#: An environment variable that fixes the memory flexfem plans for (GiB) instead of reading
#: what is free now: for a machine shared with other jobs, and for tests, whose budgets must
#: not depend on the load of the moment.
MEMORY_VARIABLE = "FLEXFEM_MEMORY_GIB"


def available_memory_bytes() -> int:
    """Memory available to a new allocation: ``FLEXFEM_MEMORY_GIB`` where it is set, else
    what is available now (Linux MemAvailable), else free pages; never more than this
    process' address-space limit (``ulimit -v``) leaves."""
    return int(min(_memory_bytes(), _address_space_left()))


def _address_space_left() -> float:
    """Bytes the address-space limit (RLIMIT_AS) leaves above this process' virtual size;
    inf where there is no limit (or it cannot be read)."""
    try:
        import resource

        limit = resource.getrlimit(resource.RLIMIT_AS)[0]
        if limit == resource.RLIM_INFINITY:
            return math.inf
        with open("/proc/self/status") as f:
            size = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize:"))
        return max(limit - size, 0)
    except (ImportError, OSError, ValueError, StopIteration):
        return math.inf


def _memory_bytes() -> int:
    fixed = os.environ.get(MEMORY_VARIABLE)
    if fixed:
        try:
            gib = float(fixed)
        except ValueError:
            gib = math.nan
        if not (math.isfinite(gib) and gib > 0):
            raise ValueError(f"{MEMORY_VARIABLE} = {fixed!r} must be a number of GiB > 0")
        return int(gib * 2**30)
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, AttributeError):
        return FALLBACK_MEMORY


def memory_bytes(dofs: float, dim: int) -> float:
    """The peak memory (bytes) expected of the solve of ``dofs`` unknowns in ``dim``-D:
    BASE_BYTES + dofs x BYTES_PER_DOF, the bytes a DOF growing above GROWTH_FROM."""
    dim = dim if dim in BYTES_PER_DOF else 3
    growth = max(1.0, dofs / GROWTH_FROM[dim]) ** GROWTH[dim]
    return BASE_BYTES[dim] + dofs * BYTES_PER_DOF[dim] * growth


def max_dofs_for(memory: float, dim: int) -> int:
    """The most DOFs whose :func:`memory_bytes` is within ``memory`` (bytes)."""
    low, high = 0, max(1, int(memory / BYTES_PER_DOF[dim]) + 1)
    while high - low > 1:
        mid = (low + high) // 2
        low, high = (mid, high) if memory_bytes(mid, dim) <= memory else (low, mid)
    return max(low, 1)


def default_max_dofs(dim: int) -> int:
    """DOFs whose solve fits in half the available memory."""
    return max_dofs_for(0.5 * available_memory_bytes(), dim)


def check_grid(nelx: int, nely: int, what: str) -> None:
    """BudgetError when a topology optimisation's nelx x nely grid (2 DOFs a node) needs more
    than half the available memory at TOPOPT_BYTES_PER_DOF, naming ``what``."""
    dofs = 2 * (nelx + 1) * (nely + 1)
    memory, limit = dofs * TOPOPT_BYTES_PER_DOF, 0.5 * available_memory_bytes()
    if memory > limit:
        raise BudgetError(f"{what}: {nelx:,} x {nely:,} elements are {dofs:,} DOFs (~"
                          f"{memory / 2**30:.1f} GiB to solve), above the budget of "
                          f"{int(limit / TOPOPT_BYTES_PER_DOF):,} DOFs (half the available "
                          "memory); use a coarser grid")


def check_budget(estimate: dict, dim: int, max_dofs: int | None = None,
                 what: str = "model") -> None:
    """Raise BudgetError when ``estimate["dofs"]`` exceeds ``max_dofs`` (None: the machine's
    default_max_dofs), naming the estimate, its memory and how to raise the limit."""
    if max_dofs is not None and (isinstance(max_dofs, bool) or not isinstance(max_dofs, int)
                                 or max_dofs < 1):
        raise ValueError(f"max_dofs = {max_dofs!r} must be an integer >= 1")
    limit = default_max_dofs(dim) if max_dofs is None else max_dofs
    source = ("half the available memory" if max_dofs is None else "max_dofs")
    if _ESTIMATING.get() and (estimate["dofs"] or estimate["elements"]):  # 0: a check of max_dofs
        raise Estimated(dict(estimate), limit, source, what, dim)
    if estimate["dofs"] <= limit:
        return
    memory = memory_bytes(estimate["dofs"], dim) / 2**30
    raise BudgetError(
        f"{what}: about {estimate['elements']:,} elements and {estimate['dofs']:,} DOFs "
        f"(~{memory:.1f} GiB to solve), above the budget of {limit:,} DOFs ({source}); "
        "use a coarser mesh (a larger size_factor) or raise the budget with --max-dofs N "
        "(option max_dofs = N)")


#: Share of the available memory a direct factorization may take: in core, its whole factor;
#: out of core (PARDISO's factor on disk), its working set in memory.
FACTOR_SHARE = 0.5


def factor_plan(in_core: float, out_of_core: float | None,
                available: float | None = None,
                address_space: float | None = None) -> tuple[str, str]:
    """How a direct factorization fits the memory: ('in-core' | 'out-of-core' | 'iterative',
    why). ``in_core``: the peak (bytes) of the factor held in memory; ``out_of_core``: the
    peak with the factor on disk (None: no out-of-core mode); both from PARDISO's analysis.
    ``available`` (bytes; None: :func:`available_memory_bytes`) of which FACTOR_SHARE may be
    taken. In core wherever it fits, out of core next, the iterative path beyond. PARDISO's
    out-of-core mode fails (its error -2) under an address-space limit below its in-core
    factor, whatever its budget (docs/large_models.md): ``address_space`` (bytes; None:
    what this process' ``ulimit -v`` leaves, inf without one) below ``in_core`` rules it out."""
    budget = FACTOR_SHARE * (available_memory_bytes() if available is None else available)
    room = _address_space_left() if address_space is None else address_space
    gib = 2**30
    head = f"the direct factor's {in_core / gib:.2f} GiB (PARDISO's analysis)"
    share = f"half the available memory, {budget / gib:.2f} GiB"
    if in_core <= budget:
        return "in-core", f"{head} fits {share}"
    if out_of_core is not None and out_of_core <= budget and room < in_core:
        return "iterative", (f"{head} is above {share}; out of core PARDISO needs an address "
                             f"space above its in-core factor, and the address-space limit "
                             f"(ulimit -v) leaves {room / gib:.2f} GiB")
    if out_of_core is not None and out_of_core <= budget:
        return "out-of-core", (f"{head} is above {share}; out of core (the factor on disk) it "
                               f"needs {out_of_core / gib:.2f} GiB in memory, which fits")
    ooc = ("" if out_of_core is None else
           f", and out of core its {out_of_core / gib:.2f} GiB in memory too")
    return "iterative", f"{head} is above {share}{ooc}"
