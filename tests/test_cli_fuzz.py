"""Every numeric option of every ``flexfem`` command at extreme but finite values: 1e-300 and
1e300 (whole-number options also 0 and 10**300). The options are found by walking
``build_parser()``, so an option added to any command is fuzzed without editing this file.

Each call either succeeds (exit 0) with every number of its ``--json`` output finite, or is
refused: exit status 2, exactly one ``flexfem COMMAND: error: ...`` line on stderr that names
the option (or its quantity), no traceback -- never nan, inf, a hang or a stack dump.

The commands run in-process with their cheapest settings (a coarse 2-D mesh, ``--quick``,
in-process workers); the two accepted values that run a whole design search are marked slow.
"""
import argparse
import json
import math
import numbers
import warnings
from pathlib import Path

import pytest

from flexfem.studies.cli import build_parser, main

EXAMPLES = Path(__file__).parents[1] / "examples"
MODEL = str(EXAMPLES / "bodies" / "guide.toml")
TOY_STUDY = 'mechanism = "toy"\nname = "fuzz"\n[grid]\nlength_m = [0.05, 0.1]\n'

# What each command needs besides the fuzzed option: its required arguments (positionals,
# required options) and the cheapest sensible settings; "{tmp}" is the case's own folder.
# The fuzzed option comes last, so it overrides a setting given here. A command with a
# numeric option and a required argument must be listed (test_every_command_is_listed).
COMMAND_ARGS = {
    "dbma analyze": ["--dim", "2", "--size-factor", "20"],
    "dbma frf": ["--dim", "2", "--size-factor", "20"],
    "dbma mesh": ["{tmp}/dbma.msh", "--dim", "2", "--size-factor", "20"],
    "linkage trace": ["watt"],
    "eightbar trace": [],
    "eightbar analyze": ["--quick"],
    "eightbar driving": ["--model", "beam"],
    "eightbar mesh": ["{tmp}/eightbar.msh"],
    "analyze": [MODEL],
    "export": [MODEL, "{tmp}/guide.dxf"],
    "optimize dbma": ["--quick", "--max-evaluations", "8", "--out", "{tmp}/search"],
    "sweep": ["{tmp}/study.toml", "--out", "{tmp}/out", "--workers", "1"],
    "converge": ["toy", "--metric", "tip_deflection", "--out", "{tmp}/converge"],
}
# accepted values that run a whole design search (~30 s each): CI runs them (-m slow)
SLOW = {
    ("optimize dbma", "--min-frequency", "1e-300"),
    ("optimize dbma", "--min-output-stiffness", "1e-300"),
}
EXTREMES = ("1e-300", "1e300")
WHOLE_EXTREMES = ("0", str(10**300))
# warnings Python does not print by default (outside __main__)
QUIET = (DeprecationWarning, PendingDeprecationWarning, ImportWarning, ResourceWarning)
SAMPLES = ("1", "2", "3", "8", "0.5", "0.01", "1e-3", "3e-5")


def leaf_parsers(parser, path=()):
    """(command words, parser) of every command that runs: the leaves of the sub-commands."""
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield " ".join(path), parser
    for sub in subs:
        for name, child in sub.choices.items():
            yield from leaf_parsers(child, (*path, name))


def parsed_samples(action) -> list:
    """What the option's type makes of a few ordinary numbers (those it accepts)."""
    out = []
    for text in SAMPLES:
        try:
            out.append(action.type(text))
        except (ValueError, TypeError, argparse.ArgumentTypeError):
            pass
    return out


