"""A gmsh ``.geo`` is a program: only what a geometry needs may run (an allow-list).

gmsh's scripting language can run programs, write and read files, prompt on stdin and end the
process. A model file is data (docs/model_files.md, "What a model file may do"), so
:func:`check_geo` reads a ``.geo`` the way gmsh's own lexer does (``src/parser/Gmsh.l``: both
``"..."`` and ``'...'`` strings, with no escapes; ``//`` and ``/* */`` comments; no line
continuations) and accepts only:

- the commands and functions of :data:`ALLOWED` (points, curves, surfaces, volumes, the
  OpenCASCADE primitives and booleans, extrusions, transforms, physical groups, mesh sizes,
  ``DefineConstant``, ``For``/``If``, arithmetic and string formatting);
- the user's own variables, used as variables (assigned, or read in an expression: a name
  followed by a string, number or another name would be a command gmsh knows by that name);
- ``Mesh.*``/``Geometry.*`` options of :data:`MESH_OPTIONS`/:data:`GEOMETRY_OPTIONS`, and
  ``Field`` types and options of :data:`FIELD_TYPES`/:data:`FIELD_OPTIONS`;
- ``Include``/``Merge``/``ShapeFromFile`` of a literal file name inside the model's folder,
  whose content (not its name) decides what it is: a mesh (``$MeshFormat``), a STEP or BREP
  file, or a script, checked by the same rules; compressed and binary files are refused;
- ``For`` loops whose literal bounds give at most :data:`MAX_LOOP` passes (a computed bound is
  held by the time limit of the child that runs gmsh, geometry/user_model/bounded.py).

Everything else is refused with its file, line and the reason, unless the user allows code.
"""
from dataclasses import dataclass
from pathlib import Path
import re

MAX_LOOP = 100_000

#: gmsh words a geometry needs: commands, functions, constants, and the words of its grammar.
ALLOWED = frozenset("""
Point Line Curve Circle Ellipse Ellipsis Spline BSpline Bezier CatmullRom Nurbs Knots Order Wire
Surface Plane Ruled Volume Loop Compound Physical In BoundingBox PointsOf Boundary
CombinedBoundary Duplicata Delete Recursive Physicals Coherence HealShapes Sewing
Rectangle Disk Box Block Sphere Cylinder Cone Torus Wedge Ellipsoid ThruSections ThickSolid
Fillet Chamfer BooleanUnion BooleanDifference BooleanIntersection BooleanFragments BooleanFuse
BooleanCut BooleanCommon BooleanCoherence BooleanSection
Extrude Layers Recombine ScaleLastLayer Using Rotate Translate Symmetry Dilate Affine
Characteristic Length MeshSize MeshAlgorithm Transfinite Progression Bump Beta Left Right
Alternate AlternateLeft AlternateRight Periodic Smoother Field Background
SetFactory DefineConstant DefineNumber Name Label Help Units Min Max Step Choices Visible
ReadOnly Highlight Closed
For EndFor If ElseIf Else EndIf Exists
Printf Sprintf Error Warning StrCat Str StrCmp StrLen StrSub StrFind StrReplace StrPrefix
UpperCase LowerCase StrChoice NameToString N2S StringToName S2N
Abs Fabs Acos ArcCos Asin ArcSin Atan ArcTan Atan2 ArcTan2 Ceil Floor Round Cos Cosh Sin Sinh
Tan Tanh Exp Log Log10 Sqrt Hypot Fmod Modulo Pi LinSpace LogSpace Unique Mass CenterOfMass
newp newl newc newll newcl news newsl newv newreg newf
""".split())

#: Words that read or write files: allowed with a literal name inside the model's folder.
READS = ("Include", "Merge", "ShapeFromFile")

