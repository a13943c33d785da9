"""flexfem analyze --out DIR: the field files read back with their fields and groups and
agree with the numbers, the pictures are images, the page renders in Chromium with every
picture, and a bad DIR is refused before anything is solved."""
import contextlib
import io
import json
from pathlib import Path
import re
import shutil
import subprocess

import matplotlib.image as mpimg
import meshio
import numpy as np
import pytest

from flexfem.studies.cli import main
from flexfem.studies.user_model import pictures

ROOT = Path(__file__).resolve().parents[3]
COMPOUND = str(ROOT / "examples/bodies/compound.toml")


def _analyze(*argv) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(["analyze", *argv])
    return code, out.getvalue(), err.getvalue()


def _run(folder: Path, *extra) -> dict:
    code, out, err = _analyze(COMPOUND, "--out", str(folder), "--json", *extra)
    assert code == 0, err
    return json.loads(out)


@pytest.fixture(scope="module")
def continuum(tmp_path_factory):
    folder = tmp_path_factory.mktemp("out") / "new" / "compound"  # made, parents too
    return folder, _run(folder)


@pytest.fixture(scope="module")
def beam(tmp_path_factory):
    folder = tmp_path_factory.mktemp("beam_out")
    return folder, _run(folder, "--model", "beam")


def test_the_json_lists_every_file_written(continuum):
    folder, result = continuum
    names = [Path(f).name for f in result["files"]]
    assert names[0] == "summary.json" and names[-1] == "index.html"
    assert {"static.vtu", "modes.vtu", "mechanism.png", "deformed.png", "mode_1.png"} <= set(names)
    assert all(Path(f).parent == folder for f in result["files"])
    assert sorted(p.name for p in folder.iterdir()) == sorted(names)  # nothing else, no .part
    kept = json.loads((folder / "summary.json").read_text())
    assert kept["files"] == result["files"]
    assert kept["stiffness"] == result["stiffness"]


def test_the_load_case_vtu_holds_the_fields_and_groups(continuum):
    folder, result = continuum
    m = meshio.read(folder / "static.vtu")
    u, vm, stress = (m.point_data[k] for k in ("displacement", "von_mises", "stress"))
    assert u.shape == (len(m.points), 3) and stress.shape == (len(m.points), 9)
    assert vm.max() == pytest.approx(result["max_von_mises"], rel=1e-9)
    # the largest displacement is at least the loaded group's mean
    stage = np.linalg.norm(result["mean_displacement"]["stage"])
    assert np.linalg.norm(u, axis=1).max() >= stage > 0
    # the groups as cell data: the stage's facets move as the JSON says it does (the stage
    # is a rigid block: its outline's nodes move by its mean displacement)
    assert {"group_id", "ground", "stage", "shuttle"} <= set(m.cell_data)
    blocks = [b for b, flag in zip(m.cells, m.cell_data["stage"]) if flag.any()]
    nodes = np.unique(np.concatenate([b.data[f == 1].ravel() for b, f in
                                      zip(m.cells, m.cell_data["stage"]) if f.any()]))
    assert blocks and blocks[0].type == "line"
    assert u[nodes, 0].mean() == pytest.approx(result["mean_displacement"]["stage"][0], rel=0.01)
    ground = np.concatenate([b.data[f == 1].ravel() for b, f in
                             zip(m.cells, m.cell_data["ground"]) if f.any()])
    assert np.abs(u[ground]).max() == 0.0  # held


def test_the_modes_vtu_names_each_mode_by_its_frequency(continuum):
    folder, result = continuum
    m = meshio.read(folder / "modes.vtu")
    names = [k for k in m.point_data if k.startswith("mode_")]
    assert len(names) == len(result["frequencies_hz"])
    for name, f in zip(sorted(names), result["frequencies_hz"]):
        assert float(re.search(r"\(([\d.e+]+) Hz\)", name).group(1)) == pytest.approx(f, rel=1e-5)
        assert np.abs(m.point_data[name]).max() > 0


@pytest.mark.parametrize("name", ["mechanism.png", "deformed.png", "mode_1.png", "mode_3.png"])
def test_the_pictures_are_images(continuum, name):
    image = mpimg.imread(continuum[0] / name)
    assert image.shape[0] > 200 and image.shape[1] > 200
    assert image[..., :3].std() > 0.05  # not one colour


