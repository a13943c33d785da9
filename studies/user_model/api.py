"""A user's own model file from Python: :func:`load_model` reads and checks it,
:func:`analyze` solves it by the continuum or the beam model and returns a
:class:`~.model_report.Report`.

    from flexfem.studies.user_model import load_model, analyze

    model = load_model("examples/bodies/guide.toml", set={"t": "0.8 mm"})
    report = analyze(model, fidelity="beam")
    print(report.stiffness["stage"]["x"], "N/m")

``flexfem analyze`` (:mod:`.cli`) is this, with its options as flags.
"""
from ...geometry.user_model.spec import ModelSpec, load_spec
from .analysis import MODELS, analyze_model
from .mesh_choice import choose_size_factor
from .model_report import Report


def load_model(path, set: dict | None = None, *, dim: int | None = None,
               allow_code: bool = False) -> ModelSpec:
    """Read and check a model file (TOML: bodies and flexures, or a geometry file and what to
    do with it; docs/model_files.md).

    Parameters
    ----------
    path : str or os.PathLike
        The model file.
    set : dict, optional
        Overrides, as ``flexfem analyze --set``: ``{"L": 0.05}`` replaces a [parameters] entry
        (SI, or a string with a unit such as ``"50 mm"``), ``{"material.E": 2e11}`` a key of
        another table (material, section, mesh, analysis, beam_model).
    dim : int, optional
        3 extrudes a file of bodies and flexures to a solid by its [section] thickness (m);
        a geometry file has its own dimension (None: the file's).
    allow_code : bool
        Trust the file: its .geo may run programs and read outside its folder (refused by
        default).

    Returns
    -------
    ModelSpec
        The checked description (SI), holding the file's path (``.path``, ``.source``).

    Raises
    ------
    ValueError
        One line naming the file (and the key's line where it can be found) for anything
        wrong in it, e.g. an override of a name the file does not declare.
    """
    return load_spec(path, set, allow_code=allow_code, dim=dim)


def analyze(model: ModelSpec, fidelity: str = "continuum", *, size_factor: float | None = None,
            max_dofs: int | None = None) -> Report:
    """Solve the model file's problem: the static load case and what its [analysis] asks for
    (modes, large deflection, compliance, buckling, harmonic response, stroke limits).

    Parameters
    ----------
    model : ModelSpec
        The model file, from :func:`load_model`.
    fidelity : {"continuum", "beam"}
        ``"continuum"``: the finite-element model of the geometry; ``"beam"``: the file's beam
        model ([[beam]] and [[rigid]], or that of its bodies and flexures).
    size_factor : float, optional
        The continuum's element sizes times this factor (-); None: 1, or for a solid of bodies
        and flexures the smallest factor whose mesh fits the DOF budget. The beam model has
        no mesh: refused with it.
    max_dofs : int, optional
        The continuum's mesh budget (unknowns), refused before meshing when estimated above;
        None: what half the available memory affords.

    Returns
    -------
    Report
        The numbers as attributes (SI), ``to_dict()``, ``summary(units=...)``, ``write(dir)``.
    """
    if fidelity not in MODELS:
        raise ValueError(f"{model.source}: fidelity = {fidelity!r} must be one of {MODELS}")
    choice = None
    if fidelity == "beam":
        if size_factor is not None:
            raise ValueError(f"{model.source}: size_factor sets the continuum's mesh; the beam "
                             "model has none")
        size_factor = 1.0
    else:
        size_factor, choice = choose_size_factor(model, size_factor, max_dofs)
    solved = {}
    data = analyze_model(model, size_factor, model=fidelity, max_dofs=max_dofs, fields=solved)
    if choice is not None:
        data.update(size_factor=size_factor, mesh_choice=choice)
    return Report.from_dict(model, fidelity, data, solved)
