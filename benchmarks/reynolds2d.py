r"""Cost and accuracy of the Reynolds solver on (theta, z) against N x n_axial.

The case is the paper's apparatus (a = 0.8 cm, b = 1.125 cm, L = 10.35 cm,
L/a = 12.94), thin gap, open ends, at kappa = 0.6 and 0.99 and near contact,
1 - kappa = 1e-6 and 1e-9 (passed in directly), one motion per solve (the unit
inner rotation: f_chi and T_a; the squeeze is timed alike). Near contact the
theta grid is the graded one of :func:`lubrication.reynolds2d.default_clustering`.

Methods, each timed per solve, JIT compilation excluded:

* "modal jit": :func:`lubrication.reynolds2d_kernels.modal_forces` from a numba loop,
  with the z-modes of the grid precomputed (they depend on the z-grid only and
  are cached): what an integrator step would pay;
* "python": :func:`lubrication.reynolds2d.reynolds2d_forces`, checks,
  grid building (cached z-modes) and dataclasses included;
* "sparse LU": the same discrete system assembled by
  :func:`lubrication.reynolds2d_kernels.assemble_general` and solved by SuperLU
  (scipy ``splu``), forces by :func:`lubrication.reynolds2d_kernels.lines_film` from
  the nodal field, its axial outflow from the same sparse algebra as the
  general solver: the baseline that does not use the separation in z, timed
  in three stages (assembly, factorisation and solve, forces). It must agree
  with the modal solve to rounding (checked in the run). The ratio reported
  is the LU stage alone against the whole modal solve.

Accuracy, per (N, n_axial) with N = 2 n_axial:

* against a much finer solve: the Richardson-extrapolated (4096, 2048) one,
  whose own error is below 1e-9 (its neighbour (2048, 1024) differs by less);
* against the limits: at kappa = 0 the squeeze factor is 1 - tanh(l/2)/(l/2)
  exactly (:func:`lubrication.finite_length.small_eccentricity_factor`);
  both plain and extrapolated (the latter costs 1.25 solves).

Timing follows ``benchmarks/reynolds.py``: batches of at least 5 ms, 15
rounds, every method once per round in shuffled order, median wall time and
median thread CPU time (which the other jobs of a shared machine do not
inflate).

Run ``python -m benchmarks.reynolds2d`` (or ``python benchmarks/reynolds2d.py``)
from the project root; it writes ``benchmarks/results/reynolds2d.json`` and
``reynolds2d.md``.
"""

from __future__ import annotations

import dataclasses
import datetime
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import Timer, machine, publish, time_all
from lubrication import (
    Annulus,
    Fluid,
    Motion,
    closed_form_forces,
    reynolds2d_kernels,
    reynolds_kernels,
)
from lubrication.finite_length import small_eccentricity_factor
from lubrication.reynolds2d import (
    general_outflow,
    general_solve,
    general_system,
    line_data,
    reynolds2d_forces,
    solver_setup,
)

A, B, LENGTH = 0.008, 0.01125, 0.1035  # the paper's apparatus (Table 2), m
FLUID = Fluid(nu=2.0e-4, rho=960.0)
FLUID_MU = FLUID.mu  # a global the jitted loop freezes at compilation
GAPS = (0.4, 0.01, 1e-6, 1e-9)  # 1 - kappa
SIZES = ((32, 16), (64, 32), (128, 64), (256, 128), (512, 256))  # (N, n_axial)
SPARSE_SIZES = SIZES[:4]  # the sparse LU of (512, 256) costs seconds per solve
REFERENCE = (4096, 2048)
ROUNDS = 15
BATCH_SECONDS = 5e-3
MOTIONS = {"rotation": Motion(omega_a=1.0), "squeeze": Motion(eps_dot=1e-5)}
STAGES = ("assemble", "solve", "forces")  # timed separately for the sparse-LU baseline


