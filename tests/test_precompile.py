"""The kernels a first `snail run` needs are compiled by the build and shipped in the wheel."""

from __future__ import annotations

import importlib.util
import io
import pickle
import re
import subprocess
import sys
import zipfile
from pathlib import Path, PurePosixPath

import numba
import pytest

from dynamics.app.precompile import SCENES
from dynamics.scenes import load_scene
from lubrication.registry import kernel_model
from numerics.jit import sources_stamp, stamped_roots

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
        # the engine's driver and the full model's right-hand side with the exact Stokes forces, compiled for the
        # default scene and filed under the hash of the kernels' sources as shipped
        for kernel in ("driver.advance", f"full._rhs_{kernel_model('stokes-exact').kernel_name}-"):
            assert any(i.name.startswith(kernel) for i in indexes), kernel
        # numba loads an index only if its stamp is the one its locator computes: the installed packages' sources
        # (each package's kernels are keyed on its sources and those of the packages below it)
        shipped = {package: sources_stamp(*(unpacked / Path(root).name for root in stamped_roots(package)))
                   for package in ("numerics", "lubrication", "dynamics")}
        for index in indexes:
            version, stamp = _index_stamp(wheel.read(str(index)))
            assert version == numba.__version__
            assert stamp == shipped[index.parts[0]], index


def _backend():
    """The in-tree build backend (``buildsystem/backend.py``), as pip loads it."""
    spec = importlib.util.spec_from_file_location("snail_build_backend", ROOT / "buildsystem" / "backend.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize(("setting", "compiles"), [(None, True), ("1", True), ("0", False)])
def test_the_build_asks_for_numba_only_where_it_compiles_the_kernels(monkeypatch, setting, compiles):
    backend = _backend()
    # setuptools' own answer runs setup.py's egg_info, which writes into the tree: only what is added is checked
    monkeypatch.setattr(backend._setuptools, "get_requires_for_build_wheel", lambda config_settings=None: ["wheel"])
    if setting is None:
        monkeypatch.delenv("SNAIL_BUILD_KERNELS", raising=False)
    else:
        monkeypatch.setenv("SNAIL_BUILD_KERNELS", setting)
    names = {re.split(r"[<>=!~ ;\[]", requirement, maxsplit=1)[0].lower()
             for requirement in backend.get_requires_for_build_wheel()}
    # what setup.py's compiling step imports: the kernels (numba) and the default scene (numpy, scipy, pint)
    kernels = {"numba", "numpy", "scipy", "pint"}
    assert kernels <= names if compiles else kernels.isdisjoint(names)
    assert "wheel" in names
