"""The notebooks' parameters: their checks, their smoke values, and the runner.

A notebook's first code cell after its parameters calls :func:`check_parameters`
with every parameter, so a bad value stops it at once with one line (a
:class:`NotebookParameterError`, shown without a traceback) instead of failing
deep inside a sweep. :func:`run_notebook` executes a notebook with papermill
after refusing any parameter name the notebook does not have; ``make figures``
and ``make figures-smoke`` call it through :func:`main`::

    python -m img2logo.experiments notebooks/04_tolerance_sweep.ipynb out.ipynb -p tolerance 4
    python -m img2logo.experiments notebooks/04_tolerance_sweep.ipynb out.ipynb --smoke

:data:`SMOKE` holds each notebook's small parameters (CI, ``make test``): they
are passed in like any other, a notebook never rewrites a parameter it was given.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any, NoReturn

from .._io import printable
from ..errors import Img2LogoError, InvalidParameterError
from .paths import data_path, eval_path, kit_module

#: Environment variable: "0" turns off the kit's progress bars (set while papermill runs a notebook).
PROGRESS_ENV = "IMG2LOGO_PROGRESS"


class NotebookParameterError(InvalidParameterError):
    """A notebook parameter has a bad value or an unknown name.

    Jupyter shows it as its one-line message, without a traceback (IPython's
    ``_render_traceback_`` hook).
    """

    def _render_traceback_(self) -> list[str]:
        return [f"{type(self).__name__}: {self}"]


class NotebookError(Img2LogoError, RuntimeError):
    """A notebook failed while papermill executed it."""


#: Each notebook's smoke parameters: small inputs, outputs in build/smoke/ (never over figures/).
SMOKE: dict[str, dict[str, Any]] = {
    "00_segment_graphs": {"smoke": True, "images": ["clipart-fish.png", "drawing-fish.png", "photo-cat.png"]},
    "01_overview": {"smoke": True, "images": ["drawing-fish.png"]},
    "02_visual_results": {"smoke": True, "images": ["drawing-fish.png", "drawing-bird.png"]},
    "03_simplicity": {"smoke": True, "images": ["drawing-fish.png"]},
    "04_tolerance_sweep": {
        "smoke": True,
        "images": ["drawing-bird.png"],
        "table_tolerances": [4.0, 9.0],
        "sweep_tolerances": [4.0, 9.0],
    },
    "05_connectivity_ablation": {"smoke": True, "images": ["drawing-bird.png"]},
    "06_redundant_intersections": {
        "smoke": True,
        "images": ["clipart-dolphin.png", "drawing-bird.png"],
        "tolerances": [5.0],
    },
    "07_arc_extraction": {"smoke": True, "images": ["drawing-bird.png"], "hook_angles": [0, 30, 60, 90]},
    "08_rdp_robustness": {"smoke": True, "images": ["drawing-bird.png"], "rdp_tolerances": [2.0, 8.0]},
    "09_timing": {"smoke": True, "images": ["drawing-leaf.png"], "repeats": 1},
    "10_design_exploration": {
        "smoke": True,
        "fig15_image": "drawing-fish.png",
        "bias_image": "drawing-fish.png",
        "search_tolerances": [3.0, 8.0],
        "biases": [None, 0.5],
    },
    "11_explore_levels": {"smoke": True, "image": "drawing-fish.png"},
    "12_designer_features": {"smoke": True, "fill_images": ["clipart-fish.png"]},
    "13_symmetry": {"smoke": True, "images": ["clipart-fox.png"], "eval_images": ["drawing-umbrella.png"]},
    "14_studio": {"smoke": True, "image": "drawing-fish.png"},
    "15_tangency": {"smoke": True, "images": ["drawing-bird.png"]},
    "16_limitations": {
        "smoke": True,
        "images": ["drawing-fish.png"],
        "tolerances": [5.0, 9.0],
        "complex_image": "drawing-fish.png",
        "search_tolerances": [5.0, 9.0],
        "window_tolerance": 9.0,
    },
}

#: What each notebook reproduces of the paper and what it shows: the notebooks index of the docs
#: site and the README's table are made from it (a test compares the README).
PAPER_ITEMS: dict[str, tuple[str, str]] = {
    "00_segment_graphs": ("Fig. 4a-b", "feature lines and segment graphs of every example"),
    "01_overview": ("Fig. 1, 4, 7, 8", "input, lines, segments, levels, result; free vs connected golden circles"),
    "02_visual_results": ("Fig. 10", "final results of the 15 examples, input as inset"),
    "03_simplicity": ("Table 1", "levels along a run; arcs and $E^s$ against the iteration"),
    "04_tolerance_sweep": ("Table 2", "T = 4, 5, 9 side by side; arcs against T"),
    "05_connectivity_ablation": ("Fig. 11, 6", "with / without the connectivity constraint; gaps"),
    "06_redundant_intersections": ("Fig. 12", "with / without intersection avoidance"),
    "07_arc_extraction": ("Fig. 9", "Fréchet vs sum-of-squares arc choice"),
    "08_rdp_robustness": ("Fig. 13", "RDP tolerances 1-8 px: segments and results"),
    "09_timing": ("Table 3", "localized fitting x simplification, the paper's timings beside ours"),
    "10_design_exploration": ("Fig. 15, 16", "chosen radii; a lock mask keeps the bird's beak; the bias"),
    "11_explore_levels": ("(interactive)", "a slider over the levels, T, bias, RDP, image, kind"),
    "12_designer_features": ("Fig. 17, 18", "user edits; colour fills"),
    "13_symmetry": ("(beyond the paper)", "mirror axes; free and symmetric logos"),
    "14_studio": ("Sec. 7, 8, Fig. 16, 17", "the designer's studio (`make studio`)"),
    "15_tangency": ("(beyond the paper)", "with / without tangent joins"),
    "16_limitations": (
        "Fig. 14, 20, 21",
        "simplicity a designer prefers; disconnected segments; straight lines; lost features",
    ),
}


# --------------------------------------------------------------------------- value checks
Check = Callable[[str, Any], None]


def _rule(ok: Callable[[Any], bool], expected: str) -> Check:
    """A check refusing a value ``ok`` rejects, with one line saying what was ``expected`` and what came."""

    def check(name: str, value: Any) -> None:
        if not ok(value):
            raise NotebookParameterError(f"parameter {name}: expected {expected}, got {value!r}")

    return check


def _number(low: float = -math.inf, high: float = math.inf, *, closed: bool = True) -> Callable[[Any], bool]:
    """A finite number in [low, high] (``closed``) or [low, high)."""
    return lambda v: (
        isinstance(v, int | float)
        and not isinstance(v, bool)
        and math.isfinite(v)
        and low <= v
        and (v <= high if closed else v < high)
    )


def _integer(minimum: float) -> Callable[[Any], bool]:
    return lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= minimum


def _listed(ok: Callable[[Any], bool]) -> Callable[[Any], bool]:
    """A non-empty list (or tuple) of values ``ok`` accepts."""
    return lambda v: isinstance(v, list | tuple) and bool(v) and all(ok(x) for x in v)


def _image(name: str, value: Any) -> None:
    if not isinstance(value, str) or not value:
        raise NotebookParameterError(f"parameter {name}: expected a file name in data/, got {value!r}")
    try:
        data_path(value)
    except Img2LogoError as err:
        raise NotebookParameterError(f"parameter {name}: {err}") from None


def _images(name: str, value: Any) -> None:
    if value != "all":
        _rule(_listed(lambda _: True), '"all" or a non-empty list of file names in data/')(name, value)
        for item in value:
            _image(name, item)


def _choice(*options: str) -> Check:
    return _rule(lambda v: v in options, " or ".join(repr(o) for o in options))


def _evaluation_image(v: Any) -> bool:
    if not isinstance(v, str):
        return False
    try:
        eval_path(v)
    except Img2LogoError:
        return False
    return True


def _positive(v: Any) -> bool:
    return _number()(v) and v > 0


_bias = _number(0.0, 1.0, closed=False)

#: How each notebook parameter is checked, by name (one meaning per name in every notebook).
PARAMETER_RULES: dict[str, Check] = {
    **dict.fromkeys(("smoke", "interactive", "tangency"), _rule(lambda v: isinstance(v, bool), "True or False")),
    **dict.fromkeys(("images", "fill_images"), _images),
    "eval_images": _rule(_listed(_evaluation_image), "a non-empty list of file names in benchmarks/data/"),
    **dict.fromkeys(("image", "edit_image", "fig15_image", "lock_image", "bias_image", "complex_image"), _image),
    "kind": _choice("auto", "photo", "clipart", "drawing"),
    "lock_form": _choice("disc", "square"),
    **dict.fromkeys(
        (
            "tolerance",
            "rdp_tolerance",
            "zoom",
            "threshold",
            "lost_threshold",
            "beak_radius",
            "lock_radius",
            "window_tolerance",
        ),
        _rule(_positive, "a positive number (px)"),
    ),
    "min_length": _rule(_number(0.0), "a number in [0, inf]"),
    "hook": _rule(_number(0.0, 180.0), "a number in [0, 180]"),
    "fit_fraction": _rule(_number(0.0, 1.0), "a number in [0, 1]"),
    "fractions": _rule(_listed(_number(0.0, 1.0)), "a non-empty list of fractions in [0, 1]"),
    **dict.fromkeys(
        ("tolerances", "table_tolerances", "sweep_tolerances", "search_tolerances", "rdp_tolerances"),
        _rule(_listed(_positive), "a non-empty list of positive numbers (px)"),
    ),
    "hook_angles": _rule(_listed(_number(0.0, 180.0)), "a non-empty list of angles in [0, 180] degrees"),
    **dict.fromkeys(("levels", "columns", "cases", "repeats", "n_exponents"), _rule(_integer(1), "an integer >= 1")),
    "zooms": _rule(_integer(0), "an integer >= 0"),
    "max_exponent": _rule(_integer(-30), "an integer ladder exponent k >= -30"),
    "strip_levels": _rule(_integer(2), "an integer >= 2"),
    "user_exponents": _rule(
        lambda v: v is None or _listed(_integer(-math.inf))(v), "None or a non-empty list of integer ladder exponents k"
    ),
    "beak_center": _rule(lambda v: _listed(_number())(v) and len(v) == 2, "a point (x, y) in px"),
    "bias": _rule(lambda v: v == "auto" or _bias(v), '"auto" or a ladder bias in [0, 1)'),
    "biases": _rule(
        _listed(lambda b: b is None or _bias(b)), "a non-empty list of ladder biases in [0, 1) or None (automatic)"
    ),
}


def check_parameters(**parameters: Any) -> None:
    """Check a notebook's parameters, each by the rule of its name (:data:`PARAMETER_RULES`).

    Called once at the top of every notebook with all its parameters.

    Raises
    ------
    NotebookParameterError
        The first bad value, as one line naming the parameter, what was
        expected and what came.
    """
    for name, value in parameters.items():
        rule = PARAMETER_RULES.get(name)
        if rule is None:
            raise NotebookParameterError(f"parameter {name}: no check is defined for it (add one to PARAMETER_RULES)")
        rule(name, value)


# --------------------------------------------------------------------------- running
def notebook_parameters(path: str | os.PathLike[str]) -> dict[str, Any]:
    """The parameters of a notebook's cell tagged ``parameters``, by name (``papermill.inspect_notebook``)."""
    return dict(kit_module("papermill").inspect_notebook(str(path)))