#: Why some gmsh words are refused (any other word that is neither allowed nor a variable of
#: the file is refused too, as a command gmsh may know and this check does not).
REFUSED = {
    "System": "runs a shell command", "SystemCall": "runs a shell command",
    "NonBlockingSystemCall": "runs a shell command", "OnelabRun": "runs a program",
    "Shell": "runs a shell command", "Exit": "ends the process", "Abort": "ends the process",
    "Print": "writes a file", "Save": "writes a file", "CreateDir": "creates a folder",
    "CreateDirectory": "creates a folder", "DeleteFile": "deletes a file",
    "RenameFile": "renames a file", "Plugin": "runs a plugin (plugins may write files)",
    "GetEnv": "reads the environment", "Sleep": "stalls the process",
    "GetValue": "waits for an answer on the terminal", "GetString": "reads ONELAB strings",
    "GetNumber": "reads options by name", "SetString": "sets options and ONELAB strings",
    "SetNumber": "sets options by name", "OnelabAction": "drives ONELAB clients",
    "ListFromFile": "reads a file", "FileExists": "looks at files",
    "AbsolutePath": "looks at paths", "DirName": "looks at paths",
    "CurrentDirectory": "looks at paths", "CurrentDir": "looks at paths",
    "CurrentFileName": "looks at paths", "FixRelativePath": "looks at paths",
    "MergeWithBoundingBox": "reads a file", "Macro": "defines a macro (not needed for a "
    "geometry)", "Function": "defines a macro (not needed for a geometry)",
    "Call": "calls a macro", "Rand": "makes the geometry random", "Today": "reads the clock",
    "Cpu": "reads the clock", "Memory": "reads the machine", "TotalMemory": "reads the machine",
    "RefineMesh": "refines the mesh outside the size estimate",
    "Mesh": "meshes inside the script (flexfem meshes the geometry itself)",
    "View": "makes post-processing views", "Solver": "sets solver programs",
    "PostProcessing": "sets post-processing output", "Fltk": "drives the graphical interface",
    "General": "sets general options (files, programs, exit behaviour)",
}

#: Options a .geo may set (numbers that shape the geometry and its mesh, no files).
MESH_OPTIONS = frozenset("""
Algorithm Algorithm3D AlgorithmSwitchOnFailure AngleToleranceFacetOverlap AnisoMax
CharacteristicLengthExtendFromBoundary CharacteristicLengthFactor CharacteristicLengthFromCurvature
CharacteristicLengthFromPoints CharacteristicLengthMax CharacteristicLengthMin ElementOrder
HighOrderOptimize MeshSizeExtendFromBoundary MeshSizeFactor MeshSizeFromCurvature
MeshSizeFromCurvatureIsotropic MeshSizeFromParametricPoints MeshSizeFromPoints MeshSizeMax
MeshSizeMin MinimumCircleNodes MinimumCirclePoints MinimumCurveNodes MinimumCurvePoints
MinimumElementsPerTwoPi Optimize OptimizeNetgen OptimizeThreshold QualityType RandomFactor
RandomFactor3D RecombinationAlgorithm Recombine3DAll RecombineAll SecondOrderIncomplete
SecondOrderLinear Smoothing ToleranceEdgeLength ToleranceInitialDelaunay
""".split())
GEOMETRY_OPTIONS = frozenset("""
Tolerance ToleranceBoolean AutoCoherence OCCAutoFix OCCBooleanPreserveNumbering OCCFixDegenerated
OCCFixSmallEdges OCCFixSmallFaces OCCSewFaces OCCMakeSolids OCCParallel OCCScaling OCCUnionUnify
OCCBoundsUseStl ExactExtrusion ExtrudeReturnLateralEntities ExtrudeSplinePoints
CopyMeshingMethod MatchMeshTolerance Points Curves Surfaces Volumes PointNumbers CurveNumbers
SurfaceNumbers VolumeNumbers LabelType OCCTargetUnit
""".split())
FIELD_TYPES = frozenset("Box Ball Cylinder Frustum Distance Attractor Threshold Min Max "
                        "Constant Restrict".split())
FIELD_OPTIONS = frozenset("""
VIn VOut XMin XMax YMin YMax ZMin ZMax Thickness Radius XCenter YCenter ZCenter XAxis YAxis
ZAxis R1_inner R1_outer R2_inner R2_outer V1_inner V1_outer V2_inner V2_outer X1 Y1 Z1 X2 Y2 Z2
PointsList CurvesList SurfacesList VolumesList NodesList EdgesList FacesList RegionsList
Sampling NumPointsPerCurve InField IField SizeMin SizeMax LcMin LcMax DistMin DistMax
StopAtDistMax Sigmoid FieldsList IncludeBoundary
""".split())

