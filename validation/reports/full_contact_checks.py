"""Rough contact in the full model (:mod:`validation.full_contact_checks`): the figure and the paragraph.

:func:`run` is the group of ``snail validate``.
"""

from __future__ import annotations

from pathlib import Path

from numerics.files import save_figure

from ..contact_checks import KAPPA_STAR, SANDPAPER_SLOPE_DEG
from ..full_contact_checks import BRANCHES, MU_RATIO, RATIOS, STICK_SLIP_PSI, S, compute

__all__ = ["run"]


def _figure(path: Path, runs: dict, reduced_runs: dict) -> None:
    """The full model's releases against the reduced hybrid runs of section 5 (:func:`reduced_releases`)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), sharex=True)
    for ax, (branch, psi) in zip(axes, BRANCHES.items()):
        reduced = reduced_runs[branch]
        r = reduced.columns
        ax.plot(reduced.t, r["omega_b"], "k-", lw=2.5, alpha=0.35, label="reduced (section 5), Omega_b")
        ax.plot(reduced.t, r["omega_a"], "k--", lw=2.5, alpha=0.35, label="reduced, Omega_a")
        for ratio, trajectory in runs[branch].items():
            c = trajectory.columns
            keep = c["t_tau"] <= 60.0
            line, = ax.plot(c["t_tau"][keep], c["omega_b"][keep] * trajectory.tau, lw=1, label=f"full, delta/a = {ratio:g}")
            ax.plot(c["t_tau"][keep], c["omega_a"][keep] * trajectory.tau, "--", lw=1, color=line.get_color())
        ax.set_title(f"psi = {psi:g} ({branch})")
        ax.set_xlabel("t / tau")
    axes[0].set_ylabel("Omega tau")
    axes[0].legend(fontsize=7)
    fig.suptitle(f"Figure 7's release (s = {S:g}, Upsilon = 1, mu_ = {MU_RATIO:g}, kappa* = {KAPPA_STAR:g}): "
                 "full model with contact against section 5", fontsize=9)
    save_figure(path, fig)
    plt.close(fig)


def run(outdir, quick: bool = False):
    """All full-model contact checks; returns (checks, figure file names, a markdown paragraph)."""
    outdir = Path(outdir)
    r = compute(quick)
    figures = []
    if not quick:
        _figure(outdir / "full_contact_release.png", r["runs"], r["reduced"])
        figures.append("full_contact_release.png")
    return r["checks"], figures, _paragraph(r["slopes"], r["runs"], r["stick_slip"], r["phases"], r["once"],
                                            r["speeds"])


def _paragraph(slopes, runs, stick_slip, phases, once, speeds) -> str:
    """The group's summary, every number in it measured by this run."""
    ratios = ", ".join(f"{name} {s:.3f} ({err:.2g} at delta/a = {RATIOS[-1]:g})" for name, (s, err) in slopes.items())
    impact = {branch: runs[branch][RATIOS[0]].info["switches"][0]["t"] / runs[branch][RATIOS[0]].tau
              for branch in runs}
    text = (
        "Contact in the full model is a unilateral constraint at eps* = delta - sigma with Coulomb friction at the "
        "single contact point and a plastic impact (dynamics.contact.full). Its steady rolling states approach "
        f"section 5's (5.6)-(5.11) at first order in delta/a: log-log slopes {ratios}. Figure 7's release at "
        f"delta/a = 0.01 touches at t = {impact['sliding']:.4g} tau and settles on the full model's own fixed point "
        "(figure: the rates against the reduced hybrid run). Just above the onset of sliding (psi = "
        f"{STICK_SLIP_PSI}) the rocking pair switched {len(phases)} times between locked and sliding in "
        f"{stick_slip.steps} steps, against {once.steps} for a run that locks once."
    )
    v_red = speeds["v_reduced"]
    parts = [f"{name} forces {1e3 * speeds[name]['v']:.2f} mm/s ({speeds[name]['v'] / v_red:.3f} of it, "
             f"{speeds[name]['phase']})" for name in ("closed-form", "stokes") if name in speeds]
    text += (f" The steel apparatus (delta/a = {speeds['delta_over_a']:.2f}) in 500 cSt oil at "
             f"{SANDPAPER_SLOPE_DEG:g} degrees with sigma = 50 micrometres: (6.1) with the exact fixed point gives "
             f"{1e3 * v_red:.2f} mm/s ({speeds['phase_reduced']}); the full model with " + "; with ".join(parts) + ".")
    return text