def run_notebook(
    path: str | os.PathLike[str],
    output: str | os.PathLike[str],
    parameters: Mapping[str, Any] | None = None,
    *,
    kernel_name: str = "python3",
) -> Path:
    """Execute a notebook with papermill, in its own folder, after checking the parameter names.

    Parameters
    ----------
    path : path
        The notebook.
    output : path
        Where the executed copy goes (written also when a cell fails).
    parameters : mapping, optional
        Values for names of the notebook's parameters cell.

    Returns
    -------
    Path
        ``output``, its kernelspec's display name the kernel's (so JupyterLab
        does not open it marked modified).

    Raises
    ------
    InvalidParameterError
        Before anything runs: the notebook is missing or no file, the output's
        folder is missing, or the output is the notebook itself (also through a
        link) or a folder.
    NotebookParameterError
        A name the notebook does not have (before anything runs), or a value
        its :func:`check_parameters` call refused.
    NotebookError
        Another error in a cell: its one-line message and the executed copy
        holding the traceback.
    """
    nb = Path(path)
    _check_paths(nb, Path(output))
    papermill = kit_module("papermill")
    from papermill.exceptions import PapermillExecutionError

    parameters = dict(parameters or {})
    known = notebook_parameters(nb)
    unknown = sorted(set(parameters) - set(known))
    if unknown:
        raise NotebookParameterError(
            f"{nb.name}: no parameter {', '.join(unknown)}; its parameters are {', '.join(known)}"
        )
    # A run for the record draws no progress bar into the executed notebook (sweep(progress=None)).
    # The kernel inherits the environment: one BLAS/OpenMP thread, as the command runs (cli.THREAD_VARIABLES:
    # the same bytes, without threads spinning beside the next notebook), unless the user set a count.
    from img2logo.app.cli import THREAD_VARIABLES

    settings = {PROGRESS_ENV: "0", **{var: os.environ.get(var, "1") for var in THREAD_VARIABLES}}
    previous = {name: os.environ.get(name) for name in settings}
    os.environ.update(settings)
    try:
        papermill.execute_notebook(
            str(nb),
            str(output),
            parameters=parameters,
            kernel_name=kernel_name,
            cwd=str(nb.resolve().parent),
            progress_bar=False,
            # The kernel's own log (a warning about its local TCP transport) is not ours to show.
            extra_arguments=["--IPKernelApp.log_level=ERROR"],
        )
    except PapermillExecutionError as err:
        message = f"{nb.name}: {err.ename}: {err.evalue}"
        if err.ename == NotebookParameterError.__name__:
            raise NotebookParameterError(message) from None
        raise NotebookError(f"{message} (cell {err.exec_count}; the traceback is in {output})") from None
    finally:
        for name, value in previous.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value
    name_the_kernel(Path(output), kernel_name)
    return Path(output)


