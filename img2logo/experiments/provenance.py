"""Where a committed figure came from: ``figures/<notebook>/provenance.json``.

``make figures`` calls :func:`write_provenance` after papermill executed a notebook.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from .paths import figure_dir, project_root


def write_provenance(executed: str | os.PathLike[str]) -> Path:
    """Write ``figures/<notebook>/provenance.json`` for a notebook papermill executed.

    It records the git commit of the repository (and whether the work tree had
    uncommitted changes), the parameters papermill injected and the defaults of
    the notebook's parameters cell, and the date of the run (UTC): what a
    reader needs to know where a committed figure came from; and the
    :func:`environment` it ran in (Python, the numerical packages, the
    platform), what explains a figure that differs in its last digits elsewhere.

    The folder then holds what this run wrote and nothing else: a file older
    than the run's start (papermill's ``start_time``), left by an earlier run
    whose outputs were named otherwise, is removed, so no committed figure
    outlives the code that made it. ``outputs`` lists the files kept,
    ``removed`` those removed.
    """
    import datetime
    import json
    import subprocess

    from .._io import atomic_write

    path = Path(executed)
    nb = json.loads(path.read_text(encoding="utf-8"))
    meta = nb.get("metadata", {}).get("papermill", {})
    defaults = next(
        ("".join(c["source"]) for c in nb["cells"] if "parameters" in c.get("metadata", {}).get("tags", [])), ""
    )
    root = project_root()

    def git(*args: str) -> str:
        done = subprocess.run(["git", *args], cwd=root, capture_output=True, text=True, check=False)
        return done.stdout.strip() if done.returncode == 0 else "unknown"

    record = {
        "notebook": f"notebooks/{path.name}",
        "git_commit": git("rev-parse", "HEAD"),
        "uncommitted_changes": bool(git("status", "--porcelain", "--", "img2logo", "notebooks", "data")),
        "parameters_injected": meta.get("parameters", {}),
        "parameters_cell": defaults,
        "date_utc": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "duration_s": round(float(meta.get("duration") or 0.0), 1),
        **environment(),
    }
    folder = figure_dir(path.stem)
    target = folder / "provenance.json"
    started = meta.get("start_time")
    removed: list[str] = []
    if started:
        # One second of slack: a file system may keep mtimes coarser than the clock.
        since = datetime.datetime.fromisoformat(started).timestamp() - 1.0
        for old in sorted(folder.iterdir()):
            if old != target and old.is_file() and old.stat().st_mtime < since:
                old.unlink()
                removed.append(old.name)
    record["outputs"] = sorted(p.name for p in folder.iterdir() if p.is_file() and p != target)
    record["removed"] = removed
    text = json.dumps(record, indent=2, sort_keys=True) + "\n"
    return atomic_write(target, lambda f: f.write(text.encode("utf-8")))


#: The distributions whose versions :func:`environment` records: those that compute the figures.
PROVENANCE_PACKAGES: tuple[str, ...] = (
    "numpy",
    "scipy",
    "opencv-contrib-python-headless",
    "scikit-image",
    "matplotlib",
    "numba",
    "shapely",
    "pandas",
    "pillow",
)


def environment() -> dict[str, Any]:
    """What a run depended on besides the code: ``python``, ``packages`` and ``platform``.

    ``packages`` maps each distribution of :data:`PROVENANCE_PACKAGES` to its
    installed version (``None`` when it is not installed), and ``opencv`` to
    the version OpenCV itself reports (the wheel's name varies); ``platform``
    holds the machine, the system and its release, and the CPU count.
    """
    import importlib.metadata
    import platform

    packages: dict[str, str | None] = {}
    for name in PROVENANCE_PACKAGES:
        try:
            packages[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            packages[name] = None
    try:
        import cv2

        packages["opencv"] = str(cv2.__version__)
    except ImportError:  # pragma: no cover - a dependency
        packages["opencv"] = None
    return {
        "python": platform.python_version(),
        "python_implementation": platform.python_implementation(),
        "packages": packages,
        "platform": {
            "system": platform.system(),
            "release": platform.release(),
            "machine": platform.machine(),
            "platform": platform.platform(),
            "cpu_count": os.cpu_count(),
        },
    }
