"""Parameter sweeps of scenes on dask: ``snail sweep``.

One module per concept, each importing only those before it:

``spec``
    The sweep file: a base scene and its axes, validated; the points they make,
    each named by a hash of its overrides.
``point``
    One point: its scene built, run and classified into a row (the regime and
    the numbers that decided it), a failure recorded with its reason.
``compiled``
    The compiled loop: many runs of the reduced equations (2.11) in one call.
``batch``
    The points of the reduced equations without contact set up as ``simulate``
    would, run in the compiled loop and classified to the same rows; every
    other point alone. The task a dask worker runs.
``store``
    ``sweep.csv``, appended as points finish and read back, and ``sweep.json``.
``run``
    The batches on dask.distributed, and resuming a stopped sweep.
``plot``
    The regime map of two axes, and where rocking ends and runaway begins.
``cli``
    The ``snail sweep`` command.

The public names are importable from here, loaded on first use, so that the
``snail`` command pays for none of them until it runs a sweep.
"""

from importlib import import_module

_WHERE = {
    "plot_regime_map": "plot", "save_regime_map": "plot", "slope_limits": "plot",
    "REGIMES": "point", "classify_point": "point", "run_point": "point",
    "SweepResult": "run", "run_sweep": "run",
    "Axis": "spec", "Sweep": "spec", "SweepError": "spec", "load_sweep": "spec", "overrides": "spec",
    "parse_sweep": "spec", "point_key": "spec",
    "CSV_NAME": "store", "MANIFEST_NAME": "store", "NUMBERS": "store", "read_rows": "store",
}

__all__ = sorted(_WHERE)


def __getattr__(name: str):
    if name in _WHERE:
        value = getattr(import_module(f"{__name__}.{_WHERE[name]}"), name)
        globals()[name] = value
        return value
    msg = f"module {__name__!r} has no attribute {name!r}"
    raise AttributeError(msg)
