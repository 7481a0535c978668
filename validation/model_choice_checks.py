r"""The automatic model choice against computations made now.

:mod:`dynamics.app.auto` chooses from the stored speed-versus-accuracy study
(``dynamics/data/model_choice.json``, written by ``benchmarks/accuracy.py``).
These checks do not trust the stored numbers: each choice is recomputed at
run time against the reference it claims to meet.

* Different gaps, different choices. At one tolerance, 5e-2, the thin gap
  delta/a = 0.01 gets the closed forms (2.5)-(2.7), whose error there is
  O(delta/a) (the largest term, f_chi per W_b, is about 2.5 delta/a), and the
  reduced equations (2.11); the paper's apparatus, delta/a = 0.406
  (a = 0.8 cm, b = 1.125 cm), gets the exact Stokes forces and the full
  equations (2.1)-(2.4).
* The chosen force model meets its tolerance. Its five resistance
  coefficients are compared, at kappas that are not study points, with the
  exact 2-D Stokes solution (:mod:`lubrication.stokes_exact`), or, when the
  exact solution is the choice, with a finite-element Stokes solve on the
  coarsest mesh whose own error is a hundredth of the tolerance (2.5e-6 on
  the default mesh against the exact solution, falling as the fourth power
  of the cell counts); error convention of the study (T_a per W_b against
  |T_a per W_a|).
* The chosen equations meet theirs. The reduced equations and the full
  equations with the exact Stokes forces are both run from rest at kappa = 0.5,
  phi = 0.5 for 200 tau (the distinguished-limit apparatus with the steel
  apparatus' groups); at delta/a = 0.01 the relative error of X_b and of the
  gap 1 - kappa at the end must be within the tolerance, at 0.406 (where the full equations
  were chosen) it must exceed it.
"""

from __future__ import annotations

from dynamics.app.auto import choose_equations, choose_forces
from dynamics.apparatus import Apparatus, preset
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.simulation import simulate
from lubrication.geometry import Annulus, Fluid, Motion, Resistance
from lubrication.registry import kernel_model, resistance
from lubrication.stokes import clear_cache, default_mesh

from .checks import absolute, at_least, at_most

__all__ = ["compute"]

THIN, APPARATUS = 0.01, 0.40625
# One scene tolerance that separates the gaps: the closed forms were measured at 2.5e-2 (delta/a = 0.01)
# and 0.58 (0.406), the reduced equations at 3.0e-2 and 0.65.
FORCE_TOLERANCE = EQUATIONS_TOLERANCE = 5e-2
KAPPA_BAND = 0.99  # the study's near-contact band, as a trajectory needs
FLUID = Fluid(nu=2.0e-4, rho=960.0)
T_END_TAU = 200.0
# Largest relative error of the finite elements on the default mesh against the exact
# solution, kappa <= 0.99 and delta/a in [0.01, 0.41] (benchmarks/results/accuracy.md)
FEM_ERROR = 2.5e-6


def _row_error(got: Resistance, truth: Resistance) -> float:
    g, t = got.as_tuple(), truth.as_tuple()
    return max([abs(g[i] - t[i]) / abs(t[i]) for i in range(4)] + [abs(g[4] - t[4]) / abs(t[2])])


def _chosen_resistance(choice, annulus: Annulus) -> Resistance:
    model = kernel_model(choice.model, **choice.options)
    unit = [model.forces(annulus, Motion(**{k: 1.0}), FLUID) for k in ("eps_dot", "omega_a", "omega_b")]
    return Resistance(unit[0].f_eps, unit[1].f_chi, unit[1].T_a, unit[2].f_chi, unit[2].T_a)


def force_errors(tolerance: float, delta: float, kappas) -> tuple:
    """The choice at (tolerance, delta/a) and its error against an independent Stokes solution at each kappa:
    the exact one, or the finite elements when the exact one was chosen."""
    choice = choose_forces(tolerance, delta, KAPPA_BAND)
    if choice.model == "stokes-exact":
        reference = {"model": "stokes", **_fem_mesh(tolerance, delta)}
    else:
        reference = {"model": "stokes-exact"}
    errors = {}
    for kappa in kappas:
        annulus = Annulus.from_kappa(0.008, 0.008 * (1.0 + delta), kappa, length=0.1035)
        errors[kappa] = _row_error(_chosen_resistance(choice, annulus), resistance(annulus, FLUID, **reference))
        clear_cache()  # each reference geometry is solved once: keep one system in memory, not several
    return choice, errors


def _fem_mesh(tolerance: float, delta: float) -> dict:
    """The coarsest mesh whose own error is a hundredth of the tolerance.

    The default mesh's error is at most FEM_ERROR and falls like the fourth
    power of the cell counts (:func:`lubrication.stokes.default_mesh`); the
    scale is kept in [1/2, 2] (a coarser mesh no longer resolves the gap).
    """
    scale = min(2.0, max(0.5, (100.0 * FEM_ERROR / tolerance) ** 0.25))
    n_around, n_across = default_mesh(delta)
    return {"n_around": round(scale * n_around), "n_across": max(2, round(scale * n_across))}


