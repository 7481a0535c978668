"""Write dynamics/data/stokes_error.json: the quasi-steady models' measured error against the Stokes number.

The study is :mod:`validation.stokes_limit` (coupled Navier-Stokes runs against the full equations with
the exact Stokes forces, at several viscosities); its stored numbers are in
``docs/stokes_limit/stokes_limit.json``. This script keeps what every run states in its summary
(:func:`dynamics.equations.limits.unsteady_error`): per start, ``frame_terms`` and ``fluid_spin``, the
pairs (St, |x_b error|) in increasing St, and the horizon (in tau, or s). Rerun after the study is rerun; then check
``tests/test_stokes_limit.py``.

    python generators/stokes_error.py
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # run as a script from a checkout
    sys.path.insert(0, str(ROOT))

DATA_FILE = ROOT / "dynamics" / "data" / "stokes_error.json"


def stokes_error(result: dict) -> dict:
    """The package's table from the study's stored numbers: an error below the reference's own is stated as that."""
    from dynamics.equations.full import FLUID_SPIN
    from validation.stokes_limit import FRAME_TERMS

    def pairs(points, frame, spin):
        return sorted([p["stokes_number"], max(abs(p["models"][frame][spin]["x_b_relative"]), p["reference_error"])]
                      for p in points)

    return {"basis": "the full equations with the exact Stokes forces against coupled Navier-Stokes runs at "
                     "several viscosities (docs/stokes_limit.md)",
            "horizon": {f["label"]: f"{f['horizon_tau']:g} tau" if f["horizon_s"] is None else f"{f['horizon_s']:g} s"
                        for f in result["families"]},
            "families": {f["label"]: {frame: {spin: pairs(f["points"], frame, spin) for spin in FLUID_SPIN}
                                      for frame in FRAME_TERMS}
                         for f in result["families"]}}


def main() -> Path:
    from numerics.files import write_text
    from validation.stokes_limit import RESULTS

    table = stokes_error(json.loads(RESULTS.read_text()))
    return write_text(DATA_FILE, json.dumps(table, indent=1) + "\n")


if __name__ == "__main__":
    print(f"wrote {main()}")
