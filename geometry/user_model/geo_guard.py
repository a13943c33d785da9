"""A gmsh ``.geo`` is a program: check it before gmsh parses it.

gmsh's scripting language runs programs (``System``, ``SystemCall``, ``NonBlockingSystemCall``,
``OnelabRun``), writes files (``Printf(...) > "path"``, ``Print``, ``Save``, ``CreateDir``,
plugins, options that name files), reads files (``Include``, ``Merge``, ``ShapeFromFile``,
``GetEnv`` for the environment) and ends the process (``Exit``, ``Abort``). A model file is data
(docs/model_files.md, "What a model file may do"), so :func:`check_geo` refuses all of these,
naming the file, the line and the command, unless the user allows code. ``Include``/``Merge``
of a literal file name inside the model's folder stay allowed, and the included file is checked
in turn.

The check works on tokens outside comments and strings, with gmsh's own case-sensitive names;
it is a list of what reaches the operating system in gmsh's reference manual (the commands of
"General commands", "Loops and conditionals" and the file-handling string functions), kept
strict: an unknown command that looks like one of them is refused rather than guessed at.
"""
from pathlib import Path
import re

#: Commands that run a program, write or delete a file, or stop the process.
FORBIDDEN = {
    "System": "runs a shell command", "SystemCall": "runs a shell command",
    "NonBlockingSystemCall": "runs a shell command", "OnelabRun": "runs a program",
    "Shell": "runs a shell command", "Exit": "ends the process", "Abort": "ends the process",
    "Print": "writes a file", "Save": "writes a file", "CreateDir": "creates a folder",
    "CreateDirectory": "creates a folder", "DeleteFile": "deletes a file",
    "RenameFile": "renames a file", "Plugin": "runs a plugin (plugins may write files)",
    "GetEnv": "reads the environment", "Sleep": "stalls the process",
    "SetString": "sets a ONELAB string (program and file names)",
    "OnelabAction": "drives ONELAB clients",
}
#: Commands that read a file: allowed for a literal path inside the model's folder.
READS = ("Include", "Merge", "MergeWithBoundingBox", "ShapeFromFile")
#: Option categories a .geo may set: geometry and meshing only (General.* names files and
#: saves options on exit, Solver.* names executables, Print.*/PostProcessing.* write files).
OPTION_CATEGORIES = ("Geometry", "Mesh")
SAFE_GENERAL = ("Verbosity", "Terminal", "NumThreads", "Tolerance")

_TOKEN = re.compile(r'//[^\n]*|/\*.*?\*/|"(?:\\.|[^"\\])*"|[A-Za-z_]\w*|\S', re.S)


class CodeInGeometry(ValueError):
    """A .geo asks gmsh for something a model file may not do."""


def _tokens(text: str):
    """(token, line) pairs outside comments; strings kept whole with their quotes."""
    for match in _TOKEN.finditer(text):
        token = match.group()
        if token.startswith(("//", "/*")):
            continue
        yield token, text.count("\n", 0, match.start()) + 1


def _inside(path: Path, root: Path) -> bool:
    try:
        path.resolve().relative_to(root.resolve())
    except ValueError:
        return False
    return True


def check_geo(path, root=None, allow_code: bool = False, _seen=None) -> None:
    """Raise :class:`CodeInGeometry` (a ValueError) naming ``path``, the line and the command
    if the .geo ``path`` (or a file it includes) runs a program, writes, deletes or reads a file
    outside ``root`` (default: its own folder), reads the environment, sets an option outside
    Geometry.*/Mesh.* or ends the process. ``allow_code`` skips the check."""
    if allow_code:
        return
    path = Path(path)
    root = Path(root) if root is not None else path.parent
    seen = _seen if _seen is not None else set()
    if path.resolve() in seen:
        return
    seen.add(path.resolve())
    tokens = list(_tokens(path.read_text(errors="replace")))

    def refuse(line, what):
        raise CodeInGeometry(f"{path}:{line}: {what}; a model file's .geo may not do this "
                             "(docs/model_files.md, 'What a model file may do'). If you trust "
                             "this file, pass --allow-code (allow_code=True in Python)")

    for i, (token, line) in enumerate(tokens):
        after = tokens[i + 1][0] if i + 1 < len(tokens) else ""
        if token in FORBIDDEN:
            refuse(line, f"{token!r} {FORBIDDEN[token]}")
        if token in ("Printf", "Sprintf") and after == "(":
            depth, j = 0, i + 1
            while j < len(tokens):
                depth += {"(": 1, ")": -1}.get(tokens[j][0], 0)
                if depth == 0:
                    break
                j += 1
            if j + 1 < len(tokens) and tokens[j + 1][0] == ">":
                refuse(line, f"{token!r} with '>' writes a file")
        if token in READS:
            name = tokens[i + 2][0] if after == "(" and i + 2 < len(tokens) else after
            if not name.startswith('"'):
                refuse(line, f"{token!r} of a computed file name (give a literal \"FILE\")")
            target = (path.parent / name[1:-1]).resolve()
            if not _inside(target, root):
                refuse(line, f"{token!r} reads {name}, outside the model's folder {root}")
            if target.suffix.lower() == ".geo" and target.is_file():
                check_geo(target, root, allow_code, seen)
        if after == "." and i + 2 < len(tokens) and tokens[i + 2][0][:1].isalpha():
            option = tokens[i + 2][0]
            assigned = i + 3 < len(tokens) and tokens[i + 3][0] == "=" and (
                i + 4 >= len(tokens) or tokens[i + 4][0] != "=")
            if assigned and _is_category(token) and not (
                    token in OPTION_CATEGORIES or (token == "General" and option in SAFE_GENERAL)):
                refuse(line, f"setting the option {token}.{option} (only Geometry.* and Mesh.* "
                       "options may be set)")


def _is_category(name: str) -> bool:
    """gmsh's option categories (an assignment Category.Name = ... sets an option)."""
    return name in ("General", "Geometry", "Mesh", "Solver", "PostProcessing", "Print", "View",
                    "Fltk", "Plugin")


def check_inside(path, root, allow_code: bool = False) -> Path:
    """``path`` resolved (symlinks followed); ValueError if it lies outside ``root`` (the
    model file's folder) and the user has not allowed it."""
    resolved = Path(path).resolve()
    if not allow_code and not _inside(resolved, Path(root)):
        raise CodeInGeometry(f"{path} resolves to {resolved}, outside the model file's "
                             f"folder {Path(root).resolve()}; a model file reads only its own "
                             "folder (pass --allow-code to lift this)")
    return resolved
