"""A user's own flexure, from files: a model file (TOML) naming a geometry file (.geo with
DefineConstant parameters and Physical groups, .step/.stp/.brep with [[select]] rules, or
.msh) with its material, section, supports, loads and analysis, or describing its mechanism
as bodies and flexures ([[body]], [[flexure]]; in Python: ``mechanism_spec``). See
docs/model_files.md.

    spec = load_spec("examples/parallel_guide/guide.toml", {"L": 0.05})
    mesh = mesh_geometry(spec)          # FEMesh with the named groups
"""
from .geometry import GeometryInfo, define_constant_names, inspect_geometry, mesh_geometry
from .spec import ModelSpec, load_spec, mechanism_spec

__all__ = ["GeometryInfo", "ModelSpec", "define_constant_names", "inspect_geometry",
           "load_spec", "mechanism_spec", "mesh_geometry"]