def name_the_kernel(executed: Path, kernel_name: str | None) -> None:
    """Give the executed copy the kernelspec's display name, as JupyterLab does when it opens it.

    papermill keeps the source's ``"display_name"``; JupyterLab sets the running
    kernel's on opening, and a notebook whose metadata changed opens marked
    modified.
    """
    import nbformat
    from jupyter_client.kernelspec import KernelSpecManager, NoSuchKernel

    nb = nbformat.read(executed, as_version=4)
    spec = nb.metadata.setdefault("kernelspec", {})
    try:
        shown = KernelSpecManager().get_kernel_spec(kernel_name or spec.get("name") or "python3").display_name
    except NoSuchKernel:
        return
    if spec.get("display_name") != shown:
        spec["display_name"] = shown
        nbformat.write(nb, executed)


def _check_paths(nb: Path, output: Path) -> None:
    """Refuse, before anything runs, a notebook that is not there and an output that cannot be written or is it."""
    if not nb.is_file():
        raise InvalidParameterError(f"notebook not found: {nb}" if not nb.exists() else f"notebook {nb} is not a file")
    if output.is_dir():
        raise InvalidParameterError(f"output {output} is a folder; give a notebook file name")
    folder = output.parent if str(output.parent) else Path(".")
    if not folder.is_dir():
        raise InvalidParameterError(f"output folder not found: {folder} (for {output})")
    same = os.path.realpath(output) == os.path.realpath(nb)
    if not same and output.exists():
        try:
            same = os.path.samefile(output, nb)
        except OSError:
            same = False
    if same:
        raise InvalidParameterError(
            f"output {output} is the notebook {nb}: refusing to write over it; give another file"
        )


