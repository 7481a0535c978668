r"""
A small regime map: which releases rock and which run away
==========================================================

From rest, the reduced model (2.11) either rocks down towards contact
(figure 2) or runs away (figure 3), depending on the slope group :math:`s` and
on the release. Here a 20 x 12 grid of (:math:`s`, initial :math:`\kappa`) at the
paper's :math:`\Upsilon = \bar\mu = 1`, released straight above the centre, each run
100 :math:`\tau` long and classified by :func:`dynamics.regime.classify`, the
rule ``snail run`` and ``snail sweep`` report. ``snail sweep`` runs the same thing
on dask for thousands of points (:doc:`/sweeps`; the example "A parameter
sweep on dask" does it from Python).
"""

import matplotlib.pyplot as plt
import numpy as np

from dynamics import Initial, ReducedParams
from dynamics.regime import classify
from dynamics.simulation import simulate

slopes = np.linspace(0.05, 1.2, 20)
kappas = np.linspace(0.0, 0.9, 12)
codes = {"rocking": 0, "sedimenting": 0, "runaway": 1}
regime = np.full((kappas.size, slopes.size), np.nan)
for j, s in enumerate(slopes):
    for i, kappa0 in enumerate(kappas):
        run = simulate(ReducedParams(s, 1.0, 1.0), Initial(kappa0, 0.0), 100.0, rtol=1e-6)
        name, _ = classify(run)
        regime[i, j] = codes.get(name, 0.5)

fig, ax = plt.subplots(figsize=(8, 4.2), layout="constrained")
step_s, step_k = slopes[1] - slopes[0], kappas[1] - kappas[0]
ax.imshow(regime, origin="lower", aspect="auto", cmap="coolwarm", vmin=0, vmax=1,
          extent=(slopes[0] - step_s / 2, slopes[-1] + step_s / 2, kappas[0] - step_k / 2, kappas[-1] + step_k / 2))
ax.axvline(1.0, color="k", ls="--", lw=0.8)
ax.text(1.01, 0.85, "s = 1: no rest\npoint at contact", fontsize=8, va="top")
ax.set_xlabel("s, the slope group (2.12)")
ax.set_ylabel("initial kappa")
ax.set_title("Reduced model, Upsilon = mu_ = 1, from rest above the centre: blue rocks, red runs away",
             fontsize=10)
print(f"{int(np.sum(regime == 0))} rocking, {int(np.sum(regime == 1))} runaway, "
      f"{int(np.sum(regime == 0.5))} other, of {regime.size}")
