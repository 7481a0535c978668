"""Table 3 re-inferred (:mod:`validation.table3`): its tables, its paragraph, its figure and its files.

:func:`run` is the group of ``snail validate``; run ``python -m validation.reports.table3`` from the
project root to write ``docs/table3/table3.md``, ``table3.json`` and ``table3.png``.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

from dynamics.contact.reduced import LOCKED, SLIDING
from numerics.files import save_figure, write_json, write_text

from ..checks import Check, Finding
from ..table3 import (
    ABOUT,
    BRACKET_FACTOR,
    CLOSED_FORMS,
    LOCKED_SLOPES_DEG,
    MODELS,
    PAPER_RATIO,
    PARTICLE_SIZE,
    ROOT_RTOL,
    _about_four,
    _power_law,
    compute,
    paper_speed,
    records,
    reduced_speed,
    sigma_bounds,
    the_apparatus,
)

__all__ = ["detail_table", "figure", "main_table", "markdown", "run", "write_outputs"]


# -- the report ---------------------------------------------------------------------

def _mm(x: float, digits: int = 3) -> str:
    return "-" if not math.isfinite(x) else f"{1e3 * x:.{digits}g}"


def _ratio(x) -> str:
    return "-" if x is None or not math.isfinite(x) else f"{x:.2f}"


def main_table(result: dict) -> str:
    """Grade, particle size, the paper's sigma, sigma re-inferred with both models, ratios, 'about four'."""
    e, o = MODELS
    lines = ["| grade | mean particle size (mm) | sigma, paper (mm) | sigma re-inferred, exact forces (mm) | "
             "sigma re-inferred, exact forces + finite length (mm) | sigma / particle size: paper | exact | "
             "exact + length | 'about four' (exact / exact + length) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in result["rows"]:
        me, mo = r["models"][e], r["models"][o]
        if r["grade"] in PARTICLE_SIZE:
            verdict = " / ".join("holds" if _about_four(m["ratio"]) else "fails" for m in (me, mo))
        else:
            verdict = "no particle size"
        lines.append(f"| {r['grade']} | {_mm(r['particle_size'], 2)} | {_mm(r['sigma_paper'])} | "
                     f"{_mm(me['sigma'], 4)} | {_mm(mo['sigma'], 4)} | {_ratio(r.get('ratio_paper'))} | "
                     f"{_ratio(me.get('ratio'))} | {_ratio(mo.get('ratio'))} | {verdict} |")
    return "\n".join(lines)


def detail_table(result: dict) -> str:
    """The target speed, the model speed at the paper's sigma, the steps from (6.1) to the full model."""
    e, o = MODELS
    names = list(result["rows"][0]["decomposition"])
    lines = ["| grade | V (6.1), paper's sigma (mm/s) | V full exact at paper's sigma (mm/s) | "
             + " | ".join(f"sigma, {n} (mm)" for n in names)
             + " | sigma, full exact (mm) | sigma, full exact + length (mm) | phase | d ln V / d ln sigma |",
             "|---|---|---|" + "---|" * len(names) + "---|---|---|---|"]
    for r in result["rows"]:
        me, mo = r["models"][e], r["models"][o]
        lines.append(f"| {r['grade']} | {1e3 * r['v_target']:.3f} | {1e3 * me['speed_at_paper_sigma']:.3f} | "
                     + " | ".join(f"{_mm(r['decomposition'][n]['sigma'], 4)} ({r['decomposition'][n]['phase']})"
                                  for n in names)
                     + f" | {_mm(me['sigma'], 4)} | {_mm(mo['sigma'], 4)} | {me['phase']} / {mo['phase']} | "
                     f"{me['elasticity']:.3f} / {mo['elasticity']:.3f} |")
    return "\n".join(lines)


def markdown(result: dict) -> str:
    """The method, the model, the conditions, the tables and what they show; every number measured."""
    ap, rows = result["apparatus"], result["rows"]
    e, o = MODELS
    exps = {name: _power_law({r["grade"]: (r["sigma_paper"] if name == "paper" else r["models"][name]["sigma"])
                              for r in rows if r["grade"] in PARTICLE_SIZE}) for name in ("paper", *MODELS)}
    ratios = {name: [r["models"][name]["ratio"] for r in rows if r["grade"] in PARTICLE_SIZE] for name in MODELS}
    holds = {name: sum(_about_four(x) for x in ratios[name]) for name in MODELS}
    smooth = next(r for r in rows if r["grade"] == "smooth")
    psi_lock = max((r["models"][n]["psi_to_lock"] for r in rows for n in MODELS
                    if r["models"][n]["phase"] == LOCKED), default=math.nan)
    found = sorted({r["models"][n]["phase"] for r in rows for n in MODELS})
    phases = f"{found[0]} for every grade" if len(found) == 1 else "locked for some grades, sliding for others"
    traj = result["trajectories"]
    closed = [r["decomposition"][CLOSED_FORMS]["phase"] for r in rows]
    closed_phases = (f" (with these forces the pair slides at the paper's psi: {closed.count(SLIDING)} of {len(rows)})"
                     if SLIDING in closed else "")
    worst_traj = max(abs(t["speed"] / next(r for r in rows if r["grade"] == t["grade"])["v_target"] - 1.0)
                     for t in traj)
    text = (
        "Method. The paper infers Table 3's minimum gaps sigma from measured speeds with its leading-order speed "
        "law (6.1)-(6.3), V = V* sin(alpha) zeta* Max(1/2, 1 - sqrt(1 - s^2) tan(psi)/s), zeta* = sqrt(1 - kappa*^2), "
        "kappa* = 1 - sigma/delta; its sigma make (6.1) reproduce the measured speeds, so (6.1) with the paper's "
        "sigma stands in for the measurements, which are not tabulated. For each grade and the smooth cylinder, "
        "sigma is re-inferred as the root of V_full(sigma) = V_(6.1)(sigma_paper), where V_full = b Omega_b is the "
        "steady rolling speed of the full model (2.1)-(2.4) with rough contact (a unilateral constraint at "
        "eps* = delta - sigma with Coulomb friction and a plastic impact, dynamics.contact.full), found as the fixed "
        "point of its contact phase by Newton's method; the root by scipy's brentq on a bracket grown from the "
        f"paper's sigma by factors of {BRACKET_FACTOR:g}, to a relative tolerance {ROOT_RTOL:g} in sigma. "
        f"{len(traj)} trajector{'y' if len(traj) == 1 else 'ies'} released at rest on the asperities at the bottom "
        f"(phi = pi) at the re-inferred sigma end{'s' if len(traj) == 1 else ''} on the fixed point "
        f"({sum(t['phase'] == t['fixed_phase'] for t in traj)} of {len(traj)} in its phase), at the target "
        "speed within "
        f"{worst_traj:.1e}.\n\n"
        "Model. Forces: the exact 2-D Stokes forces of circular walls (stokes-exact), and the same times the "
        "thin-gap finite-length factors of an annulus whose gap opens into the end regions (stokes-exact/open-ends, "
        f"L/a = {ap['length_over_a']:.2f}; within 4.7% of 3-D Stokes in f_chi, docs/finite_length/stokes3d.md). "
        f"The reduced model's lubrication forms are leading order in delta/a, here {ap['delta_over_a']:.3f}.\n\n"
        f"Conditions. Steel apparatus (Table 2 as dynamics.apparatus reconciles it), {1e6 * ap['nu']:g} cSt oil "
        f"(figure 11), slope {ap['slope_deg']:g} degrees (figure 5(a)), s = {ap['s']:.4f}, V* = {ap['v_star']:.4g} "
        f"m/s. Friction: the paper's, the onset of sliding at about 3 degrees (section 6.2) through (6.4), scaled "
        f"psi = {ap['psi']:.4f} rad, tan(psi_hat) = {ap['tan_psi_hat']:.4f} (C2). (6.1) is locked there and does not "
        f"depend on psi; the full model is {phases} at the re-inferred sigma"
        + (f" and would stay locked down to psi = {psi_lock:.4f}" if math.isfinite(psi_lock) else "")
        + ". While locked, the re-inferred sigma does not depend on the slope (proportionality to "
        "sin(alpha), checked at "
        + ", ".join(f"{s:g}" for s in result["slopes"] if s in LOCKED_SLOPES_DEG) + " degrees)."
        " Particle sizes: Table 3's 'expected' row, the mean particle size of the American CAMI standard "
        "(0.07, 0.09, 0.12, 0.2, 0.36 mm).\n\n"
        + main_table(result) + "\n\n"
        f"The paper's own ratios are {min(r['ratio_paper'] for r in rows if 'ratio_paper' in r):.2f}-"
        f"{max(r['ratio_paper'] for r in rows if 'ratio_paper' in r):.2f}, which it calls 'about four'; here a "
        f"ratio within {ABOUT:.0%} of 4 counts as 'about four'. Re-inferred, the ratio runs from "
        f"{max(ratios[e]):.2f} (grade 220) down to {min(ratios[e]):.2f} (grade 50) with exact forces and from "
        f"{max(ratios[o]):.2f} to {min(ratios[o]):.2f} with the finite length: 'about four' holds for "
        f"{holds[e]} and {holds[o]} of the five grades. A least-squares fit sigma ~ d^p to the particle size d "
        f"gives p = {exps[e]:.2f} (exact) and {exps[o]:.2f} (finite length), against "
        f"{exps['paper']:.2f} for the paper's values. The smooth cylinder's 50 micrometres becomes "
        f"{1e6 * smooth['models'][e]['sigma']:.0f} and {1e6 * smooth['models'][o]['sigma']:.0f} micrometres.\n\n"
        "Where the change comes from: sigma re-inferred with section 5's exact fixed point (5.10)/(5.11) removes "
        "only the zeta* expansion of (6.1) (the locked (6.1) underestimates that fixed point by (2 + kappa*^2)/"
        "(3 kappa*^2), which grows with sigma); the full model with the closed forms (2.5)-(2.7) adds the finite "
        "gap's geometry and kinematics" + closed_phases + "; the exact Stokes forces add the finite gap's larger "
        "resistance; the finite "
        "length lowers the resistance again. The elasticity d ln V / d ln sigma converts a relative error in a "
        "measured speed into one in sigma (divide by it).\n\n"
        + detail_table(result)
    )
    return text


# -- the figure ---------------------------------------------------------------------

def figure(path, result: dict) -> None:
    """(a) sigma against the mean particle size; (b) the steady speeds against sigma, and the roots."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FormatStrFormatter, NullFormatter

    ap = the_apparatus(result["apparatus"]["slope_deg"])
    psi = result["apparatus"]["psi"]
    rows = [r for r in result["rows"] if r["grade"] in PARTICLE_SIZE]
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.4))
    d = np.array([1e3 * r["particle_size"] for r in rows])
    ax_a.loglog(d, [1e3 * r["sigma_paper"] for r in rows], "ks", mfc="none", label="paper (Table 3), via (6.1)")
    for name, marker in zip(MODELS, "o^"):
        ax_a.loglog(d, [1e3 * r["models"][name]["sigma"] for r in rows], marker, label=f"full model, {name}")
    line = np.array([0.05, 0.5])
    ax_a.loglog(line, PAPER_RATIO * line, "k:", lw=0.8, label="sigma = 4 x particle size")
    for r, x in zip(rows, d):
        ax_a.annotate(r["grade"], (x, 1e3 * r["sigma_paper"]), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax_a.set_xlabel("mean particle size, CAMI (mm)")
    ax_a.set_ylabel("minimum gap sigma (mm)")
    ax_a.set_title("(a) inferred roughness against particle size", fontsize=9)
    ax_a.legend(fontsize=7)
    scale = ap.v_star * math.sin(ap.alpha)
    grid = np.geomspace(*sigma_bounds(ap), 200)
    ax_b.loglog(1e3 * grid, [paper_speed(ap, s, psi) / scale for s in grid], "k-", lw=1, label="(6.1) as printed")
    ax_b.loglog(1e3 * grid, [reduced_speed(ap, s, psi) / scale for s in grid], "k--", lw=0.8,
                label="section 5 exact fixed point")
    for k, (name, scan) in enumerate(result["scans"].items()):
        ax_b.loglog(1e3 * np.array(scan["sigma"]), np.array(scan["speed"]) / scale, color=f"C{k}", lw=1,
                    label=f"full model, {name}")
    for r in result["rows"]:
        ax_b.plot([1e3 * r["sigma_paper"]], [r["v_target"] / scale], "ks", mfc="none", ms=5)
        for k, name in enumerate(MODELS):
            ax_b.plot([1e3 * r["models"][name]["sigma"]], [r["v_target"] / scale], "o^"[k], color=f"C{k}", ms=4)
    ax_b.set_xlabel("minimum gap sigma (mm)")
    ax_b.set_ylabel("V / (V* sin alpha)")
    ax_b.set_title(f"(b) steady speed, steel, 500 cSt, {result['apparatus']['slope_deg']:g} degrees; "
                   "squares: paper, markers: re-inferred", fontsize=8)
    for ax in (ax_a, ax_b):
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_formatter(FormatStrFormatter("%g"))
            axis.set_minor_formatter(NullFormatter())
    ax_b.legend(fontsize=7)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


# -- the group ----------------------------------------------------------------------

def run(outdir, quick: bool = False):
    """Table 3 re-inferred; returns (records, figure file names, a markdown paragraph)."""
    result = compute(quick)
    figures = []
    if not quick:
        figure(Path(outdir) / "table3.png", result)
        figures.append("table3.png")
    return records(result), figures, markdown(result)


def write_outputs(result: dict, outdir) -> list[Path]:
    """table3.md, table3.json (the result and the records) and table3.png in ``outdir``."""
    outdir = Path(outdir)
    recs = records(result)
    checks = [r for r in recs if isinstance(r, Check)]
    findings = [r for r in recs if isinstance(r, Finding)]
    lines = ["# Table 3 re-inferred with the full model", "", markdown(result), "",
             "## Checks", "", "| check | kind | measured | reference | tolerance | passed |",
             "|---|---|---|---|---|---|"]
    lines += [f"| {c.name} | {c.kind} | {c.measured:.6g} | {c.reference:.6g} | {c.tolerance:.3g} | "
              f"{'yes' if c.passed else '**NO**'} |" for c in checks]
    lines += ["", "## Findings (reported, not judged)", "", "| finding | value | note |", "|---|---|---|"]
    lines += [f"| {f.name} | {f.value:.6g} | {f.note} |" for f in findings]
    paths = [write_text(outdir / "table3.md", "\n".join(lines) + "\n")]
    paths.append(write_json(outdir / "table3.json", _json_ready(
        {"result": result, "checks": [c.as_dict() for c in checks], "findings": [f.as_dict() for f in findings]})))
    if "scans" in result:
        figure(outdir / "table3.png", result)
        paths.append(outdir / "table3.png")
    return paths


def _json_ready(obj):
    """NaN and infinities as strings, the rest unchanged (JSON has no non-finite numbers)."""
    if isinstance(obj, dict):
        return {str(k): _json_ready(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_json_ready(v) for v in obj]
    if isinstance(obj, float) and not math.isfinite(obj):
        return str(obj)
    return obj


if __name__ == "__main__":
    quick_run = "--quick" in sys.argv[1:]
    outputs = write_outputs(compute(quick_run), Path(__file__).resolve().parents[2] / "docs" / "table3")
    for written in outputs:
        print(f"wrote {written}")
