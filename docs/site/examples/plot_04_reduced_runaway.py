r"""
The reduced model runs away (the paper's figure 3)
==================================================

On a steeper slope, :math:`s = 0.9` (:math:`\Upsilon = \bar\mu = 1`, released from rest
at :math:`\kappa = 0.5`, :math:`\phi = 0.3` rad), the line of centres winds round and
round and the rotation keeps growing: the runaway of section 3.3, in which
:math:`\Omega_a \sim \Omega_b \sim \dot\phi \sim s\,t/((\bar\mu + 1/2)\Upsilon)` (3.11).
A run stops once the outer cylinder has turned ``Limits.max_turns`` times (100 by
default): a runaway has no end of its own.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from dynamics import Initial, ReducedParams
from dynamics.equations.special import runaway_spin_rate
from dynamics.simulation import simulate

params = ReducedParams(s=0.9, upsilon=1.0, mu_ratio=1.0)
run = simulate(params, Initial(kappa=0.5, phi=0.3), t_end=1e4)
print(f"{run.status} (event {run.event!r}): {run.message}")

c = run.columns
t = c["t"]
rate = runaway_spin_rate(params.s, params.upsilon, params.mu_ratio)

fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), layout="constrained")
axes[0].plot(t, c["kappa"], lw=0.6)
axes[0].set_ylabel("kappa")
axes[1].plot(t, c["omega_a"], lw=0.7, label="Omega_a tau")
axes[1].plot(t, c["omega_b"], lw=0.7, label="Omega_b tau")
offset = c["omega_b"][-1] - rate * t[-1]
axes[1].plot(t, rate * t + offset, "k--", lw=0.8, label="slope of (3.11): s / ((mu_ + 1/2) Upsilon)")
axes[1].set_ylabel("spin x tau")
axes[1].legend(fontsize=8)
axes[2].plot(t, c["x_b"], lw=0.8, label="X_b / b")
axes[2].plot(t, 0.5 * rate * t**2, "k--", lw=0.8, label="(3.11) integrated")
axes[2].set_ylabel("X_b / b")
axes[2].legend(fontsize=8)
for ax in axes:
    ax.set_xlabel("t / tau")
fig.suptitle("Reduced model (2.11), Upsilon = mu_ = 1, s = 0.9: runaway")

# %%
# The slopes over the second half of the run, against (3.11). The mean of
# kappa sin(phi) over a turn is O(1/Omega), which adds a slowly growing
# logarithm: the fit includes one.
late = t > 0.5 * t[-1]
basis = np.column_stack([t[late], np.log(t[late]), np.ones(late.sum())])
for name in ("omega_a", "omega_b"):
    slope = np.linalg.lstsq(basis, c[name][late], rcond=None)[0][0]
    print(f"d{name}/dt = {slope:.4f}   (3.11): {rate:.4f}")
print(f"the outer cylinder turned {c['x_b'][-1] / (2 * math.pi):.1f} times in {t[-1]:.1f} tau")
