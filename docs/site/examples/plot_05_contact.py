r"""
Rough contact: sliding and locked rolling (the paper's figures 7 and 8)
=======================================================================

Smooth walls never touch: the film thins for ever (see the rocking example).
Section 5 lets asperities stop the approach at :math:`\kappa = \kappa^*` (here 0.98,
a minimum gap of 2% of :math:`\delta`), with Coulomb friction of scaled angle
:math:`\psi`, :math:`\tan\psi = (a/\delta)\tan\hat\psi`. A run switches exactly, at
events located on the integrator's dense output, between free motion, sliding
contact and locked contact (:math:`\Omega_a = \Omega_b`); :math:`\Omega_a` jumps
when the cylinders lock, as the paper's model says.

The groups are those of figure 2 (:math:`\Upsilon = \bar\mu = 1`, :math:`s = 1/4`,
release at rest from :math:`\kappa = 0.5`, :math:`\phi = 0.3` rad). With
:math:`\psi = 0.05` the cylinders slide for good (figure 7); with :math:`\psi = 0.5`
they lock (figure 8). Each settles on the steady state of (5.6)-(5.11), with
(5.11) as corrected (:doc:`/physics`).
"""

import matplotlib.pyplot as plt

from dynamics import ContactParams, Initial, ReducedParams
from dynamics.contact.steady import steady_state
from dynamics.simulation import simulate

params = ReducedParams(s=0.25, upsilon=1.0, mu_ratio=1.0)
kappa_star = 0.98
runs = {}
for psi in (0.05, 0.5):
    run = simulate(params, Initial(kappa=0.5, phi=0.3), t_end=120.0, contact=ContactParams(kappa_star, psi),
                   output_interval=0.05)
    runs[psi] = run
    switches = ", ".join(f"{sw['from']} -> {sw['to']} at t = {sw['t']:.2f}" for sw in run.info["switches"])
    print(f"psi = {psi}: {run.status}, ends {run.info['final_phase']}; {switches}")

fig, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex=True, layout="constrained")
for column, (psi, run) in enumerate(runs.items()):
    c = run.columns
    steady = steady_state(params.s, kappa_star, psi)
    ax = axes[0, column]
    ax.plot(c["t"], c["omega_a"], lw=0.8, label="Omega_a tau")
    ax.plot(c["t"], c["omega_b"], lw=0.8, label="Omega_b tau")
    ax.axhline(steady.omega_a, color="C0", ls=":", lw=0.8)
    ax.axhline(steady.omega_b, color="C1", ls=":", lw=0.8, label=f"steady {steady.phase} state")
    ax.set_title(f"psi = {psi}: ends {run.info['final_phase']}", fontsize=10)
    ax.legend(fontsize=8)
    ax = axes[1, column]
    ax.plot(c["t"], c["phi"], lw=0.8, label="phi")
    ax.axhline(steady.phi, color="k", ls=":", lw=0.8, label="(5.6): kappa* sin(phi) = -s")
    for switch in run.info["switches"]:
        for row in axes[:, column]:
            row.axvline(switch["t"], color="0.5", lw=0.6)
        ax.annotate(f" {switch['from']} -> {switch['to']}", (switch["t"], ax.get_ylim()[0]), fontsize=8,
                    va="bottom")
    ax.set_xlabel("t / tau")
    ax.legend(fontsize=8, loc="center right")
axes[0, 0].set_ylabel("spin x tau")
axes[1, 0].set_ylabel("phi (rad)")
fig.suptitle("Reduced model with rough contact, kappa* = 0.98, Upsilon = mu_ = 1, s = 1/4")

# %%
# The final rates against the fixed points of section 5:
for psi, run in runs.items():
    steady = steady_state(params.s, kappa_star, psi)
    c = run.columns
    print(f"psi = {psi}: Omega_a = {c['omega_a'][-1]:.6f} (steady {steady.omega_a:.6f}), "
          f"Omega_b = {c['omega_b'][-1]:.6f} (steady {steady.omega_b:.6f})")
