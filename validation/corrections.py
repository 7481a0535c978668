r"""How wrong are the lubrication forms (2.5)-(2.7) at finite delta/a?

The closed forms are leading order in delta/a; the paper's apparatus has
delta/a = 0.325/0.8 = 0.406. For each of the five resistance coefficients
(f_eps per eps', f_chi and T_a per W_a and per W_b) this study computes the
ratio exact / lubrication against kappa,

* with the full Stokes solution (the tabulated resistance functions of
  :mod:`lubrication.stokes_tables`, whose nodes are finite-element solves),
* with the Reynolds equation solved on the exact eccentric gap
  sqrt(b^2 - eps^2 sin^2 theta) - eps cos theta - a instead of (B1),

for delta/a in {0.01, 0.03, 0.1, 0.3, 0.406, 1}, and fits the leading
correction ratio = 1 + c(kappa) delta/a + O(delta/a)^2 from the three thinnest
gaps (a quadratic in delta/a for (ratio - 1)/(delta/a), evaluated at 0).

Checked: both ratios tend to 1 as delta/a -> 0, with a log-log slope of
ratio - 1 against delta/a of 1 (the forms are leading order, no better and no
worse); reported: the share of the Stokes correction c that the exact gap
alone accounts for in the Reynolds equation, and the ratios at the paper's
apparatus (Table 2: a = 0.8 cm, b = 1.125 cm).
"""

from __future__ import annotations

import csv
import io
import math
import time
from pathlib import Path

import numpy as np

from lubrication import Annulus, Fluid, resistance
from lubrication.stokes_tables import KAPPA_AXIS, RATIO_NAMES, StokesTable

from .checks import Check, Finding, absolute, at_least, at_most

__all__ = ["DELTAS", "APPARATUS", "corrections_command", "register", "run", "study"]

#: Table 2: a = 0.8 cm, b = 1.125 cm, hence delta/a = 0.325/0.8.
APPARATUS = {"a_m": 0.008, "b_m": 0.01125, "delta_over_a": 0.325 / 0.8}
DELTAS = (0.01, 0.03, 0.1, 0.3, APPARATUS["delta_over_a"], 1.0)
#: The three thinnest gaps, for the fit of c(kappa).
THIN = DELTAS[:3]
#: Quick mode: coarser tables, built in memory, and only the gaps the checks need.
QUICK_DELTAS = (*THIN, APPARATUS["delta_over_a"])
QUICK_NODES = 6

#: Reynolds cells on the Sommerfeld grid. The grid is matched to the thin gap,
#: not the exact one, so convergence is slower than for (B1) at kappa = 0.99:
#: 64 cells leave 3e-4, 512 cells below 1e-9 (measured for delta/a up to 1).
REYNOLDS_CELLS = 512

LABELS = {"f_eps_per_eps_dot": "f_eps per eps' (2.5)", "f_chi_per_w_a": "f_chi per W_a (2.6)",
          "t_a_per_w_a": "T_a per W_a (2.7)", "f_chi_per_w_b": "f_chi per W_b (2.6)",
          "t_a_per_w_b": "T_a per W_b (2.7)"}

_FLUID = Fluid(nu=1.0, rho=1.0)  # the ratios are independent of the fluid


def reynolds_ratios(delta_over_a: float, kappas) -> np.ndarray:
    """Reynolds on the exact eccentric gap / (2.5)-(2.7), shape (5, len(kappas)).

    kappa = 0 is evaluated at KAPPA_AXIS, where both f_chi forms vanish.
    """
    out = np.empty((len(RATIO_NAMES), len(kappas)))
    for i, kappa in enumerate(kappas):
        annulus = Annulus.from_kappa(1.0, 1.0 + delta_over_a, max(kappa, KAPPA_AXIS))
        exact = resistance(annulus, _FLUID, "reynolds", n=REYNOLDS_CELLS, profile="eccentric")
        lub = resistance(annulus, _FLUID, "closed-form")
        out[:, i] = np.array(exact.as_tuple()) / np.array(lub.as_tuple())
    return out


