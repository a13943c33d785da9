"""Selection rules for CAD geometry: a tiny, safe predicate language (no ``eval``).

A rule such as ``"x < 1e-9"`` or ``"abs(y - 0.02) < 1e-6 and zmax <= 0.001"`` is evaluated on
each gmsh entity of the rule's dimension. Names: ``x``, ``y``, ``z`` (the entity's centre of
mass, m) and ``xmin``, ``ymin``, ``zmin``, ``xmax``, ``ymax``, ``zmax`` (its bounding box, m).
Grammar: numbers, those names, ``+ - * /``, ``abs( )``, parentheses, comparisons
``< <= > >= ==`` (``==`` within 1e-9 relative), ``and``, ``or``, ``not``.
"""
import math
import re

NAMES = ("x", "y", "z", "xmin", "ymin", "zmin", "xmax", "ymax", "zmax")
_TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)|"
                    r"([A-Za-z_]\w*)|(<=|>=|==|[-+*/()<>]))")
_COMPARE = {"<": lambda a, b: a < b, "<=": lambda a, b: a <= b, ">": lambda a, b: a > b,
            ">=": lambda a, b: a >= b,
            "==": lambda a, b: math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)}
_ARITH = {"+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b,
          "/": lambda a, b: a / b}


def _tokenize(text: str) -> list[str]:
    tokens, pos = [], 0
    text = text.rstrip()
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise ValueError(f"cannot read {text[pos:].strip()!r} in {text!r}")
        tokens.append(m.group(0).strip())
        pos = m.end()
    return tokens


class _Parser:
    """Recursive descent: or > and > not > comparison > +- > */ > unary > atom. A node is a
    tuple ('num', v) | ('name', n) | (op, a, b) | ('neg', a) | ('abs', a) | ('not', a)."""

    def __init__(self, text: str):
        self.text, self.tokens, self.i = text, _tokenize(text), 0

    def peek(self):
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self, expected=None):
        token = self.peek()
        if token is None or (expected is not None and token != expected):
            raise ValueError(f"expected {expected or 'more'} at the end of {self.text!r}"
                             if token is None else f"expected {expected!r}, not {token!r}, in "
                             f"{self.text!r}")
        self.i += 1
        return token

    def parse(self):
        node = self.boolean("or")
        if self.peek() is not None:
            raise ValueError(f"unexpected {self.peek()!r} in {self.text!r}")
        if node[0] not in ("or", "and", "not", *_COMPARE):
            raise ValueError(f"{self.text!r} is not a condition; compare, e.g. 'x < 0.001'")
        return node

    def boolean(self, op):
        inner = (lambda: self.boolean("and")) if op == "or" else self.negation
        node = inner()
        while self.peek() == op:
            self.take()
            node = (op, node, inner())
        return node

    def negation(self):
        if self.peek() == "not":
            self.take()
            return ("not", self.negation())
        node = self.arith("+-")
        if self.peek() in _COMPARE:
            op = self.take()
            node = (op, node, self.arith("+-"))
        return node

    def arith(self, ops):
        inner = (lambda: self.arith("*/")) if ops == "+-" else self.unary
        node = inner()
        while self.peek() is not None and self.peek() in ops and len(self.peek()) == 1:
            op = self.take()
            node = (op, node, inner())
        return node

    def unary(self):
        if self.peek() in ("-", "+"):
            sign = self.take()
            node = self.unary()
            return ("neg", node) if sign == "-" else node
        return self.atom()

    def atom(self):
        token = self.take()
        if token == "(":
            node = self.boolean("or")
            self.take(")")
            return node
        if token == "abs":
            self.take("(")
            node = self.arith("+-")
            self.take(")")
            return ("abs", node)
        if token in NAMES:
            return ("name", token)
        if token[0].isdigit() or token[0] == ".":
            return ("num", float(token))
        raise ValueError(f"unknown name {token!r} in {self.text!r}; allowed: "
                         f"{', '.join(NAMES)}, abs, and, or, not")


def _evaluate(node, values: dict):
    kind = node[0]
    if kind == "num":
        return node[1]
    if kind == "name":
        return values[node[1]]
    if kind == "neg":
        return -_evaluate(node[1], values)
    if kind == "abs":
        return abs(_evaluate(node[1], values))
    if kind == "not":
        return not _evaluate(node[1], values)
    a, b = _evaluate(node[1], values), _evaluate(node[2], values)
    if kind == "and":
        return a and b
    if kind == "or":
        return a or b
    if kind in _COMPARE:
        return _COMPARE[kind](a, b)
    return _ARITH[kind](a, b)


def _check_types(node, want_bool: bool, text: str) -> None:
    """Refuse arithmetic on conditions and logic on numbers, e.g. 'x and y'."""
    kind = node[0]
    is_bool = kind in ("and", "or", "not", *_COMPARE)
    if is_bool != want_bool:
        raise ValueError(f"{text!r}: {'a condition' if want_bool else 'a number'} was expected "
                         "where the other was given")
    if kind in ("and", "or"):
        _check_types(node[1], True, text)
        _check_types(node[2], True, text)
    elif kind == "not":
        _check_types(node[1], True, text)
    elif kind in ("neg", "abs"):
        _check_types(node[1], False, text)
    elif kind in _COMPARE or kind in _ARITH:
        _check_types(node[1], False, text)
        _check_types(node[2], False, text)


def compile_rule(text: str):
    """Parse ``text`` once; return ``predicate(values: dict) -> bool`` (values: the NAMES, m).
    Raises ValueError for anything outside the grammar."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"where = {text!r} must be a non-empty condition such as 'x < 0.001'")
    tree = _Parser(text).parse()
    _check_types(tree, True, text)
    return lambda values: bool(_evaluate(tree, values))


def entity_values(gmsh, dim: int, tag: int) -> dict:
    """The NAMES of one gmsh entity: centre of mass and bounding box (m)."""
    xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(dim, tag)
    if dim == 0:
        x, y, z = gmsh.model.getValue(0, tag, [])
    else:
        x, y, z = gmsh.model.occ.getCenterOfMass(dim, tag)
    return dict(zip(NAMES, (x, y, z, xmin, ymin, zmin, xmax, ymax, zmax)))
