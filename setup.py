"""setuptools' build, with one step more: the compiled kernels are built into the wheel.

``python -m pip wheel .`` (or ``python -m build``) runs ``build_py``, which here also
compiles :mod:`img2logo._compiled`'s entry points ahead of time with numba's ``pycc``
(for the architecture's generic processor) into ``img2logo/_compiled/`` of the
wheel: an installed wheel's first run starts in about a second instead of
compiling them first. The wheel is then specific to the platform and Python
version it was built for. Without a C compiler the wheel is built without
them, with a warning; the first run compiles them (and says so).
An editable install (``pip install -e .``) builds nothing: the first run does.
"""

from __future__ import annotations

import sys
import types
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution


class BuildWithKernels(build_py):
    """``build_py``, then the ahead-of-time kernels into the built package."""

    def run(self) -> None:
        super().run()
        if getattr(self, "editable_mode", False):
            return
        here = Path(self.build_lib) / "img2logo"
        for stale in (here / "_compiled").glob("_kernels_*"):  # an earlier build's, of other sources
            stale.unlink()
        # img2logo._compiled alone: its kernels need numpy and numba, not the package's other dependencies.
        package = types.ModuleType("img2logo")
        package.__path__ = [str(here)]
        saved = {k: v for k, v in sys.modules.items() if k == "img2logo" or k.startswith("img2logo.")}
        for k in saved:
            del sys.modules[k]
        sys.modules["img2logo"] = package
        try:
            from img2logo._compiled import kernels

            built = kernels.build(here / "_compiled", cpu="")
            self.announce(f"img2logo: compiled kernels {built.name}", level=2)
        except Exception as err:  # no C compiler or no numba: the first run compiles them
            print(f"warning: img2logo's kernels not built into the wheel ({err}); the first run compiles them")
        finally:
            for k in [k for k in sys.modules if k == "img2logo" or k.startswith("img2logo.")]:
                del sys.modules[k]
            sys.modules.update(saved)


class BinaryDistribution(Distribution):
    """A wheel with a compiled module: tagged for its platform and Python."""

    def has_ext_modules(self) -> bool:
        return True


setup(cmdclass={"build_py": BuildWithKernels}, distclass=BinaryDistribution)
