"""Build step beyond ``pyproject.toml``: compile the kernels of a first ``snail run`` into the wheel.

numba compiles a kernel the first time it runs, about a minute and a half for
what a default ``snail run`` needs, and caches it beside the source. The
build runs :mod:`dynamics.app.precompile` on the staged package, so that the
cache ships with it and the first run after installing only loads it. The
cache is keyed on the sources of the packages (``numerics.jit``), the
Python and numba versions and the CPU; where one differs at run time, numba
compiles again as before.
``SNAIL_BUILD_KERNELS=0`` leaves the step out.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py


class BuildWithKernels(build_py):
    """Stage the packages, then fill their ``__pycache__`` folders with compiled kernels."""

    def run(self):
        super().run()
        if self.editable_mode:  # an editable install compiles in the source tree on first use
            return
        staged = Path(self.build_lib).resolve()
        # setuptools reuses its staging folder: a previous build's kernels must not ship with this one
        for stale in (*staged.rglob("*.nbi"), *staged.rglob("*.nbc")):
            stale.unlink()
        if os.environ.get("SNAIL_BUILD_KERNELS", "1") == "0":  # where only the source tree will run (tests)
            return
        # numba must write beside the staged sources (no NUMBA_CACHE_DIR), and the
        # run must not touch the user's table cache
        env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
        env["PYTHONPATH"] = os.pathsep.join(filter(None, (str(staged), env.get("PYTHONPATH"))))
        env["SNAIL_CACHE"] = str(staged / ".build-cache")
        done = subprocess.run([sys.executable, "-m", "dynamics.app.precompile"], check=False, cwd=staged,
                              env=env)
        shutil.rmtree(staged / ".build-cache", ignore_errors=True)
        if done.returncode != 0:
            self.warn("compiling the kernels failed; numba will compile them on the first run instead")


setup(cmdclass={"build_py": BuildWithKernels})
