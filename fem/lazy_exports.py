"""A package whose public names are imported on first use (so that importing it, e.g. for the
command line's parsers, does not import the solvers behind them)."""
import importlib


def lazy_exports(package: str, exports: dict) -> tuple:
    """``(__getattr__, __dir__)`` for the package ``package`` (its ``__name__``): ``exports``
    maps each name to the submodule (relative, without the dot) that defines it; a name is
    imported on first use and then cached in the package."""
    def __getattr__(name: str):
        if name not in exports:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f".{exports[name]}", package), name)
        setattr(importlib.import_module(package), name, value)
        return value

    def __dir__() -> list:
        return sorted(set(vars(importlib.import_module(package))) | set(exports))

    return __getattr__, __dir__