@njit
def _modal_loop(repeats, kappa, omk, eps_dot, w_a, kappa_g, omk_g, rule, cell_rule, m, lam, coef, half, end):
    cpsi, spsi, vpsi, ppsi, wpsi, stretch = rule
    tpos, lower0, lower1 = cell_rule
    total = 0.0
    for _ in range(repeats):
        f_eps, f_chi, t_a = reynolds2d_kernels.modal_forces(reynolds_kernels.THIN, A, B, FLUID_MU, kappa, omk, eps_dot, w_a, 0.0,
                                                    kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, stretch, tpos,
                                                    lower0, lower1, m, lam, coef, half, end)
        total += f_eps + f_chi + t_a
    return total


def _modal_args(annulus, motion, n, n_axial):
    setup = solver_setup(annulus, "thin", n, n_axial, "open", None, 2, None)
    lam, coef, _ = setup.modes
    return (annulus.kappa, annulus.one_minus_kappa, motion.eps_dot, motion.w_a, setup.kappa_g, setup.omk_g,
            setup.rule, setup.cell_rule, setup.m, lam, coef, float(setup.weights.sum()), float(setup.weights[-1]))


def _modal_forces(annulus, motion, n, n_axial):
    args = _modal_args(annulus, motion, n, n_axial)
    rule, cell_rule = args[6], args[7]
    return reynolds2d_kernels.modal_forces(reynolds_kernels.THIN, A, B, FLUID_MU, *args[:2], args[2], args[3], 0.0, args[4],
                                   args[5], *rule, *cell_rule, *args[8:])


def _sparse_forces(annulus, motion, n, n_axial, stage_times=None):
    """The modal solver's discrete system, assembled and solved by SuperLU on the half length.

    ``stage_times``, when a list, receives the seconds of the three stages: assembly
    (line integrals, kernel, CSR), solve (factorisation and solve), forces (the axial
    outflow by the same sparse algebra, and the line integrals).
    """
    start = time.perf_counter()
    setup = dataclasses.replace(solver_setup(annulus, "thin", n, n_axial, "open", None, 2, None), modes=None)
    z_lines = setup.z.size
    integrals, masses = line_data(setup, annulus, motion.eps_dot)
    integrals = np.repeat(integrals, z_lines, axis=0)
    masses = np.repeat(masses, z_lines, axis=0)
    half_u = 0.5 * A * motion.w_a
    matrix, rhs, known, axial, end_lines = general_system(setup, integrals, masses, half_u, sealed=False)
    assembled = time.perf_counter()
    phi = general_solve(matrix, rhs, known)
    solved = time.perf_counter()
    outflow = general_outflow(setup, integrals, masses, half_u, phi, axial, end_lines)
    lines = np.empty((z_lines, 3))
    sums = reynolds2d_kernels.lines_film(integrals, masses, 2.0 * half_u, 0.0, phi.reshape(z_lines, n), outflow,
                                 setup.weights, False, 0.0, lines)
    if stage_times is not None:
        stage_times[:] = [assembled - start, solved - assembled, time.perf_counter() - solved]
    scale = 12.0 * FLUID_MU * A * A * 2.0 * A
    return scale * sums[0], scale * sums[1], FLUID_MU * A * A * 2.0 * A * sums[2]


def _batch(kind, annulus, motion, n, n_axial):
    if kind == "modal jit":
        args = _modal_args(annulus, motion, n, n_axial)

        def batch(calls):
            start = time.perf_counter()
            _modal_loop(calls, *args)
            return [time.perf_counter() - start]
    elif kind == "python":
        def batch(calls):
            start = time.perf_counter()
            for _ in range(calls):
                reynolds2d_forces(annulus, motion, FLUID, n=n, n_axial=n_axial)
            return [time.perf_counter() - start]
    else:
        def batch(calls):
            totals = np.zeros(3)
            stages = [0.0, 0.0, 0.0]
            for _ in range(calls):
                _sparse_forces(annulus, motion, n, n_axial, stages)
                totals += stages
            return list(totals)
    return batch


