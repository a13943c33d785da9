"""Functions imported when first called: the command line's modules name what their commands
compute with (meshing, solvers, plotting, the topology optimisation) without importing it, so
that ``flexfem`` parses a command line, and runs a light command, without scikit-fem, gmsh or
matplotlib (studies/cli.py).

    stage_study = Lazy(".stage:stage_study", __package__)   # in studies/eightbar/cli.py
    stage_study(quick=True)                                  # imports .stage, then calls
"""
import importlib


class Lazy:
    """The callable "module:attribute" (``module`` relative to ``package`` where it starts
    with a dot), imported on the first call and kept; a module attribute holding one can be
    replaced as the function itself could (a test's monkeypatch)."""

    def __init__(self, target: str, package: str | None = None):
        module, sep, attribute = target.partition(":")
        if not (sep and module and attribute.isidentifier()):
            raise ValueError(f"Lazy({target!r}): write 'module:attribute'")
        self.target, self.package, self._function = target, package, None

    def resolve(self):
        """The named object, imported now if it was not yet."""
        if self._function is None:
            module, _, attribute = self.target.partition(":")
            self._function = getattr(importlib.import_module(module, self.package), attribute)
        return self._function

    def __call__(self, *args, **kwargs):
        return self.resolve()(*args, **kwargs)

    def __repr__(self) -> str:
        return f"Lazy({self.target!r}{'' if self.package is None else f', {self.package!r}'})"