def thin_gap_coefficient(deltas, ratios) -> np.ndarray:
    """c in ratio = 1 + c delta/a + ..., from ratios of shape (len(deltas), 5, n_kappa).

    (ratio - 1)/(delta/a) is fitted by the polynomial of degree len(deltas) - 1
    through the points and evaluated at delta/a = 0.
    """
    d = np.asarray(deltas, dtype=float)
    q = (np.asarray(ratios) - 1.0) / d[:, None, None]
    flat = q.reshape(len(d), -1)
    coeffs = np.polyfit(d, flat, len(d) - 1)
    return coeffs[-1].reshape(q.shape[1:])


def log_slope(deltas, ratios) -> np.ndarray:
    """Slope of log|ratio - 1| against log(delta/a) between the two thinnest gaps."""
    r = np.abs(np.asarray(ratios)[:2] - 1.0)
    return np.log(r[1] / r[0]) / math.log(deltas[1] / deltas[0])


def study(quick: bool = False, folder=None) -> dict:
    """Every number of the study; tables come from the cache ``folder`` (quick: built in memory).

    The Stokes ratios are those at the tables' nodes, which are finite-element
    solves, not interpolations; every table has the same nodes in kappa.
    """
    start = time.perf_counter()
    deltas = QUICK_DELTAS if quick else DELTAS
    tables = {}
    for d in deltas:
        if quick:
            tables[d] = StokesTable.build(d, n_nodes=QUICK_NODES)
        else:
            tables[d] = StokesTable.load(d, folder=folder)
    kappas = tables[deltas[0]].kappa_nodes[::-1]
    stokes = np.array([tables[d].node_ratios[:, ::-1] for d in deltas])
    reynolds = np.array([reynolds_ratios(d, kappas) for d in deltas])
    thin = [deltas.index(d) for d in THIN]
    return {
        "deltas": deltas, "kappas": kappas, "tables": tables,
        "stokes": stokes, "reynolds": reynolds,
        "c_stokes": thin_gap_coefficient(THIN, stokes[thin]),
        "c_reynolds": thin_gap_coefficient(THIN, reynolds[thin]),
        "slope_stokes": log_slope(THIN, stokes[thin]),
        "slope_reynolds": log_slope(THIN, reynolds[thin]),
        "wall_time_s": time.perf_counter() - start,
    }


#: The fitted c(kappa) reproduce these forms to 4e-4 (T_a per W_b: to 1e-4 of the row's
#: larger entry; near contact it is a small remainder that the solver resolves less well).
#: Each agrees with the contact limits (b/a)^p of :mod:`lubrication.stokes_tables`
#: expanded to first order, and the two W_b entries follow from the W_a ones by
#: R_chi_b = (b/a)^2 R_chi_a and the reciprocity R_t_b = -R_t_a - eps R_chi_a.
C_FORMS = {"f_eps_per_eps_dot": lambda k: 1.5 + 0.0 * k,
           "f_chi_per_w_a": lambda k: 0.5 + 0.0 * k,
           "t_a_per_w_a": lambda k: 1.5 / (1.0 + 2.0 * k * k),
           "f_chi_per_w_b": lambda k: 2.5 + 0.0 * k,
           "t_a_per_w_b": lambda k: 1.5 + 0.0 * k}


