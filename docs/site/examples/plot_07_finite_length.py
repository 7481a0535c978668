r"""
Finite length: what the open ends of the annulus take away
==========================================================

The force models are per unit length of an infinitely long annulus. The
apparatus' inner cylinder is 10.35 cm long (L/a = 12.9), and its gap opens at
both ends into oil-filled end regions, where the gap pressure must fall to the
end pressure. The squeeze force f_eps and the rotation force f_chi are then
smaller than L times the 2-D ones; the torque's Couette part does not feel the
ends (:mod:`lubrication.finite_length`, :doc:`/corrections`).

The factors F = (coefficient of the finite annulus) / (L x coefficient per unit
length) come from the Reynolds equation on (theta, z)
(:mod:`lubrication.reynolds2d`); a Chebyshev table of them serves the
equations of motion (``ends = "open"`` in a scene, or
``kernel_model("closed-form", ends="open", length_over_a=L/a)``). Here the table
is drawn for several lengths, checked against direct (theta, z) solves at the
apparatus' length, and a trajectory of the default scene is run with both ends.
"""

import matplotlib.pyplot as plt
import numpy as np

from dynamics import Initial, Limits, preset
from dynamics.simulation import simulate
from lubrication.finite_length import (
    APPARATUS_LENGTH_OVER_A,
    finite_length_factors,
    small_eccentricity_factor,
    table_factors,
)
from lubrication.registry import kernel_model

kappas = np.linspace(0.0, 0.99, 100)
fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True, layout="constrained")
for length_over_a in (2.0, 5.0, APPARATUS_LENGTH_OVER_A, 50.0):
    factors = [table_factors(k, length_over_a) for k in kappas]
    label = f"L/a = {length_over_a:.3g}" + (" (apparatus)" if length_over_a == APPARATUS_LENGTH_OVER_A else "")
    axes[0].plot(kappas, [f["f_eps_per_eps_dot"] for f in factors], label=label)
    axes[1].plot(kappas, [f["f_chi_per_w_a"] for f in factors], label=label)

# %%
# Direct solves of the (theta, z) Reynolds equation at the apparatus' length
# (thin gap), and the closed form of the small-eccentricity limit,
# 1 - tanh(l/2)/(l/2) with l = L/a:
check = [0.0, 0.3, 0.6, 0.9]
direct = [finite_length_factors(k, APPARATUS_LENGTH_OVER_A) for k in check]
axes[0].plot(check, [d["f_eps_per_eps_dot"] for d in direct], "k+", ms=9, label="(theta, z) solver")
axes[1].plot(check[1:], [d["f_chi_per_w_a"] for d in direct[1:]], "k+", ms=9, label="(theta, z) solver")
for ax in axes:
    ax.plot([0.0], [small_eccentricity_factor(APPARATUS_LENGTH_OVER_A)], "ko", mfc="none",
            label="1 - tanh(l/2)/(l/2)")
    ax.set_xlabel("kappa")
axes[0].set_title("squeeze: f_eps per eps'", fontsize=10)
axes[1].set_title("rotation: f_chi per W_a (and per W_b)", fontsize=10)
axes[0].set_ylabel("finite-length factor F")
axes[1].legend(fontsize=8)
fig.suptitle("Open ends: the resistance of an annulus of length L over L times the 2-D one (thin gap)")
for k, d in zip(check, direct):
    table = table_factors(k, APPARATUS_LENGTH_OVER_A)
    print(f"kappa = {k}: F_eps table {table['f_eps_per_eps_dot']:.6f}, direct {d['f_eps_per_eps_dot']:.6f}")

# %%
# In a trajectory: the default release of the steel apparatus, closed-form
# forces per unit length against the same forces with open ends. The ends
# weaken the squeeze film, so the inner cylinder reaches the wall sooner.
steel = preset("steel", nu=2e-4)
runs = {ends: simulate(steel, Initial(kappa=0.5, phi=0.5), 10.0, limits=Limits(on_invalid="warn"),
                       forces=kernel_model("closed-form", ends=ends, length_over_a=steel.length / steel.a))
        for ends in ("infinite", "open")}
fig2, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 3.8), layout="constrained")
for ends, run in runs.items():
    ax1.loglog(run.columns["t"][1:], run.columns["one_minus_kappa"][1:], label=f"ends = {ends!r}")
    ax2.plot(run.columns["t"], run.columns["x_b"] * 1e3, label=f"ends = {ends!r}")
    print(f"ends = {ends!r}: {run.status}; X_b(10 s) = {run.columns['x_b'][-1] * 1e3:.2f} mm, "
          f"1 - kappa = {run.columns['one_minus_kappa'][-1]:.2e}")
ax1.set_xlabel("t (s)")
ax1.set_ylabel("1 - kappa")
ax2.set_xlabel("t (s)")
ax2.set_ylabel("X_b (mm)")
ax1.legend(fontsize=8)
fig2.suptitle("Steel apparatus, 200 cSt, 2.4 degrees: infinitely long against open ends")
