r"""
Cavitation: a film that ruptures holds the inner cylinder up (section 7)
========================================================================

A full film cannot lift the inner cylinder: the pressure of a rotating film is
antisymmetric about the line of centres, so its force is all f_chi and none
f_eps, and the cylinder sinks until it nearly touches. A liquid cannot sustain
pressures far below its cavitation pressure p_cav; where the full film would,
it ruptures (:mod:`lubrication.cavitation`): half-Sommerfeld truncation
(p = max(p, p_cav)), the Swift-Stieber (Reynolds) conditions, or the
mass-conserving Jakobsson-Floberg-Olsson model. The pressure p_ref holds at the
widest gap, where the experiment's trapped bubble sits; what matters is the
margin p_ref - p_cav.

First the pressure around the gap of the apparatus at kappa = 0.9, both
cylinders turning at 1 rad/s, with a margin of 3 Pa.
"""

import matplotlib.pyplot as plt
import numpy as np

from dynamics import Initial, Limits, preset
from dynamics.simulation import simulate
from lubrication import Annulus, Fluid, Motion
from lubrication.cavitation import cavitating_pressure
from lubrication.registry import kernel_model

p_ref = 101325.0  # Pa, at the widest gap
margin = 3.0  # Pa: p_ref - p_cav
annulus = Annulus.from_kappa(0.008, 0.01125, 0.9, length=0.1035)
fluid = Fluid(nu=2e-4, rho=1000.0)
motion = Motion(omega_a=1.0, omega_b=1.0)

fig, ax = plt.subplots(figsize=(8, 4), layout="constrained")
for model in ("none", "half-sommerfeld", "swift-stieber", "jfo"):
    film = cavitating_pressure(annulus, motion, fluid, model, p_cav=p_ref - margin, p_ref=p_ref)
    theta = np.angle(np.exp(1j * film.theta))  # in (-pi, pi]: the narrowest gap in the middle
    order = np.argsort(theta)
    ax.plot(np.degrees(theta[order]), film.p[order] - p_ref, label=model, lw=1.0)
    print(f"{model:>16}: f_eps = {film.forces.f_eps:+.4f} N, f_chi = {film.forces.f_chi:+.4f} N")
ax.axhline(-margin, color="k", ls=":", lw=0.8, label="p_cav")
ax.set_xlabel("theta from the narrowest gap (deg); the widest gap at +-180")
ax.set_ylabel("p - p_ref (Pa)")
ax.legend(fontsize=8)
ax.set_title("kappa = 0.9, Omega_a = Omega_b = 1 rad/s, 200 cSt, the apparatus' gap", fontsize=10)

# %%
# A ruptured film gives a force along the line of centres (f_eps < 0 pushes the
# inner cylinder back towards the centre of the outer one). In trajectories of
# the full equations (2.1)-(2.4) with Reynolds forces, the steel apparatus on
# 2.4 degrees: the full film keeps closing the gap, as 1/t^2; every cavitation
# model, half-Sommerfeld truncation included, settles at a finite gap and a
# steady rolling speed. (The release passes the gap Reynolds limit for a few
# milliseconds: the runs are told to warn there and go on.)
steel = preset("steel", nu=2e-4)
fig2, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 3.8), layout="constrained")
for model in ("none", "half-sommerfeld", "swift-stieber", "jfo"):
    options = {} if model == "none" else {"cavitation": model, "p_cav": p_ref - 100.0, "p_ref": p_ref}
    run = simulate(steel, Initial(kappa=0.5, phi=0.5), 20.0, forces=kernel_model("reynolds", n=64, **options), rtol=1e-6,
                   limits=Limits(on_invalid="warn"))
    c = run.columns
    ax1.loglog(c["t"][1:], c["one_minus_kappa"][1:], label=model)
    ax2.plot(c["t"], c["x_b"] * 1e3, label=model)
    print(f"{model:>16}: 1 - kappa(20 s) = {c['one_minus_kappa'][-1]:.2e}, X_b(20 s) = {c['x_b'][-1] * 1e3:.1f} mm")
ax1.set_xlabel("t (s)")
ax1.set_ylabel("1 - kappa")
ax2.set_xlabel("t (s)")
ax2.set_ylabel("X_b (mm)")
ax2.legend(fontsize=8)
fig2.suptitle("Steel apparatus, 200 cSt, 2.4 degrees, p_ref - p_cav = 100 Pa")
