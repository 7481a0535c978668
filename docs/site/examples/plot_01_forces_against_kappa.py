r"""
Fluid forces against eccentricity, every model
==============================================

A full film exerts on the inner cylinder a force and a torque linear in the
velocities: five resistance coefficients fix them (f_eps per eps', and f_chi and
T_a per W_a = Omega_a - chi' and per W_b = Omega_b - chi';
:class:`lubrication.geometry.Resistance`). Here each coefficient of every model
is divided by the lubrication closed form (2.5)-(2.7), at the gap of the paper's
apparatus, delta/a = 0.40625, for kappa from 0 to 0.99:

* the Reynolds solver on the thin gap (B1) reproduces the closed forms to rounding;
* the Reynolds solver on the exact eccentric gap takes part of the finite-gap correction;
* the exact 2-D Stokes solution (``"stokes-exact"``) is the whole of it;
* finite elements (``"stokes"``, the ``fem`` extra) check it at two eccentricities;
* open ends (``ends="open"``): the closed forms times the finite-length factors
  of the 10.35 cm annulus, which lower the squeeze and the rotation forces.
"""

import matplotlib.pyplot as plt
import numpy as np

from lubrication import Annulus, Fluid, resistance
from lubrication.geometry import RESISTANCE_NAMES
from lubrication.stokes import stokes_resistance

a, b, length = 0.008, 0.01125, 0.1035  # m: Table 2 of the paper
fluid = Fluid(nu=2e-4, rho=1000.0)  # 200 cSt
kappas = np.linspace(0.02, 0.99, 60)  # f_chi vanishes at kappa = 0: its ratio is a limit there

models = {
    "Reynolds, thin gap (N = 16)": lambda an: resistance(an, fluid, "reynolds", n=16).as_tuple(),
    "Reynolds, exact gap (N = 64)": lambda an: resistance(an, fluid, "reynolds", n=64,
                                                           profile="eccentric").as_tuple(),
    "exact 2-D Stokes": lambda an: resistance(an, fluid, "stokes-exact").as_tuple(),
    # the gap opens into end regions: the closed forms times the finite-length factors of L/a = 12.9
    "closed forms, open ends": lambda an: resistance(an, fluid, "closed-form", ends="open").as_tuple(),
}
ratios = {name: np.empty((kappas.size, 5)) for name in models}
for i, kappa in enumerate(kappas):
    annulus = Annulus.from_kappa(a, b, kappa, length=length)
    lubrication = np.array(resistance(annulus, fluid, "closed-form").as_tuple())
    for name, model in models.items():
        ratios[name][i] = np.array(model(annulus)) / lubrication

# %%
# Finite elements are too slow for a curve (about a second a geometry): two points.
# ``resistance(annulus, fluid, "stokes")`` would mesh and factorise the geometry once
# for each of its three unit motions; :func:`~lubrication.stokes.stokes_resistance`
# solves the three with one factorisation, per unit length.
fem_kappas = [0.3, 0.9]
fem = []
for kappa in fem_kappas:
    annulus = Annulus.from_kappa(a, b, kappa, length=length)
    solved = stokes_resistance(a, b, kappa, mu=fluid.mu)
    per_length = np.array([getattr(solved, name) for name in RESISTANCE_NAMES])
    fem.append(per_length * length / np.array(resistance(annulus, fluid, "closed-form").as_tuple()))
fem = np.array(fem)

titles = {"f_eps_per_eps_dot": "f_eps per eps'  (2.5)", "f_chi_per_w_a": "f_chi per W_a  (2.6)",
          "t_a_per_w_a": "T_a per W_a  (2.7)", "f_chi_per_w_b": "f_chi per W_b  (2.6)",
          "t_a_per_w_b": "T_a per W_b  (2.7)"}
fig, axes = plt.subplots(2, 3, figsize=(11, 6.5), sharex=True, layout="constrained")
for j, (name, ax) in enumerate(zip(RESISTANCE_NAMES, axes.flat)):
    for label, values in ratios.items():
        ax.plot(kappas, values[:, j], label=label)
    ax.plot(fem_kappas, fem[:, j], "k+", ms=10, mew=1.5, label="finite elements")
    ax.axhline(1.0, color="0.6", lw=0.6)
    ax.set_title(titles[name], fontsize=10)
for ax in axes[1]:
    ax.set_xlabel("kappa = eps / delta")
axes[0, 0].set_ylabel("ratio to the closed form")
axes[1, 0].set_ylabel("ratio to the closed form")
handles, labels = axes[0, 0].get_legend_handles_labels()
axes[1, 2].axis("off")
axes[1, 2].legend(handles, labels, loc="center", fontsize=9)
fig.suptitle("Resistance coefficients at delta/a = 0.406 (the paper's apparatus), over (2.5)-(2.7)")

# %%
# The thin-gap Reynolds solver lies on 1: it is the closed forms, computed.
# At contact the exact ratios tend to powers of b/a = 1.406 (3/2, 1/2, 1/2, 5/2, 3/2):
print("exact / closed form at kappa = 0.99:", np.round(ratios["exact 2-D Stokes"][-1], 4))
print("(b/a)^p:                            ", np.round((b / a) ** np.array([1.5, 0.5, 0.5, 2.5, 1.5]), 4))
print("finite elements / exact at kappa = 0.3, 0.9:")
for kappa, row in zip(fem_kappas, fem):
    annulus = Annulus.from_kappa(a, b, kappa, length=length)
    exact = np.array(resistance(annulus, fluid, "stokes-exact").as_tuple())
    lubrication = np.array(resistance(annulus, fluid, "closed-form").as_tuple())
    print(f"  kappa = {kappa}: largest relative difference {np.max(np.abs(row * lubrication / exact - 1)):.1e}")
