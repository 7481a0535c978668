"""The inertia study (:mod:`validation.inertia`): its figures, its markdown and its files.

Run ``python -m validation.reports.inertia`` to write ``docs/inertia/`` (figures, ``inertia.json``,
``inertia.md``).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..inertia import (
    APPARATUS,
    DELTAS,
    KAPPAS,
    LEVELS,
    OILS,
    RUNAWAY_FIT_START,
    RUNAWAY_MODELS,
    RUNAWAY_SLOPES,
    RUNAWAY_T_END,
    RUNAWAY_TIMES,
    RUNAWAY_WINDOW,
    TABLE_PROBES,
    run,
)

__all__ = ["figure", "runaway_figure", "write_outputs"]


def figure(result: dict, path: str | Path):
    """Four panels: error against Re* and against Re, G(kappa), torque error."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    colours = {d: c for d, c in zip(DELTAS, ("tab:blue", "tab:orange", "tab:green"))}
    markers = {"inner": "o", "outer": "s", "rolling": "^"}
    for row in result["sweeps"]:
        c, m = colours[row["delta_over_a"]], markers[row["motion"]]
        label = f"delta/a={row['delta_over_a']:.3g}, {row['motion']}" if row["kappa"] == KAPPAS[0] else None
        err = np.array(row["force_error"])
        axes[0, 0].loglog(row["reduced_reynolds"], err, m + "-", color=c, ms=3, lw=0.6, label=label)
        axes[0, 1].loglog(row["reynolds"], err, m + "-", color=c, ms=3, lw=0.6)
        if row["motion"] != "rolling":  # the rolling state is torque-free at leading order
            axes[1, 1].loglog(row["reduced_reynolds"], np.maximum(row["torque_error"], 1e-16), m + "-",
                              color=c, ms=3, lw=0.6)
    x = np.logspace(-2, 2, 10)
    axes[0, 0].loglog(x, 0.1 * x, "k--", lw=1, label="0.1 Re* (thin-gap co-rotation, kappa -> 0)")
    for ax in (axes[0, 0], axes[0, 1]):
        for level in LEVELS:
            ax.axhline(level, color="grey", lw=0.5, ls=":")
        ax.set_ylabel("|F - F_Stokes| / |F_Stokes|")
    axes[0, 0].set_xlabel("Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a)")
    axes[0, 1].set_xlabel("Re = max(|W_a| a, |W_b| b) delta / nu")
    axes[0, 0].legend(fontsize=6)
    axes[0, 0].set_title("force error: collapses on Re*", fontsize=9)
    axes[0, 1].set_title("the same against Re: a factor a/delta apart", fontsize=9)
    fo = result["first_order"]
    kap = np.array(fo["kappa"])
    styles = {"inner": "-", "outer": "--", "rolling": "-.", "co-rotating": ":"}
    for j, d in enumerate(fo["delta_over_a"]):
        if not any(abs(d - dd) < 1e-12 for dd in DELTAS):
            continue
        for name, ls in styles.items():
            axes[1, 0].plot(kap, fo[name][j], ls, color=colours[min(DELTAS, key=lambda q: abs(q - d))],
                            label=f"{name}" if j == 0 else None)
    axes[1, 0].plot([0, 0], [1 / 30, 1 / 10], "kx", label="thin gap, kappa -> 0: 1/30, 1/10")
    axes[1, 0].set_xlabel("kappa")
    axes[1, 0].set_ylabel("G = first-order error / Re*")
    axes[1, 0].legend(fontsize=6)
    axes[1, 0].set_title("first inertial correction (a pure f_eps) per Re*; blue, orange, green: "
                         "delta/a = 0.01, 0.1, 0.406", fontsize=8)
    axes[1, 1].set_xlabel("Re*")
    axes[1, 1].set_ylabel("|T_a - T_a,Stokes| / |T_a,Stokes|")
    axes[1, 1].set_title("torque (inner, outer rotation): second order in Re", fontsize=9)
    fig.suptitle("Steady Navier-Stokes against quasi-steady Stokes, eccentric annulus (kappa = 0.3, 0.6, 0.9)",
                 fontsize=10)
    fig.tight_layout()
    save_figure(path, fig, dpi=90)
    plt.close(fig)
    return path