def test_the_deformed_picture_states_its_scale():
    assert pictures.scale_text(pictures.nice_scale(6.5e-5, 0.08)) == "displacement x 100"
    assert pictures.nice_scale(1e-3, 0.08) == 5.0
    assert pictures.scale_text(pictures.nice_scale(0.0, 0.08)) == "no displacement"


def test_the_page_has_the_numbers_and_relative_links(continuum):
    folder, result = continuum
    page = (folder / "index.html").read_text()
    assert f"{result['stiffness']['stage']['x']:.4g} N/m" in page
    assert ", ".join(f"{f:.4g}" for f in result["frequencies_hz"]) + " Hz" in page
    links = re.findall(r"(?:src|href)='([^']+)'", page)
    assert links and all(not link.startswith(("/", "file:")) for link in links)
    assert all((folder / link).exists() for link in links)


def _chromium() -> str:
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        pytest.skip("chromium is not installed (Debian package 'chromium'; .ci/run installs it)")
    return chromium


def _chromium_args(page: Path, profile: Path) -> list[str]:
    return [_chromium(), "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
            "--no-first-run", "--disable-background-networking", "--disable-component-update",
            "--disable-sync", f"--user-data-dir={profile}", "--allow-file-access-from-files",
            "--virtual-time-budget=5000"]


def _check_page(folder: Path, tmp_path: Path, n_images: int) -> None:
    """The page renders in headless Chromium: every picture decoded, every table with rows,
    none wider than the page; its screenshot is not blank."""
    page = folder / "index.html"
    dom = subprocess.run(_chromium_args(page, tmp_path / "profile") + [
        "--window-size=1280,1000", "--dump-dom", page.as_uri()],
        capture_output=True, text=True, timeout=120).stdout
    body = re.search(r"<body([^>]*)>", dom)
    assert body, "chromium returned no document"
    counts = {k: int(v) for k, v in re.findall(r'data-([a-z-]+)="(\d+)"', body.group(1))}
    assert counts["images-total"] == n_images
    assert counts["images-loaded"] == n_images
    assert counts["tables-with-rows"] == counts["tables-total"] >= 1
    assert counts["tables-overflowing"] == 0
    shot = tmp_path / "screenshot.png"
    subprocess.run(_chromium_args(page, tmp_path / "profile") + [
        "--window-size=1280,2400", f"--screenshot={shot}", page.as_uri()],
        capture_output=True, timeout=120)
    pixels = mpimg.imread(shot)[..., :3]
    assert (pixels.min(axis=2) < 0.9).mean() > 0.05  # text and pictures, not a white page
    assert pixels.std() > 0.1


def test_the_page_renders_in_chromium(continuum, tmp_path):
    folder, result = continuum
    _check_page(folder, tmp_path, sum(f.endswith(".png") for f in result["files"]))


def test_the_beam_model_writes_its_lines_and_pictures(beam, tmp_path):
    folder, result = beam
    names = {Path(f).name for f in result["files"]}
    assert {"static.vtu", "modes.vtu", "beam_model.png", "deformed.png", "mode_1.png"} <= names
    m = meshio.read(folder / "static.vtu")
    assert {b.type for b in m.cells} == {"line"}
    u = m.point_data["displacement"]
    # a beam model's group is its node: its displacement is the JSON's mean displacement
    stage = np.flatnonzero(m.point_data["stage"])
    assert len(stage) == 1
    assert u[stage[0], :2] == pytest.approx(result["mean_displacement"]["stage"], rel=1e-9,
                                            abs=1e-15)
    assert np.nanmax(np.concatenate(m.cell_data["beam_stress"])) == pytest.approx(
        result["max_von_mises"], rel=1e-9)
    modes = meshio.read(folder / "modes.vtu")
    assert sum(k.startswith("mode_") for k in modes.point_data) == len(result["frequencies_hz"])
    for name in ("beam_model.png", "deformed.png", "mode_1.png"):
        assert mpimg.imread(folder / name)[..., :3].std() > 0.05
    _check_page(folder, tmp_path, sum(f.endswith(".png") for f in result["files"]))


