"""The one expression language of model files, parsed and checked once, never ``eval``-ed.

Numbers (``1e-9``), the names the caller allows, ``pi``, ``+ - * / **``, parentheses and the
functions ``sqrt sin cos tan atan atan2 abs`` make a number; comparisons ``< <= > >= ==``
(``==`` within 1e-9 relative), ``and``, ``or``, ``not`` make a condition. A beam's coordinate
(``"L / (2 * sqrt(2))"``, beam_tables.py, mechanism_tables.py) is a number; a CAD file's
``[[select]]`` rule (``"x < 0.001 and abs(y) < 1e-6"``, selection.py) a condition. Anything
else (attributes, calls of other names, chained comparisons, logic on numbers or arithmetic
on conditions) is refused with a ValueError naming the expression and the problem.
"""
import ast
from functools import lru_cache
import math
import operator

from ...fem.checks import is_finite as is_number

FUNCTIONS = {"sqrt": (math.sqrt, 1), "sin": (math.sin, 1), "cos": (math.cos, 1),
             "tan": (math.tan, 1), "atan": (math.atan, 1), "atan2": (math.atan2, 2),
             "abs": (abs, 1)}
CONSTANTS = {"pi": math.pi}
MAX_LENGTH = 2000  # characters: a model file's expression is a line, not a program
MAX_DEPTH = 100  # nested operations, well inside Python's recursion limit
_BINARY = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
           ast.Div: operator.truediv, ast.Pow: operator.pow}
_COMPARE = {ast.Lt: operator.lt, ast.LtE: operator.le, ast.Gt: operator.gt,
            ast.GtE: operator.ge,
            ast.Eq: lambda a, b: math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)}
_ARITHMETIC = f"+ - * / **, parentheses, pi and {', '.join(FUNCTIONS)}"


class Expression:
    """A checked expression: ``expression(values) -> float | bool``, ``values`` {name: float}
    holding every allowed name it uses; ``condition``: True for a condition."""

    def __init__(self, text: str, function, condition: bool):
        self.text, self._function, self.condition = text, function, condition

    def __call__(self, values: dict):
        try:
            result = self._function(values)
        except (ZeroDivisionError, OverflowError, TypeError, ValueError) as error:
            raise ValueError(f"{self.text!r} cannot be evaluated ({error})") from None
        if not self.condition and not math.isfinite(result):
            raise ValueError(f"{self.text!r} = {result} is not finite")
        return result


def names_in(text) -> set:
    """The names an expression string uses (empty for anything that does not parse)."""
    try:
        tree = _parse(text) if isinstance(text, str) else None
    except ValueError:
        return set()
    if tree is None:
        return set()
    return {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}


@lru_cache(maxsize=1024)
def compile_expression(text: str, names: frozenset, condition: bool = False,
                       what: str = "a parameter of the geometry") -> Expression:
    """Check ``text`` once: a number (or, ``condition``, a condition) of ``names`` (m); an
    unknown name is refused as not being ``what``. Raises ValueError naming text and problem."""
    tree = _parse(text, condition)
    function, is_condition = _build(tree.body, _Context(text, names, condition, what))
    if is_condition != condition:
        raise ValueError(f"{text!r} is not a condition; compare, e.g. 'x < 0.001'" if condition
                         else f"{text!r} is a condition, not a number")
    return Expression(text, function, condition)


def evaluate_expression(value, names: dict, where: str) -> float:
    """A number, or an expression string of ``names`` ({name: float}), as a float; ValueError
    prefixed by ``where`` otherwise."""
    if is_number(value):
        return float(value)
    if not isinstance(value, str):
        raise ValueError(f"{where}: {value!r} must be a number (m) or an expression string")
    try:
        return compile_expression(value, frozenset(names))(names)
    except ValueError as error:
        raise ValueError(f"{where}: {error}") from None


