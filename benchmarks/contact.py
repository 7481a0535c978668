"""What rough contact costs: a contact trajectory against the same run without contact.

The paper's figure 7 and 8 parameters (s = 1/4, Upsilon = mu_ = 1, released from rest at
kappa = 0.5, phi = 0.3) over 300 tau, with kappa* = 0.98 and psi in {0, 0.05, 0.5}
(sliding, sliding, locked), against the smooth-wall reduced model over the same window,
which rocks down towards the gap floor instead. The same for the full model (2.1)-(2.4)
with closed-form forces on a distinguished-limit apparatus with delta/a = 0.01 (mu_ = 1.5:
a real device has mu_ > 1). Every run goes through :func:`dynamics.simulation.simulate` with the
compiled Radau IIA engine at rtol 1e-8; the smooth-wall runs with the gap floor lowered to 1e-12,
so that they run the whole window. Reported: median wall time of 5 runs, steps, right-hand-side
evaluations and phase switches; ratios are to the smooth-wall run of the same model. Run from the project root with
``python -m benchmarks.contact``; writes ``benchmarks/results/contact.json`` and ``.md``.
"""

from __future__ import annotations

import sys
from pathlib import Path

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import machine, publish, repeat
from dynamics.apparatus import Apparatus
from dynamics.contact.reduced import ContactParams
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import ReducedParams
from dynamics.initial import Initial
from dynamics.simulation import simulate
from lubrication.registry import kernel_model

PARAMS = ReducedParams(0.25, 1.0, 1.0)
START, T_END = Initial(kappa=0.5, phi=0.3), 300.0
SMOOTH_LIMITS = Limits(gap_floor=1e-12, max_gap_reynolds=None)  # cost, not validity: every run to t_end
REPEATS = 5
PSIS = (0.0, 0.05, 0.5)


def _median_run(simulate) -> dict:
    timed = repeat(simulate, REPEATS)
    run = timed.result
    return {"seconds": timed.median, "steps": run.steps, "nfev": run.nfev,
            "switches": len(run.info.get("switches", ())), "stop": run.event or "t_end", "status": run.status}


def _rows(cases: dict) -> dict:
    rows = {name: _median_run(fn) for name, fn in cases.items()}
    base = rows["no contact"]["seconds"]
    for row in rows.values():
        row["ratio"] = row["seconds"] / base
    return rows


def run() -> dict:
    reduced = {"no contact": lambda: simulate(PARAMS, START, T_END, limits=SMOOTH_LIMITS)}
    for psi in PSIS:
        reduced[f"contact, psi = {psi:g}"] = (
            lambda psi=psi: simulate(PARAMS, START, T_END, contact=ContactParams(0.98, psi), limits=SMOOTH_LIMITS))
    device = Apparatus.from_groups(s=PARAMS.s, upsilon=PARAMS.upsilon, mu_ratio=1.5, delta_over_a=0.01)
    t_end = T_END * device.tau
    full = {"no contact": lambda: simulate(device, START, t_end, forces=kernel_model("closed-form"), limits=SMOOTH_LIMITS)}
    for psi in PSIS:
        full[f"contact, psi = {psi:g}"] = (lambda psi=psi: simulate(
            device, START, t_end, forces=kernel_model("closed-form"), contact=ContactParams(0.98, psi), limits=SMOOTH_LIMITS))
    return {"machine": machine(), "t_end_tau": T_END, "repeats": REPEATS,
            "rows": _rows(reduced), "full_rows": _rows(full)}


def to_markdown(results: dict) -> str:
    out = ["# Cost of rough contact", "",
           (f"s = 1/4, Upsilon = 1, from rest at kappa = 0.5, phi = 0.3, {results['t_end_tau']:g} tau, "
           f"kappa* = 0.98; median of {results['repeats']} runs.")]
    for title, key in (("Reduced model (2.11), mu_ = 1", "rows"),
                       ("Full model (2.1)-(2.4), closed-form forces, delta/a = 0.01, mu_ = 1.5", "full_rows")):
        out += ["", f"## {title}", "",
                "| run | wall time (ms) | ratio to no contact | steps | rhs evaluations | switches | stop |",
                "|---|---|---|---|---|---|---|"]
        for name, r in results[key].items():
            out.append(f"| {name} | {1e3 * r['seconds']:.1f} | {r['ratio']:.2f} | {r['steps']} | {r['nfev']} | "
                       f"{r['switches']} | {r['stop']} |")
    return "\n".join(out)


def main() -> None:
    results = run()
    publish("contact", results, to_markdown(results))


if __name__ == "__main__":
    main()