def test_an_existing_file_as_out_is_refused_in_one_line(tmp_path, monkeypatch):
    target = tmp_path / "results.txt"
    target.write_text("keep me")
    monkeypatch.setattr("flexfem.studies.user_model.cli.analyze",
                        lambda *a, **k: pytest.fail("solved before refusing --out"))
    code, out, err = _analyze(COMPOUND, "--out", str(target))
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "is a file, not a folder" in err
    assert target.read_text() == "keep me"


def test_a_failing_picture_keeps_the_numbers(tmp_path, monkeypatch):
    """The numbers are written first: a picture that cannot be drawn loses none of them, and
    no half-written file is left behind."""
    def broken(*args, **kwargs):
        raise ValueError("no picture today")

    monkeypatch.setattr(pictures, "deformed_figure", broken)
    code, _, err = _analyze(COMPOUND, "--out", str(tmp_path), "--json")
    assert code == 2 and "no picture today" in err
    kept = json.loads((tmp_path / "summary.json").read_text())
    assert kept["stiffness"]["stage"]["x"] > 0
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".part")]


def test_the_summary_says_what_was_written(tmp_path):
    code, out, _ = _analyze(COMPOUND, "--model", "beam", "--out", str(tmp_path))
    assert code == 0
    assert f"the page {tmp_path / 'index.html'}" in out.splitlines()[-1]


def test_a_group_is_labelled_once_per_body():
    """Labels: a ground of two blocks twice, an edge meshed coarser than the gap once, an
    outline interrupted by the flexures' roots once."""
    def box(x0, y0, x1, y1):
        c = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
        return np.stack([c, np.roll(c, -1, axis=0)], axis=1)

    two = np.concatenate([box(0, 0, 1, 1), box(3, 0, 4, 1)])
    assert len(pictures.part_centres(two, gap=0.2)) == 2
    edge = np.array([[[0.0, 0.0], [1.0, 0.0]], [[1.0, 0.0], [2.0, 0.0]]])
    assert len(pictures.part_centres(edge, gap=0.1)) == 1
    cut = np.array([[[0.0, 0.0], [0.95, 0.0]], [[1.05, 0.0], [2.0, 0.0]]])
    assert len(pictures.part_centres(cut, gap=0.2)) == 1


@pytest.mark.slow
def test_the_solid_is_written_and_drawn_as_a_projection(tmp_path):
    """--dim 3: tetrahedra with the groups' triangles in the VTU; the pictures say they are a
    projection and show the model (the guide's upper face seen from +z)."""
    code, out, err = _analyze(str(ROOT / "examples/bodies/guide.toml"), "--dim", "3",
                              "--out", str(tmp_path), "--json")
    assert code == 0, err
    result = json.loads(out)
    m = meshio.read(tmp_path / "static.vtu")
    assert {b.type for b in m.cells} == {"tetra", "triangle"}
    assert m.point_data["von_mises"].max() == pytest.approx(result["max_von_mises"], rel=1e-9)
    assert np.linalg.norm(m.point_data["displacement"], axis=1).max() >= np.linalg.norm(
        result["mean_displacement"]["stage"])
    for name in ("mechanism.png", "deformed.png", "mode_1.png"):
        assert mpimg.imread(tmp_path / name)[..., :3].std() > 0.05
    assert "projected onto the x-y plane" in (tmp_path / "index.html").read_text()


def test_the_page_says_what_it_does_not_draw():
    """The stroke check's large-deflection path and the spatial beam model's modes have no
    picture: the page says so in one line each, and says nothing where all is drawn."""
    from flexfem.studies.user_model.page import not_drawn

    path = {"stroke_check": {"model": "beam", "strokes": [0.0, 5e-5, 1e-4]}}
    (line,) = not_drawn(path, None, {})
    assert "large-deflection path (the beam model, to 0.1 mm) is not drawn" in line
    (line,) = not_drawn({"frequencies_hz": [265.2]}, None, {"modes": None})
    assert "mode shapes of this model are not drawn" in line
    assert not_drawn({}, None, {}) == []
