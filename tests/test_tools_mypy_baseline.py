"""make lint's type check (tools/mypy_baseline.py): per-file error counts that may go down, never up."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

_PATH = Path(__file__).resolve().parents[1] / "tools" / "mypy_baseline.py"
_SPEC = importlib.util.spec_from_file_location("mypy_baseline", _PATH)
assert _SPEC is not None and _SPEC.loader is not None
mypy_baseline = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(mypy_baseline)

OUTPUT = """\
img2logo/design/edits.py:156: error: Argument 1 to "enumerate" has incompatible type  [arg-type]
img2logo/design/edits.py:157: error: Value of type "tuple[int | None, ...] | None" is not indexable  [index]
img2logo/design/edits.py:157: note: a note is no error
img2logo/experiments/layout.py:12:5: error: Cannot infer type of lambda  [misc]
Found 3 errors in 2 files (checked 60 source files)
"""


def test_errors_are_counted_per_file_without_notes_or_the_summary():
    assert mypy_baseline.count_errors(OUTPUT) == {"img2logo/design/edits.py": 2, "img2logo/experiments/layout.py": 1}
    assert mypy_baseline.count_errors("Success: no issues found in 60 source files\n") == {}


def test_the_baseline_reads_back_what_it_writes():
    counts = {"img2logo/b.py": 3, "img2logo/a.py": 1, "img2logo/clean.py": 0}
    text = mypy_baseline.format_baseline(counts)
    assert text.endswith("1 img2logo/a.py\n3 img2logo/b.py\n")  # sorted, files without errors left out
    assert mypy_baseline.read_baseline(text) == {"img2logo/a.py": 1, "img2logo/b.py": 3}
    with pytest.raises(ValueError, match=r"line 1: expected '<errors> <path>', got 'three img2logo/a\.py'"):
        mypy_baseline.read_baseline("three img2logo/a.py\n")


def test_a_count_that_rises_fails_and_one_that_falls_is_reported():
    baseline = {"img2logo/a.py": 2, "img2logo/b.py": 5}
    assert mypy_baseline.compare({"img2logo/a.py": 2, "img2logo/b.py": 5}, baseline) == ([], [])
    rose, fell = mypy_baseline.compare({"img2logo/a.py": 3, "img2logo/b.py": 1, "img2logo/new.py": 1}, baseline)
    assert rose == ["img2logo/a.py: 3 errors, baseline 2", "img2logo/new.py: 1 error, baseline 0"]
    assert fell == ["img2logo/b.py: 1 error, baseline 5"]
    # a file fixed entirely, or removed, goes down to 0
    assert mypy_baseline.compare({}, baseline) == (
        [],
        ["img2logo/a.py: 0 errors, baseline 2", "img2logo/b.py: 0 errors, baseline 5"],
    )


def test_the_committed_baseline_is_readable_and_names_files_of_the_package():
    counts = mypy_baseline.read_baseline(mypy_baseline.BASELINE.read_text(encoding="utf-8"))
    assert counts and all(path.startswith("img2logo/") and path.endswith(".py") for path in counts)
    root = mypy_baseline.ROOT
    assert all((root / path).is_file() for path in counts), [p for p in counts if not (root / p).is_file()]
