"""The mechanisms flexfem knows: one entry each, and the only place that names them.

A mechanism is a frozen parameter dataclass (in geometry/<name>/ where it has a geometry),
its closed-form models, an ``evaluate(params: dict, **options) -> dict[str, float]`` for
studies, its report sections and its CLI commands, all in the package studies/<name>/. The
study engine (sweep, convergence), the optimiser, the report and the CLI find mechanisms only
here. Targets are ``"module:attribute"`` strings inside the mechanism's package, imported when
first used, as Python entry points are: a study of the toy never imports gmsh.

Which code a study may run: a study file names a mechanism, never code. The mechanisms are the
built-in ones below, model files ("model:<path>@<digest>") and those that installed packages
register under the entry-point group ``flexfem.mechanisms`` (name = "module:function", loaded
with importlib.metadata). An arbitrary "module:function" is Python code: it is refused unless
the caller opts in (``allow_code=True``, ``flexfem sweep --allow-code``), as importing and
calling any function with the file's values (``subprocess:run`` with ``shell = true``) runs
anything.

``evaluate`` fills defaults for the parameters it is not given (the base design is the
mechanism's own) and returns its metrics, FEM and analytical side by side; it may also return
``"h"`` (a characteristic element size, m) and ``"dofs"`` (the number of unknowns) for
convergence studies.
"""
from dataclasses import dataclass
import functools
import hashlib
import importlib
from pathlib import Path
import tomllib


@dataclass(frozen=True)
class ReportSection:
    """One report section: its folder, its title and ``"module:function"``, a
    ``reproduce(out_dir, quick=False[, full=False]) -> summary``."""

    folder: str
    title: str
    target: str


@dataclass(frozen=True)
class RegisteredMechanism:
    """One registry entry; targets are relative to ``flexfem.studies.<package>``.

    evaluate : "module:function" for studies ("" when the mechanism has no study metrics)
    commands : module with ``register(subparsers)`` adding its CLI commands
    optimizer : module with ``add_arguments(parser)``, ``run(args)`` and ``summarize(result)``
        for ``flexfem optimize <name>`` ("" when it has none)
    coarsest_size_factor : size_factor of the coarsest level of its convergence studies
        (1 = its default mesh)
    document : key of the source document it reproduces (data/sources.toml), "" for none
    units : "module:attribute" of its {parameter or metric name: unit} table (axis labels)
    """

    name: str
    title: str
    package: str
    evaluate: str = ""
    commands: str = ""
    optimizer: str = ""
    sections: tuple = ()
    coarsest_size_factor: float = 1.0
    document: str = ""
    units: str = ""

    def load(self, target: str):
        """The object a ``"module:attribute"`` (or ``"module"``) target of this entry names."""
        module_name, _, attribute = target.partition(":")
        module = importlib.import_module(f"flexfem.studies.{self.package}.{module_name}")
        return getattr(module, attribute) if attribute else module


BUILTIN = (
    RegisteredMechanism(
        "dbma", "Double-row bow-type micro-displacement amplifier (servo valve)", "dbma",
        evaluate="evaluate:evaluate", commands="cli", optimizer="cli_optimize", document="dbma",
        units="evaluate:UNITS",
        # coarser start: halving the size three times from 4x stays affordable
        coarsest_size_factor=4.0,
        sections=(
            ReportSection("dbma_analytical", "DBMA: pseudo-rigid-body and enhanced analytical models",
                    "figures:reproduce_analytical"),
            ReportSection("dbma_fem", "DBMA: FEM amplification ratio, stress, modes and convergence",
                    "report:reproduce"),
            ReportSection("dbma_optimize", "DBMA: FEM-decided hinge design search (beyond the sources)",
                    "optimize_output:reproduce"),
            ReportSection("dbma_dynamics", "DBMA: output compliance, FRF, bandwidth, buckling",
                    "dynamics_report:reproduce"),
            ReportSection("dbma_beam", "DBMA: beam model beside the closed forms and the FEM",
                    "beam_report:reproduce"),
            ReportSection("dbma_topopt", "DBMA: a topology-optimised amplifier in its envelope",
                    "topopt_report:reproduce"),
        )),
    RegisteredMechanism(
        "eightbar", "Symmetric rectilinear eight-bar flexure suspension", "eightbar",
        evaluate="evaluate:evaluate", commands="cli", document="eightbar", units="evaluate:UNITS",
        sections=(
            ReportSection("eightbar_rigid",
                    "Eight-bar and straight-line linkages: rigid-body paths and synthesis",
                    "path:reproduce"),
            ReportSection("eightbar_fem",
                    "Eight-bar flexure suspension: FEM, stress and large-deflection path",
                    "report:reproduce"),
            ReportSection("eightbar_stage", "Eight-bar as a stage: compliance, modes, buckling",
                    "stage_report:reproduce"),
            ReportSection("eightbar_beam",
                    "Eight-bar flexure suspension: beam model beside the PRBM and the FEM",
                    "beam_report:reproduce"),
        )),
    RegisteredMechanism(
        "eightbar_driving", "Eight-bar thesis' driving linkage: two lambdas, two suspensions",
        "eightbar", evaluate="driving_models:evaluate", document="eightbar",
        units="driving_models:UNITS"),
    RegisteredMechanism(
        "balancing", "Five-bar parallel robot: optimum static balancing and flexure pivots",
        "balancing", commands="cli", document="balancing",
        sections=(
            ReportSection("balancing", "Five-bar robot: optimum static balancing and flexure pivots",
                    "report:reproduce"),
            ReportSection("balancing_pivot_stability",
                    "Flexure pivots: limit point, stability margin, centre shift",
                    "pivot_stability_report:reproduce"),
            ReportSection("balancing_beam",
                    "Balancing pivots: beam model beside beam theory and the FEM",
                    "beam_report:reproduce"),
        )),
    RegisteredMechanism(
        "model", "Your own flexure from a model file (TOML + .geo, .step or .msh)", "user_model",
        evaluate="analysis:evaluate", commands="cli", units="analysis:UNITS"),
    RegisteredMechanism(
        "toy", "Tapered cantilever (closed form): the study engine's own check", "toy",
        evaluate="model:evaluate", units="model:UNITS",
        sections=(
            ReportSection("studies_engine",
                    "Study engine: sweep and Richardson convergence checked on a closed form",
                    "report:reproduce"),
        )),
)