def _value(text: str) -> Any:
    """A ``-p`` value as YAML: ``4`` is an int, ``4.5`` a float, ``[a.png, b.png]`` a list, ``null`` None."""
    yaml = kit_module("yaml")

    try:
        return yaml.safe_load(text)
    except yaml.YAMLError:
        return text


class _Parser(argparse.ArgumentParser):
    """The runner's argument parser: an error is one line, ``error: ...`` (exit status 2), as the runner's others."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"error: {printable(message)} (see {self.prog} --help)\n")


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m img2logo.experiments NOTEBOOK OUTPUT [--smoke] [-p NAME VALUE]...``.

    Exit status 0 on success; 2 for a bad parameter, a missing notebook or output folder, or an
    output that is the notebook (one line, nothing run); 1 for a failed cell.
    """
    parser = _Parser(
        prog="python -m img2logo.experiments",
        description="Run a notebook with papermill; refuse parameter names it does not have.",
    )
    parser.add_argument("notebook", type=Path)
    parser.add_argument("output", type=Path)
    parser.add_argument("--smoke", action="store_true", help="pass the notebook's smoke parameters (SMOKE)")
    parser.add_argument(
        "-p", "--parameter", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"), help="a value, as YAML"
    )
    args = parser.parse_args(argv)
    parameters = dict(SMOKE.get(args.notebook.stem, {"smoke": True})) if args.smoke else {}
    try:
        parameters.update({name: _value(text) for name, text in args.parameter})
        run_notebook(args.notebook, args.output, parameters)
    except InvalidParameterError as err:  # a bad parameter, notebook or output: nothing ran
        print(f"error: {printable(err)}", file=sys.stderr)
        return 2
    except Img2LogoError as err:
        print(f"error: {printable(err)}", file=sys.stderr)
        return 1
    return 0