_ASSIGN = {"=", "+=", "-=", "*=", "/="}
_OPERATORS = frozenset("; = += -= *= /= : ... || && ++ -- == != <= >= >> << + - * / ^ % ( ) [ ] "
                       "{ } , < > ! ? # ~ & |".split())
_LEXEME = re.compile(r"""
    (?P<space>[ \t\r\n\f\v]+)
  | (?P<comment>//[^\n]*|/\*.*?(?:\*/|\Z))
  | (?P<string>"[^"]*(?:"|\Z)|'[^']*(?:'|\Z))
  | (?P<number>\d+\.\d*(?:[eE][-+]?\d+)?|\d*\.\d+(?:[eE][-+]?\d+)?|\d+[eE][-+]?\d+|\d+)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<op>\.\.\.|::|\|\||&&|\+\+|--|==|!=|<=|>=|>>|<<|\+=|-=|\*=|/=|.)
""", re.S | re.X)


class CodeInGeometry(ValueError):
    """A .geo asks gmsh for something a model file may not do."""


@dataclass(frozen=True)
class Token:
    kind: str  # "string", "number", "name" or "op"
    text: str
    line: int


def file_kind(path: Path) -> str:
    """What a file is by its content: "mesh" ($MeshFormat), "step", "brep", "compressed",
    "binary" or "script" (text gmsh would parse as a .geo)."""
    with open(path, "rb") as f:
        head = f.read(4096)
    start = head.lstrip()
    if head[:2] == b"\x1f\x8b" or head[:4] in (b"PK\x03\x04", b"BZh9") or head[:6] == b"\xfd7zXZ\x00":
        return "compressed"
    if start.startswith(b"$MeshFormat"):
        return "mesh"
    if start.startswith(b"ISO-10303-21"):
        return "step"
    if start.startswith((b"DBRep_DrawableShape", b"CASCADE Topology")):
        return "brep"
    if b"\x00" in head:
        return "binary"
    try:
        head.decode("utf-8")
    except UnicodeDecodeError as error:
        if error.start < len(head) - 4:  # not just a character cut at the 4096th byte
            return "binary"
    return "script"


def tokens(text: str, path) -> list[Token]:
    """The .geo ``text`` as gmsh's lexer splits it, comments dropped; CodeInGeometry for an
    unterminated string or comment."""
    out, line = [], 1
    for match in _LEXEME.finditer(text):
        kind, lexeme = match.lastgroup, match.group()
        if kind == "comment" and lexeme.startswith("/*") and not lexeme.endswith("*/"):
            raise CodeInGeometry(f"{path}:{line}: a /* comment is never closed")
        if kind == "string" and (len(lexeme) < 2 or lexeme[-1] != lexeme[0]):
            raise CodeInGeometry(f"{path}:{line}: a string is never closed")
        if kind not in ("space", "comment"):
            out.append(Token(kind, lexeme, line))
        line += lexeme.count("\n")
    return out


def _inside(path: Path, root: Path) -> bool:
    try:
        path.resolve().relative_to(root.resolve())
    except ValueError:
        return False
    return True


def _refuse(path, line, what):
    raise CodeInGeometry(f"{path}:{line}: {what}; a model file's .geo may not do this "
                         "(docs/model_files.md, 'What a model file may do'). If you trust this "
                         "file, pass --allow-code (allow_code=True in Python)")


def _closing(toks: list[Token], i: int) -> int:
    """Index of the bracket closing the one at ``i`` (len(toks) if none)."""
    pairs = {"(": ")", "[": "]", "{": "}"}
    depth, opener = 0, toks[i].text
    for j in range(i, len(toks)):
        if toks[j].kind == "op" and toks[j].text == opener:
            depth += 1
        elif toks[j].kind == "op" and toks[j].text == pairs[opener]:
            depth -= 1
            if depth == 0:
                return j
    return len(toks)


def _text(toks, i) -> str:
    return toks[i].text if 0 <= i < len(toks) else ""