def is_number(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def numeric_options(parser) -> list[tuple[str, bool]]:
    """(option, whole) of each option whose type parses numbers; whole: it makes ints."""
    out = []
    for action in parser._actions:
        if not action.option_strings or action.type is None:
            continue
        values = parsed_samples(action)
        if values and all(is_number(v) for v in values):
            out.append((action.option_strings[-1], all(isinstance(v, int) for v in values)))
    return out


def required_arguments(parser) -> list[str]:
    return [a.dest for a in parser._actions
            if a.required or (not a.option_strings and a.nargs not in ("?", "*", 0))
            if not isinstance(a, argparse._SubParsersAction)]


COMMANDS = dict(leaf_parsers(build_parser()))
CASES = [(command, option, value)
         for command, parser in COMMANDS.items()
         for option, whole in numeric_options(parser)
         for value in EXTREMES + (WHOLE_EXTREMES if whole else ())]


def nonfinite(value, where="result"):
    """The places in a JSON value holding a number that is not finite (nan, inf)."""
    if isinstance(value, float) and not math.isfinite(value):
        yield where
    elif isinstance(value, dict):
        for key, item in value.items():
            yield from nonfinite(item, f"{where}[{key!r}]")
    elif isinstance(value, list):
        for i, item in enumerate(value):
            yield from nonfinite(item, f"{where}[{i}]")


def names_of(parser, option) -> set[str]:
    """The ways an error line may name ``option``: as given, its words, its destination."""
    action = next(a for a in parser._actions if option in a.option_strings)
    bare = option.lstrip("-")
    return {option, bare, bare.replace("-", "_"), bare.replace("-", " "), action.dest}


def run_case(command, option, value, tmp_path, capsys):
    (tmp_path / "study.toml").write_text(TOY_STUDY)
    argv = [*command.split(), *(a.format(tmp=tmp_path) for a in COMMAND_ARGS.get(command, [])),
            option, value, "--json"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("default")  # what the command line would print
        try:
            status = main(argv)
        except SystemExit as exit_:  # argparse refuses the value
            status = exit_.code
    out, err = capsys.readouterr()
    shown = " ".join(argv)
    # a warning is a line on stderr too (numpy's "overflow encountered", ...)
    shown_warnings = [f"{w.category.__name__}: {w.message}" for w in caught
                      if not issubclass(w.category, QUIET)]
    assert shown_warnings == [], f"{shown}: warnings {shown_warnings}"
    if status == 0:
        result = json.loads(out)
        assert list(nonfinite(result)) == [], f"{shown}: non-finite output"
        return
    assert status == 2, f"{shown}: exit {status}\n{err}"
    lines = err.splitlines()
    assert len(lines) == 1 and "Traceback" not in err, f"{shown}: not one line:\n{err}"
    assert lines[0].startswith(f"flexfem {command.split()[0]}") and ": error: " in lines[0], err
    assert any(name in lines[0] for name in names_of(COMMANDS[command], option)), \
        f"{shown}: the refusal does not name {option}: {lines[0]}"


def _param(case):
    marks = [pytest.mark.slow] if case in SLOW else []
    return pytest.param(*case, marks=marks, id=" ".join(case)[:80])


@pytest.mark.parametrize("command, option, value", [_param(c) for c in CASES])
def test_extreme_value_is_finite_output_or_one_line_refusal(command, option, value, tmp_path,
                                                            capsys):
    run_case(command, option, value, tmp_path, capsys)


def test_every_command_is_listed():
    """A command with numeric options and required arguments has its arguments here; every
    entry is a command that exists; the slow cases are cases."""
    fuzzed = {command for command, _, _ in CASES}
    missing = sorted(c for c in fuzzed if required_arguments(COMMANDS[c]) and c not in COMMAND_ARGS)
    assert missing == [], f"add the required arguments of {missing} to COMMAND_ARGS"
    assert set(COMMAND_ARGS) <= set(COMMANDS), set(COMMAND_ARGS) - set(COMMANDS)
    assert SLOW <= set(CASES), SLOW - set(CASES)


def test_the_walk_finds_the_numeric_options():
    """The discovery is not vacuous: options of each kind of type are found (int, float, the
    checked types of studies/options.py), whole-number ones as such, text ones left out."""
    found = {(c, o): whole for c, p in COMMANDS.items() for o, whole in numeric_options(p)}
    for key, whole in {("dbma analyze", "--size-factor"): False, ("dbma analyze", "--max-dofs"): True,
                       ("dbma frf", "--damping"): False, ("linkage trace", "--points"): True,
                       ("eightbar analyze", "--travel"): False, ("sweep", "--workers"): True,
                       ("converge", "--tol"): False, ("optimize dbma", "--stroke"): False,
                       ("analyze", "--dim"): True}.items():
        assert found.get(key) is whole, key
    assert ("converge", "--params") not in found and ("analyze", "--set") not in found
    assert len(CASES) > 100
