"""The public names of the sweeps in one module: the sweep file, running it, its table, its map.

Each lives in the module of its concept (:mod:`dynamics.app.sweeps`); this
module gathers them, so that ``from dynamics.app.sweeps.sweep import run_sweep``
and ``from dynamics.app.sweeps import run_sweep`` both work.
"""

from dynamics.app.sweeps.plot import plot_regime_map, save_regime_map, slope_limits
from dynamics.app.sweeps.point import REGIMES, classify_point, run_point
from dynamics.app.sweeps.run import SweepResult, run_sweep
from dynamics.app.sweeps.spec import Axis, Sweep, SweepError, load_sweep, overrides, parse_sweep, point_key
from dynamics.app.sweeps.store import CSV_NAME, MANIFEST_NAME, NUMBERS, read_rows

__all__ = [
    "CSV_NAME",
    "MANIFEST_NAME",
    "NUMBERS",
    "REGIMES",
    "Axis",
    "Sweep",
    "SweepError",
    "SweepResult",
    "classify_point",
    "load_sweep",
    "overrides",
    "parse_sweep",
    "plot_regime_map",
    "point_key",
    "read_rows",
    "run_point",
    "run_sweep",
    "save_regime_map",
    "slope_limits",
]
