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

The disk cache is keyed on every source of the packages ``dynamics`` and
``lubrication`` (:func:`project_stamp`), not only on the kernel's own file as
numba keys it: a kernel carries the code of the kernels it calls from other
modules and the values of their constants, so an edit to any of them must
compile it anew rather than load code that no longer matches the sources. Any
edit to the two packages therefore recompiles their kernels on the next run.
"""

from __future__ import annotations

import functools
import hashlib
import os
import types
from pathlib import Path

from numba import njit
from numba.core import caching

__all__ = ["JIT_OPTIONS", "jit", "project_stamp", "sources_hash", "sources_stamp", "specialise"]

#: Options every kernel is compiled with; a kernel may add ``inline`` or ``parallel``.
JIT_OPTIONS = {"cache": True, "nogil": True, "fastmath": False, "error_model": "numpy"}


def jit(func=None, **extra):
    """Compile ``func`` with :data:`JIT_OPTIONS` (plus ``extra``); usable as ``@jit`` or ``@jit(...)``."""
    options = {**JIT_OPTIONS, **extra}
    if func is None:
        return njit(**options)
    return njit(**options)(func)


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
    also where this numba's caching leaves :func:`project_stamp` out.
    """
    digest = hashlib.sha256()
    for path in paths:
        digest.update(Path(path).read_bytes())
    return digest.hexdigest()[:12]


#: The packages whose compiled code calls into one another; they are installed side by side.
PACKAGES = ("dynamics", "lubrication")
_ROOTS = tuple(os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), name) for name in PACKAGES)


def sources_stamp(*packages) -> str:
    """The sha256 of every ``*.py`` file under the folders ``packages``: relative paths and contents, in path order."""
    digest = hashlib.sha256()
    for package in map(os.fspath, packages):
        base, paths = os.path.dirname(package), []
        for folder, subfolders, names in os.walk(package):
            subfolders[:] = [d for d in subfolders if d != "__pycache__"]  # numba's cache files: hundreds
            paths += [os.path.join(folder, name) for name in names if name.endswith(".py")]
        for path in sorted(paths):
            digest.update(os.path.relpath(path, base).replace(os.sep, "/").encode() + b"\0")
            with open(path, "rb") as source:
                digest.update(source.read())
    return digest.hexdigest()


@functools.cache
def project_stamp() -> str:
    """:func:`sources_stamp` of :data:`PACKAGES` as this process found them: the key of their kernels' cache."""
    return sources_stamp(*_ROOTS)


class _ProjectStamped:
    """A numba cache locator for the kernels of :data:`PACKAGES`: the cache is keyed on :func:`project_stamp`."""

    @classmethod
    def from_function(cls, py_func, py_file):
        path = os.path.abspath(py_file)
        if not any(path.startswith(root + os.sep) for root in _ROOTS):
            return None  # not ours: numba's own locators take it
        return super().from_function(py_func, py_file)

    def get_source_stamp(self):
        return project_stamp()


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
    if not any(issubclass(c, _ProjectStamped) for c in classes):
        classes[:0] = [type(f"Project{name}", (_ProjectStamped, base), {}) for name, base in zip(names, bases)]
    return True


LOCATORS_INSTALLED = _install_locators()
