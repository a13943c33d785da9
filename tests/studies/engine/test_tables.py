"""The shared CSV writer: columns in first-seen order, gaps empty, chosen columns only."""
import csv

import pytest
from flexfem.studies.engine.tables import write_rows


def read(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def test_columns_are_the_union_of_keys_in_first_seen_order(tmp_path):
    path = write_rows(tmp_path / "t.csv", [{"a": 1, "b": 2.5}, {"b": 3, "c": "x"}])
    assert read(path) == [["a", "b", "c"], ["1", "2.5", ""], ["", "3", "x"]]


def test_chosen_columns_only_and_empty_input_rejected(tmp_path):
    path = write_rows(tmp_path / "t.csv", [{"a": 1, "curve": [1, 2]}], columns=["a"])
    assert read(path) == [["a"], ["1"]]
    assert read(write_rows(tmp_path / "h.csv", [], columns=["a"])) == [["a"]]
    with pytest.raises(ValueError, match="no rows"):
        write_rows(tmp_path / "e.csv", [])
