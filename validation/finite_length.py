r"""3-D Stokes flow against "2-D Stokes x finite-length factor", at the paper's apparatus.

The equations of motion can take the exact 2-D (per unit length) Stokes
coefficients times L times the thin-gap finite-length factors of the
Reynolds equation (:mod:`lubrication.finite_length`). This study measures that
product against the full 3-D Stokes solution of the annulus of length L with
open ends (:mod:`lubrication.stokes3d`): a = 0.8 cm, b = 1.125 cm (delta/a =
0.406), L = 10.35 cm (L/a = 12.94).

For each kappa and each of the five coefficients R (f_eps per eps', f_chi
and T_a per W_a and per W_b):

* the 3-D factor F3 = R_3D / (L R_2D) with R_2D on the same cross-section
  mesh, whose errors then largely cancel; two meshes give its error;
* the Reynolds factors F_thin (thin gap) and F_ecc (exact eccentric gap at the
  apparatus' delta/a);
* the finite-gap factor r_S = R_2D / R_lub of the exact 2-D Stokes against (2.5)-(2.7);
* the error against the 3-D coefficient R_3D = F3 L R_2D of: L R_lub, L R_2D,
  L R_lub F_thin, L R_2D F_thin, L R_2D F_ecc, and, for the torques, the
  additive form L [T_2D - (eps/2)(F_chi - 1) f_chi,2D] (the thin gap's
  T_a = Couette - (eps/2) f_chi applied to the end correction alone).

It also tabulates the five Reynolds factors at the apparatus' length
(:func:`factors_at_the_apparatus`). Run ``python -m validation.reports.finite_length``
from the project root: it writes ``docs/finite_length/factors.{json,md}`` and
``docs/finite_length/stokes3d.{json,md}`` (:mod:`validation.reports.finite_length`).
"""

from __future__ import annotations

import time

from lubrication import Annulus, Fluid, Motion, closed_form_forces
from lubrication.finite_length import FACTOR_NAMES, finite_length_factors
from lubrication.stokes import stokes_resistance
from lubrication.stokes3d import stokes3d_resistance

__all__ = ["KAPPAS", "LENGTH", "MESHES", "A", "B", "compare", "factors_at_the_apparatus", "run"]

A, B, LENGTH = 0.008, 0.01125, 0.1035  # Table 2, m
KAPPAS = (0.3, 0.6, 0.9, 0.99)
#: (n_around, n_across, n_axial): the error estimate is the difference between the two.
MESHES = ((48, 3, 16), (64, 4, 16))
LABELS = {"f_eps_per_eps_dot": "f_eps / eps'", "f_chi_per_w_a": "f_chi / W_a", "t_a_per_w_a": "T_a / W_a",
          "f_chi_per_w_b": "f_chi / W_b", "t_a_per_w_b": "T_a / W_b"}
MODELS = ("L lub", "L 2D", "L lub F_thin", "L 2D F_thin", "L 2D F_ecc", "L 2D additive")


def _lubrication(kappa: float) -> dict[str, float]:
    annulus = Annulus.from_kappa(A, B, kappa, 1.0)
    fluid = Fluid(nu=1.0, rho=1.0)
    f = {m: closed_form_forces(annulus, Motion(**{m: 1.0}), fluid) for m in ("eps_dot", "omega_a", "omega_b")}
    return {"f_eps_per_eps_dot": f["eps_dot"].f_eps, "f_chi_per_w_a": f["omega_a"].f_chi,
            "t_a_per_w_a": f["omega_a"].T_a, "f_chi_per_w_b": f["omega_b"].f_chi, "t_a_per_w_b": f["omega_b"].T_a}


def compare(kappa: float, meshes=MESHES) -> dict:
    """The numbers of the module docstring for one kappa."""
    eps = kappa * (B - A)
    exact = stokes_resistance(A, B, kappa)
    lub = _lubrication(kappa)
    thin = finite_length_factors(kappa, LENGTH / A)
    ecc = finite_length_factors(kappa, LENGTH / A, delta_over_a=(B - A) / A, profile="eccentric")
    factors = []
    for n_around, n_across, n_axial in meshes:
        r3 = stokes3d_resistance(A, B, kappa, LENGTH, n_around=n_around, n_across=n_across, n_axial=n_axial)
        r2 = stokes_resistance(A, B, kappa, n_around=n_around, n_across=n_across)
        factors.append({"mesh": [n_around, n_across, n_axial], "dofs": r3.dofs, "wall_time_s": r3.wall_time_s,
                        "f3": {name: getattr(r3, name) / (LENGTH * getattr(r2, name)) for name in FACTOR_NAMES}})
    rows = {}
    for name in FACTOR_NAMES:
        f3 = factors[-1]["f3"][name]
        r_2d = getattr(exact, name)
        r_3d = f3 * LENGTH * r_2d
        models = {
            "L lub": LENGTH * lub[name],
            "L 2D": LENGTH * r_2d,
            "L lub F_thin": LENGTH * lub[name] * thin[name],
            "L 2D F_thin": LENGTH * r_2d * thin[name],
            "L 2D F_ecc": LENGTH * r_2d * ecc[name],
        }
        if name.startswith("t_a"):
            f_chi = getattr(exact, name.replace("t_a", "f_chi"))
            models["L 2D additive"] = LENGTH * (r_2d - 0.5 * eps * (thin["f_chi_per_w_a"] - 1.0) * f_chi)
        # T_a per W_b is a small difference near contact: its errors are also given against T_a per W_a
        row_scale = abs(LENGTH * exact.t_a_per_w_a * factors[-1]["f3"]["t_a_per_w_a"]) if name.startswith(
            "t_a") else abs(r_3d)
        rows[name] = {
            "F3": f3,
            "F3_error": abs(f3 - factors[0]["f3"][name]),
            "F_thin": thin[name],
            "F_ecc": ecc[name],
            "r_stokes": r_2d / lub[name],
            "R_3d": r_3d,
            "errors": {m: v / r_3d - 1.0 for m, v in models.items()},
            "errors_row": {m: (v - r_3d) / row_scale for m, v in models.items()},
        }
    return {"kappa": kappa, "meshes": factors, "rows": rows}


def factors_at_the_apparatus(kappas=(*KAPPAS, 0.999)) -> dict:
    """The five Reynolds factors at L/a = 12.94: thin gap, exact gap at delta/a = 0.406, short-bearing limit.

    Also the table kernel's values (:func:`lubrication.finite_length.table_factors`) and their
    difference from the solver.
    """
    from lubrication.finite_length import short_bearing_factors, table_factors

    rows = []
    for kappa in kappas:
        thin = finite_length_factors(kappa, LENGTH / A)
        rows.append({"kappa": kappa, "thin": thin,
                     "eccentric": finite_length_factors(kappa, LENGTH / A, delta_over_a=(B - A) / A,
                                                        profile="eccentric"),
                     "table": table_factors(kappa, LENGTH / A),
                     "short_bearing": short_bearing_factors(kappa, LENGTH / A)})
    return {"length_over_a": LENGTH / A, "rows": rows}


def run(kappas=KAPPAS, meshes=MESHES) -> dict:
    start = time.perf_counter()
    results = [compare(k, meshes) for k in kappas]
    return {"a_m": A, "b_m": B, "length_m": LENGTH, "length_over_a": LENGTH / A, "delta_over_a": (B - A) / A,
            "results": results, "wall_time_s": time.perf_counter() - start}
