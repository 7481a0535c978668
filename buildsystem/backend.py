"""The build backend: setuptools', with the kernels' build requirements only where the build compiles them.

``setup.py`` compiles the kernels of a first ``snail run`` into the wheel, which
needs numba and what the default scene imports in the isolated build
environment. With ``SNAIL_BUILD_KERNELS=0`` it compiles nothing, and pip need not
install those packages into that environment first, the larger part of setting
it up. An editable install never compiles them (they compile in the source tree
on first use), and asks for setuptools' own requirements only.
"""

from __future__ import annotations

import os
import re
import tomllib
from pathlib import Path

from setuptools import build_meta as _setuptools
from setuptools.build_meta import *  # noqa: F403 - every hook of the PEP 517 interface, as setuptools has it

#: What compiling the kernels imports (numba and the default scene's dependencies), as the project pins them.
KERNEL_PACKAGES = ("numpy", "scipy", "numba", "pint")


def _kernel_requirements() -> list[str]:
    project = tomllib.loads((Path(__file__).resolve().parents[1] / "pyproject.toml").read_text())["project"]
    return [requirement for requirement in project["dependencies"]
            if re.split(r"[<>=!~ ;\[]", requirement, maxsplit=1)[0].lower() in KERNEL_PACKAGES]


def _compiles_kernels() -> bool:
    return os.environ.get("SNAIL_BUILD_KERNELS", "1") != "0"


def get_requires_for_build_wheel(config_settings=None):
    extra = _kernel_requirements() if _compiles_kernels() else []
    return [*_setuptools.get_requires_for_build_wheel(config_settings), *extra]