def _annulus(omk: float) -> Annulus:
    return Annulus(a=A, b=B, length=LENGTH, one_minus_kappa=omk)


def _label(omk: float) -> str:
    return f"kappa = {1.0 - omk:g}" if omk >= 1e-3 else f"1 - kappa = {omk:g}"


def _accuracy(omk, motion, index):
    """Relative errors of plain and extrapolated solves against the fine reference."""
    annulus = _annulus(omk)
    reference = reynolds2d_forces(annulus, motion, FLUID, n=REFERENCE[0], n_axial=REFERENCE[1],
                                  extrapolate=True).as_tuple()[index]
    neighbour = reynolds2d_forces(annulus, motion, FLUID, n=REFERENCE[0] // 2, n_axial=REFERENCE[1] // 2,
                                  extrapolate=True).as_tuple()[index]
    rows = []
    for n, n_axial in SIZES:
        plain = reynolds2d_forces(annulus, motion, FLUID, n=n, n_axial=n_axial).as_tuple()[index]
        extrapolated = reynolds2d_forces(annulus, motion, FLUID, n=n, n_axial=n_axial,
                                         extrapolate=True).as_tuple()[index]
        rows.append({"n": n, "n_axial": n_axial, "plain": plain / reference - 1.0,
                     "extrapolated": extrapolated / reference - 1.0})
    return {"reference": reference, "reference_spread": abs(neighbour / reference - 1.0), "rows": rows}


def _limit_accuracy():
    """kappa = 0, squeeze: the exact factor 1 - tanh(l/2)/(l/2)."""
    annulus = Annulus.from_kappa(A, B, 0.0, LENGTH)
    motion = Motion(eps_dot=1.0)
    exact = small_eccentricity_factor(LENGTH / A) * closed_form_forces(annulus, motion, FLUID).f_eps
    rows = []
    for n, n_axial in SIZES:
        plain = reynolds2d_forces(annulus, motion, FLUID, n=n, n_axial=n_axial).f_eps
        extrapolated = reynolds2d_forces(annulus, motion, FLUID, n=n, n_axial=n_axial, extrapolate=True).f_eps
        rows.append({"n": n, "n_axial": n_axial, "plain": plain / exact - 1.0,
                     "extrapolated": extrapolated / exact - 1.0})
    return rows


def run(gaps=GAPS, sizes=SIZES, rounds=ROUNDS, batch_seconds=BATCH_SECONDS, seed=0) -> dict:
    """Median seconds per solve of every method at every size, the agreement of the two solvers, the errors."""
    timers, agreement = [], []
    for omk in gaps:
        annulus = _annulus(omk)
        for name, motion in MOTIONS.items():
            for n, n_axial in sizes:
                kinds = ("modal jit", "python") + (("sparse LU",) if (n, n_axial) in SPARSE_SIZES else ())
                for kind in kinds:
                    stages = STAGES if kind == "sparse LU" else ("total",)
                    timers.append(Timer((omk, name, n, n_axial, kind), _batch(kind, annulus, motion, n, n_axial),
                                         stages))
                if (n, n_axial) in SPARSE_SIZES:
                    modal = np.array(_modal_forces(annulus, motion, n, n_axial))
                    sparse = np.array(_sparse_forces(annulus, motion, n, n_axial))
                    agreement.append(float(np.max(np.abs(sparse - modal)) / np.max(np.abs(modal))))
    start = time.perf_counter()
    times = time_all(timers, rounds, batch_seconds, np.random.default_rng(seed))
    timing_seconds = time.perf_counter() - start
    records = [{"one_minus_kappa": k, "motion": name, "n": n, "n_axial": nz, "method": kind,
                **times[(k, name, n, nz, kind)]} for (k, name, n, nz, kind) in times]
    accuracy = {f"{omk}": {name: _accuracy(omk, motion, 0 if name == "squeeze" else 1)
                           for name, motion in MOTIONS.items()} for omk in gaps}
    return {"date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
            "machine": machine(), "timing_seconds": timing_seconds,
            "case": {"a_m": A, "b_m": B, "length_m": LENGTH, "one_minus_kappa": list(gaps), "profile": "thin",
                     "ends": "open", "points_per_cell": 2, "rounds": rounds, "batch_seconds": batch_seconds,
                     "reference": list(REFERENCE)},
            "solver_agreement_max": max(agreement), "records": records, "accuracy": accuracy,
            "limit_kappa0_squeeze": _limit_accuracy()}