@lru_cache(maxsize=1024)
def _parse(text: str, condition: bool = False) -> ast.Expression:
    kind = "a condition" if condition else "an arithmetic expression"
    if len(text) > MAX_LENGTH:
        raise ValueError(f"{text[:40]!r}... is not {kind}: over {MAX_LENGTH} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except (SyntaxError, RecursionError, MemoryError):
        raise ValueError(f"{text!r} is not {kind}") from None
    if _depth(tree) > MAX_DEPTH:
        raise ValueError(f"{text[:40]!r}... is not {kind}: nested over {MAX_DEPTH} deep")
    return tree


def _depth(tree) -> int:
    """The deepest nesting of the ast ``tree``, counted without recursion."""
    deepest, stack = 0, [(tree, 1)]
    while stack:
        node, depth = stack.pop()
        deepest = max(deepest, depth)
        stack.extend((child, depth + 1) for child in ast.iter_child_nodes(node))
    return deepest


class _Context:
    def __init__(self, text, names, condition, what):
        self.text, self.names, self.what = text, names, what
        logic = ", comparisons, and, or, not" if condition else ""
        self.language = (f"only numbers, {'parameters' if not condition else 'names'}, "
                         f"{_ARITHMETIC}{logic} are allowed")

    def refuse(self, problem=None):
        return ValueError(f"{self.text!r}: {problem or self.language}")


def _numbers(nodes, ctx):
    """The functions of ``nodes``, each required to give a number."""
    out = []
    for node in nodes:
        f, is_condition = _build(node, ctx)
        if is_condition:
            raise ctx.refuse("a number was expected where a condition was given")
        out.append(f)
    return out


def _build(node, ctx):
    """(function of the values, True for a condition) of one checked ast node."""
    if isinstance(node, ast.Constant) and is_number(node.value):
        value = float(node.value)
        return (lambda v: value), False
    if isinstance(node, ast.Name):
        return _name(node.id, ctx), False
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
        f, is_condition = _build(node.operand, ctx)
        if not is_condition:
            raise ctx.refuse("a condition was expected where a number was given")
        return (lambda v: not f(v)), True
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        f, = _numbers([node.operand], ctx)
        return ((lambda v: -f(v)) if isinstance(node.op, ast.USub) else f), False
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        op, (a, b) = _BINARY[type(node.op)], _numbers([node.left, node.right], ctx)
        return (lambda v: op(a(v), b(v))), False
    if isinstance(node, ast.BoolOp):
        parts = [_build(n, ctx) for n in node.values]
        if not all(is_condition for _, is_condition in parts):
            raise ctx.refuse("a condition was expected where a number was given")
        fs = [f for f, _ in parts]
        if isinstance(node.op, ast.And):
            return (lambda v: all(f(v) for f in fs)), True
        return (lambda v: any(f(v) for f in fs)), True
    if isinstance(node, ast.Compare) and all(type(op) in _COMPARE for op in node.ops):
        if len(node.ops) != 1:
            raise ctx.refuse("one comparison at a time: join them with and")
        op, (a, b) = _COMPARE[type(node.ops[0])], _numbers([node.left, *node.comparators], ctx)
        return (lambda v: op(a(v), b(v))), True
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
            and node.func.id in FUNCTIONS and not node.keywords):
        function, arity = FUNCTIONS[node.func.id]
        if len(node.args) != arity:
            raise ctx.refuse(f"{node.func.id} takes {arity} argument{'s' * (arity > 1)}")
        args = _numbers(node.args, ctx)
        return (lambda v: function(*(a(v) for a in args))), False
    raise ctx.refuse()


def _name(name, ctx):
    if name in CONSTANTS:
        value = CONSTANTS[name]
        return lambda v: value
    if name not in ctx.names:
        raise ValueError(f"{name!r} in {ctx.text!r} is not {ctx.what}; known: "
                         f"{', '.join(sorted(ctx.names)) or 'none'}")
    return lambda v: float(v[name])
