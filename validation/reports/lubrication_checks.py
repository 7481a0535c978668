"""The Reynolds solver against the closed forms (:mod:`validation.lubrication_checks`): figure and paragraph.

:func:`run` is the group of ``snail validate``.
"""

from __future__ import annotations

from ..lubrication_checks import CONVERGENCE_KAPPAS, checks_of, convergence_errors

__all__ = ["convergence_figure", "run"]


def convergence_figure(path, convergence: dict) -> None:
    """Error of the Reynolds solver against N, both grids, for several kappa (:func:`convergence_errors`)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    ns = convergence["ns"]
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for kappa, colour in zip(CONVERGENCE_KAPPAS, ("C0", "C1", "C2", "C3")):
        for grid, style in (("sommerfeld", "-o"), ("uniform", "--s")):
            err = convergence["errors"][kappa, grid]
            ax.loglog(ns, err, style, color=colour, ms=3, label=f"{grid}, kappa={kappa:g}")
    ax.set_xlabel("cells N (one Gauss point per cell)")
    ax.set_ylabel("max relative error of the resistance coefficients")
    ax.set_title("Reynolds solver against (2.5)-(2.7)")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(True, which="major", alpha=0.3)
    fig.tight_layout()
    save_figure(path, fig, dpi=120)
    plt.close(fig)


def run(outdir, quick: bool = False):
    """All lubrication checks; returns (checks, figure file names, a markdown paragraph)."""
    checks = checks_of()
    figures = []
    if not quick:
        convergence_figure(outdir / "reynolds_convergence.png", convergence_errors())
        figures.append("reynolds_convergence.png")
    text = ("The numerical Reynolds solver on the thin gap (B1) reproduces the five resistance "
            "coefficients of (2.5)-(2.7) to rounding for every kappa up to 1 - 1e-6; the grid "
            "uniform in the Sommerfeld angle keeps that accuracy with a few dozen cells where a "
            "uniform theta grid needs N ~ 25/acosh(1/kappa).")
    return checks, figures, text
