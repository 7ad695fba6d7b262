"""The wheel as a user gets it: built, installed in a fresh venv outside the repository, run once.

Marked ``wheel`` (``make test-wheel``; deselected by ``make test``): it needs a C compiler
and PyPI (pip installs the build's and the package's dependencies), and takes minutes.
"""

from __future__ import annotations

import os
import subprocess
import sys
import venv
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.wheel


#: The environment of every command: without PYTHONPATH, which would show pip and Python the checkout's img2logo.
ENV = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}


def _run(cmd: list[str], cwd: Path, timeout: float = 3600) -> subprocess.CompletedProcess[str]:
    out = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=ENV)
    assert out.returncode == 0, f"{cmd[:4]} failed:\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}"
    return out


def test_the_wheel_ships_its_kernels_and_the_first_run_uses_them(tmp_path):
    from img2logo._compiled import kernels

    wheels = tmp_path / "wheels"
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", str(ROOT), "-w", str(wheels)], cwd=tmp_path)
    (wheel,) = wheels.glob("img2logo-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    assert "img2logo/py.typed" in names and "img2logo/export/abstraction.schema.json" in names
    shipped = [n for n in names if n.startswith(f"img2logo/_compiled/{kernels.module_name()}.")]
    assert len(shipped) == 1, [n for n in names if "_kernels_" in n]
    assert "-py3-none-any" not in wheel.name  # a compiled module: tagged for its platform

    env_dir = tmp_path / "venv"
    venv.EnvBuilder(with_pip=True).create(env_dir)
    python = env_dir / "bin" / "python"
    _run([str(python), "-m", "pip", "install", "-q", str(wheel)], cwd=tmp_path)

    svg = tmp_path / "fish.svg"
    cache = tmp_path / "cache"  # an empty user cache: the kernels can only come from the wheel
    command = [str(env_dir / "bin" / "img2logo"), str(ROOT / "data" / "clipart-fish.png"), "--svg", str(svg)]
    out = subprocess.run(
        command, cwd=tmp_path, capture_output=True, text=True, timeout=600, env={**ENV, "XDG_CACHE_HOME": str(cache)}
    )
    assert out.returncode == 0, out.stderr[-3000:]
    assert svg.read_text().startswith("<?xml") and "<path" in svg.read_text()
    assert "compiling its kernels" not in out.stderr  # nothing compiled: the wheel's module ran
    assert not cache.exists() or not any(cache.rglob("_kernels_*"))
    where = _run(
        [str(python), "-c", "from img2logo._compiled import kernels; kernels.usable(); print(kernels.source)"], tmp_path
    )
    assert where.stdout.strip().startswith(str(env_dir)) and "/img2logo/_compiled/_kernels_" in where.stdout

    # The validation the API promises works in a plain install (jsonschema is a dependency).
    check = (
        "import json, sys; from img2logo.export.contract import validate_document\n"
        "validate_document(json.load(open(sys.argv[1]))); print('valid')"
    )
    doc = tmp_path / "fish.json"
    subprocess.run(
        [str(env_dir / "bin" / "img2logo"), str(ROOT / "data" / "clipart-fish.png"), "-q", "--json", str(doc)],
        cwd=tmp_path,
        check=True,
        timeout=600,
        env=ENV,
    )
    assert _run([str(python), "-c", check, str(doc)], tmp_path).stdout.strip() == "valid"
