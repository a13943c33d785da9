"""gmsh mesh-size fields shared by the drawings: a size graded away from entities
(:func:`threshold_field`) and the least of several fields as the only size
(:func:`size_by_fields`). Call them inside an open gmsh session."""


def threshold_field(gmsh, entities, dim: int, size: float, far: float, near: float,
                    reach: float, sampling: int = 100) -> int:
    """A gmsh Threshold field of ``size`` (m) within ``near`` (m) of the entities (of
    dimension dim - 1), growing to ``far`` (m) at ``near + reach``, the distance sampled at
    ``sampling`` points a curve; its tag."""
    field = gmsh.model.mesh.field
    distance = field.add("Distance")
    field.setNumbers(distance, "CurvesList" if dim == 2 else "SurfacesList", entities)
    field.setNumber(distance, "Sampling", sampling)
    threshold = field.add("Threshold")
    field.setNumber(threshold, "InField", distance)
    field.setNumber(threshold, "SizeMin", size)
    field.setNumber(threshold, "SizeMax", far)
    field.setNumber(threshold, "DistMin", near)
    field.setNumber(threshold, "DistMax", near + reach)
    return threshold


def size_by_fields(gmsh, fields, largest: float) -> None:
    """The mesh sizes: the least of the gmsh ``fields`` (tags) everywhere, at most
    ``largest`` (m), from nothing else (not the boundary, points or curvature)."""
    field = gmsh.model.mesh.field
    minimum = field.add("Min")
    field.setNumbers(minimum, "FieldsList", fields)
    field.setAsBackgroundMesh(minimum)
    for option in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
        gmsh.option.setNumber(f"Mesh.{option}", 0)
    gmsh.option.setNumber("Mesh.MeshSizeMax", largest)
