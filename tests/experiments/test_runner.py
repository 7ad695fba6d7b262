"""img2logo.experiments.runner: the notebooks' parameter checks and smoke values."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from img2logo import InvalidParameterError
from img2logo.experiments import check_parameters
from img2logo.experiments.runner import PARAMETER_RULES, SMOKE, NotebookParameterError

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize(
    ("name", "value", "expected"),
    [
        ("tolerance", -1, "parameter tolerance: expected a positive number (px), got -1"),
        ("tolerance", "5", "parameter tolerance: expected a positive number (px), got '5'"),
        ("tolerance", float("nan"), "parameter tolerance: expected a positive number (px), got nan"),
        ("smoke", "yes", "parameter smoke: expected True or False, got 'yes'"),
        ("repeats", 0, "parameter repeats: expected an integer >= 1, got 0"),
        ("repeats", 2.0, "parameter repeats: expected an integer >= 1, got 2.0"),
        ("kind", "sketch", "parameter kind: expected 'auto' or 'photo' or 'clipart' or 'drawing', got 'sketch'"),
        ("bias", 1.0, 'parameter bias: expected "auto" or a ladder bias in [0, 1), got 1.0'),
        ("images", [], 'parameter images: expected "all" or a non-empty list of file names in data/, got []'),
        ("images", ["nope.png"], "parameter images: no example image 'nope.png' in data/; available: clipart-apple"),
        ("sweep_tolerances", [4.0, -9.0], "expected a non-empty list of positive numbers (px), got [4.0, -9.0]"),
        ("fractions", [0.0, 1.5], "expected a non-empty list of fractions in [0, 1], got [0.0, 1.5]"),
        ("beak_center", (1.0,), "parameter beak_center: expected a point (x, y) in px, got (1.0,)"),
        ("biases", [None, 2.0], "expected a non-empty list of ladder biases in [0, 1) or None (automatic)"),
        ("user_exponents", [1.5], "expected None or a non-empty list of integer ladder exponents k, got [1.5]"),
    ],
)
def test_a_bad_value_is_one_line_naming_the_parameter(name, value, expected):
    with pytest.raises(NotebookParameterError) as caught:
        check_parameters(**{name: value})
    assert expected in str(caught.value)
    assert "\n" not in str(caught.value)
    assert isinstance(caught.value, InvalidParameterError)  # an img2logo error, a ValueError too


def test_good_values_pass():
    check_parameters(
        images="all",
        tolerance=5,
        bias="auto",
        biases=[None, 0.0, 0.5],
        user_exponents=None,
        beak_center=[375.0, 155.0],
        hook_angles=list(range(0, 95, 5)),
        zooms=0,
        min_length=0.0,
        smoke=True,
    )


def test_a_name_without_a_rule_is_refused():
    with pytest.raises(NotebookParameterError, match="parameter colour: no check is defined"):
        check_parameters(colour="red")


def test_jupyter_shows_the_error_as_its_one_line():
    err = NotebookParameterError("parameter tolerance: expected a positive number (px), got -1")
    assert err._render_traceback_() == [
        "NotebookParameterError: parameter tolerance: expected a positive number (px), got -1"
    ]


@pytest.mark.parametrize("notebook", sorted(SMOKE))
def test_the_smoke_values_pass_their_checks(notebook):
    values = SMOKE[notebook]
    assert values["smoke"] is True  # smoke outputs go to build/smoke/, never over figures/
    assert set(values) <= set(PARAMETER_RULES)
    check_parameters(**values)


def test_without_the_kit_extra_the_runner_says_so_in_one_line(tmp_path):
    code = """
import importlib.abc, sys

class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] == "papermill":
            raise ImportError("blocked: " + name)

sys.meta_path.insert(0, Block())
from img2logo.experiments.runner import main
sys.exit(main(sys.argv[1:]))
"""
    nb = ROOT / "notebooks" / "01_overview.ipynb"
    done = subprocess.run(
        [sys.executable, "-c", code, str(nb), str(tmp_path / "out.ipynb")], capture_output=True, text=True, check=False
    )
    assert done.returncode == 1
    assert done.stderr.count("\n") == 1 and "papermill is missing" in done.stderr and "[kit]" in done.stderr


def test_executed_notebook_names_its_kernel_as_jupyterlab_does(tmp_path):
    """JupyterLab opens a notebook whose kernelspec display name differs from the kernel's marked modified."""
    nbformat = pytest.importorskip("nbformat")
    pytest.importorskip("jupyter_client")
    from jupyter_client.kernelspec import KernelSpecManager

    from img2logo.experiments.runner import name_the_kernel

    nb = nbformat.v4.new_notebook(metadata={"kernelspec": {"name": "python3", "display_name": "Python 3"}})
    path = tmp_path / "run.ipynb"
    nbformat.write(nb, path)
    name_the_kernel(path, "python3")
    shown = KernelSpecManager().get_kernel_spec("python3").display_name
    assert nbformat.read(path, as_version=4).metadata.kernelspec.display_name == shown


@pytest.mark.parametrize(
    ("notebook", "output", "message"),
    [
        ("{tmp}/missing.ipynb", "{tmp}/out.ipynb", "error: notebook not found: {tmp}/missing.ipynb"),
        ("{tmp}", "{tmp}/out.ipynb", "error: notebook {tmp} is not a file"),
        (
            "{nb}",
            "{tmp}/no/such/out.ipynb",
            "error: output folder not found: {tmp}/no/such (for {tmp}/no/such/out.ipynb)",
        ),
        ("{nb}", "{tmp}", "error: output {tmp} is a folder; give a notebook file name"),
        ("{tmp}/copy.ipynb", "{tmp}/copy.ipynb", "error: output {tmp}/copy.ipynb is the notebook {tmp}/copy.ipynb"),
        ("{tmp}/copy.ipynb", "{tmp}/link.ipynb", "error: output {tmp}/link.ipynb is the notebook {tmp}/copy.ipynb"),
        ("{tmp}/copy.ipynb", "{tmp}/hard.ipynb", "error: output {tmp}/hard.ipynb is the notebook {tmp}/copy.ipynb"),
    ],
)
def test_bad_notebook_or_output_paths_are_one_line_exit_two(tmp_path, capsys, notebook, output, message):
    import os
    import shutil

    from img2logo.experiments.runner import main

    nb = ROOT / "notebooks" / "01_overview.ipynb"
    shutil.copy(nb, tmp_path / "copy.ipynb")
    (tmp_path / "link.ipynb").symlink_to(tmp_path / "copy.ipynb")
    os.link(tmp_path / "copy.ipynb", tmp_path / "hard.ipynb")
    before = (tmp_path / "copy.ipynb").read_bytes()
    names = sorted(p.name for p in tmp_path.iterdir())

    def fill(text: str) -> str:
        return text.replace("{tmp}", str(tmp_path)).replace("{nb}", str(nb))

    assert main([fill(notebook), fill(output)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(fill(message)) and err.count("\n") == 1
    assert (tmp_path / "copy.ipynb").read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == names


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        ([], "error: the following arguments are required: notebook, output"),
        (["a.ipynb", "b.ipynb", "--bogus"], "error: unrecognized arguments: --bogus"),
        (["a.ipynb", "b.ipynb", "-p", "levels"], "error: argument -p/--parameter: expected 2 arguments"),
    ],
)
def test_the_runners_own_argument_errors_are_one_line_exit_two(capsys, argv, message):
    from img2logo.experiments.runner import main

    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert err == f"{message} (see python -m img2logo.experiments --help)\n"