def to_markdown(results: dict) -> str:
    m = results["machine"]
    case = results["case"]
    machine = (f"{m['cpu']}, {m['cores']} cores; Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, "
               f"numba {m['numba']}. {results['date']}; timing took {results['timing_seconds']:.0f} s.")
    intro = (f"The apparatus (L/a = {case['length_m'] / case['a_m']:.2f}), thin gap, open ends. Microseconds per "
             f"solve, medians of {case['rounds']} interleaved samples, thread CPU time in brackets (the machine is "
             f"shared: wall times of the fastest methods are up to twice their CPU times). The sparse-LU "
             f"baseline solves the same discrete system (largest relative difference from the modal solve over "
             f"all cases: {results['solver_agreement_max']:.1e}).")
    lines = ["# Reynolds solver on (theta, z): cost and accuracy", "", machine, "", intro, ""]
    by_key = {(r["one_minus_kappa"], r["motion"], r["n"], r["n_axial"], r["method"]): r
              for r in results["records"]}
    for omk in case["one_minus_kappa"]:
        for name in MOTIONS:
            acc = results["accuracy"][f"{omk}"][name]
            err = {(row["n"], row["n_axial"]): row for row in acc["rows"]}
            note = (f"Errors against the extrapolated ({case['reference'][0]}, {case['reference'][1]}) solve "
                    f"(which moves by {acc['reference_spread']:.0e} from its half-size neighbour).")
            header = ("| N x n_axial | modal jit us (CPU) | python us (CPU) | sparse: assemble + LU + forces us | "
                      "LU alone / modal | error | extrapolated error |")
            lines += [f"## {_label(omk)}, {name}", "", note, "", header, "|---|---|---|---|---|---|---|"]
            for n, n_axial in SIZES:
                modal = by_key.get((omk, name, n, n_axial, "modal jit"))
                if modal is None:
                    continue
                python = by_key[(omk, name, n, n_axial, "python")]
                sparse = by_key.get((omk, name, n, n_axial, "sparse LU"))
                e = err[(n, n_axial)]
                lu = (f"{1e6 * sparse['assemble']:.0f} + {1e6 * sparse['solve']:.0f} + {1e6 * sparse['forces']:.0f}"
                      if sparse else "-")
                ratio = f"{sparse['solve'] / modal['total']:.0f}" if sparse else "-"
                lines.append(f"| {n} x {n_axial} | {1e6 * modal['total']:.0f} ({1e6 * modal['cpu']:.0f}) | "
                             f"{1e6 * python['total']:.0f} ({1e6 * python['cpu']:.0f}) | {lu} | {ratio} | "
                             f"{abs(e['plain']):.1e} | {abs(e['extrapolated']):.1e} |")
            lines.append("")
    lines += ["## The kappa = 0 limit", "",
              "Squeeze at kappa = 0, against the exact factor 1 - tanh(l/2)/(l/2):", "",
              "| N x n_axial | error | extrapolated error |", "|---|---|---|"]
    for row in results["limit_kappa0_squeeze"]:
        lines.append(f"| {row['n']} x {row['n_axial']} | {abs(row['plain']):.1e} | {abs(row['extrapolated']):.1e} |")
    return "\n".join(lines)


def main() -> None:
    results = run()
    publish("reynolds2d", results, to_markdown(results))


if __name__ == "__main__":
    main()
