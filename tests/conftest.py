import os
import signal
import tempfile

import numpy as np
import pytest

# Tests write only into temporary folders: the stored tables (finite-length factors, pint's
# definitions) go to a temporary folder of this test run, not to the user's ~/.cache. Subprocesses inherit it.
_CACHE = tempfile.TemporaryDirectory(prefix="snail-test-cache-")
os.environ["SNAIL_CACHE"] = _CACHE.name


@pytest.fixture(autouse=True)
def _raise_on_floating_point_errors():
    """Overflow, invalid operations and division by zero are bugs here, not warnings."""
    old = np.seterr(all="raise", under="ignore")
    yield
    np.seterr(**old)


@pytest.fixture
def rng():
    return np.random.default_rng(20070523)


@pytest.fixture
def ctrl_c():
    """Ctrl-C raises KeyboardInterrupt during the test, as on a terminal, even where the tests run in
    the background (a shell starts background jobs with SIGINT ignored)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def _sigint_as_on_a_terminal():
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.fixture
def terminal_child():
    """``preexec_fn`` for a subprocess: Ctrl-C handled in the child, as from a terminal, even where the tests
    run in the background (a shell starts background jobs with SIGINT ignored, and children inherit that)."""
    return _sigint_as_on_a_terminal


@pytest.fixture(scope="module")
def quick_group(tmp_path_factory):
    """``quick_group(name)``: the quick form of the group of ``snail validate`` that ``validation.reports.<name>``
    runs, as (folder, records, figure names, paragraph); run once a test file, into a folder of its own."""
    from validation import suite

    modules = {module.__name__.rpartition(".")[2]: module for module in suite.GROUPS.values()}
    done = {}

    def run(name: str):
        if name not in done:
            outdir = tmp_path_factory.mktemp(name)
            done[name] = (outdir, *modules[name].run(outdir, quick=True))
        return done[name]

    return run


#: What a test file names when it runs the integrator (in process, through ``snail`` or the README's
#: examples), whose driver numba compiles once for the whole run; the documentation's build compiles it early on.
_INTEGRATING = ("dynamics", "validation", "benchmarks", "numerics.engine", "numerics.integrate", "README")


def _file_rank(path, memo={}) -> int:  # noqa: B006 - one cache for the run
    """0 the documentation's build, 1 the sweeps, 2 files that never integrate, 3 the rest."""
    if path not in memo:
        text = path.read_text()
        memo[path] = (0 if path.name == "test_docs.py" else 1 if path.name.startswith("test_sweep")
                      else 3 if any(word in text for word in _INTEGRATING) else 2)
    return memo[path]


def pytest_collection_modifyitems(config, items):
    """Files in an order that keeps both processes busy (pytest's options keep it: ``--no-loadscope-reorder``).

    The documentation's build first, the longest file of the run: it goes to one process at the
    start, rather than last while the other waits. It compiles the integrator early on and would
    compile the sweeps' batch loop last, on the run's longest path (one process compiles a kernel,
    the others wait and load it). So the other process starts with the sweeps, which compile that
    loop meanwhile, then takes the files that never integrate, while the build compiles the
    integrator the rest need.
    """
    items.sort(key=lambda item: _file_rank(item.path))