def equations_error(delta: float) -> float:
    """Relative error of (X_b, 1 - kappa) after T_END_TAU of the reduced equations against the full
    equations with exact Stokes forces, at ``delta`` with the steel apparatus' groups."""
    steel = preset("steel")
    app = Apparatus.from_groups(steel.s, steel.upsilon, steel.mu_ratio, delta)
    release = Initial(kappa=0.5, phi=0.5)
    # a comparison of two sets of equations: the inertial guard, a statement about the fluid, is lifted
    # (the release's swing passes Re* = 1 at every delta/a of the study)
    lifted = Limits(max_gap_reynolds=None)
    reduced = simulate(app, release, T_END_TAU * app.tau, equations="reduced", rtol=1e-10, limits=lifted)
    full = simulate(app, release, T_END_TAU * app.tau, forces=kernel_model("stokes-exact"), rtol=1e-10,
                    limits=lifted)
    r, f = reduced.columns, full.columns
    return max(abs(r["x_b"][-1] - f["x_b"][-1]) / abs(f["x_b"][-1]),
               abs(r["one_minus_kappa"][-1] - f["one_minus_kappa"][-1]) / f["one_minus_kappa"][-1])


def compute(quick: bool = False) -> dict:
    """Every choice, its error now, and the checks of the automatic choice.

    Returns ``checks``; the force choices ``thin``, ``wide`` and ``strict`` with their errors per kappa
    (``thin_errors``, ...); the equations' choices ``eq_thin`` and ``eq_wide``; and the reduced
    equations' trajectory errors at both gaps (``reduced_error``, ``reduced_wide_error``).
    """
    kappas = (0.3, 0.95) if quick else (0.3, 0.7, 0.95, 0.985)
    thin, thin_errors = force_errors(FORCE_TOLERANCE, THIN, kappas)
    wide, wide_errors = force_errors(FORCE_TOLERANCE, APPARATUS, kappas)
    strict, strict_errors = force_errors(1e-4, THIN, kappas)
    eq_thin = choose_equations(EQUATIONS_TOLERANCE, THIN)
    eq_wide = choose_equations(EQUATIONS_TOLERANCE, APPARATUS)
    reduced_error = equations_error(THIN)
    reduced_wide_error = equations_error(APPARATUS)
    checks = [
        absolute(f"auto forces differ at delta/a {THIN:g} ({thin.model}) and {APPARATUS:g} ({wide.model}), "
                 f"tolerance {FORCE_TOLERANCE:g}", float(thin.model != wide.model), 1.0, 0.0),
        absolute(f"auto equations differ at delta/a {THIN:g} ({eq_thin.model}) and {APPARATUS:g} "
                 f"({eq_wide.model}), tolerance {EQUATIONS_TOLERANCE:g}",
                 float(eq_thin.model != eq_wide.model), 1.0, 0.0),
    ]
    for choice, errors, tol, delta in ((thin, thin_errors, FORCE_TOLERANCE, THIN),
                                       (wide, wide_errors, FORCE_TOLERANCE, APPARATUS),
                                       (strict, strict_errors, 1e-4, THIN)):
        for kappa, err in errors.items():
            checks.append(at_most(f"auto {choice.model} forces against Stokes, delta/a {delta:g}, kappa {kappa:g}, "
                                  f"tolerance {tol:g}", err, tol,
                                  note=f"stored error {choice.error:.2e}; reference: "
                                       + ("finite elements" if choice.model == "stokes-exact" else "exact Stokes")))
    checks.append(at_most(f"auto {eq_thin.model} equations against full + Stokes, delta/a {THIN:g}, "
                          f"tolerance {EQUATIONS_TOLERANCE:g}", reduced_error, EQUATIONS_TOLERANCE,
                          note=f"stored error {eq_thin.error:.2e}"))
    checks.append(at_least(f"reduced equations miss tolerance {EQUATIONS_TOLERANCE:g} at delta/a {APPARATUS:g}",
                           reduced_wide_error, EQUATIONS_TOLERANCE, "so the full equations are needed"))
    checks.append(absolute(f"auto chose the full equations at delta/a {APPARATUS:g} (1 if so)",
                           float(eq_wide.model == "full"), 1.0, 0.0, f"chose {eq_wide.model}"))
    return {"checks": checks, "thin": thin, "thin_errors": thin_errors, "wide": wide, "wide_errors": wide_errors,
            "strict": strict, "strict_errors": strict_errors, "eq_thin": eq_thin, "eq_wide": eq_wide,
            "reduced_error": reduced_error, "reduced_wide_error": reduced_wide_error}
