"""The counts a gmsh ``.msh`` file claims, checked against its size before gmsh reads it.

gmsh trusts the ``$Nodes`` and ``$Elements`` headers: a file that claims 1e11 nodes makes it
reserve memory for them and fail with no message at all. Every node and element takes some
bytes in the file (ASCII: at least its tag and coordinates, digits and separators; binary: at
least its coordinates or its node tags), so a count above size / those bytes is a damaged or
truncated file, refused here with what it claims and what the file holds.
"""
from pathlib import Path
import struct

#: The fewest bytes a node and an element take in a file: ASCII "0 0 0\n" (6), binary three
#: 8-byte coordinates; an element at least its type or tag and one node ("1 1\n", 4 bytes;
#: binary one 4-byte node tag).
MIN_BYTES = {("ascii", "node"): 6, ("ascii", "element"): 4,
             ("binary", "node"): 24, ("binary", "element"): 4}


def _header(path: Path, data: bytes) -> tuple[float, bool, int]:
    """(version, binary, size_t bytes) of the $MeshFormat section."""
    at = data.find(b"$MeshFormat")
    if at < 0:
        raise ValueError(f"{path}: no $MeshFormat section: not a gmsh mesh file")
    fields = data[at + len(b"$MeshFormat"):].split(b"\n", 2)[1].split()
    try:
        return float(fields[0]), fields[1] == b"1", int(fields[2])
    except (IndexError, ValueError):
        raise ValueError(f"{path}: its $MeshFormat line {fields!r} is not 'version file-type "
                         "data-size'; the file is damaged") from None


def _claimed(data: bytes, section: bytes, version: float, binary: bool, size_t: int):
    """The count the header of ``section`` claims, or None where the file has none."""
    at = data.find(b"\n" + section)
    if at < 0:
        return None
    body = data[at + 1 + len(section):].lstrip(b"\r\n")
    if version >= 4 and binary:
        code = {4: "<I", 8: "<Q"}.get(size_t)
        if code is None or len(body) < 2 * size_t:
            return None
        return struct.unpack(code, body[size_t:2 * size_t])[0]  # numEntityBlocks, num...
    fields = body.split(b"\n", 1)[0].split()
    index = 1 if version >= 4 else 0  # 4.x: numEntityBlocks numNodes ...; 2.x: numNodes
    try:
        return int(fields[index])
    except (IndexError, ValueError):
        return None


def check_msh_counts(path) -> None:
    """ValueError naming ``path`` where its $Nodes or $Elements header claims more than the
    file's size can hold (a damaged or truncated file that gmsh would fail on silently)."""
    path = Path(path)
    size = path.stat().st_size
    with open(path, "rb") as handle:  # the headers sit before the data; 64 MiB is ample
        data = handle.read(64 * 2 ** 20)
    version, binary, size_t = _header(path, data)
    kind = "binary" if binary else "ascii"
    for section, what in ((b"$Nodes", "node"), (b"$Elements", "element")):
        n = _claimed(data, section, version, binary, size_t)
        need = None if n is None else n * MIN_BYTES[kind, what]
        if need is not None and need > size:
            raise ValueError(f"{path}: its {section.decode()} header claims {n:,} {what}s, "
                             f"which need at least {need:,} bytes, but the file has {size:,}: "
                             "it is damaged or truncated; export the mesh again")