def _defined(toks: list[Token]) -> set:
    """The variables a file defines: names assigned (``x =``, ``x[] =``, ``x(1) +=``,
    ``x~{i} =``, ``x++``) and loop variables."""
    names = set()
    for i, tok in enumerate(toks):
        if tok.kind != "name" or tok.text in ALLOWED or tok.text in REFUSED:
            continue
        j = i + 1
        while _text(toks, j) == "~" and _text(toks, j + 1) == "{":
            j = _closing(toks, j + 1) + 1
        if _text(toks, j) in ("[", "("):
            j = _closing(toks, j) + 1
        if _text(toks, j) in _ASSIGN | {"++", "--"} or _text(toks, i - 1) == "For":
            names.add(tok.text)
    return names


def _loop_count(toks: list[Token], i: int):
    """Passes of the ``For`` at ``i`` when its range is literal numbers, else None."""
    j = i + 1
    if _text(toks, j) == "(":
        start = j
    else:
        start = j + 2 if _text(toks, j + 1) == "In" else j
    if _text(toks, start) not in ("(", "{"):
        return None
    end = _closing(toks, start)
    values, sign = [], 1.0
    for tok in toks[start + 1:end]:
        if tok.kind == "op" and tok.text == "-":
            sign = -sign
        elif tok.kind == "number":
            values.append(sign * float(tok.text))
            sign = 1.0
        elif not (tok.kind == "op" and tok.text == ":"):
            return None
    if len(values) not in (2, 3):
        return None
    step = values[2] if len(values) == 3 else 1.0
    if step == 0:
        return float("inf")
    return max(0.0, (values[1] - values[0]) / step + 1)


def _gather(path: Path, root: Path, files: dict) -> None:
    """Lex ``path`` and every script it includes into ``files`` {path: tokens}, checking
    each Include/Merge/ShapeFromFile target."""
    resolved = path.resolve()
    if resolved in files:
        return
    kind = file_kind(path)
    if kind != "script":
        _refuse(path, 1, f"the file is {kind}, not a .geo script")
    toks = tokens(path.read_text(encoding="utf-8", errors="replace"), path)
    files[resolved] = (path, toks)
    for i, tok in enumerate(toks):
        if tok.kind != "name" or tok.text not in READS:
            continue
        j = i + 2 if _text(toks, i + 1) == "(" else i + 1
        if j >= len(toks) or toks[j].kind != "string" or _text(toks, j + 1) not in (";", ")"):
            _refuse(path, tok.line, f"{tok.text!r} of a computed file name (give a literal "
                                    "\"FILE\")")
        name = toks[j].text[1:-1]
        target = path.parent / name
        if not _inside(target, root):
            _refuse(path, tok.line, f"{tok.text!r} reads {name!r}, outside the model's folder "
                                    f"{root}")
        if not target.is_file():
            _refuse(path, tok.line, f"{tok.text!r} reads {name!r}, which does not exist")
        what = file_kind(target)
        if what in ("compressed", "binary"):
            _refuse(path, tok.line, f"{tok.text!r} reads {name!r}, a {what} file (gmsh would "
                                    "unpack it into the folder); give it uncompressed")
        if what == "script":
            _gather(target, root, files)


