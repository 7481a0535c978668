"""Rough contact against the paper (:mod:`validation.contact_checks`): figures 7-10 and the paragraph.

:func:`run` is the group of ``snail validate``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from dynamics.apparatus import preset
from dynamics.contact.reduced import ContactParams
from dynamics.contact.steady import compact_steady_rates, steady_speed, steady_state
from dynamics.trajectory import Trajectory
from numerics.files import save_figure

from ..contact_checks import (
    FIGURE7,
    FIGURE7_PSI,
    FIGURE7_T_PLOT,
    FIGURE9_PSI,
    KAPPA_STAR,
    OILS,
    PSI_EXPERIMENT,
    RELEASE,
    SANDPAPER_SLOPE_DEG,
    ZETAS,
    _final,
    _max_or_nan,
    _settled,
    _speed_error,
    _touch,
    compute,
    onset_slope,
)

__all__ = ["figure7", "figure8", "figure9", "figure10", "run", "sandpaper_table"]


# -- tables -------------------------------------------------------------------------

def sandpaper_table(rows: list[dict]) -> str:
    lines = ["| grade | sigma (mm) | kappa* | zeta* | V (6.1), (5.12) (mm/s) | V simulated (mm/s) | phase |",
             "|---|---|---|---|---|---|---|"]
    lines += [f"| {r['grade']} | {1e3 * r['sigma']:g} | {r['kappa_star']:.4f} | "
              f"{r['zeta_star']:.3f} | {1e3 * r['v_compact']:.2f} | {1e3 * r['v']:.2f} | {r['phase']} |"
              for r in rows]
    return "\n".join(lines)


# -- figures ------------------------------------------------------------------------

def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def figure7(path, trajectory: Trajectory, unlimited: Trajectory,
            t_plot: float = FIGURE7_T_PLOT) -> None:
    """Figure 7: the path of A in the (kappa, phi) plane, kappa(t), phi(t), Omega_a(t) and Omega_b(t)."""
    plt = _pyplot()
    c, free = trajectory.columns, unlimited.columns
    shown, free_shown = c["t_tau"] <= t_plot, unlimited.t <= t_plot
    fig = plt.figure(figsize=(10, 6.2))
    grid = fig.add_gridspec(3, 2, width_ratios=(1, 1.4))
    ax = fig.add_subplot(grid[:, 0])
    circle = np.linspace(0.0, 2.0 * math.pi, 300)
    ax.plot(np.sin(circle), np.cos(circle), "k", lw=0.5)
    ax.plot(KAPPA_STAR * np.sin(circle), KAPPA_STAR * np.cos(circle), "k--", lw=0.4, label="kappa = kappa*")
    for kappa, phi, style, label in ((c["kappa"], c["phi"], "-", "rough contact"),
                                     (free["kappa"], free["phi"], ":", "unlimited")):
        ax.plot(kappa * np.sin(phi), kappa * np.cos(phi), style, color="C0", lw=0.8, label=label)
    ax.plot(RELEASE.kappa * math.sin(RELEASE.phi), RELEASE.kappa * math.cos(RELEASE.phi), "o", ms=4, label="release")
    ax.set_aspect("equal")
    ax.set_xlabel("kappa sin(phi)")
    ax.set_ylabel("kappa cos(phi)  (up)")
    ax.set_title("(a) path of the inner centre", fontsize=9)
    ax.legend(fontsize=7, loc="upper right")
    panels = (("kappa", "(b) kappa"), ("phi", "(c) phi (rad)"), (None, "(d) Omega x tau"))
    first = None
    for row, (name, label) in enumerate(panels):
        ax = fig.add_subplot(grid[row, 1], sharex=first)
        first = first or ax
        if name is None:
            for key, colour in (("omega_a", "C0"), ("omega_b", "C1")):
                ax.plot(c["t_tau"][shown], c[key][shown], color=colour, lw=0.8, label=key.replace("omega", "Omega"))
                ax.plot(unlimited.t[free_shown], free[key][free_shown], ":", color=colour, lw=0.8)
            ax.legend(fontsize=7)
            ax.set_xlabel("t / tau")
        else:
            ax.plot(c["t_tau"][shown], c[name][shown], lw=0.8)
            ax.plot(unlimited.t[free_shown], free[name][free_shown], ":", color="C0", lw=0.8)
        ax.set_ylabel(label, fontsize=9)
    fig.suptitle(f"Figure 7: s = {FIGURE7.s:g}, Upsilon = mu = 1, kappa* = {KAPPA_STAR:g}, psi = {FIGURE7_PSI:g}; "
                 "dotted: unlimited (smooth walls)", fontsize=9)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def figure8(path, runs: dict[float, Trajectory], t_plot: float = 60.0) -> None:
    """Figure 8: kappa, phi, Omega_a, Omega_b for the three psi, offset for clarity, contact dashed."""
    plt = _pyplot()
    names = (("kappa", 0.0), ("phi", 0.5), ("omega_a", 0.15), ("omega_b", 0.15))  # column, offset per run
    fig, axes = plt.subplots(len(names), 1, figsize=(7.5, 8), sharex=True)
    for k, (psi, trajectory) in enumerate(runs.items()):
        c = trajectory.columns
        shown = c["t_tau"] <= t_plot
        for ax, (name, offset) in zip(axes, names):
            ax.plot(c["t_tau"][shown], c[name][shown] + k * offset, color=f"C{k}", lw=0.8,
                    label=f"psi = {psi:g} ({trajectory.info['final_phase']})")
    t_touch, _ = _touch(next(iter(runs.values())))
    for ax, (name, offset) in zip(axes, names):
        ax.axvline(t_touch, color="k", ls="--", lw=0.6)
        ax.set_ylabel(name.replace("omega", "Omega") + (f" (+{offset:g} per run)" if offset else ""), fontsize=8)
    axes[0].legend(fontsize=7)
    axes[-1].set_xlabel("t / tau")
    fig.suptitle(f"Figure 8: s = {FIGURE7.s:g}, Upsilon = mu = 1, kappa* = {KAPPA_STAR:g}; dashed: contact",
                 fontsize=9)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def figure9(path, runs: dict[float, Trajectory]) -> None:
    """Figure 9: Omega_a/(3 zeta*) and Omega_b/(3 zeta*) against s; exact, compact (5.12), simulated."""
    plt = _pyplot()
    zeta = ContactParams(KAPPA_STAR, FIGURE9_PSI).zeta_star
    s_exact = np.linspace(1e-3, KAPPA_STAR - 1e-3, 400)
    exact = np.array([steady_state(s, KAPPA_STAR, FIGURE9_PSI)[2:4] for s in s_exact]) / (3.0 * zeta)
    s_compact = np.linspace(1e-3, 1.0 - 1e-3, 400)
    compact = np.array([compact_steady_rates(s, KAPPA_STAR, FIGURE9_PSI) for s in s_compact]) / (3.0 * zeta)
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for j, (name, colour) in enumerate((("Omega_a", "C0"), ("Omega_b", "C1"))):
        ax.plot(s_exact, exact[:, j], color=colour, lw=1.0, label=f"{name}, fixed point (5.10)/(5.11)")
        ax.plot(s_compact, compact[:, j], "--", color=colour, lw=0.8, label=f"{name}, compact (5.12)")
        settled = [(s, _final(tr)[1 + j]) for s, tr in runs.items() if _settled(tr)]
        ax.plot([p[0] for p in settled], [p[1] / (3.0 * zeta) for p in settled], "o", color=colour, ms=4,
                mfc="none", label=f"{name}, simulated")
    away = [s for s, tr in runs.items() if not _settled(tr)]
    if away:
        ax.plot(away, np.zeros(len(away)), "kx", ms=5, label="runs away from the release")
    ax.axvline(onset_slope(FIGURE9_PSI), color="k", ls=":", lw=0.8, label="onset of sliding (6.4)")
    ax.set_xlabel("s")
    ax.set_ylabel("Omega / (3 zeta*)")
    ax.set_title(f"Figure 9: psi = {FIGURE9_PSI:g} rad, kappa* = {KAPPA_STAR:g}, Upsilon = mu = 1", fontsize=9)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    save_figure(path, fig, dpi=120)
    plt.close(fig)


def figure10(path, rows: list[dict]) -> None:
    """Figure 10: (a) the speeds against the slope, (b) V/V* against sin(alpha) with the lines of (6.1)."""
    plt = _pyplot()
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.6))
    markers = dict(zip(OILS, "osD^"))
    colours = {"steel": "C0", "aluminium": "C3"}
    for r in rows:
        if not r["settled"]:
            continue
        style = dict(marker=markers[r["nu"]], color=colours[r["material"]], ms=4, ls="none",
                     mfc="none" if r["zeta_star"] < max(ZETAS) else colours[r["material"]])
        ax_a.semilogy(r["alpha_deg"], 1e3 * r["v"], **style)
        ax_b.plot(r["sin_alpha"], r["v"] / r["v_star"], **style)
    sin_alpha = np.linspace(math.sin(math.radians(0.5)), math.sin(math.radians(5.8)), 200)
    for material, colour in colours.items():
        apparatus = preset(material)
        s_per_sin = apparatus.s / math.sin(apparatus.alpha)  # s is proportional to sin(alpha) (2.12)
        for zeta, style in zip(ZETAS, (":", "-")):
            kappa_star = math.sqrt(1.0 - zeta**2)
            line = [steady_speed(1.0, math.asin(x), s_per_sin * x, kappa_star, PSI_EXPERIMENT) for x in sin_alpha]
            ax_b.plot(sin_alpha, line, style, color=colour, lw=0.8,
                      label=f"{material}, (6.1) zeta* = {zeta:g}")
    for nu, marker in markers.items():
        ax_a.plot([], [], marker, color="grey", ls="none", label=f"nu = {nu:g} m^2/s")
    ax_a.plot([], [], "o", color="grey", mfc="none", ls="none", label=f"open: zeta* = {min(ZETAS):g}")
    ax_a.set_xlabel("slope alpha (degrees)")
    ax_a.set_ylabel("V = b Omega_b (mm/s)")
    ax_a.set_title("(a) simulated steady speeds", fontsize=9)
    ax_a.legend(fontsize=7)
    ax_b.set_xlabel("sin(alpha)")
    ax_b.set_ylabel("V / V*")
    ax_b.set_title(f"(b) scaled by V* (6.2); psi = {PSI_EXPERIMENT:.3g} rad (steel slides above 3 degrees)",
                   fontsize=9)
    ax_b.legend(fontsize=7)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


# -- the group ----------------------------------------------------------------------

def run(outdir, quick: bool = False):
    """All rough-contact checks; returns (checks, figure file names, a markdown paragraph)."""
    outdir = Path(outdir)
    r = compute(quick)
    figures = []
    if not quick:
        for name, draw, data in (("contact_figure7.png", figure7, (r["fig7"], r["unlimited"])),
                                 ("contact_figure8.png", figure8, (r["fig8"],)),
                                 ("contact_figure9.png", figure9, (r["fig9"],)),
                                 ("contact_figure10.png", figure10, (r["fig10"],))):
            draw(outdir / name, *data)
            figures.append(name)
    return r["checks"], figures, _paragraph(r["fig8"], r["t_touch"], r["fig9"], r["s_onset"], r["fig10"],
                                            r["sandpaper"])


def _paragraph(fig8, t_touch, fig9, s_onset, fig10, sandpaper) -> str:
    """The group's summary, every number in it measured by this run."""
    steady = steady_state(FIGURE7.s, KAPPA_STAR, FIGURE7_PSI)
    outcomes = ", ".join(f"psi = {psi:g} {tr.info['final_phase']}" for psi, tr in fig8.items())
    zeta9 = ContactParams(KAPPA_STAR, FIGURE9_PSI).zeta_star
    compact9 = _max_or_nan(
        max(abs(np.subtract(compact_steady_rates(s, KAPPA_STAR, FIGURE9_PSI),
                            steady_state(s, KAPPA_STAR, FIGURE9_PSI)[2:4]))) / (3.0 * zeta9 * s)
        for s, tr in fig9.items() if _settled(tr))
    away9 = [s for s, tr in fig9.items() if not _settled(tr)]
    settled10 = [r for r in fig10 if r["settled"]]
    worst = max(settled10, key=lambda r: abs(r["v"] / r["v_compact"] - 1.0))
    rates = [r["settling_rate"] for r in settled10]
    text = (
        f"Figure 7 (s = 1/4, Upsilon = mu = 1, kappa* = {KAPPA_STAR:g}, psi = {FIGURE7_PSI:g}): released at rest "
        f"from (kappa, phi) = ({RELEASE.kappa:g}, {RELEASE.phi:g}), the inner cylinder touches at t = "
        f"{t_touch:.4g} tau on the unlimited solution and settles on the sliding fixed point Omega_a = "
        f"{steady.omega_a:.5g}, Omega_b = {steady.omega_b:.5g} (1/tau) of (5.11) as corrected (erratum 6; the "
        f"printed form is not a fixed point). Figure 8 ends {outcomes}; on locking Omega_a jumps to Omega_b. "
        f"Figure 9 (psi = {FIGURE9_PSI:g}): the simulated steady rates lie on the exact fixed points and switch "
        f"from locked to sliding at s_c = {s_onset:.4f} (the exact locking test), against "
        f"{onset_slope(FIGURE9_PSI):.4f} from (6.4); the compact (5.12) is off by up to {compact9:.1%} of "
        f"3 zeta* s at zeta* = {zeta9:.3f}."
    )
    if away9:
        text += (f" From this release the runs with s >= {min(away9):g} swing over and run away (section 3.3): "
                 "their fixed point exists but the release is outside its basin.")
    text += (
        f" Figure 10(b): {len(settled10)} of {len(fig10)} dimensional runs (steel and aluminium, nu = "
        f"{', '.join(f'{nu:g}' for nu in sorted({r['nu'] for r in fig10}))} m^2/s, slopes "
        f"{min(r['alpha_deg'] for r in fig10):g}-{max(r['alpha_deg'] for r in fig10):g} degrees, zeta* = "
        f"{', '.join(f'{z:g}' for z in sorted({round(r['zeta_star'], 3) for r in fig10}))}, psi = "
        f"{PSI_EXPERIMENT:.4f} rad) settle, with b Omega_b equal to (6.1) to "
        f"{_max_or_nan(map(_speed_error, settled10)):.1e} and V/V* the same for every oil; (6.1) with the compact "
        f"(5.12) differs from the exact speed by up to {abs(worst['v'] / worst['v_compact'] - 1.0):.1%} (zeta* = "
        f"{worst['zeta_star']:g}). Their slowest modes decay at {min(rates, default=math.nan):.3g} to "
        f"{_max_or_nan(rates):.3g} per tau."
    )
    away10 = {}
    for r in fig10:
        if not r["settled"]:
            away10.setdefault((r["material"], r["alpha_deg"], r["zeta_star"]), []).append(r["nu"])
    if away10:
        text += " Runs that run away instead (the aluminium cylinder did at 5 degrees, figure 6): " + "; ".join(
            f"{m} at {a:.3g} degrees, zeta* = {z:g}, nu = {', '.join(f'{nu:g}' for nu in nus)}"
            for (m, a, z), nus in away10.items()) + "."
    ratio = [r["v"] / r["v_compact"] for r in sandpaper]
    text += (
        f"\n\nTable 3's roughness on the steel cylinder in 500 cSt oil at {SANDPAPER_SLOPE_DEG:g} degrees "
        f"(V* = {sandpaper[0]['v_star']:.3g} m/s, s = {sandpaper[0]['s']:.3f}), kappa* = 1 - sigma/delta (6.3): "
        f"the simulated speed is the exact fixed point's, which the compact (6.1) used to collapse figure 11 "
        f"underestimates by a factor {min(ratio):.3f}-{max(ratio):.3f} as zeta* grows (locked: "
        f"(2 + kappa*^2)/(3 kappa*^2)).\n\n" + sandpaper_table(sandpaper)
    )
    return text