def stokes_identities(result: dict) -> tuple[float, float]:
    """Largest departures, over the study's gaps and kappa, from two exact identities.

    Returns (max |R_chi_b / ((b/a)^2 R_chi_a) - 1|,
    max |R_t_b + R_t_a + eps R_chi_a| / |R_t_a|). The second is reciprocity
    (the resistance matrix is symmetric: the torque on A from rotating B is
    the torque on B from rotating A) plus the balance of torques on the fluid
    about B. The first holds to the solver's accuracy; its proof is not given here.
    """
    chi, recip = 0.0, 0.0
    for i, d in enumerate(result["deltas"]):
        for j, kappa in enumerate(result["kappas"]):
            annulus = Annulus.from_kappa(1.0, 1.0 + d, max(kappa, KAPPA_AXIS))
            lub = np.array(resistance(annulus, _FLUID, "closed-form").as_tuple())
            r_eps, r_chi_a, r_t_a, r_chi_b, r_t_b = result["stokes"][i, :, j] * lub
            chi = max(chi, abs(r_chi_b / ((1.0 + d) ** 2 * r_chi_a) - 1.0))
            recip = max(recip, abs(r_t_b + r_t_a + annulus.eps * r_chi_a) / abs(r_t_a))
    return chi, recip


def checks_of(result: dict) -> list[Check]:
    """Thin-gap limit of both models, c(kappa), two identities, and the share of the correction."""
    checks = []
    kappas = result["kappas"]
    for k, name in enumerate(RATIO_NAMES):
        slopes = result["slope_stokes"][k]
        worst = int(np.argmax(np.abs(slopes - 1.0)))
        checks.append(absolute(
            f"Stokes: slope of log|ratio - 1| against log(delta/a), {name}", slopes[worst], 1.0, 0.1,
            f"worst over kappa in [0, 0.99] (kappa={kappas[worst]:g}); delta/a = {THIN[0]:g}, {THIN[1]:g}"))
        checks.append(at_most(
            f"Stokes: max |ratio - 1| over kappa at delta/a = {THIN[0]:g}, {name}",
            float(np.max(np.abs(result["stokes"][0, k] - 1.0))), 3.0 * THIN[0],
            "leading order: O(delta/a), uniformly in kappa"))
        # R_t_b against R_t_a, the larger entry of its row: (2.7) gives their ratio
        weight = (1.0 - kappas**2) / (1.0 + 2.0 * kappas**2) if name == "t_a_per_w_b" else 1.0
        c_err = float(np.max(weight * np.abs(result["c_stokes"][k] - C_FORMS[name](kappas))))
        checks.append(at_most(f"Stokes: fitted c(kappa) against its closed form, {name}", c_err, 2e-3,
                              "max over kappa of |c - c_form| (T_a per W_b: times R_t_b/R_t_a of (2.7)); "
                              "C_FORMS"))
    for k, name in enumerate(RATIO_NAMES):
        # where the exact gap carries no O(delta/a) part (f_chi and T_a per W_a at kappa -> 0)
        # ratio - 1 is rounding, and a slope means nothing
        moving = np.abs(result["reynolds"][1, k] - 1.0) > 1e-6
        slope = float(np.min(result["slope_reynolds"][k][moving]))
        checks.append(at_least(
            f"Reynolds on the exact gap: slope of log|ratio - 1| against log(delta/a), {name}",
            slope, 0.9,
            f"min over kappa in [0, 0.99] where |ratio - 1| > 1e-6: the ratio tends to 1 at "
            f"least linearly; max c = {np.max(result['c_reynolds'][k]):.3g} (at kappa = 0.99: "
            "not uniform near contact)"))
    chi, recip = stokes_identities(result)
    checks.append(at_most("Stokes: R_chi_b = (b/a)^2 R_chi_a, max relative departure", chi, 1e-5,
                          "every tabulated gap and kappa"))
    checks.append(at_most("Stokes: reciprocity R_t_b = -R_t_a - eps R_chi_a, max departure / |R_t_a|",
                          recip, 1e-10, "every tabulated gap and kappa; exact for the discrete system "
                          "too (symmetric matrix, loads from its residual), so rounding only"))
    share = result["c_reynolds"] / result["c_stokes"]
    for k, name in enumerate(RATIO_NAMES):
        checks.append(Finding(
            f"share of the Stokes O(delta/a) correction carried by the exact gap, {name}",
            float(share[k, 0]),
            f"c_reynolds/c_stokes at kappa=0; over kappa <= 0.99: {share[k].min():.3g} .. {share[k].max():.3g}"))
    return checks


