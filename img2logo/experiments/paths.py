"""Where the kit finds the repository, its example images and its output folders; the kit's extra packages."""

from __future__ import annotations

import dataclasses
import importlib
import os
from pathlib import Path
from typing import Any

from ..errors import Img2LogoError
from ..images.loading import LoadedImage, load_image

#: Environment variable naming the repository root, when it cannot be found.
ROOT_ENV = "IMG2LOGO_ROOT"
_MARKER = Path("data") / "ATTRIBUTION.md"


def kit_module(name: str) -> Any:
    """Import ``name``, one of the packages of the extra ``[kit]`` (papermill, ipywidgets, yaml).

    Raises
    ------
    Img2LogoError
        One line saying how to install the extra, when the package is missing.
    """
    try:
        return importlib.import_module(name)
    except ImportError:
        raise Img2LogoError(
            f"{name} is missing: the notebook kit needs the extra [kit] "
            "(pip install -e '.[kit]'; make test, make figures and make lab install it)"
        ) from None


def project_root() -> Path:
    """The repository root: the folder holding ``data/ATTRIBUTION.md``.

    Looked up from ``$IMG2LOGO_ROOT``, then upwards from the working directory,
    then upwards from this package (an editable install inside the repository).
    """
    env = os.environ.get(ROOT_ENV)
    if env:
        root = Path(env).resolve()
        if not (root / _MARKER).is_file():
            raise Img2LogoError(f"${ROOT_ENV}={env} does not hold {_MARKER}")
        return root
    for start in (Path.cwd(), Path(__file__).resolve().parent.parent):
        for folder in (start, *start.parents):
            if (folder / _MARKER).is_file():
                return folder
    raise Img2LogoError(f"cannot find the img2logo repository (a folder with {_MARKER}); set ${ROOT_ENV}")


def data_path(name: str) -> Path:
    """Absolute path of an example image in ``data/``, e.g. ``data_path("clipart-fish.png")``."""
    path = project_root() / "data" / name
    if not path.is_file():
        available = ", ".join(p.name for p in example_images())
        raise Img2LogoError(f"no example image {name!r} in data/; available: {available}")
    return path


def eval_path(name: str) -> Path:
    """Absolute path of an image of the evaluation set, ``benchmarks/data/<name>``."""
    path = project_root() / "benchmarks" / "data" / name
    if not path.is_file():
        raise Img2LogoError(f"no image {name!r} in benchmarks/data/")
    return path


def example_images(prefix: str = "") -> list[Path]:
    """The example images of ``data/`` whose names start with ``prefix``, sorted."""
    return sorted((project_root() / "data").glob(f"{prefix}*.png"))


def repo_relative(path: str | os.PathLike[str]) -> str:
    """``path`` relative to the repository root (``data/clipart-fish.png``), POSIX style; absolute if outside.

    Result documents name their input this way, so a ``make figures`` in any
    checkout writes the same bytes.
    """
    resolved = Path(path).resolve()
    try:
        return resolved.relative_to(project_root()).as_posix()
    except ValueError:
        return str(resolved)


def load_example(path: Any) -> LoadedImage:
    """:func:`img2logo.load_image`, a path's ``source`` made relative to the repository (:func:`repo_relative`)."""
    if not isinstance(path, str | os.PathLike):
        return load_image(path)
    return dataclasses.replace(load_image(path), source=repo_relative(path))


def figure_dir(notebook: str, *, smoke: bool = False) -> Path:
    """The output folder of a notebook, created: ``figures/<notebook>/`` (smoke runs: ``build/smoke/<notebook>/``)."""
    out = project_root() / ("build/smoke" if smoke else "figures") / notebook
    out.mkdir(parents=True, exist_ok=True)
    return out
