"""Write dynamics/data/model_choice.json: the speed-versus-accuracy study that ``auto`` chooses models from.

The study is the accuracy benchmark's (:mod:`benchmarks.accuracy`): every force model's largest error
against the exact Stokes solution and its cost, and the trajectory errors of the full and the reduced
equations, on a grid of delta/a and kappa. This script turns its results into the package's file
(:func:`benchmarks.accuracy.model_choice`). Rerun after a change to a force model, to the study's grid, or
to how :mod:`dynamics.app.auto` reads it; then check ``tests/test_auto.py`` and ``snail validate``.

    python generators/model_choice.py              # runs the study (minutes), then writes the file
    python generators/model_choice.py --from-json  # from benchmarks/results/accuracy.json as stored
                                                   # (python -m benchmarks.accuracy --trajectories updates it
                                                   # after a change to the equations of motion)
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # run as a script from a checkout
    sys.path.insert(0, str(ROOT))

CHOICE_FILE = ROOT / "dynamics" / "data" / "model_choice.json"


def main(argv=None) -> Path:
    from benchmarks.accuracy import model_choice, rederive, run
    from benchmarks.harness import RESULTS
    from numerics.files import write_text

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--from-json", action="store_true", help="from the stored benchmarks/results/accuracy.json")
    args = parser.parse_args(argv)
    results = rederive(json.loads((RESULTS / "accuracy.json").read_text())) if args.from_json else run()
    return write_text(CHOICE_FILE, json.dumps(model_choice(results), indent=None, separators=(",", ":")) + "\n")


if __name__ == "__main__":
    print(f"wrote {main()}")
