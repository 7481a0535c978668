"""The project's one jit policy: every numba kernel is compiled through :func:`jit`.

Compiled code is cached on disk (``cache=True``), releases the GIL (``nogil``,
so that threads and dask workers run kernels side by side) and keeps IEEE
semantics (``fastmath=False``: a validation code must not trade NaN and
rounding guarantees for speed), division included (``error_model="numpy"``: a
division by zero gives inf or NaN, which the integrator and the Python faces
report, where numba's default would raise an exception that a call through a
first-class function, as the engine makes, cannot pass on: the process went on
with undefined state and crashed). ``NUMBA_DISABLE_JIT=1`` runs every kernel as
plain Python, for coverage and debugging.

The disk cache of a package's kernels is keyed on every source of that package
and of the packages below it (:func:`stamp_kernels`, which each package calls),
not only on the kernel's own file as numba keys it: a kernel carries the code of
the kernels it calls from other modules and the values of their constants, so an
edit to any of them must compile it anew rather than load code that no longer
matches the sources. An edit to a package therefore recompiles its kernels and
those of the packages above it on the next run. This module names no package.
"""

from __future__ import annotations

import contextlib
import hashlib
import inspect
import tempfile
import time
import types
from pathlib import Path

try:
    import fcntl
except ImportError:  # not POSIX: no lock, each process compiles for itself
    fcntl = None

from numba import njit
from numba.core import caching, event

from numerics.stamps import (
    package_stamp,
    roots_of,
    sources_stamp,
    stamp,
    stamp_kernels,
    stamped_roots,
)

__all__ = ["JIT_OPTIONS", "CompileWatch", "compile_shared", "compile_watch", "jit", "package_stamp", "sources_hash", "sources_stamp", "specialise", "stamp_kernels",
           "stamped_roots"]

#: Options every kernel is compiled with; a kernel may add ``inline`` or ``parallel``.
JIT_OPTIONS = {"cache": True, "nogil": True, "fastmath": False, "error_model": "numpy"}


def jit(func=None, **extra):
    """Compile ``func`` with :data:`JIT_OPTIONS` (plus ``extra``); usable as ``@jit`` or ``@jit(...)``."""
    options = {**JIT_OPTIONS, **extra}
    if func is None:
        return njit(**options)
    return njit(**options)(func)


def compile_shared(dispatcher, signature) -> None:
    """``dispatcher.compile(signature)``, at most one process of this machine compiling it at a time.

    The others wait for it and then load the compiled code from numba's disk cache,
    where compiling alongside would double the cost (the engine's driver: about 40 s;
    a sweep's batch loop: about 70 s) on cores that are already busy: the workers of
    a sweep and the processes of a test run start on the same kernels together.
    The lock is an ``flock`` on a file in the temporary folder named after the
    function's file, name and signature; the system releases it if its holder dies.
    """
    if fcntl is None:
        dispatcher.compile(signature)
        return
    py_func = dispatcher.py_func
    key = f"{inspect.getfile(py_func)}:{py_func.__qualname__}:{signature}"
    lock = Path(tempfile.gettempdir()) / f"numba-compile-{hashlib.sha256(key.encode()).hexdigest()[:16]}.lock"
    with lock.open("a") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            dispatcher.compile(signature)
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


#: The globals each (module, template, name) was compiled with, in this process.
_SPECIALISED: dict = {}


def specialise(template, name: str, **bound):
    """:func:`jit` of a copy of the plain function ``template`` in which the globals ``bound`` are given.

    Compiled functions a template calls through a global name (a force kernel, say)
    are compiled into its code: a copy per choice carries only the code it calls.
    Numba files a compiled function under its qualified name, so each copy is named
    ``<template>_<name>`` and keeps its own entry in the disk cache; the cache is
    keyed on sources, not on the globals bound, so ``name`` must say what ``bound``
    holds; the same name with other globals is refused (ValueError).
    """
    key = (template.__module__, template.__qualname__, name)
    if _SPECIALISED.setdefault(key, bound) != bound:
        msg = f"{template.__qualname__}_{name} is already compiled with other globals: give these another name"
        raise ValueError(msg)
    namespace = {**template.__globals__, **bound}
    copy = types.FunctionType(template.__code__, namespace, f"{template.__name__}_{name}", template.__defaults__,
                              template.__closure__)
    copy.__qualname__ = f"{template.__qualname__}_{name}"
    copy.__module__ = template.__module__
    copy.__doc__ = template.__doc__
    return jit(copy)


def sources_hash(*paths: Path) -> str:
    """The first 12 hex digits of the sha256 of the files ``paths``, in the order given.

    numba by itself checks only the source file of a function it loads from its
    cache, not of the code compiled into it: a :func:`specialise` copy named with
    the hash of every source it carries is compiled anew when any of them changes,
    also where this numba's caching leaves the sources stamp of :func:`stamp_kernels` out.
    """
    digest = hashlib.sha256()
    for path in paths:
        digest.update(Path(path).read_bytes())
    return digest.hexdigest()[:12]


class _SourcesStamped:
    """A numba cache locator for the kernels of the packages of :func:`stamp_kernels`, keyed on their sources."""

    @classmethod
    def from_function(cls, py_func, py_file):
        roots = roots_of(py_file)
        if roots is None:
            return None  # not a registered package's: numba's own locators take it
        locator = super().from_function(py_func, py_file)
        if locator is not None:
            locator.stamped_roots = roots
        return locator

    def get_source_stamp(self):
        return stamp(self.stamped_roots)


def _install_locators() -> bool:
    """Put the project's locators ahead of numba's own; False where this numba's caching differs.

    Without them (another numba), numba keys each kernel on its own file, and the
    names that carry :func:`sources_hash` still cover the force kernels and the engine.
    """
    impl = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl", None)
    names = ("UserProvidedCacheLocator", "InTreeCacheLocator", "UserWideCacheLocator")
    bases = [getattr(caching, name, None) or getattr(caching, f"_{name}", None) for name in names]
    classes = getattr(impl, "_locator_classes", None)
    if not isinstance(classes, list) or None in bases:
        return False
    if not any(issubclass(c, _SourcesStamped) for c in classes):
        classes[:0] = [type(f"Stamped{name}", (_SourcesStamped, base), {}) for name, base in zip(names, bases)]
    return True


LOCATORS_INSTALLED = _install_locators()


class CompileWatch(event.Listener):
    """Seconds numba spends compiling (cache misses; loading from the cache is not compiling), and a
    callback at the first compile. Compiles nested in another (a callee compiled with its caller) count once.
    """

    def __init__(self, on_first=None):
        self.compile_s, self.compiled, self._depth, self._start, self._on_first = 0.0, 0, 0, 0.0, on_first

    def on_start(self, ev):
        if self._depth == 0:
            if self.compiled == 0 and self._on_first is not None:
                self._on_first(ev)
            self._start = time.perf_counter()
        self._depth += 1

    def on_end(self, ev):
        self._depth -= 1
        if self._depth == 0:
            self.compile_s += time.perf_counter() - self._start
            self.compiled += 1


@contextlib.contextmanager
def compile_watch(on_first=None):
    """A :class:`CompileWatch` listening to numba's compiles inside the block (``on_first(event)`` at the first)."""
    watch = CompileWatch(on_first)
    with event.install_listener("numba:compile", watch):
        yield watch
