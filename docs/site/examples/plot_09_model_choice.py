r"""
Speed against accuracy, and the automatic choice of model
=========================================================

``benchmarks/accuracy.py`` measures the cost and the error of every way of
getting the forces, against the exact 2-D Stokes solution, for delta/a from
0.003 to 1 (:doc:`/speed_accuracy`). Its results ship
with the package (``dynamics/data/model_choice.json``), and ``forces = "auto"``
and ``equations = "auto"`` choose from them: the cheapest model whose measured
error meets ``model.tolerance`` at the scene's delta/a, over kappa up to 0.99
(:mod:`dynamics.app.auto`). Nothing is recomputed here: this example reads the
stored study.
"""

import matplotlib.pyplot as plt

from dynamics.app.auto import choose_equations, choose_forces, study

data = study()
deltas, kappas = data["deltas"], data["kappas"]
# Colour and label of each family of the study. The exact solution is the reference, its error zero:
# it is drawn at the rounding of double precision. The finite-element costs are whole solves called
# from Python.
ROUNDING = 1e-15
families = {"closed-form": ("C0", "closed forms (2.5)-(2.7)"), "reynolds": ("C1", "Reynolds solver"),
            "stokes-exact": ("C2", "exact Stokes (the reference, at rounding)"),
            "stokes-fem": ("C3", "Stokes finite elements (Python)")}

fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True, layout="constrained")
for ax, delta_over_a in zip(axes, (0.01, 0.40625)):
    row = deltas.index(delta_over_a)
    seen = set()
    for entry in data["forces"]:
        error = max(max(entry["error"][row]), ROUNDING)  # the worst over kappa <= 0.99
        compiled = [t for t in entry["jit_s"][row] if t is not None]
        cost = max(compiled) if compiled else max(entry["python_s"][row])
        family = entry["model"]
        colour, label = families.get(family, ("k", family))
        ax.loglog(cost * 1e6, error, "o", color=colour, ms=5, label=None if family in seen else label)
        seen.add(family)
    ax.set_title(f"delta/a = {delta_over_a:g}", fontsize=10)
    ax.set_xlabel("cost of one force evaluation (us)")
    ax.grid(True, which="major", lw=0.3)
axes[0].set_ylabel("largest relative error of the 5 coefficients")
axes[0].legend(fontsize=8)
fig.suptitle("Force models: error against cost (stored study; Reynolds at N = 8 ... 1024, both grids and profiles)")

# %%
# What ``auto`` picks, with the measured number it rests on:
for delta_over_a in (0.01, 0.40625):
    for tolerance in (0.1, 0.05, 1e-2, 1e-4):
        equations = choose_equations(tolerance, delta_over_a)
        if equations.model == "reduced":  # (2.11) has the closed forms built in
            forces = f"(2.11) alone, measured trajectory error {equations.error:.1e}"
        else:
            choice = choose_forces(tolerance, delta_over_a, max(kappas), trajectory=True)
            forces = f"with {choice.model} forces, measured error {choice.error:.1e}"
        print(f"delta/a = {delta_over_a:<7g} tolerance {tolerance:<6g}: {equations.model} equations {forces}")
print()
print(choose_forces(1e-2, 0.40625, 0.99).reason)