MECHANISMS = {m.name: m for m in BUILTIN}
MODEL_PREFIX = "model:"
ENTRY_POINT_GROUP = "flexfem.mechanisms"


@functools.lru_cache(maxsize=1)
def plugin_mechanisms() -> dict:
    """{name: entry point} of the mechanisms installed packages register in the group
    ``flexfem.mechanisms`` (a built-in name wins over a package's)."""
    import importlib.metadata  # the installed packages' metadata: read when a name is looked up

    points = importlib.metadata.entry_points(group=ENTRY_POINT_GROUP)
    return {ep.name: ep for ep in points if ep.name not in MECHANISMS}


def model_mechanism(path, base_dir=None, allow_code: bool = False) -> str:
    """The mechanism name of a model file: "model:<absolute path>@<digest>", the digest over
    the model file and the geometry file it names, so that a study's stored cases are not
    reused once either file changes. ``path`` is relative to ``base_dir`` (default: cwd); a
    study (``base_dir`` given) names only model files inside its own folder (a relative path,
    symbolic links resolved) unless ``allow_code``."""
    if not isinstance(path, (str, Path)) or not str(path):
        raise ValueError(f"mechanism.model = {path!r} must be the path of a model file")
    if base_dir is not None and not allow_code and Path(path).is_absolute():
        raise ValueError(f"mechanism.model = {str(path)!r} is an absolute path; a study names "
                         "its model file relative to its own folder (pass --allow-code to "
                         "lift this)")
    path = Path(base_dir or ".") / path
    if base_dir is not None and not allow_code:
        try:
            path.resolve().relative_to(Path(base_dir).resolve())
        except ValueError:
            raise ValueError(f"mechanism.model = {str(path)!r} lies outside the study's folder "
                             f"{Path(base_dir).resolve()}; a study reads only its own folder "
                             "(pass --allow-code to lift this)") from None
    if not path.is_file():
        raise ValueError(f"mechanism.model = {str(path)!r}: no such model file")
    return f"{MODEL_PREFIX}{path.resolve()}@{_model_digest(path)}"


def _model_digest(path: Path) -> str:
    """The first 12 hex digits of the sha256 over a model file and the geometry it names."""
    digest = hashlib.sha256(path.read_bytes())
    try:
        geometry = tomllib.loads(path.read_text()).get("geometry")
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{path}: not valid TOML: {error}") from None
    if isinstance(geometry, str) and (path.parent / geometry).is_file():
        digest.update((path.parent / geometry).read_bytes())
    return digest.hexdigest()[:12]


def verify_model_mechanism(name: str, key: str = "mechanism") -> str:
    """``name`` ("model:<path>@<digest>") if its file exists and still has that digest; else
    ValueError naming ``key``: a case stored under a digest is the file as it was then."""
    path, _, digest = name[len(MODEL_PREFIX):].rpartition("@")
    if not Path(path).is_absolute() or not Path(path).is_file():
        raise ValueError(f"{key} = {name!r}: no model file {path!r} (a model mechanism is "
                         "\"model:<absolute path>@<digest>\", as model_mechanism gives it)")
    actual = _model_digest(Path(path))
    if digest != actual:
        raise ValueError(f"{key} = {name!r}: the digest {digest!r} is not that of {path} "
                         f"({actual!r}): the file changed or the name was written by hand; "
                         "name the model file (mechanism = { model = \"FILE.toml\" })")
    return name


