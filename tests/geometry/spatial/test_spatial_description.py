"""Spatial model files: what makes a file spatial, and the one-line errors of a bad
description (file, line, body or flexure)."""
from pathlib import Path
import re

import pytest

from flexfem.geometry.spatial.tables import is_spatial, load_spatial
from flexfem.geometry.user_model import load_spec

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "spatial"
WIRE_GUIDE = (EXAMPLES / "wire_guide.toml").read_text()
LEAF_GUIDE = (EXAMPLES / "leaf_guide.toml").read_text()


def _write(tmp_path, text, name="m.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _error(tmp_path, text) -> str:
    path = _write(tmp_path, text)
    with pytest.raises(ValueError) as info:
        load_spatial(path)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(str(path))
    return message


def test_examples_are_spatial_and_planar_files_are_not():
    import tomllib

    assert is_spatial(tomllib.loads(WIRE_GUIDE))
    planar = (EXAMPLES.parent / "bodies" / "guide.toml").read_text()
    assert not is_spatial(tomllib.loads(planar))


def test_units_and_expressions_read_as_si():
    mechanism, _, parameters = load_spatial(EXAMPLES / "wire_guide.toml")
    assert parameters["L"] == pytest.approx(0.03)
    wire = mechanism.flexures[0]
    assert wire.diameter == pytest.approx(1e-3)
    assert wire.end == pytest.approx((-0.012, -0.012, 0.03))
    assert mechanism.span(0).length == pytest.approx(0.03, rel=1e-8)


def test_an_end_outside_its_body_is_refused(tmp_path):
    text = WIRE_GUIDE.replace('to = ["-a", "-a", "L"]', 'to = ["-a", "-a", "L - 1 mm"]', 1)
    message = _error(tmp_path, text)
    assert re.search(r"line \d+: flexure 1 'w1' \(wire between 'base' and 'stage'\)", message)
    assert "outside body 'stage'" in message


def test_width_along_not_perpendicular_is_refused(tmp_path):
    text = LEAF_GUIDE.replace("width_along = [1, 0, 0]", "width_along = [1, 0, 1]", 1)
    message = _error(tmp_path, text)
    assert re.search(r"line \d+: flexure 1 'front'", message) and "not perpendicular" in message


def test_intersecting_flexures_are_refused_unless_declared(tmp_path):
    text = WIRE_GUIDE.replace('from = ["a", "-a", 0.0]\nto = ["a", "-a", "L"]',
                              'from = ["a", "-a", 0.0]\nto = ["-a", "-a", "L"]')
    text = text.replace('from = ["-a", "-a", 0.0]\nto = ["-a", "-a", "L"]',
                        'from = ["-a", "-a", 0.0]\nto = ["a", "-a", "L"]')
    message = _error(tmp_path, text)
    assert re.search(r"line \d+: flexure 2 'w2' .* intersects flexure 1 'w1'", message)
    assert "crosses" in message
    declared = text.replace('name = "w2"', 'name = "w2"\ncrosses = ["w1"]')
    mechanism, _, _ = load_spatial(_write(tmp_path, declared, "crossing.toml"))
    assert len(mechanism.flexures) == 4


def test_a_body_joined_to_nothing_is_refused(tmp_path):
    text = WIRE_GUIDE.replace("[[supports]]", '[[body]]\nname = "loose"\n'
                              'box = [[0.1, 0.1, 0.1], [0.11, 0.11, 0.11]]\n\n[[supports]]')
    message = _error(tmp_path, text)
    assert "body 'loose' is joined to nothing" in message
    assert re.search(r"line \d+", message)


def test_no_support_is_refused(tmp_path):
    path = _write(tmp_path, WIRE_GUIDE.replace('[[supports]]\ngroup = "base"', ""))
    for read in (load_spec, load_spatial):
        with pytest.raises(ValueError) as info:
            read(path)
        message = str(info.value)
        assert message.startswith(f"{path}: the mechanism has no support")
        assert "(bodies: base, stage)" in message


def test_a_support_on_no_body_is_refused_at_its_line(tmp_path):
    text = WIRE_GUIDE.replace('[[supports]]\ngroup = "base"',
                              '[[supports]]\ngroup = "base"\n\n[[supports]]\ngroup = "solid"')
    line = text.splitlines().index('group = "solid"') + 1
    path = _write(tmp_path, text)
    with pytest.raises(ValueError) as info:
        load_spec(path)
    assert str(info.value).startswith(f"{path} line {line}: [[supports]] group = 'solid' is "
                                      "no body")


def test_unknown_body_and_wrong_unit_are_refused(tmp_path):
    message = _error(tmp_path, WIRE_GUIDE.replace('between = ["base", "stage"]',
                                                  'between = ["base", "stag"]', 1))
    assert "'stag' is no body" in message
    with pytest.raises(ValueError, match="diameter"):
        load_spatial(_write(tmp_path, WIRE_GUIDE.replace('d = "1 mm"', 'd = "1 mm"\nq = 1')
                            .replace('diameter = "d"', 'diameter = "5 deg"', 1), "u.toml"))


def test_a_root_fillet_is_refused_not_ignored(tmp_path):
    """Neither model draws a spatial flexure's root fillet yet: a nonzero fillet would run
    the square-rooted design unchanged, so it is refused at its line; 0 is accepted."""
    text = LEAF_GUIDE.replace('width = "w"', 'width = "w"\nfillet = "0.5 mm"', 1)
    message = _error(tmp_path, text)
    assert re.search(r"line \d+: flexure 1 'front'", message)
    assert "fillet = 0.0005 m" in message and "not modelled" in message
    zero = _write(tmp_path, LEAF_GUIDE.replace('width = "w"', 'width = "w"\nfillet = 0', 1),
                  "zero.toml")
    assert load_spatial(zero)[0].flexures[0].fillet == 0