def _check_tokens(path: Path, toks: list[Token], defined: set) -> None:
    consumed = set()  # indices read as option or field names by an earlier rule
    for i, tok in enumerate(toks):
        if i in consumed or tok.kind in ("string", "number"):
            continue
        word, after = tok.text, _text(toks, i + 1)
        if tok.kind == "op":
            if word not in _OPERATORS:
                _refuse(path, tok.line, f"{word!r} is not part of a geometry")
            continue
        if word == "Printf" and after == "(":  # it prints to the terminal, never to a file
            redirect = _text(toks, _closing(toks, i + 1) + 1)
            if redirect in (">", ">>"):
                _refuse(path, tok.line, f"Printf(...) {redirect} FILE writes a file (whatever "
                                        "names it: a string, StrCat, a variable)")
        if word in ("Mesh", "Geometry", "General") and after == ".":
            option, assigned = _text(toks, i + 2), _text(toks, i + 3) in _ASSIGN
            allowed = {"Mesh": MESH_OPTIONS, "Geometry": GEOMETRY_OPTIONS,
                       "General": {"Verbosity"}}[word]
            if assigned and option not in allowed:
                _refuse(path, tok.line, f"setting the option {word}.{option} (a .geo may set "
                                        "the Mesh.* and Geometry.* options of geometry and "
                                        "element size listed in docs/model_files.md)")
            consumed.update((i + 1, i + 2))
            continue
        if word in REFUSED:
            _refuse(path, tok.line, f"{word!r} {REFUSED[word]}")
        if word in READS:
            continue  # its target was checked by _gather
        if word == "Field" and after == "[":
            close = _closing(toks, i + 1)
            if _text(toks, close + 1) == "=" and toks[close + 2:close + 3] and \
                    toks[close + 2].kind == "name":
                if toks[close + 2].text not in FIELD_TYPES:
                    _refuse(path, tok.line, f"a Field of type {toks[close + 2].text!r} (a .geo "
                                            f"may use {', '.join(sorted(FIELD_TYPES))})")
                consumed.add(close + 2)
            elif _text(toks, close + 1) == ".":
                if _text(toks, close + 2) not in FIELD_OPTIONS:
                    _refuse(path, tok.line, f"the Field option {_text(toks, close + 2)!r}")
                consumed.update((close + 1, close + 2))
            continue
        if word == "For":
            count = _loop_count(toks, i)
            if count is not None and count > MAX_LOOP:
                _refuse(path, tok.line, f"a loop of {count:.3g} passes (at most {MAX_LOOP:,})")
        if word in ALLOWED:
            continue
        if word not in defined:
            _refuse(path, tok.line, f"{word!r} is neither a gmsh command a geometry needs nor "
                                    "a variable the file defines")
        follows = toks[i + 1] if i + 1 < len(toks) else None
        loop_variable = _text(toks, i - 1) == "For" and after == "In"
        if follows is not None and not loop_variable and (
                follows.kind != "op" or follows.text == "."):
            _refuse(path, tok.line, f"{word!r} {follows.text!r}: a variable used as a command")


def check_geo(path, root=None, allow_code: bool = False) -> None:
    """Raise :class:`CodeInGeometry` (a ValueError) naming the file, the line and the reason
    unless the .geo ``path`` and every file it includes use only what a geometry needs (see
    the module's docstring) and read only inside ``root`` (default: its own folder).
    ``allow_code`` skips the check."""
    if allow_code:
        return
    path = Path(path)
    root = Path(root) if root is not None else path.parent
    files: dict = {}
    _gather(path, root, files)
    defined = set().union(*(_defined(toks) for _, toks in files.values()))
    for shown, toks in files.values():
        _check_tokens(shown, toks, defined)


def check_geometry_file(path, root=None, allow_code: bool = False) -> None:
    """A model file's geometry file is what its name says, by its content: a .geo a safe
    script (:func:`check_geo`), a .msh a gmsh mesh, a .step/.stp a STEP file, a .brep a BREP
    file; else CodeInGeometry naming the file."""
    if allow_code:
        return
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".geo":
        check_geo(path, root, allow_code)
        return
    expected = {".msh": "mesh", ".step": "step", ".stp": "step", ".brep": "brep"}.get(suffix)
    kind = file_kind(path)
    if expected is not None and kind != expected:
        raise CodeInGeometry(f"{path}: its content is {_KINDS[kind]}, not {_KINDS[expected]} "
                             "as its name says; gmsh reads a file by its content, so a model "
                             "file's geometry must be what it is named")


_KINDS = {"script": "text gmsh would run as a .geo script", "mesh": "a gmsh mesh ($MeshFormat)",
          "step": "a STEP file (ISO-10303-21)", "brep": "an OpenCASCADE BREP file",
          "compressed": "compressed data", "binary": "binary data"}


def check_inside(path, root, allow_code: bool = False) -> Path:
    """``path`` resolved (symlinks followed); ValueError if it lies outside ``root`` (the
    model file's folder) and the user has not allowed it."""
    resolved = Path(path).resolve()
    if not allow_code and not _inside(resolved, Path(root)):
        raise CodeInGeometry(f"{path} resolves to {resolved}, outside the model file's "
                             f"folder {Path(root).resolve()}; a model file reads only its own "
                             "folder (pass --allow-code to lift this)")
    return resolved