class BoundEvaluate(functools.partial):
    """An evaluate with keywords the caller binds (a model file's ``file`` and
    ``allow_code``): a call that sets one of them again is refused, so that no study option
    overrides what the command line chose (picklable, for the workers)."""

    def __call__(self, *args, **options):
        taken = sorted(set(options) & set(self.keywords))
        if taken:
            raise ValueError(f"option(s) {taken} are set by the command line, not by a study")
        return super().__call__(*args, **options)


def _model_path(name: str) -> str | None:
    if isinstance(name, str) and name.startswith(MODEL_PREFIX):
        return name[len(MODEL_PREFIX):].rpartition("@")[0] or None
    return None


def is_target(name: str) -> bool:
    """True for a "package.module:function" string (an evaluate given by its import path)."""
    module, sep, function = name.partition(":")
    return bool(sep) and bool(module) and function.isidentifier()


def _known() -> list[str]:
    builtin = [n for n, m in MECHANISMS.items() if m.evaluate and n != "model"]
    return sorted(builtin + list(plugin_mechanisms()))


def check_mechanism(name: str, key: str = "mechanism", allow_code: bool = False) -> str:
    """Return ``name`` if it is a registered mechanism with an evaluate, a package's
    (``plugin_mechanisms``), a model file's mechanism (``model_mechanism``), or with
    ``allow_code`` a "module:function" target, without importing anything; else ValueError
    naming ``key``."""
    if name == "model":
        raise ValueError(f"{key} = 'model' needs its model file: "
                         "mechanism = { model = \"FILE.toml\" } in a study file, or the file's "
                         "path on the command line")
    if not isinstance(name, str):
        raise ValueError(f"{key} = {name!r} must be a mechanism's name; known: {_known()}")
    known = (name in MECHANISMS and MECHANISMS[name].evaluate) or name in plugin_mechanisms()
    if known or _model_path(name):
        return name
    if is_target(name):
        if allow_code:
            return name
        raise ValueError(f"{key} = {name!r} is Python code (module:function), not a registered "
                         f"mechanism (known: {_known()}); a study runs only registered "
                         "mechanisms. If you trust this study, pass --allow-code "
                         "(allow_code=True in Python): the function is imported and called "
                         "with the study's values")
    raise ValueError(f"{key} = {name!r} is not a known mechanism; known: {_known()}")


def get_evaluator(name: str, allow_code: bool = False):
    """The evaluate function of mechanism ``name`` (a registered name, a package's, a model
    file's, or with ``allow_code`` a "module:function").

    Raises ValueError listing the known names when the name is unknown or refused, or when
    its module cannot be imported or lacks the function.
    """
    check_mechanism(name, allow_code=allow_code)
    if _model_path(name):
        verify_model_mechanism(name)
        model = MECHANISMS["model"]
        bind = functools.partial if allow_code else BoundEvaluate  # trusted: may override
        return bind(model.load(model.evaluate), file=_model_path(name), allow_code=allow_code)
    if name in MECHANISMS:
        return MECHANISMS[name].load(MECHANISMS[name].evaluate)
    target = plugin_mechanisms()[name].value if name in plugin_mechanisms() else name
    module_name, _, function_name = target.partition(":")
    try:
        module = importlib.import_module(module_name.strip())
    except ModuleNotFoundError as error:
        raise ValueError(f"mechanism {name!r}: module {module_name!r} is not importable "
                         f"({error}); known: {_known()}") from error
    evaluate = getattr(module, function_name.strip(), None)
    if not callable(evaluate):
        raise ValueError(f"mechanism {name!r}: {module_name} has no function {function_name!r}; "
                         f"known: {_known()}")
    return evaluate


def quantity_units(name: str) -> dict:
    """{parameter or metric name: unit} of mechanism ``name`` ({} when it declares none)."""
    entry = MECHANISMS["model"] if _model_path(name) else MECHANISMS.get(name)
    return dict(entry.load(entry.units)) if entry is not None and entry.units else {}


def coarsest_size_factor(name: str) -> float:
    """The size_factor a convergence study of mechanism ``name`` starts from (default 1)."""
    return MECHANISMS[name].coarsest_size_factor if name in MECHANISMS else 1.0


def report_sections() -> list[tuple[RegisteredMechanism, ReportSection]]:
    """Every report section, in report order (registry order, then each entry's own)."""
    return [(m, s) for m in BUILTIN for s in m.sections]


def command_modules() -> list:
    """The CLI modules of the registered mechanisms (each has ``register(subparsers)``)."""
    return [m.load(m.commands) for m in BUILTIN if m.commands]


def optimizers() -> dict:
    """{name: module} of the mechanisms that have a design search (``flexfem optimize``)."""
    return {m.name: m.load(m.optimizer) for m in BUILTIN if m.optimizer}