def _apparatus_index(result: dict) -> int:
    return result["deltas"].index(APPARATUS["delta_over_a"])


def to_csv(result: dict) -> str:
    """One row per (model, delta/a, kappa): the five ratios to (2.5)-(2.7)."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(["model", "delta_over_a", "kappa", *RATIO_NAMES])
    for model in ("stokes", "reynolds"):
        label = "stokes" if model == "stokes" else "reynolds-eccentric"
        for i, d in enumerate(result["deltas"]):
            for j, kappa in enumerate(result["kappas"]):
                writer.writerow([label, f"{d:.10g}", f"{kappa:.10g}",
                                 *(f"{x:.10g}" for x in result[model][i, :, j])])
    return buf.getvalue()


def to_json(result: dict, checks: list[Check]) -> dict:
    """JSON-ready summary: ratios, c(kappa), the apparatus' headline numbers, table settings."""
    names = list(RATIO_NAMES)
    kappas = [float(k) for k in result["kappas"]]

    def per_name(arr):
        return {n: [float(x) for x in arr[k]] for k, n in enumerate(names)}

    i = _apparatus_index(result)
    headline = {}
    for model in ("stokes", "reynolds"):
        r = result[model][i]
        headline[model] = {n: {"min": float(r[k].min()), "max": float(r[k].max()),
                               "at_kappa": dict(zip((f"{k:.6g}" for k in kappas), map(float, r[k])))}
                           for k, n in enumerate(names)}
    table = result["tables"][APPARATUS["delta_over_a"]]
    headline["stokes"]["contact_limit"] = dict(zip(names, map(float, table.contact)))
    return {
        "names": names, "kappa": kappas,
        "delta_over_a": [float(d) for d in result["deltas"]],
        "stokes_ratio": {f"{d:.10g}": per_name(result["stokes"][i_])
                         for i_, d in enumerate(result["deltas"])},
        "reynolds_eccentric_ratio": {f"{d:.10g}": per_name(result["reynolds"][i_])
                                     for i_, d in enumerate(result["deltas"])},
        "thin_gap_coefficient": {"fit_delta_over_a": list(THIN),
                                 "stokes": per_name(result["c_stokes"]),
                                 "reynolds_eccentric": per_name(result["c_reynolds"])},
        "apparatus": {**APPARATUS, "ratio": headline},
        "tables": {f"{d:.10g}": {**t.settings, "build_time_s": t.build_time_s}
                   for d, t in result["tables"].items()},
        "reynolds_cells": REYNOLDS_CELLS,
        "checks": [c.as_dict() for c in checks],
        "wall_time_s": result["wall_time_s"],
    }