def runaway_figure(result: dict, path: str | Path):
    """The runaways of :func:`runaway_trajectories`: X_b, 1 - kappa, Re* and the estimated error, the forces."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from dynamics.equations.limits import MAX_REYNOLDS
    from numerics.files import save_figure

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    colours = dict(zip(RUNAWAY_SLOPES, ("tab:blue", "tab:orange")))
    styles = {"paper": "-", "quasi-steady": "--", "quasi-steady+inertia": ":"}
    for r in result["runaway_trajectories"]:
        sr, c, ls = r["series"], colours[r["slope_deg"]], styles[r["model"]]
        t = np.array(sr["t"])
        label = f"{r['slope_deg']:g} deg, {r['model']}"
        axes[0, 0].plot(t, sr["x_b"], ls, color=c, lw=1, label=label)
        axes[0, 1].semilogy(t, sr["one_minus_kappa"], ls, color=c, lw=1)
        if r["model"] == "paper":
            axes[1, 0].semilogy(t, sr["reduced_reynolds"], "-", color=c, lw=1, label=f"Re*, {r['slope_deg']:g} deg")
            axes[1, 0].semilogy(t, sr["estimated_force_error"], "--", color=c, lw=1,
                                label=f"estimated force error, {r['slope_deg']:g} deg")
            axes[1, 1].semilogy(t, sr["frame_force_over_weight"], "-", color=c, lw=1,
                                label=f"frame force, {r['slope_deg']:g} deg")
            axes[1, 1].semilogy(t, sr["first_order_force_over_weight"], "--", color=c, lw=1,
                                label=f"first inertial correction, {r['slope_deg']:g} deg")
            axes[0, 0].plot(t, t**2 * r["acceleration_observed_law"] / 2.0, color=c, lw=3, alpha=0.25)
    axes[0, 0].set_ylabel("X_b (m)")
    axes[0, 0].legend(fontsize=6)
    axes[0, 0].set_title("distance rolled; thick: the observed law g t^2 sin(alpha)/3", fontsize=9)
    axes[0, 1].set_ylabel("1 - kappa")
    axes[0, 1].set_title("the gap: pressed shut by the centripetal force", fontsize=9)
    axes[1, 0].axhline(MAX_REYNOLDS, color="grey", lw=0.6, ls=":")
    axes[1, 0].set_ylabel("Re*, estimated relative force error")
    axes[1, 0].legend(fontsize=6)
    axes[1, 0].set_title("relative flow: Re* and the first-order force error ('paper')", fontsize=9)
    axes[1, 1].set_ylabel("force / m'_a g")
    axes[1, 1].legend(fontsize=6)
    axes[1, 1].set_title("frame force (left out as printed) and first inertial correction", fontsize=9)
    for ax in axes.flat:
        ax.set_xlabel("t (s)")
    fig.suptitle("Aluminium runaway (nu = 2e-4 m^2/s, closed forms) followed past the Reynolds limit", fontsize=10)
    fig.tight_layout()
    save_figure(path, fig, dpi=90)
    plt.close(fig)
    return path


def _frame_terms_markdown(result: dict) -> list[str]:
    comp = {c["slope_deg"]: c for c in result["runaway_comparison"]}
    five, ten = comp[RUNAWAY_SLOPES[0]]["frame_terms"], comp[RUNAWAY_SLOPES[1]]["frame_terms"]
    masses = {(r["slope_deg"], r["model"]): r["centripetal_mass"] / (r["m_eff"] if r["frame_terms"] == "paper"
                                                                        else r["m_a_reduced"])
              for r in result["runaway_trajectories"] if r["model"] != "quasi-steady+inertia"}
    worst_mass = max(abs(v - 1.0) for v in masses.values())
    square = comp[RUNAWAY_SLOPES[0]]["m_eff_over_m_reduced_squared"]
    papers = [r for r in result["runaway_trajectories"] if r["model"] == "paper"]
    frame = " and ".join(f"{r['inertia']['max_frame_force_over_weight']:.0f}" for r in papers)
    late_re = max(max(v for t, v in zip(r["series"]["t"], r["series"]["reduced_reynolds"])
                      if t >= RUNAWAY_FIT_START) for r in papers)
    end_re = " and ".join(f"{r['series']['reduced_reynolds'][-1]:.2g}" for r in papers)
    stokes = papers[0]["inertia"]["stokes_number"]
    gaps = [r["series"]["one_minus_kappa"][-1] for r in result["runaway_trajectories"]]
    return ["", "## frame_terms: the force of the fluid turning with the line of centres", "",
            ("`simulate(..., frame_terms=...)` and `[model] frame_terms` choose how the full equations treat it "
             "(dynamics.equations.full.frame_force). **\"paper\"** is (2.1)-(2.2) as printed: m_eff on every "
             "term of r'', the fluid force being quasi-steady Stokes flow in the non-rotating frame of the "
             "fluid's centre of mass. **\"quasi-steady\"** takes the flow as steady in a frame turning at the "
             "rate Omega, where the centrifugal and Coriolis forces of a plane flow only shift the pressure "
             "(sections above); their pressure pushes the inner cylinder with (m_eff - m'_a)(eps Omega (Omega - "
             "2 chi') e_eps + 2 Omega eps' e_chi), which for Omega = chi' puts m'_a instead of m_eff on the "
             "centripetal and Coriolis terms of (2.1)-(2.2)."), "",
            ("The frame rate is chi' clipped to the range of the wall rates [min(Omega_a, Omega_b), "
             "max(Omega_a, Omega_b)], no free constant: every part of the fluid turns at a rate between its "
             "walls', and where chi' leaves that range (A swinging past B while the walls are slow, chi' = "
             "(e_chi . r')/eps -> infinity) the line of centres is no frame the fluid turns with. The clipped "
             "force is chi''s wherever chi' lies between the wall rates (the runaway, the approach to contact), "
             "tends to the Coriolis force 2 (m_eff - m'_a) Omega J r' of a disc crossing a rigidly turning "
             "fluid as eps -> 0 where the chi' form diverges like |r'|^2/eps, and elsewhere differs from the "
             "chi' form by at most (1 + m''_a/m_f)(delta/a) Re*/6 of the nearer wall's Stokes force, the order "
             "of the relative flow's own inertial error (tests/test_frame_terms.py)."), "",
            ("**Where it matters, and a claim against the paper's equations.** The force is radial. In the "
             "aluminium runaway below (closed forms, nu = 2e-4 m^2/s, released from rest at kappa = 0.5) it "
             f"reaches {frame} times the buoyant weight m'_a g by {RUNAWAY_T_END:g} s "
             f"({' and '.join(f'{d:g}' for d in RUNAWAY_SLOPES)} degrees), while the "
             f"relative flow is slow (Re* <= {late_re:.2g} after {RUNAWAY_FIT_START:g} s, {end_re} at the end). "
             "It presses A into the outer wall against the "
             "squeeze film: in (2.2), (12 nu a m''_a / delta^2) q' ~ m eps chi'^2, q = kappa/zeta, with m = m_eff "
             "as printed and m'_a with the frame terms. The rows of each run reproduce m to "
             f"{worst_mass:.0e} (centripetal_mass, over {RUNAWAY_WINDOW[0]:g}-{RUNAWAY_WINDOW[1]:g} s). Hence "
             f"1 - kappa at {RUNAWAY_T_END:g} s is "
             f"{five['gap_ratio']:.1f} and {ten['gap_ratio']:.1f} times larger with the frame terms "
             f"(5 and 10 degrees; (m_eff/m'_a)^2 = {square:.2f} from the growth of q alone), while the rolling "
             f"hardly changes: X_b by {100 * five['x_b']:+.1f}% and {100 * ten['x_b']:+.1f}%, the late "
             f"acceleration by {100 * five['acceleration']:+.1f}% and {100 * ten['acceleration']:+.1f}%, the "
             f"mean Omega_b over the last 0.5 s by {100 * five['omega_b_mean']:+.1f}% and "
             f"{100 * ten['omega_b_mean']:+.1f}% (Omega_b swings within each turn, so its value at one instant, "
             f"{100 * five['omega_b_final']:+.1f}% and {100 * ten['omega_b_final']:+.1f}% at the end, mostly "
             "measures a phase). The printed (2.1)-(2.2) are right given the true fluid force; they "
             "understate the centripetal push only when that force is taken as quasi-steady Stokes flow in "
             "the frame of the fluid's centre of mass while the fluid turns with the line of centres. The "
             "claim holds under those conditions: plane, steady flow in the turning frame (Stokes number "
             f"delta^2/(nu tau) small: {stokes:.2g} here, so only roughly), chi' between the wall rates. The "
             f"gaps at stake, 1 - kappa = {min(gaps):.1g} to {max(gaps):.1g}, are below the asperity scale of "
             "the real walls (section 5: 1 - kappa* ~ 0.015), where a contact model takes over.")]


def _runaway_markdown(result: dict) -> list[str]:
    lines = ["", f"## The aluminium runaway followed to {RUNAWAY_T_END:g} s, with its inertial error", "",
             ("Figure 6's apparatus (aluminium, Table 2, nu = 2e-4 m^2/s), released from rest at kappa = 0.5, "
              "phi = 0.5 rad (the default scene's start), on 5 and 10 degree slopes; full equations with the "
              "closed forms, `on_invalid = \"warn\"` and the default Reynolds limit Re* = 1 (crossed, and "
              "recorded, in the first swing). Three treatments of the fluid's inertia: 'paper' ((2.1)-(2.2) as "
              "printed), 'quasi-steady' (with frame_terms), 'quasi-steady+inertia' (also the forces' first "
              "inertial correction, `model.inertia = 'first-order'`). Columns of the tables: Re*; the estimated "
              "relative force error (first order, against |f_chi,a| + |f_chi,b|); the first inertial "
              "correction and the frame force over m'_a g."), "",
             "![The aluminium runaway followed past the Reynolds limit](runaway.png)", ""]
    for deg in RUNAWAY_SLOPES:
        runs = {r["model"]: r for r in result["runaway_trajectories"] if r["slope_deg"] == deg}
        paper = runs["paper"]
        inertia = paper["inertia"]
        lines += [f"### {deg:g} degrees", "",
                  (f"'paper': {paper['status']} at t = {paper['t_last']:g} s ({paper['steps']} steps); "
                   f"largest Re* {inertia['max_reduced_reynolds']:.3g} at t = "
                   f"{inertia['t_at_max_reduced_reynolds']:.3g} s with an estimated force error of "
                   f"{100 * inertia['estimated_force_error_at_max_reduced_reynolds']:.1f}% there; largest "
                   f"estimated error {100 * inertia['max_estimated_force_error']:.1f}% at t = "
                   f"{inertia['t_at_max_estimated_force_error']:.3g} s. Limits passed: "
                   + "; ".join(f"Re* = 1 at t = {p['t']:.3g} s" for p in paper["limits_passed"]) + "."), "",
                  "| t (s) | X_b (m) | 1 - kappa | Omega_b (rad/s) | Re* | est. error | F^(1) / m'_a g | "
                  "frame / m'_a g |", "|---|---|---|---|---|---|---|---|"]
        series = paper["series"]
        for t in RUNAWAY_TIMES:
            i = series["t"].index(min(series["t"], key=lambda x: abs(x - t)))
            lines.append(f"| {series['t'][i]:.3g} | {series['x_b'][i]:.4g} | {series['one_minus_kappa'][i]:.3g} | "
                         f"{series['omega_b'][i]:.4g} | {series['reduced_reynolds'][i]:.3g} | "
                         f"{100 * series['estimated_force_error'][i]:.2g}% | "
                         f"{series['first_order_force_over_weight'][i]:.2g} | "
                         f"{series['frame_force_over_weight'][i]:.3g} |")
        end = f"{RUNAWAY_T_END:g} s"
        lines += ["", f"| run | X_b at {end} (m) | acceleration, t > {RUNAWAY_FIT_START:g} s (m/s^2) | "
                  f"1 - kappa at {end} | "
                  "largest Re* | largest est. error | largest frame / m'_a g |", "|---|---|---|---|---|---|---|"]
        for label, _, _ in RUNAWAY_MODELS:
            r = runs[label]
            lines.append(f"| {label} | {r['series']['x_b'][-1]:.4g} | {r['acceleration']:.4g} | "
                         f"{r['series']['one_minus_kappa'][-1]:.3g} | {r['inertia']['max_reduced_reynolds']:.3g} | "
                         f"{100 * r['inertia']['max_estimated_force_error']:.1f}% | "
                         f"{r['inertia']['max_frame_force_over_weight']:.3g} |")
        comp = next(c for c in result["runaway_comparison"] if c["slope_deg"] == deg)["first_order_inertia"]
        lines += ["", (f"Observed law X = g t^2 sin(alpha)/3: acceleration {paper['acceleration_observed_law']:.4g} "
                       f"m/s^2; (3.11): {paper['acceleration_311']:.4g} m/s^2. The first inertial correction, "
                       f"added to the forces, moves X_b at {end} by {100 * comp['x_b']:+.2f}%, the mean Omega_b over "
                       f"the last 0.5 s by {100 * comp['omega_b_mean']:+.2f}% and 1 - kappa by a factor "
                       f"{comp['gap_ratio']:.3f}: the trajectory-level size of the O(Re*) error, most of which "
                       f"is made in the first swing (Re* up to {inertia['max_reduced_reynolds']:.2g}, estimated "
                       f"error up to {100 * inertia['max_estimated_force_error']:.0f}%)."), ""]
    return lines


def _markdown(result: dict) -> str:
    th = result["thresholds"]
    app = f"{APPARATUS['delta_over_a']:g}"
    lines = ["# Fluid inertia: where quasi-steady Stokes fails", "",
             "Generated by `python -m validation.reports.inertia` (lubrication.navier_stokes, lubrication.inertia).", "",
             "## Headline", "",
             ("In the frame of the line of centres the fictitious forces of a plane flow only shift the "
             "pressure: the rotation rate chi' adds the exact force -m''_a chi'^2 eps e_eps + "
             "2 m''_a chi' eps' e_chi and nothing else. The rest of the inertial error depends on the "
             "wall rotations relative to that frame, W = Omega - chi', through the reduced Reynolds number "
             "Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a). Its first correction is a force along the "
             "line of centres, G(kappa, motion) Re* relative to the Stokes force of the wall rotations; "
             "f_chi and T_a change only at O(Re^2)."), "",
             ("**The error scale.** Every relative force error here is |F - F_Stokes| over "
             "|R_chi_a W_a| + |R_chi_b W_b|, the sum of the magnitudes of the two rotational terms of the "
             "Stokes force f_chi = R_chi_a W_a + R_chi_b W_b. For walls turning in the same sense that is "
             "|f_chi| itself; for counter-rotating walls f_chi can vanish (R_chi_a W_a = -R_chi_b W_b) while "
             "the inertial f_eps does not, and a ratio to |f_chi| would be unbounded. Against this scale the "
             "first-order error is below Re*/10 for every wall motion (the largest G below, over every "
             "direction of (W_a, W_b) and every kappa)."), "",
             ("| delta/a | max G over kappa and wall motion | at kappa, U_b/U_a | Re* at 1% | Re* at 10% | "
              "Re at 1% | Re at 10% |"),
             "|---|---|---|---|---|---|---|"]
    for (d, row), at in zip(th.items(), result["first_order"]["g_max_at"]):
        lines.append(f"| {d} | {row['g_max']:.4f} | {at['kappa']:g}, {at['u_b_over_u_a']:.3g} | "
                     f"{row['reduced_0.01']:.3g} | {row['reduced_0.1']:.3g} | "
                     f"{row['relative_0.01']:.3g} | {row['relative_0.1']:.3g} |")
    lines += ["", ("Re = max(|W_a| a, |W_b| b) delta / nu (relative wall Reynolds number), U = W a or W b (wall "
              f"speeds). For the apparatus (delta/a = {app}): Re* = {float(app):.3f} Re."), "",
              ("**The run guard.** `[run] max_gap_reynolds` defaults to Re* = 1 "
               "(dynamics/equations/limits.py): there the estimated first-order error is at most 10% for every "
               "gap and wall motion (9.95% at delta/a = 0.01, "
               f"{100 * th[app]['g_max']:.1f}% at the apparatus' gap), and the Newton solutions below agree "
               "with the first-order error to 1% of it up to Re* = 1. A run reports in summary.json "
               "`inertia` the largest Re* and the estimated error there, and the largest estimated error, "
               "each with its time (dynamics.equations.limits.inertia_report)."), "",
              "## kappa -> 0: thin-gap closed form (the DiPrima & Stuart regime), exact, finite elements", "",
              ("G = d(f_eps)/d(Re*) over |f_chi,a| + |f_chi,b| at kappa -> 0. Thin-gap closed form "
              "|U_a^2 + 4 U_a U_b + U_b^2| / (30 (|U_a| + |U_b|) V), the project's own derivation "
              "(lubrication.inertia.thin_gap_small_kappa): the coefficients of DiPrima & Stuart (1972) were "
              "not available to compare with. What is quoted of their theory agrees in kind: the first "
              "inertial correction changes the direct stiffness d f_eps / d eps linearly in Re and leaves the "
              "cross-coupled stiffness and the load magnitude unchanged at that order (\"Approximations in "
              "hydrodynamic lubrication\", J. Tribol. 114, 14-25, 1992). Here, for the journal alone "
              "(inner, U_b = 0), the correction is perpendicular to the Stokes load f_chi: the attitude angle "
              "turns by Re*/30 and d f_eps/d eps gains (pi/5) rho a U_a^2 / delta per unit length. The last "
              "column is |f_chi| over the scale: small for counter-rotation (U_b = -U_a), where f_chi "
              "nearly cancels."), "",
              "| delta/a | motion | thin gap | exact (ODE) | finite elements | f_chi / scale |",
              "|---|---|---|---|---|---|"]
    for r in result["small_kappa"]:
        lines.append(f"| {r['delta_over_a']:g} | {r['motion']} | {r['thin_gap']:.5f} | {r['exact']:.5f} | "
                     f"{r['finite_elements']:.5f} | {r['stokes_f_chi_over_scale']:.3g} |")
    fo = result["first_order"]
    j = min(range(len(fo["delta_over_a"])), key=lambda i: abs(fo["delta_over_a"][i] - float(app)))
    lines += ["", f"## First-order G(kappa) at the apparatus gap (delta/a = {app})", "",
              ("Relative force error per unit Re*, from the table (finite-element values at its nodes); "
              "co-rotating: W_a = W_b."), "",
              "| kappa | inner | outer | rolling | co-rotating |", "|---|---|---|---|---|"]
    for i, k in enumerate(fo["kappa"]):
        lines.append(f"| {k:g} | " + " | ".join(f"{fo[n][j][i]:.4f}" for n in ("inner", "outer", "rolling",
                                                                                "co-rotating")) + " |")
    lines += ["", "## Continuation sweeps", "",
              ("Newton continuation in Re on the meshes of `lubrication.navier_stokes.inertial_mesh`. "
              "Columns: first-order G; Re* where the Newton solution's force error reaches 1% and 10%; "
              "the ratio of the Newton error to the first-order G Re* at Re* = 1, 3, 10, 30; the largest "
              "Re* reached (Newton stops when the continuation step has been halved six times)."), "",
              ("| delta/a | kappa | motion | G | Re* at 1% | Re* at 10% | ratio at 1 | 3 | 10 | 30 | "
              "Re* reached | mesh | s |"), "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in result["sweeps"]:
        red = np.array(r["reduced_reynolds"])
        ratio = np.array(r["first_order_ratio"])
        at = [ratio[np.isclose(red, x)] for x in (1.0, 3.0, 10.0, 30.0)]
        cells = " | ".join(f"{v[0]:.3f}" if v.size else "-" for v in at)
        lines.append(f"| {r['delta_over_a']:.3g} | {r['kappa']:g} | {r['motion']} | {r['first_order_g']:.4f} | "
                     f"{float(r['crossings']['0.01']):.3g} | {float(r['crossings']['0.1']):.3g} | {cells} | "
                     f"{r['max_reduced_reynolds']:.3g} | {r['mesh'][0]} x {r['mesh'][1]} | {r['wall_time_s']:.1f} |")
    lines += ["", "![Force error against the Reynolds number; first-order G; torque error](inertia.png)", "",
              "## The inertia-corrected force model", "",
              ("The closed forms and the exact Stokes forces with `inertia = 'first-order'` "
               "(lubrication.registry) add the tabulated first inertial correction f_eps^(1) "
               "to the Stokes forces, inside the compiled right-hand side. Its error is what the Newton "
               "solutions leave after it, |F - F_Stokes - F^(1)| / |F_Stokes|, largest over the sweeps "
               "above (at the table's nodes; between them add the interpolation error, below 3% of the "
               "correction: see 'The tabulated estimate'). The squeeze's inertia and the unsteady inertia "
               "are not in it."), "",
              "| Re* | plain Stokes error | corrected error |", "|---|---|---|"]
    for level, row in result["corrected_model_error"].items():
        lines.append(f"| {level} | {row['plain']:.3g} | {row['corrected']:.3g} |")
    lines += ["", "## The runaway: the same relative flow in faster-turning frames", "",
              ("Relative co-rotation W_a = W_b (Re = 10), apparatus gap, kappa = 0.6; chi' = s W with the "
              "fictitious forces discretised."), "",
              "| s | dynamic force error | Re (relative) | Re (absolute wall) | shear Re | rotation number |",
              "|---|---|---|---|---|---|"]
    for r in result["runaway"]:
        lines.append(f"| {r['spin']:g} | {r['relative_error']:.5f} | {r['reynolds_relative']:g} | "
                     f"{r['reynolds_absolute']:.3g} | {r['reynolds_shear']:.3g} | {r['rotation_number']:.3g} |")
    lines += ["", "## The force (2.1)-(2.2) miss: m''_a (1 + m''_a/m_f) eps chi'^2", "",
              ("Orbit rate chi' at which it reaches 1% / 10% of the buoyant weight m'_a g, and the absolute "
              "wall Reynolds number chi' b delta / nu there: large or small, it does not measure this force, "
              "which is exact in the frame of the line of centres (the run guard measures Re*)."), "",
              "| apparatus | kappa | level | chi' (rad/s) | m_eff / m'_a | Re_abs for nu = "
              + ", ".join(f"{nu:g}" for nu in OILS) + " m^2/s |", "|---|---|---|---|---|---|"]
    for r in result["apparatus_frame_force"]:
        res = ", ".join(f"{v:.3g}" for v in r["reynolds_absolute"].values())
        lines.append(f"| {r['apparatus']} | {r['kappa']:g} | {r['level']:g} | {r['chi_dot']:.3g} | "
                     f"{r['m_eff_over_m_reduced']:.3f} | {res} |")
    lines += _frame_terms_markdown(result) + _runaway_markdown(result)
    lines += ["", "## Unsteady inertia (not computed): Stokes numbers delta^2 / (nu tau)", "",
              "| apparatus | nu (m^2/s) | tau (s) | delta^2 / (nu tau) |", "|---|---|---|---|"]
    for r in result["stokes_numbers"]:
        lines.append(f"| {r['apparatus']} | {r['nu']:g} | {r['tau_s']:.3g} | {r['stokes_number']:.3g} |")
    acc = result["table_accuracy"]
    lines += ["", "## The tabulated estimate", "",
              (f"`lubrication.inertia.inertial_error_estimate` against fresh solves at {len(TABLE_PROBES)} "
              f"off-node points x 4 motions: max relative error {acc['max_relative']:.3g} (where G > 0.01), "
              f"max absolute error in G {acc['max_absolute_g']:.2g} (G <= 0.1)."), "",
              "## Checks", "", "| check | measured | reference | tolerance | passed |", "|---|---|---|---|---|"]
    for c in result["checks"]:
        lines.append(f"| {c['name']} | {c['measured']:.4g} | {c['reference']:.4g} | {c['tolerance']:.3g} | "
                     f"{c['passed']} |")
    wt = result["wall_time_s"]
    lines += ["", "Wall time (s): " + ", ".join(f"{k} {v:.0f}" for k, v in wt.items()), ""]
    return "\n".join(lines)


def write_outputs(result: dict, outdir: str | Path) -> list[Path]:
    """Write inertia.json, inertia.md, inertia.png and runaway.png into ``outdir``."""
    from numerics.files import write_json, write_text

    outdir = Path(outdir)

    def clean(obj):
        if isinstance(obj, dict):
            return {k: clean(v) for k, v in obj.items()}
        if isinstance(obj, (list, tuple)):
            return [clean(v) for v in obj]
        if isinstance(obj, float) and not math.isfinite(obj):
            return str(obj)
        if isinstance(obj, np.generic):
            return clean(obj.item())
        return obj

    return [write_json(outdir / "inertia.json", clean(result)), write_text(outdir / "inertia.md", _markdown(result)),
            Path(figure(result, outdir / "inertia.png")), Path(runaway_figure(result, outdir / "runaway.png"))]


if __name__ == "__main__":
    outdir = Path(__file__).resolve().parents[2] / "docs" / "inertia"
    result = run()
    for path in write_outputs(result, outdir):
        print(f"wrote {path}")
    failed = [c["name"] for c in result["checks"] if not c["passed"]]
    print(f"{len(result['checks']) - len(failed)} of {len(result['checks'])} checks passed")
    for name in failed:
        print(f"FAILED: {name}")
