"""Write lubrication/spin_table.py: the angular momentum that the walls' rotations give the fluid, on nodes.

One Stokes solve per wall and node (:func:`lubrication.stokes.fluid_angular_momentum`, finite elements on
the default mesh), as the share lambda of the concentric Couette flow's, and the table of
mu = (1 - lambda)/kappa^2 (finite at kappa = 0, where lambda = 1 - mu kappa^2 + O(kappa^4), by
Richardson extrapolation from kappa = 0.02 and 0.04) with its derivative in kappa at the nodes (monotone
cubic, :class:`scipy.interpolate.PchipInterpolator`). Rerun after a change to the Stokes solver or to the
nodes (those of the inertia table, generators/inertia_table.py); then check tests/test_fluid_spin.py.

    python generators/spin_table.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # run as a script from a checkout
    sys.path.insert(0, str(ROOT))

from generators.inertia_table import TABLE_DELTAS, TABLE_KAPPAS, _format_array  # noqa: E402

TABLE_MODULE = ROOT / "lubrication" / "spin_table.py"
#: kappa of the two solves from which mu(0) is extrapolated
SMALL_KAPPA = 0.02


def couette_shares(kappa: float, delta_over_a: float) -> tuple[float, float]:
    """lambda_a, lambda_b: the angular momentum of each wall's rotation relative to the line of centres over
    the concentric Couette flow's, m_f a^2 W_a / 2 and m_f b^2 W_b / 2."""
    from lubrication.geometry import Annulus, Fluid, Motion
    from lubrication.stokes import fluid_angular_momentum

    a, b = 1.0, 1.0 + delta_over_a
    annulus, fluid = Annulus(a=a, b=b, eps=kappa * delta_over_a, length=1.0), Fluid(rho=1.0, nu=1.0)
    m_f = np.pi * (b * b - a * a)
    inner = fluid_angular_momentum(annulus, Motion(0.0, 0.0, 1.0, 0.0), fluid) / (0.5 * m_f * a * a)
    outer = fluid_angular_momentum(annulus, Motion(0.0, 0.0, 0.0, 1.0), fluid) / (0.5 * m_f * b * b)
    return inner, outer


def build_table(path: str | Path = TABLE_MODULE) -> Path:
    from scipy.interpolate import PchipInterpolator

    from numerics.files import write_text

    kappas = np.array(TABLE_KAPPAS)
    mu = np.empty((kappas.size, len(TABLE_DELTAS), 2))
    for j, d in enumerate(TABLE_DELTAS):
        for i, kappa in enumerate(kappas):
            if kappa == 0.0:
                near = [(1.0 - np.array(couette_shares(k, d))) / k**2 for k in (SMALL_KAPPA, 2 * SMALL_KAPPA)]
                mu[i, j] = (4.0 * near[0] - near[1]) / 3.0
            else:
                mu[i, j] = (1.0 - np.array(couette_shares(kappa, d))) / kappa**2
        print(f"delta/a = {d}: mu_a {mu[:, j, 0].round(4)}, mu_b {mu[:, j, 1].round(4)}", flush=True)
    slope = PchipInterpolator(kappas, mu, axis=0).derivative()(kappas)
    text = f'''"""The fluid's angular momentum from the walls' rotations, as shares of Couette flow's (generated; do not edit).

Written by ``python generators/spin_table.py`` (generators/README.md) from
:func:`lubrication.stokes.fluid_angular_momentum`: for wall w (a, b) turning at W relative to the line of
centres, lambda_w = 1 - mu_w kappa^2 of m_f r_w^2 W / 2. ``MU[i, j]`` is (mu_a, mu_b) at KAPPA_NODES[i],
DELTA_NODES[j]; ``SLOPE`` its derivative in kappa (monotone cubic). Used by
:func:`lubrication.angular_momentum.spin_shares`; beyond the nodes the columns are held at the nearest edge.
"""

import numpy as np

KAPPA_NODES = np.array({_format_array(kappas)})
DELTA_NODES = np.array({_format_array(np.array(TABLE_DELTAS))})
#: shape (len(KAPPA_NODES), len(DELTA_NODES), 2)
MU = np.array({_format_array(mu)})
SLOPE = np.array({_format_array(slope)})
'''
    return write_text(Path(path), text)


if __name__ == "__main__":
    print(build_table())