def figure(result: dict, path) -> None:
    """Ratio to (2.5)-(2.7) against kappa for every coefficient and gap, and c(kappa)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from lubrication.files import save_figure

    fine = np.linspace(0.0, 0.999, 300)
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    for k, (ax, name) in enumerate(zip(axes.flat, RATIO_NAMES)):
        for i, d in enumerate(result["deltas"]):
            colour = f"C{i}"
            ax.plot(fine, result["tables"][d].ratios(fine)[k], "-", color=colour, label=f"Stokes, {d:.3g}")
            ax.plot(result["kappas"], result["reynolds"][i, k], "--o", color=colour, ms=3,
                    label=f"Reynolds exact gap, {d:.3g}")
        ax.set_title(LABELS[name], fontsize=10)
        ax.set_xlabel("kappa")
        ax.set_ylabel("exact / lubrication")
        if name == "t_a_per_w_b":
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
    axes.flat[0].legend(fontsize=6, ncol=2, title="delta/a", title_fontsize=7)
    ax = axes.flat[5]
    for k, name in enumerate(RATIO_NAMES):
        ax.plot(result["kappas"], result["c_stokes"][k], "-o", color=f"C{k}", ms=3, label=f"Stokes, {name}")
        ax.plot(result["kappas"], result["c_reynolds"][k], "--s", color=f"C{k}", ms=3, label=f"Reynolds, {name}")
    ax.set_ylim(-0.5, 4.0)
    ax.set_title("c(kappa) in ratio = 1 + c delta/a + ...", fontsize=10)
    ax.set_xlabel("kappa")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    fig.suptitle("Full Stokes and Reynolds-on-the-exact-gap against the lubrication forms (2.5)-(2.7)")
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def _paragraph(result: dict) -> str:
    i = _apparatus_index(result)
    r = result["stokes"][i]
    parts = ", ".join(f"{LABELS[n].split(' (')[0]} x{r[k].min():.3f}..{r[k].max():.3f}"
                      for k, n in enumerate(RATIO_NAMES))
    c = result["c_stokes"]
    cs = ", ".join(f"{n} {c[k].min():.3f}..{c[k].max():.3f}" for k, n in enumerate(RATIO_NAMES))
    return (f"Full Stokes resistance against the lubrication forms (2.5)-(2.7). At the paper's apparatus "
            f"(delta/a = {APPARATUS['delta_over_a']:.4g}) the exact coefficients are the closed forms times: "
            f"{parts} (kappa from 0 to 0.99). The thin-gap correction ratio = 1 + c delta/a has, over "
            f"kappa in [0, 0.99], c = {cs}. The Reynolds equation on the exact gap carries only part of it.")


def run(outdir, quick: bool = False, folder=None):
    """The study as a validation group: (checks, figure names, paragraph); writes CSV and JSON too."""
    from lubrication.files import write_json, write_text

    outdir = Path(outdir)
    result = study(quick=quick, folder=folder)
    checks = checks_of(result)
    write_text(outdir / "corrections.csv", to_csv(result))
    write_json(outdir / "corrections.json", to_json(result, checks))
    figure(result, outdir / "corrections.png")
    return checks, ["corrections.png"], _paragraph(result)


def corrections_command(args) -> int:
    """``snail corrections``: run the study, write CSV, JSON and figure into ``args.output``."""
    import importlib.util

    if importlib.util.find_spec("skfem") is None:
        msg = ('the correction study needs the Stokes solver (scikit-fem), which is not installed; '
               'install the finite-element extra with: pip install "snail-cylinder[fem]"')
        raise ImportError(msg)
    records, _, text = run(args.output, quick=args.quick)
    checks = [c for c in records if isinstance(c, Check)]
    failed = [c for c in checks if not c.passed]
    print(text)
    print(f"{len(checks) - len(failed)} of {len(checks)} checks passed; "
          f"corrections.csv, corrections.json and corrections.png in {args.output}")
    return 1 if failed else 0


def register(subparsers) -> None:
    """Add ``snail corrections`` (entry point of the ``snail.commands`` group)."""
    p = subparsers.add_parser(
        "corrections", help="delta/a correction study: lubrication and Reynolds against Stokes",
        description="Ratio of the full-Stokes and the exact-gap Reynolds resistance coefficients to "
                    "the lubrication forms (2.5)-(2.7) against kappa for delta/a from 0.01 to 1, the "
                    "thin-gap correction coefficients and the paper's apparatus. Writes "
                    "corrections.csv, corrections.json and corrections.png. Stokes tables are cached "
                    "in $SNAIL_CACHE (default ~/.cache/snail-cylinder).")
    p.add_argument("-o", "--output", default="corrections", help="output folder (default corrections)")
    p.add_argument("--quick", action="store_true",
                   help="coarse tables built in memory and the four gaps the checks need")
    p.set_defaults(run=corrections_command)
