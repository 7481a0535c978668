"""What rough contact costs: a contact trajectory against the same run without contact.

The paper's figure 7 and 8 parameters (s = 1/4, Upsilon = mu_ = 1, released from rest at
kappa = 0.5, phi = 0.3) over 300 tau, with kappa* = 0.98 and psi in {0, 0.05, 0.5}
(sliding, sliding, locked), against the smooth-wall reduced model over the same window,
which rocks down towards the gap floor instead. Reported: median wall time of 5 runs,
steps, right-hand-side evaluations and phase switches. Run from the project root with
``python -m benchmarks.contact``; writes ``benchmarks/results/contact.json`` and ``.md``.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.publish import publish  # noqa: E402
from benchmarks.reynolds import _machine  # noqa: E402
from dynamics.contact import ContactParams, simulate_contact  # noqa: E402
from dynamics.reduced import ReducedParams, simulate_reduced  # noqa: E402

PARAMS = ReducedParams(0.25, 1.0, 1.0)
KAPPA0, PHI0, T_END = 0.5, 0.3, 300.0
REPEATS = 5


def _median_run(simulate) -> dict:
    simulate()  # warm-up
    times, run = [], None
    for _ in range(REPEATS):
        start = time.perf_counter()
        run = simulate()
        times.append(time.perf_counter() - start)
    return {"seconds": float(np.median(times)), "steps": run.steps, "nfev": run.nfev,
            "switches": len(getattr(run, "switches", ())), "stop": run.stop_reason}


def run() -> dict:
    cases = {"no contact": lambda: simulate_reduced(PARAMS, T_END, KAPPA0, PHI0)}
    for psi in (0.0, 0.05, 0.5):
        cases[f"contact, psi = {psi:g}"] = (
            lambda psi=psi: simulate_contact(PARAMS, ContactParams(0.98, psi), T_END, KAPPA0, PHI0))
    rows = {name: _median_run(fn) for name, fn in cases.items()}
    base = rows["no contact"]["seconds"]
    for row in rows.values():
        row["ratio"] = row["seconds"] / base
    return {"machine": _machine(), "t_end_tau": T_END, "repeats": REPEATS, "rows": rows}


def to_markdown(results: dict) -> str:
    out = ["# Cost of rough contact", "",
           f"Reduced model, s = 1/4, Upsilon = mu_ = 1, from rest at kappa = 0.5, phi = 0.3, "
           f"{results['t_end_tau']:g} tau; median of {results['repeats']} runs.", "",
           "| run | wall time (ms) | ratio to no contact | steps | rhs evaluations | switches | stop |",
           "|---|---|---|---|---|---|---|"]
    for name, r in results["rows"].items():
        out.append(f"| {name} | {1e3 * r['seconds']:.1f} | {r['ratio']:.2f} | {r['steps']} | {r['nfev']} | "
                   f"{r['switches']} | {r['stop']} |")
    return "\n".join(out)


def main() -> None:
    results = run()
    publish("contact", results, to_markdown(results))


if __name__ == "__main__":
    main()
