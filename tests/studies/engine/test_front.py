"""Front searches: NSGA-II (pymoo) finds ZDT1's known front, honours a constraint, and a re-run
finds every evaluation in its store."""
import math

import pytest
from flexfem.studies.cli import main
from flexfem.studies.run import run_front

pytest.importorskip("pymoo", reason="pymoo is a dependency of front searches")


def _front_file(tmp_path, constraint: str = "", generations: int = 60) -> str:
    path = tmp_path / "zdt1.toml"
    variables = "\n".join(f"x{i} = [0.0, 1.0]" for i in range(1, 6))
    path.write_text(f'mechanism = "zdt1:evaluate"\n[variables]\n{variables}\n'
                    '[[objectives]]\nmetric = "f1"\ngoal = "min"\n'
                    '[[objectives]]\nmetric = "f2"\ngoal = "min"\n' + constraint +
                    f"[search]\npopulation = 40\ngenerations = {generations}\nseed = 1\n")
    return str(path)


def test_zdt1_front_is_found(tmp_path):
    result = run_front(_front_file(tmp_path), tmp_path / "out", allow_code=True)
    designs = result["designs"]
    assert len(designs) >= 20
    f1 = [d["objectives"]["f1"] for d in designs]
    gaps = [d["objectives"]["f2"] - (1 - math.sqrt(d["objectives"]["f1"])) for d in designs]
    assert max(gaps) < 0.05 and min(gaps) > -1e-9  # on the true front, never beyond it
    assert min(f1) < 0.05 and max(f1) > 0.9          # and spread along it
    again = run_front(_front_file(tmp_path), tmp_path / "out", allow_code=True)
    assert again["designs"] == designs               # the same designs, from the store


def test_a_reference_design_is_placed_beside_the_front(tmp_path):
    """x = 0.5 everywhere lies far behind ZDT1's front (g = 5.5): front designs dominate it."""
    reference = "[[reference]]\nname = \"middle\"\nparams = " + "{ " + ", ".join(
        f"x{i} = 0.5" for i in range(1, 6)) + " }\n"
    path = _front_file(tmp_path, generations=20)
    with open(path, "a") as f:
        f.write(reference)
    result = run_front(path, tmp_path / "out", allow_code=True)
    (middle,) = result["references"]
    assert middle["name"] == "middle" and middle["objectives"]["f1"] == pytest.approx(0.5)
    assert middle["dominated_by"] >= 1


def test_a_constraint_cuts_the_front(tmp_path):
    constraint = '[[constraints]]\nmetric = "f1"\nat_least = 0.5\n'
    result = run_front(_front_file(tmp_path, constraint, 40), tmp_path / "out", allow_code=True)
    assert all(d["objectives"]["f1"] >= 0.5 - 1e-9 for d in result["designs"])
    assert all(d["margins"]["f1"] >= -1e-9 for d in result["designs"])


def test_code_is_refused_without_allow_code(tmp_path, capsys):
    assert main(["front", _front_file(tmp_path), "--out", str(tmp_path / "o")]) == 2
    assert "--allow-code" in capsys.readouterr().err


@pytest.mark.parametrize("old, new, message", [
    ('goal = "min"\n[[objectives]]', 'goal = "min"\nweight = 2\n[[objectives]]',
     r"unknown key\(s\) \['weight'\]"),
    ("seed = 1", 'seed = "abc"', "search.seed = 'abc' must be an integer >= 0"),
    ("seed = 1", "seed = 1\npopulaton = 8", r"\[search\]: unknown key\(s\) \['populaton'\]"),
    ("[search]", '[[constraints]]\nmetric = "f1"\nat_least = "half"\n[search]',
     "constraint 'f1' at_least = 'half' must be a number"),
])
def test_a_bad_front_file_is_refused_by_its_key(tmp_path, old, new, message):
    path = _front_file(tmp_path)
    text = open(path).read()
    assert old in text
    open(path, "w").write(text.replace(old, new, 1))
    with pytest.raises(ValueError, match=message):
        run_front(path, tmp_path / "out", allow_code=True)
    assert not (tmp_path / "out").exists()


def test_a_constraint_bound_may_carry_a_unit():
    from flexfem.studies.engine.front import _bound

    assert _bound("0.5 mm", "at_least") == pytest.approx(5e-4)
    assert _bound("2 kN/m", "at_least") == pytest.approx(2000.0)
    assert _bound(3, "at_least") == 3.0
