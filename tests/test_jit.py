"""numerics.jit: specialised copies of a template, and a disk cache keyed on the sources of each package and of
the packages below it."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from numerics import jit as _jit
from numerics.jit import (
    jit,
    package_stamp,
    sources_hash,
    sources_stamp,
    specialise,
    stamped_roots,
)


@jit
def _double(x):
    return 2.0 * x


@jit
def _square(x):
    return x * x


def _template(values):
    out = np.empty(values.size)
    for i in range(values.size):
        out[i] = KERNEL(values[i]) + 1.0  # noqa: F821 - bound by specialise
    return out


def test_each_copy_calls_its_own_function():
    values = np.array([0.5, 3.0])
    doubled = specialise(_template, "double", KERNEL=_double)
    squared = specialise(_template, "square", KERNEL=_square)
    np.testing.assert_array_equal(doubled(values), [2.0, 7.0])
    np.testing.assert_array_equal(squared(values), [1.25, 10.0])
    assert doubled.py_func.__qualname__ == "_template_double"


def test_a_name_taken_by_other_globals_is_refused():
    """Numba files a copy under its name: a second meaning of one name would load the first's code."""
    specialise(_template, "twice", KERNEL=_double)
    specialise(_template, "twice", KERNEL=_double)  # the same globals: accepted
    with pytest.raises(ValueError, match="_template_twice is already compiled with other globals"):
        specialise(_template, "twice", KERNEL=_square)


def test_the_sources_hash_follows_every_byte(tmp_path):
    first, second = tmp_path / "a.py", tmp_path / "b.py"
    first.write_text("x = 1\n")
    second.write_text("y = 2\n")
    before = sources_hash(first, second)
    assert sources_hash(first, second) == before
    second.write_text("y = 3\n")
    assert sources_hash(first, second) != before


def test_the_equations_are_filed_under_the_kernels_sources():
    """Compiled with a force kernel from another package, the equations' copies carry its name and the hash of
    its sources in theirs."""
    from dynamics.contact import full as contact
    from dynamics.equations import full
    from lubrication.registry import kernel_model

    for name in ("closed-form", "stokes-exact", "reynolds"):
        model = kernel_model(name)
        copies = [*full.model_functions(model), *contact.contact_functions(model)]
        assert all(c.py_func.__qualname__.endswith(model.kernel_name) for c in copies)
        assert model.kernel_name.startswith(name.replace("-", "_") + "_")


def test_the_stamp_follows_every_source_and_only_sources(tmp_path):
    package = tmp_path / "package"
    (package / "sub").mkdir(parents=True)
    (package / "a.py").write_text("A = 1\n")
    (package / "sub" / "b.py").write_text("B = 2\n")
    (package / "table.json").write_text("{}")
    before = sources_stamp(package)
    (package / "table.json").write_text("[]")  # not a source
    assert sources_stamp(package) == before
    (package / "sub" / "b.py").write_text("B = 3\n")
    edited = sources_stamp(package)
    assert edited != before
    (package / "sub" / "b.py").rename(package / "b.py")  # the same bytes elsewhere
    assert sources_stamp(package) != edited


def test_each_package_keys_its_kernels_on_its_sources_and_those_below_it():
    from dynamics.equations import reduced
    from lubrication import closed_form
    from numerics.engine import driver

    assert _jit.LOCATORS_INSTALLED
    names = {package: [Path(root).name for root in stamped_roots(package)]
             for package in ("numerics", "lubrication", "dynamics")}
    assert names == {"numerics": ["numerics"], "lubrication": ["lubrication", "numerics"],
                     "dynamics": ["dynamics", "lubrication", "numerics"]}
    assert reduced.rhs._cache._impl.locator.get_source_stamp() == package_stamp("dynamics")
    lubrication_kernel = closed_form.closed_form_resistance
    assert lubrication_kernel._cache._impl.locator.get_source_stamp() == package_stamp("lubrication")
    assert driver.no_events._cache._impl.locator.get_source_stamp() == package_stamp("numerics")
    assert len({package_stamp(p) for p in names}) == 3
    assert _double._cache._impl.locator.get_source_stamp() not in {package_stamp(p) for p in names}  # numba's own


_CALLEE = """from numerics.jit import jit

SCALE = {scale}


@jit
def callee(x):
    return SCALE * x
"""
_CALLER = """from numerics.jit import jit
from lubrication._probe_callee import callee


@jit
def caller(x):
    return callee(x) + 1.0


print(caller(3.0), sum(caller.stats.cache_hits.values()))
"""


def test_an_edit_to_a_called_module_recompiles_its_caller(tmp_path):
    """numba alone would load the caller's cached code, with the callee as it was compiled then."""
    root = Path(_jit.__file__).resolve().parents[1]
    for name in ("numerics", "lubrication", "dynamics"):
        shutil.copytree(root / name, tmp_path / name, ignore=shutil.ignore_patterns("__pycache__"))
    (tmp_path / "lubrication" / "_probe_caller.py").write_text(_CALLER)
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env["PYTHONPATH"] = str(tmp_path)

    def run(scale):
        (tmp_path / "lubrication" / "_probe_callee.py").write_text(_CALLEE.format(scale=scale))
        done = subprocess.run([sys.executable, "-m", "lubrication._probe_caller"], cwd=tmp_path, env=env,
                              capture_output=True, text=True, check=True)
        value, hits = done.stdout.split()
        return float(value), int(hits)

    assert run(2.0) == (7.0, 0)  # compiled and cached
    assert run(2.0) == (7.0, 1)  # loaded from the cache
    assert run(5.0) == (16.0, 0)  # the callee edited: compiled anew


_SHARED = '''
import sys
import time
from pathlib import Path

from numba import types

from numerics.jit import compile_shared, jit


@jit
def kernel(x):
    total = 0.0
    for i in range(10):
        total += x ** i / (1.0 + i)
    return total


print("ready", flush=True)
while not Path(sys.argv[1]).exists():
    time.sleep(0.005)
compile_shared(kernel, (types.float64,))
print(sum(kernel.stats.cache_misses.values()), sum(kernel.stats.cache_hits.values()))
'''


def test_processes_starting_together_compile_a_kernel_once(tmp_path):
    """Of two processes that ask for the same kernel at the same moment, one compiles and the other loads it."""
    (tmp_path / "probe_shared.py").write_text(_SHARED)
    go = tmp_path / "go"
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env["PYTHONPATH"] = os.pathsep.join([str(tmp_path), str(Path(_jit.__file__).resolve().parents[1])])
    procs = [subprocess.Popen([sys.executable, "probe_shared.py", str(go)], cwd=tmp_path, env=env,
                              stdout=subprocess.PIPE, text=True) for _ in range(2)]
    for proc in procs:
        assert proc.stdout.readline().strip() == "ready"
    go.touch()
    counts = [tuple(int(n) for n in proc.communicate(timeout=120)[0].split()) for proc in procs]
    assert sorted(counts) == [(0, 1), (1, 0)]  # (compiled, loaded) in each process
