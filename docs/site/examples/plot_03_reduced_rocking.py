r"""
The reduced model rocks towards contact (the paper's figure 2)
==============================================================

The reduced equations (2.11) with the groups of the paper's figure 2,
:math:`\Upsilon = \bar\mu = 1` and :math:`s = 1/4`, released from rest at
:math:`\kappa = 0.5`, :math:`\phi = 0.3` rad (the text does not give the release).
Times are in :math:`\tau` (2.9), rates in :math:`1/\tau`, :math:`X_b` in units of
:math:`b`: a :class:`~dynamics.equations.reduced.ReducedParams` alone is a
dimensionless system.

The inner cylinder falls through the oil and swings about its resting angle
:math:`\phi^* = \pi + \arcsin s` ever more slowly as the film thins. Near contact
the multiple-scale solution (3.9)-(3.10) describes it:
:math:`\zeta = \sqrt{1 - \kappa^2}` decays as
:math:`\zeta_0/(1 + t\,\zeta_0\sqrt{1 - s^2})`, the swing has the angular frequency
:math:`\omega^2 = \sqrt{1 - s^2}/(\Upsilon(\bar\mu + 1/2))`, and its amplitude decays
as :math:`(\zeta/\zeta_0)^q` with :math:`q = 3(1 + 4\bar\mu^2)/(2(1 + 2\bar\mu)^2)`.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from dynamics import Initial, Limits, ReducedParams
from dynamics.equations.special import (
    contact_equilibrium,
    decay_exponent,
    rocking_frequency,
    slow_approach,
)
from dynamics.simulation import simulate

params = ReducedParams(s=0.25, upsilon=1.0, mu_ratio=1.0)
omega = rocking_frequency(params.s, params.upsilon, params.mu_ratio)
run = simulate(params, Initial(kappa=0.5, phi=0.3), t_end=400.0, output_interval=2 * math.pi / omega / 40,
               limits=Limits(gap_floor=1e-6), rtol=1e-9)
print(f"{run.status}: {run.message} ({run.steps} steps, {run.wall_time_s:.2f} s)")

c = run.columns
t = c["t"]
zeta = np.sqrt(c["one_minus_kappa"] * (1.0 + c["kappa"]))
phi_star = contact_equilibrium(params.s)

# %%
# The first 150 tau, as in the paper's figure: the path of the inner centre
# relative to the outer one (kappa sin phi down the slope, kappa cos phi up),
# the eccentricity, the angle and the two spins.
early = t <= 150.0
fig, axes = plt.subplots(2, 2, figsize=(10, 7), layout="constrained")
ax = axes[0, 0]
ax.plot(c["kappa"][early] * np.sin(c["phi"][early]), c["kappa"][early] * np.cos(c["phi"][early]), lw=0.7)
circle = np.linspace(0.0, 2.0 * math.pi, 200)
ax.plot(np.sin(circle), np.cos(circle), "k", lw=0.5)
ax.set_aspect("equal")
ax.set_xlabel("kappa sin(phi)")
ax.set_ylabel("kappa cos(phi)")
ax.set_title("path of the inner centre", fontsize=10)
axes[0, 1].plot(t[early], c["kappa"][early], lw=0.8)
axes[0, 1].set_ylabel("kappa")
axes[1, 0].plot(t[early], c["phi"][early], lw=0.6)
axes[1, 0].axhline(phi_star, color="C3", ls="--", lw=0.8, label="phi* = pi + arcsin(s)")
axes[1, 0].set_ylabel("phi (rad)")
axes[1, 0].legend(fontsize=8)
axes[1, 1].plot(t[early], c["omega_a"][early], lw=0.6, label="Omega_a tau")
axes[1, 1].plot(t[early], c["omega_b"][early], lw=0.6, label="Omega_b tau")
axes[1, 1].set_ylabel("spin x tau")
axes[1, 1].legend(fontsize=8)
for ax in (axes[0, 1], axes[1, 0], axes[1, 1]):
    ax.set_xlabel("t / tau")
fig.suptitle("Reduced model (2.11), Upsilon = mu_ = 1, s = 1/4: rocking towards contact")

# %%
# The approach to contact against (3.9)-(3.10), from t = 100 tau on: the gap,
# the envelope of the swing, and the distance rolled. Averaged over the swing
# the outer cylinder turns at 3 s zeta, kept up by the shear of the closing
# film, so X_b grows as (3 s / sqrt(1 - s^2)) ln t (the text's t^(1 - q)
# belongs to the zero-mean swing).
start = np.searchsorted(t, 100.0)
law = slow_approach(t[start:] - t[start], zeta[start], params.s, params.mu_ratio)
swing = c["phi"] - phi_star
peaks = np.nonzero((np.abs(swing[1:-1]) > np.abs(swing[:-2])) & (np.abs(swing[1:-1]) >= np.abs(swing[2:])))[0] + 1
late_peaks = peaks[t[peaks] >= t[start]]

fig2, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
ax1.loglog(t[1:], zeta[1:], lw=0.8, label="zeta = sqrt(1 - kappa^2)")
ax1.loglog(t[start:], law.zeta, "k--", lw=0.8, label="(3.9)")
ax1.loglog(t[late_peaks], np.abs(swing[late_peaks]), ".", ms=3, color="C1", label="|phi - phi*| at the peaks")
ax1.loglog(t[start:], np.abs(swing[late_peaks[0]]) * law.amplitude, "k:", lw=1.2, zorder=3,
           label=f"(zeta/zeta_100)^q, q = {decay_exponent(params.mu_ratio):.4f}")
ax1.set_xlabel("t / tau")
ax1.legend(fontsize=8)
ax2.semilogx(t[1:], c["x_b"][1:], lw=0.8, label="X_b / b")
ax2.semilogx(t[start:], c["x_b"][start] + law.x_b, "k--", lw=0.8, label="X_b(100) + (3 s/sqrt(1 - s^2)) ln(...)")
ax2.set_xlabel("t / tau")
ax2.legend(fontsize=8)
fig2.suptitle("Approach to contact against the multiple-scale solution (3.9)-(3.10)")

# %%
# The rocking frequency measured from the last peaks against (3.10):
half_periods = np.diff(t[late_peaks][-20:])
print(f"omega measured {math.pi / half_periods.mean():.5f}, (3.10) {omega:.5f}")
