"""Command-line value types: each refuses a bad value with a message that names what it
expects, which argparse prints after the option's name ("argument --tol: ...")."""
import argparse
import json
import math

from ..fem import checks


def _checked(text: str, check, what: str | None = None, **options):
    """The number ``text`` through ``check`` (fem/checks.py: positive, in_range, count; a
    count's 1e6 read as 1000000), refused in the command line's words ("'0' must be a finite
    number > 0"); ``what`` (e.g. "a size factor ...") replaces the check's own words."""
    try:
        value = float(text)
    except ValueError:
        value = None  # not a number: refused below
    if check is checks.count and checks.is_finite(value) and value == int(value):
        value = int(value)
    try:
        return check("", value, **options)
    except checks.InputError as error:
        expected = what or error.must
        raise argparse.ArgumentTypeError(f"{_shown(text)} is not a number; expected {expected}"
                                         if value is None else
                                         f"{_shown(text)} must be {expected}") from None


def _shown(text: str) -> str:
    """The value as typed, shortened where it is long (10**300 written out)."""
    return repr(text) if len(text) <= 24 else f"{text[:12]!r}... ({len(text)} characters)"


def positive(text: str) -> float:
    """A finite number > 0."""
    return _checked(text, checks.positive)


def length(text: str) -> str | float:
    """A length > 0: a number (m), or a number with a unit ("2 mm"; the model file's reading
    checks that the unit is a length)."""
    try:
        value = float(text)
    except ValueError:
        if text.strip()[:1].isdigit() or text.strip()[:1] == ".":
            return text.strip()
        raise argparse.ArgumentTypeError(f"{text!r} is not a length; expected a number > 0 (m) "
                                         "or one with a unit, e.g. 0.002 or '2 mm'") from None
    if not (math.isfinite(value) and 1e-9 <= value <= 10.0):
        raise argparse.ArgumentTypeError(f"{text!r} must be a length from 1e-09 to 10 (m): a "
                                         "flexure mechanism is 1 um to 10 m")
    return value


def size_factor(text: str) -> float:
    """A size factor from 0.001 to 1000 (1: the default mesh)."""
    return _checked(text, checks.in_range, "a size factor from 0.001 to 1000 (1: the default "
                    "mesh)", bounds=(1e-3, 1e3))


def count(text: str) -> int:
    """A whole number >= 1 (1e6 is accepted as 1000000)."""
    return _checked(text, checks.count)


def whole_number(low: int, high: int):
    """The type of an option that takes a whole number from ``low`` to ``high`` (1e3 is
    accepted as 1000): a count whose upper end bounds the work or memory it asks for."""

    def parse(text: str) -> int:
        return _checked(text, checks.count, least=low, most=high)

    parse.__name__ = "whole_number"
    return parse


def damping_ratio(text: str) -> float:
    """A damping ratio in (0, 1)."""
    return _checked(text, checks.in_range, "a damping ratio in (0, 1), e.g. 0.02",
                    bounds=(0, 1), closed=False)


def tolerance(text: str) -> float:
    """A relative tolerance, '0.5%' or 0.005."""
    from .engine.convergence import parse_tolerance  # with plotting: only when --tol is given

    try:
        return parse_tolerance(text)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error).replace("tol = ", "")) from None


def json_object(text: str) -> dict:
    """A JSON object, e.g. '{"length_m": 0.05}'."""
    try:
        value = json.loads(text)
    except json.JSONDecodeError as error:
        raise argparse.ArgumentTypeError(f"{text!r} is not JSON ({error.msg}); expected an "
                                         "object such as '{\"length_m\": 0.05}'") from None
    if not isinstance(value, dict):
        raise argparse.ArgumentTypeError(f"{text!r} must be a JSON object of parameters")
    return value


MODELS = ("continuum", "beam")


def add_model_options(parser, model_help: str, dim_default: int | None = None,
                      dim_help: str | None = None, dest: str = "model") -> None:
    """A command's ``--model continuum|beam`` (default continuum: the FEM; beam: the reduced
    beam model) and, with ``dim_help``, its ``--dim 2|3`` (default ``dim_default``)."""
    parser.add_argument("--model", dest=dest, choices=MODELS, default="continuum",
                        help=model_help)
    if dim_help is not None:
        parser.add_argument("--dim", type=int, choices=(2, 3), default=dim_default,
                            help=dim_help)


class DefaultsHelp(argparse.ArgumentDefaultsHelpFormatter):
    """Help that shows every option's default, unless the help text already says it."""

    def _get_help_string(self, action):
        text = action.help or ""
        if "default" in text or action.default in (None, False, argparse.SUPPRESS):
            return text
        return super()._get_help_string(action)


class Parser(argparse.ArgumentParser):
    """An argument parser whose help shows defaults; its sub-command parsers are Parsers too
    (argparse makes sub-parsers of the parent's class).

    A sub-command may add its arguments later (:func:`deferred`): its parser is built when it
    is first used (parsing its words, its help, a look at its actions), so that the command
    line starts without importing what only the other commands' options need."""

    def __init__(self, *args, **kwargs):
        self.__dict__["_pending"] = None  # argparse's own __init__ reads _actions
        kwargs.setdefault("formatter_class", DefaultsHelp)
        super().__init__(*args, **kwargs)

    @property
    def _actions(self):
        if self._pending is not None:
            build, self._pending = self._pending, None
            build(self)
        return self.__dict__["_actions"]

    @_actions.setter
    def _actions(self, actions):
        self.__dict__["_actions"] = actions

    def parse_known_args(self, args=None, namespace=None):
        self._actions  # noqa: B018 - builds a deferred parser before argparse reads its parts
        return super().parse_known_args(args, namespace)

    def format_usage(self):
        self._actions  # noqa: B018
        return super().format_usage()

    def format_help(self):
        self._actions  # noqa: B018
        return super().format_help()

    def error(self, message):
        """A bad command line is one ``flexfem COMMAND: error: ...`` line and exit status 2,
        as every other error the user can cause (argparse would print the usage first)."""
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def deferred(parser, build) -> None:
    """``build(parser)`` (it adds the parser's arguments and defaults) when ``parser`` is first
    used, if it is a :class:`Parser`; at once otherwise (a plain argparse parser)."""
    if isinstance(parser, Parser):
        parser._pending = build
    else:
        build(parser)
