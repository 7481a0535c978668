"""Compile the kernels of a first ``snail run``, so that numba's cache of them can ship with the package.

The build (``setup.py``) runs this module on the staged copy of the package:
it integrates the embedded default scene (the full equations (2.1)-(2.4) with
the closed forms), and numba writes every kernel that takes to the
``__pycache__`` folder beside its source. Other models compile on their first
run, as before (the reduced equations (2.11): about 30 s); each would add as
much to every install. That cache is keyed on the packages' sources
(``numerics.jit``), the Python and numba versions and the CPU, so the
installed copy loads it as it stands; where anything differs (another CPU,
another numba) numba compiles again, as it would without it.
"""

from __future__ import annotations

from dynamics.app.run import run_scene
from dynamics.scenes import load_scene

__all__ = ["SCENES", "main"]

#: Overrides of the default scene that are compiled: none, the scene as shipped.
SCENES = ([],)


def main() -> None:
    """Run each of :data:`SCENES` once, which leaves its kernels in numba's cache."""
    for overrides in SCENES:
        run_scene(load_scene(None, overrides))


if __name__ == "__main__":
    main()
