"""The kernels a first `snail run` needs are compiled by the build and shipped in the wheel."""

from __future__ import annotations

import io
import pickle
import subprocess
import sys
import zipfile
from pathlib import Path, PurePosixPath

import numba
import pytest

from dynamics.app.precompile import SCENES
from dynamics.equations.forces import CLOSED, KIND_NAMES
from dynamics.scenes import load_scene
from lubrication._jit import PACKAGES, sources_stamp

ROOT = Path(__file__).resolve().parents[1]


def test_the_precompiled_scene_is_the_default_one():
    assert [load_scene(None, overrides) for overrides in SCENES] == [load_scene()]


def _index_stamp(data: bytes):
    """numba's version and the source stamp an index file (.nbi) was written with."""
    stream = io.BytesIO(data)
    version = pickle.load(stream)
    stamp, _ = pickle.loads(stream.read())
    return version, stamp


@pytest.mark.slow
def test_the_wheel_ships_caches_numba_accepts_for_its_own_sources(tmp_path):
    subprocess.run([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-w", str(tmp_path)],
                   check=True, capture_output=True)
    unpacked = tmp_path / "unpacked"
    with zipfile.ZipFile(next(tmp_path.glob("*.whl"))) as wheel:
        wheel.extractall(unpacked)
        indexes = [PurePosixPath(n) for n in wheel.namelist() if n.endswith(".nbi")]
        # the engine's driver and the full model's right-hand side with the closed forms, compiled for the
        # default scene and filed under the hash of the kernels' sources as shipped
        for kernel in ("driver.advance", f"full._rhs_{KIND_NAMES[CLOSED]}-"):
            assert any(i.name.startswith(kernel) for i in indexes), kernel
        # numba loads an index only if its stamp is the one its locator computes: the installed packages' sources
        shipped = sources_stamp(*(unpacked / name for name in PACKAGES))
        for index in indexes:
            version, stamp = _index_stamp(wheel.read(str(index)))
            assert version == numba.__version__
            assert stamp == shipped, index
