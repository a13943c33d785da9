"""The result of analysing a model file: :class:`Report`, its numbers as attributes (SI), its
dict (:meth:`Report.to_dict`, what ``flexfem analyze --json`` prints), its human summary
(:meth:`Report.summary`) and its files (:meth:`Report.write`, what ``--out`` writes)."""
import copy
from dataclasses import dataclass, field

import numpy as np

from ...geometry.user_model.spec import ModelSpec
from .summary import LENGTH_UNITS, summarize

#: The keys of the analysis dict that make up :attr:`Report.stroke_limits`.
STROKE_KEYS = ("stroke_group", "stroke_direction", "stress_per_stroke", "stroke_stress_basis",
               "stroke_stress_singular", "stroke_limit_where", "stroke_limit_yield",
               "stroke_limit_fatigue", "fatigue_cycles", "fatigue_criterion", "fatigue_source",
               "safety_factor", "mean_stroke", "stroke_limit_basis", "stroke_check")


def _vectors(table: dict) -> dict:
    return {group: np.asarray(v, float) for group, v in table.items()}


@dataclass(frozen=True)
class Report:
    """The analysis of one model file by one model (:func:`~.api.analyze` makes it).

    Every number is SI: lengths in m, forces in N, stresses in Pa, stiffness in N/m (N m/rad
    for a rotation), frequencies in Hz. An analysis the file did not ask for is None (or an
    empty dict); :attr:`not_available` says why a quantity that was asked for is missing.
    """

    model: ModelSpec
    """The model file analysed (its path: ``model.path``)."""
    fidelity: str
    """``"continuum"`` (the finite-element model of the geometry) or ``"beam"`` (its beam
    model)."""
    dim: int
    """2 or 3: the dimension of the analysis (a file of bodies and flexures is 3 when loaded
    with ``dim=3``)."""
    dofs: int
    """The solved model's unknowns (-)."""
    solver: str
    """The linear solver that ran (e.g. ``"mkl-pardiso"``)."""
    h: float
    """The characteristic element size (m): the continuum's mean edge length, the beam
    model's mean element length."""
    max_von_mises: float
    """The largest von Mises stress (Pa) of the load case."""
    max_von_mises_location: np.ndarray
    """Where it is (m), shape (dim,)."""
    mean_displacement: dict
    """{group: mean displacement (m), shape (dim,)} of every support and load group."""
    reactions: dict
    """{group: reaction force (N), shape (dim,)} of every support."""
    stiffness: dict
    """{group: {axis: stiffness (N/m)}} of the loaded group along each loaded axis (a model
    with a single force load; else empty)."""
    yield_strength: float | None
    """The material's yield strength (Pa), None where [material] gives none."""
    frequencies_hz: np.ndarray | None
    """The natural frequencies (Hz) where [analysis] modes asks for them."""
    outputs: dict
    """{name: value} of the file's [outputs] metrics (in the units of their expressions)."""
    observations: dict
    """{group: {component: value}} observed of bodies and faces (u* in m, r* in rad)."""
    nonlinear: dict | None
    """The large-deflection solve at full load ([analysis] steps): its mean_displacement (m),
    reactions (N), max_von_mises (Pa), observations and outputs."""
    compliance: dict | None
    """[analysis] compliance: the rigid-face compliance matrix of a group (m/N, rad/(N m)),
    its point (m), stiffness, principal compliances and centre of compliance (m)."""
    buckling: dict | None
    """[analysis] buckling: {"load_factors": [...]} (-), multiples of the load case."""
    harmonic: dict | None
    """[analysis] harmonic: the frequency response of a group (frequencies in Hz, amplitude in
    m per the load, phase in rad, resonances in Hz)."""
    stroke_limits: dict
    """The stroke limits (:data:`STROKE_KEYS`): stroke_limit_yield and stroke_limit_fatigue
    (m), the stress they were sized by (stroke_stress_basis, stress_per_stroke in Pa/m) and
    where (stroke_limit_where, m), the safety factor and fatigue data used; empty where the
    model has no stroke to size."""
    not_available: dict
    """{quantity: why it is missing} of what was asked for but could not be given."""
    solved_model: object = field(default=None, repr=False)
    """The solved :class:`flexfem.fem.Model` (continuum) or beam model, for fields."""
    static: object = field(default=None, repr=False)
    """The static result of the load case (displacement, stress fields, reactions)."""
    modes: object = field(default=None, repr=False)
    """The solved mode shapes (:func:`flexfem.fem.solve_modes`'s result), where [analysis]
    modes asked for them and the model kept them (None for the spatial beam model)."""
    stroke_path: object = field(default=None, repr=False)
    """(model, result) of the stroke check's large-deflection path, where it ran."""
    _data: dict = field(default_factory=dict, repr=False)

    @classmethod
    def from_dict(cls, model: ModelSpec, fidelity: str, data: dict,
                  solved: dict | None = None) -> "Report":
        """The report of the analysis dict ``data`` (:func:`~.analysis.analyze_model`'s, SI) of
        ``model`` by ``fidelity``; ``solved``: the solved "model", "static" and "modes"."""
        solved = solved or {}
        freqs = data.get("frequencies_hz")
        return cls(
            model=model, fidelity=fidelity, dim=data["dim"], dofs=data["dofs"],
            solver=data["solver"], h=data["h"], max_von_mises=data["max_von_mises"],
            max_von_mises_location=np.asarray(data["max_von_mises_location"], float),
            mean_displacement=_vectors(data["mean_displacement"]),
            reactions=_vectors(data["reactions"]), stiffness=data["stiffness"],
            yield_strength=data["yield_strength"],
            frequencies_hz=None if freqs is None else np.asarray(freqs, float),
            outputs=data.get("outputs", {}), observations=data.get("observations", {}),
            nonlinear=data.get("nonlinear"), compliance=data.get("compliance"),
            buckling=data.get("buckling"), harmonic=data.get("harmonic"),
            stroke_limits={k: data[k] for k in STROKE_KEYS if k in data},
            not_available=data.get("not_available", {}),
            solved_model=solved.get("model"), static=solved.get("static"),
            modes=solved.get("modes"), stroke_path=solved.get("stroke_path"),
            _data=copy.deepcopy(data))

    def to_dict(self) -> dict:
        """The analysis as one JSON-able dict (SI; a copy): what ``flexfem analyze --json``
        prints."""
        return copy.deepcopy(self._data)

    def _shown(self, units: str) -> dict:
        if units not in LENGTH_UNITS:
            raise ValueError(f"units = {units!r}: use one of {', '.join(LENGTH_UNITS)}")
        data = self.to_dict()
        if units != "m":
            data["display_units"] = units
        return data

    def summary(self, units: str = "m") -> str:
        """The human summary, one line a quantity (what ``flexfem analyze`` prints).

        Parameters
        ----------
        units : str
            The length unit of the text: ``"m"``, ``"mm"`` or ``"um"`` (stiffness per that
            length); the numbers of :meth:`to_dict` stay SI.
        """
        return summarize(self._shown(units))

    def write(self, out_dir, units: str = "m") -> list[str]:
        """Write summary.json, the field files (VTU), the pictures (PNG) and index.html into
        the folder ``out_dir`` (created if missing): what ``flexfem analyze --out`` writes.

        Parameters
        ----------
        out_dir : str or os.PathLike
            The folder.
        units : str
            The length unit of the page's summary (``"m"``, ``"mm"``, ``"um"``).

        Returns
        -------
        list of str
            The files written, the page last.
        """
        from ..out_folder import check_out
        from .page import write_outputs  # matplotlib: only where pictures are drawn

        check_out(out_dir)
        if self.solved_model is None:
            raise ValueError(f"{self.model.source}: this report holds no solved model to write")
        data = self._shown(units)
        solved = {"model": self.solved_model, "static": self.static}
        if self.modes is not None:
            solved["modes"] = self.modes
        if self.stroke_path is not None:
            solved["stroke_path"] = self.stroke_path
        return write_outputs(out_dir, self.model, data, solved, summarize(data))
