"""The ``flexfem`` command: a thin layer over the Python API.

Each command module registers its sub-command with ``register(subparsers)`` and sets two
defaults on its parser: ``run(args) -> dict`` (JSON-able, computed by one public function) and
``summarize(result) -> str`` (the human summary). The mechanisms' commands come from the
registry (studies/mechanisms.py); this module only dispatches: with ``--json`` it prints the
dict as one JSON object and nothing else on stdout, otherwise the summary.

Every error the user can cause is one ``flexfem COMMAND: error: ...`` line on stderr and exit
status 2: a bad value (ValueError, TypeError), a file that cannot be read or written
(OSError: missing, a folder, no permission), a damaged result store (sqlite3). Ctrl-C exits
with 130 at once, even inside gmsh or a solver: the command runs in a worker thread and the
main thread, which receives SIGINT, ends the process (a study's store commits each case
atomically, so nothing is left half-written; its worker processes exit with their parent).
A closed stdout (``| head -1``) exits quietly.

The command line starts lightly: the command modules hold their parsers and import what a
command computes with (scikit-fem, gmsh, matplotlib, the topology optimisation) inside its
``run``; a parser whose options need a heavy module is built when its command is chosen
(``options.deferred``). ``flexfem analyze FILE --model beam`` imports none of them
(tests/studies/test_cli_imports.py).
"""
import argparse
import json
import os
import sqlite3
import sys
import threading
import warnings

from . import run_cli
from .engine.serialize import jsonable
from .lazy import Lazy
from .mechanisms import command_modules, optimizers
from .options import Parser, deferred
from .report import cli as report_cli
from .spatial import cli as spatial_cli

TOPOPT_HELP = "topology optimisation of a 2-D structure or compliant mechanism from a problem file"
TOPOPT_DESCRIPTION = ("``flexfem topopt PROBLEM.toml [--json] [--out DIR]``: optimise the "
                      "design a problem file describes; the state after every iteration, the "
                      "densities and the result go into DIR, and a rerun with the same DIR "
                      "continues where the last one stopped.")


def register_optimize(subparsers) -> None:
    """``flexfem optimize MECHANISM``: the design search of each mechanism that has one (its
    options built, and its module imported, when that search is the command)."""
    parser = subparsers.add_parser("optimize", help="design search of a mechanism's dimensions")
    choices = parser.add_subparsers(dest="mechanism", required=True, metavar="MECHANISM")
    for name, module in optimizers().items():
        sub = choices.add_parser(name, help=module.HELP)
        sub.set_defaults(run=module.run, summarize=module.summarize)
        deferred(sub, module.add_arguments)  # its defaults: the search's (OptimizeSpec)


def register_topopt(subparsers) -> None:
    """``flexfem topopt PROBLEM.toml``: its parser here, flexfem.topopt imported by its run."""
    parser = subparsers.add_parser("topopt", help=TOPOPT_HELP, description=TOPOPT_DESCRIPTION)
    parser.add_argument("problem", help="problem file (TOML; see docs/topopt.md)")
    parser.add_argument("--out", default=None,
                        help="output folder (default: PROBLEM's name + '_topopt' here)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(run=Lazy("..topopt.cli:run", __package__),
                        summarize=Lazy("..topopt.cli:summarize", __package__))


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="flexfem", description=__doc__.splitlines()[0])
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    report_cli.register(subparsers)
    for module in command_modules():
        module.register(subparsers)
    register_optimize(subparsers)
    run_cli.register(subparsers)
    register_topopt(subparsers)
    spatial_cli.register(subparsers)
    return parser


USER_ERRORS = (ValueError, TypeError, OSError, sqlite3.Error, ArithmeticError)


def _one_line(error: BaseException) -> str:
    text = " ".join(str(error).split()) or type(error).__name__
    return text if isinstance(error, (ValueError, TypeError)) else f"{type(error).__name__}: {text}"


def _output(args, result) -> None:
    if getattr(args, "json", False):
        json.dump(jsonable(result), sys.stdout)
        sys.stdout.write("\n")
    else:
        print(args.summarize(result))
    sys.stdout.flush()


def run_interruptibly(function, *args):
    """``function(*args)`` in a worker thread, the main thread waiting in short joins: Ctrl-C
    reaches it (as KeyboardInterrupt) while the worker is inside C code (gmsh, a solver)."""
    box = {}

    def target():
        try:
            box["result"] = function(*args)
        except BaseException as error:  # noqa: BLE001 - handed to the main thread
            box["error"] = error

    thread = threading.Thread(target=target, name="flexfem-command", daemon=True)
    thread.start()
    while thread.is_alive():
        thread.join(0.1)
    if "error" in box:
        raise box["error"]
    return box["result"]


def _interrupted(command: str) -> int:
    print(f"flexfem {command}: interrupted; what completed is stored", file=sys.stderr)
    sys.stderr.flush()
    if threading.active_count() > 1:  # the command's thread may be inside gmsh: end here
        os._exit(130)
    return 130


# numpy's floating-point warnings (an overflow on the way to a refused non-finite result)
# would print lines of library internals before the one-line refusal that names the quantity
FLOATING_POINT = r".*(overflow|invalid value|divide by zero|underflow) encountered"


def main(argv=None) -> int:
    """Run one command; returns its exit status (2: a user error)."""
    args = build_parser().parse_args(argv)  # a bad command line: SystemExit(2), one line
    warnings.filterwarnings("ignore", FLOATING_POINT, RuntimeWarning)
    try:
        _output(args, run_interruptibly(args.run, args))
    except BrokenPipeError:  # the reader went away (| head -1): nothing more to say
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # Python's flush at exit would fail again
        return 0
    except KeyboardInterrupt:
        return _interrupted(args.command)
    except USER_ERRORS as error:
        print(f"flexfem {args.command}: error: {_one_line(error)}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
