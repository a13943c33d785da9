"""The docs stay true to the code: every file path they name exists, and every Python block
in docs/*.md runs (the pages that check their block's numbers do it in their own tests)."""
from pathlib import Path
import re

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted((ROOT / "docs").glob("*.md")) + [ROOT / "README.md"]
PATH = re.compile(r"(?<![\w./-])((?:fem|geometry|studies|data|tests|benchmarks|examples|docs|scripts)"
                  r"/[\w./-]+\.(?:py|toml|md|geo|step|sh|json))")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_file_a_page_names_exists(page):
    missing = sorted({m for m in PATH.findall(page.read_text()) if not (ROOT / m).exists()})
    assert missing == []


BLOCKS = [(page, k, block) for page in sorted((ROOT / "docs").glob("*.md"))
          for k, block in enumerate(re.findall(r"```python\n(.*?)```", page.read_text(), re.S))]


@pytest.mark.parametrize("page, k, block", BLOCKS, ids=[f"{p.name}:{k}" for p, k, _ in BLOCKS])
def test_every_python_block_of_the_docs_runs(page, k, block, tmp_path, monkeypatch):
    monkeypatch.chdir(ROOT)  # blocks name files relative to the repository root
    exec(compile(block, f"{page.name} block {k}", "exec"), {"__name__": "__docs__"})
