r"""
A tilt of the inner cylinder along a release
============================================

The default scene's release on smooth walls (steel, 200 cSt, 2.4 degrees), and the
linear tilt equation of :mod:`dynamics.tilt` along it: unit tilts of the inner
cylinder's axis at 0.05 s, in both directions, carried by the film's strips and the
cylinder's inertia. Top: the gap and the angle of the line of centres as the
cylinder rocks towards contact. Bottom: the largest amplification of a unit tilt,
and the largest growth rate of the equation frozen at each instant. Frozen, about
half the instants have a growing mode; carried along the rocking, a tilt decays.
"""

import warnings

import matplotlib.pyplot as plt
import numpy as np

from dynamics import Initial, Limits, ValidityWarning, preset, simulate
from dynamics.tilt import tilt_history

warnings.simplefilter("ignore", ValidityWarning)  # the first swing passes the gap Reynolds limit
steel = preset("steel", nu=2e-4)
release = simulate(steel, Initial(kappa=0.5, phi=0.5), t_end=10.0, limits=Limits(on_invalid="warn"))
tilt = tilt_history(release, steel, t_span=(0.05, 10.0))
print(f"a unit tilt at 0.05 s is {tilt.gain[-1]:.2g} of itself at 10 s; the frozen equation grows at "
      f"{np.mean(tilt.frozen_growth > 0):.0%} of the instants, at up to {tilt.frozen_growth.max():.3g}/s")

fig, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True, layout="constrained")
c = release.columns
axes[0].semilogy(c["t"], c["one_minus_kappa"], lw=0.8, label="1 - kappa")
twin = axes[0].twinx()
twin.plot(c["t"], c["phi"], color="C1", lw=0.8)
twin.set_ylabel("phi (rad)", color="C1")
axes[0].set_ylabel("1 - kappa")
axes[1].semilogy(tilt.t, tilt.gain, lw=1.0, label="largest amplification of a unit tilt")
axes[1].semilogy(tilt.t, np.where(tilt.frozen_growth > 0, tilt.frozen_growth, np.nan), ".", ms=1.5, color="C3",
                 label="frozen growth rate (1/s), where positive")
axes[1].set_xlabel("t (s)")
axes[1].legend(fontsize=8)
fig.suptitle("A tilt of the inner cylinder decays along the release on smooth walls")
