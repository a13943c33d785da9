"""Build the API reference of flexfem's public face into docs/api/ with pdoc (numpydoc-style
docstrings): ``python scripts/api_docs.py [OUT_DIR]`` (``bash scripts/api_docs.sh``). Exits
with status 1, listing them, where pdoc warns (a docstring or annotation it cannot read);
tests/test_api_docs.py runs the same build."""
from pathlib import Path
import sys
import warnings

#: The public face: a user's own model file, the analyses and their results, materials and
#: models (the continuum's and the beam's), the study engine's sweep and convergence entry
#: points.
PUBLIC_MODULES = (
    "flexfem.studies.user_model",
    "flexfem.studies.user_model.api",
    "flexfem.studies.user_model.model_report",
    "flexfem.fem.analyses",
    "flexfem.fem.static_result",
    "flexfem.fem.modal",
    "flexfem.fem.nonlinear_result",
    "flexfem.fem.buckling",
    "flexfem.fem.compliance",
    "flexfem.fem.harmonic",
    "flexfem.fem.materials",
    "flexfem.fem.model",
    "flexfem.fem.beam",
    "flexfem.fem.beam.model",
    "flexfem.fem.beam.section",
    "flexfem.fem.beam.mesh",
    "flexfem.fem.beam.spatial",
    "flexfem.fem.beam.spatial.model",
    "flexfem.studies.engine.sweep",
    "flexfem.studies.engine.convergence",
)
ROOT = Path(__file__).resolve().parents[1]


def build(out_dir=ROOT / "docs" / "api", modules=PUBLIC_MODULES) -> list[str]:
    """Render ``modules`` into ``out_dir`` (HTML, one page a module and an index); returns
    pdoc's warnings, one line each (empty: a clean build)."""
    import pdoc
    import pdoc.render

    pdoc.render.configure(docformat="numpy", show_source=False, search=True,
                          footer_text="flexfem API reference")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        pdoc.pdoc(*modules, output_directory=Path(out_dir))
    return [f"{w.category.__name__}: {w.message}" for w in caught
            if "pdoc" in Path(w.filename).parts or issubclass(w.category, RuntimeWarning)]


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else argv
    out = Path(args[0]) if args else ROOT / "docs" / "api"
    found = build(out)
    for line in found:
        print(f"api_docs: {line}", file=sys.stderr)
    print(f"api_docs: {len(PUBLIC_MODULES)} modules into {out}/index.html"
          + (f", {len(found)} warnings" if found else ""))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
