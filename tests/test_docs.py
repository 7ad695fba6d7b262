"""The README and the docs site say what is: short, the paper table the notebooks', no history."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from img2logo.experiments.runner import PAPER_ITEMS

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
HISTORY = re.compile(r"\b[Ss]ession [0-9]+|merged main of")


def test_the_readme_is_short_and_keeps_the_two_commands():
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 250
    assert "make figures" in text and "make test" in text


def test_the_readmes_notebook_table_is_the_notebooks():
    # Each notebook of notebooks/ has a row naming what PAPER_ITEMS says it reproduces.
    rows = re.findall(r"^\| `(\d\d_\w+)` \| ([^|]+) \|", README.read_text(encoding="utf-8"), flags=re.M)
    assert {name: item.strip() for name, item in rows} == {name: item for name, (item, _) in PAPER_ITEMS.items()}
    assert sorted(PAPER_ITEMS) == sorted(p.stem for p in (ROOT / "notebooks").glob("*.ipynb"))


@pytest.mark.parametrize("folder", ["README.md", "docs", "img2logo", "notebooks"])
def test_no_development_rounds_are_named(folder):
    paths = [ROOT / folder] if folder.endswith(".md") else sorted((ROOT / folder).rglob("*"))
    named = []
    for path in paths:
        if path.suffix not in {".md", ".py", ".ipynb", ".rst", ".json", ".css"} or "generated" in path.parts:
            continue
        if HISTORY.search(path.read_text(encoding="utf-8", errors="replace")):
            named.append(str(path.relative_to(ROOT)))
    assert not named, f"name development rounds (git log holds history): {named}"


def test_the_readmes_links_exist():
    text = README.read_text(encoding="utf-8")
    for target in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", text):
        assert (ROOT / target).exists(), f"README links to a missing file: {target}"


def test_the_quality_script_writes_the_docs_page(tmp_path):
    # A run over a part (one thick drawing) writes its tables, the command and the date to the page asked for.
    page = tmp_path / "quality.md"
    done = subprocess.run(
        [
            sys.executable,
            str(ROOT / "benchmarks" / "quality.py"),
            "--only",
            "thick/drawing-leaf-9",
            "--no-sheets",
            "--out",
            str(tmp_path),
            "--docs",
            str(page),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    text = page.read_text(encoding="utf-8")
    assert text.startswith("# Quality\n")
    assert "`python benchmarks/quality.py --only thick/drawing-leaf-9 --no-sheets" in text
    assert re.search(r"on \d{4}-\d\d-\d\d;", text)
    assert "| thick/drawing-leaf-9 | thick drawing | thick drawing | drawing |" in text
