"""The ``[outputs]`` table of a model file: named metrics, each an expression of
observations of groups (``GROUP.ux``, ``GROUP.uy``, ``GROUP.rz``; in 3-D also ``uz``,
``rx``, ``ry``) and of the file's [parameters], in the one expression language of model files
(expressions.py: never ``eval``-ed)::

    [outputs]
    R = "(out_top.uy - out_bottom.uy) / (2 * input.ux)"

A group is any group of the model: a body, a face of a body (``stage.top``,
``stage.face(+x)``, geometry/mechanism/faces.py), a geometry file's boundary group or
subdomain. Its displacement is its mean (as ``mean_displacement``), its rotation the rigid
rotation that fits its motion best (least squares, studies/user_model/observe.py). An unknown
group or component, a name that is no parameter, or an output named as a built-in metric is
refused when the file is read, naming the file, the line and the known names with the
nearest."""
from dataclasses import dataclass
import re

from .expressions import CONSTANTS, FUNCTIONS, compile_expression, names_in
from .names import nearest

COMPONENTS = {2: ("ux", "uy", "rz"), 3: ("ux", "uy", "uz", "rx", "ry", "rz")}
#: The flat metrics of a model file's evaluate (studies/user_model/analysis.py): names and
#: fnmatch patterns an output may not take.
BUILT_IN = ("dofs", "h", "max_von_mises", "mean_displacement_*", "reaction_*", "stiffness_*",
            "f*_hz", "buckling_factor_*", "compliance_*", "stroke_limit_yield",
            "stroke_limit_fatigue", "harmonic_resonance_hz", "observed_*", "not_available")
#: GROUP.COMPONENT: a group is a name, dotted names and face(+x) selectors; the last dotted
#: part is the component.
_TOKEN = re.compile(r"(?<![\w.])([A-Za-z_]\w*(?:\.(?:face\(\s*[+-]\s*[xyz]\s*\)|[A-Za-z_]\w*))*)"
                    r"\.([A-Za-z_]\w*)")
_NAME = re.compile(r"^[A-Za-z_]\w*$")


@dataclass(frozen=True)
class Output:
    """One [outputs] entry: ``name`` = ``text``; ``observed`` ((group, component), ...) in
    the order of the expression's placeholders; ``source``: 'file line N'."""

    name: str
    text: str
    observed: tuple
    source: str = ""
    _expression: object = None
    _parameters: tuple = ()

    @property
    def groups(self) -> list[str]:
        return list(dict.fromkeys(g for g, _ in self.observed))

    def value(self, observations: dict, parameters: dict) -> float:
        """The output's value from ``observations`` {group: {component: value}} (SI);
        ValueError naming the output where it cannot be evaluated (a division by zero)."""
        values = {**{k: parameters[k] for k in self._parameters},
                  **{f"__obs{i}": observations[g][c] for i, (g, c) in enumerate(self.observed)}}
        try:
            return float(self._expression(values))
        except ValueError as error:
            raise ValueError(f"{self.source}: [outputs] {self.name}: "
                             f"{str(error).replace(self._expression.text, self.text)}") from None


def _is_built_in(name: str) -> bool:
    from fnmatch import fnmatchcase

    return any(fnmatchcase(name, p) for p in BUILT_IN)


def _group_error(group, groups, where, text, name) -> ValueError:
    known = sorted(groups)
    listed = ", ".join(k for k in known if "." not in k) or "none"
    faces = any("." in k for k in known)
    hint = (" and their faces (BODY.top, .bottom, .left, .right, .face(+x), ...)"
            if faces else "")
    return ValueError(f"{where}: [outputs] {name} = {text!r}: {group!r} is not a group of the "
                      f"model; groups: {listed}{hint}{nearest(group, known)}")


def parse_outputs(raw, parameters: dict, groups, dim: int, loc) -> tuple:
    """The [outputs] table -> (Output, ...). ``parameters``: the names an expression may use
    besides observations; ``groups``: every group name that may be observed (bodies and all
    their faces, or the geometry's groups); ``loc``: the file's Locator (tables.py)."""
    if raw is None:
        return ()
    if not isinstance(raw, dict):
        raise loc.error(f"[outputs] must be a table of NAME = \"expression\", not {raw!r}",
                        None, "outputs")
    components = COMPONENTS[dim]
    out = []
    for name, text in raw.items():
        where = loc.at("outputs", name)
        if not _NAME.match(name):
            raise ValueError(f"{where}: [outputs] {name!r}: a name of letters, digits and _ "
                             "(not starting with a digit), usable as a study's metric")
        if _is_built_in(name) or name in parameters:
            what = "a built-in metric" if _is_built_in(name) else "a [parameters] name"
            raise ValueError(f"{where}: [outputs] {name!r} is {what}; give the output "
                             "another name")
        if not isinstance(text, str) or not text.strip():
            raise ValueError(f"{where}: [outputs] {name} = {text!r} must be an expression "
                             "string such as \"stage.ux / input.ux\"")
        observed, pieces, last = [], [], 0
        for m in _TOKEN.finditer(text):
            group, component = m.group(1), m.group(2)
            if group not in groups:
                raise _group_error(group, groups, where, text, name)
            if component not in components:
                raise ValueError(f"{where}: [outputs] {name} = {text!r}: {component!r} of "
                                 f"{group!r} is not a component; components ({dim}-D): "
                                 f"{', '.join(components)}{nearest(component, components)}")
            key = (group, component)
            if key not in observed:
                observed.append(key)
            pieces += [text[last:m.start()], f"__obs{observed.index(key)}"]
            last = m.end()
        substituted = "".join(pieces) + text[last:]
        for unknown in sorted(names_in(substituted) - set(parameters) - set(CONSTANTS)
                             - set(FUNCTIONS)):
            if unknown.startswith("__obs"):
                continue
            if unknown in groups:
                raise ValueError(f"{where}: [outputs] {name} = {text!r}: {unknown!r} is a "
                                 f"group; name its component, e.g. {unknown}.{components[0]} "
                                 f"({', '.join(components)})")
            known = sorted(set(parameters) | set(groups))
            raise ValueError(f"{where}: [outputs] {name} = {text!r}: {unknown!r} is neither a "
                             f"parameter ({', '.join(sorted(parameters)) or 'none'}) nor "
                             f"GROUP.COMPONENT nor a function ({', '.join(FUNCTIONS)})"
                             f"{nearest(unknown, known)}")
        used = tuple(sorted(names_in(substituted) & set(parameters)))
        allowed = frozenset(used) | {f"__obs{i}" for i in range(len(observed))}
        try:
            expression = compile_expression(substituted, allowed, what="a parameter")
        except ValueError as error:
            message = str(error).replace(repr(substituted), repr(text))
            raise ValueError(f"{where}: [outputs] {name}: {message}") from None
        out.append(Output(name, text, tuple(observed), where, expression, used))
    return tuple(out)


def output_names(raw: dict) -> list[str]:
    """The [outputs] names of a model file's raw TOML (for the study engine's metric names)."""
    table = raw.get("outputs", {})
    return list(table) if isinstance(table, dict) else []
