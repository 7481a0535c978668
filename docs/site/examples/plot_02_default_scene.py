r"""
A trajectory of the full equations: the default scene
=====================================================

``snail run`` with no scene runs the embedded default: the paper's steel
apparatus (Table 2) in 200 cSt oil on a 2.4 degree slope, released from rest
half-way to contact (kappa = 0.5) above the centre, integrated for 10 s with the
full equations (2.1)-(2.4) and the closed-form forces (2.5)-(2.7).

The same run from Python: load the scene, run it, and draw the figure
``snail run`` writes as ``trajectory.png``.
"""

from dynamics import load_scene, run_scene
from dynamics.app.figures import trajectory_figure
from dynamics.app.output import summary

scene = load_scene()  # the embedded default; load_scene("my_scene.toml") reads a file
trajectory = run_scene(scene)
print(f"{trajectory.status}: {trajectory.message}")
print(f"{trajectory.steps} steps in {trajectory.wall_time_s:.2f} s; tau = {trajectory.tau:.4f} s")

fig = trajectory_figure(trajectory)

# %%
# What ``summary.json`` says about it: the regime the run settled into, and the
# numbers that decided it. With smooth walls the inner cylinder rocks down
# towards contact and the gap keeps closing (as 1/t^2, (3.9)), ever more slowly.
info = summary(trajectory)
for key in ("regime", "mean_speed", "status", "reason"):  # the mean speed down the slope in m/s
    value = info[key]
    print(f"{key:>12}: {value:.4g}" if isinstance(value, float) else f"{key:>12}: {value}")
print("groups:", {k: round(v, 4) for k, v in trajectory.groups.items()})

# %%
# The same run without a scene file, in the Python API (SI units throughout):
from dynamics import Initial, preset
from dynamics.simulation import simulate

steel = preset("steel", nu=2e-4)  # Table 2's device; the preset already has 2.4 degrees
same = simulate(steel, Initial(kappa=0.5, phi=0.5), t_end=10.0, forces="closed-form",
                limits=scene.run.limits)  # the scene's: past the release's Re* = 8, with a warning
print(f"X_b(10 s) = {same.columns['x_b'][-1] * 1e3:.3f} mm (scene: {trajectory.columns['x_b'][-1] * 1e3:.3f} mm), "
      f"1 - kappa = {same.columns['one_minus_kappa'][-1]:.3e}")

# %%
# Every run also estimates how far its quasi-steady Stokes forces can be trusted
# (see :doc:`/equations_of_motion`): the release swings the inner cylinder past the
# centre fast enough for the reduced gap Reynolds number Re* to pass the limit at
# which a run stops by default (the scene says ``on_invalid = "warn"``). The report
# holds numbers (times in s, the others dimensionless) and one sentence,
# ``force_error_scale``, which says what the force errors are relative to.
for key, value in trajectory.info["inertia"].items():
    shown = f"{value:.3g}" if isinstance(value, int | float) else value
    print(f"{key:>45}: {shown}")
