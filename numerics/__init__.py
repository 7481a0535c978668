"""Numerics that know no physics: what every body and every model of the project shares.

    jit.py        the one jit policy, and the disk cache keyed on the sources
    keys.py       what a parameter means: its unit, range and help, stated once
    units.py      quantities with units read from scene files (pint), memoised
    files.py      files written whole or not at all
    folder.py     an output folder replaced as one set, never half-written
    engine/       the compiled Radau IIA integrator: dense output, events, resumable
    packed.py     a model's several arrays as one args array, the type every model shares
    integrate.py  one call for the engine and scipy's integrators (cross-checks)
    hybrid.py     runs in phases (contact, changes of variables) on the integrator

Nothing here imports ``lubrication`` or ``dynamics``; they build on it.
"""

from numerics.stamps import stamp_kernels

stamp_kernels(__name__)
