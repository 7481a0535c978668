"""Write lubrication/inertia_table.py: the first inertial correction of the wall rotations on a grid of nodes.

One steady Navier-Stokes solve per node (:func:`lubrication.navier_stokes.build_error_table`, finite
elements, Newton), then the table as a Python module of numbers. Rerun after a change to the steady
Navier-Stokes solver, to the table's columns (:data:`lubrication.inertia.TABLE_COLUMNS`) or to its nodes
below; then check ``tests/test_navier_stokes.py`` and ``python -m validation.reports.inertia`` (which compares
the interpolated table with fresh solves off the nodes).

    python generators/inertia_table.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # run as a script from a checkout
    sys.path.insert(0, str(ROOT))

#: Nodes of :mod:`lubrication.inertia_table`: dense near contact, where the
#: normalised coefficients change fastest, and across the gaps of interest.
TABLE_KAPPAS = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 0.999)
TABLE_DELTAS = (0.01, 0.03, 0.1, 0.2, 0.3, 0.40625, 0.6, 1.0)  # 0.40625 = 0.325/0.8: the apparatus of Table 2
TABLE_MODULE = ROOT / "lubrication" / "inertia_table.py"


def _format_array(values: np.ndarray) -> str:
    return np.array2string(np.asarray(values), separator=", ", precision=17, floatmode="unique",
                           threshold=100000, max_line_width=100)


def build_table(path: str | Path = TABLE_MODULE) -> Path:
    """Solve the first inertial correction on the table's nodes and write the table module."""
    from lubrication.inertia import TABLE_COLUMNS
    from lubrication.navier_stokes import build_error_table
    from numerics.files import write_text

    table = build_error_table(TABLE_KAPPAS, TABLE_DELTAS)
    text = f'''"""Tabulated first inertial correction of the wall rotations (generated; do not edit).

Written by ``python generators/inertia_table.py`` (generators/README.md): one
:func:`lubrication.navier_stokes.first_inertial_correction` per node, on the
default mesh (:func:`lubrication.stokes.default_mesh`; coefficient error about
1e-4, measured against the exact small-kappa solution). Columns:
:data:`lubrication.inertia.TABLE_COLUMNS`. Used by
:func:`lubrication.inertia.inertial_error_estimate` with bilinear
interpolation in (kappa, delta/a); its measured accuracy against fresh solves
off the nodes is in ``docs/inertia/inertia.md``. Outside the nodes the
normalised columns are held at the nearest edge (kappa > {TABLE_KAPPAS[-1]},
delta/a < {TABLE_DELTAS[0]} or > {TABLE_DELTAS[-1]}).
"""

import numpy as np

KAPPA_NODES = np.array({_format_array(np.array(TABLE_KAPPAS))})
DELTA_NODES = np.array({_format_array(np.array(TABLE_DELTAS))})
#: shape (len(KAPPA_NODES), len(DELTA_NODES), {len(TABLE_COLUMNS)})
TABLE = np.array({_format_array(table)})
'''
    return write_text(path, text)


if __name__ == "__main__":
    print(f"wrote {build_table()}")
