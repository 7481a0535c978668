r"""
How far quasi-steady Stokes flow can be trusted: the inertial error estimate
============================================================================

Every force model solves quasi-steady Stokes flow. In the frame of the line of
centres the centrifugal and Coriolis forces of a plane flow only shift the
pressure, so what inertia changes depends on the flow relative to that frame,
through the reduced gap Reynolds number

.. math::

    \mathrm{Re}^* = \max(|W_a|\,a, |W_b|\,b)\,\frac{\delta^2}{\nu a}, \qquad W = \Omega - \dot\chi.

To first order the error of the force is :math:`G(\kappa, \text{motion})\,\mathrm{Re}^*`
times the Stokes force of the two walls' rotations, :math:`|R_{\chi a} W_a| + |R_{\chi b} W_b|`
(a scale that does not cancel), a force along the line of centres; :math:`G` was
measured with steady Navier-Stokes solves (:mod:`lubrication.navier_stokes`) and is
tabulated (:func:`lubrication.inertia.inertial_error_estimate`). :math:`G \le 0.0995`
for every gap and motion, so :math:`\mathrm{Re}^* = 0.1` bounds the error by about 1%
and :math:`\mathrm{Re}^* = 1` by 10%: runs stop at :math:`\mathrm{Re}^* = 1` by default
(``Limits.max_gap_reynolds``) unless told to go on (``on_invalid = "warn"``), and
report their estimates (:doc:`/equations_of_motion`).
"""

import matplotlib.pyplot as plt
import numpy as np

from dynamics import Initial, Limits, preset
from dynamics.simulation import simulate
from lubrication.inertia import inertial_error_estimate

kappas = np.linspace(0.0, 0.99, 100)
motions = {"inner wall turns": (1.0, 0.0), "outer wall turns": (0.0, 1.0), "both, one speed": (1.0, 1.0)}
fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), sharey=True, layout="constrained")
for ax, delta_over_a in zip(axes, (0.01, 0.1, 0.40625)):
    for label, (u_a, u_b) in motions.items():
        # G: the error per unit Re*, with relative wall Reynolds numbers U delta / nu = U / delta_over_a per Re*
        g = [inertial_error_estimate(k, delta_over_a, u_a / delta_over_a, u_b / delta_over_a) for k in kappas]
        ax.plot(kappas, g, label=label)
    ax.set_title(f"delta/a = {delta_over_a:g}", fontsize=10)
    ax.set_xlabel("kappa")
axes[0].set_ylabel("G = relative force error / Re*")
axes[0].legend(fontsize=8)
fig.suptitle("First-order inertial error of the Stokes force, per unit reduced Reynolds number")

# %%
# Along a run: the paper's steel apparatus released from rest (the default
# scene). The inner cylinder swings past the outer one's centre within the first
# fraction of a second, fast enough for Re* to reach about 8, far beyond the 10%
# mark where a run stops by default; this one goes on past it ("warn") to show the
# whole release. Then the rocking is slow and the estimate small.
steel = preset("steel", nu=2e-4)
run = simulate(steel, Initial(kappa=0.5, phi=0.5), t_end=10.0, limits=Limits(on_invalid="warn"))
c = run.columns
w_a, w_b = c["omega_a"] - c["phi_dot"], c["omega_b"] - c["phi_dot"]
per = steel.delta / steel.nu
re_star = np.maximum(np.abs(w_a) * steel.a, np.abs(w_b) * steel.b) * per * steel.delta_over_a
error = [inertial_error_estimate(min(k, 1 - 1e-12), steel.delta_over_a, wa * steel.a * per, wb * steel.b * per)
         for k, wa, wb in zip(c["kappa"], w_a, w_b)]

fig2, ax = plt.subplots(figsize=(8, 3.5), layout="constrained")
ax.semilogy(c["t"], np.maximum(re_star, 1e-6), label="Re*")
ax.semilogy(c["t"], np.maximum(error, 1e-8), label="estimated relative force error")
ax.axhline(1.0, color="C3", ls="--", lw=0.8, label="default stop: Re* = 1")
ax.axhline(0.1, color="0.5", ls=":", lw=0.8, label="10% error")
ax.set_xscale("symlog", linthresh=0.1)
ax.set_xlim(0.0, 10.0)
ax.set_xlabel("t (s)")
ax.legend(fontsize=8)
ax.set_title("Steel apparatus, 200 cSt, 2.4 degrees, released from rest", fontsize=10)

# %%
# What the run reports of it (``Trajectory.info["inertia"]``, and ``summary.json``):
report = run.info["inertia"]
print(f"largest Re* {report['max_reduced_reynolds']:.3g} at t = {report['t_at_max_reduced_reynolds']:.3g} s, "
      f"estimated force error there {report['estimated_force_error_at_max_reduced_reynolds']:.0%}")
print(f"largest estimated force error {report['max_estimated_force_error']:.0%} "
      f"at t = {report['t_at_max_estimated_force_error']:.3g} s")
print(f"the errors are relative to {report['force_error_scale']}")
print(f"not covered by the estimate: the squeeze Reynolds number, up to {report['max_squeeze_reynolds']:.3g}, "
      f"and the Stokes number {report['stokes_number']:.3g}")
