"""Mechanism name -> evaluate function, resolved lazily from "module:function" strings.

An evaluate function is ``evaluate(params: dict, **options) -> dict[str, float]``: it fills
defaults for the parameters it is not given (the base design is the mechanism's own), and
returns its metrics, FEM and analytical side by side; it may also return ``"h"`` (a
characteristic element size, m) and ``"dofs"`` (the number of unknowns) for convergence
studies. Nothing is imported until a mechanism is asked for, so a study of the toy never
imports gmsh, and a mechanism whose module is not written yet fails only when it is used.
"""
import importlib

MECHANISMS = {
    "toy": "flexfem.studies.toy:evaluate",
    "dbma": "flexfem.studies.dbma_fem:evaluate",
    "eightbar": "flexfem.studies.eightbar_fem:evaluate",
}

# size_factor of the coarsest level of a convergence study (1 = the mechanism's default mesh):
# the DBMA starts coarser so that halving the size three times stays affordable; the eight-bar's
# default (3 elements across each flexure) is already its coarsest.
COARSEST_SIZE_FACTOR = {"dbma": 4.0, "eightbar": 1.0}


def coarsest_size_factor(name: str) -> float:
    """The size_factor a convergence study of mechanism ``name`` starts from (default 1)."""
    return COARSEST_SIZE_FACTOR.get(name, 1.0)


def is_target(name: str) -> bool:
    """True for a "package.module:function" string (an evaluate given by its import path)."""
    module, sep, function = name.partition(":")
    return bool(sep) and bool(module) and function.isidentifier()


def check_mechanism(name: str, key: str = "mechanism") -> str:
    """Return ``name`` if it is a registered mechanism or a "module:function" target, without
    importing anything; otherwise raise ValueError naming ``key`` and the known names."""
    if not isinstance(name, str) or not (name in MECHANISMS or is_target(name)):
        raise ValueError(f"{key} = {name!r} is not a known mechanism; known: {sorted(MECHANISMS)}"
                         " (or a 'package.module:function' evaluate)")
    return name


def get_evaluator(name: str):
    """The evaluate function of mechanism ``name`` (a key of MECHANISMS or "module:function").

    Raises ValueError listing the known names when the name is unknown, or when its module
    cannot be imported (yet) or lacks the function.
    """
    target = MECHANISMS.get(check_mechanism(name))
    target = target or name
    module_name, _, function_name = target.partition(":")
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as error:
        raise ValueError(f"mechanism {name!r}: module {module_name!r} is not importable "
                         f"({error}); known: {sorted(MECHANISMS)}") from error
    evaluate = getattr(module, function_name, None)
    if not callable(evaluate):
        raise ValueError(f"mechanism {name!r}: {module_name} has no function {function_name!r}; "
                         f"known: {sorted(MECHANISMS)}")
    return evaluate
