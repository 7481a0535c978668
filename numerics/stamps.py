"""Which sources key the disk cache of a package's kernels: its own and those of the packages below it.

Kept apart from :mod:`numerics.jit` so that a package can register itself in its
``__init__`` without importing numba: ``import lubrication`` stays cheap.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import os

__all__ = ["package_stamp", "roots_of", "sources_stamp", "stamp", "stamp_kernels", "stamped_roots"]

#: The root folder of each package that keys its kernels on its sources, and the roots whose sources
#: key them: its own, then those of the packages below it (:func:`stamp_kernels`).
_STAMPED: dict[str, tuple[str, ...]] = {}


def _root(package: str) -> str:
    """The folder of the importable package ``package`` (found, not imported)."""
    spec = importlib.util.find_spec(package)
    if spec is None or not spec.submodule_search_locations:
        msg = f"{package!r} is not an importable package"
        raise ValueError(msg)
    return os.path.abspath(next(iter(spec.submodule_search_locations)))


def stamp_kernels(package: str, *below: str) -> None:
    """Key the disk cache of ``package``'s kernels on its sources and on those of the packages ``below`` it.

    A package calls this in its ``__init__`` (before any of its kernels is compiled or
    loaded), naming the packages whose kernels its own may call: a layer names only
    layers beneath it, and this module names none.
    """
    roots = tuple(_root(name) for name in (package, *below))
    _STAMPED[roots[0]] = roots


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
def stamp(roots: tuple[str, ...]) -> str:
    return sources_stamp(*roots)


def stamped_roots(package: str) -> tuple[str, ...]:
    """The folders whose sources key the kernels of ``package`` (registered by :func:`stamp_kernels`)."""
    return _STAMPED[_root(package)]


def package_stamp(package: str) -> str:
    """The key of the disk cache of ``package``'s kernels, as this process found the sources."""
    return stamp(stamped_roots(package))


def roots_of(path: str) -> tuple[str, ...] | None:
    """The stamped roots of the innermost registered package holding the file ``path``, or None."""
    path = os.path.abspath(path)
    owners = [root for root in _STAMPED if path.startswith(root + os.sep)]
    return _STAMPED[max(owners, key=len)] if owners else None
