"""The examples in the docstrings of the public API run, and say what they show.

Every public class and function of ``img2logo`` (``img2logo/__init__.pyi``) has an example
(numpydoc's Examples section) on the sample image :func:`img2logo.data.ring`; this runs them
as doctests in a temporary folder, with the package's own example and those of
``img2logo.data`` and ``img2logo.quality``.
"""

from __future__ import annotations

import doctest
import inspect

import pytest

import img2logo
from img2logo import data, quality

FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


def _public() -> list[tuple[str, object]]:
    """The public classes and functions (not the errors and warnings, whose docstrings say when)."""
    found = []
    for name in sorted(img2logo.__all__):
        obj = getattr(img2logo, name)
        if inspect.isclass(obj) and issubclass(obj, (Exception, Warning)):
            continue
        if inspect.isclass(obj) or inspect.isfunction(obj):
            found.append((name, obj))
    return found


def _run(tests: list[doctest.DocTest]) -> list[str]:
    """Run ``tests``; the report of each failure."""
    failures: list[str] = []
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    for test in tests:
        runner.run(test, out=failures.append)
    return failures


@pytest.mark.parametrize(("name", "obj"), _public(), ids=[name for name, _ in _public()])
def test_every_public_name_has_an_example_that_runs(name, obj, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the examples write their files here
    tests = [t for t in doctest.DocTestFinder(recurse=False).find(obj, f"img2logo.{name}") if t.examples]
    assert tests, f"img2logo.{name} has no example in its docstring"
    failures = _run(tests)
    assert not failures, "".join(failures)


@pytest.mark.parametrize("module", [img2logo, data, quality], ids=["img2logo", "img2logo.data", "img2logo.quality"])
def test_the_module_examples_run(module, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    tests = [t for t in doctest.DocTestFinder().find(module, module.__name__) if t.examples]
    assert tests
    failures = _run(tests)
    assert not failures, "".join(failures)
