"""The command line says what it does: every option's help shows its default, and a bad value
is refused with the option's name and what it expects, never an internal function name."""
import argparse

import pytest

from flexfem.studies.cli import build_parser, main


def _parsers(parser, path=("flexfem",)):
    yield path, parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _parsers(sub, path + (name,))


def test_every_option_help_shows_its_default():
    missing = []
    for path, parser in _parsers(build_parser()):
        text = parser.format_help()
        text = text[text.index("options:"):]  # the options' help, after the usage line
        for action in parser._actions:
            if action.option_strings and action.default not in (None, False, argparse.SUPPRESS) \
                    and action.help != argparse.SUPPRESS:
                flag = action.option_strings[-1]
                block = text[text.index("  " + flag):]
                following = block.find("\n  -", 2)   # the next option's line
                if "default" not in (block if following < 0 else block[:following]):
                    missing.append(f"{' '.join(path)} {flag}")
    assert missing == []


@pytest.mark.parametrize("argv, message", [
    (["dbma", "analyze", "--size-factor", "0"], "argument --size-factor: '0' must be a finite number > 0"),
    (["converge", "toy", "--metric", "x", "--tol", "abc"], "argument --tol: 'abc' is not a number"),
    (["converge", "toy", "--metric", "x", "--params", "[1]"], "argument --params: '[1]' must be a JSON object"),
    (["eightbar", "trace", "--travel", "-1"], "argument --travel: '-1' must be a finite number > 0"),
])
def test_a_bad_value_names_the_option(argv, message, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    err = capsys.readouterr().err
    assert exit_.value.code == 2 and message in err and "invalid" not in err
